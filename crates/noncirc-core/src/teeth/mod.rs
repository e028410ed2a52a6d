//! Teeth: conjugate tooth outlines for both gears of a ratio-1 pair (and so for every gear
//! of the three-arm train), cut by a rack or a shaper rolling on the pitch curves, with
//! the checks that decide whether they can be made and will run: undercut, pointed or thin
//! tips, and a whole-cycle mesh check (least clearance, backlash, contact ratio).
//!
//! Units: mm and radians; proportions of the tool (addendum, dedendum, tip radius, shift)
//! in modules, as on a drawing.

mod cut_gear;
mod mate_roots;
mod mesh;
mod polyline;
mod profile;
mod roots;
mod tool;
mod track;

pub use cut_gear::{Side, Tooth, ToothedGear, Undercut};
pub use mate_roots::MateRoots;
pub use mesh::MeshReport;
pub use polyline::segment_distance;
pub use track::{Frame, Member, PairTrack};

use crate::curve::PitchCurve;
use crate::error::{positive, Error, Result};
use profile::Cut;
use serde::{Deserialize, Serialize};
use tool::Tool;

/// The cutting tool: a rack, or a pinion-type shaper cutter for pitch curves with concave
/// arcs (its pitch radius must stay below their least radius of curvature).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Cutter {
    #[default]
    Rack,
    Shaper {
        /// Teeth of the shaper (its pitch radius is `m·teeth/2`).
        teeth: u32,
    },
}

/// How teeth are cut and checked (`[gear.teeth]` in a scene). Heights and radii in
/// modules; the tooth count is the module rule's (`gear.module.teeth`, or the largest
/// admissible module's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ToothSpec {
    /// Pressure angle of the tool (degrees).
    pub pressure_angle_deg: f64,
    /// Addendum: tip height above the pitch curve (× m).
    pub addendum: f64,
    /// Dedendum: root depth below the pitch curve (× m).
    pub dedendum: f64,
    /// Radius of the tool's tip rounding, which cuts the root fillet (× m).
    pub tip_radius: f64,
    /// Circumferential backlash of a pair on the pitch curve (mm), half from each gear.
    pub backlash_mm: f64,
    /// Profile shift of the driver (sun, planets) (× m); the intermediates take the
    /// opposite, so the centre distance stays.
    pub profile_shift: f64,
    pub cutter: Cutter,
    /// Least segments per flank of the outline; more where `chord_tolerance_mm` needs them
    /// (accuracy: see docs/teeth.md).
    pub flank_samples: usize,
    /// Least segments per root fillet; more where `chord_tolerance_mm` needs them.
    pub fillet_samples: usize,
    /// Largest distance (mm) of an outline chord from the generated curve (the mesh check
    /// measures to the curves the chords stand for, to a fraction of it).
    pub chord_tolerance_mm: f64,
    /// Mesh positions per pitch in the whole-cycle check (one more over the turn, so that
    /// the teeth together sample the mesh cycle `teeth` times as finely); a pair whose
    /// roots the mate cuts is checked at 8 times as many (`MATE_CHECK_STEPS`).
    pub mesh_steps_per_pitch: usize,
    /// Panels per turn of the arc-length tables.
    pub arc_panels: usize,
    /// Least tip land (× m) below which a tooth is too thin at the tip.
    pub min_tip_land: f64,
    /// Whether undercut is accepted (it weakens the tooth and shortens the contact).
    pub allow_undercut: bool,
    /// Whether a tooth space whose root the mate's tips overlap (by a concave arc, where
    /// they reach deeper than the cutter did) is cut again by the mate's tips, with the
    /// bottom clearance `(dedendum − addendum)·m` below their tip lands.
    pub mate_roots: bool,
}

