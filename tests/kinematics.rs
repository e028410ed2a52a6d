//! Convention-free physics of the three-arm train (spec §2): at every sample and both
//! meshes, each gear's own pitch curve, placed by its own orientation, reaches the same
//! contact point on the line of centres; the curves are tangent there; the material points'
//! velocities agree. Run for both rotation senses, both sun frames and several designs, for
//! the paper's train and the train with two pairs.

use noncirc::core::{
    unit, CurveSpec, GearPair, Kinematics, PitchCurve, Resolution, Rotation, SunFrame, TrainSpec,
    Vec2,
};
use std::f64::consts::{PI, TAU};

/// The intermediate's own pitch curve: the material point of sun parameter ψ at own angle
/// χ = −(phi2(ψ) − phi2(ψ_start)), radius a − ρ(ψ); built from the gear-pair code path.
fn intermediate_curve(sun: &PitchCurve, a: f64, psi_start: f64) -> PitchCurve {
    let pair = GearPair::solve(sun.clone(), Resolution::DEFAULT.with_samples(2880)).unwrap();
    let n = pair.samples().len();
    let offset = pair.phi2(psi_start);
    let mut points: Vec<(f64, f64)> = (0..n)
        .map(|j| (-(pair.phi2_nodes()[j] - offset), a - pair.samples()[j].rho))
        .collect();
    points.reverse();
    let (angles, radii): (Vec<f64>, Vec<f64>) =
        points.iter().map(|(c, r)| (c.to_degrees(), *r)).unzip();
    CurveSpec::Table {
        radii_mm: radii,
        angles_deg: angles,
    }
    .build()
    .unwrap()
}

fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(TAU) - PI
}

/// Absolute tangent direction (mod π) of a polar curve placed with orientation `orient`,
/// at own angle `chi`.
fn tangent(curve: &PitchCurve, orient: f64, chi: f64) -> f64 {
    let p = curve.eval(chi);
    orient + chi + p.rho.atan2(p.d1)
}

/// Largest mismatch over the cycle: (radius sum − a, tangent angle, velocity) at both meshes.
/// With `second`, the intermediate's layer B drives the planet, its conjugate.
fn mesh_errors(
    spec: &CurveSpec,
    second: Option<&CurveSpec>,
    train: &TrainSpec,
    samples: usize,
) -> (f64, f64, f64) {
    let sun = spec.build().unwrap();
    let layer_b = second.map(|c| c.build().unwrap());
    let res = Resolution::DEFAULT.with_samples(samples);
    let kin = Kinematics::solve(&sun, layer_b.as_ref(), train, &res).unwrap();
    let a = kin.centre_distance();
    let inter = intermediate_curve(&sun, a, train.psi_start());
    // The second mesh's curves and centre distance: the planet's own angle 0 meets layer
    // B's own angle γ0 − π (where the intermediate's layer A meets the sun at θ = 0).
    let (inter2, planet, a2) = match &layer_b {
        None => (inter.clone(), sun.clone(), a),
        Some(b) => {
            let a2 = kin.centre_distances()[1];
            let start = train.gamma0_deg.to_radians() - PI;
            (b.clone(), intermediate_curve(b, a2, start), a2)
        }
    };
    let sun_angle = train.sun_angle();
    let (mut radius, mut tang, mut vel) = (0.0f64, 0.0f64, 0.0f64);
    for j in 0..kin.len() {
        let theta = kin.theta(j) + 0.37 * TAU / kin.len() as f64;
        let s = kin.state_at(theta);
        let dir = |p: Vec2, q: Vec2| (q.y - p.y).atan2(q.x - p.x);
        // Mesh 1: sun (fixed, turned by sun_angle) and intermediate, on the line O1 O2.
        let phi_h = dir(Vec2::ZERO, s.o2);
        let chi1 = phi_h + PI - s.theta2;
        let r_sun = sun.eval(phi_h - sun_angle).rho;
        let r_int = inter.eval(chi1).rho;
        radius = radius.max((r_sun + r_int - a).abs());
        let t_sun = tangent(&sun, sun_angle, phi_h - sun_angle);
        let t_int = tangent(&inter, s.theta2, chi1);
        tang = tang.max(wrap(2.0 * (t_sun - t_int)).abs() / 2.0);
        // Mesh 2: intermediate and planet, on the line O2 O3.
        let toward_o3 = dir(s.o2, s.o3);
        let chi2 = toward_o3 - s.theta2;
        let chi3 = toward_o3 + PI - s.theta3;
        let (ri, rp) = (inter2.eval(chi2).rho, planet.eval(chi3).rho);
        radius = radius.max((ri + rp - a2).abs());
        let t_i = tangent(&inter2, s.theta2, chi2);
        let t_p = tangent(&planet, s.theta3, chi3);
        tang = tang.max(wrap(2.0 * (t_i - t_p)).abs() / 2.0);
        // Velocities of the two material points at the mesh-2 contact (central differences).
        let c = s.o2 + unit(toward_o3) * ri;
        let h = 1e-5;
        // Where the material point now at `c` is when its body sits at (centre2, angle2).
        let moved = |centre: Vec2, angle: f64, centre2: Vec2, angle2: f64| {
            centre2 + (c - centre).rotated(unit(angle2 - angle))
        };
        let (sp, sm) = (kin.state_at(theta + h), kin.state_at(theta - h));
        let vi = {
            let (p, m) = (
                moved(s.o2, s.theta2, sp.o2, sp.theta2),
                moved(s.o2, s.theta2, sm.o2, sm.theta2),
            );
            (p - m) * (0.5 / h)
        };
        let vp = {
            let (p, m) = (
                moved(s.o3, s.theta3, sp.o3, sp.theta3),
                moved(s.o3, s.theta3, sm.o3, sm.theta3),
            );
            (p - m) * (0.5 / h)
        };
        vel = vel.max((vi - vp).hypot());
        // Mesh 1 velocity: the intermediate's point at C1 must be at rest (the sun is fixed).
        let c1 = unit(phi_h) * r_sun;
        let moved1 =
            |st: &noncirc::core::ArmState| st.o2 + (c1 - s.o2).rotated(unit(st.theta2 - s.theta2));
        let (p, m) = (moved1(&sp), moved1(&sm));
        vel = vel.max(((p - m) * (0.5 / h)).hypot());
    }
    (radius, tang, vel)
}

