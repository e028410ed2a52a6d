//! Picking and planting (spec §3): where each happens on the trajectory, whether a machine
//! can pick there, and how far the next candidate extreme is.
//!
//! Picking is the tip's extreme point along the tray's inward normal `n`; planting is its
//! lowest point. Both are located between samples. An extreme point is only a picking
//! instant if a machine can pick there ([`PickingCheck`]): the tip is in the tray, the
//! pusher points into it, the planet centre, the gearbox housing and the other two arms
//! stay on the machine's side of the tray surface, and no other branch of the trajectory
//! enters the tray (a second entry per turn would strike the seedlings). The last
//! condition is also what makes the event trustworthy: when a small change of the design
//! moves the extreme to another branch, the runner-up branch is by then nearly as deep,
//! so the design fails the check before and after the switch instead of jumping silently.

use crate::agronomy::Agronomy;
use crate::angle::unit;
use crate::curve::{parabola_vertex, TAU};
use crate::planetary::{ArmState, Kinematics, MarkedWalks};
use crate::vec2::Vec2;
use serde::Serialize;
use wide::{f64x2, CmpGe, CmpGt};

/// A located event: carrier angle (rad) and the tip there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Event {
    pub carrier_rad: f64,
    pub tip_mm: Vec2,
    /// Arm attitude: the pusher direction's dip below the horizontal (deg).
    pub attitude_deg: f64,
}

/// Whether a machine can pick at the picking point: each condition as a signed distance
/// (mm), positive when it holds. The picking objective's value is their least.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PickingCheck {
    /// Distance of the tray surface from the carrier axis along the inward normal (mm).
    pub tray_surface_mm: f64,
    /// How far the tip reaches past the tray surface (mm).
    pub tip_depth_mm: f64,
    /// With a tray at a given distance: `min(depth, tray depth − depth)`, the tip reaches
    /// into the pots without striking the tray's floor (mm). `None` for a tray placed by
    /// the trajectory, where the depth is the tray depth by construction.
    pub reach_mm: Option<f64>,
    /// How far the planet centre `O3` stays behind the tray surface (mm).
    pub planet_behind_mm: f64,
    /// How far the gearbox housing, the disc it sweeps about the carrier axis, stays
    /// behind the tray surface (mm).
    pub housing_behind_mm: f64,
    /// `S · (pusher direction · n)`: how far the pusher axis advances into the tray over
    /// the arm's length (mm); negative when the pusher points back at the machine.
    pub pusher_into_tray_mm: f64,
    /// `S · (arm direction · n)`, the same for the arm line `O3 → D` (mm).
    pub arm_into_tray_mm: f64,
    /// How far the other arms (capsules of the arm half-width; II and III of three) stay
    /// behind the tray surface at the picking instant (mm); `None` for a one-arm train.
    pub other_arms_behind_mm: Option<f64>,
    /// How far the next candidate extreme along `n` (another branch of the trajectory)
    /// stays behind the tray surface (mm); `None` when the trajectory has one extreme.
    pub second_entry_behind_mm: Option<f64>,
}

impl PickingCheck {
    /// The conditions by name, with their signed distances (mm).
    pub fn conditions(&self) -> Vec<(&'static str, f64)> {
        self.each().collect()
    }

    /// The conditions by name, with their signed distances (mm), one by one: the always
    /// present, then those the trajectory and the tray have.
    fn each(&self) -> impl Iterator<Item = (&'static str, f64)> {
        let always = [
            (
                "planet centre behind the tray surface",
                self.planet_behind_mm,
            ),
            (
                "gearbox housing behind the tray surface",
                self.housing_behind_mm,
            ),
            ("pusher points into the tray", self.pusher_into_tray_mm),
            ("arm points into the tray", self.arm_into_tray_mm),
        ];
        let present = [
            (
                "the other arms behind the tray surface",
                self.other_arms_behind_mm,
            ),
            ("tip within the tray depth", self.reach_mm),
            (
                "no other branch enters the tray",
                self.second_entry_behind_mm,
            ),
        ];
        (always.into_iter()).chain(present.into_iter().filter_map(|(name, d)| Some((name, d?))))
    }

    /// The least of the conditions (mm): ≥ 0 when a machine can pick there.
    pub fn margin_mm(&self) -> f64 {
        self.each().map(|c| c.1).fold(f64::INFINITY, f64::min)
    }

    /// The conditions that fail, each with how far (mm), or `None` when all hold.
    pub fn failures(&self) -> Option<String> {
        let failed: Vec<String> = self
            .each()
            .filter(|c| c.1 < 0.0)
            .map(|(name, v)| format!("{name} fails by {:.2} mm", -v))
            .collect();
        (!failed.is_empty()).then(|| failed.join("; "))
    }
}

/// Picking and planting events, the picking window and the tip speed at picking.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Events {
    pub picking: Event,
    pub planting: Event,
    /// Carrier-angle span (rad, start < end, possibly past 2π) with the tip inside the tray.
    pub picking_window_rad: [f64; 2],
    /// Tip speed relative to the (machine-fixed) seedling at picking (m/s).
    pub picking_tip_speed_m_s: f64,
    /// Lowest and highest tip heights (mm).
    pub y_min_mm: f64,
    pub y_max_mm: f64,
    /// Whether a machine can pick at the picking point.
    pub check: PickingCheck,
    /// How far the runner-up extreme along the tray normal falls short of the picking
    /// point (mm): the margin before the picking event moves to another branch. `None`
    /// when the trajectory has a single extreme along the normal.
    pub picking_branch_gap_mm: Option<f64>,
    /// The same for planting: how much higher the runner-up low point is (mm).
    pub planting_branch_gap_mm: Option<f64>,
    /// The tip's velocity at planting (mm per radian of carrier): its sign along x tells
    /// the machine's travel direction under `travel = "auto"` without another arm state.
    #[serde(skip)]
    pub planting_tip_d1: Vec2,
}

