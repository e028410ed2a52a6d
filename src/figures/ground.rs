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
        let labels = ["arm I", "arm II", "arm III", "ground", "planted seedling"];
        let (margin, x_label, y_label) = (12u32, 40u32, 55u32);
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
        let place = legend_place(labels, 13, (w, h));
        let (plot_w, plot_h) = place.plot_size((w, h), margin, (x_label, y_label));
        let all = curves.iter().flatten().copied().chain([
            Vec2::new(curves[0][0].x, ground),
            Vec2::new(
                curves[0][0].x,
                ev.planting.tip_mm.y + agro.seedling_height_mm,
            ),
        ]);
        let ((x0, x1), (y0, y1)) = equal_ranges(all, plot_w as f64, plot_h as f64, 20.0);
        let mut chart = chart_on(&area, margin, place, (x_label, y_label))
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .x_labels((plot_w / 70).max(3) as usize)
            .y_label_formatter(&tick)
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
        let mut entries: Entries = (0..kin.arms())
            .map(|k| {
                (
                    format!("arm {}", ARM_NAMES[k]),
                    Swatch::Line(ARM_COLOURS[k].into(), 2),
                )
            })
            .collect();
        entries.push((
            labels[3].into(),
            Swatch::Line(RGBColor(120, 80, 40).into(), 2),
        ));
        entries.push((labels[4].into(), Swatch::Tick(GREEN.into(), 4)));
        draw_legend(&area, chart.plotting_area(), &entries, 13, place)?;
        Ok(())
    }
}
