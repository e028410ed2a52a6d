//! Repairing a design (`noncirc repair`, Python's `repair`): the design nearest the given
//! one that meets every objective and whose teeth cut and mesh. It is the fit with the
//! design as its own target: the design's tip path with its picking and planting poses,
//! and each free parameter pulled towards its value over a tenth of its search interval
//! (`target.design`), searched in boxes about it within the scene's box with every
//! objective a constraint. The fitted design's teeth are then cut and checked over a full
//! turn, with the teeth advice's settings if the scene's own fail.

use crate::files::{create_dir, json_text, toml_text, write_file};
use crate::fit::{fit_scene, FitOptions, FitOutcome, FitRun};
use crate::report::{requirement_rows, RequirementRow};
use crate::scene_file::apply_overrides;
use crate::search::RunOptions;
use crate::teeth::{Advice, TeethRun};
use crate::{Error, Result};
use noncirc_core::{
    symbol, target_of, DesignPull, Evaluation, Evaluator, FreeParam, Goal, LocalSettings, Observer,
    Param, Scene, SceneProblem, Target,
};
use serde::Serialize;
use std::path::Path;
use std::sync::Arc;

/// The boxes searched in turn until one holds a design that works: the design's
/// neighbourhood, this fraction of each parameter's interval either side (within the
/// scene's box). A search over the whole box finds a feasible design far from the given
/// one (the path 266 mm away for the paper's design): the nearest lies close.
const REACHES: [f64; 3] = [0.25, 0.5, 1.0];

/// A parameter within this fraction of its interval of a box's bound is on its edge (the
/// search ends near a bound it presses on, not on it).
const EDGE: f64 = 0.01;

/// Points of the design's own path in the repair's target.
pub const TARGET_POINTS: usize = 256;

/// How to run a repair.
pub struct RepairOptions {
    /// The search and the refinement.
    pub fit: FitOptions,
    /// The path's tolerance (mm) in the fit: a path off by this (RMS) costs as much as a
    /// parameter moved by its scale.
    pub path_tolerance_mm: f64,
    /// Each parameter's pull scale as a fraction of its search interval.
    pub design_scale: f64,
}

impl RepairOptions {
    /// The path's tolerance by default (mm).
    pub const PATH_TOLERANCE_MM: f64 = 1.0;
    /// The pull scale by default: a tenth of each parameter's interval.
    pub const DESIGN_SCALE: f64 = 0.1;
    /// The refinement's evaluations at most, for each box: the repaired design sits on a
    /// constraint (the module), where Levenberg–Marquardt gains a tenth of the cost for the
    /// paper's design (its step cut back to feasibility), and a box with no feasible design
    /// gains nothing.
    pub const LOCAL_EVALUATIONS: u64 = 2_000;

    /// The repair's options by default, with `run`'s search settings.
    pub fn new(run: RunOptions) -> Self {
        Self {
            fit: FitOptions {
                run,
                local: LocalSettings {
                    max_evaluations: Self::LOCAL_EVALUATIONS,
                    ..LocalSettings::default()
                },
            },
            path_tolerance_mm: Self::PATH_TOLERANCE_MM,
            design_scale: Self::DESIGN_SCALE,
        }
    }

    /// Checks the two weights, naming the bad one.
    pub fn check(&self) -> Result<()> {
        for (name, v, max) in [
            ("path tolerance (mm)", self.path_tolerance_mm, 1e3),
            ("design scale", self.design_scale, 10.0),
        ] {
            if !(v > 0.0 && v <= max) {
                return Err(Error::Input(format!(
                    "repair's {name} {v}: expected above 0, at most {max}"
                )));
            }
        }
        Ok(())
    }
}

/// The repaired design.
pub struct Repaired {
    /// The given scene with the repaired design's parameters (and the teeth settings that
    /// cut, when the scene's own did not).
    pub scene: Scene,
    pub evaluation: Evaluation,
    /// Its path against the original's (the repair's target, with the pulls).
    pub fit: noncirc_core::FitReport,
    /// Every failed check of its teeth (empty: they cut and mesh); `None`: not cut, as
    /// the design misses an objective (a tiny module's thousands of teeth take seconds).
    pub teeth_failures: Option<Vec<String>>,
    /// The teeth settings changed to make them cut (`--set` assignments).
    pub teeth_set: Vec<String>,
}

