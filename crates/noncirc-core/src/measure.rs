//! Measures: every named number noncirc reports about a design, with its unit. The
//! objectives' values, the events, the trajectory's sections (the anatomy), the
//! moving box's travel and the dynamics at working speed. `sweep --measure`, the search goals `min:NAME`/`max:NAME` and
//! Python read them by name.

use crate::error::{Error, Result};
use crate::objective_kind::ObjectiveKind;
use noncirc_search::nearest;
use serde::Serialize;

/// The four sections, in the order of motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Section {
    Removal,
    Conveying,
    Planting,
    Return,
}

impl Section {
    /// All four, in the order of motion.
    pub const ALL: [Section; 4] = [
        Section::Removal,
        Section::Conveying,
        Section::Planting,
        Section::Return,
    ];

    /// Stable snake-case name.
    pub fn name(self) -> &'static str {
        match self {
            Section::Removal => "removal",
            Section::Conveying => "conveying",
            Section::Planting => "planting",
            Section::Return => "return",
        }
    }

    /// What a person reads.
    pub fn label(self) -> &'static str {
        match self {
            Section::Removal => "seedling removal",
            Section::Conveying => "conveying",
            Section::Planting => "planting",
            Section::Return => "return",
        }
    }
}

/// A quantity measured on each trajectory section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SectionQuantity {
    /// Carrier span (deg).
    Span,
    /// Tip path length (mm).
    Length,
    /// Lowest tip height (mm).
    YMin,
    /// Highest tip height (mm).
    YMax,
}

impl SectionQuantity {
    const ALL: [SectionQuantity; 4] = [
        SectionQuantity::Span,
        SectionQuantity::Length,
        SectionQuantity::YMin,
        SectionQuantity::YMax,
    ];
}

/// A measure that is neither an objective nor a section's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    PickingCarrier,
    PlantingCarrier,
    PickingWindow,
    PickingTipSpeed,
    InTraySpeed,
    GearOverlap,
    PlantingGroundSpeed,
    PickingBranchGap,
    PlantingBranchGap,
    PickingHeight,
    PlantingHeight,
    ReturnHeight,
    PickingToPlantingHeight,
    LoopWidth,
    LoopHeight,
    BoxTravel,
}

impl Scalar {
    const ALL: [Scalar; 16] = [
        Scalar::PickingCarrier,
        Scalar::PlantingCarrier,
        Scalar::PickingWindow,
        Scalar::PickingTipSpeed,
        Scalar::InTraySpeed,
        Scalar::GearOverlap,
        Scalar::PlantingGroundSpeed,
        Scalar::PickingBranchGap,
        Scalar::PlantingBranchGap,
        Scalar::PickingHeight,
        Scalar::PlantingHeight,
        Scalar::ReturnHeight,
        Scalar::PickingToPlantingHeight,
        Scalar::LoopWidth,
        Scalar::LoopHeight,
        Scalar::BoxTravel,
    ];

    /// Name (with its unit) and description.
    fn describe(self) -> (&'static str, &'static str) {
        match self {
            Scalar::PickingCarrier => ("picking_carrier_deg", "carrier angle of arm I's picking"),
            Scalar::PlantingCarrier => {
                ("planting_carrier_deg", "carrier angle of arm I's planting")
            }
            Scalar::PickingWindow => (
                "picking_window_deg",
                "carrier span with the tip inside the tray",
            ),
            Scalar::PickingTipSpeed => (
                "picking_tip_speed_m_s",
                "tip speed relative to the seedling at picking",
            ),
            Scalar::InTraySpeed => (
                "in_tray_speed_m_s",
                "mean tip speed relative to the seedling while inside the tray",
            ),
            Scalar::GearOverlap => (
                "gear_overlap_mm",
                "deepest overlap of the pitch curves of different arm sets' gears (0: clear)",
            ),
            Scalar::PlantingGroundSpeed => (
                "planting_ground_speed_m_s",
                "tip speed in the ground frame at planting",
            ),
            Scalar::PickingBranchGap => (
                "picking_branch_gap_mm",
                "how far the next extreme along the tray normal falls short of picking",
            ),
            Scalar::PlantingBranchGap => (
                "planting_branch_gap_mm",
                "how much higher the next low point is than planting",
            ),
            Scalar::PickingHeight => ("picking_height_mm", "height of the picking point"),
            Scalar::PlantingHeight => ("planting_height_mm", "height of the planting point"),
            Scalar::ReturnHeight => (
                "return_height_mm",
                "height of the return section's highest point",
            ),
            Scalar::PickingToPlantingHeight => (
                "picking_to_planting_height_mm",
                "vertical distance from planting up to picking",
            ),
            Scalar::LoopWidth => (
                "loop_width_mm",
                "horizontal extent of the seedling-removal loop",
            ),
            Scalar::LoopHeight => (
                "loop_height_mm",
                "vertical extent of the seedling-removal loop",
            ),
            Scalar::BoxTravel => (
                "box_travel_mm",
                "moving-box travel while picking (transplanter scenes)",
            ),
        }
    }
}

