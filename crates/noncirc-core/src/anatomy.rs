//! The trajectory's anatomy in the three-arm paper's terms (§4.2): each arm's static
//! trajectory in four sections, in the order of motion, with the measures the paper's
//! parameter analysis speaks of.
//!
//! - **Seedling removal** (the picking loop): the run around picking where the tip is
//!   within one tray depth of the tray surface, from one pot depth before entering the
//!   tray until the pulled pot has cleared it.
//! - **Conveying**: from the end of removal to the start of planting.
//! - **Planting**: the run around the lowest point where the tip is in the soil (below the
//!   ground line, `planting_depth_mm` above the lowest point).
//! - **Return**: from the end of planting back to the start of removal.
//!
//! Sections overlap only on degenerate designs (a removal zone that reaches the soil);
//! the later section is then cut where the earlier one ends.

use crate::agronomy::Agronomy;
use crate::curve::{parabola_vertex, TAU};
use crate::events::{span_where, Events};
use crate::measure::Section;
use crate::objectives::{advance_per_rad, travel_sign};
use crate::planetary::Kinematics;
use crate::vec2::Vec2;
use serde::Serialize;

/// One section's measures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SectionMeasures {
    pub section: Section,
    /// Carrier angles where arm I enters and leaves the section (deg; start in [0, 360),
    /// end ≥ start, possibly past 360).
    pub carrier_deg: [f64; 2],
    /// Carrier span (deg).
    pub span_deg: f64,
    /// Path length of the tip (mm).
    pub length_mm: f64,
    /// Lowest and highest tip heights in the section (mm).
    pub y_min_mm: f64,
    pub y_max_mm: f64,
    /// Least and largest tip x in the section (mm).
    pub x_min_mm: f64,
    pub x_max_mm: f64,
}

/// The trajectory's sections and the measures of paper §4.2 (mm, m/s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Anatomy {
    /// In the order of motion: removal, conveying, planting, return.
    pub sections: [SectionMeasures; 4],
    /// Horizontal and vertical extent of the seedling-removal section (the loop).
    pub loop_width_mm: f64,
    pub loop_height_mm: f64,
    /// Heights of the picking and planting points, and of the return section's highest
    /// point (the return point).
    pub picking_height_mm: f64,
    pub planting_height_mm: f64,
    pub return_height_mm: f64,
    /// Vertical distance from the planting point up to the picking point.
    pub picking_to_planting_height_mm: f64,
    /// Tip speed in the ground frame at planting, with the machine's advance (m/s).
    pub planting_ground_speed_m_s: f64,
    /// Mean tip speed relative to the (machine-fixed) seedling while the tip is inside the
    /// tray (m/s): its path from entering the tray to leaving it over the time it takes.
    /// Unlike the speed at the picking instant, which a cusp there can bring to zero, the
    /// path it averages goes in to the picking depth and out again. A tip that never
    /// enters the tray has no window: then it is the speed at the picking instant.
    pub in_tray_speed_m_s: f64,
}

impl Anatomy {
    /// One section's measures.
    pub fn section(&self, s: Section) -> &SectionMeasures {
        &self.sections[s as usize]
    }

    /// The section arm I is in at carrier angle `theta_deg`.
    pub fn section_at(&self, theta_deg: f64) -> Section {
        let start = self.sections[0].carrier_deg[0];
        let t = start + (theta_deg - start).rem_euclid(360.0);
        (self.sections.iter())
            .find(|s| t < s.carrier_deg[1] || s.section == Section::Return)
            .map_or(Section::Return, |s| s.section)
    }
}

/// Measures the sections of arm I's trajectory.
pub fn anatomy(kin: &Kinematics, agro: &Agronomy, ev: &Events) -> Anatomy {
    let n = kin.len();
    let h = TAU / n as f64;
    let tips = kin.tips();
    let node = |t: f64| ((t / h).round() as usize) % n;
    let normal = agro.tray_normal();
    let zone = ev.check.tray_surface_mm - agro.tray_depth_mm;
    let ground = ev.y_min_mm + agro.planting_depth_mm;
    let tp = ev.picking.carrier_rad;
    let tl = ev.planting.carrier_rad;
    // Each zone contains its own event's node (an extreme lies within it by construction);
    // a tray the tip does not reach leaves a removal section of the picking instant alone.
    let [r0, r1] = span_where(n, node(tp), |j| tips[j].dot(normal) - zone).unwrap_or([tp, tp]);
    let [p0, p1] = span_where(n, node(tl), |j| ground - tips[j].y).unwrap_or([tl, tl]);
    // Planting after removal, within one turn of its start.
    let turns = ((p0 - r0) / TAU).floor() * TAU;
    let (p0, p1) = (p0 - turns, p1 - turns);
    let end = r0 + TAU;
    let plant = [p0.max(r1).min(end), p1.max(r1).min(end)];
    // The sections' ends, each the start of the next; the arm's state once at each.
    let ends = [r0, r1, plant[0], plant[1], end];
    let at_ends = ends.map(|t| End::at(kin, t));
    let speeds = kin.node_tip_speeds();
    let sections = std::array::from_fn(|i| {
        measure_section(kin, &speeds, Section::ALL[i], [at_ends[i], at_ends[i + 1]])
    });
    let removal: &SectionMeasures = &sections[0];
    let [w0, w1] = ev.picking_window_rad;
    // A tray the tip does not reach has an empty window: the speed at picking itself. A
    // NaN window stays NaN.
    let in_tray = if w1 == w0 {
        kin.state_at(tp).tip_d1.hypot()
    } else {
        path_length(kin, &speeds, [End::at(kin, w0), End::at(kin, w1)]) / (w1 - w0)
    };
    let planted = kin.state_at(tl);
    let ground_velocity = Vec2::new(
        travel_sign(agro, ev) * planted.tip_d1.x + advance_per_rad(kin.arms(), agro),
        planted.tip_d1.y,
    );
    Anatomy {
        loop_width_mm: removal.x_max_mm - removal.x_min_mm,
        loop_height_mm: removal.y_max_mm - removal.y_min_mm,
        picking_height_mm: ev.picking.tip_mm.y,
        planting_height_mm: ev.planting.tip_mm.y,
        return_height_mm: sections[3].y_max_mm,
        picking_to_planting_height_mm: ev.picking.tip_mm.y - ev.planting.tip_mm.y,
        planting_ground_speed_m_s: ground_velocity.hypot() * kin.carrier_speed() / 1000.0,
        in_tray_speed_m_s: in_tray * kin.carrier_speed() / 1000.0,
        sections,
    }
}