/// A finished (or stopped) repair.
pub struct RepairOutcome {
    /// The given scene, its search problem (the box the changes are measured in) and its
    /// evaluation.
    pub original: Scene,
    pub problem: SceneProblem,
    pub before: Evaluation,
    /// The boxes searched.
    pub stages: Vec<StageRow>,
    /// The fit of the box whose design is reported: the nearest that works, else the last.
    pub fit: FitOutcome,
    /// The repaired design, if the fit found one that evaluates.
    pub repaired: Option<Repaired>,
}

/// The repair's target: `scene`'s own tip path and picking and planting poses (the path
/// and positions held to `opts.path_tolerance_mm`, the attitudes to 1°), and each of
/// `problem`'s free parameters pulled towards its value with scale `opts.design_scale`
/// of its interval.
pub fn repair_target(
    scene: &Scene,
    eval: &Evaluation,
    problem: &SceneProblem,
    opts: &RepairOptions,
) -> Result<Target> {
    let (Some(kin), Some(events)) = (&eval.kinematics, &eval.events) else {
        return Err(Error::Input(format!(
            "a {} scene has no tip path: repair needs a three_arm or transplanter scene",
            scene.kind.name()
        )));
    };
    let mut target = target_of(kin, events, TARGET_POINTS);
    target.tolerance_mm = opts.path_tolerance_mm;
    for pose in &mut target.poses {
        pose.position_tolerance_mm = opts.path_tolerance_mm;
        pose.attitude_tolerance_deg = 1.0;
    }
    let (lower, upper) = problem.bounds();
    for (i, name) in problem.names().into_iter().enumerate() {
        let value = Param::parse(name, scene)?
            .get(scene)
            .ok_or_else(|| Error::Input(format!("repair: the free parameter '{name}' is unset")))?;
        target.design.push(DesignPull {
            name: name.to_string(),
            value,
            scale: opts.design_scale * (upper[i] - lower[i]),
        });
    }
    target.validate()?;
    Ok(target)
}

/// Repairs `scene`'s design: the fit to its own target (see the module's doc) in boxes
/// around it, each wider than the last until one holds a design that works; each box's
/// fitted design is checked, then the search's best confirmed one. Refuses a scene whose
/// design does not evaluate (its path is the target).
pub fn repair_scene(
    scene: &Scene,
    opts: &RepairOptions,
    observers: &mut [&mut (dyn Observer + Send)],
) -> Result<RepairOutcome> {
    if opts.fit.run.resume.is_some() {
        return Err(Error::Input(
            "repair starts from the scene's design and does not resume a checkpoint".into(),
        ));
    }
    let mut stages = RepairStages::new(scene, opts)?;
    while let Some(fitting) = stages.next_scene() {
        let fit = fit_scene(&fitting, &opts.fit, observers)?;
        stages.finish_stage(fit)?;
    }
    Ok(stages.outcome())
}

/// A repair's boxes, searched in turn (the CLI runs them; the studio slices each box's
/// search for its worker).
pub struct RepairStages {
    original: Scene,
    problem: SceneProblem,
    before: Evaluation,
    target: Arc<Target>,
    stages: Vec<StageRow>,
    found: Option<(FitOutcome, Option<Repaired>)>,
    done: bool,
}

/// A box searched.
#[derive(Debug, Clone, Serialize)]
pub struct StageRow {
    /// The box: this fraction of each parameter's interval either side of the design.
    pub reach: f64,
    pub evaluations: u64,
    pub seconds: f64,
    /// Whether its design meets every objective with teeth that cut and mesh.
    pub works: bool,
    /// Whether that design lies on an edge of the box (within the scene's box), so that
    /// the next box was searched too.
    pub on_edge: bool,
}

