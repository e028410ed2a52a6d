//! A batch of designs reduced to their numbers: for each row of parameter values, the
//! fitness, the objectives, the chosen measures and, when asked, the tip's path (Python's
//! `evaluate_batch`). No other part of a trajectory outlives its row. The benchmarks time
//! this same code.

use crate::search::map_batch;
use noncirc_core::{
    ConstraintValue, Evaluator, Fitness, Measure, Measured, ObjectiveValue, Resolution, Scene,
    SceneProblem,
};
use std::sync::atomic::{AtomicBool, Ordering};

/// One design's numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct RowValues {
    pub objectives: Vec<ObjectiveValue>,
    /// The scene's `search.constraints`, scored.
    pub constraints: Vec<ConstraintValue>,
    /// The chosen measures (`None` where the scene does not compute one).
    pub measures: Vec<Option<f64>>,
    /// The tip of arm I at each of the resolution's samples of a carrier turn, from
    /// carrier angle 0 (mm, the carrier's frame), when [`BatchRows::with_tip_paths`] asked.
    pub tip_path: Option<Vec<[f64; 2]>>,
}

/// One row's numbers, or the error that refused the design.
pub type RowOutcome = std::result::Result<RowValues, String>;

/// The rows of a batch of one problem at one resolution, with the measures to return.
pub struct BatchRows<'a> {
    problem: &'a SceneProblem,
    resolution: &'a Resolution,
    measures: &'a [Measure],
    tip_paths: bool,
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
            tip_paths: false,
        }
    }

    /// The rows keep the tip's path too (`samples_per_turn` points each).
    pub fn with_tip_paths(self, tip_paths: bool) -> Self {
        Self { tip_paths, ..self }
    }

    /// Evaluates one row with a worker's evaluator and scene to edit.
    pub fn row(&self, state: &mut (Evaluator, Scene), x: &[f64]) -> (Fitness, RowOutcome) {
        let (evaluator, scratch) = state;
        let (fitness, outcome) =
            (self.problem).fitness_at_values(x, evaluator, scratch, self.resolution);
        let outcome = outcome
            .map(|eval| {
                let on = Measured::new(&eval, scratch);
                let measures = self.measures.iter().map(|m| m.value(&on)).collect();
                let tip_path = (eval.kinematics.as_ref())
                    .filter(|_| self.tip_paths)
                    .map(|kin| kin.tips().iter().map(|&p| p.into()).collect());
                RowValues {
                    objectives: eval.objectives,
                    constraints: eval.constraints,
                    measures,
                    tip_path,
                }
            })
            .map_err(|e| e.to_string());
        (fitness, outcome)
    }

    /// Evaluates `rows` in order: in the caller's thread without a pool (so that
    /// concurrent callers overlap), on the pool's threads with one. Once `stop` is set the
    /// rows not yet started are skipped and `None` is returned: Ctrl-C is answered within
    /// one row's evaluation per thread.
    pub fn run(
        &self,
        pool: Option<&rayon::ThreadPool>,
        rows: &[Vec<f64>],
        stop: &AtomicBool,
    ) -> Option<Vec<(Fitness, RowOutcome)>> {
        let planned = Evaluator::planned(self.resolution);
        let row = |state: &mut (Evaluator, Scene), x: &Vec<f64>| {
            (!stop.load(Ordering::Relaxed)).then(|| self.row(state, x))
        };
        match pool {
            None => {
                let mut state = (planned, self.problem.base().clone());
                rows.iter().map(|x| row(&mut state, x)).collect()
            }
            Some(pool) => map_batch(pool, &planned, self.problem.base(), rows, row)
                .into_iter()
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_file::load_scene;
    use noncirc_core::{MeasureCost, Rng};

    /// `n` designs drawn uniformly from `problem`'s box with `seed`.
    fn random_rows(problem: &SceneProblem, n: usize, seed: u64) -> Vec<Vec<f64>> {
        let mut rng = Rng::new(seed);
        (0..n)
            .map(|_| problem.decode(&rng.point(problem.dim())))
            .collect()
    }

    #[test]
    fn rows_are_the_same_on_one_and_two_threads_and_the_default_measures_cost_nothing() {
        let scene = load_scene(Some("paper-search")).unwrap();
        let problem = SceneProblem::new(&scene).unwrap();
        let resolution = scene.resolution;
        let rows = random_rows(&problem, 40, 3);
        let measures = Measure::batch_default();
        assert!(measures.iter().all(|m| m.cost() == MeasureCost::Read));
        assert!(!measures.iter().any(|m| m.name() == "gear_overlap_mm"));
        let batch = BatchRows::new(&problem, &resolution, &measures);
        let go_on = AtomicBool::new(false);
        let one = batch.run(None, &rows, &go_on).unwrap();
        let pool = crate::search::thread_pool(2).unwrap();
        let two = batch.run(Some(&pool), &rows, &go_on).unwrap();
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
        for row in valid {
            assert_eq!(row.tip_path, None);
            for (m, v) in measures.iter().zip(&row.measures) {
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

    /// The tip paths are the evaluations' own: each row's path is `evaluate`'s trajectory
    /// of that design, point for point, on any thread count.
    #[test]
    fn tip_paths_are_each_designs_trajectory() {
        let scene = load_scene(Some("paper-search")).unwrap();
        let problem = SceneProblem::new(&scene).unwrap();
        let resolution = scene.resolution;
        let rows = random_rows(&problem, 12, 5);
        let batch = BatchRows::new(&problem, &resolution, &[]).with_tip_paths(true);
        let pool = crate::search::thread_pool(2).unwrap();
        let out = batch
            .run(Some(&pool), &rows, &AtomicBool::new(false))
            .unwrap();
        let mut checked = 0;
        for (x, (_, outcome)) in rows.iter().zip(&out) {
            let mut design = scene.clone();
            problem.apply(&problem.encode(x), &mut design);
            let alone = Evaluator::new().evaluate(&design);
            match (outcome, alone) {
                (Ok(row), Ok(eval)) => {
                    let path = row.tip_path.as_ref().unwrap();
                    let tips = eval.kinematics.as_ref().unwrap().tips();
                    assert_eq!(path.len(), resolution.samples_per_turn);
                    assert_eq!(path.len(), tips.len());
                    for (p, t) in path.iter().zip(tips) {
                        assert_eq!(*p, <[f64; 2]>::from(*t));
                    }
                    checked += 1;
                }
                (Err(_), Err(_)) => {}
                (a, b) => panic!("batch {a:?} vs alone {:?}", b.map(|_| ())),
            }
        }
        assert!(checked >= 3, "{checked} valid designs");
    }

    /// Once stopped, a batch evaluates no row that had not started and says so; without a
    /// pool and with one.
    #[test]
    fn a_stopped_batch_skips_the_rows_not_started() {
        let scene = load_scene(Some("paper-search")).unwrap();
        let problem = SceneProblem::new(&scene).unwrap();
        let rows = random_rows(&problem, 64, 7);
        let batch = BatchRows::new(&problem, &scene.resolution, &[]);
        let pool = crate::search::thread_pool(2).unwrap();
        for pool in [None, Some(&pool)] {
            assert!(batch.run(pool, &rows, &AtomicBool::new(true)).is_none());
            let none = batch.run(pool, &[], &AtomicBool::new(true));
            assert_eq!(none.map(|rows| rows.len()), Some(0));
        }
    }
}
