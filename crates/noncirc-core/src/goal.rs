//! Search goals: what a search minimises once every objective is met, by name, and what
//! each means in physical terms. Their values for an evaluation are the problem's.

use crate::error::{Error, Result};
use crate::measure::{FitMeasure, Measure};
use crate::objective_kind::{scale, Bounds, ObjectiveKind};
use noncirc_search::nearest;
use serde::{Deserialize, Serialize};

/// Violation for a design the model refuses (invalid curve, under-resolved, …).
pub const INVALID_CV: f64 = 1e5;

/// A goal read in physical terms: the quantity it optimises, its unit and which way.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GoalQuantity {
    /// Named as a column, ending in its unit: `module_mm`, `picking_tip_speed_m_s`,
    /// `picking_angle_margin_deg`, `least_normalised_margin` (no unit).
    pub name: String,
    /// `mm`, `deg`, `m/s`, or empty for a normalised (dimensionless) quantity.
    pub unit: &'static str,
    /// Whether the search makes it larger (its minimised value is its negative).
    pub maximised: bool,
}

impl GoalQuantity {
    /// As a person reads it on an axis: `module (mm), maximised`.
    pub fn label(&self) -> String {
        let token = format!("_{}", unit_token(self.unit));
        let bare = self.name.strip_suffix(&token).unwrap_or(&self.name);
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.unit)
        };
        let way = if self.maximised {
            "maximised"
        } else {
            "minimised"
        };
        format!("{}{unit}, {way}", bare.replace('_', " "))
    }
}

/// `name` ending in `unit` once: (`module`, `mm`) gives `module_mm`.
fn with_unit(name: &str, unit: &str) -> String {
    let token = unit_token(unit);
    if token.is_empty() || name.ends_with(&format!("_{token}")) {
        name.to_string()
    } else {
        format!("{name}_{token}")
    }
}

/// A unit as names end in it: `m/s` → `m_s`, `N·m` → `nm`, `kg·m²` → `kg_m2`, `N` → `n`.
pub(crate) fn unit_token(unit: &str) -> String {
    unit.replace('/', "_")
        .replace("kg·m", "kg_m")
        .replace('·', "")
        .replace('²', "2")
        .replace('³', "3")
        .to_lowercase()
}

/// A goal to minimise once the constraints are met.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Goal {
    /// Maximise the least normalised margin over the objectives and the search
    /// constraints (the default).
    LeastMargin,
    /// Maximise one objective's normalised margin.
    Margin(ObjectiveKind),
    /// Minimise the tip speed relative to the seedling at picking (m/s).
    PickingTipSpeed,
    /// Minimise the box travel while picking (transplanter scenes; mm).
    BoxTravel,
    /// Minimise (`min:NAME`) or maximise (`max:NAME`) any measure (`noncirc measures`).
    Measure { measure: Measure, maximise: bool },
    /// Maximise the probability that the design meets every objective once cut and
    /// assembled with the scene's tolerances (`probability`).
    Probability,
    /// Maximise the least normalised margin at quantile `q` of the tolerance samples
    /// (`margin_quantile:0.05`: the margin 95 % of the built machines exceed).
    MarginQuantile(f64),
    /// Minimise the fit's cost to the scene's target (`fit`): half the squared norm of
    /// the path's and the counting poses' residuals, each over its tolerance.
    Fit,
}

