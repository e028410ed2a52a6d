//! Solid models of a scene's gears and train (`noncirc cad`): each toothed gear's cut
//! outline extruded by the face width with its bore, keyway and phase mark; a train's two
//! carrier side plates, its arms and pushers; each part once in its own frame, and each
//! instance of it placed at a carrier angle. Written as STEP AP214 ([`step`]) and binary
//! STL ([`stl`]). docs/cad.md.

pub mod profile;
#[cfg(feature = "step")]
pub mod step;
pub mod stl;

use crate::cad;
use crate::teeth::{train_layout, PlacedGear, TeethRun};
use crate::{Error, Result};
use noncirc_core::{CadSpec, Kinematics, Member, Scene, ToothedGear, Vec2};
use profile::{circle, hull_of_circles, keyed_bore, oriented, Profile};
use serde::Serialize;

/// A part: a profile (mm, own frame) extruded by `thickness_mm` along +z from z = 0.
#[derive(Debug, Clone)]
pub struct Part {
    /// `sun`, `intermediate`, `planet`, `carrier_plate`, `arm`, … (a file name).
    pub name: String,
    pub profile: Profile,
    pub thickness_mm: f64,
}

/// One placed copy of a part: its own frame's origin at `at_mm` and turned by `angle_deg`
/// about z.
#[derive(Debug, Clone, Serialize)]
pub struct Instance {
    /// `sun`, `intermediate_1`, `carrier_plate_bottom`, `arm_2`, …
    pub name: String,
    /// The part's index in [`Assembly::parts`].
    pub part: usize,
    pub at_mm: [f64; 3],
    pub angle_deg: f64,
}

/// Every part of a scene's gears (and train) and where each copy stands.
#[derive(Debug, Clone)]
pub struct Assembly {
    /// The assembly's name (`train`, or `gear_pair`).
    pub name: String,
    pub parts: Vec<Part>,
    pub instances: Vec<Instance>,
    /// The carrier angle it is assembled at (degrees; `None` for a gear pair).
    pub carrier_deg: Option<f64>,
}

/// A file format of `noncirc cad`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// STEP AP214: the assembly and each part.
    Step,
    /// Binary STL, each part in its own frame.
    Stl,
}

/// `assembly.json`: what the files hold, for a reader or a test.
#[derive(Debug, Serialize)]
pub struct Manifest<'a> {
    pub name: &'a str,
    /// Degrees; `None` for a gear pair.
    pub carrier_deg: Option<f64>,
    /// The largest distance of the STEP's lines and arcs from the cut outline, and of the
    /// STL's chords from those arcs (mm).
    pub tolerance_mm: f64,
    pub parts: Vec<PartEntry<'a>>,
    pub instances: &'a [Instance],
}

/// A part in `assembly.json`.
#[derive(Debug, Serialize)]
pub struct PartEntry<'a> {
    pub name: &'a str,
    pub thickness_mm: f64,
    /// The profile's area (mm²), exactly from its lines and arcs.
    pub area_mm2: f64,
    pub volume_mm3: f64,
}

/// What [`export`] did: the files written (none where the teeth fail a check and
/// `force` is off) and the teeth's failed checks.
#[derive(Debug, Clone)]
pub struct Export {
    pub paths: Vec<std::path::PathBuf>,
    pub failures: Vec<String>,
    /// The failed checks' names, for a one-line verdict.
    pub failed_checks: String,
    pub assembly: Option<Assembly>,
}

/// Checks a carrier angle (degrees) named `name`: a finite number.
pub fn check_carrier(name: &str, carrier_deg: f64) -> Result<()> {
    if carrier_deg.is_finite() {
        return Ok(());
    }
    Err(noncirc_core::Error::NonFinite {
        name: name.into(),
        value: carrier_deg,
    }
    .into())
}

/// Cuts the scene's teeth at carrier angle `carrier_deg` (degrees), builds the solids and
/// writes the files of `formats` into `dir` (`noncirc cad`, Python's `noncirc.cad`). Teeth
/// that cannot be cut, a `[cad]` dimension that does not fit or a bad argument is an error
/// and nothing is written; teeth that fail a check are written only with `force`.
pub fn export(
    scene: &Scene,
    carrier_deg: f64,
    formats: &[Format],
    tolerance_mm: f64,
    dir: &std::path::Path,
    force: bool,
) -> Result<Export> {
    cad::check_tolerance("tolerance_mm", tolerance_mm)?;
    check_carrier("carrier_deg", carrier_deg)?;
    let run = TeethRun::from_scene(scene, carrier_deg)?;
    let failures = run.failures();
    let failed_checks = run.failed_checks();
    if !failures.is_empty() && !force {
        return Ok(Export {
            paths: Vec::new(),
            failures,
            failed_checks,
            assembly: None,
        });
    }
    let assembly = Assembly::from_run(scene, &run, tolerance_mm)?;
    let files = assembly.files(formats, tolerance_mm)?;
    crate::files::create_dir(dir)?;
    let mut paths = Vec::with_capacity(files.len());
    for (name, bytes) in files {
        let path = dir.join(name);
        crate::files::write_file(&path, &bytes)?;
        paths.push(path);
    }
    Ok(Export {
        paths,
        failures,
        failed_checks,
        assembly: Some(assembly),
    })
}

