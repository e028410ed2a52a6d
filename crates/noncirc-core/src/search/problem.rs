//! A search problem made from a scene: free parameters with bounds, the objectives'
//! violations as constraints, and goals to minimise.

use super::{Fitness, Goal, GoalQuantity};
use crate::error::{Error, Result};
use crate::evaluation::{Evaluation, Evaluator};
use crate::objectives::{Bounds, ObjectiveKind};
use crate::params::Param;
use crate::resolution::Resolution;
use crate::robustness::{least_normalised_margin, radius_count, robust_score, ToleranceSamples};
use crate::scene::{FreeParam, Scene};

/// Violation for a design the model refuses (invalid curve, under-resolved, …).
pub const INVALID_CV: f64 = 1e5;

/// The normalising scale of an objective's violation and margin: half the admissible
/// range for two-sided bounds, else a tenth of the bound (at least one unit).
pub fn scale(kind: ObjectiveKind, bounds: &Bounds) -> f64 {
    match kind.bounds(bounds) {
        (Some(l), Some(u)) => ((u - l) / 2.0).max(1e-9),
        (Some(b), None) | (None, Some(b)) => (b.abs() * 0.1).max(1.0),
        (None, None) => 1.0,
    }
}

/// The default free parameters around a three-arm design: the control radii (±60 %, at
/// least 5 mm), `Φ0` ± 60°, `β0` ± 60°, `S` ± 40 %, `H1` ± 40 % (below `S`), `γ0` ± 50°.
pub fn default_space(scene: &Scene) -> Vec<FreeParam> {
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
        match evaluator.evaluate_at(scratch, resolution) {
            Ok(eval) => {
                let bounds = &scratch.bounds;
                let cv = eval
                    .objectives
                    .iter()
                    .map(|o| o.violation / scale(o.kind, bounds))
                    .sum::<f64>();
                let cv = if cv.is_finite() {
                    cv.min(INVALID_CV)
                } else {
                    INVALID_CV
                };
                // Robust goals sample only designs that meet every objective as drawn.
                let f = self.minimised(evaluator, &eval, scratch, cv == 0.0);
                (Fitness { cv, f }, Ok(eval))
            }
            Err(e) => (
                Fitness {
                    cv: INVALID_CV,
                    f: vec![INVALID_CV; self.goals.len()],
                },
                Err(e),
            ),
        }
    }
}
