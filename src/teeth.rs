//! Teeth for a scene: its toothed pair, the train (or the pair) assembled at a carrier
//! angle, and the manufacturing exports.

use noncirc_core::{
    Cutter, GearPair, Kinematics, Member, ModuleReading, PairTrack, PitchCurve, Scene, SceneKind,
    TeethReport, ToothSpec, ToothedPair, Vec2,
};
use serde::Serialize;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::cad;
use crate::files::{create_dir, write_file};
use crate::Result;

/// One gear of the assembly: which toothed gear, where its centre is, how it is turned.
#[derive(Debug, Clone, Serialize)]
pub struct PlacedGear {
    /// `sun`, `intermediate_1`, `planet_1`, … (`driver`, `driven` for a gear pair).
    pub name: String,
    #[serde(skip)]
    pub member: Member,
    pub centre_mm: Vec2,
    /// Turn of the gear's own frame in the drawing (degrees).
    pub angle_deg: f64,
}

/// A scene's teeth and their assembly.
#[derive(Debug, Clone)]
pub struct TeethRun {
    pub pair: ToothedPair,
    /// Where the tooth count came from.
    pub count_from: &'static str,
    /// Carrier angle of the assembly (degrees; `None` for a gear pair).
    pub carrier_deg: Option<f64>,
    pub layout: Vec<PlacedGear>,
}

/// What `noncirc teeth` reports.
#[derive(Debug, Clone, Serialize)]
pub struct TeethSummary<'a> {
    pub count_from: &'static str,
    pub carrier_deg: Option<f64>,
    pub checks: &'a TeethReport,
    pub layout: &'a [PlacedGear],
    /// Other settings tried when a check fails ([`Advice::for_scene`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub advice: Option<Advice>,
}

impl TeethRun {
    /// Cuts the scene's gears (`gear.module.teeth`, or the module rule's tooth count) and
    /// assembles them at carrier angle `carrier_deg` (three-arm scenes).
    pub fn from_scene(scene: &Scene, carrier_deg: f64) -> Result<Self> {
        let Prepared {
            curve,
            centre_distance,
            teeth,
            count_from,
            kin,
        } = Prepared::from_scene(scene)?;
        let train = kin.is_some();
        let toothed = ToothedPair::cut(&curve, centre_distance, teeth, &scene.gear.teeth)?;
        let a = toothed.track.centre_distance();
        let layout = match &kin {
            None => vec![
                PlacedGear {
                    name: "driver".into(),
                    member: Member::Driver,
                    centre_mm: Vec2::ZERO,
                    angle_deg: 0.0,
                },
                PlacedGear {
                    name: "driven".into(),
                    member: Member::Driven,
                    centre_mm: Vec2::new(a, 0.0),
                    angle_deg: 180.0,
                },
            ],
            Some(kin) => train_layout(kin, &toothed, carrier_deg.to_radians()),
        };
        Ok(Self {
            pair: toothed,
            count_from,
            carrier_deg: train.then_some(carrier_deg),
            layout,
        })
    }

    /// The failed checks counted in words ("1 check", "3 checks"), as the CLI and the
    /// studio say why they do not export.
    pub fn failed_checks(&self) -> String {
        let n = self.pair.report.failures.len();
        format!("{n} check{}", if n == 1 { "" } else { "s" })
    }

