//! Non-circular gear pairs of average ratio 1: closure, conjugate curve, ratio, module.

use crate::curve::{parabola_vertex, PitchCurve, Polar, TAU};
use crate::error::{positive, Error, Result};
use crate::quadrature::SpectralIntegrator;
use crate::resolution::Resolution;
use crate::vec2::Vec2;
use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;
use wide::{f64x2, CmpEq, CmpGt, CmpLt};

/// The solved closure condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closure {
    /// Centre distance `a` (mm).
    pub centre_distance: f64,
    /// Estimated absolute error of `a` from the half-grid quadrature (mm, conservative).
    pub error_estimate: f64,
    /// Iterations of the safeguarded Newton solve.
    pub iterations: usize,
}

/// Solves `(1/2π) ∮ rho/(a - rho) dψ = 1` for `a > max rho` from uniform samples of `rho`
/// (trapezoid rule: spectrally accurate for smooth periodic curves).
///
/// Safeguarded Newton on `H(a) = 1/M(a) - 1` (nearly linear near the singular end) inside the
/// bracket `[max(ρmax, 2ρmin), 2ρmax]`, falling back to bisection: it cannot fail to converge.
/// The radii must be positive and finite, twice the largest finite too (the bracket's upper
/// end), and there must be at least one: else the error names the first bad radius, or the
/// empty list.
pub fn solve_closure(rho: &[f64], res: &Resolution) -> Result<Closure> {
    let (rmin, rmax) = radius_extremes(rho);
    // Start from the second-order expansion of the closure about the mean radius:
    // a ≈ 2ρ̄ + 2 var(ρ)/ρ̄ = 2·mean(ρ²)/mean(ρ).
    let (sum, sum_sq) = rho.iter().fold((0.0, 0.0), |(s, q), &r| (s + r, q + r * r));
    // The extremes pass a NaN over, but the sum takes it: three checks, not one a radius.
    if !(rmin > 0.0 && 2.0 * rmax < f64::INFINITY && !sum.is_nan()) || rho.is_empty() {
        return Err(bad_radii(rho));
    }
    let (mut lo, mut hi) = (rmax.max(2.0 * rmin), 2.0 * rmax);
    let mut a = (2.0 * sum_sq / sum).clamp(lo, hi);
    if a <= rmax {
        a = 0.5 * (lo + hi);
    }
    let mut iterations = 0;
    let n = rho.len() as f64;
    // The sums at the last iterate: the error estimate below reuses them when the iteration
    // ends with a step far below the estimate's own accuracy.
    let mut last_sums = None;
    if hi - lo > res.newton_rel_tol * hi {
        loop {
            iterations += 1;
            let sums = ratio_sums(rho, a, rmax);
            last_sums = sums;
            let (m, dm) = match sums {
                Some((s, ds)) => ((s[0] + s[1]) / n, ds / n),
                None => (f64::INFINITY, f64::NEG_INFINITY),
            };
            let (h, dh) = if m.is_finite() {
                (1.0 / m - 1.0, -dm / (m * m))
            } else {
                (-1.0, f64::NAN)
            };
            // Stop on the residual first: at convergence a rounding-level Newton step can land
            // just outside the bracket and would otherwise trigger needless bisections.
            if h.abs() <= 4.0 * f64::EPSILON {
                break;
            }
            if h < 0.0 {
                lo = a;
            } else {
                hi = a;
            }
            let mut next = a - h / dh;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            let step = (next - a).abs();
            a = next;
            if step <= res.newton_rel_tol * a
                || hi - lo <= res.newton_rel_tol * a
                || iterations >= 400
            {
                // A last step this small (relative 1e-14 by default) moves the half-grid
                // difference by far less than its size: the last sums serve.
                if step > 1e-10 * a {
                    last_sums = None;
                }
                break;
            }
        }
    } else {
        a = hi;
    }
    // Error estimate: the same integral on the even half of the grid.
    let (sums, dm_sum) = last_sums
        .or_else(|| ratio_sums(rho, a, rmax))
        .unwrap_or(([f64::INFINITY; 2], f64::NEG_INFINITY));
    let (m_full, dm) = ((sums[0] + sums[1]) / n, dm_sum / n);
    let m_half = sums[0] / rho.len().div_ceil(2) as f64;
    let error_estimate = if dm.abs() > 0.0 {
        (m_full - m_half).abs() / dm.abs()
    } else {
        0.0
    };
    if error_estimate > res.closure_rel_tol * a {
        return Err(Error::UnderResolved {
            samples: rho.len(),
            error_mm: error_estimate,
            tolerance_mm: res.closure_rel_tol * a,
        });
    }
    Ok(Closure {
        centre_distance: a,
        error_estimate,
        iterations,
    })
}

/// What is wrong with radii that admit no closure: the first that is not positive and
/// finite, or whose double is not finite, by its sample, or their absence.
#[cold]
fn bad_radii(rho: &[f64]) -> Error {
    (rho.iter().enumerate())
        .find_map(|(j, &r)| {
            let name = format!("the closure's radius at sample {j}");
            let huge = || Error::OutOfRange {
                name: name.clone(),
                value: r,
                expected: "at most half the largest f64 (mm): the centre distance may reach \
                           twice the largest radius"
                    .into(),
            };
            let err = positive(&name, r).err();
            err.or_else(|| (2.0 * r == f64::INFINITY).then(huge))
        })
        .unwrap_or(Error::TooFewPoints {
            kind: "the closure's radii",
            min: 1,
            got: rho.len(),
        })
}

/// The least and the largest of the radii (`+∞` and 0 for none), a NaN passed over.
fn radius_extremes(rho: &[f64]) -> (f64, f64) {
    let (mut rmin, mut rmax) = (f64::INFINITY, 0.0f64);
    for &r in rho {
        // Comparisons, not `min` and `max`, whose NaN rule costs four instructions each: a
        // NaN radius fails both and is passed over, as they pass it over.
        if r < rmin {
            rmin = r;
        }
        if r > rmax {
            rmax = r;
        }
    }
    (rmin, rmax)
}

