//! `noncirc dynamics`: a scene's train at its working speed (the core's
//! [`noncirc_core::dynamics`]) and its teeth's strength ([`noncirc_core::strength`]), as a
//! table, JSON and figures (docs/dynamics.md).

use crate::{Error, Result};
use noncirc_core::{
    cut_train, scene_dynamics, strength, Dynamics, Evaluation, Evaluator, Scene, SceneKind,
    SpeedFluctuation, Strength,
};
use serde::Serialize;
use std::fmt::Write;

/// What `noncirc dynamics` reports: the dynamics (its fields at the top level of the JSON)
/// and the teeth's strength, or why there is none.
#[derive(Debug, Clone, Serialize)]
pub struct DynamicsReport {
    #[serde(flatten)]
    pub dynamics: Dynamics,
    /// The carrier's speed over the turn with a constant drive torque and the scene's
    /// flywheel; the least flywheel on the carrier's axis that holds its fluctuation to
    /// `dynamics.speed_fluctuation_allowed` (kg·m²), and that coefficient.
    pub speed: SpeedFluctuation,
    pub flywheel_needed_kg_m2: f64,
    pub speed_fluctuation_allowed: f64,
    /// The teeth's stresses and safety factors; `None` when the scene's teeth cannot be
    /// cut (`strength_unavailable` says why) or were not asked for ([`report_from`]).
    pub strength: Option<Strength>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strength_unavailable: Option<String>,
}

/// The dynamics of `scene`'s design and the strength of its teeth, cut as `noncirc teeth`
/// cuts them (the scene's tooth count, or its module rule's), as the objectives
/// `bending_safety` and `contact_safety` compute it ([`noncirc_core::train_strength`]).
pub fn report_of(scene: &Scene) -> Result<DynamicsReport> {
    let eval = evaluated(scene)?;
    report_from(scene, &eval, true)
}

/// [`report_of`] for `eval`, `scene`'s evaluation; the teeth cut and checked for strength
/// only `with_strength` (half a second for a design, against a millisecond for the rest).
pub fn report_from(
    scene: &Scene,
    eval: &Evaluation,
    with_strength: bool,
) -> Result<DynamicsReport> {
    let d = dynamics_from(scene, eval)?;
    let (strength, strength_unavailable) = if with_strength {
        match strength_from(scene, eval, &d) {
            Ok(s) => (Some(s), None),
            Err(e) => (None, Some(format!("the teeth cannot be cut: {e}"))),
        }
    } else {
        (None, None)
    };
    let allowed = scene.dynamics.speed_fluctuation_allowed;
    Ok(DynamicsReport {
        speed: d.speed_with(scene.dynamics.flywheel_inertia_kg_m2),
        flywheel_needed_kg_m2: d.flywheel_needed_kg_m2(allowed),
        speed_fluctuation_allowed: allowed,
        dynamics: d,
        strength,
        strength_unavailable,
    })
}

/// The strength of the teeth of `eval`'s train (`scene`'s evaluation), cut as `noncirc
/// teeth` cuts them, under the loads of `d`, its dynamics; an error says why they cannot be
/// cut.
pub fn strength_from(scene: &Scene, eval: &Evaluation, d: &Dynamics) -> Result<Strength> {
    let kin = (eval.kinematics.as_ref())
        .ok_or_else(|| noncirc_core::Error::Infeasible("no train to cut".into()))?;
    let pairs = cut_train(kin, scene)?;
    Ok(strength(d, &pairs, &scene.dynamics)?)
}

/// The dynamics of `scene`'s design at its resolution and working speed.
pub fn dynamics_of(scene: &Scene) -> Result<Dynamics> {
    dynamics_from(scene, &evaluated(scene)?)
}

/// `scene`'s evaluation, for a scene with a train to move.
fn evaluated(scene: &Scene) -> Result<Evaluation> {
    check_kind(scene)?;
    Ok(Evaluator::planned(&scene.resolution).evaluate(scene)?)
}

/// An error unless `scene` has a train to move.
fn check_kind(scene: &Scene) -> Result<()> {
    if matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter) {
        return Ok(());
    }
    Err(Error::Input(format!(
        "dynamics needs a three_arm or transplanter scene, not {}",
        scene.kind.name()
    )))
}

/// The dynamics of `eval`, `scene`'s evaluation, which must have a motion.
pub fn dynamics_from(scene: &Scene, eval: &Evaluation) -> Result<Dynamics> {
    check_kind(scene)?;
    let (Some(kin), Some(events)) = (&eval.kinematics, &eval.events) else {
        return Err(Error::Input(
            "the design has no motion to move the bodies".into(),
        ));
    };
    Ok(scene_dynamics(kin, events, scene)?)
}

