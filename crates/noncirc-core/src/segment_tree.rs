//! Nearest points and self-crossings of a closed polyline, through a tree of boxes over
//! runs of its consecutive segments: the target path's and the tip path's distances to
//! each other (`target`, `fit`). A curve's consecutive segments lie close together, so
//! the runs' boxes are tight, and a query costs about the tree's depth however far it is
//! from the curve (a uniform grid would scan rings of empty cells). The teeth's outlines
//! keep their own grid (`teeth::polyline::OutlineGrid`), signed and bounded by a reach.

use crate::vec2::Vec2;

/// The point of a polyline nearest a query: squared distance (mm²), segment, and the
/// parameter in `[0, 1]` along it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Nearest {
    pub(crate) d2: f64,
    pub(crate) segment: usize,
    pub(crate) t: f64,
}

/// An axis-aligned box `[lo, hi]` (mm).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Aabb {
    lo: Vec2,
    hi: Vec2,
}

impl Aabb {
    fn of(a: Vec2, b: Vec2) -> Self {
        Self {
            lo: Vec2::new(a.x.min(b.x), a.y.min(b.y)),
            hi: Vec2::new(a.x.max(b.x), a.y.max(b.y)),
        }
    }

    fn union(self, o: Self) -> Self {
        Self {
            lo: Vec2::new(self.lo.x.min(o.lo.x), self.lo.y.min(o.lo.y)),
            hi: Vec2::new(self.hi.x.max(o.hi.x), self.hi.y.max(o.hi.y)),
        }
    }

    /// Squared distance (mm²) from `p` to the box (0 inside).
    fn distance2(self, p: Vec2) -> f64 {
        let dx = (self.lo.x - p.x).max(p.x - self.hi.x).max(0.0);
        let dy = (self.lo.y - p.y).max(p.y - self.hi.y).max(0.0);
        dx * dx + dy * dy
    }

    fn overlaps(self, o: Self) -> bool {
        self.lo.x <= o.hi.x && o.lo.x <= self.hi.x && self.lo.y <= o.hi.y && o.lo.y <= self.hi.y
    }
}

/// Segments per leaf run.
const LEAF: usize = 8;

/// A closed polyline with a binary tree of boxes over runs of its segments.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SegmentTree {
    /// The points with the first repeated at the end: segment `i` is
    /// `points[i]→points[i + 1]`.
    points: Vec<Vec2>,
    /// The boxes, level by level from the leaves (runs of [`LEAF`] segments) up to the
    /// root: node `k` of a level covers nodes `2k` and `2k + 1` of the level below.
    levels: Vec<Vec<Aabb>>,
}

impl SegmentTree {
    /// The tree of the closed polyline through `points` (at least 2, finite).
    pub(crate) fn closed(points: &[Vec2]) -> Self {
        let mut closed = Vec::with_capacity(points.len() + 1);
        closed.extend_from_slice(points);
        closed.push(points[0]);
        let n = points.len();
        let leaves = (0..n.div_ceil(LEAF))
            .map(|k| {
                let end = ((k + 1) * LEAF).min(n);
                (k * LEAF..end)
                    .map(|i| Aabb::of(closed[i], closed[i + 1]))
                    .reduce(Aabb::union)
                    .expect("a run has a segment")
            })
            .collect();
        let mut levels: Vec<Vec<Aabb>> = vec![leaves];
        while levels.last().is_some_and(|l| l.len() > 1) {
            let below = levels.last().expect("a level");
            let up = below
                .chunks(2)
                .map(|c| c.iter().copied().reduce(Aabb::union).expect("a child"))
                .collect();
            levels.push(up);
        }
        Self {
            points: closed,
            levels,
        }
    }

    /// The polyline's points (without the repeated first one).
    pub(crate) fn points(&self) -> &[Vec2] {
        &self.points[..self.points.len() - 1]
    }

    fn segments(&self) -> usize {
        self.points.len() - 1
    }

    /// The nearest point of segment `i` to `p`.
    fn segment_nearest(&self, p: Vec2, i: usize) -> Nearest {
        let (d2, t) = nearest_on_segment(p, self.points[i], self.points[i + 1]);
        Nearest { d2, segment: i, t }
    }

    /// The polyline's point nearest `p`. `hint`, a segment likely near (the answer for
    /// the previous point of a path), bounds the search from the start.
    pub(crate) fn nearest(&self, p: Vec2, hint: usize) -> Nearest {
        let best = self.segment_nearest(p, hint.min(self.segments() - 1));
        let top = self.levels.len() - 1;
        let mut best = best;
        self.descend(p, top, 0, &mut best);
        best
    }

    /// Searches node `k` of level `level` for a point nearer than `best`, children nearer
    /// first.
    fn descend(&self, p: Vec2, level: usize, k: usize, best: &mut Nearest) {
        if level == 0 {
            let end = ((k + 1) * LEAF).min(self.segments());
            for i in k * LEAF..end {
                let candidate = self.segment_nearest(p, i);
                if candidate.d2 < best.d2 {
                    *best = candidate;
                }
            }
            return;
        }
        let below = &self.levels[level - 1];
        let children = [2 * k, 2 * k + 1];
        let mut near: [(f64, usize); 2] = [(f64::INFINITY, 0); 2];
        for (slot, &c) in near.iter_mut().zip(&children) {
            if let Some(b) = below.get(c) {
                *slot = (b.distance2(p), c);
            }
        }
        if near[1].0 < near[0].0 {
            near.swap(0, 1);
        }
        for (d2, c) in near {
            if d2 < best.d2 {
                self.descend(p, level - 1, c, best);
            }
        }
    }

