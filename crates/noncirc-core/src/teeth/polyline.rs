//! Plane polylines: segment intersection, signed distance to a closed outline through a
//! uniform grid of its segments, and the simplicity check of a closed outline.

use crate::segment_tree::nearest_on_segment;
pub(super) use crate::segment_tree::segments_cross;
use crate::vec2::Vec2;

/// The first crossing of two open polylines, as fractional indices `(i + t, j + u)`.
pub(super) fn first_crossing(a: &[Vec2], b: &[Vec2]) -> Option<(f64, f64)> {
    for i in 0..a.len().saturating_sub(1) {
        for j in 0..b.len().saturating_sub(1) {
            if let Some((t, u)) = segments_cross(a[i], a[i + 1], b[j], b[j + 1]) {
                return Some((i as f64 + t, j as f64 + u));
            }
        }
    }
    None
}

/// Distance (mm) from `p` to the segment `a→b`.
pub fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f64 {
    nearest_on_segment(p, a, b).0.sqrt()
}

/// Signed curvature (1/mm; positive turning left) of the circle through `a`, `b`, `c`.
pub(super) fn menger_curvature(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let product = ((b - a).hypot2() * (c - b).hypot2() * (c - a).hypot2()).sqrt();
    if product > 0.0 {
        2.0 * (b - a).cross(c - b) / product
    } else {
        0.0
    }
}

/// How far (mm, to the right of the chord's direction) a curve lies from its chord `chord`
/// at the chord's middle, where the curve turns with curvatures `kappa_a`, `kappa_b` (1/mm,
/// positive left) at the chord's ends: `κ L²/8`, the parabola through the ends with the
/// mean curvature (at the fraction `t` of the way along, `4t(1 − t)` times this). Where one
/// end turns more than twice as sharply as the other, it is taken for a corner (which the
/// circle through its neighbours cannot measure) and the other end's curvature for the
/// chord's. Zero where the ends turn different ways (an inflection, or a reflex corner),
/// and where the bow would be more than twice the `chord_tolerance` (mm) the chords were
/// cut to: the chord then runs between corners (a tip land) and is the outline itself.
pub(super) fn chord_bow(kappa_a: f64, kappa_b: f64, chord: Vec2, chord_tolerance: f64) -> f64 {
    if kappa_a * kappa_b <= 0.0 {
        return 0.0;
    }
    let (lo, hi) = (
        kappa_a.abs().min(kappa_b.abs()),
        kappa_a.abs().max(kappa_b.abs()),
    );
    let kappa = if hi > 2.0 * lo {
        lo.copysign(kappa_a)
    } else {
        0.5 * (kappa_a + kappa_b)
    };
    let bow = 0.125 * kappa * chord.hypot2();
    if bow.abs() > 2.0 * chord_tolerance {
        0.0
    } else {
        bow
    }
}

/// A closed outline (counter-clockwise: material on the left of each segment) with its
/// segments binned on a uniform grid, for signed distances to points within a reach.
#[derive(Debug, Clone)]
pub(super) struct OutlineGrid {
    /// The outline's points with the first repeated at the end: segment `i` is
    /// `points[i]→points[i + 1]`.
    points: Vec<Vec2>,
    /// The segments as the queries' inner loop reads them, without a division.
    segments: Vec<Segment>,
    /// Distance (mm) up to which [`Self::signed_distance`] answers.
    reach: f64,
    /// Largest distance (mm) of a chord from the curve it stands for.
    chord_tolerance: f64,
    /// Whether each point is a joint: where two pieces of the outline meet, at an angle or
    /// with a jump in curvature (the circle through its neighbours belongs to neither).
    joint: Vec<bool>,
    origin: Vec2,
    /// Inverse of the cell width (1/mm); the width is at least twice the reach, so a
    /// query's square of half-width `reach` overlaps at most two cells a side.
    inv_cell: f64,
    cols: usize,
    /// Columns and rows, as numbers.
    size: Vec2,
    /// Where each cell's segment indices start in `items` (row-major; one more entry than
    /// cells, the last one `items.len()`).
    starts: Vec<u32>,
    items: Vec<u32>,
}

/// A segment `start → start + direction` with the inverse of its squared length (0 for a
/// degenerate segment).
#[derive(Debug, Clone, Copy)]
struct Segment {
    start: Vec2,
    direction: Vec2,
    inv_len2: f64,
}

