//! Periodic quadrature on uniform grids: spectral cumulative integrals and Hermite interpolation.

use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Spectral cumulative integration of periodic samples on a uniform grid.
///
/// Holds the FFT plans and scratch buffers so that repeated use allocates nothing.
#[derive(Clone)]
pub struct SpectralIntegrator {
    n: usize,
    forward: Arc<dyn Fft<f64>>,
    inverse: Arc<dyn Fft<f64>>,
    buffer: Vec<Complex64>,
    scratch: Vec<Complex64>,
}

impl std::fmt::Debug for SpectralIntegrator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SpectralIntegrator({})", self.n)
    }
}

impl SpectralIntegrator {
    /// Plans transforms of length `n` (samples per period).
    pub fn new(n: usize) -> Self {
        let mut planner = FftPlanner::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        let scratch_len = forward
            .get_inplace_scratch_len()
            .max(inverse.get_inplace_scratch_len());
        Self {
            n,
            forward,
            inverse,
            buffer: vec![Complex64::default(); n],
            scratch: vec![Complex64::default(); scratch_len],
        }
    }

    /// Samples per period this integrator was planned for.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether the planned length is zero.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Fourier coefficients `c_k`, k = 0..n/2 (exclusive of Nyquist), of the trigonometric
    /// interpolant `f(u) = Σ c_k e^{iku}` of real samples (negative k are conjugates).
    pub fn coefficients(&mut self, f: &[f64]) -> Vec<Complex64> {
        let n = self.n;
        for (b, &v) in self.buffer.iter_mut().zip(f) {
            *b = Complex64::new(v, 0.0);
        }
        self.forward
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        self.buffer[..n.div_ceil(2)]
            .iter()
            .map(|c| c / n as f64)
            .collect()
    }

    /// `out[j] = ∫_0^{u_j} f(u) du` for `f` sampled at `u_j = j·2π/n`, spectrally accurate
    /// for smooth periodic `f`. Returns the mean of `f` (the drift per radian).
    ///
    /// The periodic part is integrated term by term in the trigonometric interpolant;
    /// the Nyquist term (even `n`) is dropped, as its integral is not determined by the samples.
    pub fn cumulative(&mut self, f: &[f64], out: &mut [f64]) -> f64 {
        let n = self.n;
        assert!(
            f.len() == n && out.len() == n,
            "sample count must match the plan"
        );
        for (b, &v) in self.buffer.iter_mut().zip(f) {
            *b = Complex64::new(v, 0.0);
        }
        self.forward
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        let mean = self.buffer[0].re / n as f64;
        self.buffer[0] = Complex64::default();
        let scale = 1.0 / n as f64;
        for k in 1..n {
            let wave = if 2 * k < n {
                k as f64
            } else if 2 * k > n {
                k as f64 - n as f64
            } else {
                self.buffer[k] = Complex64::default();
                continue;
            };
            // Divide by i·k: (x + i y)/(i k) = (y - i x)/k.
            let c = self.buffer[k];
            self.buffer[k] = Complex64::new(c.im, -c.re) * (scale / wave);
        }
        self.inverse
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        let p0 = self.buffer[0].re;
        let h = std::f64::consts::TAU / n as f64;
        for (j, (o, b)) in out.iter_mut().zip(&self.buffer).enumerate() {
            *o = mean * h * j as f64 + b.re - p0;
        }
        mean
    }
}

/// The quintic Hermite interpolant on one cell of width `h`, from values, first and second
/// derivatives at both ends, as a polynomial in the cell position `s ∈ [0, 1]`: built once,
/// evaluated by Horner's rule.
#[derive(Debug, Clone, Copy)]
pub struct QuinticCell {
    /// Coefficients of `s⁰..s⁵`.
    c: [f64; 6],
    h: f64,
}

