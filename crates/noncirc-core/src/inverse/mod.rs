//! Exact inversion for the train with two pairs (docs/inverse.md §6): from a target tip
//! path, the arm length and the carrier's geometry back to both pitch curves.
//!
//! The planet centre moves on a circle of radius `R = |a_A + a_B·e^{iγ0}|` and the tip is
//! a two-link chain, so each point `P` of the path fixes the carrier angle (`O3 = R·e(α)`
//! at distance `S` from `P`) and the arm's direction `A = arg(P − O3)`. The arm makes no
//! net turn while the carrier turns once, so the chain passes through its straight
//! positions once each a loop: the path touches the circles `|P| = R + S` and
//! `|P| = |R − S|`, which fixes R and S, and the elbow changes branch at those two points.
//! The planet's lag behind the carrier, `L(θ) = Φ_B(Φ_A(θ)) = θ − σ(A(θ) − A(0))`, gives
//! the overall ratio `i = L' = 1 − A'/α'`; a split `g_A = i^λ / mean(i^λ)`,
//! `g_B(Φ_A) = i/g_A` shares it between the pairs, and each pitch curve follows from its
//! ratio by `ρ = a·g/(1 + g)`. Both pairs close by construction: `mean g_A = 1`, and
//! `∮ g_B dΦ_A = ∮ i dθ = 2π` when the arm makes no net turn.
//!
//! The target is read as a smoothed Fourier series, and when the best reading's gears
//! miss, its ratio is shaped within the tolerance for buildable curves ([`shaping`]).

mod shaping;

use crate::angle::unit;
use crate::curve::CurveSpec;
use crate::error::{Error, Result};
use crate::evaluation::Evaluation;
use crate::evaluator::Evaluator;
use crate::quadrature::SpectralIntegrator;
use crate::scene::Scene;
use crate::target::Target;
use crate::vec2::Vec2;
use rustfft::num_complex::Complex64;
use rustfft::FftPlanner;
use serde::Serialize;
use shaping::{power_split, RatioShaping};
use std::f64::consts::{PI, TAU};

/// Samples of the target per turn for its Fourier series (a power of two).
const PATH_SAMPLES: usize = 4096;

/// Which of the two planet-centre positions at distance `S` from a path point the chain
/// takes on the arc from the path's farthest point to its nearest (it takes the other on
/// the way back).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// `α = arg P + acos c`: the planet centre turned counter-clockwise from the tip's
    /// direction.
    Plus,
    /// `α = arg P − acos c`.
    Minus,
}

impl Branch {
    fn sign(self) -> f64 {
        match self {
            Branch::Plus => 1.0,
            Branch::Minus => -1.0,
        }
    }
}

/// How to invert: the ratio of the pairs' centre distances, the split of the transmission
/// ratio, the elbow branch (`None`: both, the better kept) and the samples per turn of the
/// curves written. The path fixes the planet-circle radius R and the arm length S; the
/// centre distances follow from R and their ratio.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InverseSpec {
    /// `a_B / a_A`, the intermediate–planet centre distance over the sun–intermediate one.
    pub centre_ratio: f64,
    /// The first pair's share λ of the overall ratio's variation, 0 to 1: `g_A ∝ i^λ`.
    /// 0 makes the first pair circular, ½ shares it equally (geometric), 1 makes the second
    /// pair circular.
    pub split: f64,
    /// The elbow branch; `None` tries both.
    pub branch: Option<Branch>,
    /// Samples per turn of the tabulated curves and of the forward check.
    pub samples_per_turn: usize,
}

impl InverseSpec {
    /// Checks the numbers, naming the bad one.
    pub fn validate(&self, arms: usize) -> Result<()> {
        if !(self.centre_ratio.is_finite() && (0.05..=20.0).contains(&self.centre_ratio)) {
            return Err(Error::OutOfRange {
                name: "centre ratio a_B/a_A".into(),
                value: self.centre_ratio,
                expected: "0.05 to 20".into(),
            });
        }
        if !(0.0..=1.0).contains(&self.split) {
            return Err(Error::OutOfRange {
                name: "split".into(),
                value: self.split,
                expected: "0 (first pair circular) to 1 (second pair circular)".into(),
            });
        }
        let n = self.samples_per_turn;
        if !(64..=65_536).contains(&n) || !n.is_multiple_of(arms) {
            return Err(Error::OutOfRange {
                name: "samples per turn".into(),
                value: n as f64,
                expected: format!("64 to 65536, a multiple of train.arms = {arms}"),
            });
        }
        Ok(())
    }
}

/// Where on the path a condition fails: the arc of the target (mm of arc length from its
/// first point, as the tip runs it), the carrier angles there when known (°), and the
/// worst point (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Place {
    pub path_mm: [f64; 2],
    #[serde(skip_serializing_if = "Option::is_none")]
    pub carrier_deg: Option<[f64; 2]>,
    pub point_mm: Vec2,
}

