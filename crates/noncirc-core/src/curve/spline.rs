//! Periodic cubic interpolating spline of `rho` in `psi` (period 2π).

use crate::angle::node_index;
use crate::curve::{Polar, TAU};
use crate::error::{finite_with, positive_with, Error, Result};
use crate::lanes::Lanes;
use std::cell::RefCell;
use wide::{f64x2, CmpGe, CmpLt};

/// A C² periodic cubic spline through `(psi_i, rho_i)`, period 2π.
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicSpline {
    /// Knot angles (rad), strictly increasing, span < 2π.
    knots: Vec<f64>,
    /// Per-segment coefficients `[a, b, c, d]`: rho = a + b t + c t² + d t³, t = psi - knot.
    coeffs: Vec<[f64; 4]>,
    /// Exact least and largest `rho` (mm), found once.
    rho_range: (f64, f64),
}

impl PeriodicSpline {
    /// Builds the spline through `(psi_i [rad], rho_i [mm])`. `kind` names it in errors.
    pub fn new(kind: &'static str, psi: Vec<f64>, rho: &[f64]) -> Result<Self> {
        let n = psi.len();
        if n < 4 || rho.len() != n {
            return Err(Error::TooFewPoints {
                kind,
                min: 4,
                got: n.min(rho.len()),
            });
        }
        for (i, (&p, &r)) in psi.iter().zip(rho).enumerate() {
            finite_with(|| format!("{kind} angle {i} (rad)"), p)?;
            if r > 0.0 {
                positive_with(|| format!("{kind} radius {i} (mm)"), r)?;
            } else {
                finite_with(|| format!("{kind} radius {i} (mm)"), r)?;
            }
            if r <= 0.0 {
                return Err(Error::NonPositiveRadius {
                    psi_deg: crate::angle::degrees_in_turn(p),
                    rho_mm: r,
                });
            }
        }
        check_angles(&psi)?;
        // Knot spacings, without an integer division each.
        let h = |i: usize| {
            if i + 1 < n {
                psi[i + 1] - psi[i]
            } else {
                psi[0] + TAU - psi[n - 1]
            }
        };
        let coeffs = periodic_cubic(h, rho);
        let mut spline = Self {
            knots: psi,
            coeffs,
            rho_range: (f64::NAN, f64::NAN),
        };
        let [(psi_min, rho_min), (_, rho_max)] = spline.extremes();
        if rho_min <= 0.0 {
            return Err(Error::NonPositiveRadius {
                psi_deg: crate::angle::degrees_in_turn(psi_min),
                rho_mm: rho_min,
            });
        }
        spline.rho_range = (rho_min, rho_max);
        Ok(spline)
    }

    /// Exact `(min, max)` of `rho` (mm).
    pub fn rho_range(&self) -> (f64, f64) {
        self.rho_range
    }

    /// Segment index and local offset for `psi` (any real angle).
    #[inline]
    fn locate(&self, psi: f64) -> (usize, f64) {
        let x = self.knots[0] + crate::angle::wrap_turn(psi - self.knots[0]);
        let i = self.knots.partition_point(|&k| k <= x).saturating_sub(1);
        (i, x - self.knots[i])
    }

    /// rho and its first two derivatives at `psi` (rad).
    #[inline]
    pub fn eval(&self, psi: f64) -> Polar {
        let (i, t) = self.locate(psi);
        self.eval_in(i, t)
    }

    /// As [`Self::eval`] at each angle (rad), the same values: each segment found by
    /// walking from the last one instead of a search (a step or none for angles in order).
    pub fn eval_each(&self, psi: impl IntoIterator<Item = f64>) -> Vec<Polar> {
        let last = self.knots.len() - 1;
        let mut i = 0;
        (psi.into_iter())
            .map(|psi| {
                let x = self.knots[0] + crate::angle::wrap_turn(psi - self.knots[0]);
                while i > 0 && x < self.knots[i] {
                    i -= 1;
                }
                while i < last && x >= self.knots[i + 1] {
                    i += 1;
                }
                self.eval_in(i, x - self.knots[i])
            })
            .collect()
    }

