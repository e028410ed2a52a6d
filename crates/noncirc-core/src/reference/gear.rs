//! The reference of `[gear]`: the pitch curve, the module rule and the teeth.

use super::{Field, Range};

pub(super) const FIELDS: &[Field] = &[
    Field {
        key: "gear.second_curve",
        symbol: "",
        unit: "",
        range: Range::Rule("unset, or a pitch curve of any kind, as `gear.curve` takes it"),
        meaning: "The train with two pairs: the pitch curve of the intermediate's second \
                  layer (layer B, on the shaft of the sun's conjugate and in its own frame), \
                  which drives the planet, its conjugate. Unset: the paper's train, whose \
                  planet is congruent to the sun. `noncirc inverse` writes it as a `table`.",
        refused: &[
            "gear.second_curve={kind=\"ellipse\",semi_major_mm=30.0,eccentricity=1.5}",
            "gear.second_curve={kind=\"circle\"}",
        ],
        number: None,
    },
    Field {
        key: "gear.curve.kind",
        symbol: "",
        unit: "",
        range: Range::Rule("`spline`, `bspline`, `bezier`, `table`, `fourier` or `ellipse`"),
        meaning: "How the sun's pitch curve is given: a periodic cubic spline of ρ(ψ) \
                  through polar control points (the paper's), a closed B-spline or Bézier \
                  curve of the control points read as Cartesian points, measured samples, \
                  a Fourier series, or an ellipse turning about a focus.",
        refused: &["gear.curve.kind=\"circle\""],
        number: None,
    },
    Field {
        key: "gear.curve.radii_mm",
        symbol: "r1 … r12",
        unit: "mm",
        range: Range::from_to(1e-9, 1e9)
            .and("; as many as `angles_deg`, at least 4 (at most 64 for `bezier`); the curve they give positive everywhere"),
        meaning: "Radii of the control points (spline, bspline, bezier, table).",
        refused: &[
            "gear.curve.radii_mm[7]=0",
            "gear.curve.radii_mm=[20.0,30.0]",
            "gear.curve={kind=\"spline\",radii_mm=[20.0,30.0,40.0],angles_deg=[0.0,90.0,180.0]}",
        ],
        number: Some(curve_list!(radii_mm: Spline | Bspline | Bezier | Table)),
    },
    Field {
        key: "gear.curve.angles_deg",
        symbol: "θ1 … θ12",
        unit: "°",
        range: Range::FINITE.and(", strictly increasing within one turn"),
        meaning: "Polar angles of the control points in the sun's own frame.",
        refused: &[
            "gear.curve.angles_deg[2]=30",
            "gear.curve.angles_deg[11]=400",
        ],
        number: Some(curve_list!(angles_deg: Spline | Bspline | Bezier | Table)),
    },
    Field {
        key: "gear.curve.c0_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(1e-9, 1e9).and("; the series positive everywhere"),
        meaning: "Mean radius of a Fourier curve `ρ = c0 + Σk (cos_k cos kψ + sin_k sin kψ)`.",
        refused: &["gear.curve={kind=\"fourier\",c0_mm=-5.0,cos_mm=[1.0],sin_mm=[0.0]}"],
        number: Some(curve!(Fourier, c0_mm)),
    },
    Field {
        key: "gear.curve.cos_mm",
        symbol: "",
        unit: "mm",
        range: Range::FINITE,
        meaning: "Cosine coefficients of a Fourier curve, k = 1, 2, …",
        refused: &["gear.curve={kind=\"fourier\",c0_mm=30.0,cos_mm=[40.0],sin_mm=[0.0]}"],
        number: Some(curve_list!(cos_mm: Fourier)),
    },
    Field {
        key: "gear.curve.sin_mm",
        symbol: "",
        unit: "mm",
        range: Range::FINITE,
        meaning: "Sine coefficients of a Fourier curve, k = 1, 2, …",
        refused: &["gear.curve={kind=\"fourier\",c0_mm=30.0,cos_mm=[0.0],sin_mm=[31.0]}"],
        number: Some(curve_list!(sin_mm: Fourier)),
    },
    Field {
        key: "gear.curve.semi_major_mm",
        symbol: "A",
        unit: "mm",
        range: Range::from_to(1e-9, 1e9),
        meaning: "Semi-major axis of an ellipse `ρ = A(1 − k²)/(1 − k cos ψ)`.",
        refused: &["gear.curve={kind=\"ellipse\",semi_major_mm=0.0,eccentricity=0.3}"],
        number: Some(curve!(Ellipse, semi_major_mm)),
    },
    Field {
        key: "gear.curve.eccentricity",
        symbol: "k",
        unit: "",
        range: Range::from_below(0.0, 1.0),
        meaning: "Eccentricity of an ellipse.",
        refused: &["gear.curve={kind=\"ellipse\",semi_major_mm=40.0,eccentricity=1.0}"],
        number: Some(curve!(Ellipse, eccentricity)),
    },
    Field {
        key: "gear.module.rule",
        symbol: "",
        unit: "",
        range: Range::Rule("`undercut`, `perimeter` or `teeth`"),
        meaning: "How the module is read: the largest module whose teeth the curvature \
                  allows without undercut; `m = L/(πz)` for `teeth` teeth with no check \
                  (how the paper computed its 2.5 mm); or `m = L/(πz)` met only if the \
                  teeth cut with `gear.teeth` pass every check (docs/teeth.md).",
        refused: &[
            "gear.module.rule=\"largest\"",
            "gear.module.rule=\"perimeter\"",
        ],
        number: None,
    },
    Field {
        key: "gear.module.teeth",
        symbol: "z",
        unit: "",
        range: Range::from_to(1.0, 1000.0).and("; required by `perimeter` and `teeth`"),
        meaning: "Teeth per gear (shared by meshing gears). At most 1 000: a module of \
                  0.2 mm on a 600 mm pitch curve; cutting the teeth costs about the square \
                  of their count.",
        refused: &[
            "gear.module.teeth=-3",
            "gear.module.teeth=2.5",
            "gear.module.teeth=1001",
        ],
        number: Some(optional_integer!(u32, gear.module.teeth)),
    },
    Field {
        key: "gear.module.z_min",
        symbol: "z_min",
        unit: "",
        range: Range::above(0.0),
        meaning: "Fewest teeth of a rack that cut a convex arc without undercut (17 for a \
                  20° rack).",
        refused: &["gear.module.z_min=0"],
        number: Some(real!(gear.module.z_min)),
    },
    Field {
        key: "gear.module.cutter_teeth",
        symbol: "",
        unit: "",
        range: Range::above(0.0).and(" (unset: concave arcs forbidden)"),
        meaning: "Teeth of the shaper cutter that cuts concave arcs.",
        refused: &["gear.module.cutter_teeth=0"],
        number: Some(optional!(gear.module.cutter_teeth)),
    },
    Field {
        key: "gear.teeth.pressure_angle_deg",
        symbol: "α",
        unit: "°",
        range: Range::between(5.0, 45.0),
        meaning: "Pressure angle of the cutting tool.",
        refused: &[
            "gear.teeth.pressure_angle_deg=5",
            "gear.teeth.pressure_angle_deg=45",
        ],
        number: Some(real!(gear.teeth.pressure_angle_deg)),
    },
    Field {
        key: "gear.teeth.addendum",
        symbol: "ha*",
        unit: "× m",
        range: Range::above(0.0),
        meaning: "Tip height above the pitch curve, in modules.",
        refused: &["gear.teeth.addendum=0"],
        number: Some(real!(gear.teeth.addendum)),
    },
    Field {
        key: "gear.teeth.dedendum",
        symbol: "hf*",
        unit: "× m",
        range: Range::above(0.0),
        meaning: "Root depth below the pitch curve, in modules.",
        refused: &["gear.teeth.dedendum=-1"],
        number: Some(real!(gear.teeth.dedendum)),
    },
    Field {
        key: "gear.teeth.tip_radius",
        symbol: "ρa*",
        unit: "× m",
        range: Range::above(0.0),
        meaning: "Radius of the tool's tip rounding, which cuts the root fillet.",
        refused: &["gear.teeth.tip_radius=0"],
        number: Some(real!(gear.teeth.tip_radius)),
    },
    Field {
        key: "gear.teeth.backlash_mm",
        symbol: "j",
        unit: "mm",
        range: Range::at_least(0.0),
        meaning: "Circumferential backlash of a pair on the pitch curve, half from each gear.",
        refused: &["gear.teeth.backlash_mm=-0.1"],
        number: Some(real!(gear.teeth.backlash_mm)),
    },
    Field {
        key: "gear.teeth.profile_shift",
        symbol: "x",
        unit: "× m",
        range: Range::FINITE.and(", less than the addendum in size"),
        meaning: "Profile shift of the driver (sun, planets); the intermediates take the \
                  opposite, so the centre distance stays.",
        refused: &["gear.teeth.profile_shift=1.0"],
        number: Some(real!(gear.teeth.profile_shift)),
    },
    Field {
        key: "gear.teeth.cutter.kind",
        symbol: "",
        unit: "",
        range: Range::Rule("`rack` or `shaper`"),
        meaning: "The cutting tool: a rack, or a pinion-type shaper for pitch curves with \
                  concave arcs.",
        refused: &["gear.teeth.cutter.kind=\"hob\""],
        number: None,
    },
    Field {
        key: "gear.teeth.cutter.teeth",
        symbol: "z0",
        unit: "",
        range: Range::Rule("6 or more (a shaper only)"),
        meaning: "Teeth of the shaper cutter: its pitch radius is `m·z0/2`.",
        refused: &["gear.teeth.cutter={kind=\"shaper\",teeth=5}"],
        number: None,
    },
    Field {
        key: "gear.teeth.flank_samples",
        symbol: "",
        unit: "",
        range: Range::from_to(2.0, 1e5),
        meaning: "Least segments per flank of the outline; more where the chord tolerance \
                  needs them (docs/teeth.md).",
        refused: &["gear.teeth.flank_samples=1"],
        number: Some(integer!(usize, gear.teeth.flank_samples)),
    },
    Field {
        key: "gear.teeth.fillet_samples",
        symbol: "",
        unit: "",
        range: Range::from_to(2.0, 1e5),
        meaning: "Least segments per root fillet; more where the chord tolerance needs them.",
        refused: &["gear.teeth.fillet_samples=100001"],
        number: Some(integer!(usize, gear.teeth.fillet_samples)),
    },
    Field {
        key: "gear.teeth.chord_tolerance_mm",
        symbol: "",
        unit: "mm",
        range: Range::from_to(1e-6, 0.1),
        meaning: "Largest distance of an outline chord (flank, fillet, root, tip) from the \
                  generated curve: the outline's accuracy (the mesh check measures to the \
                  curves the chords stand for, to a fraction of it; docs/teeth.md).",
        refused: &["gear.teeth.chord_tolerance_mm=0"],
        number: Some(real!(gear.teeth.chord_tolerance_mm)),
    },
    Field {
        key: "gear.teeth.mesh_steps_per_pitch",
        symbol: "",
        unit: "",
        range: Range::from_to(1.0, 1e5),
        meaning: "Mesh positions per pitch in the whole-turn mesh check (8 times as many \
                  for a pair whose roots the mate cuts).",
        refused: &["gear.teeth.mesh_steps_per_pitch=0"],
        number: Some(integer!(usize, gear.teeth.mesh_steps_per_pitch)),
    },
    Field {
        key: "gear.teeth.arc_panels",
        symbol: "",
        unit: "",
        range: Range::from_to(16.0, 1e5),
        meaning: "Panels per turn of the arc-length tables.",
        refused: &["gear.teeth.arc_panels=8"],
        number: Some(integer!(usize, gear.teeth.arc_panels)),
    },
    Field {
        key: "gear.teeth.min_tip_land",
        symbol: "sa*",
        unit: "× m",
        range: Range::at_least(0.0),
        meaning: "Least tip land below which a tooth is too thin at the tip.",
        refused: &["gear.teeth.min_tip_land=-0.1"],
        number: Some(real!(gear.teeth.min_tip_land)),
    },
    Field {
        key: "gear.teeth.allow_undercut",
        symbol: "",
        unit: "",
        range: Range::Rule("`true` or `false`"),
        meaning: "Whether undercut is accepted (it weakens the tooth and shortens the contact).",
        refused: &["gear.teeth.allow_undercut=1"],
        number: None,
    },
    Field {
        key: "gear.teeth.mate_roots",
        symbol: "",
        unit: "",
        range: Range::Rule("`true` or `false`"),
        meaning: "Whether a tooth space whose root the mate's tips overlap (by a concave arc) \
                  is cut again by the mate's tips, with the bottom clearance \
                  (dedendum − addendum)·m below their tip lands (docs/teeth.md).",
        refused: &["gear.teeth.mate_roots=\"yes\""],
        number: None,
    },
];
