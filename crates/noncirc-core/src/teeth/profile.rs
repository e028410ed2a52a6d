//! One gear's tooth outline, cut by a rack or a shaper rolling without slip on its pitch
//! curve (the generalised involute; Litvin, *Gear Geometry and Applied Theory*, ch. 2 and
//! 17; Bäsel, arXiv:1905.02642).
//!
//! At rolling position `s` (mm of pitch arc) the pitch point is `I = P(s)` and the tool's
//! pitch line (or circle) touches the pitch curve there. A straight tool flank crossing the
//! pitch line at `u0` touches the gear where the normal through `I` meets it: on the line
//! of action `I + λ (cos α T + σ sin α N)`, `λ = −(s − u0) cos α`, `σ = +1` for a tooth's
//! right flank (towards growing `s`), `−1` for its left. An involute shaper cutter of the
//! same pitch and pressure angle gives the same `λ(s)` on any pitch curve (its line of
//! action through `I` is tangent to its base circle, and its involute advances along it at
//! `cos α` per mm of rolling), so the flanks do not depend on the cutter: the cutter shapes
//! only the root fillet, the envelope of its tip rounding (radius `ρf`, the contact point
//! on the far side of the rounding's centre from `I`), and decides which concave arcs can
//! be cut at all. The flank is regular while `sin α + σ λ κ > 0`; where that factor
//! vanishes the envelope has a cusp: below the pitch curve on a convex arc that is
//! undercut, and the fillet then cuts across the flank.

use super::cut_gear::{Probe, Side, Tooth, ToothedGear, Undercut};
use super::polyline::{segment_distance, OutlineGrid};
use super::roots::{regula_falsi, rough_cube_root};
use super::tool::{Rounding, Tool};
use super::track::{Frame, Member, PairTrack};
use super::MAX_OUTLINE_POINTS;
use crate::error::{Error, Result};
use crate::vec2::Vec2;

/// A point of a gear's outline as a function of the rolling position: the flank, the
/// fillet, or an offset of the pitch curve.
#[derive(Debug, Clone, Copy)]
enum Piece {
    Flank { u0: f64, sigma: f64 },
    Fillet { u0: f64, sigma: f64 },
    Offset { height: f64 },
}

/// A point of a piece and where it was generated: rolling position `s` (mm), driver
/// parameter `psi` (rad), `ds/dψ` there (mm/rad) and the pitch curve's frame.
#[derive(Debug, Clone, Copy)]
struct Sample {
    s: f64,
    psi: f64,
    rate: f64,
    frame: Frame,
    point: Vec2,
}

/// Cuts one gear of a pair.
pub(super) struct Cut<'a> {
    pub track: &'a PairTrack,
    pub member: Member,
    pub tool: Tool,
    /// Pitch (mm).
    pub pitch: f64,
    /// Pitch arc of tooth 0's centre (mm).
    pub phase: f64,
    pub teeth: usize,
    /// Least segments per flank; more where the chord tolerance needs them.
    pub flank_samples: usize,
    /// Largest distance (mm) of an outline chord from the generated curve.
    pub chord_tolerance: f64,
    /// Module (mm).
    pub module: f64,
    /// Reach (mm) of the mesh check's distance queries to this gear.
    pub reach: f64,
    /// Fractions of the way along a fillet of its `fillet_samples + 1` points: even in the
    /// angle of the rounding's contact, `tan(k·e/n)/tan(e)` with `e = π/2 − α`.
    pub fillet_spacing: Vec<f64>,
    pub name: &'static str,
}

