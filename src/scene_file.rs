//! Loading scenes from TOML or JSON files, built-in names, and `--set key=value` overrides.

use noncirc_core::Scene;
use std::path::Path;

/// Why a scene could not be loaded: always names the file (or source) and, where known,
/// the line, key and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{origin}: {message}")]
    Parse { origin: String, message: String },
    #[error("cannot read {path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("unknown built-in scene '{0}' (see `noncirc scenes`)")]
    UnknownBuiltin(String),
    #[error("--set {assignment}: {message}")]
    Override { assignment: String, message: String },
    /// A `--set` key the scene does not have, with the nearest keys it does have.
    #[error("--set {assignment}: unknown key '{key}': the nearest are {}", nearest.join(", "))]
    UnknownKey {
        assignment: String,
        key: String,
        nearest: Vec<String>,
    },
    /// A scene that reads but cannot be evaluated or searched as written; `line` is the
    /// line of the file that sets the bad value, where it can be found.
    #[error("{origin}: {}{source}", line.map(|l| format!("line {l}: ")).unwrap_or_default())]
    Invalid {
        origin: String,
        line: Option<usize>,
        #[source]
        source: noncirc_core::Error,
    },
}

impl SceneError {
    /// The message without the `--set key=value:` it starts with, for a front end that
    /// shows it beside the field or call that set the value (the studio, Python).
    pub fn detail(&self) -> String {
        match self {
            SceneError::Override { message, .. } => message.clone(),
            SceneError::UnknownKey { key, nearest, .. } => {
                format!(
                    "unknown key '{key}': the nearest are {}",
                    nearest.join(", ")
                )
            }
            SceneError::Invalid {
                origin,
                line,
                source,
            } if origin.starts_with("--set ") => match line {
                Some(l) => format!("line {l}: {source}"),
                None => source.to_string(),
            },
            other => other.to_string(),
        }
    }
}

/// Checks a scene edited in memory (Python's `with_values`) as a scene file is checked;
/// `origin` names the edit in errors.
pub fn check_scene(scene: Scene, origin: &str) -> Result<Scene, SceneError> {
    checked(scene, origin, None)
}

/// The scene if every value in it can be evaluated and searched, else why not; `text`,
/// the file the scene was read from, locates the bad value's line.
fn checked(scene: Scene, origin: &str, text: Option<&str>) -> Result<Scene, SceneError> {
    scene
        .validate()
        .and_then(|()| scene.validate_search())
        .and_then(|()| scene.gear.curves().map(drop))
        .and_then(|()| scene.validate_target())
        .map_err(|source| SceneError::Invalid {
            origin: origin.to_string(),
            line: text.and_then(|t| line_of(t, error_key(&source)?)),
            source,
        })?;
    Ok(scene)
}

/// The scene path an error names (`bounds.picking_angle_deg` of
/// `bounds.picking_angle_deg[1]`), if it names one.
fn error_key(e: &noncirc_core::Error) -> Option<&str> {
    use noncirc_core::Error;
    let name = match e {
        Error::NonFinite { name, .. }
        | Error::OutOfRange { name, .. }
        | Error::Missing { name, .. }
        | Error::OpenTarget { name, .. }
        | Error::OutOfReach { name, .. }
        | Error::TargetCrossing { name, .. } => name.as_str(),
        Error::BadList { list, .. } => list,
        Error::SecondPair(_) => "gear.second_curve",
        _ => return None,
    };
    let end = name
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.'))
        .unwrap_or(name.len());
    name[..end].contains('.').then_some(&name[..end])
}

/// The 1-based line of a scene file that sets `path` (`table.key`): a `key = …` line
/// under the `[table]` (or `[[table]]`) header, or the header of a table `path`; in JSON,
/// the first `"key":`. Best effort: `None` when the file does not spell it out.
fn line_of(text: &str, path: &str) -> Option<usize> {
    let (table, key) = path.rsplit_once('.').unwrap_or(("", path));
    if text.trim_start().starts_with('{') {
        let quoted = format!("\"{key}\"");
        return text
            .lines()
            .position(|l| l.contains(&quoted))
            .map(|i| i + 1);
    }
    let mut current = String::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if let Some(header) = line.strip_prefix('[') {
            current = header
                .trim_matches(|c| c == '[' || c == ']')
                .trim()
                .to_string();
            if current == path {
                return Some(i + 1);
            }
            continue;
        }
        let assigned = line
            .strip_prefix(key)
            .is_some_and(|rest| rest.trim_start().starts_with('='));
        if assigned && current == table {
            return Some(i + 1);
        }
    }
    None
}