/// One condition of the inversion: whether it holds, its value against its bound, what it
/// means, and where it fails.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Condition {
    /// `pusher_within_arm`, `carrier_advances`, `carrier_turns_once`, `arm_turns_back`,
    /// `ratio_positive`, `<gear>_convex`, `evaluates`, `path_within_tolerance`,
    /// `pose:<name>` or `objective:<name>`.
    pub name: String,
    pub holds: bool,
    /// Whether failing it leaves no design (the curves cannot be built, or cannot be cut).
    pub blocks: bool,
    pub value: f64,
    pub bound: f64,
    pub unit: &'static str,
    /// What it means, in words.
    pub meaning: String,
    /// Where it fails (empty when it holds, or for a condition of the whole loop).
    pub places: Vec<Place>,
}

/// What the inversion found: the conditions, and when the curves could be built the scene
/// with both tabulated curves and its forward evaluation against the target.
#[derive(Debug, Clone)]
pub struct InverseOutcome {
    pub branch: Branch,
    /// The arm length S and the planet-circle radius R the path fixes (mm), and the
    /// centre distances that follow (mm).
    pub arm_length_mm: f64,
    pub planet_radius_mm: f64,
    pub centre_distances_mm: [f64; 2],
    /// Whether the target was read backwards, to run in the carrier's sense.
    pub reversed: bool,
    /// The half-weight harmonic of the target's smoothed Fourier series, and its largest
    /// distance from the target's points (mm).
    pub half_weight_harmonic: f64,
    pub smoothing_mm: f64,
    /// The largest move of the tip (mm) by the ratio's shaping (0: not shaped).
    pub shaping_mm: f64,
    /// The pusher offset H1 (mm) chosen for the poses' attitudes (`None`: the scene's
    /// kept, as no counting pose names an attitude, or none met it).
    pub pusher_offset_mm: Option<f64>,
    pub conditions: Vec<Condition>,
    pub scene: Option<Scene>,
    pub evaluation: Option<Evaluation>,
}

impl InverseOutcome {
    /// Whether every condition holds (the design meets every objective too).
    pub fn met(&self) -> bool {
        self.scene.is_some() && self.conditions.iter().all(|c| c.holds)
    }

    /// The conditions that fail.
    pub fn failures(&self) -> impl Iterator<Item = &Condition> {
        self.conditions.iter().filter(|c| !c.holds)
    }
}

/// A closed path as a finite Fourier series in `t ∈ [0, 2π)`, `t` proportional to arc
/// length: `z(t) = Σ_k c_k e^{ikt}`.
struct FourierPath {
    /// `(k, c_k)`, by k.
    terms: Vec<(f64, Complex64)>,
    /// The smoothing's half-weight harmonic.
    half_weight: f64,
    length_mm: f64,
}

impl FourierPath {
    /// The smoothest series within `tolerance_mm` of `points` (a closed polyline, sampled
    /// at [`PATH_SAMPLES`] points by arc length): each harmonic of the samples' spectrum
    /// above the first weighted by `1/(1 + (|k|/k½)⁶)`, a periodic smoothing spline
    /// penalising the path's third derivative (which the pitch curves' curvature
    /// follows), with the lowest half-weight harmonic `k½` that keeps within the
    /// tolerance (bisection). A sharp truncation would ripple the third derivative
    /// instead. Also returns the largest distance reached.
    fn fit(points: &[Vec2], tolerance_mm: f64) -> (Self, f64) {
        let (samples, length_mm) = resample(points, PATH_SAMPLES);
        let m = samples.len();
        let mut planner = FftPlanner::new();
        let mut spectrum: Vec<Complex64> =
            samples.iter().map(|p| Complex64::new(p.x, p.y)).collect();
        planner.plan_fft_forward(m).process(&mut spectrum);
        for c in &mut spectrum {
            *c /= m as f64;
        }
        let inverse = planner.plan_fft_inverse(m);
        let harmonic = |i: usize| {
            if i <= m / 2 {
                i as f64
            } else {
                i as f64 - m as f64
            }
        };
        // The centre and the fundamental (an ellipse) are kept whole: the smoothing is
        // for the detail, and would otherwise shrink a circle.
        let weight = |k: f64, half: f64| {
            if k.abs() <= 1.0 {
                1.0
            } else {
                1.0 / (1.0 + (k / half).powi(6))
            }
        };
        let deviation = |half: f64| {
            let mut z: Vec<Complex64> = (spectrum.iter().enumerate())
                .map(|(i, &c)| c * weight(harmonic(i), half))
                .collect();
            inverse.process(&mut z);
            (z.iter().zip(&samples))
                .map(|(z, p)| (Vec2::new(z.re, z.im) - *p).hypot())
                .fold(0.0, f64::max)
        };
        // The least k½ within tolerance, by bisection on its logarithm (the deviation
        // falls as k½ grows); at m/2 the series keeps the samples to within rounding.
        let (mut lo, mut hi) = (1.0f64, (m / 2) as f64);
        let mut reached = deviation(hi);
        if reached > tolerance_mm {
            lo = hi;
        }
        for _ in 0..40 {
            let mid = (lo * hi).sqrt();
            let at_mid = deviation(mid);
            if at_mid <= tolerance_mm {
                (hi, reached) = (mid, at_mid);
            } else {
                lo = mid;
            }
        }
        let half = hi;
        // The smallest terms dropped while together they reach at most a thousandth of the
        // tolerance: nothing it can see, and the series stays short to evaluate.
        let mut terms: Vec<(f64, Complex64)> = (spectrum.iter().enumerate())
            .map(|(i, &c)| (harmonic(i), c * weight(harmonic(i), half)))
            .collect();
        terms.sort_by(|a, b| b.1.norm().total_cmp(&a.1.norm()));
        let mut dropped = 0.0;
        while let Some(last) = terms.last() {
            dropped += last.1.norm();
            if dropped > 1e-3 * tolerance_mm {
                break;
            }
            terms.pop();
        }
        terms.sort_by(|a, b| a.0.total_cmp(&b.0));
        (
            Self {
                terms,
                half_weight: half,
                length_mm,
            },
            reached,
        )
    }

