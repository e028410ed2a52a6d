//! The trajectory relative to the ground as the machine advances.

use super::*;

/// Ground-frame motion: tip x advanced by the machine's travel, with the planted seedlings.
pub struct GroundFigure<'a> {
    pub kin: &'a Kinematics,
    pub events: &'a Events,
    pub scene: &'a Scene,
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
        // As the seedling-push objective moves the machine.
        let sign = travel_sign(kin, agro, ev);
        let advance = advance_per_rad(agro);
        let n = kin.len();
        let turns = 2usize;
        let mut curves = Vec::new();
        for k in 0..3 {
            let pts: Vec<Vec2> = (0..=turns * n)
                .map(|j| {
                    let theta = TAU * j as f64 / n as f64;
                    let p = kin.tips()[kin.arm_node(k, j % n)];
                    p + Vec2::new(sign * advance * theta, 0.0)
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
                    pts.iter().map(|&p| p.into()),
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
            let x = ev.planting.tip_mm.x + sign * advance * theta;
            let (bottom, top) = (
                ev.planting.tip_mm.y,
                ev.planting.tip_mm.y + agro.seedling_height_mm,
            );
            chart
                .draw_series(LineSeries::new(
                    [(x, bottom), (x, top)],
                    GREEN.stroke_width(4),
                ))
                .map_err(err)?;
        }
        draw_legend(&mut chart, 13, None)?;
        Ok(())
    }
}
