//! The paper design's computed values (pinned), event accuracy, and robustness of the
//! objectives over random designs.

use noncirc::core::evaluate_all;
use noncirc::core::events;
use noncirc::core::{
    Agronomy, Bounds, CurveSpec, ModuleRule, ObjectiveKind, Resolution, TrainSpec,
};
use noncirc::core::{Kinematics, Rotation};
use noncirc::report::EvaluationReport;
use noncirc::scene_file::load_scene;
use proptest::prelude::*;

fn paper(samples: usize) -> (Vec<noncirc::core::ObjectiveValue>, noncirc::core::Events) {
    let kin = Kinematics::solve(
        &CurveSpec::paper().build().unwrap(),
        None,
        &TrainSpec::default(),
        &Resolution::DEFAULT.with_samples(samples),
    )
    .unwrap();
    evaluate_all(
        &kin,
        &Agronomy::default(),
        &Bounds::default(),
        &ModuleRule::default(),
    )
}

/// Regression pin of the paper design under the conventions of docs/replication.md.
#[test]
fn paper_design_values_are_pinned() {
    let (values, ev) = paper(360);
    let expect = [
        (ObjectiveKind::Interference, 44.974, 0.01),
        (ObjectiveKind::PickingAngle, 0.2970, 1e-3),
        (ObjectiveKind::PushingAngle, 53.9909, 1e-3),
        (ObjectiveKind::AngleDifference, 53.6939, 1e-3),
        (ObjectiveKind::SeedlingPush, 0.0, 1e-9),
        (ObjectiveKind::GroundClearance, 45.106, 0.01),
        (ObjectiveKind::TrajectoryHeight, 338.0309, 1e-3),
        (ObjectiveKind::Module, 0.1892, 1e-3),
        (ObjectiveKind::PickingAdmissible, 51.9908, 0.01),
    ];
    for (v, (kind, value, tol)) in values.iter().zip(expect) {
        assert_eq!(v.kind, kind);
        assert!(
            (v.value - value).abs() < tol,
            "{}: {} vs pinned {value}",
            kind.name(),
            v.value
        );
    }
    let met: Vec<_> = values
        .iter()
        .filter(|v| v.violation == 0.0)
        .map(|v| v.kind)
        .collect();
    assert_eq!(met.len(), 8, "all but the module are met");
    assert!(!met.contains(&ObjectiveKind::Module));
    assert!((ev.picking.carrier_rad.to_degrees() - 71.879).abs() < 0.01);
    assert!((ev.planting.carrier_rad.to_degrees() - 157.179).abs() < 0.01);
}

/// Picking and planting are extreme points located between samples: the located angle and
/// attitude agree across resolutions far better than one sample step.
#[test]
fn events_are_located_to_sub_sample_accuracy() {
    let (_, coarse) = paper(120);
    let (_, fine) = paper(2880);
    for (c, f) in [
        (coarse.picking, fine.picking),
        (coarse.planting, fine.planting),
    ] {
        assert!(
            (c.carrier_rad - f.carrier_rad).to_degrees().abs() < 0.01,
            "{} vs {}",
            c.carrier_rad,
            f.carrier_rad
        );
        assert!((c.attitude_deg - f.attitude_deg).abs() < 0.01);
        assert!((c.tip_mm - f.tip_mm).hypot() < 0.01);
    }
    // At the refined planting point the tip's vertical velocity vanishes.
    let kin = Kinematics::solve(
        &CurveSpec::paper().build().unwrap(),
        None,
        &TrainSpec::default(),
        &Resolution::DEFAULT,
    )
    .unwrap();
    let ev = events(&kin, &Agronomy::default());
    assert!(kin.state_at(ev.planting.carrier_rad).tip_d1.y.abs() < 1e-6);
}

/// Both rotation senses trace the same closed trajectory, in opposite directions.
#[test]
fn rotation_senses_trace_one_curve_backwards() {
    let curve = CurveSpec::paper().build().unwrap();
    let cw = Kinematics::solve(&curve, None, &TrainSpec::default(), &Resolution::DEFAULT).unwrap();
    let ccw = Kinematics::solve(
        &curve,
        None,
        &TrainSpec {
            rotation: Rotation::Counterclockwise,
            ..TrainSpec::default()
        },
        &Resolution::DEFAULT,
    )
    .unwrap();
    let n = cw.len();
    for j in 0..n {
        let (p, q) = (cw.tips()[j], ccw.tips()[(n - j) % n]);
        assert!((p - q).hypot() < 1e-6, "node {j}");
    }
}

