//! Tooth strength over the cycle (docs/dynamics.md, "Tooth strength"): for every gear of
//! the train, the root stress of the tooth in mesh and the contact stress of its flank at
//! every carrier angle, from the mesh forces of the inverse dynamics and the teeth as
//! cut, against the material's allowable stresses.
//!
//! **Root stress**: ISO 6336-3's method B, read on each cut tooth rather than from the
//! formulas for a circular gear: the critical section joins the two fillet points whose
//! tangents make 30° with the tooth's centreline (the pitch curve's normal at the tooth's
//! centre), the whole normal force acts at the tip along the flank's normal there, and
//! `σF = KA·Fn·6·hFe·cos αFen·YS / (b·sFn²)` with ISO's stress correction `YS` from the
//! section and the fillet's radius of curvature there. Each tooth is taken loaded on its
//! weaker flank. **Contact stress**: Hertz's line contact at the pitch point, where the
//! flank of a rack-cut tooth has radius of curvature `R·sin α` (Euler–Savary, `R` the pitch
//! curve's own, negative where concave): `σH = √(KA·Fn·E*·(κ1 + κ2) / (π·b·sin α))`,
//! `1/E* = 2(1 − ν²)/E`.
//!
//! Approximations, all on the safe side but the last: one pair of teeth carries the whole
//! force (no load sharing, `Yε = 1`), at the tip (bending) and at the pitch point
//! (contact, `ZB = ZD = 1`); `KV`, `KFβ`, `KFα` are 1 (the cycle's inertia is computed,
//! the face is loaded evenly); the life and size factors are 1 (endurance). ISO 6336-3's
//! `YS` is fitted for `1 ≤ qs < 8`; `qs` is held in that range.

use crate::dynamics::{scene_dynamics, Dynamics};
use crate::dynamics_spec::DynamicsSpec;
use crate::error::{Error, Result};
use crate::events::Events;
use crate::planetary::Kinematics;
use crate::scene::Scene;
use crate::teeth::{Member, PairTrack, Side, ToothedGear, ToothedPair};
use crate::vec2::Vec2;
use serde::Serialize;

/// The root-stress geometry of one cut tooth loaded at the tip of one flank (ISO 6336-3
/// method B's quantities, measured on the outline).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ToothForm {
    /// The flank that carries the load.
    pub loaded: Side,
    /// Critical section `sFn` (mm): the chord between the fillet's 30° tangent points.
    pub root_chord_mm: f64,
    /// Bending lever `hFe` (mm): from the section's middle up to where the load's line
    /// meets the tooth's centreline.
    pub lever_mm: f64,
    /// Radius of curvature `ρF` of the fillet at the 30° points (mm, their mean).
    pub fillet_radius_mm: f64,
    /// Load angle `αFen` (°): between the load and the normal to the centreline.
    pub load_angle_deg: f64,
    /// Form factor `YF = 6·(hFe/m)·cos αFen / ((sFn/m)²·cos α)`.
    pub form_factor: f64,
    /// Stress correction `YS` (ISO 6336-3, eq. 65).
    pub stress_correction: f64,
    /// Root stress per newton of normal force on a face 1 mm wide (MPa/N):
    /// `6·hFe·cos αFen·YS / sFn²`.
    pub stress_per_newton: f64,
}

/// One gear's stresses over the cycle and their worst.
#[derive(Debug, Clone, Serialize)]
pub struct GearStrength {
    /// `sun`, `intermediate`, `layer B` or `planet`.
    pub name: &'static str,
    pub teeth: usize,
    pub module_mm: f64,
    /// Root stress of the tooth in mesh at each node (MPa; the larger of its two meshes'
    /// for the paper's intermediate).
    pub bending_mpa: Vec<f64>,
    /// Contact stress of the flank in mesh at each node (MPa).
    pub contact_mpa: Vec<f64>,
    /// The cycle's largest root stress (MPa), the tooth (index from the tooth at `ψ = 0`)
    /// and carrier angle (°) where it occurs, and `σFE / σF`.
    pub bending_peak_mpa: f64,
    pub bending_worst_tooth: usize,
    pub bending_peak_carrier_deg: f64,
    pub bending_safety: f64,
    /// The same for the contact stress and `σHlim / σH`.
    pub contact_peak_mpa: f64,
    pub contact_worst_tooth: usize,
    pub contact_peak_carrier_deg: f64,
    pub contact_safety: f64,
    /// The worst tooth's root geometry.
    pub worst_form: ToothForm,
    /// The least and largest form factor `YF` over the gear's teeth: how much the teeth
    /// of a non-circular gear differ.
    pub form_factor_range: [f64; 2],
}

