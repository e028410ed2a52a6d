//! Every figure and export is produced and valid: SVG parses, PNG decodes, the DXF reads
//! back (with an independent reader) to the exported geometry within 1e-6 mm.

use noncirc::core::Vec2;
use noncirc::core::{Evaluator, GearPair};
use noncirc::export::{export_gears, outlines};
use noncirc::scene_file::load_scene;
use std::f64::consts::TAU;
use std::path::Path;

/// A fresh directory of this test process named by `name` (unique within the binary).
pub(crate) fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("noncirc-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Checks every file of `files` as [`check_file`] does, and that the SVGs named in
/// `named` are among them.
pub(crate) fn check_figures(files: &[std::path::PathBuf], named: &[&str]) {
    for name in named {
        assert!(
            files
                .iter()
                .any(|f| f.file_name().is_some_and(|n| n == *name)),
            "{name}: {files:?}"
        );
    }
    for f in files {
        check_file(f);
    }
}

pub(crate) fn check_file(path: &Path) {
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
            check_text_layout(path, &doc);
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

/// A text's box in the SVG's pixels, estimated from its anchor, its font size and its
/// length (DejaVu Sans averages 0.55 em a character), turned with a `rotate(270, …)`.
fn text_box(node: roxmltree::Node) -> Option<(String, [f64; 4])> {
    let text: String = node.text()?.trim().to_string();
    if text.is_empty() {
        return None;
    }
    let num = |name: &str| node.attribute(name)?.parse::<f64>().ok();
    let (x, y, size) = (num("x")?, num("y")?, num("font-size")?);
    let width = 0.55 * size * text.chars().count() as f64;
    let left = match node.attribute("text-anchor").unwrap_or("start") {
        "middle" => x - width / 2.0,
        "end" => x - width,
        _ => x,
    };
    let top = match node.attribute("dy") {
        Some("0.76em") => y,
        Some("0.5ex") => y - size / 2.0,
        Some("-0.5ex") => y - size,
        _ => y - 0.8 * size,
    };
    let b = [left, top, left + width, top + size];
    let b = match node.attribute("transform") {
        // Turned a quarter back about (x, y): x' = x + (v − y), y' = y − (u − x).
        Some(t) if t.starts_with("rotate(270") => [
            x + (b[1] - y),
            y - (b[2] - x),
            x + (b[3] - y),
            y - (b[0] - x),
        ],
        Some(t) => panic!("a text turned by {t}: not estimated"),
        None => b,
    };
    Some((text, b))
}

/// What a reviewer reads first: every text inside the canvas, no two texts on each other
/// (their estimated boxes, less a pixel each side, do not meet). Figures sized in mm (the
/// gears' drawings to scale) are not laid out with text and are left out.
fn check_text_layout(path: &Path, doc: &roxmltree::Document) {
    let root = doc.root_element();
    let size = |name: &str| root.attribute(name).and_then(|v| v.parse::<f64>().ok());
    let (Some(w), Some(h)) = (size("width"), size("height")) else {
        return;
    };
    let boxes: Vec<(String, [f64; 4])> = (doc.descendants())
        .filter(|n| n.tag_name().name() == "text")
        .filter_map(text_box)
        .collect();
    let mut faults = Vec::new();
    for (text, b) in &boxes {
        if b[0] < -1.0 || b[1] < -1.0 || b[2] > w + 1.0 || b[3] > h + 1.0 {
            faults.push(format!("{text:?} leaves the {w}×{h} canvas at {b:.0?}"));
        }
    }
    // The papers' symbols with units, not the scene's paths (`train.gamma0_deg`).
    let tables = [
        "train.",
        "gear.",
        "agronomy.",
        "search.",
        "dynamics.",
        "bounds.",
    ];
    for (text, _) in &boxes {
        for word in text.split(|c: char| c.is_whitespace() || "()[],:;".contains(c)) {
            let code = tables.iter().any(|t| {
                word.strip_prefix(t)
                    .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_alphanumeric()))
            });
            if code {
                faults.push(format!(
                    "{text:?} names a scene path ({word}), not its symbol"
                ));
            }
        }
    }
    let inner = |b: &[f64; 4]| [b[0] + 1.0, b[1] + 1.0, b[2] - 1.0, b[3] - 1.0];
    for (i, (ta, a)) in boxes.iter().enumerate() {
        for (tb, b) in &boxes[i + 1..] {
            let (a, b) = (inner(a), inner(b));
            if a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3] {
                faults.push(format!("{ta:?} overlaps {tb:?}"));
            }
        }
    }
    assert!(
        faults.is_empty(),
        "{}:\n{}",
        path.display(),
        faults.join("\n")
    );
}

