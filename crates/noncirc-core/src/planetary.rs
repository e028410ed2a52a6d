//! The planetary transplanting mechanism: fixed sun, intermediate and planet gears on a
//! carrier, an arm on each planet (spec §2); three arm sets as in the paper, or 1 to 4
//! (`TrainSpec::arms`). In the paper's train the intermediate is the sun's conjugate and
//! meshes with a planet congruent to the sun; in the train with two pairs the
//! intermediate carries a second pitch curve of its own (its layer B, on the same shaft),
//! which drives a planet that is that curve's conjugate.

use crate::angle::{node_index, unit, units};
use crate::blank::Blank;
use crate::curve::{PitchCurve, Polar, TAU};
use crate::error::{finite, length, positive, Error, Result};
use crate::gear::{GearPair, ModuleReport, ModuleRule, Rotation, SampleGrid, SampledDriver};
use crate::quadrature::{DriftInverse, MonotoneDrift, SpectralIntegrator};
use crate::resolution::Resolution;
use crate::vec2::Vec2;
use serde::{Deserialize, Serialize};
use std::sync::{Arc, Mutex};
use wide::f64x2;

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

/// Moves for the tests of reassembled trains: the train moved by `d` (each in [-1, 1]):
/// Φ0 and β0 by up to 0.2°·`size`, S and H1 by up to 0.4 mm; and that train moved again
/// (Φ0 by +0.1°, β0 by −0.1°), a reassembly of a reassembly.
#[cfg(test)]
pub(crate) fn moved_for_tests(spec: &TrainSpec, d: [f64; 4], size: f64) -> [TrainSpec; 2] {
    let [dphi, dbeta, ds, dh] = d;
    let moved = TrainSpec {
        phi0_deg: spec.phi0_deg + 0.2 * size * dphi,
        beta0_deg: spec.beta0_deg + 0.2 * size * dbeta,
        arm_length_mm: spec.arm_length_mm + 0.4 * ds,
        pusher_offset_mm: spec.pusher_offset_mm + 0.4 * dh,
        ..*spec
    };
    let again = TrainSpec {
        phi0_deg: moved.phi0_deg + 0.1,
        beta0_deg: moved.beta0_deg - 0.1,
        ..moved
    };
    [moved, again]
}

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
        let gamma = crate::angle::wrap(self.gamma0_deg, 360.0);
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
    /// Arm tip `D`.
    pub tip: Vec2,
    /// `dD/dθ` (mm/rad).
    pub tip_d1: Vec2,
    /// `d²D/dθ²` (mm/rad²).
    pub tip_d2: Vec2,
    /// Pusher-axis direction angle (rad), pointing from the arm towards the tip.
    pub pusher_angle: f64,
    /// `dθ2/dθ` and `d²θ2/dθ²`: the intermediate's absolute turn per carrier turn.
    pub theta2_d: [f64; 2],
    /// `dθ3/dθ` and `d²θ3/dθ²`: the planet's (and its arm's) absolute turn.
    pub theta3_d: [f64; 2],
}

/// Where a pitch curve touches its mate: the centre of the gear whose curve is read, the
/// unit vector from that centre towards the mate's centre, the curve's own parameter `ψ`
/// there (rad, as the pair's teeth are cut on it), and the curve's radius (mm) and its
/// derivative in the gear's own angle (mm/rad) at the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PitchContact {
    pub centre: Vec2,
    pub towards: Vec2,
    pub psi: f64,
    pub rho: f64,
    pub rho_d1: f64,
}

/// The planet's lag `lag(θ)` with its first two derivatives, and what they come from:
/// the pair's driven angle `Φ_A(θ)` and its ratio `g(θ)`, `g'(θ)`; and the driving curves
/// at the two meshes (the sun's at the intermediate; at the planet, the sun's twin's or
/// layer B's).
struct Lag {
    big_phi: f64,
    g: f64,
    dg: f64,
    value: f64,
    d1: f64,
    d2: f64,
    curves: [Polar; 2],
}

/// One closed pair on its grid, with what interpolating its driven angle needs: `Φ` with
/// its first two derivatives at the nodes, and those of `Φ⁻¹`.
#[derive(Debug)]
struct SolvedPair {
    /// The pair: node `j` is the driver's own-frame parameter `start + sense·u_j`, and the
    /// pair's driven angle at the node is `Φ(u_j)`.
    pair: GearPair,
    /// `Φ''(u_j) = g̃'` (`Φ' = g̃` is the pair's ratio at the nodes).
    dg: Vec<f64>,
    /// `(Φ⁻¹)' = 1/g̃` and `(Φ⁻¹)'' = −g̃'/g̃³` at the nodes.
    inv_d1: Vec<f64>,
    inv_d2: Vec<f64>,
    /// `Φ(2π) − Φ(0)` (rad; 2π up to the closure error).
    phi_period: f64,
}

impl SolvedPair {
    fn new(pair: GearPair) -> Self {
        let a = pair.centre_distance();
        let sense = pair.grid().sense.sign();
        let dg: Vec<f64> = (pair.samples().iter())
            .map(|p| sense * a * p.d1 / ((a - p.rho) * (a - p.rho)))
            .collect();
        // Written in place: `unzip` pushes, a capacity check per node.
        let (mut inv_d1, mut inv_d2) = (vec![0.0; dg.len()], vec![0.0; dg.len()]);
        let nodes = pair.ratio_nodes().iter().zip(&dg);
        for ((d1, d2), (&g, &dg)) in inv_d1.iter_mut().zip(&mut inv_d2).zip(nodes) {
            (*d1, *d2) = DriftInverse::node_derivatives(g, dg);
        }
        let phi_period = pair.phi2_mean_rate() * TAU;
        Self {
            pair,
            dg,
            inv_d1,
            inv_d2,
            phi_period,
        }
    }

