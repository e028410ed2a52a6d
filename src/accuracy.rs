//! `noncirc accuracy`: each output's error and the time per evaluation over a ladder of
//! resolutions, against a converged reference that is itself checked.

use crate::report::table;
use noncirc_core::{observed_order, output_errors, ErrorRow};
use noncirc_core::{Evaluation, Evaluator, Resolution, Scene};
use serde::Serialize;
use std::time::Instant;

/// Samples per turn of the ladder, coarse to fine.
pub const LADDER: &[usize] = &[30, 60, 90, 120, 180, 240, 360, 480, 720, 1440, 2880];
/// The two reference levels: the finer is the reference, the coarser checks it.
pub const REFERENCE: [usize; 2] = [5760, 11520];

/// One rung of the ladder.
#[derive(Debug, Clone, Serialize)]
pub struct Level {
    pub samples_per_turn: usize,
    pub newton_rel_tol: f64,
    /// Mean wall time of one evaluation (µs); `None` if the level failed.
    pub time_us: Option<f64>,
    pub errors: Option<ErrorRow>,
    /// Why the level failed (e.g. the closure is under-resolved).
    pub error: Option<String>,
    /// Observed order of the worst mm error against the previous successful level.
    pub order_mm: Option<f64>,
}

/// The whole measurement.
#[derive(Debug, Clone, Serialize)]
pub struct AccuracyReport {
    pub scene: String,
    pub reference_samples: usize,
    /// The reference's own uncertainty: the coarser reference level against it.
    pub reference_check: ErrorRow,
    pub levels: Vec<Level>,
    pub tolerance_ladder: Vec<Level>,
}

fn timed(scene: &Scene, res: &Resolution) -> Result<(Evaluation, f64), String> {
    let mut ev = Evaluator::new();
    let first = ev.evaluate_at(scene, res).map_err(|e| e.to_string())?;
    let start = Instant::now();
    let mut runs = 0u32;
    while runs < 3 || (start.elapsed().as_secs_f64() < 0.05 && runs < 10_000) {
        ev.evaluate_at(scene, res).map_err(|e| e.to_string())?;
        runs += 1;
    }
    Ok((first, start.elapsed().as_secs_f64() * 1e6 / runs as f64))
}

/// Runs the ladder; closure tolerances are relaxed to the largest accepted (1e-2) so that
/// every usable level reports its error.
pub fn measure(scene: &Scene, probes: usize) -> Result<AccuracyReport, String> {
    let base = Resolution {
        closure_rel_tol: Resolution::MAX_CLOSURE_REL_TOL,
        ..scene.resolution
    };
    let reference = Evaluator::new()
        .evaluate_at(scene, &base.with_samples(REFERENCE[1]))
        .map_err(|e| format!("reference failed: {e}"))?;
    let check = Evaluator::new()
        .evaluate_at(scene, &base.with_samples(REFERENCE[0]))
        .map_err(|e| format!("reference check failed: {e}"))?;
    let rung = |res: Resolution, previous: Option<(usize, f64)>| match timed(scene, &res) {
        Ok((eval, time)) => {
            let errors = output_errors(&eval, &reference, probes);
            let order_mm = previous
                .and_then(|(n, e)| observed_order(n, e, res.samples_per_turn, errors.worst().0));
            Level {
                samples_per_turn: res.samples_per_turn,
                newton_rel_tol: res.newton_rel_tol,
                time_us: Some(time),
                errors: Some(errors),
                error: None,
                order_mm,
            }
        }
        Err(e) => Level {
            samples_per_turn: res.samples_per_turn,
            newton_rel_tol: res.newton_rel_tol,
            time_us: None,
            errors: None,
            error: Some(e),
            order_mm: None,
        },
    };
    let mut levels: Vec<Level> = Vec::new();
    for &n in LADDER {
        let previous = levels
            .iter()
            .rev()
            .find_map(|l| l.errors.as_ref().map(|e| (l.samples_per_turn, e.worst().0)));
        levels.push(rung(base.with_samples(n), previous));
    }
    let tolerance_ladder = [1e-4, 1e-8, 1e-12, 1e-14]
        .iter()
        .map(|&t| {
            rung(
                Resolution {
                    newton_rel_tol: t,
                    ..base
                },
                None,
            )
        })
        .collect();
    Ok(AccuracyReport {
        scene: scene.name.clone(),
        reference_samples: REFERENCE[1],
        reference_check: output_errors(&check, &reference, probes),
        levels,
        tolerance_ladder,
    })
}

impl AccuracyReport {
    /// A readable table: one row per level.
    pub fn table(&self) -> String {
        let (rm, rd) = self.reference_check.worst();
        let mut out = table(&[
            ("scene", self.scene.clone()),
            (
                "reference",
                format!("{} samples/turn", self.reference_samples),
            ),
            (
                "reference check",
                format!(
                    "{} vs {} samples: {rm:.1e} mm, {rd:.1e}°",
                    REFERENCE[0], REFERENCE[1]
                ),
            ),
        ]);
        out += "\nsamples  newton_tol  time/eval   centre mm  traject. mm  event °    attitude °  worst objective   order\n";
        for l in self.levels.iter().chain(&self.tolerance_ladder) {
            match (&l.errors, l.time_us) {
                (Some(e), Some(t)) => {
                    let worst = e
                        .objectives
                        .iter()
                        .max_by(|a, b| a.1.total_cmp(&b.1))
                        .map_or(String::new(), |(n, v)| format!("{n} {v:.1e}"));
                    out += &format!(
                        "{:>7}  {:>10.0e}  {:>7.1} µs  {:>9.1e}  {:>11.1e}  {:>9.1e}  {:>10.1e}  {:<26} {}\n",
                        l.samples_per_turn,
                        l.newton_rel_tol,
                        t,
                        e.centre_distance_mm,
                        e.trajectory_mm,
                        e.event_angle_deg,
                        e.attitude_deg,
                        worst,
                        l.order_mm.map_or(String::new(), |o| format!("{o:.1}"))
                    );
                }
                _ => {
                    out += &format!(
                        "{:>7}  {:>10.0e}  failed: {}\n",
                        l.samples_per_turn,
                        l.newton_rel_tol,
                        l.error.as_deref().unwrap_or("")
                    )
                }
            }
        }
        out
    }
}
