//! Closed curves given as Cartesian control points (B-spline, Bézier), read in polar form.

use crate::curve::{Polar, TAU};
use crate::error::{Error, Result};
use crate::vec2::Vec2;

/// Which closed Cartesian construction the control points feed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CartesianKind {
    /// Closed uniform cubic B-spline (approximating, C²).
    BSpline,
    /// One closed Bézier curve of degree n, `P_n = P_0` (corner at `P_0` in general).
    Bezier,
}

impl CartesianKind {
    fn name(self) -> &'static str {
        match self {
            CartesianKind::BSpline => "bspline",
            CartesianKind::Bezier => "bezier",
        }
    }
}

/// A star-shaped closed Cartesian curve, evaluated as `rho(psi)` by inverting its polar angle.
#[derive(Debug, Clone, PartialEq)]
pub struct CartesianCurve {
    kind: CartesianKind,
    points: Vec<Vec2>,
    /// Parameter range `[0, t_end)`: n for the B-spline, 1 for the Bézier curve.
    t_end: f64,
    /// Monotone table `(t, unwrapped psi)` used to bracket the inversion.
    table_t: Vec<f64>,
    table_psi: Vec<f64>,
}

/// Position and first two parameter derivatives of a Cartesian curve.
struct Jet {
    p: Vec2,
    d1: Vec2,
    d2: Vec2,
}

/// Most control points of a Bézier curve (see [`CartesianCurve::new`]).
pub(crate) const MAX_BEZIER_POINTS: usize = 64;

/// Table samples per B-spline segment (and `8 n` for the Bézier curve) used to bracket `t(psi)`.
const TABLE_PER_SEGMENT: usize = 32;

impl CartesianCurve {
    /// Builds the curve from control points `(x, y)` in mm, checking star-shapedness. A
    /// Bézier curve takes at most [`MAX_BEZIER_POINTS`]: its cost grows as the cube of
    /// their count, and a point pulls the curve by at most 1/√(2π n t(1−t)) of its own
    /// move, a tenth at the middle of a degree-64 curve.
    pub fn new(kind: CartesianKind, points: Vec<Vec2>) -> Result<Self> {
        let n = points.len();
        if n < 4 {
            return Err(Error::TooFewPoints {
                kind: kind.name(),
                min: 4,
                got: n,
            });
        }
        if kind == CartesianKind::Bezier && n > MAX_BEZIER_POINTS {
            return Err(Error::TooManyPoints {
                kind: kind.name(),
                max: MAX_BEZIER_POINTS,
                got: n,
                why: "one Bézier curve of degree n costs n² per point and n³ to build (1 000 \
                      points took 31 s), and each point moves it less as n grows; for a \
                      finer curve use kind = \"bspline\" or \"spline\"",
            });
        }
        let t_end = match kind {
            CartesianKind::BSpline => n as f64,
            CartesianKind::Bezier => 1.0,
        };
        let m = TABLE_PER_SEGMENT * n;
        let mut curve = Self {
            kind,
            points,
            t_end,
            table_t: Vec::with_capacity(m + 1),
            table_psi: Vec::with_capacity(m + 1),
        };
        let mut previous = f64::NAN;
        for j in 0..=m {
            let t = t_end * j as f64 / m as f64;
            let jet = curve.jet(t);
            let Vec2 { x, y } = jet.p;
            let r2 = jet.p.hypot2();
            let psi_t = jet.p.cross(jet.d1) / r2;
            if r2 == 0.0 || psi_t.is_nan() || psi_t <= 0.0 {
                return Err(Error::NotStarShaped {
                    kind: kind.name(),
                    x_mm: x,
                    y_mm: y,
                });
            }
            let mut psi = y.atan2(x);
            if j > 0 {
                psi = previous + (psi - previous + std::f64::consts::PI).rem_euclid(TAU)
                    - std::f64::consts::PI;
                if psi <= previous {
                    return Err(Error::NotStarShaped {
                        kind: kind.name(),
                        x_mm: x,
                        y_mm: y,
                    });
                }
            }
            previous = psi;
            curve.table_t.push(t);
            curve.table_psi.push(psi);
        }
        let winding = curve.table_psi[m] - curve.table_psi[0];
        if (winding - TAU).abs() > 1e-9 {
            let Vec2 { x, y } = curve.jet(0.0).p;
            return Err(Error::NotStarShaped {
                kind: kind.name(),
                x_mm: x,
                y_mm: y,
            });
        }
        Ok(curve)
    }

