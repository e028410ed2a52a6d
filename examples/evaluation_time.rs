//! Native time of one full evaluation of a scene at its own resolution, as the studio's
//! browser test times the same evaluation in WebAssembly: rounds of repeated evaluations
//! on one thread, reported as JSON `{median_us, min_us, max_us, rounds, per_round}`.
//!
//! `cargo run --release --example evaluation_time -- [SCENE]` (default `paper-search`).

use noncirc::core::Evaluator;
use noncirc::scene_file::load_scene;
use std::time::Instant;

/// Rounds timed, and evaluations per round (about 40 ms each at 18 µs).
const ROUNDS: usize = 15;
const PER_ROUND: u32 = 2000;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let name = std::env::args().nth(1);
    let scene = load_scene(Some(name.as_deref().unwrap_or("paper-search")))?;
    let mut evaluator = Evaluator::new();
    // Warm-up: plans the transforms and faults in the memory.
    evaluator.evaluate(&scene)?;
    let mut times: Vec<f64> = (0..ROUNDS)
        .map(|_| {
            let start = Instant::now();
            let mut sum = 0.0;
            for _ in 0..PER_ROUND {
                sum += evaluator
                    .evaluate(&scene)
                    .map_or(0.0, |e| e.total_violation());
            }
            std::hint::black_box(sum);
            start.elapsed().as_secs_f64() * 1e6 / f64::from(PER_ROUND)
        })
        .collect();
    times.sort_by(f64::total_cmp);
    println!(
        "{{\"median_us\": {}, \"min_us\": {}, \"max_us\": {}, \"rounds\": {ROUNDS}, \"per_round\": {PER_ROUND}}}",
        times[ROUNDS / 2],
        times[0],
        times[ROUNDS - 1]
    );
    Ok(())
}
