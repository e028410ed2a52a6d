//! A search problem made from a scene: free parameters with bounds, the objectives' and
//! the search constraints' violations as constraints, and goals to minimise.

use crate::error::{Error, Result};
use crate::evaluation::Evaluation;
use crate::evaluator::{Evaluator, Screened};
use crate::goal::{Goal, GoalQuantity, INVALID_CV};
use crate::measure_value::Measured;
use crate::objective_kind::scale;
use crate::objectives::ObjectiveValue;
use crate::params::Param;
use crate::resolution::Resolution;
use crate::robustness::{
    least_normalised_margin, radius_count, robust_score, RobustScore, ToleranceSamples,
};
use crate::scene::{FreeParam, Scene};
use noncirc_search::Fitness;

/// The default free parameters around a three-arm design: the control radii (±60 %, at
/// least 5 mm), `Φ0` ± 60°, `β0` ± 60°, `S` ± 40 %, `H1` ± 40 % (below `S`), `γ0` ± 50°.
pub(crate) fn default_space(scene: &Scene) -> Vec<FreeParam> {
    let mut free = Vec::new();
    if let Some(radii) = match &scene.gear.curve {
        crate::curve::CurveSpec::Spline { radii_mm, .. }
        | crate::curve::CurveSpec::Bspline { radii_mm, .. }
        | crate::curve::CurveSpec::Bezier { radii_mm, .. } => Some(radii_mm),
        _ => None,
    } {
        for (i, r) in radii.iter().enumerate() {
            free.push(FreeParam {
                name: format!("gear.curve.radii_mm[{i}]"),
                lower: (0.4 * r).max(5.0),
                upper: 1.6 * r,
            });
        }
    }
    let t = &scene.train;
    free.push(FreeParam {
        name: "train.phi0_deg".into(),
        lower: t.phi0_deg - 60.0,
        upper: t.phi0_deg + 60.0,
    });
    free.push(FreeParam {
        name: "train.beta0_deg".into(),
        lower: t.beta0_deg - 60.0,
        upper: t.beta0_deg + 60.0,
    });
    free.push(FreeParam {
        name: "train.arm_length_mm".into(),
        lower: 0.6 * t.arm_length_mm,
        upper: 1.4 * t.arm_length_mm,
    });
    free.push(FreeParam {
        name: "train.pusher_offset_mm".into(),
        lower: 0.6 * t.pusher_offset_mm,
        upper: (1.4 * t.pusher_offset_mm).min(0.59 * t.arm_length_mm),
    });
    free.push(FreeParam {
        name: "train.gamma0_deg".into(),
        lower: t.gamma0_deg - 50.0,
        upper: t.gamma0_deg + 50.0,
    });
    free
}

/// Weight of an objective's normalised violation among a fit's residuals: a tenth of an
/// objective's scale costs as much as a path one tolerance off everywhere.
pub const VIOLATION_WEIGHT: f64 = 10.0;

/// Each residual of a design the model refuses, in a fit: far above any design it takes.
pub const REFUSED_RESIDUAL: f64 = 1e3;

/// The search problem.
#[derive(Debug, Clone)]
pub struct SceneProblem {
    base: Scene,
    params: Vec<Param>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    goals: Vec<Goal>,
    screening: Resolution,
    /// The deviations every design meets under robust goals (common random numbers).
    tolerance_samples: Option<ToleranceSamples>,
}

impl SceneProblem {
    /// Builds the problem from the scene's `[search]` settings (default space if empty).
    pub fn new(scene: &Scene) -> Result<Self> {
        scene.validate()?;
        scene.validate_search()?;
        let free = if scene.search.free.is_empty() {
            default_space(scene)
        } else {
            scene.search.free.clone()
        };
        let mut params = Vec::with_capacity(free.len());
        let (mut lower, mut upper) = (Vec::new(), Vec::new());
        for f in &free {
            params.push(Param::parse(&f.name, scene)?);
            // The default space is derived from the scene's values: check it as a user's.
            if !(f.lower < f.upper && (f.upper - f.lower).is_finite()) {
                return Err(Error::OutOfRange {
                    name: format!("bounds of '{}'", f.name),
                    value: f.lower,
                    expected: format!("finite lower < upper (upper = {})", f.upper),
                });
            }
            lower.push(f.lower);
            upper.push(f.upper);
        }
        let goals = if scene.search.goals.is_empty() {
            vec![Goal::LeastMargin]
        } else {
            scene.search.goals.clone()
        };
        scene.search.screening.validate()?;
        let tolerance_samples = if goals.iter().any(|g| g.is_robust()) {
            let tol = &scene.tolerances;
            Some(ToleranceSamples::new(
                tol,
                radius_count(&scene.gear.curve),
                tol.seed,
            )?)
        } else {
            None
        };
        Ok(Self {
            tolerance_samples,
            base: scene.clone(),
            params,
            lower,
            upper,
            goals,
            screening: scene.search.screening,
        })
    }

