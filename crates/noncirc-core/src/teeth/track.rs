//! The two pitch curves of a ratio-1 pair as tracks in arc length: the driver `ρ(ψ)` and
//! its conjugate, each with its point, unit tangent, outward normal and curvature at any
//! driver parameter `ψ`, and the arc length `s(ψ)` (mm) they share (rolling without slip).
//!
//! The centre distance is re-closed here by Newton on the Gauss–Legendre sum of
//! `∫ ρ/(a − ρ) dψ = 2π`, so that the conjugate gear's teeth close to the quadrature's
//! accuracy rather than to the evaluation's closure tolerance.

use crate::angle::unit;
use crate::curve::{PitchCurve, Polar, TAU};
use crate::error::{Error, Result};
use crate::gear::conjugate_polar;
use crate::quadrature::QuinticCell;
use crate::vec2::Vec2;

/// Which gear of the pair a track follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Member {
    /// The driver (sun and planets): `ρ(ψ)` at polar angle `ψ`, traversed counter-clockwise.
    Driver,
    /// Its conjugate (the intermediates): radius `a − ρ(ψ)` at its own polar angle
    /// `χ(ψ) = −∫₀^ψ ρ/(a − ρ)`, traversed clockwise as `ψ` grows; angle 0 meets `ψ = 0`.
    Driven,
}

/// A pitch curve's frame at one point: position, unit tangent (direction of growing arc
/// length), outward unit normal, signed curvature (1/mm, positive where convex).
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    pub point: Vec2,
    pub tangent: Vec2,
    pub normal: Vec2,
    pub curvature: f64,
}

/// Gauss–Legendre nodes and weights on `[0, 1]`, 4 points (exact for degree 7). Four
/// leave the tables' error to the quintic cells between nodes (on the Fourier pair, 256
/// panels: arc length 4e-12 mm with four or eight points; on the paper curve, whose
/// 1.6 mm radius of curvature is the hardest case, 9e-6 against 8e-6 mm).
const GAUSS: [(f64, f64); 4] = [
    (0.06943184420297371, 0.17392742256872679),
    (0.33000947820757187, 0.3260725774312732),
    (0.6699905217924281, 0.3260725774312732),
    (0.9305681557970262, 0.17392742256872679),
];

/// Arc length and conjugate angle of a pair, tabulated on uniform panels in `ψ` and
/// interpolated between nodes by quintic Hermite cells.
#[derive(Debug, Clone)]
pub struct PairTrack {
    curve: PitchCurve,
    /// Centre distance (mm), closed by this track's quadrature.
    a: f64,
    panels: usize,
    /// Panel width (rad) and its inverse.
    panel_width: f64,
    panels_per_radian: f64,
    /// `panels` over the perimeter (1/mm): the steps of [`Self::panel_at_arc`].
    steps_per_mm: f64,
    /// Arc length cells, one per panel.
    arc: Vec<QuinticCell>,
    /// `s` at the panel nodes (mm), `panels + 1` values.
    s_nodes: Vec<f64>,
    /// For each of `panels` equal steps of arc length, the panel where the step starts:
    /// [`Self::psi_at`] starts there rather than search `s_nodes`.
    panel_at_arc: Vec<u32>,
    /// `∫ ρ/(a − ρ) dψ` cells, one per panel.
    turn: Vec<QuinticCell>,
    /// Least curvature (1/mm) of the driver and of the driven curve over the Gauss nodes,
    /// with the `ψ` (rad) where it occurs.
    least_curvature: [(f64, f64); 2],
}