/// `|F|` of each force of a series (N): the axle loads' and the shaking force's size over
/// the cycle, as the figures and the studio draw them.
pub fn magnitudes(forces: &[[f64; 2]]) -> Vec<f64> {
    forces.iter().map(|[x, y]| x.hypot(*y)).collect()
}

/// The same design with two, three and four arm sets at the scene's picking rate (the
/// carrier slower as the arms are more): how the arm count balances the train. An arm
/// count the model refuses for this design is left out.
pub fn by_arm_count(scene: &Scene) -> Vec<(usize, Dynamics)> {
    let rate = scene.train.picking_rate();
    (2..=4)
        .filter_map(|arms| {
            let mut s = scene.clone();
            s.train.arms = arms;
            s.train.picks_per_minute = Some(rate);
            dynamics_of(&s).ok().map(|d| (arms, d))
        })
        .collect()
}

/// The dynamics' table and the strength's, for a person.
pub fn report_table(r: &DynamicsReport) -> String {
    let mut t = table(&r.dynamics);
    let v = &r.speed;
    let _ = writeln!(
        t,
        "\nwith a constant drive torque of {:.4} N·m (carrier Jc = {} kg·m², flywheel Jf = {} kg·m²):",
        v.drive_torque_nm, v.carrier_inertia_kg_m2, v.flywheel_inertia_kg_m2
    );
    let (lo, hi) = (v.carrier_speed_rad_s.iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &w| {
            (l.min(w), h.max(w))
        });
    let rpm = 60.0 / std::f64::consts::TAU;
    for (name, value) in [
        (
            "carrier speed, least and largest (r/min)".to_string(),
            format!("{:.2} … {:.2}", lo * rpm, hi * rpm),
        ),
        (
            "speed fluctuation (ω_max − ω_min)/ω_mean".to_string(),
            format!("{:.4}", v.coefficient),
        ),
        (
            format!(
                "flywheel needed for δ ≤ {} (kg·m²)",
                r.speed_fluctuation_allowed
            ),
            format!("{:.4}", r.flywheel_needed_kg_m2),
        ),
    ] {
        let _ = writeln!(t, "{name:<58} {value}");
    }
    t.push('\n');
    match (&r.strength, &r.strength_unavailable) {
        (Some(s), _) => t.push_str(&strength_table(s)),
        (None, why) => {
            let _ = writeln!(
                t,
                "tooth strength: not computed: {}",
                why.as_deref().unwrap_or("—")
            );
        }
    }
    t
}

/// Each gear's worst root and contact stress, where they occur and the safety factors.
pub fn strength_table(s: &Strength) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "tooth strength (ISO 6336-3 method B on the cut teeth, Hertz at the pitch point): {}, \
         b = {} mm, KA = {}; σFE = {} MPa, σHlim = {} MPa",
        s.material, s.face_width_mm, s.application_factor, s.bending_limit_mpa, s.contact_limit_mpa
    );
    let _ = writeln!(
        t,
        "\ngear          teeth  m (mm)   YF least…largest   σF peak (MPa)  tooth  at θ (°)    SF   \
         σH peak (MPa)  tooth  at θ (°)    SH"
    );
    for g in &s.gears {
        let _ = writeln!(
            t,
            "{:<12} {:>6} {:>7.3}   {:>6.3} … {:<6.3}   {:>13.1} {:>6} {:>9.1} {:>6.2}   {:>13.1} {:>6} {:>9.1} {:>6.2}",
            g.name,
            g.teeth,
            g.module_mm,
            g.form_factor_range[0],
            g.form_factor_range[1],
            g.bending_peak_mpa,
            g.bending_worst_tooth,
            g.bending_peak_carrier_deg,
            g.bending_safety,
            g.contact_peak_mpa,
            g.contact_worst_tooth,
            g.contact_peak_carrier_deg,
            g.contact_safety,
        );
    }
    let _ = writeln!(
        t,
        "\nleast safety factor: bending {:.2}, contact {:.2}",
        s.bending_safety_min, s.contact_safety_min
    );
    t
}