    /// Number of free parameters.
    pub fn dim(&self) -> usize {
        self.params.len()
    }

    /// Number of goals.
    pub fn goals(&self) -> usize {
        self.goals.len()
    }

    /// The goals, in the order of each fitness's values.
    pub fn goal_list(&self) -> &[Goal] {
        &self.goals
    }

    /// The goals in physical terms: their quantities' names with units, and directions.
    pub fn goal_quantities(&self) -> Vec<GoalQuantity> {
        (self.goals.iter())
            .map(|g| g.quantity(&self.base.bounds))
            .collect()
    }

    /// The goals' quantities in their units for an evaluation of `scene` (robust goals
    /// sample its tolerances again).
    pub fn goal_values_of(&self, eval: &Evaluation, scene: &Scene) -> Vec<f64> {
        let feasible = eval.total_violation() == 0.0;
        let f = self.minimised(&mut Evaluator::new(), eval, scene, feasible);
        (self.goals.iter().zip(f))
            .map(|(g, v)| g.physical(v, &scene.bounds))
            .collect()
    }

    /// The goals' minimised values for an evaluation of `scene`; robust goals sample the
    /// design's tolerances when it is `feasible` as drawn.
    fn minimised(
        &self,
        evaluator: &mut Evaluator,
        eval: &Evaluation,
        scene: &Scene,
        feasible: bool,
    ) -> Vec<f64> {
        let robust = (self.tolerance_samples.as_ref())
            .filter(|_| feasible)
            .and_then(|samples| robust_score(evaluator, scene, eval, samples).ok());
        (self.goals.iter())
            .map(|g| {
                if g.is_robust() {
                    g.robust_value(robust.as_ref(), least_normalised_margin(eval, scene))
                } else {
                    g.value(eval, scene)
                }
            })
            .collect()
    }

    /// The goals' quantities in their units, from a fitness's minimised values `f`.
    pub fn goal_values(&self, f: &[f64]) -> Vec<f64> {
        (self.goals.iter().zip(f))
            .map(|(g, &v)| g.physical(v, &self.base.bounds))
            .collect()
    }

