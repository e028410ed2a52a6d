//! The scene reference (docs/scenes.md) is current, covers every field of a scene and
//! only those, and every admissible range it states refuses a value outside it.

use noncirc::scene_file::{apply_overrides, parse_scene, BUILTIN};
use noncirc_core::fields;
use std::collections::BTreeSet;

/// The field paths of a scene's tree: a list of numbers or names is one field (`key`), a
/// list of tables has fields `key[i].name`. `gear.second_curve` is one field: its keys are
/// `gear.curve`'s.
fn field_paths(v: &serde_json::Value, path: &str, out: &mut BTreeSet<String>) {
    if path == "gear.second_curve" {
        out.insert(path.to_string());
        return;
    }
    let join = |k: &str| {
        if path.is_empty() {
            k.to_string()
        } else {
            format!("{path}.{k}")
        }
    };
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                field_paths(x, &join(k), out);
            }
        }
        serde_json::Value::Array(a) if a.iter().any(|x| x.is_object()) => {
            out.insert(path.to_string());
            for x in a {
                field_paths(x, &format!("{path}[i]"), out);
            }
        }
        _ => {
            out.insert(path.to_string());
        }
    }
}

/// Scenes that between them hold every field: the built-ins, and edits that set what the
/// built-ins leave out (the other curve kinds, a shaper, the optional values).
fn scenes() -> Vec<noncirc_core::Scene> {
    let mut scenes: Vec<_> = (BUILTIN.iter())
        .map(|(name, text)| parse_scene(text, name).unwrap())
        .collect();
    let base = scenes[0].clone();
    let edits: &[&[&str]] = &[
        &["gear.curve={kind=\"fourier\",c0_mm=40.0,cos_mm=[5.0],sin_mm=[2.0]}"],
        &["gear.curve={kind=\"ellipse\",semi_major_mm=40.0,eccentricity=0.3}"],
        &[
            "gear.teeth.cutter={kind=\"shaper\",teeth=12}",
            "gear.module.teeth=40",
            "search.confirm_with_teeth=true",
            "search.constraints=[\"loop_width_mm <= 50\"]",
            "agronomy.tray_distance_mm=120",
            "moving_box.speed_ratio=3",
            "dynamics.planting_force_n=8",
            "cad.bore_diameter_mm=10",
        ],
        &[
            "tolerances.radius_mm={sigma=0.01}",
            "tolerances.centre_distance_mm={sigma=0.01}",
            "tolerances.phi0_deg={sigma=0.05}",
            "tolerances.beta0_deg={sigma=0.05}",
            "tolerances.gamma0_deg={sigma=0.02}",
            "tolerances.arm_length_mm={sigma=0.2}",
            "tolerances.pusher_offset_mm={sigma=0.1}",
            "tolerances.tray_distance_mm={sigma=0.3}",
            "tolerances.tray_normal_deg={sigma=0.2}",
        ],
        &["tolerances.samples=32"],
        &["train.arms=2", "train.picks_per_minute=180"],
        &["gear.second_curve={kind=\"ellipse\",semi_major_mm=30.0,eccentricity=0.2}"],
        &[
            "target={kind=\"spline\",x_mm=[200.0,0.0,-200.0,0.0],y_mm=[0.0,150.0,0.0,-300.0],\
           tolerance_mm=0.5,samples=128,counts=true,poses=[{name=\"picking\",at=\"picking\",\
           x_mm=200.0,y_mm=0.0,attitude_deg=10.0,carrier_deg=20.0,position_tolerance_mm=0.5,\
           attitude_tolerance_deg=0.5,carrier_tolerance_deg=2.0,counts=true}],\
           design=[{name=\"train.phi0_deg\",value=86.0,scale=12.0}]}",
        ],
    ];
    for edit in edits {
        let edit: Vec<String> = edit.iter().map(|s| s.to_string()).collect();
        scenes.push(apply_overrides(base.clone(), &edit).unwrap());
    }
    scenes
}

#[test]
fn docs_scenes_md_is_current() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scenes.md");
    let written = std::fs::read_to_string(path).unwrap_or_default();
    let generated = noncirc::scene_reference::markdown();
    if written != generated {
        if std::env::var_os("NONCIRC_WRITE_DOCS").is_some() {
            std::fs::write(path, &generated).unwrap();
        }
        panic!(
            "docs/scenes.md is not current: `noncirc scenes --reference > docs/scenes.md` \
             (or run this test with NONCIRC_WRITE_DOCS=1)"
        );
    }
}

#[test]
fn the_reference_names_every_field_and_only_fields() {
    let mut paths = BTreeSet::new();
    for scene in scenes() {
        field_paths(&serde_json::to_value(&scene).unwrap(), "", &mut paths);
    }
    let listed: BTreeSet<String> = fields().map(|f| f.key.to_string()).collect();
    let missing: Vec<_> = paths.difference(&listed).collect();
    let extra: Vec<_> = listed.difference(&paths).collect();
    assert!(
        missing.is_empty(),
        "fields missing from the reference: {missing:?}"
    );
    assert!(
        extra.is_empty(),
        "the reference lists what is no field: {extra:?}"
    );
    assert_eq!(listed.len(), fields().count(), "a field is listed twice");
}

