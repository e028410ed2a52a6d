//! Named scene parameters that search, sweeps and Python read and write: every number of a
//! scene by the same dotted path as `--set` and the scene files (`train.phi0_deg`,
//! `gear.curve.radii_mm[3]`, `bounds.picking_angle_deg[0]`), parsed once into typed field
//! accessors so that applying a design vector is a handful of field writes.

use crate::curve::CurveSpec;
use crate::error::{finite, Error, Result};
use crate::scene::{Scene, SceneKind, SearchSpec};
use noncirc_search::nearest;

/// Reads a field (`None`: the scene does not have it, e.g. another curve kind, or an
/// optional field left unset).
type Get = fn(&Scene) -> Option<f64>;
/// Writes a field; `false` when the scene does not have it.
type Set = fn(&mut Scene, f64) -> bool;
/// A list field's length and element access.
type ListGet = fn(&Scene) -> Option<&Vec<f64>>;
type ListSet = fn(&mut Scene) -> Option<&mut Vec<f64>>;

/// A real field: `field!("path", a.b)`.
macro_rules! real {
    ($path:literal, $($f:ident).+) => {
        ($path, (|s| Some(s.$($f).+)) as Get, (|s, v| { s.$($f).+ = v; true }) as Set)
    };
}

/// An optional real field: unset reads as absent, and writing sets it.
macro_rules! optional {
    ($path:literal, $($f:ident).+) => {
        ($path, (|s| s.$($f).+) as Get, (|s, v| { s.$($f).+ = Some(v); true }) as Set)
    };
}

/// An integer field, written rounded to the nearest integer. A negative or non-finite value
/// saturates (Rust's float-to-integer cast) and is then refused by `Scene::validate`.
macro_rules! integer {
    ($path:literal, $ty:ty, $($f:ident).+) => {
        (
            $path,
            (|s| Some(s.$($f).+ as f64)) as Get,
            (|s, v| { s.$($f).+ = v.round() as $ty; true }) as Set,
        )
    };
}

/// An optional integer field.
macro_rules! optional_integer {
    ($path:literal, $ty:ty, $($f:ident).+) => {
        (
            $path,
            (|s| s.$($f).+.map(|x| x as f64)) as Get,
            (|s, v| { s.$($f).+ = Some(v.round() as $ty); true }) as Set,
        )
    };
}

/// One element of a two-sided bound `[lower, upper]`: `bound!("path", a.b, 0)`.
macro_rules! bound {
    ($path:literal, $($f:ident).+ [$i:literal]) => {
        ($path, (|s| Some(s.$($f).+[$i])) as Get, (|s, v| { s.$($f).+[$i] = v; true }) as Set)
    };
}

/// A field of one pitch-curve kind.
macro_rules! curve {
    ($path:literal, $kind:ident, $f:ident) => {
        (
            $path,
            (|s| match &s.gear.curve {
                CurveSpec::$kind { $f, .. } => Some(*$f),
                _ => None,
            }) as Get,
            (|s, v| match &mut s.gear.curve {
                CurveSpec::$kind { $f, .. } => {
                    *$f = v;
                    true
                }
                _ => false,
            }) as Set,
        )
    };
}