    fn jet(&self, t: f64) -> Jet {
        match self.kind {
            CartesianKind::BSpline => self.bspline_jet(t),
            CartesianKind::Bezier => self.bezier_jet(t),
        }
    }

    fn bspline_jet(&self, t: f64) -> Jet {
        let n = self.points.len();
        let t = t.rem_euclid(n as f64);
        let i = (t.floor() as usize).min(n - 1);
        let u = t - i as f64;
        let (u2, u3) = (u * u, u * u * u);
        let b = [
            (1.0 - u).powi(3) / 6.0,
            (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0,
            (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0,
            u3 / 6.0,
        ];
        let db = [
            -(1.0 - u).powi(2) / 2.0,
            (3.0 * u2 - 4.0 * u) / 2.0,
            (-3.0 * u2 + 2.0 * u + 1.0) / 2.0,
            u2 / 2.0,
        ];
        let ddb = [1.0 - u, 3.0 * u - 2.0, -3.0 * u + 1.0, u];
        let mut jet = Jet {
            p: Vec2::ZERO,
            d1: Vec2::ZERO,
            d2: Vec2::ZERO,
        };
        for k in 0..4 {
            let q = self.points[(i + k + n - 1) % n];
            jet.p = axpy(b[k], q, jet.p);
            jet.d1 = axpy(db[k], q, jet.d1);
            jet.d2 = axpy(ddb[k], q, jet.d2);
        }
        jet
    }

    fn bezier_jet(&self, t: f64) -> Jet {
        // Control polygon P_0..P_{n-1}, P_n = P_0; de Casteljau down to degree 2 gives the jet.
        let n = self.points.len();
        let mut q: Vec<Vec2> = self
            .points
            .iter()
            .copied()
            .chain(std::iter::once(self.points[0]))
            .collect();
        let t = t.clamp(0.0, 1.0);
        let degree = n as f64;
        for level in (3..=n).rev() {
            for j in 0..level {
                q[j] = lerp(q[j], q[j + 1], t);
            }
        }
        // q[0..3] now span the last quadratic stage.
        let (a, b, d) = (q[0], q[1], q[2]);
        let (l0, l1) = (lerp(a, b, t), lerp(b, d, t));
        let second = axpy(-2.0, b, a + d);
        let scale = degree * (degree - 1.0);
        Jet {
            p: lerp(l0, l1, t),
            d1: (l1 - l0) * degree,
            d2: second * scale,
        }
    }

    /// rho and its first two psi-derivatives at `psi` (rad).
    pub fn eval(&self, psi: f64) -> Polar {
        let psi0 = self.table_psi[0];
        let target = psi0 + (psi - psi0).rem_euclid(TAU);
        let j = self
            .table_psi
            .partition_point(|&p| p <= target)
            .clamp(1, self.table_psi.len() - 1);
        let (mut lo, mut hi) = (self.table_t[j - 1], self.table_t[j]);
        let (psi_lo, psi_hi) = (self.table_psi[j - 1], self.table_psi[j]);
        let mut t = lo + (hi - lo) * (target - psi_lo) / (psi_hi - psi_lo);
        // Safeguarded Newton on psi(t) = target within the bracket.
        let unwrap = psi_lo - psi_lo.rem_euclid(TAU);
        for _ in 0..60 {
            let jet = self.jet(t);
            let Vec2 { x, y } = jet.p;
            let r2 = jet.p.hypot2();
            let mut psi_t_val = y.atan2(x).rem_euclid(TAU) + unwrap;
            if psi_t_val < psi_lo - std::f64::consts::PI {
                psi_t_val += TAU;
            } else if psi_t_val > psi_hi + std::f64::consts::PI {
                psi_t_val -= TAU;
            }
            let f = psi_t_val - target;
            if f.abs() <= 1e-15 * (target.abs() + 1.0) {
                break;
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let psi_t = jet.p.cross(jet.d1) / r2;
            let mut next = t - f / psi_t;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            let converged = (next - t).abs() <= 1e-15 * self.t_end.max(1.0);
            t = next;
            if converged || hi - lo <= 1e-15 * self.t_end {
                break;
            }
        }
        polar_from_jet(&self.jet(t))
    }
}

/// `s x + y`.
#[inline]
fn axpy(s: f64, x: Vec2, y: Vec2) -> Vec2 {
    x * s + y
}

/// `(1 - t) a + t b`.
#[inline]
fn lerp(a: Vec2, b: Vec2, t: f64) -> Vec2 {
    a * (1.0 - t) + b * t
}

/// Polar `(rho, rho', rho'')` from a Cartesian jet, by the chain rule in `t`.
fn polar_from_jet(jet: &Jet) -> Polar {
    let Vec2 { x, y } = jet.p;
    let Vec2 { x: dx, y: dy } = jet.d1;
    let Vec2 { x: ddx, y: ddy } = jet.d2;
    let r = x.hypot(y);
    let r2 = r * r;
    let psi_t = (x * dy - y * dx) / r2;
    let r_t = (x * dx + y * dy) / r;
    let psi_tt = (x * ddy - y * ddx) / r2 - 2.0 * psi_t * r_t / r;
    let r_tt = (dx * dx + dy * dy + x * ddx + y * ddy) / r - r_t * r_t / r;
    Polar {
        rho: r,
        d1: r_t / psi_t,
        d2: (r_tt * psi_t - r_t * psi_tt) / psi_t.powi(3),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon(n: usize, r: f64) -> Vec<Vec2> {
        (0..n)
            .map(|i| {
                let a = TAU * i as f64 / n as f64;
                Vec2::new(r * a.cos(), r * a.sin())
            })
            .collect()
    }

    #[test]
    fn bspline_of_regular_polygon_is_nearly_circular_and_derivatives_match() {
        let c = CartesianCurve::new(CartesianKind::BSpline, polygon(12, 50.0)).unwrap();
        // At a vertex the uniform cubic B-spline sits at (P_{i-1} + 4 P_i + P_{i+1}) / 6.
        let vertex = 50.0 * (4.0 + 2.0 * (TAU / 12.0).cos()) / 6.0;
        assert!((c.eval(TAU / 12.0).rho - vertex).abs() < 1e-12);
        for k in 0..50 {
            let psi = 0.123 * k as f64;
            let p = c.eval(psi);
            assert!(p.rho > 47.7 && p.rho < 50.0, "rho {}", p.rho);
            let h = 1e-5;
            let fd1 = (c.eval(psi + h).rho - c.eval(psi - h).rho) / (2.0 * h);
            let fd2 = (c.eval(psi + h).d1 - c.eval(psi - h).d1) / (2.0 * h);
            assert!((fd1 - p.d1).abs() < 1e-5, "{fd1} vs {}", p.d1);
            assert!((fd2 - p.d2).abs() < 1e-4, "{fd2} vs {}", p.d2);
        }
    }

    #[test]
    fn bezier_passes_through_first_point_and_inverts_angle() {
        let pts = polygon(8, 40.0);
        let c = CartesianCurve::new(CartesianKind::Bezier, pts.clone()).unwrap();
        assert!((c.eval(0.0).rho - 40.0).abs() < 1e-9);
        // By symmetry of the regular polygon about the x axis, rho(psi) = rho(-psi).
        for k in 1..20 {
            let psi = 0.15 * k as f64;
            assert!((c.eval(psi).rho - c.eval(-psi).rho).abs() < 1e-9);
        }
    }

    #[test]
    fn centre_outside_is_not_star_shaped() {
        let pts: Vec<Vec2> = polygon(8, 10.0)
            .iter()
            .map(|&p| p + Vec2::new(30.0, 0.0))
            .collect();
        assert!(matches!(
            CartesianCurve::new(CartesianKind::BSpline, pts),
            Err(Error::NotStarShaped { .. })
        ));
    }
}