#[test]
fn evaluate_report_has_the_documented_keys() {
    let (report, _) = EvaluationReport::from_scene(&load_scene(None).unwrap()).unwrap();
    let json = serde_json::to_value(&report).unwrap();
    for key in [
        "centre_distance_mm",
        "trajectory_height_mm",
        "events",
        "sections",
        "objectives",
        "measures",
    ] {
        assert!(json.get(key).is_some(), "missing {key}");
    }
    assert!(json["events"]["picking_carrier_deg"].is_number());
    assert!(json["events"]["planting_carrier_deg"].is_number());
    let objectives = json["objectives"].as_array().unwrap();
    assert_eq!(objectives.len(), 9);
    for o in objectives {
        for key in ["name", "value", "unit", "lower", "upper", "violation"] {
            assert!(o.get(key).is_some(), "objective missing {key}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The located events are the arm's state at their carrier angle: the tip, the
    /// attitude, the planet centre (the picking check) and the tip speed agree with
    /// `state_at` there far below the trajectory's accuracy (1e-3 mm at 120 samples), as
    /// Newton's last step is taken along the state's Taylor series; the picking point is
    /// an extreme along the tray normal and planting the lowest point. Both senses.
    #[test]
    fn events_are_the_arm_state_at_their_angle(
        radii in prop::collection::vec(10.0f64..70.0, 12),
        phi0 in -180.0f64..180.0, beta0 in -90.0f64..90.0, s in 60.0f64..250.0,
        h1 in 0.0f64..59.0, gamma0 in -170.0f64..170.0, clockwise in any::<bool>(),
    ) {
        let (_, angles) = noncirc::core::paper_control_points();
        let Ok(curve) = (CurveSpec::Spline { radii_mm: radii, angles_deg: angles }).build() else { return Ok(()); };
        let rotation = if clockwise { Rotation::Clockwise } else { Rotation::Counterclockwise };
        let train = TrainSpec { phi0_deg: phi0, beta0_deg: beta0, arm_length_mm: s, pusher_offset_mm: h1, gamma0_deg: gamma0, rotation, ..TrainSpec::default() };
        let Ok(kin) = Kinematics::solve(&curve, None, &train, &Resolution::DEFAULT) else { return Ok(()); };
        let agro = Agronomy::default();
        let ev = events(&kin, &agro);
        let normal = noncirc::core::unit(agro.tray_normal_deg.to_radians());
        let down = noncirc::core::Vec2::new(0.0, -1.0);
        for (event, dir) in [(ev.picking, normal), (ev.planting, down)] {
            let at = kin.state_at(event.carrier_rad);
            prop_assert!((event.tip_mm - at.tip).hypot() < 1e-7, "{:?} vs {:?}", event.tip_mm, at.tip);
            let attitude = noncirc::core::attitude_deg(at.pusher_angle);
            prop_assert!((event.attitude_deg - attitude).abs() < 1e-7, "{} vs {attitude}", event.attitude_deg);
            // Stationary along the direction (or the node, where Newton found no extreme).
            let slope = at.tip_d1.dot(dir).abs();
            let node = kin.tips().iter().any(|t| (*t - event.tip_mm).hypot() < 1e-9);
            prop_assert!(slope < 1e-6 * at.tip_d1.hypot() || node, "slope {slope}");
        }
        let at = kin.state_at(ev.picking.carrier_rad);
        let behind = ev.check.tray_surface_mm - at.o3.dot(normal);
        prop_assert!((ev.check.planet_behind_mm - behind).abs() < 1e-7, "{} vs {behind}", ev.check.planet_behind_mm);
        let speed = at.tip_d1.hypot() * kin.carrier_speed() / 1000.0;
        prop_assert!((ev.picking_tip_speed_m_s - speed).abs() < 1e-9 * speed.max(1.0), "{} vs {speed}", ev.picking_tip_speed_m_s);
    }

    /// Random designs around the paper: either a typed error or nine finite objectives with
    /// non-negative violations that are zero exactly when the value is within bounds.
    #[test]
    fn objectives_are_finite_or_typed_errors(
        radii in prop::collection::vec(10.0f64..70.0, 12),
        phi0 in -180.0f64..180.0, beta0 in -90.0f64..90.0, s in 60.0f64..250.0,
        h1 in 0.0f64..59.0, gamma0 in -170.0f64..170.0,
    ) {
        let (_, angles) = noncirc::core::paper_control_points();
        let Ok(curve) = (CurveSpec::Spline { radii_mm: radii, angles_deg: angles }).build() else { return Ok(()); };
        let train = TrainSpec { phi0_deg: phi0, beta0_deg: beta0, arm_length_mm: s, pusher_offset_mm: h1, gamma0_deg: gamma0, ..TrainSpec::default() };
        let Ok(kin) = Kinematics::solve(&curve, None, &train, &Resolution::FAST) else { return Ok(()); };
        let (values, ev) = evaluate_all(&kin, &Agronomy::default(), &Bounds::default(), &ModuleRule::default());
        prop_assert!(ev.picking.carrier_rad.is_finite() && ev.planting.carrier_rad.is_finite());
        for v in values {
            prop_assert!(v.value.is_finite(), "{} = {}", v.kind.name(), v.value);
            prop_assert!(v.violation >= 0.0);
            let inside = v.lower.is_none_or(|l| v.value >= l) && v.upper.is_none_or(|u| v.value <= u);
            prop_assert_eq!(inside, v.violation == 0.0);
        }
    }
}
