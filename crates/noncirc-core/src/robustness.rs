//! Tolerance analysis: how a design fares once it is cut and assembled with the scene's
//! [`Tolerances`]. Deviations come from a scrambled Sobol sequence keyed on the tolerance
//! seed, so every design meets the same deviations (common random numbers). Each of the
//! sets of machined parts (cut gears, carrier) is solved once; its samples only reassemble the train
//! ([`Kinematics::reassembled`]) and re-run the events and objectives.
//!
//! The tray stays where the nominal design puts it: a scene that places the tray by the
//! trajectory (no `agronomy.tray_distance_mm`) has it fixed at the nominal design's tray
//! surface, as a machine's tray is bolted where the drawing says, with pots twice the
//! tray depth deep (the tip may then reach one tray depth less or more than drawn).

use crate::agronomy::Agronomy;
use crate::constraint::requirements;
use crate::curve::{CurveSpec, TAU};
use crate::error::{Error, Result};
use crate::evaluation::Evaluation;
use crate::evaluator::Evaluator;
use crate::events::{mark_walk_nodes, walks_tilt};
use crate::interference::mark_nodes_near_least_clearance;
use crate::objective_kind::{scale, ObjectiveKind};
use crate::planetary::{Kinematics, TrainSpec};
use crate::resolution::Resolution;
use crate::scene::{Scene, SceneKind};
use crate::tolerance::{Tolerances, ASSEMBLY};
use serde::Serialize;

/// A picking or planting instant that moves further than this (rad, 10°) under the
/// tolerances has jumped to another branch of the trajectory.
pub(crate) const BRANCH_SWITCH_RAD: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// Most Sobol dimensions (the sequence's table): 8 assembly groups and the radii.
const MAX_DIMENSIONS: usize = 256;

/// A point in (0, 1) from the scrambled Sobol sequence: dimension `dim` of point `index`.
/// The sequence's f32 is moved off 0 to the middle of its cell, so that no deviation is
/// infinite under a normal spread.
pub(crate) fn sobol(index: usize, dim: usize, seed: u64) -> f64 {
    let seed = (seed ^ (seed >> 32)) as u32;
    let u = sobol_burley::sample(index as u32, dim as u32, seed) as f64;
    let cells = (1u64 << 24) as f64;
    ((u * cells).floor() + 0.5) / cells
}

/// The number of radius-like values of a pitch curve that the radius tolerance deviates:
/// the control radii, a Fourier curve's `c0`, an ellipse's semi-major axis.
pub fn radius_count(curve: &CurveSpec) -> usize {
    match curve {
        CurveSpec::Spline { radii_mm, .. }
        | CurveSpec::Bspline { radii_mm, .. }
        | CurveSpec::Bezier { radii_mm, .. }
        | CurveSpec::Table { radii_mm, .. } => radii_mm.len(),
        CurveSpec::Fourier { .. } | CurveSpec::Ellipse { .. } => 1,
    }
}

/// `curve` with its radius-like values moved by `deviations` (mm).
fn deviated_curve(curve: &CurveSpec, deviations: &[f64]) -> CurveSpec {
    let mut out = curve.clone();
    match &mut out {
        CurveSpec::Spline { radii_mm, .. }
        | CurveSpec::Bspline { radii_mm, .. }
        | CurveSpec::Bezier { radii_mm, .. }
        | CurveSpec::Table { radii_mm, .. } => {
            for (r, d) in radii_mm.iter_mut().zip(deviations) {
                *r += d;
            }
        }
        CurveSpec::Fourier { c0_mm, .. } => *c0_mm += deviations[0],
        CurveSpec::Ellipse { semi_major_mm, .. } => *semi_major_mm += deviations[0],
    }
    out
}

/// The deviations a tolerance analysis or a robust goal applies: per cut gear the radius
/// deviations, per sample the assembly deviations (in [`ASSEMBLY`] order) and its gear.
#[derive(Debug, Clone, PartialEq)]
pub struct ToleranceSamples {
    /// Per gear variant, one deviation per radius-like value (mm).
    pub radii: Vec<Vec<f64>>,
    /// Per sample, the assembly deviations.
    pub assembly: Vec<[f64; 8]>,
}

impl ToleranceSamples {
    /// `tol.samples` samples for a curve of `radii` radius-like values, keyed on `seed`.
    /// A variant is a set of machined parts, the cut gears (their radii) and the carrier
    /// (its corner angle `γ0`): each is solved once, and its samples only turn and move
    /// the assembly. Sobol dimensions: 0–7 the assembly of each sample (its `γ0` slot
    /// unused), 8 the variant's `γ0`, 9… its radii.
    pub fn new(tol: &Tolerances, radii: usize, seed: u64) -> Result<Self> {
        tol.validate()?;
        if 9 + radii > MAX_DIMENSIONS {
            return Err(Error::OutOfRange {
                name: "gear.curve.radii_mm (count, for the tolerance analysis)".into(),
                value: radii as f64,
                expected: format!("at most {} radii", MAX_DIMENSIONS - 9),
            });
        }
        let spreads = tol.assembly();
        let variants = tol.part_sets();
        let gamma0: Vec<f64> = (0..variants)
            .map(|v| tol.gamma0_deg.deviation(sobol(v, 8, seed)))
            .collect();
        let assembly = (0..tol.samples)
            .map(|i| {
                std::array::from_fn(|d| match ASSEMBLY[d] {
                    "gamma0_deg" => gamma0[i % variants],
                    _ => spreads[d].deviation(sobol(i, d, seed)),
                })
            })
            .collect();
        let radii = (0..variants)
            .map(|v| {
                (0..radii)
                    .map(|r| tol.radius_mm.deviation(sobol(v, 9 + r, seed)))
                    .collect()
            })
            .collect();
        Ok(Self { radii, assembly })
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.assembly.len()
    }

