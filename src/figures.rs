//! Figures (SVG and PNG, plotters) and the animation (GIF). Text uses DejaVu Sans, embedded
//! in the binary, so rendering needs no system font or package.

use noncirc_core::unit;
use noncirc_core::Events;
use noncirc_core::Kinematics;
use noncirc_core::PitchCurve;
use noncirc_core::Travel;
use noncirc_core::{anatomy, Section};
use noncirc_core::{box_curves, BoxReport, BoxSpec};
use noncirc_core::{Evaluation, ObjectiveValue, Scene};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::files::create_dir;
use crate::{Error, Result};
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

/// Axis ranges with equal scale in x and y for a plot area of `w × h` pixels.
fn equal_ranges(
    points: impl Iterator<Item = [f64; 2]>,
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
    for [x, y] in points {
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

/// Tip positions over a carrier span (degrees, end may exceed 360°), one point per degree
/// plus both ends, so section boundaries meet exactly.
fn section_points(kin: &Kinematics, span_deg: [f64; 2]) -> Vec<(f64, f64)> {
    let steps = (span_deg[1] - span_deg[0]).abs().ceil().max(1.0) as usize;
    (0..=steps)
        .map(|i| {
            let deg = span_deg[0] + (span_deg[1] - span_deg[0]) * i as f64 / steps as f64;
            let tip = kin.state_at(deg.to_radians()).tip;
            (tip[0], tip[1])
        })
        .collect()
}

/// Figure: the trajectory relative to the machine with arm poses, events, tray and ground.
pub struct TrajectoryFigure<'a> {
    pub kin: &'a Kinematics,
    pub events: &'a Events,
    pub scene: &'a Scene,
}

impl Figure for TrajectoryFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let kin = self.kin;
        let ev = self.events;
        let agro = &self.scene.agronomy;
        root.fill(&WHITE).map_err(err)?;
        let tips = kin.tips();
        let ((x0, x1), (y0, y1)) =
            equal_ranges(tips.iter().copied().chain([[0.0, 0.0]]), 800.0, 600.0, 40.0);
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Tip trajectory relative to the machine (three arms)",
                (FONT, 22),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("x (mm)")
            .y_desc("y (mm)")
            .label_style((FONT, 14))
            .draw()
            .map_err(err)?;
        // Ground and tray lines.
        let ground = ev.y_min_mm + agro.planting_depth_mm;
        chart
            .draw_series(LineSeries::new(
                [(x0, ground), (x1, ground)],
                RGBColor(120, 80, 40).stroke_width(2),
            ))
            .map_err(err)?
            .label(format!(
                "ground ({} mm above the lowest point)",
                agro.planting_depth_mm
            ))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(120, 80, 40)));
        let n = unit(agro.tray_normal_deg.to_radians());
        let p = ev.picking.tip_mm;
        let s = [
            p[0] - agro.tray_depth_mm * n[0],
            p[1] - agro.tray_depth_mm * n[1],
        ];
        let t = [-n[1], n[0]];
        chart
            .draw_series(LineSeries::new(
                [
                    (s[0] - 120.0 * t[0], s[1] - 120.0 * t[1]),
                    (s[0] + 120.0 * t[0], s[1] + 120.0 * t[1]),
                ],
                RGBColor(90, 90, 90).stroke_width(2),
            ))
            .map_err(err)?
            .label(format!("tray surface (normal {}°)", agro.tray_normal_deg))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(90, 90, 90)));
        // Trajectory coloured by section, and all three arms at five carrier angles 24° apart.
        let anatomy = anatomy(kin, agro, ev);
        for (section, colour) in Section::ALL.into_iter().zip(SECTION_COLOURS) {
            let m = anatomy.section(section);
            let points = section_points(kin, m.carrier_deg);
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(3)))
                .map_err(err)?
                .label(format!(
                    "{} ({:.0} mm, θ {:.0}°..{:.0}°)",
                    section.label(),
                    m.length_mm,
                    m.carrier_deg[0],
                    m.carrier_deg[1]
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3))
                });
        }
        for (k, colour) in ARM_COLOURS.iter().enumerate() {
            for step in 0..5 {
                let theta = step as f64 * TAU / 15.0 - k as f64 * TAU / 3.0;
                let st = kin.state_at(theta);
                chart
                    .draw_series(LineSeries::new(
                        [(st.o3[0], st.o3[1]), (st.tip[0], st.tip[1])],
                        colour.mix(0.55).stroke_width(2),
                    ))
                    .map_err(err)?;
            }
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(0.0, 0.0), (0.0, 0.0)],
                    colour.stroke_width(2),
                )))
                .map_err(err)?
                .label(format!(
                    "arm {} at θ = 0°, 24°, …, 96°",
                    ["I", "II", "III"][k]
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        chart
            .draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, BLACK.filled())))
            .map_err(err)?;
        for (label, e) in [("picking", &ev.picking), ("planting", &ev.planting)] {
            let (x, y) = (e.tip_mm[0], e.tip_mm[1]);
            chart
                .draw_series(std::iter::once(Circle::new((x, y), 6, MAGENTA.filled())))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Text::new(
                    format!(
                        "{label}: θ = {:.1}°, attitude {:.1}°",
                        e.carrier_rad.to_degrees(),
                        e.attitude_deg
                    ),
                    (x, y),
                    // Text on the side of the point with more room, so it stays in the plot.
                    TextStyle::from((FONT, 15)).pos(if x > 0.5 * (x0 + x1) {
                        Pos::new(HPos::Right, VPos::Bottom)
                    } else {
                        Pos::new(HPos::Left, VPos::Bottom)
                    }),
                )))
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FONT, 13))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

