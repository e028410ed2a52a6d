//! Reports: what the CLI prints, as serialisable structs and readable tables.

use noncirc_core::{GearPair, Result, Scene};
use serde::Serialize;

/// Everything `noncirc gear` reports about a gear pair.
#[derive(Debug, Clone, Serialize)]
pub struct GearReport {
    pub curve_kind: String,
    pub samples_per_turn: usize,
    pub centre_distance_mm: f64,
    pub centre_distance_error_estimate_mm: f64,
    pub closure_iterations: usize,
    pub perimeter_mm: f64,
    pub module_max_mm: f64,
    pub teeth: u32,
    pub module_limit_mm: f64,
    pub min_convex_radius_mm: f64,
    pub min_concave_radius_mm: Option<f64>,
    pub rho_min_mm: f64,
    pub rho_max_mm: f64,
    pub ratio_min: f64,
    pub ratio_max: f64,
}

impl GearReport {
    /// Solves the scene's gear pair and gathers the report.
    pub fn from_scene(scene: &Scene) -> Result<(Self, GearPair)> {
        let curve = scene.gear.curve.build()?;
        let pair = GearPair::solve(curve, scene.resolution)?;
        let module = pair.module(&scene.gear.module);
        let a = pair.centre_distance();
        let (mut rmin, mut rmax) = (f64::INFINITY, 0.0f64);
        for p in pair.samples() {
            rmin = rmin.min(p.rho);
            rmax = rmax.max(p.rho);
        }
        let kind = serde_json::to_value(&scene.gear.curve)
            .ok()
            .and_then(|v| v.get("kind").and_then(|k| k.as_str().map(String::from)))
            .unwrap_or_default();
        let report = GearReport {
            curve_kind: kind,
            samples_per_turn: scene.resolution.samples_per_turn,
            centre_distance_mm: a,
            centre_distance_error_estimate_mm: pair.closure().error_estimate,
            closure_iterations: pair.closure().iterations,
            perimeter_mm: pair.perimeter(),
            module_max_mm: module.module_max_mm,
            teeth: module.teeth,
            module_limit_mm: module.module_limit_mm,
            min_convex_radius_mm: module.min_convex_radius_mm,
            min_concave_radius_mm: module
                .min_concave_radius_mm
                .is_finite()
                .then_some(module.min_concave_radius_mm),
            rho_min_mm: rmin,
            rho_max_mm: rmax,
            ratio_min: (a - rmax) / rmax,
            ratio_max: (a - rmin) / rmin,
        };
        Ok((report, pair))
    }

    /// A readable two-column table.
    pub fn table(&self) -> String {
        let concave = self
            .min_concave_radius_mm
            .map_or("none (all convex)".to_string(), |r| format!("{r:.3} mm"));
        let rows = [
            (
                "pitch curve",
                format!(
                    "{} ({} samples/turn)",
                    self.curve_kind, self.samples_per_turn
                ),
            ),
            (
                "centre distance",
                format!(
                    "{:.6} mm  (± {:.1e} mm)",
                    self.centre_distance_mm, self.centre_distance_error_estimate_mm
                ),
            ),
            (
                "perimeter (both gears)",
                format!("{:.4} mm", self.perimeter_mm),
            ),
            (
                "pitch radius",
                format!("{:.3} .. {:.3} mm", self.rho_min_mm, self.rho_max_mm),
            ),
            (
                "ratio i12",
                format!("{:.4} .. {:.4}", self.ratio_min, self.ratio_max),
            ),
            (
                "least convex R_c",
                format!("{:.3} mm", self.min_convex_radius_mm),
            ),
            ("least concave |R_c|", concave),
            ("module bound", format!("{:.4} mm", self.module_limit_mm)),
            (
                "largest module",
                format!("{:.4} mm with {} teeth", self.module_max_mm, self.teeth),
            ),
        ];
        table(&rows)
    }
}

/// Formats `(label, value)` rows as an aligned two-column table.
pub fn table(rows: &[(&str, String)]) -> String {
    let width = rows.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
    rows.iter()
        .map(|(k, v)| format!("{k:<width$}  {v}\n"))
        .collect()
}