    /// `z(t)` and `z'(t)` (mm, mm/rad).
    fn eval(&self, t: f64) -> (Vec2, Vec2) {
        let [z, dz, _] = self.eval2(t);
        (z, dz)
    }

    /// `z(t)`, `z'(t)` and `z''(t)`.
    fn eval2(&self, t: f64) -> [Vec2; 3] {
        let zero = Complex64::new(0.0, 0.0);
        let (mut z, mut dz, mut ddz) = (zero, zero, zero);
        for &(k, c) in &self.terms {
            let e = c * Complex64::from_polar(1.0, k * t);
            z += e;
            dz += e * Complex64::new(0.0, k);
            ddz -= e * (k * k);
        }
        [z, dz, ddz].map(|z| Vec2::new(z.re, z.im))
    }

    /// The parameter (rad) where `|z|` is largest (`farthest`) or least, refined by Newton
    /// steps on `(|z|²)' = 2 z·z'` from the best of `samples` equally spaced samples.
    fn extreme_radius(&self, samples: usize, farthest: bool) -> f64 {
        let sign = if farthest { 1.0 } else { -1.0 };
        let mut t = (0..samples)
            .map(|k| TAU * k as f64 / samples as f64)
            .max_by(|&a, &b| {
                (sign * self.eval(a).0.hypot2()).total_cmp(&(sign * self.eval(b).0.hypot2()))
            })
            .unwrap_or(0.0);
        let h = TAU / samples as f64;
        for _ in 0..30 {
            let [z, dz, ddz] = self.eval2(t);
            let (f, df) = (z.dot(dz), dz.hypot2() + z.dot(ddz));
            if df == 0.0 {
                break;
            }
            let step = (f / df).clamp(-h, h);
            t -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        t.rem_euclid(TAU)
    }

    /// The same path run backwards: `z(−t)`.
    fn reversed(&self) -> Self {
        Self {
            terms: self.terms.iter().map(|&(k, c)| (-k, c)).collect(),
            half_weight: self.half_weight,
            length_mm: self.length_mm,
        }
    }
}

/// `count` points equally spaced by arc length along the closed polyline, and its length.
fn resample(points: &[Vec2], count: usize) -> (Vec<Vec2>, f64) {
    let n = points.len();
    let mut cumulative = Vec::with_capacity(n + 1);
    cumulative.push(0.0);
    for i in 0..n {
        let step = (points[(i + 1) % n] - points[i]).hypot();
        cumulative.push(cumulative[i] + step);
    }
    let length = cumulative[n];
    let mut out = Vec::with_capacity(count);
    let mut seg = 0;
    for k in 0..count {
        let s = length * k as f64 / count as f64;
        while seg + 1 < n && cumulative[seg + 1] <= s {
            seg += 1;
        }
        let span = cumulative[seg + 1] - cumulative[seg];
        let f = if span > 0.0 {
            (s - cumulative[seg]) / span
        } else {
            0.0
        };
        out.push(points[seg] + (points[(seg + 1) % n] - points[seg]) * f);
    }
    (out, length)
}

/// The two-link chain at one path parameter: the carrier's planet-centre angle and the
/// arm's direction (rad) and their rates in `t`.
#[derive(Debug, Clone, Copy)]
struct Chain {
    point: Vec2,
    alpha: f64,
    alpha_d1: f64,
    arm: f64,
    arm_d1: f64,
}

/// The train's geometry the chain needs.
#[derive(Debug, Clone, Copy)]
struct ChainGeometry {
    /// Planet-circle radius R (mm) and the arm length S (mm).
    radius: f64,
    arm_length: f64,
    /// The branch on the arc from the farthest point `t_far` to the nearest `t_near`
    /// (±1); the other on the way back.
    branch: f64,
    t_far: f64,
    t_near: f64,
}

impl ChainGeometry {
    /// The elbow's branch at `t`.
    fn branch_at(&self, t: f64) -> f64 {
        let from_far = (t - self.t_far).rem_euclid(TAU);
        let to_near = (self.t_near - self.t_far).rem_euclid(TAU);
        if from_far < to_near {
            self.branch
        } else {
            -self.branch
        }
    }

    /// The chain at `t`. Within a micro-radian of a straight position, where the elbow's
    /// rate is 0/0, its rate is the mean of the rates either side.
    fn at(&self, path: &FourierPath, t: f64) -> Chain {
        let near_switch = [self.t_far, self.t_near]
            .iter()
            .any(|&s| ((t - s + PI).rem_euclid(TAU) - PI).abs() < 1e-6);
        let mut chain = self.at_exactly(path, t);
        if near_switch {
            let h = 1e-4;
            let (a, b) = (self.at_exactly(path, t - h), self.at_exactly(path, t + h));
            chain.alpha_d1 = 0.5 * (a.alpha_d1 + b.alpha_d1);
            chain.arm_d1 = 0.5 * (a.arm_d1 + b.arm_d1);
        }
        chain
    }

