//! Robust design: each objective's margin distribution under the tolerances against its
//! bound, and the Sobol indices as a heat map.

use super::*;
use crate::robustness::{parameter_label, Robustness, Sensitivity};

/// One panel per objective: the histogram of its margin over the tolerance samples (in
/// its unit), the bound (margin 0) and the nominal design's margin.
pub struct MarginsFigure<'a> {
    pub analysis: &'a Robustness,
}

/// Columns of panels.
const COLUMNS: usize = 3;

/// Height of the line under a panel's caption that says how far a bound off the chart is
/// (px).
const NOTE_LINE_PX: u32 = 16;

impl Figure for MarginsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let rows = self
            .analysis
            .report
            .objectives
            .len()
            .div_ceil(COLUMNS)
            .max(1);
        (1200, 96 + (260 + NOTE_LINE_PX) * rows as u32)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let r = &self.analysis.report;
        let [lo, hi] = r.probability_all_ci95;
        let title = format!(
            "Margins under the tolerances: {} samples, P({} met) = {:.3} (95 % interval \
             {lo:.4}–{hi:.4})",
            r.samples,
            r.requirements(),
            r.probability_all
        );
        let area = root.titled(&title, (FONT, 20)).map_err(err)?;
        let (area, key_area) = area.split_vertically(area.dim_in_pixel().1.saturating_sub(26));
        let rows = r.objectives.len().div_ceil(COLUMNS).max(1);
        let panels = area.split_evenly((rows, COLUMNS));
        let bound = RGBColor(200, 30, 60);
        let bars = RGBColor(70, 110, 170);
        for ((o, margins), panel) in r.objectives.iter().zip(&self.analysis.margins).zip(&panels) {
            let values: Vec<f64> = margins.iter().copied().filter(|m| m.is_finite()).collect();
            let (lo, hi) = (values.iter().chain([&o.nominal_margin]))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            // The bound is drawn where it is within two spreads of the samples; farther,
            // the panel says how far (else the distribution would shrink to a line).
            let spread = (hi - lo).max(1e-9);
            let bound_shown = lo - 2.0 * spread <= 0.0 && 0.0 <= hi + 2.0 * spread;
            let (lo, hi) = if bound_shown {
                (lo.min(0.0), hi.max(0.0))
            } else {
                (lo, hi)
            };
            // A margin that does not move (the seedling push, 0 whenever met) still gets
            // an axis a unit wide around it.
            let pad = ((hi - lo) * 0.08).max(if hi - lo < 1e-9 { 0.5 } else { 0.0 });
            let (lo, hi) = (lo - pad, hi + pad);
            let bins = 24;
            let width = (hi - lo) / bins as f64;
            let mut counts = vec![0usize; bins];
            for v in &values {
                counts[(((v - lo) / width) as usize).min(bins - 1)] += 1;
            }
            let top = counts.iter().copied().max().unwrap_or(1).max(1) as f64 * 1.15;
            let [p_lo, p_hi] = o.probability_ci95;
            // The analysis bolts a tray the path places: this is another margin than
            // evaluate's (the table's note says how).
            let fixed = if o.objective == noncirc_core::ObjectiveKind::PickingAdmissible
                && r.picking_admissible_placed_mm.is_some()
            {
                " (tray fixed)"
            } else {
                ""
            };
            let caption = format!(
                "{}{fixed}: P = {:.3} ({p_lo:.4}–{p_hi:.4})",
                o.objective.label(),
                o.probability
            );
            // The caption, then a line for the note on a far bound (kept empty otherwise,
            // so that the panels' charts line up), then the chart: no text on the data.
            let below = panel.titled(&caption, (FONT, 14)).map_err(err)?;
            let (note_area, chart_area) = below.split_vertically(NOTE_LINE_PX);
            let mut chart = ChartBuilder::on(&chart_area)
                .margin(8)
                .x_label_area_size(38)
                .y_label_area_size(44)
                .build_cartesian_2d(lo..hi, 0.0..top)
                .map_err(err)?;
            chart
                .configure_mesh()
                .disable_x_mesh()
                .x_labels(5)
                .y_labels(4)
                .x_label_formatter(&tick)
                .y_label_formatter(&tick)
                .x_desc(format!("margin ({})", o.unit))
                .y_desc("samples")
                .label_style((FONT, 11))
                .draw()
                .map_err(err)?;
            chart
                .draw_series(counts.iter().enumerate().map(|(i, &c)| {
                    let x0 = lo + i as f64 * width;
                    Rectangle::new([(x0, 0.0), (x0 + width, c as f64)], bars.mix(0.75).filled())
                }))
                .map_err(err)?;
            // The bound (margin 0): left of it the objective is missed.
            if bound_shown {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(0.0, 0.0), (0.0, top)],
                        bound.stroke_width(2),
                    )))
                    .map_err(err)?;
            }
            let note = if values.is_empty() {
                Some("no sample: the model refused every one".to_string())
            } else if bound_shown {
                None
            } else {
                // The bound is left of every sample when they meet it, right when they miss.
                let sd = o.margin_sd.max(1e-12);
                let (gap, side) = if o.margin_quantiles[0] > 0.0 {
                    (o.margin_quantiles[0], "left")
                } else {
                    (-o.margin_quantiles[4], "right")
                };
                Some(format!(
                    "bound {gap:.2} {} to the {side} ({:.0} sd)",
                    o.unit,
                    gap / sd
                ))
            };
            if let Some(note) = note {
                // Left-aligned with the plotting area (its y-label area and margin).
                note_area
                    .draw(&Text::new(
                        note,
                        (8 + 44, 2),
                        TextStyle::from((FONT, 11)).color(&bound),
                    ))
                    .map_err(err)?;
            }
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(o.nominal_margin, 0.0), (o.nominal_margin, top)],
                    6,
                    4,
                    BLACK.stroke_width(1),
                ))
                .map_err(err)?;
        }
        // One key for every panel, under them.
        let key = "red line: the bound (margin 0, missed to its left; where it is far, the \
                   panel says how far from the nearest 1 % of the samples); dashed: the design as drawn; bars: \
                   the tolerance samples (machines as built)";
        key_area
            .draw(&Text::new(key, (12, 4), (FONT, 13)))
            .map_err(err)?;
        Ok(())
    }
}

