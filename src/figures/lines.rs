//! Line and point charts of named series (convergence, Pareto sets, responses).

use super::*;

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
        draw_legend(&mut chart, 12, None)?;
        Ok(())
    }
}
