//! The train with two pairs (`gear.second_curve`) through the whole evaluation: the paper's
//! train written as two pairs evaluates as the paper's train, and a second pair unlike the
//! first limits the module and moves the path.

use noncirc::scene_file::{apply_overrides, parse_scene, BUILTIN};
use noncirc_core::{CurveSpec, Evaluator, ObjectiveKind, Scene};

fn paper() -> Scene {
    parse_scene(BUILTIN[0].1, BUILTIN[0].0).unwrap()
}

/// `scene` written as a train of two pairs whose layer B is the intermediate's own curve
/// (so the planet is the sun's copy), with β0 turned by the constant that the two
/// conventions place the planet's own frame apart.
fn as_two_pairs(scene: &Scene) -> Scene {
    let dense = scene.resolution.with_samples(2880);
    let one = scene.kinematics(&dense).unwrap();
    let mut two = scene.clone();
    two.gear.second_curve = Some(CurveSpec::table_through(&one.pair().driven_points()));
    let turned = two.kinematics(&dense).unwrap();
    let shift = one.planet_angles()[0] - turned.planet_angles()[0];
    two.train.beta0_deg += shift.to_degrees();
    two
}

#[test]
fn the_paper_train_as_two_pairs_meets_the_same_objectives() {
    // The intermediate's sharp lobe, sampled in its own angle, needs more than the
    // default 120 samples to close (the evaluation says so: `UnderResolved`).
    let mut scene = paper();
    scene.resolution = scene.resolution.with_samples(720);
    let two = as_two_pairs(&scene);
    let mut evaluator = Evaluator::new();
    let (e1, e2) = (
        evaluator.evaluate(&scene).unwrap(),
        evaluator.evaluate(&two).unwrap(),
    );
    let gear = e2.gear.unwrap();
    let second = gear
        .second
        .expect("a two-pair train reports its second pair");
    let (a1, a2) = (gear.centre_distance_mm, second.centre_distance_mm);
    assert!(
        (a1 - a2).abs() < 1e-6 * a1,
        "centre distances {a1} and {a2} mm"
    );
    for (o1, o2) in e1.objectives.iter().zip(&e2.objectives) {
        assert_eq!(o1.kind, o2.kind);
        let tol = 1e-3 * (1.0 + o1.value.abs());
        assert!(
            (o1.value - o2.value).abs() < tol,
            "{}: {} as one pair, {} as two",
            o1.kind.name(),
            o1.value,
            o2.value
        );
    }
    let (p1, p2) = (e1.events.unwrap().picking, e2.events.unwrap().picking);
    assert!((p1.tip_mm - p2.tip_mm).hypot() < 1e-3, "{p1:?} vs {p2:?}");
}

#[test]
fn a_second_pair_sets_the_module_when_it_is_the_sharper() {
    let base = apply_overrides(
        paper(),
        &["gear.curve={kind=\"ellipse\",semi_major_mm=30.0,eccentricity=0.1}".into()],
    )
    .unwrap();
    let sharp = apply_overrides(
        base.clone(),
        &["gear.second_curve={kind=\"ellipse\",semi_major_mm=30.0,eccentricity=0.45}".into()],
    )
    .unwrap();
    let mut evaluator = Evaluator::new();
    let module = |s: &Scene, ev: &mut Evaluator| {
        let e = ev.evaluate(s).unwrap();
        e.objective(ObjectiveKind::Module).unwrap().value
    };
    let (m1, m2) = (
        module(&base, &mut evaluator),
        module(&sharp, &mut evaluator),
    );
    let alone = noncirc_core::GearPair::solve(
        CurveSpec::Ellipse {
            semi_major_mm: 30.0,
            eccentricity: 0.45,
        }
        .build()
        .unwrap(),
        base.resolution,
    )
    .unwrap()
    .module(&base.gear.module)
    .module_max_mm;
    assert!(
        m2 < m1,
        "the sharper second pair lowers the module: {m1} → {m2}"
    );
    assert!(
        (m2 - alone).abs() < 1e-6,
        "{m2} vs the second pair alone {alone}"
    );
}

