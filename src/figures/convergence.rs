//! How a search converged: the best constraint violation until a feasible design is found,
//! then the best goal in its unit.

use super::*;
use noncirc_core::{GoalQuantity, HistoryRow};

/// Two panels over evaluations: above, the best violation (log scale) while every design
/// is infeasible, and where the first feasible one came; below, the best feasible goal.
pub struct ConvergenceFigure<'a> {
    pub algorithm: &'a str,
    pub history: &'a [HistoryRow],
    /// The (first) goal and its value in its unit for each history row's `best_goal`.
    pub goal: GoalQuantity,
    pub goal_value: &'a dyn Fn(f64) -> f64,
}

impl Figure for ConvergenceFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 720)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let area = root
            .titled(
                &format!("Search convergence ({})", self.algorithm),
                (FONT, 20),
            )
            .map_err(err)?;
        let (top, bottom) = area.split_vertically(area.dim_in_pixel().1 / 2);
        let h = self.history;
        let x1 = h.last().map_or(1.0, |r| r.evaluations as f64).max(1.0);
        // Infeasible rows: their violation, on a log scale; a violation of 0 has no
        // logarithm and is not drawn as one: the first feasible design is a line.
        let cv: Vec<(f64, f64)> = (h.iter())
            .filter(|r| r.best_cv > 0.0 && r.best_cv.is_finite())
            .map(|r| (r.evaluations as f64, r.best_cv.log10()))
            .collect();
        let feasible_at = h
            .iter()
            .find(|r| r.best_cv == 0.0)
            .map(|r| r.evaluations as f64);
        let feasible_label = match feasible_at {
            Some(at) => format!("first feasible design, after {at:.0} evaluations"),
            None => "no feasible design found".to_string(),
        };
        let goal_label = format!("best feasible {}", self.goal.label());
        let place = legend_place(
            [
                "best violation",
                feasible_label.as_str(),
                goal_label.as_str(),
            ],
            12,
            top.dim_in_pixel(),
        );
        // log10 of the violation on a linear axis, whole decades at the ends, labelled
        // with the violation itself.
        let (lo, hi) = (cv.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
        let (lo, hi) = if cv.is_empty() {
            (-3.0, 0.0)
        } else {
            ((lo - 0.05).floor(), (hi + 0.05).ceil())
        };
        let mut chart = chart_on(&top, 10, place, (35, 70))
            .build_cartesian_2d(0.0..x1, lo..hi)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .x_desc("evaluations")
            .y_desc("best violation (sum of normalised), log scale")
            .y_label_formatter(&|v| two_digits(10f64.powf(*v)))
            .label_style((FONT, 12))
            .draw()
            .map_err(err)?;
        let red = RGBColor(200, 30, 60);
        chart
            .draw_series(LineSeries::new(cv, red.stroke_width(2)))
            .map_err(err)?;
        let green = RGBColor(30, 140, 50);
        let marker = chart.draw_series(
            feasible_at.map(|at| PathElement::new(vec![(at, lo), (at, hi)], green.stroke_width(2))),
        );
        marker.map_err(err)?;
        let entries = vec![
            ("best violation".to_string(), Swatch::Line(red.into(), 2)),
            (feasible_label, Swatch::Tick(green.into(), 2)),
        ];
        draw_legend(&top, chart.plotting_area(), &entries, 12, place)?;

        let goal: Vec<(f64, f64)> = (h.iter())
            .filter(|r| r.best_cv == 0.0)
            .map(|r| (r.evaluations as f64, (self.goal_value)(r.best_goal)))
            .filter(|p| p.1.is_finite())
            .collect();
        let (g0, g1) = goal
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
        let (g0, g1) = if goal.is_empty() {
            (0.0, 1.0)
        } else {
            let pad = ((g1 - g0) * 0.08).max(1e-6 * g0.abs().max(1.0));
            (g0 - pad, g1 + pad)
        };
        let mut chart = chart_on(&bottom, 10, place, (35, 70))
            .build_cartesian_2d(0.0..x1, g0..g1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .x_desc("evaluations")
            .y_desc(self.goal.label())
            .label_style((FONT, 12))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(goal, green.stroke_width(2)))
            .map_err(err)?;
        let entries = vec![(goal_label, Swatch::Line(green.into(), 2))];
        draw_legend(&bottom, chart.plotting_area(), &entries, 12, place)?;
        Ok(())
    }
}

/// `x` (positive) to two significant digits: `0.032`, `3.2`, `10`.
fn two_digits(x: f64) -> String {
    let decimals = (1.0 - x.log10().floor()).max(0.0) as usize;
    tick(&format!("{x:.decimals$}").parse().unwrap_or(x))
}
