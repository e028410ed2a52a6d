//! Roots of one variable for the cut: a fast cube root and the Illinois regula falsi.

/// The cube root of `c` (positive, finite) to about 1e-6 relative: Kahan's guess from
/// the bits (a third of the exponent, good to about a tenth) and two Newton steps, enough
/// to place samples (the library's `cbrt`, a software routine here, cost a fortieth of a
/// toothed pair).
pub(super) fn rough_cube_root(c: f64) -> f64 {
    let mut y = f64::from_bits(c.to_bits() / 3 + 0x2A9F_7893_0000_0000);
    for _ in 0..2 {
        y = (2.0 * y + c / (y * y)) * (1.0 / 3.0);
    }
    y
}

/// The root of `f` between `lo` and `hi` (each `(x, f(x))`, `f(lo) ≤ 0 < f(hi)`) by the
/// Illinois variant of regula falsi, to 1e-13 of the bracket: a handful of evaluations
/// where bisection to the last bit takes fifty. Returns a point where `f > 0`.
pub(super) fn regula_falsi(f: impl Fn(f64) -> f64, mut lo: (f64, f64), mut hi: (f64, f64)) -> f64 {
    let tolerance = 1e-13 * (hi.0 - lo.0).abs();
    let mut last_side = 0;
    for _ in 0..100 {
        if (hi.0 - lo.0).abs() <= tolerance {
            break;
        }
        let x = (lo.0 * hi.1 - hi.0 * lo.1) / (hi.1 - lo.1);
        // Keep each trial inside the bracket and off its ends.
        let x = if x > lo.0.min(hi.0) && x < lo.0.max(hi.0) {
            x
        } else {
            0.5 * (lo.0 + hi.0)
        };
        let y = f(x);
        if y <= 0.0 {
            lo = (x, y);
            if last_side == -1 {
                hi.1 *= 0.5;
            }
            last_side = -1;
        } else {
            hi = (x, y);
            if last_side == 1 {
                lo.1 *= 0.5;
            }
            last_side = 1;
        }
    }
    hi.0
}

#[cfg(test)]
mod tests {
    use super::{regula_falsi, rough_cube_root};
    use std::cell::Cell;

    #[test]
    fn rough_cube_root_is_within_2e6_of_the_library_over_the_positive_range() {
        let mut worst = 0.0f64;
        for k in 0..20_000 {
            let c = 10f64.powf(-12.0 + 24.0 * k as f64 / 20_000.0) * (1.0 + 0.37 * (k % 7) as f64);
            let (ours, libm) = (rough_cube_root(c), c.cbrt());
            worst = worst.max((ours - libm).abs() / libm);
        }
        println!("worst relative error {worst:e}");
        assert!(worst <= 2e-6, "{worst}");
    }

    #[test]
    fn regula_falsi_finds_roots_in_few_evaluations() {
        // A convex function, where plain regula falsi keeps one end and crawls.
        for (f, root) in [
            (
                &(|x: f64| x * x * x - 2.0) as &dyn Fn(f64) -> f64,
                2f64.cbrt(),
            ),
            (&|x: f64| x.exp() - 10.0, 10f64.ln()),
            (&|x: f64| 1.0 - (-x).exp() * 50.0, 50f64.ln()),
        ] {
            let calls = Cell::new(0);
            let (lo, hi) = (0.0, 8.0);
            let x = regula_falsi(
                |x| {
                    calls.set(calls.get() + 1);
                    f(x)
                },
                (lo, f(lo)),
                (hi, f(hi)),
            );
            assert!((x - root).abs() < 1e-11, "{x} vs {root}");
            assert!(f(x) > 0.0);
            assert!(calls.get() < 30, "{} evaluations", calls.get());
        }
    }
}
