//! The objectives by kind (name, label, unit) and their admissible ranges ([`Bounds`]),
//! with the scale that normalises a violation or margin.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The admissible range of each objective (paper §4.1 defaults).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Bounds {
    /// Least clearance between arms and other planets (mm).
    pub clearance_min_mm: f64,
    /// Picking angle range (deg).
    pub picking_angle_deg: [f64; 2],
    /// Pushing (planting) angle range (deg).
    pub pushing_angle_deg: [f64; 2],
    /// Pushing − picking angle range (deg).
    pub angle_difference_deg: [f64; 2],
    /// Largest forward excursion past the planted seedling (mm).
    pub seedling_push_max_mm: f64,
    /// Least gearbox ground clearance (mm).
    pub ground_clearance_min_mm: f64,
    /// Least trajectory height (mm).
    pub trajectory_height_min_mm: f64,
    /// Least admissible module (mm).
    pub module_min_mm: f64,
    /// Least margin of the picking conditions (mm): how far the worst of them holds.
    pub picking_admissible_min_mm: f64,
    /// Least bending safety factor `SFmin` of the teeth at working speed (ISO 6336-1's
    /// usual minimum: 1.4).
    pub bending_safety_min: f64,
    /// Least contact (pitting) safety factor `SHmin` (ISO 6336-1's usual minimum: 1.0).
    pub contact_safety_min: f64,
}

impl Bounds {
    /// Every two-sided bound ordered, lower ≤ upper. (That every bound is finite, so
    /// that a NaN bound cannot count as met, is each field's interval in the field table,
    /// which `Scene::validate` checks first.)
    pub(crate) fn check_order(&self) -> Result<()> {
        for (name, [lower, upper]) in [
            ("bounds.picking_angle_deg", self.picking_angle_deg),
            ("bounds.pushing_angle_deg", self.pushing_angle_deg),
            ("bounds.angle_difference_deg", self.angle_difference_deg),
        ] {
            if lower > upper {
                return Err(Error::OutOfRange {
                    name: format!("{name}[1]"),
                    value: upper,
                    expected: format!("at least the lower bound {lower}"),
                });
            }
        }
        Ok(())
    }
}

impl Default for Bounds {
    fn default() -> Self {
        Self {
            clearance_min_mm: 0.0,
            picking_angle_deg: [-5.0, 15.0],
            pushing_angle_deg: [45.0, 65.0],
            angle_difference_deg: [50.0, 60.0],
            seedling_push_max_mm: 0.0,
            ground_clearance_min_mm: 20.0,
            trajectory_height_min_mm: 260.0,
            module_min_mm: 2.5,
            picking_admissible_min_mm: 0.0,
            bending_safety_min: 1.4,
            contact_safety_min: 1.0,
        }
    }
}

/// The paper's eight objectives in its order, then whether a machine can pick at all, then
/// the teeth's strength at working speed (the strength check that can replace the module
/// proxy; not among a scene's default objectives: it needs the dynamics and the cut teeth).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum ObjectiveKind {
    Interference,
    PickingAngle,
    PushingAngle,
    AngleDifference,
    SeedlingPush,
    GroundClearance,
    TrajectoryHeight,
    Module,
    PickingAdmissible,
    BendingSafety,
    ContactSafety,
}

impl ObjectiveKind {
    /// A scene's objectives by default: the paper's eight and `picking_admissible`, read
    /// from the kinematics alone.
    pub const DEFAULT: [ObjectiveKind; 9] = [
        ObjectiveKind::Interference,
        ObjectiveKind::PickingAngle,
        ObjectiveKind::PushingAngle,
        ObjectiveKind::AngleDifference,
        ObjectiveKind::SeedlingPush,
        ObjectiveKind::GroundClearance,
        ObjectiveKind::TrajectoryHeight,
        ObjectiveKind::Module,
        ObjectiveKind::PickingAdmissible,
    ];

    /// All eleven, in order: the default nine, then the teeth's strength.
    pub const ALL: [ObjectiveKind; 11] = {
        let mut all = [ObjectiveKind::ContactSafety; 11];
        let mut i = 0;
        while i < Self::DEFAULT.len() {
            all[i] = Self::DEFAULT[i];
            i += 1;
        }
        all[9] = ObjectiveKind::BendingSafety;
        all
    };