    fn at_exactly(&self, path: &FourierPath, t: f64) -> Chain {
        let branch = self.branch_at(t);
        let (p, dp) = path.eval(t);
        let (r2, s2, big_r) = (p.hypot2(), self.arm_length.powi(2), self.radius);
        let r = r2.sqrt();
        let c = (big_r * big_r + r2 - s2) / (2.0 * big_r * r);
        let r_d1 = p.dot(dp) / r;
        let c_d1 = r_d1 * (1.0 / (2.0 * big_r) - (big_r * big_r - s2) / (2.0 * big_r * r2));
        let within = c.clamp(-1.0, 1.0);
        let root = (1.0 - within * within).sqrt().max(1e-300);
        let alpha = p.y.atan2(p.x) + branch * within.acos();
        let alpha_d1 = p.cross(dp) / r2 - branch * c_d1 / root;
        let o3 = unit(alpha) * big_r;
        let o3_d1 = unit(alpha).turn_90() * (big_r * alpha_d1);
        let (d, dd) = (p - o3, dp - o3_d1);
        Chain {
            point: p,
            alpha,
            alpha_d1,
            arm: d.y.atan2(d.x),
            arm_d1: d.cross(dd) / d.hypot2(),
        }
    }
}

/// Continuous angles from angles known modulo 2π, in order.
fn unwrap(angles: &mut [f64]) {
    for i in 1..angles.len() {
        let step = angles[i] - angles[i - 1];
        angles[i] -= TAU * (step / TAU).round();
    }
}

/// Runs of consecutive failing samples (cyclic) as index ranges `[first, last]`, each with
/// its worst sample (the largest `badness`).
fn runs(fails: &[bool], badness: impl Fn(usize) -> f64) -> Vec<([usize; 2], usize)> {
    let n = fails.len();
    (cyclic_runs(fails).into_iter())
        .map(|run| {
            let len = (run[1] + n - run[0]) % n + 1;
            let worst = (0..len)
                .map(|i| (run[0] + i) % n)
                .max_by(|&x, &y| badness(x).total_cmp(&badness(y)))
                .unwrap_or(run[0]);
            (run, worst)
        })
        .collect()
}

/// Runs of consecutive failing samples (cyclic) as index ranges `[first, last]`.
fn cyclic_runs(fails: &[bool]) -> Vec<[usize; 2]> {
    let n = fails.len();
    let Some(start) = (0..n).find(|&i| !fails[i]) else {
        return if n == 0 { vec![] } else { vec![[0, n - 1]] };
    };
    let mut out = Vec::new();
    let mut open: Option<usize> = None;
    for step in 1..=n {
        let i = (start + step) % n;
        match (fails[i], open) {
            (true, None) => open = Some(i),
            (false, Some(first)) => {
                out.push([first, (i + n - 1) % n]);
                open = None;
            }
            _ => {}
        }
    }
    if let Some(first) = open {
        out.push([first, (start + n - 1) % n]);
    }
    out
}

/// Inverts `target` for `scene`'s train (its γ0, Φ0, H1, sense, arms and sun frame) with
/// `spec`. `Err` only for bad input;
/// every failing condition is in the outcome. Both senses of the path and both branches
/// are tried (unless `spec` names one): the outcome is the best, the path's own sense
/// first on a tie.
pub fn invert(scene: &Scene, target: &Target, spec: &InverseSpec) -> Result<InverseOutcome> {
    scene.validate()?;
    spec.validate(scene.train.arms)?;
    let prepared = target.prepare()?;
    // The smoothest series within half the tolerance: the design follows the series
    // exactly, so its path is within the tolerance of the points with room to spare, and
    // a drawn spline's kinks in curvature are not copied into the gears.
    let (path, smoothing_mm) = FourierPath::fit(prepared.polyline(), target.tolerance_mm / 2.0);
    let backwards = path.reversed();
    let branches = match spec.branch {
        Some(b) => vec![b],
        None => vec![Branch::Plus, Branch::Minus],
    };
    let score = |o: &InverseOutcome| {
        let blocking = o.failures().filter(|c| c.blocks).count();
        (
            o.evaluation.is_some(),
            usize::MAX - blocking,
            usize::MAX - o.failures().count(),
        )
    };
    let mut best: Option<InverseOutcome> = None;
    for (path, reversed) in [(&path, false), (&backwards, true)] {
        for &branch in &branches {
            let read = (path, reversed, smoothing_mm, branch);
            let outcome = invert_on(scene, target, spec, read, false)?;
            if best.as_ref().is_none_or(|b| score(&outcome) > score(b)) {
                best = Some(outcome);
            }
        }
    }
    let best = best.expect("at least one branch");
    // The ratio is shaped for the best reading only, when its gears are what it misses:
    // a curve the cutter cannot cut, or the module.
    let gears_fail =
        (best.failures()).any(|c| c.name.ends_with("_convex") || c.name == "objective:module");
    if best.evaluation.is_none() || !gears_fail {
        return Ok(best);
    }
    let path = if best.reversed { &backwards } else { &path };
    let read = (path, best.reversed, smoothing_mm, best.branch);
    let shaped = invert_on(scene, target, spec, read, true)?;
    Ok(if score(&shaped) >= score(&best) {
        shaped
    } else {
        best
    })
}

/// One reading of the target: the series (`reversed` or not), its distance from the
/// target's points (mm) and the elbow branch.
type Reading<'a> = (&'a FourierPath, bool, f64, Branch);