/// The train's tooth strength at working speed.
#[derive(Debug, Clone, Serialize)]
pub struct Strength {
    pub material: String,
    pub face_width_mm: f64,
    pub application_factor: f64,
    /// `σFE` and `σHlim` (MPa).
    pub bending_limit_mpa: f64,
    pub contact_limit_mpa: f64,
    /// The sun, the intermediate, (layer B,) the planet.
    pub gears: Vec<GearStrength>,
    /// The least safety factors over the gears.
    pub bending_safety_min: f64,
    pub contact_safety_min: f64,
}

/// The gears of `scene`'s train `kin` cut with the scene's tooth count
/// (`gear.module.teeth`, or the module rule's, as `noncirc teeth` cuts them): the sun's
/// pair, and layer B's in the train with two pairs.
pub fn cut_train(kin: &Kinematics, scene: &Scene) -> Result<Vec<ToothedPair>> {
    let rule = &scene.gear.module;
    let teeth = match rule.teeth {
        Some(z) => z,
        None => match kin.module(rule).teeth {
            0 => {
                return Err(Error::Infeasible(
                    "no tooth count: the module rule admits no module for this curve; set \
                     gear.module.teeth"
                        .into(),
                ))
            }
            z => z,
        },
    };
    let first = kin.pair();
    let mut pairs = vec![ToothedPair::cut(
        first.curve(),
        first.centre_distance(),
        teeth,
        &scene.gear.teeth,
    )?];
    if let Some(second) = kin.second_pair() {
        pairs.push(
            ToothedPair::cut(
                second.curve(),
                second.centre_distance(),
                teeth,
                &scene.gear.teeth,
            )
            .map_err(|e| Error::SecondPair(Box::new(e)))?,
        );
    }
    Ok(pairs)
}

/// The strength of the teeth of `scene`'s train `kin` (with its `events`) at its working
/// speed, cut as [`cut_train`] cuts them.
pub fn train_strength(kin: &Kinematics, events: &Events, scene: &Scene) -> Result<Strength> {
    let d = scene_dynamics(kin, events, scene)?;
    strength(&d, &cut_train(kin, scene)?, &scene.dynamics)
}

