//! The scene's fields, one table per scene table: for every field the papers' symbol, its
//! unit, its admissible values, its meaning and, for a number, how it is read and written
//! (its accessor: search, sweeps, `--set` and Python's `with_set` go through it).
//! docs/scenes.md is generated from this table (with each field's default read from the
//! code); a test holds the table to the scene's fields both ways and probes every
//! admissible range with a value it must refuse.
//!
//! To add a field: the struct field (with its default) and one entry here (a model's
//! number is also named by the model's own check, which a test holds to this table).

use crate::scene::Scene;

/// Reads a number (`None`: the scene does not have it, e.g. another curve kind, or an
/// optional field left unset).
type Get = fn(&Scene) -> Option<f64>;
/// Writes a number; `false` when the scene does not have the field.
type Set = fn(&mut Scene, f64) -> bool;
/// A list of numbers, to read (`None`: the scene does not have it).
type ListGet = fn(&Scene) -> Option<&[f64]>;
/// A list of numbers, to write in place.
type ListSet = fn(&mut Scene) -> Option<&mut [f64]>;

/// How a numeric field is read and written.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Number {
    /// One number.
    Scalar(Get, Set),
    /// One number that may be left unset.
    Optional(Get, Set),
    /// A list of numbers, indexed as `key[i]`.
    List(ListGet, ListSet),
}

/// A real field: `real!(train.phi0_deg)`.
macro_rules! real {
    ($($f:ident).+) => {
        $crate::reference::Number::Scalar(|s| Some(s.$($f).+), |s, v| { s.$($f).+ = v; true })
    };
}

/// An optional real field: unset reads as absent, and writing sets it.
macro_rules! optional {
    ($($f:ident).+) => {
        $crate::reference::Number::Optional(|s| s.$($f).+, |s, v| { s.$($f).+ = Some(v); true })
    };
}

/// An integer field, written rounded to the nearest integer. A negative or non-finite value
/// saturates (Rust's float-to-integer cast): to 0, which the field's check refuses where
/// 0 is outside its range (`search.seed` and `search.budget` admit it).
macro_rules! integer {
    ($ty:ty, $($f:ident).+) => {
        $crate::reference::Number::Scalar(|s| Some(s.$($f).+ as f64), |s, v| { s.$($f).+ = v.round() as $ty; true })
    };
}

/// An optional integer field.
macro_rules! optional_integer {
    ($ty:ty, $($f:ident).+) => {
        $crate::reference::Number::Optional(
            |s| s.$($f).+.map(|x| x as f64),
            |s, v| { s.$($f).+ = Some(v.round() as $ty); true },
        )
    };
}

/// A two-sided bound `[lower, upper]`, indexed as a list of two.
macro_rules! pair {
    ($($f:ident).+) => {
        $crate::reference::Number::List(|s| Some(&s.$($f).+[..]), |s| Some(&mut s.$($f).+[..]))
    };
}

/// A number of one pitch-curve kind.
macro_rules! curve {
    ($kind:ident, $f:ident) => {
        $crate::reference::Number::Scalar(
            |s| match &s.gear.curve {
                $crate::curve::CurveSpec::$kind { $f, .. } => Some(*$f),
                _ => None,
            },
            |s, v| match &mut s.gear.curve {
                $crate::curve::CurveSpec::$kind { $f, .. } => {
                    *$f = v;
                    true
                }
                _ => false,
            },
        )
    };
}

/// A list of one or more pitch-curve kinds.
macro_rules! curve_list {
    ($f:ident: $($kind:ident)|+) => {
        $crate::reference::Number::List(
            |s| match &s.gear.curve {
                $($crate::curve::CurveSpec::$kind { $f, .. })|+ => Some(&$f[..]),
                #[allow(unreachable_patterns)]
                _ => None,
            },
            |s| match &mut s.gear.curve {
                $($crate::curve::CurveSpec::$kind { $f, .. })|+ => Some(&mut $f[..]),
                #[allow(unreachable_patterns)]
                _ => None,
            },
        )
    };
}

mod agronomy;
mod bounds;
mod cad;
mod dynamics;
mod gear;
mod moving_box;
mod range;
mod search;
mod target;
mod tolerances;
mod top;
mod train;

pub(crate) use range::interval_checks;
pub use range::{Bound, Range};