    /// Whether there are none (never, for samples made by [`ToleranceSamples::new`]).
    pub fn is_empty(&self) -> bool {
        self.assembly.is_empty()
    }

    /// The gear variant of sample `i`.
    pub fn variant(&self, i: usize) -> usize {
        i % self.radii.len()
    }
}

/// One sample's outcome.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SampleOutcome {
    /// Each objective's margin in its unit, in the scene's objective order (negative when
    /// violated; NaN when the model refused the sample).
    pub margins: Vec<f64>,
    /// The least normalised margin over the objectives (as the `least_margin` goal reads
    /// it; −∞ when refused).
    pub least_normalised_margin: f64,
    /// Every objective met.
    pub met: bool,
    /// The model refused the deviated design (e.g. the pusher offset past the arm).
    pub refused: bool,
    /// The picking (planting) instant moved to another branch of the trajectory.
    pub picking_switch: bool,
    pub planting_switch: bool,
}

/// The least normalised margin of an evaluation over its objectives, skipping the seedling
/// push (its margin is 0 whenever it is met).
fn least_objective_margin(eval: &Evaluation, scene: &Scene) -> f64 {
    (eval.objectives.iter())
        .filter(|o| o.kind != ObjectiveKind::SeedlingPush)
        .map(|o| o.margin / scale(o.kind, &scene.bounds))
        .fold(f64::INFINITY, f64::min)
}

/// The least normalised margin over the objectives (the seedling push skipped) and the
/// search constraints (a constraint without a value counts as missed without end): the
/// goal `least_margin`'s, and what a built machine's samples are ranked by.
pub fn least_normalised_margin(eval: &Evaluation, scene: &Scene) -> f64 {
    (eval.constraints.iter())
        .map(|c| c.margin / c.constraint.scale())
        .map(|m| if m.is_nan() { f64::NEG_INFINITY } else { m })
        .fold(least_objective_margin(eval, scene), f64::min)
}

/// Wrapped distance between two carrier angles (rad).
fn angle_gap(a: f64, b: f64) -> f64 {
    let d = crate::angle::wrap_turn(a - b);
    d.min(TAU - d)
}

/// A design and its nominal evaluation, ready to be deviated.
pub struct Deviated {
    /// The design with its tray fixed where the nominal design puts it.
    fixed: Scene,
    /// The evaluation of `fixed` as drawn.
    nominal: Evaluation,
    resolution: Resolution,
}