/// The strength of the train whose dynamics is `dynamics`, its gears cut as `pairs` (the
/// paper's train: one pair, the sun's, whose driver is also the planet; two pairs: the
/// sun's, then layer B's), of the material and face width of `spec`.
pub fn strength(
    dynamics: &Dynamics,
    pairs: &[ToothedPair],
    spec: &DynamicsSpec,
) -> Result<Strength> {
    let two_pairs = match pairs.len() {
        1 => false,
        2 => true,
        n => {
            return Err(Error::BadList {
                list: "strength pairs",
                problem: format!("{n} toothed pairs: the train has one or two"),
            })
        }
    };
    for (key, value) in [
        ("dynamics.face_width_mm", spec.face_width_mm),
        ("dynamics.youngs_modulus_gpa", spec.youngs_modulus_gpa),
        ("dynamics.bending_limit_mpa", spec.bending_limit_mpa),
        ("dynamics.contact_limit_mpa", spec.contact_limit_mpa),
    ] {
        if !(value > 0.0 && value.is_finite()) {
            return Err(Error::OutOfRange {
                name: key.into(),
                value,
                expected: "a positive number".into(),
            });
        }
    }
    if !(1.0..=10.0).contains(&spec.application_factor) {
        return Err(Error::OutOfRange {
            name: "dynamics.application_factor".into(),
            value: spec.application_factor,
            expected: "from 1 to 10".into(),
        });
    }
    if !(0.0..0.5).contains(&spec.poisson_ratio) {
        return Err(Error::OutOfRange {
            name: "dynamics.poisson_ratio".into(),
            value: spec.poisson_ratio,
            expected: "from 0 up to 0.5".into(),
        });
    }
    let pair_of_mesh = |m: usize| &pairs[if two_pairs { m } else { 0 }];
    let e_star = 1e3 * spec.youngs_modulus_gpa / (2.0 * (1.0 - spec.poisson_ratio.powi(2)));
    let b = spec.face_width_mm;
    let ka = spec.application_factor;
    let n = dynamics.carrier_deg.len();
    // Each mesh over the cycle: its factored load, the teeth in contact, its Hertz stress.
    let meshes: Vec<MeshCycle> = (0..2)
        .map(|m| {
            MeshCycle::new(
                pair_of_mesh(m),
                &dynamics.mesh_force_n[m],
                &dynamics.mesh_contact_psi_rad[m],
                ka,
                e_star,
                b,
            )
        })
        .collect::<Result<_>>()?;
    // The gears: name, pair, member, and the meshes it is in.
    let gears: Vec<(&str, usize, Member, Vec<usize>)> = if two_pairs {
        vec![
            ("sun", 0, Member::Driver, vec![0]),
            ("intermediate", 0, Member::Driven, vec![0]),
            ("layer B", 1, Member::Driver, vec![1]),
            ("planet", 1, Member::Driven, vec![1]),
        ]
    } else {
        vec![
            ("sun", 0, Member::Driver, vec![0]),
            ("intermediate", 0, Member::Driven, vec![0, 1]),
            ("planet", 0, Member::Driver, vec![1]),
        ]
    };
    // Each cut gear's tooth forms, once (the paper's sun and planet are one gear's twins).
    let mut forms: Vec<((usize, Member), Vec<ToothForm>)> = Vec::new();
    let mut result = Vec::new();
    for (name, p, member, on) in gears {
        let pair = &pairs[p];
        let index = usize::from(member == Member::Driven);
        let at = match forms.iter().position(|(key, _)| *key == (p, member)) {
            Some(at) => at,
            None => {
                let cut = tooth_forms(
                    &pair.gears[index],
                    name,
                    &pair.track,
                    member,
                    pair.module_mm,
                    pair.spec.pressure_angle_deg.to_radians(),
                )?;
                forms.push(((p, member), cut));
                forms.len() - 1
            }
        };
        let tooth_forms = &forms[at].1;
        let mut bending = vec![0.0; n];
        let mut bending_tooth = vec![0usize; n];
        let mut contact = vec![0.0; n];
        let mut contact_tooth = vec![0usize; n];
        for &m in &on {
            let mesh = &meshes[m];
            for j in 0..n {
                let tooth = mesh.tooth[index][j];
                let sigma_f = mesh.load[j] * tooth_forms[tooth].stress_per_newton / b;
                if sigma_f > bending[j] {
                    (bending[j], bending_tooth[j]) = (sigma_f, tooth);
                }
                if mesh.contact[j] > contact[j] {
                    (contact[j], contact_tooth[j]) = (mesh.contact[j], tooth);
                }
            }
        }
        let peak = |v: &[f64]| (0..n).fold(0, |best, j| if v[j] > v[best] { j } else { best });
        let (jb, jc) = (peak(&bending), peak(&contact));
        let ratio = |limit: f64, stress: f64| {
            if stress > 0.0 {
                limit / stress
            } else {
                f64::INFINITY
            }
        };
        let yf = tooth_forms.iter().map(|f| f.form_factor);
        result.push(GearStrength {
            name,
            teeth: tooth_forms.len(),
            module_mm: pair.module_mm,
            bending_peak_mpa: bending[jb],
            bending_worst_tooth: bending_tooth[jb],
            bending_peak_carrier_deg: dynamics.carrier_deg[jb],
            bending_safety: ratio(spec.bending_limit_mpa, bending[jb]),
            contact_peak_mpa: contact[jc],
            contact_worst_tooth: contact_tooth[jc],
            contact_peak_carrier_deg: dynamics.carrier_deg[jc],
            contact_safety: ratio(spec.contact_limit_mpa, contact[jc]),
            worst_form: tooth_forms[bending_tooth[jb]],
            form_factor_range: [
                yf.clone().fold(f64::INFINITY, f64::min),
                yf.fold(0.0, f64::max),
            ],
            bending_mpa: bending,
            contact_mpa: contact,
        });
    }
    let least =
        |f: &dyn Fn(&GearStrength) -> f64| result.iter().map(f).fold(f64::INFINITY, f64::min);
    Ok(Strength {
        material: spec.material.clone(),
        face_width_mm: b,
        application_factor: ka,
        bending_limit_mpa: spec.bending_limit_mpa,
        contact_limit_mpa: spec.contact_limit_mpa,
        bending_safety_min: least(&|g| g.bending_safety),
        contact_safety_min: least(&|g| g.contact_safety),
        gears: result,
    })
}

