//! One function per command but `optimise` (crate::optimise): each loads its scene, runs
//! the library, writes its files and prints its report.

use crate::args::{
    AnimateArgs, CadArgs, CadFormat, CompareArgs, Format, GearArgs, RobustnessArgs, SceneArgs,
    ScenesArgs, SensitivityArgs, StudioArgs, SweepArgs, TeethArgs,
};
use crate::output::{json, out};
use crate::studio as server;
use noncirc::core::{Measure, SceneKind};
use noncirc::report::{EvaluationReport, GearReport};
use noncirc::scene_file::{load_scene_with, BUILTIN};
use std::error::Error;

/// Solve a gear pair and report (or export) it.
pub(crate) fn gear(args: GearArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
    let (report, pair) = GearReport::from_scene(&scene)?;
    noncirc::report::check_finite(&report)?;
    for dir in [&args.export, &args.scene.plot].into_iter().flatten() {
        for f in noncirc::export::export_gears(&pair, None, dir)? {
            say!("wrote {}", f.display());
        }
    }
    match args.scene.format {
        Format::Json => out(&json(&report)?)?,
        Format::Table => out(&report.table())?,
    }
    Ok(())
}

/// A design whose teeth fail a check or cannot be cut: the command reports it and exits
/// with [`crate::EXIT_VERDICT`] (docs/reliability.md).
#[derive(Debug)]
pub(crate) struct VerdictFailed(pub(crate) String);

impl std::fmt::Display for VerdictFailed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl Error for VerdictFailed {}

/// Cut, check and export the train's teeth. Teeth that fail a check are reported, not
/// exported unless `--force`, and the command exits with the verdict's code.
pub(crate) fn teeth(args: TeethArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
    noncirc::cad::check_tolerance("--tolerance-mm", args.tolerance_mm)?;
    // Checked in a gear scene too, where no train is assembled: never silently ignored.
    noncirc::solids::check_carrier("--carrier-deg", args.carrier_deg)?;
    let run = match noncirc::teeth::TeethRun::from_scene(&scene, args.carrier_deg) {
        Ok(run) => run,
        Err(noncirc::Error::Core(
            e @ (noncirc::core::Error::Teeth { .. } | noncirc::core::Error::OutlineCrossing { .. }),
        )) => {
            // The refusal is the verdict; advice that cannot be had does not replace it.
            let advice = noncirc::teeth::Advice::for_scene(&scene).ok();
            match args.scene.format {
                Format::Json => out(&json(&serde_json::json!({
                    "refused": e.to_string(),
                    "advice": advice,
                }))?)?,
                Format::Table => {
                    if let Some(advice) = &advice {
                        say!("advice: {}", advice.line());
                    }
                }
            }
            return Err(Box::new(VerdictFailed(format!(
                "the teeth cannot be cut: {e}"
            ))));
        }
        Err(e) => return Err(e.into()),
    };
    noncirc::report::check_finite(&run.summary())?;
    let failures = run.failures().len();
    let checks = run.failed_checks();
    if let Some(dir) = &args.export {
        if failures == 0 || args.force {
            for f in run.export(dir, args.tolerance_mm)? {
                say!("wrote {}", f.display());
            }
        } else {
            say!("not exported: the teeth fail {checks} (--force exports them anyway)");
        }
    }
    if let Some(dir) = &args.scene.plot {
        for f in noncirc::figures::teeth_figures(&run, dir, &args.scene.figures()?)? {
            say!("wrote {}", f.display());
        }
    }
    let mut summary = run.summary();
    if failures > 0 {
        summary.advice = Some(noncirc::teeth::Advice::for_scene(&scene)?);
    }
    match args.scene.format {
        Format::Json => out(&json(&summary)?)?,
        Format::Table => {
            let mut table = run.table();
            if let Some(advice) = &summary.advice {
                table += &format!("ADVICE              {}\n", advice.line());
            }
            out(&table)?
        }
    }
    if failures > 0 {
        return Err(Box::new(VerdictFailed(format!(
            "the teeth fail {checks}: {}",
            run.failures().join("; ")
        ))));
    }
    Ok(())
}