fn designs() -> Vec<(&'static str, CurveSpec)> {
    let (r, a) = noncirc::core::paper_control_points();
    vec![
        (
            "paper spline",
            CurveSpec::Spline {
                radii_mm: r.clone(),
                angles_deg: a.clone(),
            },
        ),
        (
            "paper bspline",
            CurveSpec::Bspline {
                radii_mm: r,
                angles_deg: a,
            },
        ),
        (
            "fourier",
            CurveSpec::Fourier {
                c0_mm: 40.0,
                cos_mm: vec![8.0, 3.0],
                sin_mm: vec![-4.0, 1.0, 0.5],
            },
        ),
    ]
}

/// Both meshes of `spec`'s train (with `second`, the train with two pairs) touch on the
/// line of centres without slip, for both senses, both sun frames and two γ0.
fn assert_meshes(name: &str, spec: &CurveSpec, second: Option<&CurveSpec>) {
    for rotation in [Rotation::Clockwise, Rotation::Counterclockwise] {
        for sun_frame in [SunFrame::Installed, SunFrame::Ground] {
            for gamma0_deg in [-53.0, 70.0] {
                let train = TrainSpec {
                    rotation,
                    sun_frame,
                    gamma0_deg,
                    ..TrainSpec::default()
                };
                let (radius, tang, vel) = mesh_errors(spec, second, &train, 720);
                let label = format!("{name} {rotation:?} {sun_frame:?} γ0={gamma0_deg}");
                assert!(radius < 1e-4, "{label}: radii miss by {radius:e} mm");
                assert!(tang < 1e-4, "{label}: tangents differ by {tang:e} rad");
                assert!(vel < 1e-3, "{label}: slip velocity {vel:e} mm/rad");
            }
        }
    }
}

#[test]
fn both_meshes_touch_on_the_line_of_centres_without_slip() {
    for (name, spec) in designs() {
        assert_meshes(name, &spec, None);
    }
}

/// Second pairs unlike the first: an ellipse about its focus, and a Fourier curve.
fn second_curves() -> Vec<(&'static str, CurveSpec)> {
    vec![
        (
            "ellipse",
            CurveSpec::Ellipse {
                semi_major_mm: 30.0,
                eccentricity: 0.25,
            },
        ),
        (
            "fourier",
            CurveSpec::Fourier {
                c0_mm: 35.0,
                cos_mm: vec![-3.0, 2.0],
                sin_mm: vec![5.0, 0.0, 0.7],
            },
        ),
    ]
}

#[test]
fn both_meshes_of_the_two_pair_train_touch_on_the_line_of_centres_without_slip() {
    let designs = designs();
    for (name, spec) in [&designs[0], &designs[2]] {
        for (second_name, second) in second_curves() {
            assert_meshes(&format!("{name} + {second_name}"), spec, Some(&second));
        }
    }
}

