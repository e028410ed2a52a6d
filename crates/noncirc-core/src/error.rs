//! Typed errors: every one names the offending value.

/// Everything that can go wrong in the core. Each variant carries the bad value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A number that must be finite is NaN or infinite.
    #[error("{} must be a finite number, got {}", Named(name), Num(*value))]
    NonFinite { name: String, value: f64 },
    /// A scalar parameter is outside its admissible range.
    #[error("{} = {} is out of range: expected {expected}", Named(name), Num(*value))]
    OutOfRange {
        name: String,
        value: f64,
        expected: String,
    },
    /// A pitch curve reaches zero or negative radius.
    #[error(
        "pitch radius must be positive everywhere, but rho = {rho_mm:.6} mm at psi = {psi_deg:.4}°"
    )]
    NonPositiveRadius { psi_deg: f64, rho_mm: f64 },
    /// Control angles are not strictly increasing within one turn.
    #[error("control angles must be strictly increasing within one turn: angle {index} is {angle_deg}° after {previous_deg}°")]
    ControlAngles {
        index: usize,
        angle_deg: f64,
        previous_deg: f64,
    },
    /// Too few control points for the representation.
    #[error("{kind} needs at least {min} points, got {got}")]
    TooFewPoints {
        kind: &'static str,
        min: usize,
        got: usize,
    },
    /// A Cartesian curve is not star-shaped about the rotation centre.
    #[error("{kind} pitch curve is not star-shaped about the centre: its polar angle turns back near ({x_mm:.3}, {y_mm:.3}) mm")]
    NotStarShaped {
        kind: &'static str,
        x_mm: f64,
        y_mm: f64,
    },
    /// The quadrature is too coarse for the curve: the closure integral is not resolved.
    #[error("closure not resolved at {samples} samples per turn: centre distance uncertain by about {error_mm:.3e} mm (tolerance {tolerance_mm:.1e} mm); the curve's sharpest feature needs more samples per turn")]
    UnderResolved {
        samples: usize,
        error_mm: f64,
        tolerance_mm: f64,
    },
    /// The pitch curve's maximum lies between samples and reaches past the centre distance.
    #[error("pitch curve reaches rho = {rho_max_mm:.6} mm between samples, beyond the centre distance {centre_distance_mm:.6} mm: raise samples per turn")]
    SpikeBetweenSamples {
        rho_max_mm: f64,
        centre_distance_mm: f64,
    },
    /// A name (of a measure, a goal, a parameter) that does not exist.
    #[error("unknown {what} '{name}': the nearest are {}", nearest.join(", "))]
    UnknownName {
        what: &'static str,
        name: String,
        nearest: Vec<String>,
    },
    /// A search state (checkpoint) that cannot be resumed: what is wrong with it.
    #[error("checkpoint: {0}")]
    Checkpoint(String),
    /// An optional setting that another setting needs.
    #[error("{name} is not set: {needed_by}")]
    Missing { name: String, needed_by: String },
    /// A list of the scene (objectives, goals, free parameters) with an entry that cannot
    /// stand there, or empty where it must not be; `problem` names the entry.
    #[error("{list}: {problem}")]
    BadList { list: &'static str, problem: String },
    /// Teeth that cannot be cut on this pitch curve with these settings: where and why.
    #[error("{gear} gear, tooth {tooth} (pitch arc {arc_mm:.3} mm): {why}")]
    Teeth {
        gear: &'static str,
        tooth: usize,
        arc_mm: f64,
        why: String,
    },
    /// A toothed outline that crosses itself, and where.
    #[error("{gear} gear: the toothed outline crosses itself near ({x_mm:.4}, {y_mm:.4}) mm")]
    OutlineCrossing {
        gear: &'static str,
        x_mm: f64,
        y_mm: f64,
    },
    /// A design that cannot be manufactured (e.g. a module of zero).
    #[error("{0}")]
    Infeasible(String),
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

/// Displays a number readably: scientific notation when very large or very small.
/// A scene path with the papers' symbol where they name one: `train.arm_length_mm (S)`.
struct Named<'a>(&'a str);

impl std::fmt::Display for Named<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match crate::reference::symbol(self.0) {
            Some(symbol) => write!(f, "{} ({symbol})", self.0),
            None => write!(f, "{}", self.0),
        }
    }
}

struct Num(f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        if v.is_finite() && v != 0.0 && !(1e-4..1e9).contains(&v.abs()) {
            write!(f, "{v:e}")
        } else {
            write!(f, "{v}")
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
