//! The dimensions of the solid models that the pitch curves and the train do not give
//! (`[cad]` in a scene): each gear's bore, keyway and phase mark, the carrier's side plates,
//! and the arm and pusher bodies. The gears' thickness is the face width
//! (`dynamics.face_width_mm`), shared with the dynamics. docs/cad.md shows each on a figure.

use serde::{Deserialize, Serialize};

/// The solids' dimensions (mm).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CadSpec {
    /// Bore diameter `db` of every gear, the carrier's axle holes and the arms' hubs (mm).
    pub bore_diameter_mm: f64,
    /// Width `bk` of the keyway in each gear's bore (mm); 0: a plain bore.
    pub key_width_mm: f64,
    /// Depth `t2` of the keyway into the hub beyond the bore (mm; DIN 6885-1's hub depth).
    pub key_depth_mm: f64,
    /// Diameter of the phase mark, a hole through each gear on its own frame's +x axis,
    /// halfway between the keyway and the root (mm); 0: none.
    pub mark_diameter_mm: f64,
    /// Thickness `tp` of each of the carrier's two side plates (mm).
    pub plate_thickness_mm: f64,
    /// Axial gap between a gear layer and the next plate or layer (mm).
    pub axial_gap_mm: f64,
    /// Material of the side plates beyond the largest gear's tip circle around every axle
    /// (mm): the plates' outline is the hull of those circles.
    pub plate_margin_mm: f64,
    /// Width `wa` of each arm's body, in the plane of motion (mm).
    pub arm_width_mm: f64,
    /// Thickness `ta` of each arm's body, along the axles (mm).
    pub arm_thickness_mm: f64,
    /// Length of each pusher, back from the tip along the pusher's axis (mm).
    pub pusher_length_mm: f64,
    /// Width of each pusher's body (mm).
    pub pusher_width_mm: f64,
}

impl Default for CadSpec {
    /// A 12 mm bore with DIN 6885-1's 4 × 4 key (hub depth 1.8 mm), 5 mm plates, 16 × 10 mm
    /// arms and 6 mm pushers of 40 mm.
    fn default() -> Self {
        Self {
            bore_diameter_mm: 12.0,
            key_width_mm: 4.0,
            key_depth_mm: 1.8,
            mark_diameter_mm: 2.0,
            plate_thickness_mm: 5.0,
            axial_gap_mm: 1.0,
            plate_margin_mm: 6.0,
            arm_width_mm: 16.0,
            arm_thickness_mm: 10.0,
            pusher_length_mm: 40.0,
            pusher_width_mm: 6.0,
        }
    }
}

impl CadSpec {
    /// Whether every value is the default (a written scene then leaves the table out).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}
