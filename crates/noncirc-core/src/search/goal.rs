//! Search goals: what a search minimises once every objective is met, by name.

use super::problem::{scale, INVALID_CV};
use crate::error::{Error, Result};
use crate::evaluation::Evaluation;
use crate::measures::{nearest, Measure};
use crate::objectives::{ObjectiveKind, ObjectiveValue};
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

/// A goal to minimise once the constraints are met.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Goal {
    /// Maximise the least normalised margin over the objectives (the default).
    LeastMargin,
    /// Maximise one objective's normalised margin.
    Margin(ObjectiveKind),
    /// Minimise the tip speed relative to the seedling at picking (m/s).
    PickingTipSpeed,
    /// Minimise the box travel while picking (transplanter scenes; mm).
    BoxTravel,
    /// Minimise (`min:NAME`) or maximise (`max:NAME`) any measure (`noncirc measures`).
    Measure { measure: Measure, maximise: bool },
}

impl Goal {
    /// Parses a goal's name: `least_margin`, `picking_tip_speed`, `box_travel`, an objective's
    /// name (its margin), or `min:NAME` / `max:NAME` of a measure (`noncirc measures`).
    pub fn parse(name: &str) -> Result<Self> {
        match name {
            "least_margin" => Ok(Goal::LeastMargin),
            "picking_tip_speed" => Ok(Goal::PickingTipSpeed),
            "box_travel" => Ok(Goal::BoxTravel),
            other if other.starts_with("min:") || other.starts_with("max:") => Ok(Goal::Measure {
                measure: Measure::parse(&other[4..])?,
                maximise: other.starts_with("max:"),
            }),
            other => (ObjectiveKind::ALL.iter())
                .find(|k| k.name() == other)
                .map(|&k| Goal::Margin(k))
                .ok_or_else(|| {
                    let mut names: Vec<String> =
                        ["least_margin", "picking_tip_speed", "box_travel"]
                            .map(String::from)
                            .to_vec();
                    names.extend(ObjectiveKind::ALL.iter().map(|k| k.name().to_string()));
                    Error::UnknownName {
                        what: "search goal (or min:NAME / max:NAME of a measure)",
                        name: other.to_string(),
                        nearest: nearest(other, &names),
                    }
                }),
        }
    }

    /// The goal as a person reads it, with its unit once (it is minimised: a maximised
    /// measure is negated).
    pub fn label(self) -> String {
        match self {
            Goal::LeastMargin => "−(least normalised margin)".to_string(),
            Goal::Margin(k) => format!("−({} normalised margin)", k.name()),
            Goal::PickingTipSpeed => "picking tip speed (m/s)".to_string(),
            Goal::BoxTravel => "box travel while picking (mm)".to_string(),
            Goal::Measure { measure, maximise } => {
                // A measure's name may end in its unit (`…_mm`, `…_m_s`).
                let (name, unit) = (measure.name(), measure.unit());
                let suffix = format!("_{}", unit.replace('/', "_"));
                format!(
                    "{}{} ({unit})",
                    if maximise { "−" } else { "" },
                    name.strip_suffix(&suffix).unwrap_or(&name),
                )
            }
        }
    }

    /// The goal's name, as [`Goal::parse`] reads it.
    pub fn name(self) -> String {
        match self {
            Goal::LeastMargin => "least_margin".into(),
            Goal::Margin(k) => k.name().into(),
            Goal::PickingTipSpeed => "picking_tip_speed".into(),
            Goal::BoxTravel => "box_travel".into(),
            Goal::Measure { measure, maximise } => {
                format!(
                    "{}:{}",
                    if maximise { "max" } else { "min" },
                    measure.name()
                )
            }
        }
    }

    /// Whether only a scene with a moving box (a transplanter) can compute it.
    pub fn needs_moving_box(self) -> bool {
        match self {
            Goal::BoxTravel => true,
            Goal::Measure { measure, .. } => measure.name() == "box_travel_mm",
            _ => false,
        }
    }

    pub(crate) fn value(self, eval: &Evaluation, scene: &Scene) -> f64 {
        let bounds = &scene.bounds;
        let norm = |o: &ObjectiveValue| o.margin / scale(o.kind, bounds);
        let v = match self {
            // The seedling-push margin is 0 whenever it is met: it cannot rank designs.
            Goal::LeastMargin => -eval
                .objectives
                .iter()
                .filter(|o| o.kind != ObjectiveKind::SeedlingPush)
                .map(norm)
                .fold(f64::INFINITY, f64::min),
            Goal::Margin(k) => -eval.objective(k).map_or(f64::NEG_INFINITY, norm),
            Goal::PickingTipSpeed => eval
                .events
                .as_ref()
                .map_or(f64::INFINITY, |e| e.picking_tip_speed_m_s),
            Goal::BoxTravel => eval
                .moving_box
                .as_ref()
                .map_or(f64::INFINITY, |b| b.elliptic_delta_h_mm),
            Goal::Measure { measure, maximise } => {
                let anatomy = if measure.needs_anatomy() {
                    eval.anatomy(&scene.agronomy)
                } else {
                    None
                };
                let v = measure.value(eval, anatomy.as_ref()).unwrap_or(f64::NAN);
                if maximise {
                    -v
                } else {
                    v
                }
            }
        };
        if v.is_finite() {
            v
        } else {
            INVALID_CV
        }
    }
}

impl TryFrom<String> for Goal {
    type Error = Error;
    fn try_from(name: String) -> Result<Self> {
        Goal::parse(&name)
    }
}

impl From<Goal> for String {
    fn from(goal: Goal) -> String {
        goal.name()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_goal_name_parses_back() {
        let mut goals = vec![Goal::LeastMargin, Goal::PickingTipSpeed, Goal::BoxTravel];
        goals.extend(ObjectiveKind::ALL.iter().map(|&k| Goal::Margin(k)));
        for m in Measure::all() {
            for maximise in [false, true] {
                goals.push(Goal::Measure {
                    measure: m,
                    maximise,
                });
            }
        }
        for g in goals {
            assert_eq!(Goal::parse(&g.name()).unwrap(), g, "{}", g.name());
        }
    }

    #[test]
    fn a_measure_goal_label_carries_its_unit_once() {
        for measure in Measure::all() {
            let label = Goal::Measure {
                measure,
                maximise: false,
            }
            .label();
            let unit = measure.unit();
            assert!(label.ends_with(&format!(" ({unit})")), "{label}");
            let bare = &label[..label.len() - unit.len() - 3];
            assert!(
                !bare.ends_with(&format!("_{}", unit.replace('/', "_"))),
                "{label}"
            );
        }
        let speed = Goal::Measure {
            measure: Measure::parse("picking_tip_speed_m_s").unwrap(),
            maximise: true,
        };
        assert_eq!(speed.label(), "−picking_tip_speed (m/s)");
    }

    #[test]
    fn an_unknown_goal_names_the_nearest() {
        match Goal::parse("least_margn") {
            Err(Error::UnknownName { name, nearest, .. }) => {
                assert_eq!(name, "least_margn");
                assert_eq!(nearest[0], "least_margin");
            }
            other => panic!("{other:?}"),
        }
    }
}
