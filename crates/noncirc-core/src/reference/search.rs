//! The reference of `[search]`: how the design space is searched.

use super::{Field, Range};

/// The range of a `u64` field, and how TOML holds its upper half.
pub(super) const WHOLE_NUMBER: &str =
    "0 to 2^64 − 1 (from 2^63 on, a string in TOML: \"18446744073709551615\")";

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "search.free",
        symbol: "",
        unit: "",
        range: Range::Rule("at most 1000 entries, each a parameter that exists, once"),
        meaning: "The free parameters of a search, `{ name, lower, upper }`; empty: the \
                  default space around the scene's design (docs/search.md).",
        refused: &[
            "search.free=[{name=\"train.s\",lower=0.0,upper=1.0}]",
            "search.free=[{name=\"train.arm_length_mm\",lower=150.0,upper=140.0}]",
        ],
        number: None,
    },
    Field {
        key: "search.free[i].name",
        symbol: "",
        unit: "",
        range: Range::Rule("a numeric scene path (`train.phi0_deg`, `gear.curve.radii_mm[3]`)"),
        meaning: "The free parameter.",
        refused: &["search.free=[{name=\"train.rotation\",lower=0.0,upper=1.0}]"],
        number: None,
    },
    Field {
        key: "search.free[i].lower",
        symbol: "",
        unit: "the parameter's",
        range: Range::Rule("finite, below `upper`"),
        meaning: "Lower bound of the parameter.",
        refused: &["search.free=[{name=\"train.phi0_deg\",lower=nan,upper=1.0}]"],
        number: None,
    },
    Field {
        key: "search.free[i].upper",
        symbol: "",
        unit: "the parameter's",
        range: Range::Rule("finite, above `lower`"),
        meaning: "Upper bound of the parameter.",
        refused: &["search.free=[{name=\"train.phi0_deg\",lower=0.0,upper=inf}]"],
        number: None,
    },
    Field {
        key: "search.algorithm",
        symbol: "",
        unit: "",
        range: Range::Rule("an algorithm's name (below)"),
        meaning: "The search algorithm.",
        refused: &["search.algorithm=\"annealing\""],
        number: None,
    },
    Field {
        key: "search.budget",
        symbol: "",
        unit: "evaluations",
        range: Range::Rule(WHOLE_NUMBER),
        meaning: "Evaluation budget.",
        refused: &["search.budget=-1"],
        number: Some(integer!(u64, search.budget)),
    },
    Field {
        key: "search.population",
        symbol: "",
        unit: "",
        range: Range::from_to(1.0, 1e5),
        meaning: "Population size of population-based algorithms.",
        refused: &["search.population=0", "search.population=100001"],
        number: Some(integer!(usize, search.population)),
    },
    Field {
        key: "search.seed",
        symbol: "",
        unit: "",
        range: Range::Rule(WHOLE_NUMBER),
        meaning: "Random seed: the same seed gives the same run, whatever the thread count.",
        refused: &["search.seed=-1"],
        number: Some(integer!(u64, search.seed)),
    },
    Field {
        key: "search.screening.samples_per_turn",
        symbol: "",
        unit: "",
        range: Range::Rule("as `resolution.samples_per_turn`"),
        meaning: "Samples per turn while screening; every reported design is re-evaluated \
                  at the scene's resolution.",
        refused: &["search.screening.samples_per_turn=10"],
        number: Some(integer!(usize, search.screening.samples_per_turn)),
    },
    Field {
        key: "search.screening.closure_rel_tol",
        symbol: "",
        unit: "",
        range: Range::Rule("as `resolution.closure_rel_tol`"),
        meaning: "Closure tolerance while screening.",
        refused: &["search.screening.closure_rel_tol=0"],
        number: Some(real!(search.screening.closure_rel_tol)),
    },
    Field {
        key: "search.screening.newton_rel_tol",
        symbol: "",
        unit: "",
        range: Range::Rule("as `resolution.newton_rel_tol`"),
        meaning: "Closure iteration stop while screening.",
        refused: &["search.screening.newton_rel_tol=1e-3"],
        number: Some(real!(search.screening.newton_rel_tol)),
    },
    Field {
        key: "search.goals",
        symbol: "",
        unit: "",
        range: Range::Rule("goal names (below), each once"),
        meaning: "Goals beyond feasibility; empty: `least_margin`. Two or more make a \
                  multi-objective search (docs/search.md).",
        refused: &[
            "search.goals=[\"fastest\"]",
            "search.goals=[\"module\",\"module\"]",
        ],
        number: None,
    },
    Field {
        key: "search.constraints",
        symbol: "",
        unit: "",
        range: Range::Rule(
            "`NAME <= VALUE` or `NAME >= VALUE` of a measure (below), each once, at most 200; \
             three-arm and transplanter scenes",
        ),
        meaning: "Bounds on any measure that a design must meet beside the objectives \
                  (`picking_height_mm <= -90`): every search counts a missed one as a \
                  missed objective, `evaluate` reports them (docs/search.md).",
        refused: &[
            "search.constraints=[\"loop_width_mm < 50\"]",
            "search.constraints=[\"path_rms_mm <= 1\"]",
            "search.constraints=[\"loop_width_mm <= 50\",\"loop_width_mm <= 50\"]",
        ],
        number: None,
    },
    Field {
        key: "search.confirm_with_teeth",
        symbol: "",
        unit: "",
        range: Range::Rule("`true` or `false`; `true` needs `gear.module.teeth`"),
        meaning: "Confirm the reported designs with their teeth cut and checked while the \
                  search screens with the scene's own module rule.",
        refused: &["search.confirm_with_teeth=true"],
        number: None,
    },
];