/// The data a figure draws: each `<polyline>`'s segments and each filled `<rect>` but the
/// background, as `[x0, y0, x1, y1]` in the SVG's pixels.
fn data_marks(doc: &roxmltree::Document) -> (Vec<[f64; 4]>, Vec<[f64; 4]>) {
    let mut segments = Vec::new();
    let mut rects = Vec::new();
    for n in doc.descendants() {
        let num = |name: &str| n.attribute(name).and_then(|v| v.parse::<f64>().ok());
        match n.tag_name().name() {
            "polyline" => {
                let points: Vec<[f64; 2]> = (n.attribute("points").unwrap_or_default())
                    .split_whitespace()
                    .filter_map(|p| {
                        let (x, y) = p.split_once(',')?;
                        Some([x.parse().ok()?, y.parse().ok()?])
                    })
                    .collect();
                segments.extend(
                    points
                        .windows(2)
                        .map(|w| [w[0][0], w[0][1], w[1][0], w[1][1]]),
                );
            }
            "rect"
                if n.attribute("fill")
                    .is_some_and(|f| f != "none" && f != "#FFFFFF") =>
            {
                if let (Some(x), Some(y), Some(w), Some(h)) =
                    (num("x"), num("y"), num("width"), num("height"))
                {
                    // An empty bin is drawn with no height: nothing to cover.
                    if w > 0.0 && h > 0.0 {
                        rects.push([x, y, x + w, y + h]);
                    }
                }
            }
            _ => {}
        }
    }
    (segments, rects)
}

/// Whether the segment `s` meets the box `b` (Liang–Barsky clipping).
fn segment_meets_box(s: [f64; 4], b: [f64; 4]) -> bool {
    let (dx, dy) = (s[2] - s[0], s[3] - s[1]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, s[0] - b[0]),
        (dx, b[2] - s[0]),
        (-dy, s[1] - b[1]),
        (dy, b[3] - s[1]),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    t0 <= t1
}

/// No text of the figure at `path` lies on its data: its lines (the bound, the dashed
/// design, the axes) and its bars.
fn check_text_clear_of_data(path: &Path) {
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let (segments, rects) = data_marks(&doc);
    assert!(
        !segments.is_empty() && !rects.is_empty(),
        "{}: no data found",
        path.display()
    );
    let mut faults = Vec::new();
    for (text, b) in (doc.descendants())
        .filter(|n| n.tag_name().name() == "text")
        .filter_map(text_box)
    {
        let b = [b[0] + 1.0, b[1] + 1.0, b[2] - 1.0, b[3] - 1.0];
        if let Some(s) = segments.iter().find(|&&s| segment_meets_box(s, b)) {
            faults.push(format!("{text:?} lies on a line {s:.0?}"));
        }
        if let Some(r) =
            (rects.iter()).find(|r| r[0] < b[2] && b[0] < r[2] && r[1] < b[3] && b[1] < r[3])
        {
            faults.push(format!("{text:?} lies on a bar {r:.0?}"));
        }
    }
    assert!(
        faults.is_empty(),
        "{}:\n{}",
        path.display(),
        faults.join("\n")
    );
}

