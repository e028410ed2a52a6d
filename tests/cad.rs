//! The solids of `noncirc cad` (src/solids): exact profile areas, STL meshes that are
//! closed and outward, STEP files whose every reference resolves, and the `[cad]` checks.
//! OpenCascade reads the files in python/tests/test_cad.py.

use noncirc::scene_file::load_scene_with;
use noncirc::solids::profile::{area, points_along};
use noncirc::solids::{stl, Assembly, Format};
use noncirc::teeth::TeethRun;
use std::collections::{HashMap, HashSet};

/// The two-arm design cut by a shaper (a rack cannot cut its concave arcs).
fn assembly(extra: &[&str]) -> noncirc::Result<Assembly> {
    let mut sets = vec!["gear.teeth.cutter={kind=\"shaper\",teeth=100}".to_string()];
    sets.extend(extra.iter().map(|s| s.to_string()));
    let scene = load_scene_with(Some("two-arm"), &sets)?;
    let run = TeethRun::from_scene(&scene, 30.0)?;
    Assembly::from_run(&scene, &run, 1e-3)
}

/// The area of a polygon through `pts` (mm², counter-clockwise positive).
fn polygon_area(pts: &[noncirc::core::Vec2]) -> f64 {
    let n = pts.len();
    (0..n).map(|i| 0.5 * pts[i].cross(pts[(i + 1) % n])).sum()
}

#[test]
fn each_profiles_exact_area_is_the_limit_of_its_polygons() {
    let asm = assembly(&[]).unwrap();
    let names: Vec<&str> = asm.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "sun",
            "intermediate",
            "planet",
            "carrier_plate",
            "arm",
            "pusher"
        ]
    );
    for p in &asm.parts {
        let loops = std::iter::once(&p.profile.outer).chain(&p.profile.holes);
        for (k, l) in loops.enumerate() {
            // Outline counter-clockwise, holes clockwise.
            assert_eq!(area(l) > 0.0, k == 0, "{} loop {k}", p.name);
            // Chords within h of their arcs cut off about (2/3)·h·(arc length): the error
            // falls as h (first order), below 1e-7 relative at h = 1e-8 mm (the 1 mm mark).
            let errors: Vec<f64> = [1e-4, 1e-6, 1e-8]
                .iter()
                .map(|&h| {
                    let mut pts = Vec::new();
                    (0..l.len()).for_each(|i| points_along(l, i, h, &mut pts));
                    (polygon_area(&pts) - area(l)).abs() / area(l).abs()
                })
                .collect();
            assert!(errors[2] < 1e-7, "{} loop {k}: {errors:?}", p.name);
            if errors[0] > 1e-9 {
                let order = (errors[0] / errors[2]).log10() / 4.0;
                assert!(
                    (order - 1.0).abs() < 0.01,
                    "{} loop {k}: {errors:?}",
                    p.name
                );
            }
        }
    }
}

#[test]
fn every_stl_is_closed_and_outward_with_the_profiles_volume() {
    let asm = assembly(&[]).unwrap();
    for (p, v) in asm.parts.iter().zip(asm.volumes()) {
        let tol = 1e-3;
        let tris = stl::triangles(p, tol).unwrap();
        // Each directed edge once and its reverse once: closed, consistently oriented.
        let key = |a: [f64; 3]| a.map(f64::to_bits);
        let mut edges: HashMap<_, usize> = HashMap::new();
        for t in &tris {
            for i in 0..3 {
                *edges.entry((key(t[i]), key(t[(i + 1) % 3]))).or_default() += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1, "{}: a directed edge twice", p.name);
            assert_eq!(edges.get(&(b, a)), Some(&1), "{}: an open edge", p.name);
        }
        // Outward: positive volume, short of the exact by at most tol × perimeter × t.
        let vol = stl::volume(&tris);
        let mut perimeter = 0.0;
        for l in std::iter::once(&p.profile.outer).chain(&p.profile.holes) {
            let mut pts = Vec::new();
            (0..l.len()).for_each(|i| points_along(l, i, tol, &mut pts));
            perimeter += (0..pts.len())
                .map(|i| (pts[(i + 1) % pts.len()] - pts[i]).hypot2().sqrt())
                .sum::<f64>();
        }
        assert!(vol > 0.0);
        assert!(
            (vol - v).abs() <= tol * perimeter * p.thickness_mm,
            "{}: {vol} against {v}",
            p.name
        );
        let bytes = stl::binary(&p.name, &tris);
        assert_eq!(bytes.len(), 84 + 50 * tris.len());
    }
}

