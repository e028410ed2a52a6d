//! Inverse dynamics of the planetary train at working speed (docs/dynamics.md): with the
//! carrier turning at a constant speed, the torque that drives it, the normal force at
//! each mesh, the force on every axle, and what the gearbox shakes into the frame, over
//! one carrier turn, for every arm set.
//!
//! Each arm set has two moving bodies on the carrier: the intermediate (its blank, with
//! layer B in the train with two pairs) about `O2`, and the planet with its arm about
//! `O3`. At a mesh the force passes through the pitch point (the instantaneous centre of
//! the two gears' motion relative to the carrier) along the line of action: the pitch
//! curves' common normal tilted by the teeth's pressure angle towards the flank that
//! carries the load. Solving the planet, then the intermediate, for their mesh forces
//! and the carrier for its torque is the Newton–Euler formulation; the energy balance
//! (power in = rate of kinetic and potential energy − power of the tip's loads) gives the
//! same torque independently, and both are reported.
//!
//! Arm k is arm I a k-th of a turn later (the same sun, the same place in the ground
//! frame), so the whole train's quantities at node j sum arm I's at nodes `j − k·n/arms`.

use crate::angle::unit;
use crate::blank::Blank;
use crate::curve::TAU;
use crate::dynamics_spec::DynamicsSpec;
use crate::error::{Error, Result};
use crate::events::Events;
use crate::flywheel::{Cycle, SpeedFluctuation};
use crate::planetary::{ArmState, Kinematics, PitchContact};
use crate::scene::Scene;
use crate::vec2::Vec2;
use serde::Serialize;

/// mm to m.
const M: f64 = 1e-3;

/// One carrier turn of the train at working speed. Vectors are `[x, y]` in the ground
/// frame (y up); moments and torques are about `+z` (counter-clockwise) unless said.
#[derive(Debug, Clone, Serialize)]
pub struct Dynamics {
    /// Carrier speed (rad/s).
    pub carrier_speed_rad_s: f64,
    /// Arm sets on the carrier.
    pub arms: usize,
    /// The teeth's pressure angle (°) that tilts the lines of action.
    pub pressure_angle_deg: f64,
    /// One arm set's bodies in their own frames (centres of mass in mm from the axle):
    /// the intermediate, the planet gear, the arm (in the planet's frame), and the planet
    /// with its arm as one body.
    pub intermediate: Blank,
    pub planet: Blank,
    pub arm: Blank,
    pub planet_with_arm: Blank,
    /// Where the carrier holds the intermediate's and the planet's axles in its own frame,
    /// whose x axis runs from the carrier axis to the intermediate (mm).
    pub intermediate_axle_on_carrier_mm: [f64; 2],
    pub planet_axle_on_carrier_mm: [f64; 2],
    /// Carrier angle θ of each node (°).
    pub carrier_deg: Vec<f64>,
    /// Torque that drives the carrier, all arm sets (N·m; positive: the drive delivers
    /// power), from the Newton–Euler balance of the bodies.
    pub input_torque_nm: Vec<f64>,
    /// The same from the energy balance.
    pub input_torque_energy_nm: Vec<f64>,
    /// Arm set I: the moment its meshes put on the intermediate about `O2`, and on the
    /// planet about `O3` (N·m): the torque each hinge would need were it driven.
    pub intermediate_moment_nm: Vec<f64>,
    pub planet_moment_nm: Vec<f64>,
    /// Arm set I: the normal force along the line of action at the sun–intermediate and at
    /// the intermediate–planet mesh (N).
    pub mesh_force_n: [Vec<f64>; 2],
    /// Arm set I: where each mesh's contact lies on its driving pitch curve (the sun's, then
    /// the planet's or layer B's), as that curve's own parameter `ψ` (rad): the teeth it
    /// loads.
    pub mesh_contact_psi_rad: [Vec<f64>; 2],
    /// Arm set I: the force the carrier puts on the intermediate's and on the planet's
    /// axle (N).
    pub intermediate_axle_n: Vec<[f64; 2]>,
    pub planet_axle_n: Vec<[f64; 2]>,
    /// All arm sets: the force the sun puts on its shaft, and the carrier on its bearing,
    /// its own weight included (N).
    pub sun_shaft_n: Vec<[f64; 2]>,
    pub carrier_bearing_n: Vec<[f64; 2]>,
    /// All arm sets: the inertial force and moment (about the carrier axis) the moving
    /// bodies put on the frame, `−Σ m·a_G` and `−Σ (J·α + r_G × m·a_G)` (N, N·m).
    pub shaking_force_n: Vec<[f64; 2]>,
    pub shaking_moment_nm: Vec<f64>,
    /// All arm sets: the moving bodies' kinetic energy over `½ω²` (kg·m²), the carrier's
    /// own inertia and the flywheel's left out; and the torque gravity and the tip's loads
    /// need whatever the speed (N·m). The input torque is `½·dIm/dφ·ω² + Q`.
    pub reduced_inertia_kg_m2: Vec<f64>,
    pub load_torque_nm: Vec<f64>,
    /// The carrier's own moment of inertia about its axis (kg·m²): with a flywheel's, what
    /// holds its speed when the drive's torque is constant ([`Dynamics::speed_with`]).
    pub carrier_inertia_kg_m2: f64,
    /// Arm set I's joints for an independent multibody check: the carrier's angle `φH`
    /// and the intermediate's and planet's angles relative to the carrier (rad), and
    /// their first and second derivatives per carrier radian.
    pub joint_rad: Vec<[f64; 3]>,
    pub joint_d1: Vec<[f64; 3]>,
    pub joint_d2: Vec<[f64; 3]>,
    pub summary: DynamicsSummary,
}

