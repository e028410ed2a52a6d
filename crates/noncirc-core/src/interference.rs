//! Objective 1, interference: the least clearance between the arms' capsules and
//! against the other planets' gear envelopes over the cycle.

use crate::agronomy::Agronomy;
use crate::curve::parabola_vertex;
use crate::planetary::Kinematics;
use crate::vec2::Vec2;
use std::cmp::Ordering;

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
///
/// A train reassembled from one whose nodes near its least clearance are marked
/// ([`mark_nodes_near_least_clearance`]), and moved little against their band, scans
/// only those nodes: the same value, bit for bit.
pub(crate) fn interference_clearance(kin: &Kinematics, agro: &Agronomy) -> f64 {
    let scan = Scan::new(kin, agro);
    if let Some(value) = scan.confined() {
        return value;
    }
    match scan.least() {
        Some((j, least)) => scan.refined(j, least),
        None => f64::INFINITY,
    }
}

/// Marks the nodes where `kin`'s clearance (for `agro`'s arm width) comes within
/// `band_mm` of its least: a reassembly of `kin` whose arms and planet centres move by
/// less than a quarter of the band has its least clearance at one of them. Nothing is
/// marked for a train without pairs, or whose first node's clearance is not finite.
pub(crate) fn mark_nodes_near_least_clearance(kin: &mut Kinematics, agro: &Agronomy, band_mm: f64) {
    let scan = Scan::new(kin, agro);
    let mut least = scan.clearance(0);
    if scan.arms < 2 || !least.is_finite() {
        return;
    }
    // One pass: the nodes within the band of the least so far (their clearances exact),
    // then those within the band of the least.
    let mut near = vec![(0, least)];
    let mut reach = scan.reach(least + band_mm);
    for k in 1..kin.len() {
        let c = scan.below(k, &reach);
        if c <= least + band_mm {
            near.push((k, c));
            least = least.min(c);
            reach = scan.reach(least + band_mm);
        }
    }
    let nodes = (near.into_iter())
        .filter(|&(_, c)| c <= least + band_mm)
        .map(|(k, _)| k)
        .collect();
    kin.mark_nodes(nodes, agro.arm_half_width_mm, band_mm);
}

/// A train's clearance at its nodes.
struct Scan<'a> {
    kin: &'a Kinematics,
    /// The number of arms.
    arms: usize,
    tips: &'a [Vec2],
    centres: &'a [Vec2],
    /// The sun's largest radius, the arm's half-width and its length (mm).
    rmax: f64,
    w: f64,
    s: f64,
    /// `1/S²` (1/mm²): every arm segment O3→D has length S.
    inv_s2: f64,
    /// Half the arm's length, with a margin that covers rounding in |O3D| = S (mm).
    half: f64,
}

/// Per node, the least squared distances (mm²) from arm I's midpoint to the other arms'
/// midpoints and to the other planets' centres ([`Scan::apart`]).
struct Apart {
    arms: Vec<f64>,
    planets: Vec<f64>,
}

/// What [`Scan::below`] compares with, for one bound (mm): the squares of the distances
/// from arm I's midpoint beyond which another arm's midpoint, that arm, or a planet
/// centre cannot bring a part of the clearance below the bound. NaN for a distance that
/// is not positive: no square compares at or above it, so nothing is left out. Computed
/// where the bound changes, not at every node.
struct Reach {
    arm_midpoint: f64,
    arm: f64,
    planet: f64,
}

impl<'a> Scan<'a> {
    fn new(kin: &'a Kinematics, agro: &Agronomy) -> Self {
        let s = kin.spec().arm_length_mm;
        Self {
            kin,
            arms: kin.arms(),
            tips: kin.tips(),
            centres: kin.planet_centres(),
            rmax: kin.radius_range().1,
            w: agro.arm_half_width_mm,
            s,
            inv_s2: 1.0 / (s * s),
            half: 0.5 * s * (1.0 + 1e-12),
        }
    }

    /// The reaches for `bound` (mm).
    fn reach(&self, bound: f64) -> Reach {
        let (w, half) = (self.w, self.half);
        let square = |reach: f64| if reach > 0.0 { reach * reach } else { f64::NAN };
        Reach {
            arm_midpoint: square(bound + 2.0 * w + 2.0 * half),
            arm: square(bound + 2.0 * w + half),
            planet: square(bound + self.rmax + w + half),
        }
    }

