//! Evaluation throughput: one full three-arm evaluation at the fast and default levels,
//! populations on 1 and 2 threads, a gear-only scene against a full one, the moving box,
//! and the cost curve over samples per turn.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use noncirc::core::SceneProblem;
use noncirc::core::{BatchEvaluator, Rng};
use noncirc::core::{Evaluator, Resolution};
use noncirc::scene_file::load_scene;
use noncirc::search::ParallelEvaluator;
use std::hint::black_box;

fn single(c: &mut Criterion) {
    let scene = load_scene(None).unwrap();
    let mut group = c.benchmark_group("three_arm_evaluation");
    group.throughput(Throughput::Elements(1));
    for (name, res) in [("fast", Resolution::FAST), ("default", Resolution::DEFAULT)] {
        let mut ev = Evaluator::new();
        group.bench_function(name, |b| {
            b.iter(|| ev.evaluate_at(black_box(&scene), &res).unwrap())
        });
    }
    group.finish();

    let mut group = c.benchmark_group("scene_kind");
    group.throughput(Throughput::Elements(1));
    for name in ["ellipse-gear", "paper", "moving-box", "transplanter"] {
        let scene = load_scene(Some(name)).unwrap();
        let mut ev = Evaluator::new();
        group.bench_function(name, |b| b.iter(|| ev.evaluate(black_box(&scene)).unwrap()));
    }
    let mut gear_only = load_scene(None).unwrap();
    gear_only.kind = noncirc::core::SceneKind::Gear;
    gear_only.objectives = vec![noncirc::core::ObjectiveKind::Module];
    let mut ev = Evaluator::new();
    group.bench_function("paper-gear-only", |b| {
        b.iter(|| ev.evaluate(black_box(&gear_only)).unwrap())
    });
    group.finish();

    let mut group = c.benchmark_group("cost_curve");
    for n in [60usize, 120, 240, 480, 960] {
        let res = Resolution {
            closure_rel_tol: 1e-3,
            ..Resolution::DEFAULT.with_samples(n)
        };
        let mut ev = Evaluator::new();
        group.throughput(Throughput::Elements(1));
        group.bench_with_input(BenchmarkId::from_parameter(n), &res, |b, res| {
            b.iter(|| ev.evaluate_at(&scene, res).unwrap())
        });
    }
    group.finish();
}

fn population(c: &mut Criterion) {
    let scene = load_scene(Some("paper-search")).unwrap();
    let problem = SceneProblem::new(&scene).unwrap();
    let mut rng = Rng::new(5);
    let points: Vec<Vec<f64>> = (0..1024).map(|_| rng.point(problem.dim())).collect();
    let mut group = c.benchmark_group("population_default_resolution");
    group.throughput(Throughput::Elements(points.len() as u64));
    for threads in [1usize, 2] {
        let mut ev = ParallelEvaluator::new(&problem, threads).unwrap();
        group.bench_with_input(BenchmarkId::new("threads", threads), &points, |b, pts| {
            b.iter(|| ev.confirm(black_box(pts)))
        });
    }
    group.finish();
}

criterion_group!(benches, single, population);
criterion_main!(benches);
