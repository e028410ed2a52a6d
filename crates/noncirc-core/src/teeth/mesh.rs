//! The whole-cycle mesh check of a toothed pair: the two gears turned through a full turn
//! by the conjugate law, their least clearance, their backlash, and the contact ratio.
//!
//! Every mesh of the three-arm train is this pair at some rolling position: the sun and
//! the planets are congruent and carry their teeth at the same pitch arcs, the
//! intermediates are the conjugate, and two gears in mesh stand, relative to each other,
//! as the rolling position alone says. One turn of the pair therefore checks all six
//! meshes over a full carrier turn.

use super::cut_gear::{Side, ToothedGear};
use super::polyline::{chord_bow, menger_curvature, OutlineGrid};
use super::track::{Member, PairTrack};
use super::OVERLAP_TOLERANCE_MM;
use crate::angle::unit;
use crate::golden::golden_min;
use crate::vec2::Vec2;
use serde::Serialize;

/// What the whole-cycle check found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeshReport {
    /// Rolling positions checked over one turn: the even steps and those of the search for
    /// the deepest overlaps between them.
    pub positions: usize,
    /// Least signed distance between the tooth bodies over the turn (mm; negative: they
    /// overlap); the check's reach (0.05 m plus the backlash) if nothing comes closer.
    pub least_clearance_mm: f64,
    /// Pitch arc (mm) of the rolling position where it occurs.
    pub least_clearance_at_mm: f64,
    /// Least and largest normal backlash over the turn (mm): the gaps between the two
    /// sides' facing flanks, added; `None` if no position had both sides within the
    /// check's reach.
    pub backlash_mm: Option<(f64, f64)>,
    /// Least contact ratio over the teeth and both flank sides: pitches rolled while one
    /// tooth pair is in contact (≥ 1: the next pair takes over before this one lets go).
    pub contact_ratio_min: f64,
    /// Mean contact ratio over the teeth and both sides.
    pub contact_ratio_mean: f64,
    /// Pitch arc (mm) of the flank with the least contact ratio.
    pub contact_ratio_min_at_mm: f64,
}

/// Which side of the pair a flank faces across: driver right flanks face driven left
/// flanks (0), driver left flanks face driven right flanks (1).
fn pair_side(gear: usize, side: Side) -> usize {
    match (gear, side) {
        (0, Side::Right) | (1, Side::Left) => 0,
        _ => 1,
    }
}