impl Default for ToothSpec {
    fn default() -> Self {
        Self {
            pressure_angle_deg: 20.0,
            addendum: 1.0,
            dedendum: 1.25,
            tip_radius: 0.38,
            backlash_mm: 0.0,
            profile_shift: 0.0,
            cutter: Cutter::Rack,
            flank_samples: 18,
            fillet_samples: 12,
            chord_tolerance_mm: 0.002,
            mesh_steps_per_pitch: 1,
            arc_panels: 256,
            min_tip_land: 0.25,
            allow_undercut: false,
            mate_roots: true,
        }
    }
}

/// Most points of one gear's outline: finer settings are refused, not run out of memory.
pub(crate) const MAX_OUTLINE_POINTS: usize = 2_000_000;

/// Largest overlap of tooth bodies the mesh check tolerates (mm).
pub(crate) const OVERLAP_TOLERANCE_MM: f64 = 1e-3;

/// How far the mate's flanks are set back when its tips cut roots, as a share of the mesh
/// check's tolerance: the real tips may then overlap the cut roots by at most this much.
const MATE_MARGIN: f64 = 0.25;

/// Rounds of mate-generated roots and mesh checks at most.
const MATE_ROUNDS: usize = 3;

/// How many times the scene's mesh steps a pair whose roots the mate cuts is checked at.
const MATE_CHECK_STEPS: usize = 8;

/// How far (× m, beyond the backlash) the mesh check measures distances between the
/// gears: clearances and backlash gaps up to this are exact, larger ones are not
/// measured. Conjugate flanks touch, so only the backlash and interference are small.
pub(crate) const MESH_REACH_MODULES: f64 = 0.05;

impl ToothSpec {
    /// Whether every setting is the default (a scene then leaves the table out).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// The mesh check's tolerance (mm): the chord tolerance, or the verdict's overlap
    /// tolerance where that is finer.
    fn check_tolerance_mm(&self) -> f64 {
        self.chord_tolerance_mm.min(OVERLAP_TOLERANCE_MM)
    }

    /// `factor` times the flank, fillet and mesh samples and a chord tolerance `factor²`
    /// finer (the chords' sag falls with the square of their count), within the settings'
    /// ranges: the reference a convergence check compares the settings with.
    pub fn refined(&self, factor: usize) -> Self {
        let more = |n: usize| (factor * n).min(100_000);
        Self {
            flank_samples: more(self.flank_samples),
            fillet_samples: more(self.fillet_samples),
            mesh_steps_per_pitch: more(self.mesh_steps_per_pitch),
            chord_tolerance_mm: (self.chord_tolerance_mm / (factor * factor) as f64).max(1e-6),
            ..*self
        }
    }

    /// Checks every setting, naming the bad one.
    pub fn validate(&self) -> Result<()> {
        let angle = self.pressure_angle_deg;
        if !(angle > 5.0 && angle < 45.0) {
            return Err(Error::OutOfRange {
                name: "gear.teeth.pressure_angle_deg".into(),
                value: angle,
                expected: "between 5 and 45 degrees".into(),
            });
        }
        positive("gear.teeth.addendum", self.addendum)?;
        positive("gear.teeth.dedendum", self.dedendum)?;
        positive("gear.teeth.tip_radius", self.tip_radius)?;
        if !(self.min_tip_land >= 0.0 && self.min_tip_land.is_finite()) {
            return Err(Error::OutOfRange {
                name: "gear.teeth.min_tip_land".into(),
                value: self.min_tip_land,
                expected: "zero or more".into(),
            });
        }
        let tol = self.chord_tolerance_mm;
        if !(1e-6..=0.1).contains(&tol) {
            return Err(Error::OutOfRange {
                name: "gear.teeth.chord_tolerance_mm".into(),
                value: tol,
                expected: "from 1e-6 to 0.1 mm".into(),
            });
        }
        if !(self.backlash_mm >= 0.0 && self.backlash_mm.is_finite()) {
            return Err(Error::OutOfRange {
                name: "gear.teeth.backlash_mm".into(),
                value: self.backlash_mm,
                expected: "zero or more".into(),
            });
        }
        if !self.profile_shift.is_finite() || self.profile_shift.abs() >= self.addendum {
            return Err(Error::OutOfRange {
                name: "gear.teeth.profile_shift".into(),
                value: self.profile_shift,
                expected: "less than the addendum in size".into(),
            });
        }
        for (name, value, least) in [
            ("gear.teeth.flank_samples", self.flank_samples, 2),
            ("gear.teeth.fillet_samples", self.fillet_samples, 2),
            (
                "gear.teeth.mesh_steps_per_pitch",
                self.mesh_steps_per_pitch,
                1,
            ),
            ("gear.teeth.arc_panels", self.arc_panels, 16),
        ] {
            if value < least || value > 100_000 {
                return Err(Error::OutOfRange {
                    name: name.into(),
                    value: value as f64,
                    expected: format!("between {least} and 100000"),
                });
            }
        }
        if let Cutter::Shaper { teeth } = self.cutter {
            if teeth < 6 {
                return Err(Error::OutOfRange {
                    name: "gear.teeth.cutter.teeth".into(),
                    value: f64::from(teeth),
                    expected: "at least 6".into(),
                });
            }
        }
        Ok(())
    }
}

