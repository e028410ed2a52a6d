//! The variable-speed moving box (moving-box paper): an elliptical-gear drive of the spiral
//! shaft, the sinusoidal spiral shaft, slider forces, and the box travel while picking.

use crate::curve::{Ellipse, PitchCurve, TAU};
use crate::error::{finite, length, positive, Error, Result};
use crate::gear::GearPair;
use crate::golden::golden_min;
use crate::quadrature::SpectralIntegrator;
use crate::resolution::Resolution;
use crate::vec2::Vec2;
use serde::{Deserialize, Serialize};

const G: f64 = 9.806_65;

/// Moving-box parameters (paper defaults; masses in kg, lengths in mm, angles in degrees).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BoxSpec {
    /// Eccentricity `k` of the elliptical gears; `1/(2+√3)` gives a speed ratio of 3.
    pub eccentricity: f64,
    /// If set, `k` is derived from this fastest/slowest speed ratio instead (≥ 1).
    pub speed_ratio: Option<f64>,
    /// Pot pitch: box travel per input turn (mm).
    pub pot_pitch_mm: f64,
    /// Pot width: the box may move at most 1/6 of it while a seedling is picked (mm).
    pub pot_width_mm: f64,
    /// Gear module (mm) and tooth count: fix the ellipses' size.
    pub module_mm: f64,
    pub teeth: u32,
    /// Input shaft speed (r/min).
    pub input_speed_rpm: f64,
    /// Picking window on the driving gear: width and centre (deg).
    pub window_deg: f64,
    pub window_centre_deg: f64,
    /// Sinusoidal spiral shaft: spiral angle `φs` of the groove development (deg).
    pub spiral_angle_deg: f64,
    /// Slider dynamics: box mass (kg), groove-wall angle `α`, groove friction angle `φ` and
    /// the box's slide friction angle `φ1` (deg). The paper gives none of them: assumptions.
    pub box_mass_kg: f64,
    pub groove_wall_angle_deg: f64,
    pub groove_friction_angle_deg: f64,
    pub slide_friction_angle_deg: f64,
    /// Transplanter coupling: box input turns per carrier turn (one pot per pick: 3 for
    /// the three-arm mechanism; a transplanter scene requires `train.arms`).
    pub input_turns_per_carrier_turn: f64,
}

impl Default for BoxSpec {
    fn default() -> Self {
        Self {
            eccentricity: 1.0 / (2.0 + 3f64.sqrt()),
            speed_ratio: None,
            pot_pitch_mm: 20.0,
            pot_width_mm: 18.0,
            module_mm: 2.25,
            teeth: 23,
            input_speed_rpm: 200.0,
            window_deg: 60.0,
            window_centre_deg: 180.0,
            spiral_angle_deg: 45.0,
            box_mass_kg: 5.0,
            groove_wall_angle_deg: 30.0,
            groove_friction_angle_deg: 8.5,
            slide_friction_angle_deg: 8.5,
            input_turns_per_carrier_turn: 3.0,
        }
    }
}

/// `k` giving the fastest/slowest speed ratio `r` of an elliptical pair: `((1+k)/(1-k))² = r`.
pub fn eccentricity_for_ratio(r: f64) -> Result<f64> {
    finite("moving_box.speed_ratio", r)?;
    if r < 1.0 {
        return Err(Error::OutOfRange {
            name: "moving_box.speed_ratio".into(),
            value: r,
            expected: ">= 1".into(),
        });
    }
    let q = r.sqrt();
    Ok((q - 1.0) / (q + 1.0))
}

impl BoxSpec {
    /// The eccentricity actually used.
    pub fn k(&self) -> Result<f64> {
        let k = match self.speed_ratio {
            Some(r) => eccentricity_for_ratio(r)?,
            None => self.eccentricity,
        };
        Ellipse::new(1.0, k)
            .map(|e| e.k)
            .map_err(|_| Error::OutOfRange {
                name: "moving_box.eccentricity".into(),
                value: k,
                expected: "0 <= k < 1".into(),
            })
    }

