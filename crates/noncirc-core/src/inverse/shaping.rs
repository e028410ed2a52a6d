//! The overall ratio shaped within the target's tolerance for buildable pitch curves
//! (docs/inverse.md §6): a drawn spline's ripple, which the ratio reads from the path's
//! third derivative, taken out before the curves are built.

use crate::angle::unit;
use crate::gear::{curvature_limit, ModuleRule};
use crate::quadrature::SpectralIntegrator;
use crate::vec2::Vec2;
use noncirc_search::{refine, LocalSettings, ResidualBatch};
use std::f64::consts::TAU;

/// Harmonics of the correction [`RatioShaping`] makes to the planet's lag.
const SHAPING_HARMONICS: usize = 32;
/// Most residual vectors the shaping's refinement evaluates (about a second).
const SHAPING_EVALUATIONS: u64 = 6_000;

/// The overall ratio at the carrier nodes, shaped within the tolerance so that every pitch
/// curve is convex and no sharper than the module's bound asks.
///
/// The inversion reads the ratio from the path's third derivative, so the ripple a drawn
/// spline has at the spacing of its points reaches the gears' curvature, and a path within
/// a millimetre of a buildable one can invert to concave gears. A correction of the lag,
/// `δL(θ) = Σ_{k ≤ 32} a_k cos kθ + b_k sin kθ` (so `δi = δL'` keeps the mean ratio 1 and
/// the arm turning back), turns the arm by `−σ·δL` at each carrier angle and moves the tip
/// by at most `S·|δL − c|` (the constant `c` taken up by β0). Levenberg–Marquardt, from no
/// correction, minimises residuals for each node's curvature outside `[0.1 κ_max, κ_max]`
/// on each of the four curves (ten times over below), for the tip's move beyond 0.9 of the
/// budget, and 0.003 of the move itself (the least correction).
pub(super) struct RatioShaping {
    /// The shaped ratio at the nodes.
    pub(super) ratio: Vec<f64>,
    /// The turn added to the arm at θ = 0 (rad, times the carrier's sense σ).
    pub(super) arm_shift: f64,
    /// The largest move of the tip (mm).
    pub(super) moved_mm: f64,
}

/// The shaping's problem for the local refinement: the read ratio, the split, the centre
/// distances, the curvature bound and the move's budget.
struct ShapingProblem<'a> {
    ratio: &'a [f64],
    split: f64,
    centre_distances: [f64; 2],
    kappa_max: f64,
    arm_length: f64,
    budget_mm: f64,
    /// `cos kθ_j, sin kθ_j` for k = 1..=K, node-major.
    waves: Vec<[f64; 2]>,
    integrator: SpectralIntegrator,
}

impl ShapingProblem<'_> {
    /// The amplitude of each coefficient at the cube's faces (rad): one harmonic alone
    /// moves the tip by at most the budget.
    fn amplitude(&self) -> f64 {
        self.budget_mm / self.arm_length
    }

    /// The lag's correction and the ratio's at the nodes for the point `u` of the cube.
    fn correction(&self, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = self.ratio.len();
        let amplitude = self.amplitude();
        let mut lag = vec![0.0; n];
        let mut ratio = self.ratio.to_vec();
        for j in 0..n {
            for k in 0..SHAPING_HARMONICS {
                let [cos, sin] = self.waves[j * SHAPING_HARMONICS + k];
                let (a, b) = (
                    (2.0 * u[2 * k] - 1.0) * amplitude,
                    (2.0 * u[2 * k + 1] - 1.0) * amplitude,
                );
                let wave = (k + 1) as f64;
                lag[j] += a * cos + b * sin;
                ratio[j] += wave * (b * cos - a * sin);
            }
        }
        (lag, ratio)
    }

    /// The tip's move at each node (mm) about the lag's midrange `c`, and `c` (rad).
    fn moves(&self, lag: &[f64]) -> (Vec<f64>, f64) {
        let (lo, hi) = lag
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        let centre = 0.5 * (lo + hi);
        (
            lag.iter().map(|v| self.arm_length * (v - centre)).collect(),
            centre,
        )
    }
}