/// Every numeric scalar of a scene, by path: the same paths as `--set` and the scene files
/// (a test checks that every number in every built-in scene's serialisation is here).
const SCALARS: &[(&str, Get, Set)] = &[
    integer!(
        "resolution.samples_per_turn",
        usize,
        resolution.samples_per_turn
    ),
    real!("resolution.closure_rel_tol", resolution.closure_rel_tol),
    real!("resolution.newton_rel_tol", resolution.newton_rel_tol),
    curve!("gear.curve.c0_mm", Fourier, c0_mm),
    curve!("gear.curve.semi_major_mm", Ellipse, semi_major_mm),
    curve!("gear.curve.eccentricity", Ellipse, eccentricity),
    optional_integer!("gear.module.teeth", u32, gear.module.teeth),
    real!("gear.module.z_min", gear.module.z_min),
    optional!("gear.module.cutter_teeth", gear.module.cutter_teeth),
    real!("train.phi0_deg", train.phi0_deg),
    real!("train.beta0_deg", train.beta0_deg),
    real!("train.arm_length_mm", train.arm_length_mm),
    real!("train.pusher_offset_mm", train.pusher_offset_mm),
    real!("train.gamma0_deg", train.gamma0_deg),
    real!("train.carrier_speed_rpm", train.carrier_speed_rpm),
    integer!("train.arms", usize, train.arms),
    optional!("train.picks_per_minute", train.picks_per_minute),
    real!("agronomy.tray_normal_deg", agronomy.tray_normal_deg),
    real!("agronomy.tray_depth_mm", agronomy.tray_depth_mm),
    optional!("agronomy.tray_distance_mm", agronomy.tray_distance_mm),
    real!("agronomy.plant_spacing_mm", agronomy.plant_spacing_mm),
    real!("agronomy.seedling_height_mm", agronomy.seedling_height_mm),
    real!("agronomy.planting_depth_mm", agronomy.planting_depth_mm),
    real!("agronomy.arm_half_width_mm", agronomy.arm_half_width_mm),
    real!("agronomy.housing_margin_mm", agronomy.housing_margin_mm),
    real!("bounds.clearance_min_mm", bounds.clearance_min_mm),
    bound!("bounds.picking_angle_deg[0]", bounds.picking_angle_deg[0]),
    bound!("bounds.picking_angle_deg[1]", bounds.picking_angle_deg[1]),
    bound!("bounds.pushing_angle_deg[0]", bounds.pushing_angle_deg[0]),
    bound!("bounds.pushing_angle_deg[1]", bounds.pushing_angle_deg[1]),
    bound!(
        "bounds.angle_difference_deg[0]",
        bounds.angle_difference_deg[0]
    ),
    bound!(
        "bounds.angle_difference_deg[1]",
        bounds.angle_difference_deg[1]
    ),
    real!("bounds.seedling_push_max_mm", bounds.seedling_push_max_mm),
    real!(
        "bounds.ground_clearance_min_mm",
        bounds.ground_clearance_min_mm
    ),
    real!(
        "bounds.trajectory_height_min_mm",
        bounds.trajectory_height_min_mm
    ),
    real!("bounds.module_min_mm", bounds.module_min_mm),
    real!(
        "bounds.picking_admissible_min_mm",
        bounds.picking_admissible_min_mm
    ),
    real!("moving_box.eccentricity", moving_box.eccentricity),
    optional!("moving_box.speed_ratio", moving_box.speed_ratio),
    real!("moving_box.pot_pitch_mm", moving_box.pot_pitch_mm),
    real!("moving_box.pot_width_mm", moving_box.pot_width_mm),
    real!("moving_box.module_mm", moving_box.module_mm),
    integer!("moving_box.teeth", u32, moving_box.teeth),
    real!("moving_box.input_speed_rpm", moving_box.input_speed_rpm),
    real!("moving_box.window_deg", moving_box.window_deg),
    real!("moving_box.window_centre_deg", moving_box.window_centre_deg),
    real!("moving_box.spiral_angle_deg", moving_box.spiral_angle_deg),
    real!("moving_box.box_mass_kg", moving_box.box_mass_kg),
    real!(
        "moving_box.groove_wall_angle_deg",
        moving_box.groove_wall_angle_deg
    ),
    real!(
        "moving_box.groove_friction_angle_deg",
        moving_box.groove_friction_angle_deg
    ),
    real!(
        "moving_box.slide_friction_angle_deg",
        moving_box.slide_friction_angle_deg
    ),
    real!(
        "moving_box.input_turns_per_carrier_turn",
        moving_box.input_turns_per_carrier_turn
    ),
    integer!("search.budget", u64, search.budget),
    integer!("search.population", usize, search.population),
    integer!("search.seed", u64, search.seed),
    integer!(
        "search.screening.samples_per_turn",
        usize,
        search.screening.samples_per_turn
    ),
    real!(
        "search.screening.closure_rel_tol",
        search.screening.closure_rel_tol
    ),
    real!(
        "search.screening.newton_rel_tol",
        search.screening.newton_rel_tol
    ),
];

