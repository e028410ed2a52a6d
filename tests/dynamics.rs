//! Dynamics at working speed (`noncirc_core::dynamics`): the Newton–Euler torque equals
//! the energy balance's for every arm count and both trains; closed forms (a constant
//! ratio needs no torque, an eccentric mass shakes as the textbook says); the pitch points
//! the forces pass through are the pitch curves' contacts. Tooth strength: circular gears
//! carry ISO 6336-2's contact stress; the safety factors as objectives, measures and goals
//! are the dynamics report's; a design whose teeth cannot be cut says why.

use noncirc_core::{
    dynamics, events, CurveSpec, Dynamics, Evaluator, Goal, Measure, MeasureCost, Measured,
    ObjectiveKind, Scene,
};

use crate::common::{paper, two_pair_design as two_pairs};

fn run(scene: &Scene) -> Dynamics {
    let mut scene = scene.clone();
    if scene.train.arms == 1 {
        // One arm strikes nothing: the scene refuses the objective.
        scene
            .objectives
            .retain(|&o| o != ObjectiveKind::Interference);
    }
    scene.validate().unwrap();
    let kin = scene.kinematics(&scene.resolution).unwrap();
    let ev = events(&kin, &scene.agronomy);
    dynamics(
        &kin,
        &ev,
        &scene.dynamics,
        scene.gear.teeth.pressure_angle_deg,
    )
    .unwrap()
}

#[test]
fn newton_euler_and_energy_give_the_same_torque_for_every_arm_count_and_train() {
    for base in [paper(), two_pairs()] {
        for arms in 1..=4 {
            let mut scene = base.clone();
            scene.train.arms = arms;
            scene.resolution = scene
                .resolution
                .with_samples(if arms == 3 { 360 } else { 720 });
            scene.train.picks_per_minute = Some(300.0);
            scene.dynamics.planting_force_n = 8.0;
            let d = run(&scene);
            assert!(
                d.summary.formulations_rel_diff < 1e-6,
                "{arms} arms, two pairs {}: {:e}",
                scene.gear.second_curve.is_some(),
                d.summary.formulations_rel_diff
            );
            assert!(d.summary.torque_peak_nm > 0.01, "{arms}: {:?}", d.summary);
            // Loads take power: the mean torque is what they and nothing else take.
            assert!(d.summary.torque_mean_nm > 0.0);
        }
    }
}

#[test]
fn without_loads_the_torque_averages_to_zero_over_a_turn() {
    // Inertia and gravity are conservative: what the drive puts in, it takes back. (On
    // a smooth train: the paper's sharp lobe needs far more samples for its mean.)
    let mut scene = two_pairs();
    scene.dynamics.picking_force_n = 0.0;
    let d = run(&scene);
    assert!(
        d.summary.torque_mean_nm.abs() < 1e-9 * d.summary.torque_peak_nm,
        "{:?}",
        d.summary
    );
    assert_eq!(d.summary.torque_fluctuation, None);
}

#[test]
fn circular_gears_at_constant_speed_need_no_torque() {
    // Equal circles: the planet translates (θ3' = 0) and every centre of mass runs round
    // a circle at constant speed; without gravity and loads the kinetic energy is constant.
    let mut scene = paper();
    scene.gear.curve = CurveSpec::Ellipse {
        semi_major_mm: 30.0,
        eccentricity: 0.0,
    };
    scene.dynamics.gravity_m_s2 = 0.0;
    scene.dynamics.picking_force_n = 0.0;
    let d = run(&scene);
    let scale = d.summary.mesh_force_peak_n[1] * 0.1;
    assert!(d.summary.torque_peak_nm < 1e-9 * scale, "{:?}", d.summary);
    // The mesh forces are not zero: they carry the arm round.
    assert!(d.summary.mesh_force_peak_n[1] > 1.0);
}