/// Sums of `rho/(a - rho)` over the even and over the odd samples, and the sum of its
/// derivative in `a` over all; `None` if `a ≤ rmax`, the largest radius
/// ([`radius_extremes`]). One division per sample, in four lanes (a sample's lane is its
/// index mod 4), each summed in sample order: two pairs of vector lanes (`wide::f64x2`),
/// whose arithmetic is each lane's own IEEE operation. The least gap `a − ρ` is
/// `a − rmax` itself, as rounding keeps the order, so it is not tracked per sample.
#[inline]
fn ratio_sums(rho: &[f64], a: f64, rmax: f64) -> Option<([f64; 2], f64)> {
    let (zero, a2) = (f64x2::ZERO, f64x2::splat(a));
    let (mut q, mut dq) = ([zero; 2], [zero; 2]);
    let (chunks, tail) = rho.as_chunks::<4>();
    for c in chunks {
        let pairs = [f64x2::new([c[0], c[1]]), f64x2::new([c[2], c[3]])];
        for (p, r) in pairs.into_iter().enumerate() {
            let inv = f64x2::ONE / (a2 - r);
            let term = r * inv;
            q[p] += term;
            dq[p] -= term * inv;
        }
    }
    let [mut q, mut dq] = [q, dq].map(|[lo, hi]| {
        let (lo, hi) = (lo.to_array(), hi.to_array());
        [lo[0], lo[1], hi[0], hi[1]]
    });
    // The tail starts at an index divisible by 4: its lane parity is its index parity.
    for (l, &r) in tail.iter().enumerate() {
        let gap = a - r;
        q[l] += r / gap;
        dq[l] -= r / (gap * gap);
    }
    (a - rmax > 0.0).then_some(([q[0] + q[2], q[1] + q[3]], dq.iter().sum()))
}

/// The driven curve's `(ρ2, dρ2/dφ2, d²ρ2/dφ2²)` at the contact where the driver shows `p`.
#[inline]
pub(crate) fn conjugate_polar(p: Polar, a: f64) -> Polar {
    let gap = a - p.rho;
    // dφ2/dψ = ρ/(a-ρ); dρ2/dψ = -ρ'. One division: everything is over powers of ρ.
    let (inv, slope2) = (1.0 / p.rho, p.d1 * p.d1);
    let q = -p.d1 * gap * inv;
    let dq = inv * (slope2 * (1.0 + gap * inv) - p.d2 * gap);
    Polar {
        rho: gap,
        d1: q,
        d2: dq * gap * inv,
    }
}

/// Which reading of the module objective: the spec's undercut rule, or the perimeter alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum ModuleReading {
    /// The largest module whose teeth the curvature allows without undercut (spec §1.4).
    #[default]
    Undercut,
    /// `m = L/(πz)` for the given tooth count, with no undercut check: how the three-arm
    /// paper most likely computed its 2.5 mm (docs/replication.md).
    Perimeter,
    /// `m = L/(πz)` for the given tooth count, met only if the teeth cut with
    /// `gear.teeth` pass every check (undercut, tip land, whole-cycle mesh): the teeth
    /// stage replaces the curvature proxy (docs/teeth.md).
    Teeth,
}

/// How teeth may be cut: the rules that bound the module (spec §1.4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ModuleRule {
    /// Which reading: `undercut` (the default) or `perimeter`.
    pub rule: ModuleReading,
    /// Tooth count of the `perimeter` reading (shared by meshing gears).
    pub teeth: Option<u32>,
    /// Fewest teeth of a rack that cut a convex arc without undercut (17 for a 20° rack).
    pub z_min: f64,
    /// Teeth of the shaper cutter for concave arcs; `None` forbids concave arcs.
    pub cutter_teeth: Option<f64>,
}

impl Default for ModuleRule {
    fn default() -> Self {
        Self {
            rule: ModuleReading::Undercut,
            teeth: None,
            z_min: 17.0,
            cutter_teeth: Some(12.0),
        }
    }
}

impl ModuleRule {
    /// Most teeth per gear: 1 000, a module of 0.2 mm on a pitch curve of 600 mm (a
    /// transplanter's gears are under 300 mm round and cut at 1 mm or more). Cutting and
    /// checking the teeth costs about the square of their count (0.13 s for 1 000 on
    /// `ellipse-gear`, 1.1 s for 3 000; 100 000 ran past a minute).
    pub const MAX_TEETH: u32 = 1_000;

    /// Checks the rule, naming the bad value: the `perimeter` reading needs a tooth count.
    pub fn validate(&self) -> Result<()> {
        positive("gear.module.z_min", self.z_min)?;
        if let Some(z) = self.cutter_teeth {
            positive("gear.module.cutter_teeth", z)?;
        }
        match (self.rule, self.teeth) {
            (ModuleReading::Perimeter | ModuleReading::Teeth, None) => Err(Error::Missing {
                name: "gear.module.teeth".into(),
                needed_by: "gear.module.rule = \"perimeter\" or \"teeth\" reads the module \
                            from a tooth count"
                    .into(),
            }),
            (_, Some(z)) if z == 0 || z > Self::MAX_TEETH => Err(Error::OutOfRange {
                name: "gear.module.teeth".into(),
                value: z.into(),
                expected: format!("1 to {}", Self::MAX_TEETH),
            }),
            _ => Ok(()),
        }
    }
}

/// The largest admissible module and what limits it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModuleReport {
    /// Largest admissible module over integer tooth counts (mm); 0 if none is admissible.
    pub module_max_mm: f64,
    /// The tooth count that gives it.
    pub teeth: u32,
    /// Module bound from curvature before rounding to whole teeth (mm).
    pub module_limit_mm: f64,
    /// Least convex radius of curvature over all gears (mm).
    pub min_convex_radius_mm: f64,
    /// Least concave |radius of curvature| over all gears (mm); `None` if none is concave.
    pub min_concave_radius_mm: Option<f64>,
}

/// The module bound from curvature (mm): a convex arc of least radius `min_convex` needs
/// `2ρ/z_min`, a concave one of least |radius| `min_concave` (infinite: none) `2ρ/z_cutter`
/// with a shaper and cannot be cut without one (0).
pub(crate) fn curvature_limit(min_convex: f64, min_concave: f64, rule: &ModuleRule) -> f64 {
    let convex_limit = 2.0 * min_convex / rule.z_min;
    let concave_limit = match rule.cutter_teeth {
        _ if min_concave.is_infinite() => f64::INFINITY,
        Some(z) => 2.0 * min_concave / z,
        None => 0.0,
    };
    convex_limit.min(concave_limit)
}

