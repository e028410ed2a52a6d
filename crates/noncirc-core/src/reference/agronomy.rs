//! The reference of `[agronomy]`: the tray, the seedling and the field.

use super::{Field, Range};

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "agronomy.tray_normal_deg",
        symbol: "",
        unit: "°",
        range: Range::FINITE,
        meaning: "Direction of the tray's inward normal from +x, counter-clockwise: the \
                  picking point is the trajectory's extreme point along it.",
        refused: &["agronomy.tray_normal_deg=nan"],
        number: Some(real!(agronomy.tray_normal_deg)),
    },
    Field {
        key: "agronomy.tray_depth_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e9),
        meaning: "Depth of the tray's pots: how far the tip reaches past the tray surface.",
        refused: &["agronomy.tray_depth_mm=-1"],
        number: Some(real!(agronomy.tray_depth_mm)),
    },
    Field {
        key: "agronomy.tray_distance_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e9),
        meaning: "Distance of the tray surface from the carrier axis along the inward \
                  normal; unset, the tray is placed so that the tip reaches exactly \
                  `tray_depth_mm` past it.",
        refused: &["agronomy.tray_distance_mm=-5"],
        number: Some(optional!(agronomy.tray_distance_mm)),
    },
    Field {
        key: "agronomy.plant_spacing_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e9),
        meaning: "Plant spacing along the row; the machine advances three spacings per turn.",
        refused: &["agronomy.plant_spacing_mm=-140"],
        number: Some(real!(agronomy.plant_spacing_mm)),
    },
    Field {
        key: "agronomy.seedling_height_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e9),
        meaning: "Height of the planted seedling above the planting point.",
        refused: &["agronomy.seedling_height_mm=1e10"],
        number: Some(real!(agronomy.seedling_height_mm)),
    },
    Field {
        key: "agronomy.planting_depth_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e9),
        meaning: "Planting depth: the ground lies this far above the trajectory's lowest point.",
        refused: &["agronomy.planting_depth_mm=-1"],
        number: Some(real!(agronomy.planting_depth_mm)),
    },
    Field {
        key: "agronomy.arm_half_width_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e9),
        meaning: "Half-width of an arm's capsule around O3 → D (the interference check).",
        refused: &["agronomy.arm_half_width_mm=-1"],
        number: Some(real!(agronomy.arm_half_width_mm)),
    },
    Field {
        key: "agronomy.housing_margin_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e9),
        meaning: "Wall margin of the gearbox housing around the gears' envelope.",
        refused: &["agronomy.housing_margin_mm=-1"],
        number: Some(real!(agronomy.housing_margin_mm)),
    },
    Field {
        key: "agronomy.travel",
        symbol: "",
        unit: "",
        range: Range::Rule("`auto`, `plus_x` or `minus_x`"),
        meaning: "Travel direction of the machine; `auto`: opposite to the tip's motion at \
                  the planting point.",
        refused: &["agronomy.travel=\"forward\""],
        number: None,
    },
];
