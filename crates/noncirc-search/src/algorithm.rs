//! The algorithms' registry: `Algorithm` (names, parsing) and `Solver` (a resumable state
//! of any algorithm, serialised by variant name), and the dispatch between them.

use crate::cmaes::Cmaes;
use crate::de::DifferentialEvolution;
use crate::error::Error;
use crate::fitness::{BatchEvaluator, Candidate};
use crate::guided::ParameterGuided;
use crate::nsga::Nsga;
use crate::rng::Rng;
use crate::solver::SolverState;
use serde::{Deserialize, Serialize};

impl TryFrom<String> for Algorithm {
    type Error = Error;
    fn try_from(name: String) -> crate::error::Result<Self> {
        Algorithm::parse(&name)
    }
}

impl From<Algorithm> for String {
    fn from(a: Algorithm) -> String {
        a.name().into()
    }
}

impl std::str::FromStr for Algorithm {
    type Err = Error;
    fn from_str(name: &str) -> crate::error::Result<Self> {
        Algorithm::parse(name)
    }
}

/// The registry of algorithms: each line gives the variant, its state's type, its name and
/// aliases, its description and how to start it from `(dim, goals, population, rng)`. It
/// makes `Algorithm` (names, parsing) and `Solver` (the resumable state, serialised by
/// variant name) and the dispatch between them.
macro_rules! algorithms {
    ($(
        $(#[doc = $doc:literal])*
        $variant:ident($state:ty) = $name:literal $(| $alias:literal)*,
        |$dim:ident, $goals:ident, $population:ident, $rng:ident| $new:expr;
    )*) => {
        /// The algorithms. In scene files and on the command line by name (`de`, `cmaes`, …).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
        #[serde(try_from = "String", into = "String")]
        pub enum Algorithm {
            $($(#[doc = $doc])* $variant,)*
        }

        impl Algorithm {
            /// Every algorithm, in the order `noncirc optimise --help` lists them.
            pub const ALL: &'static [Algorithm] = &[$(Algorithm::$variant),*];

            /// Parses a name or an alias; an unknown name is [`Error::UnknownName`] with the
            /// nearest names.
            pub fn parse(name: &str) -> crate::error::Result<Self> {
                match name {
                    $($name $(| $alias)* => Ok(Algorithm::$variant),)*
                    _ => Err(Error::UnknownName {
                        what: "algorithm",
                        name: name.to_string(),
                        nearest: crate::names::nearest(
                            name,
                            &[$($name.to_string()),*],
                        ),
                    }),
                }
            }

            pub fn name(self) -> &'static str {
                match self {
                    $(Algorithm::$variant => $name,)*
                }
            }
        }

        /// A solver's resumable state.
        #[derive(Debug, Clone, Serialize, Deserialize)]
        pub enum Solver {
            $($variant($state),)*
        }

        impl Solver {
            /// A fresh solver for `dim` parameters and `goals` goals.
            pub fn new(
                algorithm: Algorithm,
                dim: usize,
                goals: usize,
                population: usize,
                seed: u64,
            ) -> Self {
                let rng = Rng::new(seed);
                match algorithm {
                    $(Algorithm::$variant => {
                        let ($dim, $goals, $population, $rng) = (dim, goals, population, rng);
                        Solver::$variant($new)
                    })*
                }
            }

            /// The algorithm this state belongs to.
            pub fn algorithm(&self) -> Algorithm {
                match self {
                    $(Solver::$variant(_) => Algorithm::$variant,)*
                }
            }

            pub(crate) fn state(&self) -> &dyn SolverState {
                match self {
                    $(Solver::$variant(s) => s,)*
                }
            }

            pub(crate) fn state_mut(&mut self) -> &mut dyn SolverState {
                match self {
                    $(Solver::$variant(s) => s,)*
                }
            }
        }
    };
}

algorithms! {
    /// The papers' parameter-guided heuristic.
    Guided(ParameterGuided) = "guided" | "parameter-guided",
        |dim, _goals, _population, rng| ParameterGuided::new(dim, rng);
    /// Differential evolution (rand/1/bin, dithered F).
    De(DifferentialEvolution) = "de",
        |dim, _goals, population, rng| DifferentialEvolution::new(dim, population, rng);
    /// CMA-ES with restarts.
    Cmaes(Cmaes) = "cmaes" | "cma-es",
        |dim, _goals, population, rng| Cmaes::new(dim, population, rng);
    /// NSGA-II with constraint domination.
    Nsga2(Nsga) = "nsga2" | "nsga-ii",
        |dim, _goals, population, rng| Nsga::nsga2(dim, population, rng);
    /// NSGA-III with constraint domination, for more than three goals.
    Nsga3(Nsga) = "nsga3" | "nsga-iii",
        |dim, goals, population, rng| Nsga::nsga3(dim, population, goals, rng);
}

impl Solver {
    /// One generation (or probe round); returns the candidates it evaluated.
    pub fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        self.state_mut().step(eval)
    }

    /// Checks the state against a problem of `dim` parameters and `goals` goals.
    pub fn check(&self, dim: usize, goals: usize) -> crate::Result<()> {
        self.state().check(dim, goals)
    }

    /// The current non-dominated feasible set (multi-objective solvers), if any.
    pub fn front(&self) -> Vec<Candidate> {
        self.state().front()
    }
}