/// Ground-frame motion: tip x advanced by the machine's travel, with the planted seedlings.
pub struct GroundFigure<'a> {
    pub kin: &'a Kinematics,
    pub events: &'a Events,
    pub scene: &'a Scene,
}

/// The machine's travel sign (+1: towards +x) as the seedling-push objective uses it.
fn travel_sign(kin: &Kinematics, ev: &Events, travel: Travel) -> f64 {
    match travel {
        Travel::PlusX => 1.0,
        Travel::MinusX => -1.0,
        Travel::Auto => {
            if kin.state_at(ev.planting.carrier_rad).tip_d1[0] > 0.0 {
                -1.0
            } else {
                1.0
            }
        }
    }
}

impl Figure for GroundFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1100, 600)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let (kin, ev, agro) = (self.kin, self.events, &self.scene.agronomy);
        root.fill(&WHITE).map_err(err)?;
        let sign = travel_sign(kin, ev, agro.travel);
        let advance = 3.0 * agro.plant_spacing_mm / TAU;
        let n = kin.len();
        let turns = 2usize;
        let mut curves = Vec::new();
        for k in 0..3 {
            let pts: Vec<[f64; 2]> = (0..=turns * n)
                .map(|j| {
                    let theta = TAU * j as f64 / n as f64;
                    let p = kin.tips()[kin.arm_node(k, j % n)];
                    [p[0] + sign * advance * theta, p[1]]
                })
                .collect();
            curves.push(pts);
        }
        let ground = ev.y_min_mm + agro.planting_depth_mm;
        let all = curves.iter().flatten().copied();
        let ((x0, x1), (y0, y1)) = equal_ranges(all, 1000.0, 500.0, 30.0);
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!(
                    "Tip paths over the ground ({} mm spacing, travel {}x)",
                    agro.plant_spacing_mm,
                    if sign > 0.0 { "+" } else { "−" }
                ),
                (FONT, 22),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("x over the ground (mm)")
            .y_desc("y (mm)")
            .label_style((FONT, 14))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(
                [(x0, ground), (x1, ground)],
                RGBColor(120, 80, 40).stroke_width(2),
            ))
            .map_err(err)?;
        for (k, pts) in curves.iter().enumerate() {
            chart
                .draw_series(LineSeries::new(
                    pts.iter().map(|p| (p[0], p[1])),
                    ARM_COLOURS[k].stroke_width(2),
                ))
                .map_err(err)?
                .label(format!("arm {}", ["I", "II", "III"][k]))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], ARM_COLOURS[k].stroke_width(2))
                });
        }
        // Seedlings at each planting: arm k plants at θp + k·120° (+ whole turns).
        for k in 0..3 * turns {
            let theta = ev.planting.carrier_rad + k as f64 * TAU / 3.0;
            if theta > turns as f64 * TAU {
                continue;
            }
            let x = ev.planting.tip_mm[0] + sign * advance * theta;
            let (bottom, top) = (
                ev.planting.tip_mm[1],
                ev.planting.tip_mm[1] + agro.seedling_height_mm,
            );
            chart
                .draw_series(LineSeries::new(
                    [(x, bottom), (x, top)],
                    GREEN.stroke_width(4),
                ))
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FONT, 13))
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

