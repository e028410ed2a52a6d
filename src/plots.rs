//! What `--plot DIR` writes for each command: figures plus the CSV/SVG/DXF exports.

use crate::export::{export_gears, export_trajectory};
use crate::figures::{
    evaluation_figures, save, ConvergenceFigure, FigureOptions, FitFigure, InverseFigure,
    LinesFigure, FIGURE_SAMPLES,
};
use crate::search::Outcome;
use crate::sweep::SweepRow;
use noncirc_core::{Evaluation, Param, Scene};
use std::path::{Path, PathBuf};

use crate::files::create_dir;
use crate::Result;

/// Figures of an evaluation, the trajectory CSV and the pitch-curve exports.
pub fn evaluation_outputs(
    scene: &Scene,
    eval: &Evaluation,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    let mut files = evaluation_figures(scene, eval, dir, options)?;
    if let Some(kin) = &eval.kinematics {
        files.push(export_trajectory(kin, dir)?);
    }
    if let Some(pair) = eval.pair() {
        let second = eval.kinematics.as_ref().and_then(|k| k.second_pair());
        files.extend(export_gears(pair, second, dir)?);
    }
    Ok(files)
}

/// Search convergence, the Pareto set (two goals or more), and the best design's figures.
pub fn search_figures(
    outcome: &Outcome,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    let mut files = progress_figures(outcome, dir, options)?;
    if let Some((scene, Some(eval))) = &outcome.confirmed.best {
        files.extend(evaluation_outputs(scene, eval, &dir.join("best"), options)?);
    }
    Ok(files)
}

/// Search convergence and the Pareto set (two goals or more).
fn progress_figures(
    outcome: &Outcome,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let problem = &outcome.problem;
    let goal_value = |f: f64| problem.goal_values(&[f])[0];
    let mut files = save(
        &ConvergenceFigure {
            algorithm: outcome.state.algorithm.name(),
            history: &outcome.state.history,
            goal: problem.goal_quantities().swap_remove(0),
            goal_value: &goal_value,
        },
        &dir.join("convergence"),
        options,
    )?;
    // Only feasible designs form the front: with none, the report holds the best
    // infeasible design, whose goals may be the invalid design's sentinel, not values.
    // In physical units: a maximised goal is drawn as itself, not negated.
    let pts: Vec<(f64, f64)> = (outcome.confirmed.pareto.iter())
        .filter(|(_, f)| f.feasible() && f.f.len() >= 2)
        .map(|(_, f)| outcome.problem.goal_values(&f.f))
        .map(|v| (v[0], v[1]))
        .collect();
    if !pts.is_empty() {
        // The reported design, the front's best on the first goal, drawn over it.
        let reported = (outcome.confirmed.best.as_ref())
            .and_then(|(scene, eval)| Some(outcome.problem.goal_values_of(eval.as_ref()?, scene)))
            .filter(|v| v.len() >= 2)
            .map(|v| vec![(v[0], v[1])])
            .unwrap_or_default();
        let mut series = vec![("first front".into(), pts.clone())];
        if !reported.is_empty() {
            series.push((
                "reported design: the front's best on the first goal".into(),
                reported,
            ));
        }
        files.extend(save(
            &LinesFigure {
                title: format!(
                    "Pareto set: {} designs, confirmed at the default resolution",
                    pts.len()
                ),
                x_desc: outcome.problem.goal_quantities()[0].label(),
                y_desc: outcome.problem.goal_quantities()[1].label(),
                series,
                points_only: true,
                markers: false,
                band: None,
            },
            &dir.join("pareto"),
            options,
        )?);
    }
    Ok(files)
}

/// A fit's figures: the search's convergence, the fitted design's figures (`best/`), and
/// the fit: target and fitted path overlaid with the pose errors (`fit.*`), and each
/// target sample's distance to the path (`fit_distance.*`).
pub fn fit_figures(
    outcome: &crate::fit::FitOutcome,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = progress_figures(&outcome.search, dir, options)?;
    if let Some((scene, eval)) = &outcome.best {
        files.extend(evaluation_outputs(scene, eval, &dir.join("best"), options)?);
        files.extend(target_figures(
            scene,
            eval,
            ["fitted", "target"],
            dir,
            options,
        )?);
    }
    Ok(files)
}

