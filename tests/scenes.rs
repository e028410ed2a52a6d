//! Scenes evaluate only what they ask for; loading never panics, whatever the file.

use noncirc::core::{Evaluator, ObjectiveKind, Scene, SceneKind};
use noncirc::report::{check_finite, EvaluationReport};
use noncirc::scene_file::{load_scene, parse_scene, SceneError, BUILTIN};
use proptest::prelude::*;

#[test]
fn every_builtin_scene_evaluates() {
    for (name, _) in BUILTIN {
        let scene = load_scene(Some(name)).unwrap();
        let eval = Evaluator::new()
            .evaluate(&scene)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            eval.resolution, scene.resolution,
            "{name}: the result names its resolution"
        );
    }
}

#[test]
fn a_gear_scene_never_moves_the_mechanism() {
    let scene = load_scene(Some("ellipse-gear")).unwrap();
    let mut ev = Evaluator::new();
    for _ in 0..5 {
        ev.evaluate(&scene).unwrap();
    }
    let c = ev.counts();
    assert_eq!(
        (
            c.pitch_curve,
            c.closure,
            c.kinematics,
            c.events,
            c.moving_box
        ),
        (5, 5, 0, 0, 0)
    );
    assert_eq!(c.objectives[ObjectiveKind::Module as usize], 5);
    assert_eq!(c.objectives.iter().sum::<u64>(), 5);
}

#[test]
fn a_three_arm_scene_runs_only_the_objectives_asked() {
    let mut scene = load_scene(None).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate(&scene).unwrap();
    // The nine default objectives; not the teeth's strength, which none asked for.
    assert_eq!(ev.counts().objectives, [1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0]);
    assert_eq!((ev.counts().events, ev.counts().strength), (1, 0));
    // Interference and module need no events: none are located, and no other objective runs.
    scene.objectives = vec![ObjectiveKind::Interference, ObjectiveKind::Module];
    let mut ev = Evaluator::new();
    let out = ev.evaluate(&scene).unwrap();
    assert_eq!(out.objectives.len(), 2);
    let c = ev.counts();
    assert_eq!((c.kinematics, c.events, c.moving_box), (1, 0, 0));
    assert_eq!(c.objectives, [1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0]);
}

#[test]
fn moving_box_and_transplanter_scenes_run_the_box() {
    let mut ev = Evaluator::new();
    ev.evaluate(&load_scene(Some("moving-box")).unwrap())
        .unwrap();
    let c = ev.counts();
    assert_eq!((c.pitch_curve, c.kinematics, c.moving_box), (0, 0, 1));
    let mut ev = Evaluator::new();
    let out = ev
        .evaluate(&load_scene(Some("transplanter")).unwrap())
        .unwrap();
    assert_eq!(
        (
            ev.counts().kinematics,
            ev.counts().events,
            ev.counts().moving_box
        ),
        (1, 1, 1)
    );
    let b = out.moving_box.unwrap();
    let w = out.events.unwrap().picking_window_rad;
    assert!(((b.window_deg[1] - b.window_deg[0]) - 3.0 * (w[1] - w[0]).to_degrees()).abs() < 1e-9);
}

#[test]
fn a_gear_scene_cannot_ask_for_mechanism_objectives() {
    let scene = Scene {
        kind: SceneKind::Gear,
        objectives: vec![ObjectiveKind::PickingAngle],
        ..Scene::default()
    };
    let e = Evaluator::new().evaluate(&scene).unwrap_err().to_string();
    assert!(e.contains("picking_angle"), "{e}");
}