/// A field of `[cad]` that does not fit the design: the typed error naming it.
fn misfit(name: &str, value: f64, expected: String) -> Error {
    noncirc_core::Error::OutOfRange {
        name: name.into(),
        value,
        expected,
    }
    .into()
}

/// Checks the `[cad]` fields that depend on each other and on the gears: a key narrower
/// than the bore, the keyway and the phase mark inside every gear's root, an arm wider
/// than its hub's bore; the radius the keyway's corners reach (mm).
fn check(spec: &CadSpec, gears: &[(&str, &ToothedGear)]) -> Result<f64> {
    let r = 0.5 * spec.bore_diameter_mm;
    if spec.key_width_mm >= spec.bore_diameter_mm {
        return Err(misfit(
            "cad.key_width_mm",
            spec.key_width_mm,
            format!(
                "narrower than the bore (cad.bore_diameter_mm = {} mm)",
                spec.bore_diameter_mm
            ),
        ));
    }
    let inner = if spec.key_width_mm > 0.0 {
        (r + spec.key_depth_mm).hypot(0.5 * spec.key_width_mm)
    } else {
        r
    };
    for (name, g) in gears {
        let root = least_radius(g.outline());
        if inner >= root {
            let (field, value) = if spec.key_width_mm > 0.0 && r < root {
                ("cad.key_depth_mm", spec.key_depth_mm)
            } else {
                ("cad.bore_diameter_mm", spec.bore_diameter_mm)
            };
            return Err(misfit(
                field,
                value,
                format!(
                    "a bore{} inside the {name}'s least root radius {root:.3} mm (it reaches {inner:.3} mm)",
                    if spec.key_width_mm > 0.0 { " and keyway" } else { "" }
                ),
            ));
        }
        if spec.mark_diameter_mm >= 0.5 * (root - inner) {
            return Err(misfit(
                "cad.mark_diameter_mm",
                spec.mark_diameter_mm,
                format!(
                    "less than half the {name}'s rim between the keyway and the root ({:.3} mm)",
                    0.5 * (root - inner)
                ),
            ));
        }
    }
    if spec.arm_width_mm <= spec.bore_diameter_mm {
        return Err(misfit(
            "cad.arm_width_mm",
            spec.arm_width_mm,
            format!(
                "wider than the bore of its hub (cad.bore_diameter_mm = {} mm)",
                spec.bore_diameter_mm
            ),
        ));
    }
    Ok(inner)
}

/// The least distance of an outline's points from its centre (mm): its root.
fn least_radius(outline: &[Vec2]) -> f64 {
    (outline.iter())
        .map(|p| p.hypot2().sqrt())
        .fold(f64::INFINITY, f64::min)
}

/// The greatest distance of an outline's points from its centre (mm): its tip.
fn greatest_radius(outline: &[Vec2]) -> f64 {
    outline
        .iter()
        .map(|p| p.hypot2().sqrt())
        .fold(0.0, f64::max)
}

/// The part a placed gear is a copy of: its name without the copy's number
/// (`intermediate_2_b` → `intermediate_b`).
fn part_name(instance: &str) -> String {
    instance
        .split('_')
        .filter(|w| w.parse::<usize>().is_err())
        .collect::<Vec<_>>()
        .join("_")
}

