//! Checks of a search state read from outside (a damaged or hand-edited checkpoint, a
//! migrant): lengths, points in the unit cube, violations that are numbers.

use crate::fitness::Candidate;

/// A state that does not fit its problem or contradicts itself (a damaged or hand-edited
/// checkpoint): what is wrong, for [`crate::Error::Checkpoint`].
pub(crate) fn state_error(problem: String) -> crate::Error {
    crate::Error::Checkpoint(problem)
}

/// Checks `what`'s length against `expected`.
pub(crate) fn check_len(what: &str, len: usize, expected: usize) -> crate::Result<()> {
    if len == expected {
        Ok(())
    } else {
        Err(state_error(format!(
            "{what} has {len} entries, expected {expected}"
        )))
    }
}

/// Checks a candidate: `dim` coordinates in the unit cube, `goals` goals, a violation that
/// is a number at least 0.
pub(crate) fn check_candidate(
    what: &str,
    c: &Candidate,
    dim: usize,
    goals: usize,
) -> crate::Result<()> {
    check_len(&format!("{what}: point"), c.u.len(), dim)?;
    check_len(&format!("{what}: goals"), c.fitness.f.len(), goals)?;
    if let Some(x) = c.u.iter().find(|x| !(0.0..=1.0).contains(*x)) {
        return Err(state_error(format!(
            "{what}: coordinate {x} is outside the unit cube"
        )));
    }
    if c.fitness.cv.is_nan() || c.fitness.cv < 0.0 || c.fitness.f.iter().any(|f| f.is_nan()) {
        return Err(state_error(format!(
            "{what}: fitness {:?} is not a violation >= 0 with goals that are numbers",
            c.fitness
        )));
    }
    Ok(())
}
