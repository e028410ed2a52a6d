//! What every solver's state does, and the largest population a solver takes.

use crate::check::state_error;
use crate::fitness::{BatchEvaluator, Candidate};

/// Largest population: a generation of 100 000 designs takes about two seconds.
pub const MAX_POPULATION: usize = 100_000;

/// What every algorithm's state does. Each algorithm lives in its own file (its state and
/// this trait) and is registered once, in the `algorithms!` registry (algorithm.rs).
pub trait SolverState {
    /// One generation (or probe round); returns the candidates it evaluated.
    fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate>;
    /// Checks a state read from outside against a problem of `dim` parameters and `goals`
    /// goals.
    fn check(&self, dim: usize, goals: usize) -> crate::Result<()>;
    /// The current non-dominated feasible set (multi-objective solvers).
    fn front(&self) -> Vec<Candidate> {
        Vec::new()
    }
    /// The population, best first, for an island model's migration; empty for a solver
    /// without one (CMA-ES, the parameter-guided probes), which then takes no migrants.
    fn ranked_population(&self) -> Vec<Candidate> {
        Vec::new()
    }
    /// Puts `migrants` in place of the worst members, as an island model's migration
    /// does. Only solvers with a population take them.
    fn immigrate(&mut self, _migrants: &[Candidate]) -> crate::Result<()> {
        Err(state_error(
            "this algorithm keeps no population to take migrants into (use de, nsga2 or nsga3)"
                .into(),
        ))
    }
}