    pub fn summary(&self) -> TeethSummary<'_> {
        TeethSummary {
            count_from: self.count_from,
            carrier_deg: self.carrier_deg,
            checks: &self.pair.report,
            layout: &self.layout,
            advice: None,
        }
    }

    /// A table for people.
    pub fn table(&self) -> String {
        let r = &self.pair.report;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "teeth per gear      {} (from {})",
            r.teeth, self.count_from
        );
        let _ = writeln!(s, "module              {:.4} mm", r.module_mm);
        let _ = writeln!(s, "pressure angle      {:.1}°", r.pressure_angle_deg);
        let _ = writeln!(s, "centre distance     {:.6} mm", r.centre_distance_mm);
        let _ = writeln!(s, "pitch perimeter     {:.6} mm", r.perimeter_mm);
        for g in &r.gears {
            let _ = writeln!(
                s,
                "{:<7} undercut teeth {:>4} (flank lost up to {:.4} mm), least tip land {:.4} mm, pointed {}, {} outline points",
                g.name, g.undercut_teeth, g.undercut_lost_height_mm, g.tip_land_min_mm, g.pointed_teeth, g.outline_points
            );
            let cut = g.mate_roots;
            if cut.spaces > 0 {
                let _ = writeln!(
                    s,
                    "{:<7} roots cut by the mate's tips in {} tooth spaces (the cutter's left them overlapped), up to {:.4} mm deeper",
                    g.name, cut.spaces, cut.deepest_mm
                );
            }
        }
        let m = &r.mesh;
        let _ = writeln!(
            s,
            "mesh over one turn  {} positions: least clearance {} mm (at pitch arc {:.3} mm)",
            m.positions,
            tenth_micrometres(m.least_clearance_mm),
            m.least_clearance_at_mm
        );
        if let Some((lo, hi)) = m.backlash_mm {
            let (lo, hi) = (tenth_micrometres(lo), tenth_micrometres(hi));
            let _ = writeln!(s, "normal backlash     {lo} … {hi} mm");
        }
        let _ = writeln!(
            s,
            "contact ratio       least {:.3} (at pitch arc {:.3} mm), mean {:.3}",
            m.contact_ratio_min, m.contact_ratio_min_at_mm, m.contact_ratio_mean
        );
        let a = r.accuracy;
        let _ = writeln!(
            s,
            "accuracy            outline chords within {:.2} µm of the generated curves; flank lost \
             and contact ratio from flank heights to {:.0e} µm (Newton); clearance and backlash \
             measured to the curves, between probes to {:.2} µm",
            a.chord_mm * 1e3,
            a.flank_height_mm * 1e3,
            a.gap_bottom_mm * 1e3
        );
        if r.failures.is_empty() {
            let _ = writeln!(s, "verdict             every check passes");
        } else {
            for f in &r.failures {
                let _ = writeln!(s, "FAILS               {f}");
            }
        }
        s
    }

    /// Writes `driver.dxf`/`driven.dxf` (each gear in its own frame), `train.dxf` and
    /// `train.svg` (the assembly), `driver.csv`/`driven.csv` (every outline point) and
    /// `pitch_driver.csv` (the pitch curve to `tolerance_mm` of chord), into `dir`.
    pub fn export(&self, dir: &Path, tolerance_mm: f64) -> Result<Vec<PathBuf>> {
        create_dir(dir)?;
        let mut paths = Vec::new();
        for (name, text) in self.files(tolerance_mm) {
            let path = dir.join(name);
            write_file(&path, text.as_bytes())?;
            paths.push(path);
        }
        Ok(paths)
    }

    /// The files [`Self::export`] writes, as `(name, contents)`, for front ends without a
    /// file system (the studio downloads them).
    pub fn files(&self, tolerance_mm: f64) -> Vec<(&'static str, String)> {
        let gears = &self.pair.gears;
        let fitted: Vec<Vec<cad::Piece>> = gears
            .iter()
            .map(|g| cad::fit(g.outline(), &g.corners, tolerance_mm))
            .collect();
        let mark = 0.5 * self.pair.module_mm;
        let mut files = Vec::new();
        for (k, name) in ["driver", "driven"].iter().enumerate() {
            let own = [cad::Placed {
                layer: &name.to_uppercase(),
                pieces: &fitted[k],
                centre: Vec2::ZERO,
                angle: 0.0,
            }];
            files.push((
                ["driver.dxf", "driven.dxf"][k],
                cad::dxf(&own, &[Vec2::ZERO], mark, &[]),
            ));
            let mut csv = String::from("x_mm,y_mm\n");
            for p in gears[k].outline() {
                let _ = writeln!(csv, "{:.9},{:.9}", p.x, p.y);
            }
            files.push((["driver.csv", "driven.csv"][k], csv));
        }
        let layers: Vec<String> = self.layout.iter().map(|g| g.name.to_uppercase()).collect();
        let placed: Vec<cad::Placed> = self
            .layout
            .iter()
            .zip(&layers)
            .map(|(g, layer)| cad::Placed {
                layer,
                pieces: &fitted[usize::from(g.member == Member::Driven)],
                centre: g.centre_mm,
                angle: g.angle_deg.to_radians(),
            })
            .collect();
        let marks: Vec<Vec2> = self.layout.iter().map(|g| g.centre_mm).collect();
        files.push(("train.dxf", cad::dxf(&placed, &marks, mark, &[])));
        files.push(("train.svg", cad::svg(&placed, &marks)));
        let mut csv = String::from("x_mm,y_mm\n");
        let [pitch, _] = crate::export::pitch_points(&self.pair.track, 0.0, tolerance_mm);
        for p in pitch {
            let _ = writeln!(csv, "{:.9},{:.9}", p.x, p.y);
        }
        files.push(("pitch_driver.csv", csv));
        files
    }

    /// Lines and arcs per gear at `tolerance_mm`, and the raw point counts.
    pub fn entity_counts(&self, tolerance_mm: f64) -> [(usize, usize); 2] {
        [0, 1].map(|k| {
            let g = &self.pair.gears[k];
            (
                cad::fit(g.outline(), &g.corners, tolerance_mm).len(),
                g.outline().len(),
            )
        })
    }
}