    /// Arm I's segment at node `j`.
    #[inline]
    fn arm(&self, j: usize) -> Segment {
        Segment::with_inv_len2(self.centres[j], self.tips[j], self.inv_s2)
    }

    /// Arm I against another arm (mm). Out of line, as [`Scan::planet`]: the scan takes
    /// them at few nodes, and inlined, what they need of arm I was made ready at every
    /// node.
    #[inline(never)]
    fn arms(&self, seg: &Segment, other: &Segment) -> f64 {
        seg.distance_sq_to(other).sqrt() - 2.0 * self.w
    }

    /// Arm I against the planet centred at `c` (mm).
    #[inline(never)]
    fn planet(&self, seg: &Segment, c: Vec2) -> f64 {
        seg.distance_sq(c).sqrt() - self.rmax - self.w
    }

    /// The clearance at node `j`: the least part; NaN only when every part is NaN
    /// (`f64::min` drops a NaN).
    fn clearance(&self, j: usize) -> f64 {
        let (kin, arms) = (self.kin, self.arms);
        let seg = self.arm(j);
        let others = (1..=arms / 2).map(|m| self.arms(&seg, &self.arm(kin.arm_node(m, j))));
        let planets = (1..arms).map(|m| self.planet(&seg, self.centres[kin.arm_node(m, j)]));
        others.chain(planets).fold(f64::NAN, f64::min)
    }

    /// The clearance at node `k` where it is below the bound of `reach`; otherwise a value
    /// at or above that bound (+∞ when every part is). Every point of an arm lies within
    /// S/2 of its midpoint m, so arm I is at least |m − c| − S/2 from a planet centre c, and
    /// at least |m − m₂| − S, then dist(m, arm II) − S/2, from another arm. Where such a
    /// bound cannot come below the bound, the exact distance is skipped: squared distances
    /// only, no root.
    #[inline(always)]
    fn below(&self, k: usize, reach: &Reach) -> f64 {
        let arms = self.arms;
        // Beyond a reach (a NaN reach: never).
        let beyond = |d2: f64, reach2: f64| d2 >= reach2;
        let dist_sq = |p: Vec2, q: Vec2| (p - q).hypot2();
        let seg = self.arm(k);
        let m = seg.midpoint();
        let mut c = f64::INFINITY;
        for lag in 1..=arms / 2 {
            let other = self.arm(self.kin.arm_node_within(lag, k));
            let far = beyond(dist_sq(m, other.midpoint()), reach.arm_midpoint)
                || beyond(other.distance_sq(m), reach.arm);
            if !far {
                c = c.min(self.arms(&seg, &other));
            }
        }
        for lag in 1..arms {
            let centre = self.centres[self.kin.arm_node_within(lag, k)];
            if !beyond(dist_sq(m, centre), reach.planet) {
                c = c.min(self.planet(&seg, centre));
            }
        }
        c
    }

    /// Per node, the least squared distance (mm²) from arm I's midpoint to another arm's
    /// midpoint and to another planet's centre: what [`Scan::below`] first compares with
    /// its reaches. One pass over the nodes per lag, each node's partner found by a
    /// rotation of the slice, not an index per node, so the compiler runs the passes in
    /// vector lanes. A distance that is not a number is left out, as the scan's
    /// `f64::min` leaves out a clearance that is not one.
    fn apart(&self) -> Apart {
        let n = self.kin.len();
        let mids: Vec<Vec2> = (self.centres.iter().zip(self.tips))
            .map(|(&a, &b)| Segment::with_inv_len2(a, b, self.inv_s2).midpoint())
            .collect();
        let nearest = |others: &[Vec2], lags: std::ops::Range<usize>| {
            let mut least = vec![f64::INFINITY; n];
            for lag in lags {
                // Node k's partner is node k − shift, wrapped into the turn.
                let shift = self.kin.arm_lag_nodes(lag);
                let (head, tail) = others.split_at(n - shift);
                let (first, rest) = least.split_at_mut(shift);
                // The least kept is never NaN: a comparison, not `f64::min`'s NaN rule.
                let nearer = |(d, (&m, &o)): (&mut f64, (&Vec2, &Vec2))| {
                    let square = (m - o).hypot2();
                    *d = if square < *d { square } else { *d };
                };
                first
                    .iter_mut()
                    .zip(mids[..shift].iter().zip(tail))
                    .for_each(nearer);
                rest.iter_mut()
                    .zip(mids[shift..].iter().zip(head))
                    .for_each(nearer);
            }
            least
        };
        Apart {
            arms: nearest(&mids, 1..self.arms / 2 + 1),
            planets: nearest(self.centres, 1..self.arms),
        }
    }