    /// Samples at `start + step·j` for `j = 0..n` (rad): the same values as [`Self::eval`],
    /// found by walking the segments along the grid instead of searching for each point,
    /// two samples at a time in vector lanes where both lie in one segment.
    pub fn sample_uniform(&self, start: f64, step: f64, n: usize) -> Vec<Polar> {
        let mut walk = GridWalk::new(self, start, step);
        // Pairs collected at their known count (no capacity check per pair), one sample
        // past the last for an odd count.
        let pairs: Vec<[Polar; 2]> = (0..n.div_ceil(2)).map(|k| walk.pair(2 * k)).collect();
        let mut out = pairs.into_flattened();
        out.truncate(n);
        out
    }

    /// Segment `i`'s span within the turn from the first knot (rad).
    #[inline(always)]
    fn span(&self, i: usize) -> (f64, f64) {
        let upper = match self.knots.get(i + 1) {
            Some(&next) => next,
            None => self.knots[0] + TAU,
        };
        (self.knots[i], upper)
    }

    /// rho and its first two derivatives at offset `t` (rad) into segment `i`.
    #[inline]
    fn eval_in(&self, i: usize, t: f64) -> Polar {
        let [rho, d1, d2] = cubic(self.coeffs[i], t);
        Polar { rho, d1, d2 }
    }

    /// Exact minimum and maximum of the spline, each as `(psi, rho)`, in one pass.
    fn extremes(&self) -> [(f64, f64); 2] {
        let n = self.knots.len();
        let mut least = (self.knots[0], self.coeffs[0][0]);
        let mut most = least;
        for i in 0..n {
            let h = if i + 1 < n {
                self.knots[i + 1] - self.knots[i]
            } else {
                self.knots[0] + TAU - self.knots[i]
            };
            let [a, b, c, d] = self.coeffs[i];
            let value = |t: f64| a + t * (b + t * (c + t * d));
            // Candidates in order: the segment's start and the roots of b + 2c t + 3d t²
            // in (0, h). A plain closure per candidate: an iterator filtered over the three
            // was a sixth of the spline's construction.
            let mut consider = |t: f64| {
                if (0.0..h).contains(&t) {
                    let v = value(t);
                    if v < least.1 {
                        least = (self.knots[i] + t, v);
                    }
                    if v > most.1 {
                        most = (self.knots[i] + t, v);
                    }
                }
            };
            consider(0.0);
            let (qa, qb, qc) = (3.0 * d, 2.0 * c, b);
            if qa.abs() > 1e-300 {
                let disc = qb * qb - 4.0 * qa * qc;
                if disc >= 0.0 {
                    let (s, inv) = (disc.sqrt(), 0.5 / qa);
                    consider((-qb + s) * inv);
                    consider((-qb - s) * inv);
                }
            } else if qb.abs() > 1e-300 {
                consider(-qc / qb);
            }
        }
        [least, most]
    }
}

/// The periodic C² cubic through `values` with knot spacings `h(i)` (from knot `i` to the
/// next; the last to the first closes the period): per segment `[a, b, c, d]`, the value
/// `a + b t + c t² + d t³` at `t` past its knot. The system's factors are kept per thread
/// for the last spacings ([`CyclicFactors`]): a pitch curve's, whose angles a search keeps
/// while it moves the radii.
pub(crate) fn periodic_cubic(h: impl Fn(usize) -> f64, values: &[f64]) -> Vec<[f64; 4]> {
    cubic_segments(&h, values, |slope| {
        FACTORS.with(|kept| {
            let mut factors = kept.borrow_mut();
            if !factors.are_for(values.len(), &h) {
                factors.factor(values.len(), &h);
            }
            factors.solve(right_hand_side(slope))
        })
    })
}

/// As [`periodic_cubic`] for a curve built once, a target's path: its system solved whole
/// in one sweep (factors then a solve take two), none kept. The inversion's shaping
/// (docs/inverse.md §6) follows the path to its last bit, so its path keeps this solve.
pub(crate) fn periodic_cubic_once(h: impl Fn(usize) -> f64, values: &[f64]) -> Vec<[f64; 4]> {
    let n = values.len();
    let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
    cubic_segments(&h, values, |slope| {
        let rhs = right_hand_side(slope);
        solve_cyclic_tridiagonal(n, |i| h(prev(i)), |i| 2.0 * (h(prev(i)) + h(i)), &h, rhs)
    })
}

/// The system's right-hand side by row, `6(s_i − s_{i−1})`, from the chord slopes `s`.
fn right_hand_side(slope: &[f64]) -> impl Fn(usize) -> f64 + '_ {
    let n = slope.len();
    move |i| 6.0 * (slope[i] - slope[if i == 0 { n - 1 } else { i - 1 }])
}