/// The paper's train written as two pairs (layer B the intermediate's own curve, so the
/// planet is the sun's copy) moves its planets as the paper's train does, up to the
/// constant turn by which the two conventions place the planet's own frame: with β0 less
/// that turn, the tips coincide.
#[test]
fn the_paper_train_written_as_two_pairs_moves_as_the_paper_train() {
    let sun = CurveSpec::paper().build().unwrap();
    let res = Resolution::DEFAULT.with_samples(720);
    for rotation in [Rotation::Clockwise, Rotation::Counterclockwise] {
        let train = TrainSpec {
            rotation,
            ..TrainSpec::default()
        };
        let one = Kinematics::solve(&sun, None, &train, &res).unwrap();
        let inter = intermediate_curve(&sun, one.centre_distance(), train.psi_start());
        let two = Kinematics::solve(&sun, Some(&inter), &train, &res).unwrap();
        let [a1, a2] = two.centre_distances();
        assert!((a1 - a2).abs() < 1e-6 * a1, "{rotation:?}: {a1} vs {a2}");
        let shift = one.planet_angles()[0] - two.planet_angles()[0];
        let worst = (one.planet_angles().iter().zip(two.planet_angles()))
            .map(|(p, q)| wrap(p - q - shift).abs())
            .fold(0.0, f64::max);
        // Layer B is a table through 2880 samples of the intermediate: its interpolation
        // error near the paper curve's sharp lobe (about 6e-7 rad) is the whole gap.
        assert!(
            worst < 2e-6,
            "{rotation:?}: planet turns differ by {worst:e} rad"
        );
        let shifted = TrainSpec {
            beta0_deg: train.beta0_deg + shift.to_degrees(),
            ..train
        };
        let two = Kinematics::solve(&sun, Some(&inter), &shifted, &res).unwrap();
        let gap = (one.tips().iter().zip(two.tips()))
            .map(|(p, q)| (*p - *q).hypot())
            .fold(0.0, f64::max);
        assert!(gap < 3e-4, "{rotation:?}: tips {gap:e} mm apart");
    }
}

/// Two circular pairs: the planet keeps its orientation (θ3' = σ(1 − g_A g_B) = 0), so the
/// tip runs round a circle of the planet radius |a_A + a_B e^{iγ0}| about S·e(θ3 + β0).
#[test]
fn two_circular_pairs_translate_the_planet_round_a_circle() {
    let circle = |r: f64| CurveSpec::Fourier {
        c0_mm: r,
        cos_mm: vec![0.0],
        sin_mm: vec![0.0],
    };
    let (sun, layer_b) = (circle(30.0).build().unwrap(), circle(22.0).build().unwrap());
    let train = TrainSpec::default();
    let kin = Kinematics::solve(&sun, Some(&layer_b), &train, &Resolution::DEFAULT).unwrap();
    let [a1, a2] = kin.centre_distances();
    assert!(
        (a1 - 60.0).abs() < 1e-9 && (a2 - 44.0).abs() < 1e-9,
        "{a1} {a2}"
    );
    let g = train.gamma0_deg.to_radians();
    let radius = (a1 * a1 + a2 * a2 + 2.0 * a1 * a2 * g.cos()).sqrt();
    assert!((kin.planet_radius() - radius).abs() < 1e-9);
    let theta3 = kin.planet_angles()[0];
    let centre = unit(theta3 + train.beta0_deg.to_radians()) * train.arm_length_mm;
    for j in 0..kin.len() {
        assert!(wrap(kin.planet_angles()[j] - theta3).abs() < 1e-12);
        let off = ((kin.tips()[j] - centre).hypot() - radius).abs();
        assert!(off < 1e-9, "node {j}: {off:e} mm off the circle");
        let s = kin.state_at(kin.theta(j) + 0.3 * TAU / kin.len() as f64);
        assert!(((s.tip - centre).hypot() - radius).abs() < 1e-9);
    }
}