impl Events {
    /// The point of the tray surface nearest the picking point (mm): the picking point
    /// moved back along the tray's inward unit normal `n` onto the surface.
    pub fn tray_surface_point(&self, n: Vec2) -> Vec2 {
        let tip = self.picking.tip_mm;
        tip - n * (tip.dot(n) - self.check.tray_surface_mm)
    }
}

/// Arm attitude (deg): the pusher direction's dip below the horizontal, in [−90°, 90°].
pub fn attitude_deg(pusher_angle: f64) -> f64 {
    (-pusher_angle.sin()).clamp(-1.0, 1.0).asin().to_degrees()
}

/// What the events read of arm I at an extreme: the carrier angle (rad), the tip (mm),
/// its velocity (mm/rad), the planet centre (mm) and the pusher-axis angle (rad).
#[derive(Debug, Clone, Copy)]
struct AtExtreme {
    theta: f64,
    tip: Vec2,
    tip_d1: Vec2,
    o3: Vec2,
    pusher_angle: f64,
}

impl AtExtreme {
    fn of(s: &ArmState) -> Self {
        Self {
            theta: s.theta,
            tip: s.tip,
            tip_d1: s.tip_d1,
            o3: s.o3,
            pusher_angle: s.pusher_angle,
        }
    }

    /// The state `dt` (rad) of carrier angle past `s`, by Taylor's series: second order
    /// for the tip and the planet centre (`O3` turns with the carrier, `O3' = σ·O3⊥`,
    /// `O3'' = −O3`), first for the tip's velocity and the pusher angle (`θ3'`). For
    /// `|dt|` below 1e-7 rad the terms left out are below 1e-13 of each value. The series
    /// takes the model's exact derivatives, while [`Kinematics::state_at`] places the arm
    /// through the interpolated `Φ⁻¹`, whose slope differs from them by the interpolation's
    /// error: the two agree to about 1e-8 mm at 120 samples (a test holds them to 1e-7 mm),
    /// far below the trajectory's own accuracy (1e-3 mm, docs/accuracy.md).
    fn advanced(s: &ArmState, sigma: f64, dt: f64) -> Self {
        Self {
            theta: s.theta + dt,
            tip: s.tip + (s.tip_d1 + s.tip_d2 * (0.5 * dt)) * dt,
            tip_d1: s.tip_d1 + s.tip_d2 * dt,
            o3: s.o3 + (s.o3.turn_90() * sigma - s.o3 * (0.5 * dt)) * dt,
            pusher_angle: s.pusher_angle + s.theta3_d[0] * dt,
        }
    }
}

/// Refines the extreme of `t ↦ D(t)·dir` near node `j` by Newton on the derivative,
/// using the exact tip derivatives; `max` chooses maximum or minimum. Returns the arm
/// there and the extreme value, or the node's where Newton finds no point beyond it
/// within 1.5 nodes. Newton starts where the sextic through the node's value and
/// derivatives and its four nearest nodes' values has its extreme ([`sextic_extreme`]):
/// 1.4 arm states an extreme in a robust evaluation of the paper's design, against 2.0
/// from the node. Where that start fails, it starts from the node. It converges
/// quadratically: once a step falls below 1e-7 rad, the next is below 1e-13 rad, so that
/// last step is taken along the Taylor series of the state in hand
/// ([`AtExtreme::advanced`]) instead of with a new arm state.
fn refine_extreme(kin: &Kinematics, dir: Vec2, j: usize, max: bool) -> (AtExtreme, f64) {
    let tips = kin.tips();
    let n = tips.len();
    let h = TAU / n as f64;
    let sigma = kin.spec().rotation.sign();
    let dot = |v: Vec2| v.dot(dir);
    let start = kin.theta(j);
    // The node's state from what the nodes keep (to rounding `state_at(θ_j)`).
    let at_node = kin.node_state(j);
    let node_value = dot(tips[j]);
    let newton = |mut state: ArmState| {
        for _ in 0..20 {
            let (d1, d2) = (dot(state.tip_d1), dot(state.tip_d2));
            if (max && d2 >= 0.0) || (!max && d2 <= 0.0) {
                break;
            }
            let step = (d1 / d2).clamp(-h, h);
            if step.abs() < 1e-7 {
                return AtExtreme::advanced(&state, sigma, -step);
            }
            state = kin.state_at(state.theta - step);
        }
        AtExtreme::of(&state)
    };
    // Newton's end where it is beyond the node and within 1.5 nodes of it.
    let kept = |last: AtExtreme| {
        let refined = dot(last.tip);
        let better = if max {
            refined >= node_value
        } else {
            refined <= node_value
        };
        (better && (last.theta - start).abs() <= 1.5 * h).then_some((last, refined))
    };
    // The two nodes before and after j, around the turn (j < n): one wrap, no `%`.
    let wrap = |k: usize| if k >= n { k - n } else { k };
    let around = [j + n - 2, j + n - 1, j + 1, j + 2].map(|k| dot(tips[wrap(k)]));
    let slopes = [dot(at_node.tip_d1), dot(at_node.tip_d2)];
    (sextic_extreme(around, node_value, slopes, h, max))
        .and_then(|t| kept(newton(kin.state_at(start + t))))
        .or_else(|| kept(newton(at_node)))
        .unwrap_or((AtExtreme::of(&at_node), node_value))
}

