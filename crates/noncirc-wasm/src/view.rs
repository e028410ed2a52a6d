//! What the studio draws, as plain numbers (mm, degrees): the pitch curve in polar form,
//! the tip trajectory by section with its events, tray and ground, and the mechanism at a
//! carrier angle. The page only scales and strokes them.

use noncirc::core::{unit, Evaluation, Kinematics, PreparedTarget, Scene, Section, Target, Vec2};
use noncirc::teeth::{train_layout, TeethRun};
use serde::Serialize;
use std::f64::consts::TAU;

/// A polyline (mm).
type Line = Vec<[f64; 2]>;

/// Points of the pitch curve per turn in the polar plot.
const CURVE_POINTS: usize = 360;

/// Most points of a drawn trajectory or pitch outline: a finer resolution (up to 786 432
/// samples a turn) is thinned to this, which is finer than a screen shows.
const MAX_DRAWN: usize = 1440;

/// Every `k`-th point, `k` the least step that keeps at most [`MAX_DRAWN`].
fn thinned(points: &[Vec2]) -> Vec<Vec2> {
    let step = points.len().div_ceil(MAX_DRAWN).max(1);
    points.iter().step_by(step).copied().collect()
}

/// The design's drawings.
#[derive(Serialize)]
pub struct View {
    /// The sun's pitch curve: `[ψ (deg), ρ (mm)]` over one turn.
    curve: Line,
    /// The tip's path over one carrier turn, one point per sample up to [`MAX_DRAWN`] (mm).
    trajectory: Line,
    /// The trajectory's four sections in the order of motion: `(name, label, path)`.
    sections: Vec<(&'static str, &'static str, Line)>,
    picking_mm: Option<[f64; 2]>,
    planting_mm: Option<[f64; 2]>,
    /// The tray surface through the picking point's tray (a segment, mm).
    tray: Option<Line>,
    /// The ground's height (mm): the planting depth above the lowest point.
    ground_y_mm: Option<f64>,
    /// The scene's target: its table (points, poses, tolerances) and its path as drawn.
    target: Option<TargetView>,
}

/// The target as the page draws and edits it.
#[derive(Serialize)]
struct TargetView {
    /// The `[target]` table as a scene file holds it.
    table: Target,
    /// The path through its points (the spline's fine polyline, thinned; mm).
    path: Line,
}

impl View {
    /// The drawings of `eval`, the evaluation of `scene`, whose target (if it has one) is
    /// prepared as `prepared`.
    pub fn new(scene: &Scene, eval: &Evaluation, prepared: Option<&PreparedTarget>) -> Self {
        let curve = eval.pair().map_or_else(Vec::new, |pair| {
            (0..=CURVE_POINTS)
                .map(|i| {
                    let psi = TAU * i as f64 / CURVE_POINTS as f64;
                    [psi.to_degrees(), pair.curve().eval(psi).rho]
                })
                .collect()
        });
        let mut view = Self {
            curve,
            trajectory: Vec::new(),
            sections: Vec::new(),
            picking_mm: None,
            planting_mm: None,
            tray: None,
            ground_y_mm: None,
            target: None,
        };
        if let (Some(table), Some(prepared)) = (&scene.target, prepared) {
            let path = thinned(prepared.polyline());
            view.target = Some(TargetView {
                table: (**table).clone(),
                path: path
                    .into_iter()
                    .chain(prepared.polyline().first().copied())
                    .map(Into::into)
                    .collect(),
            });
        }
        let (Some(kin), Some(events)) = (&eval.kinematics, &eval.events) else {
            return view;
        };
        let agro = &scene.agronomy;
        view.trajectory = thinned(kin.tips()).into_iter().map(Into::into).collect();
        if let Some(anatomy) = eval.anatomy(agro) {
            view.sections = (Section::ALL.into_iter())
                .map(|s| {
                    let span = anatomy.section(s).carrier_deg;
                    (s.name(), s.label(), tip_path(kin, span))
                })
                .collect();
        }
        view.picking_mm = Some(events.picking.tip_mm.into());
        view.planting_mm = Some(events.planting.tip_mm.into());
        let n = agro.tray_normal();
        let surface = events.tray_surface_point(n);
        let along = n.turn_90() * 120.0;
        view.tray = Some(vec![(surface - along).into(), (surface + along).into()]);
        view.ground_y_mm = Some(events.y_min_mm + agro.planting_depth_mm);
        view
    }
}

