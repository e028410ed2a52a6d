//! The planetary transplanting mechanism: fixed sun, intermediate (conjugate) and planet
//! (congruent to the sun) gears on a carrier, an arm on each planet (spec §2); three arm
//! sets as in the paper, or 1 to 4 (`TrainSpec::arms`).

use crate::angle::unit;
use crate::curve::{PitchCurve, TAU};
use crate::error::{finite, length, positive, Error, Result};
use crate::gear::{GearPair, ModuleReport, ModuleRule, Rotation, SampleGrid};
use crate::quadrature::{DriftInverse, MonotoneDrift, SpectralIntegrator};
use crate::resolution::Resolution;
use crate::vec2::Vec2;
use serde::{Deserialize, Serialize};
use std::sync::{Arc, Mutex};

/// Which of the two lines through the tip at distance `H1` from `O3` is the pusher axis,
/// seen looking from `O3` along the arm towards the tip.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PusherSide {
    /// The axis is turned counter-clockwise from the arm line `O3 → D`.
    Left,
    /// The axis is turned clockwise from the arm line `O3 → D`.
    Right,
}

/// How the sun's pitch curve (its control angles) sits in the ground frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SunFrame {
    /// The sun is installed turned by `Φ0` (paper eq. 5, `φ1 = φ0`): changing `Φ0` tilts the
    /// whole mechanism and its trajectory, as the paper's §4.2 says it does.
    Installed,
    /// The control angles are measured in the ground frame (spec §2 read literally):
    /// `Φ0` then only shifts which carrier angle is called zero.
    Ground,
}

/// The train's and arm's geometric parameters (angles in degrees, lengths in mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TrainSpec {
    /// Installation angle `Φ0` of the carrier (deg). Paper: 86.
    pub phi0_deg: f64,
    /// Arm installation angle `β0` relative to the planet (deg). Paper: −29.
    pub beta0_deg: f64,
    /// Distance `S` from the planet centre to the arm tip (mm). Paper: 145.
    pub arm_length_mm: f64,
    /// Distance `H1` from the planet centre to the pusher axis (mm). Paper: 65.
    pub pusher_offset_mm: f64,
    /// Carrier corner angle `γ0` between `O1O2` and `O2O3` (deg). Paper: −53.
    pub gamma0_deg: f64,
    /// Carrier rotation sense. Paper: clockwise.
    pub rotation: Rotation,
    /// Side of the pusher axis.
    pub pusher_side: PusherSide,
    /// How the sun's control angles sit in the ground frame.
    pub sun_frame: SunFrame,
    /// Carrier speed (r/min): 60 gives the paper's 180 picks per minute. Not used when
    /// `picks_per_minute` is set.
    pub carrier_speed_rpm: f64,
    /// Arm sets on the carrier, evenly spaced (1 to 4): each a planet, an intermediate
    /// and an arm. The paper's mechanism has three; the classic rotary one two. Left out
    /// of a written scene while it is 3.
    #[serde(skip_serializing_if = "TrainSpec::is_default_arms")]
    pub arms: usize,
    /// The picking rate (picks per minute): when set, the carrier turns at
    /// `picks_per_minute / arms` r/min, so trains with other arm counts compare at the
    /// same rate. Left out of a written scene while unset.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub picks_per_minute: Option<f64>,
}

impl Default for TrainSpec {
    fn default() -> Self {
        Self {
            phi0_deg: 86.0,
            beta0_deg: -29.0,
            arm_length_mm: 145.0,
            pusher_offset_mm: 65.0,
            gamma0_deg: -53.0,
            rotation: Rotation::Clockwise,
            pusher_side: PusherSide::Left,
            sun_frame: SunFrame::Installed,
            carrier_speed_rpm: 60.0,
            arms: 3,
            picks_per_minute: None,
        }
    }
}

/// The arms' names, in order: arm k lags arm I by k·360°/arms.
pub const ARM_NAMES: [&str; TrainSpec::MAX_ARMS] = ["I", "II", "III", "IV"];

