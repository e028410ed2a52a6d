//! noncirc-search: the problem-independent optimiser of noncirc. It knows points of the unit
//! cube `[0, 1]^d` and their fitness, nothing of gears or scenes:
//!
//! - feasibility-first [`Fitness`] (Deb's rule, constraint domination) and [`Candidate`]s;
//! - the [`BatchEvaluator`] trait, behind which a problem scores batches of points, so that
//!   threads live at the edge (the CLI's rayon evaluator) while the solvers stay pure and
//!   deterministic;
//! - the solvers, each a resumable [`SolverState`]: differential evolution, CMA-ES,
//!   NSGA-II/III and the parameter-guided probes, registered by name as [`Algorithm`];
//! - the search state ([`SearchState`]: best screened and confirmed designs, counters,
//!   history) and the executor that steps it under a budget and asks its [`Observer`]s;
//! - a local least-squares refinement ([`refine`], Levenberg–Marquardt) of a problem's
//!   residual vector ([`ResidualBatch`]);
//! - a seeded, serialisable [`Rng`], serde for non-finite floats, and checks of a state
//!   read from outside.
//!
//! The scene's search problem (free parameters, goals, the evaluator of a scene) and the
//! checkpoint format live in noncirc-core, which re-exports this crate's items at its root.

// Every public item is reachable from the root, and every type in a public signature can
// be named there.
#![warn(unreachable_pub, unnameable_types)]

mod algorithm;
mod check;
mod cmaes;
mod de;
mod error;
mod executor;
mod fitness;
mod guided;
mod local;
mod names;
mod nonfinite;
mod nsga;
mod rng;
mod solver;
mod state;
#[cfg(test)]
mod test_problem;

pub use algorithm::{Algorithm, Solver};
pub use cmaes::Cmaes;
pub use de::DifferentialEvolution;
pub use error::{Error, Result};
pub use executor::{execute, stop_after_generations, Control, Ending, Observer};
pub use fitness::{BatchEvaluator, Candidate, Fitness};
pub use guided::ParameterGuided;
pub use local::{refine, LocalReport, LocalSettings, ResidualBatch};
pub use names::nearest;
pub use nsga::{non_dominated_fronts, Nsga, Survival};
pub use rng::Rng;
pub use solver::{SolverState, MAX_POPULATION};
pub use state::{HistoryRow, SearchState};