/// A list of one or more pitch-curve kinds.
macro_rules! curve_list {
    ($path:literal, $f:ident: $($kind:ident)|+) => {
        (
            $path,
            (|s| match &s.gear.curve {
                $(CurveSpec::$kind { $f, .. })|+ => Some($f),
                #[allow(unreachable_patterns)]
                _ => None,
            }) as ListGet,
            (|s| match &mut s.gear.curve {
                $(CurveSpec::$kind { $f, .. })|+ => Some($f),
                #[allow(unreachable_patterns)]
                _ => None,
            }) as ListSet,
        )
    };
}

/// List parameters by path (indexed as `path[i]`).
const LISTS: &[(&str, ListGet, ListSet)] = &[
    curve_list!("gear.curve.radii_mm", radii_mm: Spline | Bspline | Bezier | Table),
    curve_list!("gear.curve.angles_deg", angles_deg: Spline | Bspline | Bezier | Table),
    curve_list!("gear.curve.cos_mm", cos_mm: Fourier),
    curve_list!("gear.curve.sin_mm", sin_mm: Fourier),
];

#[derive(Clone, Copy)]
enum Access {
    Scalar(Get, Set),
    Item(ListGet, ListSet, usize),
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
    /// Parses `path` and checks that `scene` has it (the curve kind has the field, the list
    /// is long enough). An unknown path is [`Error::UnknownName`] with the nearest paths.
    pub fn parse(path: &str, scene: &Scene) -> Result<Self> {
        let unknown = || Error::UnknownName {
            what: "parameter",
            name: path.to_string(),
            nearest: nearest(path, &Self::paths(scene)),
        };
        let access = match path.split_once('[') {
            Some((base, rest)) if LISTS.iter().any(|(n, _, _)| *n == base) => {
                let index: usize = rest
                    .strip_suffix(']')
                    .and_then(|i| i.parse().ok())
                    .ok_or_else(unknown)?;
                let (_, get, set) = LISTS.iter().find(|(n, _, _)| *n == base).expect("found");
                Access::Item(*get, *set, index)
            }
            _ => {
                let (_, get, set) = SCALARS
                    .iter()
                    .find(|(n, _, _)| *n == path)
                    .ok_or_else(unknown)?;
                Access::Scalar(*get, *set)
            }
        };
        let param = Self {
            name: path.to_string(),
            access,
        };
        // Present in this scene (an optional field left unset still counts: it can be set).
        let present = match access {
            Access::Scalar(_, set) => set(&mut scene.clone(), 0.0),
            Access::Item(get, _, i) => get(scene).is_some_and(|v| i < v.len()),
        };
        if !present {
            return Err(unknown());
        }
        Ok(param)
    }

    /// Every parameter path `scene` has, lists expanded (`gear.curve.radii_mm[0]`, …).
    pub fn paths(scene: &Scene) -> Vec<String> {
        let mut probe = scene.clone();
        let mut out: Vec<String> = SCALARS
            .iter()
            .filter(|(_, _, set)| set(&mut probe, 0.0))
            .map(|(n, _, _)| n.to_string())
            .collect();
        for (name, get, _) in LISTS {
            if let Some(list) = get(scene) {
                out.extend((0..list.len()).map(|i| format!("{name}[{i}]")));
            }
        }
        out
    }

    /// The path this parameter was parsed from.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Writes `value` into `scene` (integer fields take it rounded).
    pub fn set(&self, scene: &mut Scene, value: f64) {
        match self.access {
            Access::Scalar(_, set) => {
                set(scene, value);
            }
            Access::Item(_, set, i) => {
                if let Some(slot) = set(scene).and_then(|v| v.get_mut(i)) {
                    *slot = value;
                }
            }
        }
    }

    /// Reads the current value from `scene`; `None` for an optional field left unset.
    pub fn get(&self, scene: &Scene) -> Option<f64> {
        match self.access {
            Access::Scalar(get, _) => get(scene),
            Access::Item(get, _, i) => get(scene).and_then(|v| v.get(i).copied()),
        }
    }
}

