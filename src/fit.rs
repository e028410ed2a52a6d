//! Fitting a design to a target (`noncirc fit`, Python's `fit`): the scene's search with
//! the goal `fit` (the objectives stay constraints, so a fit that cannot pick is no fit),
//! then Levenberg–Marquardt from its best design on the fit's residuals at the scene's
//! resolution, kept only if it stays feasible and fits better.

use crate::files::{create_dir, json_text, read_limited, toml_text, write_file};
use crate::report::{requirement_rows, RequirementRow};
use crate::search::{map_batch, thread_pool, Outcome, RunOptions};
use crate::{Error, Result};
use noncirc_core::{
    refine, symbol, Error as CoreError, Evaluation, Evaluator, FitMeasure, FitReport, Goal,
    LocalReport, LocalSettings, Measure, Observer, PoseQuantity, ResidualBatch, Resolution, Scene,
    SceneProblem, Target, TargetKind,
};
use serde::Serialize;
use std::path::Path;
use std::sync::Arc;

/// Largest target file read (bytes): a CSV of 100 000 points.
pub const MAX_TARGET_BYTES: u64 = 8 << 20;

/// Reads a target: a CSV of `x_mm,y_mm` rows (a header line is allowed; `points`, the
/// default tolerance), or a TOML file with a `[target]` table.
pub fn read_target(path: &Path) -> Result<Target> {
    let bytes = read_limited(path, MAX_TARGET_BYTES)?;
    let text = String::from_utf8(bytes)
        .map_err(|_| Error::Input(format!("{}: not UTF-8 text", path.display())))?;
    let is_toml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    parse_target(&text, &path.display().to_string(), is_toml)
}

/// A target from text: TOML with a `[target]` table, or CSV of `x_mm,y_mm` rows;
/// `origin` names it in errors. Checked whole.
pub fn parse_target(text: &str, origin: &str, is_toml: bool) -> Result<Target> {
    let target = if is_toml {
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct File {
            target: Target,
        }
        toml::from_str::<File>(text)
            .map_err(|e| Error::Input(format!("{origin}: {e}")))?
            .target
    } else {
        target_from_csv(text, origin)?
    };
    target.prepare().map_err(|source| Error::Content {
        path: origin.into(),
        source,
    })?;
    Ok(target)
}

/// `target` as a file's `[target]` table (TOML), as [`read_target`] reads it back.
pub fn target_toml(target: &Target) -> Result<String> {
    #[derive(Serialize)]
    struct File<'a> {
        target: &'a Target,
    }
    toml_text(&File { target }, "the target")
}

/// A `points` target from CSV text of `x_mm,y_mm` rows; `origin` names it in errors.
pub fn target_from_csv(text: &str, origin: &str) -> Result<Target> {
    let (mut x_mm, mut y_mm) = (Vec::new(), Vec::new());
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let numbers: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        match numbers.as_deref() {
            Some([x, y]) => {
                x_mm.push(*x);
                y_mm.push(*y);
            }
            // The first line may name the columns.
            None if x_mm.is_empty() && fields.len() == 2 => continue,
            _ => {
                return Err(Error::Input(format!(
                    "{origin}, line {}: expected two numbers `x_mm,y_mm`, got '{line}'",
                    i + 1
                )))
            }
        }
    }
    Ok(Target {
        kind: TargetKind::Points,
        x_mm,
        y_mm,
        tolerance_mm: 0.5,
        samples: 128,
        counts: true,
        poses: Vec::new(),
        design: Vec::new(),
    })
}

/// Bound on a spline pitch curve's largest radius over its control radii: the periodic
/// cubic spline's Lebesgue constant on near-uniform knots is about 1.55.
const SPLINE_OVERSHOOT: f64 = 1.6;

