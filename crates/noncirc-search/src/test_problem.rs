//! A batch evaluator made from a function of one point, for the solvers' unit tests.

use crate::fitness::{BatchEvaluator, Fitness};

/// `dim` parameters, `goals` goals, each point scored by `score`.
pub(crate) struct FnProblem<F> {
    pub dim: usize,
    pub goals: usize,
    pub score: F,
}

impl<F: Fn(&[f64]) -> Fitness> BatchEvaluator for FnProblem<F> {
    fn dim(&self) -> usize {
        self.dim
    }
    fn goals(&self) -> usize {
        self.goals
    }
    fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        points.iter().map(|p| (self.score)(p)).collect()
    }
}

/// The unconstrained sphere about `centre` in `dim` dimensions, one goal.
pub(crate) fn sphere(dim: usize, centre: f64) -> FnProblem<impl Fn(&[f64]) -> Fitness> {
    FnProblem {
        dim,
        goals: 1,
        score: move |p: &[f64]| Fitness {
            cv: 0.0,
            f: vec![p.iter().map(|x| (x - centre).powi(2)).sum()],
        },
    }
}