#[test]
fn a_point_mass_at_the_planet_shakes_the_frame_with_m_r_omega_squared() {
    let mut scene = point_mass_at_the_planet(paper(), 1.5);
    scene.train.carrier_speed_rpm = 200.0;
    scene.dynamics.gravity_m_s2 = 0.0;
    let d = run(&scene);
    let kin = scene.kinematics(&scene.resolution).unwrap();
    let omega = 200.0 * std::f64::consts::TAU / 60.0;
    let expected = 1.5 * kin.planet_radius() * 1e-3 * omega * omega;
    for f in &d.shaking_force_n {
        let magnitude = (f[0] * f[0] + f[1] * f[1]).sqrt();
        assert!(
            (magnitude - expected).abs() < 1e-9 * expected,
            "{magnitude} vs {expected}"
        );
    }
    assert!(d.summary.torque_peak_nm < 1e-9 * expected);
    // The carrier bearing takes the whole of it (no gravity).
    assert!((d.summary.carrier_bearing_peak_n - expected).abs() < 1e-9 * expected);
}

#[test]
fn the_forces_pass_through_the_pitch_curves_contacts() {
    // The pitch point of each mesh, from the bodies' rates, lies at the driving curve's
    // radius from its centre: the kinematics and the curves agree.
    for scene in [paper(), two_pairs()] {
        let kin = scene.kinematics(&scene.resolution).unwrap();
        for j in (0..kin.len()).step_by(7) {
            let (st, contacts) = kin.state_and_contacts(kin.theta(j) + 0.013);
            assert_eq!(st, kin.state_at(kin.theta(j) + 0.013));
            let sigma = kin.spec().rotation.sign();
            let (w2, w3) = (st.theta2_d[0] - sigma, st.theta3_d[0] - sigma);
            let p1 = st.o2 * (w2 / (w2 + sigma));
            let p2 = st.o2 + (st.o3 - st.o2) * (w3 / (w3 - w2));
            for (p, c) in [(p1, contacts[0]), (p2, contacts[1])] {
                let r = (p - c.centre).hypot();
                assert!((r - c.rho).abs() < 1e-6 * c.rho, "{r} vs {}", c.rho);
                let along = (p - c.centre).dot(c.towards);
                assert!((along - r).abs() < 1e-9 * r);
            }
        }
    }
}

#[test]
fn each_contact_s_curve_parameter_turns_with_its_gear() {
    // The teeth in mesh are read off the contact's own-frame parameter ψ: in the ground
    // frame the contact lies at the gear's angle plus ψ, so `angle(towards) − gear angle
    // − ψ` stays put over the cycle (the sun does not turn; the paper's planet turns by θ3,
    // layer B with the intermediate by θ2).
    for scene in [paper(), two_pairs()] {
        let kin = scene.kinematics(&scene.resolution).unwrap();
        let offsets: Vec<[f64; 2]> = (0..kin.len())
            .step_by(5)
            .map(|j| {
                let (st, [a, b]) = kin.state_and_contacts(kin.theta(j) + 0.013);
                let turn = if kin.second_pair().is_some() {
                    st.theta2
                } else {
                    st.theta3
                };
                let angle = |c: &noncirc_core::PitchContact| c.towards.y.atan2(c.towards.x);
                [angle(&a) - a.psi, angle(&b) - turn - b.psi]
            })
            .collect();
        for m in 0..2 {
            for o in &offsets {
                let d = (o[m] - offsets[0][m] + std::f64::consts::PI)
                    .rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                assert!(d.abs() < 1e-9, "mesh {m}: {d:e}");
            }
        }
    }
}

