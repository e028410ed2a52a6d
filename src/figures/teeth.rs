//! The toothed train: every gear at its place at one carrier angle, and a close view of
//! the first mesh.

use super::*;
use crate::teeth::{tenth_micrometres, TeethRun};
use noncirc_core::Member;

/// The assembled toothed gears and a close view of a mesh.
pub struct TeethFigure<'a> {
    pub run: &'a TeethRun,
}

fn placed(run: &TeethRun, k: usize) -> Vec<(f64, f64)> {
    let g = &run.layout[k];
    super::gears::place(run.outline(g), g.centre_mm, g.angle_deg.to_radians())
}

impl Figure for TeethFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1400, 700)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(err)?;
        let (left, right) = root.split_horizontally(700);
        let run = self.run;
        let r = &run.pair.report;
        let all: Vec<Vec<(f64, f64)>> = (0..run.layout.len()).map(|k| placed(run, k)).collect();
        // Gears per arm set after the sun: intermediate, [its layer B,] planet.
        let per_arm = match run.carrier_deg {
            Some(_) => 1 + run.pairs().count(),
            None => 1,
        };
        let colour = |k: usize| {
            let g = &run.layout[k];
            let planet = (g.pair == 0 && g.member == Member::Driver)
                || g.pair == 1 && g.member == Member::Driven;
            match k {
                0 => RGBColor(40, 40, 40),
                _ if planet => ARM_COLOURS[(k - 1) / per_arm % 3],
                _ => {
                    let RGBColor(r, g, b) = ARM_COLOURS[(k - 1) / per_arm % 3];
                    let light = |c: u8| c + (255 - c) / 2;
                    RGBColor(light(r), light(g), light(b))
                }
            }
        };
        let title = match run.carrier_deg {
            Some(t) => format!(
                "Toothed train at θ = {t:.0}°: z = {}, m = {:.3} mm",
                r.teeth, r.module_mm
            ),
            None => format!("Toothed pair: z = {}, m = {:.3} mm", r.teeth, r.module_mm),
        };
        let points = all.iter().flatten().map(|&(x, y)| Vec2::new(x, y));
        let ((x0, x1), (y0, y1)) = equal_ranges(points, 640.0, 600.0, 2.0);
        let mut c = plane_chart(
            &left,
            &title,
            18,
            x0..x1,
            y0..y1,
            LegendPlace { right: 0, below: 0 },
        )?;
        for (k, pts) in all.iter().enumerate() {
            c.draw_series(LineSeries::new(pts.clone(), colour(k).stroke_width(1)))
                .map_err(err)?;
        }
        // Close view of the sun–intermediate mesh (or the pair's), around the pitch point.
        let other = 1;
        let (o1, o2) = (run.layout[0].centre_mm, run.layout[other].centre_mm);
        let d = o2 - o1;
        let rho = pitch_point_distance(run, d);
        let pitch = o1 + d * (rho / d.hypot());
        let half = 3.0 * r.module_mm;
        let window = (
            (pitch.x - half, pitch.x + half),
            (pitch.y - half, pitch.y + half),
        );
        let caption = format!(
            "The {} – {} mesh: least clearance {} mm, contact ratio ≥ {:.2}",
            run.layout[0].name,
            run.layout[other].name,
            tenth_micrometres(r.mesh.least_clearance_mm),
            r.mesh.contact_ratio_min
        );
        let (wx, wy) = window;
        let mut c = plane_chart(
            &right,
            &caption,
            16,
            wx.0..wx.1,
            wy.0..wy.1,
            LegendPlace { right: 0, below: 0 },
        )?;
        for k in [0, other] {
            let style = colour(k).stroke_width(2);
            let runs = clipped_runs(&all[k], window.0, window.1);
            c.draw_series(runs.into_iter().map(|run| PathElement::new(run, style)))
                .map_err(err)?
                .label(run.layout[k].name.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        }
        c.draw_series(std::iter::once(Circle::new(
            (pitch.x, pitch.y),
            4,
            RED.filled(),
        )))
        .map_err(err)?
        .label("pitch point")
        .legend(|(x, y)| Circle::new((x + 10, y), 4, RED.filled()));
        c.configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font((FONT, 13))
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

/// Distance from the first gear's centre to the pitch point on the line of centres `d`.
fn pitch_point_distance(run: &TeethRun, d: Vec2) -> f64 {
    let g = &run.layout[0];
    let psi = d.y.atan2(d.x) - g.angle_deg.to_radians();
    run.pair.track.curve().eval(psi).rho
}

/// The teeth figure into `dir`.
pub fn teeth_figures(run: &TeethRun, dir: &Path, options: &FigureOptions) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    save(&TeethFigure { run }, &dir.join("teeth"), options)
}