/// Where the sextic `q(t)` with a node's value `at`, slope and curvature (`slopes`, per
/// rad and per rad²) at `t = 0` and the values `around` it at `t = −2h, −h, h, 2h` (rad)
/// has its extreme of the kind asked for (`max`) within one node of it: the offset `t`
/// (rad), from the node's Newton step by three Newton steps on `q'`. Newton's next step
/// from there is typically 1e-8 to 1e-6 rad, where from the node's own Newton step it is
/// about 1e-4 rad (the path's fourth derivative jumps at the pitch curve's knots, which
/// bounds what a wider stencil gains). `None` where the node's curvature has the wrong
/// sign, or the sextic's extreme lies more than `h` away, or is of the other kind there.
fn sextic_extreme(around: [f64; 4], at: f64, slopes: [f64; 2], h: f64, max: bool) -> Option<f64> {
    let ([f_2, f_1, f1, f2], [d1, d2]) = (around, slopes);
    if (max && d2 >= 0.0) || (!max && d2 <= 0.0) {
        return None;
    }
    // In nodes, s = t/h: q = at + a·s + b·s²/2 + c3·s³ + c4·s⁴ + c5·s⁵ + c6·s⁶, its odd part
    // through (f(s) − f(−s))/2 − a·s and its even part through (f(s) + f(−s))/2 − at −
    // b·s²/2 at s = 1 and 2: c3 + c5 and 8c3 + 32c5, c4 + c6 and 16c4 + 64c6.
    let (a, b) = (d1 * h, d2 * h * h);
    let odd = [0.5 * (f1 - f_1) - a, 0.5 * (f2 - f_2) - 2.0 * a];
    let even = [
        0.5 * (f1 + f_1) - at - 0.5 * b,
        0.5 * (f2 + f_2) - at - 2.0 * b,
    ];
    let c5 = (odd[1] - 8.0 * odd[0]) * (1.0 / 24.0);
    let c3 = odd[0] - c5;
    let c6 = (even[1] - 16.0 * even[0]) * (1.0 / 48.0);
    let c4 = even[0] - c6;
    let slope =
        |s: f64| a + s * (b + s * (3.0 * c3 + s * (4.0 * c4 + s * (5.0 * c5 + s * 6.0 * c6))));
    let bend = |s: f64| b + s * (6.0 * c3 + s * (12.0 * c4 + s * (20.0 * c5 + s * 30.0 * c6)));
    let mut s = (-a / b).clamp(-1.0, 1.0);
    for _ in 0..3 {
        s -= slope(s) / bend(s);
    }
    let kind = if max { bend(s) < 0.0 } else { bend(s) > 0.0 };
    (s.abs() <= 1.0 && kind).then_some(s * h)
}

/// The node of the largest `D·dir`, and the sub-sample value of the largest other local
/// maximum (another branch), if the trajectory has one: over every node, or over `marked`
/// nodes alone (ascending) where every node that is a local maximum (or holds the largest
/// value) is among them ([`walk_nodes`]), with the same result.
///
/// One pass: one value per node, rolled through (previous, this, next), with neighbours by
/// comparison, not `%` (an integer division per node cost more than the rest of the walk;
/// this runs twice per evaluation). The local maxima are strict on the left, so no two are
/// neighbours: at most two lie within one node of the best node (those that are its own
/// peak), and the three highest local maxima hold the runner-up.
fn extreme_and_runner_up(
    tips: &[Vec2],
    dir: Vec2,
    marked: Option<&[usize]>,
) -> (usize, Option<f64>) {
    let n = tips.len();
    if n == 0 {
        return (0, None);
    }
    let v = |j: usize| tips[j].dot(dir);
    let walk = match marked {
        None => Walk::over_every_node(&tips.iter().map(|t| t.dot(dir)).collect::<Vec<_>>()),
        Some(nodes) => {
            let mut walk = Walk::starting_at(v(0));
            for &j in nodes {
                let (prev, next) = (
                    if j == 0 { n } else { j } - 1,
                    if j + 1 == n { 0 } else { j + 1 },
                );
                walk.node(j, v(prev), v(j), v(next));
            }
            walk
        }
    };
    walk.best_and_runner_up(n)
}

/// The node of the highest tip, the last of equals: over every node, or over `marked`
/// nodes alone (ascending) where every node that holds the largest height is among them
/// ([`walk_nodes`]), with the same result.
fn highest_node(tips: &[Vec2], marked: Option<&[usize]>) -> usize {
    match marked {
        Some(nodes) => last_highest(tips, nodes.iter().copied()),
        None => last_highest(tips, 0..tips.len()),
    }
    .unwrap_or(0)
}

/// `max_by`'s rule over `nodes` (the last of equals in `total_cmp`'s order), with the
/// highest so far kept in a register as its `total_cmp` key rather than loaded through its
/// node, or its key taken again, at every step.
fn last_highest(tips: &[Vec2], mut nodes: impl Iterator<Item = usize>) -> Option<usize> {
    // `f64::total_cmp`'s own key: its order is that of these integers.
    let key = |y: f64| {
        let bits = y.to_bits() as i64;
        bits ^ (((bits >> 63) as u64) >> 1) as i64
    };
    let first = nodes.next()?;
    let (mut best, mut top) = (first, key(tips[first].y));
    for j in nodes {
        let k = key(tips[j].y);
        if k >= top {
            (best, top) = (j, k);
        }
    }
    Some(best)
}

/// A walk for the largest value over the nodes, in node order: the best node so far
/// (the first of equals) and the three highest local maxima, highest first, as
/// `(node, sub-sample value)`.
struct Walk {
    best: usize,
    best_value: f64,
    peaks: [(usize, f64); 3],
}

impl Walk {
    /// A walk that has seen node 0's value.
    fn starting_at(first: f64) -> Self {
        Self {
            best: 0,
            best_value: first,
            peaks: [(usize::MAX, f64::NEG_INFINITY); 3],
        }
    }

    /// Node `j`, its value `c` and its neighbours' `m` (before) and `p` (after).
    #[inline(always)]
    fn node(&mut self, j: usize, m: f64, c: f64, p: f64) {
        if c > self.best_value {
            (self.best, self.best_value) = (j, c);
        }
        if c > m && c >= p {
            Self::peak(&mut self.peaks, j, [m, c, p]);
        }
    }

