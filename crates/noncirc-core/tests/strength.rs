//! Tooth strength on cut teeth against ISO 6336-3's method B: on a circular gear cut by
//! the standard rack, the critical section, lever, fillet radius, form factor and stress
//! correction measured on the outline equal the standard's closed forms; on a
//! non-circular gear the teeth differ as the pitch curve's curvature says.

use noncirc_core::{tooth_forms, Ellipse, Member, PitchCurve, ToothForm, ToothSpec, ToothedPair};
use std::f64::consts::PI;

fn inv(a: f64) -> f64 {
    a.tan() - a
}

/// ISO 6336-3:2019 method B for an external spur gear of `z` teeth cut by a rack of
/// dedendum `hfp` and tip radius `rho_fp` (× m), profile shift `x`, addendum `ha`,
/// loaded at the tip: `(sFn/m, hFe/m, ρF/m, αFen, YF, YS)`.
fn iso_method_b(z: f64, alpha: f64, hfp: f64, rho_fp: f64, x: f64, ha: f64) -> [f64; 6] {
    let e = PI / 4.0 - hfp * alpha.tan() - (1.0 - alpha.sin()) * rho_fp / alpha.cos();
    let g = rho_fp - hfp + x;
    let h = 2.0 / z * (PI / 2.0 - e) - PI / 3.0;
    let mut theta = PI / 6.0;
    for _ in 0..100 {
        theta = 2.0 * g / z * theta.tan() - h;
    }
    let s_fn = z * (PI / 3.0 - theta).sin() + 3f64.sqrt() * (g / theta.cos() - rho_fp);
    let rho_f = rho_fp + 2.0 * g * g / (theta.cos() * (z * theta.cos().powi(2) - 2.0 * g));
    let d_en = z + 2.0 * ha + 2.0 * x;
    let alpha_en = (z * alpha.cos() / d_en).acos();
    let gamma_e = (PI / 2.0 + 2.0 * x * alpha.tan()) / z + inv(alpha) - inv(alpha_en);
    let alpha_fen = alpha_en - gamma_e;
    let h_fe = 0.5
        * ((gamma_e.cos() - gamma_e.sin() * alpha_fen.tan()) * d_en
            - z * (PI / 3.0 - theta).cos()
            - g / theta.cos()
            + rho_fp);
    let yf = 6.0 * h_fe * alpha_fen.cos() / (s_fn * s_fn * alpha.cos());
    let l = s_fn / h_fe;
    let qs = s_fn / (2.0 * rho_f);
    let ys = (1.2 + 0.13 * l) * qs.powf(1.0 / (1.21 + 2.3 / l));
    [s_fn, h_fe, rho_f, alpha_fen, yf, ys]
}

fn circle(r: f64) -> PitchCurve {
    PitchCurve::Ellipse(Ellipse::new(r, 0.0).unwrap())
}

fn forms(curve: &PitchCurve, a: f64, z: u32, spec: &ToothSpec) -> [Vec<ToothForm>; 2] {
    let pair = ToothedPair::cut(curve, a, z, spec).unwrap();
    let alpha = spec.pressure_angle_deg.to_radians();
    [Member::Driver, Member::Driven].map(|member| {
        let g = usize::from(member == Member::Driven);
        tooth_forms(
            &pair.gears[g],
            "gear",
            &pair.track,
            member,
            pair.module_mm,
            alpha,
        )
        .unwrap()
    })
}

#[test]
fn a_cut_spur_tooth_has_iso_6336_method_b_form_and_stress_factors() {
    let m = 2.0;
    for (z, x) in [(17u32, 0.0), (24, 0.0), (40, 0.0), (80, 0.0), (24, 0.3)] {
        let spec = ToothSpec {
            profile_shift: x,
            ..ToothSpec::default()
        };
        let r = m * f64::from(z) / 2.0;
        let alpha = spec.pressure_angle_deg.to_radians();
        // The driven gear is cut with the opposite shift.
        for (g, teeth) in forms(&circle(r), 2.0 * r, z, &spec).iter().enumerate() {
            let shift = if g == 0 { x } else { -x };
            let [s_fn, h_fe, rho_f, alpha_fen, yf, ys] = iso_method_b(
                f64::from(z),
                alpha,
                spec.dedendum,
                spec.tip_radius,
                shift,
                spec.addendum,
            );
            assert_eq!(teeth.len(), z as usize);
            for f in teeth {
                let rel = |a: f64, b: f64| (a - b).abs() / b;
                let said = format!("z {z}, x {shift}: {f:?} against ISO s {s_fn} h {h_fe} ρ {rho_f} αFen {} YF {yf} YS {ys}", alpha_fen.to_degrees());
                assert!(rel(f.root_chord_mm / m, s_fn) < 1e-3, "{said}");
                assert!(rel(f.lever_mm / m, h_fe) < 1e-3, "{said}");
                assert!(rel(f.fillet_radius_mm / m, rho_f) < 0.01, "{said}");
                assert!(
                    (f.load_angle_deg - alpha_fen.to_degrees()).abs() < 0.02,
                    "{said}"
                );
                assert!(rel(f.form_factor, yf) < 2e-3, "{said}");
                assert!(rel(f.stress_correction, ys) < 3e-3, "{said}");
            }
        }
    }
}

