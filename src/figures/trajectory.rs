//! The trajectory relative to the machine: sections, arm poses, events, tray and ground.

use super::*;

/// Figure: the trajectory relative to the machine with arm poses, events, tray and ground.
pub struct TrajectoryFigure<'a> {
    pub kin: &'a Kinematics,
    pub events: &'a Events,
    pub scene: &'a Scene,
}

/// Legend text size (px).
const LEGEND_FONT: u32 = 13;

impl Figure for TrajectoryFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1240, 720)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let kin = self.kin;
        let ev = self.events;
        let agro = &self.scene.agronomy;
        root.fill(&WHITE).map_err(err)?;
        let anatomy = anatomy(kin, agro, ev);
        // Every legend entry first: the room they need sets the plot's size.
        let ground_label = format!(
            "ground ({} mm above the lowest point)",
            agro.planting_depth_mm
        );
        let tray_label = format!("tray surface (normal {}°)", agro.tray_normal_deg);
        let section_labels: Vec<String> = (Section::ALL.iter())
            .map(|&section| {
                let m = anatomy.section(section);
                format!(
                    "{} ({:.0} mm, θ {:.0}°..{:.0}°)",
                    section.label(),
                    m.length_mm,
                    m.carrier_deg[0],
                    m.carrier_deg[1]
                )
            })
            .collect();
        let arm_labels: Vec<String> = (0..kin.arms())
            .map(|k| format!("arm {} at θ = 0°, 24°, …, 96°", ARM_NAMES[k]))
            .collect();
        let event_labels: Vec<String> = [("picking", &ev.picking), ("planting", &ev.planting)]
            .iter()
            .map(|(label, e)| {
                format!(
                    "{label}: θ = {:.1}°, attitude {:.1}°",
                    e.carrier_rad.to_degrees(),
                    e.attitude_deg
                )
            })
            .collect();
        // The arms at the poses drawn: every arm at five carrier angles 24° apart.
        let poses: Vec<(usize, Vec2, Vec2)> = (0..kin.arms())
            .flat_map(|k| {
                (0..5).map(move |step| {
                    let theta = step as f64 * TAU / 15.0 - kin.arm_lag(k);
                    let st = kin.state_at(theta);
                    (k, st.o3, st.tip)
                })
            })
            .collect();
        let area = root
            .titled(
                &format!(
                    "Tip trajectory relative to the machine ({})",
                    arm_count(kin.arms())
                ),
                (FONT, 22),
            )
            .map_err(err)?;
        let (w, h) = area.dim_in_pixel();
        let place = legend_place(
            [&ground_label, &tray_label]
                .into_iter()
                .chain(&section_labels)
                .chain(&arm_labels)
                .chain(&event_labels)
                .map(String::as_str),
            LEGEND_FONT,
            (w, h),
        );
        // Equal scale in x and y, everything drawn inside: the path, the arms, the carrier.
        let drawn = (kin.tips().iter().copied())
            .chain(poses.iter().flat_map(|&(_, o3, tip)| [o3, tip]))
            .chain([Vec2::ZERO]);
        let mut chart = equal_scale_chart(&area, place, 60, drawn, 15.0, "x (mm)")?;
        let (Range { start: x0, end: x1 }, Range { start: y0, end: y1 }) =
            (chart.x_range(), chart.y_range());
        let clip = |points: &[(f64, f64)]| clipped_runs(points, (x0, x1), (y0, y1));
        let mut entries: Entries = Vec::new();
        // Ground and tray lines.
        let ground = ev.y_min_mm + agro.planting_depth_mm;
        let brown = RGBColor(120, 80, 40);
        chart
            .draw_series(LineSeries::new(
                [(x0, ground), (x1, ground)],
                brown.stroke_width(2),
            ))
            .map_err(err)?;
        entries.push((ground_label, Swatch::Line(brown.into(), 2)));
        let n = agro.tray_normal();
        let s = ev.tray_surface_point(n);
        let t = n.turn_90();
        let grey = RGBColor(90, 90, 90);
        for run in clip(&[(s - t * 120.0).into(), (s + t * 120.0).into()]) {
            chart
                .draw_series(LineSeries::new(run, grey.stroke_width(2)))
                .map_err(err)?;
        }
        entries.push((tray_label, Swatch::Line(grey.into(), 2)));
        // The arms under the path, so that it stays readable.
        for &(k, o3, tip) in &poses {
            chart
                .draw_series(LineSeries::new(
                    [o3.into(), tip.into()],
                    ARM_COLOURS[k].mix(0.45).stroke_width(2),
                ))
                .map_err(err)?;
        }
        for (k, label) in arm_labels.into_iter().enumerate() {
            entries.push((label, Swatch::Line(ARM_COLOURS[k].mix(0.45), 2)));
        }
        // The path, coloured by section.
        for ((section, colour), label) in Section::ALL
            .into_iter()
            .zip(SECTION_COLOURS)
            .zip(section_labels)
        {
            let points = tip_points(kin, anatomy.section(section).carrier_deg);
            fine_line(&mut chart, &points, colour.into(), 3)?;
            entries.push((label, Swatch::Line(colour.into(), 3)));
        }
        chart
            .draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, BLACK.filled())))
            .map_err(err)?;
        // The events as markers, their numbers in the legend: no text over the path.
        let [picking, planting] = [event_labels[0].clone(), event_labels[1].clone()];
        let Vec2 { x, y } = ev.picking.tip_mm;
        chart
            .draw_series(std::iter::once(Circle::new((x, y), 7, MAGENTA.filled())))
            .map_err(err)?;
        entries.push((picking, Swatch::Dot(MAGENTA.into())));
        let Vec2 { x, y } = ev.planting.tip_mm;
        chart
            .draw_series(std::iter::once(TriangleMarker::new(
                (x, y),
                9,
                MAGENTA.filled(),
            )))
            .map_err(err)?;
        entries.push((planting, Swatch::Triangle(MAGENTA.into())));
        draw_legend(&area, chart.plotting_area(), &entries, LEGEND_FONT, place)?;
        Ok(())
    }
}