    /// The first node at the least clearance, and that clearance; `None` for a train
    /// without pairs. A part whose bound holds is at least the least so far: leaving it
    /// out cannot change whether, or to what, the least clearance moves. A NaN
    /// (numerical breakdown) loses to any number.
    fn least(&self) -> Option<(usize, f64)> {
        if self.arms < 2 {
            return None;
        }
        // Passed over: a node whose every part lies beyond the reaches of the least so far
        // (`below` would give +∞ there), and one whose every part lies strictly beyond
        // the reaches of `above`, the clearance at some node, which the least clearance
        // cannot exceed: such a node is not the first at the least clearance, and
        // lowering the least so far on the way there changes nothing at the end. `above`
        // is taken where arm I's midpoint comes nearest another planet's centre, where
        // the least clearance usually lies.
        let apart = self.apart();
        let nearest = |squares: &[f64]| {
            let (mut nearest, mut least) = (0, f64::INFINITY);
            for (k, &square) in squares.iter().enumerate() {
                if square < least {
                    (nearest, least) = (k, square);
                }
            }
            nearest
        };
        let above = self.clearance(nearest(&apart.planets));
        let ceiling = self.reach(above);
        // Cut to the nodes' count: the nodes below it need no bounds check.
        let n = self.kin.len();
        let (arms_apart, planets_apart) = (&apart.arms[..n], &apart.planets[..n]);
        self.least_over(0..n, |k, reach| {
            let (arms, planets) = (arms_apart[k], planets_apart[k]);
            (arms >= reach.arm_midpoint && planets >= reach.planet)
                || (arms > ceiling.arm_midpoint && planets > ceiling.planet)
        })
    }

    /// As [`Scan::least`], over `nodes` (ascending) alone; `None` for no nodes. A node
    /// where `beyond(k, reach)`, for the reach of the least so far, is passed over: it
    /// must be one that cannot change the result.
    #[inline(always)]
    fn least_over(
        &self,
        mut nodes: impl Iterator<Item = usize>,
        beyond: impl Fn(usize, &Reach) -> bool,
    ) -> Option<(usize, f64)> {
        let first = nodes.next()?;
        let (mut j, mut least) = (first, self.clearance(first));
        let mut reach = self.reach(least);
        // Whether `least` is NaN, kept with it: tested at every node, it changes with it.
        let mut broken = least.is_nan();
        for k in nodes {
            if beyond(k, &reach) {
                continue;
            }
            let c = self.below(k, &reach);
            if c < least || (broken && c.is_finite()) {
                (j, least) = (k, c);
                reach = self.reach(least);
                broken = false;
            }
        }
        Some((j, least))
    }

    /// The least clearance `least`, at node `j`, refined by the parabola through it and
    /// its neighbours; a value that is not finite as it is.
    fn refined(&self, j: usize, least: f64) -> f64 {
        if !least.is_finite() {
            return least;
        }
        let n = self.kin.len();
        let wrap = |j: usize| if j >= n { j - n } else { j };
        parabola_vertex(
            self.clearance(wrap(j + n - 1)),
            least,
            self.clearance(wrap(j + 1)),
        )
    }