/// A repair's figures: the repaired design's (`repaired/`) and its path against the
/// given design's (`fit.*`, `fit_distance.*`).
pub fn repair_figures(
    outcome: &crate::repair::RepairOutcome,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = Vec::new();
    if let Some(r) = &outcome.repaired {
        files.extend(evaluation_outputs(
            &r.scene,
            &r.evaluation,
            &dir.join("repaired"),
            options,
        )?);
        let mut scene = r.scene.clone();
        scene.target = (outcome.fit.search.problem.base().target).clone();
        let mut eval = r.evaluation.clone();
        eval.fit = Some(r.fit.clone());
        files.extend(target_figures(
            &scene,
            &eval,
            ["repaired", "given design's"],
            dir,
            options,
        )?);
    }
    Ok(files)
}

/// An inversion's figures: where its conditions fail on the target (`inverse.*`), the
/// design's figures (`design/`, when one was built) and its path against the target
/// (`fit.*`, `fit_distance.*`).
pub fn inverse_figures(
    outcome: &noncirc_core::InverseOutcome,
    target: &noncirc_core::Target,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = Vec::new();
    let prepared = target.prepare()?;
    files.extend(save(
        &InverseFigure {
            outcome,
            prepared: &prepared,
        },
        &dir.join("inverse"),
        options,
    )?);
    if let (Some(scene), Some(eval)) = (&outcome.scene, &outcome.evaluation) {
        files.extend(evaluation_outputs(
            scene,
            eval,
            &dir.join("design"),
            options,
        )?);
        files.extend(target_figures(
            scene,
            eval,
            ["inverted", "target"],
            dir,
            options,
        )?);
    }
    Ok(files)
}

/// The design's path against its scene's target with the pose errors (`fit.*`), and each
/// target sample's distance to the path (`fit_distance.*`); `[how, against]` name the
/// design ("fitted", "inverted", "repaired") and the target ("target", "given design's").
fn target_figures(
    scene: &Scene,
    eval: &noncirc_core::Evaluation,
    [how, against]: [&str; 2],
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    if let (Some(target), Some(fit), Some(kin)) = (&scene.target, &eval.fit, &eval.kinematics) {
        let prepared = target.prepare()?;
        files.extend(save(
            &FitFigure {
                how,
                against,
                kin,
                target,
                prepared: &prepared,
                fit,
            },
            &dir.join("fit"),
            options,
        )?);
        // Each target sample's distance to the path drawn densely (every 0.05° of
        // carrier angle: chords far shorter than any tolerance shown).
        let path: Vec<noncirc_core::Vec2> = (0..7200)
            .map(|i| kin.state_at(std::f64::consts::TAU * i as f64 / 7200.0).tip)
            .collect();
        let samples = prepared.samples();
        let step = prepared.length_mm() / samples.len() as f64;
        let distances: Vec<(f64, f64)> = (samples.iter().enumerate())
            .map(|(i, &q)| {
                let d = (0..path.len())
                    .map(|k| noncirc_core::segment_distance(q, path[k], path[(k + 1) % path.len()]))
                    .fold(f64::INFINITY, f64::min);
                (i as f64 * step, d)
            })
            .collect();
        files.extend(save(
            &LinesFigure {
                title: format!(
                    "Distance of the {how} tip path from the {against} path (Hausdorff {:.3} mm)",
                    fit.path_hausdorff_mm
                ),
                x_desc: format!("arc length along the {against} path from its first point (mm)"),
                y_desc: "distance to the tip path (mm)".into(),
                series: vec![(format!("{against} path's samples"), distances)],
                points_only: false,
                markers: true,
                // A distance is never negative: the band runs from zero, not from the axis.
                band: Some((Some(0.0), Some(target.tolerance_mm))),
            },
            &dir.join("fit_distance"),
            options,
        )?);
    }
    Ok(files)
}

