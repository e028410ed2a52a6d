//! The moving box against the moving-box paper and its own closed forms.

use noncirc::core::Resolution;
use noncirc::core::{box_curves, eccentricity_for_ratio, evaluate_box, BoxSpec};
use std::f64::consts::{PI, TAU};

fn res() -> Resolution {
    Resolution {
        samples_per_turn: 2400,
        ..Resolution::DEFAULT
    }
}

#[test]
fn closed_form_and_numerical_travel_agree_to_a_nanometre() {
    for k in [0.0, 0.1, 1.0 / (2.0 + 3f64.sqrt()), 0.5, 0.7] {
        for (c, w) in [
            (180.0f64, 60.0f64),
            (180.0, 15.0),
            (90.0, 40.0),
            (300.0, 120.0),
        ] {
            let spec = BoxSpec {
                eccentricity: k,
                window_centre_deg: c,
                window_deg: w,
                ..BoxSpec::default()
            };
            let r = evaluate_box(&spec, None, &res()).unwrap();
            assert!(
                (r.elliptic_delta_h_mm - r.elliptic_delta_h_numeric_mm).abs() < 1e-9,
                "k={k} c={c} w={w}: {} vs {}",
                r.elliptic_delta_h_mm,
                r.elliptic_delta_h_numeric_mm
            );
        }
    }
}

#[test]
fn the_papers_figures_as_computed() {
    let r = evaluate_box(&BoxSpec::default(), None, &res()).unwrap();
    assert!((r.speed_ratio - 3.0).abs() < 1e-12);
    assert_eq!(r.window_deg, [150.0, 210.0]);
    // 150°–210°: the elliptical drive moves 1.954 mm (paper: 2.1 theory, 2.05 rig), the
    // constant-speed box 3.333 mm (paper: 3.33). A 15° window gives neither figure.
    assert!(
        (r.elliptic_delta_h_mm - 1.954_217).abs() < 1e-6,
        "{}",
        r.elliptic_delta_h_mm
    );
    assert!((r.uniform_delta_h_mm - 10.0 / 3.0).abs() < 1e-12);
    assert!(r.within_limit && r.limit_mm == 3.0);
    let narrow = evaluate_box(
        &BoxSpec {
            window_deg: 15.0,
            ..BoxSpec::default()
        },
        None,
        &res(),
    )
    .unwrap();
    assert!((narrow.uniform_delta_h_mm - 20.0 * 15.0 / 360.0).abs() < 1e-12);
    assert!(narrow.elliptic_delta_h_mm < 0.5);
    // Sinusoidal shaft with the same speed ratio: p/2π (w − sin(w/2)) for w = 60°.
    assert!((r.sinusoidal_delta_h_mm - 20.0 / TAU * (PI / 3.0 - 0.5)).abs() < 1e-12);
    // Speed extremes: mean pitch speed times (1∓k)/(1±k).
    let v = 20.0 * 200.0 / 60.0;
    assert!((r.speed_min_mm_s - v / 3f64.sqrt()).abs() < 1e-9);
    assert!((r.speed_max_mm_s - v * 3f64.sqrt()).abs() < 1e-9);
    // Size: 23 teeth of module 2.25 on the pitch ellipse.
    assert!(r.semi_major_mm > 20.0 && r.semi_major_mm < 30.0);
}

#[test]
fn window_centred_on_180_degrees_minimises_travel() {
    for k in [0.05, 0.27, 0.6] {
        for w in [10.0, 60.0, 150.0] {
            let spec = BoxSpec {
                eccentricity: k,
                window_deg: w,
                window_centre_deg: 37.0,
                ..BoxSpec::default()
            };
            let r = evaluate_box(&spec, None, &res()).unwrap();
            assert!(
                (r.best_window_centre_deg - 180.0).abs() < 1e-4,
                "k={k} w={w}: {}",
                r.best_window_centre_deg
            );
        }
    }
}

#[test]
fn acceleration_and_forces_come_from_the_displacement_law() {
    let spec = BoxSpec::default();
    let n = 7200;
    let c = box_curves(&spec, n);
    let dt = TAU / n as f64 / spec.omega();
    for j in (1..n).step_by(97) {
        let speed = (c.elliptic_mm[j + 1] - c.elliptic_mm[j - 1]) / (2.0 * dt);
        assert!(
            (speed - c.elliptic_speed_mm_s[j]).abs()
                < 1e-3 * c.elliptic_speed_mm_s[j].abs().max(1.0)
        );
        let accel = (c.elliptic_mm[j + 1] - 2.0 * c.elliptic_mm[j] + c.elliptic_mm[j - 1])
            / (dt * dt)
            / 1000.0;
        assert!(
            (accel - c.elliptic_accel_m_s2[j]).abs() < 1e-3,
            "{accel} vs {}",
            c.elliptic_accel_m_s2[j]
        );
        assert!(
            (c.slider_normal_n[j] - spec.slider_forces(c.elliptic_accel_m_s2[j]).0).abs() < 1e-12
        );
    }
    // One pot pitch per input turn, for every drive.
    assert!((c.elliptic_mm[n] - 20.0).abs() < 1e-9);
    assert!((c.uniform_mm[n] - 20.0).abs() < 1e-9);
    assert!((c.sinusoidal_mm[n] - 20.0).abs() < 1e-9);
}