/// One mesh over the cycle: the factored load (N), the tooth of each gear in contact
/// (driver, driven), and the Hertz stress at the pitch point (MPa).
struct MeshCycle {
    load: Vec<f64>,
    tooth: [Vec<usize>; 2],
    contact: Vec<f64>,
}

impl MeshCycle {
    fn new(
        pair: &ToothedPair,
        force: &[f64],
        psi: &[f64],
        ka: f64,
        e_star: f64,
        b: f64,
    ) -> Result<Self> {
        let track = &pair.track;
        let perimeter = track.perimeter();
        let sin_alpha = pair.spec.pressure_angle_deg.to_radians().sin();
        let mut mesh = MeshCycle {
            load: Vec::with_capacity(force.len()),
            tooth: [
                Vec::with_capacity(force.len()),
                Vec::with_capacity(force.len()),
            ],
            contact: Vec::with_capacity(force.len()),
        };
        for (&f, &psi) in force.iter().zip(psi) {
            if !f.is_finite() {
                return Err(Error::NonFinite {
                    name: "dynamics: mesh force".into(),
                    value: f,
                });
            }
            let load = ka * f.abs();
            let s = track.arc(psi).rem_euclid(perimeter);
            for (g, gear) in pair.gears.iter().enumerate() {
                mesh.tooth[g].push(nearest_tooth(gear, s, perimeter));
            }
            let curvature = track.frame(Member::Driver, psi).curvature
                + track.frame(Member::Driven, psi).curvature;
            if curvature <= 0.0 {
                return Err(Error::Teeth {
                    gear: "pair",
                    tooth: nearest_tooth(&pair.gears[0], s, perimeter),
                    arc_mm: s,
                    why: format!(
                        "the pitch curves' curvatures sum to {curvature:.3e} 1/mm: the flanks \
                         cannot touch along a line there"
                    ),
                });
            }
            mesh.load.push(load);
            mesh.contact
                .push((load * e_star * curvature / (std::f64::consts::PI * b * sin_alpha)).sqrt());
        }
        Ok(mesh)
    }
}

/// The tooth of `gear` whose centre is nearest the pitch arc `s` (mm); the teeth lie one
/// pitch apart in growing arc.
fn nearest_tooth(gear: &ToothedGear, s: f64, perimeter: f64) -> usize {
    let z = gear.teeth.len();
    let pitch = perimeter / z as f64;
    let k = ((s - gear.teeth[0].centre_arc_mm) / pitch).round();
    k.rem_euclid(z as f64) as usize % z
}

/// The root-stress geometry of every tooth of `gear` (the `member` of `track`, module `m`
/// mm, pressure angle `alpha` rad), each loaded on its weaker flank.
pub fn tooth_forms(
    gear: &ToothedGear,
    name: &'static str,
    track: &PairTrack,
    member: Member,
    m: f64,
    alpha: f64,
) -> Result<Vec<ToothForm>> {
    let outline = gear.outline();
    let runs = flank_runs(gear, name)?;
    (0..gear.teeth.len())
        .map(|k| {
            let frame = track.frame(member, track.psi_at(gear.teeth[k].centre_arc_mm));
            let local = |i: usize| {
                let d = outline[i] - frame.point;
                Vec2::new(d.dot(frame.tangent), d.dot(frame.normal))
            };
            let sides = [0, 1].map(|s| {
                let (first, len) = runs[k][s];
                FlankEnds::new(outline.len(), first, len, &local)
            });
            let arc_mm = gear.teeth[k].centre_arc_mm;
            let sections = [0, 1].map(|s| thirty_degree_point(gear, &sides[s], &local, k));
            let fail = |why: String| Error::Teeth {
                gear: name,
                tooth: k,
                arc_mm,
                why,
            };
            let [a, b] = [
                sections[0].ok_or_else(|| fail(NO_SECTION.into()))?,
                sections[1].ok_or_else(|| fail(NO_SECTION.into()))?,
            ];
            let chord = (a.point - b.point).hypot2().sqrt();
            let section_height = 0.5 * (a.point.y + b.point.y);
            let fillet_radius = 0.5 * (a.radius + b.radius);
            let form = |s: usize| {
                let flank = &sides[s];
                let tip = local(flank.tip);
                let along = flank_tangent_at_tip(
                    tip,
                    local(flank.below_tip),
                    local(flank.second_below_tip),
                );
                // The flank's normal at the tip, pointing to the centreline.
                let mut d = Vec2::new(along.y, -along.x);
                if d.x * tip.x > 0.0 {
                    d = -d;
                }
                let meets = tip.y - tip.x * d.y / d.x;
                let lever = meets - section_height;
                let cos_load = d.x.abs();
                let l = chord / lever;
                let qs = (chord / (2.0 * fillet_radius)).clamp(1.0, 8.0);
                let ys = (1.2 + 0.13 * l) * qs.powf(1.0 / (1.21 + 2.3 / l));
                let yf = 6.0 * (lever / m) * cos_load / ((chord / m).powi(2) * alpha.cos());
                ToothForm {
                    loaded: if s == 0 { Side::Left } else { Side::Right },
                    root_chord_mm: chord,
                    lever_mm: lever,
                    fillet_radius_mm: fillet_radius,
                    load_angle_deg: cos_load.acos().to_degrees(),
                    form_factor: yf,
                    stress_correction: ys,
                    stress_per_newton: 6.0 * lever * cos_load * ys / (chord * chord),
                }
            };
            let (left, right) = (form(0), form(1));
            let worse = if right.stress_per_newton > left.stress_per_newton {
                right
            } else {
                left
            };
            if !(worse.lever_mm > 0.0 && chord > 0.0 && worse.stress_per_newton.is_finite()) {
                return Err(fail(format!(
                    "no root section below its tip (section {chord:.4} mm wide, lever {:.4} mm)",
                    worse.lever_mm
                )));
            }
            Ok(worse)
        })
        .collect()
}

