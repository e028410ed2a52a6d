//! Reports: what the CLI prints, as serialisable structs and readable tables.

use noncirc_core::GearSummary;
use noncirc_core::SectionMeasures;
use noncirc_core::{BoxReport, FitReport};
use noncirc_core::{
    ConstraintValue, Evaluation, Evaluator, GearPair, ObjectiveValue, Result, Scene, SceneKind,
};
use noncirc_core::{Events, PickingCheck};
use noncirc_core::{Measure, MeasureCost, Measured};
use serde::Serialize;

mod finite;
mod tables;
pub use tables::{
    box_table, keys_in_scene_order, natural_cmp, objective_table, scene_order, summary_table,
    sweep_table, table,
};

/// Everything `noncirc gear` reports about a gear pair.
#[derive(Debug, Clone, Serialize)]
pub struct GearReport {
    pub curve_kind: String,
    pub samples_per_turn: usize,
    pub centre_distance_mm: f64,
    pub centre_distance_error_estimate_mm: f64,
    pub closure_iterations: usize,
    pub perimeter_mm: f64,
    pub module_max_mm: f64,
    pub teeth: u32,
    pub module_limit_mm: f64,
    pub min_convex_radius_mm: f64,
    pub min_concave_radius_mm: Option<f64>,
    pub rho_min_mm: f64,
    pub rho_max_mm: f64,
    pub ratio_min: f64,
    pub ratio_max: f64,
}

impl GearReport {
    /// Solves the scene's gear pair and gathers the report: a moving-box scene's pair is
    /// the box's elliptical gears (sized by its module and tooth count), any other scene's
    /// is its pitch curve's.
    pub fn from_scene(scene: &Scene) -> Result<(Self, GearPair)> {
        let spec = match scene.kind {
            SceneKind::MovingBox => {
                let b = noncirc_core::evaluate_box(&scene.moving_box, None, &scene.resolution)?;
                noncirc_core::CurveSpec::Ellipse {
                    semi_major_mm: b.semi_major_mm,
                    eccentricity: b.eccentricity,
                }
            }
            _ => scene.gear.curve.clone(),
        };
        let curve = spec.build()?;
        let pair = GearPair::solve(curve, scene.resolution)?;
        let module = pair.module(&scene.gear.module);
        let a = pair.centre_distance();
        // The curve's own extremes (exact for the spline), not the sample extremes.
        let (rmin, rmax) = pair.radius_range();
        let kind = serde_json::to_value(&spec)
            .ok()
            .and_then(|v| v.get("kind").and_then(|k| k.as_str().map(String::from)))
            .unwrap_or_default();
        let report = GearReport {
            curve_kind: kind,
            samples_per_turn: scene.resolution.samples_per_turn,
            centre_distance_mm: a,
            centre_distance_error_estimate_mm: pair.closure().error_estimate,
            closure_iterations: pair.closure().iterations,
            perimeter_mm: pair.perimeter(),
            module_max_mm: module.module_max_mm,
            teeth: module.teeth,
            module_limit_mm: module.module_limit_mm,
            min_convex_radius_mm: module.min_convex_radius_mm,
            min_concave_radius_mm: module.min_concave_radius_mm,
            rho_min_mm: rmin,
            rho_max_mm: rmax,
            ratio_min: (a - rmax) / rmax,
            ratio_max: (a - rmin) / rmin,
        };
        Ok((report, pair))
    }