#[test]
fn the_joint_rates_are_the_derivatives_of_the_joint_angles() {
    // θ2', θ2'', θ3', θ3'' (which the bodies' accelerations rest on) against central
    // differences of the angles themselves, on both trains. The angles interpolate the
    // inverse of the driven angle (quintic cells) while the rates read the curves, so they
    // agree to the interpolation's accuracy, which the samples refine.
    let worst = |scene: &Scene| {
        let kin = scene.kinematics(&scene.resolution).unwrap();
        let h = 1e-4;
        let mut worst = [0.0f64; 2];
        for j in (0..kin.len()).step_by(kin.len() / 40) {
            let theta = kin.theta(j) + 0.007;
            let [m, c, p] = [theta - h, theta, theta + h].map(|t| kin.state_at(t));
            let pairs = [
                ([m.theta2, c.theta2, p.theta2], c.theta2_d),
                ([m.theta3, c.theta3, p.theta3], c.theta3_d),
            ];
            for ([am, ac, ap], d) in pairs {
                let d1 = (ap - am) / (2.0 * h);
                let d2 = (ap - 2.0 * ac + am) / (h * h);
                worst[0] = worst[0].max((d1 - d[0]).abs() / (1.0 + d[0].abs()));
                worst[1] = worst[1].max((d2 - d[1]).abs() / (1.0 + d[1].abs()));
            }
        }
        worst
    };
    // The paper's sharp lobe at 120 and 480 samples: 3.7e-5 → 3.6e-7 in θ', 1.8e-3 →
    // 3.4e-5 in θ'' (third order or so).
    let mut fine = paper();
    fine.resolution = fine.resolution.with_samples(480);
    let ([c1, c2], [f1, f2]) = (worst(&paper()), worst(&fine));
    assert!(c1 < 1e-4 && c2 < 5e-3, "{c1} {c2}");
    assert!(f1 < c1 / 20.0 && f2 < c2 / 20.0, "{c1} {c2} → {f1} {f2}");
    // A smooth train: as close as the differences themselves can tell.
    let [s1, s2] = worst(&two_pairs());
    assert!(s1 < 1e-8 && s2 < 1e-5, "{s1} {s2}");
}

#[test]
fn circular_gears_carry_the_hertz_line_contact_stress_of_iso_6336_2() {
    // Equal circles cut with 30 teeth: at every carrier angle the flank's stress is
    // ISO 6336-2's nominal contact stress `ZH·ZE·√(KA·Ft/(b·d)·(u + 1)/u)`, u = 1, from
    // the mesh's normal force `Fn = Ft / cos α`; every tooth is alike, so the root stress
    // is the same multiple of the force throughout.
    let mut scene = paper();
    scene.gear.curve = CurveSpec::Ellipse {
        semi_major_mm: 30.0,
        eccentricity: 0.0,
    };
    scene.gear.module.teeth = Some(30);
    scene.train.picks_per_minute = Some(300.0);
    let r = noncirc::dynamics::report_of(&scene).unwrap();
    let s = r.strength.expect("circles cut");
    let spec = &scene.dynamics;
    let alpha = scene.gear.teeth.pressure_angle_deg.to_radians();
    let e = spec.youngs_modulus_gpa * 1e3;
    let z_e = (1.0 / (std::f64::consts::PI * 2.0 * (1.0 - spec.poisson_ratio.powi(2)) / e)).sqrt();
    let z_h = (2.0 / (alpha.cos().powi(2) * alpha.tan())).sqrt();
    let d = 60.0;
    assert_eq!(s.gears.len(), 3);
    for (g, meshes) in [(0, vec![0]), (1, vec![0, 1]), (2, vec![1])] {
        let gear = &s.gears[g];
        assert_eq!(gear.teeth, 30);
        let [least, most] = gear.form_factor_range;
        assert!(
            most - least < 1e-6 * most,
            "{}: {least} … {most}",
            gear.name
        );
        for j in 0..r.dynamics.carrier_deg.len() {
            let f = meshes
                .iter()
                .map(|&m| r.dynamics.mesh_force_n[m][j].abs())
                .fold(0.0, f64::max);
            let ft = spec.application_factor * f * alpha.cos();
            let iso = z_h * z_e * (ft / (spec.face_width_mm * d) * 2.0).sqrt();
            assert!(
                (gear.contact_mpa[j] - iso).abs() <= 1e-9 * iso,
                "{} at node {j}: {} against {iso}",
                gear.name,
                gear.contact_mpa[j]
            );
            let per_newton = gear.worst_form.stress_per_newton;
            let bending = spec.application_factor * f * per_newton / spec.face_width_mm;
            assert!((gear.bending_mpa[j] - bending).abs() <= 1e-6 * bending.max(1e-9));
        }
        assert!(gear.contact_peak_mpa > 0.0 && gear.bending_peak_mpa > 0.0);
        assert!(
            (gear.contact_safety - spec.contact_limit_mpa / gear.contact_peak_mpa).abs() < 1e-12
        );
    }
}