/// Both toothed gears of a ratio-1 pair, and what the checks found.
#[derive(Debug, Clone)]
pub struct ToothedPair {
    pub track: PairTrack,
    pub spec: ToothSpec,
    /// Teeth per gear.
    pub teeth: u32,
    /// Module (mm): the perimeter over `π·teeth`.
    pub module_mm: f64,
    /// The driver (sun and planets) and the driven gear (intermediates), each in its own
    /// frame (the driver's tooth 0 centred at `ψ = 0`; the driven gear's angle 0 meets it).
    pub gears: [ToothedGear; 2],
    pub report: TeethReport,
}

/// One gear's verdicts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GearTeethReport {
    pub name: &'static str,
    /// Teeth with an undercut flank.
    pub undercut_teeth: usize,
    /// Largest flank height lost to undercut (mm).
    pub undercut_lost_height_mm: f64,
    /// Every undercut flank: where and how deep.
    pub undercuts: Vec<Undercut>,
    /// Least tip land (mm).
    pub tip_land_min_mm: f64,
    /// Teeth ending in a point.
    pub pointed_teeth: usize,
    /// Points of the closed outline.
    pub outline_points: usize,
    /// What the mate's tips cut out of the roots the cutter left too shallow.
    pub mate_roots: MateRoots,
}

/// The checks of a toothed pair.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TeethReport {
    pub teeth: u32,
    pub module_mm: f64,
    pub pressure_angle_deg: f64,
    pub centre_distance_mm: f64,
    pub perimeter_mm: f64,
    pub gears: [GearTeethReport; 2],
    pub mesh: MeshReport,
    /// Sum of the normalised shortfalls (0: the teeth pass every check).
    pub violation: f64,
    /// What fails, in words (empty: every check passes).
    pub failures: Vec<String>,
    /// How closely the quantities above are computed.
    pub accuracy: TeethAccuracy,
}

/// How closely a pair's reported quantities are computed, from its settings (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TeethAccuracy {
    /// Largest distance of an outline chord from the generated curve.
    pub chord_mm: f64,
    /// The flank heights (the flank lost to undercut, the contact ratio's active flank):
    /// Newton's last step, in rolling.
    pub flank_height_mm: f64,
    /// The bottom of a gap or overlap between a flank's probes, measured to the curves the
    /// chords stand for.
    pub gap_bottom_mm: f64,
}