/// The two-pair train's state between nodes agrees with its nodes, and its tip derivatives
/// with the tip's differences.
#[test]
fn the_two_pair_train_state_agrees_with_its_nodes_and_differences() {
    let sun = CurveSpec::paper().build().unwrap();
    for (name, second) in second_curves() {
        let layer_b = second.build().unwrap();
        for rotation in [Rotation::Clockwise, Rotation::Counterclockwise] {
            let train = TrainSpec {
                rotation,
                ..TrainSpec::default()
            };
            let res = Resolution::DEFAULT.with_samples(720);
            let kin = Kinematics::solve(&sun, Some(&layer_b), &train, &res).unwrap();
            for j in (0..kin.len()).step_by(7) {
                let theta = kin.theta(j);
                let s = kin.state_at(theta);
                let gap = (s.tip - kin.tips()[j]).hypot();
                assert!(gap < 1e-7, "{name} {rotation:?} node {j}: {gap:e} mm");
                let h = 1e-4;
                let (p, m) = (kin.state_at(theta + h), kin.state_at(theta - h));
                let d1 = (p.tip - m.tip) * (0.5 / h);
                let d2 = (p.tip - s.tip * 2.0 + m.tip) * (1.0 / (h * h));
                let (e1, e2) = ((d1 - s.tip_d1).hypot(), (d2 - s.tip_d2).hypot());
                assert!(
                    e1 < 1e-4 * (1.0 + s.tip_d1.hypot()),
                    "{name} tip′ off by {e1:e}"
                );
                assert!(
                    e2 < 1e-2 * (1.0 + s.tip_d2.hypot()),
                    "{name} tip″ off by {e2:e}"
                );
            }
        }
    }
}

#[test]
fn mesh_error_shrinks_as_resolution_grows() {
    let (r, a) = noncirc::core::paper_control_points();
    let spec = CurveSpec::Spline {
        radii_mm: r,
        angles_deg: a,
    };
    let train = TrainSpec::default();
    let coarse = mesh_errors(&spec, None, &train, 120);
    let fine = mesh_errors(&spec, None, &train, 480);
    assert!(
        fine.0 < coarse.0 / 4.0,
        "radius error {coarse:?} -> {fine:?}"
    );
    assert!(fine.2 < coarse.2 / 4.0, "slip {coarse:?} -> {fine:?}");
}

/// The train solves its sun–intermediate pair once, on the carrier grid: for a clockwise
/// train with the sun installed, node j is the sun's parameter −θ_j, so the pair is the
/// standard-grid pair read backwards, and its driven outline is the same curve.
#[test]
fn the_train_pair_is_the_gear_pair_on_the_carrier_grid() {
    let sun = CurveSpec::paper().build().unwrap();
    let res = Resolution::DEFAULT.with_samples(720);
    let kin = Kinematics::solve(&sun, None, &TrainSpec::default(), &res).unwrap();
    let standard = GearPair::solve(sun, res).unwrap();
    let pair = kin.pair();
    let n = pair.samples().len();
    assert_eq!(pair.grid().sense, Rotation::Clockwise);
    let a = standard.centre_distance();
    assert!((pair.centre_distance() - a).abs() < 1e-9 * a);
    let (ours, theirs) = (pair.driven_points(), standard.driven_points());
    for (j, (p, q)) in pair.samples().iter().zip(&ours).enumerate() {
        let k = (n - j) % n;
        assert!((p.rho - standard.samples()[k].rho).abs() < 1e-12);
        let gap = (*q - theirs[k]).hypot();
        assert!(gap < 1e-8, "node {j}: driven points {gap:e} mm apart");
    }
    // The module read from the train is the gear command's module.
    let rule = noncirc::core::ModuleRule::default();
    let (m1, m2) = (pair.module(&rule), standard.module(&rule));
    assert!((m1.module_max_mm - m2.module_max_mm).abs() < 1e-9);
}

/// On any carrier grid (either sense, the sun installed or in the ground frame) the pair's
/// driven outline is the conjugate read from the standard-grid pair: the point meeting the
/// sun's parameter ψ sits at radius a − ρ(ψ) and own angle −(φ2(ψ) − φ2(ψ_start)).
#[test]
fn the_train_pair_has_the_conjugate_on_every_grid() {
    let sun = CurveSpec::paper().build().unwrap();
    let res = Resolution::DEFAULT.with_samples(720);
    let standard = GearPair::solve(sun.clone(), res).unwrap();
    for (rotation, sun_frame) in [
        (Rotation::Counterclockwise, SunFrame::Installed),
        (Rotation::Counterclockwise, SunFrame::Ground),
        (Rotation::Clockwise, SunFrame::Ground),
    ] {
        let train = TrainSpec {
            rotation,
            sun_frame,
            ..TrainSpec::default()
        };
        let kin = Kinematics::solve(&sun, None, &train, &res).unwrap();
        let pair = kin.pair();
        let (a, start) = (pair.centre_distance(), train.psi_start());
        assert_eq!(pair.psi(0), start);
        let points = pair.driven_points();
        for j in (0..pair.samples().len()).step_by(37) {
            let psi = pair.psi(j);
            let expected = -(standard.phi2(psi) - standard.phi2(start));
            let p = points[j];
            let angle_gap = (p.y.atan2(p.x) - expected + PI).rem_euclid(TAU) - PI;
            assert!(
                angle_gap.abs() < 1e-9,
                "{rotation:?} {sun_frame:?} node {j}: {angle_gap:e}"
            );
            assert!((p.hypot() - (a - sun.eval(psi).rho)).abs() < 1e-9);
        }
    }
}