/// Largest module for a ratio-1 train whose gears show the given curvature radii and share
/// the pitch perimeter (mm) that `perimeter` gives: asked only when the module depends on
/// it (not when the curvature allows no module at all).
pub(crate) fn module_max(
    perimeter: impl FnOnce() -> f64,
    min_convex: f64,
    min_concave: f64,
    rule: &ModuleRule,
) -> ModuleReport {
    let limit = curvature_limit(min_convex, min_concave, rule);
    let by_count = matches!(rule.rule, ModuleReading::Perimeter | ModuleReading::Teeth);
    let (teeth, module) = if let (true, Some(z)) = (by_count, rule.teeth) {
        (z, perimeter() / (std::f64::consts::PI * f64::from(z)))
    } else if limit > 0.0 {
        let perimeter = perimeter();
        let z = (perimeter / (std::f64::consts::PI * limit) - 1e-9)
            .ceil()
            .max(1.0);
        (z as u32, perimeter / (std::f64::consts::PI * z))
    } else {
        (0, 0.0)
    };
    ModuleReport {
        module_max_mm: module,
        teeth,
        module_limit_mm: limit,
        min_convex_radius_mm: min_convex,
        min_concave_radius_mm: min_concave.is_finite().then_some(min_concave),
    }
}

/// The driver's least convex and least concave |R_c| (mm; infinite where it has none):
/// known before the closure. Its scan takes lengths in units of the curve's largest radius
/// `rho_max` (mm), so that no power overflows.
pub(crate) fn driver_curvature_extremes(samples: &[Polar], rho_max: f64) -> (f64, f64) {
    extremes_of(samples, 1.0 / rho_max, |p| p.curvature(), false)
}

/// The least convex and least concave |R_c| of the driver's conjugate at centre
/// distance `a` (mm), at the contacts of `samples`.
pub(crate) fn conjugate_curvature_extremes(samples: &[Polar], a: f64) -> (f64, f64) {
    extremes_of(
        samples,
        1.0 / a,
        |p| conjugate_polar(p, a).curvature(),
        true,
    )
}

/// One gear's least convex and concave |R_c|. The scan for the extreme samples orders
/// them by the curvature's signed square ([`curvature_order`]) in units of `1/inv_unit`:
/// one division per sample, where `κ` itself costs a root and two divisions (three for
/// the conjugate). The divider is the scan's bottleneck. Only the three samples around
/// each extreme take `κ` itself.
fn extremes_of(
    samples: &[Polar],
    inv_unit: f64,
    kappa_at: impl Fn(Polar) -> f64,
    driven: bool,
) -> (f64, f64) {
    let n = samples.len();
    // `j` is at most 2n − 1 here: a subtraction wraps it (no integer division per sample).
    let kappa = |j: usize| kappa_at(samples[if j < n { j } else { j - n }]);
    let ((jmax, kmax), (jmin, kmin)) = extreme_orders(samples, inv_unit, driven);
    let refine = |j: usize, sign: f64| {
        let (ym, y0, yp) = (
            sign * kappa(j + n - 1),
            sign * kappa(j),
            sign * kappa(j + 1),
        );
        sign * parabola_vertex(ym, y0, yp)
    };
    // `min` from infinity: a refinement that broke down (NaN) counts as none.
    let (mut convex, mut concave) = (f64::INFINITY, f64::INFINITY);
    if kmax > 0.0 {
        convex = convex.min(1.0 / refine(jmax, -1.0));
    }
    if kmin < 0.0 {
        concave = concave.min(-1.0 / refine(jmin, 1.0));
    }
    (convex, concave)
}

/// The first samples of the largest and of the least [`curvature_order`], and those
/// orders: `(0, −∞)` and `(0, +∞)` where none is a number. Even and odd samples in two
/// vector lanes (`wide::f64x2`, each lane's arithmetic the scalar's), each keeping the
/// first of its extremes; a tie between the lanes goes to the earlier sample. The
/// divisions of two samples take one instruction.
fn extreme_orders(samples: &[Polar], inv_unit: f64, driven: bool) -> ((usize, f64), (usize, f64)) {
    let (pairs, tail) = samples.as_chunks::<2>();
    let unit = f64x2::splat(inv_unit);
    let (mut kmax, mut kmin) = (f64x2::splat(f64::NEG_INFINITY), f64x2::splat(f64::INFINITY));
    // Sample indices as floats (exact below 2⁵³).
    let (mut jmax, mut jmin, mut j) = (f64x2::ZERO, f64x2::ZERO, f64x2::new([0.0, 1.0]));
    for [p, q] in pairs {
        let [r, d1, d2] =
            [[p.rho, q.rho], [p.d1, q.d1], [p.d2, q.d2]].map(|v| f64x2::new(v) * unit);
        let s = r * r + d1 * d1;
        let (numerator, gap) = if driven {
            let g = f64x2::ONE - r;
            (r * r * r + d1 * d1 * (r - g) + r * d2 * g, g)
        } else {
            (r * r + f64x2::splat(2.0) * d1 * d1 - r * d2, f64x2::ONE)
        };
        let k = numerator * numerator.abs() / (gap * gap * s * s * s);
        let above = k.cmp_gt(kmax);
        (kmax, jmax) = (above.blend(k, kmax), above.blend(j, jmax));
        let below = k.cmp_lt(kmin);
        (kmin, jmin) = (below.blend(k, kmin), below.blend(j, jmin));
        j += f64x2::splat(2.0);
    }
    // The lanes' extremes, then the odd sample left, each against the earlier candidate.
    let lanes = |k: f64x2, j: f64x2| {
        let (k, j) = (k.to_array(), j.to_array());
        [(j[0] as usize, k[0]), (j[1] as usize, k[1])]
    };
    let first_of = |best: (usize, f64), other: (usize, f64), beats: fn(f64, f64) -> bool| {
        if beats(other.1, best.1) || (other.1 == best.1 && other.0 < best.0) {
            other
        } else {
            best
        }
    };
    let [max0, max1] = lanes(kmax, jmax);
    let [min0, min1] = lanes(kmin, jmin);
    let (mut largest, mut least) = (
        first_of(max0, max1, |a, b| a > b),
        first_of(min0, min1, |a, b| a < b),
    );
    for (i, &p) in tail.iter().enumerate() {
        let k = (2 * pairs.len() + i, curvature_order(p, inv_unit, driven));
        largest = first_of(largest, k, |a, b| a > b);
        least = first_of(least, k, |a, b| a < b);
    }
    (largest, least)
}

