//! Named scene parameters that search, sweeps and Python read and write: every number of a
//! scene by the same dotted path as `--set` and the scene files (`train.phi0_deg`,
//! `gear.curve.radii_mm[3]`, `bounds.picking_angle_deg[0]`), parsed once into typed field
//! accessors (each field's own, from its entry in the field table, [`crate::reference`])
//! so that applying a design vector is a handful of field writes.

use crate::error::{Error, Result};
use crate::reference::{fields, Number};
use crate::scene::Scene;
use noncirc_search::nearest;

/// A field's accessor and, for a list, the element.
#[derive(Clone, Copy)]
struct Access {
    number: Number,
    index: usize,
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
        Self::find(path, scene).ok_or_else(|| Error::UnknownName {
            what: "parameter",
            name: path.to_string(),
            nearest: nearest(path, &Self::paths(scene)),
        })
    }

    /// As [`Param::parse`], `None` for a path `scene` does not have: for a caller that
    /// probes paths, which `parse` would answer with the nearest names (an edit distance
    /// to every path).
    pub fn find(path: &str, scene: &Scene) -> Option<Self> {
        let (key, index) = match path.split_once('[') {
            Some((key, rest)) => (key, Some(rest.strip_suffix(']')?.parse().ok()?)),
            None => (path, None),
        };
        let number = fields().find(|f| f.key == key)?.number?;
        // A list needs an element, a scalar none.
        let index = match (number, index) {
            (Number::List(..), Some(i)) => i,
            (Number::Scalar(..) | Number::Optional(..), None) => 0,
            _ => return None,
        };
        // Present in this scene (an optional field left unset still counts: it can be set).
        let present = match number {
            Number::Scalar(_, set) | Number::Optional(_, set) => set(&mut scene.clone(), 0.0),
            Number::List(get, _) => get(scene).is_some_and(|v| index < v.len()),
        };
        present.then(|| Self {
            name: path.to_string(),
            access: Access { number, index },
        })
    }

    /// Every parameter path `scene` has, lists expanded (`gear.curve.radii_mm[0]`, …).
    pub fn paths(scene: &Scene) -> Vec<String> {
        Self::every(scene).into_iter().map(|p| p.name).collect()
    }

    /// Every parameter `scene` has, in the field table's order, lists expanded: what
    /// [`Param::find`] finds of each path, with one copy of the scene to probe the fields
    /// on, not one per field.
    pub fn every(scene: &Scene) -> Vec<Param> {
        let param = |name: String, number, index| Param {
            name,
            access: Access { number, index },
        };
        let mut probe = scene.clone();
        let mut out = Vec::new();
        for field in fields() {
            match field.number {
                Some(number @ (Number::Scalar(_, set) | Number::Optional(_, set)))
                    if set(&mut probe, 0.0) =>
                {
                    out.push(param(field.key.to_string(), number, 0));
                }
                Some(number @ Number::List(get, _)) => {
                    let len = get(scene).map_or(0, <[f64]>::len);
                    out.extend((0..len).map(|i| param(format!("{}[{i}]", field.key), number, i)));
                }
                _ => {}
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
        match self.access.number {
            Number::Scalar(_, set) | Number::Optional(_, set) => {
                set(scene, value);
            }
            Number::List(_, set) => {
                if let Some(slot) = set(scene).and_then(|v| v.get_mut(self.access.index)) {
                    *slot = value;
                }
            }
        }
    }

    /// Reads the current value from `scene`; `None` for an optional field left unset.
    pub fn get(&self, scene: &Scene) -> Option<f64> {
        match self.access.number {
            Number::Scalar(get, _) | Number::Optional(get, _) => get(scene),
            Number::List(get, _) => get(scene).and_then(|v| v.get(self.access.index).copied()),
        }
    }
}

/// The current values of the parameters that `scene`'s target pulls (`target.design`),
/// in its order (none without a target). A name the scene does not have is
/// [`Error::UnknownName`] with the nearest paths; an optional field left unset, refused.
pub(crate) fn pulled_values(scene: &Scene) -> Result<Vec<f64>> {
    let Some(target) = &scene.target else {
        return Ok(Vec::new());
    };
    (target.design.iter().enumerate())
        .map(|(k, pull)| {
            let param = Param::parse(&pull.name, scene).map_err(|e| match e {
                Error::UnknownName { name, nearest, .. } => Error::UnknownName {
                    what: "parameter (target.design)",
                    name,
                    nearest,
                },
                e => e,
            })?;
            param.get(scene).ok_or_else(|| Error::OutOfRange {
                name: format!("target.design[{k}].name"),
                value: f64::NAN,
                expected: format!("a parameter the scene sets ('{}' is unset)", pull.name),
            })
        })
        .collect()
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

    /// `find` has what `parse` parses and nothing else: every path of a scene of each
    /// curve kind, each field's bare key (lists refuse it), elements past a list's end,
    /// malformed indices and unknown names.
    #[test]
    fn find_has_exactly_what_parse_parses() {
        let ellipse = Scene {
            gear: crate::GearSpec {
                curve: crate::CurveSpec::Ellipse {
                    semi_major_mm: 40.0,
                    eccentricity: 0.2,
                },
                ..Scene::default().gear
            },
            ..Scene::default()
        };
        for scene in [Scene::default(), ellipse] {
            let mut probes = Param::paths(&scene);
            probes.extend(fields().map(|f| f.key.to_string()));
            probes.extend(fields().map(|f| format!("{}[12]", f.key)));
            let odd = [
                "gear.curve.radii_mm[x]",
                "gear.curve.radii_mm[3",
                "",
                "train.nope",
            ];
            probes.extend(odd.map(String::from));
            let mut found = 0;
            for path in &probes {
                let (found_it, parsed) = (Param::find(path, &scene), Param::parse(path, &scene));
                assert_eq!(found_it.is_some(), parsed.is_ok(), "{path}");
                if let (Some(f), Ok(p)) = (found_it, parsed) {
                    assert_eq!(f.name(), p.name());
                    assert_eq!(f.get(&scene), p.get(&scene), "{path}");
                    found += 1;
                }
            }
            assert!(found >= Param::paths(&scene).len(), "{found}");
            for p in Param::every(&scene) {
                let f = Param::find(p.name(), &scene).expect("every path is found");
                assert_eq!(
                    (f.access.index, f.get(&scene)),
                    (p.access.index, p.get(&scene))
                );
            }
        }
    }
}
