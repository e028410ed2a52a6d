//! Agronomic inputs of the objectives: the tray, the plant spacing and seedling, the
//! planting depth, the arms' and housing's widths, and the machine's travel direction.

use crate::angle::unit;
use crate::vec2::Vec2;
use serde::{Deserialize, Serialize};

/// Which way the machine travels over the field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Travel {
    /// Opposite to the tip's motion at the planting point (so the tip lags the ground).
    Auto,
    /// Towards +x.
    PlusX,
    /// Towards −x.
    MinusX,
}

/// Agronomic inputs (angles in degrees, lengths in mm). Defaults: see `docs/replication.md`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Agronomy {
    /// Direction of the tray's inward normal, pointing from the machine into the tray (deg
    /// from +x, counter-clockwise): the picking point is the trajectory's extreme point
    /// along it. −10: a tray to the right of the mechanism whose surface is inclined 80° to
    /// the horizontal, the middle of the directions under which the paper's design picks
    /// and meets its angle objectives (docs/replication.md).
    pub tray_normal_deg: f64,
    /// Depth of the tray's pots (mm): how far the tip reaches past the tray surface.
    pub tray_depth_mm: f64,
    /// Distance of the tray surface from the carrier axis along the inward normal (mm).
    /// Omitted: the tray is placed by the trajectory, so that the tip reaches exactly
    /// `tray_depth_mm` past its surface.
    pub tray_distance_mm: Option<f64>,
    /// Plant spacing along the row (mm); the machine advances three spacings per turn.
    pub plant_spacing_mm: f64,
    /// Height of the planted seedling above the planting point (mm).
    pub seedling_height_mm: f64,
    /// Planting depth: the ground lies this far above the trajectory's lowest point (mm).
    pub planting_depth_mm: f64,
    /// Half-width of an arm's capsule around `O3 → D` (mm).
    pub arm_half_width_mm: f64,
    /// Wall margin of the gearbox housing around the gears' envelope (mm).
    pub housing_margin_mm: f64,
    /// Travel direction of the machine.
    pub travel: Travel,
}

impl Agronomy {
    /// The tray's inward normal, a unit vector (`tray_normal_deg`).
    pub fn tray_normal(&self) -> Vec2 {
        unit(self.tray_normal_deg.to_radians())
    }
}

impl Default for Agronomy {
    fn default() -> Self {
        Self {
            tray_normal_deg: -10.0,
            tray_depth_mm: 15.0,
            tray_distance_mm: None,
            plant_spacing_mm: 140.0,
            seedling_height_mm: 120.0,
            planting_depth_mm: 25.0,
            arm_half_width_mm: 12.0,
            housing_margin_mm: 10.0,
            travel: Travel::Auto,
        }
    }
}