/// The inversion of one reading of the target, with the ratio shaped for buildable
/// curves (`shape`) or as read.
fn invert_on(
    scene: &Scene,
    target: &Target,
    spec: &InverseSpec,
    (path, reversed, smoothing_mm, branch): Reading<'_>,
    shape: bool,
) -> Result<InverseOutcome> {
    let train = &scene.train;
    let sigma = train.rotation.sign();
    let (gamma0, phi0) = (train.gamma0_deg.to_radians(), train.phi0_deg.to_radians());
    let m = PATH_SAMPLES;
    // The straight positions of the chain: R + S and |R − S| are the path's extreme radii.
    let (t_far, t_near) = (path.extreme_radius(m, true), path.extreme_radius(m, false));
    let (far, near) = (path.eval(t_far).0.hypot(), path.eval(t_near).0.hypot());
    // A path round the carrier axis needs the planet circle longer than the arm (the tip
    // then circles the axis with the planet); one beside it, the arm longer.
    let mut turning: Vec<f64> = (0..=m)
        .map(|k| {
            let p = path.eval(TAU * k as f64 / m as f64).0;
            p.y.atan2(p.x)
        })
        .collect();
    unwrap(&mut turning);
    let arm_longer = ((turning[m] - turning[0]) / TAU).round() == 0.0;
    let (long, short) = (0.5 * (far + near), 0.5 * (far - near));
    let (arm_length, radius) = if arm_longer {
        (long, short)
    } else {
        (short, long)
    };
    // The carrier's corner: a_A + a_B e^{iγ0} = R e^{iδ}, with a_B = k a_A.
    let corner = Vec2::new(1.0, 0.0) + unit(gamma0) * spec.centre_ratio;
    let a1 = radius / corner.hypot();
    let a2 = spec.centre_ratio * a1;
    let delta = corner.y.atan2(corner.x);
    let geometry = ChainGeometry {
        radius,
        arm_length,
        branch: branch.sign(),
        t_far,
        t_near,
    };
    let t_of = |k: usize| TAU * k as f64 / m as f64;
    let chains: Vec<Chain> = (0..m).map(|k| geometry.at(path, t_of(k))).collect();
    let s_of = |k: usize| path.length_mm * k as f64 / m as f64;
    let place = |run: [usize; 2], worst: usize| Place {
        path_mm: [s_of(run[0]), s_of(run[1])],
        carrier_deg: None,
        point_mm: chains[worst].point,
    };
    let places_where = |fails: &[bool], badness: &dyn Fn(usize) -> f64| -> Vec<Place> {
        (runs(fails, badness).into_iter())
            .map(|(run, worst)| place(run, worst))
            .collect()
    };
    let mut conditions = vec![pusher_within_arm(train.pusher_offset_mm, arm_length)];
    // 2. The carrier advances along the whole path, 3. once a loop.
    let rate: Vec<f64> = chains.iter().map(|c| sigma * c.alpha_d1).collect();
    let fails: Vec<bool> = rate.iter().map(|&r| r <= 0.0).collect();
    let least_rate = rate.iter().copied().fold(f64::INFINITY, f64::min);
    conditions.push(Condition {
        name: "carrier_advances".into(),
        holds: least_rate > 0.0,
        blocks: true,
        value: least_rate,
        bound: 0.0,
        unit: "rad/rad",
        meaning: "the carrier angle increases all along the path (the value is its least \
                  rate per radian of the path's parameter)"
            .into(),
        places: places_where(&fails, &|k| -rate[k]),
    });
    let mut alpha: Vec<f64> = chains.iter().map(|c| c.alpha).collect();
    alpha.push(chains[0].alpha);
    unwrap(&mut alpha);
    let turns = sigma * (alpha[m] - alpha[0]) / TAU;
    conditions.push(Condition {
        name: "carrier_turns_once".into(),
        holds: (turns - 1.0).abs() < 1e-6,
        blocks: true,
        value: turns,
        bound: 1.0,
        unit: "turns",
        meaning: "the carrier turns once, in its sense, as the tip runs round the path once".into(),
        places: vec![],
    });
    let mut arm: Vec<f64> = chains.iter().map(|c| c.arm).collect();
    arm.push(chains[0].arm);
    unwrap(&mut arm);
    let arm_turns = (arm[m] - arm[0]) / TAU;
    conditions.push(Condition {
        name: "arm_turns_back".into(),
        holds: arm_turns.abs() < 1e-6,
        blocks: true,
        value: arm_turns,
        bound: 0.0,
        unit: "turns",
        meaning: "the arm makes no net turn over the loop (the overall ratio averages 1)".into(),
        places: vec![],
    });
    let ratio: Vec<f64> = chains.iter().map(|c| 1.0 - c.arm_d1 / c.alpha_d1).collect();
    let fails: Vec<bool> = ratio.iter().map(|&i| i <= 0.0).collect();
    let least_ratio = ratio.iter().copied().fold(f64::INFINITY, f64::min);
    conditions.push(Condition {
        name: "ratio_positive".into(),
        holds: least_ratio > 0.0,
        blocks: true,
        value: least_ratio,
        bound: 0.0,
        unit: "",
        meaning: "the overall ratio i = 1 − A'/α' stays positive (the arm turns slower \
                  than the carrier, in the sense the gears can drive it)"
            .into(),
        places: places_where(&fails, &|k| -ratio[k]),
    });
    let mut outcome = InverseOutcome {
        branch,
        arm_length_mm: arm_length,
        planet_radius_mm: radius,
        centre_distances_mm: [a1, a2],
        reversed,
        half_weight_harmonic: path.half_weight,
        smoothing_mm,
        shaping_mm: 0.0,
        pusher_offset_mm: None,
        conditions,
        scene: None,
        evaluation: None,
    };
    if outcome.conditions.iter().any(|c| !c.holds) {
        return Ok(outcome);
    }
    // The carrier angle along the path, θ(t) = σ(α − δ − Φ0), continuous from its value
    // in [0, 2π) at t = 0; the nodes θ_j = 2πj/N found between the dense samples.
    let theta0 = (sigma * (alpha[0] - delta - phi0)).rem_euclid(TAU);
    let theta_dense: Vec<f64> = alpha
        .iter()
        .map(|a| theta0 + sigma * (a - alpha[0]))
        .collect();
    let n = spec.samples_per_turn;
    let mut node_t = Vec::with_capacity(n);
    for j in 0..n {
        let mut goal = TAU * j as f64 / n as f64;
        if goal < theta0 {
            goal += TAU;
        }
        // The dense interval [θ_k, θ_k+1] that holds the goal (θ increases along t).
        let k = theta_dense
            .partition_point(|&v| v <= goal)
            .saturating_sub(1)
            .min(m - 1);
        node_t.push(solve_theta(
            &geometry,
            path,
            goal,
            [t_of(k), t_of(k + 1)],
            [theta_dense[k], theta_dense[k + 1]],
            // Continuous with the bracket's start: the chain's α is known modulo 2π.
            |c: &Chain| theta_dense[k] + sigma * ((c.alpha - alpha[k] + PI).rem_euclid(TAU) - PI),
        ));
    }
    let nodes: Vec<Chain> = node_t.iter().map(|&t| geometry.at(path, t)).collect();
    // The arm's direction, continuous from the node at θ = 0.
    let mut arm_nodes: Vec<f64> = nodes.iter().map(|c| c.arm).collect();
    unwrap(&mut arm_nodes);
    let read_ratio: Vec<f64> = nodes.iter().map(|c| 1.0 - c.arm_d1 / c.alpha_d1).collect();
    // What is left of the tolerance once the series has taken its share, with a tenth
    // kept for the forward check's own discretisation.
    let budget_mm = if shape {
        0.9 * target.tolerance_mm - smoothing_mm
    } else {
        0.0
    };
    let shaped = RatioShaping::within(
        &read_ratio,
        spec.split,
        [a1, a2],
        (&scene.gear.module, scene.bounds.module_min_mm),
        arm_length,
        budget_mm,
    );
    let ratio_nodes = shaped.ratio.clone();
    arm_nodes[0] += sigma * shaped.arm_shift;
    outcome.shaping_mm = shaped.moved_mm;
    let g_a = power_split(&ratio_nodes, spec.split);
    let mut phi_a = vec![0.0; n];
    SpectralIntegrator::new(n).cumulative(&g_a, &mut phi_a);
    let psi_start = train.psi_start();
    let sun: Vec<Vec2> = (0..n)
        .map(|j| {
            let psi = psi_start + sigma * TAU * j as f64 / n as f64;
            unit(psi) * (a1 * g_a[j] / (1.0 + g_a[j]))
        })
        .collect();
    let layer_b: Vec<Vec2> = (0..n)
        .map(|j| {
            let g_b = ratio_nodes[j] / g_a[j];
            unit(gamma0 - PI - sigma * phi_a[j]) * (a2 * g_b / (1.0 + g_b))
        })
        .collect();
    let mut designed = scene.clone();
    designed.gear.curve = CurveSpec::table_through(&sun);
    designed.gear.second_curve = Some(CurveSpec::table_through(&layer_b));
    let beta0 = arm_nodes[0] - phi0 - gamma0 - PI;
    designed.train.beta0_deg = ((beta0.to_degrees() + 180.0).rem_euclid(360.0)) - 180.0;
    designed.train.arm_length_mm = arm_length;
    designed.resolution = designed.resolution.with_samples(n);
    designed.target = Some(std::sync::Arc::new(target.clone()));
    let mut evaluator = Evaluator::new();
    let evaluated = evaluator
        .evaluate(&designed)
        .map(|e| aim_poses(&mut evaluator, &mut designed, e));
    match evaluated {
        Ok((evaluation, aimed)) => {
            outcome.pusher_offset_mm = aimed;
            if let Some(h1) = aimed {
                for c in (outcome.conditions.iter_mut()).filter(|c| c.name == "pusher_within_arm") {
                    *c = pusher_within_arm(h1, arm_length);
                }
            }
            let node_s: Vec<f64> = node_t.iter().map(|t| path.length_mm * t / TAU).collect();
            (outcome.conditions).extend(design_conditions(&designed, &evaluation, &node_s));
            outcome.evaluation = Some(evaluation);
        }
        // Curves too sharp for their samples, say: the design is written, and named.
        Err(e) => outcome.conditions.push(Condition {
            name: "evaluates".into(),
            holds: false,
            blocks: true,
            value: n as f64,
            bound: n as f64,
            unit: "samples",
            meaning: format!("the design evaluates at {n} samples per turn: {e}"),
            places: vec![],
        }),
    }
    outcome.scene = Some(designed);
    Ok(outcome)
}

