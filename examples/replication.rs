//! The replication table of docs/replication.md: the paper's design under every reading the
//! paper leaves open, with the picking check, and the tray directions under which the
//! paper's reading picks and meets the angle objectives.
//!
//! `cargo run --release --example replication`

use noncirc::core::{Evaluator, ObjectiveKind, Scene};
use noncirc::scene_file::{apply_overrides, load_scene};

fn evaluate(sets: &[String]) -> Result<noncirc::core::Evaluation, String> {
    let mut all = vec!["resolution.samples_per_turn=360".to_string()];
    all.extend_from_slice(sets);
    let scene: Scene = apply_overrides(load_scene(Some("paper")).map_err(|e| e.to_string())?, &all)
        .map_err(|e| e.to_string())?;
    Evaluator::new().evaluate(&scene).map_err(|e| e.to_string())
}

fn main() -> Result<(), String> {
    println!("| construction | sun frame | pusher side | tray normal | picking at | planting at | picking angle | pushing angle | difference | can pick (mm) | met |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for construction in ["spline", "bspline", "bezier"] {
        for frame in ["installed", "ground"] {
            for side in ["left", "right"] {
                for tray in [-10.0, 135.0] {
                    let eval = evaluate(&[
                        format!("gear.curve.kind=\"{construction}\""),
                        format!("train.sun_frame=\"{frame}\""),
                        format!("train.pusher_side=\"{side}\""),
                        format!("agronomy.tray_normal_deg={tray}"),
                    ])?;
                    let ev = eval.events.as_ref().ok_or("no events")?;
                    let v = |k: ObjectiveKind| eval.objective(k).map_or(f64::NAN, |o| o.value);
                    let missed: Vec<&str> = (eval.objectives.iter())
                        .filter(|o| o.violation > 0.0)
                        .map(|o| o.kind.name())
                        .collect();
                    println!(
                        "| {construction} | {frame} | {side} | {tray}° | {:.1}° | {:.1}° | {:.1}° | {:.1}° | {:.1}° | {:.1} | {}/9{} |",
                        ev.picking.carrier_rad.to_degrees(),
                        ev.planting.carrier_rad.to_degrees(),
                        v(ObjectiveKind::PickingAngle),
                        v(ObjectiveKind::PushingAngle),
                        v(ObjectiveKind::AngleDifference),
                        v(ObjectiveKind::PickingAdmissible),
                        9 - missed.len(),
                        if missed.is_empty() {
                            String::new()
                        } else {
                            format!(" (missed: {})", missed.join(", "))
                        }
                    );
                }
            }
        }
    }
    println!();
    println!("Module under both readings (spline/bspline/bezier, installed, left, tray -10°):");
    println!();
    println!(
        "| construction | perimeter L (mm) | undercut rule (default) | perimeter rule, z = 40 |"
    );
    println!("|---|---|---|---|");
    for construction in ["spline", "bspline", "bezier"] {
        let kind = format!("gear.curve.kind=\"{construction}\"");
        let verdict = |eval: &noncirc::core::Evaluation| {
            eval.objective(ObjectiveKind::Module)
                .map_or(("-".to_string(), f64::NAN), |o| {
                    let word = if o.violation == 0.0 { "met" } else { "missed" };
                    (format!("{:.2} mm, {word}", o.value), o.value)
                })
        };
        let (undercut, _) = verdict(&evaluate(std::slice::from_ref(&kind))?);
        let (perimeter, m) = verdict(&evaluate(&[
            kind,
            "gear.module.rule=\"perimeter\"".into(),
            "gear.module.teeth=40".into(),
        ])?);
        println!(
            "| {construction} | {:.1} | {undercut} | {perimeter} |",
            m * std::f64::consts::PI * 40.0
        );
    }
    println!();
    println!("Tray directions (every 1°) under which each reading picks where a machine can and meets the three angle objectives:");
    println!();
    for construction in ["spline", "bspline", "bezier"] {
        for frame in ["installed", "ground"] {
            for side in ["left", "right"] {
                let mut good = Vec::new();
                for tray in -180..180 {
                    let eval = evaluate(&[
                        format!("gear.curve.kind=\"{construction}\""),
                        format!("train.sun_frame=\"{frame}\""),
                        format!("train.pusher_side=\"{side}\""),
                        format!("agronomy.tray_normal_deg={tray}"),
                    ])?;
                    let ok = [
                        ObjectiveKind::PickingAdmissible,
                        ObjectiveKind::PickingAngle,
                        ObjectiveKind::PushingAngle,
                        ObjectiveKind::AngleDifference,
                    ]
                    .iter()
                    .all(|&k| eval.objective(k).is_some_and(|o| o.violation == 0.0));
                    if ok {
                        good.push(tray);
                    }
                }
                println!("- {construction}, {frame}, {side}: {}", ranges(&good));
            }
        }
    }
    Ok(())
}

/// Whole degrees as runs: `-33..15, 40..41`, or `none`.
fn ranges(degrees: &[i32]) -> String {
    let mut runs: Vec<(i32, i32)> = Vec::new();
    for &d in degrees {
        match runs.last_mut() {
            Some((_, end)) if *end + 1 == d => *end = d,
            _ => runs.push((d, d)),
        }
    }
    if runs.is_empty() {
        return "none".into();
    }
    runs.iter()
        .map(|(a, b)| format!("{a}°..{b}°"))
        .collect::<Vec<_>>()
        .join(", ")
}
