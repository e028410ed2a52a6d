//! The trajectory relative to the machine: sections, arm poses, events, tray and ground.

use super::*;

/// Tip positions over a carrier span (degrees, end may exceed 360°), one point per degree
/// plus both ends, so section boundaries meet exactly.
fn section_points(kin: &Kinematics, span_deg: [f64; 2]) -> Vec<(f64, f64)> {
    let steps = (span_deg[1] - span_deg[0]).abs().ceil().max(1.0) as usize;
    (0..=steps)
        .map(|i| {
            let deg = span_deg[0] + (span_deg[1] - span_deg[0]) * i as f64 / steps as f64;
            let tip = kin.state_at(deg.to_radians()).tip;
            tip.into()
        })
        .collect()
}

/// Figure: the trajectory relative to the machine with arm poses, events, tray and ground.
pub struct TrajectoryFigure<'a> {
    pub kin: &'a Kinematics,
    pub events: &'a Events,
    pub scene: &'a Scene,
}

impl Figure for TrajectoryFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let kin = self.kin;
        let ev = self.events;
        let agro = &self.scene.agronomy;
        root.fill(&WHITE).map_err(err)?;
        let tips = kin.tips();
        let ((x0, x1), (y0, y1)) =
            equal_ranges(tips.iter().copied().chain([Vec2::ZERO]), 800.0, 600.0, 40.0);
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Tip trajectory relative to the machine (three arms)",
                (FONT, 22),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("x (mm)")
            .y_desc("y (mm)")
            .label_style((FONT, 14))
            .draw()
            .map_err(err)?;
        // Ground and tray lines.
        let ground = ev.y_min_mm + agro.planting_depth_mm;
        chart
            .draw_series(LineSeries::new(
                [(x0, ground), (x1, ground)],
                RGBColor(120, 80, 40).stroke_width(2),
            ))
            .map_err(err)?
            .label(format!(
                "ground ({} mm above the lowest point)",
                agro.planting_depth_mm
            ))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(120, 80, 40)));
        let n = unit(agro.tray_normal_deg.to_radians());
        let p = ev.picking.tip_mm;
        let s = p - n * agro.tray_depth_mm;
        let t = n.turn_90();
        chart
            .draw_series(LineSeries::new(
                [(s - t * 120.0).into(), (s + t * 120.0).into()],
                RGBColor(90, 90, 90).stroke_width(2),
            ))
            .map_err(err)?
            .label(format!("tray surface (normal {}°)", agro.tray_normal_deg))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(90, 90, 90)));
        // Trajectory coloured by section, and all three arms at five carrier angles 24° apart.
        let anatomy = anatomy(kin, agro, ev);
        for (section, colour) in Section::ALL.into_iter().zip(SECTION_COLOURS) {
            let m = anatomy.section(section);
            let points = section_points(kin, m.carrier_deg);
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(3)))
                .map_err(err)?
                .label(format!(
                    "{} ({:.0} mm, θ {:.0}°..{:.0}°)",
                    section.label(),
                    m.length_mm,
                    m.carrier_deg[0],
                    m.carrier_deg[1]
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3))
                });
        }
        for (k, colour) in ARM_COLOURS.iter().enumerate() {
            for step in 0..5 {
                let theta = step as f64 * TAU / 15.0 - k as f64 * TAU / 3.0;
                let st = kin.state_at(theta);
                chart
                    .draw_series(LineSeries::new(
                        [st.o3.into(), st.tip.into()],
                        colour.mix(0.55).stroke_width(2),
                    ))
                    .map_err(err)?;
            }
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(0.0, 0.0), (0.0, 0.0)],
                    colour.stroke_width(2),
                )))
                .map_err(err)?
                .label(format!(
                    "arm {} at θ = 0°, 24°, …, 96°",
                    ["I", "II", "III"][k]
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        chart
            .draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, BLACK.filled())))
            .map_err(err)?;
        for (label, e) in [("picking", &ev.picking), ("planting", &ev.planting)] {
            let Vec2 { x, y } = e.tip_mm;
            chart
                .draw_series(std::iter::once(Circle::new((x, y), 6, MAGENTA.filled())))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Text::new(
                    format!(
                        "{label}: θ = {:.1}°, attitude {:.1}°",
                        e.carrier_rad.to_degrees(),
                        e.attitude_deg
                    ),
                    (x, y),
                    // Text on the side of the point with more room, so it stays in the plot.
                    TextStyle::from((FONT, 15)).pos(if x > 0.5 * (x0 + x1) {
                        Pos::new(HPos::Right, VPos::Bottom)
                    } else {
                        Pos::new(HPos::Left, VPos::Bottom)
                    }),
                )))
                .map_err(err)?;
        }
        draw_legend(&mut chart, 13, Some(SeriesLabelPosition::UpperRight))?;
        Ok(())
    }
}