impl Cut<'_> {
    #[inline]
    fn frame(&self, s: f64) -> Frame {
        self.track.frame(self.member, self.track.psi_at(s))
    }

    /// The rolling position `s` (mm), its rate `ds/dψ` (mm/rad) and the frame at driver
    /// parameter `psi` (rad): no inversion of the arc length.
    #[inline]
    fn frame_at_psi(&self, psi: f64) -> (f64, f64, Frame) {
        let (s, rate) = self.track.arc_with_rate(psi);
        (s, rate, self.track.frame(self.member, psi))
    }

    #[inline]
    fn lambda(&self, s: f64, u0: f64) -> f64 {
        -(s - u0) * self.tool.cos
    }

    /// The outline point of `piece` generated at rolling position `s` with frame `f`.
    #[inline]
    fn point(&self, piece: Piece, s: f64, f: &Frame) -> Vec2 {
        let t = &self.tool;
        match piece {
            Piece::Flank { u0, sigma } => {
                let dir = f.tangent * t.cos + f.normal * (sigma * t.sin);
                f.point + dir * self.lambda(s, u0)
            }
            Piece::Fillet { u0, sigma } => {
                let (du, dv) = match t.rounding {
                    Rounding::Rack { du, v } => (u0 + sigma * du - s, v),
                    Rounding::Shaper { rc, r, phi } => {
                        let a = sigma * phi + (u0 - s) / rc;
                        let (sn, cs) = a.sin_cos();
                        (r * sn, rc - r * cs)
                    }
                };
                let off = f.tangent * du + f.normal * dv;
                let len = off.hypot2().sqrt();
                f.point + off * (1.0 + t.cutting_side * t.radius / len)
            }
            Piece::Offset { height } => f.point + f.normal * height,
        }
    }

    /// The rate `d/ds` (per mm of rolling) of [`Self::point`]: the frame turns as
    /// `T' = −κN`, `N' = κT`.
    #[inline]
    fn velocity(&self, piece: Piece, s: f64, f: &Frame) -> Vec2 {
        let t = &self.tool;
        let (tangent, normal, kappa) = (f.tangent, f.normal, f.curvature);
        match piece {
            Piece::Flank { u0, sigma } => {
                let dir = tangent * t.cos + normal * (sigma * t.sin);
                let turn = tangent * (sigma * t.sin) - normal * t.cos;
                tangent - dir * t.cos + turn * (self.lambda(s, u0) * kappa)
            }
            Piece::Fillet { u0, sigma } => {
                let (du, dv, ddu, ddv) = match t.rounding {
                    Rounding::Rack { du, v } => (u0 + sigma * du - s, v, -1.0, 0.0),
                    Rounding::Shaper { rc, r, phi } => {
                        let a = sigma * phi + (u0 - s) / rc;
                        let (sn, cs) = a.sin_cos();
                        (r * sn, rc - r * cs, -r * cs / rc, -r * sn / rc)
                    }
                };
                let off = tangent * du + normal * dv;
                let d_off = tangent * (ddu + kappa * dv) + normal * (ddv - kappa * du);
                let len = off.hypot2().sqrt();
                let r = t.cutting_side * t.radius;
                tangent + d_off * (1.0 + r / len) - off * (r * off.dot(d_off) / (len * len * len))
            }
            Piece::Offset { height } => tangent * (1.0 + height * kappa),
        }
    }

    fn at(&self, piece: Piece, s: f64) -> Vec2 {
        self.point(piece, s, &self.frame(s))
    }

    /// The sample of `piece` at driver parameter `psi` (rad).
    fn sample_at_psi(&self, piece: Piece, psi: f64) -> Sample {
        let (s, rate, frame) = self.frame_at_psi(psi);
        Sample {
            s,
            psi,
            rate,
            frame,
            point: self.point(piece, s, &frame),
        }
    }

    /// The rate `dP/dψ` (mm/rad) of `piece` at `x`.
    fn derivative(&self, piece: Piece, x: &Sample) -> Vec2 {
        self.velocity(piece, x.s, &x.frame) * x.rate
    }

    /// `n + 1` points of `piece` from `s0` to `s1`, uniform in `ψ`, with their
    /// parameters and frames.
    fn sample(&self, piece: Piece, s0: f64, s1: f64, n: usize) -> Vec<Sample> {
        self.sample_spaced(piece, s0, s1, n, |k| k as f64 / n as f64)
    }

    /// `n + 1` points of `piece` from `s0` to `s1`, point `k` at the fraction `spacing(k)`
    /// of the way in `ψ`, with their parameters and frames.
    fn sample_spaced(
        &self,
        piece: Piece,
        s0: f64,
        s1: f64,
        n: usize,
        spacing: impl Fn(usize) -> f64,
    ) -> Vec<Sample> {
        let (p0, p1) = (self.track.psi_at(s0), self.track.psi_at(s1));
        (0..=n)
            .map(|k| {
                let psi = p0 + (p1 - p0) * spacing(k);
                let (s, rate) = self.track.arc_with_rate(psi);
                let s = match k {
                    0 => s0,
                    _ if k == n => s1,
                    _ => s,
                };
                let frame = self.track.frame(self.member, psi);
                Sample {
                    s,
                    psi,
                    rate,
                    frame,
                    point: self.point(piece, s, &frame),
                }
            })
            .collect()
    }

    /// The flank crossing the pitch curve at `u0` on side `sigma`, from rolling position
    /// `s0` to `s1`, in chords of even sag. The flank advances `f = sin α + σλκ` mm per mm
    /// of rolling and bends with radius `f/κ` (`κ` of the pitch curve at `u0`), so a chord
    /// over `Δs` of rolling sags `fκΔs²/8`: even sag wants `Δs ∝ f^(-1/2)`, even steps in
    /// `f^(3/2)` (`f` is linear in `s`). Uniform where `f` is not positive at both ends or
    /// hardly changes. At least `flank_samples` chords, and as many as keep the sag within
    /// the chord tolerance with the `sharpest` |κ| (1/mm) met over the flank's rolling;
    /// then halved where they still sag more ([`Self::refine`]: the estimate takes the
    /// pitch curve's curvature for constant, and near the foot of an undercut flank its
    /// chords sagged up to 1.27 µm at a tolerance of 1 µm).
    fn sample_flank(
        &self,
        u0: f64,
        sigma: f64,
        (kappa, sharpest): (f64, f64),
        s0: f64,
        s1: f64,
    ) -> Vec<Sample> {
        let t = &self.tool;
        let f = |s: f64| t.sin + sigma * self.lambda(s, u0) * kappa;
        let (f0, f1) = (f(s0), f(s1));
        let piece = Piece::Flank { u0, sigma };
        let tol = self.chord_tolerance;
        if f0 > 0.0 && f1 > 0.0 && (f1 - f0).abs() > 1e-6 * (f0 + f1) {
            // Even steps `Δg` in `g = f^(3/2)` (`f` with `κ` at `u0`) sag
            // `κ' Δg²/(18 κ² cos²α)` each where the pitch curve's curvature is `κ'`.
            let (g0, g1) = (f0 * f0.sqrt(), f1 * f1.sqrt());
            let needed =
                (g1 - g0).abs() * sharpest.sqrt() / (kappa.abs() * t.cos * (18.0 * tol).sqrt());
            let n = self.flank_samples.max(segments(needed));
            // (The ends exactly, the rest roughly: the halving below holds the tolerance.)
            let points = self.sample_spaced(piece, s0, s1, n, |k| match k {
                0 => 0.0,
                _ if k == n => 1.0,
                _ => {
                    let g = g0 + (g1 - g0) * k as f64 / n as f64;
                    (rough_cube_root(g * g) - f0) / (f1 - f0)
                }
            });
            self.refine(piece, &points, tol)
        } else {
            let n = self.chords(
                self.flank_samples,
                s1 - s0,
                f0.abs().max(f1.abs()) * sharpest,
            );
            self.refine(piece, &self.sample(piece, s0, s1, n), tol)
        }
    }

    /// The fillet from the root (`s0`) to `s1`, `fillet_samples` segments spaced evenly in
    /// the angle of the rounding's contact (exactly so for a rack, where `ψ` follows `s`
    /// linearly over a fillet: uniform spacing would crowd them where the contact hardly
    /// moves), each halved until it is within the chord tolerance: the fillet bends
    /// sharply near its root on a convex arc (at 12 even segments its chords sagged up to
    /// 14 µm on the moving-box ellipse, m = 2.25 mm).
    fn sample_fillet(&self, piece: Piece, s0: f64, s1: f64) -> Vec<Sample> {
        let spacing = &self.fillet_spacing;
        let points = self.sample_spaced(piece, s0, s1, spacing.len() - 1, |k| spacing[k]);
        self.refine(piece, &points, self.chord_tolerance)
    }

    /// Halves (in `ψ`) every segment of `points` (samples of `piece` in order) that lies
    /// farther than `tol` (mm) from the piece, until none does or a segment has been
    /// halved [`MAX_HALVINGS`] times (at a cusp). A segment's sag is that of the cubic
    /// through its ends with the piece's derivatives there ([`hermite_sag_within`]), or where
    /// that cubic cannot stand for the piece, the distance of the piece's midpoint from
    /// it: a segment kept costs no evaluation of the piece. (Dividing a segment at once
    /// into as many parts as its sag asks for, rather than halving, made more points: the
    /// cubic of a long segment is a poorer guess.)
    fn refine(&self, piece: Piece, points: &[Sample], tol: f64) -> Vec<Sample> {
        let mut out = Vec::with_capacity(points.len());
        let Some(&first) = points.first() else {
            return out;
        };
        out.push(first);
        let mut a = (first, self.derivative(piece, &first));
        for &b in &points[1..] {
            let b = (b, self.derivative(piece, &b));
            self.halve(piece, a, b, tol, 0, &mut out);
            a = b;
        }
        out
    }

    /// Pushes `b`, after the points halving `a→b` needs (see [`Self::refine`]); each end
    /// comes with its derivative `dP/dψ`.
    fn halve(
        &self,
        piece: Piece,
        a: (Sample, Vec2),
        b: (Sample, Vec2),
        tol: f64,
        depth: u32,
        out: &mut Vec<Sample>,
    ) {
        let h = b.0.psi - a.0.psi;
        let within = hermite_sag_within(a.0.point, a.1 * h, b.0.point, b.1 * h, tol);
        if depth >= MAX_HALVINGS || within == Some(true) {
            out.push(b.0);
            return;
        }
        let mid = self.sample_at_psi(piece, a.0.psi + 0.5 * h);
        if within.is_none() && segment_distance(mid.point, a.0.point, b.0.point) <= tol {
            out.push(b.0);
            return;
        }
        let mid = (mid, self.derivative(piece, &mid));
        self.halve(piece, a, mid, tol, depth + 1, out);
        self.halve(piece, mid, b, tol, depth + 1, out);
    }

    /// Newton on `F(a) = G(b)` from the rolling positions `(a, b)` (mm), stepping in the
    /// driver parameter with exact derivatives; the rolling positions where they meet and
    /// the point.
    fn meet(&self, f: Piece, g: Piece, a: f64, b: f64) -> Option<(f64, f64, Vec2)> {
        let (mut pa, mut pb) = (self.track.psi_at(a), self.track.psi_at(b));
        for _ in 0..12 {
            let (sa, rate_a, fa) = self.frame_at_psi(pa);
            let (sb, rate_b, fb) = self.frame_at_psi(pb);
            let point = self.point(f, sa, &fa);
            let r = point - self.point(g, sb, &fb);
            let da = self.velocity(f, sa, &fa) * rate_a;
            let db = self.velocity(g, sb, &fb) * rate_b;
            // Solve da·Δa − db·Δb = −r.
            let det = da.cross(-db);
            if det == 0.0 || !det.is_finite() {
                return None;
            }
            let step_a = (-r).cross(-db) / det;
            let step_b = da.cross(-r) / det;
            pa += step_a;
            pb += step_b;
            // Quadratic convergence: after a step below 1e-7 pitch (well under a
            // micrometre) the error is of the order of its square, and the step's linear
            // update is as good as evaluating there again.
            let (move_a, move_b) = (step_a * rate_a, step_b * rate_b);
            if move_a.abs().max(move_b.abs()) < NEWTON_STEP_PITCHES * self.pitch {
                let p = point + da * step_a;
                return p.is_finite().then_some((sa + move_a, sb + move_b, p));
            }
        }
        None
    }

    /// Where the flank meets the tip curve, bracketed where Newton from the circle's guess
    /// `s_guess` fails (where the pitch curve bends sharply within the tooth): the flank's
    /// height over the tip curve, measured from its foot point there, is marched from the
    /// pitch curve (`u0`) past the guess until it changes sign, then the crossing is found
    /// by regula falsi and polished by Newton. If the flank does not get there within three
    /// times the guess (it folds back first, at a cusp above the pitch curve, whatever the
    /// cutter), the highest it got (mm, negative: below the tip curve; NaN if unmeasured).
    fn tip_crossing(
        &self,
        flank: Piece,
        tip: Piece,
        u0: f64,
        s_guess: f64,
    ) -> std::result::Result<(f64, f64, Vec2), f64> {
        let cos = self.tool.cos;
        // The flank point at rolling `a`, its foot on the tip curve (rolling `b`, Newton
        // from the straight-line guess) and its height over the tip curve there.
        let above = |a: f64| -> Option<(f64, f64)> {
            let p = self.at(flank, a);
            let mut b = a + self.lambda(a, u0) * cos;
            for _ in 0..30 {
                let f = self.frame(b);
                let q = self.point(tip, b, &f);
                let v = self.velocity(tip, b, &f);
                let step = (q - p).dot(v) / v.hypot2();
                b -= step;
                if step.abs() < 1e-12 * self.pitch {
                    let f = self.frame(b);
                    let q = self.point(tip, b, &f);
                    return Some(((p - q).dot(f.normal), b));
                }
            }
            None
        };
        let steps = 24;
        let span = 3.0 * (s_guess - u0);
        let mut lo = (u0, above(u0).ok_or(f64::NAN)?.0);
        let mut highest = lo.1;
        for k in 1..=steps {
            let a = u0 + span * k as f64 / steps as f64;
            let (h, _) = above(a).ok_or(highest)?;
            if h > 0.0 {
                let a = super::roots::regula_falsi(
                    |x| above(x).map_or(f64::NAN, |(h, _)| h),
                    lo,
                    (a, h),
                );
                let (_, b) = above(a).ok_or(highest)?;
                return Ok(self
                    .meet(flank, tip, a, b)
                    .unwrap_or((a, b, self.at(flank, a))));
            }
            lo = (a, h);
            highest = highest.max(h);
        }
        Err(highest)
    }

    /// Segments (at least `least`) of the offset of the pitch curve at `height` (mm) from
    /// rolling position `s0` to `s1` within the chord tolerance: a chord over `Δs` of
    /// rolling sags `(1 + hκ)κΔs²/8`.
    fn offset_segments(&self, least: usize, height: f64, s0: f64, s1: f64) -> usize {
        let kappa = self.frame(0.5 * (s0 + s1)).curvature;
        self.chords(least, s1 - s0, ((1.0 + height * kappa) * kappa).abs())
    }

    /// Chords (at least `least`) over `span` mm of rolling of a curve whose chord over `Δs`
    /// sags `bend·Δs²/8` (`bend` in 1/mm), within the chord tolerance.
    fn chords(&self, least: usize, span: f64, bend: f64) -> usize {
        least.max(segments(
            span.abs() * (bend / (8.0 * self.chord_tolerance)).sqrt(),
        ))
    }

    fn fail(&self, tooth: usize, s: f64, why: String) -> Error {
        Error::Teeth {
            gear: self.name,
            tooth,
            arc_mm: s,
            why,
        }
    }

    /// One side of tooth `j` from the root to the tip: the fillet, then the flank up to the
    /// tip curve. Returns the chain's points, the index where the flank starts, the flank's
    /// tip parameter, and the undercut if the fillet crosses the flank.
    fn side(&self, j: usize, u0: f64, side: Side) -> Result<SideChain> {
        let t = &self.tool;
        let sigma = side.sign();
        let flank = Piece::Flank { u0, sigma };
        let fillet = Piece::Fillet { u0, sigma };
        let tip = Piece::Offset { height: t.tip };
        let form = u0 - sigma * t.lambda_form / t.cos;
        let root_end = u0 + sigma * t.fillet_reach;
        // Where the flank meets the tip curve: from the tool's tip height.
        let s_guess = u0 - sigma * t.tip / (t.sin * t.cos);
        let w_guess = s_guess + self.lambda(s_guess, u0) * t.cos;
        let crossing = match self.meet(flank, tip, s_guess, w_guess) {
            Some(found) => Ok(found),
            None => self.tip_crossing(flank, tip, u0, s_guess),
        };
        let (s_tip, w_tip, _) = crossing.map_err(|highest| {
            let radius = 1.0 / self.frame(u0).curvature;
            let short = if highest.is_finite() {
                format!(
                    ": the flank folds back (a cusp of the envelope) {:.4} mm below it, \
                     whatever the cutter",
                    -highest
                )
            } else {
                String::new()
            };
            self.fail(
                j,
                u0,
                format!(
                    "the flank does not reach the tip curve {:.3} mm outside the pitch curve{short}; \
                     the pitch curve's radius of curvature is {radius:.3} mm here: it bends too \
                     sharply for teeth of module {:.4} mm",
                    t.tip,
                    self.pitch / std::f64::consts::PI
                ),
            )
        })?;
        let factor = |s: f64, f: &Frame| t.sin + sigma * self.lambda(s, u0) * f.curvature;
        let kappa = self.frame(u0).curvature;
        // The flank bends with the pitch curve where it is generated: the sharpest bend
        // over its rolling sets the count of samples.
        let sharpest = [form, s_tip]
            .into_iter()
            .fold(kappa.abs(), |a, s| a.max(self.frame(s).curvature.abs()));
        let flank_pts = self.sample_flank(u0, sigma, (kappa, sharpest), form, s_tip);
        let fillet_pts = self.sample_fillet(fillet, root_end, form);
        // Where the flank is singular (a cusp of the envelope). A singular stretch at the
        // flank's foot is undercut: the fillet then cuts across the regular flank above
        // it. Anywhere else the tool cannot cut the flank.
        let singular = flank_pts.iter().rposition(|x| factor(x.s, &x.frame) <= 0.0);
        let regular_from = match singular {
            None => None,
            Some(k)
                if k + 1 < flank_pts.len()
                    && flank_pts[..=k].iter().all(|x| factor(x.s, &x.frame) <= 0.0) =>
            {
                let (xk, xn) = (&flank_pts[k], &flank_pts[k + 1]);
                let lo = (xk.psi, factor(xk.s, &xk.frame));
                let hi = (xn.psi, factor(xn.s, &xn.frame));
                let factor_at = |psi: f64| {
                    let (s, _, f) = self.frame_at_psi(psi);
                    factor(s, &f)
                };
                Some(self.track.arc(regula_falsi(factor_at, lo, hi)))
            }
            Some(k) => {
                let Sample { s, frame: f, .. } = flank_pts[k];
                let height = sigma * self.lambda(s, u0) * t.sin;
                return Err(self.fail(
                    j,
                    u0,
                    format!(
                        "the generated flank has a cusp {height:.4} mm from the pitch curve, \
                         where the pitch curve's radius of curvature is {:.4} mm: the tool \
                         cannot cut this flank (a smaller module, or a pitch curve with \
                         gentler curvature)",
                        1.0 / f.curvature
                    ),
                ));
            }
        };
        let (fillet_pts, flank_pts, undercut, start) = match regular_from {
            None => (fillet_pts, flank_pts, None, form),
            Some(cusp) => {
                // The fillet continues the flank's lower branch (form point to cusp); the
                // regular branch rises from the cusp. Where the two first meet again, seen
                // from the tip, the cut flank starts.
                let tol = SEARCH_TOLERANCE_MODULES * self.module;
                let lower = self.refine(flank, &self.sample(flank, form, cusp, 8), tol);
                let regular = self.refine(
                    flank,
                    &self.sample(flank, cusp, s_tip, UNDERCUT_SEARCH_SAMPLES),
                    tol,
                );
                let fine_fillet = self.refine(fillet, &fillet_pts, tol);
                let chain: Vec<(Piece, f64, Vec2)> =
                    (fine_fillet.iter().map(|x| (fillet, x.s, x.point)))
                        .chain(lower.iter().skip(1).map(|x| (flank, x.s, x.point)))
                        .collect();
                let found = last_crossing(&chain, &regular, true);
                // Newton from the polylines' crossing, kept if it stays on the branches it
                // started on (the two flank branches are one curve folded at the cusp:
                // Newton can slide over the fold to a point of the regular branch, and the
                // outline then runs past the corner and back); the polylines' crossing
                // itself otherwise.
                let converged = found.and_then(|(piece, sa, sb)| {
                    let (sa, sb, _) = self.meet(piece, flank, sa, sb)?;
                    let beyond = |s: f64| (s - cusp) * (s_tip - cusp) > 0.0;
                    let lower = !matches!(piece, Piece::Flank { .. }) || !beyond(sa);
                    (beyond(sb) && lower).then_some((piece, sa, sb))
                });
                // No crossing at the search tolerance: the swallowtail is thinner than that,
                // and the fillet meets the regular flank at the cusp.
                let (piece, sa, sb) = converged.or(found).unwrap_or((fillet, form, cusp));
                let start_height = sigma * self.lambda(sb, u0) * t.sin;
                let undercut = Undercut {
                    side,
                    pitch_arc_mm: u0,
                    flank_starts_at_mm: start_height,
                    lost_height_mm: start_height - t.form_height(),
                };
                let kept = match piece {
                    Piece::Fillet { .. } => self.sample_fillet(fillet, root_end, sa),
                    _ => {
                        let mut pts = fillet_pts;
                        let lower = self.sample(flank, form, sa, 4);
                        let lower = self.refine(flank, &lower, self.chord_tolerance);
                        pts.extend(lower.into_iter().skip(1));
                        pts
                    }
                };
                (
                    kept,
                    self.sample_flank(u0, sigma, (kappa, sharpest), sb, s_tip),
                    Some(undercut),
                    sb,
                )
            }
        };
        let mut points: Vec<Vec2> = fillet_pts.iter().map(|x| x.point).collect();
        let flank_start = points.len() - 1;
        points.extend(flank_pts.iter().skip(1).map(|x| x.point));
        // The flank from the segment that crosses the pitch curve up: every contact of a
        // pair lies on the pitch curve or above it on one of the two gears (at height h on
        // one, −h on the other), so the two gears' probes meet each contact.
        let upper = flank_pts
            .iter()
            .position(|x| sigma * self.lambda(x.s, u0) >= 0.0)
            .unwrap_or(flank_pts.len() - 1)
            .saturating_sub(1);
        Ok(SideChain {
            points,
            flank_start,
            probe_from: flank_start + upper,
            tip_param: w_tip,
            root_end,
            undercut,
            active: (
                sigma * self.lambda(start, u0) * t.sin,
                sigma * self.lambda(s_tip, u0) * t.sin,
            ),
        })
    }

    /// Cuts every tooth and assembles the closed outline.
    pub(super) fn run(&self) -> Result<ToothedGear> {
        let t = &self.tool;
        let mut outline: Vec<Vec2> = Vec::new();
        let mut corners = Vec::new();
        // Where pieces meet (root and fillet, fillet and flank, flank and tip): the corners
        // and the joints without an angle, where the curvature jumps.
        let mut joints = Vec::new();
        let mut flank_of: Vec<Option<(usize, Side)>> = Vec::new();
        let mut probes: Vec<bool> = Vec::new();
        let mut teeth = Vec::with_capacity(self.teeth);
        let centre = |j: usize| self.phase + self.pitch * j as f64;
        let mut sides = Vec::with_capacity(self.teeth);
        let mut tooth_starts = Vec::with_capacity(self.teeth);
        let mut total = 0;
        for j in 0..self.teeth {
            let c = centre(j);
            let left = self.side(j, c - 0.5 * t.thickness, Side::Left)?;
            let right = self.side(j, c + 0.5 * t.thickness, Side::Right)?;
            total += left.points.len() + right.points.len();
            if total > MAX_OUTLINE_POINTS {
                return Err(Error::OutOfRange {
                    name: "gear.teeth.chord_tolerance_mm".into(),
                    value: self.chord_tolerance,
                    expected: format!(
                        "a tolerance the {} outline meets in at most {MAX_OUTLINE_POINTS} \
                         points (it needed more by tooth {j})",
                        self.name
                    ),
                });
            }
            sides.push((left, right));
        }
        // Every side's points, three tip and two root points a tooth, and the closing
        // point the grid adds.
        let points = sides
            .iter()
            .map(|(l, r)| l.points.len() + r.points.len() + 5)
            .sum::<usize>()
            + 1;
        outline.reserve(points);
        flank_of.reserve(points);
        probes.reserve(points);
        for j in 0..self.teeth {
            let (left, right) = &sides[j];
            let c = centre(j);
            let mut tooth = Tooth {
                centre_arc_mm: c,
                tip_land_mm: 0.0,
                pointed: false,
                undercut: [left.undercut, right.undercut],
                active: [left.active, right.active],
            };
            // Left chain root → tip.
            let mut left_pts = left.points.clone();
            let mut right_pts = right.points.clone();
            let mut tip_pts = Vec::new();
            if left.tip_param < right.tip_param {
                let a = left_pts.last().copied().unwrap_or_default();
                let b = right_pts.last().copied().unwrap_or_default();
                tooth.tip_land_mm = (b - a).hypot();
                let tip = Piece::Offset { height: t.tip };
                let n = self.offset_segments(4, t.tip, left.tip_param, right.tip_param);
                for k in 1..n {
                    let w =
                        left.tip_param + (right.tip_param - left.tip_param) * k as f64 / n as f64;
                    tip_pts.push(self.at(tip, w));
                }
            } else {
                // The flanks cross below the tip curve: the tooth ends in a point.
                let (lf, rf) = (
                    &left_pts[left.flank_start..],
                    &right_pts[right.flank_start..],
                );
                let cross = super::polyline::first_crossing(lf, rf).ok_or_else(|| {
                    self.fail(
                        j,
                        c,
                        "the tip curve misses the tooth and its flanks do not meet".into(),
                    )
                })?;
                let (li, ri) = (cross.0.floor() as usize, cross.1.floor() as usize);
                let apex = lf[li] + (lf[li + 1] - lf[li]) * (cross.0 - li as f64);
                left_pts.truncate(left.flank_start + li + 1);
                left_pts.push(apex);
                right_pts.truncate(right.flank_start + ri + 1);
                tooth.pointed = true;
            }
            let base = outline.len();
            tooth_starts.push(base);
            flank_of.extend(
                (0..left_pts.len()).map(|k| (k >= left.flank_start).then_some((j, Side::Left))),
            );
            probes.extend((0..left_pts.len()).map(|k| k >= left.probe_from));
            outline.extend(&left_pts);
            if left.undercut.is_some() {
                corners.push(base + left.flank_start);
            }
            corners.push(outline.len() - 1);
            joints.extend([base, base + left.flank_start, outline.len() - 1]);
            flank_of.extend(tip_pts.iter().map(|_| None));
            probes.extend(tip_pts.iter().map(|_| true));
            outline.extend(tip_pts);
            if !tooth.pointed {
                corners.push(outline.len());
            }
            let right_start = outline.len();
            let rn = right_pts.len();
            for (k, p) in right_pts.iter().rev().enumerate() {
                let idx = rn - 1 - k;
                flank_of.push((idx >= right.flank_start).then_some((j, Side::Right)));
                probes.push(idx >= right.probe_from);
                outline.push(*p);
            }
            if right.undercut.is_some() {
                corners.push(right_start + (rn - 1 - right.flank_start));
            }
            joints.extend([
                right_start,
                right_start + (rn - 1 - right.flank_start),
                right_start + rn - 1,
            ]);
            // The root to the next tooth's left fillet.
            let next = &sides[(j + 1) % self.teeth].0;
            let (s0, s1) = (
                right.root_end,
                next.root_end
                    + if j + 1 == self.teeth {
                        self.pitch * self.teeth as f64
                    } else {
                        0.0
                    },
            );
            if s1 > s0 {
                let root = Piece::Offset { height: t.root };
                let n = self.offset_segments(3, t.root, s0, s1);
                for k in 1..n {
                    let s = s0 + (s1 - s0) * k as f64 / n as f64;
                    let f = self.frame(s);
                    if 1.0 + t.root * f.curvature <= 0.0 {
                        return Err(self.fail(j, s, format!(
                            "the root curve {:.4} mm inside the pitch curve folds where the pitch curve's radius of curvature is {:.4} mm",
                            -t.root, 1.0 / f.curvature)));
                    }
                    outline.push(self.point(root, s, &f));
                    flank_of.push(None);
                    probes.push(false);
                }
            } else {
                return Err(self.fail(
                    j,
                    s0,
                    "the fillets of neighbouring teeth cross: the tooth space is narrower than \
                     the tool's tip"
                        .into(),
                ));
            }
            teeth.push(tooth);
        }
        let n = outline.len();
        // Each tooth's probes, from its points (and the root that follows).
        let mut tooth_probes = Vec::with_capacity(self.teeth);
        let mut probe_list = Vec::with_capacity(probes.iter().filter(|p| **p).count());
        for (j, &start) in tooth_starts.iter().enumerate() {
            let end = tooth_starts.get(j + 1).copied().unwrap_or(n);
            let first = probe_list.len();
            probe_list.extend((start..end).filter(|&i| probes[i]).map(|i| Probe {
                point: outline[i],
                side: flank_of[i].map(|(_, side)| side),
            }));
            tooth_probes.push((first, probe_list.len()));
        }
        if self.member == Member::Driven {
            outline.reverse();
            flank_of.reverse();
            for c in corners.iter_mut().chain(&mut joints) {
                *c = n - 1 - *c;
            }
            corners.sort_unstable();
        }
        let grid = OutlineGrid::new(outline, self.reach, self.chord_tolerance, &joints);
        if let Some(p) = grid.self_crossing() {
            return Err(Error::OutlineCrossing {
                gear: self.name,
                x_mm: p.x,
                y_mm: p.y,
            });
        }
        Ok(ToothedGear {
            corners,
            flank_of,
            probes: probe_list,
            tooth_probes,
            teeth,
            grid,
        })
    }
}