/// The flank's unit tangent at its tip point `tip` (towards the tip), from its last two
/// chords (`below → tip`, `second → below`): their directions' angle extrapolated
/// linearly in arc length from the chords' midpoints to the tip, exact to second order
/// (a chord's own direction is the tangent half a chord down the flank).
fn flank_tangent_at_tip(tip: Vec2, below: Vec2, second: Vec2) -> Vec2 {
    let (last, before) = (tip - below, below - second);
    let (l2, l1) = (last.hypot2().sqrt(), before.hypot2().sqrt());
    let turn = before.cross(last).atan2(before.dot(last));
    let extra = turn * (0.5 * l2) / (0.5 * (l1 + l2));
    (last * (1.0 / l2)).rotated(crate::angle::unit(extra))
}

/// A flank's run of outline points: its first index and its count, in the outline's cyclic
/// order.
type Run = (usize, usize);

/// For each tooth, the run of outline points on its left and on its right flank.
fn flank_runs(gear: &ToothedGear, name: &'static str) -> Result<Vec<[Run; 2]>> {
    let n = gear.flank_of.len();
    let mut runs = vec![[None; 2]; gear.teeth.len()];
    // Start where no flank is, so that no run wraps past the start.
    let start = (gear.flank_of.iter())
        .position(Option::is_none)
        .ok_or_else(|| Error::Teeth {
            gear: name,
            tooth: 0,
            arc_mm: 0.0,
            why: "the outline is all flank: no root or tip land".into(),
        })?;
    for step in 0..n {
        let i = (start + step) % n;
        if let Some((k, side)) = gear.flank_of[i] {
            let slot = &mut runs[k][usize::from(side == Side::Right)];
            *slot = Some(match *slot {
                None => (i, 1),
                Some((first, _)) => (first, (i + n - first) % n + 1),
            });
        }
    }
    (runs.iter().enumerate())
        .map(|(k, sides)| match sides {
            [Some(left), Some(right)] => Ok([*left, *right]),
            _ => Err(Error::Teeth {
                gear: name,
                tooth: k,
                arc_mm: gear.teeth[k].centre_arc_mm,
                why: "a flank is missing from the outline".into(),
            }),
        })
        .collect()
}

/// A flank's run seen from its tooth: the outline index of its foot (the end nearer the
/// root) and the step (±1) that leaves the flank there into the fillet, and its tip end
/// with the point below it.
struct FlankEnds {
    n: usize,
    foot: usize,
    outward: isize,
    tip: usize,
    below_tip: usize,
    second_below_tip: usize,
}

