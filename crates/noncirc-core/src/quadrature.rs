//! Periodic quadrature on uniform grids: spectral cumulative integrals and Hermite interpolation.

use crate::angle::node_index;
use crate::lanes::Lanes;
use realfft::num_complex::Complex64;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use std::sync::Arc;
use wide::f64x2;

/// Spectral cumulative integration of periodic samples on a uniform grid.
///
/// Holds the real-input FFT plans (`realfft`: half the work of a complex transform of the
/// same length) and their buffers so that repeated use allocates nothing.
#[derive(Clone)]
pub(crate) struct SpectralIntegrator {
    n: usize,
    forward: Arc<dyn RealToComplex<f64>>,
    inverse: Arc<dyn ComplexToReal<f64>>,
    /// The samples in, the inverse transform out (`n`; the forward transform overwrites it).
    real: Vec<f64>,
    /// Coefficients `k = 0 … n/2`.
    spectrum: Vec<Complex64>,
    scratch: Vec<Complex64>,
    /// `(1/n)/k` for `k = 0 … n/2` (the first unused): the integral's factors, divided
    /// once per plan rather than once per coefficient of every integral.
    integral_factors: Vec<f64>,
}

impl std::fmt::Debug for SpectralIntegrator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SpectralIntegrator({})", self.n)
    }
}

impl SpectralIntegrator {
    /// Plans transforms of length `n` (samples per period).
    pub(crate) fn new(n: usize) -> Self {
        let mut planner = RealFftPlanner::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        let scratch_len = forward.get_scratch_len().max(inverse.get_scratch_len());
        let spectrum = forward.make_output_vec();
        let scale = 1.0 / n as f64;
        Self {
            n,
            real: forward.make_input_vec(),
            integral_factors: (0..spectrum.len()).map(|k| scale / k as f64).collect(),
            spectrum,
            scratch: vec![Complex64::default(); scratch_len],
            forward,
            inverse,
        }
    }

    /// Samples per period this integrator was planned for.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// The unnormalised forward transform of `f` into `self.spectrum` (`k = 0 … n/2`).
    fn transform(&mut self, f: &[f64]) {
        self.real.copy_from_slice(f);
        // Lengths are the plan's own: the transform cannot fail.
        let done = (self.forward).process_with_scratch(
            &mut self.real,
            &mut self.spectrum,
            &mut self.scratch,
        );
        debug_assert!(done.is_ok());
    }

    /// Fourier coefficients `c_k`, k = 0..n/2 (exclusive of Nyquist), of the trigonometric
    /// interpolant `f(u) = Σ c_k e^{iku}` of real samples (negative k are conjugates).
    pub(crate) fn coefficients(&mut self, f: &[f64]) -> Vec<Complex64> {
        let n = self.n;
        self.transform(f);
        self.spectrum[..n.div_ceil(2)]
            .iter()
            .map(|c| c / n as f64)
            .collect()
    }

    /// `out[j] = ∫_0^{u_j} f(u) du` for `f` sampled at `u_j = j·2π/n`, spectrally accurate
    /// for smooth periodic `f`. Returns the mean of `f` (the drift per radian).
    ///
    /// The periodic part is integrated term by term in the trigonometric interpolant;
    /// the Nyquist term (even `n`) is dropped, as its integral is not determined by the samples.
    pub(crate) fn cumulative(&mut self, f: &[f64], out: &mut [f64]) -> f64 {
        let n = self.n;
        assert!(
            f.len() == n && out.len() == n,
            "sample count must match the plan"
        );
        self.transform(f);
        let mean = self.spectrum[0].re / n as f64;
        self.spectrum[0] = Complex64::default();
        let factors = &self.integral_factors[..self.spectrum.len()];
        for (k, &factor) in factors.iter().enumerate().skip(1) {
            let c = &mut self.spectrum[k];
            *c = if 2 * k == n {
                Complex64::default()
            } else {
                // Divide by i·k: (x + i y)/(i k) = (y - i x)/k.
                Complex64::new(c.im, -c.re) * factor
            };
        }
        // The spectrum's zero and Nyquist terms are real (set to 0 above): cannot fail.
        let done = (self.inverse).process_with_scratch(
            &mut self.spectrum,
            &mut self.real,
            &mut self.scratch,
        );
        debug_assert!(done.is_ok());
        let p0 = self.real[0];
        let h = std::f64::consts::TAU / n as f64;
        for (j, (o, b)) in out.iter_mut().zip(&self.real).enumerate() {
            *o = mean * h * node_index(j) + b - p0;
        }
        mean
    }
}

