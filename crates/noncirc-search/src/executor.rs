//! The search loop, once for every front end: the executor owns the budget and asks its
//! observers, before the first generation and after each one, whether to go on. It has no
//! threads, clock or I/O of its own (so it runs in the browser): the CLI plugs in a progress
//! bar, Ctrl-C and timed checkpoints as observers, Python its signal check and progress
//! callback. In the spirit of argmin's `Executor` and observers.

use crate::fitness::BatchEvaluator;
use crate::state::SearchState;

/// An observer's answer: go on, or stop cleanly after the generation just finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    Continue,
    Stop,
}

/// Watches a search. `poll` is called before the first generation and after every
/// generation, with the state and the budget (evaluations).
pub trait Observer {
    fn poll(&mut self, state: &SearchState, budget: u64) -> Control;
}

/// Any `FnMut(&SearchState, u64) -> Control` is an observer.
impl<F: FnMut(&SearchState, u64) -> Control> Observer for F {
    fn poll(&mut self, state: &SearchState, budget: u64) -> Control {
        self(state, budget)
    }
}

/// Why a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// The budget was spent.
    Budget,
    /// An observer stopped it; the state is whole and resumable.
    Stopped,
}

/// Steps `state` until `budget` evaluations are spent or an observer stops it. Every
/// observer is polled each time (a progress bar still draws when another one stops).
///
/// Differential evolution on a sphere centred in the unit cube, with an observer (any
/// closure of the state and the budget) that stops the search once a design lies within
/// 0.01 of the centre:
///
/// ```
/// use noncirc_search::{execute, Algorithm, BatchEvaluator, Control, Ending, Fitness, SearchState};
///
/// struct Sphere;
/// impl BatchEvaluator for Sphere {
///     fn dim(&self) -> usize { 3 }
///     fn goals(&self) -> usize { 1 }
///     fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
///         let f = |u: &Vec<f64>| u.iter().map(|x| (x - 0.5).powi(2)).sum::<f64>();
///         points.iter().map(|u| Fitness { cv: 0.0, f: vec![f(u)] }).collect()
///     }
/// }
///
/// let mut state = SearchState::new(Algorithm::De, 3, 1, 12, 7); // population 12, seed 7
/// let mut close_enough = |s: &SearchState, _budget: u64| match &s.best {
///     Some(best) if best.fitness.f[0] < 1e-4 => Control::Stop,
///     _ => Control::Continue,
/// };
/// let ending = execute(&mut state, &mut Sphere, 100_000, &mut [&mut close_enough]);
/// assert_eq!(ending, Ending::Stopped);
/// assert!(state.best.unwrap().fitness.f[0] < 1e-4 && state.evaluations < 100_000);
/// ```
pub fn execute(
    state: &mut SearchState,
    evaluator: &mut dyn BatchEvaluator,
    budget: u64,
    observers: &mut [&mut dyn Observer],
) -> Ending {
    let mut poll = |state: &SearchState| {
        observers.iter_mut().fold(Control::Continue, |control, o| {
            match o.poll(state, budget) {
                Control::Stop => Control::Stop,
                Control::Continue => control,
            }
        })
    };
    if poll(state) == Control::Stop {
        return Ending::Stopped;
    }
    while state.evaluations < budget {
        state.step(evaluator);
        // A stop asked for after the budget's last generation changes nothing.
        if poll(state) == Control::Stop && state.evaluations < budget {
            return Ending::Stopped;
        }
    }
    Ending::Budget
}

/// An observer that stops after `n` generations of this run (for tests of interrupted runs).
pub fn stop_after_generations(n: u64) -> impl Observer {
    let mut seen = 0u64;
    move |_: &SearchState, _: u64| {
        seen += 1;
        // The first poll comes before any generation.
        if seen > n {
            Control::Stop
        } else {
            Control::Continue
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_problem::{sphere, FnProblem};
    use crate::{Algorithm, Fitness};

    /// A run stopped and continued equals a run that never stopped.
    #[test]
    fn stopping_and_continuing_equals_one_run() {
        let mut whole = SearchState::new(Algorithm::De, 3, 1, 12, 5);
        assert_eq!(
            execute(&mut whole, &mut sphere(3, 0.5), 600, &mut []),
            Ending::Budget
        );
        let mut parts = SearchState::new(Algorithm::De, 3, 1, 12, 5);
        let mut stop = stop_after_generations(7);
        let ending = execute(&mut parts, &mut sphere(3, 0.5), 600, &mut [&mut stop]);
        assert_eq!(ending, Ending::Stopped);
        assert_eq!(parts.generation, 7);
        assert_eq!(
            execute(&mut parts, &mut sphere(3, 0.5), 600, &mut []),
            Ending::Budget
        );
        assert_eq!(
            serde_json::to_string(&whole).unwrap(),
            serde_json::to_string(&parts).unwrap()
        );
    }

    /// Every observer is polled before the first generation and after each one.
    #[test]
    fn observers_see_every_generation() {
        let mut state = SearchState::new(Algorithm::Cmaes, 3, 1, 8, 1);
        let mut seen = Vec::new();
        let mut log = |s: &SearchState, budget: u64| {
            seen.push((s.generation, budget));
            Control::Continue
        };
        execute(&mut state, &mut sphere(3, 0.5), 80, &mut [&mut log]);
        assert_eq!(seen.len() as u64, state.generation + 1);
        assert!(seen
            .iter()
            .enumerate()
            .all(|(i, &(g, b))| g == i as u64 && b == 80));
    }

    /// A constrained sphere in 4 dimensions, two goals (so NSGA's crowding distances are
    /// infinite at the front's ends).
    fn two_goals() -> FnProblem<impl Fn(&[f64]) -> Fitness> {
        FnProblem {
            dim: 4,
            goals: 2,
            score: |p: &[f64]| Fitness {
                cv: (0.3 - p[0]).max(0.0),
                f: vec![p.iter().map(|x| x * x).sum(), (1.0 - p[0]).powi(2) + p[1]],
            },
        }
    }

    /// Every algorithm's state survives a checkpoint (JSON) mid-run and ends exactly where
    /// an uninterrupted run does.
    #[test]
    fn every_algorithm_resumes_bit_for_bit_from_json() {
        for algorithm in [
            Algorithm::Guided,
            Algorithm::De,
            Algorithm::Cmaes,
            Algorithm::Nsga2,
            Algorithm::Nsga3,
        ] {
            let fresh = || SearchState::new(algorithm, 4, 2, 12, 11);
            let mut whole = fresh();
            execute(&mut whole, &mut two_goals(), 1200, &mut []);
            let mut part = fresh();
            execute(
                &mut part,
                &mut two_goals(),
                1200,
                &mut [&mut stop_after_generations(9)],
            );
            let json = serde_json::to_string(&part).unwrap();
            let mut resumed: SearchState = serde_json::from_str(&json)
                .unwrap_or_else(|e| panic!("{algorithm:?}: checkpoint does not load: {e}"));
            execute(&mut resumed, &mut two_goals(), 1200, &mut []);
            assert_eq!(
                serde_json::to_string(&whole).unwrap(),
                serde_json::to_string(&resumed).unwrap(),
                "{algorithm:?}"
            );
        }
    }
}