#[test]
fn closed_form_extremes_bound_and_meet_dense_samples() {
    for k in [0.0, 0.05, 1.0 / (2.0 + 3f64.sqrt()), 0.6, 0.9] {
        let spec = BoxSpec {
            eccentricity: k,
            ..BoxSpec::default()
        };
        let c = box_curves(&spec, 72_000);
        let accel = c
            .elliptic_accel_m_s2
            .iter()
            .fold(0.0f64, |m, a| m.max(a.abs()));
        let force = c.slider_normal_n.iter().fold(0.0f64, |m, f| m.max(f.abs()));
        let (accel_max, force_max) = (spec.accel_max(), spec.slider_force_max());
        // Sampled at 0.005°: the sampled extremes fall short by O(step²) at most.
        let near = |sampled: f64, exact: f64| {
            sampled <= exact * (1.0 + 1e-12) && sampled >= exact * (1.0 - 1e-6)
        };
        assert!(near(accel, accel_max), "k={k}: {accel} vs {accel_max}");
        assert!(near(force, force_max), "k={k}: {force} vs {force_max}");
    }
}

#[test]
fn eccentricity_from_speed_ratio_and_bad_inputs() {
    for r in [1.0, 2.0, 3.0, 9.0] {
        let k = eccentricity_for_ratio(r).unwrap();
        assert!((((1.0 + k) / (1.0 - k)).powi(2) - r).abs() < 1e-12);
    }
    let spec = BoxSpec {
        speed_ratio: Some(3.0),
        eccentricity: 0.9,
        ..BoxSpec::default()
    };
    assert!((spec.k().unwrap() - 1.0 / (2.0 + 3f64.sqrt())).abs() < 1e-15);
    for bad in [
        BoxSpec {
            eccentricity: 1.0,
            ..BoxSpec::default()
        },
        BoxSpec {
            eccentricity: f64::NAN,
            ..BoxSpec::default()
        },
        BoxSpec {
            pot_pitch_mm: -1.0,
            ..BoxSpec::default()
        },
        BoxSpec {
            window_deg: 400.0,
            ..BoxSpec::default()
        },
        BoxSpec {
            teeth: 0,
            ..BoxSpec::default()
        },
        BoxSpec {
            speed_ratio: Some(0.5),
            ..BoxSpec::default()
        },
    ] {
        assert!(evaluate_box(&bad, None, &res()).is_err(), "{bad:?}");
    }
}

#[test]
fn groove_development_is_the_rotated_sine() {
    let spec = BoxSpec::default();
    let (s, c) = spec.spiral_angle_deg.to_radians().sin_cos();
    // At the sine's zeros the groove lies on the straight spiral line.
    let period = TAU / spec.omega();
    for m in 0..4 {
        let t = m as f64 * period / 2.0;
        let noncirc::core::Vec2 { x, y } = spec.groove_point(t);
        assert!((x - t * s).abs() < 1e-12 && (y - t * c).abs() < 1e-12);
    }
}

/// `noncirc gear moving-box` reports the box's elliptical gears: an ellipse turning about
/// a focus meshes with its twin at twice its semi-major axis.
#[test]
fn the_gear_report_of_a_moving_box_scene_is_its_ellipse() {
    let scene = noncirc::scene_file::load_scene(Some("moving-box")).unwrap();
    let (report, _) = noncirc::report::GearReport::from_scene(&scene).unwrap();
    let b = noncirc::core::evaluate_box(&scene.moving_box, None, &scene.resolution).unwrap();
    assert_eq!(report.curve_kind, "ellipse");
    assert!(
        (report.centre_distance_mm - 2.0 * b.semi_major_mm).abs() < 1e-9,
        "{} against 2 × {}",
        report.centre_distance_mm,
        b.semi_major_mm
    );
    // Speed ratio (1 + k)² / (1 − k)² between the extreme ratios.
    let k = b.eccentricity;
    let ratio = report.ratio_max / report.ratio_min;
    assert!(
        (ratio - ((1.0 + k) / (1.0 - k)).powi(2)).abs() < 1e-6,
        "{ratio}"
    );
}