/// The cycle's extremes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DynamicsSummary {
    /// Input torque: largest magnitude, root mean square, mean, least and largest (N·m).
    pub torque_peak_nm: f64,
    pub torque_rms_nm: f64,
    pub torque_mean_nm: f64,
    pub torque_min_nm: f64,
    pub torque_max_nm: f64,
    /// `(T_max − T_min)/T_mean`; `None` when the mean is below 1 % of the RMS torque: the
    /// drive then mostly trades energy with the bodies (inertia and gravity average to
    /// zero over a turn) and a coefficient over the mean would say nothing.
    pub torque_fluctuation: Option<f64>,
    /// Largest mesh forces, sun–intermediate and intermediate–planet (N).
    pub mesh_force_peak_n: [f64; 2],
    /// Largest axle loads (N): intermediate, planet, sun shaft, carrier bearing.
    pub intermediate_axle_peak_n: f64,
    pub planet_axle_peak_n: f64,
    pub sun_shaft_peak_n: f64,
    pub carrier_bearing_peak_n: f64,
    /// Largest shaking force (N) and moment (N·m).
    pub shaking_force_peak_n: f64,
    pub shaking_moment_peak_nm: f64,
    /// Largest difference between the two formulations' torques, over the peak torque.
    pub formulations_rel_diff: f64,
}

/// The carrier's speed when the drive's torque is constant: computed on request, not with
/// every dynamics (a solve of the turn, a few for the flywheel needed).
impl Dynamics {
    fn cycle(&self) -> Cycle<'_> {
        Cycle {
            reduced_inertia_kg_m2: &self.reduced_inertia_kg_m2,
            load_torque_nm: &self.load_torque_nm,
            omega: self.carrier_speed_rad_s,
            carrier_inertia_kg_m2: self.carrier_inertia_kg_m2,
        }
    }

    /// The carrier's speed over the turn with a flywheel of `flywheel_kg_m2` on its axis.
    pub fn speed_with(&self, flywheel_kg_m2: f64) -> SpeedFluctuation {
        self.cycle().fluctuation(flywheel_kg_m2)
    }

    /// The least flywheel on the carrier's axis (kg·m², 0 when none is needed) that holds
    /// the coefficient of speed fluctuation to `allowed`.
    pub fn flywheel_needed_kg_m2(&self, allowed: f64) -> f64 {
        self.cycle().flywheel_for(allowed)
    }
}

/// A body's motion at one node: its centre of mass and, per carrier radian, its first
/// and second derivatives (mm), and its angle's.
struct Moving {
    body: Blank,
    axle: Vec2,
    g: Vec2,
    g_d1: Vec2,
    g_d2: Vec2,
    angle_d: [f64; 2],
}

