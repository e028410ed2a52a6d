//! Plane polylines: segment intersection, signed distance to a closed outline through a
//! uniform grid of its segments, and the simplicity check of a closed outline.

use crate::vec2::Vec2;

/// Where segments `p0→p1` and `q0→q1` cross: the parameters `(t, u)` in `[0, 1]` of each.
pub fn segments_cross(p0: Vec2, p1: Vec2, q0: Vec2, q1: Vec2) -> Option<(f64, f64)> {
    let (d, e) = (p1 - p0, q1 - q0);
    let den = d.cross(e);
    if den == 0.0 {
        return None;
    }
    let w = q0 - p0;
    let (t, u) = (w.cross(e) / den, w.cross(d) / den);
    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then_some((t, u))
}

/// The first crossing of two open polylines, as fractional indices `(i + t, j + u)`.
pub fn first_crossing(a: &[Vec2], b: &[Vec2]) -> Option<(f64, f64)> {
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
    segment_nearest(p, a, b).0.sqrt()
}

/// Squared distance from `p` to segment `a→b` and the parameter of the nearest point.
#[inline]
fn segment_nearest(p: Vec2, a: Vec2, b: Vec2) -> (f64, f64) {
    let d = b - a;
    let len2 = d.hypot2();
    let t = if len2 > 0.0 {
        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((a + d * t - p).hypot2(), t)
}

/// A closed outline (counter-clockwise: material on the left of each segment) with its
/// segments binned on a uniform grid, for signed distances to nearby points.
#[derive(Debug, Clone)]
pub struct OutlineGrid {
    points: Vec<Vec2>,
    origin: Vec2,
    cell: f64,
    cols: usize,
    rows: usize,
    /// Segment indices per cell, row-major (`start..end` into `items`).
    spans: Vec<(u32, u32)>,
    items: Vec<u32>,
}

impl OutlineGrid {
    /// Bins the segments of `points` (closed, counter-clockwise) in cells of `cell` mm.
    pub fn new(points: Vec<Vec2>, cell: f64) -> Self {
        let (mut lo, mut hi) = (points[0], points[0]);
        for p in &points {
            lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        let origin = lo - Vec2::new(cell, cell);
        let cols = ((hi.x - origin.x) / cell).ceil() as usize + 2;
        let rows = ((hi.y - origin.y) / cell).ceil() as usize + 2;
        let n = points.len();
        let mut cells: Vec<Vec<u32>> = vec![Vec::new(); cols * rows];
        for i in 0..n {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let (c0, r0) = Self::cell_of(origin, cell, Vec2::new(a.x.min(b.x), a.y.min(b.y)));
            let (c1, r1) = Self::cell_of(origin, cell, Vec2::new(a.x.max(b.x), a.y.max(b.y)));
            for r in r0..=r1 {
                for c in c0..=c1 {
                    cells[r * cols + c].push(i as u32);
                }
            }
        }
        let mut spans = Vec::with_capacity(cells.len());
        let mut items = Vec::new();
        for list in cells {
            let start = items.len() as u32;
            items.extend(list);
            spans.push((start, items.len() as u32));
        }
        Self {
            points,
            origin,
            cell,
            cols,
            rows,
            spans,
            items,
        }
    }

    #[inline]
    fn cell_of(origin: Vec2, cell: f64, p: Vec2) -> (usize, usize) {
        (
            ((p.x - origin.x) / cell).max(0.0) as usize,
            ((p.y - origin.y) / cell).max(0.0) as usize,
        )
    }

    /// The outline's points.
    pub fn points(&self) -> &[Vec2] {
        &self.points
    }

    /// Signed distance (mm) from `p` to the outline, negative inside the material, if the
    /// outline passes within one cell width of `p` (exact then); `None` if it does not.
    pub fn signed_distance(&self, p: Vec2) -> Option<f64> {
        let c = (p.x - self.origin.x) / self.cell;
        let r = (p.y - self.origin.y) / self.cell;
        if c < 0.0 || r < 0.0 || c >= self.cols as f64 || r >= self.rows as f64 {
            return None;
        }
        let (c, r) = (c as usize, r as usize);
        let mut best = (f64::INFINITY, 0usize, 0.0);
        for rr in r.saturating_sub(1)..(r + 2).min(self.rows) {
            for cc in c.saturating_sub(1)..(c + 2).min(self.cols) {
                let (s, e) = self.spans[rr * self.cols + cc];
                for &i in &self.items[s as usize..e as usize] {
                    let i = i as usize;
                    let (a, b) = (self.points[i], self.points[(i + 1) % self.points.len()]);
                    let (d2, t) = segment_nearest(p, a, b);
                    if d2 < best.0 {
                        best = (d2, i, t);
                    }
                }
            }
        }
        if best.0 >= self.cell * self.cell {
            return None;
        }
        let (d2, i, t) = best;
        let n = self.points.len();
        let side = |k: usize| {
            let (a, b) = (self.points[k % n], self.points[(k + 1) % n]);
            (b - a).cross(p - a)
        };
        // Inside (left of a counter-clockwise outline) by the nearest segment, or at a
        // vertex by both of its segments: left of both at a convex corner, of either at a
        // reflex one.
        let inside = if t > 0.0 && t < 1.0 {
            side(i) > 0.0
        } else {
            let v = if t >= 1.0 { i + 1 } else { i + n };
            let (prev, next) = (v - 1, v);
            let (a, b, c) = (
                self.points[prev % n],
                self.points[v % n],
                self.points[(v + 1) % n],
            );
            let convex = (b - a).cross(c - b) >= 0.0;
            if convex {
                side(prev) > 0.0 && side(next) > 0.0
            } else {
                side(prev) > 0.0 || side(next) > 0.0
            }
        };
        let d = d2.sqrt();
        Some(if inside { -d } else { d })
    }

    /// Where the closed outline crosses itself (the first crossing found), if it does:
    /// non-adjacent segments that meet, found through the grid.
    pub fn self_crossing(&self) -> Option<Vec2> {
        let n = self.points.len();
        for (s, e) in &self.spans {
            let list = &self.items[*s as usize..*e as usize];
            for (k, &i) in list.iter().enumerate() {
                for &j in &list[k + 1..] {
                    let (i, j) = (i as usize, j as usize);
                    if (i + 1) % n == j || (j + 1) % n == i || i == j {
                        continue;
                    }
                    let (a0, a1) = (self.points[i], self.points[(i + 1) % n]);
                    let (b0, b1) = (self.points[j], self.points[(j + 1) % n]);
                    if let Some((t, _)) = segments_cross(a0, a1, b0, b1) {
                        return Some(a0 + (a1 - a0) * t);
                    }
                }
            }
        }
        None
    }
}

/// Signed area (mm²) of a closed polyline: positive when counter-clockwise.
pub fn signed_area(points: &[Vec2]) -> f64 {
    let n = points.len();
    0.5 * (0..n)
        .map(|i| points[i].cross(points[(i + 1) % n]))
        .sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let g = OutlineGrid::new(square(), 0.5);
        assert!((g.signed_distance(Vec2::new(1.0, 0.2)).unwrap() + 0.2).abs() < 1e-15);
        assert!((g.signed_distance(Vec2::new(1.0, -0.3)).unwrap() - 0.3).abs() < 1e-15);
        let corner = g.signed_distance(Vec2::new(2.3, 2.4)).unwrap();
        assert!((corner - 0.5).abs() < 1e-15);
        assert!(g.signed_distance(Vec2::new(1.9, 1.95)).unwrap() < 0.0);
        assert_eq!(g.signed_distance(Vec2::new(9.0, 9.0)), None);
        assert!((signed_area(&square()) - 4.0).abs() < 1e-15);
        assert_eq!(g.self_crossing(), None);
    }

    #[test]
    fn a_bow_tie_crosses_itself() {
        let bow = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(0.0, 2.0),
        ];
        let x = OutlineGrid::new(bow, 0.7).self_crossing().unwrap();
        assert!((x - Vec2::new(1.0, 1.0)).hypot() < 1e-12);
    }
}
