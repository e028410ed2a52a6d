//! Global sensitivity: first-order and total Sobol indices by Saltelli's sampling, the
//! first-order estimator of Saltelli et al. (2010) and Jansen's total estimator (the pair
//! SALib uses, and the pair that paper recommends), with bootstrap confidence intervals and
//! a check of whether the indices can be read at the samples taken. The points and the
//! outputs are laid out as SALib's `sobol.sample(..., calc_second_order=False)` lays them
//! out, so its users can run `SALib.analyze.sobol` on the same outputs and get the same
//! indices (docs/robustness.md).

use crate::error::{Error, Result};
use crate::robustness::sobol;
use noncirc_search::Rng;
use serde::Serialize;

/// Most parameters: the Sobol table has 256 dimensions, two per parameter.
pub(crate) const MAX_PARAMETERS: usize = 128;

/// Saltelli's points in the unit cube for `k` parameters and `n` base points: for each
/// base point `j`, the rows `A_j`, `A_j` with column `i` from `B_j` for each `i`, then
/// `B_j` (`n·(k + 2)` rows). `A` and `B` are two halves of one scrambled Sobol sequence
/// keyed on `seed`.
pub fn saltelli_points(k: usize, n: usize, seed: u64) -> Result<Vec<Vec<f64>>> {
    if !(1..=MAX_PARAMETERS).contains(&k) {
        return Err(Error::OutOfRange {
            name: "free parameters (count, for the Sobol indices)".into(),
            value: k as f64,
            expected: format!("1 to {MAX_PARAMETERS}"),
        });
    }
    if !(2..=1 << 16).contains(&n) {
        return Err(Error::OutOfRange {
            name: "base samples".into(),
            value: n as f64,
            expected: "2 to 65536".into(),
        });
    }
    let mut rows = Vec::with_capacity(n * (k + 2));
    for j in 0..n {
        let a: Vec<f64> = (0..k).map(|d| sobol(j, d, seed)).collect();
        let b: Vec<f64> = (0..k).map(|d| sobol(j, k + d, seed)).collect();
        rows.push(a.clone());
        for i in 0..k {
            let mut ab = a.clone();
            ab[i] = b[i];
            rows.push(ab);
        }
        rows.push(b);
    }
    Ok(rows)
}

/// One output's Sobol indices, per parameter, each with the half-width of its 95 %
/// bootstrap confidence interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SobolIndices {
    /// First-order indices `S_i`: the share of the variance `x_i` explains alone.
    pub first: Vec<f64>,
    pub first_conf: Vec<f64>,
    /// Total indices `S_Ti`: the share with all its interactions.
    pub total: Vec<f64>,
    pub total_conf: Vec<f64>,
    /// The output's variance over the box (its unit squared).
    pub variance: f64,
    /// Base points whose `k + 2` outputs all exist (the model may refuse some designs;
    /// their base points are left out).
    pub rows_used: usize,
}

/// Per base point, what the estimators sum, computed once for the estimate and every
/// bootstrap resample: `f(A)`, `f(B)`, and for each parameter `i` (in one row of `2k`)
/// `(f(B) − centre)(f(A_B^i) − f(A))` then `(f(A) − f(A_B^i))²`.
///
/// Saltelli (2010): V_i = E[f(B)(f(A_B^i) − f(A))]; Jansen: V_Ti = ½E[(f(A) − f(A_B^i))²].
/// Jansen's first order, V − ½E[(f(B) − f(A_B^i))²], subtracts two estimates of nearly
/// the same size: for an inert parameter it scatters about 0 by the sampling error of V
/// (its ΣS1 drifted above 1), where Saltelli's is exactly 0 (f(A_B^i) = f(A)). Its spread
/// grows with the output's mean, so f(B) is taken about the mean of all outputs, as SALib
/// standardises them (the expectation is the same: E[f(A_B^i) − f(A)] = 0).
struct Terms {
    k: usize,
    a: Vec<f64>,
    b: Vec<f64>,
    /// `2k` per base point, then zeros to a whole number of [`LANES`].
    sums: Vec<f64>,
}

/// Terms summed side by side in registers.
const LANES: usize = 16;