/// The segments of the periodic cubic through `values` with knot spacings `h`, its second
/// derivatives `M` from `solve` (given the chord slopes, for [`right_hand_side`]).
fn cubic_segments(
    h: impl Fn(usize) -> f64,
    values: &[f64],
    solve: impl FnOnce(&[f64]) -> Vec<f64>,
) -> Vec<[f64; 4]> {
    let n = values.len();
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    // Each segment's chord slope, divided once: the system's right-hand side takes it twice
    // and the segment's linear coefficient once.
    let slope: Vec<f64> = (0..n)
        .map(|i| (values[next(i)] - values[i]) / h(i))
        .collect();
    let m = solve(&slope);
    (0..n)
        .map(|i| {
            let (m0, m1, hi) = (m[i], m[next(i)], h(i));
            [
                values[i],
                slope[i] - hi * (2.0 * m0 + m1) / 6.0,
                m0 / 2.0,
                (m1 - m0) / (6.0 * hi),
            ]
        })
        .collect()
}

thread_local! {
    /// Each thread's factors for the last knot spacings it solved for. The factors are a
    /// pure function of the spacings, so a spline never depends on what was kept: a
    /// thread that solved other spacings in between gives the same bits
    /// (`the_kept_factors_never_change_a_spline`).
    static FACTORS: RefCell<CyclicFactors> = RefCell::new(CyclicFactors::none());
}

/// The cyclic tridiagonal system of the periodic spline's second derivatives for knot
/// spacings `h`, factored by Sherman–Morrison on the Thomas algorithm: row `i` reads
/// `h(i−1) M[i−1] + 2(h(i−1) + h(i)) M[i] + h(i) M[i+1] = rhs(i)`, indices mod n. A
/// search moves the radii and keeps the angles, so the factors serve design after design:
/// each solve is then one forward sweep of multiplications (no division: the reciprocal
/// pivots are kept) and one back substitution. Against the Thomas algorithm solved whole
/// each time, the second derivatives move by rounding (tested to 1e-13 of their largest).
struct CyclicFactors {
    spacings: Vec<f64>,
    /// Per row: the sub-diagonal, the reciprocal pivot, the eliminated super-diagonal, and
    /// `z` (`A' z = u`, the Sherman–Morrison correction's solve).
    rows: Vec<[f64; 4]>,
    /// `h(n−1)/γ`, with `γ = −2(h(n−1) + h(0))`.
    sub0_over_gamma: f64,
    /// `1/(1 + vᵀz)`.
    inv_d: f64,
}

impl CyclicFactors {
    /// No factors yet.
    fn none() -> Self {
        Self {
            spacings: Vec::new(),
            rows: Vec::new(),
            sub0_over_gamma: 0.0,
            inv_d: 0.0,
        }
    }

    /// Factors the system of spacings `h(0..n)` in place of the kept one (its buffers
    /// reused).
    fn factor(&mut self, n: usize, h: impl Fn(usize) -> f64) {
        self.spacings.clear();
        self.spacings.extend((0..n).map(&h));
        self.rows.clear();
        if n == 0 {
            return;
        }
        let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
        let sub = |i: usize| h(prev(i));
        let diag = |i: usize| 2.0 * (h(prev(i)) + h(i));
        // The non-cyclic matrix A' = A − u vᵀ, u = (γ, 0, …, 0, h(n−1)), v = (1, 0, …, h(n−1)/γ).
        let gamma = -diag(0);
        let sub0_over_gamma = sub(0) / gamma;
        let pivot_base = |i: usize| match i {
            0 => diag(0) - gamma,
            _ if i + 1 == n => diag(i) - h(i) * sub0_over_gamma,
            _ => diag(i),
        };
        let u = |i: usize| match i {
            0 => gamma,
            _ if i + 1 == n => h(i),
            _ => 0.0,
        };
        let (mut c_last, mut z_last) = (0.0, 0.0);
        for i in 0..n {
            let pivot = pivot_base(i) - sub(i) * c_last;
            let c = if i + 1 < n { h(i) / pivot } else { 0.0 };
            let z = (u(i) - sub(i) * z_last) / pivot;
            self.rows.push([sub(i), 1.0 / pivot, c, z]);
            (c_last, z_last) = (c, z);
        }
        let rows = &mut self.rows;
        for i in (0..n - 1).rev() {
            rows[i][3] -= rows[i][2] * rows[i + 1][3];
        }
        let d = 1.0 + rows[0][3] + sub0_over_gamma * rows[n - 1][3];
        (self.sub0_over_gamma, self.inv_d) = (sub0_over_gamma, 1.0 / d);
    }