/// Checks that every point and pose of `target` lies where some design of `problem`'s box
/// could put the tip: no farther from the carrier axis than `S + |O3|`, with
/// `|O3| = 2a|cos(γ0/2)| ≤ 2a ≤ 4ρ_max` (a pair's centre distance is at most twice its
/// largest radius), and no nearer than `S − |O3|`. A loose band: it catches a target in the
/// wrong units or frame, not a hard fit.
pub fn check_reach(problem: &SceneProblem, target: &Target) -> Result<()> {
    let base = problem.base();
    let (lower, upper) = problem.bounds();
    let names = problem.names();
    let free = |name: &str| names.iter().position(|n| *n == name);
    let arm = base.train.arm_length_mm;
    let (s_min, s_max) = free("train.arm_length_mm").map_or((arm, arm), |i| (lower[i], upper[i]));
    let curve = base.gear.curve.build()?;
    let samples = curve.sample_uniform(0.0, std::f64::consts::TAU / 720.0, 720);
    let mut rho_max = curve.radius_range(&samples).1;
    for (i, name) in names.iter().enumerate() {
        if name.starts_with("gear.curve.") {
            rho_max = rho_max.max(SPLINE_OVERSHOOT * upper[i].abs());
        }
    }
    let planet_max = 4.0 * rho_max;
    let (inner, outer) = ((s_min - planet_max).max(0.0), s_max + planet_max);
    let check = |name: String, x: f64, y: f64| {
        let distance = x.hypot(y);
        if distance > outer || distance < inner {
            Err(Error::Core(CoreError::OutOfReach {
                name,
                distance_mm: distance,
                inner_mm: inner,
                outer_mm: outer,
            }))
        } else {
            Ok(())
        }
    };
    for (i, (&x, &y)) in target.x_mm.iter().zip(&target.y_mm).enumerate() {
        check(format!("target.x_mm[{i}]"), x, y)?;
    }
    for (k, p) in target.poses.iter().enumerate() {
        check(format!("target.poses[{k}]"), p.x_mm, p.y_mm)?;
    }
    Ok(())
}

/// How to run a fit.
pub struct FitOptions {
    pub run: RunOptions,
    pub local: LocalSettings,
}

/// A finished (or stopped) fit.
pub struct FitOutcome {
    /// The global search.
    pub search: Outcome,
    /// The local refinement from the search's best design, if it ran.
    pub local: Option<LocalReport>,
    /// Whether the refined design replaced the search's (feasible, and a better fit).
    pub refined: bool,
    /// The fitted design and its evaluation at the scene's resolution.
    pub best: Option<(Scene, Evaluation)>,
}

/// The fit's residuals of a batch of designs at one resolution, evaluated in order: on
/// the pool's threads, or in the caller's thread without one (the studio's worker).
struct FitResiduals<'a> {
    problem: &'a SceneProblem,
    pool: Option<rayon::ThreadPool>,
    planned: Evaluator,
    resolution: Resolution,
}

impl ResidualBatch for FitResiduals<'_> {
    fn dim(&self) -> usize {
        self.problem.dim()
    }
    fn residuals(&mut self, points: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let (problem, resolution) = (self.problem, self.resolution);
        let residuals = |(evaluator, scratch): &mut (Evaluator, Scene), u: &Vec<f64>| {
            problem.fit_residuals(u, evaluator, scratch, &resolution).0
        };
        match &self.pool {
            Some(pool) => map_batch(pool, &self.planned, problem.base(), points, residuals),
            None => {
                let mut planned = self.planned.clone();
                planned.prepare_target(problem.base());
                let mut state = (planned, problem.base().clone());
                points.iter().map(|u| residuals(&mut state, u)).collect()
            }
        }
    }
}

/// Carrier nodes a turn at which the refinement evaluates its residuals (at least).
pub const LOCAL_SAMPLES_PER_TURN: usize = 720;

/// The refinement's resolution: the scene's with at least [`LOCAL_SAMPLES_PER_TURN`] nodes.
/// Its residuals must change smoothly with the design for their differences to be a
/// Jacobian; at the scene's 120 nodes the tip path gains exact points in its tightest
/// loop where the nodes' curve is uncertain, and a point added or not between two nearby
/// designs moves the distances by up to the path's accuracy (5 % of the tolerance), more
/// than a difference step's own effect. At 720 nodes the nodes' curve is within 2e-4 mm of
/// the paper's path everywhere and no point is added.
fn local_resolution(scene: &Resolution) -> Resolution {
    scene.with_samples(scene.samples_per_turn.max(LOCAL_SAMPLES_PER_TURN))
}

/// Bisections back along the refinement's step when it ends beyond a constraint: the
/// step's end located to 2⁻¹² of its length.
const BISECTIONS: usize = 12;

/// Fits `scene` to its target: the search (its `[search]` box, algorithm, budget and
/// seed; the goal `fit`), then the local refinement. Refuses, before anything runs, a
/// scene without a target and a target out of the box's reach.
pub fn fit_scene(
    scene: &Scene,
    opts: &FitOptions,
    observers: &mut [&mut (dyn Observer + Send)],
) -> Result<FitOutcome> {
    let scene = if opts.run.resume.is_some() {
        // The checkpoint holds the scene (with its target and goal) that ran.
        scene.clone()
    } else {
        prepare_fit(scene)?
    };
    let search = crate::search::run(&scene, &opts.run, observers)?;
    refine_search(search, Some(opts.run.threads), &opts.local)
}