/// Built-in scenes: `(name, file contents)`; the same files live under `scenes/`.
pub const BUILTIN: &[(&str, &str)] = &[
    ("paper", include_str!("../scenes/paper.toml")),
    ("paper-search", include_str!("../scenes/paper-search.toml")),
    ("moving-box", include_str!("../scenes/moving-box.toml")),
    ("transplanter", include_str!("../scenes/transplanter.toml")),
    ("ellipse-gear", include_str!("../scenes/ellipse-gear.toml")),
    ("two-arm", include_str!("../scenes/two-arm.toml")),
];

/// Largest scene file read (bytes): the built-in scenes are about 3 kB.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// The default scene's name: the three-arm paper's design.
pub const DEFAULT_SCENE: &str = "paper";

/// Parses and checks scene text. `origin` names it in errors; JSON if it starts with `{`,
/// else TOML.
pub fn parse_scene(text: &str, origin: &str) -> Result<Scene, SceneError> {
    checked(read_scene(text, origin)?, origin, Some(text))
}

/// The first place where `tree` has a list (or a value) where a scene has a table:
/// serde reads a list into a table position by position (`gear = []` took every default,
/// `train = [10, -29, …]` set the fields in order), so a table must be written as one.
fn table_written_as_list(tree: &serde_json::Value) -> Option<String> {
    fn walk(user: &serde_json::Value, reference: &serde_json::Value, path: &str) -> Option<String> {
        let serde_json::Value::Object(fields) = reference else {
            return None;
        };
        match user {
            serde_json::Value::Object(given) => given.iter().find_map(|(key, value)| {
                let inner = if path.is_empty() {
                    key.clone()
                } else {
                    format!("{path}.{key}")
                };
                fields.get(key).and_then(|r| walk(value, r, &inner))
            }),
            serde_json::Value::Array(_) => Some(format!(
                "key '{path}': a table is written as one (`[{path}]` or `{path} = {{ … }}`), \
                 not as a list (a list would be read position by position)"
            )),
            _ => None,
        }
    }
    walk(tree, &scene_tree(&Scene::default()), "")
}

/// Parses scene text without checking its values (they may still be set by `--set`).
fn read_scene(text: &str, origin: &str) -> Result<Scene, SceneError> {
    let parse_err = |message: String| SceneError::Parse {
        origin: origin.to_string(),
        message,
    };
    let tree: Option<serde_json::Value> = if text.trim_start().starts_with('{') {
        serde_json::from_str(text).ok()
    } else {
        toml::from_str::<toml::Table>(text)
            .ok()
            .and_then(|t| serde_json::to_value(t).ok())
    };
    if let Some(message) = tree.as_ref().and_then(table_written_as_list) {
        return Err(parse_err(message));
    }
    if text.trim_start().starts_with('{') {
        let mut de = serde_json::Deserializer::from_str(text);
        let scene: Scene = serde_path_to_error::deserialize(&mut de).map_err(|e| {
            let inner = e.inner();
            parse_err(format!(
                "line {}, column {}: key '{}': {}",
                inner.line(),
                inner.column(),
                e.path(),
                inner
            ))
        })?;
        // Text after the scene's closing brace is a damaged file, not a comment.
        de.end().map_err(|e| {
            parse_err(format!(
                "line {}, column {}: text after the scene: {e}",
                e.line(),
                e.column()
            ))
        })?;
        Ok(scene)
    } else {
        let de = toml::Deserializer::new(text);
        serde_path_to_error::deserialize(de).map_err(|e| {
            let key = e.path().to_string();
            let inner = e.into_inner();
            let at = inner.span().map(|s| place(text, s.start));
            // The path is "." (the root) when the text is not TOML at all: a syntax error,
            // told with its column and the line it is on, not as a key.
            if key == "." {
                let (location, quoted) = at
                    .map(|(line, column, source)| {
                        (
                            format!("line {line}, column {column}: "),
                            format!(" (in `{source}`)"),
                        )
                    })
                    .unwrap_or_default();
                return parse_err(format!(
                    "{location}not valid TOML: {}{quoted}",
                    inner.message().trim_end()
                ));
            }
            let location = at
                .map(|(line, ..)| format!("line {line}: "))
                .unwrap_or_default();
            parse_err(format!("{location}key '{key}': {}", inner.message()))
        })
    }
}