/// The signed square `(κu)|κu|` of the curvature `κ` of the driver at `p`, or of its
/// conjugate at the same contact (`driven`), in units of a length `u` (given as
/// `inv_unit = 1/u`, mm⁻¹): the same order as `κ`, without its root. For the conjugate
/// `u` is the centre distance `a`; for the driver, the curve's largest radius. In such
/// units no power overflows. With `S = ρ² + ρ'²` and the gap `g = a − ρ`, the
/// driver's `κ` is `(ρ² + 2ρ'² − ρρ'')/S^{3/2}` and the conjugate's, [`conjugate_polar`]'s
/// curve, is `(ρ³ + ρ'²(ρ − g) + ρρ''g)/(g·S^{3/2})` (its `ρ`-powers cleared).
#[inline]
pub(crate) fn curvature_order(p: Polar, inv_unit: f64, driven: bool) -> f64 {
    let (r, d1, d2) = (p.rho * inv_unit, p.d1 * inv_unit, p.d2 * inv_unit);
    let s = r * r + d1 * d1;
    let (numerator, gap) = if driven {
        let g = 1.0 - r;
        (r * r * r + d1 * d1 * (r - g) + r * d2 * g, g)
    } else {
        (r * r + 2.0 * d1 * d1 - r * d2, 1.0)
    };
    numerator * numerator.abs() / (gap * gap * s * s * s)
}

/// Sense in which the carrier turns, seen in the frame with `y` up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Rotation {
    /// `phiH = phi0 - θ` (paper eq. 4).
    Clockwise,
    /// `phiH = phi0 + θ`.
    Counterclockwise,
}

impl Rotation {
    /// `σ`: −1 clockwise, +1 counter-clockwise.
    pub fn sign(self) -> f64 {
        match self {
            Rotation::Clockwise => -1.0,
            Rotation::Counterclockwise => 1.0,
        }
    }

    /// The other sense.
    pub fn reversed(self) -> Self {
        match self {
            Rotation::Clockwise => Rotation::Counterclockwise,
            Rotation::Counterclockwise => Rotation::Clockwise,
        }
    }
}

/// Where a gear pair samples its driver: `psi_j = start ± j·2π/N` (+ counter-clockwise). The gear command
/// uses [`SampleGrid::STANDARD`]; the planetary train samples the sun on its carrier grid
/// (its start and its rotation sense), so one solved pair serves the motion, the module and
/// the outlines.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleGrid {
    /// Driver parameter of node 0 (rad).
    pub start: f64,
    /// The sense in which the nodes advance in ψ.
    pub sense: Rotation,
}

impl SampleGrid {
    /// `psi_j = j·2π/N`.
    pub const STANDARD: SampleGrid = SampleGrid {
        start: 0.0,
        sense: Rotation::Counterclockwise,
    };
}

/// A driver's pitch curve sampled on its grid, before the closure: the first stage of
/// [`GearPair::solve_on`]. What the driver's own curvature allows of the module is known
/// here; the conjugate's can only lower it. A solved [`GearPair`] keeps it.
#[derive(Debug, Clone)]
pub(crate) struct SampledDriver {
    curve: PitchCurve,
    resolution: Resolution,
    grid: SampleGrid,
    /// Driver samples at the grid's nodes, positive and finite.
    samples: Vec<Polar>,
    /// The curve's own least and largest radius (mm; exact or refined between samples).
    radius_range: (f64, f64),
    /// The pitch perimeter (mm), computed on first use.
    perimeter: OnceLock<f64>,
    /// The driver's least convex and concave |R_c| (mm), computed on first use.
    driver_extremes: OnceLock<(f64, f64)>,
}

/// Whether a driver sample's radius is positive and its derivatives finite.
fn valid(p: &Polar) -> bool {
    p.rho > 0.0 && p.d1.is_finite() && p.d2.is_finite()
}

/// Whether every sample is [`valid`]: two samples at a time in vector lanes, without a
/// branch each (the first bad sample is looked for only where there is one).
fn all_valid(samples: &[Polar]) -> bool {
    let (pairs, tail) = samples.as_chunks::<2>();
    // `is_finite` in lanes: |x| < ∞, false for a NaN.
    let finite = |x: f64x2| x.abs().cmp_lt(f64x2::splat(f64::INFINITY));
    let mut all = f64x2::ZERO.cmp_eq(f64x2::ZERO); // true in both lanes
    for [p, q] in pairs {
        let [rho, d1, d2] = [[p.rho, q.rho], [p.d1, q.d1], [p.d2, q.d2]].map(f64x2::new);
        all &= rho.cmp_gt(f64x2::ZERO) & finite(d1) & finite(d2);
    }
    all.move_mask() == 0b11 && tail.iter().all(valid)
}

impl SampledDriver {
    /// Samples `curve` on `grid` at `resolution`; the samples must be positive and finite.
    pub(crate) fn sample(
        curve: PitchCurve,
        resolution: Resolution,
        grid: SampleGrid,
    ) -> Result<Self> {
        resolution.validate()?;
        let n = resolution.samples_per_turn;
        let sense = grid.sense.sign();
        let samples = curve.sample_uniform(grid.start, sense * TAU / n as f64, n);
        if let Some((j, p)) = (!all_valid(&samples))
            .then(|| samples.iter().enumerate().find(|(_, p)| !valid(p)))
            .flatten()
        {
            return Err(Error::NonPositiveRadius {
                psi_deg: (grid.start.to_degrees() + sense * 360.0 * j as f64 / n as f64)
                    .rem_euclid(360.0),
                rho_mm: p.rho,
            });
        }
        let radius_range = curve.radius_range(&samples);
        Ok(Self {
            curve,
            resolution,
            grid,
            samples,
            radius_range,
            perimeter: OnceLock::new(),
            driver_extremes: OnceLock::new(),
        })
    }