#[test]
fn a_non_circular_tooth_is_the_spur_tooth_of_its_osculating_circle() {
    // Each tooth of an elliptic pair against ISO's tooth of a spur gear whose pitch radius
    // is the pitch curve's radius of curvature at the tooth's centre (the virtual gear of
    // the non-circular gear literature): the teeth on the flatter arcs are the stronger.
    let spec = ToothSpec::default();
    let curve = PitchCurve::Ellipse(Ellipse::new(40.0, 0.45).unwrap());
    let pair = ToothedPair::cut(&curve, 80.0, 30, &spec).unwrap();
    let (m, alpha) = (pair.module_mm, spec.pressure_angle_deg.to_radians());
    for (g, member) in [Member::Driver, Member::Driven].into_iter().enumerate() {
        let forms = tooth_forms(&pair.gears[g], "gear", &pair.track, member, m, alpha).unwrap();
        let (mut least, mut most) = (f64::INFINITY, 0.0f64);
        for (tooth, f) in pair.gears[g].teeth.iter().zip(&forms) {
            let frame = pair
                .track
                .frame(member, pair.track.psi_at(tooth.centre_arc_mm));
            let z_virtual = 2.0 / (frame.curvature * m);
            let [.., yf, _] = iso_method_b(z_virtual, alpha, 1.25, 0.38, 0.0, 1.0);
            let rel = (f.form_factor - yf).abs() / yf;
            assert!(
                rel < 3e-3,
                "gear {g}, z_v {z_virtual:.1}: YF {} against {yf}",
                f.form_factor
            );
            least = least.min(f.form_factor);
            most = most.max(f.form_factor);
        }
        // The teeth do differ: this ellipse spans virtual gears of 25 to 36 teeth, YF 2.45–2.62.
        assert!(most / least > 1.05, "gear {g}: YF from {least} to {most}");
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(32))]

    /// Over random elliptic pairs, tooth counts and profile shifts, every cut tooth of
    /// both gears has a section, a lever and a load angle, and the form factor of the
    /// spur tooth of its osculating circle (the same shift) to 1 %.
    #[test]
    fn every_tooth_of_a_random_elliptic_pair_is_its_osculating_spur_tooth(
        e in 0.0f64..0.4,
        z in 24u32..48,
        x in -0.2f64..0.3,
    ) {
        let spec = ToothSpec { profile_shift: x, ..ToothSpec::default() };
        let curve = PitchCurve::Ellipse(Ellipse::new(40.0, e).unwrap());
        // An ellipse is convex everywhere: the rack cuts it.
        let pair = ToothedPair::cut(&curve, 80.0, z, &spec).unwrap();
        let (m, alpha) = (pair.module_mm, spec.pressure_angle_deg.to_radians());
        for (g, member) in [Member::Driver, Member::Driven].into_iter().enumerate() {
            let shift = if g == 0 { x } else { -x };
            let forms = tooth_forms(&pair.gears[g], "gear", &pair.track, member, m, alpha).unwrap();
            for (tooth, f) in pair.gears[g].teeth.iter().zip(&forms) {
                proptest::prop_assert!(f.root_chord_mm > 0.0 && f.lever_mm > 0.0);
                proptest::prop_assert!(f.load_angle_deg > 0.0 && f.load_angle_deg < 60.0);
                proptest::prop_assert!(f.stress_correction >= 1.0);
                let frame = pair.track.frame(member, pair.track.psi_at(tooth.centre_arc_mm));
                let z_virtual = 2.0 / (frame.curvature * m);
                let [.., yf, _] = iso_method_b(z_virtual, alpha, 1.25, 0.38, shift, 1.0);
                proptest::prop_assert!(
                    (f.form_factor - yf).abs() < 0.01 * yf,
                    "e {e}, z {z}, x {shift}, z_v {z_virtual:.1}: YF {} against {yf}",
                    f.form_factor
                );
            }
        }
    }
}