impl Assembly {
    /// The scene's gears as `run` cut and placed them (`TeethRun::from_scene`), their
    /// outlines fitted with lines and arcs within `tolerance_mm`, with the scene's `[cad]`
    /// dimensions and `dynamics.face_width_mm` as the gears' thickness.
    pub fn from_run(scene: &Scene, run: &TeethRun, tolerance_mm: f64) -> Result<Self> {
        let spec = &scene.cad;
        let b = scene.dynamics.face_width_mm;
        let gear_of = |pair: usize, member: Member| {
            let p = run.pairs().nth(pair).expect("the layout's pair is cut");
            &p.gears[usize::from(member == Member::Driven)]
        };
        let mut names: Vec<String> = Vec::new();
        let mut kinds: Vec<(usize, Member)> = Vec::new();
        for g in &run.layout {
            let name = part_name(&g.name);
            if !names.contains(&name) {
                names.push(name);
                kinds.push((g.pair, g.member));
            }
        }
        let gears: Vec<(&str, &ToothedGear)> = (names.iter().zip(&kinds))
            .map(|(n, &(pair, member))| (n.as_str(), gear_of(pair, member)))
            .collect();
        let inner = check(spec, &gears)?;
        let r = 0.5 * spec.bore_diameter_mm;
        let bore = oriented(
            keyed_bore(r, spec.key_width_mm, r + spec.key_depth_mm),
            false,
        );
        let mut parts: Vec<Part> = (gears.iter())
            .map(|(name, g)| {
                let outer = oriented(cad::fit(g.outline(), &g.corners, tolerance_mm), true);
                let mut holes = vec![bore.clone()];
                if spec.mark_diameter_mm > 0.0 {
                    let at = 0.5 * (inner + least_radius(g.outline()));
                    let mark = circle(Vec2::new(at, 0.0), 0.5 * spec.mark_diameter_mm);
                    holes.push(oriented(mark, false));
                }
                Part {
                    name: name.to_string(),
                    profile: Profile { outer, holes },
                    thickness_mm: b,
                }
            })
            .collect();
        // A train's motion: its plates, arms and pushers, and where every copy stands.
        let kin = match run.carrier_deg {
            Some(_) => Some(scene.kinematics(&scene.resolution)?),
            None => None,
        };
        let name = match &kin {
            None => "gear_pair",
            Some(kin) => {
                // The train: the carrier's side plates in its own frame (the axles at
                // carrier angle 0), each arm from its planet's axle to its tip, a pusher.
                let mut axles = vec![Vec2::ZERO];
                for k in 0..kin.arms() {
                    let st = kin.state_at(-kin.arm_lag(k));
                    axles.extend([st.o2, st.o3]);
                }
                for (i, a) in axles.iter().enumerate() {
                    let near = axles[..i].iter().map(|c| (*c - *a).hypot2().sqrt());
                    if let Some(d) = near.filter(|d| *d <= 2.0 * r).reduce(f64::min) {
                        return Err(misfit(
                            "cad.bore_diameter_mm",
                            spec.bore_diameter_mm,
                            format!("less than the distance between two axles ({d:.3} mm)"),
                        ));
                    }
                }
                let tip = (gears.iter())
                    .map(|(_, g)| greatest_radius(g.outline()))
                    .fold(0.0, f64::max);
                parts.push(Part {
                    name: "carrier_plate".into(),
                    profile: Profile {
                        outer: hull_of_circles(&axles, tip + spec.plate_margin_mm),
                        holes: axles
                            .iter()
                            .map(|a| oriented(circle(*a, r), false))
                            .collect(),
                    },
                    thickness_mm: spec.plate_thickness_mm,
                });
                let st = kin.state_at(0.0);
                let (wa, wp) = (spec.arm_width_mm, spec.pusher_width_mm);
                parts.push(Part {
                    name: "arm".into(),
                    profile: Profile {
                        outer: profile::stadium(
                            Vec2::ZERO,
                            Vec2::new((st.tip - st.o3).hypot2().sqrt(), 0.0),
                            0.5 * wa,
                        ),
                        holes: vec![oriented(circle(Vec2::ZERO, r), false)],
                    },
                    thickness_mm: spec.arm_thickness_mm,
                });
                parts.push(Part {
                    name: "pusher".into(),
                    profile: Profile {
                        outer: profile::stadium(
                            Vec2::ZERO,
                            Vec2::new(spec.pusher_length_mm, 0.0),
                            0.5 * wp,
                        ),
                        holes: vec![],
                    },
                    thickness_mm: wp,
                });
                "train"
            }
        };
        let mut assembly = Self {
            name: name.into(),
            parts,
            instances: Vec::new(),
            carrier_deg: run.carrier_deg,
        };
        assembly.instances = match (&kin, run.carrier_deg) {
            (Some(kin), Some(theta)) => assembly.train_instances(scene, kin, run, theta),
            _ => assembly.gear_instances(&run.layout, b + spec.axial_gap_mm),
        };
        Ok(assembly)
    }

    /// The gears' copies of `layout`, each pair's layer `layer_mm` above the last.
    fn gear_instances(&self, layout: &[PlacedGear], layer_mm: f64) -> Vec<Instance> {
        (layout.iter())
            .map(|g| Instance {
                name: g.name.clone(),
                part: self.part(&part_name(&g.name)),
                at_mm: [g.centre_mm.x, g.centre_mm.y, g.pair as f64 * layer_mm],
                angle_deg: g.angle_deg,
            })
            .collect()
    }

    fn part(&self, name: &str) -> usize {
        (self.parts.iter())
            .position(|p| p.name == name)
            .expect("every copy's part is made")
    }