fn place(outline: &[[f64; 2]], centre: [f64; 2], angle: f64) -> Vec<(f64, f64)> {
    let (s, c) = angle.sin_cos();
    outline
        .iter()
        .chain(outline.first())
        .map(|p| {
            (
                centre[0] + c * p[0] - s * p[1],
                centre[1] + s * p[0] + c * p[1],
            )
        })
        .collect()
}

/// Sun outline in its own frame.
fn sun_outline(curve: &PitchCurve, n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|j| {
            let psi = TAU * j as f64 / n as f64;
            let r = curve.eval(psi).rho;
            [r * psi.cos(), r * psi.sin()]
        })
        .collect()
}

/// Gears on the carrier at carrier angle `theta`, with the ratio and attitude over the cycle.
pub struct GearsFigure<'a> {
    pub kin: &'a Kinematics,
    pub theta: f64,
}

impl Figure for GearsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 600)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let kin = self.kin;
        root.fill(&WHITE).map_err(err)?;
        let (left, right) = root.split_horizontally(600);
        let (top, bottom) = right.split_vertically(300);
        draw_train(
            &left,
            kin,
            self.theta,
            &format!(
                "Pitch curves on the carrier at θ = {:.0}°",
                self.theta.to_degrees()
            ),
        )?;
        let n = kin.len();
        let ratio: Vec<(f64, f64)> = (0..n)
            .map(|j| {
                let r = kin.pair().samples()[j].rho;
                (kin.theta(j).to_degrees(), (kin.centre_distance() - r) / r)
            })
            .collect();
        let rmax = ratio.iter().map(|p| p.1).fold(0.0, f64::max);
        let mut c = ChartBuilder::on(&top)
            .caption(
                "Transmission ratio i12 = (a − ρ)/ρ at the sun mesh",
                (FONT, 16),
            )
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(0.0..360.0, 0.0..rmax * 1.05)
            .map_err(err)?;
        c.configure_mesh()
            .x_desc("carrier angle (°)")
            .label_style((FONT, 12))
            .draw()
            .map_err(err)?;
        c.draw_series(LineSeries::new(ratio, BLUE.stroke_width(2)))
            .map_err(err)?;
        let attitude: Vec<(f64, f64)> = (0..n)
            .map(|j| {
                (
                    kin.theta(j).to_degrees(),
                    noncirc_core::attitude_deg(kin.pusher_angle(kin.planet_angles()[j])),
                )
            })
            .collect();
        let mut c = ChartBuilder::on(&bottom)
            .caption(
                "Arm attitude (dip of the pusher axis below horizontal)",
                (FONT, 16),
            )
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(0.0..360.0, -90.0..90.0)
            .map_err(err)?;
        c.configure_mesh()
            .x_desc("carrier angle (°)")
            .y_desc("°")
            .label_style((FONT, 12))
            .draw()
            .map_err(err)?;
        c.draw_series(LineSeries::new(attitude, RED.stroke_width(2)))
            .map_err(err)?;
        Ok(())
    }
}

/// Draws the sun, the three intermediates and planets, and the arms at carrier angle `theta`.
fn draw_train<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    kin: &Kinematics,
    theta: f64,
    caption: &str,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let curve = kin.curve();
    let sun = sun_outline(curve, kin.len());
    let inter = kin.pair().driven_points();
    let mut shapes: Vec<(Vec<(f64, f64)>, RGBColor)> = vec![(
        place(&sun, [0.0, 0.0], kin.spec().sun_angle()),
        RGBColor(60, 60, 60),
    )];
    let mut arms = Vec::new();
    for (k, &colour) in ARM_COLOURS.iter().enumerate() {
        let st = kin.state_at(theta - k as f64 * TAU / 3.0);
        shapes.push((place(&inter, st.o2, st.theta2), colour));
        shapes.push((place(&sun, st.o3, st.theta3), colour));
        arms.push(([st.o3, st.tip], colour));
    }
    let pts = shapes
        .iter()
        .flat_map(|(s, _)| s.iter().map(|p| [p.0, p.1]))
        .chain(arms.iter().flat_map(|(a, _)| a.iter().copied()));
    let (w, h) = (
        area.dim_in_pixel().0 as f64 - 70.0,
        area.dim_in_pixel().1 as f64 - 80.0,
    );
    let ((x0, x1), (y0, y1)) = equal_ranges(pts, w, h, 10.0);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 18))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(45)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("x (mm)")
        .y_desc("y (mm)")
        .label_style((FONT, 12))
        .draw()
        .map_err(err)?;
    for (shape, colour) in shapes {
        chart
            .draw_series(LineSeries::new(shape, colour.stroke_width(2)))
            .map_err(err)?;
    }
    for ([a, b], colour) in arms {
        chart
            .draw_series(LineSeries::new(
                [(a[0], a[1]), (b[0], b[1])],
                colour.stroke_width(5),
            ))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Circle::new(
                (b[0], b[1]),
                4,
                colour.filled(),
            )))
            .map_err(err)?;
    }
    Ok(())
}