    /// The free parameters' lower and upper bounds.
    pub fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }

    /// The free parameters' names.
    pub fn names(&self) -> Vec<&str> {
        self.params.iter().map(|p| p.name()).collect()
    }

    /// The scene the search started from.
    pub fn base(&self) -> &Scene {
        &self.base
    }

    /// The screening resolution.
    pub fn screening(&self) -> Resolution {
        self.screening
    }

    /// Unit-cube point to parameter values.
    pub fn decode(&self, u: &[f64]) -> Vec<f64> {
        self.decoded(u).collect()
    }

    /// As [`Self::decode`], without collecting.
    fn decoded<'a>(&'a self, u: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
        u.iter()
            .zip(self.lower.iter().zip(&self.upper))
            .map(|(u, (lo, hi))| lo + u.clamp(0.0, 1.0) * (hi - lo))
    }

    /// Parameter values to unit-cube point.
    pub fn encode(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .zip(self.lower.iter().zip(&self.upper))
            .map(|(x, (lo, hi))| ((x - lo) / (hi - lo)).clamp(0.0, 1.0))
            .collect()
    }

    /// Writes the design `u` into `scene` (a scratch copy of the base scene).
    pub fn apply(&self, u: &[f64], scene: &mut Scene) {
        for (p, x) in self.params.iter().zip(self.decoded(u)) {
            p.set(scene, x);
        }
    }

    /// The full scene of design `u`.
    pub fn scene_at(&self, u: &[f64]) -> Scene {
        let mut s = self.base.clone();
        self.apply(u, &mut s);
        s
    }

    /// Evaluates design `u` at `resolution`: the fitness, and the evaluation if it succeeded.
    pub fn fitness(
        &self,
        u: &[f64],
        evaluator: &mut Evaluator,
        scratch: &mut Scene,
        resolution: &Resolution,
    ) -> (Fitness, Option<Evaluation>) {
        self.apply(u, scratch);
        let (fitness, outcome) = self.score(evaluator, scratch, resolution);
        (fitness, outcome.ok())
    }

    /// As [`SceneProblem::fitness`], without the evaluation: a search's usual call. An
    /// evaluation is some kilobytes, and handing it back would copy them.
    pub fn fitness_alone(
        &self,
        u: &[f64],
        evaluator: &mut Evaluator,
        scratch: &mut Scene,
        resolution: &Resolution,
    ) -> Fitness {
        self.apply(u, scratch);
        let outcome = evaluator.evaluate_beside(scratch, Some(&self.base), resolution);
        self.scored(evaluator, scratch, outcome.as_ref())
    }

    /// As [`SceneProblem::fitness`] for a design that competes with a `rival` (DE's trial
    /// against its target): a design whose violation part-way already exceeds the rival's
    /// is not finished, and gets that lower bound of its violation with every goal at
    /// [`INVALID_CV`] (it loses to the rival either way; `BatchEvaluator::evaluate_against`).
    pub fn fitness_against(
        &self,
        u: &[f64],
        rival: &Fitness,
        evaluator: &mut Evaluator,
        scratch: &mut Scene,
        resolution: &Resolution,
    ) -> Fitness {
        // A violation above INVALID_CV scores INVALID_CV: a rival there cannot be beaten
        // by the violation alone.
        if rival.cv.is_nan() || rival.cv >= INVALID_CV {
            return self.fitness_alone(u, evaluator, scratch, resolution);
        }
        self.apply(u, scratch);
        match evaluator.evaluate_beside_unless_beaten(
            scratch,
            Some(&self.base),
            resolution,
            rival.cv,
        ) {
            Ok(Screened::Beaten { violation_at_least }) => Fitness {
                cv: violation_at_least.min(INVALID_CV),
                f: vec![INVALID_CV; self.goals.len()],
            },
            Ok(Screened::Evaluated(eval)) => self.scored(evaluator, scratch, Ok(&eval)),
            Err(e) => self.scored(evaluator, scratch, Err(&e)),
        }
    }

    /// How many residuals [`SceneProblem::fit_residuals`] gives at `resolution`: the
    /// target's ([`FitReport::residuals`](crate::fit::FitReport)), then one per objective
    /// and one per constraint.
    pub fn fit_residual_count(&self, resolution: &Resolution) -> usize {
        let target = self.base.target.as_deref();
        let path = target
            .filter(|t| t.counts)
            .map_or(0, |t| t.samples + resolution.samples_per_turn);
        let poses: usize = (target.map_or(&[][..], |t| &t.poses[..]).iter())
            .filter(|p| p.counts)
            .map(|p| 2 + p.attitude_deg.is_some() as usize + p.carrier_deg.is_some() as usize)
            .sum();
        let pulls = target.map_or(0, |t| t.design.len());
        path + poses + pulls + self.base.objectives.len() + self.base.search.constraints.len()
    }

    /// The residuals of design `u` for a fit at `resolution`: the fit's to the scene's
    /// target, then each objective's and each constraint's violation over its scale times
    /// [`VIOLATION_WEIGHT`] (zero when met); and the design's fitness. A design the model refuses (or a scene
    /// without a target) gives [`REFUSED_RESIDUAL`] for each.
    pub fn fit_residuals(
        &self,
        u: &[f64],
        evaluator: &mut Evaluator,
        scratch: &mut Scene,
        resolution: &Resolution,
    ) -> (Vec<f64>, Fitness) {
        let count = self.fit_residual_count(resolution);
        let (fitness, eval) = self.fitness(u, evaluator, scratch, resolution);
        let residuals = eval
            .and_then(|eval| {
                let mut r = eval.fit?.residuals;
                let bounds = &scratch.bounds;
                r.extend(
                    (eval.objectives.iter())
                        .map(|o| VIOLATION_WEIGHT * o.violation / scale(o.kind, bounds)),
                );
                r.extend(
                    (eval.constraints.iter()).map(|c| VIOLATION_WEIGHT * c.normalised_violation()),
                );
                (r.len() == count && r.iter().all(|x| x.is_finite())).then_some(r)
            })
            .unwrap_or_else(|| vec![REFUSED_RESIDUAL; count]);
        (residuals, fitness)
    }

    /// Evaluates the design with parameter values `x` (not clamped to the bounds): the
    /// fitness, and the evaluation or the error that refused it.
    pub fn fitness_at_values(
        &self,
        x: &[f64],
        evaluator: &mut Evaluator,
        scratch: &mut Scene,
        resolution: &Resolution,
    ) -> (Fitness, Result<Evaluation>) {
        for (p, v) in self.params.iter().zip(x) {
            p.set(scratch, *v);
        }
        self.score(evaluator, scratch, resolution)
    }

    fn score(
        &self,
        evaluator: &mut Evaluator,
        scratch: &Scene,
        resolution: &Resolution,
    ) -> (Fitness, Result<Evaluation>) {
        let outcome = evaluator.evaluate_beside(scratch, Some(&self.base), resolution);
        (self.scored(evaluator, scratch, outcome.as_ref()), outcome)
    }

    /// The fitness of an evaluation of `scratch`, or of the model's refusal. By reference:
    /// an evaluation is some kilobytes, and each move of it a copy.
    fn scored(
        &self,
        evaluator: &mut Evaluator,
        scratch: &Scene,
        outcome: std::result::Result<&Evaluation, &Error>,
    ) -> Fitness {
        match outcome {
            Ok(eval) => {
                let cv = eval.normalised_violation(&scratch.bounds);
                let cv = if cv.is_finite() {
                    cv.min(INVALID_CV)
                } else {
                    INVALID_CV
                };
                // Robust goals sample only designs that meet every objective as drawn.
                let f = self.minimised(evaluator, eval, scratch, cv == 0.0);
                Fitness { cv, f }
            }
            Err(_) => Fitness {
                cv: INVALID_CV,
                f: vec![INVALID_CV; self.goals.len()],
            },
        }
    }
}

