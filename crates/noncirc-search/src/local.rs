//! Local least squares: Levenberg–Marquardt (MINPACK's trust region, from the
//! `levenberg-marquardt` crate) on a problem's residual vector over the unit cube, with a
//! Jacobian by central differences whose points go to the problem as one batch (so a
//! parallel problem uses every thread, and the result does not depend on their count).
//! Points are kept in the cube by projection.

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Owned};
use serde::{Deserialize, Serialize};
use std::cell::RefCell;

/// A problem whose points of the unit cube `[0, 1]^d` give residual vectors.
pub trait ResidualBatch {
    /// Dimension `d`.
    fn dim(&self) -> usize;
    /// The residual vectors at `points`, in order: all of one length, finite (a point the
    /// problem refuses gives large finite residuals).
    fn residuals(&mut self, points: &[Vec<f64>]) -> Vec<Vec<f64>>;
}

/// Settings of a local refinement.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LocalSettings {
    /// Most residual vectors evaluated (each Jacobian costs `2d`).
    pub max_evaluations: u64,
    /// Central-difference step in the unit cube.
    pub step: f64,
    /// Relative tolerance of the cost's decrease and of the step (`ftol`, `xtol`).
    pub tolerance: f64,
}

impl Default for LocalSettings {
    fn default() -> Self {
        Self {
            max_evaluations: 10_000,
            step: 1e-4,
            tolerance: 1e-8,
        }
    }
}

/// What a local refinement did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LocalReport {
    /// Where it ended, in the unit cube.
    pub u: Vec<f64>,
    /// Half the squared norm of the residuals at the start and at the end.
    pub start_cost: f64,
    pub cost: f64,
    /// Residual vectors evaluated.
    pub evaluations: u64,
    /// Why it stopped (MINPACK's reasons: converged, orthogonal, lost patience…).
    pub termination: String,
}

/// The problem as the LM crate sees it: the point, its residuals, and the evaluator
/// behind a `RefCell` (the crate asks the Jacobian through `&self`).
struct Adapter<'p> {
    problem: RefCell<&'p mut dyn ResidualBatch>,
    u: DVector<f64>,
    residuals: Vec<f64>,
    step: f64,
    evaluations: RefCell<u64>,
}

/// `u` projected into the unit cube.
fn clamped(u: &DVector<f64>) -> Vec<f64> {
    u.iter().map(|x| x.clamp(0.0, 1.0)).collect()
}

impl Adapter<'_> {
    fn evaluate(&self, points: &[Vec<f64>]) -> Vec<Vec<f64>> {
        *self.evaluations.borrow_mut() += points.len() as u64;
        self.problem.borrow_mut().residuals(points)
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Adapter<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, u: &DVector<f64>) {
        self.u = u.clone();
        let point = clamped(u);
        self.residuals = self.evaluate(&[point]).pop().unwrap_or_default();
    }

    fn params(&self) -> DVector<f64> {
        self.u.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        Some(DVector::from_column_slice(&self.residuals))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let centre = clamped(&self.u);
        let (d, h) = (centre.len(), self.step);
        // Per coordinate, the two points of its difference (one-sided at a face).
        let mut points = Vec::with_capacity(2 * d);
        let mut spans = Vec::with_capacity(d);
        for i in 0..d {
            let (lo, hi) = ((centre[i] - h).max(0.0), (centre[i] + h).min(1.0));
            for x in [lo, hi] {
                let mut p = centre.clone();
                p[i] = x;
                points.push(p);
            }
            spans.push(hi - lo);
        }
        let rows = self.evaluate(&points);
        let m = self.residuals.len();
        let mut jacobian = DMatrix::zeros(m, d);
        for i in 0..d {
            let (below, above) = (&rows[2 * i], &rows[2 * i + 1]);
            if below.len() != m || above.len() != m {
                return None;
            }
            for k in 0..m {
                jacobian[(k, i)] = (above[k] - below[k]) / spans[i];
            }
        }
        Some(jacobian)
    }
}

/// Half the squared norm.
fn cost(r: &[f64]) -> f64 {
    0.5 * r.iter().map(|x| x * x).sum::<f64>()
}