/// The terms per base point for `k` parameters, padded to whole lanes.
fn padded_width(k: usize) -> usize {
    (2 * k).div_ceil(LANES) * LANES
}

impl Terms {
    /// The terms per base point, padded.
    fn width(&self) -> usize {
        padded_width(self.k)
    }

    /// The terms of `y` (laid out as [`saltelli_points`] lays out the points), `centre`
    /// the mean of every output of the base points used.
    fn new(y: &[f64], k: usize, centre: f64) -> Self {
        let step = k + 2;
        let n = y.len() / step;
        let (mut a, mut b) = (Vec::with_capacity(n), Vec::with_capacity(n));
        let width = padded_width(k);
        let mut sums = Vec::with_capacity(width * n);
        for block in y.chunks_exact(step) {
            let (fa, fb) = (block[0], block[k + 1]);
            let abs = &block[1..=k];
            sums.extend(abs.iter().map(|&ab| (fb - centre) * (ab - fa)));
            sums.extend(abs.iter().map(|&ab| (fa - ab).powi(2)));
            sums.resize(sums.len() + width - 2 * k, 0.0);
            a.push(fa);
            b.push(fb);
        }
        Self { k, a, b, sums }
    }

    /// The first-order and total indices and the variance over the base points `rows`
    /// (indices into the base; a bootstrap resample repeats some). Every sum adds the rows
    /// in their order.
    fn indices_on(&self, rows: &[usize]) -> (Vec<f64>, Vec<f64>, f64) {
        let k = self.k;
        let m = rows.len() as f64;
        let (a, b) = (&self.a, &self.b);
        // The variance of A and B together, as SALib takes it (population variance).
        let mean = rows.iter().map(|&j| a[j] + b[j]).sum::<f64>() / (2.0 * m);
        let var = rows
            .iter()
            .map(|&j| (a[j] - mean).powi(2) + (b[j] - mean).powi(2))
            .sum::<f64>()
            / (2.0 * m);
        let mut first = vec![0.0; k];
        let mut total = vec![0.0; k];
        if var > 0.0 {
            // One row of 2k terms per base point (padded to whole lanes): the sums of
            // `LANES` terms at a time kept in registers over all rows.
            let width = self.width();
            let mut sums = vec![0.0; width];
            for (c, lane) in sums.chunks_exact_mut(LANES).enumerate() {
                let mut acc = [0.0; LANES];
                for &j in rows {
                    let t = &self.sums[width * j + LANES * c..][..LANES];
                    for (s, t) in acc.iter_mut().zip(t) {
                        *s += t;
                    }
                }
                lane.copy_from_slice(&acc);
            }
            for i in 0..k {
                first[i] = sums[i] / (m * var);
                total[i] = sums[k + i] / (2.0 * m * var);
            }
        }
        (first, total, var)
    }
}

/// The bootstrap's draws: `bootstrap` resamples of `m` positions (into the base points an
/// output uses), drawn from `seed`. Every output of a study with all `m` base points used
/// draws the same, so they can share one draw ([`sobol_indices_sharing`]).
#[derive(Debug, Clone)]
pub struct Resamples {
    m: usize,
    bootstrap: usize,
    seed: u64,
    /// `bootstrap` rows of `m`.
    positions: Vec<u32>,
}

/// Most positions a shared draw keeps (16 MB): the default study draws 102 400; a larger
/// one (up to 65 536 base points and 10 000 resamples) draws for each output as it goes.
pub const MAX_SHARED_POSITIONS: usize = 1 << 22;

impl Resamples {
    /// The draw [`sobol_indices`] makes for `m` base points used, `bootstrap` resamples and
    /// `seed`; `None` beyond [`MAX_SHARED_POSITIONS`].
    pub fn new(m: usize, bootstrap: usize, seed: u64) -> Option<Self> {
        if m.saturating_mul(bootstrap) > MAX_SHARED_POSITIONS {
            return None;
        }
        let mut rng = Rng::new(seed);
        Some(Self {
            m,
            bootstrap,
            seed,
            positions: (0..bootstrap * m).map(|_| rng.below(m) as u32).collect(),
        })
    }

