//! Search: problems, feasibility-first fitness, solvers, and the resumable search state.
//!
//! Solvers work in the unit cube `[0, 1]^d`; a problem maps it onto its parameter bounds.
//! Evaluation is behind [`BatchEvaluator`], so that threads live at the edge (the CLI's
//! rayon evaluator) while the solvers stay pure and deterministic.

pub mod checkpoint;
mod cmaes;
mod de;
pub mod executor;
mod goal;
mod guided;
mod nonfinite;
mod nsga;
pub mod problem;
mod rng;
mod serial;
#[cfg(test)]
mod test_problem;

pub use checkpoint::{Checkpoint, Migrants, FORMAT as CHECKPOINT_FORMAT};
pub use cmaes::Cmaes;
pub use de::DifferentialEvolution;
pub use executor::{execute, stop_after_generations, Control, Ending, Observer};
pub use goal::{Goal, GoalQuantity};
pub use guided::ParameterGuided;
pub use nsga::{das_dennis, non_dominated_fronts, Nsga, Survival};
pub use problem::{scale, SceneProblem, INVALID_CV};
pub use rng::Rng;
pub use serial::SerialEvaluator;

use crate::error::Error;
use serde::{Deserialize, Serialize};

/// Feasibility-first fitness: the summed normalised constraint violation (pymoo's `CV`)
/// and the goals to minimise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fitness {
    /// Σ violation_i / scale_i (0: feasible).
    pub cv: f64,
    /// Goals to minimise (one for single-objective solvers).
    pub f: Vec<f64>,
}

impl Fitness {
    /// Whether every constraint is met.
    pub fn feasible(&self) -> bool {
        self.cv == 0.0
    }

    /// Deb's rule on the first goal: feasible beats infeasible, lower violation beats
    /// higher, and between feasible designs the lower goal wins.
    pub fn better_than(&self, other: &Fitness) -> bool {
        match (self.feasible(), other.feasible()) {
            (true, false) => true,
            (false, true) => false,
            (false, false) => self.cv < other.cv,
            (true, true) => self.f[0] < other.f[0],
        }
    }

    /// A scalar that orders like `better_than` (lower is better).
    pub fn merit(&self) -> f64 {
        if self.feasible() {
            self.f[0]
        } else {
            INFEASIBLE_OFFSET + self.cv
        }
    }

    /// Constraint domination (Deb) for several goals.
    pub fn dominates(&self, other: &Fitness) -> bool {
        match (self.feasible(), other.feasible()) {
            (true, false) => true,
            (false, true) => false,
            (false, false) => self.cv < other.cv,
            (true, true) => {
                self.f.iter().zip(&other.f).all(|(a, b)| a <= b)
                    && self.f.iter().zip(&other.f).any(|(a, b)| a < b)
            }
        }
    }
}

/// Offset that puts every infeasible merit above every feasible goal value.
const INFEASIBLE_OFFSET: f64 = 1e6;

/// A point in the unit cube with its fitness.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    pub u: Vec<f64>,
    pub fitness: Fitness,
}

/// Evaluates batches of unit-cube points, in order.
pub trait BatchEvaluator {
    /// Dimension of the unit cube.
    fn dim(&self) -> usize;
    /// Number of goals in each fitness.
    fn goals(&self) -> usize;
    /// Fitness of each point, in the same order (at the screening resolution).
    fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness>;
    /// Fitness at the confirming (default) resolution; the same as `evaluate` unless the
    /// problem screens at a coarser one.
    fn confirm(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        self.evaluate(points)
    }
}

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