impl ToothedPair {
    /// Cuts both gears of the pair of `curve` with `teeth` teeth each (the centre distance
    /// re-closed from `centre_distance_guess`, mm) and runs every check.
    pub fn cut(
        curve: &PitchCurve,
        centre_distance_guess: f64,
        teeth: u32,
        spec: &ToothSpec,
    ) -> Result<Self> {
        spec.validate()?;
        if teeth < 3 {
            return Err(Error::OutOfRange {
                name: "gear.module.teeth".into(),
                value: f64::from(teeth),
                expected: "at least 3 teeth".into(),
            });
        }
        let least_points = 2 * teeth as usize * (spec.flank_samples + spec.fillet_samples);
        if least_points > MAX_OUTLINE_POINTS {
            return Err(Error::OutOfRange {
                name: "gear.teeth.flank_samples".into(),
                value: spec.flank_samples as f64,
                expected: format!(
                    "fewer samples: with gear.teeth.fillet_samples and {teeth} teeth the \
                     outline would have more than {MAX_OUTLINE_POINTS} points"
                ),
            });
        }
        let track = PairTrack::new(curve, centre_distance_guess, spec.arc_panels)?;
        let pitch = track.perimeter() / f64::from(teeth);
        let m = pitch / std::f64::consts::PI;
        check_concave(&track, spec, m, teeth)?;
        let alpha = spec.pressure_angle_deg.to_radians();
        let thick =
            |shift: f64| 0.5 * pitch + 2.0 * shift * m * alpha.tan() - 0.5 * spec.backlash_mm;
        let x = spec.profile_shift;
        for (shift, name) in [(x, "driver"), (-x, "driven")] {
            if thick(shift) <= 0.0 {
                return Err(Error::OutOfRange {
                    name: "gear.teeth.backlash_mm".into(),
                    value: spec.backlash_mm,
                    expected: format!("less than leaves the {name}'s teeth a thickness"),
                });
            }
        }
        let reach = MESH_REACH_MODULES * m + spec.backlash_mm;
        let end = std::f64::consts::FRAC_PI_2 - alpha;
        let n = spec.fillet_samples;
        let fillet_spacing: Vec<f64> = (0..=n)
            .map(|k| (end * k as f64 / n as f64).tan() / end.tan())
            .collect();
        let cut_with =
            |tool: Tool, member, phase: f64, name, chord_tolerance| -> Result<ToothedGear> {
                Cut {
                    track: &track,
                    member,
                    tool,
                    pitch,
                    phase,
                    teeth: teeth as usize,
                    flank_samples: spec.flank_samples,
                    chord_tolerance,
                    module: m,
                    reach,
                    fillet_spacing: fillet_spacing.clone(),
                    name,
                }
                .run()
            };
        let cut = |member, shift: f64, phase: f64, name| {
            cut_with(
                Tool::new(spec, m, shift, thick(shift))?,
                member,
                phase,
                name,
                spec.chord_tolerance_mm,
            )
        };
        let mut gears = [
            cut(Member::Driver, x, 0.0, "driver")?,
            cut(Member::Driven, -x, 0.5 * pitch, "driven")?,
        ];
        let tolerance = spec.check_tolerance_mm();
        let check = |gears: &[ToothedGear; 2], steps_per_pitch: usize| {
            mesh::check(
                &track,
                gears,
                pitch,
                reach,
                alpha.sin_cos(),
                steps_per_pitch,
                tolerance,
            )
        };
        let mut checked = check(&gears, spec.mesh_steps_per_pitch);
        let mut mate_roots = [MateRoots::default(); 2];
        // What stopped the mate-generated roots, if anything did (the pair is then reported
        // with the roots as far as they were cut).
        let mut mate_failure = None;
        // With no bottom clearance asked for (dedendum ≤ addendum) the mate's tips are meant
        // to reach the root: there is nothing to generate.
        if spec.mate_roots
            && spec.dedendum > spec.addendum
            && checked.overlaps.iter().any(|o| !o.is_empty())
        {
            // Each gear cut as a shaper for its mate's roots: its tips raised by the bottom
            // clearance (the tool's dedendum for its addendum), its flanks set back by a
            // margin so that they do not cut the flanks they are conjugate to.
            let as_shaper = ToothSpec {
                addendum: spec.dedendum,
                ..*spec
            };
            let margin = MATE_MARGIN * tolerance;
            // The mate's flanks and tips, as they cut, and the paths they sweep, within
            // the verdict's tolerance (finer if the scene's chords are): material a
            // coarser cut leaves in the roots overlaps the real tips by up to its
            // tolerance. (Half of it cost the failing pair's advice four times as
            // long, 12.5 s against 3.4 s, and changed none of its verdicts.)
            let mate_tolerance = tolerance.max(mate_roots::SWEEP_TOLERANCE_FLOOR_MM);
            let shaper = |g: usize| {
                let (member, shift, phase, name) = if g == 0 {
                    (Member::Driven, -x, 0.5 * pitch, "driven")
                } else {
                    (Member::Driver, x, 0.0, "driver")
                };
                let thinner = thick(shift) - 2.0 * margin / alpha.cos();
                cut_with(
                    Tool::new(&as_shaper, m, shift, thinner)?,
                    member,
                    phase,
                    name,
                    mate_tolerance,
                )
            };
            let mate_cut = mate_roots::MateCut {
                track: &track,
                pitch,
                module: m,
                clearance: (spec.dedendum - spec.addendum) * m,
                depth: (spec.dedendum + spec.addendum + 1.0) * m,
                tolerance: mate_tolerance,
            };
            // The roots the mate cuts leave overlaps shorter than a step (by a concave arc,
            // a few micrometres that the default steps missed on the crazy heart): the
            // rounds of cut and check, and the verdict, check these pairs more finely, at
            // a small share of what the cut costs.
            let fine_steps = MATE_CHECK_STEPS * spec.mesh_steps_per_pitch;
            let mut cutters: [Option<ToothedGear>; 2] = [None, None];
            let mut done: [Vec<usize>; 2] = Default::default();
            // A cut can bring the next deepest overlaps to light (the check searches the
            // deepest few between its steps): a few rounds.
            'rounds: for _ in 0..MATE_ROUNDS {
                let overlaps = std::mem::take(&mut checked.overlaps);
                let before = done.clone();
                for (g, overlaps) in overlaps.iter().enumerate() {
                    if overlaps.is_empty() {
                        continue;
                    }
                    let outcome = match &cutters[g] {
                        Some(cutter) => Ok(cutter),
                        None => shaper(g).map(|c| &*cutters[g].insert(c)),
                    }
                    .and_then(|cutter| {
                        mate_cut.cut(
                            &mut gears,
                            g,
                            cutter,
                            overlaps,
                            &mut done[g],
                            &mut mate_roots[g],
                        )
                    });
                    if let Err(e) = outcome {
                        mate_failure = Some(e.to_string());
                        checked = check(&gears, fine_steps);
                        break 'rounds;
                    }
                }
                checked = check(&gears, fine_steps);
                if done == before {
                    break;
                }
            }
        }
        let mesh = checked.report;
        let report = verdict(
            &track,
            &gears,
            &mesh,
            (&mate_roots, mate_failure.as_deref()),
            spec,
            teeth,
            m,
        );
        Ok(Self {
            track,
            spec: *spec,
            teeth,
            module_mm: m,
            gears,
            report,
        })
    }
}