/// The goals' values for an evaluation.
impl Goal {
    /// A robust goal's minimised value from the design's samples; `None` (a design that
    /// misses an objective at its nominal dimensions, whose samples are not drawn) scores
    /// probability 0 and its nominal least margin as the quantile.
    fn robust_value(self, score: Option<&RobustScore>, nominal_least: f64) -> f64 {
        let v = match (self, score) {
            (Goal::Probability, Some(s)) => -s.probability,
            (Goal::Probability, None) => 0.0,
            (Goal::MarginQuantile(q), Some(s)) => -s.margin_quantile(q),
            (Goal::MarginQuantile(_), None) => -nominal_least,
            _ => f64::NAN,
        };
        if v.is_finite() {
            v
        } else {
            INVALID_CV
        }
    }

    /// The goal's minimised value for an evaluation of `scene` (a robust goal's is
    /// [`Goal::robust_value`]); a value that is not finite scores [`INVALID_CV`].
    fn value(self, eval: &Evaluation, scene: &Scene) -> f64 {
        let bounds = &scene.bounds;
        let norm = |o: &ObjectiveValue| o.margin / scale(o.kind, bounds);
        let v = match self {
            Goal::LeastMargin => -least_normalised_margin(eval, scene),
            Goal::Margin(k) => -eval.objective(k).map_or(f64::NEG_INFINITY, norm),
            Goal::PickingTipSpeed => eval
                .events
                .as_ref()
                .map_or(f64::INFINITY, |e| e.picking_tip_speed_m_s),
            Goal::BoxTravel => eval
                .moving_box
                .as_ref()
                .map_or(f64::INFINITY, |b| b.elliptic_delta_h_mm),
            Goal::Probability | Goal::MarginQuantile(_) => f64::NAN,
            Goal::Fit => eval.fit.as_ref().map_or(f64::INFINITY, |f| f.cost),
            Goal::Measure { measure, maximise } => {
                let v = measure
                    .value(&Measured::new(eval, scene))
                    .unwrap_or(f64::NAN);
                if maximise {
                    -v
                } else {
                    v
                }
            }
        };
        if v.is_finite() {
            v
        } else {
            INVALID_CV
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objective_kind::ObjectiveKind;

    #[test]
    fn a_goal_physical_value_is_the_objective_or_its_margin_in_its_unit() {
        use crate::evaluator::Evaluator;
        let scene = Scene::default();
        let eval = Evaluator::new()
            .evaluate_at(&scene, &scene.resolution)
            .unwrap();
        let b = &scene.bounds;
        for &k in &ObjectiveKind::DEFAULT {
            let o = eval.objective(k).unwrap();
            let goal = Goal::Margin(k);
            let physical = goal.physical(goal.value(&eval, &scene), b);
            let expected = match k.bounds(b) {
                (Some(_), None) | (None, Some(_)) => o.value,
                _ => o.margin,
            };
            assert!(
                (physical - expected).abs() < 1e-9 * expected.abs().max(1.0),
                "{k:?}"
            );
        }
        let least = Goal::LeastMargin.value(&eval, &scene);
        assert_eq!(Goal::LeastMargin.physical(least, b), -least);
        assert!(Goal::PickingTipSpeed.physical(INVALID_CV, b).is_nan());
    }

    #[test]
    fn the_fit_residuals_are_as_many_as_counted_with_poses_and_design_pulls() {
        use crate::evaluator::Evaluator;
        let mut scene = Scene::default();
        let eval = Evaluator::new().evaluate(&scene).unwrap();
        let kin = eval.kinematics.unwrap();
        let mut target = crate::fit::target_of(&kin, eval.events.as_ref().unwrap(), 256);
        target.design = vec![crate::target::DesignPull {
            name: "train.gamma0_deg".into(),
            value: -50.0,
            scale: 1.5,
        }];
        scene.target = Some(std::sync::Arc::new(target));
        let problem = SceneProblem::new(&scene).unwrap();
        let u = vec![0.5; problem.dim()];
        let (mut evaluator, mut scratch) = (Evaluator::new(), scene.clone());
        for samples in [120, 720] {
            let resolution = scene.resolution.with_samples(samples);
            let (r, fitness) = problem.fit_residuals(&u, &mut evaluator, &mut scratch, &resolution);
            assert_eq!(r.len(), problem.fit_residual_count(&resolution));
            assert!(fitness.cv < INVALID_CV, "the design evaluates");
            assert!(
                r.iter().all(|x| *x != REFUSED_RESIDUAL),
                "{samples}: refused"
            );
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]
        /// Over random designs, a search constraint adds its normalised violation to the
        /// fitness's and nothing else: the value is the measure's, read without it, and
        /// the goals do not change.
        #[test]
        fn a_constraint_adds_its_normalised_violation_to_the_fitness(
            u in proptest::collection::vec(0.0..1.0f64, 17),
            bound in -130.0..-60.0f64,
            at_most in proptest::bool::ANY,
        ) {
            use crate::constraint::Constraint;
            use crate::measure::Measure;
            use crate::measure_value::Measured;
            let plain = Scene::default();
            let measure = Measure::parse("picking_height_mm").unwrap();
            let mut constrained = plain.clone();
            let c = Constraint { measure, bound, at_most };
            constrained.search.constraints = vec![c];
            let (without, with) = (SceneProblem::new(&plain).unwrap(), SceneProblem::new(&constrained).unwrap());
            proptest::prop_assert_eq!(without.dim(), u.len());
            let res = plain.search.screening;
            let mut evaluator = Evaluator::new();
            let (f0, e0) = without.fitness(&u, &mut evaluator, &mut plain.clone(), &res);
            let (f1, e1) = with.fitness(&u, &mut evaluator, &mut constrained.clone(), &res);
            // The search's call without the evaluation scores the same.
            let alone = with.fitness_alone(&u, &mut evaluator, &mut constrained.clone(), &res);
            proptest::prop_assert_eq!(&alone, &f1);
            match (e0, e1) {
                (Some(e0), Some(e1)) => {
                    let scene = without.scene_at(&u);
                    let value = measure.value(&Measured::new(&e0, &scene)).unwrap();
                    let reading = e1.constraints[0];
                    proptest::prop_assert_eq!(reading.value, value);
                    let past = if at_most { value - bound } else { bound - value };
                    proptest::prop_assert_eq!(reading.violation, past.max(0.0));
                    let expected = (f0.cv + past.max(0.0) / (0.1 * bound.abs()).max(1.0)).min(INVALID_CV);
                    proptest::prop_assert!((f1.cv - expected).abs() <= 1e-12 * expected.max(1.0), "{} vs {}", f1.cv, expected);
                    proptest::prop_assert_eq!(e1.total_violation() == 0.0, f1.cv == 0.0);
                    // The default goal, the least normalised margin, counts it too.
                    let margin = reading.margin / (0.1 * bound.abs()).max(1.0);
                    proptest::prop_assert_eq!(f1.f[0], f0.f[0].max(-margin));
                }
                (None, None) => {
                    proptest::prop_assert_eq!(f1.cv, INVALID_CV);
                    proptest::prop_assert_eq!(&f0.f, &f1.f);
                }
                _ => proptest::prop_assert!(false, "one evaluation refused, the other not"),
            }
        }
    }
}