    fn fits(&self, m: usize, bootstrap: usize, seed: u64) -> bool {
        (self.m, self.bootstrap, self.seed) == (m, bootstrap, seed)
    }
}

/// The Sobol indices of one output `y`, laid out as [`saltelli_points`] lays out the
/// points, for `k` parameters; `bootstrap` resamples of the base points (seeded by `seed`)
/// give each index's 95 % half-width (1.96 standard deviations, as SALib reports it). An
/// output that does not vary has all indices 0.
pub fn sobol_indices(y: &[f64], k: usize, bootstrap: usize, seed: u64) -> Result<SobolIndices> {
    sobol_indices_sharing(y, k, bootstrap, seed, None)
}

/// As [`sobol_indices`], taking the bootstrap's draws from `shared` when they are the
/// ones it would draw (the same count of base points used, resamples and seed): the same
/// indices, without drawing them again for each output.
pub fn sobol_indices_sharing(
    y: &[f64],
    k: usize,
    bootstrap: usize,
    seed: u64,
    shared: Option<&Resamples>,
) -> Result<SobolIndices> {
    let step = k + 2;
    if k == 0 || !y.len().is_multiple_of(step) {
        return Err(Error::OutOfRange {
            name: "outputs (count)".into(),
            value: y.len() as f64,
            expected: format!("a multiple of k + 2 = {step}"),
        });
    }
    let n = y.len() / step;
    let rows: Vec<usize> = (0..n)
        .filter(|&j| y[j * step..(j + 1) * step].iter().all(|v| v.is_finite()))
        .collect();
    if rows.len() < 2 {
        return Err(Error::OutOfRange {
            name: "base points with every output".into(),
            value: rows.len() as f64,
            expected: "at least 2 (the model refused the others)".into(),
        });
    }
    let centre = rows
        .iter()
        .flat_map(|&j| &y[j * step..(j + 1) * step])
        .sum::<f64>()
        / (rows.len() * step) as f64;
    let terms = Terms::new(y, k, centre);
    let (first, total, variance) = terms.indices_on(&rows);
    // The shared draw where it is this output's, else this output's own as it goes.
    let shared = shared.filter(|d| d.fits(rows.len(), bootstrap, seed));
    let mut rng = Rng::new(seed);
    let (mut s1, mut st) = (vec![Vec::new(); k], vec![Vec::new(); k]);
    let mut resample = vec![0; rows.len()];
    for r in 0..bootstrap {
        match shared {
            Some(draws) => {
                let positions = &draws.positions[r * rows.len()..(r + 1) * rows.len()];
                for (row, &p) in resample.iter_mut().zip(positions) {
                    *row = rows[p as usize];
                }
            }
            None => resample.fill_with(|| rows[rng.below(rows.len())]),
        }
        let (f, t, _) = terms.indices_on(&resample);
        for i in 0..k {
            s1[i].push(f[i]);
            st[i].push(t[i]);
        }
    }
    let conf = |v: &Vec<f64>| {
        if v.len() < 2 {
            return 0.0;
        }
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64;
        1.959_963_984_540_054 * var.sqrt()
    };
    Ok(SobolIndices {
        first,
        first_conf: s1.iter().map(conf).collect(),
        total,
        total_conf: st.iter().map(conf).collect(),
        variance,
        rows_used: rows.len(),
    })
}

/// The 95 % half-width an index should be read to: `±0.1`, one decimal.
pub const READABLE_HALF_WIDTH: f64 = 0.1;

/// Fewest base points whose bootstrap intervals are taken at their word.
pub const FEWEST_ROWS: usize = 100;

/// How far past its interval an index must be to be flagged: closer than this it reads
/// as its bound at two decimals.
const MATERIAL: f64 = 0.01;