/// Newton's last step (in pitches of rolling) where two pieces meet ([`Cut::meet`]).
pub(super) const NEWTON_STEP_PITCHES: f64 = 1e-7;

/// Most halvings of one segment in [`Cut::refine`] (a cusp would take them without end).
const MAX_HALVINGS: u32 = 10;

/// Largest ratio of an end's speed `|dP/dψ|·Δψ` to the chord (or of the chord to it) at
/// which [`hermite_sag_within`] measures a segment: beyond it a cusp is near.
const HERMITE_SPEED_RATIO: f64 = 1.5;

/// Whether the cubic Hermite curve from `a` to `b` with end derivatives `da`, `db` (mm per
/// unit of the segment's parameter) lies within `tol` (mm) of the chord `a→b`: the sag of
/// a smooth piece between two of its points, to fourth order in their spacing (second
/// order is the chord's own error). `None` where the ends' derivatives do not let the
/// cubic stand for the piece: a speed unlike the chord's (a cusp near) or a turn of more
/// than 45°. (In squares and scaled by the chord's length: no square root but one.)
fn hermite_sag_within(a: Vec2, da: Vec2, b: Vec2, db: Vec2, tol: f64) -> Option<bool> {
    let chord = b - a;
    let (len2, speed2_a, speed2_b) = (chord.hypot2(), da.hypot2(), db.hypot2());
    let ratio2 = HERMITE_SPEED_RATIO * HERMITE_SPEED_RATIO;
    let like = |v2: f64| v2 * ratio2 > len2 && v2 < len2 * ratio2;
    let turn = da.dot(db);
    let smooth = len2 > 0.0 && like(speed2_a) && like(speed2_b);
    if !(smooth && turn > 0.0 && 2.0 * turn * turn >= speed2_a * speed2_b) {
        return None;
    }
    // Off the chord, the cubic is `d(t) = t (1 − t)(p − (p + q) t)` with `p`, `q` the end
    // derivatives' normal parts (here times the chord's length). It vanishes at both
    // ends, so it is largest where `d' = p − 2(2p + q) t + 3(p + q) t²` vanishes: with
    // `u = p + q`, at `t = (p + u ± r)/(3u)`, `r² = p² − pu + u²` (never negative).
    let (p, q) = (chord.cross(da), chord.cross(db));
    let u = p + q;
    let d = |t: f64| t * (1.0 - t) * (p - u * t);
    let sag = if u.abs() > 1e-9 * p.abs() {
        let r = (p * p - p * u + u * u).sqrt();
        let scale = 1.0 / (3.0 * u);
        let at = |t: f64| if t > 0.0 && t < 1.0 { d(t).abs() } else { 0.0 };
        at((p + u + r) * scale).max(at((p + u - r) * scale))
    } else {
        // A symmetric bow: largest midway.
        d(0.5).abs()
    };
    Some(sag * sag <= tol * tol * len2)
}