    /// The walk that has seen every node of a closed turn of `values` ([`Walk::node`] at
    /// each, from [`Walk::starting_at`] node 0), in vector lanes (`wide::f64x2`). The best
    /// node by two lanes, the even and the odd nodes, each keeping its first best, a tie
    /// between them to the earlier node; the local maxima by comparisons two nodes at a
    /// time, taken in node order.
    fn over_every_node(values: &[f64]) -> Self {
        let n = values.len();
        let best = first_largest(values);
        let mut walk = Self {
            best,
            best_value: values[best],
            ..Self::starting_at(values[0])
        };
        let value = |j: usize| values[if j == n { 0 } else { j }];
        let mut peak_at = |j: usize, m: f64| {
            let (c, p) = (values[j], value(j + 1));
            if c > m && c >= p {
                Self::peak(&mut walk.peaks, j, [m, c, p]);
            }
        };
        peak_at(0, values[n - 1]);
        // Nodes 1 … n − 2 in pairs, both neighbours inside the turn; then the rest.
        let inner = n.saturating_sub(2);
        let pairs = |from: usize| {
            (values.get(from..from + inner)).map_or(&[][..], |v| v.as_chunks::<2>().0)
        };
        let (before, nodes, after) = (pairs(0), pairs(1), pairs(2));
        for (k, ((&m, &c), &p)) in before.iter().zip(nodes).zip(after).enumerate() {
            let [m, c, p] = [m, c, p].map(f64x2::new);
            if (c.cmp_gt(m) & c.cmp_ge(p)).any() {
                let j = 2 * k + 1;
                peak_at(j, values[j - 1]);
                peak_at(j + 1, values[j]);
            }
        }
        for j in 1 + 2 * nodes.len()..n {
            peak_at(j, values[j - 1]);
        }
        walk
    }

    /// Local maximum `j` with the values around it, among the three highest `peaks`.
    /// Out of line: the walk meets a few peaks in a turn, and inlined, the peaks' six
    /// values took registers that every node then moved about (half a node's
    /// instructions).
    #[inline(never)]
    fn peak(peaks: &mut [(usize, f64); 3], j: usize, [m, c, p]: [f64; 3]) {
        let peak = (j, -parabola_vertex(-m, -c, -p));
        if peak.1 > peaks[2].1 {
            peaks[2] = peak;
            if peaks[2].1 > peaks[1].1 {
                peaks.swap(1, 2);
                if peaks[1].1 > peaks[0].1 {
                    peaks.swap(0, 1);
                }
            }
        }
    }

    /// The best node, and the highest local maximum that is not the best node's own peak
    /// (within one node of it, around the turn of `n` nodes).
    fn best_and_runner_up(self, n: usize) -> (usize, Option<f64>) {
        let best = self.best;
        let runner_up = (self.peaks.iter())
            .filter(|(j, _)| *j != usize::MAX)
            .find(|(j, _)| {
                let d = j.abs_diff(best);
                !(d <= 1 || d + 1 >= n)
            })
            .map(|&(_, value)| value);
        (best, runner_up)
    }
}

/// The first node of the largest value, as a walk that moves on only to a strictly larger
/// number from node 0 finds it (node 0 where it is not a number): two lanes, the even and
/// the odd nodes, each keeping its first largest, a tie between them to the earlier node.
fn first_largest(values: &[f64]) -> usize {
    let Some(&first) = values.first().filter(|v| !v.is_nan()) else {
        return 0;
    };
    let (pairs, tail) = values.as_chunks::<2>();
    // Node indices as floats (exact below 2⁵³); the odd lane starts with none.
    let (mut best, mut node) = (
        f64x2::new([first, f64::NEG_INFINITY]),
        f64x2::new([0.0, f64::INFINITY]),
    );
    let mut j = f64x2::new([0.0, 1.0]);
    for &pair in pairs {
        let v = f64x2::new(pair);
        let above = v.cmp_gt(best);
        (best, node) = (above.blend(v, best), above.blend(j, node));
        j += f64x2::splat(2.0);
    }
    let ([b0, b1], [j0, j1]) = (best.to_array(), node.to_array());
    let (mut top, mut at) = if b1 > b0 || (b1 == b0 && j1 < j0) {
        (b1, j1)
    } else {
        (b0, j0)
    };
    for (k, &v) in tail.iter().enumerate() {
        if v > top {
            (top, at) = (v, (2 * pairs.len() + k) as f64);
        }
    }
    at as usize
}

/// The events' walks, by the direction they walk along.
#[derive(Debug, Clone, Copy)]
enum Along {
    /// The tray's inward normal (picking).
    Normal = 0,
    /// Down (planting).
    Down = 1,
    /// Up (the highest point).
    Up = 2,
}

/// Straight down.
const DOWN: Vec2 = Vec2::new(0.0, -1.0);
/// Straight up.
const UP: Vec2 = Vec2::new(0.0, 1.0);