    /// `Φ(u)`, the driven gear's turn after the driver's turn `u` along the grid.
    fn phi(&self) -> MonotoneDrift<'_> {
        MonotoneDrift {
            value: self.pair.phi2_nodes(),
            d1: self.pair.ratio_nodes(),
            d2: &self.dg,
            period_increment: self.phi_period,
        }
    }

    /// `Φ⁻¹`, interpolated from the same nodes.
    fn phi_inverse(&self) -> DriftInverse<'_> {
        DriftInverse {
            forward: self.phi(),
            d1: &self.inv_d1,
            d2: &self.inv_d2,
        }
    }

    /// The driver curve's own parameter `start + sense·u` (rad) after the turn `u`.
    fn parameter(&self, u: f64) -> f64 {
        let grid = self.pair.grid();
        grid.start + grid.sense.sign() * u
    }

    /// `g̃(u) = g(start + sense·u)` at each turn `u` of `turns` (rad), from the curve
    /// itself: as [`SolvedPair::ratio_and_curve_at`], the curve walked once for turns in
    /// order.
    fn ratios_along(&self, turns: &[f64]) -> Vec<f64> {
        let a = self.pair.centre_distance();
        let curve = self
            .pair
            .curve()
            .eval_each(turns.iter().map(|&u| self.parameter(u)));
        curve.iter().map(|p| p.rho / (a - p.rho)).collect()
    }

    /// `g̃(u) = g(start + sense·u)` and `g̃'(u)` at any turn `u`, from the curve itself,
    /// with the driver curve's value there.
    fn ratio_and_curve_at(&self, u: f64) -> (f64, f64, Polar) {
        let a = self.pair.centre_distance();
        let p = self.pair.curve().eval(self.parameter(u));
        let gap = a - p.rho;
        (
            p.rho / gap,
            self.pair.grid().sense.sign() * a * p.d1 / (gap * gap),
            p,
        )
    }
}

/// What the gears alone determine, shared by every assembly of them
/// ([`Kinematics::reassembled`]): the pairs on their grids and the module (computed once
/// per rule).
#[derive(Debug)]
struct SolvedGears {
    /// The sun–intermediate pair on the carrier grid: node `j` is the sun's own-frame
    /// parameter `psi_start + σθ_j` at the contact, and the pair's driven angle is
    /// `Φ_A(θ_j)`, the intermediate's turn relative to the carrier.
    first: SolvedPair,
    /// The train with two pairs: the intermediate's layer B driving the planet. Node `k`
    /// is layer B's own angle `γ0 − π − σu_k` at the planet mesh when the intermediate has
    /// turned by `u_k = Φ_A` against the carrier, and the driven angle `Φ_B(u_k)` is the
    /// planet's turn against the carrier. `None`: the paper's train.
    second: Option<SolvedPair>,
    /// The module under the last rule asked.
    module: Mutex<Option<(ModuleRule, ModuleReport)>>,
}

impl SolvedGears {
    /// The train's module under `rule` (spec §1.4): the report of the pair that limits
    /// it (the first on a tie), computed once per rule for the gears and every reassembly
    /// of them.
    fn module(&self, rule: &ModuleRule) -> ModuleReport {
        let mut cache = self.module.lock().unwrap_or_else(|e| e.into_inner());
        match *cache {
            Some((r, report)) if r == *rule => report,
            _ => {
                let first = self.first.pair.module(rule);
                let report = match self.second.as_ref().map(|p| p.pair.module(rule)) {
                    Some(second) if second.module_max_mm < first.module_max_mm => second,
                    _ => first,
                };
                *cache = Some((*rule, report));
                report
            }
        }
    }
}

/// A train's first pair sampled on its grid, before any closure: the first stage of
/// [`Kinematics::solve_with`]. A search asks the module's bound here, to stop a design
/// that the sun's curvature already rules out.
pub(crate) struct SampledTrain {
    first: SampledDriver,
    /// The second pair's driver (layer B of the intermediate), for a train with two pairs.
    second: Option<PitchCurve>,
    spec: TrainSpec,
    resolution: Resolution,
}

impl SampledTrain {
    /// Samples `curve`, the sun, on the grid of `spec` at `resolution`.
    pub(crate) fn sample(
        curve: PitchCurve,
        second: Option<PitchCurve>,
        spec: &TrainSpec,
        resolution: &Resolution,
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
        Ok(Self {
            first: SampledDriver::sample(curve, *resolution, grid)?,
            second,
            spec: *spec,
            resolution: *resolution,
        })
    }

    /// The most that the train's module can be under `rule` (mm): the sun's curvature
    /// alone allows it ([`SampledDriver::module_bound`]); the other gears only lower it.
    pub(crate) fn module_bound(&self, rule: &ModuleRule) -> f64 {
        self.first.module_bound(rule)
    }

    /// The resolution the train is sampled at.
    pub(crate) fn resolution(&self) -> Resolution {
        self.resolution
    }

    /// Closes the pairs on their grids, reusing a planned integrator.
    pub(crate) fn close(self, integrator: &mut SpectralIntegrator) -> Result<ClosedGears> {
        let first = SolvedPair::new(self.first.close(integrator)?);
        let second = match self.second {
            Some(curve) => {
                let grid = SampleGrid {
                    start: self.spec.gamma0_deg.to_radians() - std::f64::consts::PI,
                    sense: self.spec.rotation.reversed(),
                };
                let pair = GearPair::solve_on(curve, self.resolution, grid, integrator)
                    .map_err(|e| Error::SecondPair(Box::new(e)))?;
                Some(SolvedPair::new(pair))
            }
            None => None,
        };
        let gears = Arc::new(SolvedGears {
            first,
            second,
            module: Mutex::new(None),
        });
        Ok(ClosedGears {
            gears,
            spec: self.spec,
        })
    }
}

/// A train's gear pairs closed on their grids, before the arm is placed on them: the
/// second stage of [`Kinematics::solve_with`].
pub(crate) struct ClosedGears {
    gears: Arc<SolvedGears>,
    /// The train the grids are for.
    spec: TrainSpec,
}

impl ClosedGears {
    /// The train's module under `rule`, as [`Kinematics::module`] gives it (one cache).
    pub(crate) fn module(&self, rule: &ModuleRule) -> ModuleReport {
        self.gears.module(rule)
    }