    /// Whether these are the factors of spacings `h(0..n)`.
    fn are_for(&self, n: usize, h: impl Fn(usize) -> f64) -> bool {
        self.spacings.len() == n && (0..n).all(|i| self.spacings[i] == h(i))
    }

    /// The second derivatives for right-hand side `rhs(0..n)`.
    fn solve(&self, rhs: impl Fn(usize) -> f64) -> Vec<f64> {
        let n = self.rows.len();
        if n == 0 {
            return Vec::new();
        }
        let mut x = vec![0.0; n];
        let mut last = 0.0;
        for (i, (xi, row)) in x.iter_mut().zip(&self.rows).enumerate() {
            last = (rhs(i) - row[0] * last) * row[1];
            *xi = last;
        }
        for i in (0..n - 1).rev() {
            x[i] -= self.rows[i][2] * x[i + 1];
        }
        let factor = (x[0] + self.sub0_over_gamma * x[n - 1]) * self.inv_d;
        for (xi, row) in x.iter_mut().zip(&self.rows) {
            *xi -= factor * row[3];
        }
        x
    }
}

/// Checks that angles are strictly increasing and span less than one turn.
pub(crate) fn check_angles(psi: &[f64]) -> Result<()> {
    for i in 1..psi.len() {
        if psi[i] <= psi[i - 1] {
            return Err(Error::ControlAngles {
                index: i,
                angle_deg: psi[i].to_degrees(),
                previous_deg: psi[i - 1].to_degrees(),
            });
        }
    }
    let last = psi.len() - 1;
    if psi[last] - psi[0] >= TAU {
        return Err(Error::ControlAngles {
            index: last,
            angle_deg: psi[last].to_degrees(),
            previous_deg: psi[0].to_degrees() + 360.0,
        });
    }
    Ok(())
}

/// Solves the cyclic tridiagonal system of `n` rows
/// `sub(i) x[i-1] + diag(i) x[i] + sup(i) x[i+1] = rhs(i)`, indices mod n, by
/// Sherman–Morrison on the Thomas algorithm. The two Thomas solves share their matrix, so
/// they run in one sweep.
fn solve_cyclic_tridiagonal(
    n: usize,
    sub: impl Fn(usize) -> f64,
    diag: impl Fn(usize) -> f64,
    sup: impl Fn(usize) -> f64,
    rhs: impl Fn(usize) -> f64,
) -> Vec<f64> {
    // The non-cyclic matrix A' = A − u vᵀ, u = (γ, 0, …, 0, sup(n−1)), v = (1, 0, …, sub(0)/γ).
    let gamma = -diag(0);
    let b = |i: usize| {
        if i == 0 {
            diag(0) - gamma
        } else if i + 1 == n {
            diag(i) - sup(i) * sub(0) / gamma
        } else {
            diag(i)
        }
    };
    let u = |i: usize| {
        if i == 0 {
            gamma
        } else if i + 1 == n {
            sup(i)
        } else {
            0.0
        }
    };
    // Forward sweep: per row the eliminated super-diagonal and both right-hand sides.
    let mut rows = vec![[0.0; 3]; n];
    let mut last = [0.0; 3];
    for (i, row) in rows.iter_mut().enumerate() {
        let denom = b(i) - sub(i) * last[0];
        let c = if i + 1 < n { sup(i) / denom } else { 0.0 };
        *row = [
            c,
            (rhs(i) - sub(i) * last[1]) / denom,
            (u(i) - sub(i) * last[2]) / denom,
        ];
        last = *row;
    }
    // Back substitution: rows[i][1] becomes x (A' x = rhs), rows[i][2] z (A' z = u).
    for i in (0..n - 1).rev() {
        let (c, next) = (rows[i][0], rows[i + 1]);
        rows[i][1] -= c * next[1];
        rows[i][2] -= c * next[2];
    }
    let (first, end) = (rows[0], rows[n - 1]);
    let factor = (first[1] + sub(0) * end[1] / gamma) / (1.0 + first[2] + sub(0) * end[2] / gamma);
    rows.iter().map(|r| r[1] - factor * r[2]).collect()
}