impl Deviated {
    /// `scene`'s design, whose evaluation is `placed`. With the tray placed by the
    /// trajectory, the design is evaluated again against the fixed tray (on the same
    /// train: no closure).
    pub fn new(evaluator: &mut Evaluator, scene: &Scene, placed: &Evaluation) -> Result<Self> {
        if !matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter) {
            return Err(Error::OutOfRange {
                name: "kind".into(),
                value: f64::NAN,
                expected: format!(
                    "a three_arm or transplanter scene for a tolerance analysis (not {})",
                    scene.kind.name()
                ),
            });
        }
        let mut fixed = scene.clone();
        let agro = &mut fixed.agronomy;
        if agro.tray_distance_mm.is_none() {
            // Such a scene says how deep the tip reaches, not how deep the pots are: take
            // pots twice as deep, so the tip may reach one tray depth less or more.
            agro.tray_distance_mm = placed.events.map(|e| e.check.tray_surface_mm);
            agro.tray_depth_mm *= 2.0;
        }
        let nominal = match (&placed.kinematics, fixed.agronomy == scene.agronomy) {
            (_, true) => placed.clone(),
            (Some(kin), false) => evaluator.evaluate_solved(&fixed, kin.clone())?,
            (None, false) => evaluator.evaluate_at(&fixed, &placed.resolution)?,
        };
        Ok(Self {
            fixed,
            resolution: nominal.resolution,
            nominal,
        })
    }

    /// The evaluation of the design as drawn, against the fixed tray.
    pub fn nominal(&self) -> &Evaluation {
        &self.nominal
    }

    /// The design with its tray fixed.
    pub fn scene(&self) -> &Scene {
        &self.fixed
    }

    /// The train of a gear cut with `radii` deviations on a carrier whose corner angle
    /// `γ0` is off by `gamma0_deg` (°): a set of machined parts, whose samples only turn
    /// and move the assembly. The nominal gears are reassembled where they can be
    /// ([`Kinematics::reassembles_for`]); other gears, or a carrier that moves a pair's
    /// grid (`γ0` with two pairs), are solved anew, for that carrier directly.
    pub fn variant(
        &self,
        evaluator: &mut Evaluator,
        radii: &[f64],
        gamma0_deg: f64,
    ) -> Result<Kinematics> {
        let nominal = self.nominal.kinematics.as_ref().ok_or(Error::Missing {
            name: "kinematics".into(),
            needed_by: "the tolerance analysis".into(),
        })?;
        let mut train = self.fixed.train;
        train.gamma0_deg += gamma0_deg;
        if radii.iter().all(|&d| d == 0.0) {
            if gamma0_deg == 0.0 {
                return Ok(nominal.clone());
            }
            if nominal.reassembles_for(&train) {
                return nominal.reassembled(&train, 0.0);
            }
        }
        let mut scene = self.fixed.clone();
        scene.gear.curve = deviated_curve(&scene.gear.curve, radii);
        scene.train = train;
        evaluator.solve_train(&scene, &self.resolution)
    }

    /// Evaluates the train `kin` (a [`Deviated::variant`] cut with `radii` deviations)
    /// assembled with `assembly` deviations ([`ASSEMBLY`] order).
    pub fn assembled(
        &self,
        evaluator: &mut Evaluator,
        kin: &Kinematics,
        radii: &[f64],
        assembly: &[f64; 8],
    ) -> Result<Evaluation> {
        self.assembled_in(evaluator, kin, radii, assembly, &mut self.fixed.clone())
    }

    /// As [`Deviated::assembled`], writing the deviated train and agronomy into `scratch`
    /// (a copy of [`Deviated::scene`]) instead of copying the scene.
    fn assembled_in(
        &self,
        evaluator: &mut Evaluator,
        kin: &Kinematics,
        radii: &[f64],
        assembly: &[f64; 8],
        scratch: &mut Scene,
    ) -> Result<Evaluation> {
        let [da, ..] = *assembly;
        let train = self.deviated_train(assembly);
        (scratch.train, scratch.agronomy) = (train, self.deviated_agronomy(assembly));
        // Φ0 under a ground-frame sun, or γ0 with two pairs, moves a pair's grid: solve
        // those anew.
        let kin = if kin.reassembles_for(&train) {
            kin.reassembled(&train, da)?
        } else {
            let mut scene = scratch.clone();
            scene.gear.curve = deviated_curve(&scene.gear.curve, radii);
            evaluator
                .solve_train(&scene, &self.resolution)?
                .reassembled(&train, da)?
        };
        evaluator.evaluate_solved(scratch, kin)
    }

    /// The train with `assembly` deviations ([`ASSEMBLY`] order; the bore error is the
    /// carrier's, not the train's).
    fn deviated_train(&self, assembly: &[f64; 8]) -> TrainSpec {
        let [_, phi0, beta0, gamma0, s, h1, ..] = *assembly;
        let mut train = self.fixed.train;
        train.phi0_deg += phi0;
        train.beta0_deg += beta0;
        train.gamma0_deg += gamma0;
        train.arm_length_mm += s;
        train.pusher_offset_mm += h1;
        train
    }

    /// The tray with `assembly` deviations ([`ASSEMBLY`] order): its distance and its
    /// normal.
    fn deviated_agronomy(&self, assembly: &[f64; 8]) -> Agronomy {
        let [.., tray_d, tray_n] = *assembly;
        let mut agronomy = self.fixed.agronomy;
        agronomy.tray_distance_mm = agronomy.tray_distance_mm.map(|d| d + tray_d);
        agronomy.tray_normal_deg += tray_n;
        agronomy
    }

    /// Marks on a set of machined parts' train `kin`, for its samples (`samples`'
    /// indices) to scan alone, the nodes where its arms come closest (the band four times
    /// the farthest any of them moves the arms, and a little more), and the nodes where
    /// their walks may find the events' extremes (the band twice that, the tilt the
    /// largest of their turns and tray normals against the set's, each a little more).
    fn mark_for_samples(
        &self,
        kin: &mut Kinematics,
        samples: &ToleranceSamples,
        indices: impl Iterator<Item = usize>,
    ) {
        let normal = self.fixed.agronomy.tray_normal();
        let (mut farthest, mut tilt) = (0.0f64, 0.0f64);
        for i in indices {
            let assembly = &samples.assembly[i];
            let train = self.deviated_train(assembly);
            let (displacement, turn) = kin.displacement_and_turn_to(&train, assembly[0]);
            farthest = farthest.max(displacement);
            let own_normal = self.deviated_agronomy(assembly).tray_normal();
            tilt = tilt.max(walks_tilt(turn, own_normal, normal));
        }
        if !farthest.is_finite() {
            return;
        }
        if self.fixed.objectives.contains(&ObjectiveKind::Interference) {
            mark_nodes_near_least_clearance(kin, &self.fixed.agronomy, 4.04 * farthest + 1e-3);
        }
        mark_walk_nodes(kin, normal, 2.02 * farthest + 1e-3, 1.01 * tilt + 1e-9);
    }

    /// The outcome of an evaluation (or of the model's refusal) of a deviated design.
    pub fn outcome(&self, eval: Result<Evaluation>) -> SampleOutcome {
        match eval {
            Ok(eval) => {
                let switch = |get: fn(&crate::events::Events) -> f64| match (
                    self.nominal.events.as_ref(),
                    eval.events.as_ref(),
                ) {
                    (Some(n), Some(e)) => angle_gap(get(n), get(e)) > BRANCH_SWITCH_RAD,
                    _ => false,
                };
                SampleOutcome {
                    margins: eval.objectives.iter().map(|o| o.margin).collect(),
                    least_normalised_margin: least_normalised_margin(&eval, &self.fixed),
                    met: eval.total_violation() == 0.0,
                    refused: false,
                    picking_switch: switch(|e| e.picking.carrier_rad),
                    planting_switch: switch(|e| e.planting.carrier_rad),
                }
            }
            Err(_) => SampleOutcome {
                margins: vec![f64::NAN; self.fixed.objectives.len()],
                least_normalised_margin: f64::NEG_INFINITY,
                met: false,
                refused: true,
                picking_switch: false,
                planting_switch: false,
            },
        }
    }

    /// Every sample's outcome, in sample order: each gear variant closed once, its samples
    /// reassembled from it.
    pub fn run(&self, evaluator: &mut Evaluator, samples: &ToleranceSamples) -> Vec<SampleOutcome> {
        let mut out: Vec<Option<SampleOutcome>> = vec![None; samples.len()];
        let mut scratch = self.fixed.clone();
        for (v, radii) in samples.radii.iter().enumerate() {
            // The variant's carrier (its γ0) assembled once: its samples keep its θ_s.
            let indices = (v..samples.len()).step_by(samples.radii.len());
            let kin = self.variant(evaluator, radii, samples.assembly[v][3]);
            let kin = kin.map(|mut kin| {
                self.mark_for_samples(&mut kin, samples, indices.clone());
                kin
            });
            for i in indices {
                let eval = match &kin {
                    Ok(kin) => {
                        let assembly = &samples.assembly[i];
                        self.assembled_in(evaluator, kin, radii, assembly, &mut scratch)
                    }
                    Err(e) => Err(e.clone()),
                };
                out[i] = Some(self.outcome(eval));
            }
        }
        out.into_iter().map(|o| o.expect("every sample")).collect()
    }
}