impl QuinticCell {
    #[inline]
    pub fn new(y: [f64; 2], d1: [f64; 2], d2: [f64; 2], h: f64) -> Self {
        let (rise, p0, p1) = (y[1] - y[0], h * d1[0], h * d1[1]);
        let (q0, q1) = (0.5 * h * h * d2[0], 0.5 * h * h * d2[1]);
        Self {
            c: [
                y[0],
                p0,
                q0,
                10.0 * rise - 6.0 * p0 - 4.0 * p1 - 3.0 * q0 + q1,
                -15.0 * rise + 8.0 * p0 + 7.0 * p1 + 3.0 * q0 - 2.0 * q1,
                6.0 * rise - 3.0 * p0 - 3.0 * p1 - q0 + q1,
            ],
            h,
        }
    }

    /// The value and its derivative per unit of the abscissa at cell position `s`.
    #[inline]
    pub fn eval(&self, s: f64) -> (f64, f64) {
        let (value, per_cell) = self.eval_in_cell(s);
        (value, per_cell / self.h)
    }

    /// The value and its derivative in `s` (per cell width) at cell position `s`.
    #[inline]
    fn eval_in_cell(&self, s: f64) -> (f64, f64) {
        let c = &self.c;
        let value = c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))));
        let slope = c[1] + s * (2.0 * c[2] + s * (3.0 * c[3] + s * (4.0 * c[4] + s * 5.0 * c[5])));
        (value, slope)
    }
}

/// Starting point in `s ∈ [0, 1]` for inverting one monotone cell at `target`: the cubic
/// Hermite interpolant of the inverse function, whose end slopes are `1/F'`. Its error is
/// O(h⁴), so one Newton step from it reaches rounding level.
#[inline]
fn inverse_hermite_guess(y: [f64; 2], d1: [f64; 2], h: f64, target: f64) -> f64 {
    let rise = y[1] - y[0];
    let t = ((target - y[0]) / rise).clamp(0.0, 1.0);
    // Slopes of s(t), the inverse in cell units: ds/dt = rise / (h F').
    let (m0, m1) = (rise / (h * d1[0]), rise / (h * d1[1]));
    let (t2, t3) = (t * t, t * t * t);
    let s = (t3 - 2.0 * t2 + t) * m0 + (3.0 * t2 - 2.0 * t3) + (t3 - t2) * m1;
    if s.is_finite() {
        s.clamp(0.0, 1.0)
    } else {
        t
    }
}