    /// The refined least clearance from the marked nodes alone, where the train was
    /// reassembled from one marked for this arm width and has moved by less than a
    /// quarter of the band. Clearances do not change when the train turns as a whole
    /// about the carrier axis, and are 1-Lipschitz in the displacement δ of the arms and
    /// planet centres beyond that turn, so each node's is within 2δ of the marked
    /// train's: an unmarked node is then at or above least_s + band − 2δ, and the least is
    /// at most least_s + 2δ, below it. A clearance that is not a number loses to any
    /// number, as in the whole scan. `None` where the band is too narrow, or where no
    /// marked node's clearance is finite (the whole scan then decides).
    fn confined(&self) -> Option<f64> {
        let marks = self.kin.marks()?;
        let marked = (marks.clearance.as_ref()).filter(|m| m.key == self.w)?;
        // Margins for the rounding of the displacement bound, the positions and the
        // distances.
        let scale = 1.0 + self.s + self.rmax + self.centres.first()?.hypot2().sqrt();
        let delta = marks.displacement_mm * (1.0 + 1e-9) + 1e-9 * scale;
        // A NaN displacement fails the comparison too.
        let narrow = (4.0 * delta).partial_cmp(&marked.band_mm) != Some(Ordering::Less);
        if narrow || self.arms < 2 {
            return None;
        }
        // As the whole scan, over the marked nodes.
        let (j, least) = self.least_over(marked.nodes.iter().copied(), |_, _| false)?;
        least.is_finite().then(|| self.refined(j, least))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's train with `arms` arms, β0 and γ0 (°), and arms `width` mm half-wide.
    fn train(arms: usize, beta0: f64, gamma0: f64, width: f64) -> (crate::TrainSpec, Agronomy) {
        let spec = crate::TrainSpec {
            beta0_deg: beta0,
            gamma0_deg: gamma0,
            arms,
            ..Default::default()
        };
        let agro = Agronomy {
            arm_half_width_mm: width,
            ..Agronomy::default()
        };
        (spec, agro)
    }

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

    /// Every node, every pair of arms (a, b) and every arm against every other planet, no
    /// pruning and no symmetry: the least over all of them, arm I's least node's value
    /// (arm I against the arms at lags 1 … arms/2 and every other planet, node by node),
    /// and that value refined as the objective refines its least node.
    fn full_scan(kin: &Kinematics, agro: &Agronomy) -> (f64, f64, f64) {
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
    }

    #[test]
    fn pruned_interference_equals_the_full_scan_of_every_pair() {
        // Its least value over the nodes is the pruned scan's least node, and the
        // objective refines it with the same parabola.
        let curve = crate::CurveSpec::paper().build().unwrap();
        let mut checked = 0;
        for arms in [2, 3, 4] {
            for beta0 in [-60.0, -29.0, 0.0, 40.0, 120.0] {
                for gamma0 in [-80.0, -53.0, -20.0, 60.0] {
                    for width in [2.0, 12.0, 40.0] {
                        let (spec, agro) = train(arms, beta0, gamma0, width);
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

    /// The pruned scan (reaches of the least so far, and of the clearance where arm I's
    /// midpoint comes nearest a planet centre) gives the full scan's refined least bit for
    /// bit on random trains of two to four arms, ellipses as well as the paper's gear,
    /// with arms from hairline to wide: both where they interfere and where they do not.
    #[test]
    fn pruned_interference_equals_the_full_scan_on_random_trains() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        use std::cell::Cell;
        let res = crate::Resolution::DEFAULT;
        let (interfering, clear) = (Cell::new(0), Cell::new(0));
        let mut runner = TestRunner::new(Config::with_cases(96));
        let cases = (
            2..=4usize,
            -180.0..180.0f64,
            -89.0..89.0f64,
            0.5..60.0f64,
            100.0..220.0f64,
            0.0..0.4f64,
        );
        runner
            .run(
                &cases,
                |(arms, beta0, gamma0, width, length, eccentricity)| {
                    let (mut spec, agro) = train(arms, beta0, gamma0, width);
                    spec.arm_length_mm = length;
                    let curve = if eccentricity < 0.05 {
                        crate::CurveSpec::paper()
                    } else {
                        crate::CurveSpec::Ellipse {
                            semi_major_mm: 30.0,
                            eccentricity,
                        }
                    };
                    let curve = curve.build().unwrap();
                    let Ok(kin) = Kinematics::solve(&curve, None, &spec, &res) else {
                        return Ok(());
                    };
                    let (_, least_node, refined) = full_scan(&kin, &agro);
                    let value = interference_clearance(&kin, &agro);
                    prop_assert_eq!(
                        value.to_bits(),
                        refined.to_bits(),
                        "{} vs {}",
                        value,
                        refined
                    );
                    let count = if least_node < 0.0 {
                        &interfering
                    } else {
                        &clear
                    };
                    count.set(count.get() + 1);
                    Ok(())
                },
            )
            .unwrap();
        assert!(
            interfering.get() > 5 && clear.get() > 5,
            "{interfering:?} {clear:?}"
        );
    }

    /// A train reassembled from one whose nodes near its least clearance are marked scans
    /// those nodes alone, and gives the whole scan's value bit for bit: on trains of two
    /// to four arms that interfere and that do not, for random reassemblies (Φ0 and β0
    /// moved by up to 0.2° or 12°, S and H1 by up to 0.4 mm, the bore by 0.04 mm), and for
    /// a reassembly of a reassembly (the displacements add). A band too narrow for the
    /// displacement is refused, so the whole scan decides. (Accepting every band, with
    /// bands below the displacement, fails this test: the least node moves out of them.)
    #[test]
    fn marked_nodes_give_the_whole_scans_clearance_bit_for_bit() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        let curve = crate::CurveSpec::paper().build().unwrap();
        let res = crate::Resolution::DEFAULT;
        let (confined, interfering, refused) = (Cell::new(0), Cell::new(0), Cell::new(0));
        use std::cell::Cell;
        let mut runner = TestRunner::new(Config::with_cases(64));
        let deviation = proptest::array::uniform5(-1.0..1.0f64);
        // Tolerance-sized moves, and moves of tens of degrees (the least node moves far).
        let cases = (
            2..=4usize,
            0..3usize,
            deviation,
            2.0..12.0f64,
            prop_oneof![Just(1.0), Just(60.0)],
        );
        runner
            .run(
                &cases,
                |(arms, design, [dphi, dbeta, ds, dh, da], band_factor, size)| {
                    let (beta0, gamma0, width) =
                        [(-29.0, -53.0, 12.0), (40.0, -20.0, 40.0), (0.0, 60.0, 2.0)][design];
                    let (spec, agro) = train(arms, beta0, gamma0, width);
                    let mut source = Kinematics::solve(&curve, None, &spec, &res).unwrap();
                    let [moved, again] =
                        crate::planetary::moved_for_tests(&spec, [dphi, dbeta, ds, dh], size);
                    let offset = 0.04 * da;
                    // The whole scan, on the same positions unmarked.
                    let whole = |spec: &crate::TrainSpec, offset: f64, from: &Kinematics| {
                        let kin = from.reassembled(spec, offset).unwrap();
                        prop_assert!(kin.marked_nodes().is_none());
                        Ok(interference_clearance(&kin, &agro))
                    };
                    let unmarked = source.clone();
                    let once = whole(&moved, offset, &unmarked)?;
                    let twice = whole(&again, 0.0, &unmarked.reassembled(&moved, offset).unwrap())?;
                    let (delta, _) = source.displacement_and_turn_to(&moved, offset);
                    let band = band_factor * delta;
                    mark_nodes_near_least_clearance(&mut source, &agro, band);
                    let marked = source.marked_nodes().unwrap();
                    prop_assert!(marked.nodes.len() < source.len() || band > 10.0);
                    let first = source.reassembled(&moved, offset).unwrap();
                    let second = first.reassembled(&again, 0.0).unwrap();
                    for (kin, value) in [(&first, once), (&second, twice)] {
                        let (m, marks) = (kin.marked_nodes().unwrap(), kin.marks().unwrap());
                        let scan = Scan::new(kin, &agro);
                        match scan.confined() {
                            Some(v) => {
                                prop_assert_eq!(v.to_bits(), value.to_bits());
                                confined.set(confined.get() + 1);
                                interfering.set(interfering.get() + usize::from(v < 0.0));
                            }
                            None => {
                                prop_assert!(4.0 * marks.displacement_mm >= 0.999_999 * m.band_mm);
                                refused.set(refused.get() + 1);
                            }
                        }
                        prop_assert_eq!(
                            interference_clearance(kin, &agro).to_bits(),
                            value.to_bits()
                        );
                    }
                    Ok(())
                },
            )
            .unwrap();
        let counts = (confined.get(), interfering.get(), refused.get());
        assert!(counts.0 > 20 && counts.1 > 0 && counts.2 > 5, "{counts:?}");
    }
}