/// A concave pitch arc cannot be cut by a rack (its straight pitch line would cut into the
/// arc's neighbours), only by a shaper whose pitch radius is below the arc's least radius
/// of curvature (spec §1.4). The error names the tooth nearest the arc's sharpest point
/// (the driver's tooth `j` is centred at pitch arc `j·p`, the driven gear's at `(j + ½)·p`).
fn check_concave(track: &PairTrack, spec: &ToothSpec, m: f64, teeth: u32) -> Result<()> {
    let pitch = track.perimeter() / f64::from(teeth);
    for (member, name, phase) in [
        (Member::Driver, "driver", 0.0),
        (Member::Driven, "driven", 0.5),
    ] {
        let (least, at) = track.least_curvature(member);
        if least >= 0.0 {
            continue;
        }
        let radius = -1.0 / least;
        let fits = match spec.cutter {
            Cutter::Rack => false,
            Cutter::Shaper { teeth } => 0.5 * m * f64::from(teeth) < radius,
        };
        if !fits {
            let largest = (2.0 * radius / m).ceil() as u32 - 1;
            let arc = track.arc(at);
            let tooth = ((arc / pitch - phase).round() as i64).rem_euclid(i64::from(teeth));
            return Err(Error::Teeth {
                gear: name,
                tooth: tooth as usize,
                arc_mm: arc,
                why: format!(
                    "the pitch curve is concave here with |R| = {radius:.3} mm: {}; {}",
                    match spec.cutter {
                        Cutter::Rack => "a rack cannot cut a concave arc".to_string(),
                        Cutter::Shaper { teeth } =>
                            format!("the {teeth}-tooth shaper is too large"),
                    },
                    if largest >= 6 {
                        format!(
                            "only a shaper of at most {largest} teeth fits in it (its pitch \
                             radius must stay below |R| at module {m:.4} mm)"
                        )
                    } else {
                        format!("no shaper of 6 teeth or more fits in it at module {m:.4} mm")
                    }
                ),
            });
        }
    }
    Ok(())
}