    /// The most that any pair of this driver can have as its module under `rule` (mm):
    /// [`GearPair::module`]'s `module_max_mm` with the driver's curvature alone (the least
    /// radii of both gears are no larger than the driver's, and the module grows with them).
    pub(crate) fn module_bound(&self, rule: &ModuleRule) -> f64 {
        let (convex, concave) = self.extremes();
        module_max(|| self.perimeter(), convex, concave, rule).module_max_mm
    }

    /// The pitch perimeter (mm), computed once.
    fn perimeter(&self) -> f64 {
        *(self.perimeter).get_or_init(|| self.curve.perimeter(&self.samples))
    }

    /// The driver's least convex and concave |R_c| (mm), computed once.
    fn extremes(&self) -> (f64, f64) {
        *(self.driver_extremes)
            .get_or_init(|| driver_curvature_extremes(&self.samples, self.radius_range.1))
    }

    /// Solves the closure and integrates the driven angle, reusing planned transforms
    /// (re-planned if the length differs). The curve must stay inside the centre distance
    /// between the samples too.
    pub(crate) fn close(self, integrator: &mut SpectralIntegrator) -> Result<GearPair> {
        let n = self.samples.len();
        // The radii for the closure first, then the ratio (one allocation).
        let mut ratio_nodes: Vec<f64> = self.samples.iter().map(|p| p.rho).collect();
        let closure = solve_closure(&ratio_nodes, &self.resolution)?;
        let a = closure.centre_distance;
        if self.radius_range.1 >= a {
            return Err(Error::SpikeBetweenSamples {
                rho_max_mm: self.radius_range.1,
                centre_distance_mm: a,
            });
        }
        for (g, p) in ratio_nodes.iter_mut().zip(&self.samples) {
            *g = p.rho / (a - p.rho);
        }
        let mut phi2_nodes = vec![0.0; n];
        if integrator.len() != n {
            *integrator = SpectralIntegrator::new(n);
        }
        let phi2_mean_rate = integrator.cumulative(&ratio_nodes, &mut phi2_nodes);
        Ok(GearPair {
            driver: self,
            closure,
            ratio_nodes,
            phi2_nodes,
            phi2_mean_rate,
            ratio_coeffs: OnceLock::new(),
        })
    }
}

/// A solved gear pair: the driver's pitch curve, its conjugate at the closing centre
/// distance, sampled on one [`SampleGrid`].
///
/// An ellipse turning about a focus meshes with its own copy: the closure puts the centres
/// two semi-major axes apart, and the ratio runs from `(1 − k)/(1 + k)` to its inverse.
///
/// ```
/// use noncirc_core::{CurveSpec, GearPair, Resolution};
///
/// let ellipse = CurveSpec::Ellipse { semi_major_mm: 30.0, eccentricity: 0.2 };
/// let pair = GearPair::solve(ellipse.build().unwrap(), Resolution::DEFAULT).unwrap();
/// assert!((pair.centre_distance() - 60.0).abs() < 1e-6);
/// let (lo, hi) = (pair.ratio_nodes().iter().copied())
///     .fold((f64::MAX, f64::MIN), |(lo, hi), r| (lo.min(r), hi.max(r)));
/// assert!((lo - 0.8 / 1.2).abs() < 1e-3 && (hi - 1.2 / 0.8).abs() < 2e-3);
/// ```
#[derive(Debug, Clone)]
pub struct GearPair {
    /// The driver as sampled on the grid, with what is known of it before the closure.
    driver: SampledDriver,
    closure: Closure,
    /// `dφ2/du = ρ/(a − ρ)` at the nodes (`u`: the driver's turn along the grid).
    ratio_nodes: Vec<f64>,
    /// Driven angle at the nodes (rad, 0 at node 0).
    phi2_nodes: Vec<f64>,
    /// Mean of `ratio_nodes` (1 up to the closure error): the driven turn per driver turn.
    phi2_mean_rate: f64,
    /// Fourier coefficients of the ratio (k ≥ 0) for `phi2` between nodes, computed on
    /// first use: the planetary train interpolates its own way and never pays for them.
    ratio_coeffs: OnceLock<Vec<Complex64>>,
}

impl GearPair {
    /// Samples the curve on the standard grid, solves the closure and integrates the
    /// driven angle.
    pub fn solve(curve: PitchCurve, resolution: Resolution) -> Result<Self> {
        resolution.validate()?;
        let mut integrator = SpectralIntegrator::new(resolution.samples_per_turn);
        Self::solve_with(curve, resolution, &mut integrator)
    }

    /// As [`GearPair::solve`], reusing planned transforms (re-planned if the length differs).
    pub(crate) fn solve_with(
        curve: PitchCurve,
        resolution: Resolution,
        integrator: &mut SpectralIntegrator,
    ) -> Result<Self> {
        Self::solve_on(curve, resolution, SampleGrid::STANDARD, integrator)
    }

    /// As [`GearPair::solve_with`], on any sample grid. Every pair of the crate is solved
    /// here: the samples must be positive and finite, the closure must converge, and the
    /// curve must stay inside the centre distance between the samples too.
    pub(crate) fn solve_on(
        curve: PitchCurve,
        resolution: Resolution,
        grid: SampleGrid,
        integrator: &mut SpectralIntegrator,
    ) -> Result<Self> {
        SampledDriver::sample(curve, resolution, grid)?.close(integrator)
    }

    /// The driver's pitch curve.
    pub fn curve(&self) -> &PitchCurve {
        &self.driver.curve
    }

    /// The resolution that produced this pair.
    pub fn resolution(&self) -> Resolution {
        self.driver.resolution
    }

    /// The closure solution (centre distance, error estimate, iterations).
    pub fn closure(&self) -> Closure {
        self.closure
    }

    /// Centre distance `a` (mm).
    pub fn centre_distance(&self) -> f64 {
        self.closure.centre_distance
    }

    /// The grid the driver is sampled on.
    pub fn grid(&self) -> SampleGrid {
        self.driver.grid
    }

    /// Driver parameter of node `j` (rad): `start ± j·2π/N`, not wrapped.
    pub fn psi(&self, j: usize) -> f64 {
        self.driver.grid.start
            + self.driver.grid.sense.sign() * TAU * j as f64 / self.driver.samples.len() as f64
    }

    /// Driver samples at the grid's nodes.
    pub fn samples(&self) -> &[Polar] {
        &self.driver.samples
    }

    /// The driver curve's least and largest radius (mm), exact or refined between samples.
    pub fn radius_range(&self) -> (f64, f64) {
        self.driver.radius_range
    }