/// The pusher offset H1 (mm) that meets the counting poses' attitudes, when the target
/// names any: the path fixes the arm's direction, not the pusher's, which H1 turns by
/// `asin(H1/S)` the same at every carrier angle (the tip does not move). A secant on the
/// poses' mean attitude error, kept in `[0, 0.99 S]`; `None` (and the design and its
/// evaluation as they were) when no pose names an attitude, a trial is refused, or the
/// error cannot be brought under 1e-6°.
fn aim_poses(
    evaluator: &mut Evaluator,
    designed: &mut Scene,
    evaluation: Evaluation,
) -> (Evaluation, Option<f64>) {
    let error = |e: &Evaluation| -> Option<f64> {
        let fit = e.fit.as_ref()?;
        let errors: Vec<f64> = (fit.poses.iter())
            .filter(|p| p.counts)
            .filter_map(|p| p.attitude_error_deg)
            .collect();
        (!errors.is_empty()).then(|| errors.iter().sum::<f64>() / errors.len() as f64)
    };
    let Some(first) = error(&evaluation) else {
        return (evaluation, None);
    };
    let arm = designed.train.arm_length_mm;
    // A trial the model refuses reads as NaN: the secant stops there.
    let mut at = |h1: f64| -> (Option<Evaluation>, f64) {
        let mut trial = designed.clone();
        trial.train.pusher_offset_mm = h1;
        let e = evaluator.evaluate(&trial).ok();
        let err = e.as_ref().and_then(error).unwrap_or(f64::NAN);
        (e, err)
    };
    let (mut h0, mut f0) = (designed.train.pusher_offset_mm, first);
    let mut h1 = (h0 + 1.0).min(0.99 * arm);
    if h1 == h0 {
        h1 = h0 - 1.0;
    }
    let (mut e1, mut f1) = at(h1);
    for _ in 0..30 {
        // A finite error comes with its evaluation.
        if f1.abs() < 1e-6 {
            if let Some(e) = e1 {
                designed.train.pusher_offset_mm = h1;
                return (e, Some(h1));
            }
        }
        if !(f1.is_finite() && f1 != f0) {
            break;
        }
        let next = (h1 - f1 * (h1 - h0) / (f1 - f0)).clamp(0.0, 0.99 * arm);
        (h0, f0) = (h1, f1);
        h1 = next;
        (e1, f1) = at(h1);
    }
    (evaluation, None)
}