impl TrainSpec {
    /// Most arm sets on a carrier.
    pub const MAX_ARMS: usize = 4;

    /// Whether `arms` is the default arm count (a written scene leaves it out then).
    fn is_default_arms(arms: &usize) -> bool {
        *arms == Self::default().arms
    }

    /// The carrier's speed (r/min): from the picking rate when it is set.
    pub fn carrier_rpm(&self) -> f64 {
        match self.picks_per_minute {
            Some(rate) => rate / self.arms as f64,
            None => self.carrier_speed_rpm,
        }
    }

    /// Picks per minute: one per arm per carrier turn.
    pub fn picking_rate(&self) -> f64 {
        self.carrier_rpm() * self.arms as f64
    }

    /// The sun's own-frame parameter at the contact when the carrier angle is 0 (rad):
    /// the contact then sits at `psi(θ) = psi_start + σθ`.
    pub fn psi_start(&self) -> f64 {
        match self.sun_frame {
            SunFrame::Installed => 0.0,
            SunFrame::Ground => self.phi0_deg.to_radians(),
        }
    }

    /// Angle by which the sun's pitch curve is turned in the ground frame (rad).
    pub fn sun_angle(&self) -> f64 {
        match self.sun_frame {
            SunFrame::Installed => self.phi0_deg.to_radians(),
            SunFrame::Ground => 0.0,
        }
    }

    /// Checks every parameter, naming the bad one.
    pub fn validate(&self) -> Result<()> {
        finite("train.phi0_deg", self.phi0_deg)?;
        finite("train.beta0_deg", self.beta0_deg)?;
        finite("train.gamma0_deg", self.gamma0_deg)?;
        positive("train.arm_length_mm", self.arm_length_mm)?;
        length("train.arm_length_mm", self.arm_length_mm)?;
        positive("train.carrier_speed_rpm", self.carrier_speed_rpm)?;
        if !(1..=Self::MAX_ARMS).contains(&self.arms) {
            return Err(Error::OutOfRange {
                name: "train.arms".into(),
                value: self.arms as f64,
                expected: format!("1 to {} arm sets", Self::MAX_ARMS),
            });
        }
        if let Some(rate) = self.picks_per_minute {
            positive("train.picks_per_minute", rate)?;
            if rate > 1e6 {
                return Err(Error::OutOfRange {
                    name: "train.picks_per_minute".into(),
                    value: rate,
                    expected: "at most 1e6 picks per minute".into(),
                });
            }
        }
        // Speeds beyond this overflow what is derived from them (tip speeds in m/s).
        if self.carrier_speed_rpm > 1e6 {
            return Err(Error::OutOfRange {
                name: "train.carrier_speed_rpm".into(),
                value: self.carrier_speed_rpm,
                expected: "at most 1e6 rpm".into(),
            });
        }
        finite("train.pusher_offset_mm", self.pusher_offset_mm)?;
        if !(self.pusher_offset_mm >= 0.0 && self.pusher_offset_mm < self.arm_length_mm) {
            return Err(Error::OutOfRange {
                name: "train.pusher_offset_mm".into(),
                value: self.pusher_offset_mm,
                expected: format!("0 <= H1 < S = {} mm", self.arm_length_mm),
            });
        }
        let gamma = self.gamma0_deg.rem_euclid(360.0);
        if gamma == 180.0 || gamma == 0.0 {
            return Err(Error::OutOfRange {
                name: "train.gamma0_deg".into(),
                value: self.gamma0_deg,
                expected: "not a multiple of 180° (the planet would sit on the sun or on the intermediate)".into(),
            });
        }
        Ok(())
    }
}

