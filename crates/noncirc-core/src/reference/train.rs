//! The reference of `[train]`: the planetary train and its arms.

use super::{Field, Range};

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "train.phi0_deg",
        symbol: "Φ0",
        unit: "°",
        range: Range::FINITE,
        meaning: "Installation angle of the planet carrier (paper: 86).",
        refused: &["train.phi0_deg=nan"],
        number: Some(real!(train.phi0_deg)),
    },
    Field {
        key: "train.beta0_deg",
        symbol: "β0",
        unit: "°",
        range: Range::FINITE,
        meaning: "Installation angle of the arm relative to the planet (paper: −29).",
        refused: &["train.beta0_deg=inf"],
        number: Some(real!(train.beta0_deg)),
    },
    Field {
        key: "train.arm_length_mm",
        symbol: "S",
        unit: "mm",
        range: Range::above_at_most(0.0, 1e9),
        meaning: "Distance from the planet's centre to the arm's tip (paper: 145).",
        refused: &["train.arm_length_mm=0", "train.arm_length_mm=-1"],
        number: Some(real!(train.arm_length_mm)),
    },
    Field {
        key: "train.pusher_offset_mm",
        symbol: "H1",
        unit: "mm",
        range: Range::at_least(0.0).and(", below S"),
        meaning: "Distance from the planet's centre to the pusher's axis (paper: 65).",
        refused: &["train.pusher_offset_mm=-1", "train.pusher_offset_mm=145"],
        number: Some(real!(train.pusher_offset_mm)),
    },
    Field {
        key: "train.gamma0_deg",
        symbol: "γ0",
        unit: "°",
        range: Range::FINITE.and(", not a multiple of 180"),
        meaning: "Corner angle of the planet carrier between O1O2 and O2O3 (paper: −53).",
        refused: &["train.gamma0_deg=180", "train.gamma0_deg=-360"],
        number: Some(real!(train.gamma0_deg)),
    },
    Field {
        key: "train.rotation",
        symbol: "σ",
        unit: "",
        range: Range::Rule("`clockwise` or `counterclockwise`"),
        meaning: "Sense of the carrier's rotation (paper: clockwise).",
        refused: &["train.rotation=\"cw\""],
        number: None,
    },
    Field {
        key: "train.pusher_side",
        symbol: "",
        unit: "",
        range: Range::Rule("`left` or `right`"),
        meaning: "Side of the arm line O3 → D on which the pusher's axis lies.",
        refused: &["train.pusher_side=\"middle\""],
        number: None,
    },
    Field {
        key: "train.sun_frame",
        symbol: "",
        unit: "",
        range: Range::Rule("`installed` or `ground`"),
        meaning: "How the sun's control angles sit in the ground frame: turned by Φ0 (the \
                  paper's eq. 5), or measured in the ground frame.",
        refused: &["train.sun_frame=\"carrier\""],
        number: None,
    },
    Field {
        key: "train.carrier_speed_rpm",
        symbol: "n",
        unit: "r/min",
        range: Range::above_at_most(0.0, 1e6),
        meaning: "Carrier speed: 60 gives the paper's 180 picks per minute. Not used when \
                  `train.picks_per_minute` is set.",
        refused: &["train.carrier_speed_rpm=0", "train.carrier_speed_rpm=2e6"],
        number: Some(real!(train.carrier_speed_rpm)),
    },
    Field {
        key: "train.arms",
        symbol: "",
        unit: "",
        range: Range::from_to(1.0, 4.0)
            .and(", dividing `resolution.samples_per_turn`; `interference` needs 2 or more"),
        meaning: "Arm sets on the carrier, evenly spaced (arm k a k-th of a turn behind arm \
                  I): a planet, an intermediate and an arm each. The paper's mechanism has \
                  three, the classic rotary transplanting mechanism two.",
        refused: &["train.arms=0", "train.arms=5", "train.arms=1"],
        number: Some(integer!(usize, train.arms)),
    },
    Field {
        key: "train.picks_per_minute",
        symbol: "",
        unit: "1/min",
        range: Range::above_at_most(0.0, 1e6),
        meaning: "The picking rate: when set, the carrier turns at picks_per_minute / arms \
                  r/min, so that trains with other arm counts compare at the same rate \
                  (the paper's rig: 180).",
        refused: &["train.picks_per_minute=0", "train.picks_per_minute=-180"],
        number: Some(optional!(train.picks_per_minute)),
    },
];
