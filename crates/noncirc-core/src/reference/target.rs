//! The reference of `[target]`: the tip path and key poses a fit aims at.

use super::{Field, Range};

/// A square target path of side 100 mm with `extra` added to its table (TOML).
macro_rules! square {
    ($extra:literal) => {
        concat!(
            "target={x_mm=[0.0,100.0,100.0,0.0],y_mm=[0.0,0.0,100.0,100.0]",
            $extra,
            "}"
        )
    };
}

/// The square with one pose, `$pose` added to its table.
macro_rules! posed {
    ($pose:literal) => {
        concat!(
            "target={x_mm=[0.0,100.0,100.0,0.0],y_mm=[0.0,0.0,100.0,100.0],poses=[{x_mm=0.0,y_mm=0.0",
            $pose,
            "}]}"
        )
    };
}

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "target.kind",
        symbol: "",
        unit: "",
        range: Range::Rule("`points` or `spline`"),
        meaning: "How the points make the path: `points`, the closed polyline through them \
                  (a measured or sampled path); `spline`, the closed centripetal cubic spline \
                  through them (a drawn path, from about ten points).",
        refused: &[square!(",kind=\"bezier\"")],
        number: None,
    },
    Field {
        key: "target.x_mm",
        symbol: "x",
        unit: "mm",
        range: Range::Rule(
            "4 to 100 000 distinct points, finite, within ±10 000 mm; closed (a `points` path's \
             last point within three median spacings of its first); not crossing itself",
        ),
        meaning: "The path's abscissae in the machine frame (origin on the carrier axis, x \
                  forward in the travel, y up), in the order of motion. A repeated last point \
                  closes the path and is dropped.",
        refused: &[
            "target={x_mm=[0.0,1.0,nan,2.0],y_mm=[0.0,0.0,1.0,1.0]}",
            "target={x_mm=[0.0,100.0,0.0,100.0],y_mm=[0.0,100.0,100.0,0.0]}",
            "target={x_mm=[0.0,1.0,2.0],y_mm=[0.0,1.0,0.0]}",
        ],
        number: None,
    },
    Field {
        key: "target.y_mm",
        symbol: "y",
        unit: "mm",
        range: Range::Rule("as many as `target.x_mm`, finite, within ±10 000 mm"),
        meaning: "The path's ordinates in the machine frame.",
        refused: &["target={x_mm=[0.0,100.0,100.0,0.0],y_mm=[0.0,0.0,100.0]}"],
        number: None,
    },
    Field {
        key: "target.tolerance_mm",
        symbol: "τ",
        unit: "mm",
        range: Range::Rule("above 0, at most 1000"),
        meaning: "The path's tolerance: its residuals are distances over τ, and the path is \
                  met when its Hausdorff distance to the trajectory is at most τ. Default 0.5.",
        refused: &[square!(",tolerance_mm=0.0")],
        number: None,
    },
    Field {
        key: "target.samples",
        symbol: "",
        unit: "",
        range: Range::Rule("16 to 4096"),
        meaning: "Samples of the target path, equally spaced by arc length, whose distances to \
                  the trajectory the fit measures (with the trajectory's own points). Default 128.",
        refused: &[square!(",samples=8")],
        number: None,
    },
    Field {
        key: "target.counts",
        symbol: "",
        unit: "",
        range: Range::Rule("true or false; something counts (the path or a pose)"),
        meaning: "Whether the path counts in the fit (false: only the poses count, the path's \
                  distances are reported). Default true.",
        refused: &[square!(",counts=false")],
        number: None,
    },
    Field {
        key: "target.poses",
        symbol: "",
        unit: "",
        range: Range::Rule("at most 4"),
        meaning: "Key poses of arm I, `{ name, at, x_mm, y_mm, attitude_deg, carrier_deg, \
                  tolerances, counts }`.",
        refused: &["target={x_mm=[0.0,100.0,100.0,0.0],y_mm=[0.0,0.0,100.0,100.0],poses=[{x_mm=0.0,y_mm=0.0},{x_mm=0.0,y_mm=0.0},{x_mm=0.0,y_mm=0.0},{x_mm=0.0,y_mm=0.0},{x_mm=0.0,y_mm=0.0}]}"],
        number: None,
    },
    Field {
        key: "target.poses[i].name",
        symbol: "",
        unit: "",
        range: Range::Rule("any text"),
        meaning: "The pose's name in reports (`picking`).",
        refused: &[posed!(",name=3")],
        number: None,
    },
    Field {
        key: "target.poses[i].at",
        symbol: "",
        unit: "",
        range: Range::Rule("`nearest`, `picking` or `planting`"),
        meaning: "Where on the trajectory the pose is read: `picking` and `planting` at the \
                  located events; `nearest` (default) where position, attitude and carrier angle \
                  (those named, each over its tolerance) come nearest.",
        refused: &[posed!(",at=\"lowest\"")],
        number: None,
    },
    Field {
        key: "target.poses[i].x_mm",
        symbol: "",
        unit: "mm",
        range: Range::Rule("finite, within ±10 000 mm"),
        meaning: "The tip's abscissa in the machine frame.",
        refused: &["target={x_mm=[0.0,100.0,100.0,0.0],y_mm=[0.0,0.0,100.0,100.0],poses=[{x_mm=nan,y_mm=0.0}]}"],
        number: None,
    },
    Field {
        key: "target.poses[i].y_mm",
        symbol: "",
        unit: "mm",
        range: Range::Rule("finite, within ±10 000 mm"),
        meaning: "The tip's ordinate in the machine frame.",
        refused: &["target={x_mm=[0.0,100.0,100.0,0.0],y_mm=[0.0,0.0,100.0,100.0],poses=[{x_mm=0.0,y_mm=inf}]}"],
        number: None,
    },
    Field {
        key: "target.poses[i].attitude_deg",
        symbol: "",
        unit: "°",
        range: Range::Rule("−90 to 90; optional"),
        meaning: "The arm's attitude: the pusher direction's dip below the horizontal, as the \
                  events report it. Unset: not fitted.",
        refused: &[posed!(",attitude_deg=95.0")],
        number: None,
    },
    Field {
        key: "target.poses[i].carrier_deg",
        symbol: "",
        unit: "°",
        range: Range::Rule("finite; optional"),
        meaning: "Carrier angle of arm I at the pose. Unset: not fitted.",
        refused: &[posed!(",carrier_deg=nan")],
        number: None,
    },
    Field {
        key: "target.poses[i].position_tolerance_mm",
        symbol: "",
        unit: "mm",
        range: Range::Rule("above 0, at most 1000"),
        meaning: "Tolerance of the tip's position. Default 0.5.",
        refused: &[posed!(",position_tolerance_mm=0.0")],
        number: None,
    },
    Field {
        key: "target.poses[i].attitude_tolerance_deg",
        symbol: "",
        unit: "°",
        range: Range::Rule("above 0, at most 90"),
        meaning: "Tolerance of the attitude. Default 0.5.",
        refused: &[posed!(",attitude_tolerance_deg=-1.0")],
        number: None,
    },
    Field {
        key: "target.poses[i].carrier_tolerance_deg",
        symbol: "",
        unit: "°",
        range: Range::Rule("above 0, at most 180"),
        meaning: "Tolerance of the carrier angle. Default 2.",
        refused: &[posed!(",carrier_tolerance_deg=0.0")],
        number: None,
    },
    Field {
        key: "target.poses[i].counts",
        symbol: "",
        unit: "",
        range: Range::Rule("true or false"),
        meaning: "Whether the pose counts in the fit (false: reported only). Default true.",
        refused: &[posed!(",counts=1")],
        number: None,
    },
    Field {
        key: "target.design",
        symbol: "",
        unit: "",
        range: Range::Rule("at most 1000, each parameter once"),
        meaning: "Design parameters the fit pulls towards values, `{ name, value, scale }`: \
                  each adds (value now − value)/scale to the residuals, so that the fit prefers \
                  the design nearest the given one (`noncirc repair` pulls each free parameter \
                  towards the given design's). They weigh in the cost, not in whether the fit \
                  is met.",
        refused: &[square!(",design=[{name=\"train.phi0_deg\",value=86.0,scale=1.0},{name=\"train.phi0_deg\",value=80.0,scale=1.0}]")],
        number: None,
    },
    Field {
        key: "target.design[i].name",
        symbol: "",
        unit: "",
        range: Range::Rule("a parameter path the scene sets (as `--set` takes it)"),
        meaning: "The parameter pulled (`train.phi0_deg`, `gear.curve.radii_mm[3]`).",
        refused: &[square!(",design=[{name=\"train.phi9_deg\",value=86.0,scale=1.0}]")],
        number: None,
    },
    Field {
        key: "target.design[i].value",
        symbol: "",
        unit: "",
        range: Range::Rule("finite (the parameter's unit)"),
        meaning: "The value the parameter is pulled towards.",
        refused: &[square!(",design=[{name=\"train.phi0_deg\",value=nan,scale=1.0}]")],
        number: None,
    },
    Field {
        key: "target.design[i].scale",
        symbol: "",
        unit: "",
        range: Range::Rule("above 0, finite (the parameter's unit)"),
        meaning: "The change that costs as much as the path off by its tolerance (RMS): \
                  `noncirc repair` takes a tenth of the parameter's search interval.",
        refused: &[square!(",design=[{name=\"train.phi0_deg\",value=86.0,scale=0.0}]")],
        number: None,
    },
];