/// The state of arm I at one carrier angle: positions (mm), angles (rad) and the tip's
/// derivatives per radian of carrier angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmState {
    /// Carrier angle θ (rad).
    pub theta: f64,
    /// Intermediate centre `O2`.
    pub o2: Vec2,
    /// Planet centre `O3`.
    pub o3: Vec2,
    /// Planet orientation `theta3` (rad).
    pub theta3: f64,
    /// Intermediate orientation (rad). Its own pitch curve carries the material point of sun
    /// parameter ψ at own angle `χ(ψ) = −∫_{ψ_start}^{ψ} ρ/(a−ρ)`, radius `a − ρ(ψ)`.
    pub theta2: f64,
    /// Sun own-frame parameter of the intermediate's material point now at the planet mesh (rad).
    pub psi_planet_mesh: f64,
    /// Arm tip `D`.
    pub tip: Vec2,
    /// `dD/dθ` (mm/rad).
    pub tip_d1: Vec2,
    /// `d²D/dθ²` (mm/rad²).
    pub tip_d2: Vec2,
    /// Pusher-axis direction angle (rad), pointing from the arm towards the tip.
    pub pusher_angle: f64,
}

/// What the gears alone determine, shared by every assembly of them
/// ([`Kinematics::reassembled`]): the pair on the carrier grid, `Φ`'s derivatives, and the
/// module (computed once per rule).
#[derive(Debug)]
struct SolvedPair {
    /// The sun–intermediate pair, sampled on the carrier grid: node `j` is the sun's
    /// own-frame parameter `psi_start + σθ_j` at the contact, and the pair's driven angle at
    /// the node is `Φ(θ_j)`, the intermediate's turn relative to the carrier.
    pair: GearPair,
    /// `Φ''(θ_j) = g̃'` (`Φ' = g̃` is the pair's ratio at the nodes).
    dg: Vec<f64>,
    /// `(Φ⁻¹)' = 1/g̃` and `(Φ⁻¹)'' = −g̃'/g̃³` at the nodes.
    inv_d1: Vec<f64>,
    inv_d2: Vec<f64>,
    /// `Φ(2π) − Φ(0)` (rad; 2π up to the closure error).
    phi_period: f64,
    /// The module under the last rule asked.
    module: Mutex<Option<(ModuleRule, ModuleReport)>>,
}

impl SolvedPair {
    fn new(pair: GearPair, sigma: f64) -> Self {
        let a = pair.centre_distance();
        let dg: Vec<f64> = (pair.samples().iter())
            .map(|p| sigma * a * p.d1 / ((a - p.rho) * (a - p.rho)))
            .collect();
        let (inv_d1, inv_d2) = (pair.ratio_nodes().iter())
            .zip(&dg)
            .map(|(&g, &dg)| DriftInverse::node_derivatives(g, dg))
            .unzip();
        let phi_period = pair.phi2_mean_rate() * TAU;
        Self {
            pair,
            dg,
            inv_d1,
            inv_d2,
            phi_period,
            module: Mutex::new(None),
        }
    }
}

/// The sampled motion of arm I over one carrier turn, plus what is needed to evaluate it at
/// any carrier angle. Arm k (of n) follows at `θ − k·360°/n`: with three, II and III at
/// `θ − 120°` and `θ − 240°`.
///
/// The paper's train: arm I's tip traces a closed loop over one carrier turn.
///
/// ```
/// use noncirc_core::{Kinematics, Scene};
///
/// let scene = Scene::default(); // the three-arm paper's design
/// let curve = scene.gear.curve.build().unwrap();
/// let kin = Kinematics::solve(&curve, &scene.train, &scene.resolution).unwrap();
/// let tips = kin.tips();
/// assert_eq!(tips.len(), kin.len());
/// // One sample per carrier step over a whole turn; the loop closes on itself.
/// let step = (tips[1] - tips[0]).hypot();
/// assert!((tips[tips.len() - 1] - tips[0]).hypot() < 3.0 * step);
/// ```
#[derive(Debug, Clone)]
pub struct Kinematics {
    /// The gears, shared with every reassembly of them.
    gears: Arc<SolvedPair>,
    spec: TrainSpec,
    sigma: f64,
    /// The spec's angles in radians: `Φ0`, `γ0`, `β0`, the sun's own-frame parameter at the
    /// contact for θ = 0 and the sun's turn in the ground frame.
    phi0: f64,
    gamma0: f64,
    beta0: f64,
    psi_start: f64,
    sun_angle: f64,
    /// Pusher-axis direction less the planet orientation (rad): `β0 ± asin(H1/S)`.
    pusher_turn: f64,
    /// Mesh delay of the intermediate between its two meshes (rad).
    delay: f64,
    /// Distance at which the carrier holds each gear from the last (mm): the pair's
    /// centre distance plus the assembly's error ([`Kinematics::reassembled`]).
    carrier_a: f64,
    /// Per node: `θ_s`, planet orientation, planet centre, tip.
    theta_s: Vec<f64>,
    theta3: Vec<f64>,
    o3: Vec<Vec2>,
    tip: Vec<Vec2>,
    /// Per node, the arm's direction `unit(θ3 + β0)`: a reassembly turns it.
    arm_dir: Vec<Vec2>,
}