#[test]
fn every_stated_range_refuses_a_value_outside_it() {
    let base = parse_scene(BUILTIN[3].1, BUILTIN[3].0).unwrap();
    assert_eq!(BUILTIN[3].0, "transplanter");
    for field in fields() {
        assert!(!field.refused.is_empty(), "{}: no refused value", field.key);
        for probe in field.refused {
            // The probe sets the field itself, or the table that holds it.
            let (key, _) = probe.split_once('=').unwrap();
            let plain = field.key.split('[').next().unwrap();
            assert!(
                plain.starts_with(key.split('[').next().unwrap()),
                "{}: the probe {probe} sets another field",
                field.key
            );
            let result = apply_overrides(base.clone(), &[probe.to_string()]);
            assert!(result.is_err(), "{}: {probe} was accepted", field.key);
        }
    }
}

#[test]
fn errors_name_the_papers_symbols() {
    let base = parse_scene(BUILTIN[3].1, BUILTIN[3].0).unwrap();
    for (probe, named) in [
        (
            "train.pusher_offset_mm=-1",
            "train.pusher_offset_mm (H1) = -1",
        ),
        ("train.arm_length_mm=0", "train.arm_length_mm (S) = 0"),
        (
            "moving_box.spiral_angle_deg=90",
            "moving_box.spiral_angle_deg (φs) = 90",
        ),
        ("train.gamma0_deg=180", "train.gamma0_deg (γ0) = 180"),
    ] {
        let err = apply_overrides(base.clone(), &[probe.to_string()]).unwrap_err();
        assert!(err.to_string().contains(named), "{probe}: {err}");
    }
}

/// The checks a scene file's scene passes: the scene's, the search settings', the curve's.
fn checks(scene: &noncirc_core::Scene) -> Result<(), String> {
    scene
        .validate()
        .and_then(|()| scene.validate_search())
        .and_then(|()| scene.gear.curve.build().map(drop))
        .and_then(|()| scene.validate_target())
        .map_err(|e| e.to_string())
}

/// Whether the scene's checks refuse it naming `key` (or one of its list's elements).
fn refused_naming(scene: &noncirc_core::Scene, key: &str) -> Option<String> {
    checks(scene).err().filter(|e| e.starts_with(key))
}

#[test]
fn every_interval_is_exactly_what_the_checks_admit() {
    use noncirc_core::{Bound, Param, Range, SceneKind};
    // Every number of the table, in a scene that reads it: at each finite bound, the value
    // just outside is refused, and, where no rule of several fields
    // joins the interval, the value at or just inside is not refused for this field (no
    // check in code is stricter than the table says).
    let mut probed = BTreeSet::new();
    for scene in scenes() {
        for field in fields() {
            let Range::Interval { low, high, and } = field.range else {
                continue;
            };
            let path = if field.is_list() {
                format!("{}[0]", field.key)
            } else {
                field.key.to_string()
            };
            let Ok(param) = Param::parse(&path, &scene) else {
                continue;
            };
            // A scene checks the tables its kind reads: a mechanism's train and agronomy,
            // a moving box where it moves.
            let mechanism = matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter);
            let moving = matches!(scene.kind, SceneKind::MovingBox | SceneKind::Transplanter);
            let reads = match field.key.split('.').next() {
                Some("train" | "agronomy" | "dynamics") => mechanism,
                Some("moving_box") => moving,
                _ => true,
            };
            if !reads {
                continue;
            }
            // Whole numbers are written rounded: step by one.
            let mut probe = scene.clone();
            param.set(&mut probe, 0.25);
            let whole = param.get(&probe) != Some(0.25);
            let step = |b: f64| if whole { 1.0 } else { 1e-6 * b.abs().max(1.0) };
            // NaN is outside every interval (where the field can hold it).
            let mut cases = vec![(f64::NAN, true)]; // (value, refused)
            for (bound, sign) in [(low, -1.0), (high, 1.0)] {
                match bound {
                    Bound::Included(b) => {
                        cases.push((b, false));
                        cases.push((b + sign * step(b), true));
                    }
                    Bound::Excluded(b) => {
                        cases.push((b - sign * step(b), false));
                        cases.push((b, true));
                    }
                    Bound::Unbounded => {}
                }
            }
            for (value, refused) in cases {
                let mut s = scene.clone();
                param.set(&mut s, value);
                let written = param
                    .get(&s)
                    .is_some_and(|v| v == value || v.is_nan() && value.is_nan());
                if !written || !(refused || and.is_empty()) {
                    continue; // not writable (a negative count saturates to 0), or a rule
                }
                // Outside: refused (a model words its own errors: `ellipse semi_major_mm`,
                // `pitch radius must be positive`). Inside: not refused for this field.
                let got = if refused {
                    checks(&s).err()
                } else {
                    refused_naming(&s, field.key)
                };
                assert_eq!(
                    got.is_some(),
                    refused,
                    "{path} = {value} in {} (range {}): {got:?}",
                    scene.name,
                    field.range
                );
                probed.insert(field.key);
            }
        }
    }
    // Every number with an interval was probed in some scene (a count that no value
    // outside its interval can even be written to, `search.seed`, is not probed).
    let unwritable = ["search.budget", "search.seed"];
    let unprobed: Vec<_> = fields()
        .filter(|f| matches!(f.range, Range::Interval { .. }) && !probed.contains(f.key))
        .filter(|f| !unwritable.contains(&f.key))
        .map(|f| f.key)
        .collect();
    assert!(unprobed.is_empty(), "never probed: {unprobed:?}");
}