impl FlankEnds {
    fn new(n: usize, first: usize, len: usize, local: &dyn Fn(usize) -> Vec2) -> Self {
        let last = (first + len - 1) % n;
        let step = |i: usize, by: isize| (i as isize + by).rem_euclid(n as isize) as usize;
        if local(first).y <= local(last).y {
            FlankEnds {
                n,
                foot: first,
                outward: -1,
                tip: last,
                below_tip: step(last, -1),
                second_below_tip: step(last, -2),
            }
        } else {
            FlankEnds {
                n,
                foot: last,
                outward: 1,
                tip: first,
                below_tip: step(first, 1),
                second_below_tip: step(first, 2),
            }
        }
    }

    /// The outline index `t` steps from the foot (negative: back up the flank).
    fn at(&self, t: isize) -> usize {
        (self.foot as isize + t * self.outward).rem_euclid(self.n as isize) as usize
    }
}

/// Where a fillet's tangent makes 30° with the tooth's centreline, in the tooth's frame
/// (mm), and the fillet's radius of curvature there (mm).
#[derive(Debug, Clone, Copy)]
struct Section {
    point: Vec2,
    radius: f64,
}

/// Why a tooth has no critical section.
const NO_SECTION: &str =
    "no fillet point whose tangent makes 30° with the centreline before the gap's middle";

/// The 30° point below `flank` (tooth `k` of `gear`): walking from the flank's foot into
/// the fillet, the chords' angle to the centreline against arc length (at their
/// midpoints) is interpolated by the parabola through three chords where it passes 30°;
/// the point lies there on the midpoints' polyline, and the radius of curvature is the
/// parabola's `ds/dangle` (both second order in the chord length, as the outline's
/// points are not evenly spaced along the fillet). `None` if the walk reaches the gap's
/// middle or the next tooth first.
fn thirty_degree_point(
    gear: &ToothedGear,
    flank: &FlankEnds,
    local: &dyn Fn(usize) -> Vec2,
    k: usize,
) -> Option<Section> {
    // Chord t runs from point t to point t + 1 away from the foot (chord −1 is the flank's
    // last): its midpoint, its angle to the centreline (rad) and its length.
    let chord = |t: isize| {
        let (p, q) = (local(flank.at(t)), local(flank.at(t + 1)));
        let d = q - p;
        let len = d.hypot2().sqrt();
        (
            p + d * 0.5,
            d.x.abs().atan2(d.y.abs()),
            len,
            d * (1.0 / len),
        )
    };
    let target = std::f64::consts::FRAC_PI_6;
    let half_gap = flank.n / (2 * gear.teeth.len()).max(1);
    let mut before = chord(-1);
    for t in 0..half_gap as isize {
        if gear.flank_of[flank.at(t + 1)].is_some_and(|(other, _)| other != k) {
            break;
        }
        let next = chord(t);
        if next.1 > target {
            // Arc length from chord t − 1's midpoint to the midpoints of t and t + 1.
            let after = chord(t + 1);
            let (s1, a1) = (0.5 * (before.2 + next.2), next.1);
            let (s2, a2) = (s1 + 0.5 * (next.2 + after.2), after.1);
            let a0 = before.1;
            let d01 = (a1 - a0) / s1;
            let d012 = ((a2 - a1) / (s2 - s1) - d01) / s2;
            let angle = |s: f64| a0 + d01 * s + d012 * s * (s - s1);
            let rate = |s: f64| d01 + d012 * (2.0 * s - s1);
            // From the chord's linear guess, Newton on the parabola within the interval.
            let mut s = if a1 > a0 {
                (target - a0) / (a1 - a0) * s1
            } else {
                0.0
            };
            for _ in 0..8 {
                let r = rate(s);
                if r <= 0.0 {
                    break;
                }
                s = (s - (angle(s) - target) / r).clamp(0.0, s1);
            }
            let r = rate(s);
            let radius = if r > 0.0 { 1.0 / r } else { f64::INFINITY };
            // A chord's midpoint lies `l²/8ρ` inside the arc, towards the centre of
            // curvature, on the side the chords turn to.
            let f = s / s1;
            let length = before.2 + (next.2 - before.2) * f;
            let turn = before.3.cross(next.3).signum();
            let towards_centre = (before.3 + (next.3 - before.3) * f).turn_90() * turn;
            let sag = length * length / (8.0 * radius);
            let towards_centre = towards_centre * (1.0 / towards_centre.hypot2().sqrt());
            return Some(Section {
                point: before.0 + (next.0 - before.0) * f - towards_centre * sag,
                radius,
            });
        }
        before = next;
    }
    None
}
