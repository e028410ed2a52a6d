//! A measure's value for an evaluation: read from its objectives, events, moving box or
//! gearbox, or from the trajectory's sections, or from the fit to a target.

use crate::anatomy::Anatomy;
use crate::evaluation::Evaluation;
use crate::measure::{Measure, Scalar, SectionQuantity};

impl Measure {
    /// The value for an evaluation (and its anatomy when [`Measure::needs_anatomy`]);
    /// `None` where the scene does not compute it (no events, no moving box, no
    /// runner-up extreme).
    pub fn value(self, eval: &Evaluation, anatomy: Option<&Anatomy>) -> Option<f64> {
        let ev = eval.events.as_ref();
        match self {
            Measure::Objective(k) => eval.objective(k).map(|o| o.value),
            Measure::Fit(m) => eval.fit.as_ref()?.value(m),
            Measure::Section(s, q) => anatomy.map(|a| {
                let m = a.section(s);
                match q {
                    SectionQuantity::Span => m.span_deg,
                    SectionQuantity::Length => m.length_mm,
                    SectionQuantity::YMin => m.y_min_mm,
                    SectionQuantity::YMax => m.y_max_mm,
                }
            }),
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
                Scalar::PlantingGroundSpeed => anatomy.map(|a| a.planting_ground_speed_m_s),
                Scalar::InTraySpeed => anatomy.map(|a| a.in_tray_speed_m_s),
                Scalar::GearOverlap => (eval.kinematics.as_ref())
                    .map(|k| crate::gearbox::gear_sets_overlap(k).unwrap_or(0.0)),
                Scalar::ReturnHeight => anatomy.map(|a| a.return_height_mm),
                Scalar::LoopWidth => anatomy.map(|a| a.loop_width_mm),
                Scalar::LoopHeight => anatomy.map(|a| a.loop_height_mm),
                Scalar::BoxTravel => eval.moving_box.as_ref().map(|b| b.elliptic_delta_h_mm),
            },
        }
    }
}
