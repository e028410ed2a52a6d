//! CAD output of closed outlines: lines and arcs fitted to a tolerance, written as DXF
//! (R2000, millimetres, a layer table, closed LWPOLYLINEs with bulges) and SVG.
//!
//! Written by hand: the DXF R2000 subset a CAD program needs here (a header with the
//! unit, the required tables, blocks and root dictionary, LWPOLYLINE with bulges, LINE,
//! CIRCLE) is small and fixed, and the crates that write DXF bring far more than that.

use noncirc_core::{segment_distance, Vec2};
use std::fmt::Write as _;

use crate::Result;

/// The coarsest fit of the outlines the exports (DXF, STEP, STL) take (mm): beyond it the
/// lines and arcs would change the teeth by more than their checks' clearances.
pub const TOLERANCE_MAX_MM: f64 = 0.05;

/// The finest fit of the outlines the exports take (mm), a thousandth of a machine tool's
/// micrometre: the files grow as the tolerance's inverse square root (the gear pair of
/// `ellipse-gear`: 0.36 MB of DXF at 1e-4 mm, 3.8 MB at 1e-8), so a finer one only
/// multiplies them (1e-300 filled 1.9 GB in a minute).
pub const TOLERANCE_MIN_MM: f64 = 1e-6;

/// Checks a fit tolerance (mm) named `name`: from [`TOLERANCE_MIN_MM`] to
/// [`TOLERANCE_MAX_MM`].
pub fn check_tolerance(name: &str, tolerance_mm: f64) -> Result<()> {
    if (TOLERANCE_MIN_MM..=TOLERANCE_MAX_MM).contains(&tolerance_mm) {
        return Ok(());
    }
    Err(noncirc_core::Error::OutOfRange {
        name: name.into(),
        value: tolerance_mm,
        expected: format!(
            "from {TOLERANCE_MIN_MM:e} to {TOLERANCE_MAX_MM} mm (a coarser fit would change \
             the teeth; a finer one only makes the files larger)"
        ),
    }
    .into())
}

/// One piece of a fitted outline: from `start` to the next piece's start, straight
/// (`bulge` 0) or along an arc with `bulge = tan(included angle / 4)`, positive
/// counter-clockwise (DXF's convention).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub start: Vec2,
    pub bulge: f64,
}