impl Moving {
    /// `body` on an axle at `axle` (mm, turning with the carrier: `O' = σO⊥`, `O'' = −O`)
    /// at the angle of unit vector `direction` with derivatives `angle_d`.
    fn new(body: Blank, axle: Vec2, sigma: f64, direction: Vec2, angle_d: [f64; 2]) -> Self {
        let c = body.centroid_mm.rotated(direction);
        let [w, dw] = angle_d;
        Self {
            body,
            axle,
            g: axle + c,
            g_d1: axle.turn_90() * sigma + c.turn_90() * w,
            g_d2: -axle + c.turn_90() * dw - c * (w * w),
            angle_d,
        }
    }

    /// `m·(a_G − g)` (N) at carrier speed `omega` (rad/s) under gravity `gravity` (m/s²).
    fn force(&self, omega: f64, gravity: Vec2) -> Vec2 {
        (self.g_d2 * (omega * omega * M) - gravity) * self.body.mass_kg
    }

    /// `J·α` (N·m).
    fn spin(&self, omega: f64) -> f64 {
        self.body.inertia_kg_m2 * self.angle_d[1] * omega * omega
    }

    /// The moment about the axle the body needs beyond its weight (N·m).
    fn moment(&self, omega: f64, gravity: Vec2) -> f64 {
        self.spin(omega) + ((self.g - self.axle) * M).cross(self.force(omega, gravity))
    }

    /// Its kinetic energy over `½ω²` (kg·m²): `m·|v_G/ω|² + J·θ'²`.
    fn kinetic(&self) -> f64 {
        let v = self.g_d1 * M;
        self.body.mass_kg * v.dot(v) + self.body.inertia_kg_m2 * self.angle_d[0] * self.angle_d[0]
    }

    /// The power its weight takes per unit carrier speed (N·m): `−m·g·v_G/ω`.
    fn weight_power(&self, gravity: Vec2) -> f64 {
        -(gravity * self.body.mass_kg).dot(self.g_d1 * M)
    }

    /// The power it takes per unit carrier speed (N·m): `m(a_G − g)·v_G/ω + Jαθ'`.
    fn power(&self, omega: f64, gravity: Vec2) -> f64 {
        self.force(omega, gravity).dot(self.g_d1 * M) + self.spin(omega) * self.angle_d[0]
    }
}

/// The pitch point of two gears turning about `a` and `b` at `wa` and `wb` relative to
/// the carrier: where their velocities agree, on the line of centres.
fn pitch_point(a: Vec2, wa: f64, b: Vec2, wb: f64) -> Vec2 {
    a + (b - a) * (wb / (wb - wa))
}

/// The pitch curves' unit tangent and normal (away from the curve's centre) at `c`.
fn frame(c: &PitchContact) -> (Vec2, Vec2) {
    let (e, e_perp) = (c.towards, c.towards.turn_90());
    let t = e * c.rho_d1 + e_perp * c.rho;
    let n = e * c.rho - e_perp * c.rho_d1;
    let len = t.hypot2().sqrt();
    (t * (1.0 / len), n * (1.0 / len))
}

/// The mesh force on a gear about `centre` that must give it `moment` (N·m), passing
/// through `p` along the line of action: `sin α·n + s·cos α·t` with `n` into the gear,
/// on the flank `s` whose push turns it the right way; `alpha` is `e(α)`. Returns the
/// force's magnitude (N) and its vector.
fn mesh_force(moment: f64, centre: Vec2, p: Vec2, n: Vec2, t: Vec2, alpha: Vec2) -> (f64, Vec2) {
    let lever = (p - centre) * M;
    let s = if moment * lever.cross(t) >= 0.0 {
        1.0
    } else {
        -1.0
    };
    let d = n * alpha.y + t * (s * alpha.x);
    let magnitude = if moment == 0.0 {
        0.0
    } else {
        moment / lever.cross(d)
    };
    (magnitude, d * magnitude)
}

/// Arm set I at one node.
struct Node {
    torque: f64,
    torque_energy: f64,
    intermediate_moment: f64,
    planet_moment: f64,
    mesh: [f64; 2],
    contact_psi: [f64; 2],
    intermediate_axle: Vec2,
    planet_axle: Vec2,
    sun_load: Vec2,
    inertial_force: Vec2,
    inertial_moment: f64,
    kinetic: f64,
    load_torque: f64,
    joint: [[f64; 3]; 3],
}

