//! What a target costs: one evaluation of paper-search's design with and without the round
//! trip's target (512 points, two poses read at the events), at the screening and the
//! default resolution, the difference being the fit's measures; and the exact inversion
//! (`noncirc inverse`, both senses and branches tried, the design evaluated against the
//! target) of a two-pair design's path (4096 points) and of the drawn loop
//! (docs/inverse.md).

/// The binaries' allocator (the CLI and the Python extension set it too).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use noncirc::core::{invert, target_of, Evaluator, InverseSpec, Resolution};
use noncirc::fit::{read_target, with_target};
use noncirc::scene_file::load_scene;
use std::hint::black_box;
use std::path::Path;

/// The designs the integration tests share (the round trip's two-pair design).
#[path = "../tests/common/mod.rs"]
mod common;

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

fn inverse(c: &mut Criterion) {
    let paper = common::paper();
    // The round trip of tests/inverse.rs: an ellipse sun, a Fourier layer B.
    let design = common::two_pair_design();
    let eval = Evaluator::new().evaluate(&design).unwrap();
    let mut two_pair = target_of(
        eval.kinematics.as_ref().unwrap(),
        eval.events.as_ref().unwrap(),
        4096,
    );
    two_pair.tolerance_mm = 0.01;
    let [a1, a2] = eval.kinematics.as_ref().unwrap().centre_distances();
    let drawn = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/targets/drawn-loop.toml");
    let drawn = read_target(&drawn).unwrap();
    let spec = |ratio: f64| InverseSpec {
        centre_ratio: ratio,
        split: 0.5,
        branch: None,
        samples_per_turn: 720,
    };
    let mut group = c.benchmark_group("inverse");
    group.sample_size(20);
    for (name, target, ratio) in [
        ("two_pair_4096", &two_pair, a2 / a1),
        ("drawn_loop", &drawn, 1.0),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| invert(black_box(&paper), target, &spec(ratio)).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, fit, inverse);
criterion_main!(benches);
