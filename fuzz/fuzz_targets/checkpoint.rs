//! Any bytes as a checkpoint: refused, or resumed to a budget a few hundred evaluations on,
//! which it must reach (every generation evaluates a design, so it ends) without a panic.
//! The state's hash is left out (`from_json_unhashed`): a mutated state would never pass it,
//! and the checks of the parts are what must hold the resumed search.
#![no_main]
use libfuzzer_sys::fuzz_target;
use noncirc::core::{execute, Checkpoint, Control, Ending, SceneProblem, SearchState};
use noncirc::search::ParallelEvaluator;

/// Evaluations the resumed search runs past the checkpoint's count.
const EXTRA: u64 = 256;

fuzz_target!(|data: &[u8]| {
    let Ok(mut cp) = Checkpoint::from_json_unhashed(data) else {
        return;
    };
    // Bounded work per input: a coarse screening, a small population, a budget that fits.
    let search = &cp.scene.search;
    if search.screening.samples_per_turn > 1440 || search.population > 512 {
        return;
    }
    let Some(budget) = cp.state.evaluations.checked_add(EXTRA) else {
        return;
    };
    let problem = SceneProblem::new(&cp.scene).expect("a checked checkpoint has a problem");
    let mut evaluator = ParallelEvaluator::new(&problem, 1).expect("one thread");
    // Every generation evaluates at least one design: EXTRA generations reach the budget.
    let mut generations = 0u64;
    let mut bounded = |s: &SearchState, _budget: u64| {
        generations += 1;
        assert!(
            generations <= EXTRA + 1,
            "{} generations left the search at {} of {budget} evaluations",
            generations - 1,
            s.evaluations
        );
        Control::Continue
    };
    let ending = execute(&mut cp.state, &mut evaluator, budget, &mut [&mut bounded]);
    assert_eq!(ending, Ending::Budget);
    assert!(cp.state.evaluations >= budget);
});