#[test]
fn a_design_whose_teeth_cannot_be_cut_reports_why_it_has_no_strength() {
    // The paper's sharp concave lobe (|R| = 1.9 mm) admits no rack.
    let r = noncirc::dynamics::report_of(&paper()).unwrap();
    assert!(r.strength.is_none());
    let why = r.strength_unavailable.unwrap();
    assert!(why.contains("concave") && why.contains("rack"), "{why}");
}

#[test]
fn the_strength_objectives_measures_and_goals_read_the_dynamics_report() {
    // The two-arm scene's design, cut by a shaper (a rack cannot cut its concave arcs).
    let mut scene = noncirc::scene_file::load_scene(Some("two-arm")).unwrap();
    scene.gear.teeth.cutter = noncirc_core::Cutter::Shaper { teeth: 100 };
    let report = noncirc::dynamics::report_of(&scene).unwrap();
    let strength = report.strength.as_ref().unwrap();
    // By default no objective asks for the strength, and none is computed.
    let mut ev = Evaluator::new();
    let plain = ev.evaluate(&scene).unwrap();
    assert!(plain.strength.is_none() && ev.counts().strength == 0);
    // Listed, the safety factors are objectives against their bounds.
    scene
        .objectives
        .extend([ObjectiveKind::BendingSafety, ObjectiveKind::ContactSafety]);
    scene.bounds.contact_safety_min = strength.contact_safety_min + 0.5;
    let mut ev = Evaluator::new();
    let eval = ev.evaluate(&scene).unwrap();
    assert_eq!(ev.counts().strength, 1);
    let bending = eval.objective(ObjectiveKind::BendingSafety).unwrap();
    let contact = eval.objective(ObjectiveKind::ContactSafety).unwrap();
    assert_eq!(bending.value, strength.bending_safety_min);
    assert_eq!(contact.value, strength.contact_safety_min);
    assert_eq!(bending.violation, 0.0);
    assert!((contact.violation - 0.5).abs() < 1e-12, "{contact:?}");
    // As measures and goals, the same numbers; the dynamics' measures are its summary's.
    let on = Measured::new(&eval, &scene);
    let value = |name: &str| Measure::parse(name).unwrap().value(&on).unwrap();
    assert_eq!(value("bending_safety"), strength.bending_safety_min);
    let s = &report.dynamics.summary;
    assert_eq!(value("input_torque_peak_nm"), s.torque_peak_nm);
    assert_eq!(value("input_torque_rms_nm"), s.torque_rms_nm);
    assert_eq!(value("sun_shaft_peak_n"), s.sun_shaft_peak_n);
    assert_eq!(value("carrier_speed_fluctuation"), report.speed.coefficient);
    assert_eq!(value("flywheel_needed_kg_m2"), report.flywheel_needed_kg_m2);
    let goal = Goal::parse("min:flywheel_needed_kg_m2").unwrap();
    assert_eq!(goal.quantity(&scene.bounds).unit, "kg·m²");
    assert_eq!(
        value("mesh_force_peak_n"),
        s.mesh_force_peak_n[0].max(s.mesh_force_peak_n[1])
    );
    let goal = Goal::parse("min:input_torque_peak_nm").unwrap();
    let q = goal.quantity(&scene.bounds);
    assert_eq!((q.name.as_str(), q.unit), ("input_torque_peak_nm", "N·m"));
    assert_eq!(q.label(), "input torque peak (N·m), minimised");
    // Without the objective, the measure cuts the teeth itself.
    let on = Measured::new(&plain, &scene);
    let measure = Measure::parse("contact_safety").unwrap();
    assert_eq!(measure.cost(), MeasureCost::Strength);
    assert_eq!(measure.value(&on), Some(strength.contact_safety_min));
}

#[test]
fn a_design_whose_teeth_cannot_be_cut_fails_the_strength_objective_and_says_why() {
    let mut scene = paper();
    scene.objectives = vec![ObjectiveKind::PickingAngle, ObjectiveKind::BendingSafety];
    let eval = Evaluator::new().evaluate(&scene).unwrap();
    let o = eval.objective(ObjectiveKind::BendingSafety).unwrap();
    assert_eq!(
        (o.value, o.violation),
        (0.0, scene.bounds.bending_safety_min)
    );
    assert!(eval.strength.is_none());
    assert!(eval.strength_unavailable.unwrap().contains("rack"));
}

