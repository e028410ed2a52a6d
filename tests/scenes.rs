//! Scenes evaluate only what they ask for; loading never panics, whatever the file.

use noncirc::core::{Evaluator, ObjectiveKind, Scene, SceneKind};
use noncirc::scene_file::{load_scene, parse_scene, BUILTIN};
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
    assert_eq!(ev.counts().objectives, [1; 9]);
    assert_eq!(ev.counts().events, 1);
    // Interference and module need no events: none are located, and no other objective runs.
    scene.objectives = vec![ObjectiveKind::Interference, ObjectiveKind::Module];
    let mut ev = Evaluator::new();
    let out = ev.evaluate(&scene).unwrap();
    assert_eq!(out.objectives.len(), 2);
    let c = ev.counts();
    assert_eq!((c.kinematics, c.events, c.moving_box), (1, 0, 0));
    assert_eq!(c.objectives, [1, 0, 0, 0, 0, 0, 0, 1, 0]);
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
                    }
                }
            }
        }
    }
}
