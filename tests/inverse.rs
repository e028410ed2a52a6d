//! Exact inversion (`noncirc_core::invert`): a target made by a train with two pairs comes
//! back as pitch curves whose path matches it; closed forms; named failures.

use noncirc_core::{
    invert, target_of, unit, Evaluator, InverseSpec, Scene, Target, TargetKind, Vec2,
};
use std::f64::consts::TAU;

use crate::common::{paper, two_pair_design};

/// The design's path as a target of `points` points with tolerance `tolerance_mm`.
fn target_of_design(scene: &Scene, points: usize, tolerance_mm: f64) -> Target {
    let eval = Evaluator::new().evaluate(scene).unwrap();
    let kin = eval.kinematics.as_ref().unwrap();
    let mut target = target_of(kin, eval.events.as_ref().unwrap(), points);
    target.tolerance_mm = tolerance_mm;
    target
}

fn spec_for(scene: &Scene, split: f64) -> InverseSpec {
    let [a1, a2] = scene
        .kinematics(&scene.resolution)
        .unwrap()
        .centre_distances();
    InverseSpec {
        centre_ratio: a2 / a1,
        split,
        branch: None,
        samples_per_turn: 720,
    }
}

#[test]
fn a_two_pair_design_is_inverted_back_to_its_path() {
    let design = two_pair_design();
    let target = target_of_design(&design, 4096, 0.01);
    for split in [0.5, 0.0] {
        let spec = spec_for(&design, split);
        let outcome = invert(&paper(), &target, &spec).unwrap();
        let blocking: Vec<_> = outcome.failures().filter(|c| c.blocks).collect();
        assert!(blocking.is_empty(), "split {split}: {blocking:#?}");
        // The design's own picking and planting poses come back with its path.
        for name in ["path_within_tolerance", "pose:picking", "pose:planting"] {
            let c = outcome.conditions.iter().find(|c| c.name == name);
            assert!(c.is_some_and(|c| c.holds), "split {split}: {name}: {c:?}");
        }
        let eval = outcome.evaluation.as_ref().unwrap();
        let fit = eval.fit.as_ref().unwrap();
        assert!(
            fit.path_hausdorff_mm <= 0.01,
            "split {split}: Hausdorff {} mm",
            fit.path_hausdorff_mm
        );
        // Both pairs close at the centre distances asked, to rounding.
        let kin = eval.kinematics.as_ref().unwrap();
        let design_a = design
            .kinematics(&design.resolution)
            .unwrap()
            .centre_distances();
        // The path's extreme radii fix R (the target's points are rounded to 0.1 µm and
        // its Fourier series is within 1 µm of them), so the distances come back to 1e-5.
        for (got, asked) in kin.centre_distances().iter().zip(design_a) {
            assert!(
                (got - asked).abs() < 1e-5 * asked,
                "split {split}: {got} vs {asked}"
            );
        }
        for pair in [Some(kin.pair()), kin.second_pair()].into_iter().flatten() {
            assert!(pair.closure().error_estimate < 1e-6, "{:?}", pair.closure());
        }
        // Split 0: the first pair is circular (its radius a_A/2 all round).
        if split == 0.0 {
            let (lo, hi) = kin.radius_range();
            let a = kin.centre_distance();
            assert!(hi - lo < 1e-9 * a, "split 0: the sun spans {lo}..{hi} mm");
        }
        // Its figures pass the layout check of tests/figures.rs.
        #[cfg(feature = "figures")]
        {
            let dir = crate::figures::temp(&format!("inverse-figures-{split}"));
            let files =
                noncirc::plots::inverse_figures(&outcome, &target, &dir, &Default::default())
                    .unwrap();
            crate::figures::check_figures(&files, &["inverse.svg", "fit.svg", "fit_distance.svg"]);
            std::fs::remove_dir_all(dir).ok();
        }
    }
}

/// A closed path of `count` points on the circle of `radius` about `centre`, run clockwise
/// (the paper's carrier sense).
fn circle(centre: Vec2, radius: f64, count: usize, tolerance_mm: f64) -> Target {
    let points: Vec<Vec2> = (0..count)
        .map(|k| centre + unit(-TAU * k as f64 / count as f64) * radius)
        .collect();
    Target {
        kind: TargetKind::Points,
        x_mm: points.iter().map(|p| p.x).collect(),
        y_mm: points.iter().map(|p| p.y).collect(),
        tolerance_mm,
        samples: 128,
        counts: true,
        poses: vec![],
        design: vec![],
    }
}

