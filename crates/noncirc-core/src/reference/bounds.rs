//! The reference of `[bounds]`: the objectives' admissible values.

use super::{Field, Range};

/// A length bound (mm): within 10 m either way. A transplanter is under 2 m across; a
/// bound beyond 10 m cannot be meant, and bounds near the largest numbers would add up to
/// an infinite violation.
const LENGTH: Range = Range::from_to(-1e4, 1e4);

/// An angle bound (°): within a turn either way.
const ANGLE: Range = Range::from_to(-360.0, 360.0);

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "bounds.clearance_min_mm",
        symbol: "",
        unit: "mm",
        range: LENGTH,
        meaning: "Least clearance between an arm and the other planets (objective \
                  `interference`).",
        refused: &["bounds.clearance_min_mm=nan"],
        number: Some(real!(bounds.clearance_min_mm)),
    },
    Field {
        key: "bounds.picking_angle_deg",
        symbol: "",
        unit: "°",
        range: ANGLE.and(": `[lower, upper]`, lower ≤ upper"),
        meaning: "Admissible picking angle (objective `picking_angle`).",
        refused: &[
            "bounds.picking_angle_deg=[30.0,10.0]",
            "bounds.picking_angle_deg=[-5.0,400.0]",
        ],
        number: Some(pair!(bounds.picking_angle_deg)),
    },
    Field {
        key: "bounds.pushing_angle_deg",
        symbol: "",
        unit: "°",
        range: ANGLE.and(": `[lower, upper]`, lower ≤ upper"),
        meaning: "Admissible pushing (planting) angle (objective `pushing_angle`).",
        refused: &["bounds.pushing_angle_deg=[70.0,inf]"],
        number: Some(pair!(bounds.pushing_angle_deg)),
    },
    Field {
        key: "bounds.angle_difference_deg",
        symbol: "",
        unit: "°",
        range: ANGLE.and(": `[lower, upper]`, lower ≤ upper"),
        meaning: "Admissible pushing − picking angle (objective `angle_difference`).",
        refused: &["bounds.angle_difference_deg=[nan,70.0]"],
        number: Some(pair!(bounds.angle_difference_deg)),
    },
    Field {
        key: "bounds.seedling_push_max_mm",
        symbol: "",
        unit: "mm",
        range: LENGTH,
        meaning: "Largest forward excursion past the planted seedling (objective \
                  `seedling_push`).",
        refused: &["bounds.seedling_push_max_mm=inf"],
        number: Some(real!(bounds.seedling_push_max_mm)),
    },
    Field {
        key: "bounds.ground_clearance_min_mm",
        symbol: "",
        unit: "mm",
        range: LENGTH,
        meaning: "Least ground clearance of the gearbox (objective `ground_clearance`).",
        refused: &["bounds.ground_clearance_min_mm=nan"],
        number: Some(real!(bounds.ground_clearance_min_mm)),
    },
    Field {
        key: "bounds.trajectory_height_min_mm",
        symbol: "",
        unit: "mm",
        range: LENGTH,
        meaning: "Least trajectory height (objective `trajectory_height`).",
        refused: &[
            "bounds.trajectory_height_min_mm=nan",
            "bounds.trajectory_height_min_mm=-2e4",
        ],
        number: Some(real!(bounds.trajectory_height_min_mm)),
    },
    Field {
        key: "bounds.module_min_mm",
        symbol: "",
        unit: "mm",
        range: LENGTH,
        meaning: "Least module of the gears (objective `module`).",
        refused: &["bounds.module_min_mm=nan", "bounds.module_min_mm=1e308"],
        number: Some(real!(bounds.module_min_mm)),
    },
    Field {
        key: "bounds.picking_admissible_min_mm",
        symbol: "",
        unit: "mm",
        range: LENGTH,
        meaning: "Least margin by which the worst picking condition holds (objective \
                  `picking_admissible`: the tip reaches into the pot, moving into the tray).",
        refused: &["bounds.picking_admissible_min_mm=nan"],
        number: Some(real!(bounds.picking_admissible_min_mm)),
    },
    Field {
        key: "bounds.bending_safety_min",
        symbol: "SFmin",
        unit: "",
        range: Range::from_to(0.0, 100.0),
        meaning: "Least bending safety factor of the teeth at working speed (objective \
                  `bending_safety`; ISO 6336-1's usual minimum 1.4).",
        refused: &[
            "bounds.bending_safety_min=-1",
            "bounds.bending_safety_min=nan",
        ],
        number: Some(real!(bounds.bending_safety_min)),
    },
    Field {
        key: "bounds.contact_safety_min",
        symbol: "SHmin",
        unit: "",
        range: Range::from_to(0.0, 100.0),
        meaning: "Least contact (pitting) safety factor of the teeth at working speed \
                  (objective `contact_safety`; ISO 6336-1's usual minimum 1.0).",
        refused: &["bounds.contact_safety_min=-0.5"],
        number: Some(real!(bounds.contact_safety_min)),
    },
];