impl PairTrack {
    /// Tabulates the pair of `curve` with `panels` panels per turn, starting Newton for the
    /// centre distance at `a_guess` (mm, the evaluation's closure).
    pub fn new(curve: &PitchCurve, a_guess: f64, panels: usize) -> Result<Self> {
        let h = TAU / panels as f64;
        // The curve at every Gauss node (four a panel): the closure, both tables and the
        // least curvatures are sums or extremes over them.
        let polar: Vec<Polar> = (0..panels)
            .flat_map(|i| {
                GAUSS
                    .iter()
                    .map(move |&(x, _)| curve.eval((i as f64 + x) * h))
            })
            .collect();
        let weights = || GAUSS.iter().cycle().map(|&(_, w)| w * h);
        let a = close(polar.iter().zip(weights()), a_guess)?;
        let least = |kappa: &dyn Fn(Polar) -> f64| {
            polar
                .iter()
                .enumerate()
                .fold((f64::INFINITY, 0.0), |best, (k, &p)| {
                    let value = kappa(p);
                    if value < best.0 {
                        (
                            value,
                            (k / GAUSS.len()) as f64 * h + GAUSS[k % GAUSS.len()].0 * h,
                        )
                    } else {
                        best
                    }
                })
        };
        let least_curvature = [
            least(&|p: Polar| p.curvature()),
            least(&|p: Polar| conjugate_polar(p, a).curvature()),
        ];
        let nodes: Vec<Polar> = (0..=panels).map(|i| curve.eval(i as f64 * h)).collect();
        let (mut s_nodes, mut t_nodes) = (vec![0.0], vec![0.0]);
        let (mut s, mut t) = (0.0, 0.0);
        for panel in polar.chunks(GAUSS.len()) {
            for (p, wh) in panel.iter().zip(weights()) {
                s += wh * p.arc_rate();
                t += wh * p.rho / (a - p.rho);
            }
            s_nodes.push(s);
            t_nodes.push(t);
        }
        let arc_d = |p: Polar| {
            let r = p.arc_rate();
            (r, (p.rho * p.d1 + p.d1 * p.d2) / r)
        };
        let turn_d = |p: Polar| {
            let g = a - p.rho;
            (p.rho / g, a * p.d1 / (g * g))
        };
        let cells = |values: &[f64], d: &dyn Fn(Polar) -> (f64, f64)| -> Vec<QuinticCell> {
            (0..panels)
                .map(|i| {
                    let (d0, e0) = d(nodes[i]);
                    let (d1, e1) = d(nodes[i + 1]);
                    QuinticCell::new([values[i], values[i + 1]], [d0, d1], [e0, e1], h)
                })
                .collect()
        };
        let perimeter = s_nodes[panels];
        let mut panel = 0;
        let panel_at_arc = (0..panels)
            .map(|k| {
                let s = perimeter * k as f64 / panels as f64;
                while panel + 1 < panels && s_nodes[panel + 1] <= s {
                    panel += 1;
                }
                panel as u32
            })
            .collect();
        Ok(Self {
            panel_at_arc,
            panel_width: h,
            panels_per_radian: 1.0 / h,
            steps_per_mm: panels as f64 / perimeter,
            arc: cells(&s_nodes, &arc_d),
            turn: cells(&t_nodes, &turn_d),
            curve: curve.clone(),
            a,
            panels,
            s_nodes,
            least_curvature,
        })
    }

    /// Centre distance (mm).
    pub fn centre_distance(&self) -> f64 {
        self.a
    }

    /// Pitch perimeter (mm), shared by both gears.
    pub fn perimeter(&self) -> f64 {
        self.s_nodes[self.panels]
    }

    /// The driver's pitch curve.
    pub fn curve(&self) -> &PitchCurve {
        &self.curve
    }

    /// Splits `ψ` (rad, any real) into whole turns, panel index and cell position.
    #[inline]
    fn locate(&self, psi: f64) -> (f64, usize, f64) {
        // `floor` is a library call on baseline x86-64: only off the first turn.
        let turns = if (0.0..TAU).contains(&psi) {
            0.0
        } else {
            (psi / TAU).floor()
        };
        // (Casts through `u32`: float-`usize` conversions are longer instruction sequences.)
        let x = (psi - turns * TAU) * self.panels_per_radian;
        let i = (x as u32 as usize).min(self.panels - 1);
        (turns, i, x - i as u32 as f64)
    }

