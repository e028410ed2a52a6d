//! The whole-cycle mesh check of a toothed pair: the two gears turned through a full turn
//! by the conjugate law, their least clearance, their backlash, and the contact ratio.
//!
//! Every mesh of the three-arm train is this pair at some rolling position: the sun and
//! the planets are congruent and carry their teeth at the same pitch arcs, the
//! intermediates are the conjugate, and two gears in mesh stand, relative to each other,
//! as the rolling position alone says. One turn of the pair therefore checks all six
//! meshes over a full carrier turn.

use super::cut_gear::{Side, ToothedGear};
use super::polyline::OutlineGrid;
use super::track::PairTrack;
use crate::angle::unit;
use crate::vec2::Vec2;
use serde::Serialize;

/// What the whole-cycle check found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeshReport {
    /// Rolling positions checked over one turn.
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

/// Turns the pair through one turn in `teeth · steps_per_pitch + 1` equal steps and
/// measures distances up to `reach` (mm). The one step more than a whole number per
/// pitch shifts each tooth's phases by `1/(teeth · steps_per_pitch)` pitch from its
/// neighbour's: each tooth is met `steps_per_pitch` times a pitch, and the teeth together
/// sample the mesh cycle at `teeth · steps_per_pitch` phases (for a circle pair, whose
/// teeth are alike, that is exactly the finer check).
pub(super) fn check(
    track: &PairTrack,
    gears: &[ToothedGear; 2],
    pitch: f64,
    reach: f64,
    sin_cos: (f64, f64),
    steps_per_pitch: usize,
) -> MeshReport {
    let teeth = gears[0].teeth.len();
    let a = track.centre_distance();
    let positions = teeth * steps_per_pitch + 1;
    let step = pitch * teeth as f64 / positions as f64;
    let mut least = (reach, 0.0);
    let mut backlash = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..positions {
        let s = step * k as f64;
        let psi = track.psi_at(s);
        let chi = track.driven_angle(psi);
        let (e1, e2) = (unit(psi), unit(psi + std::f64::consts::PI - chi));
        // Driven → driver frame: `q ↦ c + R(e2) q`; driver → driven: `p ↦ R(e2)⁻¹ (p − c)`,
        // each as a rotation and a shift.
        let centre2 = e1 * a;
        let e2_inv = Vec2::new(e2.x, -e2.y);
        let to_driver = (e2, centre2);
        let to_driven = (e2_inv, -centre2.rotated(e2_inv));
        // Per side: driver right flanks face driven left flanks (gap A), driver left
        // flanks face driven right flanks (gap B).
        let mut gap = [f64::INFINITY; 2];
        let mut visit = |g: usize, (turn, shift): (Vec2, Vec2), other: &OutlineGrid| {
            let gear = &gears[g];
            let phase = if g == 0 { 0.0 } else { 0.5 };
            let centre_tooth = (s / pitch - phase).round() as i64;
            for dj in -1..=1 {
                let j = (centre_tooth + dj).rem_euclid(teeth as i64) as usize;
                let (start, end) = gear.tooth_probes[j];
                for probe in &gear.probes[start..end] {
                    let Some(d) = other.signed_distance(probe.point.rotated(turn) + shift) else {
                        continue;
                    };
                    if d >= reach {
                        continue;
                    }
                    if d < least.0 {
                        least = (d, s);
                    }
                    if let Some(side) = probe.side {
                        let pair_side = match (g, side) {
                            (0, Side::Right) | (1, Side::Left) => 0,
                            _ => 1,
                        };
                        gap[pair_side] = gap[pair_side].min(d);
                    }
                }
            }
        };
        visit(1, to_driver, &gears[0].grid);
        visit(0, to_driven, &gears[1].grid);
        if gap.iter().all(|g| g.is_finite()) {
            let total = gap[0] + gap[1];
            backlash = (backlash.0.min(total), backlash.1.max(total));
        }
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
    MeshReport {
        positions,
        least_clearance_mm: least.0,
        least_clearance_at_mm: least.1,
        backlash_mm: backlash.0.is_finite().then_some(backlash),
        contact_ratio_min: ratio_min.0,
        contact_ratio_mean: ratio_sum / (2 * teeth) as f64,
        contact_ratio_min_at_mm: ratio_min.1,
    }
}