/// The nodes a walk of `kin`'s tips along `dir` may visit alone: those marked on the train
/// it was reassembled from ([`mark_walk_nodes`]), where its displacement and the tilt of
/// its direction (turned back by its turn) fit the marks. `None`: walk every node.
///
/// Why a walk over them finds what a walk over every node finds: the tips are the marked
/// train's, turned by `turn`, within δ (the displacement). Along `dir`, a difference of
/// two neighbours' values is then the marked train's along `dir'` (`dir` turned back)
/// within 2δ, and that is the marked train's along its own direction within
/// `|ΔD|·|dir' − dir₀|` (`ΔD` the step between the two tips). A node that is a local
/// maximum here (or holds the largest value, or one equal to it) is at or above both its
/// neighbours, so on the marked train it lies at most `2δ + |ΔD|·tilt` below either: the
/// marks keep every such node, with `band ≥ 2δ` and `tilt ≥ |dir' − dir₀|`.
fn walk_nodes(kin: &Kinematics, dir: Vec2, along: Along) -> Option<&[usize]> {
    let marks = kin.marks()?;
    let walks = marks.walks.as_deref()?;
    let marked_dir = [walks.normal, DOWN, UP][along as usize];
    let tilt = tilt(marks.turn, dir, marked_dir);
    // A NaN displacement or tilt fails the comparisons too.
    let fits = 2.0 * marks.displacement_mm * (1.0 + 1e-9) <= walks.band_mm && tilt <= walks.tilt;
    walks.nodes[along as usize].as_deref().filter(|_| fits)
}

/// How far a walk direction `dir`, turned back by the whole train's `turn` (a unit
/// complex number), lies from the marked direction `marked`: the length of their
/// difference.
fn tilt(turn: Vec2, dir: Vec2, marked: Vec2) -> f64 {
    (dir.rotated(Vec2::new(turn.x, -turn.y)) - marked)
        .hypot2()
        .sqrt()
}

/// The largest tilt ([`walk_nodes`]) of the walks of a reassembly turned by `turn` whose
/// tray has the inward `normal`, against a train marked for `marked_normal`: the normal's,
/// and the one down and up share.
pub(crate) fn walks_tilt(turn: Vec2, normal: Vec2, marked_normal: Vec2) -> f64 {
    tilt(turn, normal, marked_normal).max(tilt(turn, DOWN, DOWN))
}

/// Marks on `kin` the nodes its reassemblies' walks along the tray's inward `normal`,
/// down and up may visit alone ([`walk_nodes`]): those reassemblies that move their arms
/// by at most half of `band_mm` beyond a turn of the whole train, and whose walk
/// directions, turned back by that turn, lie within `tilt` of these. A node is marked
/// where its value along the direction lies at most `band_mm + |ΔD|·tilt` (and a margin
/// for rounding) below each neighbour's, `|ΔD|` taken as `|Δx| + |Δy|` (no root), at or
/// above the step's length. Nothing is marked where a tip is not finite, nor for a walk
/// that would visit more than a third of the nodes.
pub(crate) fn mark_walk_nodes(kin: &mut Kinematics, normal: Vec2, band_mm: f64, tilt: f64) {
    let tips = kin.tips();
    let n = tips.len();
    if n < 3 || !tips.iter().all(|t| t.is_finite()) {
        return;
    }
    let size = tips.iter().map(|t| t.hypot2()).fold(0.0, f64::max).sqrt();
    let band = band_mm + 1e-9 * (1.0 + size);
    // The step from each node to the next, its rise along each direction, and how far it
    // may fall (or rise) within the slack.
    let step = |j: usize| {
        let d = tips[if j + 1 == n { 0 } else { j + 1 }] - tips[j];
        let slack = band + (d.x.abs() + d.y.abs()) * tilt;
        ([d.dot(normal), -d.y, d.y], slack)
    };
    let mut nodes: [Vec<usize>; 3] = Default::default();
    // Whether the step into node j (from j − 1) falls by at most the slack, per direction.
    let (rise, slack) = step(n - 1);
    let mut from_below = rise.map(|r| r >= -slack);
    for j in 0..n {
        let (rise, slack) = step(j);
        for (k, marked) in nodes.iter_mut().enumerate() {
            // Node j is at most the slack below the node before and the node after.
            if from_below[k] && rise[k] <= slack {
                marked.push(j);
            }
            from_below[k] = rise[k] >= -slack;
        }
    }
    // A marked node costs three values, where the whole walk takes one a node.
    kin.mark_walks(MarkedWalks {
        normal,
        nodes: nodes.map(|nodes| (nodes.len() <= n / 3).then_some(nodes)),
        band_mm,
        tilt,
    });
}

/// The housing's radius about the carrier axis (mm): the disc the gearbox sweeps (the
/// envelope of the sun, the intermediates and the planets) plus the wall margin.
pub(crate) fn housing_radius(kin: &Kinematics, agro: &Agronomy) -> f64 {
    (kin.radius_range().1)
        .max(kin.carrier_distance() + kin.intermediate_reach())
        .max(kin.planet_radius() + kin.planet_reach())
        + agro.housing_margin_mm
}

/// Locates picking and planting, checks the picking, and finds the window and the
/// extremes of height.
pub fn events(kin: &Kinematics, agro: &Agronomy) -> Events {
    Picking::locate(kin, agro).events(kin, agro)
}

/// Picking located, the first of the events: the tip's deepest reach into the tray
/// (the tray's normal, its node, the runner-up extreme's depth, the arm there and its
/// depth along the normal, mm). A search's trial whose picking angle already loses
/// stops here.
pub(crate) struct Picking {
    /// The tray's inward normal (unit).
    normal: Vec2,
    node: usize,
    runner_up: Option<f64>,
    picked: AtExtreme,
    depth: f64,
}

impl Picking {
    /// The node deepest along the tray's normal and its runner-up, the extreme refined
    /// by Newton on the arm's state.
    pub(crate) fn locate(kin: &Kinematics, agro: &Agronomy) -> Self {
        let normal = agro.tray_normal();
        let marked = walk_nodes(kin, normal, Along::Normal);
        let (node, runner_up) = extreme_and_runner_up(kin.tips(), normal, marked);
        let (picked, depth) = refine_extreme(kin, normal, node, true);
        Self {
            normal,
            node,
            runner_up,
            picked,
            depth,
        }
    }

    /// The pusher's attitude at picking (deg): the picking angle.
    pub(crate) fn attitude_deg(&self) -> f64 {
        attitude_deg(self.picked.pusher_angle)
    }

