//! The scene reference: every field of a scene with the papers' symbol, its unit, its
//! admissible values and its meaning. docs/scenes.md is generated from this table (with
//! each field's default read from the code); a test holds the table to the scene's fields
//! both ways and probes every admissible range with a value it must refuse.

/// One field of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Field {
    /// The scene path, as `--set` and Python's `with_set` take it (`train.arm_length_mm`);
    /// a list's elements are `key[i]`.
    pub key: &'static str,
    /// The papers' symbol (`S`, `Φ0`), or "" where they name none.
    pub symbol: &'static str,
    /// Unit ("" for counts, names and ratios).
    pub unit: &'static str,
    /// The admissible values, as the checks hold them.
    pub range: &'static str,
    /// What the field means.
    pub meaning: &'static str,
    /// `key=value` assignments (TOML values) each of which a scene must refuse: the
    /// reference's test applies them, so that the range above stays true.
    pub refused: &'static [&'static str],
}

/// The field of a scene path (`gear.curve.radii_mm[3]` is `gear.curve.radii_mm`'s).
pub fn field(path: &str) -> Option<&'static Field> {
    let key = path.split('[').next().unwrap_or(path);
    FIELDS.iter().find(|f| f.key == key)
}

/// The papers' symbol of a scene path, if they name one: `train.arm_length_mm` → `S`, and
/// a list's element by its number, `gear.curve.radii_mm[3]` → `r4`.
pub fn symbol(path: &str) -> Option<String> {
    let (key, index) = match path.split_once('[') {
        Some((key, rest)) => (key, Some(rest.strip_suffix(']')?.parse::<usize>().ok()?)),
        None => (path, None),
    };
    let field = FIELDS
        .iter()
        .find(|f| f.key == key && !f.symbol.is_empty())?;
    match (index, field.symbol.split_once(" … ")) {
        // `r1 … r12`: the letters before the first number, then the element's.
        (Some(i), Some((first, _))) => {
            let letters = first.trim_end_matches(|c: char| c.is_ascii_digit());
            Some(format!("{letters}{}", i + 1))
        }
        (None, _) => Some(field.symbol.to_string()),
        (Some(_), None) => None,
    }
}