    /// The arm placed on the gears for their train.
    pub(crate) fn assemble(self) -> Kinematics {
        Kinematics::assemble(self.gears, &self.spec, 0.0, None)
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
/// let kin = Kinematics::solve(&curve, None, &scene.train, &scene.resolution).unwrap();
/// let tips = kin.tips();
/// assert_eq!(tips.len(), kin.len());
/// // One sample per carrier step over a whole turn; the loop closes on itself.
/// let step = (tips[1] - tips[0]).hypot();
/// assert!((tips[tips.len() - 1] - tips[0]).hypot() < 3.0 * step);
/// ```
#[derive(Debug, Clone)]
pub struct Kinematics {
    /// The gears, shared with every reassembly of them.
    gears: Arc<SolvedGears>,
    spec: TrainSpec,
    sigma: f64,
    /// The spec's angles in radians: `Φ0`, `γ0`, `β0` and the sun's own-frame parameter
    /// at the contact for θ = 0.
    phi0: f64,
    gamma0: f64,
    beta0: f64,
    psi_start: f64,
    /// The planet orientation's constant part: `θ3 = base + σ(θ − lag(θ)) + γ0 + π`. The
    /// sun's turn in the ground frame for the paper's train, `Φ0` for two pairs.
    planet_base: f64,
    /// Pusher-axis direction less the planet orientation (rad): `β0 ± asin(H1/S)`.
    pusher_turn: f64,
    /// The paper's train: mesh delay of the intermediate between its two meshes (rad).
    delay: f64,
    /// Distances at which the carrier holds the intermediate from the sun and the planet
    /// from the intermediate (mm): the pairs' centre distances plus the assembly's error
    /// ([`Kinematics::reassembled`]).
    carrier_a: [f64; 2],
    /// Per node: the planet's lag `lag(θ_j)` (the paper's train: `θ_s`, the carrier angle
    /// at which the intermediate's point now at the planet met the sun; two pairs:
    /// `Φ_B(Φ_A(θ_j))`; shared by its reassemblies), planet orientation, planet centre, tip.
    planet_lag: Arc<Vec<f64>>,
    theta3: Vec<f64>,
    o3: Vec<Vec2>,
    tip: Vec<Vec2>,
    /// Per node, the arm's direction `unit(θ3 + β0)`: a reassembly turns it.
    arm_dir: Vec<Vec2>,
    /// Nodes by which each arm lags the one before it (`n / arms`): arm indices by a
    /// multiplication, not an integer division per use.
    nodes_per_arm: usize,
    /// Nodes that scans of this train may be confined to, marked on it or on the train it
    /// was reassembled from ([`Kinematics::mark_nodes`], [`Kinematics::mark_walks`]).
    marks: Option<Marks>,
}

/// What scans of a train may be confined to: nodes marked on it or on the train it was
/// reassembled from, and how this train lies against that one. The marked train's arms,
/// turned by `turn` about the carrier axis, lie within `displacement_mm` of this train's
/// at every node.
#[derive(Debug, Clone)]
pub(crate) struct Marks {
    /// Nodes near the least clearance, for the interference scan.
    pub(crate) clearance: Option<MarkedNodes>,
    /// Nodes where the events' walks may find their extremes.
    pub(crate) walks: Option<Arc<MarkedWalks>>,
    /// At most how far any point of an arm, or a planet centre, of this train lies from
    /// the marked train's at the same node turned by `turn` (mm).
    pub(crate) displacement_mm: f64,
    /// The turn about the carrier axis (a unit complex number) from the marked train's
    /// planet centres to this train's: a turn of the whole train, which moves no distance
    /// between its parts.
    pub(crate) turn: Vec2,
}

/// No turn about the carrier axis, as a unit complex number.
const NO_TURN: Vec2 = Vec2::new(1.0, 0.0);

impl Marks {
    /// No marks yet, on the marked train itself.
    fn on_itself() -> Self {
        Self {
            clearance: None,
            walks: None,
            displacement_mm: 0.0,
            turn: NO_TURN,
        }
    }
}

/// Nodes of a train marked for a scan over the turn (where a least value over the nodes
/// comes within a band of its least). Where the scanned value moves with the arms and
/// planet centres by at most their own displacement, a reassembly whose displacement is
/// small against the band has its least value at one of these nodes.
#[derive(Debug, Clone)]
pub(crate) struct MarkedNodes {
    /// The nodes, ascending.
    pub(crate) nodes: Arc<[usize]>,
    /// What they were marked for (the scan's own parameter, e.g. a half-width in mm): a
    /// scan for another value leaves them.
    pub(crate) key: f64,
    /// How far above the marked train's least value the marked nodes reach (mm).
    pub(crate) band_mm: f64,
}

/// Nodes of a train marked for the events' walks along three directions: the nodes where
/// a reassembly's tip path may have a local maximum along the direction (or its largest
/// value), so that its walk may visit them alone.
#[derive(Debug)]
pub(crate) struct MarkedWalks {
    /// The tray's inward normal the first walk was marked for (unit).
    pub(crate) normal: Vec2,
    /// Per walk (along the normal, down, up), the nodes, ascending; none where so many
    /// are marked that a walk over every node costs less.
    pub(crate) nodes: [Option<Vec<usize>>; 3],
    /// How far below each neighbour's value a node's may lie and still be marked, beyond
    /// the tilt's share (mm): twice the displacement a reassembly may have.
    pub(crate) band_mm: f64,
    /// How far a reassembly's walk direction, turned back by its turn, may lie from the
    /// marked one (the length of their difference, both unit vectors).
    pub(crate) tilt: f64,
}

/// The planet orientation's constant part for `spec` (rad): the sun's turn in the ground
/// frame for the paper's train, `Φ0` for two pairs.
fn planet_base(two_pairs: bool, spec: &TrainSpec) -> f64 {
    if two_pairs {
        spec.phi0_deg.to_radians()
    } else {
        spec.sun_angle()
    }
}

/// The planet centres `O3 = a1·e1 + a2·e2` at `n` nodes (mm), the carrier directions
/// `e1 = e(φH)` and `e2 = e(φH + γ0)` turned by `step` (a unit complex number) from node
/// to node: no trigonometry. Bit for bit the recurrence
/// `o3 = e1·a1 + e2·a2; (e1, e2) = (e1.rotated(step), e2.rotated(step))`, with `e1` and
/// `e2` side by side in vector lanes.
fn planet_centres(directions: [Vec2; 2], step: Vec2, carrier_a: [f64; 2], n: usize) -> Vec<Vec2> {
    let [e1, e2] = directions;
    // Lane 0 holds e1, lane 1 e2: their x in one vector, their y in another.
    let (mut x, mut y) = (f64x2::new([e1.x, e2.x]), f64x2::new([e1.y, e2.y]));
    let (cos, sin) = (f64x2::splat(step.x), f64x2::splat(step.y));
    let a = f64x2::new(carrier_a);
    (0..n)
        .map(|_| {
            let ([x1, x2], [y1, y2]) = ((x * a).to_array(), (y * a).to_array());
            let [ox, oy] = (f64x2::new([x1, y1]) + f64x2::new([x2, y2])).to_array();
            (x, y) = (x * cos - y * sin, x * sin + y * cos);
            Vec2::new(ox, oy)
        })
        .collect()
}

/// How a train on the same gears and carrier angle `γ0` as `src` lies against it: each
/// node's planet orientation, arm direction and planet centre follow from `src`'s by one
/// turn each ([`Kinematics::reassembled`]).
#[derive(Debug, Clone, Copy)]
struct Turn {
    /// Added to each planet orientation `θ3` (rad).
    planets: f64,
    /// Multiplies each arm direction (a unit complex number).
    arm: Vec2,
    /// Multiplies each planet centre: a turn and a scale, as a complex number.
    centre_factor: Vec2,
    /// The source's planet centre at θ = 0 against its sun, `a1 + a2·e(γ0)` (mm).
    src_reach: Vec2,
}

impl Turn {
    /// `src` turned to the train whose planets' base angle, carrier distances (mm), `Φ0`
    /// and `β0` (rad) are given. The planet centres, as complex numbers
    /// `O3(θ) = e(Φ0 + σθ)·(a1 + a2·e(γ0))`, are the source's times one factor: `Φ0`
    /// turns them, the carrier's distances scale them.
    fn between(src: &Kinematics, planet_base: f64, carrier_a: [f64; 2], angles: [f64; 2]) -> Self {
        let [phi0, beta0] = angles;
        let planets = planet_base - src.planet_base;
        let e_gamma = unit(src.gamma0);
        let reach = Vec2::new(carrier_a[0], 0.0) + e_gamma * carrier_a[1];
        let src_reach = Vec2::new(src.carrier_a[0], 0.0) + e_gamma * src.carrier_a[1];
        let scale =
            reach.rotated(Vec2::new(src_reach.x, -src_reach.y)) * (1.0 / src_reach.hypot2());
        Self {
            planets,
            arm: unit(planets + beta0 - src.beta0),
            centre_factor: scale.rotated(unit(phi0 - src.phi0)),
            src_reach,
        }
    }

    /// The whole train's turn about the carrier axis: the planet centres' (a unit
    /// complex number).
    fn unit(&self) -> Vec2 {
        self.centre_factor * (1.0 / self.centre_factor.hypot2().sqrt())
    }

    /// At most how far this turn moves any point of `src`'s arms, now `s` long (mm), or a
    /// planet centre, once the train is turned back as a whole about the carrier axis.
    /// Turned back by the planet centres' turn f/|f| (which moves no distance between
    /// parts), a planet centre (at |O3| = |a1 + a2·e(γ0)|) moves by |O3|·||f| − 1|, a tip
    /// by that and |e·(f/|f|)*·S − S_src| more (the arm direction a unit vector), and
    /// every point of an arm by no more than the farther of its ends. A bound: the roots
    /// are taken plainly, their rounding far inside the margin its users keep.
    fn displacement_mm(&self, src: &Kinematics, s: f64) -> f64 {
        let f = self.centre_factor;
        let size = f.hypot2().sqrt();
        let back = Vec2::new(f.x, -f.y) * (1.0 / size);
        let centre_move = self.src_reach.hypot2().sqrt() * (size - 1.0).abs();
        let tip = self.arm.rotated(back) * s - Vec2::new(src.spec.arm_length_mm, 0.0);
        centre_move + tip.hypot2().sqrt()
    }
}

impl Kinematics {
    /// Samples the sun on the carrier grid, closes the pair and moves arm I through one
    /// turn. With `second`, the intermediate's layer B: the train with two pairs, whose
    /// planet is that curve's conjugate (`None`: the paper's train, the planet congruent
    /// to the sun).
    pub fn solve(
        curve: &PitchCurve,
        second: Option<&PitchCurve>,
        spec: &TrainSpec,
        resolution: &Resolution,
    ) -> Result<Self> {
        resolution.validate()?;
        Self::solve_with(
            curve.clone(),
            second.cloned(),
            spec,
            resolution,
            &mut SpectralIntegrator::new(resolution.samples_per_turn),
        )
    }

    /// As [`Kinematics::solve`], taking the curves and reusing a planned integrator of
    /// `samples_per_turn` points.
    pub(crate) fn solve_with(
        curve: PitchCurve,
        second: Option<PitchCurve>,
        spec: &TrainSpec,
        resolution: &Resolution,
        integrator: &mut SpectralIntegrator,
    ) -> Result<Self> {
        let sampled = SampledTrain::sample(curve, second, spec, resolution)?;
        Ok(sampled.close(integrator)?.assemble())
    }

    /// The same gears assembled anew: another `spec` (its `Φ0`, `β0`, `γ0`, `S`, `H1`) and
    /// the carrier holding each pair `centre_offset_mm` further apart than its centre
    /// distance (a bore error: the gears then mesh with backlash, at the same ratio).
    /// Reuses the closed pairs: no closure, no re-sampling. Refused where a pair's grid
    /// would change (another rotation sense, `Φ0` under [`SunFrame::Ground`], or `γ0` in
    /// the train with two pairs): solve those anew.
    pub fn reassembled(&self, spec: &TrainSpec, centre_offset_mm: f64) -> Result<Self> {
        spec.validate()?;
        finite("centre distance offset (mm)", centre_offset_mm)?;
        if !self.keeps_sun_grid(spec) {
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
        if !self.keeps_second_grid(spec) {
            return Err(Error::OutOfRange {
                name: "train.gamma0_deg".into(),
                value: spec.gamma0_deg,
                expected: format!(
                    "the solved train's γ0 = {}° (with two pairs, γ0 places the second \
                     pair's grid): solve the train anew",
                    self.spec.gamma0_deg
                ),
            });
        }
        let least = self.centre_distances()[0].min(self.centre_distances()[1]);
        if least + centre_offset_mm <= 0.0 {
            return Err(Error::OutOfRange {
                name: "centre distance offset (mm)".into(),
                value: centre_offset_mm,
                expected: format!("above -{least} mm"),
            });
        }
        // The same carrier angle γ0 keeps the lags: the assembly then only turns and moves.
        let same_carrier = spec.gamma0_deg == self.spec.gamma0_deg;
        Ok(Self::assemble(
            self.gears.clone(),
            spec,
            centre_offset_mm,
            same_carrier.then_some(self),
        ))
    }

    /// Whether [`Kinematics::reassembled`] takes `spec`: its pairs keep their grids
    /// (the same rotation sense and sun grid, and with two pairs the same `γ0`). A train
    /// it refuses is solved anew.
    pub fn reassembles_for(&self, spec: &TrainSpec) -> bool {
        self.keeps_sun_grid(spec) && self.keeps_second_grid(spec)
    }

    /// At most how far any point of an arm, or a planet centre, of this train
    /// [reassembled](Kinematics::reassembled) for `spec` with `centre_offset_mm` lies from
    /// this one's at the same node, once turned as a whole about the carrier axis (mm),
    /// and that turn (a unit complex number). +∞ and the identity for a reassembly that
    /// does not keep the carrier's `γ0` and the number of arms (its arms then lie
    /// elsewhere altogether).
    pub(crate) fn displacement_and_turn_to(
        &self,
        spec: &TrainSpec,
        centre_offset_mm: f64,
    ) -> (f64, Vec2) {
        self.turn_to(spec, centre_offset_mm)
            .map_or((f64::INFINITY, NO_TURN), |t| {
                (t.displacement_mm(self, spec.arm_length_mm), t.unit())
            })
    }

    /// The turn to the reassembly for `spec`, where it keeps the carrier's `γ0` and the
    /// number of arms.
    fn turn_to(&self, spec: &TrainSpec, centre_offset_mm: f64) -> Option<Turn> {
        let same = spec.gamma0_deg == self.spec.gamma0_deg && spec.arms == self.spec.arms;
        if !(same && self.reassembles_for(spec)) {
            return None;
        }
        let [a1, a2] = self.centre_distances();
        let carrier_a = [a1 + centre_offset_mm, a2 + centre_offset_mm];
        let angles = [spec.phi0_deg.to_radians(), spec.beta0_deg.to_radians()];
        let base = planet_base(self.gears.second.is_some(), spec);
        Some(Turn::between(self, base, carrier_a, angles))
    }

    /// Marks `nodes` (ascending) for a scan whose parameter is `key`, reaching `band_mm`
    /// above this train's least value: every reassembly of this train keeps them
    /// ([`MarkedNodes`]).
    pub(crate) fn mark_nodes(&mut self, nodes: Vec<usize>, key: f64, band_mm: f64) {
        self.marks_on_itself().clearance = Some(MarkedNodes {
            nodes: nodes.into(),
            key,
            band_mm,
        });
    }

    /// Marks `walks` for the events' walks: every reassembly of this train keeps them.
    pub(crate) fn mark_walks(&mut self, walks: MarkedWalks) {
        self.marks_on_itself().walks = Some(Arc::new(walks));
    }

    /// This train's marks, made on itself: those carried from a train it was reassembled
    /// from are dropped first.
    fn marks_on_itself(&mut self) -> &mut Marks {
        let own =
            (self.marks.as_ref()).is_some_and(|m| m.displacement_mm == 0.0 && m.turn == NO_TURN);
        if !own {
            self.marks = None;
        }
        self.marks.get_or_insert_with(Marks::on_itself)
    }

    /// The marks made on this train or on the one it was reassembled from.
    pub(crate) fn marks(&self) -> Option<&Marks> {
        self.marks.as_ref()
    }

    /// The nodes marked for the interference on this train or on the one it was
    /// reassembled from.
    #[cfg(test)]
    pub(crate) fn marked_nodes(&self) -> Option<&MarkedNodes> {
        self.marks.as_ref()?.clearance.as_ref()
    }

    /// The sun's pair keeps its grid under `spec`.
    fn keeps_sun_grid(&self, spec: &TrainSpec) -> bool {
        spec.rotation == self.spec.rotation && spec.psi_start() == self.psi_start
    }

    /// The second pair, if any, keeps its grid under `spec` (its start is `γ0 − π`).
    fn keeps_second_grid(&self, spec: &TrainSpec) -> bool {
        self.gears.second.is_none() || spec.gamma0_deg == self.spec.gamma0_deg
    }

    /// Places the arm for `spec` on solved gears (`spec` valid, the pairs on their grids).
    /// With `same_carrier`, a train on the same gears with the same `γ0`, its lags are
    /// reused and its arm directions turned (no inversion, no trigonometry per node): `Φ0`
    /// turns the planets, `β0` the arm on them.
    fn assemble(
        gears: Arc<SolvedGears>,
        spec: &TrainSpec,
        centre_offset_mm: f64,
        same_carrier: Option<&Kinematics>,
    ) -> Self {
        let sigma = spec.rotation.sign();
        let n = gears.first.pair.samples().len();
        let a = [
            gears.first.pair.centre_distance(),
            (gears.second.as_ref()).map_or(gears.first.pair.centre_distance(), |p| {
                p.pair.centre_distance()
            }),
        ];
        let gamma0 = spec.gamma0_deg.to_radians();
        let beta0 = spec.beta0_deg.to_radians();
        let delay = crate::angle::wrap_turn(sigma * (gamma0 - std::f64::consts::PI));
        let planet_base = planet_base(gears.second.is_some(), spec);
        let mut kin = Self {
            gears,
            spec: *spec,
            sigma,
            phi0: spec.phi0_deg.to_radians(),
            gamma0,
            beta0,
            psi_start: spec.psi_start(),
            planet_base,
            pusher_turn: beta0
                + match spec.pusher_side {
                    PusherSide::Left => 1.0,
                    PusherSide::Right => -1.0,
                } * (spec.pusher_offset_mm / spec.arm_length_mm).asin(),
            delay,
            carrier_a: [a[0] + centre_offset_mm, a[1] + centre_offset_mm],
            planet_lag: Arc::default(),
            theta3: Vec::new(),
            o3: Vec::new(),
            tip: Vec::new(),
            arm_dir: Vec::new(),
            nodes_per_arm: n / spec.arms,
            marks: None,
        };
        // The arms' turn relative to `same_carrier`'s: θ3 moves with the planets' base
        // angle, the arm with β0 on top, the planet centres by one factor (each node on
        // its own, no rotation carried from node to node).
        let turn = same_carrier
            .map(|src| Turn::between(src, kin.planet_base, kin.carrier_a, [kin.phi0, beta0]));
        // A reassembly keeps its source's marks (the same arms on the same nodes), adding
        // its own displacement and turn to theirs.
        kin.marks = same_carrier
            .filter(|src| src.spec.arms == spec.arms)
            .and_then(|src| Some((src, src.marks.clone()?, turn?)))
            .map(|(src, m, t)| Marks {
                displacement_mm: m.displacement_mm + t.displacement_mm(src, spec.arm_length_mm),
                turn: t.unit().rotated(m.turn),
                ..m
            });
        match same_carrier.zip(turn) {
            Some((src, turn)) => {
                // The source's arrays turned, each in a loop of its own; the lags shared.
                kin.planet_lag = src.planet_lag.clone();
                kin.theta3 = src.theta3.iter().map(|&t| t + turn.planets).collect();
                kin.arm_dir = src.arm_dir.iter().map(|d| d.rotated(turn.arm)).collect();
                kin.o3 = (src.o3.iter())
                    .map(|o| o.rotated(turn.centre_factor))
                    .collect();
            }
            None => kin.place_arms(),
        }
        let length = spec.arm_length_mm;
        kin.tip = (kin.o3.iter().zip(&kin.arm_dir))
            .map(|(&o3, &dir)| o3 + dir * length)
            .collect();
        kin
    }

    /// Places the arms of a train solved anew, node by node: the planet's lag (through
    /// `Φ⁻¹`, or the second pair's drift), then its orientation, its centre and the arm's
    /// direction.
    fn place_arms(&mut self) {
        // In an `Arc` of its own `Vec`: no copy into a shared slice.
        self.planet_lag = Arc::new(match &self.gears.second {
            None => {
                // θ_s at every node: sorted targets, so each cell is found forward from
                // the last.
                let inverse = self.gears.first.phi_inverse();
                inverse.eval_ascending(self.gears.first.pair.phi2_nodes(), self.delay)
            }
            Some(second) => {
                let phi_b = second.phi();
                (self.gears.first.pair.phi2_nodes().iter())
                    .map(|&phi_a| phi_b.eval(phi_a).0)
                    .collect()
            }
        });
        // Each array in a loop of its own over its known length: no capacity check per
        // node, as a push has.
        let n = self.planet_lag.len();
        let h = TAU / n as f64;
        let sigma = self.sigma;
        self.theta3 = (self.planet_lag.iter().enumerate())
            .map(|(j, &lag)| {
                let theta = h * node_index(j);
                self.planet_base + sigma * (theta - lag) + self.gamma0 + std::f64::consts::PI
            })
            .collect();
        self.arm_dir = units(&self.theta3, self.beta0);
        self.o3 = planet_centres(
            [unit(self.phi0), unit(self.phi0 + self.gamma0)],
            unit(sigma * h),
            self.carrier_a,
            n,
        );
    }

    /// The sun–intermediate gear pair on the carrier grid. In the paper's train the
    /// planet–intermediate mesh is the same pair (the planet is congruent to the sun).
    pub fn pair(&self) -> &GearPair {
        &self.gears.first.pair
    }

    /// The train with two pairs: the intermediate's layer B (the driver) and the planet
    /// (its conjugate), on layer B's grid. `None` for the paper's train.
    pub fn second_pair(&self) -> Option<&GearPair> {
        self.gears.second.as_ref().map(|p| &p.pair)
    }

    /// The train's module under `rule` (spec §1.4): the report of the pair that limits
    /// it (the first on a tie), computed once per rule for the gears and every
    /// reassembly of them.
    pub fn module(&self, rule: &ModuleRule) -> ModuleReport {
        self.gears.module(rule)
    }

    /// Centre distance of the sun–intermediate pair (mm); in the paper's train both
    /// meshes share it.
    pub fn centre_distance(&self) -> f64 {
        self.gears.first.pair.centre_distance()
    }

    /// Centre distances of the sun–intermediate and intermediate–planet pairs (mm).
    pub fn centre_distances(&self) -> [f64; 2] {
        let second = self
            .second_pair()
            .map_or(self.centre_distance(), |p| p.centre_distance());
        [self.centre_distance(), second]
    }

    /// Least and largest radius of the sun's pitch curve (mm).
    pub fn radius_range(&self) -> (f64, f64) {
        self.gears.first.pair.radius_range()
    }

    /// Largest radius of the intermediate's pitch curves about its axis (mm).
    pub fn intermediate_reach(&self) -> f64 {
        let layer_a = self.centre_distance() - self.radius_range().0;
        self.second_pair()
            .map_or(layer_a, |p| layer_a.max(p.radius_range().1))
    }

    /// Largest radius of the planet's pitch curve about its axis (mm).
    pub fn planet_reach(&self) -> f64 {
        self.second_pair().map_or(self.radius_range().1, |p| {
            p.centre_distance() - p.radius_range().0
        })
    }

    /// The planet's pitch curve in its own frame (mm), at the nodes of its pair: the sun's
    /// curve in the paper's train, the second pair's driven curve with two.
    pub fn planet_points(&self) -> Vec<Vec2> {
        match self.second_pair() {
            Some(p) => p.driven_points(),
            None => self.pair().driver_points(),
        }
    }

    /// The intermediate's blank (layer A, and layer B with two pairs, on one shaft) and the
    /// planet's, in their own frames (as [`Kinematics::planet_points`] and the gearbox place
    /// them), each `face_width_mm` thick of `density_kg_m3`.
    pub fn blanks(&self, face_width_mm: f64, density_kg_m3: f64) -> [Blank; 2] {
        // Each iterator by its own type (not `dyn`): the sums inline and pipeline.
        let (b, rho) = (face_width_mm, density_kg_m3);
        let first = self.pair();
        let layer_a = Blank::from_polar(first.driven_polar(), b, rho);
        match self.second_pair() {
            None => [layer_a, Blank::from_polar(first.driver_polar(), b, rho)],
            Some(second) => [
                layer_a.with(Blank::from_polar(second.driver_polar(), b, rho)),
                Blank::from_polar(second.driven_polar(), b, rho),
            ],
        }
    }

    /// Distance at which the carrier holds the intermediate from the sun (mm): the
    /// centre distance, plus the bore error of a [`Kinematics::reassembled`] train.
    pub fn carrier_distance(&self) -> f64 {
        self.carrier_a[0]
    }

    /// Distance from the carrier axis to a planet centre (mm): `|a_A + a_B·e^{iγ0}|`, in
    /// the paper's train `2a·|cos(γ0/2)|`.
    pub fn planet_radius(&self) -> f64 {
        let [a1, a2] = self.carrier_a;
        (Vec2::new(a1, 0.0) + unit(self.gamma0) * a2).hypot()
    }

    /// The sun's pitch curve.
    pub fn curve(&self) -> &PitchCurve {
        self.gears.first.pair.curve()
    }

    /// The train parameters.
    pub fn spec(&self) -> &TrainSpec {
        &self.spec
    }

    /// The resolution that produced this motion.
    pub fn resolution(&self) -> Resolution {
        self.gears.first.pair.resolution()
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
        TAU * node_index(j) / self.len() as f64
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
        // No integer division on the usual path (`k < arms`, `j < n`): this runs at every
        // node, several times.
        let k = if k < self.arms() { k } else { k % self.arms() };
        let j = if j < self.len() { j } else { j % self.len() };
        self.arm_node_within(k, j)
    }

    /// [`Kinematics::arm_node`] for `k < arms` and `j < n`, without wrapping them: the
    /// interference scan's every node.
    #[inline(always)]
    pub(crate) fn arm_node_within(&self, k: usize, j: usize) -> usize {
        debug_assert!(k < self.arms() && j < self.len());
        let lag = self.arm_lag_nodes(k);
        if j >= lag {
            j - lag
        } else {
            j + self.len() - lag
        }
    }

    /// Nodes by which arm `k` (`k < arms`) lags arm I: arm k at node `j` is arm I at node
    /// `j` less these, wrapped ([`Kinematics::arm_node_within`]).
    #[inline(always)]
    pub(crate) fn arm_lag_nodes(&self, k: usize) -> usize {
        k * self.nodes_per_arm
    }

    /// The node at or below carrier angle `u` (rad, any real), wrapped into one turn.
    fn node_below(&self, u: f64) -> usize {
        let n = self.len();
        let u = crate::angle::wrap_turn(u);
        ((u * (n as f64 / TAU)) as usize).min(n - 1)
    }

    /// The full state of arm I at any carrier angle `theta` (rad): positions, the tip's
    /// first two derivatives, orientations and the pusher-axis angle.
    pub fn state_at(&self, theta: f64) -> ArmState {
        self.state_from(theta, &self.lag_at(theta), None)
    }

    /// The state of arm I at carrier angle `theta` (rad) with the two meshes' pitch-curve
    /// contacts, read on the driving curves: the sun's against the intermediate, then the
    /// planet's against the intermediate (the paper's train: the planet is the sun's
    /// twin) or the intermediate's layer B against the planet (two pairs).
    pub fn state_and_contacts(&self, theta: f64) -> (ArmState, [PitchContact; 2]) {
        self.with_contacts(theta, &self.lag_at(theta), None)
    }

    /// [`Kinematics::state_and_contacts`] at node `j`, carrier angle `θ_j` (to rounding),
    /// from what the nodes keep: the sun's sample, the ratio and the intermediate's turn
    /// there, and the planet's lag. One curve evaluation, at the lag, instead of two with
    /// two interpolations and an inverse: the dynamics at the kinematics' nodes reads it.
    pub fn node_state_and_contacts(&self, j: usize) -> (ArmState, [PitchContact; 2]) {
        self.with_contacts(self.theta(j), &self.node_lag(j), Some(j))
    }

    /// [`Kinematics::state_at`] at node `j`, carrier angle `θ_j`, to rounding, from what
    /// the nodes keep (one curve evaluation, at the lag).
    pub fn node_state(&self, j: usize) -> ArmState {
        self.state_from(self.theta(j), &self.node_lag(j), Some(j))
    }

    /// The lag at node `j` and its derivatives, from the node's values.
    fn node_lag(&self, j: usize) -> Lag {
        let pair = &self.gears.first.pair;
        self.lag_with(
            pair.phi2_nodes()[j],
            pair.ratio_nodes()[j],
            self.gears.first.dg[j],
            pair.samples()[j],
            self.planet_lag[j],
        )
    }

    /// The state and the meshes' contacts at carrier angle `theta` (node `node`'s if given)
    /// with its `lag`.
    #[inline(always)]
    fn with_contacts(
        &self,
        theta: f64,
        lag: &Lag,
        node: Option<usize>,
    ) -> (ArmState, [PitchContact; 2]) {
        let state = self.state_from(theta, lag, node);
        let towards = |from: Vec2, to: Vec2| (to - from) * (1.0 / (to - from).hypot2().sqrt());
        let [sun, mate] = lag.curves;
        let mesh_a = PitchContact {
            centre: Vec2::ZERO,
            towards: towards(Vec2::ZERO, state.o2),
            psi: self.gears.first.parameter(theta),
            rho: sun.rho,
            rho_d1: sun.d1,
        };
        // The planet, the sun's twin, read at its lag; or layer B at the intermediate's turn.
        let (centre, other, psi) = match &self.gears.second {
            None => (state.o3, state.o2, self.gears.first.parameter(lag.value)),
            Some(second) => (state.o2, state.o3, second.parameter(lag.big_phi)),
        };
        let mesh_b = PitchContact {
            centre,
            towards: towards(centre, other),
            psi,
            rho: mate.rho,
            rho_d1: mate.d1,
        };
        (state, [mesh_a, mesh_b])
    }

    /// [`Kinematics::state_at`] from the lag at `theta`, which is node `node`'s angle if
    /// one is given.
    #[inline(always)]
    fn state_from(&self, theta: f64, lag: &Lag, node: Option<usize>) -> ArmState {
        let sigma = self.sigma;
        let Lag {
            big_phi,
            g: g_t,
            dg: dg_t,
            value: lag,
            d1: lag1,
            d2: lag2,
            ..
        } = *lag;
        let s = self.spec.arm_length_mm;
        let th1 = sigma * (1.0 - lag1);
        let th2 = -sigma * lag2;
        let phi_h = self.phi0 + sigma * theta;
        let (o2, o3, theta3, u) = self.placed(theta, lag, node);
        let tip = o3 + u * s;
        // O3'' = −O3; u' = θ3' u⊥.
        let tip_d1 = self.tip_velocity(o3, u, th1);
        let tip_d2 = -o3 + u.turn_90() * (s * th2) - u * (s * th1 * th1);
        // Intermediate: the material point of sun parameter ψ sits at its own angle
        // χ(ψ) = −∫_{ψ_start}^{ψ} g = −σΦ(θ) and meets the sun at the absolute direction φH + π.
        let theta2 = phi_h + std::f64::consts::PI + sigma * big_phi;
        ArmState {
            theta,
            o2,
            o3,
            theta3,
            theta2,
            tip,
            tip_d1,
            tip_d2,
            pusher_angle: self.pusher_angle(theta3),
            theta2_d: [sigma * (1.0 + g_t), sigma * dg_t],
            theta3_d: [th1, th2],
        }
    }

    /// The planet's lag at carrier angle `theta` (rad) with its first two derivatives.
    #[inline(always)]
    fn lag_at(&self, theta: f64) -> Lag {
        let (big_phi, value) = self.lag_value_at(theta);
        let (g, dg, sun) = self.gears.first.ratio_and_curve_at(theta);
        self.lag_with(big_phi, g, dg, sun, value)
    }

    /// The intermediate's turn `Φ_A(θ)` and the planet's lag at carrier angle `theta`
    /// (rad), without their derivatives.
    #[inline(always)]
    fn lag_value_at(&self, theta: f64) -> (f64, f64) {
        let first = &self.gears.first;
        let (big_phi, _) = first.phi().eval(theta);
        let value = match &self.gears.second {
            None => {
                // Start the cell search where node ⌊θ/h⌋'s own θ_s lies: O(1), not O(N).
                let hint = self.node_below(self.planet_lag[self.node_below(theta)]);
                first.phi_inverse().eval(big_phi - self.delay, hint).0
            }
            Some(second) => second.phi().eval(big_phi).0,
        };
        (big_phi, value)
    }

    /// Arm I's planet centre `O3` and tip at carrier angle `theta` (rad): the positions of
    /// [`Kinematics::state_at`], without the derivatives (no curve evaluation).
    pub fn planet_and_tip_at(&self, theta: f64) -> (Vec2, Vec2) {
        let (_, lag) = self.lag_value_at(theta);
        let (_, o3, _, u) = self.placed(theta, lag, None);
        (o3, o3 + u * self.spec.arm_length_mm)
    }

    /// The intermediate's centre `O2`, the planet's centre `O3` and orientation `θ3` and
    /// the arm's direction at carrier angle `theta` with the planet's `lag` (rad); node
    /// `node`'s kept values if given (to rounding what the angles give).
    #[inline(always)]
    fn placed(&self, theta: f64, lag: f64, node: Option<usize>) -> (Vec2, Vec2, f64, Vec2) {
        let phi_h = self.phi0 + self.sigma * theta;
        let o2 = unit(phi_h) * self.carrier_a[0];
        match node {
            Some(j) => (o2, self.o3[j], self.theta3[j], self.arm_dir[j]),
            None => {
                let theta3 = self.planet_base
                    + self.sigma * (theta - lag)
                    + self.gamma0
                    + std::f64::consts::PI;
                let o3 = o2 + unit(phi_h + self.gamma0) * self.carrier_a[1];
                (o2, o3, theta3, unit(theta3 + self.beta0))
            }
        }
    }

    /// The lag `value` at the carrier angle where the intermediate has turned `big_phi` at
    /// ratio `g` (rate `dg`) with the sun's curve at `sun` there: its two derivatives and
    /// the mate's curve at the planet mesh (one curve evaluation).
    #[inline(always)]
    fn lag_with(&self, big_phi: f64, g: f64, dg: f64, sun: Polar, value: f64) -> Lag {
        let first = &self.gears.first;
        let (d1, d2, mate) = match &self.gears.second {
            None => {
                let (g_s, dg_s, twin) = first.ratio_and_curve_at(value);
                let ts1 = g / g_s;
                (ts1, (dg * g_s - g * dg_s * ts1) / (g_s * g_s), twin)
            }
            Some(second) => {
                // lag = Φ_B(Φ_A(θ)): lag' = g_B·g_A, lag'' = g_B'·g_A² + g_B·g_A'.
                let (g_b, dg_b, layer_b) = second.ratio_and_curve_at(big_phi);
                (g_b * g, dg_b * g * g + g_b * dg, layer_b)
            }
        };
        Lag {
            big_phi,
            g,
            dg,
            value,
            d1,
            d2,
            curves: [sun, mate],
        }
    }

    /// `dD/dθ` (mm/rad) of a tip on the arm of direction `u` from the planet centre `o3`,
    /// the arm turning at `th1 = dθ3/dθ`: `O3' = σ O3⊥` (the carrier turns `O3` about the
    /// axis) plus the arm's turn `θ3'·S·u⊥`.
    fn tip_velocity(&self, o3: Vec2, u: Vec2, th1: f64) -> Vec2 {
        o3.turn_90() * self.sigma + u.turn_90() * (self.spec.arm_length_mm * th1)
    }

    /// Arm I's tip speed `|dD/dθ|` (mm/rad) at every node: [`Kinematics::state_at`]'s
    /// `tip_d1` at the nodes (to rounding), from the node's lag, arm direction and planet
    /// centre and the pair's ratio at the lag: one curve evaluation per node instead of a
    /// whole state.
    pub fn node_tip_speeds(&self) -> Vec<f64> {
        let sigma = self.sigma;
        let first = &self.gears.first;
        let ratio = first.pair.ratio_nodes();
        // The ratio of the pair that sets the lag, at its turn for each node (the turns
        // rise along the nodes): all of them first, so that the divisions and roots below
        // do not wait on one curve evaluation after another.
        let lag_ratio = match &self.gears.second {
            None => first.ratios_along(&self.planet_lag),
            Some(second) => second.ratios_along(first.pair.phi2_nodes()),
        };
        (0..self.len())
            .map(|j| {
                let g_t = ratio[j];
                let lag1 = match &self.gears.second {
                    None => g_t / lag_ratio[j],
                    Some(_) => lag_ratio[j] * g_t,
                };
                let tip_d1 = self.tip_velocity(self.o3[j], self.arm_dir[j], sigma * (1.0 - lag1));
                // The root of the squares, not libm's `hypot` (its care against overflow costs
                // a sixth of a sensitivity run; a tip speed is far from overflow).
                tip_d1.hypot2().sqrt()
            })
            .collect()
    }

    /// Arm I's intermediate at node `j`: its centre `O2` (mm) and orientation `theta2`
    /// (rad), as [`Kinematics::state_at`] gives them at the node, from the node's values.
    pub fn intermediate_at(&self, j: usize) -> (Vec2, f64) {
        let phi_h = self.phi0 + self.sigma * self.theta(j);
        let big_phi = self.gears.first.pair.phi2_nodes()[j];
        (
            unit(phi_h) * self.carrier_a[0],
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

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// The planet centres in lanes are the scalar recurrence's, bit for bit: any
        /// carrier angles, steps either way, carrier distances and counts.
        #[test]
        fn planet_centres_in_lanes_are_the_recurrence(
            phi0 in -7.0f64..7.0,
            gamma0 in -7.0f64..7.0,
            step in -0.5f64..0.5,
            a1 in 20.0f64..80.0,
            a2 in 20.0f64..80.0,
            n in 0usize..50,
        ) {
            let (mut e1, mut e2) = (unit(phi0), unit(phi0 + gamma0));
            let turn = unit(step);
            let recurrence: Vec<Vec2> = (0..n)
                .map(|_| {
                    let o3 = e1 * a1 + e2 * a2;
                    (e1, e2) = (e1.rotated(turn), e2.rotated(turn));
                    o3
                })
                .collect();
            let lanes = planet_centres([unit(phi0), unit(phi0 + gamma0)], turn, [a1, a2], n);
            let bits = |v: &[Vec2]| {
                v.iter().map(|p| [p.x.to_bits(), p.y.to_bits()]).collect::<Vec<_>>()
            };
            proptest::prop_assert_eq!(bits(&lanes), bits(&recurrence));
        }
    }
}
