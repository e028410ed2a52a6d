//! Every objective's value against its admissible range.

use super::*;

/// Each objective as a bar against its bounds (the paper's progress bars).
pub struct ObjectivesFigure<'a> {
    pub objectives: &'a [ObjectiveValue],
    pub scene: &'a Scene,
}

impl Figure for ObjectivesFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 90 + 78 * self.objectives.len() as u32)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let m = self.objectives.len().max(1) as f64;
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Objectives against their bounds: green band admissible, marker the design",
                (FONT, 18),
            )
            .margin(12)
            .x_label_area_size(35)
            .y_label_area_size(10)
            .build_cartesian_2d(-1.5..2.5, 0.0..m)
            .map_err(err)?;
        // Each row has its own scale (the band's edges are labelled with the bounds in the
        // objective's unit), so a shared numbered axis would mean nothing.
        chart
            .configure_mesh()
            .disable_y_mesh()
            .disable_y_axis()
            .disable_x_mesh()
            .x_labels(0)
            .x_desc("each row on its own scale: a one-sided band spans ten times the objective's margin scale")
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
            // A value beyond the row's scale is pinned to its end, with an arrow saying so.
            let off_scale = if x > 2.45 {
                Some("off scale →")
            } else if x < -1.45 {
                Some("← off scale")
            } else {
                None
            };
            let x = x.clamp(-1.45, 2.45);
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(lo, y - 0.22), (hi, y + 0.22)],
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
                    [(x - 0.02, y - 0.27), (x + 0.02, y + 0.27)],
                    colour.filled(),
                )))
                .map_err(err)?;
            if let Some(cue) = off_scale {
                let (at, pos) = if x > 0.0 {
                    (x - 0.04, HPos::Right)
                } else {
                    (x + 0.04, HPos::Left)
                };
                chart
                    .draw_series(std::iter::once(Text::new(
                        cue,
                        (at, y),
                        TextStyle::from((FONT, 12))
                            .color(&colour)
                            .pos(Pos::new(pos, VPos::Center)),
                    )))
                    .map_err(err)?;
            }
            let unit = o.kind.unit();
            let status = if o.violation == 0.0 {
                "met".to_string()
            } else {
                format!("missed by {:.2} {unit}", o.violation)
            };
            // The bounds at the band's edges, under it.
            let edges: Vec<(f64, String)> = match (o.lower, o.upper) {
                (Some(l), Some(u)) => {
                    vec![(0.0, format!("{l} {unit}")), (1.0, format!("{u} {unit}"))]
                }
                (Some(l), None) => vec![(0.0, format!("≥ {l} {unit}"))],
                (None, Some(u)) => vec![(0.0, format!("≤ {u} {unit}"))],
                (None, None) => Vec::new(),
            };
            for (at, text) in edges {
                chart
                    .draw_series(std::iter::once(Text::new(
                        text,
                        (at, y - 0.32),
                        TextStyle::from((FONT, 12)).pos(Pos::new(HPos::Center, VPos::Top)),
                    )))
                    .map_err(err)?;
            }
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{}: {:.2} {unit} ({status})", o.kind.label(), o.value,),
                    (-1.45, y + 0.45),
                    (FONT, 14),
                )))
                .map_err(err)?;
        }
        Ok(())
    }
}
