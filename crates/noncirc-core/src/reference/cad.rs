//! The reference of `[cad]`: the solid models' dimensions that the design does not give.

use super::{Field, Range};

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "cad.bore_diameter_mm",
        symbol: "db",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e4),
        meaning: "Bore of every gear, of the plates' axle holes and of the arms' hubs (less \
                  than every gear's root diameter, with the keyway and the mark inside).",
        refused: &["cad.bore_diameter_mm=0", "cad.bore_diameter_mm=-12"],
        number: Some(real!(cad.bore_diameter_mm)),
    },
    Field {
        key: "cad.key_width_mm",
        symbol: "bk",
        unit: "mm",
        range: Range::from_to(0.0, 1e4),
        meaning: "Width of the keyway in each gear's bore, narrower than the bore (0: a plain \
                  bore; DIN 6885-1: 4 mm for a 10–12 mm shaft).",
        refused: &["cad.key_width_mm=-1"],
        number: Some(real!(cad.key_width_mm)),
    },
    Field {
        key: "cad.key_depth_mm",
        symbol: "t2",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e4),
        meaning: "Depth of the keyway into the hub beyond the bore (DIN 6885-1: 1.8 mm with a \
                  4 × 4 key).",
        refused: &["cad.key_depth_mm=0"],
        number: Some(real!(cad.key_depth_mm)),
    },
    Field {
        key: "cad.mark_diameter_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e3),
        meaning: "Phase mark: a hole through each gear on its own +x axis, halfway between the \
                  keyway and the root (0: none).",
        refused: &["cad.mark_diameter_mm=-2"],
        number: Some(real!(cad.mark_diameter_mm)),
    },
    Field {
        key: "cad.plate_thickness_mm",
        symbol: "tp",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e4),
        meaning: "Thickness of each of the carrier's two side plates.",
        refused: &["cad.plate_thickness_mm=0"],
        number: Some(real!(cad.plate_thickness_mm)),
    },
    Field {
        key: "cad.axial_gap_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e4),
        meaning: "Axial gap between a gear layer and the next plate or layer.",
        refused: &["cad.axial_gap_mm=-1"],
        number: Some(real!(cad.axial_gap_mm)),
    },
    Field {
        key: "cad.plate_margin_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(0.0, 1e4),
        meaning: "The side plates' material beyond the largest tip circle around every axle: \
                  their outline is the hull of those circles.",
        refused: &["cad.plate_margin_mm=-6"],
        number: Some(real!(cad.plate_margin_mm)),
    },
    Field {
        key: "cad.arm_width_mm",
        symbol: "wa",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e4),
        meaning: "Width of each arm's body in the plane of motion, from the planet's axle to \
                  the tip (wider than the bore).",
        refused: &["cad.arm_width_mm=0"],
        number: Some(real!(cad.arm_width_mm)),
    },
    Field {
        key: "cad.arm_thickness_mm",
        symbol: "ta",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e4),
        meaning: "Thickness of each arm's body along the axles.",
        refused: &["cad.arm_thickness_mm=0"],
        number: Some(real!(cad.arm_thickness_mm)),
    },
    Field {
        key: "cad.pusher_length_mm",
        symbol: "",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e4),
        meaning: "Length of each pusher, back from the tip along the pusher's axis.",
        refused: &["cad.pusher_length_mm=0"],
        number: Some(real!(cad.pusher_length_mm)),
    },
    Field {
        key: "cad.pusher_width_mm",
        symbol: "",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e4),
        meaning: "Width of each pusher's body (its thickness is the arm's).",
        refused: &["cad.pusher_width_mm=0"],
        number: Some(real!(cad.pusher_width_mm)),
    },
];