impl RepairStages {
    /// The most boxes a repair searches.
    pub const MOST_BOXES: usize = REACHES.len();

    /// The boxes searched so far.
    pub fn boxes_searched(&self) -> usize {
        self.stages.len()
    }

    /// Evaluates `scene` and builds the repair's target; refuses bad options and a design
    /// that does not evaluate.
    pub fn new(scene: &Scene, opts: &RepairOptions) -> Result<Self> {
        opts.check()?;
        let before = Evaluator::new().evaluate(scene).map_err(|e| {
            Error::Input(format!(
                "the design of scene '{}' does not evaluate, so it has no tip path to keep: {e}",
                scene.name
            ))
        })?;
        let problem = SceneProblem::new(scene)?;
        let target = Arc::new(repair_target(scene, &before, &problem, opts)?);
        Ok(Self {
            original: scene.clone(),
            problem,
            before,
            target,
            stages: Vec::new(),
            found: None,
            done: false,
        })
    }

    /// The scene whose fit searches the next box (the design's own path and events as its
    /// target, the goal `fit`), or `None` when the repair is done.
    pub fn next_scene(&self) -> Option<Scene> {
        let reach = *REACHES.get(self.stages.len()).filter(|_| !self.done)?;
        let (lower, upper) = self.problem.bounds();
        let mut fitting = self.original.clone();
        fitting.target = Some(self.target.clone());
        fitting.search.goals = vec![Goal::Fit];
        // `reach` of each interval either side of the design, within the scene's box.
        fitting.search.free = (self.problem.names().into_iter().enumerate())
            .zip(&self.target.design)
            .map(|((i, name), pull)| {
                let width = upper[i] - lower[i];
                let centre = pull.value.clamp(lower[i], upper[i]);
                FreeParam {
                    name: name.to_string(),
                    lower: (centre - reach * width).max(lower[i]),
                    upper: (centre + reach * width).min(upper[i]),
                }
            })
            .collect();
        Some(fitting)
    }

    /// Takes the fit of the box [`RepairStages::next_scene`] gave: checks its fitted
    /// design, then the search's best confirmed one, and ends the repair when one works,
    /// the search was stopped or the widest box is done.
    pub fn finish_stage(&mut self, fit: FitOutcome) -> Result<()> {
        let fitting = fit.search.problem.base();
        let candidates = fit.best.iter().map(|(s, _)| s).chain(
            (fit.search.confirmed.best.iter())
                .filter(|(_, e)| e.is_some())
                .map(|(s, _)| s),
        );
        let mut repaired: Option<Repaired> = None;
        for candidate in candidates {
            let Some(r) = repaired_at(&self.original, fitting, &self.problem, candidate)? else {
                continue;
            };
            let works = r.works();
            if repaired.as_ref().is_none_or(|r| !r.works() && works) {
                repaired = Some(r);
            }
            if works {
                break;
            }
        }
        let works = repaired.as_ref().is_some_and(Repaired::works);
        // A working design on an edge of its box that is not the scene's own may have a
        // nearer neighbour beyond it: the next box is searched too.
        let (lower, upper) = self.problem.bounds();
        let (box_lower, box_upper) = fit.search.problem.bounds();
        let on_edge = repaired.as_ref().is_some_and(|r| {
            (self.problem.names().into_iter().enumerate()).any(|(i, name)| {
                let v = Param::parse(name, &r.scene)
                    .ok()
                    .and_then(|p| p.get(&r.scene));
                let near = |a: f64, b: f64| (a - b).abs() <= EDGE * (upper[i] - lower[i]);
                v.is_some_and(|v| {
                    (near(v, box_lower[i]) && box_lower[i] > lower[i])
                        || (near(v, box_upper[i]) && box_upper[i] < upper[i])
                })
            })
        });
        self.stages.push(StageRow {
            reach: REACHES[self.stages.len()],
            evaluations: fit.search.state.evaluations,
            seconds: fit.search.seconds,
            works,
            on_edge,
        });
        self.done =
            (works && !on_edge) || fit.search.stopped_early || self.stages.len() == REACHES.len();
        // Keep the nearest working design (the least fit cost), else the latest box's.
        let cost = |r: &Option<Repaired>| {
            (r.as_ref())
                .filter(|r| r.works())
                .map_or(f64::INFINITY, |r| r.fit.cost)
        };
        let better = match &self.found {
            None => true,
            Some((_, found)) => {
                let (new, old) = (cost(&repaired), cost(found));
                new < old || (old == f64::INFINITY && new == f64::INFINITY)
            }
        };
        if better {
            self.found = Some((fit, repaired));
        }
        Ok(())
    }