/// The tip's path over a carrier span (deg), a point per degree and both ends.
fn tip_path(kin: &Kinematics, span_deg: [f64; 2]) -> Line {
    let steps = (span_deg[1] - span_deg[0]).abs().ceil().max(1.0) as u32;
    (0..=steps)
        .map(|i| {
            let deg = span_deg[0] + (span_deg[1] - span_deg[0]) * f64::from(i) / f64::from(steps);
            kin.state_at(deg.to_radians()).tip.into()
        })
        .collect()
}

/// One arm set at a carrier angle: its intermediate gear, planet gear and arm.
#[derive(Serialize)]
struct ArmSet {
    intermediate: Line,
    /// The train with two pairs: the intermediate's layer B, which drives the planet.
    intermediate_b: Option<Line>,
    planet: Line,
    /// From the planet's centre to the tip (mm).
    arm: Line,
}

/// The mechanism at one carrier angle: the sun and the arm sets (arm k where arm I stands
/// k·360°/arms of carrier earlier), pitch curves or, when cut, teeth.
#[derive(Serialize)]
pub struct Frame {
    carrier_deg: f64,
    sun: Line,
    arms: Vec<ArmSet>,
}

/// An outline in its own frame, turned by `angle` (rad) and moved to `centre`.
fn place(outline: &[Vec2], centre: Vec2, angle: f64) -> Line {
    let turn = unit(angle);
    outline
        .iter()
        .map(|p| (centre + p.rotated(turn)).into())
        .collect()
}

impl Frame {
    pub fn new(kin: &Kinematics, teeth: Option<&TeethRun>, theta: f64) -> Self {
        let sun_angle = kin.spec().sun_angle();
        let sun = match teeth {
            Some(run) => run.pair.gears[0].outline().to_vec(),
            None => thinned(&kin.pair().driver_points()),
        };
        // Pitch curves: the intermediate's conjugate of the sun, its layer B with two
        // pairs, and the planet (the sun's copy, or the second pair's driven gear).
        let pitch = [
            thinned(&kin.pair().driven_points()),
            kin.second_pair()
                .map_or_else(Vec::new, |p| thinned(&p.driver_points())),
            thinned(&kin.planet_points()),
        ];
        let arms = (0..kin.arms())
            .map(|k| {
                let at = theta - kin.arm_lag(k);
                let st = kin.state_at(at);
                // Arm I's gears of the layout at `at`: intermediate, [layer B,] planet.
                let mut gears: Vec<Line> = match teeth {
                    Some(run) => {
                        let layout = train_layout(kin, &run.pair, run.second.as_ref(), at);
                        let own = &layout[1..1 + (layout.len() - 1) / kin.arms()];
                        (own.iter())
                            .map(|g| place(run.outline(g), g.centre_mm, g.angle_deg.to_radians()))
                            .collect()
                    }
                    None => {
                        let mut lines = vec![place(&pitch[0], st.o2, st.theta2)];
                        if kin.second_pair().is_some() {
                            lines.push(place(&pitch[1], st.o2, st.theta2));
                        }
                        lines.push(place(&pitch[2], st.o3, st.theta3));
                        lines
                    }
                };
                let planet = gears.pop().expect("every arm set has a planet");
                let intermediate_b = (gears.len() == 2).then(|| gears.pop()).flatten();
                ArmSet {
                    intermediate: gears.pop().expect("and an intermediate"),
                    intermediate_b,
                    planet,
                    arm: vec![st.o3.into(), st.tip.into()],
                }
            })
            .collect();
        Self {
            carrier_deg: theta.to_degrees(),
            sun: place(&sun, Vec2::ZERO, sun_angle),
            arms,
        }
    }
}