    /// The other events, after picking ([`events`]).
    pub(crate) fn events(self, kin: &Kinematics, agro: &Agronomy) -> Events {
        let Self {
            normal,
            node: jp,
            runner_up: picking_runner_up,
            picked,
            depth,
        } = self;
        let tips = kin.tips();
        let marked = walk_nodes(kin, DOWN, Along::Down);
        let (jl, planting_runner_up) = extreme_and_runner_up(tips, DOWN, marked);
        let (planted, neg_low) = refine_extreme(kin, DOWN, jl, true);
        // The highest node (no runner-up needed: no event hangs on it).
        let jh = highest_node(tips, walk_nodes(kin, UP, Along::Up));
        let (_, y_max) = refine_extreme(kin, UP, jh, true);
        let event = |s: &AtExtreme| Event {
            carrier_rad: crate::angle::wrap_turn(s.theta),
            tip_mm: s.tip,
            attitude_deg: attitude_deg(s.pusher_angle),
        };
        let picking = event(&picked);
        let speed = picked.tip_d1.hypot() * kin.carrier_speed() / 1000.0;
        let surface = agro.tray_distance_mm.unwrap_or(depth - agro.tray_depth_mm);
        let check = picking_check(kin, agro, &picked, surface, picking_runner_up);
        // Window: the run of nodes around the picking node with the tip beyond the surface.
        let n = kin.len();
        let [w0, w1] = span_where(n, jp, |j| tips[j].dot(normal) - surface)
            // A tray the tip does not reach (placed by distance): an empty window at picking.
            .unwrap_or([picking.carrier_rad; 2]);
        let shift = (w0 / TAU).floor() * TAU;
        Events {
            picking,
            planting: event(&planted),
            picking_window_rad: [w0 - shift, w1 - shift],
            picking_tip_speed_m_s: speed,
            y_min_mm: -neg_low,
            y_max_mm: y_max,
            check,
            picking_branch_gap_mm: picking_runner_up.map(|r| depth - r),
            planting_branch_gap_mm: planting_runner_up.map(|r| neg_low - r),
            planting_tip_d1: planted.tip_d1,
        }
    }
}