    /// The repair: the nearest working design of the boxes searched, else the last box's.
    pub fn outcome(self) -> RepairOutcome {
        let (fit, repaired) = self.found.expect("a repair's outcome after its first box");
        RepairOutcome {
            original: self.original,
            problem: self.problem,
            before: self.before,
            stages: self.stages,
            fit,
            repaired,
        }
    }
}

impl Repaired {
    /// Every objective met and the teeth cut and mesh.
    pub fn works(&self) -> bool {
        self.evaluation.total_violation() == 0.0
            && self.teeth_failures.as_ref().is_some_and(Vec::is_empty)
    }
}

/// `original` with `candidate`'s free parameters, evaluated, its fit to the repair's target
/// (`fitting`'s), and its teeth; `None` if it does not evaluate.
fn repaired_at(
    original: &Scene,
    fitting: &Scene,
    problem: &SceneProblem,
    candidate: &Scene,
) -> Result<Option<Repaired>> {
    let mut scene = original.clone();
    for name in problem.names() {
        let param = Param::parse(name, candidate)?;
        if let Some(v) = param.get(candidate) {
            param.set(&mut scene, v);
        }
    }
    let Ok(evaluation) = Evaluator::new().evaluate(&scene) else {
        return Ok(None);
    };
    let mut measured = scene.clone();
    measured.target = fitting.target.clone();
    let Some(fit) = Evaluator::new()
        .evaluate(&measured)
        .ok()
        .and_then(|e| e.fit)
    else {
        return Ok(None);
    };
    let (mut teeth_failures, mut teeth_set) = (None, Vec::new());
    if evaluation.total_violation() == 0.0 {
        let mut failures = self::teeth_failures(&scene);
        if !failures.is_empty() {
            if let Some(k) = Advice::for_scene(&scene)
                .ok()
                .and_then(|a| a.passes.map(|k| (a, k)))
            {
                teeth_set = k.0.tried[k.1].set.clone();
                scene = apply_overrides(scene, &teeth_set)?;
                failures = self::teeth_failures(&scene);
            }
        }
        teeth_failures = Some(failures);
    }
    Ok(Some(Repaired {
        scene,
        evaluation,
        fit,
        teeth_failures,
        teeth_set,
    }))
}

/// Every failed check of `scene`'s teeth (cut as `noncirc teeth` cuts them), or why they
/// could not be cut.
fn teeth_failures(scene: &Scene) -> Vec<String> {
    match TeethRun::from_scene(scene, 0.0) {
        Ok(run) => run.failures(),
        Err(e) => vec![e.to_string()],
    }
}

/// A free parameter's change.
#[derive(Debug, Clone, Serialize)]
pub struct Change {
    pub name: String,
    pub symbol: String,
    pub before: f64,
    pub after: f64,
    /// `after − before` (the parameter's unit).
    pub delta: f64,
    /// The change as a percentage of the parameter's search interval.
    pub delta_percent_of_box: f64,
}

/// Where an event moved.
#[derive(Debug, Clone, Serialize)]
pub struct EventShift {
    pub name: String,
    /// Distance between the tips before and after (mm).
    pub position_mm: f64,
    /// Attitude after minus before (deg).
    pub attitude_deg: f64,
    /// Carrier angle after minus before, wrapped to ±180° (deg).
    pub carrier_deg: f64,
}