/// Where byte `offset` of `text` is: its line and column (from 1, in characters) and that
/// line's text, trimmed.
fn place(text: &str, offset: usize) -> (usize, usize, &str) {
    // On a character's boundary, so that slicing cannot panic whatever the span says.
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = text[..offset].matches('\n').count() + 1;
    let column = text[line_start..offset].chars().count() + 1;
    let source = text[line_start..].lines().next().unwrap_or("").trim();
    (line, column, source)
}

/// Loads and checks a built-in scene by its bare name, or a scene file by its path (a file
/// named like a built-in as `./paper`).
pub fn load_scene(spec: Option<&str>) -> Result<Scene, SceneError> {
    load_scene_with(spec, &[])
}

/// [`load_scene`] with `key.path=value` overrides, checked once they are all applied (so
/// `--set` can repair a bad value in a file).
pub fn load_scene_with(spec: Option<&str>, assignments: &[String]) -> Result<Scene, SceneError> {
    let name = spec.unwrap_or(DEFAULT_SCENE);
    let builtin = BUILTIN.iter().find(|(n, _)| *n == name);
    // A built-in's bare name always means the built-in: a file or directory of that name in
    // the working directory is read as `./paper`, never in its place unseen.
    let (text, origin) = match builtin {
        Some((_, text)) => (text.to_string(), format!("built-in scene '{name}'")),
        _ => {
            let path = Path::new(name);
            if !path.exists() && path.extension().is_none() {
                return Err(SceneError::UnknownBuiltin(name.to_string()));
            }
            let io = |source| SceneError::Io {
                path: name.to_string(),
                source,
            };
            let meta = std::fs::metadata(path).map_err(io)?;
            if !meta.is_file() || meta.len() > MAX_SCENE_BYTES {
                return Err(SceneError::Parse {
                    origin: name.to_string(),
                    message: format!(
                        "not a scene file: a regular file of at most {MAX_SCENE_BYTES} bytes is \
                         expected (this is {})",
                        if meta.is_file() {
                            format!("{} bytes", meta.len())
                        } else {
                            "not a regular file".into()
                        }
                    ),
                });
            }
            (std::fs::read_to_string(path).map_err(io)?, name.to_string())
        }
    };
    let scene = read_scene(&text, &origin)?;
    if assignments.is_empty() {
        checked(scene, &origin, Some(&text))
    } else {
        // A bad value may come from the file or from --set: no line is claimed.
        checked(
            set_values(scene, assignments)?,
            &format!("{origin} with --set {}", assignments.join(" ")),
            None,
        )
    }
}

/// Whether `key` names a field of the field table ([`noncirc_core::fields`]) or a table of
/// them (`bounds`, `gear.curve`): a list's element as `key[3]`, an entry of a list of
/// tables as `search.free[0].name` (the table's `search.free[i].name`).
fn in_table(key: &str) -> bool {
    let mut general = String::new();
    let mut rest = key;
    while let Some((before, after)) = rest.split_once('[') {
        let Some((index, after)) = after.split_once(']') else {
            return false;
        };
        general += before;
        // An element of a list of tables, or a list's element at the end of the key.
        general += if after.is_empty() { "" } else { "[i]" };
        if !index.chars().all(|c| c.is_ascii_digit()) {
            return false;
        }
        rest = after;
    }
    general += rest;
    noncirc_core::fields().any(|f| {
        f.key == general
            || f.key
                .strip_prefix(general.as_str())
                .is_some_and(|r| r.starts_with('.') || r.starts_with('['))
    })
}

/// The field table's keys that `tree` has (a list of tables' `[i]` keys when the list
/// has an entry), for "the nearest are" suggestions.
fn table_keys(tree: &serde_json::Value) -> Vec<String> {
    let has = |key: &str| {
        let mut node = Some(tree);
        for part in key.split('.') {
            let (name, list) = match part.strip_suffix("[i]") {
                Some(name) => (name, true),
                None => (part, false),
            };
            node = node.and_then(|n| n.get(name));
            if list {
                node = node.and_then(|n| n.get(0));
            }
        }
        node.is_some()
    };
    (noncirc_core::fields().map(|f| f.key))
        .filter(|k| has(k))
        .map(str::to_string)
        .collect()
}

