//! The scene reference: every field of a scene with the papers' symbol, its unit, its
//! admissible values and its meaning. docs/scenes.md is generated from this table (with
//! each field's default read from the code); a test holds the table to the scene's fields
//! both ways and probes every admissible range with a value it must refuse.

mod agronomy;
mod bounds;
mod gear;
mod moving_box;
mod search;
mod tolerances;
mod top;
mod train;

/// One field of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Field {
    /// The scene path, as `--set` and Python's `with_set` take it (`train.arm_length_mm`);
    /// a list's elements are `key[i]`.
    pub key: &'static str,
    /// The papers' symbol (`S`, `Φ0`), or "" where they name none.
    pub symbol: &'static str,
    /// Unit ("" for counts, names and ratios).
    pub unit: &'static str,
    /// The admissible values, as the checks hold them.
    pub range: &'static str,
    /// What the field means.
    pub meaning: &'static str,
    /// `key=value` assignments (TOML values) each of which a scene must refuse: the
    /// reference's test applies them, so that the range above stays true.
    pub refused: &'static [&'static str],
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

/// Every field of a scene, in the order of a scene file: one table per scene table.
pub fn fields() -> impl Iterator<Item = &'static Field> {
    [
        top::FIELDS,
        gear::FIELDS,
        train::FIELDS,
        agronomy::FIELDS,
        bounds::FIELDS,
        moving_box::FIELDS,
        search::FIELDS,
        tolerances::FIELDS,
    ]
    .into_iter()
    .flatten()
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
