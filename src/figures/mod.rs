//! Figures (SVG and PNG, plotters) and the animation (GIF). Text uses DejaVu Sans, embedded
//! in the binary, so rendering needs no system font or package.

use noncirc_core::{
    advance_per_rad, anatomy, box_curves, travel_sign, unit, BoxReport, BoxSpec, Evaluation,
    Events, Kinematics, ObjectiveValue, Scene, Section, ToothedPair, Vec2,
};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::files::create_dir;
use crate::{Error, Result};

mod gears;
mod ground;
mod lines;
mod moving_box;
mod objectives;
mod teeth;
mod trajectory;

pub use gears::{animate, GearsFigure, MAX_FRAMES};
pub use ground::GroundFigure;
pub use lines::LinesFigure;
pub use moving_box::BoxFigure;
pub use objectives::ObjectivesFigure;
pub use teeth::{teeth_figures, TeethFigure};
pub use trajectory::TrajectoryFigure;

const FONT: &str = "sans-serif";

/// Registers the embedded font once per process.
pub fn register_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular()).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(Error::Figure(
            "the embedded DejaVu Sans font could not be loaded".into(),
        ))
    }
}

fn err<E: std::fmt::Display>(e: E) -> Error {
    Error::Figure(e.to_string())
}

/// The legend, drawn alike on every figure: a framed, lightly shaded box of `font_size`
/// px text, at `position` (plotters' default where `None`).
fn draw_legend<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    font_size: u32,
    position: Option<SeriesLabelPosition>,
) -> Result<()> {
    let mut legend = chart.configure_series_labels();
    legend
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, font_size));
    if let Some(position) = position {
        legend.position(position);
    }
    legend.draw().map_err(err)
}

/// A figure that can draw itself on any plotters backend.
pub trait Figure {
    fn size(&self) -> (u32, u32) {
        (900, 700)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static;
}

/// Renders `fig` to `<base>.svg` and `<base>.png`; returns both paths.
pub fn save(fig: &impl Figure, base: &Path) -> Result<Vec<PathBuf>> {
    register_font()?;
    let (svg, png) = (base.with_extension("svg"), base.with_extension("png"));
    {
        let root = SVGBackend::new(&svg, fig.size()).into_drawing_area();
        fig.draw(&root)?;
        root.present().map_err(err)?;
    }
    {
        let root = BitMapBackend::new(&png, fig.size()).into_drawing_area();
        fig.draw(&root)?;
        root.present().map_err(err)?;
    }
    Ok(vec![svg, png])
}

/// A chart of the plane on `area`, both axes in millimetres over `x` and `y`.
fn plane_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    caption_size: u32,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>>
where
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, caption_size))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(x, y)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("x (mm)")
        .y_desc("y (mm)")
        .label_style((FONT, 12))
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// The parts of the polyline `points` inside the box `x`×`y` (mm), each segment cut at
/// the box's edges (Liang–Barsky): plotters would pin points outside the plot area to its
/// border and draw lines along it.
fn clipped_runs(points: &[(f64, f64)], x: (f64, f64), y: (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut open = false;
    for w in points.windows(2) {
        let ((ax, ay), (bx, by)) = (w[0], w[1]);
        let (dx, dy) = (bx - ax, by - ay);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        let inside = [
            (-dx, ax - x.0),
            (dx, x.1 - ax),
            (-dy, ay - y.0),
            (dy, y.1 - ay),
        ]
        .into_iter()
        .all(|(p, q)| {
            if p == 0.0 {
                return q >= 0.0;
            }
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
            t0 <= t1
        });
        if !inside {
            open = false;
            continue;
        }
        let at = |t: f64| match t {
            0.0 => w[0],
            1.0 => w[1],
            _ => (ax + t * dx, ay + t * dy),
        };
        let (p, q) = (at(t0), at(t1));
        match runs.last_mut() {
            Some(run) if open && t0 == 0.0 => run.push(q),
            _ => runs.push(vec![p, q]),
        }
        open = t1 == 1.0;
    }
    runs
}

/// Axis ranges with equal scale in x and y for a plot area of `w × h` pixels.
fn equal_ranges(
    points: impl Iterator<Item = Vec2>,
    w: f64,
    h: f64,
    pad: f64,
) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for Vec2 { x, y } in points {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let scale = ((x1 - x0 + 2.0 * pad) / w).max((y1 - y0 + 2.0 * pad) / h);
    (
        (cx - 0.5 * w * scale, cx + 0.5 * w * scale),
        (cy - 0.5 * h * scale, cy + 0.5 * h * scale),
    )
}

const ARM_COLOURS: [RGBColor; 3] = [
    RGBColor(200, 30, 30),
    RGBColor(30, 110, 200),
    RGBColor(40, 150, 60),
];

/// Colours of the trajectory's sections, in `Section::ALL` order.
const SECTION_COLOURS: [RGBColor; 4] = [
    RGBColor(0, 160, 170),
    RGBColor(230, 140, 0),
    RGBColor(130, 50, 180),
    RGBColor(40, 40, 40),
];

/// Every figure of one evaluation into `dir`; returns the files written.
pub fn evaluation_figures(scene: &Scene, eval: &Evaluation, dir: &Path) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = Vec::new();
    if let (Some(kin), Some(ev)) = (&eval.kinematics, &eval.events) {
        files.extend(save(
            &TrajectoryFigure {
                kin,
                events: ev,
                scene,
            },
            &dir.join("trajectory"),
        )?);
        files.extend(save(
            &GroundFigure {
                kin,
                events: ev,
                scene,
            },
            &dir.join("ground"),
        )?);
        files.extend(save(
            &GearsFigure {
                kin,
                theta: ev.picking.carrier_rad,
            },
            &dir.join("gears"),
        )?);
    }
    if !eval.objectives.is_empty() {
        files.extend(save(
            &ObjectivesFigure {
                objectives: &eval.objectives,
                scene,
            },
            &dir.join("objectives"),
        )?);
    }
    if let Some(report) = &eval.moving_box {
        files.extend(save(
            &BoxFigure {
                spec: &scene.moving_box,
                report,
            },
            &dir.join("moving_box"),
        )?);
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::clipped_runs;

    #[test]
    fn a_polyline_leaving_the_box_is_cut_at_its_edges_into_runs() {
        // In at the left edge, out through the top, back in through the top, ending inside.
        let path = [(-1.0, 0.5), (0.5, 0.5), (0.5, 2.0), (0.8, 2.0), (0.8, 0.2)];
        let runs = clipped_runs(&path, (0.0, 1.0), (0.0, 1.0));
        assert_eq!(
            runs,
            vec![
                vec![(0.0, 0.5), (0.5, 0.5), (0.5, 1.0)],
                vec![(0.8, 1.0), (0.8, 0.2)],
            ]
        );
        // Wholly outside: nothing; wholly inside: the polyline itself.
        assert!(clipped_runs(&[(2.0, 2.0), (3.0, 2.5)], (0.0, 1.0), (0.0, 1.0)).is_empty());
        let inside = vec![(0.1, 0.1), (0.9, 0.2), (0.5, 0.9)];
        assert_eq!(clipped_runs(&inside, (0.0, 1.0), (0.0, 1.0)), vec![inside]);
    }
}
