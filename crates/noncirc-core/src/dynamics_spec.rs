//! What the dynamics at working speed needs beyond the geometry: the gears' face width and
//! material, the arm as a rigid body, the carrier, gravity and the loads at the tip
//! (`[dynamics]` in a scene; docs/dynamics.md gives the sources of the defaults), and the
//! gear material the teeth's stresses are checked against. The working speed is the
//! train's (`train.carrier_speed_rpm` or `train.picks_per_minute`).

use serde::{Deserialize, Serialize};

/// The bodies' and loads' values (SI units except lengths in mm and angles in degrees).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DynamicsSpec {
    /// Face width `b` of every gear (mm).
    pub face_width_mm: f64,
    /// Density `ρg` of the gear blanks (kg/m³): steel.
    pub gear_density_kg_m3: f64,
    /// Mass `ma` of one arm with its claw and pusher (kg).
    pub arm_mass_kg: f64,
    /// Distance `sa` from the planet centre to the arm's centre of mass, along `O3 → D` (mm).
    pub arm_com_mm: f64,
    /// Moment of inertia `Ja` of the arm about its centre of mass (kg·m²).
    pub arm_inertia_kg_m2: f64,
    /// Mass `mc` of the carrier (kg), its centre of mass on its axis.
    pub carrier_mass_kg: f64,
    /// Moment of inertia `Jc` of the carrier about its axis (kg·m²).
    pub carrier_inertia_kg_m2: f64,
    /// Moment of inertia `Jf` of a flywheel on the carrier's axis, or of the drive line
    /// reduced to it (kg·m²); 0: none.
    pub flywheel_inertia_kg_m2: f64,
    /// Coefficient of speed fluctuation `δa` the drive allows, `(ω_max − ω_min)/ω_mean`,
    /// for which the least flywheel is reported.
    pub speed_fluctuation_allowed: f64,
    /// Gravity `g` (m/s²), along −y.
    pub gravity_m_s2: f64,
    /// Seedling separation force `Fp` at the tip while it is in the tray (N), against the
    /// tip's motion.
    pub picking_force_n: f64,
    /// Planting resistance `Fs` at the tip (N), against the tip's motion over
    /// `planting_span_deg` of carrier angle centred on the planting instant.
    pub planting_force_n: f64,
    /// Carrier angle over which the planting resistance acts (°).
    pub planting_span_deg: f64,
    /// Carrier angles per turn at which the dynamics is computed (a multiple of the arm
    /// count): the peaks of a sharp design need more than the kinematics' nodes
    /// (docs/dynamics.md: the paper's peak torque is 20 % low at 120, within 0.1 % at 360).
    pub samples_per_turn: usize,
    /// The gear material, named (every gear of the train is of it).
    pub material: String,
    /// Young's modulus `E` of the material (GPa).
    pub youngs_modulus_gpa: f64,
    /// Poisson's ratio `ν` of the material.
    pub poisson_ratio: f64,
    /// Allowable tooth-root stress `σFE = YST·σFlim` (MPa): ISO 6336-5's bending endurance
    /// of the material, against which the root stress gives the bending safety factor.
    pub bending_limit_mpa: f64,
    /// Allowable contact stress `σHlim` (MPa): ISO 6336-5's pitting endurance, against
    /// which the flank's Hertz stress gives the contact safety factor.
    pub contact_limit_mpa: f64,
    /// Application factor `KA` (ISO 6336-1): the loads the cycle does not model (shocks
    /// from the drive, the tray and the soil) as a factor on the computed mesh forces.
    pub application_factor: f64,
}

/// The default material: a carburised and case-hardened steel such as 20CrMnTi, the usual
/// choice for transplanter gearboxes, with ISO 6336-5's values for quality MQ.
const DEFAULT_MATERIAL: &str = "case-hardened steel 20CrMnTi (ISO 6336-5, MQ)";

impl Default for DynamicsSpec {
    fn default() -> Self {
        Self {
            face_width_mm: 12.0,
            gear_density_kg_m3: 7850.0,
            arm_mass_kg: 0.45,
            arm_com_mm: 60.0,
            arm_inertia_kg_m2: 1.2e-3,
            carrier_mass_kg: 2.5,
            carrier_inertia_kg_m2: 0.0125,
            flywheel_inertia_kg_m2: 0.0,
            speed_fluctuation_allowed: 0.02,
            gravity_m_s2: 9.81,
            picking_force_n: 5.0,
            planting_force_n: 0.0,
            planting_span_deg: 20.0,
            samples_per_turn: 720,
            material: DEFAULT_MATERIAL.into(),
            youngs_modulus_gpa: 206.0,
            poisson_ratio: 0.3,
            bending_limit_mpa: 1000.0,
            contact_limit_mpa: 1500.0,
            application_factor: 1.25,
        }
    }
}

impl DynamicsSpec {
    /// Whether every value is the default (a written scene then leaves the table out).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}
