//! Typed errors: every one names the offending value.

/// Everything that can go wrong in the core. Each variant carries the bad value. The
/// messages are written in `messages.rs`, a layer up: they name a scene path with the
/// papers' symbol from the scene's field table (`train.arm_length_mm (S)`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A number that must be finite is NaN or infinite.
    NonFinite { name: String, value: f64 },
    /// A scalar parameter is outside its admissible range.
    OutOfRange {
        name: String,
        value: f64,
        expected: String,
    },
    /// A pitch curve reaches zero or negative radius.
    NonPositiveRadius { psi_deg: f64, rho_mm: f64 },
    /// Control angles are not strictly increasing within one turn.
    ControlAngles {
        index: usize,
        angle_deg: f64,
        previous_deg: f64,
    },
    /// Too few control points for the representation.
    TooFewPoints {
        kind: &'static str,
        min: usize,
        got: usize,
    },
    /// More control points than the representation takes, and why.
    TooManyPoints {
        kind: &'static str,
        max: usize,
        got: usize,
        why: &'static str,
    },
    /// A Cartesian curve is not star-shaped about the rotation centre.
    NotStarShaped {
        kind: &'static str,
        x_mm: f64,
        y_mm: f64,
    },
    /// The quadrature is too coarse for the curve: the closure integral is not resolved.
    UnderResolved {
        samples: usize,
        error_mm: f64,
        tolerance_mm: f64,
    },
    /// The pitch curve's maximum lies between samples and reaches past the centre distance.
    SpikeBetweenSamples {
        rho_max_mm: f64,
        centre_distance_mm: f64,
    },
    /// A name (of a measure, a goal, a parameter) that does not exist.
    UnknownName {
        what: &'static str,
        name: String,
        nearest: Vec<String>,
    },
    /// A search state (checkpoint) that cannot be resumed: what is wrong with it.
    Checkpoint(String),
    /// An optional setting that another setting needs.
    Missing { name: String, needed_by: String },
    /// A list of the scene (objectives, goals, free parameters) with an entry that cannot
    /// stand there, or empty where it must not be; `problem` names the entry.
    BadList { list: &'static str, problem: String },
    /// Teeth that cannot be cut on this pitch curve with these settings: where and why.
    Teeth {
        gear: &'static str,
        tooth: usize,
        arc_mm: f64,
        why: String,
    },
    /// A toothed outline that crosses itself, and where.
    OutlineCrossing {
        gear: &'static str,
        x_mm: f64,
        y_mm: f64,
    },
    /// A design that cannot be manufactured (e.g. a module of zero).
    Infeasible(String),
    /// A target path that does not close: `name` is its last point, `gap_mm` the distance
    /// from it to the first, `spacing_mm` the path's median spacing.
    OpenTarget {
        name: String,
        gap_mm: f64,
        spacing_mm: f64,
    },
    /// A target point or pose that no design of the search's box can reach: its distance
    /// from the carrier axis and the band of distances the arm's tip can take.
    OutOfReach {
        name: String,
        distance_mm: f64,
        inner_mm: f64,
        outer_mm: f64,
    },
    /// An error of the second pair's pitch curve (`gear.second_curve`), which would
    /// otherwise read as the sun's.
    SecondPair(Box<Error>),
    /// A target path that crosses itself: the points that start the two crossing pieces,
    /// and where.
    TargetCrossing {
        name: String,
        other: String,
        x_mm: f64,
        y_mm: f64,
    },
}

/// The optimiser's errors as the core's variants of the same names and messages.
impl From<noncirc_search::Error> for Error {
    fn from(e: noncirc_search::Error) -> Self {
        match e {
            noncirc_search::Error::UnknownName {
                what,
                name,
                nearest,
            } => Error::UnknownName {
                what,
                name,
                nearest,
            },
            noncirc_search::Error::Checkpoint(problem) => Error::Checkpoint(problem),
        }
    }
}

/// Shorthand for core results.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite, naming it in the error otherwise.
pub(crate) fn finite(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite {
            name: name.to_string(),
            value,
        })
    }
}

/// Like [`finite`], naming the value only when it is bad (no formatting on the hot path).
pub(crate) fn finite_with(name: impl FnOnce() -> String, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        finite(&name(), value)
    }
}

/// A positive length (mm) from [`MIN_LENGTH_MM`] to [`MAX_LENGTH_MM`], naming the value
/// only when it is bad.
pub(crate) fn positive_with(name: impl FnOnce() -> String, value: f64) -> Result<f64> {
    if value.is_finite() && (MIN_LENGTH_MM..=MAX_LENGTH_MM).contains(&value) {
        Ok(value)
    } else {
        let name = name();
        finite(&name, value)?;
        Err(Error::OutOfRange {
            name,
            value,
            expected: format!("a length from {MIN_LENGTH_MM:e} to {MAX_LENGTH_MM:e} mm"),
        })
    }
}

/// Smallest accepted pitch-curve length (mm), the mirror of [`MAX_LENGTH_MM`]: results
/// scale exactly over the 18 decades between them (a test holds it), while far smaller
/// lengths reach subnormal numbers (a 5e-324 mm ellipse gave a centre distance of
/// 0 ± NaN).
pub(crate) const MIN_LENGTH_MM: f64 = 1e-9;

/// Largest accepted length (mm): a thousand kilometres. Larger inputs overflow the
/// geometry (squares of lengths) and are refused by name instead.
pub(crate) const MAX_LENGTH_MM: f64 = 1e9;

/// Checks that a length (mm) is finite, non-negative and at most [`MAX_LENGTH_MM`].
pub(crate) fn length(name: &str, value: f64) -> Result<f64> {
    finite(name, value)?;
    if (0.0..=MAX_LENGTH_MM).contains(&value) {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            name: name.to_string(),
            value,
            expected: format!("0 to {MAX_LENGTH_MM:e} mm"),
        })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(name: &str, value: f64) -> Result<f64> {
    finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            name: name.to_string(),
            value,
            expected: "> 0".into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_optimisers_errors_keep_their_messages() {
        let errors = [
            noncirc_search::Error::UnknownName {
                what: "algorithm",
                name: "dee".into(),
                nearest: vec!["de".into(), "guided".into()],
            },
            noncirc_search::Error::Checkpoint("damaged".into()),
        ];
        for e in errors {
            assert_eq!(Error::from(e.clone()).to_string(), e.to_string());
        }
    }
}
