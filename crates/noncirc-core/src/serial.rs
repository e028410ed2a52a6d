//! Batches evaluated one design after another, on the caller's thread: the browser's
//! worker runs searches with it. A design's fitness does not depend on which evaluator or
//! thread computed it, so a search gives the same result with this as with the CLI's
//! parallel evaluator.

use crate::evaluator::Evaluator;
use crate::problem::SceneProblem;
use crate::scene::Scene;
use noncirc_search::{BatchEvaluator, Fitness};

/// A scene problem's batch evaluator without threads.
#[derive(Debug, Clone)]
pub struct SerialEvaluator {
    problem: SceneProblem,
    /// Evaluators planned for the screening and the confirming resolution.
    planned: [Evaluator; 2],
    /// The base scene, edited in place for each design.
    scratch: Scene,
}

impl SerialEvaluator {
    pub fn new(problem: SceneProblem) -> Self {
        let confirm = problem.base().resolution;
        Self {
            planned: [problem.screening(), confirm].map(|r| Evaluator::planned(&r)),
            scratch: problem.base().clone(),
            problem,
        }
    }

    /// The problem it evaluates.
    pub fn problem(&self) -> &SceneProblem {
        &self.problem
    }

    fn run(&mut self, points: &[Vec<f64>], confirming: bool) -> Vec<Fitness> {
        let resolution = if confirming {
            self.problem.base().resolution
        } else {
            self.problem.screening()
        };
        let evaluator = &mut self.planned[usize::from(confirming)];
        points
            .iter()
            .map(|u| (self.problem).fitness_alone(u, evaluator, &mut self.scratch, &resolution))
            .collect()
    }
}

impl BatchEvaluator for SerialEvaluator {
    fn dim(&self) -> usize {
        self.problem.dim()
    }
    fn goals(&self) -> usize {
        self.problem.goals()
    }
    fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        self.run(points, false)
    }
    fn evaluate_against(&mut self, points: &[Vec<f64>], rivals: &[Fitness]) -> Vec<Fitness> {
        let resolution = self.problem.screening();
        (points.iter().zip(rivals))
            .map(|(u, rival)| {
                (self.problem).fitness_against(
                    u,
                    rival,
                    &mut self.planned[0],
                    &mut self.scratch,
                    &resolution,
                )
            })
            .collect()
    }
    fn confirm(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        self.run(points, true)
    }
}
