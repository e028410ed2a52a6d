//! Named scene parameters that search, sweeps and `--set`-like tools can read and write:
//! dotted paths such as `train.phi0_deg` or `gear.curve.radii_mm[3]`, parsed once into
//! typed field accessors so that applying a design vector is a handful of field writes.

use crate::curve::CurveSpec;
use crate::error::{Error, Result};
use crate::scene::Scene;

type Scalar = fn(&mut Scene) -> Option<&mut f64>;
type List = fn(&mut Scene) -> Option<&mut Vec<f64>>;

/// Scalar parameters by path.
const SCALARS: &[(&str, Scalar)] = &[
    ("train.phi0_deg", |s| Some(&mut s.train.phi0_deg)),
    ("train.beta0_deg", |s| Some(&mut s.train.beta0_deg)),
    ("train.arm_length_mm", |s| Some(&mut s.train.arm_length_mm)),
    ("train.pusher_offset_mm", |s| {
        Some(&mut s.train.pusher_offset_mm)
    }),
    ("train.gamma0_deg", |s| Some(&mut s.train.gamma0_deg)),
    ("train.carrier_speed_rpm", |s| {
        Some(&mut s.train.carrier_speed_rpm)
    }),
    ("agronomy.tray_normal_deg", |s| {
        Some(&mut s.agronomy.tray_normal_deg)
    }),
    ("agronomy.tray_depth_mm", |s| {
        Some(&mut s.agronomy.tray_depth_mm)
    }),
    ("agronomy.plant_spacing_mm", |s| {
        Some(&mut s.agronomy.plant_spacing_mm)
    }),
    ("agronomy.seedling_height_mm", |s| {
        Some(&mut s.agronomy.seedling_height_mm)
    }),
    ("agronomy.planting_depth_mm", |s| {
        Some(&mut s.agronomy.planting_depth_mm)
    }),
    ("agronomy.arm_half_width_mm", |s| {
        Some(&mut s.agronomy.arm_half_width_mm)
    }),
    ("agronomy.housing_margin_mm", |s| {
        Some(&mut s.agronomy.housing_margin_mm)
    }),
    ("gear.module.z_min", |s| Some(&mut s.gear.module.z_min)),
    ("gear.curve.c0_mm", |s| match &mut s.gear.curve {
        CurveSpec::Fourier { c0_mm, .. } => Some(c0_mm),
        _ => None,
    }),
    ("gear.curve.semi_major_mm", |s| match &mut s.gear.curve {
        CurveSpec::Ellipse { semi_major_mm, .. } => Some(semi_major_mm),
        _ => None,
    }),
    ("gear.curve.eccentricity", |s| match &mut s.gear.curve {
        CurveSpec::Ellipse { eccentricity, .. } => Some(eccentricity),
        _ => None,
    }),
    ("moving_box.eccentricity", |s| {
        Some(&mut s.moving_box.eccentricity)
    }),
    ("moving_box.pot_pitch_mm", |s| {
        Some(&mut s.moving_box.pot_pitch_mm)
    }),
    ("moving_box.window_deg", |s| {
        Some(&mut s.moving_box.window_deg)
    }),
    ("moving_box.window_centre_deg", |s| {
        Some(&mut s.moving_box.window_centre_deg)
    }),
];

/// List parameters by path (indexed as `path[i]`).
const LISTS: &[(&str, List)] = &[
    ("gear.curve.radii_mm", |s| match &mut s.gear.curve {
        CurveSpec::Spline { radii_mm, .. }
        | CurveSpec::Bspline { radii_mm, .. }
        | CurveSpec::Bezier { radii_mm, .. }
        | CurveSpec::Table { radii_mm, .. } => Some(radii_mm),
        _ => None,
    }),
    ("gear.curve.angles_deg", |s| match &mut s.gear.curve {
        CurveSpec::Spline { angles_deg, .. }
        | CurveSpec::Bspline { angles_deg, .. }
        | CurveSpec::Bezier { angles_deg, .. }
        | CurveSpec::Table { angles_deg, .. } => Some(angles_deg),
        _ => None,
    }),
    ("gear.curve.cos_mm", |s| match &mut s.gear.curve {
        CurveSpec::Fourier { cos_mm, .. } => Some(cos_mm),
        _ => None,
    }),
    ("gear.curve.sin_mm", |s| match &mut s.gear.curve {
        CurveSpec::Fourier { sin_mm, .. } => Some(sin_mm),
        _ => None,
    }),
];