/// What `repair.json` holds and `noncirc repair` prints.
#[derive(Debug, Clone, Serialize)]
pub struct RepairSummary {
    pub scene: String,
    /// Every objective met and the teeth cut and mesh.
    pub repaired: bool,
    /// The given design's objectives, then its search constraints.
    pub before: Vec<RequirementRow>,
    /// The repaired design's.
    pub after: Vec<RequirementRow>,
    /// The free parameters' changes, largest (in % of the box) first.
    pub changes: Vec<Change>,
    /// Hausdorff distance of the repaired tip path from the given one (mm).
    pub path_hausdorff_mm: Option<f64>,
    /// RMS distance between them (mm).
    pub path_rms_mm: Option<f64>,
    /// The picking and planting instants' moves.
    pub events: Vec<EventShift>,
    /// The repaired design's failed teeth checks (empty: they cut and mesh; none: not cut,
    /// as it misses an objective).
    pub teeth_failures: Option<Vec<String>>,
    /// Teeth settings changed so that they cut (`--set` assignments).
    pub teeth_set: Vec<String>,
    /// The boxes searched, narrowest first.
    pub stages: Vec<StageRow>,
    /// The last box's search and refinement.
    pub run: FitRun,
}

impl RepairOutcome {
    /// Whether the repaired design meets every objective and its teeth cut and mesh.
    pub fn works(&self) -> bool {
        self.repaired.as_ref().is_some_and(Repaired::works)
    }

    pub fn summary(&self) -> RepairSummary {
        let problem = &self.problem;
        let (lower, upper) = problem.bounds();
        let r = self.repaired.as_ref();
        let mut changes: Vec<Change> = match r {
            Some(r) => (problem.names().into_iter().enumerate())
                .filter_map(|(i, name)| {
                    let p = Param::find(name, &self.original)?;
                    let (before, after) = (p.get(&self.original)?, p.get(&r.scene)?);
                    Some(Change {
                        name: name.to_string(),
                        symbol: symbol(name).unwrap_or_default(),
                        before,
                        after,
                        delta: after - before,
                        delta_percent_of_box: 100.0 * (after - before) / (upper[i] - lower[i]),
                    })
                })
                .collect(),
            None => Vec::new(),
        };
        changes.sort_by(|a, b| {
            (b.delta_percent_of_box.abs()).total_cmp(&a.delta_percent_of_box.abs())
        });
        let events = match (
            r.and_then(|r| r.evaluation.events.as_ref()),
            &self.before.events,
        ) {
            (Some(after), Some(before)) => [
                ("picking", &before.picking, &after.picking),
                ("planting", &before.planting, &after.planting),
            ]
            .into_iter()
            .map(|(name, b, a)| EventShift {
                name: name.into(),
                position_mm: (a.tip_mm - b.tip_mm).hypot(),
                attitude_deg: a.attitude_deg - b.attitude_deg,
                carrier_deg: ((a.carrier_rad - b.carrier_rad).to_degrees() + 180.0)
                    .rem_euclid(360.0)
                    - 180.0,
            })
            .collect(),
            _ => Vec::new(),
        };
        RepairSummary {
            scene: self.original.name.clone(),
            repaired: self.works(),
            before: requirement_rows(&self.before),
            after: r.map_or(Vec::new(), |r| requirement_rows(&r.evaluation)),
            changes,
            path_hausdorff_mm: r.map(|r| r.fit.path_hausdorff_mm),
            path_rms_mm: r.map(|r| r.fit.path_rms_mm),
            events,
            teeth_failures: r.and_then(|r| r.teeth_failures.clone()),
            teeth_set: r.map_or(Vec::new(), |r| r.teeth_set.clone()),
            stages: self.stages.clone(),
            run: self.fit.summary().run,
        }
    }

    /// The repaired scene as `repaired.toml` holds it: named `<scene>-repaired`.
    pub fn repaired_scene(&self) -> Option<Scene> {
        self.repaired.as_ref().map(|r| {
            let mut scene = r.scene.clone();
            scene.name = format!("{}-repaired", self.original.name);
            scene
        })
    }