/// A quantity of the dynamics at working speed (`noncirc dynamics`, docs/dynamics.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DynamicsQuantity {
    TorquePeak,
    TorqueRms,
    TorqueFluctuation,
    MeshForcePeak,
    IntermediateAxlePeak,
    PlanetAxlePeak,
    SunShaftPeak,
    CarrierBearingPeak,
    ShakingForcePeak,
    ShakingMomentPeak,
    SpeedFluctuation,
    FlywheelNeeded,
}

impl DynamicsQuantity {
    const ALL: [DynamicsQuantity; 12] = [
        DynamicsQuantity::TorquePeak,
        DynamicsQuantity::TorqueRms,
        DynamicsQuantity::TorqueFluctuation,
        DynamicsQuantity::MeshForcePeak,
        DynamicsQuantity::IntermediateAxlePeak,
        DynamicsQuantity::PlanetAxlePeak,
        DynamicsQuantity::SunShaftPeak,
        DynamicsQuantity::CarrierBearingPeak,
        DynamicsQuantity::ShakingForcePeak,
        DynamicsQuantity::ShakingMomentPeak,
        DynamicsQuantity::SpeedFluctuation,
        DynamicsQuantity::FlywheelNeeded,
    ];

    /// Name (with its unit), unit and description.
    fn describe(self) -> (&'static str, &'static str, &'static str) {
        match self {
            DynamicsQuantity::TorquePeak => (
                "input_torque_peak_nm",
                "N·m",
                "largest |torque| driving the carrier over a turn at working speed",
            ),
            DynamicsQuantity::TorqueRms => (
                "input_torque_rms_nm",
                "N·m",
                "RMS of the torque driving the carrier over a turn",
            ),
            DynamicsQuantity::TorqueFluctuation => (
                "input_torque_fluctuation",
                "",
                "(largest − least input torque) / mean (none where the mean is below 1 % of the RMS)",
            ),
            DynamicsQuantity::MeshForcePeak => (
                "mesh_force_peak_n",
                "N",
                "largest normal force at either mesh of an arm set",
            ),
            DynamicsQuantity::IntermediateAxlePeak => (
                "intermediate_axle_peak_n",
                "N",
                "largest force on an intermediate's axle",
            ),
            DynamicsQuantity::PlanetAxlePeak => (
                "planet_axle_peak_n",
                "N",
                "largest force on a planet's axle",
            ),
            DynamicsQuantity::SunShaftPeak => (
                "sun_shaft_peak_n",
                "N",
                "largest force of all arm sets on the sun's shaft",
            ),
            DynamicsQuantity::CarrierBearingPeak => (
                "carrier_bearing_peak_n",
                "N",
                "largest force on the carrier's bearing, its weight included",
            ),
            DynamicsQuantity::ShakingForcePeak => (
                "shaking_force_peak_n",
                "N",
                "largest inertial force the gearbox puts on the frame",
            ),
            DynamicsQuantity::ShakingMomentPeak => (
                "shaking_moment_peak_nm",
                "N·m",
                "largest inertial moment the gearbox puts on the frame",
            ),
            DynamicsQuantity::SpeedFluctuation => (
                "carrier_speed_fluctuation",
                "",
                "(largest − least carrier speed) / mean with a constant drive torque and the scene's flywheel",
            ),
            DynamicsQuantity::FlywheelNeeded => (
                "flywheel_needed_kg_m2",
                "kg·m²",
                "least flywheel on the carrier's axis that holds the speed fluctuation to dynamics.speed_fluctuation_allowed",
            ),
        }
    }
}

/// A quantity of a key pose's fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoseQuantity {
    /// Distance of the tip from the pose's position (mm).
    Position,
    /// Difference of the arm's attitude from the pose's (deg).
    Attitude,
    /// Difference of the carrier angle from the pose's (deg, wrapped to ±180).
    Carrier,
}

impl PoseQuantity {
    const ALL: [PoseQuantity; 3] = [
        PoseQuantity::Position,
        PoseQuantity::Attitude,
        PoseQuantity::Carrier,
    ];