/// Replacement values that are wrong in every way a file can be wrong.
fn bad_value() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e308".to_string()),
        Just("-1e308".to_string()),
        Just("-7".to_string()),
        Just("0".to_string()),
        Just("7".to_string()),
        Just("\"text\"".to_string()),
        Just("[]".to_string()),
        Just("[1, 2]".to_string()),
        Just("true".to_string()),
        Just("{ a = 1 }".to_string()),
        Just("999999999999".to_string()),
        (-1e4f64..1e4).prop_map(|v| format!("{v}")),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random and mutated scene files: a located error or a valid result, never a panic.
    #[test]
    fn mutated_scenes_give_errors_or_results(
        which in 0usize..BUILTIN.len(),
        line in 0usize..200,
        action in 0usize..4,
        value in bad_value(),
    ) {
        let text = BUILTIN[which].1;
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        let i = line % lines.len();
        match action {
            0 => if let Some((k, _)) = lines[i].clone().split_once('=') { lines[i] = format!("{k}= {value}"); },
            1 => { lines.remove(i); }
            2 => lines.insert(i, format!("unknown_key_{i} = {value}")),
            _ => lines[i] = format!("{}{}", lines[i], value),
        }
        let mutated = lines.join("\n");
        match parse_scene(&mutated, "mutated.toml") {
            Err(e) => prop_assert!(e.to_string().starts_with("mutated.toml"), "unlocated error: {e}"),
            Ok(scene) => {
                if let Ok(out) = Evaluator::new().evaluate(&scene) {
                    for o in &out.objectives {
                        prop_assert!(!o.value.is_nan(), "{} is NaN", o.kind.name());
                        // A NaN or infinite bound would count as met or give no violation.
                        prop_assert!(o.violation.is_finite() && o.violation >= 0.0,
                            "{}: violation {}", o.kind.name(), o.violation);
                        for b in [o.lower, o.upper].into_iter().flatten() {
                            prop_assert!(b.is_finite(), "{}: bound {b}", o.kind.name());
                        }
                    }
                    // Every number of the report a user reads is finite.
                    let (report, _) = EvaluationReport::from_scene(&scene).unwrap();
                    if let Err(e) = check_finite(&report) {
                        prop_assert!(false, "{e}");
                    }
                }
            }
        }
    }
}