/// Refines `start` (a point of the unit cube) by Levenberg–Marquardt on `problem`'s
/// residuals. Deterministic: the same start gives the same end.
pub fn refine(
    problem: &mut dyn ResidualBatch,
    start: &[f64],
    settings: &LocalSettings,
) -> LocalReport {
    let mut adapter = Adapter {
        problem: RefCell::new(problem),
        u: DVector::from_column_slice(start),
        residuals: Vec::new(),
        step: settings.step,
        evaluations: RefCell::new(0),
    };
    let u0 = adapter.u.clone();
    adapter.set_params(&u0);
    let start_cost = cost(&adapter.residuals);
    // The crate's patience bounds its residual evaluations at `patience·(d + 1)`
    // (MINPACK's `maxfev`), each with a Jacobian at most, which costs 2d of ours.
    let d = start.len().max(1) as u64;
    let patience = (settings.max_evaluations / ((2 * d + 1) * (d + 1))).max(1) as usize;
    let (adapter, report) = LevenbergMarquardt::new()
        .with_ftol(settings.tolerance)
        .with_xtol(settings.tolerance)
        .with_patience(patience)
        .minimize(adapter);
    let evaluations = *adapter.evaluations.borrow();
    LocalReport {
        u: clamped(&adapter.u),
        start_cost,
        cost: cost(&adapter.residuals),
        evaluations,
        termination: format!("{:?}", report.termination),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Residuals of a function of points of the cube, counting its calls.
    struct Residuals<F: Fn(&[f64]) -> Vec<f64>>(F, usize);

    impl<F: Fn(&[f64]) -> Vec<f64>> ResidualBatch for Residuals<F> {
        fn dim(&self) -> usize {
            self.1
        }
        fn residuals(&mut self, points: &[Vec<f64>]) -> Vec<Vec<f64>> {
            points.iter().map(|p| (self.0)(p)).collect()
        }
    }

    #[test]
    fn rosenbrocks_valley_is_followed_to_its_minimum() {
        // (10(y − x²), 1 − x) on x, y = 4u − 2: the minimum (1, 1) at u = (0.75, 0.75).
        let mut p = Residuals(
            |u: &[f64]| {
                let (x, y) = (4.0 * u[0] - 2.0, 4.0 * u[1] - 2.0);
                vec![10.0 * (y - x * x), 1.0 - x]
            },
            2,
        );
        let report = refine(&mut p, &[0.2, 0.9], &LocalSettings::default());
        assert!(
            (report.u[0] - 0.75).abs() < 1e-6 && (report.u[1] - 0.75).abs() < 1e-6,
            "{report:?}"
        );
        assert!(report.cost < 1e-12 && report.start_cost > 1.0);
    }

    #[test]
    fn an_exponential_fit_recovers_its_parameters() {
        // y = a e^{−b t} sampled at 20 times, a = 2 + 3u0 = 3.5, b = 2u1 = 0.6.
        let data: Vec<(f64, f64)> = (0..20)
            .map(|k| {
                let t = k as f64 * 0.25;
                (t, 3.5 * (-0.6 * t).exp())
            })
            .collect();
        let mut p = Residuals(
            move |u: &[f64]| {
                let (a, b) = (2.0 + 3.0 * u[0], 2.0 * u[1]);
                data.iter().map(|(t, y)| a * (-b * t).exp() - y).collect()
            },
            2,
        );
        let report = refine(&mut p, &[0.1, 0.1], &LocalSettings::default());
        assert!(
            (report.u[0] - 0.5).abs() < 1e-6 && (report.u[1] - 0.3).abs() < 1e-6,
            "{report:?}"
        );
    }

    #[test]
    fn an_optimum_outside_the_cube_stops_on_its_face() {
        // (x − 1.5, y − 0.3): x held at the face x = 1.
        let mut p = Residuals(|u: &[f64]| vec![u[0] - 1.5, u[1] - 0.3], 2);
        let report = refine(&mut p, &[0.5, 0.5], &LocalSettings::default());
        assert!(
            (report.u[0] - 1.0).abs() < 1e-9 && (report.u[1] - 0.3).abs() < 1e-6,
            "{report:?}"
        );
        assert!((report.cost - 0.125).abs() < 1e-6);
    }
}