/// A circle of radius ρ about a centre c: the chain follows it with the arm translating
/// (A' ≡ 0), so i ≡ 1 and both pairs are circular, of radii a_A/2 and a_B/2: R = ρ and
/// S = |c|, the arm the longer link beside the axis (|c| > ρ), the planet circle round it.
#[test]
fn a_circle_the_arm_can_follow_by_translation_gives_circular_gears() {
    let scene = paper();
    let gamma0 = scene.train.gamma0_deg.to_radians();
    for (a1, a2, beside) in [(60.0, 50.0, true), (60.0, 50.0, false)] {
        let radius = (Vec2::new(a1, 0.0) + unit(gamma0) * a2).hypot();
        let centre = unit(1.0) * if beside { 145.0 } else { 70.0 };
        let target = circle(centre, radius, 720, 0.01);
        let spec = InverseSpec {
            centre_ratio: a2 / a1,
            split: 0.5,
            branch: None,
            samples_per_turn: 720,
        };
        let outcome = invert(&scene, &target, &spec).unwrap();
        let eval = (outcome.evaluation.as_ref())
            .unwrap_or_else(|| panic!("beside {beside}: {:#?}", outcome.conditions));
        let kin = eval.kinematics.as_ref().unwrap();
        // Circles (to rounding), of the radii asked to within the 720-gon's sag (0.3 µm).
        for ((lo, hi), a) in [
            (kin.radius_range(), a1),
            (kin.second_pair().unwrap().radius_range(), a2),
        ] {
            assert!(
                hi - lo < 1e-6,
                "beside {beside}: not a circle: {lo} to {hi} mm"
            );
            assert!(
                (lo - a / 2.0).abs() < 1e-3,
                "radius {lo} mm, not {}",
                a / 2.0
            );
        }
        let fit = eval.fit.as_ref().unwrap();
        assert!(fit.path_hausdorff_mm < 1e-3, "{}", fit.path_hausdorff_mm);
    }
}

/// A circle whose centre is nearer the axis than H1: the arm the path fixes (its centre's
/// distance) is shorter than the pusher's offset, and that is named.
#[test]
fn an_arm_shorter_than_the_pusher_offset_is_named() {
    let scene = paper();
    let target = circle(Vec2::new(30.0, 0.0), 150.0, 360, 0.5);
    let spec = InverseSpec {
        centre_ratio: 1.0,
        split: 0.5,
        branch: None,
        samples_per_turn: 720,
    };
    let outcome = invert(&scene, &target, &spec).unwrap();
    assert!(outcome.scene.is_none());
    // Round the axis, the planet circle is the longer link: R = 150 mm, S = 30 mm.
    let (r, s) = (outcome.planet_radius_mm, outcome.arm_length_mm);
    assert!(
        (r - 150.0).abs() < 0.05 && (s - 30.0).abs() < 0.05,
        "R {r}, S {s}"
    );
    let pusher = (outcome.conditions.iter())
        .find(|c| c.name == "pusher_within_arm")
        .unwrap();
    assert!(!pusher.holds && pusher.blocks);
    assert_eq!(pusher.bound, scene.train.pusher_offset_mm);
}

/// The path fixes the arm's direction but not the pusher's: a design with H1 = 52 mm,
/// inverted for the paper's scene (H1 = 65 mm), comes back with the H1 its poses' attitudes
/// ask for, and with it both poses and the same path.
#[test]
fn the_poses_attitudes_give_back_the_pusher_offset() {
    let mut design = two_pair_design();
    design.train.pusher_offset_mm = 52.0;
    let target = target_of_design(&design, 4096, 0.01);
    assert!(target.poses.iter().all(|p| p.attitude_deg.is_some()));
    let outcome = invert(&paper(), &target, &spec_for(&design, 0.5)).unwrap();
    let h1 = outcome.pusher_offset_mm.expect("the poses name attitudes");
    // The attitudes are rounded to 1e-4° in the target: H1 to about S·1e-6.
    assert!((h1 - 52.0).abs() < 1e-3, "H1 {h1} mm");
    let scene = outcome.scene.as_ref().unwrap();
    assert_eq!(scene.train.pusher_offset_mm, h1);
    for name in ["pose:picking", "pose:planting", "path_within_tolerance"] {
        let c = outcome.conditions.iter().find(|c| c.name == name);
        assert!(c.is_some_and(|c| c.holds), "{name}: {c:?}");
    }
    // A target without poses keeps the scene's H1.
    let mut bare = target.clone();
    bare.poses.clear();
    let outcome = invert(&paper(), &bare, &spec_for(&design, 0.5)).unwrap();
    assert_eq!(outcome.pusher_offset_mm, None);
    assert_eq!(outcome.scene.unwrap().train.pusher_offset_mm, 65.0);
}