/// The distance to the mate (by `distance`, mm) of the flank through `gear`'s probe `k`
/// (at distance `d`, the nearest on its flank) where it comes nearest between the probes
/// beside it, to a twentieth of `tolerance` (mm): successive parabolic
/// interpolation along the chords to the neighbours on the flank (or, with one neighbour,
/// from the midpoint of the chord to it), each point measured with its chord's sag taken
/// off ([`chord_bow`]; `turning` is 1 where the probes run counter-clockwise round
/// their gear, −1 where clockwise). Infinite where no neighbour is within reach.
fn bottom_beside(
    gear: &ToothedGear,
    turning: f64,
    (k, d): (usize, f64),
    tolerance: f64,
    distance: &impl Fn(Vec2) -> Option<f64>,
) -> f64 {
    let probes = &gear.probes;
    let side = probes[k].side;
    let p = probes[k].point;
    let neighbour = |n: usize| {
        let q = probes.get(n).filter(|q| q.side == side)?;
        Some((q.point, distance(q.point)?))
    };
    let (before, after) = (neighbour(k.wrapping_sub(1)), neighbour(k + 1));
    let kappa = match (before, after) {
        (Some((a, _)), Some((b, _))) => turning * menger_curvature(a, p, b),
        _ => 0.0,
    };
    // Positions `x` along the flank: `p` at 0, the chord to the point before it on the
    // negative side, to the point after it on the positive side.
    let chords = [before.map(|(a, _)| a), after.map(|(b, _)| b)];
    let length = chords.map(|q| q.map_or(0.0, |q| (q - p).hypot2().sqrt()));
    let at = |x: f64| -> Option<f64> {
        let (q, len) = if x < 0.0 {
            (chords[0]?, length[0])
        } else {
            (chords[1]?, length[1])
        };
        let f = x.abs() / len;
        let bow = chord_bow(kappa, kappa, q - p, gear.grid.chord_tolerance());
        Some(distance(p + (q - p) * f)? - bow * 4.0 * f * (1.0 - f))
    };
    let mut bracket = match (before, after) {
        (Some((_, da)), Some((_, db))) => [(-length[0], da), (0.0, d), (length[1], db)],
        (Some((_, da)), None) => {
            let x = -0.5 * length[0];
            let Some(dm) = at(x) else {
                return f64::INFINITY;
            };
            [(-length[0], da), (x, dm), (0.0, d)]
        }
        (None, Some((_, db))) => {
            let x = 0.5 * length[1];
            let Some(dm) = at(x) else {
                return f64::INFINITY;
            };
            [(0.0, d), (x, dm), (length[1], db)]
        }
        (None, None) => return f64::INFINITY,
    };
    for _ in 0..BOTTOM_STEPS {
        let [lo, mid, hi] = bracket;
        let Some((x, predicted)) = parabola_bottom(bracket) else {
            break;
        };
        let Some(e) = at(x) else { break };
        bracket = match (e < mid.1, x < mid.0) {
            (true, true) => [lo, (x, e), mid],
            (true, false) => [mid, (x, e), hi],
            (false, true) => [(x, e), mid, hi],
            (false, false) => [lo, mid, (x, e)],
        };
        if (e - predicted).abs() < BOTTOM_PRECISION * tolerance {
            break;
        }
    }
    bracket.iter().fold(f64::INFINITY, |m, &(_, y)| m.min(y))
}

/// Precision (in the check's tolerances) to which [`bottom_beside`] finds a bottom.
pub(super) const BOTTOM_PRECISION: f64 = 0.05;

/// Most parabolic steps in [`bottom_beside`].
const BOTTOM_STEPS: usize = 4;

/// Where the parabola through three points `(x, y)` (in growing `x`) is least, if it opens
/// upward, kept within their span, and its value there.
fn parabola_bottom([(x0, y0), (x1, y1), (x2, y2)]: [(f64, f64); 3]) -> Option<(f64, f64)> {
    let (u, v) = ((y1 - y0) / (x1 - x0), (y2 - y1) / (x2 - x1));
    let c = (v - u) / (x2 - x0);
    // y = y0 + u (x − x0) + c (x − x0)(x − x1), least where its slope vanishes.
    (c > 0.0).then(|| {
        let x = (0.5 * (x0 + x1) - 0.5 * u / c).clamp(x0, x2);
        (x, y0 + u * (x - x0) + c * (x - x0) * (x - x1))
    })
}

/// Local minima of the least clearance searched between the steps (the deepest first).
const REFINED_MINIMA: usize = 3;

/// Divisions of a mesh step near a risky arc (an undercut tooth or a concave arc).
const RISKY_DIVISIONS: usize = 4;

/// Reach (in pitches) of a risky arc over the mesh steps around it.
const RISKY_REACH_PITCHES: f64 = 1.5;

/// The pitch arcs (mm) of the teeth that are undercut and of the teeth and spaces where
/// either pitch curve is concave (none to look for where both are convex throughout).
fn risky_arcs(track: &PairTrack, gears: &[ToothedGear; 2], pitch: f64) -> Vec<f64> {
    let mut arcs: Vec<f64> = gears
        .iter()
        .flat_map(|g| g.teeth.iter())
        .filter(|t| t.undercut.iter().any(Option::is_some))
        .map(|t| t.centre_arc_mm)
        .collect();
    let convex = [Member::Driver, Member::Driven]
        .into_iter()
        .all(|member| track.least_curvature(member).0 >= 0.0);
    if convex {
        return arcs;
    }
    let teeth = gears[0].teeth.len();
    for k in 0..2 * teeth {
        let s = 0.5 * pitch * k as f64;
        let psi = track.psi_at(s);
        if [Member::Driver, Member::Driven]
            .into_iter()
            .any(|member| track.frame(member, psi).curvature < 0.0)
        {
            arcs.push(s);
        }
    }
    arcs
}

