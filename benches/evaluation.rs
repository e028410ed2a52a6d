//! Evaluation throughput: one full three-arm evaluation at the fast and default levels,
//! populations on 1 and 2 threads, a gear-only scene against a full one, the moving box,
//! the cost curve over samples per turn, and Python's default `evaluate_batch` call
//! against the same batch with no measures and with the gearbox's overlap.

/// The binaries' allocator (the CLI and the Python extension set it too).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use noncirc::batch::BatchRows;
use noncirc::core::Measure;
use noncirc::core::SceneProblem;
use noncirc::core::{BatchEvaluator, Rng};
use noncirc::core::{Evaluator, Resolution};
use noncirc::scene_file::load_scene;
use noncirc::search::{thread_pool, ParallelEvaluator};
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

/// The rows Python's `evaluate_batch(scene, x)` evaluates, with its default measures,
/// none (`measures=[]`) and the default ones plus `gear_overlap_mm`.
fn python_batch(c: &mut Criterion) {
    let scene = load_scene(Some("paper-search")).unwrap();
    let problem = SceneProblem::new(&scene).unwrap();
    let resolution = scene.resolution;
    let mut rng = Rng::new(7);
    let rows: Vec<Vec<f64>> = (0..1024)
        .map(|_| problem.decode(&rng.point(problem.dim())))
        .collect();
    let default = Measure::batch_default();
    let mut with_gearbox = default.clone();
    with_gearbox.push(Measure::parse("gear_overlap_mm").unwrap());
    let mut group = c.benchmark_group("python_evaluate_batch");
    group.throughput(Throughput::Elements(rows.len() as u64));
    for threads in [1usize, 2] {
        let pool = (threads > 1).then(|| thread_pool(threads).unwrap());
        // The stop flag Python's Ctrl-C sets; never set here.
        let never = std::sync::atomic::AtomicBool::new(false);
        for (name, measures) in [
            ("default", &default[..]),
            ("no_measures", &[][..]),
            ("with_gear_overlap", &with_gearbox[..]),
        ] {
            let batch = BatchRows::new(&problem, &resolution, measures);
            group.bench_with_input(BenchmarkId::new(name, threads), &rows, |b, rows| {
                b.iter(|| batch.run(pool.as_ref(), black_box(rows), &never))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, single, population, python_batch);
criterion_main!(benches);
