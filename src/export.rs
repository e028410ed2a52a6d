//! Export for CAD and multibody tools: pitch curves as CSV, SVG and DXF (mm, each gear in
//! its own frame, centre at the origin), and the tip trajectory as CSV.

use noncirc_core::{Frame, GearPair, Kinematics, Member, PairTrack, Vec2};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::files::{create_dir, write_file};
use crate::Result;

/// A named closed polyline in mm.
pub struct Outline {
    pub name: &'static str,
    pub points: Vec<Vec2>,
}

/// Largest distance of an exported pitch-curve chord from the curve (mm).
pub const PITCH_CHORD_TOLERANCE_MM: f64 = 1e-3;

/// The driving gear (sun and planets) and the driven gear (intermediates), each in its own
/// frame, sampled so that no chord strays more than [`PITCH_CHORD_TOLERANCE_MM`] from the
/// curve (steps of `2√(2·tol·R)` of arc for the local radius of curvature `R`), not at the
/// evaluation's samples: driver points at ascending `ψ` from the pair's first sample
/// (ψ = 0 for a gear scene and a train with the sun installed, `Φ0` for a train in the
/// ground frame); driven points at its own angle `χ = −(φ2(ψ) − φ2(ψ₀))`, radius `a − ρ`,
/// the angle 0 meeting the first sample.
pub fn outlines(pair: &GearPair) -> Result<Vec<Outline>> {
    outlines_named(pair, ["driver", "driven"])
}

/// As [`outlines`], with the two outlines named `names`.
fn outlines_named(pair: &GearPair, names: [&'static str; 2]) -> Result<Vec<Outline>> {
    let track = PairTrack::new(pair.curve(), pair.centre_distance(), 256)?;
    let points = pitch_points(&track, pair.psi(0), PITCH_CHORD_TOLERANCE_MM);
    Ok((names.into_iter().zip(points))
        .map(|(name, points)| Outline { name, points })
        .collect())
}

/// The outlines of a train's pairs: `driver` (the sun) and `driven` (the intermediate),
/// and with two pairs `second_driver` (the intermediate's layer B, in the intermediate's
/// frame) and `second_driven` (the planet), the planet's angle 0 meeting layer B's first
/// sample, `γ0 − 180°`.
pub fn train_outlines(pair: &GearPair, second: Option<&GearPair>) -> Result<Vec<Outline>> {
    let mut out = outlines(pair)?;
    if let Some(second) = second {
        out.extend(outlines_named(second, ["second_driver", "second_driven"])?);
    }
    Ok(out)
}

/// Both pitch curves of `track` in their own frames from the driver's `psi0` (rad) on, the
/// driven gear turned so that its angle 0 meets `psi0`, sampled so that no chord strays
/// more than `tol` (mm) from either curve: steps of `2√(2·tol/κ)` of arc for the sharper
/// curvature at both ends of the step.
pub fn pitch_points(track: &PairTrack, psi0: f64, tol: f64) -> [Vec<Vec2>; 2] {
    let (s0, chi0) = (track.arc(psi0), track.driven_angle(psi0));
    let turn = Vec2::new((-chi0).cos(), (-chi0).sin());
    let perimeter = track.perimeter();
    let frames = |psi: f64| {
        (
            track.frame(Member::Driver, psi),
            track.frame(Member::Driven, psi),
        )
    };
    let sharpest = |(f1, f2): (Frame, Frame)| f1.curvature.abs().max(f2.curvature.abs()).max(1e-9);
    let step = |k: f64| (8.0 * tol / k).sqrt().min(0.02 * perimeter);
    let (mut driver, mut driven) = (Vec::new(), Vec::new());
    let mut s = 0.0;
    while s < perimeter {
        let here = frames(track.psi_at(s0 + s));
        driver.push(here.0.point);
        driven.push(here.1.point.rotated(turn));
        let k0 = sharpest(here);
        let k1 = sharpest(frames(track.psi_at(s0 + s + step(k0))));
        s += 0.9 * step(k0.max(k1));
    }
    [driver, driven]
}

/// DXF R2000 in millimetres (header with `$INSUNITS`, layer table), one closed LWPOLYLINE
/// per outline on a layer of its name.
pub fn dxf(outlines: &[Outline]) -> String {
    let polylines: Vec<(&str, Vec<Vec2>)> = outlines
        .iter()
        .map(|o| (o.name, o.points.clone()))
        .collect();
    crate::cad::dxf(&[], &[], 0.0, &polylines)
}

/// SVG in mm (1 user unit = 1 mm, y up as in the model), one closed path per outline.
pub fn svg(outlines: &[Outline]) -> String {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in outlines.iter().flat_map(|o| &o.points) {
        x0 = x0.min(p.x);
        x1 = x1.max(p.x);
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    let gap = 0.1 * (x1 - x0);
    let width: f64 = outlines.len() as f64 * (x1 - x0 + gap);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.3}mm\" height=\"{h:.3}mm\" viewBox=\"0 0 {width:.6} {h:.6}\">\n",
        h = y1 - y0
    );
    for (k, o) in outlines.iter().enumerate() {
        let dx = k as f64 * (x1 - x0 + gap) - x0;
        let d: Vec<String> = o
            .points
            .iter()
            .map(|Vec2 { x, y }| format!("{:.6},{:.6}", x + dx, y1 - y))
            .collect();
        let _ = writeln!(
            s,
            "  <path id=\"{}\" d=\"M {} Z\" fill=\"none\" stroke=\"black\" stroke-width=\"0.2\"/>",
            o.name,
            d.join(" L ")
        );
    }
    s + "</svg>\n"
}

