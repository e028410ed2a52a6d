//! `noncirc fit`: the search for the design nearest a target, with its progress bar,
//! signals, checkpoints and outputs (as `optimise`), then the local refinement;
//! `noncirc target`, a scene's own path as a target; `noncirc inverse`, the exact
//! inversion for the train with two pairs.

use crate::args::{BranchArg, FitArgs, Format, InverseArgs, RepairArgs, TargetArgs};
use crate::commands::VerdictFailed;
use crate::optimise::{prepare_search, PreparedSearch};
use crate::output::{json, out, out_interrupted};
use crate::Finished;
use noncirc::core::LocalSettings;
use noncirc::fit::{fit_scene, read_target, with_target, FitOptions};
use noncirc::repair::{repair_scene, RepairOptions};
use std::sync::atomic::Ordering;

/// Fit the scene's design to a target; exit 3 when the fit misses a tolerance or an
/// objective (its outputs written), 130 when a signal stopped it.
pub(crate) fn fit(args: FitArgs) -> Result<Finished, Box<dyn std::error::Error>> {
    if args.search.resume.is_some() && (args.target.is_some() || args.tolerance_mm.is_some()) {
        return Err(noncirc::Error::Input(
            "--resume continues the checkpoint's own scene and target; --target and \
             --tolerance-mm would be ignored"
                .into(),
        )
        .into());
    }
    let PreparedSearch {
        mut scene,
        opts,
        stop,
        mut progress,
    } = prepare_search(&args.search, "paper-search")?;
    if let Some(path) = &args.target {
        scene = with_target(scene, read_target(path)?);
    }
    if let Some(tolerance) = args.tolerance_mm {
        let Some(target) = scene.target.as_mut() else {
            return Err(noncirc::Error::Input(
                "--tolerance-mm sets the target path's tolerance: the scene has no target \
                 (give --target FILE)"
                    .into(),
            )
            .into());
        };
        std::sync::Arc::make_mut(target).tolerance_mm = tolerance;
        target.validate()?;
    }
    if let Some(dir) = &args.search.out {
        let name = args.search.resume.is_none().then_some(scene.name.as_str());
        noncirc::search::check_out_dir(dir, name, args.search.force)?;
    }
    let options = FitOptions {
        run: opts,
        local: LocalSettings::default(),
    };
    let outcome = fit_scene(&scene, &options, &mut [&mut progress])?;
    if let Some(bar) = progress.bar {
        bar.finish_and_clear();
    }
    if let Some(dir) = &args.search.out {
        outcome.write(dir)?;
    }
    if let Some(dir) = &args.search.scene.plot {
        for f in noncirc::plots::fit_figures(&outcome, dir, &args.search.scene.figures()?)? {
            say!("wrote {}", f.display());
        }
    }
    let summary = outcome.summary();
    conclude(
        &summary,
        summary.table(),
        args.search.scene.format,
        stop.load(Ordering::SeqCst)
            .then_some("and in the checkpoint and --out"),
        (!summary.met).then(|| summary.failures()),
    )
}

/// Prints a run's summary (its JSON, or `table`) and gives its exit: interrupted (its
/// results so far printed, and where else they are, `saved`), a verdict failed with
/// `failures`, or completed.
fn conclude(
    summary: &impl serde::Serialize,
    table: String,
    format: Format,
    interrupted: Option<&str>,
    failures: Option<String>,
) -> Result<Finished, Box<dyn std::error::Error>> {
    noncirc::report::check_finite(summary)?;
    let text = match format {
        Format::Json => json(summary)?,
        Format::Table => table,
    };
    if let Some(saved) = interrupted {
        out_interrupted(&text)?;
        say!("interrupted: the results so far are above ({saved})");
        return Ok(Finished::Interrupted);
    }
    out(&text)?;
    match failures {
        Some(failures) => Err(VerdictFailed(failures).into()),
        None => Ok(Finished::Completed),
    }
}

