//! Teeth for a scene: its toothed pair (both pairs of a train with two), the train (or the
//! pair) assembled at a carrier angle, and the manufacturing exports.

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
    /// `sun`, `intermediate_1`, `planet_1`, … (`driver`, `driven` for a gear pair); with two
    /// pairs also `intermediate_1_b`, … (the intermediates' layer B).
    pub name: String,
    #[serde(skip)]
    pub member: Member,
    /// The pair it is cut in: 0 the sun–intermediate pair, 1 the second pair (layer B and
    /// the planet) of a train with two.
    #[serde(skip)]
    pub pair: usize,
    pub centre_mm: Vec2,
    /// Turn of the gear's own frame in the drawing (degrees).
    pub angle_deg: f64,
}

/// A scene's teeth and their assembly.
#[derive(Debug, Clone)]
pub struct TeethRun {
    pub pair: ToothedPair,
    /// The train with two pairs: layer B and the planet, cut with the same tooth count.
    pub second: Option<ToothedPair>,
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
    /// The train with two pairs: the second pair's checks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub second_checks: Option<&'a TeethReport>,
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
        let second = match kin.as_ref().and_then(Kinematics::second_pair) {
            Some(p) => Some(
                ToothedPair::cut(p.curve(), p.centre_distance(), teeth, &scene.gear.teeth)
                    .map_err(|e| noncirc_core::Error::SecondPair(Box::new(e)))?,
            ),
            None => None,
        };
        let a = toothed.track.centre_distance();
        let layout = match &kin {
            None => vec![
                PlacedGear {
                    name: "driver".into(),
                    member: Member::Driver,
                    pair: 0,
                    centre_mm: Vec2::ZERO,
                    angle_deg: 0.0,
                },
                PlacedGear {
                    name: "driven".into(),
                    member: Member::Driven,
                    pair: 0,
                    centre_mm: Vec2::new(a, 0.0),
                    angle_deg: 180.0,
                },
            ],
            Some(kin) => train_layout(kin, &toothed, second.as_ref(), carrier_deg.to_radians()),
        };
        Ok(Self {
            pair: toothed,
            second,
            count_from,
            carrier_deg: train.then_some(carrier_deg),
            layout,
        })
    }

    /// The toothed pairs: the sun–intermediate pair, then the second pair of a train with
    /// two.
    pub fn pairs(&self) -> impl Iterator<Item = &ToothedPair> {
        std::iter::once(&self.pair).chain(self.second.as_ref())
    }

    /// The outline (in its own frame) of a gear of the layout.
    pub fn outline(&self, g: &PlacedGear) -> &[Vec2] {
        let pair = match (g.pair, &self.second) {
            (1, Some(second)) => second,
            _ => &self.pair,
        };
        pair.gears[usize::from(g.member == Member::Driven)].outline()
    }

    /// Every failed check, the second pair's named as its own.
    pub fn failures(&self) -> Vec<String> {
        let second = (self.second.iter()).flat_map(|p| {
            p.report
                .failures
                .iter()
                .map(|f| format!("second pair: {f}"))
        });
        self.pair
            .report
            .failures
            .iter()
            .cloned()
            .chain(second)
            .collect()
    }

    /// The failed checks counted in words ("1 check", "3 checks"), as the CLI and the
    /// studio say why they do not export.
    pub fn failed_checks(&self) -> String {
        let n = self.failures().len();
        format!("{n} check{}", if n == 1 { "" } else { "s" })
    }

    pub fn summary(&self) -> TeethSummary<'_> {
        TeethSummary {
            count_from: self.count_from,
            carrier_deg: self.carrier_deg,
            checks: &self.pair.report,
            second_checks: self.second.as_ref().map(|p| &p.report),
            layout: &self.layout,
            advice: None,
        }
    }

    /// A table for people: the pair's (or each pair's) checks.
    pub fn table(&self) -> String {
        let mut s = pair_table(&self.pair.report, self.count_from);
        if let Some(second) = &self.second {
            s += "\nthe second pair: the intermediates' layer B and the planets\n";
            s += &pair_table(&second.report, self.count_from);
        }
        s
    }

    /// Writes `driver.dxf`/`driven.dxf` (each gear in its own frame; with two pairs also
    /// `second_driver.*` for the intermediates' layer B and `second_driven.*` for the
    /// planets), `train.dxf` and `train.svg` (the assembly), `driver.csv`/`driven.csv`
    /// (every outline point) and `pitch_driver.csv` (the pitch curve to `tolerance_mm` of
    /// chord), into `dir`.
    pub fn export(&self, dir: &Path, tolerance_mm: f64) -> Result<Vec<PathBuf>> {
        cad::check_tolerance("tolerance_mm", tolerance_mm)?;
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
        // Gear k of pair p is fitted[2p + k].
        let gears: Vec<_> = self.pairs().flat_map(|p| p.gears.iter()).collect();
        let fitted: Vec<Vec<cad::Piece>> = gears
            .iter()
            .map(|g| cad::fit(g.outline(), &g.corners, tolerance_mm))
            .collect();
        let mark = 0.5 * self.pair.module_mm;
        let mut files = Vec::new();
        const NAMES: [[&str; 3]; 4] = [
            ["DRIVER", "driver.dxf", "driver.csv"],
            ["DRIVEN", "driven.dxf", "driven.csv"],
            ["SECOND_DRIVER", "second_driver.dxf", "second_driver.csv"],
            ["SECOND_DRIVEN", "second_driven.dxf", "second_driven.csv"],
        ];
        for (k, [layer, dxf, csv_name]) in NAMES.iter().enumerate().take(gears.len()) {
            let own = [cad::Placed {
                layer,
                pieces: &fitted[k],
                centre: Vec2::ZERO,
                angle: 0.0,
            }];
            files.push((*dxf, cad::dxf(&own, &[Vec2::ZERO], mark, &[])));
            let mut csv = String::from("x_mm,y_mm\n");
            for p in gears[k].outline() {
                let _ = writeln!(csv, "{:.9},{:.9}", p.x, p.y);
            }
            files.push((*csv_name, csv));
        }
        let layers: Vec<String> = self.layout.iter().map(|g| g.name.to_uppercase()).collect();
        let placed: Vec<cad::Placed> = self
            .layout
            .iter()
            .zip(&layers)
            .map(|(g, layer)| cad::Placed {
                layer,
                pieces: &fitted[2 * g.pair + usize::from(g.member == Member::Driven)],
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

    /// Lines and arcs per gear of the sun–intermediate pair at `tolerance_mm`, and the raw
    /// point counts.
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
                // A train's module is its limiting pair's (both pairs take its count).
                let m = kin
                    .as_ref()
                    .map_or_else(|| pair.module(rule), |k| k.module(rule));
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
    /// Tries the cutters that fit the pitch curves' concave arcs (a shaper's pitch radius
    /// below their least radius of curvature; the rack and shapers of 40, 20 and 12 teeth
    /// if they have none), tip roundings of 0.25 and 0.1 m and a root 0.25 m deeper, alone
    /// and together: up to 41 cuts of a millisecond or a few (23 with a rack on a convex
    /// curve), of both pairs for a train with two.
    pub fn for_scene(scene: &Scene) -> Result<Self> {
        let p = Prepared::from_scene(scene)?;
        let spec = scene.gear.teeth;
        let second = (p.kin.as_ref())
            .and_then(Kinematics::second_pair)
            .map(|pair| (pair.curve().clone(), pair.centre_distance()));
        let pairs: Vec<(&PitchCurve, f64)> = std::iter::once((&p.curve, p.centre_distance))
            .chain(second.iter().map(|(c, a)| (c, *a)))
            .collect();
        let mut m = 0.0f64;
        let mut least = f64::INFINITY;
        for &(curve, a) in &pairs {
            let track = PairTrack::new(curve, a, spec.arc_panels)?;
            m = m.max(track.perimeter() / (PI * f64::from(p.teeth)));
            for member in [Member::Driver, Member::Driven] {
                least = least.min(track.least_curvature(member).0);
            }
        }
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
                failures: (pairs.iter().enumerate())
                    .flat_map(|(k, &(curve, a))| {
                        let named = move |f: String| match k {
                            0 => f,
                            _ => format!("second pair: {f}"),
                        };
                        match ToothedPair::cut(curve, a, p.teeth, &s) {
                            Ok(pair) => pair.report.failures.into_iter().map(named).collect(),
                            Err(e) => vec![named(e.to_string())],
                        }
                    })
                    .collect(),
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

/// One toothed pair's checks as a table for people.
fn pair_table(r: &TeethReport, count_from: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "teeth per gear      {} (from {})", r.teeth, count_from);
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

/// Every gear of the planetary train at carrier angle `theta` (rad): the sun turned by its
/// installation angle; each intermediate turned so that its point meeting the sun's `ψ`
/// faces the sun; each planet at the kinematics' orientation (its frame is the sun's).
/// With a `second` pair, each intermediate's layer B in the intermediate's own frame, and
/// each planet (the second pair's driven gear) turned so that its point meeting layer B
/// faces it. Arm set `k` stands where arm I stood at `theta − k·360°/arms`, as everywhere
/// else.
pub fn train_layout(
    kin: &Kinematics,
    toothed: &ToothedPair,
    second: Option<&ToothedPair>,
    theta: f64,
) -> Vec<PlacedGear> {
    let sun_angle = kin.spec().sun_angle();
    let mut layout = vec![PlacedGear {
        name: "sun".into(),
        member: Member::Driver,
        pair: 0,
        centre_mm: Vec2::ZERO,
        angle_deg: sun_angle.to_degrees(),
    }];
    let direction = |from: Vec2, to: Vec2| (to.y - from.y).atan2(to.x - from.x);
    for k in 0..kin.arms() {
        let st = kin.state_at(theta - kin.arm_lag(k));
        let towards_sun = direction(st.o2, Vec2::ZERO);
        let psi = towards_sun + PI - sun_angle;
        let chi = toothed.track.driven_angle(psi);
        layout.push(PlacedGear {
            name: format!("intermediate_{}", k + 1),
            member: Member::Driven,
            pair: 0,
            centre_mm: st.o2,
            angle_deg: (towards_sun - chi).to_degrees(),
        });
        match second {
            None => layout.push(PlacedGear {
                name: format!("planet_{}", k + 1),
                member: Member::Driver,
                pair: 0,
                centre_mm: st.o3,
                angle_deg: st.theta3.to_degrees(),
            }),
            Some(second) => {
                layout.push(PlacedGear {
                    name: format!("intermediate_{}_b", k + 1),
                    member: Member::Driver,
                    pair: 1,
                    centre_mm: st.o2,
                    angle_deg: st.theta2.to_degrees(),
                });
                let towards_layer_b = direction(st.o3, st.o2);
                let chi_b = direction(st.o2, st.o3) - st.theta2;
                let own = second.track.driven_angle(chi_b);
                layout.push(PlacedGear {
                    name: format!("planet_{}", k + 1),
                    member: Member::Driven,
                    pair: 1,
                    centre_mm: st.o3,
                    angle_deg: (towards_layer_b - own).to_degrees(),
                });
            }
        }
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
