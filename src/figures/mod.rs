//! Figures (SVG and PNG, plotters) and the animation (GIF). Text uses DejaVu Sans, embedded
//! in the binary, so rendering needs no system font or package.

use noncirc_core::{
    advance_per_rad, anatomy, box_curves, travel_sign, BoxReport, BoxSpec, Evaluation, Events,
    Kinematics, ObjectiveValue, Scene, Section, Vec2, ARM_NAMES,
};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::f64::consts::TAU;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::files::create_dir;
use crate::{Error, Result};

mod convergence;
mod fit;
mod gears;
mod ground;
mod inverse;
mod lines;
mod moving_box;
mod objectives;
mod robustness;
mod save;
mod speeds;
mod teeth;
mod trajectory;

pub use convergence::ConvergenceFigure;
pub use fit::FitFigure;
pub use gears::{animate, GearsFigure, MAX_FRAMES};
pub use ground::GroundFigure;
pub use inverse::InverseFigure;
pub use lines::LinesFigure;
pub use moving_box::BoxFigure;
pub use objectives::ObjectivesFigure;
pub use robustness::{MarginsFigure, SensitivityFigure};
pub use save::{save, FigureFormat, FigureOptions};
pub use speeds::{ComparedDesign, SpeedComparisonFigure};
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

/// Where a chart's legend goes, as the room (px) left for it: right of the plotting area,
/// or below it (under the x axis) where the figure is too narrow for that.
#[derive(Debug, Clone, Copy)]
struct LegendPlace {
    right: u32,
    below: u32,
}

impl LegendPlace {
    /// The plotting area (px) a chart on an area of `size` px leaves with this legend, its
    /// `margin` all round and `(x, y)` label areas: what equal x and y scales are fitted to.
    fn plot_size(
        self,
        (w, h): (u32, u32),
        margin: u32,
        (x_label, y_label): (u32, u32),
    ) -> (u32, u32) {
        (
            w.saturating_sub(margin + margin.max(LAST_TICK_HALF) + y_label + self.right)
                .max(100),
            h.saturating_sub(2 * margin + x_label + self.below).max(100),
        )
    }
}

/// Half the widest x tick label a chart ends on (px): six characters at 13 px.
const LAST_TICK_HALF: u32 = 24;

/// A chart builder on `area` with `margin` px all round (on the right at least
/// [`LAST_TICK_HALF`]), the room for its legend at `place`, and `(x, y)` label areas (px).
fn chart_on<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    margin: u32,
    place: LegendPlace,
    (x_label, y_label): (u32, u32),
) -> ChartBuilder<'a, 'b, DB> {
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(margin)
        // Room for half the last x tick label ("60000"), centred on the plot's right edge.
        .margin_right(margin.max(LAST_TICK_HALF) + place.right)
        .margin_bottom(margin + place.below)
        .x_label_area_size(x_label)
        .y_label_area_size(y_label);
    builder
}

/// The size (px) of a legend box of `rows` labels, the longest `chars` characters long, at
/// `font_size` px: the row height, and DejaVu Sans's average of about 0.6 em a character.
fn legend_box(chars: usize, rows: usize, font_size: u32) -> (u32, u32) {
    let row = (f64::from(font_size) * 1.7).round() as u32;
    let width = 40 + (chars as f64 * f64::from(font_size) * 0.6).ceil() as u32;
    (width, row * rows as u32 + 8)
}

/// The legend's place for `labels` at `font_size` px on a chart of `size` px: right of
/// the plot unless that takes more than two fifths of the width, else wherever it leaves
/// the plot more room.
fn legend_place<'s>(
    labels: impl IntoIterator<Item = &'s str>,
    font_size: u32,
    (width, height): (u32, u32),
) -> LegendPlace {
    let (mut chars, mut rows) = (0, 0);
    for label in labels {
        chars = chars.max(label.chars().count());
        rows += 1;
    }
    let (w, h) = legend_box(chars, rows, font_size);
    // The box, the gap to the plot (12 px) and a little room beyond it.
    let (right, below) = (w + 20, h + 8);
    let area_right = u64::from(width.saturating_sub(right)) * u64::from(height);
    let area_below = u64::from(width) * u64::from(height.saturating_sub(below));
    if right * 5 <= width * 2 || area_right >= area_below {
        LegendPlace { right, below: 0 }
    } else {
        LegendPlace { right: 0, below }
    }
}