    /// `dφ2/du = ρ/(a − ρ)` at the nodes, `u` being the driver's turn along the grid.
    pub fn ratio_nodes(&self) -> &[f64] {
        &self.ratio_nodes
    }

    /// Driven angle at the nodes (rad, 0 at node 0; on the standard grid `phi2(psi_j)`).
    pub fn phi2_nodes(&self) -> &[f64] {
        &self.phi2_nodes
    }

    /// Mean driven turn per driver turn (1 up to the closure error).
    pub fn phi2_mean_rate(&self) -> f64 {
        self.phi2_mean_rate
    }

    /// Driven rotation `phi2(u)` (rad) after the driver has turned by `u` along the grid from
    /// node 0 (on the standard grid `u = psi`), by the trigonometric interpolant of the
    /// sampled ratio integrated term by term (O(N) per call; spectrally accurate). For even
    /// N the Nyquist term is dropped, as in the node values.
    pub fn phi2(&self, u: f64) -> f64 {
        let coeffs = self.ratio_coeffs.get_or_init(|| {
            SpectralIntegrator::new(self.ratio_nodes.len()).coefficients(&self.ratio_nodes)
        });
        let mean = coeffs[0].re;
        let mut periodic = 0.0;
        for (k, c) in coeffs.iter().enumerate().skip(1) {
            let kf = k as f64;
            // 2 Re[(c_k/(ik)) (e^{iku} - 1)]
            let (s, co) = (kf * u).sin_cos();
            periodic += 2.0 / kf * (c.im * (co - 1.0) + c.re * s);
        }
        mean * u + periodic
    }

    /// The driver's pitch curve in its own frame (mm), at the grid's nodes.
    pub fn driver_points(&self) -> Vec<Vec2> {
        (self.driver.samples.iter().enumerate())
            .map(|(j, p)| {
                let psi = self.psi(j);
                Vec2::new(p.rho * psi.cos(), p.rho * psi.sin())
            })
            .collect()
    }

    /// The driver's pitch curve as `(r, own angle, dχ)` at the nodes: radius (mm), own
    /// angle and quadrature weight (rad) of a trapezoid rule over one turn
    /// ([`Blank::from_polar`](crate::blank::Blank::from_polar)).
    pub fn driver_polar(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        let h = TAU / self.driver.samples.len() as f64;
        (self.driver.samples.iter().enumerate()).map(move |(j, p)| (p.rho, self.psi(j), h))
    }

    /// The driven pitch curve likewise: radius `a − ρ` at own angle `∓φ2` (as
    /// [`GearPair::driven_points`]), weight `dφ2 = g·dψ`.
    pub fn driven_polar(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        let (a, sense) = (self.centre_distance(), self.driver.grid.sense.sign());
        let h = TAU / self.driver.samples.len() as f64;
        (self
            .driver
            .samples
            .iter()
            .zip(&self.phi2_nodes)
            .zip(&self.ratio_nodes))
        .map(move |((p, phi2), g)| (a - p.rho, -sense * phi2, g * h))
    }

    /// Computes the spectrum [`GearPair::phi2`] interpolates with the caller's planned
    /// transforms (of the pair's sample count), so that a caller evaluating many pairs does
    /// not plan one per pair.
    pub(crate) fn prepare_phi2(&self, integrator: &mut SpectralIntegrator) {
        self.ratio_coeffs.get_or_init(|| {
            if integrator.len() != self.ratio_nodes.len() {
                *integrator = SpectralIntegrator::new(self.ratio_nodes.len());
            }
            integrator.coefficients(&self.ratio_nodes)
        });
    }

    /// The driven gear's pitch curve in its own frame (mm): the point that meets the driver's
    /// node `j` sits at radius `a − ρ_j` and own angle `−sense·phi2_j`, angle 0 meeting node 0.
    pub fn driven_points(&self) -> Vec<Vec2> {
        let a = self.centre_distance();
        let sense = self.driver.grid.sense.sign();
        (self.driver.samples.iter().zip(&self.phi2_nodes))
            .map(|(p, phi2)| {
                let (s, c) = (-sense * phi2).sin_cos();
                Vec2::new((a - p.rho) * c, (a - p.rho) * s)
            })
            .collect()
    }

    /// Transmission ratio `i12 = ω1/ω2 = (a - ρ)/ρ` at the driver parameter `psi` (rad,
    /// absolute: not a turn along the grid as for [`GearPair::phi2`]).
    pub fn ratio(&self, psi: f64) -> f64 {
        let r = self.driver.curve.eval(psi).rho;
        (self.centre_distance() - r) / r
    }

    /// Driver pitch perimeter (mm); the driven gear's is equal.
    pub fn perimeter(&self) -> f64 {
        self.driver.perimeter()
    }