/// Width of the bracket, in steps, at which a search between steps stops (2e-4 of a pitch
/// at two steps a pitch).
const GOLDEN_WIDTH_STEPS: f64 = 4e-4;

/// Where `key` of `f` is least on `[lo, hi]` by golden section ([`golden_min`]): there,
/// `f` there (all of it, not only the key), and the calls of `f`.
fn golden_minimum<T>(
    f: impl Fn(f64) -> T,
    key: impl Fn(&T) -> f64,
    lo: f64,
    hi: f64,
) -> (f64, T, usize) {
    let mut calls = 0;
    let x = golden_min(
        |x| {
            calls += 1;
            key(&f(x))
        },
        lo,
        hi,
        GOLDEN_WIDTH_STEPS * 0.5 * (hi - lo),
    );
    (x, f(x), calls + 1)
}

/// The mesh check's findings: the report, and for each gear the rolling positions (mm of
/// pitch arc) where its mate's probes were inside its body by more than the verdict
/// tolerates.
pub(super) struct MeshCheck {
    pub(super) report: MeshReport,
    pub(super) overlaps: [Vec<f64>; 2],
}

/// Where the two gears stand relative to each other at one rolling position: each as a
/// rotation (a unit vector) and a shift that take its points into the other's frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct Placement {
    /// Driven → driver frame: `q ↦ R(e2) q + c`.
    pub(super) to_driver: (Vec2, Vec2),
    /// Driver → driven frame: `p ↦ R(e2)⁻¹ (p − c)`.
    pub(super) to_driven: (Vec2, Vec2),
}

impl Placement {
    /// The placement at rolling position `s` (mm of pitch arc).
    pub(super) fn at(track: &PairTrack, s: f64) -> Self {
        let psi = track.psi_at(s);
        let chi = track.driven_angle(psi);
        let (e1, e2) = (unit(psi), unit(psi + std::f64::consts::PI - chi));
        let centre2 = e1 * track.centre_distance();
        let e2_inv = Vec2::new(e2.x, -e2.y);
        Self {
            to_driver: (e2, centre2),
            to_driven: (e2_inv, -centre2.rotated(e2_inv)),
        }
    }

    /// The transform that takes gear `g`'s points (0 driver, 1 driven) into its mate's
    /// frame, as (rotation, shift).
    pub(super) fn into_mate_of(self, g: usize) -> (Vec2, Vec2) {
        if g == 0 {
            self.to_driven
        } else {
            self.to_driver
        }
    }
}