    /// Writes `repaired.toml` (the given scene with the repaired design) and `repair.json`
    /// into `dir`.
    pub fn write(&self, dir: &Path) -> Result<()> {
        create_dir(dir)?;
        if let Some(scene) = self.repaired_scene() {
            write_file(
                &dir.join("repaired.toml"),
                toml_text(&scene, "the repaired scene")?.as_bytes(),
            )?;
        }
        write_file(
            &dir.join("repair.json"),
            json_text(&self.summary(), "the repair")?.as_bytes(),
        )
    }
}

impl RepairSummary {
    /// The repair as `noncirc repair` prints it.
    pub fn table(&self) -> String {
        let mut out = format!(
            "repair of {}: {}\n\n",
            self.scene,
            if self.repaired {
                "REPAIRED: every objective met, the teeth cut and mesh"
            } else {
                "NOT REPAIRED within the budget"
            }
        );
        out += "objective                      before     after  unit\n";
        for (b, a) in self.before.iter().zip(&self.after) {
            let mark = |o: &RequirementRow| if o.violation > 0.0 { "✗" } else { " " };
            out += &format!(
                "  {:<26} {:>9.3}{} {:>9.3}{} {}\n",
                b.name,
                b.value,
                mark(b),
                a.value,
                mark(a),
                a.unit
            );
        }
        if let (Some(h), Some(rms)) = (self.path_hausdorff_mm, self.path_rms_mm) {
            out += &format!(
                "\ntip path moved: Hausdorff {h:.2} mm, RMS {rms:.2} mm from the given design's\n"
            );
        }
        for e in &self.events {
            out += &format!(
                "  {:<9} moved {:.2} mm, attitude {:+.2}°, carrier {:+.2}°\n",
                e.name, e.position_mm, e.attitude_deg, e.carrier_deg
            );
        }
        out += "\nchanges (largest first, % of the search interval):\n";
        for c in &self.changes {
            out += &format!(
                "  {:<26} {:<4} {:>9.3} → {:>9.3}  ({:+.3}, {:+.1} %)\n",
                c.name, c.symbol, c.before, c.after, c.delta, c.delta_percent_of_box
            );
        }
        out += &match (&self.teeth_failures, self.teeth_set.is_empty()) {
            (None, _) => "\nteeth: not cut (the design misses an objective)\n".into(),
            (Some(f), true) if f.is_empty() => {
                "\nteeth: cut and checked over a full turn, every check passes\n".into()
            }
            (Some(f), false) if f.is_empty() => format!(
                "\nteeth: every check passes with {}\n",
                self.teeth_set.join(" ")
            ),
            (Some(f), _) => format!("\nteeth: {}\n", f.join("; ")),
        };
        let r = &self.run;
        out += &format!(
            "search: {} (seed {}) on {} threads{}, box by box until a design works\n",
            r.algorithm,
            r.seed,
            r.threads,
            if r.stopped_early {
                " (stopped early)"
            } else {
                ""
            }
        );
        for st in &self.stages {
            out += &format!(
                "  ±{:.0} % of each interval about the design: {} evaluations in {:.2} s{}\n",
                100.0 * st.reach,
                st.evaluations,
                st.seconds,
                match (st.works, st.on_edge) {
                    (true, false) => ", a design that works",
                    (true, true) => ", a design that works on the box's edge",
                    _ => "",
                }
            );
        }
        out
    }

    /// What is not repaired, for an exit status.
    pub fn failures(&self) -> String {
        let mut parts: Vec<String> = (self.after.iter())
            .filter(|o| o.violation > 0.0)
            .map(|o| format!("{} missed by {:.3} {}", o.name, o.violation, o.unit))
            .collect();
        parts.extend(
            self.teeth_failures
                .iter()
                .flatten()
                .map(|f| format!("teeth: {f}")),
        );
        if self.after.is_empty() {
            parts.push("no design was found that evaluates".into());
        }
        format!("not repaired: {}", parts.join(", "))
    }
}