/// The search settings' check, which parses the free parameters' paths.
impl Scene {
    /// The search settings: goals this scene can compute, each once; free parameters that
    /// exist, each once, with finite ordered bounds a finite width apart. Checked when a
    /// scene is read and when a search starts (not per design: [`Scene::validate`] is).
    pub fn validate_search(&self) -> Result<()> {
        let population = self.search.population;
        if !(1..=SearchSpec::MAX_POPULATION).contains(&population) {
            return Err(Error::OutOfRange {
                name: "search.population".into(),
                value: population as f64,
                expected: format!("1 to {}", SearchSpec::MAX_POPULATION),
            });
        }
        if self.search.free.len() > SearchSpec::MAX_FREE {
            return Err(Error::OutOfRange {
                name: "search.free (count)".into(),
                value: self.search.free.len() as f64,
                expected: format!("at most {}", SearchSpec::MAX_FREE),
            });
        }
        self.search.screening.validate()?;
        let arms = self.train.arms;
        if !self.search.screening.samples_per_turn.is_multiple_of(arms) {
            return Err(Error::OutOfRange {
                name: "search.screening.samples_per_turn".into(),
                value: self.search.screening.samples_per_turn as f64,
                expected: format!("a multiple of train.arms = {arms}"),
            });
        }
        if self.search.confirm_with_teeth && self.gear.module.teeth.is_none() {
            return Err(Error::Missing {
                name: "gear.module.teeth".into(),
                needed_by: "search.confirm_with_teeth cuts that many teeth".into(),
            });
        }
        for (i, goal) in self.search.goals.iter().enumerate() {
            let name = goal.name();
            let problem = if self.search.goals[..i].contains(goal) {
                format!("'{name}' is listed twice")
            } else if goal.needs_moving_box() && self.kind != SceneKind::Transplanter {
                format!("'{name}' needs a moving box: only a transplanter scene computes it")
            } else if goal.is_robust()
                && !matches!(self.kind, SceneKind::ThreeArm | SceneKind::Transplanter)
            {
                format!("'{name}' samples a mechanism's tolerances: a three-arm scene needs it")
            } else {
                continue;
            };
            return Err(Error::BadList {
                list: "search.goals",
                problem,
            });
        }
        for (i, f) in self.search.free.iter().enumerate() {
            Param::parse(&f.name, self)?;
            finite(&format!("search.free '{}' lower", f.name), f.lower)?;
            finite(&format!("search.free '{}' upper", f.name), f.upper)?;
            let problem = if self.search.free[..i].iter().any(|g| g.name == f.name) {
                format!("'{}' is listed twice", f.name)
            } else if !(f.lower < f.upper && (f.upper - f.lower).is_finite()) {
                format!(
                    "'{}' has bounds [{}, {}]: the lower must be below the upper, a finite \
                     width apart",
                    f.name, f.lower, f.upper
                )
            } else {
                continue;
            };
            return Err(Error::BadList {
                list: "search.free",
                problem,
            });
        }
        Ok(())
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
        assert_eq!(p.get(&scene), Some(33.0));
        let q = Param::parse("train.gamma0_deg", &scene).unwrap();
        q.set(&mut scene, -40.0);
        assert_eq!(scene.train.gamma0_deg, -40.0);
        assert!(Param::parse("gear.curve.radii_mm[12]", &scene).is_err());
        assert!(Param::parse("gear.curve.eccentricity", &scene).is_err());
        assert!(Param::parse("train.nope", &scene).is_err());
        // Every field, not a hand-picked few; unknown paths name the nearest ones.
        let m = Param::parse("bounds.module_min_mm", &scene).unwrap();
        m.set(&mut scene, 3.0);
        assert_eq!(scene.bounds.module_min_mm, 3.0);
        let e = Param::parse("bounds.modul_min_mm", &scene)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bounds.module_min_mm"), "{e}");
        let t = Param::parse("agronomy.tray_distance_mm", &scene).unwrap();
        assert_eq!(t.get(&scene), None);
        t.set(&mut scene, 400.0);
        assert_eq!(scene.agronomy.tray_distance_mm, Some(400.0));
    }
}