    /// Name with its unit, and what it is.
    fn describe(self) -> (&'static str, &'static str) {
        match self {
            PoseQuantity::Position => ("position_mm", "tip's distance from the pose's position"),
            PoseQuantity::Attitude => ("attitude_deg", "arm attitude's difference from the pose's"),
            PoseQuantity::Carrier => ("carrier_deg", "carrier angle's difference from the pose's"),
        }
    }
}

/// A measure of the fit to the scene's target (`[target]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitMeasure {
    /// Hausdorff distance between the tip path and the target path (mm).
    PathHausdorff,
    /// RMS distance between them, each sampled by arc length (mm).
    PathRms,
    /// A pose's error: of pose `slot` (0-based, in `target.poses`), or the largest over the
    /// counting poses (`None`).
    Pose {
        slot: Option<u8>,
        quantity: PoseQuantity,
    },
}

impl FitMeasure {
    /// Every fit measure: the path's, the worst pose's, then each pose slot's.
    fn all() -> impl Iterator<Item = FitMeasure> {
        let slots = std::iter::once(None).chain((0..4u8).map(Some));
        [FitMeasure::PathHausdorff, FitMeasure::PathRms]
            .into_iter()
            .chain(slots.flat_map(|slot| {
                (PoseQuantity::ALL.iter()).map(move |&quantity| FitMeasure::Pose { slot, quantity })
            }))
    }

    /// Name (with its unit) and description.
    fn describe(self) -> (String, String) {
        match self {
            FitMeasure::PathHausdorff => (
                "path_hausdorff_mm".into(),
                "largest distance between the tip path and the target path (Hausdorff)".into(),
            ),
            FitMeasure::PathRms => (
                "path_rms_mm".into(),
                "RMS distance between the tip path and the target path, both by arc length".into(),
            ),
            FitMeasure::Pose { slot, quantity } => {
                let (name, what) = quantity.describe();
                match slot {
                    None => (
                        format!("pose_{name}"),
                        format!("largest over the counting key poses: {what}"),
                    ),
                    Some(k) => (
                        format!("pose{}_{name}", k + 1),
                        format!("key pose {} (target.poses[{k}]): {what}", k + 1),
                    ),
                }
            }
        }
    }
}

/// What a measure costs beyond the evaluation that it is read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeasureCost {
    /// Read from the evaluation's objectives, events or box: nothing more.
    Read,
    /// Needs the trajectory's sections: about one more evaluation's time.
    Anatomy,
    /// Places every gear's pitch curve at every node to check the gearbox
    /// (`gearbox::gear_sets_overlap`): several evaluations' time.
    Gearbox,
    /// Read from the fit to the scene's target, which an evaluation computes when the
    /// scene has one (about a third of an evaluation's time); none without.
    Target,
    /// Needs the dynamics at working speed (`dynamics.samples_per_turn` carrier angles):
    /// about ten evaluations' time at 720.
    Dynamics,
    /// Needs the teeth cut and their stresses (the objectives `bending_safety`,
    /// `contact_safety`): tenths of a second a design, unless the scene's objectives
    /// already computed them.
    Strength,
}

/// A named measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    Objective(ObjectiveKind),
    Section(Section, SectionQuantity),
    Scalar(Scalar),
    Fit(FitMeasure),
    Dynamics(DynamicsQuantity),
}

impl Measure {
    /// Every measure, objectives first, then the events and shape, then the sections, then
    /// the fit to a target, then the dynamics.
    pub fn all() -> Vec<Measure> {
        let objectives = ObjectiveKind::ALL.iter().map(|&k| Measure::Objective(k));
        let scalars = Scalar::ALL.iter().map(|&s| Measure::Scalar(s));
        let sections = Section::ALL.iter().flat_map(|&s| {
            SectionQuantity::ALL
                .iter()
                .map(move |&q| Measure::Section(s, q))
        });
        let fits = FitMeasure::all().map(Measure::Fit);
        let dynamics = DynamicsQuantity::ALL.iter().map(|&q| Measure::Dynamics(q));
        objectives
            .chain(scalars)
            .chain(sections)
            .chain(fits)
            .chain(dynamics)
            .collect()
    }