/// Write the solids of the scene's gears and train. Teeth that fail a check or cannot be
/// cut are reported and nothing is written (unless `--force` for a failed check); a
/// `[cad]` dimension that does not fit is an error naming it, and nothing is written.
pub(crate) fn cad(args: CadArgs) -> Result<(), Box<dyn Error>> {
    use noncirc::solids::Format;
    let scene = load_scene_with(args.scene.scene.as_deref(), &args.scene.set)?;
    let formats: Vec<Format> = (args.format.iter())
        .filter_map(|f| match f {
            CadFormat::Step => Some(Format::Step),
            CadFormat::Stl => Some(Format::Stl),
            CadFormat::Json => None,
        })
        .collect();
    // The library names its own arguments; here they are flags.
    noncirc::cad::check_tolerance("--tolerance-mm", args.tolerance_mm)?;
    noncirc::solids::check_carrier("--carrier-deg", args.carrier_deg)?;
    let done = match noncirc::solids::export(
        &scene,
        args.carrier_deg,
        &formats,
        args.tolerance_mm,
        &args.out,
        args.force,
    ) {
        Ok(done) => done,
        Err(noncirc::Error::Core(
            e @ (noncirc::core::Error::Teeth { .. } | noncirc::core::Error::OutlineCrossing { .. }),
        )) => {
            return Err(Box::new(VerdictFailed(format!(
                "the teeth cannot be cut: {e} (noncirc teeth gives advice)"
            ))))
        }
        Err(e) => return Err(e.into()),
    };
    for path in &done.paths {
        say!("wrote {}", path.display());
    }
    if !done.failures.is_empty() {
        return Err(Box::new(VerdictFailed(format!(
            "{}the teeth fail {}: {}",
            if done.paths.is_empty() {
                "nothing written (--force writes them anyway): "
            } else {
                ""
            },
            done.failed_checks,
            done.failures.join("; ")
        ))));
    }
    Ok(())
}

/// Write the mechanism turning as a GIF.
pub(crate) fn animate(args: AnimateArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.scene.scene.as_deref(), &args.scene.set)?;
    let kin = scene.kinematics(&scene.resolution)?;
    let teeth = if args.teeth {
        Some(noncirc::teeth::TeethRun::from_scene(&scene, 0.0)?)
    } else {
        None
    };
    noncirc::figures::animate(&kin, teeth.as_ref(), &args.out, args.frames)?;
    say!("wrote {}", args.out.display());
    Ok(())
}

/// Evaluate a planetary design.
pub(crate) fn evaluate(args: SceneArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.input.scene.as_deref(), &args.input.set)?;
    let (report, eval) = EvaluationReport::from_scene(&scene)?;
    noncirc::report::check_finite(&report)?;
    if let Some(dir) = &args.plot {
        plot_evaluation(&scene, &eval, dir, &args.figures()?)?;
    }
    match args.format {
        Format::Json => out(&json(&report)?)?,
        Format::Table => out(&report.table())?,
    }
    Ok(())
}

/// The variable-speed moving box.
pub(crate) fn moving_box(args: SceneArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(
        Some(args.input.scene.as_deref().unwrap_or("moving-box")),
        &args.input.set,
    )?;
    let mut box_scene = scene.clone();
    if box_scene.kind != SceneKind::Transplanter {
        box_scene.kind = SceneKind::MovingBox;
    }
    let (report, _) = EvaluationReport::from_scene(&box_scene)?;
    let b = report.moving_box.ok_or("this scene has no moving box")?;
    noncirc::report::check_finite(&b)?;
    if let Some(dir) = &args.plot {
        noncirc::files::create_dir(dir)?;
        let fig = noncirc::figures::BoxFigure {
            spec: &box_scene.moving_box,
            report: &b,
        };
        for f in noncirc::figures::save(&fig, &dir.join("moving_box"), &args.figures()?)? {
            say!("wrote {}", f.display());
        }
    }
    match args.format {
        Format::Json => out(&json(&b)?)?,
        Format::Table => out(&noncirc::report::box_table(&b))?,
    }
    Ok(())
}

/// The train at working speed.
pub(crate) fn dynamics(args: SceneArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.input.scene.as_deref(), &args.input.set)?;
    let r = noncirc::dynamics::report_of(&scene)?;
    if let Some(dir) = &args.plot {
        let arm_counts = noncirc::dynamics::by_arm_count(&scene);
        for f in noncirc::dynamics::figures(&r, &arm_counts, dir, &args.figures()?)? {
            say!("wrote {}", f.display());
        }
    }
    match args.format {
        Format::Json => out(&json(&r)?)?,
        Format::Table => out(&noncirc::dynamics::report_table(&r))?,
    }
    Ok(())
}

/// Each output's error over a resolution ladder.
pub(crate) fn accuracy(args: SceneArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.input.scene.as_deref(), &args.input.set)?;
    let report = noncirc::accuracy::measure(&scene, 720)?;
    match args.format {
        Format::Json => out(&json(&report)?)?,
        Format::Table => out(&report.table())?,
    }
    Ok(())
}

/// Every objective's response to one parameter.
pub(crate) fn sweep(args: SweepArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
    let measures = (args.measures.iter())
        .map(|m| Measure::parse(m))
        .collect::<Result<Vec<_>, _>>()?;
    let rows = noncirc::sweep::sweep(
        &scene,
        &args.param,
        args.from,
        args.to,
        args.steps,
        &measures,
    )?;
    if let Some(dir) = &args.scene.plot {
        for f in
            noncirc::plots::sweep_figures(&scene, &args.param, &rows, dir, &args.scene.figures()?)?
        {
            say!("wrote {}", f.display());
        }
    }
    match args.scene.format {
        Format::Json => out(&json(&rows)?)?,
        Format::Table => out(&noncirc::report::sweep_table(&args.param, &rows))?,
    }
    Ok(())
}