    /// Arc length `s(ψ)` (mm) from `ψ = 0`, over any number of turns.
    #[inline]
    pub fn arc(&self, psi: f64) -> f64 {
        self.arc_with_rate(psi).0
    }

    /// Arc length `s(ψ)` (mm) and its rate `ds/dψ` (mm/rad).
    #[inline]
    pub fn arc_with_rate(&self, psi: f64) -> (f64, f64) {
        let (turns, i, x) = self.locate(psi);
        let (value, rate) = self.arc[i].eval(x);
        (turns * self.perimeter() + value, rate)
    }

    /// The least curvature (1/mm; negative where concave) of `member`'s pitch curve over
    /// the arc tables' Gauss nodes (four a panel), and the `ψ` (rad) where it occurs.
    pub fn least_curvature(&self, member: Member) -> (f64, f64) {
        self.least_curvature[match member {
            Member::Driver => 0,
            Member::Driven => 1,
        }]
    }

    /// The driver parameter `ψ` (rad) at arc length `s` (mm): Newton on [`Self::arc`] from
    /// the panel's linear guess.
    pub fn psi_at(&self, s: f64) -> f64 {
        let perimeter = self.perimeter();
        let turns = if (0.0..perimeter).contains(&s) {
            0.0
        } else {
            (s / perimeter).floor()
        };
        let local = s - turns * perimeter;
        let step = ((local * self.steps_per_mm) as u32 as usize).min(self.panels - 1);
        let mut i = self.panel_at_arc[step] as usize;
        while i + 1 < self.panels && self.s_nodes[i + 1] <= local {
            i += 1;
        }
        let h = self.panel_width;
        let (s0, s1) = (self.s_nodes[i], self.s_nodes[i + 1]);
        // The root lies in panel `i`: Newton on that cell's polynomial.
        let cell = &self.arc[i];
        let mut x = (local - s0) / (s1 - s0);
        for _ in 0..8 {
            let (value, rate) = cell.eval(x);
            let step = (value - local) / (rate * h);
            x -= step;
            // Quadratic convergence: a step this small (in panel widths) leaves an error
            // of the order of its square.
            if step.abs() < 1e-7 {
                break;
            }
        }
        (i as u32 as f64 + x) * h + turns * TAU
    }

    /// The frame of `member` at driver parameter `psi` (rad), in that gear's own frame.
    #[inline]
    pub fn frame(&self, member: Member, psi: f64) -> Frame {
        let p = self.curve.eval(psi);
        // Both gears' points move at `ds/dψ = √(ρ² + ρ'²)` (no slip): one square root
        // for the tangent and, through it, the curvature's `(ρ² + ρ'²)^(3/2)`.
        let inv_rate = 1.0 / (p.rho * p.rho + p.d1 * p.d1).sqrt();
        let bend = |q: Polar, inv: f64| q.curvature_numerator() * inv * inv * inv;
        match member {
            Member::Driver => {
                let e = unit(psi);
                let tangent = (e * p.d1 + e.turn_90() * p.rho) * inv_rate;
                Frame {
                    point: e * p.rho,
                    tangent,
                    normal: -tangent.turn_90(),
                    curvature: bend(p, inv_rate),
                }
            }
            Member::Driven => {
                let (turns, i, x) = self.locate(psi);
                let chi = -(turns * TAU + self.turn[i].eval(x).0);
                let e = unit(chi);
                let gap = self.a - p.rho;
                // dP/dψ = −ρ' e(χ) + (a − ρ) χ' e⊥(χ), χ' = −ρ/(a − ρ).
                let tangent = (e * (-p.d1) - e.turn_90() * p.rho) * inv_rate;
                // In its own angle χ the conjugate's `√(ρ₂² + ρ₂'²)` is `(a − ρ)/ρ` times
                // the driver's.
                let conjugate = conjugate_polar(p, self.a);
                Frame {
                    point: e * gap,
                    tangent,
                    normal: tangent.turn_90(),
                    curvature: bend(conjugate, inv_rate * p.rho / gap),
                }
            }
        }
    }