/// A walk along the grid `base + step·j` (rad): the segment it stands in, that segment's
/// span within the turn from the first knot, and the whole turns taken off so far.
struct GridWalk<'a> {
    spline: &'a PeriodicSpline,
    base: f64,
    step: f64,
    segment: usize,
    lower: f64,
    upper: f64,
    turns: f64,
    /// The segment's coefficients in both lanes.
    coeffs: [f64x2; 4],
}

impl<'a> GridWalk<'a> {
    /// The walk from `start` by `step` (rad), at the segment that holds `start`.
    fn new(spline: &'a PeriodicSpline, start: f64, step: f64) -> Self {
        let (segment, t0) = spline.locate(start);
        let (lower, upper) = spline.span(segment);
        Self {
            spline,
            base: spline.knots[segment] + t0,
            step,
            segment,
            lower,
            upper,
            turns: 0.0,
            coeffs: spline.coeffs[segment].map(f64x2::splat),
        }
    }

    /// The sample at node `j`, the walk moved on to its segment (ten samples a segment at
    /// the default resolution: most need none of the walks).
    #[inline(always)]
    fn sample(&mut self, j: usize) -> Polar {
        let spline = self.spline;
        let (first, last) = (spline.knots[0], spline.knots.len() - 1);
        let mut x = self.base + self.step * node_index(j) + self.turns;
        if !(self.lower <= x && x < self.upper) {
            while x >= first + TAU {
                x -= TAU;
                self.turns -= TAU;
                self.segment = 0;
            }
            while x < first {
                x += TAU;
                self.turns += TAU;
                self.segment = last;
            }
            while x < spline.knots[self.segment] {
                self.segment -= 1;
            }
            while self.segment < last && x >= spline.knots[self.segment + 1] {
                self.segment += 1;
            }
            (self.lower, self.upper) = spline.span(self.segment);
            self.coeffs = spline.coeffs[self.segment].map(f64x2::splat);
        }
        spline.eval_in(self.segment, x - self.lower)
    }

    /// The samples at nodes `j` and `j + 1`, bit for bit [`GridWalk::sample`]'s: in vector
    /// lanes where both lie in the walk's segment (which the walk would not move for),
    /// else one at a time.
    #[inline(always)]
    fn pair(&mut self, j: usize) -> [Polar; 2] {
        let splat = f64x2::splat;
        let nodes = f64x2::new([node_index(j), node_index(j + 1)]);
        let x = splat(self.base) + splat(self.step) * nodes + splat(self.turns);
        let lower = splat(self.lower);
        if (x.cmp_ge(lower) & x.cmp_lt(splat(self.upper))).move_mask() != 0b11 {
            return [self.sample(j), self.sample(j + 1)];
        }
        let [rho, d1, d2] = cubic(self.coeffs, x - lower).map(f64x2::to_array);
        [0, 1].map(|k| Polar {
            rho: rho[k],
            d1: d1[k],
            d2: d2[k],
        })
    }
}