/// The first NaN or infinite float in a TOML value, if any.
fn first_non_finite(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) if !x.is_finite() => Some(*x),
        toml::Value::Array(a) => a.iter().find_map(first_non_finite),
        toml::Value::Table(t) => t.values().find_map(first_non_finite),
        _ => None,
    }
}

/// Applies `key.path=value` overrides (value read as TOML, else as a string) and checks
/// the result.
pub fn apply_overrides(scene: Scene, assignments: &[String]) -> Result<Scene, SceneError> {
    if assignments.is_empty() {
        return Ok(scene);
    }
    checked(
        set_values(scene, assignments)?,
        &format!("--set {}", assignments.join(" ")),
        None,
    )
}

/// Sets scene values given as JSON values (`key.path`, value): Python's `with_set` of a
/// number, list or table. Checked as [`apply_overrides`] checks; errors name the key as
/// `--set key=value` would.
pub fn apply_values(
    scene: Scene,
    values: &[(String, serde_json::Value)],
) -> Result<Scene, SceneError> {
    let assignments: Vec<String> = (values.iter()).map(|(k, v)| format!("{k}={v}")).collect();
    let mut tree = scene_tree(&scene);
    for ((key, value), assignment) in values.iter().zip(&assignments) {
        *slot(&mut tree, key, assignment)? = value.clone();
    }
    let scene = read_tree(tree, &assignments)?;
    checked(scene, &format!("--set {}", assignments.join(" ")), None)
}

/// The value at `key.path` (`train.phi0_deg`, `gear.curve.radii_mm[3]`, `bounds`) as
/// JSON: a number, list, string or table.
pub fn value_at(scene: &Scene, key: &str) -> Result<serde_json::Value, SceneError> {
    let mut tree = scene_tree(scene);
    Ok(slot(&mut tree, key, key)?.clone())
}

/// The scene's serialised tree, with what a written scene leaves out while it is the
/// default filled in, so that it can be read and set: every number of the field table
/// (the arm count, the picking rate) by its accessor, and the tables and flags a written
/// scene leaves out (the teeth, the tolerances, `search.confirm_with_teeth`) from their
/// defaults.
fn scene_tree(scene: &Scene) -> serde_json::Value {
    let mut tree = serde_json::to_value(scene).expect("a scene always serialises");
    // The scene's own numbers (not another curve kind's), lists aside: they are written.
    for param in noncirc_core::Param::every(scene) {
        let Some((table, key)) = param.name().rsplit_once('.') else {
            continue;
        };
        if key.contains('[') {
            continue;
        }
        let node = table
            .split('.')
            .try_fold(&mut tree, |node, part| node.get_mut(part));
        if let Some(table) = node.and_then(|n| n.as_object_mut()) {
            table.entry(key).or_insert_with(|| match param.get(scene) {
                // A whole number as an integer, which an integer field reads back.
                Some(v) if v.fract() == 0.0 && v.abs() < 2f64.powi(53) => (v as i64).into(),
                v => v.into(),
            });
        }
    }
    if let Some(gear) = tree.get_mut("gear").and_then(|g| g.as_object_mut()) {
        gear.entry("teeth").or_insert_with(|| {
            serde_json::to_value(noncirc_core::ToothSpec::default()).expect("serialises")
        });
    }
    if let Some(search) = tree.get_mut("search").and_then(|s| s.as_object_mut()) {
        search
            .entry("confirm_with_teeth")
            .or_insert(serde_json::Value::Bool(false));
        search
            .entry("constraints")
            .or_insert(serde_json::Value::Array(Vec::new()));
    }
    if let Some(gear) = tree.get_mut("gear").and_then(|g| g.as_object_mut()) {
        // The paper's train: `--set gear.second_curve={…}` makes it a train of two pairs.
        gear.entry("second_curve")
            .or_insert(serde_json::Value::Null);
    }
    if let Some(top) = tree.as_object_mut() {
        top.entry("tolerances").or_insert_with(|| {
            serde_json::to_value(noncirc_core::Tolerances::default()).expect("serialises")
        });
        // No target: `--set target={…}` gives one.
        top.entry("target").or_insert(serde_json::Value::Null);
        top.entry("dynamics").or_insert_with(|| {
            serde_json::to_value(noncirc_core::DynamicsSpec::default()).expect("serialises")
        });
        top.entry("cad").or_insert_with(|| {
            serde_json::to_value(noncirc_core::CadSpec::default()).expect("serialises")
        });
    }
    tree
}