    /// The driven gear's own polar angle `χ(ψ)` (rad) of the point meeting the driver's `ψ`.
    pub fn driven_angle(&self, psi: f64) -> f64 {
        let (turns, i, x) = self.locate(psi);
        -(turns * TAU + self.turn[i].eval(x).0)
    }
}

/// Newton on `F(a) = Σ w ρ/(a − ρ) − 2π` from `a0`; `F` is convex and decreasing for
/// `a > max ρ`, so Newton from the right converges monotonically.
fn close<'a>(nodes: impl Iterator<Item = (&'a Polar, f64)> + Clone, a0: f64) -> Result<f64> {
    let rho_max = nodes.clone().fold(0.0_f64, |m, (p, _)| m.max(p.rho));
    let mut a = a0.max(rho_max * (1.0 + 1e-9));
    for _ in 0..50 {
        let (mut f, mut df) = (-TAU, 0.0);
        for (p, w) in nodes.clone() {
            let g = a - p.rho;
            f += w * p.rho / g;
            df -= w * p.rho / (g * g);
        }
        let step = f / df;
        let mut next = a - step;
        if next <= rho_max {
            next = 0.5 * (a + rho_max);
        }
        if (next - a).abs() <= 1e-14 * a {
            return Ok(next);
        }
        a = next;
    }
    Err(Error::Infeasible(format!(
        "teeth: the centre distance does not converge from {a0} mm"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{CurveSpec, Ellipse};

    #[test]
    fn circle_track_is_exact() {
        let curve = PitchCurve::Ellipse(Ellipse::new(30.0, 0.0).unwrap());
        let t = PairTrack::new(&curve, 59.0, 64).unwrap();
        assert!((t.centre_distance() - 60.0).abs() < 1e-12);
        assert!((t.perimeter() - TAU * 30.0).abs() < 1e-11);
        for k in 0..40 {
            let psi = 0.37 * k as f64 - 3.0;
            assert!((t.arc(psi) - 30.0 * psi).abs() < 1e-10);
            assert!((t.psi_at(30.0 * psi) - psi).abs() < 1e-12);
            assert!((t.driven_angle(psi) + psi).abs() < 1e-12);
        }
    }

    #[test]
    fn frames_agree_with_finite_differences_and_roll_without_slip() {
        let curve = CurveSpec::paper().build().unwrap();
        let t = PairTrack::new(&curve, 60.0, 256).unwrap();
        for member in [Member::Driver, Member::Driven] {
            for k in 0..25 {
                let psi = 0.25 * k as f64 + 0.01;
                let h = 1e-5;
                let f = t.frame(member, psi);
                let (fm, fp) = (t.frame(member, psi - h), t.frame(member, psi + h));
                let ds = t.arc(psi + h) - t.arc(psi - h);
                // Tangent = dP/ds, dT/ds = −κ N: the frame is the curve's, and the driven
                // gear's arc length is the driver's (no slip).
                let tangent = (fp.point - fm.point) * (1.0 / ds);
                // (The arc table's interpolated ds is good to ~1e-5 relative at the paper
                // curve's 1.6 mm radius of curvature with 256 panels.)
                assert!((tangent - f.tangent).hypot() < 1e-4, "{member:?} {psi}");
                let dt = (fp.tangent - fm.tangent) * (1.0 / ds);
                assert!(
                    (dt + f.normal * f.curvature).hypot() < 1e-4 * (1.0 + f.curvature.abs()),
                    "{member:?} {psi}: {dt:?} vs {}",
                    f.curvature
                );
                // The normal points away from the gear's centre on a star-shaped curve.
                assert!(f.normal.dot(f.point) > 0.0);
            }
        }
        // The conjugate closes: one driver turn is one driven turn.
        assert!((t.driven_angle(TAU) + TAU).abs() < 1e-12);
    }
}
