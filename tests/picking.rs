//! Picking as a physical event (spec §3), the branch check, the trajectory's sections and
//! the measures: the default design picks where a machine can, a tray behind the mechanism
//! is refused with its reason, a branch switch is flagged, and the sections tile the turn.

use noncirc::core::Evaluation;
use noncirc::core::ModuleReading;
use noncirc::core::Section;
use noncirc::core::Vec2;
use noncirc::core::{Evaluator, ObjectiveKind, Scene};
use noncirc::core::{Measure, MeasureCost, Measured};
use noncirc::scene_file::{apply_overrides, load_scene};
use proptest::prelude::*;

fn scene(sets: &[&str]) -> Scene {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    apply_overrides(load_scene(Some("paper")).unwrap(), &sets).unwrap()
}

fn evaluate(scene: &Scene) -> Evaluation {
    Evaluator::new().evaluate(scene).unwrap()
}

fn value(eval: &Evaluation, kind: ObjectiveKind) -> f64 {
    eval.objective(kind).unwrap().value
}

/// The built-in paper scene picks where a machine can, and its values are pinned.
#[test]
fn the_default_design_picks_where_a_machine_can() {
    let s = scene(&["resolution.samples_per_turn=360"]);
    let eval = evaluate(&s);
    let ev = eval.events.unwrap();
    let c = ev.check;
    assert!(
        c.arm_into_tray_mm > 100.0 && c.pusher_into_tray_mm > 100.0,
        "{c:?}"
    );
    assert!(
        c.planet_behind_mm > 100.0 && c.housing_behind_mm > 40.0,
        "{c:?}"
    );
    assert!(c.other_arms_behind_mm.unwrap() > 0.0 && c.second_entry_behind_mm.unwrap() > 0.0);
    assert!(ev.check.failures().is_none());
    // (That the tip picks outside the housing is the core's unit test
    // `evaluation::tests::the_paper_design_picks_outside_the_housing`.)
    let pins = [
        (ObjectiveKind::PickingAdmissible, 51.9908, 0.01),
        (ObjectiveKind::PickingAngle, 0.2970, 1e-3),
        (ObjectiveKind::PushingAngle, 53.9909, 1e-3),
        (ObjectiveKind::AngleDifference, 53.6939, 1e-3),
    ];
    for (kind, pinned, tol) in pins {
        let v = value(&eval, kind);
        assert!((v - pinned).abs() < tol, "{}: {v} vs {pinned}", kind.name());
    }
    assert!((ev.picking.carrier_rad.to_degrees() - 71.879).abs() < 0.01);
    assert!((ev.planting.carrier_rad.to_degrees() - 157.179).abs() < 0.01);
    // Every objective but the module is met.
    for o in &eval.objectives {
        assert_eq!(o.violation == 0.0, o.kind != ObjectiveKind::Module, "{o:?}");
    }
}

/// A tray behind the mechanism (the old default normal of 135°) cannot be picked from:
/// the objective is violated and the reason names the conditions.
#[test]
fn a_tray_behind_the_mechanism_is_refused_with_its_reason() {
    let eval = evaluate(&scene(&["agronomy.tray_normal_deg=135"]));
    let o = eval.objective(ObjectiveKind::PickingAdmissible).unwrap();
    assert!(o.violation > 100.0, "{o:?}");
    let why = eval.events.unwrap().check.failures().unwrap();
    assert!(
        why.contains("planet centre behind the tray surface fails"),
        "{why}"
    );
    assert!(why.contains("gearbox housing"), "{why}");
}

/// A tray at a given distance: too close, and the tip strikes its floor; too far, and the
/// tip never reaches it (an empty window).
#[test]
fn a_tray_at_a_given_distance_must_be_reached_but_not_struck() {
    let surface = evaluate(&scene(&[])).events.unwrap().check.tray_surface_mm;
    let at = |d: f64| evaluate(&scene(&[&format!("agronomy.tray_distance_mm={d}")]));
    let same = at(surface);
    let c = same.events.unwrap().check;
    assert!((c.tip_depth_mm - 15.0).abs() < 1e-9 && c.reach_mm.unwrap().abs() < 1e-9);
    let close = at(surface - 10.0);
    let why = close.events.unwrap().check.failures().unwrap();
    assert!(
        why.contains("tip within the tray depth fails by 10.00 mm"),
        "{why}"
    );
    let far = at(surface + 20.0).events.unwrap();
    assert!(far.check.reach_mm.unwrap() < -4.99);
    assert_eq!(far.picking_window_rad[0], far.picking_window_rad[1]);
}

