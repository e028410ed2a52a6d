//! The gearbox of an n-arm train: the gears of different arm sets turn in one plane (each
//! intermediate meshes with the sun, each planet with its intermediate; with two pairs, in
//! two planes), so no two of them in one plane may overlap. Their centres stand still on the carrier; only their orientations change.
//! Pitch curves are star-shaped about their centres, so a point lies inside a gear when it
//! is nearer the centre than the pitch curve in its direction.

use std::f64::consts::{PI, TAU};

use crate::angle::unit;
use crate::planetary::Kinematics;
use crate::vec2::Vec2;

/// Bins of own angle for [`Radial::most_within`].
const BINS: usize = 64;

/// Most carrier nodes, and most points of each gear, at which the overlap is measured:
/// every k-th beyond it. Each node compares every point with the other gear, a cost of the
/// square of the samples (23 s an evaluation at 307 200 samples a turn, 607 s at 786 432);
/// thinned, it costs at most what it costs at this count, and an evaluation at 786 432
/// samples takes 0.6 s (three sets) to 1.0 s (four that overlap). The nodes and points kept
/// are 1/16° and about 0.05 mm apart on a transplanter's gears, where the depth, smooth in
/// both, moves by under 1e-4 mm between them (tested); resolutions up to this count are
/// measured in full, as before.
const MOST_PROBES: usize = 5_760;

/// The step that keeps at most [`MOST_PROBES`] of `len` nodes or points (1: all of them).
fn probe_step(len: usize) -> usize {
    len.div_ceil(MOST_PROBES).max(1)
}

/// A closed pitch curve seen from its centre: its radius (mm) by own angle (rad).
struct Radial {
    /// Own angles of the samples, ascending in `[0, 2π)`.
    angles: Vec<f64>,
    radii: Vec<f64>,
    /// The largest radius (mm).
    reach: f64,
    /// The largest radius the interpolated curve reaches in each of [`BINS`] equal bins of
    /// own angle.
    bin_reach: [f64; BINS],
}

impl Radial {
    /// From the curve's points in its own frame (star-shaped about the origin).
    fn new(points: &[Vec2]) -> Self {
        let mut polar: Vec<(f64, f64)> = (points.iter())
            .map(|p| (p.y.atan2(p.x).rem_euclid(TAU), p.hypot()))
            .collect();
        polar.sort_by(|a, b| a.0.total_cmp(&b.0));
        let reach = polar.iter().map(|p| p.1).fold(0.0, f64::max);
        // Between two samples the radius lies between theirs: each bin the span between
        // neighbours crosses holds at most the larger.
        let mut bin_reach = [0.0; BINS];
        let bin = |a: f64| ((a / TAU * BINS as f64) as usize).min(BINS - 1);
        for i in 0..polar.len() {
            let ((a0, r0), (a1, r1)) = (polar[i], polar[(i + 1) % polar.len()]);
            let (first, last) = (bin(a0), bin(a1));
            let mut b = first;
            loop {
                bin_reach[b] = f64::max(bin_reach[b], r0.max(r1));
                if b == last {
                    break;
                }
                b = (b + 1) % BINS;
            }
        }
        let (angles, radii) = polar.into_iter().unzip();
        Self {
            angles,
            radii,
            reach,
            bin_reach,
        }
    }

    /// An upper bound of the radius (mm) over own angles within `half` (rad) of `centre`.
    fn most_within(&self, centre: f64, half: f64) -> f64 {
        if half >= 0.5 * TAU {
            return self.reach;
        }
        let at = |a: f64| (a.rem_euclid(TAU) / TAU * BINS as f64) as usize % BINS;
        let (first, last) = (at(centre - half), at(centre + half));
        let mut b = first;
        let mut most = self.bin_reach[b];
        while b != last {
            b = (b + 1) % BINS;
            most = most.max(self.bin_reach[b]);
        }
        most
    }