    /// Checks every parameter, naming the bad one.
    pub fn validate(&self) -> Result<()> {
        self.k()?;
        for (name, v) in [
            ("moving_box.pot_pitch_mm", self.pot_pitch_mm),
            ("moving_box.pot_width_mm", self.pot_width_mm),
            ("moving_box.module_mm", self.module_mm),
        ] {
            positive(name, v)?;
            length(name, v)?;
        }
        for (name, v, max) in [
            (
                "moving_box.input_speed_rpm",
                self.input_speed_rpm,
                Self::MAX_INPUT_SPEED_RPM,
            ),
            (
                "moving_box.box_mass_kg",
                self.box_mass_kg,
                Self::MAX_MASS_KG,
            ),
            (
                "moving_box.input_turns_per_carrier_turn",
                self.input_turns_per_carrier_turn,
                1e3,
            ),
        ] {
            positive(name, v)?;
            if v > max {
                return Err(Error::OutOfRange {
                    name: name.into(),
                    value: v,
                    expected: format!("at most {max:e}"),
                });
            }
        }
        for (name, v) in [
            ("moving_box.window_deg", self.window_deg),
            ("moving_box.window_centre_deg", self.window_centre_deg),
            ("moving_box.spiral_angle_deg", self.spiral_angle_deg),
            (
                "moving_box.groove_wall_angle_deg",
                self.groove_wall_angle_deg,
            ),
            (
                "moving_box.groove_friction_angle_deg",
                self.groove_friction_angle_deg,
            ),
            (
                "moving_box.slide_friction_angle_deg",
                self.slide_friction_angle_deg,
            ),
        ] {
            finite(name, v)?;
        }
        if !(self.window_deg >= 0.0 && self.window_deg <= 360.0) {
            return Err(Error::OutOfRange {
                name: "moving_box.window_deg".into(),
                value: self.window_deg,
                expected: "0..=360".into(),
            });
        }
        // The groove development needs 0 < φs < 90°; the slider forces divide by
        // cos(α + φ); every angle of the slider is in [0°, 90°).
        if !(self.spiral_angle_deg > 0.0 && self.spiral_angle_deg < 90.0) {
            return Err(Error::OutOfRange {
                name: "moving_box.spiral_angle_deg".into(),
                value: self.spiral_angle_deg,
                expected: "between 0° and 90° (exclusive)".into(),
            });
        }
        for (name, v) in [
            (
                "moving_box.groove_wall_angle_deg",
                self.groove_wall_angle_deg,
            ),
            (
                "moving_box.groove_friction_angle_deg",
                self.groove_friction_angle_deg,
            ),
            (
                "moving_box.groove_wall_angle_deg + groove_friction_angle_deg",
                self.groove_wall_angle_deg + self.groove_friction_angle_deg,
            ),
            (
                "moving_box.slide_friction_angle_deg",
                self.slide_friction_angle_deg,
            ),
        ] {
            if !(0.0..90.0).contains(&v) {
                return Err(Error::OutOfRange {
                    name: name.into(),
                    value: v,
                    expected: "at least 0° and below 90°".into(),
                });
            }
        }
        if self.teeth == 0 {
            return Err(Error::OutOfRange {
                name: "moving_box.teeth".into(),
                value: 0.0,
                expected: ">= 1".into(),
            });
        }
        Ok(())
    }

    /// Largest accepted input speed (r/min): transplanters run at a few hundred.
    pub const MAX_INPUT_SPEED_RPM: f64 = 1e5;
    /// Largest accepted box mass (kg).
    pub const MAX_MASS_KG: f64 = 1e5;

    /// Input angular speed (rad/s).
    pub fn omega(&self) -> f64 {
        self.input_speed_rpm * TAU / 60.0
    }

    /// The driven (spiral-shaft) angle `φ2(φ1)`, closed form, unwrapped (rad).
    pub fn phi2(&self, phi1: f64) -> f64 {
        let k = self.k().unwrap_or(0.0);
        Ellipse { semi_major: 1.0, k }.phi2_closed_form(phi1)
    }

    /// `dφ2/dφ1 = 1/i12` and `d²φ2/dφ1²` (paper eq. 7 inverted).
    pub fn phi2_derivatives(&self, phi1: f64) -> (f64, f64) {
        let k = self.k().unwrap_or(0.0);
        let d = 1.0 - 2.0 * k * phi1.cos() + k * k;
        (
            (1.0 - k * k) / d,
            -(1.0 - k * k) * 2.0 * k * phi1.sin() / (d * d),
        )
    }

