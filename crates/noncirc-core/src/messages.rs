//! The core's error messages. They sit above the error type (`error.rs`, in the bottom
//! layer) because they name a scene path with the papers' symbol from the scene's field
//! table: `train.arm_length_mm (S) = -1 is out of range: expected > 0`.

use crate::error::Error;
use crate::reference::symbol;
use std::fmt;

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { name, value } => write!(
                f,
                "{} must be a finite number, got {}", Named(name), Num(*value)
            ),
            Error::OutOfRange { name, value, expected } => write!(
                f,
                "{} = {} is out of range: expected {expected}", Named(name), Num(*value)
            ),
            Error::NonPositiveRadius { psi_deg, rho_mm } => write!(
                f,
                "pitch radius must be positive everywhere, but rho = {rho_mm:.6} mm at psi = {psi_deg:.4}°"
            ),
            Error::ControlAngles { index, angle_deg, previous_deg } => write!(
                f,
                "control angles must be strictly increasing within one turn: angle {index} is {angle_deg}° after {previous_deg}°"
            ),
            Error::TooFewPoints { kind, min, got } => write!(
                f,
                "{kind} needs at least {min} points, got {got}"
            ),
            Error::TooManyPoints {
                kind,
                max,
                got,
                why,
            } => write!(f, "{kind} takes at most {max} points, got {got}: {why}"),
            Error::NotStarShaped { kind, x_mm, y_mm } => write!(
                f,
                "{kind} pitch curve is not star-shaped about the centre: its polar angle turns back near ({x_mm:.3}, {y_mm:.3}) mm"
            ),
            Error::UnderResolved { samples, error_mm, tolerance_mm } => write!(
                f,
                "closure not resolved at {samples} samples per turn: centre distance uncertain by about {error_mm:.3e} mm (tolerance {tolerance_mm:.1e} mm); the curve's sharpest feature needs more samples per turn"
            ),
            Error::SpikeBetweenSamples { rho_max_mm, centre_distance_mm } => write!(
                f,
                "pitch curve reaches rho = {rho_max_mm:.6} mm between samples, beyond the centre distance {centre_distance_mm:.6} mm: raise samples per turn"
            ),
            Error::UnknownName { what, name, nearest } => write!(
                f,
                "unknown {what} '{name}': the nearest are {}", nearest.join(", ")
            ),
            Error::Checkpoint(message) => write!(
                f,
                "checkpoint: {message}"
            ),
            Error::Missing { name, needed_by } => write!(
                f,
                "{name} is not set: {needed_by}"
            ),
            Error::BadList { list, problem } => write!(
                f,
                "{list}: {problem}"
            ),
            Error::Teeth { gear, tooth, arc_mm, why } => write!(
                f,
                "{gear} gear, tooth {tooth} (pitch arc {arc_mm:.3} mm): {why}"
            ),
            Error::OutlineCrossing { gear, x_mm, y_mm } => write!(
                f,
                "{gear} gear: the toothed outline crosses itself near ({x_mm:.4}, {y_mm:.4}) mm"
            ),
            Error::Infeasible(message) => write!(
                f,
                "{message}"
            ),
            Error::OpenTarget { name, gap_mm, spacing_mm } => write!(
                f,
                "{name}: the target path is open: its last point is {gap_mm:.3} mm from its first, more than three times its median spacing {spacing_mm:.3} mm (close it, or end it where it starts)"
            ),
            Error::OutOfReach { name, distance_mm, inner_mm, outer_mm } => write!(
                f,
                "{name}: out of the arm's reach: {distance_mm:.3} mm from the carrier axis, and the tip of any design in the search's box stays {inner_mm:.3} to {outer_mm:.3} mm from it (is the target in mm, in the machine frame with its origin on the carrier axis?)"
            ),
            Error::SecondPair(inner) => write!(
                f,
                "gear.second_curve (the intermediate's layer B, driving the planet): {inner}"
            ),
            Error::TargetCrossing { name, other, x_mm, y_mm } => write!(
                f,
                "{name}: the target path crosses itself at ({x_mm:.3}, {y_mm:.3}) mm: the piece from this point meets the piece from {other}"
            ),
        }
    }
}

/// A scene path with the papers' symbol where they name one: `train.arm_length_mm (S)`.
struct Named<'a>(&'a str);

impl fmt::Display for Named<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match symbol(self.0) {
            Some(symbol) => write!(f, "{} ({symbol})", self.0),
            None => write!(f, "{}", self.0),
        }
    }
}

/// Displays a number readably: scientific notation when very large or very small.
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v.is_finite() && v != 0.0 && !(1e-4..1e9).contains(&v.abs()) {
            write!(f, "{v:e}")
        } else {
            write!(f, "{v}")
        }
    }
}
