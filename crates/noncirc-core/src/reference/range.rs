//! A field's admissible values as data: the bounds of a number, which the field table
//! both prints (docs/scenes.md) and, for the scene's own tables, checks (`IntervalCheck`), and the rules that only
//! code can check (names, lists, several fields at once) as prose.

use super::{Field, Number};
use crate::error::{Error, Result};
use crate::scene::Scene;
use std::fmt;

/// One end of a field's interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// No bound: any finite number.
    Unbounded,
    /// The bound is admitted.
    Included(f64),
    /// Values up to the bound are admitted, the bound itself is not.
    Excluded(f64),
}

/// What a field admits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Range {
    /// A finite number (each element of a list) from `low` to `high`, checked from this
    /// table; `and` is what code checks besides, with other fields ("" when nothing).
    Interval {
        low: Bound,
        high: Bound,
        and: &'static str,
    },
    /// Names, flags, lists and tables: what is admitted, checked in code.
    Rule(&'static str),
}

impl Range {
    /// Any finite number.
    pub(crate) const FINITE: Self = Self::interval(Bound::Unbounded, Bound::Unbounded);

    const fn interval(low: Bound, high: Bound) -> Self {
        Self::Interval { low, high, and: "" }
    }

    /// Above `low` (excluded).
    pub(crate) const fn above(low: f64) -> Self {
        Self::interval(Bound::Excluded(low), Bound::Unbounded)
    }

    /// Above `low` (excluded), at most `high`.
    pub(crate) const fn above_at_most(low: f64, high: f64) -> Self {
        Self::interval(Bound::Excluded(low), Bound::Included(high))
    }

    /// `low` or more.
    pub(crate) const fn at_least(low: f64) -> Self {
        Self::interval(Bound::Included(low), Bound::Unbounded)
    }

    /// From `low` to `high`, both included.
    pub(crate) const fn from_to(low: f64, high: f64) -> Self {
        Self::interval(Bound::Included(low), Bound::Included(high))
    }

    /// From `low` (included) up to `high` (excluded).
    pub(crate) const fn from_below(low: f64, high: f64) -> Self {
        Self::interval(Bound::Included(low), Bound::Excluded(high))
    }

    /// Strictly between `low` and `high`.
    pub(crate) const fn between(low: f64, high: f64) -> Self {
        Self::interval(Bound::Excluded(low), Bound::Excluded(high))
    }

    /// This interval, with what code checks besides (`"; in a transplanter scene, …"`).
    pub(crate) const fn and(self, rule: &'static str) -> Self {
        match self {
            Self::Interval { low, high, .. } => Self::Interval {
                low,
                high,
                and: rule,
            },
            Self::Rule(_) => self,
        }
    }

    /// Whether `value` lies in the interval (a rule admits every number: code checks it).
    #[inline]
    pub fn admits(&self, value: f64) -> bool {
        let Self::Interval { low, high, .. } = *self else {
            return true;
        };
        let above = match low {
            Bound::Unbounded => true,
            Bound::Included(b) => value >= b,
            Bound::Excluded(b) => value > b,
        };
        let below = match high {
            Bound::Unbounded => true,
            Bound::Included(b) => value <= b,
            Bound::Excluded(b) => value < b,
        };
        value.is_finite() && above && below
    }

    /// The interval alone, as an error's "expected" says it.
    fn interval_text(low: Bound, high: Bound) -> String {
        use Bound::{Excluded, Included, Unbounded};
        let n = Num;
        match (low, high) {
            (Unbounded, Unbounded) => "finite".into(),
            (Excluded(a), Unbounded) => format!("above {}", n(a)),
            (Included(a), Unbounded) => format!("{} or more", n(a)),
            (Unbounded, Included(b)) => format!("at most {}", n(b)),
            (Unbounded, Excluded(b)) => format!("below {}", n(b)),
            (Excluded(a), Included(b)) => format!("above {}, at most {}", n(a), n(b)),
            (Included(a), Included(b)) => format!("{} to {}", n(a), n(b)),
            (Included(a), Excluded(b)) => format!("{} to {} ({} excluded)", n(a), n(b), n(b)),
            (Excluded(a), Excluded(b)) => format!("between {} and {} (exclusive)", n(a), n(b)),
        }
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Interval { low, high, and } => {
                write!(f, "{}{and}", Self::interval_text(low, high))
            }
            Self::Rule(rule) => f.write_str(rule),
        }
    }
}

/// A bound as a person writes it: `1e9`, `100000`, `0.5`.
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v != 0.0 && !(1e-3..=1e5).contains(&v.abs()) {
            write!(f, "{v:e}")
        } else {
            write!(f, "{v}")
        }
    }
}

impl Field {
    /// Whether the field is a list of numbers (`gear.curve.radii_mm`), indexed `key[i]`.
    pub fn is_list(&self) -> bool {
        matches!(self.number, Some(Number::List(..)))
    }