/// One end of a stretch of the trajectory: its carrier angle (rad, unwrapped), the tip
/// there (mm) and the tip's speed (mm/rad).
#[derive(Clone, Copy)]
struct End {
    carrier_rad: f64,
    tip: Vec2,
    speed: f64,
}

impl End {
    fn at(kin: &Kinematics, carrier_rad: f64) -> Self {
        let state = kin.state_at(carrier_rad);
        Self {
            carrier_rad,
            tip: state.tip,
            speed: state.tip_d1.hypot(),
        }
    }
}

/// The tip's path length between two ends (mm): the trapezoid rule of the tip speed
/// `speeds` (mm/rad at the nodes) on the nodes inside plus the two partial cells.
fn path_length(kin: &Kinematics, speeds: &[f64], [e0, e1]: [End; 2]) -> f64 {
    let h = TAU / kin.len() as f64;
    let at = |k: i64| k.rem_euclid(kin.len() as i64) as usize;
    let (t0, t1) = (e0.carrier_rad, e1.carrier_rad);
    // Nodes strictly inside (t0, t1).
    let (first, last) = ((t0 / h).floor() as i64 + 1, (t1 / h).ceil() as i64 - 1);
    if first > last {
        return 0.5 * (e0.speed + e1.speed) * (t1 - t0);
    }
    let mut length = 0.5 * (e0.speed + speeds[at(first)]) * (first as f64 * h - t0)
        + 0.5 * (e1.speed + speeds[at(last)]) * (t1 - last as f64 * h);
    // Node indices wrap by a comparison, not a division per node.
    let n = speeds.len();
    let mut j = at(first);
    for _ in first..last {
        let next = if j + 1 == n { 0 } else { j + 1 };
        length += 0.5 * (speeds[j] + speeds[next]) * h;
        j = next;
    }
    length
}

/// The measures of one section between two ends: the path length ([`path_length`]), the
/// extremes of x and y at the nodes inside (refined by the parabola through the
/// neighbours) and at the ends.
fn measure_section(
    kin: &Kinematics,
    speeds: &[f64],
    section: Section,
    ends: [End; 2],
) -> SectionMeasures {
    let n = kin.len();
    let h = TAU / n as f64;
    let tips = kin.tips();
    let at = |k: i64| k.rem_euclid(n as i64) as usize;
    let [(t0, a), (t1, b)] = ends.map(|e| (e.carrier_rad, e.tip));
    // Nodes strictly inside (t0, t1).
    let (first, last) = ((t0 / h).floor() as i64 + 1, (t1 / h).ceil() as i64 - 1);
    let length = path_length(kin, speeds, ends);
    let mut extent = [a.x.min(b.x), a.x.max(b.x)];
    let mut heights = [a.y.min(b.y), a.y.max(b.y)];
    if first <= last {
        // Node indices wrap by a comparison, not a division per node.
        let (mut before, mut j) = (at(first - 1), at(first));
        for _ in first..=last {
            let after = if j + 1 == n { 0 } else { j + 1 };
            let (m, c, p) = (tips[before], tips[j], tips[after]);
            (before, j) = (j, after);
            for ([m, c, p], range) in [
                ([m.x, c.x, p.x], &mut extent),
                ([m.y, c.y, p.y], &mut heights),
            ] {
                // The parabola refines a node only where it is a local extreme.
                let low = if c <= m && c <= p {
                    parabola_vertex(m, c, p)
                } else {
                    c
                };
                let high = if c >= m && c >= p {
                    -parabola_vertex(-m, -c, -p)
                } else {
                    c
                };
                range[0] = range[0].min(low);
                range[1] = range[1].max(high);
            }
        }
    }
    let start = t0.to_degrees().rem_euclid(360.0);
    let span = (t1 - t0).to_degrees();
    SectionMeasures {
        section,
        carrier_deg: [start, start + span],
        span_deg: span,
        length_mm: length,
        y_min_mm: heights[0],
        y_max_mm: heights[1],
        x_min_mm: extent[0],
        x_max_mm: extent[1],
    }
}
