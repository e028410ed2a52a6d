//! Closed plane profiles of lines and arcs, with holes: what each part is extruded from.

use crate::cad::{arc_radius, Piece};
use noncirc_core::Vec2;
use std::f64::consts::PI;

/// A region of the plane (mm): its outline counter-clockwise and its holes clockwise, each
/// a closed run of [`Piece`]s (a piece runs from its start to the next piece's start).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    pub outer: Vec<Piece>,
    pub holes: Vec<Vec<Piece>>,
}

/// Where piece `i` of `loop_` starts and ends.
pub fn ends(loop_: &[Piece], i: usize) -> (Vec2, Vec2) {
    (loop_[i].start, loop_[(i + 1) % loop_.len()].start)
}

/// Points along piece `i` of `loop_` from its start (included) to its end (excluded), an
/// arc divided so that no chord is farther than `tol` (mm) from it.
pub fn points_along(loop_: &[Piece], i: usize, tol: f64, out: &mut Vec<Vec2>) {
    let (a, b) = ends(loop_, i);
    out.push(a);
    let bulge = loop_[i].bulge;
    if bulge == 0.0 {
        return;
    }
    let swept = 4.0 * bulge.atan();
    let r = arc_radius((b - a).hypot2().sqrt(), bulge);
    // A chord of angle φ lies r(1 − cos(φ/2)) from its arc.
    let step = 2.0 * (1.0 - (tol / r).min(1.0)).acos();
    let n = (swept.abs() / step.max(1e-9)).ceil().max(1.0) as usize;
    let centre = arc_centre(a, b, bulge);
    let (u, v) = (a - centre, (a - centre).turn_90());
    for k in 1..n {
        let phi = swept * k as f64 / n as f64;
        out.push(centre + u * phi.cos() + v * phi.sin());
    }
}

/// The centre of the arc from `a` to `b` with `bulge`.
pub fn arc_centre(a: Vec2, b: Vec2, bulge: f64) -> Vec2 {
    let d = b - a;
    // The centre lies on the chord's bisector, (1 − bulge²)/(4·bulge) chords to its left.
    (a + b) * 0.5 + d.turn_90() * ((1.0 - bulge * bulge) / (4.0 * bulge))
}

/// The area a closed run of pieces encloses (mm², positive counter-clockwise): the
/// polygon of the starts and each arc's circular segment, exactly.
pub fn area(loop_: &[Piece]) -> f64 {
    (0..loop_.len())
        .map(|i| {
            let (a, b) = ends(loop_, i);
            let bulge = loop_[i].bulge;
            let mut s = 0.5 * a.cross(b);
            if bulge != 0.0 {
                let swept = 4.0 * bulge.atan();
                let r = arc_radius((b - a).hypot2().sqrt(), bulge);
                s += 0.5 * r * r * (swept - swept.sin());
            }
            s
        })
        .sum()
}

impl Profile {
    /// The area of the region (mm²): the outline's less the holes'.
    pub fn area(&self) -> f64 {
        area(&self.outer) + self.holes.iter().map(|h| area(h)).sum::<f64>()
    }

    /// The same region turned by `angle` (rad) about the origin and moved by `by` (mm).
    pub fn placed(&self, angle: f64, by: Vec2) -> Profile {
        let (s, c) = angle.sin_cos();
        let move_ = |l: &Vec<Piece>| {
            l.iter()
                .map(|p| Piece {
                    start: by + p.start.rotated(Vec2::new(c, s)),
                    bulge: p.bulge,
                })
                .collect()
        };
        Profile {
            outer: move_(&self.outer),
            holes: self.holes.iter().map(move_).collect(),
        }
    }
}

/// The same closed run traversed the other way.
pub fn reversed(loop_: &[Piece]) -> Vec<Piece> {
    let n = loop_.len();
    (0..n)
        .rev()
        .map(|i| Piece {
            start: loop_[(i + 1) % n].start,
            bulge: -loop_[i].bulge,
        })
        .collect()
}

/// `loop_` counter-clockwise (`ccw`) or clockwise.
pub fn oriented(loop_: Vec<Piece>, ccw: bool) -> Vec<Piece> {
    if (area(&loop_) > 0.0) == ccw {
        loop_
    } else {
        reversed(&loop_)
    }
}

/// A circle of radius `r` about `centre`, as two half arcs, counter-clockwise.
pub fn circle(centre: Vec2, r: f64) -> Vec<Piece> {
    vec![
        Piece {
            start: centre + Vec2::new(r, 0.0),
            bulge: 1.0,
        },
        Piece {
            start: centre + Vec2::new(-r, 0.0),
            bulge: 1.0,
        },
    ]
}

/// A bore of radius `r` about the origin with a keyway of width `key_width` whose flat
/// lies `top` from the centre along +x (`key_width` 0: a plain bore), counter-clockwise.
pub fn keyed_bore(r: f64, key_width: f64, top: f64) -> Vec<Piece> {
    if key_width <= 0.0 {
        return circle(Vec2::ZERO, r);
    }
    let h = 0.5 * key_width;
    let x = (r * r - h * h).sqrt();
    // The bore's arc from the keyway's upper side round to its lower side.
    let swept = 2.0 * PI - 2.0 * h.atan2(x);
    vec![
        Piece {
            start: Vec2::new(x, h),
            bulge: (0.25 * swept).tan(),
        },
        Piece {
            start: Vec2::new(x, -h),
            bulge: 0.0,
        },
        Piece {
            start: Vec2::new(top, -h),
            bulge: 0.0,
        },
        Piece {
            start: Vec2::new(top, h),
            bulge: 0.0,
        },
    ]
}

