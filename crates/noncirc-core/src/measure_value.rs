//! A measure's value for an evaluation: read from its objectives, events, moving box or
//! gearbox, or from what [`Measured`] computes on demand (the trajectory's sections, the
//! dynamics at working speed, the teeth's strength), or from the fit to a target.

use crate::anatomy::Anatomy;
use crate::dynamics::{scene_dynamics, Dynamics};
use crate::evaluation::Evaluation;
use crate::measure::{DynamicsQuantity, Measure, Scalar, SectionQuantity};
use crate::objective_kind::ObjectiveKind;
use crate::scene::Scene;
use crate::strength::{cut_train, strength, Strength};
use std::cell::OnceCell;

/// An evaluation of a scene with what measures read beyond it, each computed once, when a
/// measure first asks: the trajectory's sections, the dynamics at working speed, the
/// teeth's strength (taken from the evaluation when its objectives computed it).
pub struct Measured<'a> {
    pub eval: &'a Evaluation,
    pub scene: &'a Scene,
    anatomy: OnceCell<Option<Anatomy>>,
    dynamics: OnceCell<Option<Dynamics>>,
    strength: OnceCell<Option<Strength>>,
}

impl<'a> Measured<'a> {
    /// `eval`, an evaluation of `scene`, with nothing computed beyond it yet.
    pub fn new(eval: &'a Evaluation, scene: &'a Scene) -> Self {
        Self {
            eval,
            scene,
            anatomy: OnceCell::new(),
            dynamics: OnceCell::new(),
            strength: OnceCell::new(),
        }
    }

    /// As [`Measured::new`], with the sections the caller already has.
    pub fn with_anatomy(eval: &'a Evaluation, scene: &'a Scene, anatomy: Option<Anatomy>) -> Self {
        let measured = Self::new(eval, scene);
        let _ = measured.anatomy.set(anatomy);
        measured
    }

    /// The trajectory's sections (`None` without a motion).
    pub fn anatomy(&self) -> Option<&Anatomy> {
        (self.anatomy)
            .get_or_init(|| self.eval.anatomy(&self.scene.agronomy))
            .as_ref()
    }

    /// The dynamics at the scene's working speed (`None` without a motion, or where the
    /// model refuses it).
    pub fn dynamics(&self) -> Option<&Dynamics> {
        (self.dynamics)
            .get_or_init(|| {
                let (kin, events) = (self.eval.kinematics.as_ref()?, self.eval.events.as_ref()?);
                scene_dynamics(kin, events, self.scene).ok()
            })
            .as_ref()
    }

    /// The teeth's strength (`None` where the teeth cannot be cut).
    pub fn strength(&self) -> Option<&Strength> {
        if let Some(s) = &self.eval.strength {
            return Some(s);
        }
        (self.strength)
            .get_or_init(|| {
                let pairs = cut_train(self.eval.kinematics.as_ref()?, self.scene).ok()?;
                strength(self.dynamics()?, &pairs, &self.scene.dynamics).ok()
            })
            .as_ref()
    }
}

impl Measure {
    /// The value for an evaluation; `None` where the scene does not compute it (no events,
    /// no moving box, no runner-up extreme, teeth that cannot be cut).
    pub fn value(self, on: &Measured) -> Option<f64> {
        let eval = on.eval;
        let ev = eval.events.as_ref();
        match self {
            Measure::Objective(k) => match eval.objective(k) {
                Some(o) => Some(o.value),
                None => match k {
                    ObjectiveKind::BendingSafety => on.strength().map(|s| s.bending_safety_min),
                    ObjectiveKind::ContactSafety => on.strength().map(|s| s.contact_safety_min),
                    _ => None,
                },
            },
            Measure::Fit(m) => eval.fit.as_ref()?.value(m),
            Measure::Section(s, q) => on.anatomy().map(|a| {
                let m = a.section(s);
                match q {
                    SectionQuantity::Span => m.span_deg,
                    SectionQuantity::Length => m.length_mm,
                    SectionQuantity::YMin => m.y_min_mm,
                    SectionQuantity::YMax => m.y_max_mm,
                }
            }),
            Measure::Dynamics(q) => {
                let d = on.dynamics()?;
                let s = &d.summary;
                match q {
                    DynamicsQuantity::TorquePeak => Some(s.torque_peak_nm),
                    DynamicsQuantity::TorqueRms => Some(s.torque_rms_nm),
                    DynamicsQuantity::TorqueFluctuation => s.torque_fluctuation,
                    DynamicsQuantity::MeshForcePeak => {
                        Some(s.mesh_force_peak_n[0].max(s.mesh_force_peak_n[1]))
                    }
                    DynamicsQuantity::IntermediateAxlePeak => Some(s.intermediate_axle_peak_n),
                    DynamicsQuantity::PlanetAxlePeak => Some(s.planet_axle_peak_n),
                    DynamicsQuantity::SunShaftPeak => Some(s.sun_shaft_peak_n),
                    DynamicsQuantity::CarrierBearingPeak => Some(s.carrier_bearing_peak_n),
                    DynamicsQuantity::ShakingForcePeak => Some(s.shaking_force_peak_n),
                    DynamicsQuantity::ShakingMomentPeak => Some(s.shaking_moment_peak_nm),
                    DynamicsQuantity::SpeedFluctuation => Some(
                        d.speed_with(on.scene.dynamics.flywheel_inertia_kg_m2)
                            .coefficient,
                    ),
                    DynamicsQuantity::FlywheelNeeded => {
                        Some(d.flywheel_needed_kg_m2(on.scene.dynamics.speed_fluctuation_allowed))
                    }
                }
            }
            Measure::Scalar(s) => match s {
                Scalar::PickingCarrier => ev.map(|e| e.picking.carrier_rad.to_degrees()),
                Scalar::PlantingCarrier => ev.map(|e| e.planting.carrier_rad.to_degrees()),
                Scalar::PickingWindow => {
                    ev.map(|e| (e.picking_window_rad[1] - e.picking_window_rad[0]).to_degrees())
                }
                Scalar::PickingTipSpeed => ev.map(|e| e.picking_tip_speed_m_s),
                Scalar::PickingBranchGap => ev.and_then(|e| e.picking_branch_gap_mm),
                Scalar::PlantingBranchGap => ev.and_then(|e| e.planting_branch_gap_mm),
                Scalar::PickingHeight => ev.map(|e| e.picking.tip_mm.y),
                Scalar::PlantingHeight => ev.map(|e| e.planting.tip_mm.y),
                Scalar::PickingToPlantingHeight => {
                    ev.map(|e| e.picking.tip_mm.y - e.planting.tip_mm.y)
                }
                Scalar::PlantingGroundSpeed => on.anatomy().map(|a| a.planting_ground_speed_m_s),
                Scalar::InTraySpeed => on.anatomy().map(|a| a.in_tray_speed_m_s),
                Scalar::GearOverlap => (eval.kinematics.as_ref())
                    .map(|k| crate::gearbox::gear_sets_overlap(k).unwrap_or(0.0)),
                Scalar::ReturnHeight => on.anatomy().map(|a| a.return_height_mm),
                Scalar::LoopWidth => on.anatomy().map(|a| a.loop_width_mm),
                Scalar::LoopHeight => on.anatomy().map(|a| a.loop_height_mm),
                Scalar::BoxTravel => eval.moving_box.as_ref().map(|b| b.elliptic_delta_h_mm),
            },
        }
    }
}
