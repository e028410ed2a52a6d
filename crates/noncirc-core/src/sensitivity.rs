//! Global sensitivity: first-order and total Sobol indices by Saltelli's sampling and
//! Jansen's estimators, with bootstrap confidence intervals. The points and the outputs are
//! laid out as SALib's `sobol.sample(..., calc_second_order=False)` lays them out, so its
//! users can run `SALib.analyze.sobol` on the same outputs (docs/robustness.md).

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

/// The output blocks `(A, B, AB_i)` of the base points in `rows` (indices into the base).
fn indices_on(y: &[f64], k: usize, rows: &[usize]) -> (Vec<f64>, Vec<f64>, f64) {
    let step = k + 2;
    let m = rows.len() as f64;
    let a = |j: usize| y[j * step];
    let b = |j: usize| y[j * step + k + 1];
    // The variance of A and B together, as SALib takes it (population variance).
    let mean = rows.iter().map(|&j| a(j) + b(j)).sum::<f64>() / (2.0 * m);
    let var = rows
        .iter()
        .map(|&j| (a(j) - mean).powi(2) + (b(j) - mean).powi(2))
        .sum::<f64>()
        / (2.0 * m);
    let mut first = vec![0.0; k];
    let mut total = vec![0.0; k];
    if var > 0.0 {
        // Jansen: V_i = V − ½E[(f(B) − f(A_B^i))²], V_Ti = ½E[(f(A) − f(A_B^i))²]. One pass
        // over the rows, each row's block read whole (its k + 2 outputs lie together); every
        // parameter's sums still add the rows in their order.
        let (mut d_first, mut d_total) = (vec![0.0; k], vec![0.0; k]);
        for &j in rows {
            let block = &y[j * step..(j + 1) * step];
            let (a, b) = (block[0], block[k + 1]);
            let abs = &block[1..=k];
            for ((df, dt), &ab) in d_first.iter_mut().zip(&mut d_total).zip(abs) {
                *df += (b - ab).powi(2);
                *dt += (a - ab).powi(2);
            }
        }
        for i in 0..k {
            first[i] = 1.0 - d_first[i] / (2.0 * m * var);
            total[i] = d_total[i] / (2.0 * m * var);
        }
    }
    (first, total, var)
}

/// The Sobol indices of one output `y`, laid out as [`saltelli_points`] lays out the
/// points, for `k` parameters; `bootstrap` resamples of the base points (seeded by `seed`)
/// give each index's 95 % half-width (1.96 standard deviations, as SALib reports it). An
/// output that does not vary has all indices 0.
pub fn sobol_indices(y: &[f64], k: usize, bootstrap: usize, seed: u64) -> Result<SobolIndices> {
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
    let (first, total, variance) = indices_on(y, k, &rows);
    let mut rng = Rng::new(seed);
    let (mut s1, mut st) = (vec![Vec::new(); k], vec![Vec::new(); k]);
    for _ in 0..bootstrap {
        let resample: Vec<usize> = (0..rows.len())
            .map(|_| rows[rng.below(rows.len())])
            .collect();
        let (f, t, _) = indices_on(y, k, &resample);
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
        // An inert parameter's total index is exactly 0 (its column changes nothing).
        assert_eq!(s.total[3], 0.0);
    }

    /// Ishigami's function, the standard test with interactions: closed-form indices
    /// (a = 7, b = 0.1 on [−π, π]³): S = (0.3139, 0.4424, 0), ST = (0.5576, 0.4424, 0.2437).
    #[test]
    fn ishigami_indices_converge_to_their_closed_form() {
        use std::f64::consts::PI;
        let points = saltelli_points(3, 4096, 11).unwrap();
        let y: Vec<f64> = (points.iter())
            .map(|p| {
                let x: Vec<f64> = p.iter().map(|u| -PI + 2.0 * PI * u).collect();
                x[0].sin() + 7.0 * x[1].sin().powi(2) + 0.1 * x[2].powi(4) * x[0].sin()
            })
            .collect();
        let s = sobol_indices(&y, 3, 100, 1).unwrap();
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