    /// Largest admissible module over the pair's teeth.
    pub fn module(&self, rule: &ModuleRule) -> ModuleReport {
        let (convex, concave) = self.driver.extremes();
        let (conj_convex, conj_concave) =
            conjugate_curvature_extremes(&self.driver.samples, self.centre_distance());
        module_max(
            || self.perimeter(),
            convex.min(conj_convex),
            concave.min(conj_concave),
            rule,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{CurveSpec, Ellipse};

    /// Least convex and least concave |R_c| of the driver and its conjugate at the given
    /// uniform samples, each refined by the parabola through the extreme sample of the
    /// curvature and its neighbours: the least of [`driver_curvature_extremes`] and
    /// [`conjugate_curvature_extremes`], as [`GearPair::module`] takes them.
    fn curvature_extremes(samples: &[Polar], a: f64) -> (f64, f64) {
        let largest = samples.iter().fold(0.0, |m: f64, p| m.max(p.rho));
        let (convex, concave) = driver_curvature_extremes(samples, largest);
        let (conj_convex, conj_concave) = conjugate_curvature_extremes(samples, a);
        (convex.min(conj_convex), concave.min(conj_concave))
    }

    fn ellipse_pair(k: f64, n: usize) -> GearPair {
        let res = Resolution {
            samples_per_turn: n,
            closure_rel_tol: 1e-6,
            ..Resolution::DEFAULT
        };
        GearPair::solve(PitchCurve::Ellipse(Ellipse::new(30.0, k).unwrap()), res).unwrap()
    }

    #[test]
    fn circle_closes_at_twice_the_radius_with_unit_ratio() {
        let pair = ellipse_pair(0.0, 60);
        assert!((pair.centre_distance() - 60.0).abs() < 1e-12);
        for k in 0..20 {
            assert!((pair.ratio(0.3 * k as f64) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn conjugate_polar_matches_finite_differences_of_the_driven_curve() {
        let spec = CurveSpec::paper();
        let pair = GearPair::solve(spec.build().unwrap(), Resolution::DEFAULT).unwrap();
        let a = pair.centre_distance();
        let curve = pair.curve();
        for k in 1..30 {
            let psi = 0.2 * k as f64;
            let h = 1e-5;
            let (p0, pm, pp) = (curve.eval(psi), curve.eval(psi - h), curve.eval(psi + h));
            let c = conjugate_polar(p0, a);
            // Driven curve as a function of phi2: use dphi2/dpsi = rho/(a - rho).
            let dphi = |p: Polar| p.rho / (a - p.rho);
            let d1_fd = ((a - pp.rho) - (a - pm.rho)) / (2.0 * h) / dphi(p0);
            assert!((d1_fd - c.d1).abs() < 1e-6, "{d1_fd} vs {}", c.d1);
            let (cm, cp) = (conjugate_polar(pm, a), conjugate_polar(pp, a));
            let d2_fd = (cp.d1 - cm.d1) / (2.0 * h) / dphi(p0);
            assert!(
                (d2_fd - c.d2).abs() < 1e-4 * (1.0 + c.d2.abs()),
                "{d2_fd} vs {}",
                c.d2
            );
        }
    }

    #[test]
    fn curvature_order_is_the_signed_square_of_the_curvature() {
        // The paper's curve and its conjugate, sampled: the closed form without the
        // conjugate's division equals (κa)|κa| of the conjugate curve itself.
        let pair =
            GearPair::solve(CurveSpec::paper().build().unwrap(), Resolution::DEFAULT).unwrap();
        let a = pair.centre_distance();
        let mut signs = [0; 2];
        for &p in pair.samples() {
            for (driven, k) in [
                (false, p.curvature()),
                (true, conjugate_polar(p, a).curvature()),
            ] {
                // Relative to the square, or near an inflection (κ → 0, where both forms
                // cancel) to 1e-3 (κa of 0.03).
                let (order, ka) = (curvature_order(p, 1.0 / a, driven), k * a);
                assert!(
                    (order - ka * ka.abs()).abs() <= 1e-12 * (ka * ka).max(1e-3),
                    "{driven}: {order} against {}",
                    ka * ka.abs()
                );
                signs[(k < 0.0) as usize] += 1;
            }
        }
        // Both signs met: convex and concave stretches.
        assert!(signs[0] > 0 && signs[1] > 0, "{signs:?}");
    }

    #[test]
    fn curvature_extremes_scale_with_the_curve_at_any_size() {
        // The paper's pair scaled by 1e±100: the least radii scale with it (the scan's
        // powers, taken in units of the centre distance, neither overflow nor underflow).
        let pair =
            GearPair::solve(CurveSpec::paper().build().unwrap(), Resolution::DEFAULT).unwrap();
        let a = pair.centre_distance();
        let (convex, concave) = curvature_extremes(pair.samples(), a);
        assert!(convex.is_finite() && concave.is_finite());
        for scale in [1e-100, 1e100] {
            let scaled: Vec<Polar> = (pair.samples().iter())
                .map(|p| Polar {
                    rho: p.rho * scale,
                    d1: p.d1 * scale,
                    d2: p.d2 * scale,
                })
                .collect();
            let (cx, cc) = curvature_extremes(&scaled, a * scale);
            assert!(
                (cx / scale - convex).abs() <= 1e-12 * convex,
                "{scale}: {cx}"
            );
            assert!(
                (cc / scale - concave).abs() <= 1e-12 * concave,
                "{scale}: {cc}"
            );
        }
    }

    /// Values that make ties, NaNs and infinities likely, for the lanes' tests.
    fn awkward() -> impl proptest::strategy::Strategy<Value = f64> {
        use proptest::prelude::*;
        prop_oneof![
            6 => 1.0f64..80.0,
            2 => prop::sample::select(vec![5.0, 20.0, 40.0]),
            1 => prop::sample::select(vec![0.0, -3.0, f64::NAN, f64::INFINITY, 1e300]),
        ]
    }

    proptest::proptest! {
        /// The closure takes radii that are all positive and finite, and refuses any
        /// other list with the error that names its first bad radius (or its emptiness),
        /// never a panic: lists of any length with ±0, negatives, ±∞ and NaN among them.
        #[test]
        fn the_closure_refuses_bad_radii_by_name(
            picks in proptest::collection::vec(0usize..24, 0..15),
        ) {
            let values = [0.0, -0.0, -3.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 1e308];
            let rho: Vec<f64> = (picks.iter())
                .map(|&i| values.get(i).copied().unwrap_or(30.0 + i as f64))
                .collect();
            let first_bad = rho.iter().position(|r| !(*r > 0.0 && (2.0 * r).is_finite()));
            match (solve_closure(&rho, &Resolution::DEFAULT), first_bad) {
                (Err(Error::TooFewPoints { got: 0, .. }), None) => {
                    proptest::prop_assert!(rho.is_empty())
                }
                (Err(Error::NonFinite { name, value }), Some(j))
                | (Err(Error::OutOfRange { name, value, .. }), Some(j)) => {
                    proptest::prop_assert!(name.ends_with(&format!("sample {j}")), "{}", name);
                    proptest::prop_assert_eq!(value.to_bits(), rho[j].to_bits());
                }
                (Ok(c), None) => proptest::prop_assert!(c.centre_distance > 0.0),
                (Err(Error::UnderResolved { .. }), None) => {}
                (other, bad) => proptest::prop_assert!(false, "{:?} for {:?}", other, bad),
            }
        }
    }

    proptest::proptest! {
        /// The check in lanes is the check of each sample: radii and derivatives drawn
        /// from a few values (±0, negative, huge, ±∞, NaN among them), odd and even counts.
        #[test]
        fn samples_checked_in_lanes_are_each_checked(
            picks in proptest::collection::vec((0usize..40, 0usize..40, 0usize..40), 0..12),
        ) {
            let values = [1.5, -0.0, 0.0, -2.0, 1e300, f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
            // Mostly good values, so that a bad one is often alone among good ones.
            let pick = |i: usize, good: f64| values.get(i).copied().unwrap_or(good);
            let samples: Vec<Polar> = (picks.iter())
                .map(|&(r, a, b)| Polar {
                    rho: pick(r, 30.0),
                    d1: pick(a, -4.0),
                    d2: pick(b, 0.5),
                })
                .collect();
            proptest::prop_assert_eq!(all_valid(&samples), samples.iter().all(valid));
        }
    }

    proptest::proptest! {
        /// The curvature scan in lanes finds the sequential scan's first largest and first
        /// least order, bit for bit: samples with ties, NaNs and infinities, of odd and
        /// even counts, for the driver and its conjugate.
        #[test]
        fn the_lanes_extreme_orders_are_the_sequential_scans(
            values in proptest::collection::vec(proptest::prop_oneof![
                (awkward(), awkward(), awkward()),
                // Repeated samples: ties within a lane and between the lanes.
                proptest::sample::select(vec![(30.0, 4.0, -9.0), (45.0, -2.0, 60.0)]),
            ], 0..13),
            inv_unit in proptest::prop_oneof![0.01f64..0.1, proptest::strategy::Just(1.0)],
            driven in proptest::bool::ANY,
        ) {
            let samples: Vec<Polar> =
                values.iter().map(|&(rho, d1, d2)| Polar { rho, d1, d2 }).collect();
            let (mut largest, mut least) = ((0, f64::NEG_INFINITY), (0, f64::INFINITY));
            for (j, &p) in samples.iter().enumerate() {
                let k = curvature_order(p, inv_unit, driven);
                if k > largest.1 {
                    largest = (j, k);
                }
                if k < least.1 {
                    least = (j, k);
                }
            }
            let bits = |(j, k): (usize, f64)| (j, k.to_bits());
            let (got_largest, got_least) = extreme_orders(&samples, inv_unit, driven);
            proptest::prop_assert_eq!(bits(got_largest), bits(largest));
            proptest::prop_assert_eq!(bits(got_least), bits(least));
        }

        /// The ratio sums in vector lanes are the four scalar lanes' sums, bit for bit,
        /// and refuse the same centre distances: radii with ties, NaNs and infinities, of
        /// any count, at centre distances below, among and above them.
        #[test]
        fn the_ratio_sums_in_lanes_are_the_scalar_lanes(
            rho in proptest::collection::vec(awkward(), 0..23),
            a in proptest::prop_oneof![1.0f64..200.0, proptest::strategy::Just(40.0)],
        ) {
            let (mut q, mut dq, mut least_gap) = ([0.0; 4], [0.0; 4], [f64::INFINITY; 4]);
            for (j, &r) in rho.iter().enumerate() {
                let (l, gap) = (j % 4, a - r);
                if j < rho.len() / 4 * 4 {
                    let inv = 1.0 / gap;
                    q[l] += r * inv;
                    dq[l] -= r * inv * inv;
                } else {
                    q[l] += r / gap;
                    dq[l] -= r / (gap * gap);
                }
                least_gap[l] = least_gap[l].min(gap);
            }
            let least = least_gap.iter().fold(f64::INFINITY, |m, &g| m.min(g));
            let want = (least > 0.0)
                .then_some(([q[0] + q[2], q[1] + q[3]], dq.iter().sum::<f64>()));
            let bits = |s: Option<([f64; 2], f64)>| {
                s.map(|([e, o], d)| [e.to_bits(), o.to_bits(), d.to_bits()])
            };
            let rmax = radius_extremes(&rho).1;
            proptest::prop_assert_eq!(bits(ratio_sums(&rho, a, rmax)), bits(want));
        }

        /// The module's bound from the driver alone, before the closure, is never below
        /// the pair's module: random 12-point splines (convex, concave and spiky), every
        /// reading, with and without a shaper, on either sense of the grid.
        #[test]
        fn the_drivers_module_bound_is_never_below_the_pairs_module(
            radii in proptest::collection::vec(20.0f64..70.0, 12),
            reading in 0usize..3,
            teeth in proptest::option::of(8u32..60),
            z_min in 8.0f64..30.0,
            cutter in proptest::option::of(10.0f64..40.0),
            reversed in proptest::bool::ANY,
        ) {
            let angles: Vec<f64> = (0..12).map(|k| 30.0 * k as f64 + 7.0).collect();
            let curve = CurveSpec::Spline { radii_mm: radii, angles_deg: angles }.build().unwrap();
            let rule = ModuleRule {
                rule: [ModuleReading::Undercut, ModuleReading::Perimeter, ModuleReading::Teeth]
                    [reading],
                teeth,
                z_min,
                cutter_teeth: cutter,
            };
            let grid = SampleGrid {
                start: 0.4,
                sense: if reversed { Rotation::Clockwise } else { Rotation::Counterclockwise },
            };
            let res = Resolution { samples_per_turn: 90, ..Resolution::DEFAULT };
            let sampled = SampledDriver::sample(curve, res, grid).unwrap();
            let bound = sampled.module_bound(&rule);
            let mut integrator = SpectralIntegrator::new(90);
            if let Ok(pair) = sampled.close(&mut integrator) {
                let module = pair.module(&rule).module_max_mm;
                proptest::prop_assert!(bound >= module, "{} < {}", bound, module);
                // The driver's extremes found before the closure are the pair's.
                let solved = GearPair::solve_on(pair.curve().clone(), res, grid, &mut integrator)
                    .unwrap();
                proptest::prop_assert_eq!(solved.module(&rule), pair.module(&rule));
            }
        }
    }

    #[test]
    fn module_rounds_to_whole_teeth() {
        let r = module_max(|| 100.0, 30.0, f64::INFINITY, &ModuleRule::default());
        assert!(r.module_max_mm <= r.module_limit_mm + 1e-12);
        assert!((r.module_max_mm * std::f64::consts::PI * r.teeth as f64 - 100.0).abs() < 1e-9);
        let forbid = ModuleRule {
            cutter_teeth: None,
            ..ModuleRule::default()
        };
        assert_eq!(module_max(|| 100.0, 30.0, 5.0, &forbid).module_max_mm, 0.0);
    }
}
