//! What a target costs: one evaluation of paper-search's design with and without the round
//! trip's target (512 points, two poses read at the events), at the screening and the
//! default resolution. The difference is the fit's measures (docs/inverse.md).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use noncirc::core::{Evaluator, Resolution};
use noncirc::fit::{read_target, with_target};
use noncirc::scene_file::load_scene;
use std::hint::black_box;
use std::path::Path;

fn fit(c: &mut Criterion) {
    let plain = load_scene(Some("paper-search")).unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/targets/roundtrip.toml");
    let targeted = with_target(plain.clone(), read_target(&path).unwrap());
    let mut group = c.benchmark_group("fit");
    group.throughput(Throughput::Elements(1));
    for (level, res) in [("fast", Resolution::FAST), ("default", Resolution::DEFAULT)] {
        for (name, scene) in [("without_target", &plain), ("with_target", &targeted)] {
            let mut ev = Evaluator::new();
            group.bench_function(format!("{level}/{name}"), |b| {
                b.iter(|| ev.evaluate_at(black_box(scene), &res).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, fit);
criterion_main!(benches);
