//! CAD output of closed outlines: lines and arcs fitted to a tolerance, written as DXF
//! (R12, millimetres, a layer table, closed polylines with bulges) and SVG.
//!
//! Written by hand: the DXF R12 subset a CAD program needs here (a header, a layer table,
//! POLYLINE with bulges, LINE, CIRCLE) is small and fixed, and the crates that write DXF
//! bring far more than that for it.

use noncirc_core::{segment_distance, Vec2};
use std::fmt::Write as _;

/// One piece of a fitted outline: from `start` to the next piece's start, straight
/// (`bulge` 0) or along an arc with `bulge = tan(included angle / 4)`, positive
/// counter-clockwise (DXF's convention).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub start: Vec2,
    pub bulge: f64,
}

/// The circle through three points, if they are not collinear.
fn circle(a: Vec2, b: Vec2, c: Vec2) -> Option<(Vec2, f64)> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.cross(ac);
    if d.abs() < 1e-300 {
        return None;
    }
    let (l1, l2) = (ab.hypot2(), ac.hypot2());
    let centre = a + Vec2::new(ac.y * l1 - ab.y * l2, ab.x * l2 - ac.x * l1) * (1.0 / d);
    Some((centre, (a - centre).hypot()))
}

/// The bulge of the arc from `points[0]` to `points[last]` through them all within `tol`
/// (mm), if there is one turning one way by less than half a turn.
fn arc_through(points: &[Vec2], tol: f64) -> Option<f64> {
    let (a, b) = (points[0], points[points.len() - 1]);
    let (c, r) = circle(a, points[points.len() / 2], b)?;
    let sense = (a - c).cross(points[1] - c).signum();
    let mut swept = 0.0;
    for w in points.windows(2) {
        let (u, v) = (w[0] - c, w[1] - c);
        let step = u.cross(v).atan2(u.dot(v));
        if step * sense <= 0.0 {
            return None;
        }
        swept += step;
    }
    if swept.abs() >= std::f64::consts::PI
        || points.iter().any(|p| ((*p - c).hypot() - r).abs() > tol)
    {
        return None;
    }
    Some((swept / 4.0).tan())
}

/// Fits lines and arcs to a closed outline through every point within `tol` (mm),
/// breaking at `corners` (indices where the outline turns sharply): greedily, the longest
/// line or arc from each piece's start. The pieces keep 1 % of `tol` in hand for the
/// files' rounding (nine decimals of a millimetre move an arc's ends and so its middle).
pub fn fit(points: &[Vec2], corners: &[usize], tol: f64) -> Vec<Piece> {
    let tol = 0.99 * tol;
    let n = points.len();
    let mut breaks: Vec<usize> = corners.iter().copied().filter(|&c| c < n).collect();
    if breaks.is_empty() {
        breaks.push(0);
    }
    breaks.sort_unstable();
    breaks.dedup();
    let mut pieces = Vec::new();
    for (k, &from) in breaks.iter().enumerate() {
        let to = if k + 1 < breaks.len() {
            breaks[k + 1]
        } else {
            breaks[0] + n
        };
        let run: Vec<Vec2> = (from..=to).map(|i| points[i % n]).collect();
        let mut i = 0;
        while i + 1 < run.len() {
            let line_fits = |j: usize| {
                run[i + 1..j]
                    .iter()
                    .all(|p| segment_distance(*p, run[i], run[j]) <= tol)
            };
            let mut best = (i + 1, 0.0);
            let mut j = i + 2;
            while j < run.len() && line_fits(j) {
                best = (j, 0.0);
                j += 1;
            }
            let mut j = best.0 + 1;
            while j < run.len() {
                match arc_through(&run[i..=j], tol) {
                    Some(bulge) => best = (j, bulge),
                    None if j > i + 3 => break,
                    None => {}
                }
                j += 1;
            }
            pieces.push(Piece {
                start: run[i],
                bulge: best.1,
            });
            i = best.0;
        }
    }
    pieces
}

/// A fitted outline placed in the drawing: its pieces, turned by `angle` (rad) about the
/// origin of its own frame and moved to `centre`.
pub struct Placed<'a> {
    pub layer: &'a str,
    pub pieces: &'a [Piece],
    pub centre: Vec2,
    pub angle: f64,
}

impl Placed<'_> {
    fn point(&self, p: Vec2) -> Vec2 {
        let (s, c) = self.angle.sin_cos();
        self.centre + p.rotated(Vec2::new(c, s))
    }
}