/// A tick label as a person writes it: `150`, `2.5`, `0.05`, not `150.0`.
fn tick(v: &f64) -> String {
    let text = format!("{v:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

/// How a legend entry shows its series.
#[derive(Debug, Clone, Copy)]
enum Swatch {
    /// A line of this width (px).
    Line(RGBAColor, u32),
    /// A dashed line of this width.
    Dashed(RGBAColor, u32),
    /// A filled band.
    Band(RGBAColor),
    /// A filled dot.
    Dot(RGBAColor),
    /// A ring (a marker that leaves the line under it visible).
    Ring(RGBAColor),
    /// A filled triangle.
    Triangle(RGBAColor),
    /// A short upright line of this width (a marker line, a seedling).
    Tick(RGBAColor, u32),
}

/// A legend's entries, in order.
type Entries = Vec<(String, Swatch)>;

/// The legend, drawn alike on every figure and never over the data: a framed box of
/// `font_size` px text beside `plot`, the plotting area of a chart built on `area` with
/// `place`'s room as its right or bottom margin. Drawn on `area` itself: plotters pins
/// whatever a chart draws to its plotting area.
fn draw_legend<DB: DrawingBackend, CT: plotters::coord::CoordTranslate>(
    area: &DrawingArea<DB, Shift>,
    plot: &DrawingArea<DB, CT>,
    entries: &[(String, Swatch)],
    font_size: u32,
    place: LegendPlace,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    if entries.is_empty() {
        return Ok(());
    }
    let ((px, py), (ax, ay)) = (plot.get_base_pixel(), area.get_base_pixel());
    let (x, y) = if place.below > 0 {
        (
            px - ax,
            area.dim_in_pixel().1 as i32 - place.below as i32 + 4,
        )
    } else {
        (px - ax + plot.dim_in_pixel().0 as i32 + 12, py - ay)
    };
    let row = (f64::from(font_size) * 1.7).round() as i32;
    let chars = (entries.iter())
        .map(|(l, _)| l.chars().count())
        .max()
        .unwrap_or(0);
    let (width, height) = legend_box(chars, entries.len(), font_size);
    let (width, height) = (width as i32, height as i32);
    area.draw(&Rectangle::new(
        [(x, y), (x + width, y + height)],
        WHITE.filled(),
    ))
    .map_err(err)?;
    area.draw(&Rectangle::new([(x, y), (x + width, y + height)], BLACK))
        .map_err(err)?;
    for (i, (label, swatch)) in entries.iter().enumerate() {
        let (sx, sy) = (x + 8, y + 4 + row * i as i32 + row / 2);
        let line = |c: RGBAColor, w: u32, a: i32, b: i32| {
            PathElement::new(vec![(sx + a, sy), (sx + b, sy)], c.stroke_width(w))
        };
        match *swatch {
            Swatch::Line(c, w) => area.draw(&line(c, w, 0, 22)),
            Swatch::Dashed(c, w) => area
                .draw(&line(c, w, 0, 8))
                .and_then(|()| area.draw(&line(c, w, 13, 22))),
            Swatch::Band(c) => area.draw(&Rectangle::new(
                [(sx, sy - 6), (sx + 22, sy + 6)],
                c.filled(),
            )),
            Swatch::Dot(c) => area.draw(&Circle::new((sx + 11, sy), 5, c.filled())),
            Swatch::Ring(c) => area.draw(&Circle::new((sx + 11, sy), 6, c.stroke_width(2))),
            Swatch::Triangle(c) => area.draw(&TriangleMarker::new((sx + 11, sy), 7, c.filled())),
            Swatch::Tick(c, w) => area.draw(&PathElement::new(
                vec![(sx + 11, sy - row / 2 + 2), (sx + 11, sy + row / 2 - 2)],
                c.stroke_width(w),
            )),
        }
        .map_err(err)?;
        area.draw(&Text::new(
            label.clone(),
            (sx + 30, sy),
            TextStyle::from((FONT, font_size)).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(err)?;
    }
    Ok(())
}

thread_local! {
    /// The curves drawn to sub-pixel precision while a figure is written as SVG: each
    /// stands in the SVG as a placeholder text that [`save`] replaces by it.
    static FINE_LINES: std::cell::RefCell<Option<Vec<String>>> = const { std::cell::RefCell::new(None) };
}

/// The placeholder of fine line `i` in the SVG text.
fn fine_placeholder(i: usize) -> String {
    format!("noncirc-fine-line-{i}")
}

/// A chart of two float axes.
type FloatChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws `points` (data coordinates) as a line: to a hundredth of a pixel in the SVG (and
/// so in the PNG and PDF rendered from it), where plotters rounds every point to a whole
/// pixel, which shows as kinks along a smooth curve; as plotters draws it elsewhere (the
/// animation). Points outside the chart's ranges are cut away.
fn fine_line<DB: DrawingBackend>(
    chart: &mut FloatChart<'_, DB>,
    points: &[(f64, f64)],
    colour: RGBAColor,
    width: u32,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let runs = clipped_runs(points, (xr.start, xr.end), (yr.start, yr.end));
    let collecting = FINE_LINES.with(|f| f.borrow().is_some());
    if !collecting {
        for run in runs {
            chart
                .draw_series(LineSeries::new(run, colour.stroke_width(width)))
                .map_err(err)?;
        }
        return Ok(());
    }
    let area = chart.plotting_area();
    let (px, py) = area.get_pixel_range();
    let to_pixel = |(x, y): (f64, f64)| {
        (
            px.start as f64 + (px.end - px.start) as f64 * (x - xr.start) / (xr.end - xr.start),
            py.end as f64 - (py.end - py.start) as f64 * (y - yr.start) / (yr.end - yr.start),
        )
    };
    for run in runs {
        let mut pts = String::new();
        for p in run {
            let (x, y) = to_pixel(p);
            pts += &format!("{x:.2},{y:.2} ");
        }
        let (RGBAColor(r, g, b, a), w) = (colour, width);
        let line = format!(
            r##"<polyline fill="none" stroke="#{r:02X}{g:02X}{b:02X}" stroke-opacity="{a:.3}" stroke-width="{w}" stroke-linejoin="round" stroke-linecap="round" points="{}"/>"##,
            pts.trim_end()
        );
        let i = FINE_LINES.with(|f| {
            let mut f = f.borrow_mut();
            let lines = f.as_mut().expect("collecting");
            lines.push(line);
            lines.len() - 1
        });
        // The placeholder keeps the line's place among what plotters draws.
        chart
            .plotting_area()
            .draw(&Text::new(
                fine_placeholder(i),
                (xr.start, yr.start),
                (FONT, 1),
            ))
            .map_err(err)?;
    }
    Ok(())
}

/// `svg` with each fine line's placeholder text replaced by the line.
fn put_fine_lines(svg: &str, lines: &[String]) -> Result<String> {
    let mut out = svg.to_string();
    for (i, line) in lines.iter().enumerate() {
        // `<text …>\nPLACEHOLDER\n</text>`: the placeholder is unique (its number ends
        // at the newline), the element around it plotters' text.
        let placeholder = format!("\n{}\n", fine_placeholder(i));
        let broken = || Error::Figure(format!("fine line {i}: its placeholder is missing"));
        let at = out.find(&placeholder).ok_or_else(broken)?;
        let start = out[..at].rfind("<text").ok_or_else(broken)?;
        let end = at + out[at..].find("</text>").ok_or_else(broken)? + "</text>".len();
        out.replace_range(start..end, line);
    }
    Ok(out)
}

/// Samples per turn of the curves a figure draws: dense enough that no polyline kink
/// shows, whatever the evaluation's resolution (at 1440 a chord of the paper's trajectory
/// is under 1.5 mm and turns by under 1.5°).
pub const FIGURE_SAMPLES: usize = 1440;

/// The mechanism's motion sampled for drawing: the evaluation's own where it is at least
/// [`FIGURE_SAMPLES`] per turn, else solved again at that density (the reported numbers
/// stay the evaluation's).
fn dense_kinematics<'k>(
    scene: &Scene,
    kin: &'k Kinematics,
) -> Result<std::borrow::Cow<'k, Kinematics>> {
    if kin.len() >= FIGURE_SAMPLES {
        return Ok(std::borrow::Cow::Borrowed(kin));
    }
    let resolution = scene.resolution.with_samples(FIGURE_SAMPLES);
    Ok(std::borrow::Cow::Owned(scene.kinematics(&resolution)?))
}

/// A figure that can draw itself on any plotters backend, at any size.
pub trait Figure {
    /// The size it is drawn at unless asked otherwise (CSS pixels, 96 to the inch).
    fn size(&self) -> (u32, u32) {
        (900, 700)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static;
}

/// A chart of the plane on `area`, both axes in millimetres over `x` and `y`, with room
/// for a legend at `legend`.
fn plane_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    caption_size: u32,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
    legend: LegendPlace,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>>
where
    DB::ErrorType: 'static,
{
    let mut chart = chart_on(area, 10, legend, (35, 50))
        .caption(caption, (FONT, caption_size))
        .build_cartesian_2d(x, y)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
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

/// The arm count in words: "one arm", "two arms", … (1 to `TrainSpec::MAX_ARMS`).
fn arm_count(arms: usize) -> &'static str {
    ["one arm", "two arms", "three arms", "four arms"][arms - 1]
}

/// Tip positions over a carrier span (degrees, end may exceed 360°), one point per degree
/// plus both ends, so section boundaries meet exactly.
fn tip_points(kin: &Kinematics, span_deg: [f64; 2]) -> Vec<(f64, f64)> {
    let steps = (span_deg[1] - span_deg[0]).abs().ceil().max(1.0) as usize;
    (0..=steps)
        .map(|i| {
            let deg = span_deg[0] + (span_deg[1] - span_deg[0]) * i as f64 / steps as f64;
            kin.state_at(deg.to_radians()).tip.into()
        })
        .collect()
}

/// A chart of the plane (mm) on `area`, equal scales in x and y, holding `points` with
/// `pad` mm to spare, the room for its legend at `place`, `y_label` px for the y axis's
/// labels: the frame of the trajectory figures.
fn equal_scale_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    place: LegendPlace,
    y_label: u32,
    points: impl Iterator<Item = Vec2>,
    pad: f64,
    x_desc: &str,
) -> Result<FloatChart<'a, DB>>
where
    DB::ErrorType: 'static,
{
    let (margin, x_label) = (12u32, 40u32);
    let (plot_w, plot_h) = place.plot_size(area.dim_in_pixel(), margin, (x_label, y_label));
    let ((x0, x1), (y0, y1)) = equal_ranges(points, plot_w as f64, plot_h as f64, pad);
    let mut chart = chart_on(area, margin, place, (x_label, y_label))
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_label_formatter(&tick)
        .x_labels((plot_w / 70).max(3) as usize)
        .y_label_formatter(&tick)
        .x_desc(x_desc)
        .y_desc("y (mm)")
        .label_style((FONT, 14))
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// One colour per arm set (up to `TrainSpec::MAX_ARMS`).
const ARM_COLOURS: [RGBColor; 4] = [
    RGBColor(200, 30, 30),
    RGBColor(30, 110, 200),
    RGBColor(40, 150, 60),
    RGBColor(150, 80, 170),
];

/// Colours of the trajectory's sections, in `Section::ALL` order.
const SECTION_COLOURS: [RGBColor; 4] = [
    RGBColor(0, 160, 170),
    RGBColor(230, 140, 0),
    RGBColor(130, 50, 180),
    RGBColor(40, 40, 40),
];

/// Every figure of one evaluation into `dir`; returns the files written.
pub fn evaluation_figures(
    scene: &Scene,
    eval: &Evaluation,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = Vec::new();
    if let (Some(kin), Some(ev)) = (&eval.kinematics, &eval.events) {
        let dense = dense_kinematics(scene, kin)?;
        let kin = dense.as_ref();
        files.extend(save(
            &TrajectoryFigure {
                kin,
                events: ev,
                scene,
            },
            &dir.join("trajectory"),
            options,
        )?);
        files.extend(save(
            &GroundFigure {
                kin,
                events: ev,
                scene,
            },
            &dir.join("ground"),
            options,
        )?);
        files.extend(save(
            &GearsFigure {
                kin,
                theta: ev.picking.carrier_rad,
            },
            &dir.join("gears"),
            options,
        )?);
    }
    if !eval.objectives.is_empty() {
        files.extend(save(
            &ObjectivesFigure {
                objectives: &eval.objectives,
                scene,
            },
            &dir.join("objectives"),
            options,
        )?);
    }
    if let Some(report) = &eval.moving_box {
        files.extend(save(
            &BoxFigure {
                spec: &scene.moving_box,
                report,
            },
            &dir.join("moving_box"),
            options,
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