impl Goal {
    /// Parses a goal's name: `least_margin`, `picking_tip_speed`, `box_travel`, an objective's
    /// name (its margin), or `min:NAME` / `max:NAME` of a measure (`noncirc measures`).
    pub fn parse(name: &str) -> Result<Self> {
        match name {
            "least_margin" => Ok(Goal::LeastMargin),
            "picking_tip_speed" => Ok(Goal::PickingTipSpeed),
            "box_travel" => Ok(Goal::BoxTravel),
            "probability" => Ok(Goal::Probability),
            "fit" => Ok(Goal::Fit),
            other if other.starts_with("margin_quantile:") => {
                let text = &other["margin_quantile:".len()..];
                match text.parse::<f64>() {
                    Ok(q) if q > 0.0 && q < 1.0 => Ok(Goal::MarginQuantile(q)),
                    _ => Err(Error::OutOfRange {
                        name: format!("search goal '{other}' (its quantile)"),
                        value: text.parse().unwrap_or(f64::NAN),
                        expected: "a probability strictly between 0 and 1, e.g. \
                                   margin_quantile:0.05"
                            .into(),
                    }),
                }
            }
            other if other.starts_with("min:") || other.starts_with("max:") => Ok(Goal::Measure {
                measure: Measure::parse(&other[4..])?,
                maximise: other.starts_with("max:"),
            }),
            other => (ObjectiveKind::ALL.iter())
                .find(|k| k.name() == other)
                .map(|&k| Goal::Margin(k))
                .ok_or_else(|| {
                    let mut names: Vec<String> = [
                        "least_margin",
                        "picking_tip_speed",
                        "box_travel",
                        "probability",
                        "fit",
                    ]
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

    /// The quantity the goal optimises, in physical terms. An objective's margin goal is
    /// the objective itself where it has one bound (`module` → `module_mm`, maximised), and
    /// its margin in its unit where it has two (`picking_angle_margin_deg`).
    pub fn quantity(self, bounds: &Bounds) -> GoalQuantity {
        let (name, unit, maximised) = match self {
            Goal::LeastMargin => ("least_normalised_margin".to_string(), "", true),
            Goal::Margin(k) => match k.bounds(bounds) {
                (Some(_), None) => (with_unit(k.name(), k.unit()), k.unit(), true),
                (None, Some(_)) => (with_unit(k.name(), k.unit()), k.unit(), false),
                _ => (
                    with_unit(&format!("{}_margin", k.name()), k.unit()),
                    k.unit(),
                    true,
                ),
            },
            Goal::PickingTipSpeed => ("picking_tip_speed_m_s".to_string(), "m/s", false),
            Goal::BoxTravel => ("box_travel_mm".to_string(), "mm", false),
            Goal::Measure { measure, maximise } => (
                with_unit(&measure.name(), measure.unit()),
                measure.unit(),
                maximise,
            ),
            Goal::Probability => ("success_probability".to_string(), "", true),
            Goal::MarginQuantile(q) => {
                (format!("least_normalised_margin_p{}", q * 100.0), "", true)
            }
            Goal::Fit => ("fit_cost".to_string(), "", false),
        };
        GoalQuantity {
            name,
            unit,
            maximised,
        }
    }

    /// The quantity's value in its unit ([`Goal::quantity`]) from `f`, the minimised
    /// value the search ranks by; NaN for a design the model refused (`f` is the
    /// invalid design's sentinel).
    pub fn physical(self, f: f64, bounds: &Bounds) -> f64 {
        if !f.is_finite() || f.abs() >= INVALID_CV {
            return f64::NAN;
        }
        match self {
            Goal::LeastMargin => -f,
            Goal::Margin(k) => {
                let margin = -f * scale(k, bounds);
                match k.bounds(bounds) {
                    (Some(lower), None) => lower + margin,
                    (None, Some(upper)) => upper - margin,
                    _ => margin,
                }
            }
            Goal::PickingTipSpeed | Goal::BoxTravel | Goal::Fit => f,
            // `0 − f`: a probability of 0 reads 0, not −0.
            Goal::Probability | Goal::MarginQuantile(_) => 0.0 - f,
            Goal::Measure { maximise, .. } => {
                if maximise {
                    -f
                } else {
                    f
                }
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
            Goal::Probability => "probability".into(),
            Goal::MarginQuantile(q) => format!("margin_quantile:{q}"),
            Goal::Fit => "fit".into(),
        }
    }

    /// The key pose (0-based) a `min:poseK_…` goal reads.
    pub fn pose_slot(self) -> Option<usize> {
        match self {
            Goal::Measure {
                measure: Measure::Fit(FitMeasure::Pose { slot: Some(k), .. }),
                ..
            } => Some(k as usize),
            _ => None,
        }
    }

    /// Whether only a scene with a target can compute it (the fit, a fit measure).
    pub fn needs_target(self) -> bool {
        matches!(
            self,
            Goal::Fit
                | Goal::Measure {
                    measure: Measure::Fit(_),
                    ..
                }
        )
    }

    /// Whether the goal reads the design's tolerance samples (a robust goal).
    pub fn is_robust(self) -> bool {
        matches!(self, Goal::Probability | Goal::MarginQuantile(_))
    }

    /// Whether only a scene with a moving box (a transplanter) can compute it.
    pub fn needs_moving_box(self) -> bool {
        match self {
            Goal::BoxTravel => true,
            Goal::Measure { measure, .. } => measure.name() == "box_travel_mm",
            _ => false,
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
        let mut goals = vec![
            Goal::LeastMargin,
            Goal::PickingTipSpeed,
            Goal::BoxTravel,
            Goal::Probability,
            Goal::MarginQuantile(0.05),
            Goal::Fit,
        ];
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
    fn a_goal_quantity_is_named_with_its_unit_once_and_its_direction() {
        let bounds = Bounds::default();
        for measure in Measure::all() {
            for maximise in [false, true] {
                let q = Goal::Measure { measure, maximise }.quantity(&bounds);
                let token = unit_token(measure.unit());
                assert!(
                    token.is_empty() || q.name.ends_with(&format!("_{token}")),
                    "{}",
                    q.name
                );
                assert!(
                    !q.name.ends_with(&format!("_{token}_{token}")),
                    "{}",
                    q.name
                );
                assert_eq!(q.maximised, maximise);
            }
        }
        let module = Goal::Margin(ObjectiveKind::Module).quantity(&bounds);
        assert_eq!(
            (module.name.as_str(), module.maximised),
            ("module_mm", true)
        );
        assert_eq!(module.label(), "module (mm), maximised");
        let speed = Goal::PickingTipSpeed.quantity(&bounds);
        assert_eq!(speed.label(), "picking tip speed (m/s), minimised");
        let angle = Goal::Margin(ObjectiveKind::PickingAngle).quantity(&bounds);
        assert_eq!(angle.name, "picking_angle_margin_deg");
        let push = Goal::Margin(ObjectiveKind::SeedlingPush).quantity(&bounds);
        assert_eq!(
            (push.name.as_str(), push.maximised),
            ("seedling_push_mm", false)
        );
        assert_eq!(
            Goal::LeastMargin.quantity(&bounds).label(),
            "least normalised margin, maximised"
        );
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