/// Under the old tray the picking event jumps between branches for a 0.75° change of β0
/// (216° → 285° of carrier). On both sides the runner-up branch is within the tray depth
/// of the extreme, so the check flags it instead of trusting either side.
#[test]
fn a_branch_switch_is_flagged_on_both_sides() {
    let at = |beta0: f64| {
        let s = scene(&[
            "agronomy.tray_normal_deg=135",
            &format!("train.beta0_deg={beta0}"),
        ]);
        evaluate(&s).events.unwrap()
    };
    let (before, after) = (at(-47.0), at(-46.25));
    let jump = (after.picking.carrier_rad - before.picking.carrier_rad).to_degrees();
    assert!(jump.abs() > 30.0, "the event jumps: {jump}°");
    for ev in [before, after] {
        let gap = ev.picking_branch_gap_mm.unwrap();
        assert!(gap < 15.0, "gap {gap}");
        assert!(ev.check.second_entry_behind_mm.unwrap() < 0.0);
        let why = ev.check.failures().unwrap();
        assert!(why.contains("no other branch enters the tray"), "{why}");
    }
    // The default tray's picking is far from any other branch.
    let gap = evaluate(&scene(&[]))
        .events
        .unwrap()
        .picking_branch_gap_mm
        .unwrap();
    assert!(gap > 250.0, "{gap}");
}

/// Paper §4.1: "in the initial position, arms I and II are in the return stage and arm III
/// in the conveying stage". Arm k at carrier θ is where arm I was at θ − k·120°.
#[test]
fn the_sections_reproduce_the_papers_initial_position() {
    let s = scene(&[]);
    let eval = evaluate(&s);
    let a = eval.anatomy(&s.agronomy).unwrap();
    assert_eq!(a.section_at(0.0), Section::Return);
    assert_eq!(a.section_at(-120.0), Section::Return);
    assert_eq!(a.section_at(-240.0), Section::Conveying);
    // The old tray's picking instant contradicts it: arm I would be conveying.
    let old = scene(&["agronomy.tray_normal_deg=135"]);
    let eval = evaluate(&old);
    assert_eq!(
        eval.anatomy(&old.agronomy).unwrap().section_at(0.0),
        Section::Conveying
    );
}

/// Total tip path length over one turn, from a dense polyline (mm).
fn path_length(eval: &Evaluation) -> f64 {
    let tips = eval.kinematics.as_ref().unwrap().tips();
    let n = tips.len();
    (0..n)
        .map(|j| {
            let (p, q) = (tips[j], tips[(j + 1) % n]);
            (q - p).hypot()
        })
        .sum()
}

/// The sections tile the turn in the order of motion, contain their events, and their
/// path lengths add up to the whole path (checked against a dense polyline).
#[test]
fn sections_tile_the_turn_and_their_lengths_converge() {
    let s = scene(&[]);
    let eval = evaluate(&s);
    let a = eval.anatomy(&s.agronomy).unwrap();
    let ev = eval.events.unwrap();
    let total_span: f64 = a.sections.iter().map(|m| m.span_deg).sum();
    assert!((total_span - 360.0).abs() < 1e-9);
    for w in a.sections.windows(2) {
        let gap = (w[1].carrier_deg[0] - w[0].carrier_deg[1]).rem_euclid(360.0);
        assert!(gap < 1e-9 || (360.0 - gap) < 1e-9, "{w:?}");
    }
    let inside = |m: &noncirc::core::SectionMeasures, t: f64| {
        (t - m.carrier_deg[0]).rem_euclid(360.0) <= m.span_deg
    };
    assert!(inside(
        a.section(Section::Removal),
        ev.picking.carrier_rad.to_degrees()
    ));
    assert!(inside(
        a.section(Section::Planting),
        ev.planting.carrier_rad.to_degrees()
    ));
    let fine = evaluate(&scene(&["resolution.samples_per_turn=5760"]));
    let dense = path_length(&fine);
    let lengths: f64 = a.sections.iter().map(|m| m.length_mm).sum();
    assert!(
        (lengths - dense).abs() < 2e-3 * dense,
        "{lengths} vs {dense}"
    );
    // Each section's length converges with resolution (trapezoid: second order).
    let fa = fine.anatomy(&s.agronomy).unwrap();
    for (c, f) in a.sections.iter().zip(&fa.sections) {
        assert!(
            (c.length_mm - f.length_mm).abs() < 3e-3 * f.length_mm,
            "{c:?} {f:?}"
        );
        assert!((c.span_deg - f.span_deg).abs() < 0.2, "{c:?} {f:?}");
    }
}

/// Arm k repeats arm I's trajectory k·120° of carrier later (paper Table 1's spacing).
#[test]
fn arms_pick_and_plant_120_degrees_apart() {
    let eval = evaluate(&scene(&[]));
    let kin = eval.kinematics.as_ref().unwrap();
    let n = kin.len();
    for j in 0..n {
        let arm_two = kin.tips()[kin.arm_node(1, (j + n / 3) % n)];
        assert_eq!(arm_two, kin.tips()[j]);
    }
}

