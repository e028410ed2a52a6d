//! Scenes that would once have given a silent wrong answer are refused when read, with an
//! error that names the bad value (issue 22's findings, one test each).

use noncirc::core::{Evaluator, GearPair, Resolution};
use noncirc::scene_file::{apply_overrides, load_scene, parse_scene, SceneError};

const PAPER: &str = include_str!("../scenes/paper.toml");

/// The error of `--set` assignments on a built-in scene, as the user reads it.
fn refused(scene: &str, assignments: &[&str]) -> String {
    let assignments: Vec<String> = assignments.iter().map(|a| a.to_string()).collect();
    match apply_overrides(load_scene(Some(scene)).unwrap(), &assignments) {
        Ok(_) => panic!("{scene} {assignments:?} was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_nan_bound_is_refused_not_counted_as_met() {
    let text = PAPER.replace("module_min_mm = 2.5", "module_min_mm = nan");
    assert_ne!(text, PAPER, "the paper scene sets module_min_mm");
    let e = parse_scene(&text, "nan.toml").unwrap_err();
    assert!(matches!(e, SceneError::Invalid { .. }), "{e}");
    assert!(e.to_string().contains("bounds.module_min_mm"), "{e}");
    // The error points at the line that sets it.
    let line = 1 + PAPER
        .lines()
        .position(|l| l.starts_with("module_min_mm"))
        .unwrap();
    assert!(
        e.to_string()
            .starts_with(&format!("nan.toml: line {line}: ")),
        "{e}"
    );
    let e = parse_scene(
        &PAPER.replace("module_min_mm = 2.5", "module_min_mm = -inf"),
        "x",
    )
    .unwrap_err();
    assert!(e.to_string().contains("bounds.module_min_mm"), "{e}");
}

#[test]
fn reversed_bounds_are_refused() {
    let e = refused("paper", &["bounds.picking_angle_deg=[15,-5]"]);
    assert!(e.contains("bounds.picking_angle_deg[1] = -5"), "{e}");
    // Equal bounds are a legitimate exact requirement.
    apply_overrides(
        load_scene(Some("paper")).unwrap(),
        &["bounds.picking_angle_deg=[5,5]".into()],
    )
    .unwrap();
}

#[test]
fn objectives_are_listed_once_and_never_empty() {
    let e = refused("paper", &["objectives=[\"module\",\"module\"]"]);
    assert!(e.contains("'module' is listed twice"), "{e}");
    let e = refused("paper", &["objectives=[]"]);
    assert!(e.contains("objectives: empty"), "{e}");
    // A moving-box scene has no objectives, and needs none.
    load_scene(Some("moving-box")).unwrap();
}

#[test]
fn goals_must_be_computable_by_the_scene() {
    let e = refused("paper", &["search.goals=[\"box_travel\"]"]);
    assert!(e.contains("needs a moving box"), "{e}");
    let e = refused("paper", &["search.goals=[\"min:box_travel_mm\"]"]);
    assert!(e.contains("needs a moving box"), "{e}");
    let e = refused(
        "paper",
        &["search.goals=[\"least_margin\",\"least_margin\"]"],
    );
    assert!(e.contains("listed twice"), "{e}");
    let e = refused("paper", &["search.goals=[\"least_margn\"]"]);
    assert!(
        e.contains("least_margin"),
        "the nearest name is suggested: {e}"
    );
    apply_overrides(
        load_scene(Some("transplanter")).unwrap(),
        &["search.goals=[\"box_travel\",\"least_margin\"]".into()],
    )
    .unwrap();
}

#[test]
fn free_parameters_exist_once_with_finite_ordered_bounds() {
    let e = refused(
        "paper-search",
        &["search.free[0].lower=-1e308", "search.free[0].upper=1e308"],
    );
    assert!(e.contains("a finite width apart"), "{e}");
    let e = refused("paper-search", &["search.free[0].lower=90"]);
    assert!(e.contains("lower must be below the upper"), "{e}");
    let e = refused(
        "paper-search",
        &["search.free[1].name=\"gear.curve.radii_mm[0]\""],
    );
    assert!(e.contains("listed twice"), "{e}");
    let e = refused("paper-search", &["search.free[0].name=\"train.phi0_dg\""]);
    assert!(
        e.contains("train.phi0_deg"),
        "the nearest name is suggested: {e}"
    );
}

#[test]
fn text_after_a_json_scene_is_refused() {
    let json = serde_json::to_string(&load_scene(Some("paper")).unwrap()).unwrap();
    parse_scene(&json, "ok.json").unwrap();
    let e = parse_scene(&format!("{json} garbage"), "bad.json").unwrap_err();
    assert!(e.to_string().contains("text after the scene"), "{e}");
}

/// The closure's stopping tolerance may not exceed a tenth of its acceptance tolerance;
/// at that limit the centre distance is within the acceptance tolerance of the default's.
#[test]
fn a_loose_stopping_tolerance_is_refused_and_the_limit_is_accurate() {
    let e = refused("paper", &["resolution.newton_rel_tol=0.9999999"]);
    assert!(e.contains("resolution.newton_rel_tol = 0.9999999"), "{e}");
    let scene = load_scene(Some("paper")).unwrap();
    let loose = Resolution {
        newton_rel_tol: 0.1 * scene.resolution.closure_rel_tol,
        ..scene.resolution
    };
    let curve = scene.gear.curve.build().unwrap();
    let a = GearPair::solve(curve.clone(), scene.resolution)
        .unwrap()
        .centre_distance();
    let b = GearPair::solve(curve, loose).unwrap().centre_distance();
    assert!(
        (a - b).abs() <= scene.resolution.closure_rel_tol * a,
        "{a} vs {b}"
    );
}

#[test]
fn the_moving_box_refuses_overflowing_inputs() {
    let e = refused("moving-box", &["moving_box.input_speed_rpm=1e308"]);
    assert!(e.contains("moving_box.input_speed_rpm (n) = 1e308"), "{e}");
    let e = refused("moving-box", &["moving_box.groove_wall_angle_deg=85"]);
    assert!(
        e.contains("groove_wall_angle_deg + groove_friction_angle_deg"),
        "{e}"
    );
    // At the largest accepted speed every reported number is finite.
    let scene = apply_overrides(
        load_scene(Some("moving-box")).unwrap(),
        &["moving_box.input_speed_rpm=1e5".into()],
    )
    .unwrap();
    let out = Evaluator::new().evaluate(&scene).unwrap();
    let report = out.moving_box.expect("a moving-box scene reports the box");
    assert!(report.speed_max_mm_s.is_finite() && report.slider_force_max_n.is_finite());
}

#[test]
fn a_subnormal_gear_is_refused() {
    let e = refused("ellipse-gear", &["gear.curve.semi_major_mm=5e-324"]);
    assert!(e.contains("semi_major_mm = 5e-324"), "{e}");
}

#[test]
fn a_table_written_as_a_list_is_refused_not_read_position_by_position() {
    // `gear = []` took every default (the paper's spline in an ellipse scene), and
    // `train = [10, -29, …]` set the fields in order: a table must be written as one.
    let ellipse = noncirc::scene_file::BUILTIN
        .iter()
        .find(|(n, _)| *n == "ellipse-gear")
        .unwrap()
        .1;
    // The scene's keys before its first table, and `gear` as a list.
    let listed = format!("gear = []\n{}", ellipse.split_once("\n[").unwrap().0);
    let e = parse_scene(&listed, "g.toml").unwrap_err().to_string();
    assert!(e.contains("key 'gear'") && e.contains("table"), "{e}");
    let e = parse_scene(r#"{"train": [10, -29, 145, 65, -53]}"#, "t.json")
        .unwrap_err()
        .to_string();
    assert!(e.contains("key 'train'"), "{e}");
    // Nested tables too, and through --set.
    let e = parse_scene("[gear]\nteeth = [1, 2]\n", "n.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("key 'gear.teeth'"), "{e}");
    for (set, key) in [
        ("bounds=[5, [100, 200]]", "'bounds'"),
        ("gear=[]", "'gear'"),
    ] {
        let e = refused("paper", &[set]);
        assert!(e.contains(key) && e.contains("table"), "{set}: {e}");
    }
    // A list where the scene has a list stays a list.
    apply_overrides(
        load_scene(None).unwrap(),
        &["bounds.picking_angle_deg=[40, 60]".into()],
    )
    .unwrap();
}

/// Bounds near the largest numbers once added up to an infinite violation, refused as "a
/// bug"; they are refused by name with what is allowed, and at the widest allowed bounds
/// every violation and their sum are finite.
#[test]
fn bounds_beyond_a_machine_are_refused_by_name_and_the_widest_sum_finitely() {
    let e = refused(
        "paper",
        &[
            "bounds.module_min_mm=1e308",
            "bounds.trajectory_height_min_mm=1e308",
        ],
    );
    assert!(
        e.contains("_min_mm = 1e308 is out of range: expected -10000 to 10000"),
        "{e}"
    );
    let e = refused("paper", &["bounds.pushing_angle_deg=[-400.0, 65.0]"]);
    assert!(e.contains("bounds.pushing_angle_deg[0] = -400"), "{e}");
    let widest = apply_overrides(
        load_scene(Some("paper")).unwrap(),
        &[
            "bounds.module_min_mm=1e4".into(),
            "bounds.trajectory_height_min_mm=1e4".into(),
            "bounds.clearance_min_mm=1e4".into(),
            "bounds.ground_clearance_min_mm=1e4".into(),
            "bounds.picking_admissible_min_mm=1e4".into(),
            "bounds.seedling_push_max_mm=-1e4".into(),
            "search.constraints=[\"loop_width_mm >= 1e9\"]".into(),
        ],
    )
    .unwrap();
    let eval = Evaluator::new().evaluate(&widest).unwrap();
    assert!(eval.total_violation().is_finite() && eval.total_violation() > 1e9);
    let report = noncirc::report::EvaluationReport::new(&widest, &eval);
    assert!(!report.feasible && report.total_violation.is_finite());
}

/// Every cost that grew faster than its input is capped where a design stops needing more,
/// and the refusal names the value and the cap (issue 40): a Bézier curve of 1 000 points
/// took 31 s, 100 000 teeth over a minute, and an export tolerance of 1e-300 mm filled
/// 1.9 GB. (786 432 samples a turn, 607 s, is now linear: gearbox.rs thins the overlap's
/// probes, tested there.)
#[test]
fn every_cost_is_capped_by_name() {
    let bezier = |n: usize| {
        let angles: Vec<String> = (0..n)
            .map(|k| format!("{}", 360.0 * k as f64 / n as f64))
            .collect();
        let radii = vec!["40"; n].join(",");
        format!(
            "gear.curve={{kind=\"bezier\",radii_mm=[{radii}],angles_deg=[{}]}}",
            angles.join(",")
        )
    };
    let e = refused("ellipse-gear", &[&bezier(65)]);
    assert!(e.contains("bezier takes at most 64 points, got 65"), "{e}");
    // The cap itself is admitted (a circle of 64 points).
    apply_overrides(load_scene(Some("ellipse-gear")).unwrap(), &[bezier(64)]).unwrap();

    let e = refused(
        "ellipse-gear",
        &["gear.module.rule=\"perimeter\"", "gear.module.teeth=1001"],
    );
    assert!(e.contains("gear.module.teeth") && e.contains("1000"), "{e}");

    let run = noncirc::teeth::TeethRun::from_scene(&load_scene(Some("ellipse-gear")).unwrap(), 0.0)
        .unwrap();
    let dir = std::env::temp_dir().join(format!("noncirc-capped-export-{}", std::process::id()));
    for tolerance in [1e-300, 0.0, -1.0, f64::NAN, 0.06] {
        let e = run.export(&dir, tolerance).unwrap_err().to_string();
        assert!(
            e.contains("tolerance_mm") && e.contains("from 1e-6 to 0.05"),
            "{e}"
        );
        assert!(!dir.exists(), "{tolerance}: nothing written");
    }
    let written = run.export(&dir, 1e-6).unwrap();
    assert!(!written.is_empty());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A gear scene that names no objectives is told which it can have, not "= NaN".
#[test]
fn a_gear_scene_without_objectives_is_told_which_it_can_have() {
    let text = "name = \"bare\"\nkind = \"gear\"\n[gear.curve]\nkind = \"ellipse\"\n\
                semi_major_mm = 30\neccentricity = 0.2\n";
    let e = match parse_scene(text, "bare.toml") {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        e.contains("'interference' cannot be evaluated in a gear scene")
            && e.contains("objectives = [\"module\"]")
            && e.contains("with no `objectives`")
            && !e.contains("NaN"),
        "{e}"
    );
}