/// Repair the scene's design; exit 3 when no design within the budget meets every
/// objective with teeth that cut and mesh (its outputs written), 130 when a signal stopped
/// it.
pub(crate) fn repair(args: RepairArgs) -> Result<Finished, Box<dyn std::error::Error>> {
    if args.search.resume.is_some() || args.search.checkpoint.is_some() {
        return Err(noncirc::Error::Input(
            "repair starts from the scene's design and takes seconds: it neither writes nor \
             resumes a checkpoint (drop --checkpoint and --resume)"
                .into(),
        )
        .into());
    }
    let PreparedSearch {
        scene,
        opts,
        stop,
        mut progress,
    } = prepare_search(&args.search, "paper-search")?;
    let options = RepairOptions {
        path_tolerance_mm: args.path_tolerance_mm,
        design_scale: args.design_scale,
        ..RepairOptions::new(opts)
    };
    let outcome = repair_scene(&scene, &options, &mut [&mut progress])?;
    if let Some(bar) = progress.bar {
        bar.finish_and_clear();
    }
    if let Some(dir) = &args.search.out {
        outcome.write(dir)?;
    }
    if let Some(dir) = &args.search.scene.plot {
        for f in noncirc::plots::repair_figures(&outcome, dir, &args.search.scene.figures()?)? {
            say!("wrote {}", f.display());
        }
    }
    let summary = outcome.summary();
    conclude(
        &summary,
        summary.table(),
        args.search.scene.format,
        stop.load(Ordering::SeqCst).then_some("and in --out"),
        (!summary.repaired).then(|| summary.failures()),
    )
}

/// Print the scene's own path and events as a `[target]` table.
pub(crate) fn target(args: TargetArgs) -> Result<(), Box<dyn std::error::Error>> {
    let [lo, hi] = [
        noncirc::core::Target::MIN_POINTS,
        noncirc::core::Target::MAX_POINTS,
    ];
    if !(lo..=hi).contains(&args.points) {
        return Err(noncirc::Error::Input(format!(
            "--points {}: expected {lo} to {hi}",
            args.points
        ))
        .into());
    }
    let scene = noncirc::scene_file::load_scene_with(args.scene.scene.as_deref(), &args.scene.set)?;
    let eval = noncirc::core::Evaluator::new().evaluate(&scene)?;
    let (Some(kin), Some(events)) = (&eval.kinematics, &eval.events) else {
        return Err(noncirc::Error::Input(format!(
            "a {} scene has no tip path: a target needs a three_arm or transplanter scene",
            scene.kind.name()
        ))
        .into());
    };
    let target = noncirc::core::target_of(kin, events, args.points);
    target.prepare()?;
    let text = format!(
        "# The tip path and events of scene '{}' as a target (noncirc target).\n{}",
        scene.name,
        noncirc::fit::target_toml(&target)?
    );
    out(&text)?;
    Ok(())
}

/// Invert a target for the train with two pairs; exit 3 when a condition fails or an
/// objective is missed (the outputs written first), 2 on bad input (nothing written).
pub(crate) fn inverse(args: InverseArgs) -> Result<Finished, Box<dyn std::error::Error>> {
    let input = &args.scene.input;
    let scene = noncirc::scene_file::load_scene_with(
        Some(input.scene.as_deref().unwrap_or("paper")),
        &input.set,
    )?;
    let target = match (&args.target, &scene.target) {
        (Some(path), _) => read_target(path)?,
        (None, Some(target)) => (**target).clone(),
        (None, None) => {
            return Err(noncirc::Error::Input(
                "no target: give --target FILE (a CSV of x_mm,y_mm or a [target] table), or \
                 a scene with a [target]"
                    .into(),
            )
            .into())
        }
    };
    let split = noncirc::inverse::parse_split(&args.split)?;
    let branch = args.branch.map(|b| match b {
        BranchArg::Plus => noncirc::core::Branch::Plus,
        BranchArg::Minus => noncirc::core::Branch::Minus,
    });
    let outcome = noncirc::inverse::inverse_scene(
        &scene,
        &target,
        args.centre_ratio,
        split,
        branch,
        args.samples,
    )?;
    if let Some(dir) = &args.out {
        noncirc::inverse::write(&outcome, split, dir)?;
    }
    if let Some(dir) = &args.scene.plot {
        for f in noncirc::plots::inverse_figures(&outcome, &target, dir, &args.scene.figures()?)? {
            say!("wrote {}", f.display());
        }
    }
    let summary = noncirc::inverse::summary(&outcome, split);
    conclude(
        &summary,
        summary.table(),
        args.scene.format,
        None,
        (!summary.met).then(|| summary.failures()),
    )
}