#[test]
fn evaluation_figures_and_exports_are_valid() {
    let dir = temp("figures");
    for name in ["paper", "transplanter"] {
        let scene = load_scene(Some(name)).unwrap();
        let eval = Evaluator::new().evaluate(&scene).unwrap();
        let files =
            noncirc::plots::evaluation_outputs(&scene, &eval, &dir, &Default::default()).unwrap();
        assert!(files.len() >= 13, "{name}: {files:?}");
        for f in &files {
            check_file(f);
        }
        if name == "paper" {
            // Two markers beyond their rows' scale (the arms' clearance, 45 mm, and the
            // picking check, 52 mm, past ten margin scales) say so.
            let svg = std::fs::read_to_string(dir.join("objectives.svg")).unwrap();
            assert_eq!(svg.matches("off scale →").count(), 2);
        }
    }
    std::fs::remove_dir_all(dir).ok();
}

/// The robustness and sensitivity figures pass the layout check, and the heat map has its
/// colour bar: a gradient of 100 steps from white to the darkest cell's blue, ticked 0 to 1.
#[test]
fn robustness_and_sensitivity_figures_read_as_a_reviewer_reads_them() {
    let dir = temp("robustness-figures");
    let scene = load_scene(None).unwrap();
    let r = noncirc::robustness::robustness(&scene, false).unwrap();
    let s = noncirc::robustness::sensitivity(&scene, 64, 20, 0.25, 2).unwrap();
    let mut files = noncirc::plots::robustness_figures(&r, &dir, &Default::default()).unwrap();
    files.extend(noncirc::plots::sensitivity_figures(&s, &dir, &Default::default()).unwrap());
    assert_eq!(files.len(), 4);
    for f in &files {
        check_file(f);
    }
    // The margins' notes (how far a bound off the chart is) stand clear of the bars and
    // of the dashed design; the paper's design puts bounds off their charts.
    let margins = dir.join("robustness_margins.svg");
    check_text_clear_of_data(&margins);
    let svg = std::fs::read_to_string(&margins).unwrap();
    let notes = svg.matches("\nbound ").count();
    assert!(notes >= 3, "{notes} notes on far bounds");
    let svg = std::fs::read_to_string(dir.join("sensitivity.svg")).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts: Vec<&str> = (doc.descendants())
        .filter(|n| n.tag_name().name() == "text")
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    for tick in ["S_T", "0.00", "0.50", "1.00"] {
        assert!(texts.contains(&tick), "no colour bar tick {tick}");
    }
    for fill in ["#FEFEFE", "#09316C"] {
        assert!(
            svg.contains(&format!("fill=\"{fill}\"")),
            "colour bar without {fill}"
        );
    }
    // At 64 base points the map marks its outputs and says how many points would do.
    assert!(texts
        .iter()
        .any(|t| t.starts_with("† indices not readable at 64 base points")));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn dxf_reads_back_the_pitch_curves() {
    let dir = temp("dxf");
    let scene = load_scene(None).unwrap();
    let pair = GearPair::solve(scene.gear.curve.build().unwrap(), scene.resolution).unwrap();
    export_gears(&pair, None, &dir).unwrap();
    let drawing = dxf::Drawing::load_file(dir.join("pitch_curves.dxf").to_str().unwrap()).unwrap();
    assert_eq!(drawing.header.version, dxf::enums::AcadVersion::R2000);
    assert_eq!(
        drawing.header.default_drawing_units,
        dxf::enums::Units::Millimeters
    );
    let mut polylines: Vec<(String, Vec<[f64; 2]>)> = Vec::new();
    for e in drawing.entities() {
        if let dxf::entities::EntityType::LwPolyline(p) = &e.specific {
            assert!(p.is_closed());
            polylines.push((
                e.common.layer.clone(),
                p.vertices.iter().map(|v| [v.x, v.y]).collect(),
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
    for f in noncirc::figures::evaluation_figures(&scene, &eval, &dir, &Default::default()).unwrap()
    {
        check_file(&f);
    }
    let paper = load_scene(None).unwrap();
    let rows = noncirc::sweep::sweep(&paper, "train.beta0_deg", -40.0, -20.0, 3, &[]).unwrap();
    let files =
        noncirc::plots::sweep_figures(&paper, "train.beta0_deg", &rows, &dir, &Default::default())
            .unwrap();
    assert_eq!(files.len(), 2 * 10);
    for f in &files {
        check_file(f);
    }
    let kin = noncirc::core::Kinematics::solve(
        &paper.gear.curve.build().unwrap(),
        None,
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

/// The PNG's declared resolution (dots per inch), from its `pHYs` chunk.
fn png_dpi(bytes: &[u8]) -> Option<f64> {
    let at = bytes.windows(4).position(|w| w == b"pHYs")?;
    let per_metre = u32::from_be_bytes(bytes[at + 4..at + 8].try_into().ok()?);
    (bytes[at + 12] == 1).then_some(f64::from(per_metre) * 0.0254)
}

#[test]
fn figures_at_a_chosen_size_resolution_and_format() {
    use noncirc::figures::{FigureFormat, FigureOptions};
    let dir = temp("options");
    let scene = load_scene(None).unwrap();
    let eval = Evaluator::new().evaluate(&scene).unwrap();
    let options = FigureOptions {
        formats: vec![FigureFormat::Svg, FigureFormat::Png, FigureFormat::Pdf],
        size_px: Some((640, 480)),
        dpi: 300,
    };
    let files = noncirc::figures::evaluation_figures(&scene, &eval, &dir, &options).unwrap();
    assert_eq!(files.len(), 4 * 3, "{files:?}");
    for f in &files {
        let bytes = std::fs::read(f).unwrap();
        match f.extension().and_then(|e| e.to_str()) {
            Some("png") => {
                // 640×480 CSS pixels at 300 dpi: 2000×1500 dots, declared as 300 dpi.
                let decoder = png::Decoder::new(std::io::Cursor::new(&bytes));
                let info = decoder.read_info().unwrap().info().clone();
                assert_eq!((info.width, info.height), (2000, 1500), "{}", f.display());
                let dpi = png_dpi(&bytes).unwrap();
                assert!((dpi - 300.0).abs() < 0.1, "{dpi}");
            }
            Some("pdf") => {
                assert!(bytes.starts_with(b"%PDF-"), "{}", f.display());
                // The font travels with it: a PDF for a paper needs none installed.
                let text = String::from_utf8_lossy(&bytes);
                assert!(text.contains("/FontFile2") || text.contains("/FontFile3"));
            }
            Some("svg") => {
                let text = String::from_utf8(bytes).unwrap();
                assert!(
                    text.contains(r#"width="640" height="480""#),
                    "{}",
                    f.display()
                );
                // Curves are drawn to sub-pixel precision, and no placeholder is left.
                assert!(!text.contains("noncirc-fine-line"));
                if f.file_stem().unwrap() == "trajectory" {
                    // The fine lines (round joins) hold coordinates between whole pixels.
                    let fine: Vec<f64> = (text.split("<polyline").skip(1))
                        .filter(|p| p.contains(r#"stroke-linejoin="round""#))
                        .flat_map(|p| p.split("points=\"").nth(1).unwrap().split('"').next())
                        .flat_map(|pts| pts.split([' ', ',']).map(|v| v.parse::<f64>().unwrap()))
                        .collect();
                    assert!(fine.len() > 500, "{} fine coordinates", fine.len());
                    let between = fine.iter().filter(|v| v.fract() != 0.0).count();
                    assert!(between * 2 > fine.len(), "{between} of {}", fine.len());
                }
            }
            other => panic!("unexpected file {other:?}"),
        }
    }
    // Bad settings are refused by name.
    for (bad, named) in [
        (
            FigureOptions {
                dpi: 0,
                ..options.clone()
            },
            "0 dpi",
        ),
        (
            FigureOptions {
                size_px: Some((10, 480)),
                ..options.clone()
            },
            "width 10 px",
        ),
        (
            FigureOptions {
                formats: vec![],
                ..options.clone()
            },
            "none given",
        ),
    ] {
        let e = noncirc::figures::evaluation_figures(&scene, &eval, &dir, &bad).unwrap_err();
        assert!(e.to_string().contains(named), "{e}");
    }
    std::fs::remove_dir_all(dir).ok();
}

/// A search's figures, for one goal (convergence and the best design; no front) and two
/// (the Pareto front too). A single-goal run that found feasible designs once panicked
/// here, reading a second goal it does not have.
#[test]
fn search_figures_for_one_goal_and_for_two() {
    use noncirc::search::RunOptions;
    use std::sync::{atomic::AtomicBool, Arc};
    let dir = temp("search");
    let options = RunOptions {
        threads: 2,
        checkpoint: None,
        checkpoint_every: std::time::Duration::from_secs(3600),
        resume: None,
        resume_budget: None,
        stop: Arc::new(AtomicBool::new(false)),
        max_generations: None,
        on_checkpoint_failure: |_| {},
    };
    let one = noncirc::scene_file::apply_overrides(
        load_scene(Some("paper-search")).unwrap(),
        &["search.budget=20000".into()],
    )
    .unwrap();
    let two = noncirc::scene_file::apply_overrides(
        one.clone(),
        &[
            r#"search.goals=["module","picking_tip_speed"]"#.into(),
            r#"search.algorithm="nsga2""#.into(),
            "search.seed=2".into(),
        ],
    )
    .unwrap();
    for (scene, front) in [(one, false), (two, true)] {
        let outcome = noncirc::search::run(&scene, &options, &mut []).unwrap();
        assert!(outcome.state.first_feasible_at.is_some(), "not feasible");
        let out = dir.join(if front { "two" } else { "one" });
        let files = noncirc::plots::search_figures(&outcome, &out, &Default::default()).unwrap();
        let names: Vec<String> = (files.iter())
            .map(|f| f.strip_prefix(&out).unwrap().display().to_string())
            .collect();
        assert!(names.contains(&"convergence.png".to_string()), "{names:?}");
        assert!(
            names.contains(&"best/trajectory.png".to_string()),
            "{names:?}"
        );
        assert_eq!(
            names.contains(&"pareto.png".to_string()),
            front,
            "{names:?}"
        );
        for f in &files {
            check_file(f);
        }
    }
    std::fs::remove_dir_all(dir).ok();
}

/// The dynamics' and the teeth's figures pass the layout check too: text inside the
/// canvas, no two texts on each other, symbols not scene paths (a repair's: tests/repair.rs).
#[test]
fn dynamics_and_teeth_figures_read_as_a_reviewer_reads_them() {
    let dir = temp("dynamics-teeth-figures");
    let options = Default::default();
    let paper = load_scene(None).unwrap();
    let report = noncirc::dynamics::report_of(&paper).unwrap();
    let arm_counts = noncirc::dynamics::by_arm_count(&paper);
    let mut files =
        noncirc::dynamics::figures(&report, &arm_counts, &dir.join("dynamics"), &options).unwrap();
    let gear = load_scene(Some("ellipse-gear")).unwrap();
    let teeth = noncirc::teeth::TeethRun::from_scene(&gear, 0.0).unwrap();
    files.extend(noncirc::figures::teeth_figures(&teeth, &dir.join("teeth"), &options).unwrap());
    let svgs = files
        .iter()
        .filter(|f| f.extension().is_some_and(|e| e == "svg"));
    assert!(svgs.count() >= 6, "{files:?}");
    for f in &files {
        check_file(f);
    }
    std::fs::remove_dir_all(dir).ok();
}