    /// A readable two-column table.
    pub fn table(&self) -> String {
        let concave = self
            .min_concave_radius_mm
            .map_or("none (all convex)".to_string(), |r| format!("{r:.3} mm"));
        let rows = [
            (
                "pitch curve",
                format!(
                    "{} ({} samples/turn)",
                    self.curve_kind, self.samples_per_turn
                ),
            ),
            (
                "centre distance",
                format!(
                    "{:.6} mm  (± {:.1e} mm)",
                    self.centre_distance_mm, self.centre_distance_error_estimate_mm
                ),
            ),
            (
                "perimeter (both gears)",
                format!("{:.4} mm", self.perimeter_mm),
            ),
            (
                "pitch radius",
                format!("{:.3} .. {:.3} mm", self.rho_min_mm, self.rho_max_mm),
            ),
            (
                "ratio i12",
                format!("{:.4} .. {:.4}", self.ratio_min, self.ratio_max),
            ),
            (
                "least convex R_c",
                format!("{:.3} mm", self.min_convex_radius_mm),
            ),
            ("least concave |R_c|", concave),
            ("module bound", format!("{:.4} mm", self.module_limit_mm)),
            (
                "largest module",
                format!("{:.4} mm with {} teeth", self.module_max_mm, self.teeth),
            ),
        ];
        table(&rows)
    }
}

/// One objective or search constraint as reported: `{name, label, value, unit, lower, upper,
/// violation, margin}` (the unit's; `violation` 0 when met, `margin` negative when missed).
/// A constraint's name is its measure's, its label as written (`picking_height_mm <= -90`).
#[derive(Debug, Clone, Serialize)]
pub struct RequirementRow {
    pub name: String,
    pub label: String,
    pub value: f64,
    pub unit: &'static str,
    pub lower: Option<f64>,
    pub upper: Option<f64>,
    pub violation: f64,
    pub margin: f64,
}

impl From<&ObjectiveValue> for RequirementRow {
    fn from(v: &ObjectiveValue) -> Self {
        Self {
            name: v.kind.name().to_string(),
            label: v.kind.label().to_string(),
            value: v.value,
            unit: v.kind.unit(),
            lower: v.lower,
            upper: v.upper,
            violation: v.violation,
            margin: v.margin,
        }
    }
}

impl From<&ConstraintValue> for RequirementRow {
    fn from(v: &ConstraintValue) -> Self {
        let c = v.constraint;
        let bound = Some(c.bound);
        Self {
            name: c.measure.name(),
            label: c.text(),
            value: v.value,
            unit: c.measure.unit(),
            lower: bound.filter(|_| !c.at_most),
            upper: bound.filter(|_| c.at_most),
            violation: v.violation,
            margin: v.margin,
        }
    }
}

/// The evaluation's objectives, then its search constraints, as reported.
pub fn requirement_rows(eval: &Evaluation) -> Vec<RequirementRow> {
    (eval.objectives.iter().map(RequirementRow::from))
        .chain(eval.constraints.iter().map(RequirementRow::from))
        .collect()
}

/// One arm's picking and planting carrier angles (deg; paper Table 1).
#[derive(Debug, Clone, Serialize)]
pub struct ArmEvents {
    pub arm: &'static str,
    pub picking_carrier_deg: f64,
    pub planting_carrier_deg: f64,
}

/// Located events of arm I (degrees), whether a machine can pick there, and the events
/// of all three arms.
#[derive(Debug, Clone, Serialize)]
pub struct EventsRow {
    pub picking_carrier_deg: f64,
    pub planting_carrier_deg: f64,
    pub picking_tip_mm: [f64; 2],
    pub planting_tip_mm: [f64; 2],
    pub picking_attitude_deg: f64,
    pub planting_attitude_deg: f64,
    pub picking_window_deg: [f64; 2],
    pub picking_tip_speed_m_s: f64,
    /// The picking conditions (mm each, positive when met).
    pub picking_check: PickingCheck,
    /// Why a machine cannot pick there (`None` when it can).
    pub picking_refused: Option<String>,
    /// Margins before the events move to another branch (mm; `None`: a single extreme).
    pub picking_branch_gap_mm: Option<f64>,
    pub planting_branch_gap_mm: Option<f64>,
    /// Every arm (I, II, III with three): arm k's events are arm I's delayed by
    /// k·360°/arms of carrier.
    pub arms: Vec<ArmEvents>,
}

