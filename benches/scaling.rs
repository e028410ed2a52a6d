//! Two threads against one, measured in pairs: each round times the same 1024-design batch
//! on a 1-thread and a 2-thread evaluator back to back (the order alternating), so the
//! VM's slow drifts in speed cancel within a pair. Prints the median ratio with its
//! quartiles, and the throughputs.
//!
//! `cargo bench --bench scaling` runs 300 rounds (~10 s); without `--bench` (as under
//! `cargo test --benches`) it runs 3, to show it works. `SCALING_DUMP=FILE` also writes
//! each round's two times (s), one round per line.

/// The binaries' allocator (the CLI and the Python extension set it too).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use noncirc::core::SceneProblem;
use noncirc::core::{BatchEvaluator, Rng};
use noncirc::scene_file::load_scene;
use noncirc::search::ParallelEvaluator;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let rounds = if std::env::args().any(|a| a == "--bench") {
        300
    } else {
        3
    };
    let scene = load_scene(Some("paper-search")).unwrap();
    let problem = SceneProblem::new(&scene).unwrap();
    let mut rng = Rng::new(5);
    let points: Vec<Vec<f64>> = (0..1024).map(|_| rng.point(problem.dim())).collect();
    let mut one = ParallelEvaluator::new(&problem, 1).unwrap();
    let mut two = ParallelEvaluator::new(&problem, 2).unwrap();
    let time = |ev: &mut ParallelEvaluator| {
        let start = Instant::now();
        black_box(ev.confirm(black_box(&points)));
        start.elapsed().as_secs_f64()
    };
    // Warm-up: page in, plan, let both pools start their threads.
    for _ in 0..3 {
        time(&mut one);
        time(&mut two);
    }
    let mut pairs: Vec<(f64, f64)> = (0..rounds)
        .map(|round| {
            if round % 2 == 0 {
                let t1 = time(&mut one);
                (t1, time(&mut two))
            } else {
                let t2 = time(&mut two);
                (time(&mut one), t2)
            }
        })
        .collect();
    if let Ok(path) = std::env::var("SCALING_DUMP") {
        let text: String = pairs.iter().map(|(a, b)| format!("{a} {b}\n")).collect();
        std::fs::write(path, text).unwrap();
    }
    let designs = points.len() as f64;
    let mut ratios: Vec<f64> = pairs.iter().map(|(t1, t2)| t1 / t2).collect();
    ratios.sort_by(f64::total_cmp);
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let rate1 = designs / pairs[pairs.len() / 2].0;
    pairs.sort_by(|a, b| a.1.total_cmp(&b.1));
    let rate2 = designs / pairs[pairs.len() / 2].1;
    let q = |p: f64| ratios[((ratios.len() - 1) as f64 * p).round() as usize];
    println!(
        "population_scaling: {rounds} paired rounds of {} designs",
        points.len()
    );
    println!("  1 thread:  {rate1:.0} designs/s (median)");
    println!("  2 threads: {rate2:.0} designs/s (median)");
    println!(
        "  2 threads / 1 thread: median {:.3}, quartiles [{:.3}, {:.3}], range [{:.3}, {:.3}]",
        q(0.5),
        q(0.25),
        q(0.75),
        q(0.0),
        q(1.0)
    );
}