/// The grid's three large buffers. A search cuts pair after pair, and fresh buffers for
/// each would leave the allocator to hand the heap's top back to the system and fault it
/// in again every time (glibc trims a free top above 128 kB; a pair's grids are twice
/// that): a dropped grid leaves its buffers, emptied, to the next one on the thread.
#[derive(Default)]
struct GridBuffers {
    segments: Vec<Segment>,
    starts: Vec<u32>,
    items: Vec<u32>,
}

/// Buffer sets kept per thread (a pair needs two).
const POOLED_GRIDS: usize = 4;

thread_local! {
    static GRID_POOL: std::cell::RefCell<Vec<GridBuffers>> = const { std::cell::RefCell::new(Vec::new()) };
}

impl GridBuffers {
    /// Empty buffers, from the thread's pool if it has some.
    fn take() -> Self {
        GRID_POOL
            .try_with(|pool| pool.borrow_mut().pop())
            .ok()
            .flatten()
            .unwrap_or_default()
    }

    /// Empties the buffers and leaves them to the thread's pool, unless it is full.
    fn give_back(mut self) {
        self.segments.clear();
        self.starts.clear();
        self.items.clear();
        let _ = GRID_POOL.try_with(|pool| {
            let mut pool = pool.borrow_mut();
            if pool.len() < POOLED_GRIDS {
                pool.push(self);
            }
        });
    }
}

impl Drop for OutlineGrid {
    fn drop(&mut self) {
        GridBuffers {
            segments: std::mem::take(&mut self.segments),
            starts: std::mem::take(&mut self.starts),
            items: std::mem::take(&mut self.items),
        }
        .give_back();
    }
}

/// Most cells along either side of a grid: a small reach on a large outline widens the
/// cells rather than allocate more (a query then scans more segments but misses none).
const MAX_CELLS_PER_SIDE: f64 = 128.0;