impl EventsRow {
    /// The events of a train of `arms` arm sets.
    fn new(e: &Events, arms: usize) -> Self {
        let lag = 360.0 / arms as f64;
        let arm = |k: usize| ArmEvents {
            arm: noncirc_core::ARM_NAMES[k],
            picking_carrier_deg: (e.picking.carrier_rad.to_degrees() + lag * k as f64)
                .rem_euclid(360.0),
            planting_carrier_deg: (e.planting.carrier_rad.to_degrees() + lag * k as f64)
                .rem_euclid(360.0),
        };
        Self {
            picking_carrier_deg: e.picking.carrier_rad.to_degrees(),
            planting_carrier_deg: e.planting.carrier_rad.to_degrees(),
            picking_tip_mm: e.picking.tip_mm.into(),
            planting_tip_mm: e.planting.tip_mm.into(),
            picking_attitude_deg: e.picking.attitude_deg,
            planting_attitude_deg: e.planting.attitude_deg,
            picking_window_deg: [
                e.picking_window_rad[0].to_degrees(),
                e.picking_window_rad[1].to_degrees(),
            ],
            picking_tip_speed_m_s: e.picking_tip_speed_m_s,
            picking_check: e.check,
            picking_refused: e.check.failures(),
            picking_branch_gap_mm: e.picking_branch_gap_mm,
            planting_branch_gap_mm: e.planting_branch_gap_mm,
            arms: (0..arms).map(arm).collect(),
        }
    }
}

/// One measure's value with its unit.
#[derive(Debug, Clone, Serialize)]
pub struct MeasureRow {
    pub name: String,
    pub value: f64,
    pub unit: &'static str,
    pub description: String,
}

/// Every measure an evaluation has, in `Measure::all()` order: the teeth's strength only
/// where the scene's objectives computed it (cutting the teeth costs tenths of a second).
pub fn measure_rows(on: &Measured) -> Vec<MeasureRow> {
    Measure::all()
        .into_iter()
        .filter(|m| m.cost() != MeasureCost::Strength || on.eval.strength.is_some())
        .filter_map(|m| {
            m.value(on).map(|value| MeasureRow {
                name: m.name(),
                value,
                unit: m.unit(),
                description: m.description(),
            })
        })
        .collect()
}

/// The trajectory-shape measures, the pass through the tray and the gearbox, as the
/// evaluate table prints them (JSON has every measure).
const SHAPE: [&str; 9] = [
    "loop_width_mm",
    "loop_height_mm",
    "picking_height_mm",
    "planting_height_mm",
    "return_height_mm",
    "picking_to_planting_height_mm",
    "planting_ground_speed_m_s",
    "in_tray_speed_m_s",
    "gear_overlap_mm",
];

/// Everything `noncirc evaluate` reports, for any scene kind.
#[derive(Debug, Clone, Serialize)]
pub struct EvaluationReport {
    pub scene: String,
    pub kind: SceneKind,
    pub samples_per_turn: usize,
    pub centre_distance_mm: Option<f64>,
    pub trajectory_height_mm: Option<f64>,
    pub feasible: bool,
    pub total_violation: f64,
    pub events: Option<EventsRow>,
    /// The trajectory's sections in the order of motion (three-arm scenes).
    pub sections: Option<[SectionMeasures; 4]>,
    pub objectives: Vec<RequirementRow>,
    /// The scene's `search.constraints`, each on its measure (empty without).
    pub constraints: Vec<RequirementRow>,
    /// Every measure with its unit: objectives, events, shape, sections, box travel.
    pub measures: Vec<MeasureRow>,
    pub gear: Option<GearSummary>,
    pub moving_box: Option<BoxReport>,
    /// The fit to the scene's target, with the target's tolerances (a scene with a
    /// `[target]`).
    pub fit: Option<FitRow>,
    /// Why the objectives `bending_safety` and `contact_safety` have no strength to read
    /// (the teeth cannot be cut); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strength_unavailable: Option<String>,
}

