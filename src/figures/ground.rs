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
        let sign = travel_sign(agro, ev);
        let advance = advance_per_rad(kin.arms(), agro);
        let n = kin.len();
        let turns = 2usize;
        let mut curves = Vec::new();
        for k in 0..kin.arms() {
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
        let labels: Vec<String> = (0..kin.arms())
            .map(|k| format!("arm {}", ARM_NAMES[k]))
            .chain(["ground".into(), "planted seedling".into()])
            .collect();
        let area = root
            .titled(
                &format!(
                    "Tip paths over the ground ({} mm spacing, travel {}x)",
                    agro.plant_spacing_mm,
                    if sign > 0.0 { "+" } else { "−" }
                ),
                (FONT, 22),
            )
            .map_err(err)?;
        let (w, h) = area.dim_in_pixel();
        let place = legend_place(labels.iter().map(String::as_str), 13, (w, h));
        let all = curves.iter().flatten().copied().chain([
            Vec2::new(curves[0][0].x, ground),
            Vec2::new(
                curves[0][0].x,
                ev.planting.tip_mm.y + agro.seedling_height_mm,
            ),
        ]);
        let mut chart = equal_scale_chart(&area, place, 55, all, 20.0, "x over the ground (mm)")?;
        let Range { start: x0, end: x1 } = chart.x_range();
        chart
            .draw_series(LineSeries::new(
                [(x0, ground), (x1, ground)],
                RGBColor(120, 80, 40).stroke_width(2),
            ))
            .map_err(err)?;
        for (k, pts) in curves.iter().enumerate() {
            let pts: Vec<(f64, f64)> = pts.iter().map(|&p| p.into()).collect();
            fine_line(&mut chart, &pts, ARM_COLOURS[k].into(), 2)?;
        }
        // Seedlings at each planting: arm k plants at θp + k·360°/arms (+ whole turns).
        for k in 0..kin.arms() * turns {
            let theta = ev.planting.carrier_rad + k as f64 * TAU / kin.arms() as f64;
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
        let arms = kin.arms();
        let mut entries: Entries = (0..arms)
            .map(|k| (labels[k].clone(), Swatch::Line(ARM_COLOURS[k].into(), 2)))
            .collect();
        entries.push((
            labels[arms].clone(),
            Swatch::Line(RGBColor(120, 80, 40).into(), 2),
        ));
        entries.push((labels[arms + 1].clone(), Swatch::Tick(GREEN.into(), 4)));
        draw_legend(&area, chart.plotting_area(), &entries, 13, place)?;
        Ok(())
    }
}