/// The quintic Hermite interpolant on one cell of width `h`, from values, first and second
/// derivatives at both ends, as a polynomial in the cell position `s ∈ [0, 1]`: built once,
/// evaluated by Estrin's scheme. On [`Lanes`]: one cell, or two side by side.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuinticCell<T = f64> {
    /// Coefficients of `s⁰..s⁵`.
    c: [T; 6],
    h: T,
}

impl<T: Lanes> QuinticCell<T> {
    #[inline]
    pub(crate) fn new(y: [T; 2], d1: [T; 2], d2: [T; 2], h: T) -> Self {
        let k = T::splat;
        let (rise, p0, p1) = (y[1] - y[0], h * d1[0], h * d1[1]);
        let (q0, q1) = (k(0.5) * h * h * d2[0], k(0.5) * h * h * d2[1]);
        Self {
            c: [
                y[0],
                p0,
                q0,
                k(10.0) * rise - k(6.0) * p0 - k(4.0) * p1 - k(3.0) * q0 + q1,
                k(-15.0) * rise + k(8.0) * p0 + k(7.0) * p1 + k(3.0) * q0 - k(2.0) * q1,
                k(6.0) * rise - k(3.0) * p0 - k(3.0) * p1 - q0 + q1,
            ],
            h,
        }
    }

    /// The value at cell position `s`.
    #[inline]
    fn value_in_cell(&self, s: T) -> T {
        let c = &self.c;
        // Estrin's scheme: half the dependent multiply-adds of Horner's rule.
        let s2 = s * s;
        (c[0] + c[1] * s) + s2 * ((c[2] + c[3] * s) + s2 * (c[4] + c[5] * s))
    }
}

impl QuinticCell {
    /// The value and its derivative per unit of the abscissa at cell position `s`.
    #[inline]
    pub(crate) fn eval(&self, s: f64) -> (f64, f64) {
        let (value, per_cell) = self.eval_in_cell(s);
        (value, per_cell / self.h)
    }

    /// The value and its derivative in `s` (per cell width) at cell position `s`.
    #[inline]
    fn eval_in_cell(&self, s: f64) -> (f64, f64) {
        let c = &self.c;
        let slope = c[1] + s * (2.0 * c[2] + s * (3.0 * c[3] + s * (4.0 * c[4] + s * 5.0 * c[5])));
        (self.value_in_cell(s), slope)
    }
}

/// A strictly increasing function with periodic derivative (`F(u + 2π) = F(u) + drift·2π`),
/// known at uniform nodes with its first two derivatives: interpolated by quintic Hermite
/// cells, evaluated at any real argument; [`DriftInverse`] inverts it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MonotoneDrift<'a> {
    /// Node values `F(u_j)`, `u_j = j·h`.
    pub value: &'a [f64],
    /// `F'(u_j)` (strictly positive).
    pub d1: &'a [f64],
    /// `F''(u_j)`.
    pub d2: &'a [f64],
    /// `F(2π) - F(0)`.
    pub period_increment: f64,
}

impl MonotoneDrift<'_> {
    fn h(&self) -> f64 {
        std::f64::consts::TAU / self.value.len() as f64
    }

    /// Node data of cell `j` (wrapping to the next period at the end).
    #[inline]
    fn cell(&self, j: usize) -> ([f64; 2], [f64; 2], [f64; 2]) {
        let n = self.value.len();
        let (j1, lift) = if j + 1 == n {
            (0, self.period_increment)
        } else {
            (j + 1, 0.0)
        };
        (
            [self.value[j], self.value[j1] + lift],
            [self.d1[j], self.d1[j1]],
            [self.d2[j], self.d2[j1]],
        )
    }

    /// `(F(u), F'(u))` at any real `u`.
    pub(crate) fn eval(&self, u: f64) -> (f64, f64) {
        let n = self.value.len();
        let h = self.h();
        // `floor` is a library call on baseline x86-64: only beyond one period either way
        // (within one below, `floor` gives −1 exactly).
        let turns = if (0.0..std::f64::consts::TAU).contains(&u) {
            0.0
        } else if (-std::f64::consts::TAU..0.0).contains(&u) {
            -1.0
        } else {
            (u / std::f64::consts::TAU).floor()
        };
        let rest = u - turns * std::f64::consts::TAU;
        let j = ((rest / h) as usize).min(n - 1);
        let (y, d1, d2) = self.cell(j);
        let (v, s) = QuinticCell::new(y, d1, d2, h).eval((rest - node_index(j) * h) / h);
        (v + turns * self.period_increment, s)
    }
}