/// What cutting a scene's teeth starts from: the sun's pitch curve, the centre distance,
/// the tooth count and where it came from, and the train's kinematics (three-arm scenes).
struct Prepared {
    curve: PitchCurve,
    centre_distance: f64,
    teeth: u32,
    count_from: &'static str,
    kin: Option<Kinematics>,
}

impl Prepared {
    fn from_scene(scene: &Scene) -> Result<Self> {
        scene.validate()?;
        if scene.gear.second_curve.is_some() {
            // The evaluation's teeth stage (module rule `teeth`) cuts and checks both pairs;
            // the assembly, its files and the studio's teeth take one pair so far.
            return Err(noncirc_core::Error::BadList {
                list: "gear.second_curve",
                problem: "the teeth command assembles and exports the paper's train (one \
                          pair) so far; for a train with two pairs, the module objective \
                          under gear.module.rule = \"teeth\" cuts and checks both pairs' \
                          teeth (noncirc evaluate), and noncirc evaluate --plot DIR exports \
                          both pairs' pitch curves"
                    .into(),
            }
            .into());
        }
        let curve = scene.gear.curve.build()?;
        let rule = &scene.gear.module;
        let train = matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter);
        let kin = if train {
            Some(scene.kinematics(&scene.resolution)?)
        } else {
            None
        };
        let solved;
        let pair: &GearPair = match &kin {
            Some(k) => k.pair(),
            None => {
                solved = GearPair::solve(curve.clone(), scene.resolution)?;
                &solved
            }
        };
        let (teeth, count_from) = match rule.teeth {
            Some(z) => (z, "gear.module.teeth"),
            None => {
                let m = pair.module(rule);
                if m.teeth == 0 {
                    return Err(noncirc_core::Error::Infeasible(
                        "no tooth count: the module rule admits no module for this curve; set gear.module.teeth".into(),
                    )
                    .into());
                }
                (
                    m.teeth,
                    match rule.rule {
                        ModuleReading::Undercut => {
                            "the largest undercut-free module (gear.module.rule = \"undercut\")"
                        }
                        _ => "gear.module.teeth",
                    },
                )
            }
        };
        let centre_distance = pair.centre_distance();
        Ok(Self {
            curve,
            centre_distance,
            teeth,
            count_from,
            kin,
        })
    }
}

/// Other cutters, tip roundings and root depths tried on a scene whose teeth fail, each
/// with what it gave: advice that has been tried.
#[derive(Debug, Clone, Serialize)]
pub struct Advice {
    /// Every setting tried, the scene's own first changed least.
    pub tried: Vec<Trial>,
    /// The first trial that passes every check, if one does.
    pub passes: Option<usize>,
}

/// One setting tried: its `--set` assignments and its verdict.
#[derive(Debug, Clone, Serialize)]
pub struct Trial {
    pub set: Vec<String>,
    /// Empty if every check passes; the refusal or the failed checks otherwise.
    pub failures: Vec<String>,
}