impl Kinematics {
    /// Samples the sun on the carrier grid, closes the pair and moves arm I through one turn.
    pub fn solve(curve: &PitchCurve, spec: &TrainSpec, resolution: &Resolution) -> Result<Self> {
        resolution.validate()?;
        Self::solve_with(
            curve.clone(),
            spec,
            resolution,
            &mut SpectralIntegrator::new(resolution.samples_per_turn),
        )
    }

    /// As [`Kinematics::solve`], taking the curve and reusing a planned integrator of
    /// `samples_per_turn` points.
    pub(crate) fn solve_with(
        curve: PitchCurve,
        spec: &TrainSpec,
        resolution: &Resolution,
        integrator: &mut SpectralIntegrator,
    ) -> Result<Self> {
        spec.validate()?;
        let n = resolution.samples_per_turn;
        if !n.is_multiple_of(spec.arms) {
            return Err(Error::OutOfRange {
                name: "resolution.samples_per_turn".into(),
                value: n as f64,
                expected: format!(
                    "a multiple of train.arms = {} (each arm a whole number of samples behind \
                     the last)",
                    spec.arms
                ),
            });
        }
        let grid = SampleGrid {
            start: spec.psi_start(),
            sense: spec.rotation,
        };
        let pair = GearPair::solve_on(curve, *resolution, grid, integrator)?;
        let gears = Arc::new(SolvedPair::new(pair, spec.rotation.sign()));
        Ok(Self::assemble(gears, spec, 0.0, None))
    }

    /// The same gears assembled anew: another `spec` (its `Φ0`, `β0`, `γ0`, `S`, `H1`) and
    /// the carrier holding the gears `centre_offset_mm` further apart than their centre
    /// distance (a bore error: the gears then mesh with backlash, at the same ratio).
    /// Reuses the closed pair: no closure, no re-sampling. Refused where the pair's grid
    /// would change (another rotation sense, or `Φ0` under [`SunFrame::Ground`]): solve
    /// those anew.
    pub fn reassembled(&self, spec: &TrainSpec, centre_offset_mm: f64) -> Result<Self> {
        spec.validate()?;
        finite("centre distance offset (mm)", centre_offset_mm)?;
        if spec.rotation != self.spec.rotation || spec.psi_start() != self.psi_start {
            return Err(Error::OutOfRange {
                name: "train.phi0_deg".into(),
                value: spec.phi0_deg,
                expected: format!(
                    "the solved train's sampling grid (Φ0 = {}° with the sun measured in the \
                     ground frame, rotation {:?}): solve the train anew",
                    self.spec.phi0_deg, self.spec.rotation
                ),
            });
        }
        let a = self.centre_distance() + centre_offset_mm;
        if a <= 0.0 {
            return Err(Error::OutOfRange {
                name: "centre distance offset (mm)".into(),
                value: centre_offset_mm,
                expected: format!("above -{} mm", self.centre_distance()),
            });
        }
        // The same carrier angle γ0 keeps θ_s: the assembly then only turns and moves.
        let same_carrier = spec.gamma0_deg == self.spec.gamma0_deg;
        Ok(Self::assemble(
            self.gears.clone(),
            spec,
            centre_offset_mm,
            same_carrier.then_some(self),
        ))
    }