/// Turns the pair through one turn in `teeth · steps_per_pitch + 1` equal steps and
/// measures distances up to `reach` (mm). The one step more than a whole number per
/// pitch shifts each tooth's phases by `1/(teeth · steps_per_pitch)` pitch from its
/// neighbour's: each tooth is met `steps_per_pitch` times a pitch, and the teeth together
/// sample the mesh cycle at `teeth · steps_per_pitch` phases (for a circle pair, whose
/// teeth are alike, that is exactly the finer check). Where the bodies overlap by more
/// than `tolerance` (mm, the outlines' chord tolerance), the deepest overlaps are then
/// searched between the steps, and so are the backlash's extremes where its range is wider
/// than four tolerances.
pub(super) fn check(
    track: &PairTrack,
    gears: &[ToothedGear; 2],
    pitch: f64,
    reach: f64,
    sin_cos: (f64, f64),
    steps_per_pitch: usize,
    tolerance: f64,
) -> MeshCheck {
    let teeth = gears[0].teeth.len();
    // The least signed distance between the bodies at rolling position `s` (mm), the gap
    // on each side (driver right flanks face driven left flanks, and the other way), and
    // the least distance of each gear's body from its mate's probes (negative: the mate's
    // tips are inside it).
    let at = |s: f64| -> (f64, [f64; 2], [f64; 2]) {
        let Placement {
            to_driver,
            to_driven,
        } = Placement::at(track, s);
        let mut into = [reach; 2];
        let mut least = reach;
        let mut gap = [f64::INFINITY; 2];
        let mut visit = |g: usize, (turn, shift): (Vec2, Vec2), other: &OutlineGrid| {
            let gear = &gears[g];
            let phase = if g == 0 { 0.0 } else { 0.5 };
            let centre_tooth = (s / pitch - phase).round() as i64;
            // The probes run counter-clockwise round the driver, clockwise round the
            // driven gear.
            let turning = if g == 0 { 1.0 } else { -1.0 };
            let distance = |p: Vec2| {
                other
                    .signed_distance_to_curve(p.rotated(turn) + shift)
                    .filter(|&d| d < reach)
            };
            // The nearest flank probe on each side of the pair: (distance, probe index).
            let mut nearest = [(f64::INFINITY, 0); 2];
            for dj in -1..=1 {
                let j = (centre_tooth + dj).rem_euclid(teeth as i64) as usize;
                let (start, end) = gear.tooth_probes[j];
                for (k, probe) in gear.probes.iter().enumerate().take(end).skip(start) {
                    let Some(d) = distance(probe.point) else {
                        continue;
                    };
                    least = least.min(d);
                    into[1 - g] = into[1 - g].min(d);
                    if let Some(side) = probe.side {
                        let pair_side = pair_side(g, side);
                        if d < nearest[pair_side].0 {
                            nearest[pair_side] = (d, k);
                        }
                    }
                }
            }
            // Two flanks near contact part quadratically along the flank, so the nearest
            // probe can be farther than the bottom between probes: it is measured too.
            for (pair_side, &(d, k)) in nearest.iter().enumerate() {
                if !d.is_finite() {
                    continue;
                }
                let bottom = d.min(bottom_beside(gear, turning, (k, d), tolerance, &distance));
                least = least.min(bottom);
                into[1 - g] = into[1 - g].min(bottom);
                gap[pair_side] = gap[pair_side].min(bottom);
            }
        };
        visit(1, to_driver, &gears[0].grid);
        visit(0, to_driven, &gears[1].grid);
        (least, gap, into)
    };
    let risky = risky_arcs(track, gears, pitch);
    // Each tooth's tip probes (where there is a risky arc): its tip land and the flank ends
    // beside it (all of a pointed tooth's), the part of a tooth that can reach into its
    // mate's fillets and root.
    let tips: [Vec<(usize, usize)>; 2] = [0, 1].map(|g| {
        if risky.is_empty() {
            return Vec::new();
        }
        let gear = &gears[g];
        gear.tooth_probes
            .iter()
            .map(|&(start, end)| {
                let land = (start..end).filter(|&k| gear.probes[k].side.is_none());
                match (land.clone().min(), land.max()) {
                    (Some(first), Some(last)) => (first.max(start + 1) - 1, (last + 2).min(end)),
                    _ => (start, end),
                }
            })
            .collect()
    });
    // The least distance of each gear's body from its mate's tip probes at `s` (mm), and
    // the least of the two: the search between steps near risky arcs, at a fraction of
    // the cost of every probe.
    let tips_at = |s: f64| -> (f64, [f64; 2]) {
        let placement = Placement::at(track, s);
        let mut into = [reach; 2];
        for g in 0..2 {
            let (turn, shift) = placement.into_mate_of(g);
            let other = &gears[1 - g].grid;
            let phase = if g == 0 { 0.0 } else { 0.5 };
            let centre_tooth = (s / pitch - phase).round() as i64;
            for dj in -1..=1 {
                let j = (centre_tooth + dj).rem_euclid(teeth as i64) as usize;
                let (start, end) = tips[g][j];
                for probe in &gears[g].probes[start..end] {
                    let point = probe.point.rotated(turn) + shift;
                    if let Some(d) = other.signed_distance_to_curve(point) {
                        into[1 - g] = into[1 - g].min(d);
                    }
                }
            }
        }
        (into[0].min(into[1]), into)
    };
    let positions = teeth * steps_per_pitch + 1;
    let step = pitch * teeth as f64 / positions as f64;
    // The normal backlash at a position: the two sides' gaps added (NaN where a side is
    // out of reach).
    let total = |gap: [f64; 2]| {
        if gap.iter().all(|g| g.is_finite()) {
            gap[0] + gap[1]
        } else {
            f64::NAN
        }
    };
    let (mut lows, mut totals) = (Vec::with_capacity(positions), Vec::with_capacity(positions));
    // Where each gear's body holds its mate's probes deeper than the verdict tolerates.
    let mut overlaps: [Vec<f64>; 2] = Default::default();
    let mut note = |s: f64, into: [f64; 2]| {
        for (g, depth) in into.into_iter().enumerate() {
            if depth < -OVERLAP_TOLERANCE_MM {
                overlaps[g].push(s);
            }
        }
    };
    for k in 0..positions {
        let s = step * k as f64;
        let (low, gap, into) = at(s);
        lows.push(low);
        totals.push(total(gap));
        note(s, into);
    }
    // Where a tip can reach into a fillet beside an undercut or into a root by a concave
    // arc, an overlap may last less than a step and hide behind the flanks' contact
    // (which holds the least distance at zero): there the steps are divided further.
    let perimeter = pitch * teeth as f64;
    let mut evaluated = positions;
    let fine_step = step / RISKY_DIVISIONS as f64;
    let mut fine_least = (f64::INFINITY, 0.0);
    for k in 0..positions {
        let s = step * (k as f64 + 0.5);
        let near = risky.iter().any(|&c| {
            let d = (c - s).rem_euclid(perimeter);
            d.min(perimeter - d) <= RISKY_REACH_PITCHES * pitch
        });
        if !near {
            continue;
        }
        for i in 1..RISKY_DIVISIONS {
            let x = step * k as f64 + fine_step * i as f64;
            let (low, into) = tips_at(x);
            note(x, into);
            evaluated += 1;
            if low < fine_least.0 {
                fine_least = (low, x);
            }
        }
    }
    let extreme = |values: &[f64], sign: f64| {
        (0..positions)
            .filter(|&k| !values[k].is_nan())
            .min_by(|&i, &j| (sign * values[i]).total_cmp(&(sign * values[j])))
    };
    let k_least = extreme(&lows, 1.0).unwrap_or(0);
    let mut least = (lows[k_least], step * k_least as f64);
    // An overlap is deepest between positions: the deepest few local minima are searched
    // for their bottom (golden section over the steps either side), so its depth does not
    // depend on where the steps fall.
    let mut minima: Vec<usize> = (0..positions)
        .filter(|&k| {
            let (before, after) = ((k + positions - 1) % positions, (k + 1) % positions);
            lows[k] < -tolerance && lows[k] <= lows[before] && lows[k] <= lows[after]
        })
        .collect();
    minima.sort_by(|&i, &j| lows[i].total_cmp(&lows[j]));
    for &k in minima.iter().take(REFINED_MINIMA) {
        let s = step * k as f64;
        let (bottom, (value, _, into), calls) = golden_minimum(at, |r| r.0, s - step, s + step);
        evaluated += calls;
        note(bottom, into);
        if value < least.0 {
            least = (value, bottom.rem_euclid(pitch * teeth as f64));
        }
    }
    // The deepest overlap found between the steps, searched for its bottom likewise.
    if fine_least.0 < least.0.min(-tolerance) {
        let s = fine_least.1;
        let (bottom, (value, _, into), calls) =
            golden_minimum(at, |r| r.0, s - fine_step, s + fine_step);
        evaluated += calls;
        note(bottom, into);
        least = if value <= fine_least.0 {
            (value, bottom.rem_euclid(pitch * teeth as f64))
        } else {
            fine_least
        };
    }
    // The backlash's least and largest, searched between the steps around the step of
    // each (golden section over the steps either side) where its range is wider than the
    // measurement's own error (four chord tolerances).
    let mut backlash = match (extreme(&totals, 1.0), extreme(&totals, -1.0)) {
        (Some(lo), Some(hi)) => Some((totals[lo], totals[hi], lo, hi)),
        _ => None,
    };
    if let Some((lo, hi, k_lo, k_hi)) = backlash.filter(|b| b.1 - b.0 > 4.0 * tolerance) {
        let search = |k: usize, sign: f64| {
            let s = step * k as f64;
            let f = |x: f64| {
                let t = sign * total(at(x).1);
                if t.is_nan() {
                    f64::INFINITY
                } else {
                    t
                }
            };
            let (_, value, calls) = golden_minimum(f, |&t| t, s - step, s + step);
            (sign * value, calls)
        };
        let (low, calls_lo) = search(k_lo, 1.0);
        let (high, calls_hi) = search(k_hi, -1.0);
        evaluated += calls_lo + calls_hi;
        backlash = Some((lo.min(low), hi.max(high), k_lo, k_hi));
    }
    // Contact ratio per tooth pair and side, from the active flank heights.
    let (sin, cos) = sin_cos;
    let mut ratio_min = (f64::INFINITY, 0.0);
    let mut ratio_sum = 0.0;
    for j in 0..teeth {
        let driver = &gears[0].teeth[j];
        let pairs = [
            (driver.active[1], gears[1].teeth[j].active[0]),
            (
                driver.active[0],
                gears[1].teeth[(j + teeth - 1) % teeth].active[1],
            ),
        ];
        for (side, ((v_start, v_tip), (w_start, w_tip))) in pairs.into_iter().enumerate() {
            let lo = v_start.max(-w_tip);
            let hi = v_tip.min(-w_start);
            let ratio = ((hi - lo) / (sin * cos * pitch)).max(0.0);
            ratio_sum += ratio;
            if ratio < ratio_min.0 {
                let arc = driver.centre_arc_mm + if side == 0 { 0.5 } else { -0.5 } * pitch;
                ratio_min = (ratio, arc);
            }
        }
    }
    let report = MeshReport {
        positions: evaluated,
        least_clearance_mm: least.0,
        least_clearance_at_mm: least.1,
        backlash_mm: backlash.map(|(lo, hi, _, _)| (lo, hi)),
        contact_ratio_min: ratio_min.0,
        contact_ratio_mean: ratio_sum / (2 * teeth) as f64,
        contact_ratio_min_at_mm: ratio_min.1,
    };
    MeshCheck { report, overlaps }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parabola through three points of `y = 2 (x − 0.3)² + 1` is that parabola: its
    /// bottom is found exactly, and kept within the points' span when it lies outside.
    #[test]
    fn the_parabolas_bottom_is_exact_and_kept_within_the_span() {
        let y = |x: f64| 2.0 * (x - 0.3) * (x - 0.3) + 1.0;
        let (x, bottom) = parabola_bottom([(-0.5, y(-0.5)), (0.1, y(0.1)), (0.8, y(0.8))]).unwrap();
        assert!((x - 0.3).abs() < 1e-14 && (bottom - 1.0).abs() < 1e-14);
        let (x, _) = parabola_bottom([(0.5, y(0.5)), (0.6, y(0.6)), (0.9, y(0.9))]).unwrap();
        assert_eq!(x, 0.5);
        assert_eq!(parabola_bottom([(0.0, 1.0), (1.0, 2.0), (2.0, 1.0)]), None);
    }
}