/// The carrier span (rad, `start ≤ end`, `start` in `[-2π, 2π)`) of the run of nodes around
/// node `j0` where `f(j) > 0`, its ends interpolated linearly between nodes; `None` when
/// `f(j0) ≤ 0`. `f` takes node indices in `0..n`.
pub(crate) fn span_where(n: usize, j0: usize, f: impl Fn(usize) -> f64) -> Option<[f64; 2]> {
    let g = |j: usize| f(j % n);
    if g(j0) <= 0.0 {
        return None;
    }
    let (mut start, mut end) = (j0 + n, j0 + n);
    while end < j0 + 2 * n - 1 && g(end + 1) > 0.0 {
        end += 1;
    }
    while start > j0 + 1 && g(start - 1) > 0.0 {
        start -= 1;
    }
    let h = TAU / n as f64;
    let cross = |a: usize, b: usize| {
        let (fa, fb) = (g(a), g(b));
        let frac = if fa != fb {
            (fa / (fa - fb)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a as f64 + frac * (b as f64 - a as f64)) * h - TAU
    };
    Some([cross(start, start - 1), cross(end, end + 1)])
}

/// The picking conditions at the picked state, for a tray surface at `surface` (mm along
/// the normal) and the runner-up extreme along the normal.
fn picking_check(
    kin: &Kinematics,
    agro: &Agronomy,
    picked: &AtExtreme,
    surface: f64,
    runner_up: Option<f64>,
) -> PickingCheck {
    let normal = agro.tray_normal();
    let dot = |p: Vec2| p.dot(normal);
    let s = kin.spec().arm_length_mm;
    let tip_depth = dot(picked.tip) - surface;
    let arm = picked.tip - picked.o3;
    // Arm k lags arm I by k·360°/arms: its state is arm I's at θ − k·360°/arms.
    let other_arms_behind = (1..kin.arms())
        .map(|k| {
            let (o3, tip) = kin.planet_and_tip_at(picked.theta - kin.arm_lag(k));
            surface - dot(o3).max(dot(tip)) - agro.arm_half_width_mm
        })
        .fold(f64::INFINITY, f64::min);
    PickingCheck {
        tray_surface_mm: surface,
        tip_depth_mm: tip_depth,
        reach_mm: agro
            .tray_distance_mm
            .map(|_| tip_depth.min(agro.tray_depth_mm - tip_depth)),
        planet_behind_mm: surface - dot(picked.o3),
        housing_behind_mm: surface - housing_radius(kin, agro),
        pusher_into_tray_mm: s * dot(unit(picked.pusher_angle)),
        arm_into_tray_mm: dot(arm),
        other_arms_behind_mm: (kin.arms() > 1).then_some(other_arms_behind),
        second_entry_behind_mm: runner_up.map(|r| surface - r),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attitude_is_the_dip_below_horizontal() {
        assert!((attitude_deg(-std::f64::consts::FRAC_PI_2) - 90.0).abs() < 1e-12);
        assert!(attitude_deg(std::f64::consts::PI).abs() < 1e-12);
        assert!((attitude_deg(std::f64::consts::PI + 0.5) - 0.5f64.to_degrees()).abs() < 1e-9);
    }

    /// The sextic's extreme against a closed form: for `D(t) = cos(t − t0) + 0.3·cos(3(t −
    /// t0))`, which peaks at `t0`, sampled at `0, ±h, ±2h` with the exact slope and
    /// curvature at 0, the offset is within 1e-9 rad of `t0` for every `t0` within half a
    /// node, where the node's Newton step `−D'/D''` misses by up to about 1e-4 rad; the
    /// minimum of `−D` is the same point; a curvature of the other kind gives none.
    #[test]
    fn the_sextics_extreme_is_the_closed_forms() {
        let h = TAU / 120.0;
        let mut worst_newton = 0.0f64;
        for k in -10..=10 {
            let t0 = 0.5 * h * k as f64 / 10.0;
            let d = |t: f64, m: u32| {
                let (u, w) = (t - t0, 3.0 * (t - t0));
                // The m-th derivative of cos(u) + 0.3·cos(w).
                let c = |x: f64, m: u32| [x.cos(), -x.sin(), -x.cos(), x.sin()][m as usize % 4];
                c(u, m) + 0.3 * 3f64.powi(m as i32) * c(w, m)
            };
            let around = [-2.0, -1.0, 1.0, 2.0].map(|i| d(i * h, 0));
            let slopes = [d(0.0, 1), d(0.0, 2)];
            let t = sextic_extreme(around, d(0.0, 0), slopes, h, true).unwrap();
            assert!((t - t0).abs() < 1e-9, "t0 {t0}: {t}");
            worst_newton = worst_newton.max((-slopes[0] / slopes[1] - t0).abs());
            let negated = (around.map(|v| -v), -d(0.0, 0), slopes.map(|v| -v));
            let low = sextic_extreme(negated.0, negated.1, negated.2, h, false).unwrap();
            assert_eq!(low, t);
            assert_eq!(sextic_extreme(around, d(0.0, 0), slopes, h, false), None);
        }
        assert!(worst_newton > 1e-5, "{worst_newton}");
    }

    /// The runner-up by its definition: every local maximum (strict on the left) more
    /// than one node from the best, each refined by its parabola, the largest of them.
    fn runner_up_by_definition(tips: &[Vec2], dir: Vec2) -> (usize, Option<f64>) {
        let n = tips.len();
        let v = |j: usize| tips[j % n].dot(dir);
        let best = (0..n).fold(0, |b, j| if v(j) > v(b) { j } else { b });
        let runner_up = (0..n)
            .filter(|&j| {
                let d = j.abs_diff(best);
                v(j) > v(j + n - 1) && v(j) >= v(j + 1) && d > 1 && d + 1 < n
            })
            .map(|j| -parabola_vertex(-v(j + n - 1), -v(j), -v(j + 1)))
            .reduce(f64::max);
        (best, runner_up)
    }

    proptest::proptest! {
        /// Wavy closed paths, many with several branches along the direction (and ties from
        /// values rounded to a grid): the one-pass walk finds the definition's best node
        /// and runner-up, bit for bit.
        #[test]
        fn one_pass_runner_up_is_the_definitions(
            n in 3usize..60,
            waves in proptest::collection::vec((1.0f64..9.0, -3.0f64..3.0, 0.0f64..6.3), 1..4),
            grid in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.05f64..0.5],
            angle in 0.0f64..6.3,
        ) {
            let tips: Vec<Vec2> = (0..n)
                .map(|j| {
                    let t = TAU * j as f64 / n as f64;
                    let x: f64 = waves.iter().map(|(k, a, p)| a * (k.floor() * t + p).sin()).sum();
                    let x = if grid > 0.0 { (x / grid).round() * grid } else { x };
                    Vec2::new(x, t.cos())
                })
                .collect();
            let dir = unit(angle);
            proptest::prop_assert_eq!(
                extreme_and_runner_up(&tips, dir, None),
                runner_up_by_definition(&tips, dir)
            );
        }
    }

    proptest::proptest! {
        /// The highest node is `max_by`'s over `total_cmp` (the last of equals), over every
        /// node and over marked nodes: heights drawn from a few values, so that ties are
        /// common, with ±0, ±∞ and NaN among them.
        #[test]
        fn highest_node_is_max_by_total_cmp(
            heights in proptest::collection::vec(0usize..8, 1..40),
            marked in proptest::collection::vec(proptest::bool::ANY, 40),
        ) {
            let values = [-1.5, -0.0, 0.0, 2.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, -f64::NAN];
            let tips: Vec<Vec2> = heights.iter().map(|&h| Vec2::new(0.0, values[h])).collect();
            let higher = |&a: &usize, &b: &usize| tips[a].y.total_cmp(&tips[b].y);
            let nodes: Vec<usize> = (0..tips.len()).filter(|&j| marked[j]).collect();
            proptest::prop_assert_eq!(
                highest_node(&tips, None),
                (0..tips.len()).max_by(higher).unwrap()
            );
            proptest::prop_assert_eq!(
                highest_node(&tips, Some(&nodes)),
                nodes.iter().copied().max_by(higher).unwrap_or(0)
            );
        }
    }

    proptest::proptest! {
        /// The walk over every node in lanes is the node-by-node walk, bit for bit: its best
        /// node and its three highest local maxima, on turns of one node up, with values
        /// drawn from a few (ties everywhere), ±0, ±∞ and NaN among them.
        #[test]
        fn every_node_in_lanes_is_the_node_by_node_walk(
            picks in proptest::collection::vec(0usize..9, 1..40),
        ) {
            let choices = [-1.5, -0.0, 0.0, 2.0, 2.5, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 1.0];
            let values: Vec<f64> = picks.iter().map(|&k| choices[k]).collect();
            let n = values.len();
            let mut by_node = Walk::starting_at(values[0]);
            let (mut m, mut c) = (values[n - 1], values[0]);
            for j in 0..n {
                let p = values[(j + 1) % n];
                by_node.node(j, m, c, p);
                (m, c) = (c, p);
            }
            let in_lanes = Walk::over_every_node(&values);
            let bits = |w: &Walk| w.peaks.map(|(j, v)| (j, v.to_bits()));
            proptest::prop_assert_eq!(in_lanes.best, by_node.best);
            proptest::prop_assert_eq!(bits(&in_lanes), bits(&by_node));
        }
    }

    #[test]
    fn runner_up_is_another_local_maximum() {
        // Two bumps along x: the larger at node 2, the smaller (a branch) at node 7.
        let xs = [0.0, 2.0, 5.0, 2.0, 0.0, 0.0, 1.0, 3.0, 2.0, 0.0];
        let tips: Vec<Vec2> = xs.iter().map(|&x| Vec2::new(x, 0.0)).collect();
        let (best, runner) = extreme_and_runner_up(&tips, Vec2::new(1.0, 0.0), None);
        assert_eq!(best, 2);
        assert_eq!(runner, Some(-parabola_vertex(-1.0, -3.0, -2.0)));
        assert!(runner.unwrap() > 3.0);
        // One bump: no runner-up.
        let tips: Vec<Vec2> = [0.0, 1.0, 2.0, 1.0]
            .iter()
            .map(|&x| Vec2::new(x, 0.0))
            .collect();
        assert_eq!(
            extreme_and_runner_up(&tips, Vec2::new(1.0, 0.0), None),
            (2, None)
        );
    }

    /// A train reassembled from one whose walks are marked walks the marked nodes alone
    /// and finds what the walk over every node finds, bit for bit (the best node, the
    /// runner-up, the highest node, and so every event): on three designs, for random
    /// reassemblies (Φ0 and β0 moved by up to 0.2° or 12°, S and H1 by up to 0.4 mm, the
    /// bore by 0.04 mm) with the tray's normal turned by up to 0.5° or 30°, and for a
    /// reassembly of a reassembly (the displacements add, the turns compose). A band or
    /// tilt too small for the move is refused, so every node is walked. (Accepting every
    /// band and tilt, with some below the move, fails this test.)
    #[test]
    fn marked_walks_find_what_the_whole_walks_find_bit_for_bit() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        use std::cell::Cell;
        let curve = crate::CurveSpec::paper().build().unwrap();
        let res = crate::Resolution::DEFAULT;
        let (confined, refused) = (Cell::new(0), Cell::new(0));
        let mut runner = TestRunner::new(Config::with_cases(160));
        let deviation = proptest::array::uniform5(-1.0..1.0f64);
        let cases = (
            0..3usize,
            deviation,
            -1.0..1.0f64,
            // Bands and tilts that fit the move, and (one case in four each) far too small.
            prop_oneof![
                2 => (1.0..6.0f64, 1.0..3.0f64),
                1 => (0.0..0.2f64, 0.0..3.0f64),
                1 => (1.0..6.0f64, 0.0..0.2f64),
            ],
            prop_oneof![Just(1.0), Just(60.0)],
        );
        runner
            .run(
                &cases,
                |(design, [dphi, dbeta, ds, dh, da], dtray, (band_factor, tilt_factor), size)| {
                    let (beta0, gamma0) = [(-29.0, -53.0), (40.0, -20.0), (0.0, 60.0)][design];
                    let spec = crate::TrainSpec {
                        beta0_deg: beta0,
                        gamma0_deg: gamma0,
                        ..Default::default()
                    };
                    let agro = Agronomy::default();
                    let mut source = Kinematics::solve(&curve, None, &spec, &res).unwrap();
                    let [moved, again] =
                        crate::planetary::moved_for_tests(&spec, [dphi, dbeta, ds, dh], size);
                    let offset = 0.04 * da;
                    // The sample's tray normal, turned against the marked one.
                    let tray = Agronomy {
                        tray_normal_deg: agro.tray_normal_deg + 0.5 * size * dtray,
                        ..agro
                    };
                    let normal = agro.tray_normal();
                    let own_normal = tray.tray_normal();
                    // The whole walks, on the same positions unmarked.
                    let unmarked = source.clone();
                    let first_whole = unmarked.reassembled(&moved, offset).unwrap();
                    let second_whole = first_whole.reassembled(&again, 0.0).unwrap();
                    // Marked for the first reassembly's move and tilt, times the factors.
                    let (delta, turn) = source.displacement_and_turn_to(&moved, offset);
                    let tilt = walks_tilt(turn, own_normal, normal);
                    mark_walk_nodes(
                        &mut source,
                        normal,
                        band_factor * 2.0 * delta,
                        tilt_factor * tilt,
                    );
                    let first = source.reassembled(&moved, offset).unwrap();
                    let second = first.reassembled(&again, 0.0).unwrap();
                    for (kin, whole) in [(&first, &first_whole), (&second, &second_whole)] {
                        prop_assert!(whole.marks().is_none());
                        let tips = kin.tips();
                        prop_assert_eq!(tips, whole.tips());
                        for (dir, along) in [(own_normal, Along::Normal), (DOWN, Along::Down)] {
                            let marked = walk_nodes(kin, dir, along);
                            let (best, runner_up) = extreme_and_runner_up(tips, dir, marked);
                            let (all_best, all_runner_up) = extreme_and_runner_up(tips, dir, None);
                            prop_assert_eq!(best, all_best);
                            prop_assert_eq!(
                                runner_up.map(f64::to_bits),
                                all_runner_up.map(f64::to_bits)
                            );
                            match marked {
                                Some(nodes) => {
                                    prop_assert!(nodes.len() <= kin.len() / 3);
                                    confined.set(confined.get() + 1);
                                }
                                None => refused.set(refused.get() + 1),
                            }
                        }
                        let up = walk_nodes(kin, UP, Along::Up);
                        prop_assert_eq!(highest_node(tips, up), highest_node(tips, None));
                        prop_assert_eq!(
                            format!("{:?}", events(kin, &tray)),
                            format!("{:?}", events(whole, &tray))
                        );
                    }
                    Ok(())
                },
            )
            .unwrap();
        let counts = (confined.get(), refused.get());
        assert!(counts.0 > 50 && counts.1 > 100, "{counts:?}");
    }
}