/// DXF R12 in millimetres: header (`$INSUNITS` = 4), a layer table, each outline a closed
/// POLYLINE with bulges, each centre a cross of two LINEs and a small CIRCLE (layer
/// `CENTRES`), and any closed polylines of points given (`extra`, e.g. pitch curves).
pub fn dxf(
    outlines: &[Placed],
    marks: &[Vec2],
    mark_size: f64,
    extra: &[(&str, Vec<Vec2>)],
) -> String {
    let mut layers: Vec<&str> = vec!["0"];
    if !marks.is_empty() {
        layers.push("CENTRES");
    }
    for l in outlines
        .iter()
        .map(|o| o.layer)
        .chain(extra.iter().map(|e| e.0))
    {
        if !layers.contains(&l) {
            layers.push(l);
        }
    }
    let mut s = String::new();
    s += "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n9\n$INSUNITS\n70\n4\n9\n$MEASUREMENT\n70\n1\n0\nENDSEC\n";
    let _ = write!(
        s,
        "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n{}\n",
        layers.len()
    );
    for (k, l) in layers.iter().enumerate() {
        let _ = write!(
            s,
            "0\nLAYER\n2\n{l}\n70\n0\n62\n{}\n6\nCONTINUOUS\n",
            1 + k % 7
        );
    }
    s += "0\nENDTAB\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
    for o in outlines {
        let _ = write!(
            s,
            "0\nPOLYLINE\n8\n{}\n66\n1\n70\n1\n10\n0.0\n20\n0.0\n30\n0.0\n",
            o.layer
        );
        for p in o.pieces {
            let q = o.point(p.start);
            let _ = write!(
                s,
                "0\nVERTEX\n8\n{}\n10\n{:.9}\n20\n{:.9}\n30\n0.0\n",
                o.layer, q.x, q.y
            );
            if p.bulge != 0.0 {
                let _ = write!(s, "42\n{:.12}\n", p.bulge);
            }
        }
        let _ = write!(s, "0\nSEQEND\n8\n{}\n", o.layer);
    }
    for c in marks {
        for (dx, dy) in [(mark_size, 0.0), (0.0, mark_size)] {
            let _ = write!(
                s,
                "0\nLINE\n8\nCENTRES\n10\n{:.9}\n20\n{:.9}\n30\n0.0\n11\n{:.9}\n21\n{:.9}\n31\n0.0\n",
                c.x - dx, c.y - dy, c.x + dx, c.y + dy
            );
        }
        let _ = write!(
            s,
            "0\nCIRCLE\n8\nCENTRES\n10\n{:.9}\n20\n{:.9}\n30\n0.0\n40\n{:.9}\n",
            c.x,
            c.y,
            0.5 * mark_size
        );
    }
    for (layer, points) in extra {
        let _ = write!(
            s,
            "0\nPOLYLINE\n8\n{layer}\n66\n1\n70\n1\n10\n0.0\n20\n0.0\n30\n0.0\n"
        );
        for p in points {
            let _ = write!(
                s,
                "0\nVERTEX\n8\n{layer}\n10\n{:.9}\n20\n{:.9}\n30\n0.0\n",
                p.x, p.y
            );
        }
        let _ = write!(s, "0\nSEQEND\n8\n{layer}\n");
    }
    s + "0\nENDSEC\n0\nEOF\n"
}

/// SVG in mm (y up as in the model), each outline a closed path of lines and arcs.
pub fn svg(outlines: &[Placed], marks: &[Vec2]) -> String {
    let all: Vec<Vec2> = outlines
        .iter()
        .flat_map(|o| o.pieces.iter().map(|p| o.point(p.start)))
        .collect();
    let (mut lo, mut hi) = (all[0], all[0]);
    for p in &all {
        lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let pad = 0.05 * (hi.x - lo.x).max(hi.y - lo.y);
    let (w, h) = (hi.x - lo.x + 2.0 * pad, hi.y - lo.y + 2.0 * pad);
    let tx = |p: Vec2| (p.x - lo.x + pad, hi.y + pad - p.y);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.3}mm\" height=\"{h:.3}mm\" viewBox=\"0 0 {w:.6} {h:.6}\">\n"
    );
    for o in outlines {
        let mut d = String::new();
        let n = o.pieces.len();
        for (k, p) in o.pieces.iter().enumerate() {
            let (a, b) = (o.point(p.start), o.point(o.pieces[(k + 1) % n].start));
            let (ax, ay) = tx(a);
            if k == 0 {
                let _ = write!(d, "M {ax:.6} {ay:.6} ");
            }
            let (bx, by) = tx(b);
            if p.bulge == 0.0 {
                let _ = write!(d, "L {bx:.6} {by:.6} ");
            } else {
                let chord = (b - a).hypot();
                let r = chord * (1.0 + p.bulge * p.bulge) / (4.0 * p.bulge.abs());
                // y flips in SVG: a counter-clockwise arc in the model sweeps clockwise.
                let sweep = u8::from(p.bulge < 0.0);
                let _ = write!(d, "A {r:.6} {r:.6} 0 0 {sweep} {bx:.6} {by:.6} ");
            }
        }
        let _ = writeln!(s, "  <path class=\"{}\" d=\"{d}Z\" fill=\"none\" stroke=\"black\" stroke-width=\"0.05\"/>", o.layer);
    }
    for c in marks {
        let (x, y) = tx(*c);
        let _ = writeln!(s, "  <circle cx=\"{x:.6}\" cy=\"{y:.6}\" r=\"0.5\" fill=\"none\" stroke=\"red\" stroke-width=\"0.05\"/>");
    }
    s + "</svg>\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sampled_circle_fits_as_a_few_arcs_within_the_tolerance() {
        let pts: Vec<Vec2> = (0..400)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 400.0;
                Vec2::new(10.0 * t.cos(), 10.0 * t.sin())
            })
            .collect();
        let pieces = fit(&pts, &[], 1e-3);
        assert!(pieces.len() <= 4, "{}", pieces.len());
        // Every bulge is counter-clockwise and they sum to one turn.
        let turn: f64 = pieces.iter().map(|p| 4.0 * p.bulge.atan()).sum();
        assert!((turn - std::f64::consts::TAU).abs() < 1e-9, "{turn}");
    }

    #[test]
    fn a_square_fits_as_four_lines() {
        let mut pts = Vec::new();
        for k in 0..4 {
            for i in 0..10 {
                let t = i as f64 / 10.0;
                let (a, b) = (
                    [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)][k],
                    [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)][k],
                );
                pts.push(Vec2::new(a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t));
            }
        }
        let pieces = fit(&pts, &[0, 10, 20, 30], 1e-9);
        assert_eq!(pieces.len(), 4);
        assert!(pieces.iter().all(|p| p.bulge == 0.0));
    }
}