#[test]
fn every_step_reference_resolves_and_names_each_part_and_instance() {
    let asm = assembly(&[]).unwrap();
    let files = asm.files(&[Format::Step], 1e-3).unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "train.step",
            "sun.step",
            "intermediate.step",
            "planet.step",
            "carrier_plate.step",
            "arm.step",
            "pusher.step",
            "assembly.json"
        ]
    );
    for (name, bytes) in &files[..files.len() - 1] {
        let text = std::str::from_utf8(bytes).unwrap();
        assert!(text.contains("FILE_SCHEMA(('AUTOMOTIVE_DESIGN"));
        let mut defined = Vec::new();
        let mut referred = HashSet::new();
        for (i, _) in text.match_indices('#') {
            let digits: String = text[i + 1..]
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            let n: usize = digits.parse().unwrap();
            let after = text[i + 1 + digits.len()..].trim_start();
            let line_start = text[..i].rfind('\n').map_or(0, |k| k + 1);
            if line_start == i && after.starts_with('=') {
                defined.push(n);
            } else {
                referred.insert(n);
            }
        }
        // Numbered 1, 2, 3, … once each, and nothing referred to that is not defined.
        assert_eq!(defined, (1..=defined.len()).collect::<Vec<_>>(), "{name}");
        assert!(
            referred.iter().all(|n| *n >= 1 && *n <= defined.len()),
            "{name}"
        );
        let solids = text.matches("MANIFOLD_SOLID_BREP(").count();
        assert_eq!(
            solids,
            if name == "train.step" {
                asm.parts.len()
            } else {
                1
            }
        );
    }
    let train = std::str::from_utf8(&files[0].1).unwrap();
    // One usage per instance, in order, each named.
    let usages: Vec<&str> = (train.lines())
        .filter(|l| l.contains("NEXT_ASSEMBLY_USAGE_OCCURRENCE("))
        .collect();
    assert_eq!(usages.len(), asm.instances.len());
    for (line, i) in usages.iter().zip(&asm.instances) {
        assert!(line.contains(&format!(",'{}',", i.name)), "{line}");
    }
    for p in &asm.parts {
        assert!(train.contains(&format!("PRODUCT('{0}','{0}'", p.name)));
    }
    // The same design, the same bytes.
    assert_eq!(
        files,
        assembly(&[]).unwrap().files(&[Format::Step], 1e-3).unwrap()
    );
}

#[test]
fn dimensions_that_do_not_fit_are_refused_naming_the_field() {
    for (set, field) in [
        ("cad.bore_diameter_mm=60", "cad.bore_diameter_mm"),
        ("cad.key_depth_mm=20", "cad.key_depth_mm"),
        ("cad.key_width_mm=12", "cad.key_width_mm"),
        ("cad.key_width_mm=13", "cad.key_width_mm"),
        ("cad.mark_diameter_mm=30", "cad.mark_diameter_mm"),
        ("cad.arm_width_mm=12", "cad.arm_width_mm"),
    ] {
        let err = assembly(&[set]).unwrap_err().to_string();
        assert!(err.starts_with(field), "{set}: {err}");
    }
    // A plain bore (no keyway) and no mark are admitted.
    let plain = assembly(&["cad.key_width_mm=0", "cad.mark_diameter_mm=0"]).unwrap();
    assert_eq!(plain.parts[0].profile.holes.len(), 1);
    assert_eq!(plain.parts[0].profile.holes[0].len(), 2);
}