#[test]
fn a_gear_scene_refuses_a_second_curve() {
    let gear = parse_scene("kind = \"gear\"\nobjectives = [\"module\"]\n", "gear").unwrap();
    let err = apply_overrides(
        gear,
        &["gear.second_curve={kind=\"ellipse\",semi_major_mm=30.0,eccentricity=0.2}".into()],
    )
    .unwrap_err();
    assert!(err.to_string().contains("gear.second_curve"), "{err}");
}

#[test]
fn a_bad_second_curve_is_named_as_the_second_pairs() {
    let err = apply_overrides(
        paper(),
        &["gear.second_curve={kind=\"fourier\",c0_mm=10.0,cos_mm=[12.0],sin_mm=[0.0]}".into()],
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("gear.second_curve"), "{err}");
}

/// A train with two unlike pairs, toothed with 40 teeth a gear.
fn toothed_two_pair_scene() -> Scene {
    apply_overrides(
        paper(),
        &[
            "gear.curve={kind=\"ellipse\",semi_major_mm=32.0,eccentricity=0.12}".into(),
            "gear.second_curve={kind=\"fourier\",c0_mm=28.0,cos_mm=[1.5,-0.8],sin_mm=[-2.0,0.4]}"
                .into(),
            "resolution.samples_per_turn=720".into(),
            "gear.module.teeth=40".into(),
        ],
    )
    .unwrap()
}

#[test]
fn both_pairs_are_toothed_assembled_and_exported() {
    let scene = toothed_two_pair_scene();
    let run = noncirc::teeth::TeethRun::from_scene(&scene, 30.0).unwrap();
    let kin = scene.kinematics(&scene.resolution).unwrap();
    let second = run.second.as_ref().expect("the second pair is cut");
    let a2 = kin.centre_distances()[1];
    assert!((second.report.centre_distance_mm - a2).abs() < 1e-6 * a2);
    assert_eq!(second.teeth, 40);
    // The sun, then per arm set an intermediate, its layer B and a planet.
    assert_eq!(run.layout.len(), 1 + 3 * kin.arms());
    let names: Vec<&str> = run.layout.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(
        &names[..4],
        ["sun", "intermediate_1", "intermediate_1_b", "planet_1"]
    );
    let files: Vec<&str> = run.files(1e-3).into_iter().map(|(name, _)| name).collect();
    for name in [
        "second_driver.dxf",
        "second_driven.dxf",
        "second_driven.csv",
        "train.dxf",
    ] {
        assert!(files.contains(&name), "{name} missing from {files:?}");
    }
    assert!(run.table().contains("the second pair"));
}

/// The toothed planet turns with the kinematics' planet: its drawing angle differs from
/// θ3 by one constant (the toothed frame's angle 0 against the pitch curve's) at every
/// carrier angle, so the assembly meshes wherever it is drawn.
#[test]
fn the_toothed_planet_turns_with_the_kinematic_planet() {
    let scene = toothed_two_pair_scene();
    let run = noncirc::teeth::TeethRun::from_scene(&scene, 0.0).unwrap();
    let kin = scene.kinematics(&scene.resolution).unwrap();
    let second = run.second.as_ref().unwrap();
    let mut offsets = Vec::new();
    for step in 0..36 {
        let theta = std::f64::consts::TAU * step as f64 / 36.0;
        let layout = noncirc::teeth::train_layout(&kin, &run.pair, Some(second), theta);
        let theta3 = kin.state_at(theta).theta3;
        let d = layout[3].angle_deg.to_radians() - theta3;
        offsets.push(d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round());
    }
    let spread = offsets
        .iter()
        .map(|o| (o - offsets[0]).abs())
        .fold(0.0, f64::max);
    assert!(
        spread < 1e-6,
        "the toothed planet slips by {spread:e} rad against θ3"
    );
}