impl ResidualBatch for ShapingProblem<'_> {
    fn dim(&self) -> usize {
        2 * SHAPING_HARMONICS
    }

    fn residuals(&mut self, points: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let n = self.ratio.len();
        points
            .iter()
            .map(|u| {
                let (lag, ratio) = self.correction(u);
                let (moves, _) = self.moves(&lag);
                let mut out = Vec::with_capacity(6 * n);
                for m in &moves {
                    out.push(100.0 * (m.abs() - 0.9 * self.budget_mm).max(0.0) / self.budget_mm);
                    out.push(0.003 * m / self.budget_mm);
                }
                if ratio.iter().any(|&i| i <= 0.0) {
                    out.extend(std::iter::repeat_n(1e3, 4 * n));
                    return out;
                }
                let g_a = power_split(&ratio, self.split);
                let kappa_max = self.kappa_max;
                split_curvatures(
                    &ratio,
                    &g_a,
                    self.centre_distances,
                    &mut self.integrator,
                    |k| {
                        out.push(
                            ((k - kappa_max).max(0.0) + 10.0 * (0.1 * kappa_max - k).max(0.0))
                                / kappa_max,
                        );
                    },
                );
                out
            })
            .collect()
    }
}

impl RatioShaping {
    /// Shapes `ratio` (at `n` uniform carrier nodes) for the split λ `split`, the centre
    /// distances, the module's rule and least module (mm), the arm length and the tip's
    /// budget (mm). A ratio whose curves the rule already cuts at the module is kept; the
    /// shaping aims at convex curves with a tenth to spare on the convex bound (for the
    /// rounding to whole teeth: `2ρ_min/z_min ≥ 1.1·m_min`).
    pub(super) fn within(
        ratio: &[f64],
        split: f64,
        centre_distances: [f64; 2],
        (rule, module_mm): (&ModuleRule, f64),
        arm_length: f64,
        budget_mm: f64,
    ) -> Self {
        let kappa_max = 2.0 / (1.1 * module_mm * rule.z_min);
        let n = ratio.len();
        let unshaped = Self {
            ratio: ratio.to_vec(),
            arm_shift: 0.0,
            moved_mm: 0.0,
        };
        let mut integrator = SpectralIntegrator::new(n);
        let (mut least, mut most) = (f64::INFINITY, f64::NEG_INFINITY);
        split_curvatures(
            ratio,
            &power_split(ratio, split),
            centre_distances,
            &mut integrator,
            |k| {
                least = least.min(k);
                most = most.max(k);
            },
        );
        if budget_mm <= 0.0 || cuts(least, most, rule, module_mm) {
            return unshaped;
        }
        let waves = (0..n)
            .flat_map(|j| {
                (1..=SHAPING_HARMONICS).map(move |k| {
                    let x = TAU * (k * j) as f64 / n as f64;
                    [x.cos(), x.sin()]
                })
            })
            .collect();
        let mut problem = ShapingProblem {
            ratio,
            split,
            centre_distances,
            kappa_max,
            arm_length,
            budget_mm,
            waves,
            integrator,
        };
        let start = vec![0.5; 2 * SHAPING_HARMONICS];
        let settings = LocalSettings {
            max_evaluations: SHAPING_EVALUATIONS,
            step: 1e-6,
            tolerance: 1e-10,
        };
        let report = refine(&mut problem, &start, &settings);
        let (lag, shaped) = problem.correction(&report.u);
        let (moves, centre) = problem.moves(&lag);
        // β0 takes up the constant: the lag's correction is integrated again from 0, so the
        // arm turns by −σ(δL(θ) − δL(0)), and turning it at θ = 0 by σ(c − δL(0)) makes
        // that −σ(δL(θ) − c).
        let turn = centre - lag[0];
        let moved_mm = moves.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if moved_mm > budget_mm || shaped.iter().any(|&i| i <= 0.0) {
            return unshaped;
        }
        Self {
            ratio: shaped,
            arm_shift: turn,
            moved_mm,
        }
    }
}

