//! The reference of the scene's own fields: its name, kind, objectives and resolution.

use super::{Field, Range};

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "name",
        symbol: "",
        unit: "",
        range: Range::Rule("any text"),
        meaning: "Short name of the scene.",
        refused: &["name=1"],
        number: None,
    },
    Field {
        key: "description",
        symbol: "",
        unit: "",
        range: Range::Rule("any text"),
        meaning: "One-line description.",
        refused: &["description=[]"],
        number: None,
    },
    Field {
        key: "kind",
        symbol: "",
        unit: "",
        range: Range::Rule("`gear`, `three_arm`, `moving_box` or `transplanter`"),
        meaning: "What the scene designs: a gear pair alone, the three-arm planetary \
                  mechanism, the moving box alone, or the mechanism with the box coupled \
                  through the picking window.",
        refused: &["kind=\"four_arm\""],
        number: None,
    },
    Field {
        key: "objectives",
        symbol: "",
        unit: "",
        range: Range::Rule("objective names (below), each once; not empty in a mechanism scene"),
        meaning: "Which objectives are evaluated; a gear scene may ask `module` only.",
        refused: &[
            "objectives=[]",
            "objectives=[\"module\",\"module\"]",
            "objectives=[\"speed\"]",
        ],
        number: None,
    },
    Field {
        key: "resolution.samples_per_turn",
        symbol: "",
        unit: "",
        range: Range::Rule(
            "a multiple of 6 from 12 to 786432, and of `train.arms` in a mechanism scene",
        ),
        meaning: "Uniform samples of the pitch curve per turn, also the carrier-angle \
                  samples per cycle (docs/accuracy.md).",
        refused: &[
            "resolution.samples_per_turn=6",
            "resolution.samples_per_turn=100",
            "resolution.samples_per_turn=786438",
        ],
        number: Some(integer!(usize, resolution.samples_per_turn)),
    },
    Field {
        key: "resolution.closure_rel_tol",
        symbol: "",
        unit: "",
        range: Range::above_at_most(0.0, 0.01),
        meaning: "Largest accepted relative uncertainty of the centre distance; above it \
                  the closure is reported as under-resolved.",
        refused: &[
            "resolution.closure_rel_tol=0",
            "resolution.closure_rel_tol=0.1",
        ],
        number: Some(real!(resolution.closure_rel_tol)),
    },
    Field {
        key: "resolution.newton_rel_tol",
        symbol: "",
        unit: "",
        range: Range::above(0.0).and(", at most a tenth of `closure_rel_tol`"),
        meaning: "Relative step below which the closure iteration stops.",
        refused: &[
            "resolution.newton_rel_tol=0",
            "resolution.newton_rel_tol=1e-5",
        ],
        number: Some(real!(resolution.newton_rel_tol)),
    },
];