/// The trains the node tests read: both trains (the paper's, and each second curve's),
/// both senses, each as solved and (where the sun does not turn the grid) reassembled with
/// another β0, Φ0 and a bore error; with a label for messages.
fn node_test_trains() -> Vec<(String, Kinematics)> {
    let sun = CurveSpec::paper().build().unwrap();
    let seconds: Vec<Option<PitchCurve>> = std::iter::once(None)
        .chain(
            second_curves()
                .into_iter()
                .map(|(_, s)| Some(s.build().unwrap())),
        )
        .collect();
    let mut trains = Vec::new();
    for second in &seconds {
        for rotation in [Rotation::Clockwise, Rotation::Counterclockwise] {
            let train = TrainSpec {
                rotation,
                ..TrainSpec::default()
            };
            let kin =
                Kinematics::solve(&sun, second.as_ref(), &train, &Resolution::DEFAULT).unwrap();
            let moved = TrainSpec {
                beta0_deg: train.beta0_deg + 7.0,
                phi0_deg: train.phi0_deg - 4.0,
                ..train
            };
            let label = format!("two pairs {} {rotation:?}", second.is_some());
            if train.sun_frame != SunFrame::Ground {
                let reassembled = kin.reassembled(&moved, 0.05).unwrap();
                trains.push((format!("{label} reassembled"), reassembled));
            }
            trains.push((label, kin));
        }
    }
    trains
}

/// The state and contacts read from the nodes (what the dynamics at the kinematics' nodes
/// uses) are those computed at the node's carrier angle, to rounding: every field, for
/// both trains, both senses, and a reassembled train.
#[test]
fn node_states_are_the_states_at_the_nodes() {
    for (train, kin) in node_test_trains() {
        for j in 0..kin.len() {
            let (node, [na, nb]) = kin.node_state_and_contacts(j);
            let (at, [a, b]) = kin.state_and_contacts(kin.theta(j));
            let label = format!("{train} node {j}");
            let close = |x: f64, y: f64, scale: f64, what: &str| {
                assert!((x - y).abs() <= 1e-11 * scale, "{label} {what}: {x} vs {y}");
            };
            let close2 = |x: Vec2, y: Vec2, scale: f64, what: &str| {
                close(x.x, y.x, scale, what);
                close(x.y, y.y, scale, what);
            };
            let mm = node.tip.hypot();
            close2(node.o2, at.o2, mm, "O2");
            close2(node.o3, at.o3, mm, "O3");
            close2(node.tip, at.tip, mm, "tip");
            close2(node.tip_d1, at.tip_d1, at.tip_d1.hypot(), "tip'");
            close2(node.tip_d2, at.tip_d2, at.tip_d2.hypot(), "tip''");
            close(node.theta2, at.theta2, 1.0, "θ2");
            close(node.theta3, at.theta3, 1.0, "θ3");
            for k in 0..2 {
                close(
                    node.theta2_d[k],
                    at.theta2_d[k],
                    at.theta2_d[k].abs().max(1.0),
                    "θ2 rates",
                );
                close(
                    node.theta3_d[k],
                    at.theta3_d[k],
                    at.theta3_d[k].abs().max(1.0),
                    "θ3 rates",
                );
            }
            for (x, y) in [(na, a), (nb, b)] {
                close2(x.centre, y.centre, mm, "contact centre");
                close2(x.towards, y.towards, 1.0, "contact direction");
                close(x.psi, y.psi, 1.0, "contact ψ");
                close(x.rho, y.rho, mm, "contact ρ");
                close(x.rho_d1, y.rho_d1, mm, "contact ρ'");
            }
        }
    }
}

/// The tip speeds at the nodes (what the trajectory's sections integrate) are the full
/// state's `|dD/dθ|` there, to rounding: for both trains, both senses, and a reassembled
/// train (another β0, Φ0 and a bore error).
#[test]
fn node_tip_speeds_are_the_states_tip_speeds_at_the_nodes() {
    for (train, kin) in node_test_trains() {
        let speeds = kin.node_tip_speeds();
        assert_eq!(speeds.len(), kin.len());
        for (j, &v) in speeds.iter().enumerate() {
            let state = kin.state_at(kin.theta(j)).tip_d1.hypot();
            assert!(
                (v - state).abs() <= 1e-12 * state,
                "{train} node {j}: {v} vs {state}"
            );
        }
    }
}