fn verdict(
    track: &PairTrack,
    gears: &[ToothedGear; 2],
    mesh: &MeshReport,
    (mate_roots, mate_failure): (&[MateRoots; 2], Option<&str>),
    spec: &ToothSpec,
    teeth: u32,
    m: f64,
) -> TeethReport {
    let gear_report = |g: &ToothedGear, name: &'static str, mate_roots: MateRoots| {
        let undercuts: Vec<Undercut> = g
            .teeth
            .iter()
            .flat_map(|t| t.undercut.iter().flatten().copied())
            .collect();
        GearTeethReport {
            name,
            undercut_teeth: g
                .teeth
                .iter()
                .filter(|t| t.undercut.iter().any(Option::is_some))
                .count(),
            undercut_lost_height_mm: undercuts.iter().fold(0.0, |a, u| a.max(u.lost_height_mm)),
            undercuts,
            tip_land_min_mm: g
                .teeth
                .iter()
                .fold(f64::INFINITY, |a, t| a.min(t.tip_land_mm)),
            pointed_teeth: g.teeth.iter().filter(|t| t.pointed).count(),
            outline_points: g.outline().len(),
            mate_roots,
        }
    };
    let reports = [
        gear_report(&gears[0], "driver", mate_roots[0]),
        gear_report(&gears[1], "driven", mate_roots[1]),
    ];
    let mut violation = 0.0;
    let mut failures = Vec::new();
    for r in &reports {
        if !spec.allow_undercut && r.undercut_teeth > 0 {
            violation += r.undercut_lost_height_mm / m;
            failures.push(format!(
                "{}: {} teeth undercut, up to {:.4} mm of flank lost",
                r.name, r.undercut_teeth, r.undercut_lost_height_mm
            ));
        }
        let least_land = spec.min_tip_land * m;
        if r.tip_land_min_mm < least_land {
            violation += (least_land - r.tip_land_min_mm) / m;
            failures.push(format!(
                "{}: tip land {:.4} mm (least {:.4} mm){}",
                r.name,
                r.tip_land_min_mm,
                least_land,
                if r.pointed_teeth > 0 {
                    format!(", {} pointed teeth", r.pointed_teeth)
                } else {
                    String::new()
                }
            ));
        }
    }
    if mesh.least_clearance_mm < -OVERLAP_TOLERANCE_MM {
        violation += (-mesh.least_clearance_mm - OVERLAP_TOLERANCE_MM) / m;
        // Near a concave arc the mate's tips, rolling on the mate's own pitch curve rather
        // than on a shaper's pitch circle, reach deeper into the root than the shaper cut.
        let pitch = track.perimeter() / f64::from(teeth);
        let concave_near = (-6..=6).any(|k| {
            let psi = track.psi_at(mesh.least_clearance_at_mm + f64::from(k) * 0.25 * pitch);
            [Member::Driver, Member::Driven]
                .into_iter()
                .any(|member| track.frame(member, psi).curvature < 0.0)
        });
        failures.push(format!(
            "the teeth overlap by {:.4} mm at pitch arc {:.3} mm{}",
            -mesh.least_clearance_mm,
            mesh.least_clearance_at_mm,
            if concave_near {
                ", by a concave arc: the mate's tips reach deeper into the root than the \
                 cutter did"
            } else {
                ""
            }
        ));
    }
    if let Some(why) = mate_failure {
        failures.push(format!(
            "the roots could not be cut by the mate's tips: {why}"
        ));
    }
    if mesh.contact_ratio_min < 1.0 {
        violation += 1.0 - mesh.contact_ratio_min;
        failures.push(format!(
            "contact ratio {:.3} < 1 at pitch arc {:.3} mm: the transmission is not continuous",
            mesh.contact_ratio_min, mesh.contact_ratio_min_at_mm
        ));
    }
    TeethReport {
        teeth,
        module_mm: m,
        pressure_angle_deg: spec.pressure_angle_deg,
        centre_distance_mm: track.centre_distance(),
        perimeter_mm: track.perimeter(),
        gears: reports,
        mesh: *mesh,
        violation,
        failures,
        accuracy: TeethAccuracy {
            chord_mm: spec.chord_tolerance_mm,
            flank_height_mm: profile::NEWTON_STEP_PITCHES * track.perimeter() / f64::from(teeth),
            gap_bottom_mm: mesh::BOTTOM_PRECISION * spec.check_tolerance_mm(),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::CurveSpec;

    /// A pair whose roots the mate cut is judged alike by a check four times as fine as
    /// the one its verdict used: on the Fourier curve (30 teeth) and the crazy
    /// heart (64 teeth), both cut by a 40-tooth shaper, the verdict's check (at
    /// [`MATE_CHECK_STEPS`] times the scene's steps) finds no overlap beyond 1 µm, and
    /// neither does the finer one. (At the scene's own steps the heart's verdict missed an
    /// overlap of 3.6 µm that lasted less than a step.)
    #[test]
    fn a_finer_mesh_check_finds_no_overlap_the_verdicts_check_missed() {
        let fourier = |cos: Vec<f64>, sin: Vec<f64>| {
            CurveSpec::Fourier {
                c0_mm: 30.0,
                cos_mm: cos,
                sin_mm: sin,
            }
            .build()
            .unwrap()
        };
        let spec = ToothSpec {
            cutter: Cutter::Shaper { teeth: 40 },
            ..ToothSpec::default()
        };
        for (name, curve, teeth) in [
            ("issue", fourier(vec![6.0, 0.0, -2.0], vec![0.0, 3.0]), 30),
            (
                "heart",
                fourier(vec![0.0, 4.5, 0.0], vec![-6.6, 0.0, 0.75]),
                64,
            ),
        ] {
            let pair = ToothedPair::cut(&curve, 60.0, teeth, &spec).unwrap();
            let pitch = pair.track.perimeter() / f64::from(teeth);
            let reach = MESH_REACH_MODULES * pair.module_mm + spec.backlash_mm;
            let sin_cos = spec.pressure_angle_deg.to_radians().sin_cos();
            let default = pair.report.mesh.least_clearance_mm;
            let fine = mesh::check(
                &pair.track,
                &pair.gears,
                pitch,
                reach,
                sin_cos,
                4 * MATE_CHECK_STEPS * spec.mesh_steps_per_pitch,
                spec.check_tolerance_mm(),
            )
            .report;
            println!(
                "{name}: fine at {} default at {} undercut {:?}",
                fine.least_clearance_at_mm,
                pair.report.mesh.least_clearance_at_mm,
                pair.report
                    .gears
                    .iter()
                    .map(|g| g
                        .undercuts
                        .iter()
                        .map(|u| u.pitch_arc_mm)
                        .collect::<Vec<_>>())
                    .collect::<Vec<_>>()
            );
            let fine = fine.least_clearance_mm;
            println!("{name}: least clearance {default:e} by default, {fine:e} four times as fine");
            assert!(default >= -OVERLAP_TOLERANCE_MM, "{name}: {default}");
            assert!(fine >= -OVERLAP_TOLERANCE_MM, "{name}: {fine}");
        }
    }
}