/// The dynamics of `scene`'s train `kin` with its `events`: [`dynamics`] with the scene's
/// bodies and loads and its teeth's pressure angle.
pub fn scene_dynamics(kin: &Kinematics, events: &Events, scene: &Scene) -> Result<Dynamics> {
    dynamics(
        kin,
        events,
        &scene.dynamics,
        scene.gear.teeth.pressure_angle_deg,
    )
}

/// The dynamics of the train `kin` at its working speed (`kin.spec()`), with its events
/// (where the tip loads act), the scene's bodies and loads, and the teeth's pressure angle
/// `pressure_angle_deg`, at `spec.samples_per_turn` carrier angles.
pub fn dynamics(
    kin: &Kinematics,
    events: &Events,
    spec: &DynamicsSpec,
    pressure_angle_deg: f64,
) -> Result<Dynamics> {
    if !(pressure_angle_deg > 0.0 && pressure_angle_deg < 45.0) {
        return Err(Error::OutOfRange {
            name: "gear.teeth.pressure_angle_deg".into(),
            value: pressure_angle_deg,
            expected: "between 0 and 45° for the lines of action".into(),
        });
    }
    let train = kin.spec();
    let sigma = train.rotation.sign();
    let omega = kin.carrier_speed();
    let alpha = unit(pressure_angle_deg.to_radians());
    let gravity = Vec2::new(0.0, -spec.gravity_m_s2);
    let [intermediate, planet] = kin.blanks(spec.face_width_mm, spec.gear_density_kg_m3);
    let (phi0, beta0) = (train.phi0_deg.to_radians(), train.beta0_deg.to_radians());
    let less_beta0 = unit(-beta0);
    let arm = Blank::body(
        spec.arm_mass_kg,
        unit(beta0) * spec.arm_com_mm,
        spec.arm_inertia_kg_m2,
    );
    let planet_with_arm = planet.with(arm);
    let n = spec.samples_per_turn;
    if !(n >= 4 && n.is_multiple_of(kin.arms())) {
        return Err(Error::OutOfRange {
            name: "dynamics.samples_per_turn".into(),
            value: n as f64,
            expected: format!("at least 4 and a multiple of train.arms = {}", kin.arms()),
        });
    }
    let theta = |j: usize| TAU * j as f64 / n as f64;
    // Arm k at node j is arm I at node j − k·n/arms (no integer division per use).
    let lags: Vec<usize> = (0..kin.arms()).map(|k| k * n / kin.arms()).collect();
    let arm_node = |k: usize, j: usize| {
        let lag = lags[k];
        if j >= lag {
            j - lag
        } else {
            j + n - lag
        }
    };
    let two_pairs = kin.second_pair().is_some();
    let span = |a: f64, b: f64| crate::angle::wrap_turn(b - a);
    let [pick_from, pick_to] = events.picking_window_rad;
    let tip_load = |theta: f64, velocity: Vec2| {
        let picking = span(pick_from, theta) <= pick_to - pick_from;
        let gap = span(events.planting.carrier_rad, theta);
        let planting = gap.min(TAU - gap) <= 0.5 * spec.planting_span_deg.to_radians();
        let force = picking as u8 as f64 * spec.picking_force_n
            + planting as u8 as f64 * spec.planting_force_n;
        let speed = velocity.hypot2().sqrt();
        if force == 0.0 || speed == 0.0 {
            Vec2::ZERO
        } else {
            velocity * (-force / speed)
        }
    };
    let node = |(st, [contact_a, contact_b]): &(ArmState, [PitchContact; 2])| -> Node {
        let inter = Moving::new(intermediate, st.o2, sigma, unit(st.theta2), st.theta2_d);
        // The planet's direction from the arm's (at β0 to it): no trigonometry.
        let arm_dir = (st.tip - st.o3) * (1.0 / train.arm_length_mm);
        let plan = Moving::new(
            planet_with_arm,
            st.o3,
            sigma,
            arm_dir.rotated(less_beta0),
            st.theta3_d,
        );
        let load = tip_load(st.theta, st.tip_d1);
        // Rates relative to the carrier: the sun's −σ, the intermediate's, the planet's.
        let (w2, w3) = (st.theta2_d[0] - sigma, st.theta3_d[0] - sigma);
        let p1 = pitch_point(Vec2::ZERO, -sigma, st.o2, w2);
        let p2 = pitch_point(st.o2, w2, st.o3, w3);
        let (t1, n1) = frame(contact_a);
        let (t2, n_b) = frame(contact_b);
        // Into the planet: away from layer B's centre, or towards the planet's own.
        let n2 = if two_pairs { n_b } else { -n_b };
        // The planet with its arm about O3: the mesh supplies what inertia and weight
        // need beyond the tip's load.
        let planet_moment = plan.moment(omega, gravity) - ((st.tip - st.o3) * M).cross(load);
        let (f2, f2v) = mesh_force(planet_moment, st.o3, p2, n2, t2, alpha);
        let planet_axle = plan.force(omega, gravity) - f2v - load;
        // The intermediate about O2: the sun's mesh balances it and the planet's reaction.
        let intermediate_moment = inter.moment(omega, gravity);
        let from_sun = intermediate_moment + ((p2 - st.o2) * M).cross(f2v);
        let (f1, f1v) = mesh_force(from_sun, st.o2, p1, n1, t1, alpha);
        let intermediate_axle = inter.force(omega, gravity) - f1v + f2v;
        // The carrier at constant speed, its centre of mass on its axis.
        let torque_z = (st.o2 * M).cross(intermediate_axle) + (st.o3 * M).cross(planet_axle);
        let torque_energy =
            inter.power(omega, gravity) + plan.power(omega, gravity) - load.dot(st.tip_d1 * M);
        let inertial = |b: &Moving| b.g_d2 * (omega * omega * M * b.body.mass_kg);
        let inertial_moment = |b: &Moving| b.spin(omega) + (b.g * M).cross(inertial(b));
        let phi_h = phi0 + sigma * st.theta;
        Node {
            torque: sigma * torque_z,
            torque_energy,
            intermediate_moment,
            planet_moment,
            mesh: [f1, f2],
            contact_psi: [contact_a.psi, contact_b.psi],
            intermediate_axle,
            planet_axle,
            sun_load: -f1v,
            inertial_force: -(inertial(&inter) + inertial(&plan)),
            inertial_moment: -(inertial_moment(&inter) + inertial_moment(&plan)),
            kinetic: inter.kinetic() + plan.kinetic(),
            load_torque: inter.weight_power(gravity) + plan.weight_power(gravity)
                - load.dot(st.tip_d1 * M),
            joint: [
                [phi_h, st.theta2 - phi_h, st.theta3 - phi_h],
                [sigma, w2, w3],
                [0.0, st.theta2_d[1], st.theta3_d[1]],
            ],
        }
    };
    // At the kinematics' nodes (its node count a multiple of n) the state is read from them.
    let stride = (kin.len().is_multiple_of(n)).then(|| kin.len() / n);
    let state = |j: usize| match stride {
        Some(s) => kin.node_state_and_contacts(j * s),
        None => kin.state_and_contacts(theta(j)),
    };
    let nodes: Vec<Node> = (0..n).map(|j| node(&state(j))).collect();
    // Every arm set at node j: arm k is arm I at node j − k·n/arms. One pass sums them.
    let weight = gravity * spec.carrier_mass_kg;
    let mut input_torque_nm = Vec::with_capacity(n);
    let mut input_torque_energy_nm = Vec::with_capacity(n);
    let mut sun_shaft = Vec::with_capacity(n);
    let mut carrier_bearing = Vec::with_capacity(n);
    let mut shaking = Vec::with_capacity(n);
    let mut shaking_moment_nm = Vec::with_capacity(n);
    let mut reduced_inertia_kg_m2 = Vec::with_capacity(n);
    let mut load_torque_nm = Vec::with_capacity(n);
    for j in 0..n {
        let (mut torque, mut torque_energy, mut kinetic, mut load, mut moment) =
            (0.0, 0.0, 0.0, 0.0, 0.0);
        let (mut sun, mut axles, mut inertial) = (Vec2::ZERO, Vec2::ZERO, Vec2::ZERO);
        for k in 0..kin.arms() {
            let x = &nodes[arm_node(k, j)];
            torque += x.torque;
            torque_energy += x.torque_energy;
            kinetic += x.kinetic;
            load += x.load_torque;
            moment += x.inertial_moment;
            sun += x.sun_load;
            axles += x.intermediate_axle + x.planet_axle;
            inertial += x.inertial_force;
        }
        input_torque_nm.push(torque);
        input_torque_energy_nm.push(torque_energy);
        sun_shaft.push(sun);
        carrier_bearing.push(-axles + weight);
        shaking.push(inertial);
        shaking_moment_nm.push(moment);
        reduced_inertia_kg_m2.push(kinetic);
        load_torque_nm.push(load);
    }
    let xy = |v: Vec2| [v.x, v.y];
    let o3_rel = (state(0).0.o3).rotated(unit(-nodes[0].joint[0][0]));
    let peak = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let peak_vec = |v: &[Vec2]| v.iter().fold(0.0f64, |m, x| m.max(x.hypot2().sqrt()));
    let column = |f: &dyn Fn(&Node) -> Vec2| nodes.iter().map(f).collect::<Vec<_>>();
    let intermediate_axle = column(&|x| x.intermediate_axle);
    let planet_axle = column(&|x| x.planet_axle);
    let mesh_force_n = [0, 1].map(|i| nodes.iter().map(|x| x.mesh[i]).collect::<Vec<_>>());
    let mesh_contact_psi_rad =
        [0, 1].map(|i| nodes.iter().map(|x| x.contact_psi[i]).collect::<Vec<_>>());
    let mean = input_torque_nm.iter().sum::<f64>() / n as f64;
    let rms = (input_torque_nm.iter().map(|t| t * t).sum::<f64>() / n as f64).sqrt();
    let (min, max) = (input_torque_nm.iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
            (lo.min(t), hi.max(t))
        });
    let torque_peak_nm = peak(&input_torque_nm);
    let diff = (input_torque_nm.iter().zip(&input_torque_energy_nm))
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let summary = DynamicsSummary {
        torque_peak_nm,
        torque_rms_nm: rms,
        torque_mean_nm: mean,
        torque_min_nm: min,
        torque_max_nm: max,
        torque_fluctuation: (mean > 0.01 * rms).then(|| (max - min) / mean),
        mesh_force_peak_n: [peak(&mesh_force_n[0]), peak(&mesh_force_n[1])],
        intermediate_axle_peak_n: peak_vec(&intermediate_axle),
        planet_axle_peak_n: peak_vec(&planet_axle),
        sun_shaft_peak_n: peak_vec(&sun_shaft),
        carrier_bearing_peak_n: peak_vec(&carrier_bearing),
        shaking_force_peak_n: peak_vec(&shaking),
        shaking_moment_peak_nm: peak(&shaking_moment_nm),
        formulations_rel_diff: if torque_peak_nm > 0.0 {
            diff / torque_peak_nm
        } else {
            diff
        },
    };
    let result = Dynamics {
        carrier_speed_rad_s: omega,
        arms: kin.arms(),
        pressure_angle_deg,
        intermediate,
        planet,
        arm,
        planet_with_arm,
        intermediate_axle_on_carrier_mm: [kin.carrier_distance(), 0.0],
        planet_axle_on_carrier_mm: xy(o3_rel),
        carrier_deg: (0..n).map(|j| theta(j).to_degrees()).collect(),
        input_torque_nm,
        input_torque_energy_nm,
        intermediate_moment_nm: nodes.iter().map(|x| x.intermediate_moment).collect(),
        planet_moment_nm: nodes.iter().map(|x| x.planet_moment).collect(),
        mesh_force_n,
        mesh_contact_psi_rad,
        intermediate_axle_n: intermediate_axle.into_iter().map(xy).collect(),
        planet_axle_n: planet_axle.into_iter().map(xy).collect(),
        sun_shaft_n: sun_shaft.into_iter().map(xy).collect(),
        carrier_bearing_n: carrier_bearing.into_iter().map(xy).collect(),
        shaking_force_n: shaking.into_iter().map(xy).collect(),
        shaking_moment_nm,
        reduced_inertia_kg_m2,
        load_torque_nm,
        carrier_inertia_kg_m2: spec.carrier_inertia_kg_m2,
        joint_rad: nodes.iter().map(|x| x.joint[0]).collect(),
        joint_d1: nodes.iter().map(|x| x.joint[1]).collect(),
        joint_d2: nodes.iter().map(|x| x.joint[2]).collect(),
        summary,
    };
    if !result.input_torque_nm.iter().all(|t| t.is_finite()) {
        return Err(Error::OutOfRange {
            name: "dynamics".into(),
            value: f64::NAN,
            expected: "finite torques: a mesh whose line of action passes through a gear's \
                       centre cannot turn it"
                .into(),
        });
    }
    Ok(result)
}