/// The bodies and the cycle's extremes, for a person.
pub fn table(d: &Dynamics) -> String {
    let s = &d.summary;
    let mut t = String::new();
    let rpm = d.carrier_speed_rad_s * 60.0 / std::f64::consts::TAU;
    let _ = writeln!(
        t,
        "carrier {rpm:.1} r/min, {} arm sets: {:.0} picks/min; pressure angle {:.1}°",
        d.arms,
        rpm * d.arms as f64,
        d.pressure_angle_deg
    );
    let _ = writeln!(
        t,
        "\nbody (one arm set)       mass (kg)  centre of mass (mm)   J about it (kg·m²)"
    );
    for (name, b) in [
        ("intermediate", d.intermediate),
        ("planet gear", d.planet),
        ("arm", d.arm),
        ("planet with arm", d.planet_with_arm),
    ] {
        let _ = writeln!(
            t,
            "{name:<22} {:>10.4}  ({:>7.2}, {:>7.2})      {:>12.3e}",
            b.mass_kg, b.centroid_mm.x, b.centroid_mm.y, b.inertia_kg_m2
        );
    }
    let fluctuation = s
        .torque_fluctuation
        .map_or("— (mean below 1 % of RMS)".to_string(), |f| {
            format!("{f:.2}")
        });
    let rows = [
        (
            "input torque, largest |T| (N·m)",
            format!("{:.4}", s.torque_peak_nm),
        ),
        ("input torque, RMS (N·m)", format!("{:.4}", s.torque_rms_nm)),
        (
            "input torque, mean (N·m)",
            format!("{:.4}", s.torque_mean_nm),
        ),
        (
            "input torque, least and largest (N·m)",
            format!("{:.4} … {:.4}", s.torque_min_nm, s.torque_max_nm),
        ),
        ("torque fluctuation (T_max − T_min)/T_mean", fluctuation),
        (
            "mesh force sun–intermediate, peak (N)",
            format!("{:.2}", s.mesh_force_peak_n[0]),
        ),
        (
            "mesh force intermediate–planet, peak (N)",
            format!("{:.2}", s.mesh_force_peak_n[1]),
        ),
        (
            "intermediate axle, peak (N)",
            format!("{:.2}", s.intermediate_axle_peak_n),
        ),
        (
            "planet axle, peak (N)",
            format!("{:.2}", s.planet_axle_peak_n),
        ),
        ("sun shaft, peak (N)", format!("{:.2}", s.sun_shaft_peak_n)),
        (
            "carrier bearing, peak (N)",
            format!("{:.2}", s.carrier_bearing_peak_n),
        ),
        (
            "shaking force, peak (N)",
            format!("{:.3}", s.shaking_force_peak_n),
        ),
        (
            "shaking moment, peak (N·m)",
            format!("{:.4}", s.shaking_moment_peak_nm),
        ),
        (
            "Newton–Euler vs energy torque, largest difference / peak",
            format!("{:.1e}", s.formulations_rel_diff),
        ),
    ];
    t.push('\n');
    for (name, value) in rows {
        let _ = writeln!(t, "{name:<58} {value}");
    }
    t
}