/// Two arms against three.
pub(crate) fn compare(args: CompareArgs) -> Result<(), Box<dyn Error>> {
    let source = args.scene.input.scene.as_deref().or(Some("paper-search"));
    let scene = load_scene_with(source, &args.scene.input.set)?;
    let paper = load_scene_with(Some("paper"), &[])?;
    let options = noncirc::compare::CompareOptions {
        arms: args.arms.clone(),
        seeds: args.seeds.clone(),
        picks_per_minute: args.picks_per_minute,
        measure: noncirc::core::Measure::parse(&args.measure)?,
        budget: Some(args.budget),
        threads: noncirc::search::threads_or_all(args.threads)?,
    };
    let c = noncirc::compare::compare(&scene, &paper, &options, &mut |r| {
        say!(
            "{} arms, seed {}: {} in {:.1} s",
            r.arms,
            r.seed,
            (r.speeds.compared_m_s)
                .filter(|_| r.speeds.feasible)
                .map_or("no feasible design".into(), |v| format!("{v:.4} m/s")),
            r.seconds
        );
    })?;
    if let Some(dir) = &args.scene.plot {
        let figures = args.scene.figures()?;
        let mut designs = Vec::new();
        for &arms in &args.arms {
            if let Some(best) = noncirc::compare::best_scene(&c, arms) {
                let (_, eval) = EvaluationReport::from_scene(&best)?;
                designs.push((best, eval));
            }
        }
        let files =
            noncirc::plots::comparison_outputs(&designs, c.picks_per_minute, dir, &figures)?;
        for f in files {
            say!("wrote {}", f.display());
        }
    }
    match args.scene.format {
        Format::Json => out(&json(&c)?)?,
        Format::Table => out(&noncirc::compare::comparison_table(&c))?,
    }
    Ok(())
}

/// The design once cut and assembled with the scene's tolerances.
pub(crate) fn robustness(args: RobustnessArgs) -> Result<(), Box<dyn Error>> {
    let mut set = args.scene.input.set.clone();
    if let Some(n) = args.samples {
        set.push(format!("tolerances.samples={n}"));
    }
    if let Some(seed) = args.seed {
        set.push(format!("tolerances.seed={seed}"));
    }
    let scene = load_scene_with(args.scene.input.scene.as_deref(), &set)?;
    let analysis = noncirc::robustness::robustness(&scene, !args.no_worst_case)?;
    if let Some(dir) = &args.scene.plot {
        let options = args.scene.figures()?;
        for f in noncirc::plots::robustness_figures(&analysis, dir, &options)? {
            say!("wrote {}", f.display());
        }
    }
    match args.scene.format {
        Format::Json => out(&json(&analysis)?)?,
        Format::Table => out(&noncirc::robustness::robustness_table(&analysis))?,
    }
    Ok(())
}

/// Sobol indices over the search box.
pub(crate) fn sensitivity(args: SensitivityArgs) -> Result<(), Box<dyn Error>> {
    let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
    let threads = noncirc::search::threads_or_all(args.threads)?;
    let s = noncirc::robustness::sensitivity(
        &scene,
        args.base_samples,
        args.bootstrap,
        args.box_scale,
        threads,
    )?;
    if let Some(dir) = &args.scene.plot {
        let options = args.scene.figures()?;
        for f in noncirc::plots::sensitivity_figures(&s, dir, &options)? {
            say!("wrote {}", f.display());
        }
    }
    match args.scene.format {
        Format::Json => out(&json(&s)?)?,
        Format::Table => out(&noncirc::robustness::sensitivity_table(&s))?,
    }
    Ok(())
}

/// Every measure with its unit.
pub(crate) fn measures() -> Result<(), Box<dyn Error>> {
    let lines: String = Measure::all()
        .iter()
        .map(|m| format!("{:<32} {:<5} {}\n", m.name(), m.unit(), m.description()))
        .collect();
    out(&lines)?;
    Ok(())
}

/// Serve the design studio.
pub(crate) fn studio(args: StudioArgs) -> Result<(), Box<dyn Error>> {
    let dir = args.dir.unwrap_or_else(server::default_dir);
    server::serve(&dir, args.port)?;
    Ok(())
}

/// The built-in scenes, or with `--reference` every field of a scene.
pub(crate) fn scenes(args: ScenesArgs) -> Result<(), Box<dyn Error>> {
    if args.reference {
        return out(&noncirc::scene_reference::markdown());
    }
    let mut lines = String::new();
    for (name, text) in BUILTIN {
        let scene = noncirc::scene_file::parse_scene(text, name)?;
        lines += &format!("{name:<12} {}\n", scene.description);
    }
    out(&lines)
}

/// Writes an evaluation's figures and CSV exports into `dir`.
fn plot_evaluation(
    scene: &noncirc::core::Scene,
    eval: &noncirc::core::Evaluation,
    dir: &std::path::Path,
    options: &noncirc::figures::FigureOptions,
) -> Result<(), Box<dyn Error>> {
    for f in noncirc::plots::evaluation_outputs(scene, eval, dir, options)? {
        say!("wrote {}", f.display());
    }
    Ok(())
}