/// A cubic segment `[a, b, c, d]` (`rho = a + b t + c t² + d t³`) at offset `t` (rad), at
/// one offset or two in lanes: `[rho, rho', rho'']`.
#[inline(always)]
fn cubic<T: Lanes>(coeffs: [T; 4], t: T) -> [T; 3] {
    let [a, b, c, d] = coeffs;
    let k = T::splat;
    [
        a + t * (b + t * (c + t * d)),
        b + t * (k(2.0) * c + k(3.0) * t * d),
        k(2.0) * c + k(6.0) * t * d,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// The kept factors solve the spline's system as the Thomas algorithm solved whole
        /// does, to rounding: knot spacings from even to 30:1, any right-hand side.
        #[test]
        fn kept_factors_solve_as_the_thomas_algorithm_does(
            weights in proptest::collection::vec(1.0f64..30.0, 4..24),
            rhs in proptest::collection::vec(-50.0f64..50.0, 24),
        ) {
            let total: f64 = weights.iter().sum();
            let h: Vec<f64> = weights.iter().map(|w| TAU * w / total).collect();
            let n = h.len();
            let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
            let whole = solve_cyclic_tridiagonal(
                n,
                |i| h[prev(i)],
                |i| 2.0 * (h[prev(i)] + h[i]),
                |i| h[i],
                |i| rhs[i],
            );
            let mut factors = CyclicFactors::none();
            factors.factor(n, |i| h[i]);
            let kept = factors.solve(|i| rhs[i]);
            let scale = whole.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in kept.iter().zip(&whole) {
                proptest::prop_assert!((a - b).abs() <= 1e-13 * scale, "{a} against {b}");
            }
            // And the system holds, row by row.
            for i in 0..n {
                let row = h[prev(i)] * kept[prev(i)]
                    + 2.0 * (h[prev(i)] + h[i]) * kept[i]
                    + h[i] * kept[(i + 1) % n];
                proptest::prop_assert!((row - rhs[i]).abs() <= 1e-12 * (1.0 + scale));
            }
        }
    }

    /// A thread keeps the factors of the last knot spacings it solved for; a spline built
    /// after others with other knots, or on a fresh thread, has the same bits.
    #[test]
    fn the_kept_factors_never_change_a_spline() {
        let (psi, first) = five_point_spline();
        let other: Vec<f64> = [0.0f64, 100.0, 170.0, 230.0, 290.0, 330.0]
            .iter()
            .map(|d| d.to_radians())
            .collect();
        let between = PeriodicSpline::new("spline", other, &[30.0, 20.0, 40.0, 35.0, 25.0, 45.0]);
        assert!(between.is_ok());
        let again = PeriodicSpline::new("spline", psi.clone(), &RADII).unwrap();
        let fresh = std::thread::spawn(move || PeriodicSpline::new("spline", psi, &RADII))
            .join()
            .unwrap()
            .unwrap();
        let bits = |s: &PeriodicSpline| -> Vec<u64> {
            (s.coeffs.iter().flatten()).map(|c| c.to_bits()).collect()
        };
        assert_eq!(bits(&again), bits(&first));
        assert_eq!(bits(&fresh), bits(&first));
    }

    const RADII: [f64; 5] = [30.0, 45.0, 25.0, 40.0, 35.0];

    /// A five-point spline: its knot angles (rad) and the spline.
    fn five_point_spline() -> (Vec<f64>, PeriodicSpline) {
        let psi: Vec<f64> = [10.0f64, 80.0, 150.0, 200.0, 300.0]
            .iter()
            .map(|d| d.to_radians())
            .collect();
        let spline = PeriodicSpline::new("spline", psi.clone(), &RADII).unwrap();
        (psi, spline)
    }

    #[test]
    fn uniform_sampling_matches_pointwise_evaluation() {
        let (psi, s) = five_point_spline();
        // Both senses, starts outside [0, 2π) and before the first knot, several turns.
        for (start, step, n) in [
            (0.0, TAU / 120.0, 120),
            (1.5, -TAU / 120.0, 120),
            (-7.0, TAU / 36.0, 100),
            (20.0, -TAU / 50.0, 130),
            (psi[2], TAU / 7.0, 21),
        ] {
            for (j, p) in s.sample_uniform(start, step, n).into_iter().enumerate() {
                let q = s.eval(start + step * j as f64);
                assert!(
                    (p.rho - q.rho).abs() < 1e-11 && (p.d1 - q.d1).abs() < 1e-9,
                    "start {start} step {step} j {j}: {p:?} vs {q:?}"
                );
            }
        }
    }

    proptest::proptest! {
        /// Samples taken two at a time in lanes are the walk's one at a time, bit for bit:
        /// random splines, starts anywhere, steps either way (some over several segments
        /// at once), odd and even counts.
        #[test]
        fn samples_in_lanes_are_the_walk_one_at_a_time(
            gaps in proptest::collection::vec(0.3f64..1.0, 4..14),
            radii in proptest::collection::vec(35.0f64..45.0, 14),
            first in -1.0f64..1.0,
            start in -20.0f64..20.0,
            step in -1.5f64..1.5,
            n in 1usize..160,
        ) {
            // Knots over less than a turn, from `first`.
            let scale = 6.0 / gaps.iter().sum::<f64>();
            let psi: Vec<f64> = (gaps.iter())
                .scan(first, |at, g| {
                    let knot = *at;
                    *at += g * scale;
                    Some(knot)
                })
                .collect();
            let spline = PeriodicSpline::new("spline", psi.clone(), &radii[..psi.len()]).unwrap();
            assert_samples_in_lanes_are_the_walks(&spline, start, step, n);
        }
    }

    /// [`PeriodicSpline::sample_uniform`] against [`GridWalk::sample`] one at a time.
    fn assert_samples_in_lanes_are_the_walks(
        spline: &PeriodicSpline,
        start: f64,
        step: f64,
        n: usize,
    ) {
        let mut walk = GridWalk::new(spline, start, step);
        let one_at_a_time: Vec<Polar> = (0..n).map(|j| walk.sample(j)).collect();
        let bits = |p: &Polar| [p.rho, p.d1, p.d2].map(f64::to_bits);
        let lanes = spline.sample_uniform(start, step, n);
        assert_eq!(lanes.len(), n);
        for (j, (a, b)) in lanes.iter().zip(&one_at_a_time).enumerate() {
            assert_eq!(bits(a), bits(b), "start {start} step {step} sample {j}");
        }
    }

    /// Samples that fall exactly on knots (eighths of a turn, sampled by sixteenths) go to
    /// the segment they start, in lanes as one at a time.
    #[test]
    fn samples_on_the_knots_in_lanes_are_the_walks() {
        let psi: Vec<f64> = (0..8).map(|i| i as f64 * (TAU / 8.0)).collect();
        let spline = PeriodicSpline::new("spline", psi, &RADII.repeat(2)[..8]).unwrap();
        for (start, step) in [
            (0.0, TAU / 16.0),
            (0.0, -TAU / 16.0),
            (TAU / 16.0, TAU / 16.0),
        ] {
            assert_samples_in_lanes_are_the_walks(&spline, start, step, 37);
        }
    }

    /// The walk from segment to segment finds the segment the search finds: the same bits,
    /// for angles in order either way, at the knots themselves, and out of order.
    #[test]
    fn evaluation_along_angles_is_pointwise_evaluation() {
        let (psi, s) = five_point_spline();
        let knots: Vec<f64> = psi
            .iter()
            .flat_map(|&k| [k, k + TAU, k - 3.0 * TAU])
            .collect();
        let rising: Vec<f64> = (0..400).map(|j| -9.0 + 0.047 * j as f64).collect();
        let falling: Vec<f64> = rising.iter().rev().copied().collect();
        let scattered: Vec<f64> = (0..200).map(|j| (j as f64 * 2.399).sin() * 20.0).collect();
        for angles in [&knots, &rising, &falling, &scattered] {
            let along = s.eval_each(angles.iter().copied());
            for (&a, p) in angles.iter().zip(&along) {
                let q = s.eval(a);
                assert_eq!(
                    [p.rho, p.d1, p.d2].map(f64::to_bits),
                    [q.rho, q.d1, q.d2].map(f64::to_bits),
                    "at {a}"
                );
            }
        }
    }

    #[test]
    fn interpolates_and_is_c2_periodic() {
        let (psi, s) = five_point_spline();
        for (p, r) in psi.iter().zip(&RADII) {
            assert!((s.eval(*p).rho - r).abs() < 1e-12);
            assert!((s.eval(*p + TAU).rho - r).abs() < 1e-11);
        }
        // Continuity of value, slope and curvature across each knot (incl. the wrap).
        for &p in &psi {
            let (l, r) = (s.eval(p - 1e-9), s.eval(p + 1e-9));
            assert!((l.rho - r.rho).abs() < 1e-7);
            assert!((l.d1 - r.d1).abs() < 1e-6);
            assert!((l.d2 - r.d2).abs() < 1e-5);
        }
    }

    #[test]
    fn reproduces_a_pure_harmonic_closely() {
        let n = 64;
        let psi: Vec<f64> = (0..n).map(|i| TAU * i as f64 / n as f64).collect();
        let rho: Vec<f64> = psi.iter().map(|p| 40.0 + 5.0 * p.cos()).collect();
        let s = PeriodicSpline::new("table", psi, &rho).unwrap();
        for k in 0..200 {
            let p = 0.0314 * k as f64;
            assert!((s.eval(p).rho - (40.0 + 5.0 * p.cos())).abs() < 1e-5);
        }
    }

    #[test]
    fn overshoot_below_zero_is_an_error_naming_the_angle() {
        let psi: Vec<f64> = [0.0f64, 10.0, 20.0, 30.0, 200.0]
            .iter()
            .map(|d| d.to_radians())
            .collect();
        let rho = [1.0, 50.0, 1.0, 50.0, 1.0];
        match PeriodicSpline::new("spline", psi, &rho) {
            Err(Error::NonPositiveRadius { rho_mm, .. }) => assert!(rho_mm <= 0.0),
            other => panic!("expected NonPositiveRadius, got {other:?}"),
        }
    }
}
