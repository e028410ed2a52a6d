//! The studio's dynamics panel: `noncirc dynamics`'s numbers for the design being edited
//! (the cycle's summary, the carrier's speed with a constant drive torque, the flywheel
//! needed; the same functions, [`noncirc::dynamics::report_from`]) and one quantity's curves
//! over the carrier turn for the plot. The page picks the quantity, so that a drag sends it
//! one set of curves, not the report's twenty.

use noncirc::core::{Dynamics, DynamicsSummary};
use noncirc::dynamics::{magnitudes, DynamicsReport};
use serde::Serialize;
use std::f64::consts::TAU;

/// Revolutions per minute in a radian per second.
const RPM: f64 = 60.0 / TAU;

/// The quantities the panel plots over the carrier angle: name, label, unit.
pub const QUANTITIES: [(&str, &str, &str); 6] = [
    ("input_torque", "input torque", "N·m"),
    ("mesh_forces", "mesh force, arm set I", "N"),
    ("axle_forces", "axle and bearing load", "N"),
    ("shaking_force", "shaking force on the frame", "N"),
    ("shaking_moment", "shaking moment on the frame", "N·m"),
    (
        "carrier_speed",
        "carrier speed, constant drive torque",
        "r/min",
    ),
];

/// The panel's numbers and the chosen quantity's curves.
#[derive(Serialize)]
pub struct DynamicsView<'a> {
    /// Working speed: the carrier's (r/min) and its arm sets.
    carrier_rpm: f64,
    arms: usize,
    summary: &'a DynamicsSummary,
    /// With a constant drive torque and the scene's flywheel: that torque (N·m), the
    /// carrier's least and largest speed (r/min), `(ω_max − ω_min)/ω_mean`.
    drive_torque_nm: f64,
    carrier_rpm_range: [f64; 2],
    speed_fluctuation: f64,
    flywheel_inertia_kg_m2: f64,
    /// The least flywheel for `speed_fluctuation_allowed` (kg·m²).
    flywheel_needed_kg_m2: f64,
    speed_fluctuation_allowed: f64,
    /// Carrier angle of each node (°) and the quantity's curves at them.
    carrier_deg: &'a [f64],
    quantity: Quantity,
}

/// One quantity over the turn.
#[derive(Serialize)]
struct Quantity {
    name: &'static str,
    label: &'static str,
    unit: &'static str,
    /// `(name, values)` of each curve.
    curves: Vec<(String, Vec<f64>)>,
}

impl<'a> DynamicsView<'a> {
    /// The view of `r` with the curves of `quantity` (one of [`QUANTITIES`]' names); `None`
    /// for another name.
    pub fn new(r: &'a DynamicsReport, quantity: &str) -> Option<Self> {
        let (name, label, unit) = *QUANTITIES.iter().find(|(n, ..)| *n == quantity)?;
        let d: &Dynamics = &r.dynamics;
        let speed = &r.speed.carrier_speed_rad_s;
        let rpm = |w: &[f64]| w.iter().map(|w| w * RPM).collect::<Vec<_>>();
        let curves = match name {
            "input_torque" => vec![
                ("input torque".into(), d.input_torque_nm.clone()),
                (
                    "its share for gravity and the tip's loads".into(),
                    d.load_torque_nm.clone(),
                ),
            ],
            "mesh_forces" => vec![
                ("sun–intermediate".into(), d.mesh_force_n[0].clone()),
                ("intermediate–planet".into(), d.mesh_force_n[1].clone()),
            ],
            "axle_forces" => vec![
                ("sun shaft".into(), magnitudes(&d.sun_shaft_n)),
                ("carrier bearing".into(), magnitudes(&d.carrier_bearing_n)),
                (
                    "intermediate axle (arm set I)".into(),
                    magnitudes(&d.intermediate_axle_n),
                ),
                (
                    "planet axle (arm set I)".into(),
                    magnitudes(&d.planet_axle_n),
                ),
            ],
            "shaking_force" => vec![("|F|".into(), magnitudes(&d.shaking_force_n))],
            "shaking_moment" => vec![("M".into(), d.shaking_moment_nm.clone())],
            _ => {
                let mut curves = vec![(
                    format!("flywheel Jf = {} kg·m²", r.speed.flywheel_inertia_kg_m2),
                    rpm(speed),
                )];
                // The flywheel needed, where it differs from the scene's.
                let needed = r.flywheel_needed_kg_m2;
                if (needed - r.speed.flywheel_inertia_kg_m2).abs() > 1e-9 * needed.max(1e-12) {
                    curves.push((
                        format!("flywheel needed, {needed:.4} kg·m²"),
                        rpm(&d.speed_with(needed).carrier_speed_rad_s),
                    ));
                }
                curves
            }
        };
        let (least, largest) = (speed.iter())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &w| {
                (l.min(w), h.max(w))
            });
        Some(Self {
            carrier_rpm: d.carrier_speed_rad_s * RPM,
            arms: d.arms,
            summary: &d.summary,
            drive_torque_nm: r.speed.drive_torque_nm,
            carrier_rpm_range: [least * RPM, largest * RPM],
            speed_fluctuation: r.speed.coefficient,
            flywheel_inertia_kg_m2: r.speed.flywheel_inertia_kg_m2,
            flywheel_needed_kg_m2: r.flywheel_needed_kg_m2,
            speed_fluctuation_allowed: r.speed_fluctuation_allowed,
            carrier_deg: &d.carrier_deg,
            quantity: Quantity {
                name,
                label,
                unit,
                curves,
            },
        })
    }
}
