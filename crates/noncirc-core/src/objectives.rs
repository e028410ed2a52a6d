//! The eight agronomic objectives of the three-arm paper (spec §3) and a ninth, that a
//! machine can pick at the picking point, with value, bounds, unit and violation.

use crate::agronomy::{Agronomy, Travel};
use crate::angle::node_index;
use crate::curve::{parabola_vertex, TAU};
use crate::events::{events, housing_radius, Events};
use crate::gear::{ModuleReport, ModuleRule};
use crate::interference::interference_clearance;
use crate::objective_kind::{scale, Bounds, ObjectiveKind};
use crate::planetary::Kinematics;
use crate::strength::Strength;
use serde::Serialize;

/// One objective's outcome.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ObjectiveValue {
    pub kind: ObjectiveKind,
    pub value: f64,
    pub lower: Option<f64>,
    pub upper: Option<f64>,
    /// 0 when met, else the distance to the violated bound (in the value's unit).
    pub violation: f64,
    /// Distance inside the nearest bound (negative when violated).
    pub margin: f64,
}

impl ObjectiveValue {
    /// Scores `value` against the kind's bounds.
    pub fn new(kind: ObjectiveKind, value: f64, bounds: &Bounds) -> Self {
        let (lower, upper) = kind.bounds(bounds);
        let below = lower.map_or(f64::INFINITY, |l| value - l);
        let above = upper.map_or(f64::INFINITY, |u| u - value);
        let margin = below.min(above);
        let violation = if value.is_nan() {
            f64::INFINITY
        } else {
            (-margin).max(0.0)
        };
        Self {
            kind,
            value,
            lower,
            upper,
            violation,
            margin,
        }
    }
}

impl ObjectiveValue {
    /// The violation over the kind's [`scale`] under `bounds`: this objective's term of an
    /// evaluation's normalised violation, which searches rank designs by.
    pub fn normalised_violation(&self, bounds: &Bounds) -> f64 {
        self.violation / scale(self.kind, bounds)
    }

    /// Adds the teeth's shortfalls (in modules, so × the module in mm) to the module
    /// objective's violation: a module whose teeth fail a check is not met.
    pub fn add_teeth(&mut self, teeth: Option<&crate::teeth::TeethReport>) {
        if let Some(t) = teeth {
            let extra = t.violation * t.module_mm;
            if extra > 0.0 {
                self.violation += extra;
                self.margin = self.margin.min(-extra);
            }
        }
    }
}

/// The machine's travel direction along x (+1 or −1), resolving [`Travel::Auto`].
pub fn travel_sign(agro: &Agronomy, ev: &Events) -> f64 {
    match agro.travel {
        Travel::PlusX => 1.0,
        Travel::MinusX => -1.0,
        Travel::Auto => {
            if ev.planting_tip_d1.x > 0.0 {
                -1.0
            } else {
                1.0
            }
        }
    }
}

/// The machine's advance per radian of carrier (mm/rad): one plant spacing per arm, so
/// `arms` spacings per turn.
pub fn advance_per_rad(arms: usize, agro: &Agronomy) -> f64 {
    arms as f64 * agro.plant_spacing_mm / TAU
}

/// Objective 5: worst forward excursion of the tip past the planted seedling in the ground
/// frame, from the planting instant (excursion 0) until the tip rises above the seedling
/// (mm; 0 when the tip never comes forward past it, which meets the bound `≤ 0`).
pub(crate) fn seedling_push(kin: &Kinematics, agro: &Agronomy, ev: &Events) -> f64 {
    let n = kin.len();
    let h = TAU / n as f64;
    let advance = advance_per_rad(kin.arms(), agro);
    let tp = ev.planting.carrier_rad;
    let forward = travel_sign(agro, ev);
    let top = ev.planting.tip_mm.y + agro.seedling_height_mm;
    let ahead = |x: f64, t: f64| forward * (x - ev.planting.tip_mm.x) + advance * (t - tp);
    let first = (tp / h).floor() as usize + 1;
    // The largest positive excursion ahead, with its neighbours along the path for the
    // parabola (`before` is set only with a positive `worst`).
    let (mut worst, mut before, mut after) = (0.0f64, None, None);
    let mut previous = None;
    for k in first..first + n {
        let p = kin.tips()[if k >= n { k - n } else { k }];
        if p.y > top {
            break;
        }
        let v = ahead(p.x, node_index(k) * h);
        if before.is_some() && after.is_none() {
            after = Some(v);
        }
        if v > worst {
            (worst, before, after) = (v, previous, None);
        }
        previous = Some(v);
    }
    match (before, after) {
        (Some(ym), Some(yp)) => -parabola_vertex(-ym, -worst, -yp),
        _ => worst,
    }
}

