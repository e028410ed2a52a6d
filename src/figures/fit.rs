//! The fit to a target: the target path dashed, the fitted tip path, where they are
//! farthest apart, and each key pose against what the arm does there.

use super::*;
use crate::report::signed_fixed;
use noncirc_core::{FitReport, PreparedTarget, Target};

/// Figure: the target and the fitted trajectory overlaid, with the pose errors drawn.
pub struct FitFigure<'a> {
    /// How the design was found, as the legend says it: "fitted", "inverted".
    pub how: &'a str,
    /// What the target is, as the legend and title name it: "target", "given design's".
    pub against: &'a str,
    pub kin: &'a Kinematics,
    pub target: &'a Target,
    pub prepared: &'a PreparedTarget,
    pub fit: &'a FitReport,
}

/// Legend text size (px).
const LEGEND_FONT: u32 = 13;
/// Length (mm) of the attitude strokes drawn at the poses.
const ATTITUDE_STROKE_MM: f64 = 40.0;

impl Figure for FitFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1240, 760)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let (kin, fit) = (self.kin, self.fit);
        root.fill(&WHITE).map_err(err)?;
        let target_label = format!(
            "{} path ({} points, tolerance {} mm)",
            self.against,
            self.target.x_mm.len(),
            self.target.tolerance_mm
        );
        let path_label = format!(
            "{} tip path: Hausdorff {:.3} mm, RMS {:.3} mm",
            self.how, fit.path_hausdorff_mm, fit.path_rms_mm
        );
        let farthest_label = "where the paths are farthest apart".to_string();
        let pose_labels: Vec<String> = (fit.poses.iter())
            .map(|p| {
                let mut text = format!(
                    "{}: θ {:.1}°, off by {:.3} mm",
                    p.name, p.carrier_deg, p.position_error_mm
                );
                if let Some(a) = p.attitude_error_deg {
                    text += &format!(", attitude {}°", signed_fixed(a, 2));
                }
                if let Some(c) = p.carrier_error_deg {
                    text += &format!(", carrier {}°", signed_fixed(c, 2));
                }
                text
            })
            .collect();
        let area = root
            .titled(
                &format!(
                    "The {} tip path against the {} path",
                    self.how, self.against
                ),
                (FONT, 22),
            )
            .map_err(err)?;
        let (w, h) = area.dim_in_pixel();
        let place = legend_place(
            [&target_label, &path_label, &farthest_label]
                .into_iter()
                .chain(&pose_labels)
                .map(String::as_str),
            LEGEND_FONT,
            (w, h),
        );
        let path: Vec<(f64, f64)> = tip_points(kin, [0.0, 360.0]);
        let target: Vec<(f64, f64)> = (self.prepared.polyline().iter())
            .chain(self.prepared.polyline().first())
            .map(|&p| p.into())
            .collect();
        // Everything inside: the paths, the poses with their attitude strokes, the axis.
        let strokes: Vec<Vec2> = (self.target.poses.iter().zip(&fit.poses))
            .flat_map(|(pose, p)| {
                let asked = Vec2::new(pose.x_mm, pose.y_mm);
                let mut ends = vec![asked, p.tip_mm, stroke_end(p.tip_mm, p.attitude_deg)];
                ends.extend(pose.attitude_deg.map(|a| stroke_end(asked, a)));
                ends
            })
            .collect();
        let drawn = (path.iter().chain(&target))
            .map(|&(x, y)| Vec2::new(x, y))
            .chain(strokes)
            .chain([Vec2::ZERO]);
        let mut chart = equal_scale_chart(&area, place, 60, drawn, 20.0, "x (mm)")?;
        let mut entries: Entries = Vec::new();
        let target_colour = RGBColor(90, 90, 90);
        chart
            .draw_series(DashedLineSeries::new(
                target.clone(),
                8,
                5,
                target_colour.stroke_width(2),
            ))
            .map_err(err)?;
        entries.push((target_label, Swatch::Dashed(target_colour.into(), 2)));
        let path_colour = RGBColor(0, 110, 190);
        fine_line(&mut chart, &path, path_colour.into(), 2)?;
        entries.push((path_label, Swatch::Line(path_colour.into(), 2)));
        let red = RGBColor(210, 40, 40);
        chart
            .draw_series(std::iter::once(Circle::new(
                fit.hausdorff_at_mm.into(),
                6,
                red.stroke_width(2),
            )))
            .map_err(err)?;
        entries.push((farthest_label, Swatch::Ring(red.into())));
        chart
            .draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, BLACK.filled())))
            .map_err(err)?;
        // Each pose: the asked position with its attitude (thin), what the arm does
        // there (thick), and the error between them.
        let stroke = |at: Vec2, attitude: f64| [at.into(), stroke_end(at, attitude).into()];
        for ((pose, p), label) in self.target.poses.iter().zip(&fit.poses).zip(pose_labels) {
            let colour = ARM_COLOURS[3];
            let asked = Vec2::new(pose.x_mm, pose.y_mm);
            if let Some(a) = pose.attitude_deg {
                chart
                    .draw_series(LineSeries::new(
                        stroke(asked, a),
                        colour.mix(0.5).stroke_width(2),
                    ))
                    .map_err(err)?;
            }
            chart
                .draw_series(LineSeries::new(
                    stroke(p.tip_mm, p.attitude_deg),
                    colour.stroke_width(3),
                ))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(
                    [asked.into(), p.tip_mm.into()],
                    red.stroke_width(2),
                ))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Cross::new(
                    asked.into(),
                    6,
                    colour.stroke_width(2),
                )))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Circle::new(
                    p.tip_mm.into(),
                    4,
                    colour.filled(),
                )))
                .map_err(err)?;
            entries.push((label, Swatch::Line(colour.into(), 3)));
        }
        draw_legend(&area, chart.plotting_area(), &entries, LEGEND_FONT, place)?;
        Ok(())
    }
}

/// The end of an attitude stroke from `at`: along the pusher's direction, which dips by
/// `attitude_deg` below the horizontal, pointing away from the carrier axis.
fn stroke_end(at: Vec2, attitude_deg: f64) -> Vec2 {
    let side = if at.x >= 0.0 { 1.0 } else { -1.0 };
    let a = attitude_deg.to_radians();
    at + Vec2::new(side * a.cos(), -a.sin()) * ATTITUDE_STROKE_MM
}