/// The `q`-quantile of `values` (linear between order statistics, numpy's default);
/// NaN for no values.
pub fn quantile(values: &[f64], q: f64) -> f64 {
    let mut v: Vec<f64> = values.to_vec();
    v.sort_by(f64::total_cmp);
    quantile_of_sorted(&v, q)
}

/// [`quantile`] of values already sorted (by `f64::total_cmp`).
fn quantile_of_sorted(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let pos = q.clamp(0.0, 1.0) * (v.len() - 1) as f64;
    let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
    let (a, b) = (v[lo], v[hi]);
    if lo == hi || a == b {
        a
    } else {
        a + (b - a) * (pos - lo as f64)
    }
}

/// The normal quantile of a two-sided 95 % interval.
const Z_95: f64 = 1.959_963_984_540_054;

/// Wilson's 95 % score interval for a probability from `met` successes in `n` trials: never
/// empty at 0 or `n` successes (where `p ± se` is a point), always within [0, 1], and close
/// to its nominal coverage down to a few trials (Brown, Cai and DasGupta 2001). `[0, 1]`
/// for no trials.
pub(crate) fn wilson_interval(met: usize, n: usize) -> [f64; 2] {
    if n == 0 {
        return [0.0, 1.0];
    }
    let (k, n) = (met.min(n) as f64, n as f64);
    let p = k / n;
    let z2 = Z_95 * Z_95;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = Z_95 / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    // At 0 and n successes one end is exactly 0 or 1 (rounding would leave 1e-17).
    let lower = if met == 0 {
        0.0
    } else {
        (centre - half).max(0.0)
    };
    let upper = if met as f64 >= n {
        1.0
    } else {
        (centre + half).min(1.0)
    };
    [lower, upper]
}

/// The quantiles a report gives of each margin.
pub const REPORTED_QUANTILES: [f64; 5] = [0.01, 0.05, 0.5, 0.95, 0.99];

/// One objective under the tolerances.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObjectiveSpread {
    pub objective: ObjectiveKind,
    /// Unit of the value and the margins.
    pub unit: &'static str,
    pub nominal_value: f64,
    pub nominal_margin: f64,
    /// Fraction of the samples that meet it (refused samples do not), and its 95 % Wilson
    /// interval with the samples taken as independent ([`wilson_interval`]).
    pub probability: f64,
    pub probability_ci95: [f64; 2],
    /// The margin's quantiles at [`REPORTED_QUANTILES`] over the samples the model took.
    pub margin_quantiles: [f64; 5],
    /// The margin's mean and standard deviation over the samples the model took (NaN when
    /// it took none).
    pub margin_mean: f64,
    pub margin_sd: f64,
    /// The worst-case bound, when computed.
    pub worst_case: Option<WorstCase>,
}

/// A linearised worst case: the margin predicted at the corner of the tolerance box that
/// the sensitivities point to, and the margin evaluated there.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorstCase {
    /// `m0 − Σ |∂m/∂x_i| w_i` (w: the band, or 3σ).
    pub predicted_margin: f64,
    /// The margin evaluated at the corner (NaN when the model refused it).
    pub corner_margin: f64,
    /// The quantity that moves the margin most, and by how much over its half-width.
    pub dominant: String,
    pub dominant_share: f64,
}

