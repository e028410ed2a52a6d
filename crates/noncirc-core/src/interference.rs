//! Objective 1, interference: the least clearance between the arms' capsules and
//! against the other planets' gear envelopes over the cycle.

use crate::agronomy::Agronomy;
use crate::curve::parabola_vertex;
use crate::planetary::Kinematics;
use crate::vec2::Vec2;

/// A segment `a→b` ready for repeated distance queries.
#[derive(Debug, Clone, Copy)]
struct Segment {
    a: Vec2,
    ab: Vec2,
    /// `1/|ab|²`, or 0 for a degenerate segment.
    inv_len2: f64,
}

impl Segment {
    #[cfg(test)]
    fn new(a: Vec2, b: Vec2) -> Self {
        let len2 = (b - a).hypot2();
        Self::with_inv_len2(a, b, if len2 > 0.0 { 1.0 / len2 } else { 0.0 })
    }

    /// The segment `a→b` whose `1/|ab|²` is known (an arm: `1/S²`), without a division.
    #[inline]
    fn with_inv_len2(a: Vec2, b: Vec2, inv_len2: f64) -> Self {
        Self {
            a,
            ab: b - a,
            inv_len2,
        }
    }

    /// Midpoint (mm).
    #[inline]
    fn midpoint(&self) -> Vec2 {
        self.a + self.ab * 0.5
    }

    /// Squared distance from `p` (mm²): compare these, take one square root.
    #[inline]
    fn distance_sq(&self, p: Vec2) -> f64 {
        let ap = p - self.a;
        let t = (ap.dot(self.ab) * self.inv_len2).clamp(0.0, 1.0);
        (ap - self.ab * t).hypot2()
    }

    /// Squared distance to another segment (mm²).
    #[inline]
    fn distance_sq_to(&self, other: &Segment) -> f64 {
        let (r, s) = (self.ab, other.ab);
        let d = other.a - self.a;
        let denom = r.cross(s);
        if denom != 0.0 {
            // Crossing at t = cross(d, s)/denom, u = cross(d, r)/denom, both in [0, 1].
            let sign = denom.signum();
            let (t, u, scale) = (sign * d.cross(s), sign * d.cross(r), denom.abs());
            if (0.0..=scale).contains(&t) && (0.0..=scale).contains(&u) {
                return 0.0;
            }
        }
        let end = |g: &Segment| g.a + g.ab;
        self.distance_sq(other.a)
            .min(self.distance_sq(end(other)))
            .min(other.distance_sq(self.a))
            .min(other.distance_sq(end(self)))
    }
}