/// Whether curves of least and largest curvature `least`, `most` (1/mm) are cut at the
/// module `module_mm` under `rule` (the module's curvature limit, as the module objective
/// reads it).
fn cuts(least: f64, most: f64, rule: &ModuleRule, module_mm: f64) -> bool {
    let concave = if least < 0.0 {
        -1.0 / least
    } else {
        f64::INFINITY
    };
    curvature_limit(1.0 / most, concave, rule) >= module_mm
}

/// `g_A = i^λ / mean(i^λ)` at the carrier nodes: the mean of 1 closes the first pair.
pub(super) fn power_split(ratio: &[f64], lambda: f64) -> Vec<f64> {
    let share: Vec<f64> = ratio.iter().map(|i| i.powf(lambda)).collect();
    let mean = share.iter().sum::<f64>() / ratio.len() as f64;
    share.iter().map(|s| s / mean).collect()
}

/// Each node's signed curvature (1/mm; positive convex) on the four pitch curves the
/// split `g_a` of `ratio` gives (the sun, the intermediate's layers A and B, the planet),
/// passed to `each` curve by curve: central differences in the carrier angle θ, in which
/// all four are periodic.
fn split_curvatures(
    ratio: &[f64],
    g_a: &[f64],
    a: [f64; 2],
    integrator: &mut SpectralIntegrator,
    mut each: impl FnMut(f64),
) {
    let n = ratio.len();
    let mut phi_a = vec![0.0; n];
    integrator.cumulative(g_a, &mut phi_a);
    let mut lag = vec![0.0; n];
    integrator.cumulative(ratio, &mut lag);
    let h = TAU / n as f64;
    let mut points = vec![Vec2::new(0.0, 0.0); n];
    for curve in 0..4 {
        for j in 0..n {
            let g_b = ratio[j] / g_a[j];
            let (r, angle) = match curve {
                0 => (a[0] * g_a[j] / (1.0 + g_a[j]), h * j as f64),
                1 => (a[0] / (1.0 + g_a[j]), phi_a[j]),
                2 => (a[1] * g_b / (1.0 + g_b), phi_a[j]),
                _ => (a[1] / (1.0 + g_b), lag[j]),
            };
            points[j] = unit(angle) * r;
        }
        let area: f64 = (0..n).map(|j| points[j].cross(points[(j + 1) % n])).sum();
        let orientation = area.signum();
        for j in 0..n {
            let (prev, here, next) = (points[(j + n - 1) % n], points[j], points[(j + 1) % n]);
            let d1 = (next - prev) * (0.5 / h);
            let d2 = (next - here * 2.0 + prev) * (1.0 / (h * h));
            each(orientation * d1.cross(d2) / d1.hypot().powi(3));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn extremes(ratio: &[f64], lambda: f64, a: [f64; 2]) -> (f64, f64) {
        let mut integrator = SpectralIntegrator::new(ratio.len());
        let (mut least, mut most) = (f64::INFINITY, f64::NEG_INFINITY);
        let g_a = power_split(ratio, lambda);
        split_curvatures(ratio, &g_a, a, &mut integrator, |k| {
            least = least.min(k);
            most = most.max(k);
        });
        (least, most)
    }

    /// A ratio of 1 all round: four circles of radius a/2, curvature 2/a.
    #[test]
    fn a_constant_ratio_gives_four_circles() {
        let a = [120.0, 90.0];
        let (least, most) = extremes(&[1.0; 360], 0.5, a);
        // Central differences on a circle sampled at h: x' shrinks by sin h / h and x''
        // by 2(1 − cos h)/h², so κ is read as κ·2(1 − cos h)/sin² h (to the second
        // difference's rounding).
        let h = TAU / 360.0;
        let read = 2.0 * (1.0 - h.cos()) / h.sin().powi(2);
        assert!((least / (read * 2.0 / a[0]) - 1.0).abs() < 1e-9, "{least}");
        assert!((most / (read * 2.0 / a[1]) - 1.0).abs() < 1e-9, "{most}");
    }

    /// Central differences: the curvature's error falls as h², so doubling the nodes
    /// quarters the change (each curve at θ = 0, a node of every grid).
    #[test]
    fn the_curvature_converges_at_second_order() {
        let at = |n: usize| {
            let ratio: Vec<f64> = (0..n)
                .map(|j| {
                    let t = TAU * j as f64 / n as f64;
                    // Mean 1: the waves average out over a turn.
                    1.0 + 0.4 * t.cos() + 0.1 * (2.0 * t).sin()
                })
                .collect();
            let mut integrator = SpectralIntegrator::new(n);
            let mut kappa = Vec::new();
            let g_a = power_split(&ratio, 0.5);
            split_curvatures(&ratio, &g_a, [120.0, 100.0], &mut integrator, |k| {
                kappa.push(k)
            });
            [0, n, 2 * n, 3 * n].map(|j| kappa[j])
        };
        let (k1, k2, k3) = (at(180), at(360), at(720));
        for c in 0..4 {
            let order = ((k1[c] - k2[c]) / (k2[c] - k3[c])).abs().log2();
            assert!((order - 2.0).abs() < 0.1, "curve {c}: order {order}");
        }
    }

    /// A ratio within the bounds is left as it is.
    #[test]
    fn a_buildable_ratio_is_not_shaped() {
        let n = 360;
        let ratio: Vec<f64> = (0..n)
            .map(|j| 1.0 + 0.2 * (TAU * j as f64 / n as f64).cos())
            .collect();
        let rule = ModuleRule::default();
        let shaped = RatioShaping::within(&ratio, 0.5, [120.0, 120.0], (&rule, 2.5), 150.0, 0.5);
        assert_eq!(shaped.ratio, ratio);
        assert_eq!((shaped.arm_shift, shaped.moved_mm), (0.0, 0.0));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(6))]
        /// A smooth ratio with a ripple at the spacing of a drawn spline's points: the
        /// shaped ratio keeps the mean 1 (the arm turns back) and stays positive, the tip
        /// moves within the budget, and the curves are no more concave than before.
        #[test]
        fn shaping_keeps_the_turn_and_the_budget(
            ripple in 0.02f64..0.08,
            wave in 10usize..18,
            phase in 0.0f64..TAU,
        ) {
            let n = 360;
            let ratio: Vec<f64> = (0..n)
                .map(|j| {
                    let t = TAU * j as f64 / n as f64;
                    1.0 + 0.45 * t.cos() + ripple * (wave as f64 * t + phase).sin()
                })
                .collect();
            let (a, rule) = ([125.0, 125.0], ModuleRule { cutter_teeth: None, ..ModuleRule::default() });
            let before = extremes(&ratio, 0.5, a);
            let budget = 0.8;
            let shaped = RatioShaping::within(&ratio, 0.5, a, (&rule, 2.5), 160.0, budget);
            // The ripple is what the shaping is for: it is not left as it was.
            prop_assert!(shaped.moved_mm > 0.0 && shaped.ratio != ratio);
            let mean = shaped.ratio.iter().sum::<f64>() / n as f64;
            prop_assert!((mean - 1.0).abs() < 1e-12, "mean {}", mean);
            prop_assert!(shaped.ratio.iter().all(|&i| i > 0.0));
            prop_assert!(shaped.moved_mm <= budget, "moved {}", shaped.moved_mm);
            let after = extremes(&shaped.ratio, 0.5, a);
            prop_assert!(after.0 >= before.0.min(0.0), "least {:?} → {:?}", before, after);
        }
    }
}