/// The scene a fit searches: `scene` with the goal `fit`. Refuses a scene without a
/// target and a target out of the box's reach.
pub fn prepare_fit(scene: &Scene) -> Result<Scene> {
    let target = scene.target.as_ref().ok_or_else(|| {
        Error::Input(
            "a fit needs a target: a file (CSV of x_mm,y_mm, or TOML with a [target] \
             table; the CLI's --target, Python's target=) or a [target] table in the scene"
                .into(),
        )
    })?;
    let mut scene = scene.clone();
    scene.search.goals = vec![Goal::Fit];
    check_reach(&SceneProblem::new(&scene)?, target)?;
    Ok(scene)
}

/// The fit's refinement of a finished search (not of a stopped one): Levenberg–Marquardt
/// from its reported design on `threads` threads (`None`: in this thread, as the studio's
/// worker runs it; the same numbers either way), kept if it meets as many objectives and
/// fits better.
pub fn refine_search(
    search: Outcome,
    threads: Option<usize>,
    settings: &LocalSettings,
) -> Result<FitOutcome> {
    let problem = &search.problem;
    let resolution = local_resolution(&problem.base().resolution);
    let start = search.state.reported().map(|c| c.u.clone());
    let interrupted = search.stopped_early;
    let mut local = None;
    let mut refined = false;
    let mut best = search
        .confirmed
        .best
        .as_ref()
        .and_then(|(s, e)| e.clone().map(|e| (s.clone(), e)));
    if let (Some(start), false) = (start, interrupted) {
        let mut residuals = FitResiduals {
            problem,
            pool: threads.map(thread_pool).transpose()?,
            planned: Evaluator::planned(&resolution),
            resolution,
        };
        let report = refine(&mut residuals, &start, settings);
        let evaluate = |u: &[f64]| {
            let scene = problem.scene_at(u);
            Evaluator::new().evaluate(&scene).ok().map(|e| (scene, e))
        };
        let mut candidate = evaluate(&report.u);
        let misses = |c: &Option<(Scene, Evaluation)>| {
            c.as_ref().is_none_or(|(_, e)| e.total_violation() > 0.0)
        };
        if misses(&candidate) && !misses(&evaluate(&start)) {
            // The refinement crossed a constraint (the fit's best often lies on one):
            // the point nearest its end on the segment from the search's design that
            // still meets every objective.
            let along = |t: f64| -> Vec<f64> {
                (start.iter().zip(&report.u))
                    .map(|(a, b)| a + t * (b - a))
                    .collect()
            };
            let (mut met, mut missed) = (0.0, 1.0);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (met + missed);
                if misses(&evaluate(&along(mid))) {
                    missed = mid;
                } else {
                    met = mid;
                }
            }
            if met > 0.0 {
                candidate = evaluate(&along(met));
            }
        }
        if let Some((candidate, eval)) = candidate {
            let cost = |e: &Evaluation| e.fit.as_ref().map_or(f64::INFINITY, |f| f.cost);
            // Violations compared as the search does: each over its scale.
            let bounds = &problem.base().bounds;
            let violation = |e: &Evaluation| e.normalised_violation(bounds);
            let better = best.as_ref().is_none_or(|(_, b)| {
                let (new_v, old_v) = (violation(&eval), violation(b));
                new_v < old_v || (new_v == old_v && cost(&eval) < cost(b))
            });
            if better {
                best = Some((candidate, eval));
                refined = true;
            }
        }
        local = Some(report);
    }
    Ok(FitOutcome {
        search,
        local,
        refined,
        best,
    })
}