/// The node of `tree` at `key` (`a.b.c`, `a.b[i]`), a field of the field table or a table
/// of them; `assignment` names the request in errors.
fn slot<'t>(
    tree: &'t mut serde_json::Value,
    key: &str,
    assignment: &str,
) -> Result<&'t mut serde_json::Value, SceneError> {
    let err = |message: String| SceneError::Override {
        assignment: assignment.to_string(),
        message,
    };
    let unknown_in = |tree: &serde_json::Value| SceneError::UnknownKey {
        assignment: assignment.to_string(),
        key: key.trim().to_string(),
        nearest: noncirc_core::nearest(key.trim(), &table_keys(tree)),
    };
    if !in_table(key.trim()) {
        return Err(unknown_in(tree));
    }
    let plain = tree.clone();
    let mut node = tree;
    let mut path = String::new();
    for part in key.trim().split('.') {
        // An optional table the scene does not have (`target`): set it whole first.
        if node.is_null() {
            return Err(err(format!(
                "the scene has no '{path}': set the table whole first, e.g. \
                 --set '{path}={{…}}' (docs/scenes.md lists its keys)"
            )));
        }
        if !path.is_empty() {
            path.push('.');
        }
        path.push_str(part.split('[').next().unwrap_or(part));
        let (name, index) = match part.split_once('[') {
            Some((name, rest)) => {
                let i = rest.strip_suffix(']').and_then(|i| i.parse::<usize>().ok());
                (
                    name,
                    Some(i.ok_or_else(|| err(format!("bad index in '{part}'")))?),
                )
            }
            None => (part, None),
        };
        node = node
            .as_object_mut()
            .and_then(|obj| obj.get_mut(name))
            .ok_or_else(|| unknown_in(&plain))?;
        if let Some(i) = index {
            node = node
                .as_array_mut()
                .and_then(|a| a.get_mut(i))
                .ok_or_else(|| err(format!("'{key}': no element {i} in '{name}'")))?;
        }
    }
    Ok(node)
}

/// Reads a scene back from its edited tree.
fn read_tree(tree: serde_json::Value, assignments: &[String]) -> Result<Scene, SceneError> {
    serde_path_to_error::deserialize(tree).map_err(|e| SceneError::Override {
        assignment: assignments.join(" "),
        message: format!("key '{}': {}", e.path(), e.inner()),
    })
}