    /// Stable name, ending in its unit (`loop_height_mm`); an objective's is its own name.
    pub fn name(self) -> String {
        match self {
            Measure::Objective(k) => k.name().to_string(),
            Measure::Scalar(s) => s.describe().0.to_string(),
            Measure::Fit(m) => m.describe().0,
            Measure::Dynamics(q) => q.describe().0.to_string(),
            Measure::Section(s, q) => format!(
                "{}_{}",
                s.name(),
                match q {
                    SectionQuantity::Span => "span_deg",
                    SectionQuantity::Length => "length_mm",
                    SectionQuantity::YMin => "y_min_mm",
                    SectionQuantity::YMax => "y_max_mm",
                }
            ),
        }
    }

    /// Unit: `mm`, `deg`, `m/s`, `N`, `N·m`, or "" for a ratio.
    pub fn unit(self) -> &'static str {
        match self {
            Measure::Objective(k) => k.unit(),
            Measure::Dynamics(q) => q.describe().1,
            Measure::Section(_, SectionQuantity::Span) => "deg",
            Measure::Section(..) => "mm",
            Measure::Scalar(
                Scalar::PickingTipSpeed | Scalar::InTraySpeed | Scalar::PlantingGroundSpeed,
            ) => "m/s",
            Measure::Scalar(
                Scalar::PickingCarrier | Scalar::PlantingCarrier | Scalar::PickingWindow,
            ) => "deg",
            Measure::Scalar(_) => "mm",
            Measure::Fit(FitMeasure::Pose {
                quantity: PoseQuantity::Attitude | PoseQuantity::Carrier,
                ..
            }) => "deg",
            Measure::Fit(_) => "mm",
        }
    }

    /// What it is, for a person.
    pub fn description(self) -> String {
        match self {
            Measure::Objective(k) => format!("objective: {}", k.label()),
            Measure::Scalar(s) => s.describe().1.to_string(),
            Measure::Fit(m) => format!("fit: {}", m.describe().1),
            Measure::Dynamics(q) => format!("dynamics: {}", q.describe().2),
            Measure::Section(s, q) => format!(
                "{} section: {}",
                s.label(),
                match q {
                    SectionQuantity::Span => "carrier span",
                    SectionQuantity::Length => "tip path length",
                    SectionQuantity::YMin => "lowest tip height",
                    SectionQuantity::YMax => "highest tip height",
                }
            ),
        }
    }

    /// The measure called `name`, or an error naming the nearest ones.
    pub fn parse(name: &str) -> Result<Measure> {
        let all = Measure::all();
        if let Some(m) = all.iter().find(|m| m.name() == name) {
            return Ok(*m);
        }
        let names: Vec<String> = all.iter().map(|m| m.name()).collect();
        Err(Error::UnknownName {
            what: "measure",
            name: name.to_string(),
            nearest: nearest(name, &names),
        })
    }

    /// What the value costs beyond the evaluation itself.
    pub fn cost(self) -> MeasureCost {
        match self {
            Measure::Section(..)
            | Measure::Scalar(
                Scalar::PlantingGroundSpeed
                | Scalar::InTraySpeed
                | Scalar::ReturnHeight
                | Scalar::LoopWidth
                | Scalar::LoopHeight,
            ) => MeasureCost::Anatomy,
            Measure::Scalar(Scalar::GearOverlap) => MeasureCost::Gearbox,
            Measure::Fit(_) => MeasureCost::Target,
            Measure::Dynamics(_) => MeasureCost::Dynamics,
            Measure::Objective(k) if k.needs_strength() => MeasureCost::Strength,
            _ => MeasureCost::Read,
        }
    }

    /// Whether the value needs the trajectory's sections (`Evaluation::anatomy`).
    pub fn needs_anatomy(self) -> bool {
        self.cost() == MeasureCost::Anatomy
    }

    /// The measures a batch returns by default: every one besides the objectives that is
    /// read from the evaluation at no cost (the events' carrier angles, picking window,
    /// tip speed, branch gaps and heights, the box's travel); not the fit's, which only a
    /// scene with a target has.
    pub fn batch_default() -> Vec<Measure> {
        (Measure::all().into_iter())
            .filter(|m| !matches!(m, Measure::Objective(_)) && m.cost() == MeasureCost::Read)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_parse_back() {
        let all = Measure::all();
        for m in &all {
            assert_eq!(Measure::parse(&m.name()).unwrap(), *m);
        }
        let mut names: Vec<String> = all.iter().map(|m| m.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), all.len());
    }

    #[test]
    fn unknown_name_suggests_the_nearest() {
        let err = Measure::parse("loop_hieght_mm").unwrap_err();
        match &err {
            Error::UnknownName { nearest, .. } => assert_eq!(nearest[0], "loop_height_mm"),
            other => panic!("{other:?}"),
        }
        assert!(err.to_string().contains("loop_height_mm"));
    }
}
