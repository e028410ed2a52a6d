//! Any bytes as a checkpoint: refused, or resumed for two generations without a panic.
//! The state's hash is left out (`from_json_unhashed`): a mutated state would never pass it,
//! and the checks of the parts are what must hold the resumed search.
#![no_main]
use libfuzzer_sys::fuzz_target;
use noncirc::core::Checkpoint;
use noncirc::core::{execute, stop_after_generations};
use noncirc::core::SceneProblem;
use noncirc::search::ParallelEvaluator;

fuzz_target!(|data: &[u8]| {
    let Ok(mut cp) = Checkpoint::from_json_unhashed(data) else {
        return;
    };
    if cp.scene.search.screening.samples_per_turn > 1440 || cp.state.generation > 1 << 20 {
        return;
    }
    let problem = SceneProblem::new(&cp.scene).expect("a checked checkpoint has a problem");
    let mut evaluator = ParallelEvaluator::new(&problem, 1).expect("one thread");
    let generations = cp.state.generation + 2;
    execute(
        &mut cp.state,
        &mut evaluator,
        u64::MAX,
        &mut [&mut stop_after_generations(generations)],
    );
});
