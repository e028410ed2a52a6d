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
    /// An observer stopped it, or the evaluator abandoned a generation part-way
    /// ([`BatchEvaluator::interrupted`]); the state is whole and resumable.
    Stopped,
}

/// Steps `state` until `budget` evaluations are spent or an observer stops it. Every
/// observer is polled each time (a progress bar still draws when another one stops). A
/// generation the evaluator abandons part-way is undone: the state goes back to the end of
/// the last complete generation and the run stops there, so that a stop asked inside a long
/// generation is answered at once and what is kept still resumes bit for bit.
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
        let before = Rollback::before_step(state);
        state.step(evaluator);
        if evaluator.interrupted() {
            before.restore(state);
            return Ending::Stopped;
        }
        // A stop asked for after the budget's last generation changes nothing.
        if poll(state) == Control::Stop && state.evaluations < budget {
            return Ending::Stopped;
        }
    }
    Ending::Budget
}

/// The state before a generation, to go back to if the evaluator abandons it. The
/// history, which grows with every generation, is not copied: a generation only appends a
/// row to it, so going back truncates it.
struct Rollback {
    without_history: SearchState,
    history_len: usize,
}

impl Rollback {
    fn before_step(state: &mut SearchState) -> Self {
        let history = std::mem::take(&mut state.history);
        let without_history = state.clone();
        state.history = history;
        Self {
            without_history,
            history_len: state.history.len(),
        }
    }

    fn restore(self, state: &mut SearchState) {
        let mut history = std::mem::take(&mut state.history);
        history.truncate(self.history_len);
        *state = self.without_history;
        state.history = history;
    }
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

    /// The two-goal problem of [`two_goals`], abandoned part-way through the batch in
    /// which its `stop_at`-th point comes (counting every point, confirmations too), as
    /// Ctrl-C inside a generation does: the rest of that batch gets placeholders.
    struct AbandonedAt {
        stop_at: u64,
        seen: u64,
        abandoned: bool,
    }

    impl BatchEvaluator for AbandonedAt {
        fn dim(&self) -> usize {
            4
        }
        fn goals(&self) -> usize {
            2
        }
        fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
            let mut problem = two_goals();
            (points.iter())
                .map(|p| {
                    self.seen += 1;
                    if self.seen >= self.stop_at {
                        self.abandoned = true;
                        Fitness {
                            cv: f64::INFINITY,
                            f: vec![f64::NAN; 2],
                        }
                    } else {
                        problem.evaluate(std::slice::from_ref(p)).remove(0)
                    }
                })
                .collect()
        }
        fn interrupted(&self) -> bool {
            self.abandoned
        }
    }

    /// A generation abandoned part-way is undone: the run stops with the state of the last
    /// complete generation (no placeholder in it), and resuming it ends where an
    /// uninterrupted run ends, for every algorithm and wherever in the batch the stop comes.
    #[test]
    fn a_generation_abandoned_part_way_is_undone_and_resumes_bit_for_bit() {
        for &algorithm in Algorithm::ALL {
            let fresh = || SearchState::new(algorithm, 4, 2, 12, 11);
            let mut whole = fresh();
            execute(&mut whole, &mut two_goals(), 1200, &mut []);
            let whole = serde_json::to_string(&whole).unwrap();
            for stop_at in [1, 5, 13, 100, 401] {
                let mut part = fresh();
                let mut abandoning = AbandonedAt {
                    stop_at,
                    seen: 0,
                    abandoned: false,
                };
                let ending = execute(&mut part, &mut abandoning, 1200, &mut []);
                assert_eq!(ending, Ending::Stopped, "{algorithm:?} at {stop_at}");
                // Every point before the stop was kept and none after it: the state holds
                // whole generations only.
                assert!(part.evaluations + part.confirmations < stop_at);
                assert_eq!(part.history.len() as u64, part.generation);
                assert!(part
                    .best
                    .iter()
                    .all(|b| b.fitness.f.iter().all(|f| f.is_finite())));
                // The same state as a run stopped by an observer after those generations.
                let mut stopped = fresh();
                let mut limit = stop_after_generations(part.generation);
                execute(&mut stopped, &mut two_goals(), 1200, &mut [&mut limit]);
                assert_eq!(
                    serde_json::to_string(&stopped).unwrap(),
                    serde_json::to_string(&part).unwrap(),
                    "{algorithm:?} at {stop_at}"
                );
                execute(&mut part, &mut two_goals(), 1200, &mut []);
                assert_eq!(
                    whole,
                    serde_json::to_string(&part).unwrap(),
                    "{algorithm:?}"
                );
            }
        }
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
        for &algorithm in Algorithm::ALL {
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