/// Objective 1: least clearance between arm capsules and against the other planets' gear envelopes
/// (circles of the sun's largest radius) over the cycle (mm). By the train's symmetry
/// (arm k is arm I a k-th of a turn later), arm I against every other planet and against
/// the arms at lags 1 … arms/2 covers every pair: the pair at lag m is the pair at lag
/// arms − m seen from the other arm. A one-arm train has no pair (the scene refuses the
/// objective there); it reads +∞. The gears of different arm sets are the measure
/// `gear_overlap_mm` (`gearbox::gear_sets_overlap`).
pub(crate) fn interference_clearance(kin: &Kinematics, agro: &Agronomy) -> f64 {
    if kin.arms() < 2 {
        return f64::INFINITY;
    }
    let n = kin.len();
    let (tips, centres) = (kin.tips(), kin.planet_centres());
    let rmax = kin.radius_range().1;
    let w = agro.arm_half_width_mm;
    // Every arm segment O3→D has length S.
    let s = kin.spec().arm_length_mm;
    let inv_s2 = 1.0 / (s * s);
    let arm = |j: usize| Segment::with_inv_len2(centres[j], tips[j], inv_s2);
    let planet_lags = 1..kin.arms();
    let arm_lags = 1..=kin.arms() / 2;
    // Arm I (`seg`) against a planet centre, and against another arm.
    let planet = |seg: &Segment, c: Vec2| seg.distance_sq(c).sqrt() - rmax - w;
    let arms = |seg: &Segment, other: &Segment| seg.distance_sq_to(other).sqrt() - 2.0 * w;
    let clearance = |j: usize| {
        let seg = arm(j);
        let others = (arm_lags.clone()).map(|m| arms(&seg, &arm(kin.arm_node(m, j))));
        let planets = (planet_lags.clone()).map(|m| planet(&seg, centres[kin.arm_node(m, j)]));
        // The least part; NaN only when every part is NaN (`f64::min` drops a NaN).
        others.chain(planets).fold(f64::NAN, f64::min)
    };
    // Every point of an arm lies within S/2 of its midpoint m, so arm I is at least
    // |m − c| − S/2 from a planet centre c, and at least |m − m₂| − S, then
    // dist(m, arm II) − S/2, from another arm. Where such a bound cannot beat the least
    // clearance so far, the exact distance is skipped: squared distances only, no root.
    // The margin covers rounding in |O3D| = S.
    let half = 0.5 * s * (1.0 + 1e-12);
    let beyond = |d2: f64, reach: f64| reach > 0.0 && d2 >= reach * reach;
    let dist_sq = |p: Vec2, q: Vec2| (p - q).hypot2();
    // The least clearance node; a NaN (numerical breakdown) loses to any number.
    let (mut j, mut least) = (0, clearance(0));
    for k in 1..n {
        let seg = arm(k);
        let m = seg.midpoint();
        let planet_reach = least + rmax + w + half;
        // A part whose bound holds is at least `least`: leaving it out cannot change
        // whether, or to what, the least clearance moves.
        let mut c = f64::INFINITY;
        for lag in arm_lags.clone() {
            let other = arm(kin.arm_node(lag, k));
            let far = beyond(dist_sq(m, other.midpoint()), least + 2.0 * w + 2.0 * half)
                || beyond(other.distance_sq(m), least + 2.0 * w + half);
            if !far {
                c = c.min(arms(&seg, &other));
            }
        }
        for lag in planet_lags.clone() {
            let centre = centres[kin.arm_node(lag, k)];
            if !beyond(dist_sq(m, centre), planet_reach) {
                c = c.min(planet(&seg, centre));
            }
        }
        if c < least || (least.is_nan() && c.is_finite()) {
            (j, least) = (k, c);
        }
    }
    if !least.is_finite() {
        return least;
    }
    let wrap = |j: usize| if j >= n { j - n } else { j };
    parabola_vertex(clearance(wrap(j + n - 1)), least, clearance(wrap(j + 1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distances() {
        let between = |p0: [f64; 2], p1: [f64; 2], q0: [f64; 2], q1: [f64; 2]| {
            Segment::new(p0.into(), p1.into())
                .distance_sq_to(&Segment::new(q0.into(), q1.into()))
                .sqrt()
        };
        assert_eq!(
            between([0.0, 0.0], [2.0, 0.0], [1.0, -1.0], [1.0, 1.0]),
            0.0
        );
        assert!((between([0.0, 0.0], [1.0, 0.0], [0.0, 2.0], [1.0, 2.0]) - 2.0).abs() < 1e-15);
        let degenerate = Segment::new(Vec2::ZERO, Vec2::ZERO);
        assert!((degenerate.distance_sq(Vec2::new(3.0, 4.0)).sqrt() - 5.0).abs() < 1e-15);
    }

    #[test]
    fn pruned_interference_equals_the_full_scan_of_every_pair() {
        // Every node, every pair of arms (a, b) and every arm against every other planet,
        // no pruning and no symmetry: its least value over the nodes is the pruned scan's
        // least node, and the objective refines it with the same parabola.
        let full_scan = |kin: &Kinematics, agro: &Agronomy| {
            let (n, s) = (kin.len(), kin.spec().arm_length_mm);
            let (tips, centres) = (kin.tips(), kin.planet_centres());
            let arm = |j: usize| Segment::with_inv_len2(centres[j], tips[j], 1.0 / (s * s));
            let w = agro.arm_half_width_mm;
            let rmax = kin.radius_range().1;
            // Arm a at node j against arm b's capsule, and against planet b.
            let capsules = |j: usize, a: usize, b: usize| {
                let seg = arm(kin.arm_node(a, j));
                seg.distance_sq_to(&arm(kin.arm_node(b, j))).sqrt() - 2.0 * w
            };
            let planet = |j: usize, a: usize, b: usize| {
                let seg = arm(kin.arm_node(a, j));
                seg.distance_sq(centres[kin.arm_node(b, j)]).sqrt() - rmax - w
            };
            let pair = |j: usize, a: usize, b: usize| capsules(j, a, b).min(planet(j, a, b));
            let arms = kin.arms();
            let every_pair = (0..n)
                .flat_map(|j| (0..arms).flat_map(move |a| (0..arms).map(move |b| (j, a, b))))
                .filter(|&(_, a, b)| a != b)
                .map(|(j, a, b)| pair(j, a, b))
                .fold(f64::INFINITY, f64::min);
            // Arm I against the arms at lags 1 … arms/2 and every other planet, node by
            // node, refined as the objective refines its least node.
            let values: Vec<f64> = (0..n)
                .map(|j| {
                    let near = (1..=arms / 2).map(|b| capsules(j, 0, b));
                    let planets = (1..arms).map(|b| planet(j, 0, b));
                    near.chain(planets).fold(f64::INFINITY, f64::min)
                })
                .collect();
            let j = (0..n).fold(0, |b, j| if values[j] < values[b] { j } else { b });
            let refined = parabola_vertex(values[(j + n - 1) % n], values[j], values[(j + 1) % n]);
            (every_pair, values[j], refined)
        };
        let curve = crate::CurveSpec::paper().build().unwrap();
        let agro = Agronomy::default();
        let mut checked = 0;
        for arms in [2, 3, 4] {
            for beta0 in [-60.0, -29.0, 0.0, 40.0, 120.0] {
                for gamma0 in [-80.0, -53.0, -20.0, 60.0] {
                    for width in [2.0, 12.0, 40.0] {
                        let spec = crate::TrainSpec {
                            beta0_deg: beta0,
                            gamma0_deg: gamma0,
                            arms,
                            ..Default::default()
                        };
                        let agro = Agronomy {
                            arm_half_width_mm: width,
                            ..agro
                        };
                        let kin =
                            Kinematics::solve(&curve, None, &spec, &crate::Resolution::DEFAULT)
                                .unwrap();
                        let value = interference_clearance(&kin, &agro);
                        let (every_pair, least_node, refined) = full_scan(&kin, &agro);
                        let at = format!("{arms} arms, β0 {beta0}, γ0 {gamma0}, w {width}");
                        // Arm I's lags cover every pair, and the pruning changes nothing.
                        assert!((every_pair - least_node).abs() < 1e-9, "{at}");
                        assert_eq!(value, refined, "{at}");
                        checked += usize::from(least_node < 0.0);
                    }
                }
            }
        }
        // Some of these designs interfere: the pruning is tested on both signs.
        assert!(checked > 0);
    }
}