/// A tolerance analysis of one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToleranceReport {
    pub samples: usize,
    /// Sets of machined parts among the samples.
    pub part_sets: usize,
    pub seed: u64,
    /// Fraction of the samples meeting every objective and every search constraint.
    pub probability_all: f64,
    /// Its standard error as if the samples were independent, `√(p(1−p)/n)` (scrambled
    /// Sobol points do at least as well), and its 95 % Wilson interval likewise
    /// ([`wilson_interval`]; not a point when every sample, or none, meets them).
    pub probability_all_se: f64,
    pub probability_all_ci95: [f64; 2],
    /// Samples the model refused.
    pub refused: usize,
    /// Samples whose picking (planting) moved to another branch of the trajectory.
    pub picking_branch_switches: usize,
    pub planting_branch_switches: usize,
    /// The least normalised margin's quantiles at [`REPORTED_QUANTILES`].
    pub least_margin_quantiles: [f64; 5],
    pub objectives: Vec<ObjectiveSpread>,
    /// The tray distance the samples were evaluated against (mm).
    pub tray_distance_mm: Option<f64>,
    /// Where the scene places the tray by the trajectory, the analysis bolts it where the
    /// nominal design puts it and `picking_admissible` here counts the tip's reach into
    /// pots twice the tray depth too; this is the design's `picking_admissible` as
    /// `noncirc evaluate` reads it, the tray placed at its own picking point (mm). `None`
    /// when the scene fixes the tray (the two agree) or has no picking point.
    pub picking_admissible_placed_mm: Option<f64>,
    /// The scene's search constraints (as written), which a sample meets too to count in
    /// [`ToleranceReport::probability_all`].
    pub constraints: Vec<String>,
}

impl ToleranceReport {
    /// What a sample meets to count as a success: "every objective", "and search
    /// constraint" where the scene has some.
    pub fn requirements(&self) -> &'static str {
        requirements(!self.constraints.is_empty())
    }
}

/// Analyses `scene`'s design under its tolerances at `resolution`: the samples (with the
/// worst-case bound when `worst_case`), and every sample's outcome.
pub fn analyse(
    evaluator: &mut Evaluator,
    scene: &Scene,
    resolution: &Resolution,
    worst_case: bool,
) -> Result<(ToleranceReport, Vec<SampleOutcome>)> {
    let tol = &scene.tolerances;
    let placed = evaluator.evaluate_at(scene, resolution)?;
    let deviated = Deviated::new(evaluator, scene, &placed)?;
    let nominal = deviated.nominal();
    let samples = ToleranceSamples::new(tol, radius_count(&scene.gear.curve), tol.seed)?;
    let outcomes = deviated.run(evaluator, &samples);
    let n = outcomes.len() as f64;
    let met_all = outcomes.iter().filter(|o| o.met).count();
    let p_all = met_all as f64 / n;
    let bounds = worst_case
        .then(|| worst_case_bounds(evaluator, &deviated))
        .transpose()?;
    let objectives = (nominal.objectives.iter().enumerate())
        .map(|(k, o)| {
            let mut margins: Vec<f64> = (outcomes.iter())
                .map(|s| s.margins[k])
                .filter(|m| !m.is_nan())
                .collect();
            margins.sort_by(f64::total_cmp);
            // Without a sample the model took, the statistics are not defined: NaN (null
            // in JSON; the table says that no sample could be evaluated).
            let mean = match margins.len() {
                0 => f64::NAN,
                taken => margins.iter().sum::<f64>() / taken as f64,
            };
            let var = match margins.len() {
                0 => f64::NAN,
                1 => 0.0,
                taken => {
                    margins.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (taken - 1) as f64
                }
            };
            let met = (outcomes.iter())
                .filter(|s| s.margins[k] >= 0.0 && !s.refused)
                .count();
            ObjectiveSpread {
                objective: o.kind,
                unit: o.kind.unit(),
                nominal_value: o.value,
                nominal_margin: o.margin,
                probability: met as f64 / n,
                probability_ci95: wilson_interval(met, outcomes.len()),
                margin_quantiles: REPORTED_QUANTILES.map(|q| quantile_of_sorted(&margins, q)),
                margin_mean: mean,
                margin_sd: var.sqrt(),
                worst_case: bounds.as_ref().map(|b| b[k].clone()),
            }
        })
        .collect();
    let mut least: Vec<f64> = outcomes.iter().map(|o| o.least_normalised_margin).collect();
    least.sort_by(f64::total_cmp);
    let report = ToleranceReport {
        samples: outcomes.len(),
        part_sets: samples.radii.len(),
        seed: tol.seed,
        probability_all: p_all,
        probability_all_se: (p_all * (1.0 - p_all) / n).sqrt(),
        probability_all_ci95: wilson_interval(met_all, outcomes.len()),
        refused: outcomes.iter().filter(|o| o.refused).count(),
        picking_branch_switches: outcomes.iter().filter(|o| o.picking_switch).count(),
        planting_branch_switches: outcomes.iter().filter(|o| o.planting_switch).count(),
        least_margin_quantiles: REPORTED_QUANTILES.map(|q| quantile_of_sorted(&least, q)),
        objectives,
        tray_distance_mm: deviated.scene().agronomy.tray_distance_mm,
        picking_admissible_placed_mm: (scene.agronomy.tray_distance_mm.is_none())
            .then(|| placed.events.map(|e| e.check.margin_mm()))
            .flatten(),
        constraints: scene.search.constraints.iter().map(|c| c.text()).collect(),
    };
    Ok((report, outcomes))
}

/// The toleranced quantities' names and half-widths (the band, or 3σ), radii first.
fn quantities(scene: &Scene) -> Vec<(String, f64)> {
    let tol = &scene.tolerances;
    let mut out: Vec<(String, f64)> = (0..radius_count(&scene.gear.curve))
        .map(|i| (format!("radius[{i}]"), tol.radius_mm.worst_case()))
        .collect();
    out.extend((ASSEMBLY.iter().zip(tol.assembly())).map(|(n, s)| (n.to_string(), s.worst_case())));
    out
}