/// Chord tolerance (× m) of the polylines searched for the fillet's crossing of an undercut
/// flank: the two curves meet at a small angle, so a coarse polyline can miss the crossing
/// nearest the tip and pick a lower one.
const SEARCH_TOLERANCE_MODULES: f64 = 1e-4;

/// Segments of the regular flank in the search for the fillet's crossing before they are
/// halved to [`SEARCH_TOLERANCE_MODULES`] ([`Cut::meet`] then refines the crossing).
const UNDERCUT_SEARCH_SAMPLES: usize = 8;

/// Segments for `x` (a positive estimate; at most 100 000).
fn segments(x: f64) -> usize {
    if x.is_finite() {
        x.ceil().clamp(1.0, 100_000.0) as usize
    } else {
        100_000
    }
}

/// The crossing of polyline `a` (points tagged with their piece and parameter) with the
/// polyline `b` nearest `b`'s end, as the piece and the two parameters (interpolated);
/// `skip_joint` skips the pair of segments that share `a`'s last and `b`'s first point.
fn last_crossing(
    a: &[(Piece, f64, Vec2)],
    b: &[Sample],
    skip_joint: bool,
) -> Option<(Piece, f64, f64)> {
    let mut best: Option<(usize, f64, usize, f64)> = None;
    for i in 0..a.len().saturating_sub(1) {
        for k in 0..b.len() - 1 {
            if skip_joint && i + 2 == a.len() && k == 0 {
                continue;
            }
            if let Some((ta, tb)) =
                super::polyline::segments_cross(a[i].2, a[i + 1].2, b[k].point, b[k + 1].point)
            {
                if best.is_none_or(|(_, _, bk, btb)| k as f64 + tb > bk as f64 + btb) {
                    best = Some((i, ta, k, tb));
                }
            }
        }
    }
    best.map(|(i, ta, k, tb)| {
        // A crossing on the joint between two pieces belongs to the later one.
        let piece = a[i + 1].0;
        let sa = if matches!((a[i].0, piece), (Piece::Fillet { .. }, Piece::Flank { .. })) {
            a[i + 1].1
        } else {
            a[i].1 + (a[i + 1].1 - a[i].1) * ta
        };
        (piece, sa, b[k].s + (b[k + 1].s - b[k].s) * tb)
    })
}

