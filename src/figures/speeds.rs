//! Two arms against three: each arm count's design, its tip path relative to the machine,
//! its pass through the tray and its speeds relative to the seedling.

use super::*;

/// One design of the comparison: its scene and evaluation (motion and events).
pub struct ComparedDesign<'a> {
    pub scene: &'a Scene,
    pub eval: &'a Evaluation,
}

/// Figure: the tip paths of the compared designs over one carrier turn, each drawn thick
/// while the tip is inside its tray, with the picking point and the tray surface; the
/// legend gives the arm count, the carrier speed and both speeds relative to the seedling.
pub struct SpeedComparisonFigure<'a> {
    pub designs: Vec<ComparedDesign<'a>>,
    /// The picking rate they all run at (picks per minute).
    pub picks_per_minute: f64,
}

/// The picking window (degrees of carrier).
fn window_deg(ev: &Events) -> [f64; 2] {
    ev.picking_window_rad.map(f64::to_degrees)
}

/// Legend text size (px).
const LEGEND_FONT: u32 = 13;

impl Figure for SpeedComparisonFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1240, 720)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        // Each design's motion (dense for drawing; the speeds are its evaluation's) and labels.
        let mut drawn = Vec::new();
        for (i, d) in self.designs.iter().enumerate() {
            let (Some(kin), Some(ev)) = (&d.eval.kinematics, &d.eval.events) else {
                continue;
            };
            let a = anatomy(kin, &d.scene.agronomy, ev);
            let label = format!(
                "{}, {:.0} r/min: {:.3} m/s in the tray ({:.0}° of carrier), {:.3} m/s at picking",
                arm_count(kin.arms()),
                d.scene.train.carrier_rpm(),
                a.in_tray_speed_m_s,
                (ev.picking_window_rad[1] - ev.picking_window_rad[0]).to_degrees(),
                ev.picking_tip_speed_m_s
            );
            drawn.push((
                i,
                dense_kinematics(d.scene, kin)?,
                ev,
                &d.scene.agronomy,
                label,
            ));
        }
        let tray_label = "tray surface".to_string();
        let picking_label = "picking point (thick: the tip inside the tray)".to_string();
        let area = root
            .titled(
                &format!(
                    "Tip paths relative to the machine at {} picks per minute",
                    self.picks_per_minute
                ),
                (FONT, 22),
            )
            .map_err(err)?;
        let (w, _) = area.dim_in_pixel();
        let (whole, zoom) = area.split_horizontally(w * 3 / 5);
        let place = legend_place(
            (drawn.iter().map(|d| d.4.as_str())).chain([tray_label.as_str(), &picking_label]),
            LEGEND_FONT,
            whole.dim_in_pixel(),
        );
        // Left: the whole turn about the carrier axis; right: the passes through the trays.
        let everything: Vec<Vec2> = (drawn.iter())
            .flat_map(|d| d.1.tips().iter().copied())
            .chain([Vec2::ZERO])
            .collect();
        let passes: Vec<Vec2> = (drawn.iter())
            .flat_map(|(_, kin, ev, _, _)| {
                tip_points(kin, window_deg(ev))
                    .into_iter()
                    .map(|(x, y)| Vec2::new(x, y))
            })
            .collect();
        let grey = RGBColor(90, 90, 90);
        for (panel, points, pad, surface_half, caption, legend) in [
            (&whole, &everything, 15.0, 60.0, "one carrier turn", true),
            (
                &zoom,
                &passes,
                12.0,
                40.0,
                "the passes through the trays",
                false,
            ),
        ] {
            let panel = panel.titled(caption, (FONT, 16)).map_err(err)?;
            // The zoom keeps the room below for the legend empty, so that both panels share
            // a height.
            let here = if legend {
                place
            } else {
                LegendPlace {
                    right: 0,
                    below: place.below,
                }
            };
            let mut chart =
                equal_scale_chart(&panel, here, 60, points.iter().copied(), pad, "x (mm)")?;
            let (Range { start: x0, end: x1 }, Range { start: y0, end: y1 }) =
                (chart.x_range(), chart.y_range());
            for (i, kin, ev, agro, _) in &drawn {
                let colour = ARM_COLOURS[*i % ARM_COLOURS.len()];
                let n = agro.tray_normal();
                let s = ev.tray_surface_point(n);
                let t = n.turn_90();
                let surface = [(s - t * surface_half).into(), (s + t * surface_half).into()];
                fine_line(&mut chart, &surface, grey.mix(0.8), 2)?;
                fine_line(
                    &mut chart,
                    &tip_points(kin, [0.0, 360.0]),
                    colour.mix(0.6),
                    2,
                )?;
                fine_line(
                    &mut chart,
                    &tip_points(kin, window_deg(ev)),
                    colour.into(),
                    5,
                )?;
                let Vec2 { x, y } = ev.picking.tip_mm;
                chart
                    .draw_series(std::iter::once(Circle::new((x, y), 5, BLACK.filled())))
                    .map_err(err)?;
            }
            if x0 < 0.0 && 0.0 < x1 && y0 < 0.0 && 0.0 < y1 {
                chart
                    .draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, BLACK.filled())))
                    .map_err(err)?;
            }
            if legend {
                let mut entries: Entries = Vec::new();
                for (i, _, _, _, label) in &drawn {
                    let colour = ARM_COLOURS[*i % ARM_COLOURS.len()];
                    entries.push((label.clone(), Swatch::Line(colour.into(), 5)));
                }
                entries.push((tray_label.clone(), Swatch::Line(grey.mix(0.8), 2)));
                entries.push((picking_label.clone(), Swatch::Dot(BLACK.into())));
                draw_legend(&panel, chart.plotting_area(), &entries, LEGEND_FONT, place)?;
            }
        }
        Ok(())
    }
}