/// Each objective's linearised worst case: secant slopes over each quantity's half-width
/// (central, the others nominal), the predicted margin at the worst corner, and the margin
/// evaluated at that corner.
fn worst_case_bounds(evaluator: &mut Evaluator, d: &Deviated) -> Result<Vec<WorstCase>> {
    let scene = d.scene();
    let quantities = quantities(scene);
    let radii = radius_count(&scene.gear.curve);
    let objectives = d.nominal.objectives.len();
    // The margins with only quantity q deviated by `x`.
    let margins_at = |ev: &mut Evaluator, deviation: &[f64]| -> Vec<f64> {
        let (r, a) = deviation.split_at(radii);
        let assembly: [f64; 8] = a.try_into().expect("eight assembly deviations");
        // The carrier's γ0 is placed with the rest of the assembly, in one step.
        let eval = d
            .variant(ev, r, 0.0)
            .and_then(|kin| d.assembled(ev, &kin, r, &assembly));
        d.outcome(eval).margins
    };
    let mut slopes = vec![vec![0.0; quantities.len()]; objectives];
    for (q, (_, w)) in quantities.iter().enumerate() {
        if *w == 0.0 {
            continue;
        }
        let mut dev = vec![0.0; quantities.len()];
        dev[q] = *w;
        let up = margins_at(evaluator, &dev);
        dev[q] = -w;
        let down = margins_at(evaluator, &dev);
        for k in 0..objectives {
            slopes[k][q] = (up[k] - down[k]) / (2.0 * w);
        }
    }
    (0..objectives)
        .map(|k| {
            let m0 = d.nominal.objectives[k].margin;
            let terms: Vec<f64> = (slopes[k].iter().zip(&quantities))
                .map(|(s, (_, w))| if s.is_nan() { 0.0 } else { s.abs() * w })
                .collect();
            let spread: f64 = terms.iter().sum();
            let (dominant, largest) = (terms.iter().enumerate())
                .max_by(|a, b| a.1.total_cmp(b.1))
                .filter(|(_, t)| **t > 0.0)
                .map(|(i, t)| (quantities[i].0.clone(), *t))
                .unwrap_or_else(|| ("none".into(), 0.0));
            let corner: Vec<f64> = (slopes[k].iter().zip(&quantities))
                .map(|(s, (_, w))| if *s > 0.0 { -w } else { *w })
                .collect();
            Ok(WorstCase {
                predicted_margin: m0 - spread,
                corner_margin: margins_at(evaluator, &corner)[k],
                dominant,
                dominant_share: if spread > 0.0 { largest / spread } else { 0.0 },
            })
        })
        .collect()
}

/// What a robust goal reads from a design's samples.
#[derive(Debug, Clone, PartialEq)]
pub struct RobustScore {
    /// Fraction of the samples meeting every objective.
    pub probability: f64,
    /// The samples' least normalised margins, sorted (−∞ for a refused sample).
    least_margins: Vec<f64>,
}

impl RobustScore {
    /// The least normalised margin's `q`-quantile over the samples.
    pub fn margin_quantile(&self, q: f64) -> f64 {
        quantile_of_sorted(&self.least_margins, q)
    }
}