/// Every field of a scene, in the order of a scene file.
pub const FIELDS: &[Field] = &[
    Field {
        key: "name",
        symbol: "",
        unit: "",
        range: "any text",
        meaning: "Short name of the scene.",
        refused: &["name=1"],
    },
    Field {
        key: "description",
        symbol: "",
        unit: "",
        range: "any text",
        meaning: "One-line description.",
        refused: &["description=[]"],
    },
    Field {
        key: "kind",
        symbol: "",
        unit: "",
        range: "`gear`, `three_arm`, `moving_box` or `transplanter`",
        meaning: "What the scene designs: a gear pair alone, the three-arm planetary \
                  mechanism, the moving box alone, or the mechanism with the box coupled \
                  through the picking window.",
        refused: &["kind=\"four_arm\""],
    },
    Field {
        key: "objectives",
        symbol: "",
        unit: "",
        range: "objective names (below), each once; not empty in a mechanism scene",
        meaning: "Which objectives are evaluated; a gear scene may ask `module` only.",
        refused: &[
            "objectives=[]",
            "objectives=[\"module\",\"module\"]",
            "objectives=[\"speed\"]",
        ],
    },
    Field {
        key: "resolution.samples_per_turn",
        symbol: "",
        unit: "",
        range: "a multiple of 6 from 12 to 786432, and of `train.arms` in a mechanism scene",
        meaning: "Uniform samples of the pitch curve per turn, also the carrier-angle \
                  samples per cycle (docs/accuracy.md).",
        refused: &[
            "resolution.samples_per_turn=6",
            "resolution.samples_per_turn=100",
            "resolution.samples_per_turn=786438",
        ],
    },
    Field {
        key: "resolution.closure_rel_tol",
        symbol: "",
        unit: "",
        range: "above 0, at most 1e-2",
        meaning: "Largest accepted relative uncertainty of the centre distance; above it \
                  the closure is reported as under-resolved.",
        refused: &[
            "resolution.closure_rel_tol=0",
            "resolution.closure_rel_tol=0.1",
        ],
    },
    Field {
        key: "resolution.newton_rel_tol",
        symbol: "",
        unit: "",
        range: "above 0, at most a tenth of `closure_rel_tol`",
        meaning: "Relative step below which the closure iteration stops.",
        refused: &[
            "resolution.newton_rel_tol=0",
            "resolution.newton_rel_tol=1e-5",
        ],
    },
    Field {
        key: "gear.curve.kind",
        symbol: "",
        unit: "",
        range: "`spline`, `bspline`, `bezier`, `table`, `fourier` or `ellipse`",
        meaning: "How the sun's pitch curve is given: a periodic cubic spline of ρ(ψ) \
                  through polar control points (the paper's), a closed B-spline or Bézier \
                  curve of the control points read as Cartesian points, measured samples, \
                  a Fourier series, or an ellipse turning about a focus.",
        refused: &["gear.curve.kind=\"circle\""],
    },
    Field {
        key: "gear.curve.radii_mm",
        symbol: "r1 … r12",
        unit: "mm",
        range: "positive; as many as `angles_deg`, at least 4; the curve they give \
                positive everywhere",
        meaning: "Radii of the control points (spline, bspline, bezier, table).",
        refused: &[
            "gear.curve.radii_mm[7]=0",
            "gear.curve.radii_mm=[20.0,30.0]",
            "gear.curve={kind=\"spline\",radii_mm=[20.0,30.0,40.0],angles_deg=[0.0,90.0,180.0]}",
        ],
    },
    Field {
        key: "gear.curve.angles_deg",
        symbol: "θ1 … θ12",
        unit: "°",
        range: "finite, strictly increasing within one turn",
        meaning: "Polar angles of the control points in the sun's own frame.",
        refused: &[
            "gear.curve.angles_deg[2]=30",
            "gear.curve.angles_deg[11]=400",
        ],
    },
    Field {
        key: "gear.curve.c0_mm",
        symbol: "",
        unit: "mm",
        range: "positive; the series positive everywhere",
        meaning: "Mean radius of a Fourier curve `ρ = c0 + Σk (cos_k cos kψ + sin_k sin kψ)`.",
        refused: &["gear.curve={kind=\"fourier\",c0_mm=-5.0,cos_mm=[1.0],sin_mm=[0.0]}"],
    },
    Field {
        key: "gear.curve.cos_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Cosine coefficients of a Fourier curve, k = 1, 2, …",
        refused: &["gear.curve={kind=\"fourier\",c0_mm=30.0,cos_mm=[40.0],sin_mm=[0.0]}"],
    },
    Field {
        key: "gear.curve.sin_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Sine coefficients of a Fourier curve, k = 1, 2, …",
        refused: &["gear.curve={kind=\"fourier\",c0_mm=30.0,cos_mm=[0.0],sin_mm=[31.0]}"],
    },
    Field {
        key: "gear.curve.semi_major_mm",
        symbol: "A",
        unit: "mm",
        range: "a length from 1e-9 to 1e9 mm",
        meaning: "Semi-major axis of an ellipse `ρ = A(1 − k²)/(1 − k cos ψ)`.",
        refused: &["gear.curve={kind=\"ellipse\",semi_major_mm=0.0,eccentricity=0.3}"],
    },
    Field {
        key: "gear.curve.eccentricity",
        symbol: "k",
        unit: "",
        range: "0 ≤ k < 1",
        meaning: "Eccentricity of an ellipse.",
        refused: &["gear.curve={kind=\"ellipse\",semi_major_mm=40.0,eccentricity=1.0}"],
    },
    Field {
        key: "gear.module.rule",
        symbol: "",
        unit: "",
        range: "`undercut`, `perimeter` or `teeth`",
        meaning: "How the module is read: the largest module whose teeth the curvature \
                  allows without undercut; `m = L/(πz)` for `teeth` teeth with no check \
                  (how the paper computed its 2.5 mm); or `m = L/(πz)` met only if the \
                  teeth cut with `gear.teeth` pass every check (docs/teeth.md).",
        refused: &[
            "gear.module.rule=\"largest\"",
            "gear.module.rule=\"perimeter\"",
        ],
    },
    Field {
        key: "gear.module.teeth",
        symbol: "z",
        unit: "",
        range: "unset, or a whole number from 1; required by `perimeter` and `teeth`",
        meaning: "Teeth per gear (shared by meshing gears).",
        refused: &["gear.module.teeth=-3", "gear.module.teeth=2.5"],
    },
    Field {
        key: "gear.module.z_min",
        symbol: "z_min",
        unit: "",
        range: "above 0",
        meaning: "Fewest teeth of a rack that cut a convex arc without undercut (17 for a \
                  20° rack).",
        refused: &["gear.module.z_min=0"],
    },
    Field {
        key: "gear.module.cutter_teeth",
        symbol: "",
        unit: "",
        range: "unset (concave arcs forbidden), or above 0",
        meaning: "Teeth of the shaper cutter that cuts concave arcs.",
        refused: &["gear.module.cutter_teeth=0"],
    },
    Field {
        key: "gear.teeth.pressure_angle_deg",
        symbol: "α",
        unit: "°",
        range: "between 5 and 45 (exclusive)",
        meaning: "Pressure angle of the cutting tool.",
        refused: &[
            "gear.teeth.pressure_angle_deg=5",
            "gear.teeth.pressure_angle_deg=45",
        ],
    },
    Field {
        key: "gear.teeth.addendum",
        symbol: "ha*",
        unit: "× m",
        range: "above 0",
        meaning: "Tip height above the pitch curve, in modules.",
        refused: &["gear.teeth.addendum=0"],
    },
    Field {
        key: "gear.teeth.dedendum",
        symbol: "hf*",
        unit: "× m",
        range: "above 0",
        meaning: "Root depth below the pitch curve, in modules.",
        refused: &["gear.teeth.dedendum=-1"],
    },
    Field {
        key: "gear.teeth.tip_radius",
        symbol: "ρa*",
        unit: "× m",
        range: "above 0",
        meaning: "Radius of the tool's tip rounding, which cuts the root fillet.",
        refused: &["gear.teeth.tip_radius=0"],
    },
    Field {
        key: "gear.teeth.backlash_mm",
        symbol: "j",
        unit: "mm",
        range: "0 or more",
        meaning: "Circumferential backlash of a pair on the pitch curve, half from each gear.",
        refused: &["gear.teeth.backlash_mm=-0.1"],
    },
    Field {
        key: "gear.teeth.profile_shift",
        symbol: "x",
        unit: "× m",
        range: "less than the addendum in size",
        meaning: "Profile shift of the driver (sun, planets); the intermediates take the \
                  opposite, so the centre distance stays.",
        refused: &["gear.teeth.profile_shift=1.0"],
    },
    Field {
        key: "gear.teeth.cutter.kind",
        symbol: "",
        unit: "",
        range: "`rack` or `shaper`",
        meaning: "The cutting tool: a rack, or a pinion-type shaper for pitch curves with \
                  concave arcs.",
        refused: &["gear.teeth.cutter.kind=\"hob\""],
    },
    Field {
        key: "gear.teeth.cutter.teeth",
        symbol: "z0",
        unit: "",
        range: "6 or more (a shaper only)",
        meaning: "Teeth of the shaper cutter: its pitch radius is `m·z0/2`.",
        refused: &["gear.teeth.cutter={kind=\"shaper\",teeth=5}"],
    },
    Field {
        key: "gear.teeth.flank_samples",
        symbol: "",
        unit: "",
        range: "2 to 100000",
        meaning: "Segments per flank of the outline (docs/teeth.md).",
        refused: &["gear.teeth.flank_samples=1"],
    },
    Field {
        key: "gear.teeth.fillet_samples",
        symbol: "",
        unit: "",
        range: "2 to 100000",
        meaning: "Segments per root fillet.",
        refused: &["gear.teeth.fillet_samples=100001"],
    },
    Field {
        key: "gear.teeth.mesh_steps_per_pitch",
        symbol: "",
        unit: "",
        range: "1 to 100000",
        meaning: "Mesh positions per pitch in the whole-turn mesh check.",
        refused: &["gear.teeth.mesh_steps_per_pitch=0"],
    },
    Field {
        key: "gear.teeth.arc_panels",
        symbol: "",
        unit: "",
        range: "16 to 100000",
        meaning: "Panels per turn of the arc-length tables.",
        refused: &["gear.teeth.arc_panels=8"],
    },
    Field {
        key: "gear.teeth.min_tip_land",
        symbol: "sa*",
        unit: "× m",
        range: "0 or more",
        meaning: "Least tip land below which a tooth is too thin at the tip.",
        refused: &["gear.teeth.min_tip_land=-0.1"],
    },
    Field {
        key: "gear.teeth.allow_undercut",
        symbol: "",
        unit: "",
        range: "`true` or `false`",
        meaning: "Whether undercut is accepted (it weakens the tooth and shortens the contact).",
        refused: &["gear.teeth.allow_undercut=1"],
    },
    Field {
        key: "train.phi0_deg",
        symbol: "Φ0",
        unit: "°",
        range: "finite",
        meaning: "Installation angle of the planet carrier (paper: 86).",
        refused: &["train.phi0_deg=nan"],
    },
    Field {
        key: "train.beta0_deg",
        symbol: "β0",
        unit: "°",
        range: "finite",
        meaning: "Installation angle of the arm relative to the planet (paper: −29).",
        refused: &["train.beta0_deg=inf"],
    },
    Field {
        key: "train.arm_length_mm",
        symbol: "S",
        unit: "mm",
        range: "above 0, at most 1e9",
        meaning: "Distance from the planet's centre to the arm's tip (paper: 145).",
        refused: &["train.arm_length_mm=0", "train.arm_length_mm=-1"],
    },
    Field {
        key: "train.pusher_offset_mm",
        symbol: "H1",
        unit: "mm",
        range: "0 ≤ H1 < S",
        meaning: "Distance from the planet's centre to the pusher's axis (paper: 65).",
        refused: &["train.pusher_offset_mm=-1", "train.pusher_offset_mm=145"],
    },
    Field {
        key: "train.gamma0_deg",
        symbol: "γ0",
        unit: "°",
        range: "finite, not a multiple of 180",
        meaning: "Corner angle of the planet carrier between O1O2 and O2O3 (paper: −53).",
        refused: &["train.gamma0_deg=180", "train.gamma0_deg=-360"],
    },
    Field {
        key: "train.rotation",
        symbol: "σ",
        unit: "",
        range: "`clockwise` or `counterclockwise`",
        meaning: "Sense of the carrier's rotation (paper: clockwise).",
        refused: &["train.rotation=\"cw\""],
    },
    Field {
        key: "train.pusher_side",
        symbol: "",
        unit: "",
        range: "`left` or `right`",
        meaning: "Side of the arm line O3 → D on which the pusher's axis lies.",
        refused: &["train.pusher_side=\"middle\""],
    },
    Field {
        key: "train.sun_frame",
        symbol: "",
        unit: "",
        range: "`installed` or `ground`",
        meaning: "How the sun's control angles sit in the ground frame: turned by Φ0 (the \
                  paper's eq. 5), or measured in the ground frame.",
        refused: &["train.sun_frame=\"carrier\""],
    },
    Field {
        key: "train.carrier_speed_rpm",
        symbol: "n",
        unit: "r/min",
        range: "above 0, at most 1e6",
        meaning: "Carrier speed: 60 gives the paper's 180 picks per minute. Not used when \
                  `train.picks_per_minute` is set.",
        refused: &["train.carrier_speed_rpm=0", "train.carrier_speed_rpm=2e6"],
    },
    Field {
        key: "train.arms",
        symbol: "",
        unit: "",
        range: "1 to 4, dividing `resolution.samples_per_turn`; `interference` needs 2 or more",
        meaning: "Arm sets on the carrier, evenly spaced (arm k a k-th of a turn behind arm \
                  I): a planet, an intermediate and an arm each. The paper's mechanism has \
                  three, the classic rotary transplanting mechanism two.",
        refused: &["train.arms=0", "train.arms=5", "train.arms=1"],
    },
    Field {
        key: "train.picks_per_minute",
        symbol: "",
        unit: "1/min",
        range: "unset, or above 0, at most 1e6",
        meaning: "The picking rate: when set, the carrier turns at picks_per_minute / arms \
                  r/min, so that trains with other arm counts compare at the same rate \
                  (the paper's rig: 180).",
        refused: &["train.picks_per_minute=0", "train.picks_per_minute=-180"],
    },
    Field {
        key: "agronomy.tray_normal_deg",
        symbol: "",
        unit: "°",
        range: "finite",
        meaning: "Direction of the tray's inward normal from +x, counter-clockwise: the \
                  picking point is the trajectory's extreme point along it.",
        refused: &["agronomy.tray_normal_deg=nan"],
    },
    Field {
        key: "agronomy.tray_depth_mm",
        symbol: "",
        unit: "mm",
        range: "0 to 1e9",
        meaning: "Depth of the tray's pots: how far the tip reaches past the tray surface.",
        refused: &["agronomy.tray_depth_mm=-1"],
    },
    Field {
        key: "agronomy.tray_distance_mm",
        symbol: "",
        unit: "mm",
        range: "unset, or 0 to 1e9",
        meaning: "Distance of the tray surface from the carrier axis along the inward \
                  normal; unset, the tray is placed so that the tip reaches exactly \
                  `tray_depth_mm` past it.",
        refused: &["agronomy.tray_distance_mm=-5"],
    },
    Field {
        key: "agronomy.plant_spacing_mm",
        symbol: "",
        unit: "mm",
        range: "0 to 1e9",
        meaning: "Plant spacing along the row; the machine advances three spacings per turn.",
        refused: &["agronomy.plant_spacing_mm=-140"],
    },
    Field {
        key: "agronomy.seedling_height_mm",
        symbol: "",
        unit: "mm",
        range: "0 to 1e9",
        meaning: "Height of the planted seedling above the planting point.",
        refused: &["agronomy.seedling_height_mm=1e10"],
    },
    Field {
        key: "agronomy.planting_depth_mm",
        symbol: "",
        unit: "mm",
        range: "0 to 1e9",
        meaning: "Planting depth: the ground lies this far above the trajectory's lowest point.",
        refused: &["agronomy.planting_depth_mm=-1"],
    },
    Field {
        key: "agronomy.arm_half_width_mm",
        symbol: "",
        unit: "mm",
        range: "0 to 1e9",
        meaning: "Half-width of an arm's capsule around O3 → D (the interference check).",
        refused: &["agronomy.arm_half_width_mm=-1"],
    },
    Field {
        key: "agronomy.housing_margin_mm",
        symbol: "",
        unit: "mm",
        range: "0 to 1e9",
        meaning: "Wall margin of the gearbox housing around the gears' envelope.",
        refused: &["agronomy.housing_margin_mm=-1"],
    },
    Field {
        key: "agronomy.travel",
        symbol: "",
        unit: "",
        range: "`auto`, `plus_x` or `minus_x`",
        meaning: "Travel direction of the machine; `auto`: opposite to the tip's motion at \
                  the planting point.",
        refused: &["agronomy.travel=\"forward\""],
    },
    Field {
        key: "bounds.clearance_min_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Least clearance between an arm and the other planets (objective \
                  `interference`).",
        refused: &["bounds.clearance_min_mm=nan"],
    },
    Field {
        key: "bounds.picking_angle_deg",
        symbol: "",
        unit: "°",
        range: "[lower, upper], finite, lower ≤ upper",
        meaning: "Admissible picking angle (objective `picking_angle`).",
        refused: &["bounds.picking_angle_deg=[30.0,10.0]"],
    },
    Field {
        key: "bounds.pushing_angle_deg",
        symbol: "",
        unit: "°",
        range: "[lower, upper], finite, lower ≤ upper",
        meaning: "Admissible pushing (planting) angle (objective `pushing_angle`).",
        refused: &["bounds.pushing_angle_deg=[70.0,inf]"],
    },
    Field {
        key: "bounds.angle_difference_deg",
        symbol: "",
        unit: "°",
        range: "[lower, upper], finite, lower ≤ upper",
        meaning: "Admissible pushing − picking angle (objective `angle_difference`).",
        refused: &["bounds.angle_difference_deg=[nan,70.0]"],
    },
    Field {
        key: "bounds.seedling_push_max_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Largest forward excursion past the planted seedling (objective \
                  `seedling_push`).",
        refused: &["bounds.seedling_push_max_mm=inf"],
    },
    Field {
        key: "bounds.ground_clearance_min_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Least ground clearance of the gearbox (objective `ground_clearance`).",
        refused: &["bounds.ground_clearance_min_mm=nan"],
    },
    Field {
        key: "bounds.trajectory_height_min_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Least trajectory height (objective `trajectory_height`).",
        refused: &["bounds.trajectory_height_min_mm=nan"],
    },
    Field {
        key: "bounds.module_min_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Least module of the gears (objective `module`).",
        refused: &["bounds.module_min_mm=nan"],
    },
    Field {
        key: "bounds.picking_admissible_min_mm",
        symbol: "",
        unit: "mm",
        range: "finite",
        meaning: "Least margin by which the worst picking condition holds (objective \
                  `picking_admissible`: the tip reaches into the pot, moving into the tray).",
        refused: &["bounds.picking_admissible_min_mm=nan"],
    },
    Field {
        key: "moving_box.eccentricity",
        symbol: "k",
        unit: "",
        range: "0 ≤ k < 1",
        meaning: "Eccentricity of the box drive's elliptical gears; 1/(2+√3) gives a \
                  fastest/slowest speed ratio of 3 (the moving-box paper).",
        refused: &["moving_box.eccentricity=1", "moving_box.eccentricity=-0.1"],
    },
    Field {
        key: "moving_box.speed_ratio",
        symbol: "",
        unit: "",
        range: "unset, or at least 1",
        meaning: "If set, k is derived from this fastest/slowest speed ratio instead.",
        refused: &["moving_box.speed_ratio=0.5"],
    },
    Field {
        key: "moving_box.pot_pitch_mm",
        symbol: "",
        unit: "mm",
        range: "above 0, at most 1e9",
        meaning: "Box travel per input turn.",
        refused: &["moving_box.pot_pitch_mm=0"],
    },
    Field {
        key: "moving_box.pot_width_mm",
        symbol: "",
        unit: "mm",
        range: "above 0, at most 1e9",
        meaning: "Pot width: the box may move at most a sixth of it while a seedling is picked.",
        refused: &["moving_box.pot_width_mm=-18"],
    },
    Field {
        key: "moving_box.module_mm",
        symbol: "m",
        unit: "mm",
        range: "above 0, at most 1e9",
        meaning: "Module of the elliptical gears (with `teeth`, it fixes their size).",
        refused: &["moving_box.module_mm=0"],
    },
    Field {
        key: "moving_box.teeth",
        symbol: "z",
        unit: "",
        range: "a whole number from 1",
        meaning: "Tooth count of the elliptical gears.",
        refused: &["moving_box.teeth=0"],
    },
    Field {
        key: "moving_box.input_speed_rpm",
        symbol: "n",
        unit: "r/min",
        range: "above 0, at most 1e5",
        meaning: "Input shaft speed.",
        refused: &[
            "moving_box.input_speed_rpm=0",
            "moving_box.input_speed_rpm=2e5",
        ],
    },
    Field {
        key: "moving_box.window_deg",
        symbol: "",
        unit: "°",
        range: "0 to 360",
        meaning: "Width of the picking window on the driving gear.",
        refused: &["moving_box.window_deg=400"],
    },
    Field {
        key: "moving_box.window_centre_deg",
        symbol: "",
        unit: "°",
        range: "finite",
        meaning: "Centre of the picking window on the driving gear.",
        refused: &["moving_box.window_centre_deg=nan"],
    },
    Field {
        key: "moving_box.spiral_angle_deg",
        symbol: "φs",
        unit: "°",
        range: "between 0 and 90 (exclusive)",
        meaning: "Spiral angle of the sinusoidal spiral shaft's groove development.",
        refused: &["moving_box.spiral_angle_deg=90"],
    },
    Field {
        key: "moving_box.box_mass_kg",
        symbol: "m",
        unit: "kg",
        range: "above 0, at most 1e6",
        meaning: "Mass of the seedling box (an assumption: the paper gives none).",
        refused: &["moving_box.box_mass_kg=0"],
    },
    Field {
        key: "moving_box.groove_wall_angle_deg",
        symbol: "α",
        unit: "°",
        range: "0 to 90 (90 excluded); with the groove friction angle below 90",
        meaning: "Angle between the spiral groove's wall and the YOZ plane (an assumption).",
        refused: &[
            "moving_box.groove_wall_angle_deg=-1",
            "moving_box.groove_wall_angle_deg=85",
        ],
    },
    Field {
        key: "moving_box.groove_friction_angle_deg",
        symbol: "φ",
        unit: "°",
        range: "0 to 90 (90 excluded)",
        meaning: "Friction angle in the spiral groove (an assumption).",
        refused: &["moving_box.groove_friction_angle_deg=90"],
    },
    Field {
        key: "moving_box.slide_friction_angle_deg",
        symbol: "φ1",
        unit: "°",
        range: "0 to 90 (90 excluded)",
        meaning: "Friction angle of the box on its slide (an assumption).",
        refused: &["moving_box.slide_friction_angle_deg=-5"],
    },
    Field {
        key: "moving_box.input_turns_per_carrier_turn",
        symbol: "",
        unit: "",
        range: "above 0, at most 1e3; in a transplanter scene, `train.arms`",
        meaning: "Transplanter coupling: box input turns per carrier turn (one pot per \
                  pick: 3 for the three-arm mechanism, `train.arms` for any).",
        refused: &[
            "moving_box.input_turns_per_carrier_turn=0",
            "moving_box.input_turns_per_carrier_turn=2",
        ],
    },
    Field {
        key: "search.free",
        symbol: "",
        unit: "",
        range: "at most 1000 entries, each a parameter that exists, once",
        meaning: "The free parameters of a search, `{ name, lower, upper }`; empty: the \
                  default space around the scene's design (docs/search.md).",
        refused: &[
            "search.free=[{name=\"train.s\",lower=0.0,upper=1.0}]",
            "search.free=[{name=\"train.arm_length_mm\",lower=150.0,upper=140.0}]",
        ],
    },
    Field {
        key: "search.free[i].name",
        symbol: "",
        unit: "",
        range: "a numeric scene path (`train.phi0_deg`, `gear.curve.radii_mm[3]`)",
        meaning: "The free parameter.",
        refused: &["search.free=[{name=\"train.rotation\",lower=0.0,upper=1.0}]"],
    },
    Field {
        key: "search.free[i].lower",
        symbol: "",
        unit: "the parameter's",
        range: "finite, below `upper`",
        meaning: "Lower bound of the parameter.",
        refused: &["search.free=[{name=\"train.phi0_deg\",lower=nan,upper=1.0}]"],
    },
    Field {
        key: "search.free[i].upper",
        symbol: "",
        unit: "the parameter's",
        range: "finite, above `lower`",
        meaning: "Upper bound of the parameter.",
        refused: &["search.free=[{name=\"train.phi0_deg\",lower=0.0,upper=inf}]"],
    },
    Field {
        key: "search.algorithm",
        symbol: "",
        unit: "",
        range: "an algorithm's name (below)",
        meaning: "The search algorithm.",
        refused: &["search.algorithm=\"annealing\""],
    },
    Field {
        key: "search.budget",
        symbol: "",
        unit: "evaluations",
        range: "a whole number, 0 or more",
        meaning: "Evaluation budget.",
        refused: &["search.budget=-1"],
    },
    Field {
        key: "search.population",
        symbol: "",
        unit: "",
        range: "1 to 100000",
        meaning: "Population size of population-based algorithms.",
        refused: &["search.population=0", "search.population=100001"],
    },
    Field {
        key: "search.seed",
        symbol: "",
        unit: "",
        range: "a whole number, 0 or more",
        meaning: "Random seed: the same seed gives the same run, whatever the thread count.",
        refused: &["search.seed=-1"],
    },
    Field {
        key: "search.screening.samples_per_turn",
        symbol: "",
        unit: "",
        range: "as `resolution.samples_per_turn`",
        meaning: "Samples per turn while screening; every reported design is re-evaluated \
                  at the scene's resolution.",
        refused: &["search.screening.samples_per_turn=10"],
    },
    Field {
        key: "search.screening.closure_rel_tol",
        symbol: "",
        unit: "",
        range: "as `resolution.closure_rel_tol`",
        meaning: "Closure tolerance while screening.",
        refused: &["search.screening.closure_rel_tol=0"],
    },
    Field {
        key: "search.screening.newton_rel_tol",
        symbol: "",
        unit: "",
        range: "as `resolution.newton_rel_tol`",
        meaning: "Closure iteration stop while screening.",
        refused: &["search.screening.newton_rel_tol=1e-3"],
    },
    Field {
        key: "search.goals",
        symbol: "",
        unit: "",
        range: "goal names (below), each once",
        meaning: "Goals beyond feasibility; empty: `least_margin`. Two or more make a \
                  multi-objective search (docs/search.md).",
        refused: &[
            "search.goals=[\"fastest\"]",
            "search.goals=[\"module\",\"module\"]",
        ],
    },
    Field {
        key: "search.confirm_with_teeth",
        symbol: "",
        unit: "",
        range: "`true` or `false`; `true` needs `gear.module.teeth`",
        meaning: "Confirm the reported designs with their teeth cut and checked while the \
                  search screens with the scene's own module rule.",
        refused: &["search.confirm_with_teeth=true"],
    },
    Field {
        key: "tolerances.radius_mm.band",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of each pitch-curve control radius, independently (a Fourier curve's `c0`, an ellipse's semi-major axis): the cut gear's radial error. Default ±0.02 mm (ISO 1328-1 grade 8 runout of a gear this size, halved). Uniform on ± this value.",
        refused: &["tolerances.radius_mm={band=-1}"],
    },
    Field {
        key: "tolerances.radius_mm.sigma",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.radius_mm.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.radius_mm={sigma=-1}"],
    },
    Field {
        key: "tolerances.centre_distance_mm.band",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of the carrier's bores: each gear pair held this much further apart than its centre distance (the gears then mesh with backlash). Default ±0.03 mm (a bored housing's centre-distance tolerance). Uniform on ± this value.",
        refused: &["tolerances.centre_distance_mm={band=-1}"],
    },
    Field {
        key: "tolerances.centre_distance_mm.sigma",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.centre_distance_mm.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.centre_distance_mm={sigma=-1}"],
    },
    Field {
        key: "tolerances.phi0_deg.band",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of Φ0, the sun's installation angle. Default ±0.1° (a keyed sun: key play over the shaft radius). Uniform on ± this value.",
        refused: &["tolerances.phi0_deg={band=-1}"],
    },
    Field {
        key: "tolerances.phi0_deg.sigma",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.phi0_deg.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.phi0_deg={sigma=-1}"],
    },
    Field {
        key: "tolerances.beta0_deg.band",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of β0, the arm's angle on the planet shaft. Default ±0.2° (a keyed or splined arm). Uniform on ± this value.",
        refused: &["tolerances.beta0_deg={band=-1}"],
    },
    Field {
        key: "tolerances.beta0_deg.sigma",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.beta0_deg.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.beta0_deg={sigma=-1}"],
    },
    Field {
        key: "tolerances.gamma0_deg.band",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of γ0, the carrier's corner angle, one value per set of machined parts. Default ±0.05° (bore position 0.03 mm over the carrier's arm). Uniform on ± this value.",
        refused: &["tolerances.gamma0_deg={band=-1}"],
    },
    Field {
        key: "tolerances.gamma0_deg.sigma",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.gamma0_deg.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.gamma0_deg={sigma=-1}"],
    },
    Field {
        key: "tolerances.arm_length_mm.band",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of S, the arm length. Default ±0.5 mm (ISO 2768-1 medium, 120–400 mm). Uniform on ± this value.",
        refused: &["tolerances.arm_length_mm={band=-1}"],
    },
    Field {
        key: "tolerances.arm_length_mm.sigma",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.arm_length_mm.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.arm_length_mm={sigma=-1}"],
    },
    Field {
        key: "tolerances.pusher_offset_mm.band",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of H1, the pusher offset. Default ±0.3 mm (ISO 2768-1 medium, 30–120 mm). Uniform on ± this value.",
        refused: &["tolerances.pusher_offset_mm={band=-1}"],
    },
    Field {
        key: "tolerances.pusher_offset_mm.sigma",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.pusher_offset_mm.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.pusher_offset_mm={sigma=-1}"],
    },
    Field {
        key: "tolerances.tray_distance_mm.band",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of the tray surface's distance from the carrier axis. Default ±1 mm (the seedling box on its rails). Uniform on ± this value.",
        refused: &["tolerances.tray_distance_mm={band=-1}"],
    },
    Field {
        key: "tolerances.tray_distance_mm.sigma",
        symbol: "",
        unit: "mm",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.tray_distance_mm.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.tray_distance_mm={sigma=-1}"],
    },
    Field {
        key: "tolerances.tray_normal_deg.band",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "Tolerance of the tray normal's direction. Default ±0.5°. Uniform on ± this value.",
        refused: &["tolerances.tray_normal_deg={band=-1}"],
    },
    Field {
        key: "tolerances.tray_normal_deg.sigma",
        symbol: "",
        unit: "°",
        range: "0 to 1000; a group has a `band` or a `sigma`",
        meaning: "As `tolerances.tray_normal_deg.band`, as the standard deviation of a normal spread.",
        refused: &["tolerances.tray_normal_deg={sigma=-1}"],
    },
    Field {
        key: "tolerances.samples",
        symbol: "",
        unit: "",
        range: "1 to 65536",
        meaning: "Samples per design of the tolerance analysis and of the robust goals \
                  (scrambled Sobol points).",
        refused: &["tolerances.samples=0", "tolerances.samples=70000"],
    },
    Field {
        key: "tolerances.assemblies_per_part_set",
        symbol: "",
        unit: "",
        range: "1 to `tolerances.samples`",
        meaning: "How many samples share one set of machined parts (cut gears, carrier): \
                  each set is solved once and assembled this many times; 1: every sample \
                  its own parts.",
        refused: &[
            "tolerances.assemblies_per_part_set=0",
            "tolerances.assemblies_per_part_set=100",
        ],
    },
    Field {
        key: "tolerances.seed",
        symbol: "",
        unit: "",
        range: "0 to 2^64 − 1",
        meaning: "Seed of the scrambled Sobol points: every design meets the same \
                  deviations (common random numbers).",
        refused: &["tolerances.seed=-1"],
    },
];

#[cfg(test)]
mod tests {
    use super::symbol;

    #[test]
    fn symbols_of_paths() {
        assert_eq!(symbol("train.arm_length_mm").as_deref(), Some("S"));
        assert_eq!(symbol("gear.curve.radii_mm[0]").as_deref(), Some("r1"));
        assert_eq!(symbol("gear.curve.angles_deg[11]").as_deref(), Some("θ12"));
        assert_eq!(symbol("gear.curve.radii_mm").as_deref(), Some("r1 … r12"));
        assert_eq!(symbol("agronomy.tray_depth_mm"), None);
        assert_eq!(symbol("no.such"), None);
        assert_eq!(symbol("gear.curve.radii_mm[x]"), None);
    }
}
