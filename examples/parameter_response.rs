//! Parameter response (three-arm paper §4.2, Figure 5): each of the 17 parameters swept
//! around the paper's design, with the trend of each section measure, and a figure of the
//! trajectories per parameter. Writes the table of docs/parameter-response.md to stdout and
//! the figures to the folder given (default `docs/figures/response`).
//!
//! `cargo run --release --example parameter_response -- docs/figures/response`

use noncirc::core::{Evaluator, Param, Scene};
use noncirc::core::{Measure, Measured};
use noncirc::figures::{save, FigureOptions, LinesFigure, FIGURE_SAMPLES};
use noncirc::scene_file::load_scene;
use std::path::PathBuf;

/// The measures §4.2 speaks of.
const MEASURES: [&str; 7] = [
    "removal_length_mm",
    "loop_height_mm",
    "return_height_mm",
    "picking_to_planting_height_mm",
    "picking_height_mm",
    "planting_height_mm",
    "picking_angle",
];

/// The 17 parameters and their sweep ranges around the paper's values.
pub fn parameters(scene: &Scene) -> Vec<(String, f64, f64)> {
    let mut out = Vec::new();
    if let noncirc::core::CurveSpec::Spline { radii_mm, .. } = &scene.gear.curve {
        for (i, r) in radii_mm.iter().enumerate() {
            out.push((format!("gear.curve.radii_mm[{i}]"), 0.8 * r, 1.2 * r));
        }
    }
    let t = &scene.train;
    out.push((
        "train.phi0_deg".into(),
        t.phi0_deg - 10.0,
        t.phi0_deg + 10.0,
    ));
    out.push((
        "train.beta0_deg".into(),
        t.beta0_deg - 10.0,
        t.beta0_deg + 10.0,
    ));
    out.push((
        "train.arm_length_mm".into(),
        0.9 * t.arm_length_mm,
        1.1 * t.arm_length_mm,
    ));
    out.push((
        "train.pusher_offset_mm".into(),
        0.8 * t.pusher_offset_mm,
        1.2 * t.pusher_offset_mm,
    ));
    out.push((
        "train.gamma0_deg".into(),
        t.gamma0_deg - 10.0,
        t.gamma0_deg + 10.0,
    ));
    out
}

fn main() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or("docs/figures/response".into()),
    );
    std::fs::create_dir_all(&dir)?;
    let scene = load_scene(Some("paper"))?;
    let measures: Vec<Measure> = MEASURES
        .iter()
        .map(|m| Measure::parse(m))
        .collect::<Result<_, _>>()?;
    let steps = 9;
    print!("| parameter | range |");
    for m in MEASURES {
        print!(" {m} |");
    }
    println!();
    println!("|---|---|{}", "---|".repeat(MEASURES.len()));
    for (name, lo, hi) in parameters(&scene) {
        let p = Param::parse(&name, &scene)?;
        let mut rows: Vec<Vec<f64>> = Vec::new();
        let mut series = Vec::new();
        for i in 0..steps {
            let v = lo + (hi - lo) * i as f64 / (steps - 1) as f64;
            let mut s = scene.clone();
            p.set(&mut s, v);
            let eval = Evaluator::new().evaluate(&s)?;
            let on = Measured::new(&eval, &s);
            rows.push(
                (measures.iter())
                    .map(|m| m.value(&on).unwrap_or(f64::NAN))
                    .collect(),
            );
            if i % 4 == 0 {
                // Drawn from a dense solution, not the evaluation's samples.
                let dense = s.resolution.with_samples(FIGURE_SAMPLES);
                let kin = s.kinematics(&dense)?;
                let pts = kin
                    .tips()
                    .iter()
                    .chain(kin.tips().first())
                    .map(|&t| t.into())
                    .collect();
                series.push((format!("{name} = {v:.1}"), pts));
            }
        }
        print!("| {} `{name}` | {lo:.1} .. {hi:.1} |", symbol(&name));
        for k in 0..measures.len() {
            let column: Vec<f64> = rows.iter().map(|r| r[k]).collect();
            print!(" {} |", trend(&column));
        }
        println!();
        let file = name.replace(['.', '[', ']'], "_");
        let file = file.trim_end_matches('_');
        // The section measures in millimetres against the parameter (angles left to the table).
        let values: Vec<f64> = (0..steps)
            .map(|i| lo + (hi - lo) * i as f64 / (steps - 1) as f64)
            .collect();
        let measure_series = (0..measures.len())
            .filter(|&k| measures[k].unit() == "mm")
            .map(|k| {
                // Change from the paper's design, the middle of the sweep.
                let base = rows[steps / 2][k];
                let pts = (values.iter().zip(&rows))
                    .map(|(&v, r)| (v, r[k] - base))
                    .collect();
                (MEASURES[k].to_string(), pts)
            })
            .collect();
        save(
            &LinesFigure {
                title: format!("section measures against {} ({name})", symbol(&name)),
                x_desc: axis(&name),
                y_desc: "change from the paper's design (mm)".into(),
                series: measure_series,
                points_only: false,
                markers: true,
                band: None,
            },
            &dir.join(format!("{file}_measures")),
            &FigureOptions::default(),
        )?;
        save(
            &LinesFigure {
                title: format!("tip trajectory against {} ({name})", symbol(&name)),
                x_desc: "x (mm)".into(),
                y_desc: "y (mm)".into(),
                series,
                points_only: false,
                markers: false,
                band: None,
            },
            &dir.join(file),
            &FigureOptions::default(),
        )?;
    }
    Ok(())
}

/// The paper's symbol for a parameter path: r1..r12, Φ0, β0, S, H1, γ0.
fn symbol(name: &str) -> String {
    noncirc::core::symbol(name).unwrap_or_else(|| name.to_string())
}

/// A parameter's axis title: its path, symbol and unit (`train.arm_length_mm, S (mm)`).
fn axis(name: &str) -> String {
    let unit = noncirc::core::field(name).map_or("", |f| f.unit);
    format!("{name}, {} ({unit})", symbol(name))
}

/// `a → b (↑)`: first and last values and the direction, `↑`/`↓` when monotone over the
/// sweep, `~` when not.
fn trend(values: &[f64]) -> String {
    let (a, b) = (values[0], values[values.len() - 1]);
    let up = values.windows(2).all(|w| w[1] >= w[0]);
    let down = values.windows(2).all(|w| w[1] <= w[0]);
    let arrow = if up && !down {
        "↑"
    } else if down && !up {
        "↓"
    } else if up && down {
        "="
    } else {
        "~"
    };
    format!("{a:.1} → {b:.1} {arrow}")
}