/// Scores `scene`'s design (its nominal evaluation `nominal`) on `samples`.
pub fn robust_score(
    evaluator: &mut Evaluator,
    scene: &Scene,
    nominal: &Evaluation,
    samples: &ToleranceSamples,
) -> Result<RobustScore> {
    let outcomes = Deviated::new(evaluator, scene, nominal)?.run(evaluator, samples);
    let met = outcomes.iter().filter(|o| o.met).count();
    let mut least_margins: Vec<f64> = outcomes.iter().map(|o| o.least_normalised_margin).collect();
    least_margins.sort_by(f64::total_cmp);
    Ok(RobustScore {
        probability: met as f64 / outcomes.len() as f64,
        least_margins,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::Spread;

    /// Wilson's interval against its closed forms at 0 and n successes (`[0, z²/(n+z²)]`,
    /// `[n/(n+z²), 1]`) and a value from the literature (5 of 10: [0.2366, 0.7634], Brown,
    /// Cai and DasGupta 2001); it holds the estimate and stays in [0, 1].
    #[test]
    fn wilson_interval_has_its_closed_forms() {
        let z2 = super::Z_95 * super::Z_95;
        for n in [1, 10, 640, 10_000] {
            let nf = n as f64;
            let [lo, hi] = super::wilson_interval(0, n);
            assert!(
                lo == 0.0 && (hi - z2 / (nf + z2)).abs() < 1e-15,
                "{n}: {lo} {hi}"
            );
            let [lo, hi] = super::wilson_interval(n, n);
            assert!(
                (lo - nf / (nf + z2)).abs() < 1e-15 && hi == 1.0,
                "{n}: {lo} {hi}"
            );
            for k in 0..=n.min(50) {
                let [lo, hi] = super::wilson_interval(k, n);
                let p = k as f64 / nf;
                assert!(
                    (0.0..=p).contains(&lo) && (p..=1.0).contains(&hi),
                    "{k}/{n}"
                );
            }
        }
        let [lo, hi] = super::wilson_interval(5, 10);
        assert!(
            (lo - 0.2366).abs() < 5e-5 && (hi - 0.7634).abs() < 5e-5,
            "{lo} {hi}"
        );
        assert_eq!(super::wilson_interval(0, 0), [0.0, 1.0]);
    }

    #[test]
    fn the_quantile_matches_numpy() {
        // numpy.quantile([3, 1, 4, 1, 5], [0, 0.1, 0.5, 0.9, 1]) = [1, 1, 3, 4.6, 5]
        let v = [3.0, 1.0, 4.0, 1.0, 5.0];
        let q: Vec<f64> = [0.0, 0.1, 0.5, 0.9, 1.0]
            .iter()
            .map(|&q| quantile(&v, q))
            .collect();
        for (a, b) in q.iter().zip([1.0, 1.0, 3.0, 4.6, 5.0]) {
            assert!((a - b).abs() < 1e-12, "{q:?}");
        }
    }

    #[test]
    fn sobol_points_fill_each_dimension_evenly_and_differ_by_seed() {
        // A scrambled Sobol sequence is stratified: 64 points put one in each 1/64 cell.
        for dim in [0, 7, 20] {
            let mut cells = [0; 64];
            for i in 0..64 {
                cells[(sobol(i, dim, 5) * 64.0) as usize] += 1;
            }
            assert!(cells.iter().all(|&c| c == 1), "dimension {dim}: {cells:?}");
        }
        assert_ne!(sobol(3, 0, 1), sobol(3, 0, 2));
        assert_eq!(sobol(3, 0, 1), sobol(3, 0, 1));
    }

    #[test]
    fn exact_tolerances_reproduce_the_nominal_design() {
        let mut scene = Scene::default();
        let exact = Spread::Band(0.0);
        let t = &mut scene.tolerances;
        (t.radius_mm, t.centre_distance_mm, t.phi0_deg, t.beta0_deg) = (exact, exact, exact, exact);
        (t.gamma0_deg, t.arm_length_mm, t.pusher_offset_mm) = (exact, exact, exact);
        (t.tray_distance_mm, t.tray_normal_deg) = (exact, exact);
        t.samples = 8;
        let mut ev = Evaluator::new();
        let placed = ev.evaluate(&scene).unwrap();
        let fixed = Deviated::new(&mut ev, &scene, &placed)
            .unwrap()
            .scene()
            .clone();
        let nominal = ev.evaluate(&fixed).unwrap();
        let (report, outcomes) = analyse(&mut ev, &scene, &scene.resolution, false).unwrap();
        for o in &outcomes {
            for (m, n) in o.margins.iter().zip(&nominal.objectives) {
                assert!(
                    (m - n.margin).abs() < 1e-9 * n.margin.abs().max(1.0),
                    "{m} {n:?}"
                );
            }
        }
        let met = nominal.total_violation() == 0.0;
        assert_eq!(report.probability_all, if met { 1.0 } else { 0.0 });
        assert_eq!(report.picking_branch_switches, 0);
    }

    /// `scene`'s design deviated, its samples for `seed`, and their outcomes (`run`).
    fn run_samples(
        scene: &Scene,
        seed: u64,
    ) -> (Evaluator, Deviated, ToleranceSamples, Vec<SampleOutcome>) {
        let mut ev = Evaluator::new();
        let placed = ev.evaluate(scene).unwrap();
        let deviated = Deviated::new(&mut ev, scene, &placed).unwrap();
        let radii = radius_count(&scene.gear.curve);
        let samples = ToleranceSamples::new(&scene.tolerances, radii, seed).unwrap();
        let outcomes = deviated.run(&mut ev, &samples);
        (ev, deviated, samples, outcomes)
    }

    #[test]
    fn marked_nodes_leave_every_samples_outcome_bit_for_bit() {
        // `run` marks each set's nodes near its least clearance and where its walks may find
        // the events' extremes, and its samples scan and walk those alone; each sample
        // assembled on the set's unmarked train scans and walks every node. The paper's
        // design and one whose arms interfere, with the tolerances as given and thirty
        // times wider (the clearance's band then holds 78–93 of the 120 nodes, not 17–19).
        let paper = Scene::default();
        // β0 = 40° and 60 mm wide arms: the clearance is −2.13 mm.
        let mut interfering = Scene::default();
        interfering.train.beta0_deg = 40.0;
        interfering.agronomy.arm_half_width_mm = 60.0;
        for (scene, widen) in [(&paper, 1.0), (&interfering, 1.0), (&paper, 30.0)] {
            let mut scene = scene.clone();
            let t = &mut scene.tolerances;
            for s in [
                &mut t.radius_mm,
                &mut t.phi0_deg,
                &mut t.beta0_deg,
                &mut t.arm_length_mm,
                &mut t.tray_normal_deg,
            ] {
                *s = match *s {
                    Spread::Band(h) => Spread::Band(h * widen),
                    Spread::Sigma(v) => Spread::Sigma(v * widen),
                };
            }
            let (mut ev, d, samples, outcomes) = run_samples(&scene, 3);
            // What `run` marks on the first set: few of the nodes for each walk.
            let mut marked = d
                .variant(&mut ev, &samples.radii[0], samples.assembly[0][3])
                .unwrap();
            let indices = (0..samples.len()).step_by(samples.radii.len());
            d.mark_for_samples(&mut marked, &samples, indices);
            let walks = marked.marks().unwrap().walks.as_ref().unwrap();
            let few = |w: &Option<Vec<usize>>| w.as_ref().is_some_and(|w| w.len() < 30);
            assert!(
                widen > 1.0 || walks.nodes.iter().all(few),
                "{:?}",
                walks.nodes
            );
            for (i, o) in outcomes.iter().enumerate() {
                let (r, assembly) = (&samples.radii[samples.variant(i)], &samples.assembly[i]);
                let kin = d.variant(&mut ev, r, assembly[3]).unwrap();
                assert!(kin.marked_nodes().is_none());
                let whole = d.outcome(d.assembled(&mut ev, &kin, r, assembly));
                let bits = |o: &SampleOutcome| {
                    let margins: Vec<u64> = o.margins.iter().map(|m| m.to_bits()).collect();
                    let least = o.least_normalised_margin.to_bits();
                    (margins, least, o.met, o.picking_switch, o.planting_switch)
                };
                assert_eq!(bits(o), bits(&whole), "sample {i}, tolerances ×{widen}");
            }
        }
    }

    #[test]
    fn a_two_pair_trains_samples_are_its_deviated_designs_solved_anew() {
        // With two pairs, γ0 places the second pair's grid: each set of machined parts is
        // solved for its own carrier, and every sample is the deviated design evaluated
        // from scratch (the bore error left out: a scene cannot state it).
        let mut scene = Scene::default();
        scene.gear.second_curve = Some(scene.gear.curve.clone());
        let t = &mut scene.tolerances;
        t.centre_distance_mm = Spread::Band(0.0);
        t.samples = 8;
        let (mut ev, deviated, samples, outcomes) = run_samples(&scene, 1);
        for (i, o) in outcomes.iter().enumerate() {
            assert!(!o.refused, "sample {i} refused");
            let [_, phi0, beta0, gamma0, s, h1, tray_d, tray_n] = samples.assembly[i];
            let mut fresh = deviated.scene().clone();
            let curve = &fresh.gear.curve;
            fresh.gear.curve = deviated_curve(curve, &samples.radii[samples.variant(i)]);
            let train = &mut fresh.train;
            (train.phi0_deg, train.beta0_deg, train.gamma0_deg) = (
                train.phi0_deg + phi0,
                train.beta0_deg + beta0,
                train.gamma0_deg + gamma0,
            );
            train.arm_length_mm += s;
            train.pusher_offset_mm += h1;
            let agro = &mut fresh.agronomy;
            agro.tray_distance_mm = agro.tray_distance_mm.map(|d| d + tray_d);
            agro.tray_normal_deg += tray_n;
            let anew = ev.evaluate(&fresh).unwrap();
            for (m, n) in o.margins.iter().zip(&anew.objectives) {
                let tol = 1e-9 * n.margin.abs().max(1.0);
                assert!((m - n.margin).abs() < tol, "sample {i}: {m} {n:?}");
            }
        }
        // The linearised worst case's corners are evaluated too.
        let (report, _) = analyse(&mut ev, &scene, &scene.resolution, true).unwrap();
        assert_eq!(report.refused, 0);
        for o in &report.objectives {
            let w = o.worst_case.as_ref().unwrap();
            assert!(w.corner_margin.is_finite(), "{:?}: {w:?}", o.objective);
        }
    }

    #[test]
    fn a_reassembled_train_equals_one_solved_for_its_assembly() {
        // Reuse must not change the answer: β0, S, H1, γ0, Φ0 moved on a solved pair give
        // the train solved from scratch with those values.
        let scene = Scene::default();
        let mut ev = Evaluator::new();
        let kin = ev.solve_train(&scene, &scene.resolution).unwrap();
        let mut moved = scene.clone();
        moved.train.beta0_deg += 0.7;
        moved.train.arm_length_mm -= 1.3;
        moved.train.pusher_offset_mm += 0.4;
        moved.train.gamma0_deg += 0.2;
        moved.train.phi0_deg -= 0.3;
        // Once with γ0 moved (θ_s solved anew), once with the carrier kept (turned only).
        for keep_carrier in [false, true] {
            if keep_carrier {
                moved.train.gamma0_deg = scene.train.gamma0_deg;
            }
            let fresh = ev.solve_train(&moved, &moved.resolution).unwrap();
            let reused = kin.reassembled(&moved.train, 0.0).unwrap();
            for (a, b) in fresh.tips().iter().zip(reused.tips()) {
                assert!((*a - *b).hypot() < 1e-9, "{a:?} {b:?}");
            }
            for (a, b) in fresh.planet_angles().iter().zip(reused.planet_angles()) {
                assert!((a - b).abs() < 1e-12);
            }
            let (x, y) = (fresh.state_at(1.234), reused.state_at(1.234));
            assert!((x.tip - y.tip).hypot() < 1e-9 && (x.tip_d2 - y.tip_d2).hypot() < 1e-9);
        }
    }

    #[test]
    fn a_bore_error_moves_the_planets_out_at_the_same_ratio() {
        let scene = Scene::default();
        let mut ev = Evaluator::new();
        let kin = ev.solve_train(&scene, &scene.resolution).unwrap();
        let wide = kin.reassembled(&scene.train, 0.05).unwrap();
        let ratio = wide.planet_radius() / kin.planet_radius();
        let a = kin.centre_distance();
        assert!((ratio - (a + 0.05) / a).abs() < 1e-12);
        for (p, q) in kin.planet_angles().iter().zip(wide.planet_angles()) {
            assert_eq!(p, q);
        }
    }
}