/// The inverse `F⁻¹` of a [`MonotoneDrift`], interpolated directly rather than solved for:
/// quintic Hermite cells on the non-uniform abscissae `[F(u_j), F(u_{j+1})]`, from
/// `(F⁻¹)' = 1/F'` and `(F⁻¹)'' = −F''/F'³` at the nodes. No Newton iteration; its error is
/// O(h⁶), the same order as the forward interpolant's.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DriftInverse<'a> {
    /// The function being inverted (its node values are the inverse's abscissae).
    pub forward: MonotoneDrift<'a>,
    /// `1/F'(u_j)`.
    pub d1: &'a [f64],
    /// `−F''(u_j)/F'(u_j)³`.
    pub d2: &'a [f64],
}

impl DriftInverse<'_> {
    /// The inverse's node derivatives `(1/F', −F''/F'³)` from the forward ones.
    #[inline]
    pub(crate) fn node_derivatives(d1: f64, d2: f64) -> (f64, f64) {
        let r = 1.0 / d1;
        (r, -d2 * r * r * r)
    }

    /// The `u` with `F(u) = target`, starting the cell search at `hint` (a node index);
    /// returns `(u, cell)` so that sorted targets cost O(1) each.
    #[inline(always)]
    pub(crate) fn eval(&self, target: f64, hint: usize) -> (f64, usize) {
        let located = self.locate(target, hint);
        (self.at(located), located.cell)
    }

    /// Whether `F`'s node values rise strictly over the period (then each value of one
    /// period lies in exactly one cell, which a cell search finds from any start).
    pub(crate) fn rises_strictly(&self) -> bool {
        let (value, period) = (self.forward.value, self.forward.period_increment);
        value.windows(2).all(|w| w[0] < w[1])
            && value.last().is_some_and(|&last| last < value[0] + period)
    }

    /// `F⁻¹(t − offset)` at each of the ascending `targets`, each bit for bit
    /// [`DriftInverse::eval`] with the cell of the one before as its hint (node 0 for the
    /// first). Where the node values rise strictly, each cell is found by a merge, forward
    /// from the one before ([`DriftInverse::locate_after`]); the values are then taken two
    /// at a time in vector lanes.
    pub(crate) fn eval_ascending(&self, targets: &[f64], offset: f64) -> Vec<f64> {
        let rises = self.rises_strictly();
        let mut previous = 0;
        let mut locate = |t: f64| {
            let located = self.locate_after(t - offset, previous, rises);
            previous = located.cell;
            located
        };
        let mut out = vec![0.0; targets.len()];
        let (pairs, tail) = targets.as_chunks::<2>();
        let (out_pairs, out_tail) = out.as_chunks_mut::<2>();
        for (o, &[a, b]) in out_pairs.iter_mut().zip(pairs) {
            let located = [locate(a), locate(b)];
            *o = self.at_pair(located);
        }
        for (o, &t) in out_tail.iter_mut().zip(tail) {
            *o = self.at(locate(t));
        }
        out
    }

    /// Where `target` lies, its cell walked to from `hint`.
    #[inline(always)]
    fn locate(&self, target: f64, hint: usize) -> Located {
        let (turns, rest) = self.turns_and_rest(target);
        Located {
            turns,
            rest,
            cell: self.cell_from(rest, hint),
        }
    }

    /// As [`DriftInverse::locate`] with the hint `previous`, for ascending targets with
    /// `previous` the cell of the one before. Where `rises` ([`DriftInverse::rises_strictly`]:
    /// one cell holds each value) the cell is found by a merge, forward from `previous`
    /// (from the first cell once the targets pass into the next period), and is the cell
    /// the walk finds; where the merge finds none, or without `rises`, the walk runs.
    #[inline(always)]
    fn locate_after(&self, target: f64, previous: usize, rises: bool) -> Located {
        let value = self.forward.value;
        if rises && previous < value.len() {
            let (turns, rest) = self.turns_and_rest(target);
            let mut j = if rest < value[previous] { 0 } else { previous };
            // Forward up to four cells at a time, counted by comparisons rather than
            // branched on: sorted targets come about a cell apart, so a branch per cell
            // went the other way about once a target. The values rise strictly, so the
            // cells at or below `rest` come first, and their count is the step.
            loop {
                let below = |k: usize| usize::from(value.get(j + k).is_some_and(|&v| v <= rest));
                let steps = below(1) + below(2) + below(3) + below(4);
                j += steps;
                if steps < 4 {
                    break;
                }
            }
            if self.holds(j, rest) {
                return Located {
                    turns,
                    rest,
                    cell: j,
                };
            }
        }
        self.locate(target, previous)
    }

    /// Whole periods of `target` from the first node's value, and what is left within one.
    #[inline(always)]
    fn turns_and_rest(&self, target: f64) -> (f64, f64) {
        let f = &self.forward;
        let (first, period) = (f.value[0], f.period_increment);
        // Whole periods below or above the first: one either way is the usual case (and
        // `floor` is a library call on baseline x86-64).
        if target < first {
            if target >= first - period {
                (-1.0, target + period)
            } else {
                let turns = ((target - first) / period).floor();
                (turns, target - turns * period)
            }
        } else if target < first + period {
            (0.0, target)
        } else if target < first + 2.0 * period {
            (1.0, target - period)
        } else {
            let turns = ((target - first) / period).floor();
            (turns, target - turns * period)
        }
    }

    /// The cell's upper node value (the next period's first past the last node).
    #[inline(always)]
    fn upper(&self, j: usize) -> f64 {
        let f = &self.forward;
        if j + 1 == f.value.len() {
            f.value[0] + f.period_increment
        } else {
            f.value[j + 1]
        }
    }

    /// Whether cell `j`, `[F_j, F_{j+1})`, holds `rest` (false for a NaN).
    #[inline(always)]
    fn holds(&self, j: usize, rest: f64) -> bool {
        self.forward.value[j] <= rest && rest < self.upper(j)
    }

    /// Walks from `hint` to the cell `[F_j, F_{j+1})` that holds `rest` (where it gives up,
    /// after two periods of cells, when no cell holds it).
    #[inline(always)]
    fn cell_from(&self, rest: f64, hint: usize) -> usize {
        let value = self.forward.value;
        let n = value.len();
        let mut j = hint.min(n - 1);
        let mut steps = 0;
        while steps < 2 * n && !self.holds(j, rest) {
            j = if rest < value[j] {
                if j == 0 {
                    n - 1
                } else {
                    j - 1
                }
            } else if j + 1 == n {
                0
            } else {
                j + 1
            };
            steps += 1;
        }
        j
    }

    /// `F⁻¹` at a located target.
    #[inline(always)]
    fn at(&self, located: Located) -> f64 {
        let Located { turns, rest, cell } = located;
        value_in_cell(turns, rest, self.cell_data(cell))
    }

    /// [`DriftInverse::at`] at two located targets, bit for bit, in vector lanes.
    #[inline(always)]
    fn at_pair(&self, located: [Located; 2]) -> [f64; 2] {
        let lanes = |f: fn(&Located) -> f64| f64x2::new(located.each_ref().map(f));
        let [a, b] = located.map(|l| self.cell_data(l.cell));
        let data = std::array::from_fn(|r| std::array::from_fn(|c| f64x2::new([a[r][c], b[r][c]])));
        value_in_cell(lanes(|l| l.turns), lanes(|l| l.rest), data).to_array()
    }

    /// Cell `j`'s ends: the inverse's abscissae `[u_j, u_{j+1}]` (its values), `F` there
    /// (its arguments; the next period's first past the last node), and the inverse's
    /// first and second derivatives.
    #[inline(always)]
    fn cell_data(&self, j: usize) -> [[f64; 2]; 4] {
        let value = self.forward.value;
        let n = value.len();
        // Cut to the values' length: one bounds check covers all three.
        let (d1, d2) = (&self.d1[..n], &self.d2[..n]);
        let h = self.forward.h();
        let j1 = if j + 1 == n { 0 } else { j + 1 };
        [
            [node_index(j) * h, node_index(j + 1) * h],
            [value[j], self.upper(j)],
            [d1[j], d1[j1]],
            [d2[j], d2[j1]],
        ]
    }
}

