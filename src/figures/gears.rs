//! The train's pitch curves on the carrier at one carrier angle, and the mechanism turning (GIF).

use super::*;
use crate::teeth::TeethRun;

/// `outline` turned by `angle` (rad) and moved to `centre`, closed, as plot points.
pub(super) fn place(outline: &[Vec2], centre: Vec2, angle: f64) -> Vec<(f64, f64)> {
    let (s, c) = angle.sin_cos();
    (outline.iter().chain(outline.first()))
        .map(|p| (centre.x + c * p.x - s * p.y, centre.y + s * p.x + c * p.y))
        .collect()
}

/// Gears on the carrier at carrier angle `theta`, with the ratio and attitude over the cycle.
pub struct GearsFigure<'a> {
    pub kin: &'a Kinematics,
    pub theta: f64,
}

impl Figure for GearsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1380, 620)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let kin = self.kin;
        root.fill(&WHITE).map_err(err)?;
        let (w, h) = root.dim_in_pixel();
        let (left, right) = root.split_horizontally(w * 58 / 100);
        let (top, bottom) = right.split_vertically(h / 2);
        draw_train(
            &left,
            kin,
            None,
            self.theta,
            &format!(
                "Pitch curves on the carrier at θ = {:.0}°",
                self.theta.to_degrees()
            ),
            true,
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
            .caption("Ratio i12 = (a − ρ)/ρ at the sun mesh", (FONT, 16))
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(0.0..360.0, 0.0..rmax * 1.05)
            .map_err(err)?;
        c.configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .x_desc("carrier angle θ (°)")
            .y_desc("ratio i12")
            .label_style((FONT, 12))
            .draw()
            .map_err(err)?;
        fine_line(&mut c, &ratio, BLUE.into(), 2)?;
        let attitude: Vec<(f64, f64)> = (0..n)
            .map(|j| {
                (
                    kin.theta(j).to_degrees(),
                    noncirc_core::attitude_deg(kin.pusher_angle(kin.planet_angles()[j])),
                )
            })
            .collect();
        let mut c = ChartBuilder::on(&bottom)
            .caption("Arm attitude (pusher axis below horizontal)", (FONT, 16))
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(0.0..360.0, -90.0..90.0)
            .map_err(err)?;
        c.configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .x_desc("carrier angle θ (°)")
            .y_desc("attitude (°)")
            .label_style((FONT, 12))
            .draw()
            .map_err(err)?;
        fine_line(&mut c, &attitude, RED.into(), 2)?;
        Ok(())
    }
}

/// Which gear of the train an outline is: drawn solid (sun, planets) or dashed
/// (intermediates).
#[derive(Clone, Copy, PartialEq)]
enum Gear {
    Sun,
    Intermediate,
    Planet,
}

/// A gear's pitch curve or toothed outline as drawn: its points, colour and kind.
type Outline = (Vec<(f64, f64)>, RGBColor, Gear);

/// The sun's colour (the arm sets have theirs).
const SUN_COLOUR: RGBColor = RGBColor(60, 60, 60);