/// The outline of the region within `r` of the segment from `a` to `b` (a slot, or a
/// disc where they meet), counter-clockwise.
pub fn stadium(a: Vec2, b: Vec2, r: f64) -> Vec<Piece> {
    hull_of_circles(&[a, b], r)
}

/// The convex hull of equal circles of radius `r` about `centres`: the hull of the centres
/// pushed out by `r`, its corners rounded by arcs about them; counter-clockwise.
pub fn hull_of_circles(centres: &[Vec2], r: f64) -> Vec<Piece> {
    let hull = convex_hull(centres);
    if hull.len() < 2 {
        return circle(hull.first().copied().unwrap_or(Vec2::ZERO), r);
    }
    let n = hull.len();
    let edge = |i: usize| hull[(i + 1) % n] - hull[i];
    let outward = |e: Vec2| Vec2::new(e.y, -e.x) * (r / e.hypot2().sqrt());
    let mut pieces = Vec::with_capacity(2 * n);
    for (i, &corner) in hull.iter().enumerate() {
        let (before, after) = (edge((i + n - 1) % n), edge(i));
        // The corner's arc from the previous edge's offset to the next's, then the edge.
        // In [0, π] on a convex hull (two centres: a half turn at each; `abs` keeps a
        // cross product of −0 from making it −π).
        let turn = before.cross(after).atan2(before.dot(after)).abs();
        pieces.push(Piece {
            start: corner + outward(before),
            bulge: (0.25 * turn).tan(),
        });
        pieces.push(Piece {
            start: corner + outward(after),
            bulge: 0.0,
        });
    }
    pieces
}

/// The convex hull of `points`, counter-clockwise, without collinear points (Andrew's
/// monotone chain).
pub fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut p: Vec<Vec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<Vec2> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let run: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in run {
            while hull.len() >= start + 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                if (b - a).cross(q - a) > 0.0 {
                    break;
                }
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn areas_are_exact() {
        // A circle, a stadium (a rectangle and a disc), a keyed bore (the disc less the
        // segment the keyway's flat sides cut, plus the keyway's rectangle).
        assert!(close(
            area(&circle(Vec2::new(3.0, -1.0), 2.0)),
            4.0 * PI,
            1e-14
        ));
        for (a, b) in [
            ((1.0, 2.0), (31.0, 42.0)),
            ((0.0, 0.0), (50.0, 0.0)),
            ((0.0, 0.0), (0.0, -50.0)),
        ] {
            let st = stadium(Vec2::new(a.0, a.1), Vec2::new(b.0, b.1), 5.0);
            assert!(
                close(area(&st), 50.0 * 10.0 + 25.0 * PI, 1e-13),
                "{a:?} {b:?}"
            );
        }
        let (r, w, top) = (6.0, 4.0, 7.8);
        let h: f64 = 2.0;
        let x = (r * r - h * h).sqrt();
        let half = h.atan2(x);
        let segment = r * r * (half - half.sin() * half.cos());
        let want = PI * r * r - segment + (top - x) * w;
        assert!(close(area(&keyed_bore(r, w, top)), want, 1e-13));
    }

    #[test]
    fn hull_of_circles_contains_every_circle_and_touches_the_outermost() {
        let centres = [
            Vec2::new(0.0, 0.0),
            Vec2::new(40.0, 5.0),
            Vec2::new(-20.0, 30.0),
            Vec2::new(5.0, 10.0),
            Vec2::new(10.0, -35.0),
        ];
        let r = 7.0;
        let loop_ = hull_of_circles(&centres, r);
        assert!(area(&loop_) > 0.0);
        let mut pts = Vec::new();
        for i in 0..loop_.len() {
            points_along(&loop_, i, 1e-6, &mut pts);
        }
        // Every boundary point is r from the nearest centre, and none is closer.
        for p in &pts {
            let d = (centres.iter().map(|c| (*p - *c).hypot2().sqrt())).fold(f64::MAX, f64::min);
            assert!((d - r).abs() < 1e-9, "{d}");
        }
        // The turns sum to one turn.
        let turn: f64 = loop_.iter().map(|p| 4.0 * p.bulge.atan()).sum();
        assert!(close(turn, 2.0 * PI, 1e-12));
    }

    #[test]
    fn reversing_negates_the_area_and_twice_is_the_identity() {
        let k = keyed_bore(6.0, 4.0, 7.8);
        assert!(close(area(&reversed(&k)), -area(&k), 1e-14));
        assert_eq!(reversed(&reversed(&k)), k);
    }

    #[test]
    fn arc_points_lie_on_the_arc_within_the_tolerance() {
        let k = keyed_bore(6.0, 4.0, 7.8);
        let mut pts = Vec::new();
        points_along(&k, 0, 1e-4, &mut pts);
        assert!(pts.len() > 20);
        for w in pts.windows(2) {
            let mid = (w[0] + w[1]) * 0.5;
            let sag = 6.0 - mid.hypot2().sqrt();
            assert!((0.0..=1e-4).contains(&sag), "{sag}");
            assert!((w[0].hypot2().sqrt() - 6.0).abs() < 1e-12);
        }
    }
}