impl Advice {
    /// Tries the cutters that fit the pitch curve's concave arcs (a shaper's pitch radius
    /// below their least radius of curvature; the rack and shapers of 40, 20 and 12 teeth
    /// if it has none), tip roundings of 0.25 and 0.1 m and a root 0.25 m deeper, alone and
    /// together: up to 41 cuts of a millisecond or a few (23 with a rack on a convex curve).
    pub fn for_scene(scene: &Scene) -> Result<Self> {
        let p = Prepared::from_scene(scene)?;
        let spec = scene.gear.teeth;
        let track = PairTrack::new(&p.curve, p.centre_distance, spec.arc_panels)?;
        let m = track.perimeter() / (PI * f64::from(p.teeth));
        let least = [Member::Driver, Member::Driven]
            .map(|member| track.least_curvature(member).0)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let mut cutters: Vec<Cutter> = if least < 0.0 {
            // At most 200 teeth: a nearly straight concave arc admits any shaper.
            let largest = ((2.0 / (-least * m)).ceil() - 1.0).min(200.0) as u32;
            [largest, 3 * largest / 4, largest / 2, 12, 8, 6]
                .into_iter()
                .filter(|&z| (6..=largest).contains(&z))
                .map(|teeth| Cutter::Shaper { teeth })
                .collect()
        } else {
            [0, 40, 20, 12]
                .into_iter()
                .map(|teeth| match teeth {
                    0 => Cutter::Rack,
                    _ => Cutter::Shaper { teeth },
                })
                .collect()
        };
        cutters.sort_by_key(|c| match c {
            Cutter::Rack => u32::MAX,
            Cutter::Shaper { teeth } => *teeth,
        });
        cutters.reverse();
        cutters.dedup();
        cutters.retain(|c| *c != spec.cutter);
        let tips: Vec<f64> = [0.25, 0.1]
            .into_iter()
            .filter(|&r| r != spec.tip_radius)
            .collect();
        let deeper = spec.dedendum + 0.25;
        let set_cutter = |c: &Cutter| match c {
            Cutter::Rack => "gear.teeth.cutter={kind=\"rack\"}".to_string(),
            Cutter::Shaper { teeth } => {
                format!("gear.teeth.cutter={{kind=\"shaper\",teeth={teeth}}}")
            }
        };
        let cutter_options: Vec<Option<&Cutter>> = std::iter::once(None)
            .chain(cutters.iter().map(Some))
            .collect();
        let tip_options: Vec<Option<f64>> = std::iter::once(None)
            .chain(tips.iter().copied().map(Some))
            .collect();
        // Every combination but the scene's own, the fewest changes first (a stable sort
        // keeps cutters before tip roundings before the root within a count).
        let mut trials: Vec<(ToothSpec, Vec<String>)> = Vec::new();
        for &cutter in &cutter_options {
            for &tip in &tip_options {
                for deepen in [false, true] {
                    let mut s = spec;
                    let mut set = Vec::new();
                    if let Some(c) = cutter {
                        s.cutter = *c;
                        set.push(set_cutter(c));
                    }
                    if let Some(r) = tip {
                        s.tip_radius = r;
                        set.push(format!("gear.teeth.tip_radius={r}"));
                    }
                    if deepen {
                        s.dedendum = deeper;
                        set.push(format!("gear.teeth.dedendum={deeper}"));
                    }
                    if !set.is_empty() {
                        trials.push((s, set));
                    }
                }
            }
        }
        trials.sort_by_key(|(_, set)| set.len());
        let tried: Vec<Trial> = trials
            .into_iter()
            .map(|(s, set)| Trial {
                set,
                failures: match ToothedPair::cut(&p.curve, p.centre_distance, p.teeth, &s) {
                    Ok(pair) => pair.report.failures,
                    Err(e) => vec![e.to_string()],
                },
            })
            .collect();
        let passes = tried.iter().position(|t| t.failures.is_empty());
        Ok(Self { tried, passes })
    }

    /// The advice in words, one line; a setting that passes as `--set` options quoted for a
    /// shell.
    pub fn line(&self) -> String {
        match self.passes {
            Some(k) => format!(
                "tried {} other settings; this one passes every check: {}",
                self.tried.len(),
                self.tried[k]
                    .set
                    .iter()
                    .map(|a| format!("--set '{a}'"))
                    .collect::<Vec<_>>()
                    .join(" ")
            ),
            None => format!(
                "tried {} other settings (other cutters that fit, other tip roundings, a \
                 deeper root, alone and together): none passes every check",
                self.tried.len()
            ),
        }
    }
}

/// Every gear of the planetary train at carrier angle `theta` (rad): the sun turned by its
/// installation angle; each intermediate turned so that its point meeting the sun's `ψ`
/// faces the sun; each planet at the kinematics' orientation (its frame is the sun's).
/// Arm set `k` stands where arm I stood at `theta − k·360°/arms`, as everywhere else.
pub fn train_layout(kin: &Kinematics, toothed: &ToothedPair, theta: f64) -> Vec<PlacedGear> {
    let sun_angle = kin.spec().sun_angle();
    let mut layout = vec![PlacedGear {
        name: "sun".into(),
        member: Member::Driver,
        centre_mm: Vec2::ZERO,
        angle_deg: sun_angle.to_degrees(),
    }];
    for k in 0..kin.arms() {
        let st = kin.state_at(theta - kin.arm_lag(k));
        let towards_sun = (-st.o2.y).atan2(-st.o2.x);
        let psi = towards_sun + PI - sun_angle;
        let chi = toothed.track.driven_angle(psi);
        layout.push(PlacedGear {
            name: format!("intermediate_{}", k + 1),
            member: Member::Driven,
            centre_mm: st.o2,
            angle_deg: (towards_sun - chi).to_degrees(),
        });
        layout.push(PlacedGear {
            name: format!("planet_{}", k + 1),
            member: Member::Driver,
            centre_mm: st.o3,
            angle_deg: st.theta3.to_degrees(),
        });
    }
    layout
}

/// `mm` to four decimals (a tenth of a micrometre), without a sign where that rounds to
/// zero: the mesh check measures contacts to a fraction of that, either side of zero.
pub(crate) fn tenth_micrometres(mm: f64) -> String {
    let text = format!("{mm:.4}");
    if text == "-0.0000" {
        "0.0000".into()
    } else {
        text
    }
}