/// Draws the sun, the three intermediates and planets, and the arms at carrier angle
/// `theta`; with `legend`, a legend that tells them apart, right of the plot.
fn draw_train<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    kin: &Kinematics,
    teeth: Option<&TeethRun>,
    theta: f64,
    caption: &str,
    legend: bool,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let mut shapes: Vec<Outline> = Vec::new();
    let mut arms = Vec::new();
    for (k, &colour) in ARM_COLOURS.iter().enumerate().take(kin.arms()) {
        let st = kin.state_at(theta - kin.arm_lag(k));
        arms.push(([st.o3, st.tip], colour));
    }
    match teeth {
        // Toothed gears where they stand (arm k at θ − k·360°/arms, as the arms above).
        Some(run) => {
            for (k, colour) in ARM_COLOURS.into_iter().enumerate().take(kin.arms()) {
                let at = theta - kin.arm_lag(k);
                let layout = crate::teeth::train_layout(kin, &run.pair, run.second.as_ref(), at);
                if k == 0 {
                    shapes.push((
                        place(
                            run.outline(&layout[0]),
                            Vec2::ZERO,
                            layout[0].angle_deg.to_radians(),
                        ),
                        SUN_COLOUR,
                        Gear::Sun,
                    ));
                }
                // Arm I's gears (layout[0] is the sun): intermediate, [layer B,] planet.
                let own = &layout[1..1 + (layout.len() - 1) / kin.arms()];
                for (i, g) in own.iter().enumerate() {
                    let kind = match i + 1 == own.len() {
                        true => Gear::Planet,
                        false => Gear::Intermediate,
                    };
                    shapes.push((
                        place(run.outline(g), g.centre_mm, g.angle_deg.to_radians()),
                        colour,
                        kind,
                    ));
                }
            }
        }
        None => {
            let sun = kin.pair().driver_points();
            // The intermediate's pitch curves: its conjugate of the sun and, with two
            // pairs, its layer B (in the same frame), which drives the planet.
            let layers: Vec<Vec<Vec2>> = std::iter::once(kin.pair().driven_points())
                .chain(kin.second_pair().map(|p| p.driver_points()))
                .collect();
            let planet = kin.planet_points();
            shapes.push((
                place(&sun, Vec2::ZERO, kin.spec().sun_angle()),
                SUN_COLOUR,
                Gear::Sun,
            ));
            for (k, &colour) in ARM_COLOURS.iter().enumerate().take(kin.arms()) {
                let st = kin.state_at(theta - kin.arm_lag(k));
                for layer in &layers {
                    shapes.push((place(layer, st.o2, st.theta2), colour, Gear::Intermediate));
                }
                shapes.push((place(&planet, st.o3, st.theta3), colour, Gear::Planet));
            }
        }
    }
    let arm_labels: Vec<String> = (0..kin.arms())
        .map(|k| format!("arm set {}", ARM_NAMES[k]))
        .collect();
    let labels: Vec<&str> = ["sun (fixed)", "intermediates: dashed", "planets: solid"]
        .into_iter()
        .chain(arm_labels.iter().map(String::as_str))
        .collect();
    let place = if legend {
        legend_place(labels.iter().copied(), 12, area.dim_in_pixel())
    } else {
        LegendPlace { right: 0, below: 0 }
    };
    let pts = shapes
        .iter()
        .flat_map(|(s, _, _)| s.iter().map(|&(x, y)| Vec2::new(x, y)))
        .chain(arms.iter().flat_map(|(a, _)| a.iter().copied()));
    let (w, h) = (
        area.dim_in_pixel().0 as f64 - 70.0 - f64::from(place.right),
        area.dim_in_pixel().1 as f64 - 80.0 - f64::from(place.below),
    );
    let ((x0, x1), (y0, y1)) = equal_ranges(pts, w, h, 10.0);
    let mut chart = plane_chart(area, caption, 18, x0..x1, y0..y1, place)?;
    for (shape, colour, gear) in shapes {
        if gear == Gear::Intermediate {
            chart
                .draw_series(DashedLineSeries::new(shape, 7, 4, colour.stroke_width(2)))
                .map_err(err)?;
        } else {
            fine_line(&mut chart, &shape, colour.into(), 2)?;
        }
    }

    for ([a, b], colour) in arms {
        chart
            .draw_series(LineSeries::new(
                [a.into(), b.into()],
                colour.stroke_width(5),
            ))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Circle::new(b.into(), 4, colour.filled())))
            .map_err(err)?;
    }
    if legend {
        let grey: RGBAColor = SUN_COLOUR.into();
        let mut entries: Entries = vec![
            (labels[0].into(), Swatch::Line(grey, 2)),
            (labels[1].into(), Swatch::Dashed(grey, 2)),
            (labels[2].into(), Swatch::Line(grey, 2)),
        ];
        for (k, colour) in ARM_COLOURS.into_iter().enumerate().take(kin.arms()) {
            entries.push((labels[3 + k].into(), Swatch::Line(colour.into(), 5)));
        }
        draw_legend(area, chart.plotting_area(), &entries, 12, place)?;
    }
    Ok(())
}

/// Most frames of an animation (a frame per 0.1° of carrier turn).
pub const MAX_FRAMES: usize = 3600;

/// `noncirc animate`: the mechanism turning, gears (toothed if `teeth` is given) and arms
/// drawn, as a GIF.
pub fn animate(
    kin: &Kinematics,
    teeth: Option<&TeethRun>,
    path: &Path,
    frames: usize,
) -> Result<()> {
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
            teeth,
            theta,
            &format!("θ = {:5.1}°", theta.to_degrees()),
            false,
        )?;
        root.present().map_err(err)?;
    }
    Ok(())
}
