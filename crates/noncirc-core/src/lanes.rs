//! Vector lanes for kernels written once over one number or two at a time.

use std::ops::{Add, Div, Mul, Sub};
use wide::{f64x2, CmpGt, CmpLt};

/// Numbers that kernels are written over once: one `f64`, or two in vector lanes
/// (`wide::f64x2`), each lane's arithmetic the scalar's own, bit for bit.
pub(crate) trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    /// `v` in every lane.
    fn splat(v: f64) -> Self;
    /// `f64::clamp(x, 0, 1)` in every lane (a NaN stays NaN, −0 stays −0).
    fn clamp_unit(self) -> Self;
}

impl Lanes for f64 {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        v
    }

    #[inline(always)]
    fn clamp_unit(self) -> Self {
        self.clamp(0.0, 1.0)
    }
}

impl Lanes for f64x2 {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        f64x2::splat(v)
    }

    /// `clamp`'s two steps as written: below 0 becomes 0, then above 1 becomes 1.
    #[inline(always)]
    fn clamp_unit(self) -> Self {
        let (zero, one) = (f64x2::ZERO, f64x2::ONE);
        let raised = self.cmp_lt(zero).blend(zero, self);
        raised.cmp_gt(one).blend(one, raised)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp_in_lanes_is_f64_clamp() {
        let edges = [
            -1.0,
            -1e-300,
            -0.0,
            0.0,
            0.5,
            1.0 - f64::EPSILON,
            1.0,
            1.0 + f64::EPSILON,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for a in edges {
            for b in edges {
                let lanes = f64x2::new([a, b]).clamp_unit().to_array();
                let scalar = [a, b].map(<f64 as Lanes>::clamp_unit);
                assert_eq!(lanes.map(f64::to_bits), scalar.map(f64::to_bits), "{a} {b}");
            }
        }
    }
}
