//! Line and point charts of named series (convergence, Pareto sets, responses).

use super::*;

/// A generic line chart (search convergence, sweeps, Pareto sets).
pub struct LinesFigure {
    pub title: String,
    pub x_desc: String,
    pub y_desc: String,
    pub series: Vec<(String, Vec<(f64, f64)>)>,
    /// Points alone, no lines (a Pareto set).
    pub points_only: bool,
    /// Lines with a marker at each data point (a sweep's evaluated values).
    pub markers: bool,
    /// The admissible range of y, drawn as a band: (lower, upper), `None` on an open side.
    pub band: Option<(Option<f64>, Option<f64>)>,
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
        // The band's bounds in view, so that the data are seen against them.
        let bounds = self.band.map_or([None, None], |(lo, hi)| [lo, hi]);
        for b in bounds.into_iter().flatten().filter(|b| b.is_finite()) {
            y0 = y0.min(b);
            y1 = y1.max(b);
        }
        // Pad the ranges; a degenerate range (one point) gets ±1 % of its value.
        let pad =
            |lo: f64, hi: f64, f: f64| ((hi - lo) * f).max(0.01 * lo.abs().max(hi.abs())).max(1e-9);
        let (dx, dy) = (pad(x0, x1, 0.05), pad(y0, y1, 0.08));
        let band_label = "admissible range";
        // The title over the whole figure (over the chart alone it was centred beside the
        // legend, and a long one ran off the left edge).
        let area = root.titled(&self.title, (FONT, 20)).map_err(err)?;
        let place = legend_place(
            (self.series.iter().map(|(n, _)| n.as_str()))
                .chain(self.band.is_some().then_some(band_label)),
            12,
            area.dim_in_pixel(),
        );
        let mut chart = chart_on(&area, 12, place, (40, 60))
            .build_cartesian_2d(x0 - dx..x1 + dx, y0 - dy..y1 + dy)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .x_desc(&self.x_desc)
            .y_desc(&self.y_desc)
            .label_style((FONT, 13))
            .draw()
            .map_err(err)?;
        let mut entries: Entries = Vec::new();
        if let Some((lo, hi)) = self.band {
            let green = RGBColor(200, 235, 200);
            let (lo, hi) = (lo.unwrap_or(y0 - dy), hi.unwrap_or(y1 + dy));
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x0 - dx, lo), (x1 + dx, hi)],
                    green.filled(),
                )))
                .map_err(err)?;
            entries.push((band_label.to_string(), Swatch::Band(green.into())));
        }
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
                    .map_err(err)?;
                entries.push((name.clone(), Swatch::Dot(colour)));
            } else {
                if self.markers {
                    chart
                        .draw_series(data.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                        .map_err(err)?;
                }
                fine_line(&mut chart, &data, colour, 2)?;
                entries.push((name.clone(), Swatch::Line(colour, 2)));
            }
        }
        draw_legend(&area, chart.plotting_area(), &entries, 12, place)?;
        Ok(())
    }
}