/// A strictly increasing function with periodic derivative (`F(u + 2π) = F(u) + drift·2π`),
/// known at uniform nodes with its first two derivatives: interpolated by quintic Hermite
/// cells, evaluated and inverted at any real argument.
#[derive(Debug, Clone, Copy)]
pub struct MonotoneDrift<'a> {
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
    pub fn eval(&self, u: f64) -> (f64, f64) {
        let n = self.value.len();
        let h = self.h();
        let turns = (u / std::f64::consts::TAU).floor();
        let rest = u - turns * std::f64::consts::TAU;
        let j = ((rest / h) as usize).min(n - 1);
        let (y, d1, d2) = self.cell(j);
        let (v, s) = QuinticCell::new(y, d1, d2, h).eval((rest - j as f64 * h) / h);
        (v + turns * self.period_increment, s)
    }

    /// The `u` with `F(u) = target`, starting the cell search at `hint` (a node index);
    /// returns `(u, cell)` so that sorted targets cost O(1) each.
    pub fn invert(&self, target: f64, hint: usize) -> (f64, usize) {
        let n = self.value.len();
        let h = self.h();
        let (first, period) = (self.value[0], self.period_increment);
        let (turns, rest) = if target >= first && target < first + period {
            (0.0, target)
        } else {
            let turns = ((target - first) / period).floor();
            (turns, target - turns * period)
        };
        // Walk from the hint to the cell [F_j, F_{j+1}) that holds `rest`.
        let mut j = hint.min(n - 1);
        let upper = |j: usize| {
            if j + 1 == n {
                first + period
            } else {
                self.value[j + 1]
            }
        };
        let mut steps = 0;
        while steps < 2 * n && !(self.value[j] <= rest && rest < upper(j)) {
            j = if rest < self.value[j] {
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
        let (y, d1, d2) = self.cell(j);
        // Safeguarded Newton in s ∈ [0, 1] from the O(h⁴) inverse-Hermite guess. It stops
        // on the residual, or once the quadratic convergence bound `|F''|/2 · Δu²` (with a
        // safety factor 4 on the nodes' |F''|) puts the next residual below the tolerance
        // (1e-13 rad, far below the interpolation's own error).
        let (mut lo, mut hi) = (0.0, 1.0);
        let mut s = inverse_hermite_guess(y, d1, h, rest);
        let quintic = QuinticCell::new(y, d1, d2, h);
        let tolerance = 1e-13 * (rest.abs() + 1.0);
        let curvature_bound = 2.0 * (d2[0].abs().max(d2[1].abs()) + (d1[1] - d1[0]).abs() / h);
        for _ in 0..60 {
            let (v, slope_in_cell) = quintic.eval_in_cell(s);
            let f = v - rest;
            if f.abs() <= tolerance {
                break;
            }
            if f > 0.0 {
                hi = s;
            } else {
                lo = s;
            }
            let newton = s - f / slope_in_cell;
            let is_newton = newton > lo && newton < hi && newton.is_finite();
            let next = if is_newton { newton } else { 0.5 * (lo + hi) };
            let du = (next - s) * h;
            s = next;
            if du.abs() < 1e-15 * h || (is_newton && curvature_bound * du * du <= tolerance) {
                break;
            }
        }
        (turns * std::f64::consts::TAU + (j as f64 + s) * h, j)
    }
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
    fn inverse_guess_converges_at_fourth_order() {
        // F(u) = u + 0.4 sin u; the guess's worst error in u over all cells, at n and 2n.
        let worst = |n: usize| {
            let h = TAU / n as f64;
            let f = |u: f64| u + 0.4 * u.sin();
            let df = |u: f64| 1.0 + 0.4 * u.cos();
            let mut worst = 0.0f64;
            for j in 0..n {
                let (u0, u1) = (j as f64 * h, (j + 1) as f64 * h);
                for k in 1..10 {
                    let u = u0 + h * k as f64 / 10.0;
                    let s = inverse_hermite_guess([f(u0), f(u1)], [df(u0), df(u1)], h, f(u));
                    worst = worst.max((u0 + s * h - u).abs());
                }
            }
            worst
        };
        let (coarse, fine) = (worst(24), worst(48));
        let order = (coarse / fine).log2();
        assert!(order > 3.7, "order {order} ({coarse:e} -> {fine:e})");
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

    #[test]
    fn monotone_drift_interpolates_and_inverse_round_trips() {
        // F(u) = u + 0.3 sin u: monotone, drift 1.
        let n = 48;
        let h = TAU / n as f64;
        let v: Vec<f64> = (0..n)
            .map(|j| j as f64 * h + 0.3 * (j as f64 * h).sin())
            .collect();
        let d1: Vec<f64> = (0..n).map(|j| 1.0 + 0.3 * (j as f64 * h).cos()).collect();
        let d2: Vec<f64> = (0..n).map(|j| -0.3 * (j as f64 * h).sin()).collect();
        let f = MonotoneDrift {
            value: &v,
            d1: &d1,
            d2: &d2,
            period_increment: TAU,
        };
        for k in -30..90 {
            let u = 0.173 * k as f64;
            let (val, slope) = f.eval(u);
            assert!((val - (u + 0.3 * u.sin())).abs() < 1e-8);
            assert!((slope - (1.0 + 0.3 * u.cos())).abs() < 1e-6);
            let (back, _) = f.invert(val, 0);
            assert!((back - u).abs() < 1e-12, "{u} -> {back}");
        }
    }
}