/// The radius of the arc across a chord of `chord` (mm) with `bulge` (not 0): the half
/// chord over the sine of half the included angle, `chord·(1 + bulge²)/(4·|bulge|)`.
pub fn arc_radius(chord: f64, bulge: f64) -> f64 {
    chord * (1.0 + bulge * bulge) / (4.0 * bulge.abs())
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
    Some((centre, (a - centre).hypot2().sqrt()))
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
    // tan(θ/4) = sagitta / half chord, by arithmetic and a square root alone, which the
    // native and the WebAssembly builds round alike (their `tan` and `atan2` differ in the
    // last bit); the points it comes from still may, so the studio's files match the
    // CLI's to the last printed digit.
    let half = 0.5 * (b - a).hypot2().sqrt();
    let bulge = half / (r + ((r - half) * (r + half)).max(0.0).sqrt());
    Some(bulge.copysign(swept))
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

/// DXF R2000 (AC1015) in millimetres: R12 would be shorter but defines no `$INSUNITS`, so a
/// reader could not tell the unit. Each outline is one closed LWPOLYLINE with a bulge for
/// each arc; each centre (mm) a cross of two LINEs `mark_size` (mm) from it each way and a
/// CIRCLE of that diameter, on layer `CENTRES`; each of `extra` a closed LWPOLYLINE through
/// its points (mm, e.g. pitch curves) on its layer. Coordinates to 1e-9 mm.
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
    // The fixed records take handles 1 to 18 (`FRAME_*`); the layers and entities follow.
    let mut next = 0x20;
    let mut layer_table = format!(
        "0 TABLE\n2 LAYER\n5 9\n330 0\n100 AcDbSymbolTable\n70 {}\n",
        layers.len()
    );
    for (k, l) in layers.iter().enumerate() {
        let _ = write!(
            layer_table,
            "0 LAYER\n5 {next:X}\n330 9\n100 AcDbSymbolTableRecord\n100 AcDbLayerTableRecord\n\
             2 {l}\n70 0\n62 {}\n6 Continuous\n",
            1 + k % 7
        );
        next += 1;
    }
    let mut entities = String::new();
    for o in outlines {
        let vertices = o.pieces.iter().map(|p| (o.point(p.start), p.bulge));
        lwpolyline(&mut entities, &mut next, o.layer, vertices);
    }
    for c in marks {
        for (dx, dy) in [(mark_size, 0.0), (0.0, mark_size)] {
            entity(&mut entities, &mut next, "LINE", "CENTRES", "AcDbLine");
            let _ = write!(
                entities,
                "10 {:.9}\n20 {:.9}\n30 0.0\n11 {:.9}\n21 {:.9}\n31 0.0\n",
                c.x - dx,
                c.y - dy,
                c.x + dx,
                c.y + dy
            );
        }
        entity(&mut entities, &mut next, "CIRCLE", "CENTRES", "AcDbCircle");
        let _ = write!(
            entities,
            "10 {:.9}\n20 {:.9}\n30 0.0\n40 {:.9}\n",
            c.x,
            c.y,
            0.5 * mark_size
        );
    }
    for (layer, points) in extra {
        lwpolyline(
            &mut entities,
            &mut next,
            layer,
            points.iter().map(|&p| (p, 0.0)),
        );
    }
    let header = format!(
        "0 SECTION\n2 HEADER\n9 $ACADVER\n1 AC1015\n9 $HANDSEED\n5 {next:X}\n\
         9 $INSUNITS\n70 4\n9 $MEASUREMENT\n70 1\n0 ENDSEC\n"
    );
    tags(&[
        &header,
        FRAME_TABLES,
        &layer_table,
        FRAME_BLOCKS,
        &entities,
        FRAME_OBJECTS,
    ])
}

/// Starts an entity in model space: type, handle (`next`, then counted on), owner (the
/// `*Model_Space` block record), layer, subclass.
fn entity(s: &mut String, next: &mut u32, kind: &str, layer: &str, class: &str) {
    let _ = write!(
        s,
        "0 {kind}\n5 {next:X}\n330 13\n100 AcDbEntity\n8 {layer}\n100 {class}\n"
    );
    *next += 1;
}

/// A closed LWPOLYLINE through `vertices` (mm), each with the bulge of the piece it starts
/// (0: straight).
fn lwpolyline(
    s: &mut String,
    next: &mut u32,
    layer: &str,
    vertices: impl ExactSizeIterator<Item = (Vec2, f64)>,
) {
    entity(s, next, "LWPOLYLINE", layer, "AcDbPolyline");
    let _ = write!(s, "90 {}\n70 1\n", vertices.len());
    for (p, bulge) in vertices {
        let _ = write!(s, "10 {:.9}\n20 {:.9}\n", p.x, p.y);
        if bulge != 0.0 {
            let _ = writeln!(s, "42 {bulge:.12}");
        }
    }
}

/// DXF text from "code value" lines (leading spaces ignored): each a group code on one
/// line and its value on the next.
fn tags(parts: &[&str]) -> String {
    let mut s = String::new();
    for line in parts.iter().flat_map(|p| p.lines()) {
        let line = line.trim_start();
        let (code, value) = line.split_once(' ').unwrap_or((line, ""));
        let _ = write!(s, "{code}\n{value}\n");
    }
    s
}

// The fixed part of the file, one "code value" tag a line, handles in hex. Required for
// R2000 (ezdxf's "DXF internals": minimal DXF content): the CLASSES section (empty), the
// tables VPORT (*Active), LTYPE (ByBlock, ByLayer, Continuous), LAYER (0 and the
// drawing's), STYLE (Standard), VIEW, UCS, APPID (ACAD), DIMSTYLE (Standard) and
// BLOCK_RECORD (*Model_Space 13, *Paper_Space 14), their two blocks, and the root
// dictionary (1) with ACAD_GROUP (2). Each record names its owner (330); tables, 0.