    /// The radius at own angle `phi` (rad, any real): linear between the neighbouring
    /// samples, across the wrap too.
    fn radius(&self, phi: f64) -> f64 {
        let phi = phi.rem_euclid(TAU);
        let n = self.angles.len();
        let i = self.angles.partition_point(|&a| a <= phi);
        let (lo, hi) = (if i == 0 { n - 1 } else { i - 1 }, i % n);
        let (a0, a1) = (self.angles[lo], self.angles[hi]);
        let span = (a1 - a0).rem_euclid(TAU);
        if span == 0.0 {
            return self.radii[lo];
        }
        let t = (phi - a0).rem_euclid(TAU) / span;
        self.radii[lo] + t * (self.radii[hi] - self.radii[lo])
    }
}

/// A gear where it stands: its curve, centre (mm) and orientation (rad).
#[derive(Clone, Copy)]
struct Placed<'a> {
    curve: &'a Radial,
    points: &'a [Vec2],
    centre: Vec2,
    angle: f64,
}

impl Placed<'_> {
    /// How deep the points of `self` reach into `other` (mm; ≤ 0 when none is inside).
    fn depth_into(&self, other: &Placed) -> f64 {
        let (turn, reach2) = (unit(self.angle), other.curve.reach * other.curve.reach);
        let mut deepest = f64::NEG_INFINITY;
        for p in self.points {
            let d = self.centre + p.rotated(turn) - other.centre;
            let r2 = d.hypot2();
            if r2 >= reach2 {
                continue;
            }
            let r = r2.sqrt();
            let inside = other.curve.radius(d.y.atan2(d.x) - other.angle) - r;
            deepest = deepest.max(inside);
        }
        deepest
    }
}

/// One gear of every arm set: its pitch curve in its own frame, the plane it turns in, and
/// whether it stands where the intermediate or the planet does.
struct SetGear {
    points: Vec<Vec2>,
    curve: Radial,
    /// Its largest radius (mm), from the pair's radius range (refined between samples).
    reach: f64,
    plane: usize,
    planet: bool,
}

impl SetGear {
    /// The gear's curve from all its `points`; at most [`MOST_PROBES`] of them, evenly
    /// spaced, probe the other gears.
    fn new(points: Vec<Vec2>, reach: f64, plane: usize, planet: bool) -> Self {
        let curve = Radial::new(&points);
        let every = probe_step(points.len());
        Self {
            points: points.into_iter().step_by(every).collect(),
            curve,
            reach,
            plane,
            planet,
        }
    }
}

/// The gears each arm set carries: in the paper's train the intermediate and the planet,
/// both in the sun's plane; with two pairs the intermediate's layer A in the sun's plane,
/// and its layer B with the planet in a second plane.
fn set_gears(kin: &Kinematics) -> Vec<SetGear> {
    let first = kin.pair();
    let layer_a = SetGear::new(
        first.driven_points(),
        first.centre_distance() - first.radius_range().0,
        0,
        false,
    );
    match kin.second_pair() {
        None => vec![
            layer_a,
            SetGear::new(first.driver_points(), first.radius_range().1, 0, true),
        ],
        Some(second) => vec![
            layer_a,
            SetGear::new(second.driver_points(), second.radius_range().1, 1, false),
            SetGear::new(kin.planet_points(), kin.planet_reach(), 1, true),
        ],
    }
}

