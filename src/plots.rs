//! What `--plot DIR` writes for each command: figures plus the CSV/SVG/DXF exports.

use crate::export::{export_gears, export_trajectory};
use crate::figures::{evaluation_figures, save, LinesFigure};
use crate::search::{Outcome, SweepRow};
use noncirc_core::{Evaluation, Param, Scene};
use std::path::{Path, PathBuf};

use crate::files::create_dir;
use crate::Result;

/// Figures of an evaluation, the trajectory CSV and the pitch-curve exports.
pub fn evaluation_outputs(scene: &Scene, eval: &Evaluation, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = evaluation_figures(scene, eval, dir)?;
    if let Some(kin) = &eval.kinematics {
        files.push(export_trajectory(kin, dir)?);
    }
    if let Some(pair) = eval.pair() {
        files.extend(export_gears(pair, dir)?);
    }
    Ok(files)
}

/// Search convergence, the Pareto set (two goals or more), and the best design's figures.
pub fn search_figures(outcome: &Outcome, dir: &Path) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let h = &outcome.state.history;
    let cv: Vec<(f64, f64)> = h
        .iter()
        .map(|r| (r.evaluations as f64, r.best_cv.max(1e-6).log10()))
        .collect();
    let goal: Vec<(f64, f64)> = h
        .iter()
        .filter(|r| r.best_cv == 0.0)
        .map(|r| (r.evaluations as f64, r.best_goal))
        .collect();
    let mut files = save(
        &LinesFigure {
            title: format!("Search convergence ({})", outcome.state.algorithm.name()),
            x_desc: "evaluations".into(),
            y_desc: "log10 best violation  /  best goal once feasible".into(),
            series: vec![
                ("log10(best CV)".into(), cv),
                ("best goal (feasible)".into(), goal),
            ],
            points_only: false,
        },
        &dir.join("convergence"),
    )?;
    // Only feasible designs form the front: with none, the report holds the best
    // infeasible design, whose goals may be the invalid design's sentinel, not values.
    // In physical units: a maximised goal is drawn as itself, not negated.
    let pts: Vec<(f64, f64)> = (outcome.confirmed.pareto.iter())
        .filter(|(_, f)| f.feasible())
        .map(|(_, f)| outcome.problem.goal_values(&f.f))
        .map(|v| (v[0], v[1]))
        .collect();
    if outcome.problem.goals() >= 2 && !pts.is_empty() {
        files.extend(save(
            &LinesFigure {
                title: format!(
                    "Pareto set: {} designs, confirmed at the default resolution",
                    pts.len()
                ),
                x_desc: outcome.problem.goal_quantities()[0].label(),
                y_desc: outcome.problem.goal_quantities()[1].label(),
                series: vec![("first front".into(), pts)],
                points_only: true,
            },
            &dir.join("pareto"),
        )?);
    }
    if let Some((scene, Some(eval))) = &outcome.confirmed.best {
        files.extend(evaluation_outputs(scene, eval, &dir.join("best"))?);
    }
    Ok(files)
}

/// The paper's Figure 5: trajectories for each swept value, and every objective's response.
pub fn sweep_figures(
    scene: &Scene,
    param: &str,
    rows: &[SweepRow],
    dir: &Path,
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
    for name in &names {
        let series = vec![(
            name.clone(),
            rows.iter()
                .filter_map(|r| {
                    let v = r.objectives.get(name).or_else(|| r.measures.get(name));
                    v.map(|v| (r.value, *v))
                })
                .collect(),
        )];
        files.extend(save(
            &LinesFigure {
                title: format!("{name} against {param}"),
                x_desc: param.into(),
                y_desc: name.clone(),
                series,
                points_only: false,
            },
            &dir.join(format!("response_{name}")),
        )?);
    }
    let p = Param::parse(param, scene)?;
    let mut series = Vec::new();
    for r in rows.iter().filter(|r| r.error.is_none()) {
        let mut s = scene.clone();
        p.set(&mut s, r.value);
        if let Ok(kin) =
            noncirc_core::Kinematics::solve(&s.gear.curve.build()?, &s.train, &s.resolution)
        {
            let pts = kin
                .tips()
                .iter()
                .chain(kin.tips().first())
                .map(|&t| t.into())
                .collect();
            series.push((format!("{param} = {:.3}", r.value), pts));
        }
    }
    if !series.is_empty() {
        files.extend(save(
            &LinesFigure {
                title: format!("Tip trajectory as {param} varies"),
                x_desc: "x (mm)".into(),
                y_desc: "y (mm)".into(),
                series,
                points_only: false,
            },
            &dir.join("response_trajectories"),
        )?);
    }
    Ok(files)
}