    /// Every copy of a train's parts at carrier angle `carrier_deg` (degrees): the gears
    /// as [`train_layout`] places them, the plates turned with the carrier, each arm on its
    /// planet's axle towards its tip and each pusher on its arm. The parts of `run` (cut at
    /// any carrier angle) and of `kin`, the scene's kinematics.
    pub fn train_instances(
        &self,
        scene: &Scene,
        kin: &Kinematics,
        run: &TeethRun,
        carrier_deg: f64,
    ) -> Vec<Instance> {
        let (spec, b) = (&scene.cad, scene.dynamics.face_width_mm);
        let gap = spec.axial_gap_mm;
        let theta = carrier_deg.to_radians();
        let layout = train_layout(kin, &run.pair, run.second.as_ref(), theta);
        let mut instances = self.gear_instances(&layout, b + gap);
        let layers = 1 + usize::from(run.second.is_some());
        let top = layers as f64 * b + (layers - 1) as f64 * gap;
        let tp = spec.plate_thickness_mm;
        // The plates' frame is the carrier's at angle 0: the turn of arm I's intermediate
        // axle since then.
        let (now, then) = (kin.state_at(theta).o2, kin.state_at(0.0).o2);
        let turn = now.y.atan2(now.x) - then.y.atan2(then.x);
        for (name, z) in [("bottom", -gap - tp), ("top", top + gap)] {
            instances.push(Instance {
                name: format!("carrier_plate_{name}"),
                part: self.part("carrier_plate"),
                at_mm: [0.0, 0.0, z],
                angle_deg: turn.to_degrees(),
            });
        }
        let z_arm = top + gap + tp + gap;
        for k in 0..kin.arms() {
            let st = kin.state_at(theta - kin.arm_lag(k));
            let along = st.tip - st.o3;
            let u = Vec2::new(st.pusher_angle.cos(), st.pusher_angle.sin());
            let back = st.tip - u * spec.pusher_length_mm;
            instances.push(Instance {
                name: format!("arm_{}", k + 1),
                part: self.part("arm"),
                at_mm: [st.o3.x, st.o3.y, z_arm],
                angle_deg: along.y.atan2(along.x).to_degrees(),
            });
            instances.push(Instance {
                name: format!("pusher_{}", k + 1),
                part: self.part("pusher"),
                at_mm: [back.x, back.y, z_arm + spec.arm_thickness_mm],
                angle_deg: st.pusher_angle.to_degrees(),
            });
        }
        instances
    }

    /// The files of `formats`: `<name>.step` (the assembly) and per part `<part>.step` and
    /// `<part>.stl` (its chords within `tolerance_mm` of its arcs), and `assembly.json`
    /// (the parts' volumes and the instances' placements); all made before any is written.
    pub fn files(&self, formats: &[Format], tolerance_mm: f64) -> Result<Vec<(String, Vec<u8>)>> {
        let mut files = Vec::new();
        if formats.contains(&Format::Step) {
            #[cfg(feature = "step")]
            {
                let assembly = step::assembly_file(self)?;
                files.push((format!("{}.step", self.name), assembly.into_bytes()));
                for p in &self.parts {
                    files.push((format!("{}.step", p.name), step::part_file(p)?.into_bytes()));
                }
            }
            #[cfg(not(feature = "step"))]
            return Err(Error::Input(
                "STEP needs noncirc built with the `step` feature (the CLI and Python have it)"
                    .into(),
            ));
        }
        if formats.contains(&Format::Stl) {
            for p in &self.parts {
                let t = stl::triangles(p, tolerance_mm)?;
                files.push((format!("{}.stl", p.name), stl::binary(&p.name, &t)));
            }
        }
        let json = serde_json::to_vec_pretty(&self.manifest(tolerance_mm)).map_err(|e| {
            Error::Serialise {
                what: "assembly.json",
                message: e.to_string(),
            }
        })?;
        files.push(("assembly.json".into(), json));
        Ok(files)
    }

    /// What `assembly.json` holds, the files made with `tolerance_mm`.
    pub fn manifest(&self, tolerance_mm: f64) -> Manifest<'_> {
        Manifest {
            name: &self.name,
            carrier_deg: self.carrier_deg,
            tolerance_mm,
            parts: (self.parts.iter().zip(self.volumes()))
                .map(|(p, volume_mm3)| PartEntry {
                    name: &p.name,
                    thickness_mm: p.thickness_mm,
                    area_mm2: p.profile.area(),
                    volume_mm3,
                })
                .collect(),
            instances: &self.instances,
        }
    }

    /// Each part's volume (mm³): its profile's area, exactly, times its thickness.
    pub fn volumes(&self) -> Vec<f64> {
        (self.parts.iter())
            .map(|p| p.profile.area() * p.thickness_mm)
            .collect()
    }
}