/// The total Sobol indices as a heat map: outputs down, parameters across, the first-order
/// index in each cell's text where the total is at least 0.05.
pub struct SensitivityFigure<'a> {
    pub sensitivity: &'a Sensitivity,
}

impl Figure for SensitivityFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let s = self.sensitivity;
        (
            // The cells, the outputs' names, the colour bar (110 px).
            410 + 60 * s.parameters.len() as u32,
            // A line more for the note on unreliable indices.
            160 + 22 * s.outputs.len() as u32 + 24 * s.base_samples_needed.is_some() as u32,
        )
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let s = self.sensitivity;
        let (k, m) = (s.parameters.len(), s.outputs.len().max(1));
        let title = format!(
            "Total Sobol indices S_T over {} of the search box ({} designs); in each cell S_T / S1",
            s.box_scale, s.evaluations
        );
        let area = root.titled(&title, (FONT, 18)).map_err(err)?;
        let (area, note_area) = match s.base_samples_needed {
            Some(_) => area.split_vertically(area.dim_in_pixel().1.saturating_sub(24)),
            None => area.split_vertically(area.dim_in_pixel().1),
        };
        let (area, bar_area) = area.split_horizontally(area.dim_in_pixel().0.saturating_sub(110));
        let chart = ChartBuilder::on(&area)
            .margin(10)
            .margin_right(20)
            .x_label_area_size(50)
            .y_label_area_size(240)
            .build_cartesian_2d(0.0..k as f64, 0.0..m as f64)
            .map_err(err)?;
        // The labels are drawn on the parent area beside the cells (plotters keeps a
        // chart's own elements inside its plotting area).
        let plot = chart.plotting_area();
        let (xs, ys) = plot.get_pixel_range();
        let (x0, y0) = area.get_base_pixel();
        let cell_w = (xs.end - xs.start) as f64 / k as f64;
        let cell_h = (ys.end - ys.start) as f64 / m as f64;
        for (row, o) in s.outputs.iter().enumerate() {
            let y = (m - 1 - row) as f64;
            let cy = ys.start + ((row as f64 + 0.5) * cell_h) as i32 - y0;
            let token = format!("_{}", o.unit.replace('/', "_"));
            let mut label = if o.name.ends_with(&token) {
                o.name.clone()
            } else {
                format!("{} ({})", o.name, o.unit)
            };
            let flagged = !o.unreliable.is_empty();
            if flagged {
                label.push_str(" †");
            }
            area.draw(&Text::new(
                label,
                (xs.start - x0 - 8, cy),
                TextStyle::from((FONT, 12))
                    .color(if flagged { &WARNING_RED } else { &BLACK })
                    .pos(Pos::new(HPos::Right, VPos::Center)),
            ))
            .map_err(err)?;
            for i in 0..k {
                let v = o.indices.total[i].clamp(0.0, 1.0);
                plot.draw(&Rectangle::new(
                    [(i as f64, y), (i as f64 + 1.0, y + 1.0)],
                    index_colour(v).filled(),
                ))
                .map_err(err)?;
                if o.indices.total[i] >= 0.05 {
                    let text_colour = if v > 0.45 { WHITE } else { BLACK };
                    plot.draw(&Text::new(
                        format!(
                            "{:.2}/{:.2}",
                            o.indices.total[i],
                            o.indices.first[i].max(0.0)
                        ),
                        (i as f64 + 0.5, y + 0.5),
                        TextStyle::from((FONT, 10))
                            .color(&text_colour)
                            .pos(Pos::new(HPos::Center, VPos::Center)),
                    ))
                    .map_err(err)?;
                }
            }
        }
        for (i, p) in s.parameters.iter().enumerate() {
            let cx = xs.start + ((i as f64 + 0.5) * cell_w) as i32 - x0;
            area.draw(&Text::new(
                parameter_label(p),
                (cx, ys.end - y0 + 8),
                TextStyle::from((FONT, 13)).pos(Pos::new(HPos::Center, VPos::Top)),
            ))
            .map_err(err)?;
        }
        area.draw(&Text::new(
            "free parameter (the papers' symbols; r1 … r12 the control radii)",
            ((xs.start + xs.end) / 2 - x0, ys.end - y0 + 30),
            TextStyle::from((FONT, 12)).pos(Pos::new(HPos::Center, VPos::Top)),
        ))
        .map_err(err)?;
        colour_bar(&bar_area, (ys.start - y0, ys.end - y0))?;
        if let Some(needed) = s.base_samples_needed {
            note_area
                .draw(&Text::new(
                    format!(
                        "† indices not readable at {} base points (the table's warning says \
                         why): about {needed} would read them to ±{}",
                        s.base_samples,
                        noncirc_core::READABLE_HALF_WIDTH
                    ),
                    (10, 4),
                    TextStyle::from((FONT, 13)).color(&WARNING_RED),
                ))
                .map_err(err)?;
        }
        Ok(())
    }
}

