//! The inversion's conditions on the target: the path, the two circles the chain's
//! straight positions touch (`R + S` and `|R − S|` about the carrier axis), and each
//! failing condition's arcs with their worst points.

use super::*;
use noncirc_core::{InverseOutcome, PreparedTarget};

/// Figure: the target with the arcs where the inversion's conditions fail.
pub struct InverseFigure<'a> {
    pub outcome: &'a InverseOutcome,
    pub prepared: &'a PreparedTarget,
}

/// Legend text size (px).
const LEGEND_FONT: u32 = 13;

impl InverseFigure<'_> {
    /// The target's points from arc length `s0` to `s1` (mm, along the path as the tip runs
    /// it: backwards from the first point when the outcome read it backwards).
    fn arc(&self, s0: f64, s1: f64) -> Vec<(f64, f64)> {
        let samples = self.prepared.samples();
        let n = samples.len();
        let length = self.prepared.length_mm();
        let index = |s: f64| {
            let k = (s / length * n as f64).round() as usize % n;
            if self.outcome.reversed {
                (n - k) % n
            } else {
                k
            }
        };
        let count = ((s1 - s0).rem_euclid(length) / length * n as f64).round() as usize + 1;
        (0..count)
            .map(|i| samples[index(s0 + length * i as f64 / n as f64)].into())
            .collect()
    }
}

impl Figure for InverseFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1240, 760)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let o = self.outcome;
        root.fill(&WHITE).map_err(err)?;
        let (far, near) = (
            o.planet_radius_mm + o.arm_length_mm,
            (o.planet_radius_mm - o.arm_length_mm).abs(),
        );
        let target_label = "target path".to_string();
        let circles_label = format!(
            "R + S = {far:.1} mm and |R − S| = {near:.1} mm (S = {:.1} mm, R = {:.1} mm)",
            o.arm_length_mm, o.planet_radius_mm
        );
        let failing: Vec<_> = o.failures().filter(|c| !c.places.is_empty()).collect();
        let labels: Vec<String> = (failing.iter())
            .map(|c| format!("fails: {} (worst ×)", c.name))
            .collect();
        let area = root
            .titled(
                if failing.is_empty() {
                    "The target and the chain's straight positions (no condition fails on it)"
                } else {
                    "Where the inversion's conditions fail on the target"
                },
                (FONT, 22),
            )
            .map_err(err)?;
        let (w, h) = area.dim_in_pixel();
        let place = legend_place(
            [&target_label, &circles_label]
                .into_iter()
                .chain(&labels)
                .map(String::as_str),
            LEGEND_FONT,
            (w, h),
        );
        let circle = |r: f64| -> Vec<(f64, f64)> {
            (0..=360)
                .map(|k| {
                    (Vec2::new(1.0, 0.0).rotated(noncirc_core::unit(f64::from(k).to_radians())) * r)
                        .into()
                })
                .collect()
        };
        let target: Vec<(f64, f64)> = (self.prepared.polyline().iter())
            .chain(self.prepared.polyline().first())
            .map(|&p| p.into())
            .collect();
        let outer = circle(far);
        let drawn = (target.iter().chain(&outer))
            .map(|&(x, y)| Vec2::new(x, y))
            .chain([Vec2::ZERO]);
        let mut chart = equal_scale_chart(&area, place, 60, drawn, 20.0, "x (mm)")?;
        let mut entries: Entries = Vec::new();
        let grey = RGBColor(90, 90, 90);
        chart
            .draw_series(LineSeries::new(target, grey.stroke_width(2)))
            .map_err(err)?;
        entries.push((target_label, Swatch::Line(grey.into(), 2)));
        let light = RGBColor(150, 150, 150);
        for r in [far, near] {
            chart
                .draw_series(DashedLineSeries::new(
                    circle(r),
                    6,
                    5,
                    light.stroke_width(1),
                ))
                .map_err(err)?;
        }
        entries.push((circles_label, Swatch::Dashed(light.into(), 1)));
        chart
            .draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, BLACK.filled())))
            .map_err(err)?;
        for (k, (c, label)) in failing.iter().zip(labels).enumerate() {
            let colour = ARM_COLOURS[k % ARM_COLOURS.len()];
            // The first drawn widest: arcs of several conditions often coincide.
            let width = 9u32.saturating_sub(3 * k as u32).max(3);
            for p in &c.places {
                chart
                    .draw_series(LineSeries::new(
                        self.arc(p.path_mm[0], p.path_mm[1]),
                        colour.stroke_width(width),
                    ))
                    .map_err(err)?;
                chart
                    .draw_series(std::iter::once(Cross::new(
                        p.point_mm.into(),
                        8,
                        colour.stroke_width(2),
                    )))
                    .map_err(err)?;
            }
            entries.push((label, Swatch::Line(colour.into(), width)));
        }
        draw_legend(&area, chart.plotting_area(), &entries, LEGEND_FONT, place)?;
        Ok(())
    }
}