/// The paper's Figure 5: trajectories for each swept value, and every objective's response.
pub fn sweep_figures(
    scene: &Scene,
    param: &str,
    rows: &[SweepRow],
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut names: Vec<String> = rows
        .iter()
        .find(|r| !r.objectives.is_empty())
        .map(|r| r.objectives.keys().cloned().collect())
        .unwrap_or_default();
    names.extend(
        rows.iter()
            .flat_map(|r| r.measures.keys().cloned())
            .collect::<std::collections::BTreeSet<_>>(),
    );
    let mut files = Vec::new();
    // The papers' symbol with its unit (β0 (°)); the scene's path only where there is none.
    let symbol = noncirc_core::symbol(param).unwrap_or_else(|| param.to_string());
    let x_desc = match noncirc_core::field(param) {
        Some(f) if !f.unit.is_empty() => format!("{symbol} ({})", f.unit),
        _ => symbol.clone(),
    };
    for name in &names {
        // Its unit (objectives are measures too), and an objective's admissible range.
        let unit = noncirc_core::Measure::parse(name).map_or("", |m| m.unit());
        let kind = (noncirc_core::ObjectiveKind::ALL.iter()).find(|k| k.name() == name);
        let band = kind.map(|k| k.bounds(&scene.bounds));
        let label = kind.map_or(name.clone(), |k| k.label().to_string());
        let series = vec![(
            label.clone(),
            rows.iter()
                .filter_map(|r| {
                    let v = r.objectives.get(name).or_else(|| r.measures.get(name));
                    v.map(|v| (r.value, *v))
                })
                .collect(),
        )];
        files.extend(save(
            &LinesFigure {
                title: format!("{label} against {symbol}"),
                x_desc: x_desc.clone(),
                y_desc: if unit.is_empty() {
                    label.clone()
                } else {
                    format!("{label} ({unit})")
                },
                series,
                points_only: false,
                markers: true,
                band,
            },
            &dir.join(format!("response_{name}")),
            options,
        )?);
    }
    let p = Param::parse(param, scene)?;
    let mut series = Vec::new();
    for r in rows.iter().filter(|r| r.error.is_none()) {
        let mut s = scene.clone();
        p.set(&mut s, r.value);
        // Drawn from a dense solution, whatever the scene's resolution.
        let dense = (s.resolution).with_samples(s.resolution.samples_per_turn.max(FIGURE_SAMPLES));
        if let Ok(kin) = s.kinematics(&dense) {
            let pts = kin
                .tips()
                .iter()
                .chain(kin.tips().first())
                .map(|&t| t.into())
                .collect();
            series.push((format!("{symbol} = {:.3}", r.value), pts));
        }
    }
    if !series.is_empty() {
        files.extend(save(
            &LinesFigure {
                title: format!("Tip trajectory as {symbol} varies"),
                x_desc: "x (mm)".into(),
                y_desc: "y (mm)".into(),
                series,
                points_only: false,
                markers: false,
                band: None,
            },
            &dir.join("response_trajectories"),
            options,
        )?);
    }
    Ok(files)
}

/// The tolerance analysis's figure: each objective's margin distribution against its bound.
pub fn robustness_figures(
    analysis: &crate::robustness::Robustness,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    crate::figures::save(
        &crate::figures::MarginsFigure { analysis },
        &dir.join("robustness_margins"),
        options,
    )
}

/// The Sobol indices as a heat map.
pub fn sensitivity_figures(
    sensitivity: &crate::robustness::Sensitivity,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    crate::figures::save(
        &crate::figures::SensitivityFigure { sensitivity },
        &dir.join("sensitivity"),
        options,
    )
}

/// Two arms against three: each arm count's slowest design in one figure
/// (`speed_comparison`), and each design's own figures and exports in `arms_N/` beside its
/// scene (`best.toml`).
pub fn comparison_outputs(
    designs: &[(Scene, Evaluation)],
    picks_per_minute: f64,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = Vec::new();
    for (scene, eval) in designs {
        let arms = scene.train.arms;
        let sub = dir.join(format!("arms_{arms}"));
        files.extend(evaluation_outputs(scene, eval, &sub, options)?);
        let toml = crate::files::toml_text(scene, "scene")?;
        let path = sub.join("best.toml");
        crate::files::write_file(&path, toml.as_bytes())?;
        files.push(path);
    }
    let figure = crate::figures::SpeedComparisonFigure {
        designs: (designs.iter())
            .map(|(scene, eval)| crate::figures::ComparedDesign { scene, eval })
            .collect(),
        picks_per_minute,
    };
    files.extend(save(&figure, &dir.join("speed_comparison"), options)?);
    Ok(files)
}