/// Dark red of the notes on unreliable indices.
const WARNING_RED: RGBColor = RGBColor(178, 24, 43);

/// A total index's colour: white at 0 to deep blue at 1.
fn index_colour(v: f64) -> RGBColor {
    let shade = |c: f64| (255.0 - v * (255.0 - c)).round() as u8;
    RGBColor(shade(8.0), shade(48.0), shade(107.0))
}

/// The heat map's colour bar, between the cells' top and bottom `rows` (pixels in `area`).
fn colour_bar<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, rows: (i32, i32)) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (top, bottom) = (rows.0.max(20), rows.1);
    let (left, width) = (16, 20);
    let steps = 100;
    for j in 0..steps {
        let v = (j as f64 + 0.5) / steps as f64;
        let y = |t: f64| bottom - ((bottom - top) as f64 * t).round() as i32;
        area.draw(&Rectangle::new(
            [
                (left, y(j as f64 / steps as f64)),
                (left + width, y((j + 1) as f64 / steps as f64)),
            ],
            index_colour(v).filled(),
        ))
        .map_err(err)?;
    }
    area.draw(&Rectangle::new(
        [(left, top), (left + width, bottom)],
        BLACK,
    ))
    .map_err(err)?;
    for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let y = bottom - ((bottom - top) as f64 * t).round() as i32;
        area.draw(&PathElement::new(
            vec![(left + width, y), (left + width + 4, y)],
            BLACK,
        ))
        .map_err(err)?;
        area.draw(&Text::new(
            format!("{t:.2}"),
            (left + width + 7, y),
            TextStyle::from((FONT, 12)).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(err)?;
    }
    area.draw(&Text::new(
        "S_T",
        (left + width / 2, top - 6),
        TextStyle::from((FONT, 13)).pos(Pos::new(HPos::Center, VPos::Bottom)),
    ))
    .map_err(err)?;
    Ok(())
}