    /// Box travel over the driver window `[a, b]` (rad): paper eq. 9, closed form (mm).
    pub fn elliptic_delta_h(&self, a: f64, b: f64) -> f64 {
        self.pot_pitch_mm / TAU * (self.phi2(b) - self.phi2(a))
    }

    /// The same travel with a constant-speed box (mm).
    pub fn uniform_delta_h(&self, a: f64, b: f64) -> f64 {
        self.pot_pitch_mm / TAU * (b - a)
    }

    /// Sinusoidal spiral shaft: box displacement (mm) at input angle `phi1` (rad).
    ///
    /// `v1 = Δv cos(ωt) + v` (paper eq. 1) with one oscillation and one pot pitch per pick;
    /// one input turn is one pick (the paper's `ω = 4π/T` is the same law for a mechanism
    /// that picks twice per turn of period T). The slowest speed falls on the window centre
    /// and `Δv` gives the elliptical drive's fastest/slowest ratio, so the two compare.
    pub fn sinusoidal_displacement(&self, phi1: f64) -> f64 {
        let (v, dv, w) = self.sinusoid();
        let t = phi1 / w;
        // Speed minimum (cos = −1) at the window centre: phase π there.
        let phase = std::f64::consts::PI - self.window_centre_deg.to_radians();
        v * t + dv / w * ((w * t + phase).sin() - phase.sin())
    }

    /// `(v, Δv, ω)` of the sinusoidal law (mm/s, mm/s, rad/s).
    fn sinusoid(&self) -> (f64, f64, f64) {
        let w = self.omega();
        let v = self.pot_pitch_mm * w / TAU;
        let ratio = {
            let k = self.k().unwrap_or(0.0);
            ((1.0 + k) / (1.0 - k)).powi(2)
        };
        (v, v * (ratio - 1.0) / (ratio + 1.0), w)
    }

    /// Groove development of the sinusoidal spiral shaft (paper eqs. 3–5): the sine curve
    /// `S' = κ sin(ωt)` rotated by `π/2 − φs`, with `κ = Δv/ω` (mm); returns `(X, Y)`.
    pub fn groove_point(&self, t: f64) -> Vec2 {
        let (_, dv, w) = self.sinusoid();
        let kappa = dv / w;
        let (s, c) = self.spiral_angle_deg.to_radians().sin_cos();
        Vec2::new(
            t * s - kappa * (w * t).sin() * c,
            t * c + kappa * (w * t).sin() * s,
        )
    }

    /// Largest box acceleration over the input turn, elliptical drive (m/s²; the least is
    /// its negative). Closed form: `d²φ2/dφ1² ∝ sin φ1 / D²` with `D = 1 − 2k cos φ1 + k²`
    /// is extreme where `2k c² + (1 + k²) c − 4k = 0`, `c = cos φ1`.
    pub fn accel_max(&self) -> f64 {
        let k = self.k().unwrap_or(0.0);
        let p = 1.0 + k * k;
        // The root in [0, 1), in the form without cancellation (0 at k = 0).
        let c = 8.0 * k / (p + (p * p + 32.0 * k * k).sqrt());
        let d = p - 2.0 * k * c;
        let d2 = (1.0 - k * k) * 2.0 * k * (1.0 - c * c).sqrt() / (d * d);
        let w = self.omega();
        self.pot_pitch_mm / TAU * d2 * w * w / 1000.0
    }

    /// Largest slider normal force over the input turn, elliptical drive (N). The force is
    /// affine in the acceleration, which sweeps `[−accel_max, accel_max]`: the larger of
    /// the two ends.
    pub fn slider_force_max(&self) -> f64 {
        let a = self.accel_max();
        let (up, down) = (self.slider_forces(a).0, self.slider_forces(-a).0);
        up.abs().max(down.abs())
    }