/// What every algorithm's state does. Each algorithm lives in its own file (its state and
/// this trait) and is registered once, in [`algorithms!`] below.
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
                        nearest: crate::measures::nearest(
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

            fn state(&self) -> &dyn SolverState {
                match self {
                    $(Solver::$variant(s) => s,)*
                }
            }

            fn state_mut(&mut self) -> &mut dyn SolverState {
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

/// One row of the search history.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HistoryRow {
    pub generation: u64,
    pub evaluations: u64,
    pub best_cv: f64,
    pub best_goal: f64,
    pub feasible_in_generation: usize,
}

/// Everything a search needs to resume exactly where it stopped.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SearchState {
    pub algorithm: Algorithm,
    pub solver: Solver,
    pub generation: u64,
    /// Screening evaluations so far.
    pub evaluations: u64,
    /// Confirming evaluations so far (at the default resolution).
    pub confirmations: u64,
    /// Best candidate at the screening resolution.
    pub best: Option<Candidate>,
    /// Best candidate confirmed feasible at the default resolution (fitness as confirmed).
    pub best_confirmed: Option<Candidate>,
    /// Screening evaluations when the first confirmed-feasible design appeared.
    pub first_feasible_at: Option<u64>,
    pub history: Vec<HistoryRow>,
}

impl SearchState {
    /// The design to report: the best confirmed-feasible one, else the best screened.
    pub fn reported(&self) -> Option<&Candidate> {
        self.best_confirmed.as_ref().or(self.best.as_ref())
    }

    pub fn new(
        algorithm: Algorithm,
        dim: usize,
        goals: usize,
        population: usize,
        seed: u64,
    ) -> Self {
        Self {
            algorithm,
            solver: Solver::new(algorithm, dim, goals, population, seed),
            generation: 0,
            evaluations: 0,
            confirmations: 0,
            best: None,
            best_confirmed: None,
            first_feasible_at: None,
            history: Vec::new(),
        }
    }

    /// Checks a state read from outside (a checkpoint) against a problem of `dim`
    /// parameters and `goals` goals: every length, every point in the unit cube, counters
    /// in order. A state that passes cannot panic or loop in [`SearchState::step`].
    pub fn check(&self, dim: usize, goals: usize) -> crate::Result<()> {
        let algorithm = self.solver.algorithm();
        if algorithm != self.algorithm {
            return Err(state_error(format!(
                "the state names algorithm '{}' but holds a '{}' solver",
                self.algorithm.name(),
                algorithm.name()
            )));
        }
        self.solver.check(dim, goals)?;
        for (what, c) in [
            ("best", &self.best),
            ("best_confirmed", &self.best_confirmed),
        ] {
            if let Some(c) = c {
                check_candidate(what, c, dim, goals)?;
            }
        }
        check_len("history", self.history.len(), self.generation as usize)?;
        if let Some(at) = self.first_feasible_at {
            if at > self.evaluations || self.best_confirmed.is_none() {
                return Err(state_error(format!(
                    "first_feasible_at = {at} with {} evaluations and {} confirmed design",
                    self.evaluations,
                    if self.best_confirmed.is_some() {
                        "a"
                    } else {
                        "no"
                    }
                )));
            }
        }
        Ok(())
    }

    /// The `count` best members of the population, to send to another island (fewer if
    /// the population is smaller; none before the first generation or for a solver
    /// without a population).
    pub fn emigrants(&self, count: usize) -> Vec<Candidate> {
        let mut ranked = self.solver.state().ranked_population();
        ranked.truncate(count);
        ranked
    }

    /// Takes `migrants` from another island of the same problem in place of the worst
    /// members, and as the best screened design when one is better. Checked as a
    /// checkpoint is: a migrant of another problem is refused. The confirmed best stays
    /// this island's own, as do the counters: a migrant was evaluated elsewhere.
    pub fn immigrate(
        &mut self,
        migrants: &[Candidate],
        dim: usize,
        goals: usize,
    ) -> crate::Result<()> {
        for (i, m) in migrants.iter().enumerate() {
            check_candidate(&format!("migrant {i}"), m, dim, goals)?;
        }
        if migrants.is_empty() {
            return Ok(());
        }
        if self.generation == 0 {
            return Err(state_error(
                "an island takes migrants after its first generation, not before".into(),
            ));
        }
        self.solver.state_mut().immigrate(migrants)?;
        for m in migrants {
            if (self.best.as_ref()).is_none_or(|b| m.fitness.better_than(&b.fitness)) {
                self.best = Some(m.clone());
            }
        }
        Ok(())
    }