/// `scene`'s train with one arm set whose only moving mass is `mass` (kg), a point at the
/// planet's centre, and no tip load.
fn point_mass_at_the_planet(mut scene: Scene, mass: f64) -> Scene {
    scene.train.arms = 1;
    let dy = &mut scene.dynamics;
    (
        dy.gear_density_kg_m3,
        dy.arm_mass_kg,
        dy.arm_com_mm,
        dy.arm_inertia_kg_m2,
    ) = (0.0, mass, 0.0, 0.0);
    dy.picking_force_n = 0.0;
    scene
}

/// `∫₀^φj f dφ` at each node of a periodic grid, by the trapezoid rule.
fn running_integral(f: &[f64]) -> Vec<f64> {
    let step = std::f64::consts::TAU / f.len() as f64;
    let mut sum = 0.0;
    (0..f.len())
        .map(|j| {
            let here = sum;
            sum += step * 0.5 * (f[j] + f[(j + 1) % f.len()]);
            here
        })
        .collect()
}

#[test]
fn with_a_constant_drive_torque_a_mass_under_gravity_swaps_height_for_speed_as_the_closed_form_says(
) {
    // One point mass m on a circle of radius R at 60 r/min with a flywheel: the drive's
    // torque is gravity's mean, zero, so ½·I·ω² + m·g·y is constant (I = m·R² + Jc + Jf),
    // and the turn's mean speed is the working speed. The closed form: ω(ψ) =
    // √(2(E0 − m·g·R·sin ψ)/I), E0 set by the mean speed (found here by bisection on a fine
    // quadrature of the turn's duration, independently of noncirc's Newton).
    let (mass, flywheel) = (1.5, 0.2);
    // Equal circles: the planet's centre runs round a circle at the carrier's speed.
    let mut scene = point_mass_at_the_planet(paper(), mass);
    scene.gear.curve = CurveSpec::Ellipse {
        semi_major_mm: 30.0,
        eccentricity: 0.0,
    };
    scene.train.carrier_speed_rpm = 60.0;
    let kin = scene.kinematics(&scene.resolution).unwrap();
    let radius = kin.planet_radius() * 1e-3;
    let inertia = mass * radius * radius + scene.dynamics.carrier_inertia_kg_m2 + flywheel;
    let omega0 = std::f64::consts::TAU;
    let g = scene.dynamics.gravity_m_s2;
    let energy_error = |samples: usize| {
        let mut scene = scene.clone();
        scene.dynamics.samples_per_turn = samples;
        let d = run(&scene);
        let speed = d.speed_with(flywheel);
        assert!(speed.drive_torque_nm.abs() < 1e-12);
        let w = &speed.carrier_speed_rad_s;
        // The mean over time is the working speed.
        let mean = w.len() as f64 / w.iter().map(|x| 1.0 / x).sum::<f64>();
        assert!((mean - omega0).abs() < 1e-12 * omega0, "{mean}");
        for (j, i) in d.reduced_inertia_kg_m2.iter().enumerate() {
            let expected = mass * radius * radius;
            assert!((i - expected).abs() < 1e-12 * expected, "node {j}: {i}");
        }
        let energy: Vec<f64> = (0..w.len())
            .map(|j| {
                let y = kin.state_at(d.carrier_deg[j].to_radians()).o3.y * 1e-3;
                0.5 * inertia * w[j] * w[j] + mass * g * y
            })
            .collect();
        let spread = energy
            .iter()
            .fold(0.0f64, |m, e| m.max((e - energy[0]).abs()));
        (spread / energy[0].abs(), speed.coefficient)
    };
    let (e720, delta) = energy_error(720);
    let (e1440, _) = energy_error(1440);
    assert!(e720 < 1e-5, "{e720}");
    // The trapezoid rule's running integral: second order.
    let order = (e720 / e1440).log2();
    assert!((order - 2.0).abs() < 0.1, "order {order}");
    // The closed form's coefficient.
    let a = mass * g * radius;
    let duration = |e0: f64| {
        let m = 200_000;
        (0..m)
            .map(|k| {
                let psi = std::f64::consts::TAU * (k as f64 + 0.5) / m as f64;
                1.0 / (2.0 * (e0 - a * psi.sin()) / inertia).sqrt()
            })
            .sum::<f64>()
            * std::f64::consts::TAU
            / m as f64
    };
    let (mut lo, mut hi) = (a * (1.0 + 1e-9), a + inertia * omega0 * omega0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if duration(mid) > std::f64::consts::TAU / omega0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let e0 = 0.5 * (lo + hi);
    let w = |e: f64| (2.0 * e / inertia).sqrt();
    let expected = (w(e0 + a) - w(e0 - a)) / omega0;
    assert!(expected > 0.1, "{expected}");
    // The nodes straddle the extremes: a relative error of the order of (π/720)².
    assert!(
        (delta - expected).abs() < 1e-4 * expected,
        "{delta} vs {expected}"
    );
}

#[test]
fn a_large_flywheel_gives_the_textbook_fluctuation_and_the_one_needed_holds_the_allowed() {
    // δ·I·ω² → ΔE (the largest swing of the energy the constant-speed torque puts in) as
    // the flywheel grows; δ falls as it grows; the flywheel reported as needed gives the
    // allowed coefficient.
    let base = run(&two_pairs());
    let n = base.input_torque_nm.len() as f64;
    let mean = base.input_torque_nm.iter().sum::<f64>() / n;
    let swing: Vec<f64> = base.input_torque_nm.iter().map(|t| t - mean).collect();
    let energy = running_integral(&swing);
    let (lo, hi) = energy
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &e| {
            (l.min(e), h.max(e))
        });
    let omega = base.carrier_speed_rad_s;
    let mean_inertia = base.reduced_inertia_kg_m2.iter().sum::<f64>() / n;
    let mut previous = f64::INFINITY;
    for flywheel in [0.0, 0.01, 0.1, 1.0, 10.0, 100.0] {
        let delta = base.speed_with(flywheel).coefficient;
        assert!(delta < previous, "{flywheel}: {delta} after {previous}");
        previous = delta;
        let inertia = flywheel + base.carrier_inertia_kg_m2 + mean_inertia;
        let textbook = (hi - lo) / (inertia * omega * omega);
        if flywheel >= 10.0 {
            assert!(
                (delta - textbook).abs() < 3.0 * textbook * textbook + 1e-3 * textbook,
                "{flywheel}: {delta} vs {textbook}"
            );
        }
    }
    let needed = base.flywheel_needed_kg_m2(0.02);
    assert!(needed > 0.0 && base.speed_with(0.0).coefficient > 0.02);
    let delta = base.speed_with(needed).coefficient;
    assert!((delta - 0.02).abs() < 1e-9, "{delta}");
    // One that meets it already needs none.
    assert_eq!(base.flywheel_needed_kg_m2(0.9), 0.0);
}

#[test]
fn the_input_torque_is_the_reduced_inertia_s_rate_and_the_loads_torque() {
    // T = ½·dIm/dφ·ω² + Q at constant speed (the Eksergian form the flywheel integrates),
    // dIm/dφ by central differences on the periodic grid: second order.
    let error = |samples: usize| {
        let mut scene = two_pairs();
        scene.dynamics.samples_per_turn = samples;
        let d = run(&scene);
        let (i, n) = (&d.reduced_inertia_kg_m2, d.reduced_inertia_kg_m2.len());
        let step = std::f64::consts::TAU / n as f64;
        let w2 = d.carrier_speed_rad_s * d.carrier_speed_rad_s;
        (0..n)
            .map(|j| {
                let rate = (i[(j + 1) % n] - i[(j + n - 1) % n]) / (2.0 * step);
                (0.5 * rate * w2 + d.load_torque_nm[j] - d.input_torque_nm[j]).abs()
            })
            .fold(0.0f64, f64::max)
            / d.summary.torque_peak_nm
    };
    let (coarse, fine) = (error(720), error(1440));
    assert!(coarse < 1e-3, "{coarse}");
    let order = (coarse / fine).log2();
    assert!((order - 2.0).abs() < 0.2, "order {order}");
}
