//! Feasibility-first fitness, candidates (unit-cube points with their fitness) and the
//! batch evaluator that scores them.

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
    /// Fitness of each point that competes with the rival of the same index (differential
    /// evolution's trial against its target). Each point gets its fitness as `evaluate`
    /// gives it, except that a point whose evaluation shows part-way that it loses may get
    /// a bound instead: an infeasible fitness whose violation is a lower bound of the
    /// point's own and already above the rival's (so `rival.better_than(bound)`, as of the
    /// whole fitness). Such a point is kept by no selection, no best and no confirmation,
    /// so the search runs exactly as with `evaluate`. By default, `evaluate`.
    fn evaluate_against(&mut self, points: &[Vec<f64>], rivals: &[Fitness]) -> Vec<Fitness> {
        debug_assert_eq!(points.len(), rivals.len());
        self.evaluate(points)
    }
    /// Fitness at the confirming (default) resolution; the same as `evaluate` unless the
    /// problem screens at a coarser one.
    fn confirm(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        self.evaluate(points)
    }
    /// Whether the last batch was abandoned part-way because a stop was asked (Ctrl-C in
    /// a large generation): some of its fitness values are placeholders, and the executor
    /// discards the generation. An evaluator that always finishes its batches says no.
    fn interrupted(&self) -> bool {
        false
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

/// Clamps into the unit cube.
pub(crate) fn clamp_unit(u: &mut [f64]) {
    for x in u {
        *x = x.clamp(0.0, 1.0);
    }
}
