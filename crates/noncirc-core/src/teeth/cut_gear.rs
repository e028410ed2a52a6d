//! A gear as cut: its closed outline, the corners between its smooth pieces, each tooth
//! (tip land, pointed or not, undercut of each flank) and the points the mesh check probes.

use super::polyline::OutlineGrid;
use crate::vec2::Vec2;
use serde::Serialize;

/// Which flank of a tooth, seen from outside with the pitch arc growing to the right.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    Left,
    Right,
}

impl Side {
    pub(super) fn sign(self) -> f64 {
        match self {
            Side::Left => -1.0,
            Side::Right => 1.0,
        }
    }
}

/// The fillet cutting across a flank: where, and how much of the flank it takes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Undercut {
    pub side: Side,
    /// Pitch arc (mm) of the flank's crossing of the pitch curve.
    pub pitch_arc_mm: f64,
    /// Height (mm above the pitch curve, negative below) where the flank now starts.
    pub flank_starts_at_mm: f64,
    /// Flank height lost to the fillet (mm): where the flank starts less where it would
    /// start without undercut (the tool's form height).
    pub lost_height_mm: f64,
}

/// One tooth as cut.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Tooth {
    /// Pitch arc of the tooth's centre (mm from `ψ = 0`).
    pub centre_arc_mm: f64,
    /// Width of the tip land (mm, chord); 0 for a pointed tooth.
    pub tip_land_mm: f64,
    /// Whether the flanks meet below the tip: the tooth ends in a point.
    pub pointed: bool,
    /// Undercut of the left and of the right flank, if any.
    pub undercut: [Option<Undercut>; 2],
    /// Active flank of the left and the right side as tool heights `(start, tip)` (mm
    /// from the pitch curve): the span the mesh can use.
    #[serde(skip)]
    pub active: [(f64, f64); 2],
}

/// A toothed gear in its own frame: one closed counter-clockwise outline (mm), the corners
/// between its smooth pieces, and its teeth.
#[derive(Debug, Clone)]
pub struct ToothedGear {
    /// Indices of outline points where two pieces meet at an angle (tip corners, undercut
    /// and root crossings, pointed tips).
    pub corners: Vec<usize>,
    /// Flank side of each outline point (`Some` on a flank), and its tooth.
    pub flank_of: Vec<Option<(usize, Side)>>,
    /// The points the mesh check probes, tooth by tooth: the tip and the flank from the
    /// pitch curve up (every contact is at or above the pitch curve of one of the two
    /// gears); the mate's probes meet the rest. In the order of growing pitch arc:
    /// counter-clockwise round the driver, clockwise round the driven gear.
    pub(super) probes: Vec<Probe>,
    /// Each tooth's probes: the range of `probes` (start, end).
    pub(super) tooth_probes: Vec<(usize, usize)>,
    pub teeth: Vec<Tooth>,
    /// The outline, its segments binned for the mesh check's distance queries.
    pub(super) grid: OutlineGrid,
}

/// A point the mesh check probes (mm, in its gear's frame) and, on a flank, its side.
#[derive(Debug, Clone, Copy)]
pub(super) struct Probe {
    pub(super) point: Vec2,
    pub(super) side: Option<Side>,
}

impl ToothedGear {
    /// The closed counter-clockwise outline (mm), in the gear's own frame.
    pub fn outline(&self) -> &[Vec2] {
        self.grid.points()
    }
}