    /// Slider forces (paper eqs. 12–15) for a box acceleration `x_dd` (m/s²): `(F_n, F_oy)` in N.
    pub fn slider_forces(&self, x_dd: f64) -> (f64, f64) {
        let m = self.box_mass_kg;
        let alpha = self.groove_wall_angle_deg.to_radians();
        let phi = self.groove_friction_angle_deg.to_radians();
        let phi1 = self.slide_friction_angle_deg.to_radians();
        let drive = G * phi1.tan() - x_dd;
        let fn_ = m * phi.cos() * drive / (alpha + phi).cos();
        let foy = m * drive * (alpha - phi).sin() / (alpha + phi).cos();
        (fn_, foy)
    }
}

/// The moving box's headline results.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoxReport {
    pub eccentricity: f64,
    pub speed_ratio: f64,
    /// Semi-major axis of each ellipse for the given module and teeth (mm).
    pub semi_major_mm: f64,
    pub centre_distance_mm: f64,
    /// Window on the driving gear (deg).
    pub window_deg: [f64; 2],
    /// Box travel over the window: elliptical drive (closed form and numerical), constant
    /// speed, and sinusoidal spiral shaft (mm).
    pub elliptic_delta_h_mm: f64,
    pub elliptic_delta_h_numeric_mm: f64,
    pub uniform_delta_h_mm: f64,
    pub sinusoidal_delta_h_mm: f64,
    /// The window centre that minimises the elliptical travel (deg), found numerically.
    pub best_window_centre_deg: f64,
    /// The 1/6-pot-width limit and whether the elliptical drive keeps within it (mm).
    pub limit_mm: f64,
    pub within_limit: bool,
    /// Box speed extremes over the input turn, elliptical drive (mm/s).
    pub speed_min_mm_s: f64,
    pub speed_max_mm_s: f64,
    /// Largest slider normal force over the turn, elliptical drive (N).
    pub slider_force_max_n: f64,
}

/// Samples of the box motion over one input turn.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoxCurves {
    pub input_deg: Vec<f64>,
    pub elliptic_mm: Vec<f64>,
    pub elliptic_speed_mm_s: Vec<f64>,
    pub elliptic_accel_m_s2: Vec<f64>,
    pub uniform_mm: Vec<f64>,
    pub sinusoidal_mm: Vec<f64>,
    pub slider_normal_n: Vec<f64>,
}

/// Box displacement, speed, acceleration and slider force over one input turn.
pub fn box_curves(spec: &BoxSpec, samples: usize) -> BoxCurves {
    let w = spec.omega();
    let scale = spec.pot_pitch_mm / TAU;
    let mut c = BoxCurves {
        input_deg: Vec::with_capacity(samples + 1),
        elliptic_mm: Vec::with_capacity(samples + 1),
        elliptic_speed_mm_s: Vec::with_capacity(samples + 1),
        elliptic_accel_m_s2: Vec::with_capacity(samples + 1),
        uniform_mm: Vec::with_capacity(samples + 1),
        sinusoidal_mm: Vec::with_capacity(samples + 1),
        slider_normal_n: Vec::with_capacity(samples + 1),
    };
    for j in 0..=samples {
        let phi = TAU * j as f64 / samples as f64;
        let (d1, d2) = spec.phi2_derivatives(phi);
        let accel = scale * d2 * w * w / 1000.0;
        c.input_deg.push(phi.to_degrees());
        c.elliptic_mm.push(scale * spec.phi2(phi));
        c.elliptic_speed_mm_s.push(scale * d1 * w);
        c.elliptic_accel_m_s2.push(accel);
        c.uniform_mm.push(scale * phi);
        c.sinusoidal_mm.push(spec.sinusoidal_displacement(phi));
        c.slider_normal_n.push(spec.slider_forces(accel).0);
    }
    c
}

/// Evaluates the moving box for the spec's window (or `window` in rad, if given).
pub fn evaluate_box(
    spec: &BoxSpec,
    window: Option<[f64; 2]>,
    resolution: &Resolution,
) -> Result<BoxReport> {
    resolution.validate()?;
    let mut integrator = SpectralIntegrator::new(resolution.samples_per_turn);
    evaluate_box_with(spec, window, resolution, &mut integrator)
}