/// Writes `key.path=value` assignments into the scene's tree and reads it back.
fn set_values(scene: Scene, assignments: &[String]) -> Result<Scene, SceneError> {
    let mut tree = scene_tree(&scene);
    for assignment in assignments {
        let err = |message: String| SceneError::Override {
            assignment: assignment.clone(),
            message,
        };
        let (key, raw) = assignment
            .split_once('=')
            .ok_or_else(|| err("expected key=value".into()))?;
        let value: serde_json::Value = match toml::from_str::<toml::Table>(&format!("v = {raw}")) {
            Ok(mut t) => {
                let v = t.remove("v").expect("parsed key");
                // JSON has no NaN or infinity: they would arrive as null and be misreported.
                if let Some(x) = first_non_finite(&v) {
                    return Err(err(format!(
                        "{x} is not a finite number: every number in a scene must be finite"
                    )));
                }
                serde_json::to_value(v).map_err(|e| err(e.to_string()))?
            }
            Err(_) => serde_json::Value::String(raw.to_string()),
        };
        *slot(&mut tree, key, assignment)? = value;
        if let Some(message) = table_written_as_list(&tree) {
            return Err(err(message));
        }
        // A table set whole (`target={…}`) gains its defaults, so that a later assignment
        // can set one of them by key; a tree that does not read yet (a curve's kind
        // changed before its fields) is kept as it is.
        if let Ok(scene) = serde_json::from_value::<Scene>(tree.clone()) {
            tree = scene_tree(&scene);
        }
    }
    read_tree(tree, assignments)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_scenes_parse() {
        for (name, text) in BUILTIN {
            parse_scene(text, name).unwrap_or_else(|e| panic!("{e}"));
        }
    }

    #[test]
    fn errors_name_line_and_key() {
        let text = "name = \"x\"\n[resolution]\nsamples_per_turn = \"many\"\n";
        let e = parse_scene(text, "bad.toml").unwrap_err().to_string();
        assert!(
            e.contains("bad.toml")
                && e.contains("line 3")
                && e.contains("resolution.samples_per_turn"),
            "{e}"
        );
        let e = parse_scene("[gear]\ncolour = 3\n", "u.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("colour") && e.contains("line 2"), "{e}");
        let e = parse_scene("{\"resolution\": {\"samples_per_turn\": -1}}", "j.json")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("j.json") && e.contains("samples_per_turn"),
            "{e}"
        );
    }

    /// Text that is not TOML is told as a syntax error with its line, column and source
    /// line, not as "key '.'".
    #[test]
    fn a_toml_syntax_error_names_its_place_not_a_key() {
        let e = parse_scene("[train]\narm_length_mm = 140 150\n", "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(!e.contains("key '.'"), "{e}");
        assert!(
            e.contains("bad.toml: line 2, column 21: not valid TOML: expected newline")
                && e.ends_with("(in `arm_length_mm = 140 150`)"),
            "{e}"
        );
    }

    #[test]
    fn overrides_change_values_and_reject_unknown_keys() {
        let scene = load_scene(None).unwrap();
        let s =
            apply_overrides(scene.clone(), &["resolution.samples_per_turn=720".into()]).unwrap();
        assert_eq!(s.resolution.samples_per_turn, 720);
        assert!(apply_overrides(scene.clone(), &["resolution.nope=1".into()]).is_err());
        assert!(
            apply_overrides(scene.clone(), &["resolution.samples_per_turn=abc".into()]).is_err()
        );
        let s = apply_overrides(scene.clone(), &["gear.curve.radii_mm[3]=33.5".into()]).unwrap();
        assert_eq!(
            noncirc_core::Param::parse("gear.curve.radii_mm[3]", &s)
                .unwrap()
                .get(&s),
            Some(33.5)
        );
        assert!(apply_overrides(scene.clone(), &["gear.curve.radii_mm[12]=1".into()]).is_err());
    }

    #[test]
    fn keys_go_through_the_field_table() {
        for key in [
            "train.arms",
            "gear.curve.radii_mm[3]",
            "bounds.picking_angle_deg[1]",
            "search.free[0].lower",
            "bounds",
            "gear.curve",
            "tolerances.radius_mm",
        ] {
            assert!(in_table(key), "{key}");
        }
        for key in ["train.arm", "gear.curve.radii_mm[x]", "bounds.", "nope"] {
            assert!(!in_table(key), "{key}");
        }
        // The arm count, left out of a written scene while it is the default, reads back
        // by its accessor, as an integer that the scene's integer field takes.
        let scene = load_scene(None).unwrap();
        assert_eq!(
            value_at(&scene, "train.arms").unwrap(),
            serde_json::json!(3)
        );
        let two = apply_overrides(scene.clone(), &["train.arms=2".into()]).unwrap();
        assert_eq!(value_at(&two, "train.arms").unwrap(), serde_json::json!(2));
        let e = apply_overrides(scene.clone(), &["train.arm_lenght_mm=1".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("the nearest are train.arm_length_mm"), "{e}");
        // A key of the table this scene does not have (another curve kind's) is unknown
        // here, and the suggestions are keys the scene has.
        let e = apply_overrides(scene.clone(), &["gear.curve.c0_mm=5".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown key 'gear.curve.c0_mm'"), "{e}");
        assert!(!e.contains("are gear.curve.c0_mm"), "{e}");
    }

    #[test]
    fn non_finite_overrides_say_so() {
        let scene = load_scene(None).unwrap();
        for (assignment, shown) in [
            ("train.arm_length_mm=nan", "NaN"),
            ("agronomy.tray_depth_mm=-inf", "-inf"),
            ("gear.curve.radii_mm=[1, 2, inf]", "inf"),
        ] {
            let e = apply_overrides(scene.clone(), &[assignment.into()])
                .unwrap_err()
                .to_string();
            assert!(
                e.contains(shown) && e.contains("finite"),
                "{assignment}: {e}"
            );
        }
    }
}
