//! Numerical resolution: every accuracy knob, explicit, with its documented default.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The accuracy knobs of an evaluation. See `docs/accuracy.md` for each level's measured
/// error and cost.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Resolution {
    /// Uniform samples of the pitch curve per turn, which are also the carrier-angle samples
    /// per cycle. A multiple of 6, at least 12, and of `train.arms` in a mechanism scene
    /// (12 for four arms). Default 120 (docs/accuracy.md).
    pub samples_per_turn: usize,
    /// Largest accepted relative uncertainty of the centre distance, estimated from the
    /// half grid; above it the closure is reported as under-resolved. Default 1e-5
    /// (about 1 µm on the paper's 85 mm pair); at most 1e-2.
    pub closure_rel_tol: f64,
    /// Relative step below which the closure iteration stops. Default 1e-14; at most a
    /// tenth of `closure_rel_tol` (a looser stop would move the centre distance by more
    /// than the closure test can see).
    pub newton_rel_tol: f64,
}

impl Default for Resolution {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Resolution {
    /// The default level: trajectory error below 0.01 mm, angles below 0.01° (docs/accuracy.md).
    pub const DEFAULT: Resolution = Resolution {
        samples_per_turn: 120,
        closure_rel_tol: 1e-5,
        newton_rel_tol: 1e-14,
    };

    /// The screening level used inside search (docs/accuracy.md).
    pub const FAST: Resolution = Resolution {
        samples_per_turn: 60,
        closure_rel_tol: 1e-4,
        newton_rel_tol: 1e-12,
    };

    /// Largest accepted closure tolerance: 1 % of the centre distance.
    pub const MAX_CLOSURE_REL_TOL: f64 = 1e-2;

    /// Largest accepted samples per turn, 786 432: an evaluation holds about 175 bytes per
    /// sample (measured peak 141 MB here; 1.09 GB at 6·2^20), and the error at 2 880 is
    /// already 1e-11 mm (docs/accuracy.md).
    pub const MAX_SAMPLES: usize = 6 << 17;

    /// This resolution with another sample count.
    pub fn with_samples(self, samples_per_turn: usize) -> Self {
        Self {
            samples_per_turn,
            ..self
        }
    }

    /// Checks every knob, naming the bad one.
    pub fn validate(&self) -> Result<()> {
        let n = self.samples_per_turn;
        if !(12..=Self::MAX_SAMPLES).contains(&n) || !n.is_multiple_of(6) {
            return Err(Error::OutOfRange {
                name: "resolution.samples_per_turn".into(),
                value: n as f64,
                expected: format!("a multiple of 6 from 12 to {}", Self::MAX_SAMPLES),
            });
        }
        let c = self.closure_rel_tol;
        if !(c.is_finite() && c > 0.0 && c <= Self::MAX_CLOSURE_REL_TOL) {
            return Err(Error::OutOfRange {
                name: "resolution.closure_rel_tol".into(),
                value: c,
                expected: format!("0 < tol <= {:e}", Self::MAX_CLOSURE_REL_TOL),
            });
        }
        // The iteration stops within `newton_rel_tol` of the root; the acceptance test only
        // sees the quadrature's error, so the stopping error must stay well below it.
        let t = self.newton_rel_tol;
        if !(t.is_finite() && t > 0.0 && t <= 0.1 * c) {
            return Err(Error::OutOfRange {
                name: "resolution.newton_rel_tol".into(),
                value: t,
                expected: format!(
                    "0 < tol <= a tenth of resolution.closure_rel_tol ({c:e}), so the \
                     iteration's stopping error stays below the accepted closure uncertainty"
                ),
            });
        }
        Ok(())
    }
}