/// Why one output's indices cannot be read at the samples taken: each names something the
/// true indices cannot do (`0 ≤ S_i ≤ S_Ti`, `ΣS_i ≤ 1`) beyond the intervals, or intervals
/// too wide or too few points to trust. Parameters are indices into the box's parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Unreliable {
    /// Fewer than [`FEWEST_ROWS`] base points had every output.
    FewRows { used: usize },
    /// The most negative first-order index, below zero beyond its interval.
    NegativeFirst {
        parameter: usize,
        first: f64,
        conf: f64,
    },
    /// The first-order index furthest above its total, beyond the two intervals.
    FirstAboveTotal {
        parameter: usize,
        first: f64,
        total: f64,
    },
    /// The first-order indices sum above 1 beyond their intervals' sum.
    FirstSumAboveOne { sum: f64 },
    /// The widest interval, wider than ±[`READABLE_HALF_WIDTH`].
    WideInterval { parameter: usize, half_width: f64 },
}

impl Unreliable {
    /// One line for a reader, with the parameters' `labels`.
    pub fn describe(&self, labels: &[String]) -> String {
        let name = |i: &usize| labels.get(*i).map_or("?", String::as_str);
        match self {
            Self::FewRows { used } => format!(
                "{used} base points used, fewer than {FEWEST_ROWS}: the intervals themselves \
                 are rough"
            ),
            Self::NegativeFirst {
                parameter,
                first,
                conf,
            } => format!(
                "S1 of {} = {first:.3} ± {conf:.3}, below 0 beyond its interval",
                name(parameter)
            ),
            Self::FirstAboveTotal {
                parameter,
                first,
                total,
            } => format!(
                "S1 of {} = {first:.3} above its S_T = {total:.3} beyond their intervals",
                name(parameter)
            ),
            Self::FirstSumAboveOne { sum } => {
                format!("the first-order indices sum to {sum:.2}, above 1 beyond their intervals")
            }
            Self::WideInterval {
                parameter,
                half_width,
            } => format!(
                "widest interval ±{half_width:.3} ({}), above ±{READABLE_HALF_WIDTH}",
                name(parameter)
            ),
        }
    }
}

impl SobolIndices {
    /// What makes these indices unreadable (empty when none): at most one entry of each
    /// kind, the worst.
    pub fn unreliable(&self) -> Vec<Unreliable> {
        let mut out = Vec::new();
        if self.rows_used < FEWEST_ROWS {
            out.push(Unreliable::FewRows {
                used: self.rows_used,
            });
        }
        let k = self.first.len();
        let worst = |score: &dyn Fn(usize) -> f64| {
            (0..k)
                .filter(|&i| score(i) > 0.0)
                .max_by(|&a, &b| score(a).total_cmp(&score(b)))
        };
        if let Some(i) = worst(&|i| -(self.first[i] + self.first_conf[i]) - MATERIAL) {
            out.push(Unreliable::NegativeFirst {
                parameter: i,
                first: self.first[i],
                conf: self.first_conf[i],
            });
        }
        if let Some(i) = worst(&|i| {
            self.first[i] - self.total[i] - self.first_conf[i] - self.total_conf[i] - MATERIAL
        }) {
            out.push(Unreliable::FirstAboveTotal {
                parameter: i,
                first: self.first[i],
                total: self.total[i],
            });
        }
        let sum: f64 = self.first.iter().sum();
        if sum - self.first_conf.iter().sum::<f64>() > 1.0 + MATERIAL {
            out.push(Unreliable::FirstSumAboveOne { sum });
        }
        if let Some(i) =
            worst(&|i| self.first_conf[i].max(self.total_conf[i]) - READABLE_HALF_WIDTH)
        {
            out.push(Unreliable::WideInterval {
                parameter: i,
                half_width: self.first_conf[i].max(self.total_conf[i]),
            });
        }
        out
    }