/// Condition 1: the pusher offset H1 (mm) lies within the arm length the path fixes (mm).
fn pusher_within_arm(pusher: f64, arm_length: f64) -> Condition {
    Condition {
        name: "pusher_within_arm".into(),
        holds: pusher < arm_length,
        blocks: true,
        value: arm_length,
        bound: pusher,
        unit: "mm",
        meaning: format!(
            "the arm length the path fixes, (farthest ± nearest radius)/2 = {arm_length:.3} \
             mm, exceeds the pusher offset H1 = {pusher:.3} mm"
        ),
        places: vec![],
    }
}

/// The `t` at which the carrier angle reaches `goal`, bracketed by `t` (angles `theta` at
/// its ends): Newton steps on the exact chain, kept inside the bracket by bisection.
fn solve_theta(
    geometry: &ChainGeometry,
    path: &FourierPath,
    goal: f64,
    t: [f64; 2],
    theta: [f64; 2],
    theta_of: impl Fn(&Chain) -> f64,
) -> f64 {
    let (mut lo, mut hi) = (t[0], t[1]);
    let span = theta[1] - theta[0];
    let mut x = if span > 0.0 {
        lo + (hi - lo) * ((goal - theta[0]) / span).clamp(0.0, 1.0)
    } else {
        0.5 * (lo + hi)
    };
    for _ in 0..50 {
        let c = geometry.at(path, x);
        let f = theta_of(&c) - goal;
        if f.abs() < 1e-14 {
            break;
        }
        if f > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let slope = c.alpha_d1.abs();
        let newton = x - f / slope;
        x = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo < 1e-15 {
            break;
        }
    }
    x
}