/// `v` with its sign and `decimals` decimals, `+` where it rounds to zero (never `-0.00`).
pub(crate) fn signed_fixed(v: f64, decimals: usize) -> String {
    let text = format!("{v:+.decimals$}");
    match text.strip_prefix('-') {
        Some(digits) if digits.chars().all(|c| c == '0' || c == '.') => format!("+{digits}"),
        _ => text,
    }
}

/// The fit to the target as `noncirc evaluate` reports it: the measures and the
/// tolerances they are held to.
#[derive(Debug, Clone, Serialize)]
pub struct FitRow {
    /// The path's tolerance (mm).
    pub tolerance_mm: f64,
    /// Whether the path counts.
    pub path_counts: bool,
    #[serde(flatten)]
    pub report: FitReport,
}

impl FitRow {
    /// The fit's lines: the path's distances, then a row per pose.
    pub fn table(&self) -> String {
        let r = &self.report;
        let mut out = format!(
            "
fit to the target: path Hausdorff {:.3} mm (at ({:.1}, {:.1}) mm), RMS {:.3} mm, tolerance {:.3} mm{}; cost {:.4}: {}\n",
            r.path_hausdorff_mm,
            r.hausdorff_at_mm.x,
            r.hausdorff_at_mm.y,
            r.path_rms_mm,
            self.tolerance_mm,
            if self.path_counts { "" } else { " (reported, not counted)" },
            r.cost,
            if r.met { "met" } else { "NOT met" }
        );
        if !r.poses.is_empty() {
            // Each heading right over its column (the rows' widths below).
            out += &format!(
                "{:<12} {:>9} {:^20} {:>8}  {:>10} {:>9} {:>9}\n",
                "pose", "carrier", "tip (mm)", "attitude", "position", "Δattitude", "Δcarrier"
            );
            for p in &r.poses {
                let opt = |v: Option<f64>| v.map_or("—".into(), |v| signed_fixed(v, 3) + "°");
                out += &format!(
                    "{:<12} {:8.2}° ({:8.2}, {:8.2}) {:7.2}°  {:7.3} mm {:>9} {:>9}  {}{}\n",
                    p.name,
                    p.carrier_deg,
                    p.tip_mm.x,
                    p.tip_mm.y,
                    p.attitude_deg,
                    p.position_error_mm,
                    opt(p.attitude_error_deg),
                    opt(p.carrier_error_deg),
                    if p.met { "met" } else { "NOT met" },
                    if p.counts { "" } else { " (not counted)" }
                );
            }
        }
        out
    }
}

impl EvaluationReport {
    /// Evaluates the scene (only the stages it needs) and gathers the report.
    pub fn from_scene(scene: &Scene) -> Result<(Self, Evaluation)> {
        let eval = Evaluator::new().evaluate(scene)?;
        Ok((Self::new(scene, &eval), eval))
    }

    /// The report of an evaluation already made.
    pub fn new(scene: &Scene, eval: &Evaluation) -> Self {
        let anatomy = eval.anatomy(&scene.agronomy);
        Self {
            scene: scene.name.clone(),
            kind: scene.kind,
            samples_per_turn: eval.resolution.samples_per_turn,
            centre_distance_mm: eval.centre_distance_mm,
            trajectory_height_mm: eval.events.as_ref().map(|e| e.y_max_mm - e.y_min_mm),
            feasible: eval.total_violation() == 0.0,
            total_violation: eval.total_violation(),
            events: (eval.events.as_ref())
                .map(|e| EventsRow::new(e, eval.kinematics.as_ref().map_or(3, |k| k.arms()))),
            sections: anatomy.as_ref().map(|a| a.sections),
            objectives: eval.objectives.iter().map(RequirementRow::from).collect(),
            constraints: eval.constraints.iter().map(RequirementRow::from).collect(),
            measures: measure_rows(&Measured::with_anatomy(eval, scene, anatomy)),
            gear: eval.gear,
            moving_box: eval.moving_box,
            fit: eval
                .fit
                .clone()
                .zip(scene.target.as_ref())
                .map(|(report, t)| FitRow {
                    tolerance_mm: t.tolerance_mm,
                    path_counts: t.counts,
                    report,
                }),
            strength_unavailable: eval.strength_unavailable.clone(),
        }
    }