    /// Base points that would read every index to ±[`READABLE_HALF_WIDTH`], from these
    /// indices taken at `base_samples`: the intervals narrow as one over the root of the
    /// points. With fewer than [`FEWEST_ROWS`] base points used the intervals are not
    /// trusted, and the count is the one that would use that many (a first step: the
    /// intervals at it tell the rest). A power of two (Sobol sequences balance at powers
    /// of two), at least `base_samples`.
    pub fn base_samples_needed(&self, base_samples: usize) -> usize {
        let n = base_samples as f64;
        let needed = if self.rows_used < FEWEST_ROWS {
            n * FEWEST_ROWS as f64 / self.rows_used.max(1) as f64
        } else {
            let widest =
                (self.first_conf.iter().chain(&self.total_conf)).fold(0.0_f64, |w, &c| w.max(c));
            n * (widest / READABLE_HALF_WIDTH).powi(2)
        };
        (needed.ceil().min(1e12) as usize)
            .max(base_samples)
            .next_power_of_two()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Y = Σ a_i x_i` on the unit cube: `S_i = S_Ti = a_i² / Σ a_j²`.
    #[test]
    fn a_linear_function_has_its_closed_form_indices_within_the_interval() {
        let a = [4.0, 2.0, 1.0, 0.0, 0.5];
        let k = a.len();
        let exact: Vec<f64> = {
            let sum: f64 = a.iter().map(|x| x * x).sum();
            a.iter().map(|x| x * x / sum).collect()
        };
        let points = saltelli_points(k, 1024, 7).unwrap();
        let y: Vec<f64> = (points.iter())
            .map(|p| p.iter().zip(&a).map(|(x, c)| x * c).sum())
            .collect();
        let s = sobol_indices(&y, k, 200, 3).unwrap();
        for (i, &exact) in exact.iter().enumerate() {
            assert!(
                (s.first[i] - exact).abs() <= s.first_conf[i].max(1e-12),
                "S{i} {} vs {} ± {}",
                s.first[i],
                exact,
                s.first_conf[i]
            );
            assert!(
                (s.total[i] - exact).abs() <= s.total_conf[i].max(1e-12),
                "ST{i} {} vs {} ± {}",
                s.total[i],
                exact,
                s.total_conf[i]
            );
            // The intervals are informative, not vacuous.
            assert!(s.first_conf[i] < 0.1 && s.total_conf[i] < 0.1, "{s:?}");
        }
        // An inert parameter's indices are exactly 0 (its column changes nothing).
        assert_eq!((s.first[3], s.total[3]), (0.0, 0.0));
        // Nothing impossible, every interval within ±0.1 (the widest, S1 of a1, ±0.06).
        assert_eq!(s.unreliable(), vec![]);
        assert_eq!(s.base_samples_needed(1024), 1024);
    }

    fn ishigami(n: usize, seed: u64) -> SobolIndices {
        use std::f64::consts::PI;
        let points = saltelli_points(3, n, seed).unwrap();
        let y: Vec<f64> = (points.iter())
            .map(|p| {
                let x: Vec<f64> = p.iter().map(|u| -PI + 2.0 * PI * u).collect();
                x[0].sin() + 7.0 * x[1].sin().powi(2) + 0.1 * x[2].powi(4) * x[0].sin()
            })
            .collect();
        sobol_indices(&y, 3, 100, 1).unwrap()
    }

    /// At 16 base points Ishigami's indices are noise, and the check says so: too few
    /// rows, intervals far wider than ±0.1. The count it gives first is the one with
    /// enough rows (128); the intervals there give the count that narrows them, and at it
    /// every interval is within ±0.1 and nothing is flagged.
    #[test]
    fn few_samples_are_flagged_with_the_samples_that_would_do() {
        let s = ishigami(16, 11);
        let flags = s.unreliable();
        assert!(
            flags.contains(&Unreliable::FewRows { used: 16 }),
            "{flags:?}"
        );
        let widest = flags.iter().find_map(|f| match f {
            Unreliable::WideInterval { half_width, .. } => Some(*half_width),
            _ => None,
        });
        assert!(widest.unwrap() > 0.2, "{flags:?}");
        assert_eq!(s.base_samples_needed(16), 128);
        let step = ishigami(128, 11);
        assert!(!step.unreliable().is_empty());
        let needed = step.base_samples_needed(128);
        assert!(needed.is_power_of_two() && needed >= 256, "{needed}");
        let enough = ishigami(needed, 11);
        assert_eq!(enough.unreliable(), vec![], "at {needed}");
        let labels: Vec<String> = ["x1", "x2", "x3"].map(String::from).into();
        assert!(flags[0]
            .describe(&labels)
            .starts_with("16 base points used"));
    }

    /// Each kind is raised by indices that break its rule, naming the worst parameter.
    #[test]
    fn impossible_indices_are_named() {
        let s = SobolIndices {
            first: vec![-0.3, 0.9, 0.8],
            first_conf: vec![0.2, 0.02, 0.02],
            total: vec![0.1, 0.5, 0.85],
            total_conf: vec![0.02, 0.02, 0.02],
            variance: 1.0,
            rows_used: 500,
        };
        let flags = s.unreliable();
        assert_eq!(
            flags,
            vec![
                Unreliable::NegativeFirst {
                    parameter: 0,
                    first: -0.3,
                    conf: 0.2
                },
                Unreliable::FirstAboveTotal {
                    parameter: 1,
                    first: 0.9,
                    total: 0.5
                },
                Unreliable::FirstSumAboveOne {
                    sum: 1.4000000000000001
                },
                Unreliable::WideInterval {
                    parameter: 0,
                    half_width: 0.2
                },
            ]
        );
        let labels: Vec<String> = ["γ0", "β0", "S"].map(String::from).into();
        assert_eq!(
            flags[1].describe(&labels),
            "S1 of β0 = 0.900 above its S_T = 0.500 beyond their intervals"
        );
        // ±0.2 is twice ±0.1: four times the points.
        assert_eq!(s.base_samples_needed(500), 2048);
    }

    /// Ishigami's function, the standard test with interactions: closed-form indices
    /// (a = 7, b = 0.1 on [−π, π]³): S = (0.3139, 0.4424, 0), ST = (0.5576, 0.4424, 0.2437).
    #[test]
    fn ishigami_indices_converge_to_their_closed_form() {
        let s = ishigami(4096, 11);
        let (first, total) = ([0.3139, 0.4424, 0.0], [0.5576, 0.4424, 0.2437]);
        for i in 0..3 {
            assert!(
                (s.first[i] - first[i]).abs() < 0.02,
                "S{i} = {}",
                s.first[i]
            );
            assert!(
                (s.total[i] - total[i]).abs() < 0.02,
                "ST{i} = {}",
                s.total[i]
            );
        }
    }

    /// A shared draw gives each output what its own draw gives, and one that does not fit
    /// (another count of base points used, resamples or seed) is not taken.
    #[test]
    fn shared_resamples_give_each_output_its_own_indices() {
        let points = saltelli_points(2, 64, 1).unwrap();
        let whole: Vec<f64> = points.iter().map(|p| p[0] + 2.0 * p[1] * p[0]).collect();
        let mut refused = whole.clone();
        refused[9] = f64::NAN;
        let shared = Resamples::new(64, 50, 3).unwrap();
        for y in [&whole, &refused] {
            let own = sobol_indices(y, 2, 50, 3).unwrap();
            assert_eq!(
                sobol_indices_sharing(y, 2, 50, 3, Some(&shared)).unwrap(),
                own
            );
            let other_seed = sobol_indices_sharing(y, 2, 50, 4, Some(&shared)).unwrap();
            assert_eq!(other_seed, sobol_indices(y, 2, 50, 4).unwrap());
            assert_ne!(other_seed.first_conf, own.first_conf);
        }
        // A draw too large to keep is not made: each output draws its own as it goes.
        assert!(Resamples::new(65_536, 10_000, 3).is_none());
        assert!(Resamples::new(1 << 11, 1 << 11, 3).is_some());
        assert_ne!(
            sobol_indices(&refused, 2, 50, 3).unwrap().first_conf,
            sobol_indices(&whole, 2, 50, 3).unwrap().first_conf
        );
    }

    #[test]
    fn refused_designs_drop_their_base_point_and_bad_shapes_are_named() {
        let points = saltelli_points(2, 16, 1).unwrap();
        let mut y: Vec<f64> = points.iter().map(|p| p[0] + 2.0 * p[1]).collect();
        y[5] = f64::NAN;
        let s = sobol_indices(&y, 2, 10, 1).unwrap();
        assert_eq!(s.rows_used, 15);
        assert!(sobol_indices(&y[..7], 2, 10, 1).is_err());
        assert!(saltelli_points(0, 16, 1).is_err());
        assert!(saltelli_points(129, 16, 1).is_err());
    }
}
