//! The carrier's speed over the cycle when the drive gives a constant torque and a
//! flywheel (docs/dynamics.md, "Speed fluctuation and the flywheel").
//!
//! The train has one degree of freedom, the carrier angle `φ`. Its kinetic energy is
//! `½·I(φ)·ω²` with `I = Im(φ) + Jc + Jf`: the moving bodies' reduced inertia, the
//! carrier's own and the flywheel's; gravity and the tip's loads need the torque `Q(φ)`
//! whatever the speed. With a drive torque `Td` constant over the turn (the mean the cycle
//! needs, `Td = mean Q`), the energy balance integrates in closed form:
//! `½·I(φ)·ω(φ)² = E0 + ∫₀^φ (Td − Q) dφ`, and `E0` is the one root that gives the working
//! speed as the turn's mean speed (`2π` over the turn's duration). The coefficient of
//! speed fluctuation is `δ = (ω_max − ω_min)/ω_mean`; as `Jf` grows it tends to the
//! textbook `ΔE/(I·ω²)`.

use crate::curve::TAU;
use serde::Serialize;

/// The carrier's speed over one turn with a constant drive torque.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedFluctuation {
    /// The constant drive torque: the mean the cycle needs (N·m).
    pub drive_torque_nm: f64,
    /// The carrier's own moment of inertia and the flywheel's on its axis (kg·m²).
    pub carrier_inertia_kg_m2: f64,
    pub flywheel_inertia_kg_m2: f64,
    /// The carrier's speed at each node (rad/s); its mean over time is the working speed.
    pub carrier_speed_rad_s: Vec<f64>,
    /// `(ω_max − ω_min)/ω_mean`.
    pub coefficient: f64,
}

/// The cycle at `n` evenly spaced carrier angles: the moving bodies' reduced inertia
/// `Im` (kg·m²) and the loads' torque `Q` (N·m) at each, the working speed `omega`
/// (rad/s), the carrier's own inertia (kg·m²).
#[derive(Debug, Clone, Copy)]
pub struct Cycle<'a> {
    pub reduced_inertia_kg_m2: &'a [f64],
    pub load_torque_nm: &'a [f64],
    pub omega: f64,
    pub carrier_inertia_kg_m2: f64,
}

impl Cycle<'_> {
    /// The speed over the turn with a flywheel `flywheel` (kg·m²).
    pub fn fluctuation(&self, flywheel: f64) -> SpeedFluctuation {
        let (speed, drive) = self.speed(flywheel);
        SpeedFluctuation {
            drive_torque_nm: drive,
            carrier_inertia_kg_m2: self.carrier_inertia_kg_m2,
            flywheel_inertia_kg_m2: flywheel,
            coefficient: coefficient(&speed),
            carrier_speed_rad_s: speed,
        }
    }

    /// The carrier's speed at each node with flywheel `flywheel`, and the drive torque.
    fn speed(&self, flywheel: f64) -> (Vec<f64>, f64) {
        let n = self.load_torque_nm.len();
        let step = TAU / n as f64;
        let drive = self.load_torque_nm.iter().sum::<f64>() / n as f64;
        // W(φ_j) = ∫₀^φj (Td − Q) dφ by the trapezoid rule: it closes over the turn.
        let mut work = Vec::with_capacity(n);
        let mut w = 0.0;
        for j in 0..n {
            work.push(w);
            let next = self.load_torque_nm[(j + 1) % n];
            w += step * (drive - 0.5 * (self.load_torque_nm[j] + next));
        }
        let inertia: Vec<f64> = (self.reduced_inertia_kg_m2.iter())
            .map(|i| i + self.carrier_inertia_kg_m2 + flywheel)
            .collect();
        let speed_at = |e0: f64, j: usize| {
            let e = e0 + work[j];
            if e > 0.0 {
                (2.0 * e / inertia[j]).sqrt()
            } else {
                0.0
            }
        };
        // The turn's duration minus the working speed's, and its slope −Σ step/(ω³·I):
        // positive below the root (slower), decreasing and convex in E0.
        let lateness = |e0: f64| {
            (0..n).fold((-TAU / self.omega, 0.0), |(f, slope), j| {
                let w = speed_at(e0, j);
                (f + step / w, slope - step / (w * w * w * inertia[j]))
            })
        };
        let half_omega2 = 0.5 * self.omega * self.omega;
        let kinetic = |j: usize| half_omega2 * inertia[j] - work[j];
        // Below `lo` every node turns slower than ω (late), above `hi` faster; E0 must keep
        // every node's energy positive.
        let (lo, hi) = (0..n).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), j| {
            (l.min(kinetic(j)), h.max(kinetic(j)))
        });
        let floor = -work.iter().fold(f64::INFINITY, |m, &w| m.min(w));
        let (mut lo, mut hi) = (lo.max(floor), hi);
        // Start from the mean: close to the root when the speed varies little.
        let mut e0 = ((0..n).map(kinetic).sum::<f64>() / n as f64).clamp(lo, hi);
        for _ in 0..200 {
            let (f, slope) = lateness(e0);
            if f == 0.0 || hi - lo <= 1e-15 * hi.abs() {
                break;
            }
            if f > 0.0 {
                lo = e0;
            } else {
                hi = e0;
            }
            let newton = e0 - f / slope;
            if (newton - e0).abs() <= 1e-15 * e0.abs() {
                break;
            }
            e0 = if newton.is_finite() && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
        }
        ((0..n).map(|j| speed_at(e0, j)).collect(), drive)
    }

    /// The least flywheel (kg·m²) that holds the coefficient of speed fluctuation to
    /// `allowed`: `1/δ` grows almost linearly with the flywheel (δ ≈ ΔE/(I·ω²)), so a
    /// secant on it, kept inside a bracket.
    pub fn flywheel_for(&self, allowed: f64) -> f64 {
        let gap = |flywheel: f64| 1.0 / coefficient(&self.speed(flywheel).0) - 1.0 / allowed;
        let at_zero = gap(0.0);
        if at_zero >= 0.0 {
            return 0.0;
        }
        let (mut lo, mut f_lo) = (0.0, at_zero);
        // From the carrier's own inertia, four times larger until it holds.
        let mut hi = self.carrier_inertia_kg_m2.max(1e-9);
        let mut f_hi = gap(hi);
        while f_hi < 0.0 && hi < 1e12 {
            (lo, f_lo) = (hi, f_hi);
            hi *= 4.0;
            f_hi = gap(hi);
        }
        // The secant through the last two points (not the bracket's ends, which would stall
        // on one side), bisection when it leaves the bracket.
        let (mut a, mut f_a, mut b, mut f_b) = (lo, f_lo, hi, f_hi);
        for _ in 0..100 {
            let secant = b - f_b * (b - a) / (f_b - f_a);
            let x = if secant > lo && secant < hi {
                secant
            } else {
                0.5 * (lo + hi)
            };
            let f = gap(x);
            if f >= 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            (a, f_a, b, f_b) = (b, f_b, x, f);
            if f.abs() <= 1e-12 / allowed || hi - lo <= 1e-12 * hi {
                return x;
            }
        }
        hi
    }
}

/// `(max − min)/mean` of the speed, the mean over time (the turn's `2π` over its duration).
fn coefficient(speed: &[f64]) -> f64 {
    let (lo, hi) = (speed.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &w| {
        (l.min(w), h.max(w))
    });
    let duration = speed.iter().map(|w| 1.0 / w).sum::<f64>() / speed.len() as f64;
    (hi - lo) * duration
}