fn csv(points: &[Vec2]) -> String {
    let mut s = String::from("x_mm,y_mm\n");
    for Vec2 { x, y } in points {
        let _ = writeln!(s, "{x:.9},{y:.9}");
    }
    s
}

/// Writes `<name>.csv` per outline of the pair (and of the `second` pair of a train with
/// two), `pitch_curves.svg` and `pitch_curves.dxf` into `dir`.
pub fn export_gears(
    pair: &GearPair,
    second: Option<&GearPair>,
    dir: &Path,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let outlines = train_outlines(pair, second)?;
    let mut files = Vec::new();
    for o in &outlines {
        let path = dir.join(format!("{}.csv", o.name));
        write_file(&path, csv(&o.points).as_bytes())?;
        files.push(path);
    }
    for (name, text) in [
        ("pitch_curves.svg", svg(&outlines)),
        ("pitch_curves.dxf", dxf(&outlines)),
    ] {
        let path = dir.join(name);
        write_file(&path, text.as_bytes())?;
        files.push(path);
    }
    Ok(files)
}

/// Writes `trajectory.csv`: carrier angle, tip of arm I, planet centre and orientation,
/// and the arm's attitude, at every sample (for ADAMS, MATLAB, …).
pub fn export_trajectory(kin: &Kinematics, dir: &Path) -> Result<PathBuf> {
    create_dir(dir)?;
    let mut s = String::from(
        "carrier_deg,tip_x_mm,tip_y_mm,planet_x_mm,planet_y_mm,planet_angle_deg,attitude_deg\n",
    );
    for j in 0..kin.len() {
        let (t, o, th) = (
            kin.tips()[j],
            kin.planet_centres()[j],
            kin.planet_angles()[j],
        );
        let att = noncirc_core::attitude_deg(kin.pusher_angle(th));
        let _ = writeln!(
            s,
            "{:.6},{:.9},{:.9},{:.9},{:.9},{:.9},{:.9}",
            kin.theta(j).to_degrees(),
            t.x,
            t.y,
            o.x,
            o.y,
            th.to_degrees(),
            att
        );
    }
    let path = dir.join("trajectory.csv");
    write_file(&path, s.as_bytes())?;
    Ok(path)
}
