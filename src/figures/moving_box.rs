//! The variable-speed moving box: travel and speed against the input angle.

use super::*;

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
                "box displacement (mm)",
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
                "box speed (mm/s)",
            ),
        ] {
            let ymax = series
                .iter()
                .flat_map(|s| s.iter())
                .fold(0.0f64, |m, &v| m.max(v))
                * 1.08;
            let place = legend_place(
                [
                    "picking window 150°–210°",
                    "elliptical gears",
                    "constant speed",
                    "sinusoidal shaft",
                ],
                12,
                area.dim_in_pixel(),
            );
            let mut chart = chart_on(area, 10, place, (35, 55))
                .caption(title, (FONT, 18))
                .build_cartesian_2d(0.0..360.0, 0.0..ymax)
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_label_formatter(&tick)
                .y_label_formatter(&tick)
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
                .map_err(err)?;
            let mut entries: Entries = vec![(
                format!("picking window {:.0}°–{:.0}°", w[0], w[1]),
                Swatch::Band(RGBColor(255, 230, 160).into()),
            )];
            for (s, (name, colour)) in series.iter().zip([
                ("elliptical gears", RED),
                ("constant speed", BLACK),
                ("sinusoidal shaft", BLUE),
            ]) {
                let pts: Vec<(f64, f64)> =
                    c.input_deg.iter().copied().zip(s.iter().copied()).collect();
                fine_line(&mut chart, &pts, colour.into(), 2)?;
                entries.push((name.to_string(), Swatch::Line(colour.into(), 2)));
            }
            draw_legend(area, chart.plotting_area(), &entries, 12, place)?;
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