    /// Where the polyline crosses itself (the crossing with the lowest pair of segment
    /// indices), if it does: segments `i < j`, not adjacent, and the point.
    pub(crate) fn self_crossing(&self) -> Option<(usize, usize, Vec2)> {
        let n = self.segments();
        for i in 0..n {
            let (a0, a1) = (self.points[i], self.points[i + 1]);
            let mut found: Option<(usize, Vec2)> = None;
            self.crossings(Aabb::of(a0, a1), self.levels.len() - 1, 0, &mut |j| {
                // Adjacent segments share a point, as do the last and the first.
                if j <= i + 1 || (i == 0 && j == n - 1) || found.is_some_and(|(k, _)| k < j) {
                    return;
                }
                let (b0, b1) = (self.points[j], self.points[j + 1]);
                if let Some((t, _)) = segments_cross(a0, a1, b0, b1) {
                    found = Some((j, a0 + (a1 - a0) * t));
                }
            });
            if let Some((j, at)) = found {
                return Some((i, j, at));
            }
        }
        None
    }

    /// Calls `visit` with each segment of node `k` of `level` whose run's box overlaps
    /// `query`.
    fn crossings(&self, query: Aabb, level: usize, k: usize, visit: &mut dyn FnMut(usize)) {
        if !self.levels[level][k].overlaps(query) {
            return;
        }
        if level == 0 {
            let end = ((k + 1) * LEAF).min(self.segments());
            (k * LEAF..end).for_each(visit);
            return;
        }
        for c in [2 * k, 2 * k + 1] {
            if c < self.levels[level - 1].len() {
                self.crossings(query, level - 1, c, visit);
            }
        }
    }
}

/// The point of segment `a→b` nearest `p`: its squared distance (mm²) and its parameter
/// in `[0, 1]` (0 for a segment of no length).
pub(crate) fn nearest_on_segment(p: Vec2, a: Vec2, b: Vec2) -> (f64, f64) {
    let d = b - a;
    let len2 = d.hypot2();
    let t = if len2 > 0.0 {
        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((a + d * t - p).hypot2(), t)
}

/// Where segments `p0→p1` and `q0→q1` cross: the parameters `(t, u)` in `[0, 1]` of each.
pub(crate) fn segments_cross(p0: Vec2, p1: Vec2, q0: Vec2, q1: Vec2) -> Option<(f64, f64)> {
    let (d, e) = (p1 - p0, q1 - q0);
    let den = d.cross(e);
    if den == 0.0 {
        return None;
    }
    let w = q0 - p0;
    let (t, u) = (w.cross(e) / den, w.cross(d) / den);
    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then_some((t, u))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn brute_force(points: &[Vec2], p: Vec2) -> f64 {
        let n = points.len();
        (0..n)
            .map(|i| {
                let (a, b) = (points[i], points[(i + 1) % n]);
                let d = b - a;
                let t = ((p - a).dot(d) / d.hypot2()).clamp(0.0, 1.0);
                (a + d * t - p).hypot2()
            })
            .fold(f64::INFINITY, f64::min)
    }

    proptest! {
        #[test]
        fn the_nearest_point_is_the_brute_forces_near_and_far(
            radii in prop::collection::vec(20.0f64..200.0, 5..200),
            qx in -2000.0f64..2000.0, qy in -2000.0f64..2000.0, scale in 0.01f64..1.0,
            hint in 0usize..1000,
        ) {
            // A star-shaped polygon, and queries from on it to ten times its size away,
            // from any hint.
            let n = radii.len();
            let points: Vec<Vec2> = (radii.iter().enumerate())
                .map(|(i, &r)| crate::angle::unit(std::f64::consts::TAU * i as f64 / n as f64) * r)
                .collect();
            let tree = SegmentTree::closed(&points);
            let q = Vec2::new(qx, qy) * scale;
            let expected = brute_force(&points, q);
            let got = tree.nearest(q, hint % n);
            prop_assert!((got.d2 - expected).abs() <= 1e-9 * expected.max(1.0), "{} vs {}", got.d2, expected);
            // The segment and parameter it names give that distance.
            let (a, b) = (points[got.segment], points[(got.segment + 1) % n]);
            prop_assert!(((a + (b - a) * got.t - q).hypot2() - got.d2).abs() <= 1e-9 * expected.max(1.0));
        }
    }

    #[test]
    fn a_bow_tie_crosses_itself_where_its_diagonals_meet() {
        let bow_tie = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(0.0, 2.0),
        ];
        let (i, j, at) = SegmentTree::closed(&bow_tie).self_crossing().unwrap();
        assert_eq!((i, j), (0, 2));
        assert!((at - Vec2::new(1.0, 1.0)).hypot() < 1e-12);
        let polygon: Vec<Vec2> = (0..1000)
            .map(|i| crate::angle::unit(std::f64::consts::TAU * i as f64 / 1000.0) * 100.0)
            .collect();
        assert_eq!(SegmentTree::closed(&polygon).self_crossing(), None);
        // A loop that crosses itself far along: a limaçon's inner loop.
        let limacon: Vec<Vec2> = (0..999)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 999.0;
                crate::angle::unit(t) * (50.0 + 100.0 * t.cos())
            })
            .collect();
        let (_, _, at) = SegmentTree::closed(&limacon).self_crossing().unwrap();
        // It crosses itself on the x axis at the origin's side: r = 0 at cos t = −1/2.
        assert!(at.hypot() < 1.0, "{at:?}");
    }
}