/// The fit measures of `fit` to `target`, each with its tolerance: the path's Hausdorff
/// distance (held to the path's tolerance when the path counts), its RMS distance
/// (reported), then each pose's position, attitude and carrier errors (those it names).
pub fn fit_measure_rows(fit: &FitReport, target: &Target) -> Vec<FitMeasureRow> {
    let mut measures = Vec::new();
    // Named, measured and held to a tolerance as the core's fit measures are.
    let mut row = |m: FitMeasure, tolerance: Option<f64>| {
        if let Some(value) = fit.value(m) {
            measures.push(FitMeasureRow {
                name: Measure::Fit(m).name(),
                value,
                unit: Measure::Fit(m).unit(),
                tolerance,
                met: tolerance.map(|limit| value <= limit),
            });
        }
    };
    row(
        FitMeasure::PathHausdorff,
        target.counts.then_some(target.tolerance_mm),
    );
    row(FitMeasure::PathRms, None);
    for (k, pose) in target.poses.iter().enumerate() {
        for (quantity, tolerance) in [
            (PoseQuantity::Position, pose.position_tolerance_mm),
            (PoseQuantity::Attitude, pose.attitude_tolerance_deg),
            (PoseQuantity::Carrier, pose.carrier_tolerance_deg),
        ] {
            let slot = Some(k as u8);
            row(
                FitMeasure::Pose { slot, quantity },
                pose.counts.then_some(tolerance),
            );
        }
    }
    measures
}

/// A fit measure with its tolerance.
#[derive(Debug, Clone, Serialize)]
pub struct FitMeasureRow {
    pub name: String,
    pub value: f64,
    pub unit: &'static str,
    /// The tolerance it is held to (none for the RMS distance, which is reported).
    pub tolerance: Option<f64>,
    pub met: Option<bool>,
}

/// A free parameter of the fitted design.
#[derive(Debug, Clone, Serialize)]
pub struct DesignRow {
    pub name: String,
    pub symbol: String,
    pub value: f64,
    pub lower: f64,
    pub upper: f64,
}

/// How the search and the refinement ran.
#[derive(Debug, Clone, Serialize)]
pub struct FitRun {
    pub algorithm: &'static str,
    pub seed: u64,
    pub evaluations: u64,
    pub seconds: f64,
    pub threads: usize,
    pub stopped_early: bool,
    /// The refinement (none when the search was stopped or found no design).
    pub local: Option<LocalReport>,
    /// Whether the refined design is the one reported.
    pub refined: bool,
}

/// What `fit.json` holds and `noncirc fit` prints.
#[derive(Debug, Clone, Serialize)]
pub struct FitSummary {
    pub scene: String,
    /// Every objective met and every counting part of the target within its tolerance.
    pub met: bool,
    /// Every objective met.
    pub feasible: bool,
    pub measures: Vec<FitMeasureRow>,
    /// The fit in full: path distances, each pose's reading and errors, the cost.
    pub fit: Option<FitReport>,
    /// The objectives, then the search constraints.
    pub objectives: Vec<RequirementRow>,
    pub design: Vec<DesignRow>,
    pub run: FitRun,
}

impl FitSummary {
    /// The fit as `noncirc fit` prints it.
    pub fn table(&self) -> String {
        let mut out = format!(
            "fit of {} to its target: {}\n\n",
            self.scene,
            match (self.met, self.feasible) {
                (true, _) => "MET: every objective, and the target within its tolerances",
                (false, true) =>
                    "NOT MET: every objective is met, the target is not within its tolerances",
                (false, false) => "NOT MET: the fitted design misses an objective",
            }
        );
        out += "measure                       value  tolerance\n";
        for m in &self.measures {
            out += &format!(
                "  {:<24} {:>9.4} {:<3} {}\n",
                m.name,
                m.value,
                m.unit,
                match (m.tolerance, m.met) {
                    (Some(t), Some(true)) => format!("≤ {t}: met"),
                    (Some(t), _) => format!("> {t}: NOT met"),
                    _ => "(reported)".into(),
                }
            );
        }
        if let Some(f) = &self.fit {
            for p in &f.poses {
                out += &format!(
                    "  pose {:<19} read at carrier {:.2}°, tip ({:.2}, {:.2}) mm, attitude {:.2}°\n",
                    p.name, p.carrier_deg, p.tip_mm.x, p.tip_mm.y, p.attitude_deg
                );
            }
        }
        out += "\nobjectives (value, violation, unit):\n";
        for o in &self.objectives {
            out += &format!(
                "  {:<28} {:>10.4} {:>9.4}  {}\n",
                o.name, o.value, o.violation, o.unit
            );
        }
        out += "\nfitted design (docs/scenes.md: the fields and the papers' symbols):\n";
        for d in &self.design {
            out += &format!(
                "  {:<28} {:<6} {:>10.4}   in [{}, {}]\n",
                d.name, d.symbol, d.value, d.lower, d.upper
            );
        }
        let r = &self.run;
        out += &format!(
            "\nsearch: {} (seed {}), {} evaluations in {:.2} s on {} threads{}\n",
            r.algorithm,
            r.seed,
            r.evaluations,
            r.seconds,
            r.threads,
            if r.stopped_early {
                " (stopped early)"
            } else {
                ""
            }
        );
        match &r.local {
            Some(l) => {
                out += &format!(
                "refinement: Levenberg–Marquardt, {} evaluations, cost {:.4} → {:.4} ({}); {}\n",
                l.evaluations,
                l.start_cost,
                l.cost,
                l.termination,
                if r.refined {
                    "its design is reported"
                } else {
                    "not kept (it missed an objective or fitted no better)"
                }
            )
            }
            None => out += "refinement: not run (the search was stopped or found no design)\n",
        }
        out
    }

