//! The speed–accuracy measurement: a checked reference, falling errors, defaults that hold.

use noncirc::accuracy::measure;
use noncirc::core::Resolution;
use noncirc::scene_file::{apply_overrides, load_scene};

#[test]
fn defaults_meet_the_accuracy_targets_on_easy_and_hard_designs() {
    let paper = load_scene(None).unwrap();
    let hard = apply_overrides(
        paper.clone(),
        &["gear.curve.radii_mm=[15, 20, 66, 62, 70, 50, 14, 8, 25, 70, 62, 18]".into()],
    )
    .unwrap();
    for scene in [paper, hard] {
        let report = measure(&scene, 360).unwrap();
        let (ref_mm, ref_deg) = report.reference_check.worst();
        assert!(
            ref_mm < 1e-8 && ref_deg < 1e-8,
            "reference not converged: {ref_mm:e} mm {ref_deg:e}°"
        );
        let at = |n: usize| {
            report
                .levels
                .iter()
                .find(|l| l.samples_per_turn == n)
                .and_then(|l| l.errors.clone())
                .unwrap()
        };
        let default = at(Resolution::DEFAULT.samples_per_turn);
        assert!(
            default.trajectory_mm < 0.01 && default.worst().1 < 0.01,
            "{default:?}"
        );
        // Errors fall at least with order 3 between 60 and 240 samples (4x: 64x).
        assert!(at(240).trajectory_mm < at(60).trajectory_mm / 64.0);
        assert!(at(240).attitude_deg < at(60).attitude_deg / 64.0);
    }
}
