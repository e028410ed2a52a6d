//! The dynamics at working speed beyond the kinematics: the paper's design, all three arm
//! sets, at 120 carrier angles (the default resolution's nodes) and at the default 720;
//! the carrier's speed with a constant drive torque and the flywheel needed beyond that.
//! The teeth's strength beyond the dynamics: the two-arm scene's design cut by a shaper
//! (the paper's cannot be cut), the cut and the stresses on the cut teeth apart.

/// The binaries' allocator (the CLI and the Python extension set it too).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use noncirc::core::{cut_train, dynamics, events, strength, Cutter, Scene};
use noncirc::scene_file::load_scene;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let scene: Scene = load_scene(None).unwrap();
    let kin = scene.kinematics(&scene.resolution).unwrap();
    let ev = events(&kin, &scene.agronomy);
    let mut group = c.benchmark_group("dynamics_beyond_kinematics");
    group.throughput(Throughput::Elements(1));
    for samples in [120, 720] {
        let mut spec = scene.dynamics.clone();
        spec.samples_per_turn = samples;
        group.bench_with_input(BenchmarkId::new("samples", samples), &spec, |b, spec| {
            b.iter(|| dynamics(black_box(&kin), &ev, spec, 20.0).unwrap())
        });
    }
    // The speed with a constant drive torque, and the flywheel for δ = 0.02, beyond the
    // dynamics at the default 720 angles.
    let d = dynamics(&kin, &ev, &scene.dynamics, 20.0).unwrap();
    group.bench_function("speed_with_flywheel", |b| {
        b.iter(|| black_box(&d).speed_with(0.0))
    });
    group.bench_function("flywheel_needed", |b| {
        b.iter(|| black_box(&d).flywheel_needed_kg_m2(0.02))
    });
    group.finish();

    let mut scene: Scene = load_scene(Some("two-arm")).unwrap();
    scene.gear.teeth.cutter = Cutter::Shaper { teeth: 100 };
    let kin = scene.kinematics(&scene.resolution).unwrap();
    let ev = events(&kin, &scene.agronomy);
    let d = dynamics(&kin, &ev, &scene.dynamics, 20.0).unwrap();
    let pairs = cut_train(&kin, &scene).unwrap();
    let mut group = c.benchmark_group("strength_beyond_dynamics");
    group.throughput(Throughput::Elements(1));
    group.sample_size(10);
    group.bench_function("cut_teeth", |b| {
        b.iter(|| cut_train(black_box(&kin), &scene).unwrap())
    });
    group.bench_function("stresses_on_cut_teeth", |b| {
        b.iter(|| strength(black_box(&d), &pairs, &scene.dynamics).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
