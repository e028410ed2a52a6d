//! Manufacturing and assembly tolerances: how far a built mechanism may stand from its
//! drawing, per group of parameters, as a ± band (uniform) or a standard deviation
//! (normal). The defaults are what an ordinary workshop holds; docs/robustness.md gives
//! their sources.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// One group's spread: `{ band = 0.02 }` (uniform on ± the band) or `{ sigma = 0.01 }`
/// (normal with that standard deviation), in the group's unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Spread {
    /// Uniform on `[−band, +band]`.
    Band(f64),
    /// Normal with standard deviation `sigma`.
    Sigma(f64),
}

impl Spread {
    /// The deviation at probability `u` in (0, 1) (the inverse distribution function).
    pub fn deviation(self, u: f64) -> f64 {
        match self {
            Spread::Band(h) => h * (2.0 * u - 1.0),
            Spread::Sigma(s) => {
                s * std::f64::consts::SQRT_2 * statrs::function::erf::erf_inv(2.0 * u - 1.0)
            }
        }
    }

    /// Half-width of the range the worst-case bound explores: the band, or 3σ.
    pub fn worst_case(self) -> f64 {
        match self {
            Spread::Band(h) => h,
            Spread::Sigma(s) => 3.0 * s,
        }
    }

    /// Whether the group is held exactly (no deviation).
    pub fn is_exact(self) -> bool {
        self.worst_case() == 0.0
    }

    fn check(self, name: &str) -> Result<()> {
        let (what, v) = match self {
            Spread::Band(h) => ("band", h),
            Spread::Sigma(s) => ("sigma", s),
        };
        // A tolerance beyond a metre is a typing error, not a workshop.
        if !(0.0..=1000.0).contains(&v) {
            return Err(Error::OutOfRange {
                name: format!("tolerances.{name}.{what}"),
                value: v,
                expected: "0 to 1000 (in the group's unit)".into(),
            });
        }
        Ok(())
    }
}

/// The toleranced groups, each a deviation from the drawing. Lengths in mm, angles in
/// degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Tolerances {
    /// Each pitch-curve control radius, independently (a Fourier curve's `c0`, an
    /// ellipse's semi-major axis): the cut gear's radial error. Default ±0.02 mm.
    pub radius_mm: Spread,
    /// The carrier's bores: each gear pair held this much further apart than its centre
    /// distance (the gears then mesh with backlash). Default ±0.03 mm.
    pub centre_distance_mm: Spread,
    /// `Φ0`, the sun's installation angle. Default ±0.1°.
    pub phi0_deg: Spread,
    /// `β0`, the arm's angle on the planet shaft. Default ±0.2°.
    pub beta0_deg: Spread,
    /// `γ0`, the carrier's corner angle, a property of the machined carrier: one value
    /// per gear variant. Default ±0.05°.
    pub gamma0_deg: Spread,
    /// `S`, the arm length. Default ±0.5 mm.
    pub arm_length_mm: Spread,
    /// `H1`, the pusher offset. Default ±0.3 mm.
    pub pusher_offset_mm: Spread,
    /// The tray surface's distance from the carrier axis. Default ±1 mm.
    pub tray_distance_mm: Spread,
    /// The tray normal's direction. Default ±0.5°.
    pub tray_normal_deg: Spread,
    /// Samples of the tolerance analysis and of a robust goal, per design.
    pub samples: usize,
    /// How many samples share one set of machined parts, the cut gears (their radii) and
    /// the carrier (its `γ0`): each set is closed and solved once and assembled this many
    /// times (assembly errors cost no closure). 1: every sample its own parts.
    pub assemblies_per_part_set: usize,
    /// Seed of the scrambled Sobol points: every design of a robust search meets the same
    /// deviations (common random numbers).
    #[serde(with = "crate::whole_number")]
    pub seed: u64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            radius_mm: Spread::Band(0.02),
            centre_distance_mm: Spread::Band(0.03),
            phi0_deg: Spread::Band(0.1),
            beta0_deg: Spread::Band(0.2),
            gamma0_deg: Spread::Band(0.05),
            arm_length_mm: Spread::Band(0.5),
            pusher_offset_mm: Spread::Band(0.3),
            tray_distance_mm: Spread::Band(1.0),
            tray_normal_deg: Spread::Band(0.5),
            samples: 64,
            assemblies_per_part_set: 8,
            seed: 1,
        }
    }
}