/// The deepest overlap (mm, > 0) between gears of different arm sets in one plane over one
/// carrier turn, at the kinematics' nodes, or `None` when no two overlap. Pairs whose
/// circles of largest radius keep apart are not looked at, so a two- or three-arm train
/// with room between its sets costs nothing.
pub(crate) fn gear_sets_overlap(kin: &Kinematics) -> Option<f64> {
    let arms = kin.arms();
    let gears = set_gears(kin);
    // Gear a of arm set I against gear b of set m, in one plane. The pair at lag m is the
    // pair at lag arms − m seen from the other set, so like gears need m ≤ arms/2, and
    // gear a of set I against every other set's gear b covers b of set I against a.
    let pairs = (0..gears.len()).flat_map(|a| {
        let gears = &gears;
        (a..gears.len())
            .filter(move |&b| gears[a].plane == gears[b].plane)
            .flat_map(move |b| {
                let lags = if a == b { 1..arms / 2 + 1 } else { 1..arms };
                lags.map(move |m| (a, b, m))
            })
    });
    let centre = |g: &SetGear, j: usize| match g.planet {
        false => kin.intermediate_at(j).0,
        true => kin.planet_centres()[j],
    };
    // The centres keep their distance on the carrier: pairs whose circles of largest
    // radius keep apart never meet.
    let near: Vec<_> = pairs
        .filter(|&(a, b, m)| {
            let (ga, gb) = (&gears[a], &gears[b]);
            (centre(ga, 0) - centre(gb, kin.arm_node(m, 0))).hypot() < ga.reach + gb.reach
        })
        .collect();
    if near.is_empty() {
        return None;
    }
    fn place<'g>(kin: &Kinematics, g: &'g SetGear, j: usize) -> Placed<'g> {
        let (centre, angle) = match g.planet {
            false => kin.intermediate_at(j),
            true => (kin.planet_centres()[j], kin.planet_angles()[j]),
        };
        Placed {
            curve: &g.curve,
            points: &g.points,
            centre,
            angle,
        }
    }
    let mut deepest = f64::NEG_INFINITY;
    let every = probe_step(kin.len());
    for (a, b, m) in near {
        for j in (0..kin.len()).step_by(every) {
            let (ga, gb) = (
                place(kin, &gears[a], j),
                place(kin, &gears[b], kin.arm_node(m, j)),
            );
            // A point of both is within each gear's reach of the other's centre, so in a
            // sector of each seen from its own centre; were the two sectors' radii short of
            // the centres' distance, none could be.
            let d = gb.centre - ga.centre;
            let dist = d.hypot();
            let towards = d.y.atan2(d.x);
            let half = |r: f64| if r < dist { (r / dist).asin() } else { TAU };
            let most = ga
                .curve
                .most_within(towards - ga.angle, half(gb.curve.reach))
                + gb.curve
                    .most_within(towards + PI - gb.angle, half(ga.curve.reach));
            if most < dist {
                continue;
            }
            deepest = deepest.max(ga.depth_into(&gb)).max(gb.depth_into(&ga));
        }
    }
    (deepest > 0.0).then_some(deepest)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `p` lies inside the closed polygon `poly` (even-odd rule).
    fn inside(poly: &[Vec2], p: Vec2) -> bool {
        let mut odd = false;
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
                odd = !odd;
            }
        }
        odd
    }

    #[test]
    fn a_radial_curve_interpolates_its_samples_across_the_wrap() {
        let points: Vec<Vec2> = (0..8)
            .map(|k| unit(TAU * (k as f64 + 0.5) / 8.0) * (10.0 + k as f64))
            .collect();
        let r = Radial::new(&points);
        assert_eq!(r.reach, 17.0);
        assert!((r.radius(TAU * 1.5 / 8.0) - 11.0).abs() < 1e-12);
        // Between the last sample (17 at 337.5°) and the first (10 at 22.5°).
        assert!((r.radius(0.0) - 13.5).abs() < 1e-12);
        assert!((r.radius(-TAU) - 13.5).abs() < 1e-12);
    }

    #[test]
    fn the_sector_bound_holds_the_curve_in_every_sector() {
        let curve = crate::CurveSpec::paper().build().unwrap();
        let pair = crate::GearPair::solve(curve, crate::Resolution::DEFAULT).unwrap();
        for points in [pair.driver_points(), pair.driven_points()] {
            let r = Radial::new(&points);
            for k in 0..97 {
                let (centre, half) = (TAU * k as f64 / 97.0, 0.02 + 0.03 * (k % 11) as f64);
                let bound = r.most_within(centre, half);
                for i in 0..=200 {
                    let phi = centre - half + 2.0 * half * i as f64 / 200.0;
                    assert!(r.radius(phi) <= bound + 1e-12, "{centre} ± {half}: {phi}");
                }
            }
        }
    }

    #[test]
    fn the_gears_at_the_nodes_are_where_the_states_put_them() {
        let curve = crate::CurveSpec::paper().build().unwrap();
        let spec = crate::TrainSpec::default();
        let kin = Kinematics::solve(&curve, None, &spec, &crate::Resolution::DEFAULT).unwrap();
        for j in 0..kin.len() {
            let st = kin.state_at(kin.theta(j));
            let (o2, theta2) = kin.intermediate_at(j);
            assert!(
                (o2 - st.o2).hypot() < 1e-9 && (theta2 - st.theta2).abs() < 1e-9,
                "{j}"
            );
            assert!((kin.planet_centres()[j] - st.o3).hypot() < 1e-9);
            assert!((kin.planet_angles()[j] - st.theta3).abs() < 1e-9);
        }
    }

    #[test]
    fn overlaps_agree_with_a_point_in_polygon_scan_of_every_pair() {
        let curve = crate::CurveSpec::paper().build().unwrap();
        let mut overlapping = 0;
        for arms in [2, 3, 4] {
            for gamma0 in [-80.0, -53.0, -20.0] {
                let spec = crate::TrainSpec {
                    gamma0_deg: gamma0,
                    arms,
                    ..Default::default()
                };
                let kin =
                    Kinematics::solve(&curve, None, &spec, &crate::Resolution::DEFAULT).unwrap();
                let pair = kin.pair();
                let (sun, inter) = (pair.driver_points(), pair.driven_points());
                // Every gear of every set at every node, as the studio draws it.
                let world = |k: usize, j: usize| {
                    let st = kin.state_at(kin.theta(kin.arm_node(k, j)));
                    let put = |pts: &[Vec2], c: Vec2, a: f64| -> Vec<Vec2> {
                        pts.iter().map(|p| c + p.rotated(unit(a))).collect()
                    };
                    [put(&inter, st.o2, st.theta2), put(&sun, st.o3, st.theta3)]
                };
                let mut scan = false;
                for j in 0..kin.len() {
                    let sets: Vec<_> = (0..arms).map(|k| world(k, j)).collect();
                    for (k, l) in (0..arms).flat_map(|k| (0..arms).map(move |l| (k, l))) {
                        if k == l {
                            continue;
                        }
                        for g in &sets[k] {
                            for h in &sets[l] {
                                scan |= g.iter().any(|&p| inside(h, p));
                            }
                        }
                    }
                }
                let found = gear_sets_overlap(&kin);
                assert_eq!(found.is_some(), scan, "{arms} arms, γ0 {gamma0}: {found:?}");
                overlapping += usize::from(scan);
            }
        }
        // The cases include overlapping and clear gearboxes.
        assert!((1..9).contains(&overlapping), "{overlapping}");
    }

    /// Above [`MOST_PROBES`] samples the overlap is measured at every k-th node and point:
    /// it stays within 1e-4 mm of the full measure at the threshold and of the finer
    /// resolutions' own, and its cost no longer grows as the square of the samples.
    #[test]
    fn thinned_overlaps_agree_with_the_full_measure() {
        let curve = crate::CurveSpec::paper().build().unwrap();
        for gamma0 in [-80.0, -53.0] {
            let spec = crate::TrainSpec {
                gamma0_deg: gamma0,
                arms: 4,
                ..Default::default()
            };
            let at = |n: usize| {
                let resolution = crate::Resolution::DEFAULT.with_samples(n);
                let kin = Kinematics::solve(&curve, None, &spec, &resolution).unwrap();
                gear_sets_overlap(&kin).expect("four sets of the paper's gears overlap")
            };
            // In full at MOST_PROBES; thinned 2, 4 and 8 to 1 above it.
            let full = at(MOST_PROBES);
            for n in [2 * MOST_PROBES, 4 * MOST_PROBES, 8 * MOST_PROBES] {
                let thinned = at(n);
                assert!(
                    (thinned - full).abs() < 1e-4,
                    "γ0 {gamma0}, {n} samples: {thinned} against {full} mm in full"
                );
            }
        }
    }
}