/// The perimeter reading of the module objective: `m = L/(πz)` for a given z.
#[test]
fn the_perimeter_reading_gives_the_papers_module() {
    let s = scene(&["gear.module.rule=\"perimeter\"", "gear.module.teeth=40"]);
    assert_eq!(s.gear.module.rule, ModuleReading::Perimeter);
    let eval = evaluate(&s);
    let g = eval.gear.unwrap();
    assert!(
        (g.module.module_max_mm - g.perimeter_mm / (40.0 * std::f64::consts::PI)).abs() < 1e-12
    );
    assert!(eval.objective(ObjectiveKind::Module).unwrap().violation == 0.0);
    let err = apply_overrides(
        load_scene(Some("paper")).unwrap(),
        &["gear.module.rule=\"perimeter\"".into()],
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("gear.module.teeth is not set"), "{err}");
}

/// The tip's ground-frame speed at planting, against finite differences of its
/// ground-frame position (machine advance: three spacings per turn, against the travel).
#[test]
fn planting_ground_speed_matches_finite_differences() {
    // At 720 samples the interpolated Φ⁻¹ is consistent with the analytic derivative to
    // well below 1e-6 (at 120 samples they differ by 5e-6 relative).
    let s = scene(&["resolution.samples_per_turn=720"]);
    let eval = evaluate(&s);
    let a = eval.anatomy(&s.agronomy).unwrap();
    let kin = eval.kinematics.as_ref().unwrap();
    let t = eval.events.unwrap().planting.carrier_rad;
    let h = 1e-5;
    let advance = 3.0 * s.agronomy.plant_spacing_mm / std::f64::consts::TAU;
    let forward = -kin.state_at(t).tip_d1.x.signum();
    let ground = |u: f64| {
        let p = kin.state_at(u).tip;
        noncirc::core::Vec2::new(forward * p.x + advance * u, p.y)
    };
    let (p, q) = (ground(t + h), ground(t - h));
    let speed = ((p - q).hypot() / (2.0 * h)) * kin.carrier_speed() / 1000.0;
    assert!(
        (speed - a.planting_ground_speed_m_s).abs() < 1e-6,
        "{speed} vs {}",
        a.planting_ground_speed_m_s
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random designs around the paper: the sections tile the turn, every measure is finite,
    /// and the picking objective is met exactly when every picking condition holds.
    #[test]
    fn sections_and_measures_hold_for_random_designs(
        radii in prop::collection::vec(12.0f64..65.0, 12),
        beta0 in -60.0f64..10.0, gamma0 in -90.0f64..-20.0, tray in -60.0f64..60.0,
    ) {
        let mut s = scene(&[]);
        if let noncirc::core::CurveSpec::Spline { radii_mm, .. } = &mut s.gear.curve {
            *radii_mm = radii;
        }
        s.train.beta0_deg = beta0;
        s.train.gamma0_deg = gamma0;
        s.agronomy.tray_normal_deg = tray;
        let Ok(eval) = Evaluator::new().evaluate(&s) else { return Ok(()); };
        let a = eval.anatomy(&s.agronomy).unwrap();
        let total: f64 = a.sections.iter().map(|m| m.span_deg).sum();
        prop_assert!((total - 360.0).abs() < 1e-9);
        for m in &a.sections {
            prop_assert!(m.span_deg >= 0.0 && m.length_mm >= 0.0 && m.y_min_mm <= m.y_max_mm);
        }
        // Every measure but the teeth's strength (tenths of a second a design to cut).
        let on = Measured::new(&eval, &s);
        for m in Measure::all().into_iter().filter(|m| m.cost() != MeasureCost::Strength) {
            if let Some(v) = m.value(&on) {
                prop_assert!(v.is_finite(), "{} = {}", m.name(), v);
            }
        }
        // The report the CLI prints holds no NaN or infinity either.
        let (report, _) = noncirc::report::EvaluationReport::from_scene(&s).unwrap();
        if let Err(e) = noncirc::report::check_finite(&report) {
            prop_assert!(false, "{e}");
        }
        let check = eval.events.unwrap().check;
        let met = eval.objective(ObjectiveKind::PickingAdmissible).unwrap().violation == 0.0;
        prop_assert_eq!(met, check.failures().is_none());
    }
}

/// The transplanter couples the corrected picking window to the box: the box's window is
/// three times the carrier window about its centre, and the travel over it is the
/// elliptical law's. Pinned: 43.8° of carrier, 131.3° of box input, 4.54 mm of travel.
#[test]
fn the_transplanter_box_window_is_the_picking_window() {
    let set = ["resolution.samples_per_turn=360"].map(String::from);
    let three_arm = evaluate(&scene(&set.each_ref().map(|s| s.as_str())));
    let transplanter = apply_overrides(load_scene(Some("transplanter")).unwrap(), &set).unwrap();
    let eval = evaluate(&transplanter);
    let [w0, w1] = three_arm
        .events
        .unwrap()
        .picking_window_rad
        .map(f64::to_degrees);
    let report = eval.moving_box.unwrap();
    let [b0, b1] = report.window_deg;
    assert!(
        ((b1 - b0) - 3.0 * (w1 - w0)).abs() < 1e-9,
        "{b0}..{b1} vs {w0}..{w1}"
    );
    assert!((0.5 * (b0 + b1) - 180.0).abs() < 1e-9);
    assert!((w1 - w0 - 43.77).abs() < 0.01, "{}", w1 - w0);
    assert!((report.elliptic_delta_h_mm - 4.540).abs() < 0.001);
    assert!((report.elliptic_delta_h_mm - report.elliptic_delta_h_numeric_mm).abs() < 1e-6);
    assert!(!report.within_limit);
}

/// `paper-search` with the design `radii` (mm) and `train` (Φ0, β0, S, H1, γ0), evaluated.
fn search_design(radii: [f64; 12], train: [f64; 5]) -> (Scene, Evaluation) {
    let names = [
        "phi0_deg",
        "beta0_deg",
        "arm_length_mm",
        "pusher_offset_mm",
        "gamma0_deg",
    ];
    let mut sets = vec![format!("gear.curve.radii_mm={radii:?}")];
    sets.extend((names.iter().zip(train)).map(|(name, v)| format!("train.{name}={v}")));
    let s = apply_overrides(load_scene(Some("paper-search")).unwrap(), &sets).unwrap();
    let eval = evaluate(&s);
    (s, eval)
}

/// Checks that `event` lies between the nodes, at the farthest point along `dir` of a scan
/// of 60 001 arm states over the 1.5 nodes either side of it.
fn assert_at_the_scans_extreme(eval: &Evaluation, event: noncirc::core::Event, dir: Vec2) {
    let kin = eval.kinematics.as_ref().unwrap();
    let h = std::f64::consts::TAU / kin.len() as f64;
    let node = (event.carrier_rad / h).round();
    assert!((event.carrier_rad / h - node).abs() > 0.1, "{event:?}");
    let (mut farthest, mut at) = (f64::NEG_INFINITY, 0.0);
    for k in -30_000..=30_000 {
        let theta = (node + 1.5 * k as f64 / 30_000.0) * h;
        let reach = kin.state_at(theta).tip.dot(dir);
        if reach > farthest {
            (farthest, at) = (reach, theta);
        }
    }
    // The scan's step is 2.6e-6 rad: its farthest point lies within it of the extreme.
    assert!(
        (event.carrier_rad - at).abs() < 3e-6,
        "{} vs {at}",
        event.carrier_rad
    );
    // The event's point follows the last arm state's Taylor series, within about 1e-8 mm
    // of `state_at` (docs/accuracy.md).
    let reach = event.tip_mm.dot(dir);
    assert!((reach - farthest).abs() < 1e-6, "{reach} vs {farthest}");
}

/// Sharp extremes of two random `paper-search` designs, located between the nodes. The
/// first design's picking: Newton started at the node failed, and the node was reported,
/// 0.024 rad from the extreme; started at the extreme of the sextic through the nearest
/// nodes, it finds the extreme. The second's planting: Newton from the sextic's start fails there,
/// and from the node's own step it finds the extreme (0.04 rad and 5 mm below the node).
#[test]
fn sharp_extremes_are_found_between_the_nodes() {
    let (s, eval) = search_design(
        [
            45.89145878113847,
            62.924661191067614,
            47.63626181170076,
            22.09613999827784,
            10.316257573286984,
            34.16789634488927,
            46.95517788799005,
            12.417765297108012,
            24.863904058096445,
            37.55718454917792,
            20.38052524536564,
            52.17541199966397,
        ],
        [
            20.21647900647245,
            -49.5783199176318,
            189.66545400915825,
            61.309818586818594,
            -26.78225733379341,
        ],
    );
    let picking = eval.events.unwrap().picking;
    assert_at_the_scans_extreme(&eval, picking, s.agronomy.tray_normal());
    let (_, eval) = search_design(
        [
            46.92186982193807,
            27.19278348521864,
            61.427501105845266,
            17.081273170575454,
            14.465795970516833,
            10.21338378373546,
            68.90349787746362,
            68.5158476851484,
            53.10939374936656,
            24.786531588436834,
            69.83539989875827,
            66.7740443518909,
        ],
        [
            127.85069468933114,
            -20.546084490658785,
            192.54714362061702,
            64.53984488734005,
            -75.78655883814604,
        ],
    );
    let planting = eval.events.unwrap().planting;
    assert_at_the_scans_extreme(&eval, planting, Vec2::new(0.0, -1.0));
}
