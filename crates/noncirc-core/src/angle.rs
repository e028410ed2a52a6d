//! Unit vectors `e(x) = (cos x, sin x)` without a libm call: a table of one turn in 256
//! steps and a short Taylor series for the remainder.
//!
//! The kinematics needs one unit vector per node and per arm state. glibc's `sincos` saves
//! and restores the floating-point rounding mode on every call (about 20 ns here, 13 % of
//! an evaluation); this is a few multiply-adds and one table load, and inlines.

use crate::vec2::Vec2;
use std::f64::consts::TAU;
use std::sync::OnceLock;
use wide::{f64x2, CmpLt};

/// Table steps per turn (a power of two: the index wraps with a mask).
const STEPS: usize = 256;
/// `2π/STEPS` split in two (Cody–Waite): the high part is `TAU/STEPS` in `f64`, the low part
/// what `TAU` lacks of 2π, per step.
const STEP_HI: f64 = TAU / STEPS as f64;
const STEP_LO: f64 = 2.449_293_598_294_706_4e-16 / STEPS as f64;

/// `e(2πk/STEPS)`, k = 0..STEPS.
fn table() -> &'static [[f64; 2]; STEPS] {
    static TABLE: OnceLock<[[f64; 2]; STEPS]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [[0.0; 2]; STEPS];
        for (k, e) in t.iter_mut().enumerate() {
            // The angle as hi + lo, with the step index in [−STEPS/2, STEPS/2): each entry
            // is then within an ulp or so of the true value.
            let k = k as f64 - if k < STEPS / 2 { 0.0 } else { STEPS as f64 };
            let (s, c) = (k * STEP_HI).sin_cos();
            let lo = k * STEP_LO;
            *e = [c - s * lo, s + c * lo];
        }
        t
    })
}

/// An angle (rad) in degrees within one turn, `[0°, 360°)`: how angles are shown to users.
pub(crate) fn degrees_in_turn(x: f64) -> f64 {
    let d = x.to_degrees().rem_euclid(360.0);
    // A tiny negative angle rounds up to 360.0 exactly.
    if d >= 360.0 {
        0.0
    } else {
        d
    }
}

/// `x.rem_euclid(2π)` (rad), bit for bit, without the library call (`fmod`) when `x` lies
/// in `(−2π, 0)`: there the remainder is `x` itself and one addition of 2π finishes it, as
/// `rem_euclid` does (at −2π it gives −0).
#[inline]
pub(crate) fn wrap_turn(x: f64) -> f64 {
    wrap(x, TAU)
}

/// `x.rem_euclid(period)` for a positive `period`, bit for bit, as [`wrap_turn`] (one
/// period either way of zero without `fmod`): angles in degrees take 360.
#[inline]
pub(crate) fn wrap(x: f64, period: f64) -> f64 {
    if (0.0..period).contains(&x) {
        x
    } else if x > -period && x < 0.0 {
        x + period
    } else {
        x.rem_euclid(period)
    }
}

/// A node's index `j` as a float, exactly (indices lie far below 2⁵³): through `i64`,
/// whose conversion is one instruction on x86-64 where `usize`'s takes six. Node angles
/// `j·h` are computed at every node of every evaluation.
#[inline(always)]
pub(crate) fn node_index(j: usize) -> f64 {
    j as i64 as f64
}

/// Beyond this |x| (rad) the table's reduction would lose digits: libm takes over.
const REDUCTION_LIMIT: f64 = 1e9;

/// `(cos x, sin x)`. The error is below `4e-16 + 2e-16·|x|` (tested against libm); a
/// non-finite `x` gives NaNs.
#[inline]
pub fn unit(x: f64) -> Vec2 {
    if x.abs() >= REDUCTION_LIMIT || x.is_nan() {
        let (s, c) = x.sin_cos();
        return Vec2::new(c, s);
    }
    // Nearest table step: adding and taking away 1.5·2⁵² rounds to an integer (half to
    // even) in floating point, whose low bits are then the step modulo 2⁵¹ in two's
    // complement. No conversion to an integer and back (a long latency) and no
    // `f64::round` (a library call on baseline x86-64).
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let shifted = x * (1.0 / STEP_HI) + ROUND;
    let (k, index) = (shifted - ROUND, shifted.to_bits() as usize & (STEPS - 1));
    // |r| <= π/256 (0.0123): cos to r⁶ and sin to r⁷ leave less than 1e-19.
    let r = (x - k * STEP_HI) - k * STEP_LO;
    let z = r * r;
    let cos_r = 1.0 - z * (0.5 - z * (1.0 / 24.0 - z * (1.0 / 720.0)));
    let sin_r = r * (1.0 - z * (1.0 / 6.0 - z * (1.0 / 120.0 - z * (1.0 / 5040.0))));
    // Two's complement: the mask wraps negative k too.
    let [c, s] = table()[index];
    Vec2::new(c * cos_r - s * sin_r, s * cos_r + c * sin_r)
}

/// `angles.iter().map(|a| unit(a + offset))`, bit for bit: two angles at a time in vector
/// lanes (`wide::f64x2`, each lane's arithmetic [`unit`]'s own), the table fetched once.
/// The kinematics takes a unit vector of every node's angle.
pub(crate) fn units(angles: &[f64], offset: f64) -> Vec<Vec2> {
    let table = table();
    let mut out = vec![Vec2::ZERO; angles.len()];
    let (pairs, tail) = angles.as_chunks::<2>();
    let (out_pairs, out_tail) = out.as_chunks_mut::<2>();
    for (o, &[a, b]) in out_pairs.iter_mut().zip(pairs) {
        *o = unit_pair(table, [a + offset, b + offset]);
    }
    for (o, &a) in out_tail.iter_mut().zip(tail) {
        *o = unit(a + offset);
    }
    out
}