    /// The objectives as gauges, like the paper's progress bars, then the events.
    pub fn table(&self) -> String {
        let mut out = format!(
            "scene {} ({}) — {} samples/turn",
            self.scene,
            self.kind.name(),
            self.samples_per_turn
        );
        if let Some(a) = self.centre_distance_mm {
            out += &format!(", centre distance {a:.4} mm");
        }
        out += "\n\n";
        if self.events.is_none() && self.objectives.is_empty() {
            out += &format!(
                "this {} scene has no mechanism: no objectives or events to report{}\n",
                self.kind.name(),
                if self.moving_box.is_some() {
                    "; its moving box:"
                } else {
                    ""
                }
            );
        }
        out += &objective_table(&self.objectives);
        if !self.constraints.is_empty() {
            out += "search constraints:\n";
            out += &objective_table(&self.constraints);
        }
        if let Some(why) = &self.strength_unavailable {
            out += &format!("  no tooth strength: {why}\n");
        }
        if let Some(e) = &self.events {
            out += &format!(
                "\npicking  at carrier {:7.2}°  tip ({:8.2}, {:8.2}) mm  attitude {:6.2}°  window {:.1}°..{:.1}°  tip speed {:.3} m/s\n",
                e.picking_carrier_deg,
                e.picking_tip_mm[0],
                e.picking_tip_mm[1],
                e.picking_attitude_deg,
                e.picking_window_deg[0],
                e.picking_window_deg[1],
                e.picking_tip_speed_m_s
            );
            out += &format!(
                "planting at carrier {:7.2}°  tip ({:8.2}, {:8.2}) mm  attitude {:6.2}°\n",
                e.planting_carrier_deg,
                e.planting_tip_mm[0],
                e.planting_tip_mm[1],
                e.planting_attitude_deg
            );
            if let Some(why) = &e.picking_refused {
                out += &format!("  a machine cannot pick there: {why}\n");
            }
            if e.picking_check.reach_mm.is_none() {
                out += &format!(
                    "tray surface placed at this design's picking point, {:.3} mm from the \
                     carrier axis (`noncirc robustness` bolts it there and counts the tip's \
                     reach into the pots too: its picking_admissible may read less)\n",
                    e.picking_check.tray_surface_mm
                );
            }
            let gap =
                |g: Option<f64>| g.map_or("none (one extreme)".into(), |g| format!("{g:.2} mm"));
            out += &format!(
                "branch margins: picking {}, planting {}\n",
                gap(e.picking_branch_gap_mm),
                gap(e.planting_branch_gap_mm)
            );
            out += "arm      picks at  plants at (carrier)\n";
            for a in &e.arms {
                out += &format!(
                    "{:<6} {:9.2}° {:9.2}°\n",
                    a.arm, a.picking_carrier_deg, a.planting_carrier_deg
                );
            }
        }
        if let Some(sections) = &self.sections {
            out += "\nsection            carrier          span     path    lowest   highest\n";
            for s in sections {
                out += &format!(
                    "{:<16} {:7.2}°..{:7.2}° {:6.2}° {:7.1} mm {:7.1} mm {:7.1} mm\n",
                    s.section.label(),
                    s.carrier_deg[0],
                    s.carrier_deg[1],
                    s.span_deg,
                    s.length_mm,
                    s.y_min_mm,
                    s.y_max_mm
                );
            }
            out += "\n";
            for m in self
                .measures
                .iter()
                .filter(|m| SHAPE.contains(&m.name.as_str()))
            {
                out += &format!("{:<32} {:9.3} {}\n", m.description, m.value, m.unit);
            }
        }
        if let Some(b) = &self.moving_box {
            out += "\n";
            out += &box_table(b);
        }
        if let Some(f) = &self.fit {
            out += &f.table();
        }
        if !self.objectives.is_empty() {
            out += &format!(
                "\n{}: total violation {:.3}\n",
                if self.feasible {
                    "FEASIBLE"
                } else {
                    "not feasible"
                },
                self.total_violation
            );
        }
        out
    }
}