    /// Places the arm for `spec` on a solved pair (`spec` valid, the pair on its grid). With
    /// `same_carrier`, a train on the same pair with the same `γ0`, its `θ_s` are reused
    /// and its arm directions turned (no inversion, no trigonometry per node): `Φ0` turns
    /// the planets, `β0` the arm on them.
    fn assemble(
        gears: Arc<SolvedPair>,
        spec: &TrainSpec,
        centre_offset_mm: f64,
        same_carrier: Option<&Kinematics>,
    ) -> Self {
        let sigma = spec.rotation.sign();
        let n = gears.pair.samples().len();
        let h = TAU / n as f64;
        let a = gears.pair.centre_distance();
        let gamma0 = spec.gamma0_deg.to_radians();
        let beta0 = spec.beta0_deg.to_radians();
        let delay = (sigma * (gamma0 - std::f64::consts::PI)).rem_euclid(TAU);
        let mut kin = Self {
            gears,
            spec: *spec,
            sigma,
            phi0: spec.phi0_deg.to_radians(),
            gamma0,
            beta0,
            psi_start: spec.psi_start(),
            sun_angle: spec.sun_angle(),
            pusher_turn: beta0
                + match spec.pusher_side {
                    PusherSide::Left => 1.0,
                    PusherSide::Right => -1.0,
                } * (spec.pusher_offset_mm / spec.arm_length_mm).asin(),
            delay,
            carrier_a: a + centre_offset_mm,
            theta_s: Vec::new(),
            theta3: vec![0.0; n],
            o3: vec![Vec2::ZERO; n],
            tip: vec![Vec2::ZERO; n],
            arm_dir: vec![Vec2::ZERO; n],
        };
        // The arms' turn relative to `same_carrier`'s: θ3 moves with the sun's angle, the
        // arm with β0 on top.
        let turn = same_carrier.map(|src| {
            let planets = kin.sun_angle - src.sun_angle;
            (planets, unit(planets + beta0 - src.beta0))
        });
        kin.theta_s = match same_carrier {
            Some(src) => src.theta_s.clone(),
            None => {
                // θ_s at every node: sorted targets, so each cell search starts at the last.
                let inverse = kin.phi_inverse();
                let mut hint = 0;
                (kin.gears.pair.phi2_nodes().iter())
                    .map(|&phi| {
                        let (ts, cell) = inverse.eval(phi - delay, hint);
                        hint = cell;
                        ts
                    })
                    .collect()
            }
        };
        // Carrier directions e(φH) and e(φH + γ0), turned by σh per node (no trigonometry).
        let step = unit(sigma * h);
        let (mut e1, mut e2) = (unit(kin.phi0), unit(kin.phi0 + gamma0));
        let carrier_a = kin.carrier_a;
        for j in 0..n {
            let theta = h * j as f64;
            let ts = kin.theta_s[j];
            let o3 = (e1 + e2) * carrier_a;
            (e1, e2) = (e1.rotated(step), e2.rotated(step));
            let (theta3, arm_dir) = match (same_carrier, turn) {
                (Some(src), Some((planets, arm))) => {
                    (src.theta3[j] + planets, src.arm_dir[j].rotated(arm))
                }
                _ => {
                    let theta3 =
                        kin.sun_angle + sigma * (theta - ts) + gamma0 + std::f64::consts::PI;
                    (theta3, unit(theta3 + beta0))
                }
            };
            kin.theta3[j] = theta3;
            kin.o3[j] = o3;
            kin.arm_dir[j] = arm_dir;
            kin.tip[j] = o3 + arm_dir * spec.arm_length_mm;
        }
        kin
    }