/// One field of a scene.
#[derive(Debug, Clone, Copy)]
pub struct Field {
    /// The scene path, as `--set` and Python's `with_set` take it (`train.arm_length_mm`);
    /// a list's elements are `key[i]`.
    pub key: &'static str,
    /// The papers' symbol (`S`, `Φ0`), or "" where they name none.
    pub symbol: &'static str,
    /// Unit ("" for counts, names and ratios).
    pub unit: &'static str,
    /// The admissible values: a number's interval, or a rule that code checks.
    pub range: Range,
    /// What the field means.
    pub meaning: &'static str,
    /// `key=value` assignments (TOML values) each of which a scene must refuse: the
    /// reference's test applies them, so that the range above stays true.
    pub refused: &'static [&'static str],
    /// How a number is read and written (`Param`); `None` for names, flags and tables,
    /// which only scene files and `--set` write.
    pub(crate) number: Option<Number>,
}

/// The field of a scene path (`gear.curve.radii_mm[3]` is `gear.curve.radii_mm`'s).
pub fn field(path: &str) -> Option<&'static Field> {
    let key = path.split('[').next().unwrap_or(path);
    fields().find(|f| f.key == key)
}

/// The papers' symbol of a scene path, if they name one: `train.arm_length_mm` → `S`, and
/// a list's element by its number, `gear.curve.radii_mm[3]` → `r4`.
pub fn symbol(path: &str) -> Option<String> {
    let (key, index) = match path.split_once('[') {
        Some((key, rest)) => (key, Some(rest.strip_suffix(']')?.parse::<usize>().ok()?)),
        None => (path, None),
    };
    let field = fields().find(|f| f.key == key && !f.symbol.is_empty())?;
    match (index, field.symbol.split_once(" … ")) {
        // `r1 … r12`: the letters before the first number, then the element's.
        (Some(i), Some((first, _))) => {
            let letters = first.trim_end_matches(|c: char| c.is_ascii_digit());
            Some(format!("{letters}{}", i + 1))
        }
        (None, _) => Some(field.symbol.to_string()),
        (Some(_), None) => None,
    }
}

/// What checks a scene table's numbers against their intervals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Checker {
    /// The code that computes with them: a model's own check (`TrainSpec::validate`, a
    /// curve's build), which a model keeps because it is a library API of its own, or
    /// the search settings' check. The test `every_interval_is_exactly_what_the_checks_admit`
    /// holds it to the table at every bound.
    Code,
    /// The table itself, in [`Scene::validate`](crate::scene::Scene::validate): the
    /// scene's own inputs, which no model checks.
    Table,
}

/// The field tables, in the order of a scene file, each with the scene table it
/// describes (its first key's part: "" for the top level and `[resolution]`) and what
/// checks its numbers.
pub(crate) const TABLES: [(&str, Checker, &[Field]); 11] = [
    ("", Checker::Code, top::FIELDS),
    ("gear", Checker::Code, gear::FIELDS),
    ("train", Checker::Code, train::FIELDS),
    ("agronomy", Checker::Table, agronomy::FIELDS),
    ("bounds", Checker::Table, bounds::FIELDS),
    ("moving_box", Checker::Code, moving_box::FIELDS),
    ("search", Checker::Code, search::FIELDS),
    ("tolerances", Checker::Code, tolerances::FIELDS),
    ("target", Checker::Code, target::FIELDS),
    ("dynamics", Checker::Table, dynamics::FIELDS),
    ("cad", Checker::Table, cad::FIELDS),
];

/// Every field of a scene, in the order of a scene file: one table per scene table.
pub fn fields() -> impl Iterator<Item = &'static Field> {
    TABLES.iter().flat_map(|(_, _, fields)| fields.iter())
}

#[cfg(test)]
mod tests {
    use super::symbol;

    #[test]
    fn symbols_of_paths() {
        assert_eq!(symbol("train.arm_length_mm").as_deref(), Some("S"));
        assert_eq!(symbol("gear.curve.radii_mm[0]").as_deref(), Some("r1"));
        assert_eq!(symbol("gear.curve.angles_deg[11]").as_deref(), Some("θ12"));
        assert_eq!(symbol("gear.curve.radii_mm").as_deref(), Some("r1 … r12"));
        assert_eq!(symbol("agronomy.tray_depth_mm"), None);
        assert_eq!(symbol("no.such"), None);
        assert_eq!(symbol("gear.curve.radii_mm[x]"), None);
    }
}
