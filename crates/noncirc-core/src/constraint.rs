//! Search constraints: a bound on any measure (`noncirc measures`) that a design must meet
//! beside the objectives, written `picking_height_mm <= -90` in `search.constraints`.
//! Every search counts a missed one as it counts a missed objective.

use crate::error::{Error, Result};
use crate::measure::Measure;
use serde::{Deserialize, Serialize};

/// A bound on a measure: `NAME <= VALUE` or `NAME >= VALUE`, the value in the measure's unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct Constraint {
    pub measure: Measure,
    /// The bound, in the measure's unit (finite).
    pub bound: f64,
    /// `<=` (the measure at most `bound`) or `>=` (at least).
    pub at_most: bool,
}

impl Constraint {
    /// The largest bound's size, in the measure's unit: far beyond any mechanism's.
    pub const MAX_BOUND: f64 = 1e9;

    /// Parses `NAME <= VALUE` or `NAME >= VALUE` (`≤`, `≥` too; spaces optional).
    pub fn parse(text: &str) -> Result<Self> {
        let (at, op, at_most) = ["<=", "≤", ">=", "≥"]
            .iter()
            .find_map(|op| text.find(op).map(|at| (at, *op, matches!(*op, "<=" | "≤"))))
            .ok_or_else(|| Error::BadList {
                list: "search.constraints",
                problem: format!(
                    "'{text}' is not a bound: write NAME <= VALUE or NAME >= VALUE, e.g. \
                     \"picking_height_mm <= -90\" (names: noncirc measures)"
                ),
            })?;
        let name = text[..at].trim();
        let value = text[at + op.len()..].trim();
        let measure = Measure::parse(name)?;
        let bound = value.parse::<f64>().map_err(|_| Error::BadList {
            list: "search.constraints",
            problem: format!("'{text}': the bound '{value}' is not a number"),
        })?;
        if !bound.is_finite() {
            return Err(Error::NonFinite {
                name: format!("search.constraints '{text}' (its bound)"),
                value: bound,
            });
        }
        if bound.abs() > Self::MAX_BOUND {
            return Err(Error::OutOfRange {
                name: format!("search.constraints '{text}' (its bound)"),
                value: bound,
                expected: format!(
                    "within ±{:e} in the measure's unit (violations that far would add up to \
                     infinity)",
                    Self::MAX_BOUND
                ),
            });
        }
        Ok(Self {
            measure,
            bound,
            at_most,
        })
    }

    /// As written in a scene: `picking_height_mm <= -90`.
    pub fn text(&self) -> String {
        let op = if self.at_most { "<=" } else { ">=" };
        format!("{} {op} {}", self.measure.name(), self.bound)
    }

    /// The scale a violation is divided by where searches add violations up (in the
    /// measure's unit): a tenth of the bound, at least 1, as for an objective's one bound.
    pub fn scale(&self) -> f64 {
        (self.bound.abs() * 0.1).max(1.0)
    }

    /// Scores the measure's `value` (`None`: the design has none, e.g. no runner-up extreme).
    pub fn score(&self, value: Option<f64>) -> ConstraintValue {
        let value = value.unwrap_or(f64::NAN);
        let margin = if self.at_most {
            self.bound - value
        } else {
            value - self.bound
        };
        // A value the design does not have cannot meet the bound: missed, as an
        // objective that cannot be read is.
        let violation = if value.is_nan() {
            f64::INFINITY
        } else {
            (-margin).max(0.0)
        };
        ConstraintValue {
            constraint: *self,
            value,
            violation,
            margin,
        }
    }
}

impl TryFrom<String> for Constraint {
    type Error = Error;
    fn try_from(text: String) -> Result<Self> {
        Constraint::parse(&text)
    }
}

impl From<Constraint> for String {
    fn from(c: Constraint) -> String {
        c.text()
    }
}

/// What a design meets to count as feasible: "every objective", and "and search
/// constraint" when there are some.
pub fn requirements(has_constraints: bool) -> &'static str {
    if has_constraints {
        "every objective and search constraint"
    } else {
        "every objective"
    }
}

/// A constraint's outcome for a design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstraintValue {
    pub constraint: Constraint,
    /// The measure's value (its unit; NaN where the design has none).
    pub value: f64,
    /// 0 when met, else the distance past the bound (the measure's unit; infinite when
    /// the value is NaN).
    pub violation: f64,
    /// Distance inside the bound (negative when missed; NaN without a value).
    pub margin: f64,
}

impl ConstraintValue {
    /// The violation over the constraint's scale, as searches add it up.
    pub fn normalised_violation(&self) -> f64 {
        self.violation / self.constraint.scale()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constraint_parses_back_from_its_text_and_scores_both_ways() {
        for text in [
            "picking_height_mm <= -90",
            "loop_width_mm>=12.5",
            "picking_tip_speed_m_s ≤ 0.25",
        ] {
            let c = Constraint::parse(text).unwrap();
            assert_eq!(Constraint::parse(&c.text()).unwrap(), c, "{text}");
        }
        let c = Constraint::parse("picking_height_mm <= -90").unwrap();
        assert_eq!(c.score(Some(-95.0)).violation, 0.0);
        assert_eq!(c.score(Some(-95.0)).margin, 5.0);
        assert_eq!(c.score(Some(-80.0)).violation, 10.0);
        assert_eq!(c.score(Some(-80.0)).normalised_violation(), 10.0 / 9.0);
        let c = Constraint::parse("loop_width_mm >= 40").unwrap();
        assert_eq!(c.score(Some(30.0)).violation, 10.0);
        assert_eq!(c.score(Some(50.0)).margin, 10.0);
        assert_eq!(c.score(None).violation, f64::INFINITY);
    }

    #[test]
    fn a_bad_constraint_is_refused_by_name() {
        for (text, named) in [
            ("picking_height_mm = -90", "NAME <= VALUE"),
            ("picking_hieght_mm <= -90", "picking_height_mm"),
            ("picking_height_mm <= low", "'low'"),
            ("picking_height_mm <= inf", "its bound"),
            ("picking_height_mm <= NaN", "its bound"),
            ("picking_height_mm >= 1e308", "within ±1e9"),
        ] {
            let err = Constraint::parse(text).unwrap_err().to_string();
            assert!(err.contains(named), "{text}: {err}");
        }
    }
}