    /// `Φ(θ)`, the intermediate's turn relative to the carrier, as an invertible function.
    fn phi_fn(&self) -> MonotoneDrift<'_> {
        MonotoneDrift {
            value: self.gears.pair.phi2_nodes(),
            d1: self.gears.pair.ratio_nodes(),
            d2: &self.gears.dg,
            period_increment: self.gears.phi_period,
        }
    }

    /// `Φ⁻¹`, interpolated from the same nodes.
    fn phi_inverse(&self) -> DriftInverse<'_> {
        DriftInverse {
            forward: self.phi_fn(),
            d1: &self.gears.inv_d1,
            d2: &self.gears.inv_d2,
        }
    }

    /// The sun–intermediate gear pair on the carrier grid (the planet–intermediate mesh is
    /// the same pair: the planet is congruent to the sun).
    pub fn pair(&self) -> &GearPair {
        &self.gears.pair
    }

    /// The pair's module under `rule` (spec §1.4), computed once per rule for the gears
    /// and every reassembly of them.
    pub fn module(&self, rule: &ModuleRule) -> ModuleReport {
        let mut cache = self.gears.module.lock().unwrap_or_else(|e| e.into_inner());
        match *cache {
            Some((r, report)) if r == *rule => report,
            _ => {
                let report = self.gears.pair.module(rule);
                *cache = Some((*rule, report));
                report
            }
        }
    }

    /// Centre distance `a` shared by both meshes (mm).
    pub fn centre_distance(&self) -> f64 {
        self.gears.pair.centre_distance()
    }

    /// Least and largest radius of the sun's pitch curve (mm).
    pub fn radius_range(&self) -> (f64, f64) {
        self.gears.pair.radius_range()
    }

    /// Distance at which the carrier holds each gear centre from the last (mm): the
    /// centre distance, plus the bore error of a [`Kinematics::reassembled`] train.
    pub fn carrier_distance(&self) -> f64 {
        self.carrier_a
    }

    /// Distance from the carrier axis to a planet centre (mm): `2a·|cos(γ0/2)|`.
    pub fn planet_radius(&self) -> f64 {
        2.0 * self.carrier_a * (self.gamma0 / 2.0).cos().abs()
    }

    /// The sun's pitch curve.
    pub fn curve(&self) -> &PitchCurve {
        self.gears.pair.curve()
    }

    /// The train parameters.
    pub fn spec(&self) -> &TrainSpec {
        &self.spec
    }

    /// The resolution that produced this motion.
    pub fn resolution(&self) -> Resolution {
        self.gears.pair.resolution()
    }

    /// Number of carrier-angle samples per turn.
    pub fn len(&self) -> usize {
        self.tip.len()
    }

    /// Whether there are no samples (never, for a solved motion).
    pub fn is_empty(&self) -> bool {
        self.tip.is_empty()
    }

    /// Carrier angle of node `j` (rad).
    pub fn theta(&self, j: usize) -> f64 {
        TAU * j as f64 / self.len() as f64
    }

    /// Tip of arm I at the nodes (mm).
    pub fn tips(&self) -> &[Vec2] {
        &self.tip
    }

    /// Planet centres of arm I at the nodes (mm).
    pub fn planet_centres(&self) -> &[Vec2] {
        &self.o3
    }

    /// Planet orientations of arm I at the nodes (rad).
    pub fn planet_angles(&self) -> &[f64] {
        &self.theta3
    }

    /// Arm sets on the carrier.
    pub fn arms(&self) -> usize {
        self.spec.arms
    }

    /// Carrier angle by which arm `k` lags arm I (rad): `k·2π/arms`.
    pub fn arm_lag(&self, k: usize) -> f64 {
        TAU * (k % self.arms()) as f64 / self.arms() as f64
    }

    /// Node index of arm `k` (0 … arms − 1) at node `j` of the carrier: arm k lags arm I
    /// by k·360°/arms (the samples per turn are a multiple of the arm count).
    pub fn arm_node(&self, k: usize, j: usize) -> usize {
        let n = self.len();
        let lag = (k % self.arms()) * n / self.arms();
        // No integer division on the usual path (`j < n`): this runs at every node.
        let j = if j < n { j } else { j % n };
        if j >= lag {
            j - lag
        } else {
            j + n - lag
        }
    }

    /// The node at or below carrier angle `u` (rad, any real), wrapped into one turn.
    fn node_below(&self, u: f64) -> usize {
        let n = self.len();
        // `rem_euclid` is a library call (fmod): only off the usual range.
        let u = if (0.0..TAU).contains(&u) {
            u
        } else {
            u.rem_euclid(TAU)
        };
        ((u * (n as f64 / TAU)) as usize).min(n - 1)
    }

    /// `g̃(u) = g(psi_start + σu)` and `g̃'(u)` at any carrier angle, from the curve itself.
    fn ratio_at(&self, u: f64) -> (f64, f64) {
        let a = self.centre_distance();
        let p = self.curve().eval(self.psi_start + self.sigma * u);
        let gap = a - p.rho;
        (p.rho / gap, self.sigma * a * p.d1 / (gap * gap))
    }

    /// The full state of arm I at any carrier angle `theta` (rad): positions, the tip's
    /// first two derivatives, orientations and the pusher-axis angle.
    pub fn state_at(&self, theta: f64) -> ArmState {
        let sigma = self.sigma;
        let (big_phi, _) = self.phi_fn().eval(theta);
        // Start the cell search where node ⌊θ/h⌋'s own θ_s lies: O(1) instead of O(N).
        let hint = self.node_below(self.theta_s[self.node_below(theta)]);
        let (ts, _) = self.phi_inverse().eval(big_phi - self.delay, hint);
        let (gamma0, beta0) = (self.gamma0, self.beta0);
        let s = self.spec.arm_length_mm;
        let a = self.carrier_a;
        let theta3 = self.sun_angle + sigma * (theta - ts) + gamma0 + std::f64::consts::PI;
        let (g_t, dg_t) = self.ratio_at(theta);
        let (g_s, dg_s) = self.ratio_at(ts);
        let ts1 = g_t / g_s;
        let ts2 = (dg_t * g_s - g_t * dg_s * ts1) / (g_s * g_s);
        let th1 = sigma * (1.0 - ts1);
        let th2 = -sigma * ts2;
        let phi_h = self.phi0 + sigma * theta;
        let (e1, e2) = (unit(phi_h), unit(phi_h + gamma0));
        let o2 = e1 * a;
        let o3 = (e1 + e2) * a;
        let u = unit(theta3 + beta0);
        let tip = o3 + u * s;
        // O3' = σ a (e1⊥ + e2⊥), O3'' = −a (e1 + e2); u' = θ3' u⊥.
        let o3_d1 = (e1 + e2).turn_90() * (sigma * a);
        let o3_d2 = (e1 + e2) * -a;
        let tip_d1 = o3_d1 + u.turn_90() * (s * th1);
        let tip_d2 = o3_d2 + u.turn_90() * (s * th2) - u * (s * th1 * th1);
        // Intermediate: the material point of sun parameter ψ sits at its own angle
        // χ(ψ) = −∫_{ψ_start}^{ψ} g = −σΦ(θ) and meets the sun at the absolute direction φH + π.
        let theta2 = phi_h + std::f64::consts::PI + sigma * big_phi;
        ArmState {
            theta,
            o2,
            o3,
            theta3,
            theta2,
            psi_planet_mesh: self.psi_start + sigma * ts,
            tip,
            tip_d1,
            tip_d2,
            pusher_angle: self.pusher_angle(theta3),
        }
    }

    /// Arm I's intermediate at node `j`: its centre `O2` (mm) and orientation `theta2`
    /// (rad), as [`Kinematics::state_at`] gives them at the node, from the node's values.
    pub fn intermediate_at(&self, j: usize) -> (Vec2, f64) {
        let phi_h = self.phi0 + self.sigma * self.theta(j);
        let big_phi = self.gears.pair.phi2_nodes()[j];
        (
            unit(phi_h) * self.carrier_a,
            phi_h + std::f64::consts::PI + self.sigma * big_phi,
        )
    }

    /// Pusher-axis direction (rad) for planet orientation `theta3`.
    pub fn pusher_angle(&self, theta3: f64) -> f64 {
        theta3 + self.pusher_turn
    }

    /// Carrier angular speed (rad/s).
    pub fn carrier_speed(&self) -> f64 {
        self.spec.carrier_rpm() * TAU / 60.0
    }
}