/// Objective 6: clearance between the gearbox housing (the gears' envelope around the
/// carrier axis plus the wall margin) and the ground (mm).
pub(crate) fn ground_clearance(kin: &Kinematics, agro: &Agronomy, ev: &Events) -> f64 {
    let housing = housing_radius(kin, agro);
    let ground = ev.y_min_mm + agro.planting_depth_mm;
    -housing - ground
}

/// One objective's value for a moved mechanism. `ev` must be given when `needs_events`,
/// `gear_module` (from [`module`], computed once per design) for the module objective, and
/// the teeth's `strength` for the safety factors (`None`: the teeth cannot be cut, and
/// their safety factor is 0).
pub(crate) fn objective_value(
    kind: ObjectiveKind,
    kin: &Kinematics,
    ev: Option<&Events>,
    agro: &Agronomy,
    gear_module: Option<&ModuleReport>,
    strength: Option<&Strength>,
) -> f64 {
    let ev = || ev.expect("events are located before the objectives that need them");
    match kind {
        ObjectiveKind::Interference => interference_clearance(kin, agro),
        ObjectiveKind::PickingAngle => ev().picking.attitude_deg,
        ObjectiveKind::PushingAngle => ev().planting.attitude_deg,
        ObjectiveKind::AngleDifference => ev().planting.attitude_deg - ev().picking.attitude_deg,
        ObjectiveKind::SeedlingPush => seedling_push(kin, agro, ev()),
        ObjectiveKind::GroundClearance => ground_clearance(kin, agro, ev()),
        ObjectiveKind::TrajectoryHeight => ev().y_max_mm - ev().y_min_mm,
        ObjectiveKind::PickingAdmissible => ev().check.margin_mm(),
        ObjectiveKind::Module => {
            gear_module
                .expect("the module is computed before the objective that needs it")
                .module_max_mm
        }
        ObjectiveKind::BendingSafety => strength.map_or(0.0, |s| s.bending_safety_min),
        ObjectiveKind::ContactSafety => strength.map_or(0.0, |s| s.contact_safety_min),
    }
}

/// Every default objective ([`ObjectiveKind::DEFAULT`]) with its value, in the paper's
/// order, and the events.
pub fn evaluate_all(
    kin: &Kinematics,
    agro: &Agronomy,
    bounds: &Bounds,
    rule: &ModuleRule,
) -> (Vec<ObjectiveValue>, Events) {
    let ev = events(kin, agro);
    let gear_module = kin.module(rule);
    let values = ObjectiveKind::DEFAULT
        .iter()
        .map(|&kind| {
            ObjectiveValue::new(
                kind,
                objective_value(kind, kin, Some(&ev), agro, Some(&gear_module), None),
                bounds,
            )
        })
        .collect();
    (values, ev)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn violation_is_distance_to_the_violated_bound() {
        let b = Bounds::default();
        let v = ObjectiveValue::new(ObjectiveKind::PickingAngle, 20.0, &b);
        assert_eq!(v.violation, 5.0);
        let v = ObjectiveValue::new(ObjectiveKind::PickingAngle, -7.0, &b);
        assert_eq!(v.violation, 2.0);
        let v = ObjectiveValue::new(ObjectiveKind::PickingAngle, 0.0, &b);
        assert_eq!((v.violation, v.margin), (0.0, 5.0));
        let v = ObjectiveValue::new(ObjectiveKind::TrajectoryHeight, 250.0, &b);
        assert_eq!(v.violation, 10.0);
    }
}
