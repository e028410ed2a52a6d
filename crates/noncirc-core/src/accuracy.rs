//! Errors of an evaluation against a converged reference: the speed–accuracy trade.

use crate::curve::TAU;
use crate::evaluation::Evaluation;
use serde::Serialize;

/// Absolute errors of one evaluation against a reference (same scene).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorRow {
    /// Centre distance (mm).
    pub centre_distance_mm: f64,
    /// Largest tip-position difference over the probe angles (mm).
    pub trajectory_mm: f64,
    /// Largest difference of the picking and planting carrier angles (deg).
    pub event_angle_deg: f64,
    /// Largest difference of the picking and planting attitudes (deg).
    pub attitude_deg: f64,
    /// Per objective, by name: |value − reference value| in its unit.
    pub objectives: Vec<(String, f64)>,
    /// Moving-box travel while picking (mm).
    pub box_travel_mm: f64,
}

impl ErrorRow {
    /// The largest error among the quantities in mm and in degrees: `(mm, deg)`.
    pub fn worst(&self) -> (f64, f64) {
        (
            self.centre_distance_mm
                .max(self.trajectory_mm)
                .max(self.box_travel_mm),
            self.event_angle_deg.max(self.attitude_deg),
        )
    }
}

fn angle_diff(a: f64, b: f64) -> f64 {
    ((a - b + 0.5 * TAU).rem_euclid(TAU) - 0.5 * TAU).abs()
}

/// Each output's error of `eval` against `reference`, probing the trajectory at `probes`
/// carrier angles.
pub fn output_errors(eval: &Evaluation, reference: &Evaluation, probes: usize) -> ErrorRow {
    let diff = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs(),
        _ => 0.0,
    };
    let trajectory_mm = match (&eval.kinematics, &reference.kinematics) {
        (Some(k), Some(r)) => (0..probes)
            .map(|i| {
                let t = TAU * (i as f64 + 0.5) / probes as f64;
                let (p, q) = (k.state_at(t).tip, r.state_at(t).tip);
                (p - q).hypot()
            })
            .fold(0.0, f64::max),
        _ => 0.0,
    };
    let (event_angle_deg, attitude_deg) = match (&eval.events, &reference.events) {
        (Some(e), Some(r)) => (
            angle_diff(e.picking.carrier_rad, r.picking.carrier_rad)
                .max(angle_diff(e.planting.carrier_rad, r.planting.carrier_rad))
                .to_degrees(),
            (e.picking.attitude_deg - r.picking.attitude_deg)
                .abs()
                .max((e.planting.attitude_deg - r.planting.attitude_deg).abs()),
        ),
        _ => (0.0, 0.0),
    };
    let objectives = eval
        .objectives
        .iter()
        .filter_map(|o| {
            reference
                .objective(o.kind)
                .map(|r| (o.kind.name().to_string(), (o.value - r.value).abs()))
        })
        .collect();
    ErrorRow {
        centre_distance_mm: diff(eval.centre_distance_mm, reference.centre_distance_mm),
        trajectory_mm,
        event_angle_deg,
        attitude_deg,
        objectives,
        box_travel_mm: diff(
            eval.moving_box.map(|b| b.elliptic_delta_h_mm),
            reference.moving_box.map(|b| b.elliptic_delta_h_mm),
        ),
    }
}

/// Observed convergence order between two levels: `log(e1/e2) / log(n2/n1)`.
pub fn observed_order(n1: usize, e1: f64, n2: usize, e2: f64) -> Option<f64> {
    (e1 > 0.0 && e2 > 0.0).then(|| (e1 / e2).ln() / (n2 as f64 / n1 as f64).ln())
}