/// Each objective as a bar against its bounds (the paper's progress bars).
pub struct ObjectivesFigure<'a> {
    pub objectives: &'a [ObjectiveValue],
    pub scene: &'a Scene,
}

impl Figure for ObjectivesFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 80 + 60 * self.objectives.len() as u32)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let m = self.objectives.len().max(1) as f64;
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Objectives against their bounds (bound = 0; two-sided ranges span 0..1)",
                (FONT, 18),
            )
            .margin(12)
            .x_label_area_size(35)
            .y_label_area_size(10)
            .build_cartesian_2d(-1.5..2.5, 0.0..m)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .disable_y_axis()
            .x_desc("position relative to the bounds")
            .label_style((FONT, 12))
            .draw()
            .map_err(err)?;
        for (i, o) in self.objectives.iter().enumerate() {
            let y = m - i as f64 - 0.5;
            let scale = noncirc_core::scale(o.kind, &self.scene.bounds);
            let (lo, hi, x) = match (o.lower, o.upper) {
                (Some(l), Some(u)) => (0.0, 1.0, (o.value - l) / (u - l)),
                (Some(l), None) => (0.0, 2.5, (o.value - l) / (scale * 10.0)),
                (None, Some(u)) => (-1.5, 0.0, (o.value - u) / (scale * 10.0)),
                (None, None) => (-1.5, 2.5, 0.0),
            };
            let x = x.clamp(-1.45, 2.45);
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(lo, y - 0.3), (hi, y + 0.3)],
                    RGBColor(210, 235, 210).filled(),
                )))
                .map_err(err)?;
            let colour = if o.violation == 0.0 {
                RGBColor(30, 140, 50)
            } else {
                RGBColor(200, 30, 30)
            };
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x - 0.02, y - 0.35), (x + 0.02, y + 0.35)],
                    colour.filled(),
                )))
                .map_err(err)?;
            let status = if o.violation == 0.0 {
                "met".to_string()
            } else {
                format!("missed by {:.2}", o.violation)
            };
            chart
                .draw_series(std::iter::once(Text::new(
                    format!(
                        "{}: {:.2} {} ({status})",
                        o.kind.label(),
                        o.value,
                        o.kind.unit()
                    ),
                    (-1.45, y + 0.42),
                    (FONT, 14),
                )))
                .map_err(err)?;
        }
        Ok(())
    }
}

/// Box displacement and speed over the input turn, elliptical vs constant speed.
pub struct BoxFigure<'a> {
    pub spec: &'a BoxSpec,
    pub report: &'a BoxReport,
}

impl Figure for BoxFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 700)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let c = box_curves(self.spec, 720);
        let (top, bottom) = root.split_vertically(350);
        let w = self.report.window_deg;
        let (w0, w1) = (
            w[0].rem_euclid(360.0),
            w[0].rem_euclid(360.0) + (w[1] - w[0]),
        );
        for (area, title, series, unit) in [
            (
                &top,
                "Box displacement over one input turn",
                [&c.elliptic_mm, &c.uniform_mm, &c.sinusoidal_mm],
                "mm",
            ),
            (
                &bottom,
                "Box speed",
                [
                    &c.elliptic_speed_mm_s,
                    &vec![
                        c.elliptic_speed_mm_s.iter().sum::<f64>()
                            / c.elliptic_speed_mm_s.len() as f64;
                        c.input_deg.len()
                    ],
                    &speed(&c.sinusoidal_mm, &c.input_deg, self.spec.omega()),
                ],
                "mm/s",
            ),
        ] {
            let ymax = series
                .iter()
                .flat_map(|s| s.iter())
                .fold(0.0f64, |m, &v| m.max(v))
                * 1.08;
            let mut chart = ChartBuilder::on(area)
                .caption(title, (FONT, 18))
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(55)
                .build_cartesian_2d(0.0..360.0, 0.0..ymax)
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc("driving gear angle (°)")
                .y_desc(unit)
                .label_style((FONT, 12))
                .draw()
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(w0.min(360.0), 0.0), (w1.min(360.0), ymax)],
                    RGBColor(255, 230, 160).filled(),
                )))
                .map_err(err)?
                .label(format!("picking window {:.0}°–{:.0}°", w[0], w[1]))
                .legend(|(x, y)| {
                    Rectangle::new(
                        [(x, y - 5), (x + 20, y + 5)],
                        RGBColor(255, 230, 160).filled(),
                    )
                });
            for (s, (name, colour)) in series.iter().zip([
                ("elliptical gears", RED),
                ("constant speed", BLACK),
                ("sinusoidal shaft", BLUE),
            ]) {
                chart
                    .draw_series(LineSeries::new(
                        c.input_deg.iter().copied().zip(s.iter().copied()),
                        colour.stroke_width(2),
                    ))
                    .map_err(err)?
                    .label(name)
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                    });
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font((FONT, 12))
                .draw()
                .map_err(err)?;
        }
        Ok(())
    }
}

