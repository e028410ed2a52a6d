//! Robust evaluation: one design under its tolerances (64 samples at the default
//! resolution, 8 sets of machined parts solved and 64 assemblies), against 64 full
//! evaluations, the parts of a sample, and a robust DE search.

/// The binaries' allocator (the CLI and the Python extension set it too).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use noncirc::core::{
    radius_count, robust_score, Deviated, Evaluator, Resolution, ToleranceSamples,
};
use noncirc::scene_file::load_scene;
use std::hint::black_box;

fn robust(c: &mut Criterion) {
    let scene = load_scene(None).unwrap();
    let res = Resolution::DEFAULT;
    let tol = &scene.tolerances;
    let samples = ToleranceSamples::new(tol, radius_count(&scene.gear.curve), tol.seed).unwrap();
    let mut ev = Evaluator::planned(&res);
    let nominal = ev.evaluate_at(&scene, &res).unwrap();
    let mut group = c.benchmark_group("robust_evaluation");
    group.throughput(Throughput::Elements(1));
    group.bench_function("64_samples", |b| {
        b.iter(|| {
            let nominal = ev.evaluate_at(black_box(&scene), &res).unwrap();
            robust_score(&mut ev, &scene, &nominal, &samples).unwrap()
        })
    });
    // What reuse saves: 64 full evaluations of the deviated designs' cost.
    group.bench_function("64_full_evaluations", |b| {
        b.iter(|| {
            for _ in 0..64 {
                black_box(ev.evaluate_at(black_box(&scene), &res).unwrap());
            }
        })
    });
    group.finish();

    let deviated = Deviated::new(&mut ev, &scene, &nominal).unwrap();
    let kin = nominal.kinematics.clone().unwrap();
    let mut group = c.benchmark_group("tolerance_sample");
    group.bench_function("gear_variant", |b| {
        b.iter(|| {
            deviated
                .variant(
                    &mut ev,
                    black_box(&samples.radii[1]),
                    samples.assembly[1][3],
                )
                .unwrap()
        })
    });
    group.bench_function("reassembled", |b| {
        b.iter(|| kin.reassembled(black_box(&scene.train), 0.01).unwrap())
    });
    group.bench_function("assembled_and_evaluated", |b| {
        b.iter(|| {
            deviated
                .assembled(
                    &mut ev,
                    &kin,
                    &samples.radii[1],
                    black_box(&samples.assembly[3]),
                )
                .unwrap()
        })
    });
    group.finish();
}

/// A robust DE search of the default search scene (goal: the probability of meeting every
/// objective under the default tolerances, 64 samples per feasible candidate), on one and
/// two threads.
fn robust_search(c: &mut Criterion) {
    let mut scene = load_scene(Some("paper-search")).unwrap();
    scene.search.goals = vec![noncirc::core::Goal::Probability];
    let mut group = c.benchmark_group("robust_search");
    group.sample_size(10);
    for threads in [1, 2] {
        let options = noncirc::search::RunOptions {
            threads,
            checkpoint: None,
            checkpoint_every: std::time::Duration::from_secs(3600),
            resume: None,
            resume_budget: None,
            stop: std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false)),
            max_generations: None,
            on_checkpoint_failure: |_| {},
        };
        group.bench_function(format!("de_probability/{threads}_threads"), |b| {
            b.iter(|| noncirc::search::run(&scene, &options, &mut []).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, robust, robust_search);
criterion_main!(benches);