impl OutlineGrid {
    /// Bins the segments of `points` (closed, counter-clockwise; chords within
    /// `chord_tolerance` mm of the curve they stand for; pieces meeting at the points
    /// `joints`) for distance queries up to `reach` (mm).
    pub(super) fn new(
        mut points: Vec<Vec2>,
        reach: f64,
        chord_tolerance: f64,
        joints: &[usize],
    ) -> Self {
        let (mut lo, mut hi) = (points[0], points[0]);
        for p in &points {
            lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        let cell = (2.0 * reach).max((hi.x - lo.x).max(hi.y - lo.y) / MAX_CELLS_PER_SIDE);
        let (origin, inv_cell) = (lo - Vec2::new(cell, cell), 1.0 / cell);
        let cols = ((hi.x - origin.x) / cell).ceil() as usize + 2;
        let rows = ((hi.y - origin.y) / cell).ceil() as usize + 2;
        let n = points.len();
        let mut joint = vec![false; n];
        for &k in joints {
            joint[k] = true;
        }
        points.push(points[0]);
        let GridBuffers {
            mut segments,
            mut starts,
            mut items,
        } = GridBuffers::take();
        segments.extend(points.windows(2).map(|w| {
            let d = w[1] - w[0];
            let len2 = d.hypot2();
            Segment {
                start: w[0],
                direction: d,
                inv_len2: if len2 > 0.0 { 1.0 / len2 } else { 0.0 },
            }
        }));
        // Each segment's cells, by its bounding box: `(first cell of each row, columns,
        // rows)`.
        let box_of = |i: usize| {
            let [c0, c1, r0, r1] = Self::box_cells(origin, inv_cell, points[i], points[i + 1]);
            (r0 * cols + c0, c1 - c0 + 1, r1 - r0 + 1)
        };
        // Counting sort: count per cell, running sums (each cell's end), then fill each
        // cell from its end down, leaving `starts[k]` at its start.
        let cells = cols * rows;
        starts.resize(cells + 1, 0);
        for i in 0..n {
            let (first, width, height) = box_of(i);
            for row in 0..height {
                let k = first + row * cols;
                for count in &mut starts[k..k + width] {
                    *count += 1;
                }
            }
        }
        for k in 1..cells {
            starts[k] += starts[k - 1];
        }
        starts[cells] = starts[cells - 1];
        items.resize(starts[cells] as usize, 0);
        for i in (0..n).rev() {
            let (first, width, height) = box_of(i);
            for row in 0..height {
                let k = first + row * cols;
                for start in &mut starts[k..k + width] {
                    *start -= 1;
                    items[*start as usize] = i as u32;
                }
            }
        }
        Self {
            points,
            segments,
            reach,
            chord_tolerance,
            joint,
            origin,
            inv_cell,
            cols,
            size: Vec2::new(cols as f64, rows as f64),
            starts,
            items,
        }
    }

    /// The segments binned in cell `k`.
    #[inline]
    fn cell_items(&self, k: usize) -> &[u32] {
        &self.items[self.starts[k] as usize..self.starts[k + 1] as usize]
    }

    /// The cells `[first column, last column, first row, last row]` of the bounding box
    /// of segment `a→b`.
    #[inline]
    fn box_cells(origin: Vec2, inv_cell: f64, a: Vec2, b: Vec2) -> [usize; 4] {
        // Through `u32`: a float-to-`usize` cast is a longer instruction sequence.
        let at = |v: f64, o: f64| ((v - o) * inv_cell).max(0.0) as u32 as usize;
        [
            at(a.x.min(b.x), origin.x),
            at(a.x.max(b.x), origin.x),
            at(a.y.min(b.y), origin.y),
            at(a.y.max(b.y), origin.y),
        ]
    }

    /// Distance (mm) up to which [`Self::signed_distance`] answers.
    pub(super) fn reach(&self) -> f64 {
        self.reach
    }

    /// Largest distance (mm) of a chord from the curve it stands for.
    pub(super) fn chord_tolerance(&self) -> f64 {
        self.chord_tolerance
    }

    /// Whether point `i` is a joint between two pieces.
    pub(super) fn is_joint(&self, i: usize) -> bool {
        self.joint[i]
    }

    /// The outline's points.
    pub(super) fn points(&self) -> &[Vec2] {
        &self.points[..self.points.len() - 1]
    }

    /// Signed distance (mm) from `p` to the outline, negative inside the material, if the
    /// outline passes within the reach of `p` (exact then); `None` if it does not. (The
    /// checks measure to the curves, [`Self::signed_distance_to_curve`]; this is what the
    /// tests hold that to.)
    #[cfg(test)]
    pub(super) fn signed_distance(&self, p: Vec2) -> Option<f64> {
        let nearest = self.nearest(p)?;
        Some(self.signed(p, nearest))
    }

    /// The signed distance (mm) from `p` to the curve the outline's chords stand for,
    /// negative inside, if the outline passes within the reach of `p`: where
    /// the nearest point lies inside a chord, the chord's sag there (from the circles
    /// through each end and its neighbours, [`chord_bow`]; at a joint, the other end's
    /// alone) is taken off. The chords of a curve cut within a tolerance lie up to that
    /// tolerance inside it; this leaves a small fraction of it.
    pub(super) fn signed_distance_to_curve(&self, p: Vec2) -> Option<f64> {
        let nearest = self.nearest(p)?;
        let (_, i, t) = nearest;
        let d = self.signed(p, nearest);
        let n = self.points.len() - 1;
        if !(t > 0.0 && t < 1.0) {
            return Some(d);
        }
        let at = |k: usize| self.points[(i + k + n - 1) % n];
        let (a, b, c, e) = (at(0), at(1), at(2), at(3));
        let turn_b = (!self.joint[i]).then(|| menger_curvature(a, b, c));
        let turn_c = (!self.joint[(i + 1) % n]).then(|| menger_curvature(b, c, e));
        let (kappa_b, kappa_c) = match (turn_b, turn_c) {
            (Some(x), Some(y)) => (x, y),
            (Some(x), None) | (None, Some(x)) => (x, x),
            (None, None) => return Some(d),
        };
        let bow = chord_bow(kappa_b, kappa_c, c - b, self.chord_tolerance);
        Some(d - bow * 4.0 * t * (1.0 - t))
    }

    /// The nearest segment to `p` within the reach: squared distance, index, parameter.
    fn nearest(&self, p: Vec2) -> Option<(f64, usize, f64)> {
        // The query's square in cell units, inside the grid or answered at once.
        let inv = self.inv_cell;
        let (x, y) = ((p.x - self.origin.x) * inv, (p.y - self.origin.y) * inv);
        let w = self.reach * inv;
        if !(x - w >= 0.0 && y - w >= 0.0 && x + w < self.size.x && y + w < self.size.y) {
            return None;
        }
        // Truncation is the floor here: the coordinates are not negative.
        let cell = |v: f64| v as u32 as usize;
        let (c0, c1, r0, r1) = (cell(x - w), cell(x + w), cell(y - w), cell(y + w));
        let mut best = (f64::INFINITY, 0usize, 0.0);
        for row in r0..=r1 {
            for col in c0..=c1 {
                for &i in self.cell_items(row * self.cols + col) {
                    let i = i as usize;
                    let Segment {
                        start: a,
                        direction: d,
                        inv_len2,
                    } = self.segments[i];
                    let t = ((p - a).dot(d) * inv_len2).clamp(0.0, 1.0);
                    let d2 = (a + d * t - p).hypot2();
                    if d2 < best.0 {
                        best = (d2, i, t);
                    }
                }
            }
        }
        (best.0 < self.reach * self.reach).then_some(best)
    }

    /// The distance of `p` from its nearest segment `(d2, i, t)`, negative inside.
    fn signed(&self, p: Vec2, (d2, i, t): (f64, usize, f64)) -> f64 {
        let n = self.points.len() - 1;
        let side = |k: usize| {
            let segment = &self.segments[k];
            segment.direction.cross(p - segment.start)
        };
        // Inside (left of a counter-clockwise outline) by the nearest segment, or at a
        // vertex by both of its segments: left of both at a convex corner, of either at a
        // reflex one.
        let inside = if t > 0.0 && t < 1.0 {
            side(i) > 0.0
        } else {
            // The segments before and after the vertex (indices wrap without a division).
            let (prev, next) = if t >= 1.0 {
                (i, if i + 1 == n { 0 } else { i + 1 })
            } else {
                (if i == 0 { n - 1 } else { i - 1 }, i)
            };
            let convex =
                (self.segments[prev].direction).cross(self.segments[next].direction) >= 0.0;
            if convex {
                side(prev) > 0.0 && side(next) > 0.0
            } else {
                side(prev) > 0.0 || side(next) > 0.0
            }
        };
        let d = d2.sqrt();
        if inside {
            -d
        } else {
            d
        }
    }

    /// Where the closed outline crosses itself (the first crossing found), if it does:
    /// non-adjacent segments that meet, found through the grid.
    pub(super) fn self_crossing(&self) -> Option<Vec2> {
        let n = self.points.len() - 1;
        let bounds = |a: Vec2, b: Vec2| (a.x.min(b.x), a.x.max(b.x), a.y.min(b.y), a.y.max(b.y));
        for i in 0..n {
            let (a0, a1) = (self.points[i], self.points[i + 1]);
            let (x0, x1, y0, y1) = bounds(a0, a1);
            let [c0, c1, r0, r1] = Self::box_cells(self.origin, self.inv_cell, a0, a1);
            for row in r0..=r1 {
                for col in c0..=c1 {
                    for &j in self.cell_items(row * self.cols + col) {
                        let j = j as usize;
                        // Adjacent segments share a point; `j > i + 1` leaves the pair
                        // that closes the outline.
                        if j <= i + 1 || (i == 0 && j == n - 1) {
                            continue;
                        }
                        let (b0, b1) = (self.points[j], self.points[j + 1]);
                        let (u0, u1, v0, v1) = bounds(b0, b1);
                        if u0 > x1 || u1 < x0 || v0 > y1 || v1 < y0 {
                            continue;
                        }
                        if let Some((t, _)) = segments_cross(a0, a1, b0, b1) {
                            return Some(a0 + (a1 - a0) * t);
                        }
                    }
                }
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn square() -> Vec<Vec2> {
        vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
        ]
    }

    #[test]
    fn signed_distance_is_negative_inside_and_exact_near_edges_and_corners() {
        let g = OutlineGrid::new(square(), 0.6, 0.01, &[]);
        assert!((g.signed_distance(Vec2::new(1.0, 0.2)).unwrap() + 0.2).abs() < 1e-15);
        assert!((g.signed_distance(Vec2::new(1.0, -0.3)).unwrap() - 0.3).abs() < 1e-15);
        let corner = g.signed_distance(Vec2::new(2.3, 2.4)).unwrap();
        assert!((corner - 0.5).abs() < 1e-15);
        assert!(g.signed_distance(Vec2::new(1.9, 1.95)).unwrap() < 0.0);
        assert_eq!(g.signed_distance(Vec2::new(9.0, 9.0)), None);
        assert_eq!(g.self_crossing(), None);
    }

    /// A circle of radius 10 mm as 60 chords (each sagging 13.7 µm): the distance to the
    /// curve the chords stand for is the circle's own within 50 µm of it, outside and
    /// inside, to 2 % of the sag, where the plain distance to the chords is off by up to it;
    /// at the square's corners and along its straight sides nothing is taken off.
    #[test]
    fn the_distance_to_the_curve_takes_off_the_chords_sag() {
        let n = 60;
        let circle: Vec<Vec2> = (0..n)
            .map(|k| {
                let (s, c) = (std::f64::consts::TAU * k as f64 / n as f64).sin_cos();
                Vec2::new(10.0 * c, 10.0 * s)
            })
            .collect();
        let sag = 10.0 * (1.0 - (std::f64::consts::PI / n as f64).cos());
        let g = OutlineGrid::new(circle, 1.0, 0.014, &[]);
        let (mut worst, mut worst_plain) = (0.0f64, 0.0f64);
        for k in 0..600 {
            let (s, c) = (0.0173 + std::f64::consts::TAU * k as f64 / 600.0).sin_cos();
            // (Near the curve, as the mesh check's contacts are: off it by `d`, the
            // correction's own error grows as `d/R` of the sag.)
            for r in [9.95, 9.99, 10.01, 10.05] {
                let p = Vec2::new(r * c, r * s);
                let exact = r - 10.0;
                worst = worst.max((g.signed_distance_to_curve(p).unwrap() - exact).abs());
                worst_plain = worst_plain.max((g.signed_distance(p).unwrap() - exact).abs());
            }
        }
        assert!(worst_plain > 0.9 * sag, "{worst_plain} vs sag {sag}");
        assert!(worst < 0.02 * sag, "{worst} against a sag of {sag}");
        let square = OutlineGrid::new(square(), 0.6, 0.01, &[]);
        for p in [
            Vec2::new(1.0, 0.2),
            Vec2::new(2.3, 2.4),
            Vec2::new(1.3, -0.1),
        ] {
            assert_eq!(
                square.signed_distance_to_curve(p),
                square.signed_distance(p)
            );
        }
    }

    #[test]
    fn a_bow_tie_crosses_itself() {
        let bow = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(0.0, 2.0),
        ];
        let x = OutlineGrid::new(bow, 0.7, 0.0, &[])
            .self_crossing()
            .unwrap();
        assert!((x - Vec2::new(1.0, 1.0)).hypot() < 1e-12);
    }
    proptest! {
        /// On random star-shaped outlines (wavy, so with reflex corners) and random
        /// points, the grid's answer is the nearest of all segments, with the sign of the
        /// winding number: the grid loses no candidate.
        #[test]
        fn grid_distance_is_the_brute_force_distance(
            radii in proptest::collection::vec(5.0f64..9.0, 12..120),
            reach in 0.05f64..1.5,
            probes in proptest::collection::vec((-12.0f64..12.0, -12.0f64..12.0), 50),
        ) {
            let n = radii.len();
            let points: Vec<Vec2> = radii
                .iter()
                .enumerate()
                .map(|(k, r)| {
                    let (s, c) = (std::f64::consts::TAU * k as f64 / n as f64).sin_cos();
                    Vec2::new(r * c, r * s)
                })
                .collect();
            let grid = OutlineGrid::new(points.clone(), reach, 0.0, &[]);
            prop_assert_eq!(grid.self_crossing(), None);
            for (x, y) in probes {
                let p = Vec2::new(x, y);
                let nearest = (0..n)
                    .map(|i| segment_distance(p, points[i], points[(i + 1) % n]))
                    .fold(f64::INFINITY, f64::min);
                let winding: f64 = (0..n)
                    .map(|i| {
                        let (a, b) = (points[i] - p, points[(i + 1) % n] - p);
                        a.cross(b).atan2(a.dot(b))
                    })
                    .sum();
                let inside = winding.abs() > 1.0;
                match grid.signed_distance(p) {
                    None => prop_assert!(nearest >= reach, "{p:?}: {nearest} within {reach}"),
                    Some(d) => {
                        prop_assert!((d.abs() - nearest).abs() < 1e-12, "{p:?}: {d} vs {nearest}");
                        prop_assert!(nearest < reach);
                        if nearest > 1e-9 {
                            prop_assert_eq!(d < 0.0, inside, "{:?}: {}", p, d);
                        }
                    }
                }
            }
        }
    }
}