/// One side of a tooth, root to tip.
struct SideChain {
    points: Vec<Vec2>,
    /// Index in `points` where the flank starts.
    flank_start: usize,
    /// Index in `points` from which the flank reaches the pitch curve: the points the mesh
    /// check probes.
    probe_from: usize,
    /// The tip curve's parameter where the flank meets it.
    tip_param: f64,
    /// Rolling position where the fillet reaches the root.
    root_end: f64,
    undercut: Option<Undercut>,
    active: (f64, f64),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{CurveSpec, Ellipse, PitchCurve};
    use crate::teeth::{Cutter, ToothSpec};

    /// A cut of `member` of the pair on `track` with `teeth` teeth by `cutter`, its chords
    /// within `tol` (mm).
    fn cut_of(
        track: &PairTrack,
        member: Member,
        teeth: usize,
        cutter: Cutter,
        tol: f64,
    ) -> Cut<'_> {
        let pitch = track.perimeter() / teeth as f64;
        let module = pitch / std::f64::consts::PI;
        let spec = ToothSpec {
            cutter,
            ..ToothSpec::default()
        };
        Cut {
            track,
            member,
            tool: Tool::new(&spec, module, 0.0, 0.5 * pitch).unwrap(),
            pitch,
            phase: 0.0,
            teeth,
            flank_samples: spec.flank_samples,
            chord_tolerance: tol,
            module,
            reach: 0.05 * module,
            fillet_spacing: (0..=spec.fillet_samples)
                .map(|k| k as f64 / spec.fillet_samples as f64)
                .collect(),
            name: "test",
        }
    }

    /// The largest distance (mm) of the piece from the chords of `points`, measured at 64
    /// points of the piece within each chord's span of `ψ`.
    fn largest_sag(cut: &Cut, piece: Piece, points: &[Sample]) -> f64 {
        points
            .windows(2)
            .flat_map(|w| {
                (1..64).map(move |k| {
                    let psi = w[0].psi + (w[1].psi - w[0].psi) * k as f64 / 64.0;
                    let p = cut.sample_at_psi(piece, psi).point;
                    segment_distance(p, w[0].point, w[1].point)
                })
            })
            .fold(0.0, f64::max)
    }

    /// Every chord of a refined fillet lies within the chord tolerance of the fillet, as
    /// measured between its points (the cubic's sag stands for the piece's), and the
    /// fillets need more than their first samples: on the Fourier pair cut by a rack and
    /// by a 40-tooth shaper and on the ellipse e = 0.3 at 12 teeth (every fillet deeply
    /// undercut), at tolerances of 4, 1 and 0.25 µm.
    #[test]
    fn refined_fillet_chords_lie_within_the_tolerance() {
        let fourier = CurveSpec::Fourier {
            c0_mm: 30.0,
            cos_mm: vec![6.0, 0.0, -2.0],
            sin_mm: vec![0.0, 3.0],
        }
        .build()
        .unwrap();
        let ellipse = PitchCurve::Ellipse(Ellipse::new(30.0, 0.3).unwrap());
        let shaper = Cutter::Shaper { teeth: 40 };
        for (curve, teeth, cutter) in [
            (&fourier, 30, Cutter::Rack),
            (&fourier, 30, shaper),
            (&ellipse, 12, Cutter::Rack),
        ] {
            let track = PairTrack::new(curve, 60.0, 256).unwrap();
            for tol in [4e-3, 1e-3, 2.5e-4] {
                for member in [Member::Driver, Member::Driven] {
                    let cut = cut_of(&track, member, teeth, cutter, tol);
                    let (tool, pitch) = (cut.tool, cut.pitch);
                    let (mut worst, mut added) = (0.0f64, 0);
                    for j in 0..teeth {
                        for sigma in [-1.0, 1.0] {
                            let u0 = pitch * j as f64 + sigma * 0.25 * pitch;
                            let piece = Piece::Fillet { u0, sigma };
                            let form = u0 - sigma * tool.lambda_form / tool.cos;
                            let root_end = u0 + sigma * tool.fillet_reach;
                            let points = cut.sample_fillet(piece, root_end, form);
                            added += points.len() - cut.fillet_spacing.len();
                            worst = worst.max(largest_sag(&cut, piece, &points) / tol);
                        }
                    }
                    println!("{cutter:?} {teeth} {member:?} {tol}: {worst:.3} of the tolerance, {added} added");
                    assert!(worst <= 1.01, "{cutter:?} {member:?} {tol}: {worst}");
                    assert!(added > 0);
                }
            }
        }
    }

    /// Every side's flank, as cut (from where the undercut leaves it to the tip), lies
    /// within the chord tolerance of its polyline, measured at 2 000 heights: on the
    /// ellipse e = 0.3 at 12 teeth, where the even-sag count (the pitch curve's curvature
    /// taken for constant) left chords sagging 1.27 µm at a tolerance of 1 µm.
    #[test]
    fn cut_flanks_lie_within_the_tolerance_of_their_polylines() {
        let curve = PitchCurve::Ellipse(Ellipse::new(30.0, 0.3).unwrap());
        let track = PairTrack::new(&curve, 60.0, 256).unwrap();
        let tol = 1e-3;
        let mut worst = 0.0f64;
        for member in [Member::Driver, Member::Driven] {
            let cut = cut_of(&track, member, 12, Cutter::Rack, tol);
            let (tool, pitch) = (cut.tool, cut.pitch);
            for j in 0..12 {
                for side in [Side::Left, Side::Right] {
                    let sigma = side.sign();
                    let u0 = pitch * j as f64 + sigma * 0.25 * pitch;
                    let chain = cut.side(j, u0, side).unwrap();
                    let polyline = &chain.points[chain.flank_start..];
                    let (lo, hi) = chain.active;
                    for k in 0..2000 {
                        // The flank point at height `h`: `λ = h/(σ sin α)`, `s = u0 − λ/cos α`.
                        let h = lo + (hi - lo) * k as f64 / 1999.0;
                        let s = u0 - h / (sigma * tool.sin) / tool.cos;
                        let p = cut.at(Piece::Flank { u0, sigma }, s);
                        let d = polyline
                            .windows(2)
                            .map(|w| segment_distance(p, w[0], w[1]))
                            .fold(f64::INFINITY, f64::min);
                        worst = worst.max(d / tol);
                    }
                }
            }
        }
        println!("flanks: {worst:.4} of the tolerance");
        assert!(worst <= 1.01, "{worst}");
    }
}