#[derive(Clone, Copy)]
enum Access {
    Scalar(Scalar),
    Item(List, usize),
}

/// A parsed parameter path.
#[derive(Clone)]
pub struct Param {
    name: String,
    access: Access,
}

impl std::fmt::Debug for Param {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Param({})", self.name)
    }
}

impl Param {
    /// Parses `path` and checks that it exists in `scene` (e.g. the list is long enough).
    pub fn parse(path: &str, scene: &Scene) -> Result<Self> {
        let unknown = |why: String| Error::OutOfRange {
            name: format!("parameter '{path}'"),
            value: f64::NAN,
            expected: why,
        };
        let access = if let Some((base, rest)) = path.split_once('[') {
            let index: usize = rest
                .strip_suffix(']')
                .and_then(|i| i.parse().ok())
                .ok_or_else(|| unknown("an index like name[3]".into()))?;
            let (_, list) = LISTS
                .iter()
                .find(|(n, _)| *n == base)
                .ok_or_else(|| unknown(format!("one of {}", Self::known())))?;
            Access::Item(*list, index)
        } else {
            let (_, scalar) = SCALARS
                .iter()
                .find(|(n, _)| *n == path)
                .ok_or_else(|| unknown(format!("one of {}", Self::known())))?;
            Access::Scalar(*scalar)
        };
        let param = Self {
            name: path.to_string(),
            access,
        };
        let mut probe = scene.clone();
        if param.slot(&mut probe).is_none() {
            return Err(unknown(
                "a parameter this scene's pitch curve has (kind or length differ)".into(),
            ));
        }
        Ok(param)
    }

    /// Every known path pattern, for error messages.
    pub fn known() -> String {
        let mut names: Vec<String> = SCALARS.iter().map(|(n, _)| n.to_string()).collect();
        names.extend(LISTS.iter().map(|(n, _)| format!("{n}[i]")));
        names.join(", ")
    }

    fn slot<'a>(&self, scene: &'a mut Scene) -> Option<&'a mut f64> {
        match self.access {
            Access::Scalar(f) => f(scene),
            Access::Item(f, i) => f(scene).and_then(|v| v.get_mut(i)),
        }
    }

    /// The path this parameter was parsed from.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Writes `value` into `scene`.
    pub fn set(&self, scene: &mut Scene, value: f64) {
        if let Some(slot) = self.slot(scene) {
            *slot = value;
        }
    }

    /// Reads the current value from `scene`.
    pub fn get(&self, scene: &Scene) -> f64 {
        let mut copy = scene.clone();
        self.slot(&mut copy).map_or(f64::NAN, |v| *v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_sets_and_reads_back() {
        let mut scene = Scene::default();
        let p = Param::parse("gear.curve.radii_mm[3]", &scene).unwrap();
        p.set(&mut scene, 33.0);
        assert_eq!(p.get(&scene), 33.0);
        let q = Param::parse("train.gamma0_deg", &scene).unwrap();
        q.set(&mut scene, -40.0);
        assert_eq!(scene.train.gamma0_deg, -40.0);
        assert!(Param::parse("gear.curve.radii_mm[12]", &scene).is_err());
        assert!(Param::parse("gear.curve.eccentricity", &scene).is_err());
        assert!(Param::parse("train.nope", &scene).is_err());
    }
}
