//! Designs the integration tests share.

use noncirc::scene_file::{parse_scene, BUILTIN};
use noncirc_core::{CurveSpec, Scene};

/// The paper's design.
pub fn paper() -> Scene {
    parse_scene(BUILTIN[0].1, BUILTIN[0].0).unwrap()
}

/// A train with two unlike pairs: an ellipse sun, a Fourier layer B, a_A ≠ a_B, at 720
/// samples per turn.
pub fn two_pair_design() -> Scene {
    let mut scene = paper();
    scene.gear.curve = CurveSpec::Ellipse {
        semi_major_mm: 32.0,
        eccentricity: 0.12,
    };
    scene.gear.second_curve = Some(CurveSpec::Fourier {
        c0_mm: 28.0,
        cos_mm: vec![1.5, -0.8],
        sin_mm: vec![-2.0, 0.4],
    });
    scene.resolution = scene.resolution.with_samples(720);
    scene
}