/// As [`evaluate_box`], reusing planned transforms (re-planned if the length differs).
pub(crate) fn evaluate_box_with(
    spec: &BoxSpec,
    window: Option<[f64; 2]>,
    resolution: &Resolution,
    integrator: &mut SpectralIntegrator,
) -> Result<BoxReport> {
    spec.validate()?;
    let k = spec.k()?;
    let [a, b] = window.unwrap_or_else(|| {
        let (c, w) = (
            spec.window_centre_deg.to_radians(),
            spec.window_deg.to_radians(),
        );
        [c - w / 2.0, c + w / 2.0]
    });
    // Size: the ellipse whose perimeter carries `teeth` teeth of the module.
    let unit_pair = GearPair::solve_with(
        PitchCurve::Ellipse(Ellipse::new(1.0, k)?),
        *resolution,
        integrator,
    )?;
    let semi_major =
        spec.module_mm * std::f64::consts::PI * spec.teeth as f64 / unit_pair.perimeter();
    unit_pair.prepare_phi2(integrator);
    let numeric = spec.pot_pitch_mm / TAU * (unit_pair.phi2(b) - unit_pair.phi2(a));
    // Best window centre for this width: golden-section search of the travel.
    let width = b - a;
    let travel = |c: f64| spec.elliptic_delta_h(c - width / 2.0, c + width / 2.0);
    let best = golden_min(travel, 0.0, TAU, 1e-10);
    let w = spec.omega();
    let scale = spec.pot_pitch_mm / TAU;
    let delta = spec.elliptic_delta_h(a, b);
    let limit = spec.pot_width_mm / 6.0;
    BoxReport {
        eccentricity: k,
        speed_ratio: ((1.0 + k) / (1.0 - k)).powi(2),
        semi_major_mm: semi_major,
        centre_distance_mm: 2.0 * semi_major,
        window_deg: [a.to_degrees(), b.to_degrees()],
        elliptic_delta_h_mm: delta,
        elliptic_delta_h_numeric_mm: numeric,
        uniform_delta_h_mm: spec.uniform_delta_h(a, b),
        sinusoidal_delta_h_mm: spec.sinusoidal_displacement(b) - spec.sinusoidal_displacement(a),
        best_window_centre_deg: best.to_degrees(),
        limit_mm: limit,
        within_limit: delta <= limit,
        speed_min_mm_s: scale * w * (1.0 - k) / (1.0 + k),
        speed_max_mm_s: scale * w * (1.0 + k) / (1.0 - k),
        slider_force_max_n: spec.slider_force_max(),
    }
    .checked()
}

impl BoxReport {
    /// The report if every number in it is finite: a last guard against inputs that pass
    /// each check alone but overflow together.
    fn checked(self) -> Result<Self> {
        for (name, v) in [
            ("moving box: semi-major axis (mm)", self.semi_major_mm),
            (
                "moving box: elliptical travel (mm)",
                self.elliptic_delta_h_mm,
            ),
            (
                "moving box: elliptical travel, numerical (mm)",
                self.elliptic_delta_h_numeric_mm,
            ),
            (
                "moving box: constant-speed travel (mm)",
                self.uniform_delta_h_mm,
            ),
            (
                "moving box: sinusoidal-shaft travel (mm)",
                self.sinusoidal_delta_h_mm,
            ),
            ("moving box: least speed (mm/s)", self.speed_min_mm_s),
            ("moving box: greatest speed (mm/s)", self.speed_max_mm_s),
            ("moving box: slider force (N)", self.slider_force_max_n),
        ] {
            finite(name, v)?;
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratio_three_gives_the_papers_eccentricity() {
        assert!((eccentricity_for_ratio(3.0).unwrap() - 1.0 / (2.0 + 3f64.sqrt())).abs() < 1e-15);
        assert!(eccentricity_for_ratio(0.5).is_err());
    }

    #[test]
    fn slider_forces_follow_eq_14_15() {
        let s = BoxSpec {
            groove_wall_angle_deg: 0.0,
            groove_friction_angle_deg: 0.0,
            ..BoxSpec::default()
        };
        // α = φ = 0: F_n = m (g tan φ1 − ẍ), F_oy = 0.
        let (fn_, foy) = s.slider_forces(1.0);
        assert!((fn_ - 5.0 * (G * 8.5f64.to_radians().tan() - 1.0)).abs() < 1e-12);
        assert!(foy.abs() < 1e-12);
    }
}
