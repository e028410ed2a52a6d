//! Gear blanks as rigid bodies: the region inside a pitch curve, extruded by a face width,
//! of uniform density. The teeth add about as much outside the pitch curve as they take
//! away inside it, so the blank stands for the cut gear (an approximation of the order of
//! the module over the radius in the moment of inertia).

use crate::vec2::Vec2;
use serde::Serialize;

/// A blank's mass properties in its own frame (the gear's axle at the origin).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Blank {
    /// Mass (kg).
    pub mass_kg: f64,
    /// Centre of mass in the gear's own frame (mm): off the axle for a non-circular gear.
    pub centroid_mm: Vec2,
    /// Moment of inertia about the axis through the centre of mass, normal to the plane
    /// (kg·m²).
    pub inertia_kg_m2: f64,
}

impl Blank {
    /// No body.
    pub const NONE: Blank = Blank {
        mass_kg: 0.0,
        centroid_mm: Vec2::ZERO,
        inertia_kg_m2: 0.0,
    };

    /// The blank of a star-shaped pitch curve given as samples `(r, χ, w)`: the radius
    /// `r` (mm) at own angle `χ` (rad) with its quadrature weight `w = dχ` (rad) of a
    /// trapezoid rule over one turn (spectrally accurate for a smooth periodic curve).
    /// Area `½∮r²dχ`, first moment `⅓∮r³e(χ)dχ`, polar moment about the axle `¼∮r⁴dχ`.
    pub fn from_polar(
        samples: impl IntoIterator<Item = (f64, f64, f64)>,
        face_width_mm: f64,
        density_kg_m3: f64,
    ) -> Blank {
        let (mut area, mut first, mut polar) = (0.0, Vec2::ZERO, 0.0);
        for (r, chi, w) in samples {
            let r2 = r * r;
            area += 0.5 * r2 * w;
            first += crate::angle::unit(chi) * (r2 * r * w / 3.0);
            polar += 0.25 * r2 * r2 * w;
        }
        // mm² × mm × kg/m³ → kg: 1e-9; mm⁴ × mm × kg/m³ → kg·m²: 1e-15.
        let mass_kg = density_kg_m3 * face_width_mm * area * 1e-9;
        let centroid_mm = first * (1.0 / area);
        let about_axle = density_kg_m3 * face_width_mm * polar * 1e-15;
        Blank {
            mass_kg,
            centroid_mm,
            inertia_kg_m2: about_axle - mass_kg * centroid_mm.hypot2() * 1e-6,
        }
    }

    /// A point-like body's properties: `mass_kg` at `centroid_mm`, with `inertia_kg_m2`
    /// about it.
    pub fn body(mass_kg: f64, centroid_mm: Vec2, inertia_kg_m2: f64) -> Blank {
        Blank {
            mass_kg,
            centroid_mm,
            inertia_kg_m2,
        }
    }

    /// Two bodies fixed together (the same frame): the masses add, the centre of mass is
    /// their mean, the inertia moves to it (parallel axes).
    pub fn with(self, other: Blank) -> Blank {
        let mass_kg = self.mass_kg + other.mass_kg;
        if mass_kg == 0.0 {
            return Blank::NONE;
        }
        let centroid_mm =
            (self.centroid_mm * self.mass_kg + other.centroid_mm * other.mass_kg) * (1.0 / mass_kg);
        let shift = |b: &Blank| b.mass_kg * (b.centroid_mm - centroid_mm).hypot2() * 1e-6;
        Blank {
            mass_kg,
            centroid_mm,
            inertia_kg_m2: self.inertia_kg_m2 + shift(&self) + other.inertia_kg_m2 + shift(&other),
        }
    }

    /// Moment of inertia about the axle (the own frame's origin, kg·m²).
    pub fn about_axle(&self) -> f64 {
        self.inertia_kg_m2 + self.mass_kg * self.centroid_mm.hypot2() * 1e-6
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    fn uniform(n: usize, r: impl Fn(f64) -> f64) -> Vec<(f64, f64, f64)> {
        let h = TAU / n as f64;
        (0..n).map(|j| (r(j as f64 * h), j as f64 * h, h)).collect()
    }

    #[test]
    fn a_disc_has_the_textbook_mass_and_inertia() {
        let (r, b, rho) = (40.0, 12.0, 7850.0);
        let disc = Blank::from_polar(uniform(64, |_| r), b, rho);
        let mass = rho * PI * (r * 1e-3).powi(2) * b * 1e-3;
        assert!((disc.mass_kg - mass).abs() < 1e-12 * mass);
        assert!(disc.centroid_mm.hypot() < 1e-12);
        let inertia = 0.5 * mass * (r * 1e-3).powi(2);
        assert!((disc.inertia_kg_m2 - inertia).abs() < 1e-12 * inertia);
    }

    #[test]
    fn an_ellipse_about_its_focus_has_its_centre_of_mass_at_the_centre() {
        // r(χ) = p/(1 + e cos χ) about the right focus; the centre lies at −c = −a·e.
        let (a, e) = (30.0, 0.4);
        let p = a * (1.0 - e * e);
        let blank = Blank::from_polar(uniform(256, |x| p / (1.0 + e * x.cos())), 10.0, 1000.0);
        let b = a * (1.0 - e * e).sqrt();
        let mass = 1000.0 * PI * a * b * 10.0 * 1e-9;
        assert!((blank.mass_kg - mass).abs() < 1e-10 * mass);
        assert!((blank.centroid_mm - Vec2::new(-a * e, 0.0)).hypot() < 1e-9);
        // About the centre: m(a² + b²)/4.
        let inertia = mass * (a * a + b * b) * 1e-6 / 4.0;
        assert!((blank.inertia_kg_m2 - inertia).abs() < 1e-9 * inertia);
    }

    #[test]
    fn bodies_fixed_together_keep_the_parallel_axis_theorem() {
        let a = Blank::body(2.0, Vec2::new(100.0, 0.0), 0.01);
        let b = Blank::body(1.0, Vec2::new(-50.0, 30.0), 0.002);
        let both = a.with(b);
        assert!((both.about_axle() - a.about_axle() - b.about_axle()).abs() < 1e-15);
        assert_eq!(both.mass_kg, 3.0);
    }
}