    /// What is not met, for an exit status: the measures beyond their tolerances and the
    /// objectives missed.
    pub fn failures(&self) -> String {
        let mut parts: Vec<String> = (self.measures.iter())
            .filter(|m| m.met == Some(false))
            .map(|m| {
                format!(
                    "{} {:.3} {} > {}",
                    m.name,
                    m.value,
                    m.unit,
                    m.tolerance.unwrap_or_default()
                )
            })
            .collect();
        parts.extend(
            (self.objectives.iter())
                .filter(|o| o.violation > 0.0)
                .map(|o| format!("{} missed by {:.3} {}", o.name, o.violation, o.unit)),
        );
        if parts.is_empty() && !self.met {
            parts.push("no design could be evaluated".into());
        }
        format!("the fit is not met: {}", parts.join(", "))
    }
}

impl FitOutcome {
    /// Whether the fitted design meets every objective and the target's tolerances.
    pub fn met(&self) -> bool {
        self.best.as_ref().is_some_and(|(_, e)| {
            e.total_violation() == 0.0 && e.fit.as_ref().is_some_and(|f| f.met)
        })
    }

    /// The summary of the fit.
    pub fn summary(&self) -> FitSummary {
        let problem = &self.search.problem;
        let base = problem.base();
        let eval = self.best.as_ref().map(|(_, e)| e);
        let fit = eval.and_then(|e| e.fit.clone());
        let target = base.target.as_deref();
        let measures = match (&fit, target) {
            (Some(f), Some(t)) => fit_measure_rows(f, t),
            _ => Vec::new(),
        };
        let objectives = eval.map_or(Vec::new(), requirement_rows);
        let (lower, upper) = problem.bounds();
        let design = match &self.best {
            Some((scene, _)) => (problem.names().into_iter().enumerate())
                .map(|(i, name)| DesignRow {
                    name: name.to_string(),
                    symbol: symbol(name).unwrap_or_default(),
                    value: noncirc_core::Param::parse(name, scene)
                        .ok()
                        .and_then(|p| p.get(scene))
                        .unwrap_or(f64::NAN),
                    lower: lower[i],
                    upper: upper[i],
                })
                .collect(),
            None => Vec::new(),
        };
        let state = &self.search.state;
        FitSummary {
            scene: base.name.clone(),
            met: self.met(),
            feasible: eval.is_some_and(|e| e.total_violation() == 0.0),
            measures,
            fit,
            objectives,
            design,
            run: FitRun {
                algorithm: state.algorithm.name(),
                seed: base.search.seed,
                evaluations: state.evaluations,
                seconds: self.search.seconds,
                threads: self.search.threads,
                stopped_early: self.search.stopped_early,
                local: self.local.clone(),
                refined: self.refined,
            },
        }
    }

    /// The fitted design's scene as `best.toml` holds it: named `<scene>-fit`, its target
    /// inline.
    pub fn fitted_scene(&self) -> Option<Scene> {
        self.best.as_ref().map(|(scene, _)| {
            let mut scene = scene.clone();
            scene.name = format!("{}-fit", self.search.problem.base().name);
            scene
        })
    }

    /// Writes the search's outputs (`optimise`'s), then `best.toml` (the fitted design,
    /// its target inline) and `fit.json` into `dir`.
    pub fn write(&self, dir: &Path) -> Result<()> {
        create_dir(dir)?;
        self.search.write(dir)?;
        if let Some(scene) = self.fitted_scene() {
            write_file(
                &dir.join("best.toml"),
                toml_text(&scene, "the fitted scene")?.as_bytes(),
            )?;
        }
        write_file(
            &dir.join("fit.json"),
            json_text(&self.summary(), "the fit")?.as_bytes(),
        )
    }
}

/// The scene with `target` set (a target file given beside a scene).
pub fn with_target(mut scene: Scene, target: Target) -> Scene {
    scene.target = Some(Arc::new(target));
    scene
}