/// The conditions on the built design: each gear's convexity (concave arcs need a shaper
/// cutter, `gear.module.cutter_teeth`) and every objective of the forward evaluation.
/// `node_s`: the arc length along the target (mm) at each carrier node.
fn design_conditions(scene: &Scene, evaluation: &Evaluation, node_s: &[f64]) -> Vec<Condition> {
    let mut out = Vec::new();
    if let Some(kin) = &evaluation.kinematics {
        let shaper = scene.gear.module.cutter_teeth.is_some();
        let tips = kin.tips();
        let pairs = [Some(kin.pair()), kin.second_pair()];
        let names = [["sun", "intermediate_a"], ["intermediate_b", "planet"]];
        // Carrier angle of pair B's node k: where Φ_A reaches u_k.
        let phi_a = kin.pair().phi2_nodes();
        for (p, pair) in pairs.iter().enumerate() {
            let Some(pair) = pair else { continue };
            let a = pair.centre_distance();
            let n = pair.samples().len();
            for (g, name) in names[p].iter().enumerate() {
                let kappa: Vec<f64> = (pair.samples().iter())
                    .map(|s| match g {
                        0 => s.curvature(),
                        _ => crate::gear::conjugate_polar(*s, a).curvature(),
                    })
                    .collect();
                let least = kappa.iter().copied().fold(f64::INFINITY, f64::min);
                let fails: Vec<bool> = kappa.iter().map(|&k| k < 0.0).collect();
                let node = |k: usize| match p {
                    0 => k,
                    _ => {
                        let u = TAU * k as f64 / n as f64;
                        phi_a.partition_point(|&v| v < u).min(tips.len() - 1)
                    }
                };
                let places = runs(&fails, |k| -kappa[k])
                    .into_iter()
                    .map(|(run, worst)| {
                        let (j0, j1) = (node(run[0]), node(run[1]));
                        Place {
                            path_mm: [node_s[j0], node_s[j1]],
                            carrier_deg: Some([
                                kin.theta(j0).to_degrees(),
                                kin.theta(j1).to_degrees(),
                            ]),
                            point_mm: tips[node(worst)],
                        }
                    })
                    .collect::<Vec<_>>();
                out.push(Condition {
                    name: format!("{name}_convex"),
                    holds: least >= 0.0 || shaper,
                    blocks: !shaper,
                    value: least,
                    bound: 0.0,
                    unit: "1/mm",
                    meaning: format!(
                        "the {} pitch curve is convex, or a shaper cutter \
                         (gear.module.cutter_teeth) cuts it (the value is its least curvature; \
                         negative, concave with radius 1/|κ|, whose module the module \
                         objective checks)",
                        name.replace('_', " ")
                    ),
                    places,
                });
            }
        }
    }
    if let (Some(fit), Some(target)) = (&evaluation.fit, &scene.target) {
        out.push(Condition {
            name: "path_within_tolerance".into(),
            holds: fit.path_hausdorff_mm <= target.tolerance_mm,
            blocks: false,
            value: fit.path_hausdorff_mm,
            bound: target.tolerance_mm,
            unit: "mm",
            meaning: format!(
                "the design's path within the target's tolerance (Hausdorff distance; \
                 farthest at ({:.2}, {:.2}) mm)",
                fit.hausdorff_at_mm.x, fit.hausdorff_at_mm.y
            ),
            places: vec![],
        });
        // The key poses: where the design's arm is at each, against the pose's tolerances.
        for (pose, got) in target.poses.iter().zip(&fit.poses) {
            let mut meaning = format!(
                "the tip within {} mm of ({:.2}, {:.2}) mm",
                pose.position_tolerance_mm, pose.x_mm, pose.y_mm
            );
            if let (Some(a), Some(e)) = (pose.attitude_deg, got.attitude_error_deg) {
                meaning += &format!(
                    " and the attitude within {}° of {a}° (off by {e:+.2}°)",
                    pose.attitude_tolerance_deg
                );
            }
            if let (Some(c), Some(e)) = (pose.carrier_deg, got.carrier_error_deg) {
                meaning += &format!(
                    " and the carrier within {}° of {c}° (off by {e:+.2}°)",
                    pose.carrier_tolerance_deg
                );
            }
            out.push(Condition {
                name: format!("pose:{}", got.name),
                holds: got.met || !got.counts,
                blocks: false,
                value: got.position_error_mm,
                bound: pose.position_tolerance_mm,
                unit: "mm",
                meaning,
                places: vec![],
            });
        }
    }
    for o in &evaluation.objectives {
        // The nearer bound (the violated one when it fails).
        let below = o.lower.map_or(f64::INFINITY, |l| o.value - l);
        let above = o.upper.map_or(f64::INFINITY, |u| u - o.value);
        let bound = match (o.lower, o.upper) {
            (Some(l), _) if below <= above => l,
            (_, Some(u)) => u,
            (Some(l), None) => l,
            (None, None) => o.value,
        };
        out.push(Condition {
            name: format!("objective:{}", o.kind.name()),
            holds: o.violation == 0.0,
            blocks: false,
            value: o.value,
            bound,
            unit: o.kind.unit(),
            meaning: format!(
                "{} within {} to {} {}",
                o.kind.name(),
                o.lower.map_or("−∞".into(), |l| format!("{l}")),
                o.upper.map_or("∞".into(), |u| format!("{u}")),
                o.kind.unit()
            ),
            places: vec![],
        });
    }
    out
}