    /// Runs one generation, tracks the best, and confirms new feasible bests.
    pub fn step(&mut self, eval: &mut dyn BatchEvaluator) {
        let batch = self.solver.step(eval);
        self.generation += 1;
        self.evaluations += batch.len() as u64;
        let mut improved = false;
        for c in &batch {
            if self
                .best
                .as_ref()
                .is_none_or(|b| c.fitness.better_than(&b.fitness))
            {
                self.best = Some(c.clone());
                improved = true;
            }
        }
        // Confirm the generation's feasible candidates that could beat the confirmed best.
        let mut pending: Vec<&Candidate> = batch
            .iter()
            .filter(|c| c.fitness.feasible())
            .filter(|c| {
                self.best_confirmed
                    .as_ref()
                    .is_none_or(|b| c.fitness.f[0] < b.fitness.f[0])
            })
            .collect();
        pending.sort_by(|a, b| a.fitness.f[0].total_cmp(&b.fitness.f[0]));
        pending.truncate(if improved { 4 } else { 2 });
        if !pending.is_empty() {
            let points: Vec<Vec<f64>> = pending.iter().map(|c| c.u.clone()).collect();
            let confirmed = eval.confirm(&points);
            self.confirmations += points.len() as u64;
            for (u, fitness) in points.into_iter().zip(confirmed) {
                if fitness.feasible()
                    && self
                        .best_confirmed
                        .as_ref()
                        .is_none_or(|b| fitness.better_than(&b.fitness))
                {
                    self.first_feasible_at.get_or_insert(self.evaluations);
                    self.best_confirmed = Some(Candidate { u, fitness });
                }
            }
        }
        let best = self.best.as_ref().map(|b| &b.fitness);
        self.history.push(HistoryRow {
            generation: self.generation,
            evaluations: self.evaluations,
            best_cv: best.map_or(f64::INFINITY, |f| f.cv),
            best_goal: best.map_or(f64::INFINITY, |f| f.f[0]),
            feasible_in_generation: batch.iter().filter(|c| c.fitness.feasible()).count(),
        });
    }
}

/// Evaluates points and pairs them with their fitness.
pub(crate) fn evaluate_all(eval: &mut dyn BatchEvaluator, points: Vec<Vec<f64>>) -> Vec<Candidate> {
    let fitness = eval.evaluate(&points);
    points
        .into_iter()
        .zip(fitness)
        .map(|(u, fitness)| Candidate { u, fitness })
        .collect()
}

/// A state that does not fit its problem or contradicts itself (a damaged or hand-edited
/// checkpoint): what is wrong, for [`crate::Error::Checkpoint`].
pub(crate) fn state_error(problem: String) -> crate::Error {
    crate::Error::Checkpoint(problem)
}

/// Checks `what`'s length against `expected`.
pub(crate) fn check_len(what: &str, len: usize, expected: usize) -> crate::Result<()> {
    if len == expected {
        Ok(())
    } else {
        Err(state_error(format!(
            "{what} has {len} entries, expected {expected}"
        )))
    }
}

/// Checks a candidate: `dim` coordinates in the unit cube, `goals` goals, a violation that
/// is a number at least 0.
pub(crate) fn check_candidate(
    what: &str,
    c: &Candidate,
    dim: usize,
    goals: usize,
) -> crate::Result<()> {
    check_len(&format!("{what}: point"), c.u.len(), dim)?;
    check_len(&format!("{what}: goals"), c.fitness.f.len(), goals)?;
    if let Some(x) = c.u.iter().find(|x| !(0.0..=1.0).contains(*x)) {
        return Err(state_error(format!(
            "{what}: coordinate {x} is outside the unit cube"
        )));
    }
    if c.fitness.cv.is_nan() || c.fitness.cv < 0.0 || c.fitness.f.iter().any(|f| f.is_nan()) {
        return Err(state_error(format!(
            "{what}: fitness {:?} is not a violation >= 0 with goals that are numbers",
            c.fitness
        )));
    }
    Ok(())
}

/// Clamps into the unit cube.
pub(crate) fn clamp_unit(u: &mut [f64]) {
    for x in u {
        *x = x.clamp(0.0, 1.0);
    }
}