/// Where a target of a [`DriftInverse`] lies: whole periods from the first node's value,
/// the rest within one, and the cell that holds the rest.
#[derive(Debug, Clone, Copy)]
struct Located {
    turns: f64,
    rest: f64,
    cell: usize,
}

/// `F⁻¹` at `rest`, `turns` periods on, in the cell of `data` ([`DriftInverse::cell_data`]),
/// on one target or two in lanes.
#[inline(always)]
fn value_in_cell<T: Lanes>(turns: T, rest: T, data: [[T; 2]; 4]) -> T {
    let [u, y, d1, d2] = data;
    let width = y[1] - y[0];
    let s = ((rest - y[0]) / width).clamp_unit();
    turns * T::splat(std::f64::consts::TAU) + QuinticCell::new(u, d1, d2, width).value_in_cell(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn cumulative_integral_of_smooth_function_is_spectral() {
        let n = 64;
        let mut integ = SpectralIntegrator::new(n);
        let f: Vec<f64> = (0..n)
            .map(|j| {
                let u = TAU * j as f64 / n as f64;
                1.5 + (3.0 * u).cos() + 0.5 * u.sin()
            })
            .collect();
        let mut out = vec![0.0; n];
        let mean = integ.cumulative(&f, &mut out);
        assert!((mean - 1.5).abs() < 1e-14);
        for (j, o) in out.iter().enumerate() {
            let u = TAU * j as f64 / n as f64;
            let exact = 1.5 * u + (3.0 * u).sin() / 3.0 + 0.5 * (1.0 - u.cos());
            assert!((o - exact).abs() < 1e-13, "{j}: {o} vs {exact}");
        }
    }

    #[test]
    fn quintic_cell_reproduces_quintics() {
        let p = |u: f64| {
            0.3 - 1.2 * u + 0.7 * u.powi(2) + 2.0 * u.powi(3) - 0.9 * u.powi(4) + 0.4 * u.powi(5)
        };
        let dp = |u: f64| -1.2 + 1.4 * u + 6.0 * u.powi(2) - 3.6 * u.powi(3) + 2.0 * u.powi(4);
        let ddp = |u: f64| 1.4 + 12.0 * u - 10.8 * u.powi(2) + 8.0 * u.powi(3);
        let (u0, h) = (0.4, 0.7);
        let u1 = u0 + h;
        let cell = QuinticCell::new([p(u0), p(u1)], [dp(u0), dp(u1)], [ddp(u0), ddp(u1)], h);
        for k in 0..=10 {
            let s = k as f64 / 10.0;
            let (v, slope) = cell.eval(s);
            assert!((v - p(u0 + s * h)).abs() < 1e-13, "{s}");
            assert!((slope - dp(u0 + s * h)).abs() < 1e-12, "{s}");
        }
    }

    /// Node data of `F(u) = u + c sin u` (monotone for |c| < 1, drift 1) at `n` nodes, with
    /// the inverse's node derivatives.
    fn sine_drift(n: usize, c: f64) -> [Vec<f64>; 5] {
        let u = |j: usize| TAU * j as f64 / n as f64;
        let v = (0..n).map(|j| u(j) + c * u(j).sin()).collect();
        let d1: Vec<f64> = (0..n).map(|j| 1.0 + c * u(j).cos()).collect();
        let d2: Vec<f64> = (0..n).map(|j| -c * u(j).sin()).collect();
        let (i1, i2) = d1
            .iter()
            .zip(&d2)
            .map(|(&a, &b)| DriftInverse::node_derivatives(a, b))
            .unzip();
        [v, d1, d2, i1, i2]
    }

    #[test]
    fn monotone_drift_interpolates_and_inverse_round_trips() {
        let c = 0.3;
        let [v, d1, d2, i1, i2] = sine_drift(48, c);
        let forward = MonotoneDrift {
            value: &v,
            d1: &d1,
            d2: &d2,
            period_increment: TAU,
        };
        let inverse = DriftInverse {
            forward,
            d1: &i1,
            d2: &i2,
        };
        for k in -30..90 {
            let u = 0.173 * k as f64;
            let (val, slope) = forward.eval(u);
            assert!((val - (u + c * u.sin())).abs() < 1e-8);
            assert!((slope - (1.0 + c * u.cos())).abs() < 1e-6);
            let (back, _) = inverse.eval(u + c * u.sin(), 0);
            assert!((back - u).abs() < 1e-8, "{u} -> {back}");
        }
        // At the nodes the inverse is exact, from any hint.
        for (j, &y) in v.iter().enumerate() {
            let (back, cell) = inverse.eval(y, (j * 7) % v.len());
            assert_eq!(cell, j);
            assert!((back - TAU * j as f64 / 48.0).abs() < 1e-14);
        }
    }

    #[test]
    fn inverse_converges_at_sixth_order() {
        // Worst error of F⁻¹ over many targets, at n and 2n nodes, for a strongly varying F.
        let c = 0.8;
        let worst = |n: usize| {
            let [v, d1, d2, i1, i2] = sine_drift(n, c);
            let inverse = DriftInverse {
                forward: MonotoneDrift {
                    value: &v,
                    d1: &d1,
                    d2: &d2,
                    period_increment: TAU,
                },
                d1: &i1,
                d2: &i2,
            };
            (0..997)
                .map(|k| {
                    let u = -1.0 + 0.0137 * k as f64;
                    (inverse.eval(u + c * u.sin(), 0).0 - u).abs()
                })
                .fold(0.0, f64::max)
        };
        let (coarse, fine) = (worst(64), worst(128));
        let order = (coarse / fine).log2();
        assert!(
            order > 5.5 && fine < 1e-8,
            "order {order} ({coarse:e} -> {fine:e})"
        );
    }

    proptest::proptest! {
        /// The merge over ascending targets (`eval_ascending`, its values in lanes) finds
        /// the walk's values bit for bit: targets `F(u_j) − delay` over two periods and a
        /// half, as the planet's lag takes them (and `stride` nodes apart, so that the merge
        /// steps over several cells at once; an odd or even count, so that the last may be
        /// taken alone), and on drifts whose nodes do not rise it leaves them to the walk.
        #[test]
        fn merge_over_ascending_targets_is_the_walk(
            n in 12usize..200,
            c in -0.95f64..0.95,
            delay in 0.0f64..TAU,
            offset in 0usize..200,
            stride in 1usize..11,
        ) {
            let [v, d1, d2, i1, i2] = sine_drift(n, c);
            let inverse = |value| DriftInverse {
                forward: MonotoneDrift { value, d1: &d1, d2: &d2, period_increment: TAU },
                d1: &i1,
                d2: &i2,
            };
            let smooth = inverse(&v);
            proptest::prop_assert!(smooth.rises_strictly());
            // A node moved to just below the one before it (node 0 to just below the
            // last, far above node 1): no longer rising.
            let mut dented = v.clone();
            dented[offset % n] = dented[(offset + n - 1) % n] - 1e-3;
            let dented_inverse = inverse(&dented);
            proptest::prop_assert!(!dented_inverse.rises_strictly());
            let targets: Vec<f64> = (0..5 * n / 2)
                .step_by(stride)
                .map(|k| v[(k + offset) % n] + TAU * ((k + offset) / n) as f64)
                .collect();
            for inv in [smooth, dented_inverse] {
                let merged = inv.eval_ascending(&targets, delay);
                let mut walked = 0;
                for (&target, a) in targets.iter().zip(merged) {
                    let (b, cell) = inv.eval(target - delay, walked);
                    proptest::prop_assert_eq!(a.to_bits(), b.to_bits(), "target {}", target);
                    walked = cell;
                }
            }
        }
    }
}