fn speed(x: &[f64], deg: &[f64], omega: f64) -> Vec<f64> {
    let n = x.len();
    (0..n)
        .map(|j| {
            let (a, b) = (j.saturating_sub(1), (j + 1).min(n - 1));
            (x[b] - x[a]) / ((deg[b] - deg[a]).to_radians() / omega)
        })
        .collect()
}

/// A generic line chart (search convergence, sweeps, Pareto sets).
pub struct LinesFigure {
    pub title: String,
    pub x_desc: String,
    pub y_desc: String,
    pub series: Vec<(String, Vec<(f64, f64)>)>,
    pub points_only: bool,
}

impl Figure for LinesFigure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let pts = self
            .series
            .iter()
            .flat_map(|(_, s)| s.iter())
            .filter(|p| p.0.is_finite() && p.1.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for p in pts {
            x0 = x0.min(p.0);
            x1 = x1.max(p.0);
            y0 = y0.min(p.1);
            y1 = y1.max(p.1);
        }
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        // Pad the ranges; a degenerate range (one point) gets ±1 % of its value.
        let pad =
            |lo: f64, hi: f64, f: f64| ((hi - lo) * f).max(0.01 * lo.abs().max(hi.abs())).max(1e-9);
        let (dx, dy) = (pad(x0, x1, 0.05), pad(y0, y1, 0.08));
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0 - dx..x1 + dx, y0 - dy..y1 + dy)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_desc)
            .y_desc(&self.y_desc)
            .label_style((FONT, 13))
            .draw()
            .map_err(err)?;
        for (i, (name, s)) in self.series.iter().enumerate() {
            let colour = Palette99::pick(i).to_rgba();
            let data: Vec<(f64, f64)> = s
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            if self.points_only {
                chart
                    .draw_series(data.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                    .map_err(err)?
                    .label(name.as_str())
                    .legend(move |(x, y)| Circle::new((x + 10, y), 4, colour.filled()));
            } else {
                chart
                    .draw_series(LineSeries::new(data, colour.stroke_width(2)))
                    .map_err(err)?
                    .label(name.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                    });
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FONT, 12))
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

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

/// Most frames of an animation (a frame per 0.1° of carrier turn).
pub const MAX_FRAMES: usize = 3600;

/// `noncirc animate`: the mechanism turning, gears and arms drawn, as a GIF.
pub fn animate(kin: &Kinematics, path: &Path, frames: usize) -> Result<()> {
    if !(2..=MAX_FRAMES).contains(&frames) {
        return Err(Error::Input(format!(
            "--frames {frames}: expected 2 to {MAX_FRAMES}"
        )));
    }
    register_font()?;
    // Open the file first: plotters reports a failure as a debug dump.
    std::fs::File::create(path).map_err(|e| Error::file("write", path, e))?;
    let root = BitMapBackend::gif(path, (640, 640), 60)
        .map_err(err)?
        .into_drawing_area();
    for f in 0..frames {
        let theta = TAU * f as f64 / frames as f64;
        root.fill(&WHITE).map_err(err)?;
        draw_train(
            &root,
            kin,
            theta,
            &format!("θ = {:5.1}°", theta.to_degrees()),
        )?;
        root.present().map_err(err)?;
    }
    Ok(())
}