/// One parameter language: every number in a scene's serialisation (the paths `--set` and
/// the scene files use) is a parameter with the same value, and nothing else is, for every
/// built-in scene and every pitch-curve kind; writing through the parameter and through
/// `--set` gives the same scene.
#[test]
fn every_number_of_a_scene_is_a_parameter() {
    use noncirc::core::Param;
    use noncirc::scene_file::apply_overrides;
    fn leaves(v: &serde_json::Value, path: String, out: &mut Vec<(String, f64)>) {
        match v {
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    let p = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    leaves(x, p, out);
                }
            }
            serde_json::Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    leaves(x, format!("{path}[{i}]"), out);
                }
            }
            serde_json::Value::Number(n) => out.push((path, n.as_f64().unwrap())),
            _ => {}
        }
    }
    let mut scenes: Vec<Scene> = BUILTIN
        .iter()
        .map(|(n, _)| load_scene(Some(n)).unwrap())
        .collect();
    for kind in [
        r#"gear.curve={kind="fourier", c0_mm=40, cos_mm=[3, 1], sin_mm=[2]}"#,
        r#"gear.curve={kind="ellipse", semi_major_mm=30, eccentricity=0.2}"#,
        r#"gear.curve={kind="table", radii_mm=[30, 35, 40, 35], angles_deg=[0, 90, 180, 270]}"#,
        "agronomy.tray_distance_mm=300",
        "gear.module.teeth=40",
    ] {
        scenes.push(apply_overrides(load_scene(Some("paper")).unwrap(), &[kind.into()]).unwrap());
    }
    for scene in &scenes {
        let mut numbers = Vec::new();
        leaves(
            &serde_json::to_value(scene).unwrap(),
            String::new(),
            &mut numbers,
        );
        // Free-parameter bounds are the search's own description, not scene parameters.
        numbers.retain(|(p, _)| !p.starts_with("search.free"));
        let mut paths = Param::paths(scene);
        for (path, value) in &numbers {
            let p =
                Param::parse(path, scene).unwrap_or_else(|e| panic!("{}: {path}: {e}", scene.name));
            assert_eq!(p.get(scene), Some(*value), "{}: {path}", scene.name);
            let mut by_param = scene.clone();
            p.set(&mut by_param, value + 1.0);
            match apply_overrides(scene.clone(), &[format!("{path}={}", value + 1.0)]) {
                Ok(by_set) => assert_eq!(by_param, by_set, "{}: {path}", scene.name),
                // A value the checks refuse is refused the same whichever way it is written.
                Err(SceneError::Invalid { .. }) => assert!(
                    by_param.validate().is_err()
                        || by_param.validate_search().is_err()
                        || by_param.gear.curve.build().is_err(),
                    "{}: {path}",
                    scene.name
                ),
                Err(e) => panic!("{}: {path}: {e}", scene.name),
            }
        }
        // Unset optional fields are parameters too (they can be set) but not numbers yet.
        paths.retain(|p| !numbers.iter().any(|(n, _)| n == p));
        // `train.arms` is left out of a scene file while it is the paper's 3, so that
        // three-arm scenes (and their checkpoints' fingerprints) read as before; so is the
        // `[gear.teeth]` table while every tooth setting is the default.
        // The `[dynamics]` and `[cad]` tables likewise while they are the default.
        let teeth = noncirc_core::ToothSpec::default();
        let dynamics = serde_json::to_value(noncirc_core::DynamicsSpec::default()).unwrap();
        let cad = serde_json::to_value(noncirc_core::CadSpec::default()).unwrap();
        for p in &paths {
            let expected = match p.as_str() {
                p if p.starts_with("dynamics.") => dynamics[&p["dynamics.".len()..]].as_f64(),
                p if p.starts_with("cad.") => cad[&p["cad.".len()..]].as_f64(),
                "train.arms" => Some(3.0),
                "gear.teeth.pressure_angle_deg" => Some(teeth.pressure_angle_deg),
                "gear.teeth.addendum" => Some(teeth.addendum),
                "gear.teeth.dedendum" => Some(teeth.dedendum),
                "gear.teeth.tip_radius" => Some(teeth.tip_radius),
                "gear.teeth.backlash_mm" => Some(teeth.backlash_mm),
                "gear.teeth.profile_shift" => Some(teeth.profile_shift),
                "gear.teeth.flank_samples" => Some(teeth.flank_samples as f64),
                "gear.teeth.fillet_samples" => Some(teeth.fillet_samples as f64),
                "gear.teeth.chord_tolerance_mm" => Some(teeth.chord_tolerance_mm),
                "gear.teeth.mesh_steps_per_pitch" => Some(teeth.mesh_steps_per_pitch as f64),
                "gear.teeth.arc_panels" => Some(teeth.arc_panels as f64),
                "gear.teeth.min_tip_land" => Some(teeth.min_tip_land),
                _ => None,
            };
            assert_eq!(
                Param::parse(p, scene).unwrap().get(scene),
                expected,
                "{}: {p} is a parameter but not in the scene's numbers",
                scene.name
            );
        }
    }
}

#[test]
fn a_target_is_set_whole_then_by_key_and_written_with_the_scene() {
    use noncirc::scene_file::apply_overrides;
    let paper = load_scene(Some("paper")).unwrap();
    // A key of a table the scene does not have: refused, saying how to set it.
    let err = apply_overrides(paper.clone(), &["target.tolerance_mm=1".into()]).unwrap_err();
    assert!(
        err.to_string()
            .contains("the scene has no 'target': set the table whole first"),
        "{err}"
    );
    // Set whole, then by key; the written scene reads back with it.
    let whole = "target={x_mm=[300.0,0.0,-250.0,0.0],y_mm=[-100.0,200.0,-150.0,-380.0]}";
    let scene = apply_overrides(paper, &[whole.into(), "target.tolerance_mm=2".into()]).unwrap();
    let target = scene.target.as_ref().unwrap();
    assert_eq!((target.x_mm.len(), target.tolerance_mm), (4, 2.0));
    let text = toml::to_string(&scene).unwrap();
    let back = parse_scene(&text, "written").unwrap();
    assert_eq!(back, scene);
    assert!(Evaluator::new().evaluate(&back).unwrap().fit.is_some());
}