/// `[unit(x[0]), unit(x[1])]`, bit for bit, from the `table`.
#[inline(always)]
fn unit_pair(table: &[[f64; 2]; STEPS], x: [f64; 2]) -> [Vec2; 2] {
    let xs = f64x2::new(x);
    // Both below the limit (a NaN is not).
    if xs.abs().cmp_lt(f64x2::splat(REDUCTION_LIMIT)).move_mask() != 0b11 {
        return x.map(unit);
    }
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let round = f64x2::splat(ROUND);
    let shifted = xs * f64x2::splat(1.0 / STEP_HI) + round;
    let k = shifted - round;
    let index = shifted
        .to_array()
        .map(|s| s.to_bits() as usize & (STEPS - 1));
    let r = (xs - k * f64x2::splat(STEP_HI)) - k * f64x2::splat(STEP_LO);
    let z = r * r;
    let c = |v: f64| f64x2::splat(v);
    let cos_r = c(1.0) - z * (c(0.5) - z * (c(1.0 / 24.0) - z * c(1.0 / 720.0)));
    let sin_r = r * (c(1.0) - z * (c(1.0 / 6.0) - z * (c(1.0 / 120.0) - z * c(1.0 / 5040.0))));
    let [[c0, s0], [c1, s1]] = index.map(|i| table[i]);
    let (ct, st) = (f64x2::new([c0, c1]), f64x2::new([s0, s1]));
    let (cos, sin) = (
        (ct * cos_r - st * sin_r).to_array(),
        (st * cos_r + ct * sin_r).to_array(),
    );
    [Vec2::new(cos[0], sin[0]), Vec2::new(cos[1], sin[1])]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn wrap_turn_is_rem_euclid_bit_for_bit() {
        let edges = [
            -TAU,
            -TAU + 1e-15,
            -1e-300,
            -0.0,
            0.0,
            TAU - 4e-16,
            TAU,
            -2.0 * TAU,
            7.5 * TAU,
            -1e12,
            f64::NAN,
        ];
        let sweep = (-40_000..40_000).map(|k| k as f64 * 3.3e-4 + 1e-7);
        let same = |got: f64, want: f64| {
            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan())
        };
        for x in edges.into_iter().chain(sweep) {
            let (got, want) = (wrap_turn(x), x.rem_euclid(TAU));
            assert!(same(got, want), "{x}: {got} vs {want}");
        }
        // In degrees, where a remainder near 180° rounds onto it: −180° + 1e-14 gives 180.
        let degrees = [
            -360.0,
            -180.0 - 1e-14,
            -180.0,
            -180.0 + 1e-14,
            -1e-20,
            180.0,
            359.9,
            720.0,
        ];
        let sweep = (-40_000..40_000).map(|k| k as f64 * 0.0191 + 3e-9);
        for x in degrees.into_iter().chain(edges).chain(sweep) {
            let (got, want) = (wrap(x, 360.0), x.rem_euclid(360.0));
            assert!(same(got, want), "{x}°: {got} vs {want}");
        }
    }

    fn error(x: f64) -> f64 {
        let Vec2 { x: c, y: s } = unit(x);
        let (s0, c0) = x.sin_cos();
        (c - c0).abs().max((s - s0).abs())
    }

    #[test]
    fn matches_libm_on_a_dense_sweep() {
        // Table points, midpoints between them (the largest remainder) and everything between.
        let mut worst = 0.0f64;
        for k in -40_000..40_000 {
            let x = k as f64 * (STEP_HI / 16.0) + 1e-3;
            worst = worst.max(error(x) / (4e-16 + 2e-16 * x.abs()));
        }
        assert!(worst <= 1.0, "worst error {worst} of the bound");
    }

    #[test]
    fn unit_length_and_non_finite_inputs() {
        for x in [0.0, -0.0, 1e-300, 0.5, -3.0, 100.0, 1e6, 1e12, -1e300] {
            assert!((unit(x).hypot() - 1.0).abs() < 1e-15, "{x}");
        }
        assert_eq!(unit(0.0), Vec2::new(1.0, 0.0));
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(unit(x).x.is_nan() && unit(x).y.is_nan(), "{x}");
        }
    }

    proptest! {
        #[test]
        fn matches_libm_anywhere(x in -1e4f64..1e4) {
            prop_assert!(error(x) <= 4e-16 + 2e-16 * x.abs(), "{x}: {}", error(x));
        }

        /// Many unit vectors are each one's own, bit for bit: any angles, table points
        /// and their halves, zeros, and angles beyond the reduction or not numbers, in
        /// either lane or the odd one left.
        #[test]
        fn many_units_are_each_ones_own_bit_for_bit(
            angles in prop::collection::vec(prop_oneof![
                4 => -1e4f64..1e4,
                2 => (-600i32..600).prop_map(|k| f64::from(k) * 0.5 * STEP_HI),
                1 => prop_oneof![
                    Just(0.0), Just(-0.0), Just(f64::NAN), Just(f64::INFINITY), Just(2e9),
                ],
            ], 0..9),
            offset in prop_oneof![Just(0.0), -4.0f64..4.0],
        ) {
            let bits = |v: &Vec2| [v.x.to_bits(), v.y.to_bits()];
            let got: Vec<_> = units(&angles, offset).iter().map(bits).collect();
            let want: Vec<_> = angles.iter().map(|&a| bits(&unit(a + offset))).collect();
            prop_assert_eq!(got, want);
        }
    }
}
