//! A batch of designs reduced to their numbers: for each row of parameter values, the
//! fitness, the objectives and the chosen measures (Python's `evaluate_batch`). No
//! trajectory outlives its row. The benchmarks time this same code.

use crate::search::map_batch;
use noncirc_core::{
    Evaluator, Fitness, Measure, Measured, ObjectiveValue, Resolution, Scene, SceneProblem,
};

/// One row's objectives and measures (`None` where the scene does not compute one), or
/// the error that refused the design.
pub type RowOutcome = std::result::Result<(Vec<ObjectiveValue>, Vec<Option<f64>>), String>;

/// The rows of a batch of one problem at one resolution, with the measures to return.
pub struct BatchRows<'a> {
    problem: &'a SceneProblem,
    resolution: &'a Resolution,
    measures: &'a [Measure],
}

impl<'a> BatchRows<'a> {
    pub fn new(
        problem: &'a SceneProblem,
        resolution: &'a Resolution,
        measures: &'a [Measure],
    ) -> Self {
        BatchRows {
            problem,
            resolution,
            measures,
        }
    }

    /// Evaluates one row with a worker's evaluator and scene to edit.
    pub fn row(&self, state: &mut (Evaluator, Scene), x: &[f64]) -> (Fitness, RowOutcome) {
        let (evaluator, scratch) = state;
        let (fitness, outcome) =
            (self.problem).fitness_at_values(x, evaluator, scratch, self.resolution);
        let outcome = outcome
            .map(|eval| {
                let on = Measured::new(&eval, scratch);
                let values = self.measures.iter().map(|m| m.value(&on)).collect();
                (eval.objectives, values)
            })
            .map_err(|e| e.to_string());
        (fitness, outcome)
    }

    /// Evaluates `rows` in order: in the caller's thread without a pool (so that
    /// concurrent callers overlap), on the pool's threads with one.
    pub fn run(
        &self,
        pool: Option<&rayon::ThreadPool>,
        rows: &[Vec<f64>],
    ) -> Vec<(Fitness, RowOutcome)> {
        let planned = Evaluator::planned(self.resolution);
        match pool {
            None => {
                let mut state = (planned, self.problem.base().clone());
                rows.iter().map(|x| self.row(&mut state, x)).collect()
            }
            Some(pool) => map_batch(pool, &planned, self.problem.base(), rows, |state, x| {
                self.row(state, x)
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_file::load_scene;
    use noncirc_core::{MeasureCost, Rng};

    #[test]
    fn rows_are_the_same_on_one_and_two_threads_and_the_default_measures_cost_nothing() {
        let scene = load_scene(Some("paper-search")).unwrap();
        let problem = SceneProblem::new(&scene).unwrap();
        let resolution = scene.resolution;
        let mut rng = Rng::new(3);
        let rows: Vec<Vec<f64>> = (0..40)
            .map(|_| problem.decode(&rng.point(problem.dim())))
            .collect();
        let measures = Measure::batch_default();
        assert!(measures.iter().all(|m| m.cost() == MeasureCost::Read));
        assert!(!measures.iter().any(|m| m.name() == "gear_overlap_mm"));
        let batch = BatchRows::new(&problem, &resolution, &measures);
        let one = batch.run(None, &rows);
        let pool = crate::search::thread_pool(2).unwrap();
        let two = batch.run(Some(&pool), &rows);
        assert_eq!(one.len(), rows.len());
        for ((f1, o1), (f2, o2)) in one.iter().zip(&two) {
            assert_eq!(f1.cv.to_bits(), f2.cv.to_bits());
            assert_eq!(format!("{o1:?}"), format!("{o2:?}"));
        }
        // Every default measure of a valid design is read without the sections: the
        // events' measures are there (a scene with events computes them all but the box's
        // travel and the runner-up gaps).
        let valid: Vec<_> = one.iter().filter_map(|(_, o)| o.as_ref().ok()).collect();
        assert!(!valid.is_empty());
        for (_, values) in valid {
            for (m, v) in measures.iter().zip(values) {
                let optional = [
                    "box_travel_mm",
                    "picking_branch_gap_mm",
                    "planting_branch_gap_mm",
                ];
                assert!(
                    v.is_some() || optional.contains(&m.name().as_str()),
                    "{}",
                    m.name()
                );
            }
        }
    }
}
