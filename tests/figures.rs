//! Every figure and export is produced and valid: SVG parses, PNG decodes, the DXF reads
//! back (with an independent reader) to the exported geometry within 1e-6 mm.

use noncirc::core::Vec2;
use noncirc::core::{Evaluator, GearPair};
use noncirc::export::{export_gears, outlines};
use noncirc::scene_file::load_scene;
use std::f64::consts::TAU;
use std::path::Path;

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("noncirc-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn check_file(path: &Path) {
    let bytes = std::fs::read(path).unwrap();
    match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => {
            let text = String::from_utf8(bytes).unwrap();
            let doc = roxmltree::Document::parse(&text)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert_eq!(doc.root_element().tag_name().name(), "svg");
            let drawn = doc
                .descendants()
                .filter(|n| {
                    matches!(
                        n.tag_name().name(),
                        "path" | "polyline" | "line" | "text" | "rect"
                    )
                })
                .count();
            assert!(drawn >= 2, "{} draws nothing", path.display());
        }
        Some("png") => {
            let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
            let mut reader = decoder.read_info().unwrap();
            let mut buf = vec![0; reader.output_buffer_size()];
            let info = reader.next_frame(&mut buf).unwrap();
            assert!(info.width >= 600 && info.height >= 300);
            // Not a blank image: some pixels are dark (lines and text).
            assert!(
                buf.iter().filter(|&&b| b < 64).count() > 1000,
                "{} looks blank",
                path.display()
            );
        }
        Some("csv") => {
            let text = String::from_utf8(bytes).unwrap();
            let mut lines = text.lines();
            let width = lines.next().unwrap().split(',').count();
            assert!(lines.clone().count() > 10);
            assert!(lines
                .all(|l| l.split(',').count() == width
                    && l.split(',').all(|v| v.parse::<f64>().is_ok())));
        }
        _ => {}
    }
}

#[test]
fn evaluation_figures_and_exports_are_valid() {
    let dir = temp("figures");
    for name in ["paper", "transplanter"] {
        let scene = load_scene(Some(name)).unwrap();
        let eval = Evaluator::new().evaluate(&scene).unwrap();
        let files = noncirc::plots::evaluation_outputs(&scene, &eval, &dir).unwrap();
        assert!(files.len() >= 13, "{name}: {files:?}");
        for f in &files {
            check_file(f);
        }
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn dxf_reads_back_the_pitch_curves() {
    let dir = temp("dxf");
    let scene = load_scene(None).unwrap();
    let pair = GearPair::solve(scene.gear.curve.build().unwrap(), scene.resolution).unwrap();
    export_gears(&pair, &dir).unwrap();
    let drawing = dxf::Drawing::load_file(dir.join("pitch_curves.dxf").to_str().unwrap()).unwrap();
    let mut polylines: Vec<(String, Vec<[f64; 2]>)> = Vec::new();
    for e in drawing.entities() {
        if let dxf::entities::EntityType::Polyline(p) = &e.specific {
            polylines.push((
                e.common.layer.clone(),
                p.vertices().map(|v| [v.location.x, v.location.y]).collect(),
            ));
        }
    }
    let expected = outlines(&pair).unwrap();
    assert_eq!(polylines.len(), expected.len());
    for (o, (layer, pts)) in expected.iter().zip(&polylines) {
        assert_eq!(o.name, layer);
        assert_eq!(o.points.len(), pts.len());
        let worst = o
            .points
            .iter()
            .zip(pts)
            .map(|(&a, &b)| (a - b.into()).hypot())
            .fold(0.0, f64::max);
        assert!(worst < 1e-6, "{}: {worst} mm", o.name);
    }
    // The driven outline is the conjugate: at each point the two radii add up to the
    // centre distance (re-closed by the export's quadrature, within the evaluation's
    // closure error of the pair's).
    let a = expected[0].points[0].hypot() + expected[1].points[0].hypot();
    assert!(
        (a - pair.centre_distance()).abs() < 1e-4,
        "{a} vs {}",
        pair.centre_distance()
    );
    for (p, q) in expected[0].points.iter().zip(&expected[1].points) {
        assert!((q.hypot() + p.hypot() - a).abs() < 1e-9);
    }
    // Sampled to a chord tolerance, not at the evaluation's nodes: no chord's midpoint
    // strays more than the tolerance from the curve.
    let curve = pair.curve();
    let pts = &expected[0].points;
    assert!(pts.len() > 2 * pair.samples().len(), "{} points", pts.len());
    for k in 0..pts.len() {
        let (u, v) = (pts[k], pts[(k + 1) % pts.len()]);
        let (a0, a1) = (u.y.atan2(u.x), v.y.atan2(v.x));
        let half = a0 + 0.5 * (a1 - a0 - TAU * ((a1 - a0) / TAU).round());
        // The curve between the two points, and its distance from the chord.
        let on_curve = Vec2::new(half.cos(), half.sin()) * curve.eval(half).rho;
        let chord = v - u;
        let off = chord.cross(on_curve - u).abs() / chord.hypot();
        assert!(
            off < 1.2 * noncirc::export::PITCH_CHORD_TOLERANCE_MM,
            "chord {k}: {off} mm"
        );
    }
    check_file(&dir.join("pitch_curves.svg"));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn box_search_and_sweep_figures_and_the_animation() {
    let dir = temp("more");
    let scene = load_scene(Some("moving-box")).unwrap();
    let eval = Evaluator::new().evaluate(&scene).unwrap();
    for f in noncirc::figures::evaluation_figures(&scene, &eval, &dir).unwrap() {
        check_file(&f);
    }
    let paper = load_scene(None).unwrap();
    let rows = noncirc::search::sweep(&paper, "train.beta0_deg", -40.0, -20.0, 3, &[]).unwrap();
    let files = noncirc::plots::sweep_figures(&paper, "train.beta0_deg", &rows, &dir).unwrap();
    assert_eq!(files.len(), 2 * 10);
    for f in &files {
        check_file(f);
    }
    let kin = noncirc::core::Kinematics::solve(
        &paper.gear.curve.build().unwrap(),
        &paper.train,
        &paper.resolution,
    )
    .unwrap();
    let gif = dir.join("mechanism.gif");
    noncirc::figures::animate(&kin, None, &gif, 6).unwrap();
    let bytes = std::fs::read(&gif).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    // Six frames: six image descriptors (0x2C) follow graphic-control extensions (0x21 0xF9).
    assert!(bytes.windows(2).filter(|w| w == &[0x21, 0xF9]).count() >= 6);
    std::fs::remove_dir_all(dir).ok();
}