/// CLASSES, then TABLES up to the LAYER table.
const FRAME_TABLES: &str = "\
0 SECTION
2 CLASSES
0 ENDSEC
0 SECTION
2 TABLES
0 TABLE
  2 VPORT
  5 3
  330 0
  100 AcDbSymbolTable
  70 1
  0 VPORT
    5 4
    330 3
    100 AcDbSymbolTableRecord
    100 AcDbViewportTableRecord
    2 *Active
    70 0
    10 0.0
    20 0.0
    11 1.0
    21 1.0
    12 0.0
    22 0.0
    16 0.0
    26 0.0
    36 1.0
    40 200.0
    41 1.5
0 ENDTAB
0 TABLE
  2 LTYPE
  5 5
  330 0
  100 AcDbSymbolTable
  70 3
  0 LTYPE
    5 6
    330 5
    100 AcDbSymbolTableRecord
    100 AcDbLinetypeTableRecord
    2 ByBlock
    70 0
    3
    72 65
    73 0
    40 0.0
  0 LTYPE
    5 7
    330 5
    100 AcDbSymbolTableRecord
    100 AcDbLinetypeTableRecord
    2 ByLayer
    70 0
    3
    72 65
    73 0
    40 0.0
  0 LTYPE
    5 8
    330 5
    100 AcDbSymbolTableRecord
    100 AcDbLinetypeTableRecord
    2 Continuous
    70 0
    3 Solid line
    72 65
    73 0
    40 0.0
0 ENDTAB
";

/// The end of the LAYER table, the other tables, BLOCKS, and the start of ENTITIES.
const FRAME_BLOCKS: &str = "\
0 ENDTAB
0 TABLE
  2 STYLE
  5 A
  330 0
  100 AcDbSymbolTable
  70 1
  0 STYLE
    5 B
    330 A
    100 AcDbSymbolTableRecord
    100 AcDbTextStyleTableRecord
    2 Standard
    70 0
    40 0.0
    41 1.0
    50 0.0
    71 0
    42 2.5
    3 txt
    4
0 ENDTAB
0 TABLE
  2 VIEW
  5 C
  330 0
  100 AcDbSymbolTable
  70 0
0 ENDTAB
0 TABLE
  2 UCS
  5 D
  330 0
  100 AcDbSymbolTable
  70 0
0 ENDTAB
0 TABLE
  2 APPID
  5 E
  330 0
  100 AcDbSymbolTable
  70 1
  0 APPID
    5 F
    330 E
    100 AcDbSymbolTableRecord
    100 AcDbRegAppTableRecord
    2 ACAD
    70 0
0 ENDTAB
0 TABLE
  2 DIMSTYLE
  5 10
  330 0
  100 AcDbSymbolTable
  70 1
  100 AcDbDimStyleTable
  0 DIMSTYLE
    105 11
    330 10
    100 AcDbSymbolTableRecord
    100 AcDbDimStyleTableRecord
    2 Standard
    70 0
0 ENDTAB
0 TABLE
  2 BLOCK_RECORD
  5 12
  330 0
  100 AcDbSymbolTable
  70 2
  0 BLOCK_RECORD
    5 13
    330 12
    100 AcDbSymbolTableRecord
    100 AcDbBlockTableRecord
    2 *Model_Space
  0 BLOCK_RECORD
    5 14
    330 12
    100 AcDbSymbolTableRecord
    100 AcDbBlockTableRecord
    2 *Paper_Space
0 ENDTAB
0 ENDSEC
0 SECTION
2 BLOCKS
0 BLOCK
  5 15
  330 13
  100 AcDbEntity
  8 0
  100 AcDbBlockBegin
  2 *Model_Space
  70 0
  10 0.0
  20 0.0
  30 0.0
  3 *Model_Space
  1