    /// The field's admissible values as the reference prints them: an optional number
    /// may also be left unset.
    pub fn admissible(&self) -> String {
        match self.number {
            Some(Number::Optional(..)) => format!("unset, or {}", self.range),
            _ => self.range.to_string(),
        }
    }

    /// The error for `value` outside the interval (at a list's element `index`).
    #[cold]
    pub(crate) fn refuse(&self, index: Option<usize>, value: f64) -> Error {
        let name = match index {
            Some(i) => format!("{}[{i}]", self.key),
            None => self.key.to_string(),
        };
        match self.range {
            Range::Interval { low, high, .. } if value.is_finite() => Error::OutOfRange {
                name,
                value,
                expected: Range::interval_text(low, high),
            },
            _ => Error::NonFinite { name, value },
        }
    }
}

/// One number's interval, as the per-design check reads it.
#[derive(Clone, Copy)]
pub(crate) struct IntervalCheck {
    /// The scene table's index in [`super::TABLES`].
    pub(crate) table: usize,
    field: &'static Field,
    number: Number,
}

impl IntervalCheck {
    /// The interval of `field`, if it is a number with one.
    fn new(table: usize, field: &'static Field) -> Option<Self> {
        let (Range::Interval { .. }, Some(number)) = (field.range, field.number) else {
            return None;
        };
        Some(Self {
            table,
            field,
            number,
        })
    }

    /// Checks the field's value in `scene` (each element of a list), naming it (a list's
    /// element as `key[i]`) when it is outside. A field this scene does not have and an
    /// optional field left unset pass.
    #[inline]
    pub(crate) fn check(&self, scene: &Scene) -> Result<()> {
        let range = &self.field.range;
        match self.number {
            Number::Scalar(get, _) | Number::Optional(get, _) => match get(scene) {
                Some(v) if !range.admits(v) => Err(self.field.refuse(None, v)),
                _ => Ok(()),
            },
            Number::List(get, _) => {
                let list = get(scene).unwrap_or_default();
                match list.iter().position(|&v| !range.admits(v)) {
                    Some(i) => Err(self.field.refuse(Some(i), list[i])),
                    None => Ok(()),
                }
            }
        }
    }
}

/// The interval of every number that the table checks itself ([`super::Checker::Table`]),
/// table by table, read once from the field table.
pub(crate) fn interval_checks() -> &'static [IntervalCheck] {
    static CHECKS: std::sync::OnceLock<Vec<IntervalCheck>> = std::sync::OnceLock::new();
    CHECKS.get_or_init(|| {
        (super::TABLES.iter().enumerate())
            .filter(|(_, (_, checker, _))| *checker == super::Checker::Table)
            .flat_map(|(t, (_, _, fields))| {
                fields.iter().filter_map(move |f| IntervalCheck::new(t, f))
            })
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_print_as_the_reference_says_and_admit_what_they_say() {
        let cases = [
            (Range::FINITE, "finite", [-1e300, 0.0, 1e300], [f64::NAN; 3]),
            (
                Range::above(0.0),
                "above 0",
                [1e-300, 1.0, 1e300],
                [0.0, -1.0, f64::INFINITY],
            ),
            (
                Range::above_at_most(0.0, 1e9),
                "above 0, at most 1e9",
                [1e-9, 1.0, 1e9],
                [0.0, 1.000_000_1e9, -1.0],
            ),
            (
                Range::at_least(1.0),
                "1 or more",
                [1.0, 2.0, 1e300],
                [0.999, -1.0, f64::NAN],
            ),
            (
                Range::from_to(0.0, 360.0),
                "0 to 360",
                [0.0, 180.0, 360.0],
                [-1e-9, 360.1, 1e9],
            ),
            (
                Range::from_below(0.0, 90.0),
                "0 to 90 (90 excluded)",
                [0.0, 45.0, 89.999],
                [90.0, -0.1, 1e3],
            ),
            (
                Range::between(5.0, 45.0),
                "between 5 and 45 (exclusive)",
                [5.001, 20.0, 44.999],
                [5.0, 45.0, 0.0],
            ),
            (
                Range::above_at_most(0.0, 0.01),
                "above 0, at most 0.01",
                [1e-12, 0.005, 0.01],
                [0.0, 0.0100001, 1.0],
            ),
        ];
        for (range, text, admitted, refused) in cases {
            assert_eq!(range.to_string(), text);
            for v in admitted {
                assert!(range.admits(v), "{text}: {v}");
            }
            for v in refused {
                assert!(!range.admits(v), "{text}: {v}");
            }
        }
        let rule = Range::Rule("`left` or `right`");
        assert_eq!(rule.to_string(), "`left` or `right`");
        assert!(rule.admits(f64::NAN), "a rule is code's to check");
        let with = Range::above(0.0).and("; at most a tenth of `closure_rel_tol`");
        assert_eq!(
            with.to_string(),
            "above 0; at most a tenth of `closure_rel_tol`"
        );
    }
}
