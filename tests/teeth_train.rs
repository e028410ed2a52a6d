//! The toothed train assembles: at any carrier angle, each planet meets its intermediate
//! at the pitch arc where the intermediate met the sun, so the planet, congruent to the
//! sun and toothed at the same pitch arcs, meshes tooth for space (docs/teeth.md).

use noncirc::core::{CurveSpec, Kinematics, Rotation, Scene, ToothSpec, ToothedPair, TrainSpec};
use noncirc::teeth::train_layout;
use std::f64::consts::{PI, TAU};

#[test]
fn every_planet_meets_its_intermediate_at_the_sun_meshs_pitch_arc() {
    let mut scene = Scene::default();
    scene.gear.curve = CurveSpec::Fourier {
        c0_mm: 30.0,
        cos_mm: vec![1.0, 0.8],
        sin_mm: vec![0.0, 0.0, 0.4],
    };
    let curve = scene.gear.curve.build().unwrap();
    for rotation in [Rotation::Clockwise, Rotation::Counterclockwise] {
        let train = TrainSpec {
            rotation,
            ..scene.train
        };
        let kin = Kinematics::solve(&curve, None, &train, &scene.resolution).unwrap();
        let toothed =
            ToothedPair::cut(&curve, kin.centre_distance(), 40, &ToothSpec::default()).unwrap();
        let track = &toothed.track;
        let a = track.centre_distance();
        for step in 0..24 {
            let theta = TAU * step as f64 / 24.0;
            let layout = train_layout(&kin, &toothed, None, theta);
            for k in 0..kin.arms() {
                let (inter, planet) = (&layout[1 + 2 * k], &layout[2 + 2 * k]);
                let d = planet.centre_mm - inter.centre_mm;
                assert!(
                    (d.hypot() - a).abs() < 1e-6 * a,
                    "centre distance {}",
                    d.hypot()
                );
                // The planet's own ψ facing the intermediate.
                let psi_p = d.y.atan2(d.x) + PI - planet.angle_deg.to_radians();
                // The intermediate's own angle facing the planet, and the sun ψ it met.
                let chi_q = d.y.atan2(d.x) - inter.angle_deg.to_radians();
                let target = |psi: f64| {
                    let diff = track.driven_angle(psi) - chi_q;
                    diff - TAU * (diff / TAU).round()
                };
                // χ decreases by 2π per turn of ψ: bisect on the wrapped difference.
                let mut best = (f64::INFINITY, 0.0);
                for j in 0..720 {
                    let psi = TAU * j as f64 / 720.0;
                    if target(psi).abs() < best.0 {
                        best = (target(psi).abs(), psi);
                    }
                }
                let mut psi_q = best.1;
                for _ in 0..30 {
                    let h = 1e-7;
                    let slope = (target(psi_q + h) - target(psi_q - h)) / (2.0 * h);
                    psi_q -= target(psi_q) / slope;
                }
                let gap = psi_p - psi_q;
                let gap = gap - TAU * (gap / TAU).round();
                // The same pitch arc: within a micrometre along the curve.
                assert!(
                    gap.abs() * 40.0 < 1e-3,
                    "arm {k} at θ = {theta}: Δψ = {gap:e}"
                );
            }
        }
    }
}
