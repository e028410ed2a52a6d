//! The outcome of one evaluation: the gear pair's summary, the objectives, the events, the
//! motion, and what else the scene asked for (the evaluator runs the stages).

use crate::agronomy::Agronomy;
use crate::anatomy::{anatomy, Anatomy};
use crate::constraint::ConstraintValue;
use crate::events::Events;
use crate::fit::FitReport;
use crate::gear::{GearPair, ModuleReport};
use crate::moving_box::BoxReport;
use crate::objective_kind::{Bounds, ObjectiveKind};
use crate::objectives::ObjectiveValue;
use crate::planetary::Kinematics;
use crate::resolution::Resolution;
use crate::scene::{Scene, SceneKind};
use crate::strength::Strength;
use crate::teeth::TeethReport;
use serde::Serialize;

/// A gear pair's summary: the (first) pair's geometry and the train's module.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GearSummary {
    pub centre_distance_mm: f64,
    pub closure_error_mm: f64,
    pub perimeter_mm: f64,
    /// The train with two pairs: the intermediate–planet pair's geometry.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub second: Option<PairGeometry>,
    /// The module of the pair that limits it.
    pub module: ModuleReport,
}

/// A closed pair's geometry (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PairGeometry {
    pub centre_distance_mm: f64,
    pub closure_error_mm: f64,
    pub perimeter_mm: f64,
}

impl PairGeometry {
    /// The geometry of a solved pair.
    pub fn of(pair: &GearPair) -> Self {
        Self {
            centre_distance_mm: pair.centre_distance(),
            closure_error_mm: pair.closure().error_estimate,
            perimeter_mm: pair.perimeter(),
        }
    }
}

/// The outcome of one evaluation, with the resolution that produced it.
#[derive(Debug, Clone)]
pub struct Evaluation {
    pub resolution: Resolution,
    pub kind: SceneKind,
    pub centre_distance_mm: Option<f64>,
    pub gear: Option<GearSummary>,
    pub objectives: Vec<ObjectiveValue>,
    pub events: Option<Events>,
    pub moving_box: Option<BoxReport>,
    /// The three-arm train's motion (it owns the solved sun–intermediate pair).
    pub kinematics: Option<Kinematics>,
    /// A gear scene's solved pair (three-arm scenes: see [`Evaluation::pair`]).
    pub gear_pair: Option<GearPair>,
    /// The teeth's checks, when the module rule is `teeth`.
    pub teeth: Option<TeethReport>,
    /// The train with two pairs: the intermediate–planet pair's teeth, cut with the same
    /// tooth count.
    pub second_teeth: Option<TeethReport>,
    /// The fit to the scene's target, when it has one.
    pub fit: Option<FitReport>,
    /// The teeth's strength at working speed, when an objective asks for it; or why there
    /// is none (the teeth cannot be cut, the dynamics cannot be solved).
    pub strength: Option<Strength>,
    pub strength_unavailable: Option<String>,
    /// The scene's `search.constraints`, each scored on its measure (three-arm and
    /// transplanter scenes).
    pub constraints: Vec<ConstraintValue>,
}

impl Evaluation {
    /// An evaluation of `scene` at `resolution` before any stage ran.
    pub(crate) fn empty(scene: &Scene, resolution: Resolution) -> Self {
        Self {
            resolution,
            kind: scene.kind,
            centre_distance_mm: None,
            gear: None,
            objectives: Vec::with_capacity(scene.objectives.len()),
            events: None,
            moving_box: None,
            kinematics: None,
            gear_pair: None,
            teeth: None,
            second_teeth: None,
            fit: None,
            strength: None,
            strength_unavailable: None,
            constraints: Vec::new(),
        }
    }

    /// Sum of the objectives' and the constraints' violations, each in its unit (0: every
    /// requested objective and every constraint is met).
    pub fn total_violation(&self) -> f64 {
        let objectives: f64 = self.objectives.iter().map(|o| o.violation).sum();
        objectives + self.constraints.iter().map(|c| c.violation).sum::<f64>()
    }

    /// Sum of the objectives' and the constraints' violations, each over its scale (an
    /// objective's [`scale`] under `bounds`, a constraint's [`Constraint::scale`]): what
    /// searches rank designs by before they meet everything (0: all met; infinite where a
    /// value is NaN).
    ///
    /// [`scale`]: crate::objective_kind::scale
    /// [`Constraint::scale`]: crate::constraint::Constraint::scale
    pub fn normalised_violation(&self, bounds: &Bounds) -> f64 {
        let objectives = (self.objectives.iter())
            .map(|o| o.normalised_violation(bounds))
            .sum::<f64>();
        let constraints = (self.constraints.iter())
            .map(|c| c.normalised_violation())
            .sum::<f64>();
        objectives + constraints
    }

    /// The trajectory's sections and their measures (computed on demand: searches that do
    /// not ask for them do not pay for them), for a three-arm evaluation.
    pub fn anatomy(&self, agro: &Agronomy) -> Option<Anatomy> {
        Some(anatomy(
            self.kinematics.as_ref()?,
            agro,
            self.events.as_ref()?,
        ))
    }

    /// The solved gear pair of the evaluation, if it has one: a gear scene's pair, or the
    /// three-arm train's sun–intermediate pair on the carrier grid.
    pub fn pair(&self) -> Option<&GearPair> {
        (self.kinematics.as_ref().map(Kinematics::pair)).or(self.gear_pair.as_ref())
    }

    /// The value of one objective, if it was evaluated.
    pub fn objective(&self, kind: ObjectiveKind) -> Option<&ObjectiveValue> {
        self.objectives.iter().find(|o| o.kind == kind)
    }
}
