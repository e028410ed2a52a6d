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
