//! `noncirc accuracy`: each output's error and the time per evaluation over a ladder of
//! resolutions, against a converged reference that is itself checked.

use crate::report::table;
use crate::teeth::TeethRun;
use noncirc_core::{observed_order, output_errors, ErrorRow};
use noncirc_core::{Evaluation, Evaluator, Resolution, Scene, TeethReport, ToothSpec};
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
    /// The teeth's reported quantities over a ladder of chord tolerances and mesh steps,
    /// against a run with 16 times the sampling (within the settings' ranges); `Err` with
    /// the reason where the scene's teeth cannot be cut.
    pub teeth: Result<Vec<TeethLevel>, String>,
}

/// One rung of the teeth's ladder.
#[derive(Debug, Clone, Serialize)]
pub struct TeethLevel {
    /// `gear.teeth.chord_tolerance_mm`.
    pub chord_tolerance_mm: f64,
    /// `gear.teeth.mesh_steps_per_pitch`.
    pub mesh_steps_per_pitch: usize,
    /// Mean wall time (ms) of the scene's teeth cut and checked from the scene (the gear
    /// pair or the train solved too, as `noncirc teeth` does); `None` if it failed.
    pub time_ms: Option<f64>,
    /// Differences from the reference; `None` if the cut failed.
    pub errors: Option<TeethErrors>,
    /// Why the cut failed.
    pub error: Option<String>,
}

/// How far a toothed pair's reported quantities are from the reference's.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct TeethErrors {
    /// Least contact ratio, relative.
    pub contact_ratio_rel: f64,
    /// Largest flank height lost to undercut over both gears (mm).
    pub flank_lost_mm: f64,
    /// Least clearance (mm).
    pub least_clearance_mm: f64,
    /// Least and largest normal backlash, the worse (mm).
    pub backlash_mm: f64,
}

/// Chord tolerances (mm) and mesh steps of the teeth's ladder, coarse to fine; the third is
/// the default.
const TEETH_LADDER: [(f64, usize); 4] = [(16e-3, 1), (4e-3, 1), (2e-3, 1), (0.5e-3, 2)];

fn teeth_ladder(scene: &Scene) -> Result<Vec<TeethLevel>, String> {
    let with = |spec: ToothSpec| {
        let mut s = scene.clone();
        s.gear.teeth = spec;
        s
    };
    let spec = scene.gear.teeth;
    let reference = TeethRun::from_scene(&with(spec.refined(16)), 0.0)
        .map_err(|e| e.to_string())?
        .pair
        .report;
    let lost = |r: &TeethReport| {
        r.gears
            .iter()
            .fold(0.0, |a: f64, g| a.max(g.undercut_lost_height_mm))
    };
    Ok(TEETH_LADDER
        .iter()
        .map(|&(tol, steps)| {
            let level = with(ToothSpec {
                chord_tolerance_mm: tol,
                mesh_steps_per_pitch: steps,
                ..spec
            });
            match timed_runs(|| TeethRun::from_scene(&level, 0.0).map(|run| run.pair.report)) {
                Ok((r, seconds)) => {
                    let (a, b) = (r.mesh, reference.mesh);
                    let backlash = match (a.backlash_mm, b.backlash_mm) {
                        (Some(x), Some(y)) => (x.0 - y.0).abs().max((x.1 - y.1).abs()),
                        _ => f64::NAN,
                    };
                    TeethLevel {
                        chord_tolerance_mm: tol,
                        mesh_steps_per_pitch: steps,
                        time_ms: Some(seconds * 1e3),
                        errors: Some(TeethErrors {
                            contact_ratio_rel: (a.contact_ratio_min / b.contact_ratio_min - 1.0)
                                .abs(),
                            flank_lost_mm: (lost(&r) - lost(&reference)).abs(),
                            least_clearance_mm: (a.least_clearance_mm - b.least_clearance_mm).abs(),
                            backlash_mm: backlash,
                        }),
                        error: None,
                    }
                }
                Err(e) => TeethLevel {
                    chord_tolerance_mm: tol,
                    mesh_steps_per_pitch: steps,
                    time_ms: None,
                    errors: None,
                    error: Some(e),
                },
            }
        })
        .collect())
}

/// The first result of `run` and the mean wall time (s) of running it again at least three
/// times and for 50 ms (at most 10 000 times).
fn timed_runs<T, E: ToString>(mut run: impl FnMut() -> Result<T, E>) -> Result<(T, f64), String> {
    let first = run().map_err(|e| e.to_string())?;
    let start = Instant::now();
    let mut runs = 0u32;
    while runs < 3 || (start.elapsed().as_secs_f64() < 0.05 && runs < 10_000) {
        run().map_err(|e| e.to_string())?;
        runs += 1;
    }
    Ok((first, start.elapsed().as_secs_f64() / f64::from(runs)))
}

fn timed(scene: &Scene, res: &Resolution) -> Result<(Evaluation, f64), String> {
    let mut ev = Evaluator::new();
    let (first, seconds) = timed_runs(|| ev.evaluate_at(scene, res))?;
    Ok((first, seconds * 1e6))
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
        teeth: teeth_ladder(scene),
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
        match &self.teeth {
            Err(e) => out += &format!("\nteeth: not cut ({e})\n"),
            Ok(levels) => {
                out += "\nteeth against 16x the sampling (chord tolerance / 256, 16x the mesh steps)\n";
                out += "chord µm  mesh steps  time/pair  contact ratio  flank lost mm  clearance mm  backlash mm\n";
                for l in levels {
                    match (&l.errors, l.time_ms) {
                        (Some(e), Some(t)) => {
                            out += &format!(
                                "{:>8}  {:>10}  {:>6.2} ms  {:>13.1e}  {:>13.1e}  {:>12.1e}  {:>11.1e}\n",
                                l.chord_tolerance_mm * 1e3,
                                l.mesh_steps_per_pitch,
                                t,
                                e.contact_ratio_rel,
                                e.flank_lost_mm,
                                e.least_clearance_mm,
                                e.backlash_mm
                            )
                        }
                        _ => {
                            out += &format!(
                                "{:>8}  {:>10}  failed: {}\n",
                                l.chord_tolerance_mm * 1e3,
                                l.mesh_steps_per_pitch,
                                l.error.as_deref().unwrap_or("")
                            )
                        }
                    }
                }
            }
        }
        out
    }
}