/// Checks that every number in a report is finite: a NaN or infinity in an output is a
/// bug (an input check missed it), refused rather than printed. Absent values (`None`)
/// are not numbers and pass. Returns the first bad number's path.
pub fn check_finite(report: &impl Serialize) -> crate::Result<()> {
    match finite::first_non_finite(report) {
        None => Ok(()),
        Some((path, x)) => Err(noncirc_core::Error::NonFinite {
            name: format!("output '{path}' (a bug: please report the scene)"),
            value: x,
        }
        .into()),
    }
}

#[cfg(test)]
mod tests {
    use super::check_finite;

    #[derive(serde::Serialize)]
    struct Inner {
        speeds: Vec<f64>,
        absent: Option<f64>,
    }

    #[derive(serde::Serialize)]
    struct Report {
        value: f64,
        inner: Inner,
    }

    #[test]
    fn a_non_finite_output_is_refused_by_its_path() {
        let mut r = Report {
            value: 1.0,
            inner: Inner {
                speeds: vec![1.0, 2.0],
                absent: None,
            },
        };
        check_finite(&r).unwrap();
        r.inner.speeds[1] = f64::INFINITY;
        let e = check_finite(&r).unwrap_err().to_string();
        assert!(
            e.contains("output 'inner.speeds[1]'") && e.contains("inf"),
            "{e}"
        );
        // A u64 beyond TOML's integers is a number like any other.
        let big = (u64::MAX, r.inner.speeds.clone());
        assert!(super::finite::first_non_finite(&big).is_some());
        r.inner.speeds[1] = 0.0;
        check_finite(&(u64::MAX, &r)).unwrap();
        let mut map = std::collections::BTreeMap::new();
        map.insert("r1".to_string(), f64::NEG_INFINITY);
        let e = check_finite(&Some(map)).unwrap_err().to_string();
        assert!(e.contains("output 'r1'"), "{e}");
        r.value = f64::NAN;
        assert!(check_finite(&r)
            .unwrap_err()
            .to_string()
            .contains("'value'"));
    }
}

#[cfg(test)]
mod names {
    use super::EvaluationReport;
    use noncirc_core::{Evaluator, Measure, Measured, Scalar, Scene};

    /// The report's events are written by the measures' names where they report the
    /// same number: a measure is read by one name wherever it is printed.
    #[test]
    fn events_carry_the_measures_names_and_values() {
        let scene = Scene::default();
        let eval = Evaluator::new().evaluate(&scene).unwrap();
        let report = serde_json::to_value(EvaluationReport::new(&scene, &eval)).unwrap();
        let events = &report["events"];
        for s in [
            Scalar::PickingCarrier,
            Scalar::PlantingCarrier,
            Scalar::PickingTipSpeed,
            Scalar::PickingBranchGap,
            Scalar::PlantingBranchGap,
        ] {
            let m = Measure::Scalar(s);
            let value = m.value(&Measured::new(&eval, &scene)).unwrap();
            let printed = events[m.name()].as_f64();
            assert_eq!(printed, Some(value), "{}", m.name());
            for arm in events["arms"].as_array().unwrap() {
                if matches!(s, Scalar::PickingCarrier | Scalar::PlantingCarrier) {
                    assert!(arm[m.name()].is_f64(), "{}", m.name());
                }
            }
        }
    }

    #[test]
    fn a_value_that_rounds_to_zero_has_no_minus_sign() {
        use super::signed_fixed;
        assert_eq!(signed_fixed(-0.001, 2), "+0.00");
        assert_eq!(signed_fixed(-0.0, 3), "+0.000");
        assert_eq!(signed_fixed(-0.006, 2), "-0.01");
        assert_eq!(signed_fixed(2.5, 1), "+2.5");
    }
}