    /// Stable snake-case name.
    pub fn name(self) -> &'static str {
        match self {
            ObjectiveKind::Interference => "interference",
            ObjectiveKind::PickingAngle => "picking_angle",
            ObjectiveKind::PushingAngle => "pushing_angle",
            ObjectiveKind::AngleDifference => "angle_difference",
            ObjectiveKind::SeedlingPush => "seedling_push",
            ObjectiveKind::GroundClearance => "ground_clearance",
            ObjectiveKind::TrajectoryHeight => "trajectory_height",
            ObjectiveKind::Module => "module",
            ObjectiveKind::PickingAdmissible => "picking_admissible",
            ObjectiveKind::BendingSafety => "bending_safety",
            ObjectiveKind::ContactSafety => "contact_safety",
        }
    }

    /// What a person reads.
    pub fn label(self) -> &'static str {
        match self {
            ObjectiveKind::Interference => "no interference between arms",
            ObjectiveKind::PickingAngle => "picking angle",
            ObjectiveKind::PushingAngle => "pushing (planting) angle",
            ObjectiveKind::AngleDifference => "angle difference",
            ObjectiveKind::SeedlingPush => "arm does not push the seedling",
            ObjectiveKind::GroundClearance => "gearbox ground clearance",
            ObjectiveKind::TrajectoryHeight => "trajectory height",
            ObjectiveKind::Module => "gear module",
            ObjectiveKind::PickingAdmissible => "a machine can pick there",
            ObjectiveKind::BendingSafety => "teeth's least bending safety factor",
            ObjectiveKind::ContactSafety => "teeth's least contact safety factor",
        }
    }

    /// Unit of the value.
    pub fn unit(self) -> &'static str {
        match self {
            ObjectiveKind::PickingAngle
            | ObjectiveKind::PushingAngle
            | ObjectiveKind::AngleDifference => "deg",
            ObjectiveKind::BendingSafety | ObjectiveKind::ContactSafety => "",
            _ => "mm",
        }
    }

    /// `(lower, upper)` from the bounds; `None` is unbounded.
    pub fn bounds(self, b: &Bounds) -> (Option<f64>, Option<f64>) {
        match self {
            ObjectiveKind::Interference => (Some(b.clearance_min_mm), None),
            ObjectiveKind::PickingAngle => {
                (Some(b.picking_angle_deg[0]), Some(b.picking_angle_deg[1]))
            }
            ObjectiveKind::PushingAngle => {
                (Some(b.pushing_angle_deg[0]), Some(b.pushing_angle_deg[1]))
            }
            ObjectiveKind::AngleDifference => (
                Some(b.angle_difference_deg[0]),
                Some(b.angle_difference_deg[1]),
            ),
            ObjectiveKind::SeedlingPush => (None, Some(b.seedling_push_max_mm)),
            ObjectiveKind::GroundClearance => (Some(b.ground_clearance_min_mm), None),
            ObjectiveKind::TrajectoryHeight => (Some(b.trajectory_height_min_mm), None),
            ObjectiveKind::Module => (Some(b.module_min_mm), None),
            ObjectiveKind::PickingAdmissible => (Some(b.picking_admissible_min_mm), None),
            ObjectiveKind::BendingSafety => (Some(b.bending_safety_min), None),
            ObjectiveKind::ContactSafety => (Some(b.contact_safety_min), None),
        }
    }

    /// Whether this objective is the teeth's strength (it needs the dynamics at working
    /// speed and the cut teeth).
    pub fn needs_strength(self) -> bool {
        matches!(
            self,
            ObjectiveKind::BendingSafety | ObjectiveKind::ContactSafety
        )
    }

    /// Whether this objective needs the picking/planting events.
    pub fn needs_events(self) -> bool {
        !matches!(self, ObjectiveKind::Interference | ObjectiveKind::Module)
    }

    /// Whether this objective needs the arms' motion (all but the module).
    pub fn needs_kinematics(self) -> bool {
        self != ObjectiveKind::Module
    }
}

/// The normalising scale of an objective's violation and margin: half the admissible
/// range for two-sided bounds, else a tenth of the bound (at least one unit).
pub fn scale(kind: ObjectiveKind, bounds: &Bounds) -> f64 {
    match kind.bounds(bounds) {
        (Some(l), Some(u)) => ((u - l) / 2.0).max(1e-9),
        (Some(b), None) | (None, Some(b)) => (b.abs() * 0.1).max(1.0),
        (None, None) => 1.0,
    }
}