0 ENDBLK
  5 16
  330 13
  100 AcDbEntity
  8 0
  100 AcDbBlockEnd
0 BLOCK
  5 17
  330 14
  100 AcDbEntity
  8 0
  100 AcDbBlockBegin
  2 *Paper_Space
  70 0
  10 0.0
  20 0.0
  30 0.0
  3 *Paper_Space
  1
0 ENDBLK
  5 18
  330 14
  100 AcDbEntity
  8 0
  100 AcDbBlockEnd
0 ENDSEC
0 SECTION
2 ENTITIES
";

/// The end of ENTITIES and OBJECTS: the root dictionary and its empty ACAD_GROUP.
const FRAME_OBJECTS: &str = "\
0 ENDSEC
0 SECTION
2 OBJECTS
0 DICTIONARY
  5 1
  330 0
  100 AcDbDictionary
  281 1
  3 ACAD_GROUP
  350 2
0 DICTIONARY
  5 2
  330 1
  100 AcDbDictionary
  281 1
0 ENDSEC
0 EOF
";

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
                let r = arc_radius((b - a).hypot(), p.bulge);
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

    #[test]
    fn the_dxf_is_r2000_in_mm_with_its_handles_owners_and_closed_lwpolylines() {
        // A half disc (a line, then a half turn counter-clockwise: bulge 1), a centre mark
        // and a triangle of points.
        let pieces = [
            Piece {
                start: Vec2::new(-10.0, 0.0),
                bulge: 0.0,
            },
            Piece {
                start: Vec2::new(10.0, 0.0),
                bulge: 1.0,
            },
        ];
        let placed = [Placed {
            layer: "DRIVER",
            pieces: &pieces,
            centre: Vec2::ZERO,
            angle: 0.0,
        }];
        let triangle = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
        ];
        let text = dxf(&placed, &[Vec2::ZERO], 1.0, &[("PITCH", triangle)]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len() % 2, 0);
        let tags: Vec<(i32, &str)> = lines
            .chunks(2)
            .map(|t| (t[0].parse().unwrap(), t[1]))
            .collect();
        let header = |name: &str| tags[tags.iter().position(|&t| t == (9, name)).unwrap() + 1].1;
        assert_eq!(header("$ACADVER"), "AC1015");
        assert_eq!(header("$INSUNITS"), "4");
        assert_eq!(tags.last(), Some(&(0, "EOF")));
        // Handles (5, DIMSTYLE's 105) unique and below $HANDSEED; every owner (330) exists.
        let hex = |h: &str| u32::from_str_radix(h, 16).unwrap();
        let seed = hex(header("$HANDSEED"));
        let body = &tags[tags.iter().position(|&t| t == (0, "ENDSEC")).unwrap()..];
        let mut handles: Vec<u32> = body
            .iter()
            .filter(|t| t.0 == 5 || t.0 == 105)
            .map(|t| hex(t.1))
            .collect();
        assert!(handles.iter().all(|&h| 0 < h && h < seed));
        for t in body.iter().filter(|t| t.0 == 330) {
            assert!(t.1 == "0" || handles.contains(&hex(t.1)), "owner {}", t.1);
        }
        let n = handles.len();
        handles.sort_unstable();
        handles.dedup();
        assert_eq!(handles.len(), n);
        // The outline and the triangle: each a closed LWPOLYLINE of its vertices.
        let polylines: Vec<&[(i32, &str)]> = (0..body.len())
            .filter(|&i| body[i] == (0, "LWPOLYLINE"))
            .map(|i| &body[i..])
            .collect();
        assert_eq!(polylines.len(), 2);
        for (p, (layer, count)) in polylines.iter().zip([("DRIVER", "2"), ("PITCH", "3")]) {
            let value = |code: i32| p.iter().find(|t| t.0 == code).unwrap().1;
            assert_eq!([value(8), value(90), value(70)], [layer, count, "1"]);
        }
        assert!(tags.contains(&(42, "1.000000000000")));
    }
}