/// The torque, the mesh forces, the axle loads over the cycle and as polar plots (the
/// force's tip in the plane), the shaking force, the carrier's speed with a constant drive
/// torque, the teeth's stresses, and the input torque with each arm count of `arm_counts`
/// ([`by_arm_count`]), into `dir`.
#[cfg(feature = "figures")]
pub fn figures(
    r: &DynamicsReport,
    arm_counts: &[(usize, Dynamics)],
    dir: &std::path::Path,
    options: &crate::figures::FigureOptions,
) -> Result<Vec<std::path::PathBuf>> {
    use crate::figures::{save, LinesFigure};
    crate::files::create_dir(dir)?;
    let (d, strength) = (&r.dynamics, r.strength.as_ref());
    let theta = &d.carrier_deg;
    let over_cycle = |v: &[f64]| theta.iter().copied().zip(v.iter().copied()).collect();
    let rpm = d.carrier_speed_rad_s * 60.0 / std::f64::consts::TAU;
    let speed = format!("{rpm:.0} r/min, {} arm sets", d.arms);
    let x_desc = "carrier angle θ (°)".to_string();
    let line = |title: String, y_desc: &str, series: Vec<(String, Vec<(f64, f64)>)>| LinesFigure {
        title,
        x_desc: x_desc.clone(),
        y_desc: y_desc.to_string(),
        series,
        points_only: false,
        markers: false,
        band: None,
    };
    let polar = |title: String, series: Vec<(String, Vec<(f64, f64)>)>| LinesFigure {
        title,
        x_desc: "Fx (N)".into(),
        y_desc: "Fy (N)".into(),
        series,
        points_only: false,
        markers: false,
        band: None,
    };
    let xy = |v: &[[f64; 2]]| v.iter().map(|f| (f[0], f[1])).collect::<Vec<_>>();
    let mut files = Vec::new();
    let figures = [
        (
            line(
                format!("Input torque at the carrier ({speed})"),
                "torque T (N·m)",
                vec![
                    ("Newton–Euler".into(), over_cycle(&d.input_torque_nm)),
                    (
                        "energy balance".into(),
                        over_cycle(&d.input_torque_energy_nm),
                    ),
                ],
            ),
            "input_torque",
        ),
        (
            line(
                format!("Mesh forces along the lines of action, arm set I ({speed})"),
                "normal force Fn (N)",
                vec![
                    ("sun–intermediate".into(), over_cycle(&d.mesh_force_n[0])),
                    ("intermediate–planet".into(), over_cycle(&d.mesh_force_n[1])),
                ],
            ),
            "mesh_forces",
        ),
        (
            line(
                format!("Axle loads ({speed})"),
                "force |F| (N)",
                vec![
                    (
                        "intermediate (set I)".into(),
                        over_cycle(&magnitudes(&d.intermediate_axle_n)),
                    ),
                    (
                        "planet (set I)".into(),
                        over_cycle(&magnitudes(&d.planet_axle_n)),
                    ),
                    ("sun shaft".into(), over_cycle(&magnitudes(&d.sun_shaft_n))),
                    (
                        "carrier bearing".into(),
                        over_cycle(&magnitudes(&d.carrier_bearing_n)),
                    ),
                ],
            ),
            "axle_loads",
        ),
        (
            polar(
                format!("Axle loads in the plane, polar ({speed})"),
                vec![
                    ("intermediate (set I)".into(), xy(&d.intermediate_axle_n)),
                    ("planet (set I)".into(), xy(&d.planet_axle_n)),
                    ("carrier bearing".into(), xy(&d.carrier_bearing_n)),
                ],
            ),
            "axle_loads_polar",
        ),
        (
            line(
                format!("Shaking force on the frame ({speed})"),
                "force (N)",
                vec![(
                    "|shaking force|".into(),
                    over_cycle(&magnitudes(&d.shaking_force_n)),
                )],
            ),
            "shaking_force",
        ),
        (
            line(
                format!("Carrier speed, constant drive torque ({speed})"),
                "carrier speed (r/min)",
                // With the scene's flywheel, and with the one needed where that differs.
                std::iter::once((r.speed.flywheel_inertia_kg_m2, r.speed.clone()))
                    .chain(
                        (r.flywheel_needed_kg_m2 != r.speed.flywheel_inertia_kg_m2).then(|| {
                            let needed = r.flywheel_needed_kg_m2;
                            (needed, d.speed_with(needed))
                        }),
                    )
                    .map(|(flywheel, v)| {
                        let rpm: Vec<f64> = (v.carrier_speed_rad_s.iter())
                            .map(|w| w * 60.0 / std::f64::consts::TAU)
                            .collect();
                        let label = format!(
                            "Td = {:.2} N·m, flywheel {flywheel:.3} kg·m²: δ = {:.3}",
                            v.drive_torque_nm, v.coefficient
                        );
                        (label, over_cycle(&rpm))
                    })
                    .collect(),
            ),
            "carrier_speed",
        ),
    ];
    for (figure, name) in figures {
        files.extend(save(&figure, &dir.join(name), options)?);
    }
    if let Some(s) = strength {
        // The tooth in mesh at each carrier angle: each gear's root stress, and each
        // mesh's contact stress (both its gears carry the same; the sun is in the first
        // mesh only, the planet in the second only).
        let root = (s.gears.iter())
            .map(|g| (g.name.to_string(), over_cycle(&g.bending_mpa)))
            .collect();
        let mut contact = Vec::new();
        if let (Some(sun), Some(planet)) = (s.gears.first(), s.gears.last()) {
            contact.push(("sun mesh".to_string(), over_cycle(&sun.contact_mpa)));
            contact.push(("planet mesh".to_string(), over_cycle(&planet.contact_mpa)));
        }
        for (title, y_desc, series, name) in [
            (
                "Root stress",
                "root stress σF (MPa)",
                root,
                "tooth_root_stress",
            ),
            (
                "Contact stress",
                "contact stress σH (MPa)",
                contact,
                "tooth_contact_stress",
            ),
        ] {
            let figure = line(format!("{title}, tooth in mesh ({speed})"), y_desc, series);
            files.extend(save(&figure, &dir.join(name), options)?);
        }
    }
    if !arm_counts.is_empty() {
        let rate = rpm * d.arms as f64;
        let series = (arm_counts.iter())
            .map(|(arms, d)| {
                let rpm = d.carrier_speed_rad_s * 60.0 / std::f64::consts::TAU;
                let label = format!("{arms} arm sets, carrier {rpm:.0} r/min");
                (
                    label,
                    d.carrier_deg
                        .iter()
                        .copied()
                        .zip(d.input_torque_nm.iter().copied())
                        .collect(),
                )
            })
            .collect();
        let figure = line(
            format!("Input torque by arm count at {rate:.0} picks/min"),
            "torque T (N·m)",
            series,
        );
        files.extend(save(&figure, &dir.join("input_torque_by_arms"), options)?);
    }
    Ok(files)
}