/// The toleranced quantities other than the radii, in the order of a sample's deviations.
pub(crate) const ASSEMBLY: [&str; 8] = [
    "centre_distance_mm",
    "phi0_deg",
    "beta0_deg",
    "gamma0_deg",
    "arm_length_mm",
    "pusher_offset_mm",
    "tray_distance_mm",
    "tray_normal_deg",
];

impl Tolerances {
    /// Most samples per design (the scrambled Sobol sequence's length).
    pub const MAX_SAMPLES: usize = 1 << 16;

    /// Whether these are the defaults (a scene then leaves them out when written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// The assembly groups' spreads, in [`ASSEMBLY`] order.
    pub fn assembly(&self) -> [Spread; 8] {
        [
            self.centre_distance_mm,
            self.phi0_deg,
            self.beta0_deg,
            self.gamma0_deg,
            self.arm_length_mm,
            self.pusher_offset_mm,
            self.tray_distance_mm,
            self.tray_normal_deg,
        ]
    }

    /// Checks every spread and count, naming the bad one.
    pub fn validate(&self) -> Result<()> {
        self.radius_mm.check("radius_mm")?;
        for (name, spread) in ASSEMBLY.iter().zip(self.assembly()) {
            spread.check(name)?;
        }
        if !(1..=Self::MAX_SAMPLES).contains(&self.samples) {
            return Err(Error::OutOfRange {
                name: "tolerances.samples".into(),
                value: self.samples as f64,
                expected: format!("1 to {}", Self::MAX_SAMPLES),
            });
        }
        if !(1..=self.samples).contains(&self.assemblies_per_part_set) {
            return Err(Error::OutOfRange {
                name: "tolerances.assemblies_per_part_set".into(),
                value: self.assemblies_per_part_set as f64,
                expected: format!("1 to tolerances.samples = {}", self.samples),
            });
        }
        Ok(())
    }

    /// The sets of machined parts among the samples.
    pub fn part_sets(&self) -> usize {
        self.samples.div_ceil(self.assemblies_per_part_set)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_normal_spread_inverts_its_distribution() {
        let s = Spread::Sigma(2.0);
        // Φ(1) = 0.841344746…, Φ(−2) = 0.022750131…
        assert!((s.deviation(0.841_344_746_068_543) - 2.0).abs() < 1e-9);
        assert!((s.deviation(0.022_750_131_948_179) + 4.0).abs() < 1e-9);
        assert_eq!(s.deviation(0.5), 0.0);
        let b = Spread::Band(0.3);
        assert!((b.deviation(0.0) + 0.3).abs() < 1e-15);
        assert!((b.deviation(0.75) - 0.15).abs() < 1e-15);
    }

    #[test]
    fn bad_tolerances_are_named() {
        let mut t = Tolerances {
            beta0_deg: Spread::Sigma(-1.0),
            ..Tolerances::default()
        };
        let e = t.validate().unwrap_err().to_string();
        assert!(e.contains("tolerances.beta0_deg.sigma"), "{e}");
        t.beta0_deg = Spread::Band(f64::NAN);
        assert!(t.validate().is_err());
        t = Tolerances {
            assemblies_per_part_set: 65,
            ..Tolerances::default()
        };
        let e = t.validate().unwrap_err().to_string();
        assert!(e.contains("tolerances.assemblies_per_part_set"), "{e}");
    }
}
