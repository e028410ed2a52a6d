//! CMA-ES (Hansen's (μ/μ_w, λ) with rank-one and rank-μ updates) in the unit cube, ranking
//! by Deb's feasibility-first rule, with restarts from a random mean when it stalls.

use crate::check::{check_len, state_error};
use crate::fitness::{evaluate_all, BatchEvaluator, Candidate};
use crate::rng::Rng;
use crate::solver::{SolverState, MAX_POPULATION};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Cmaes {
    dim: usize,
    lambda: usize,
    mean: Vec<f64>,
    sigma: f64,
    /// Covariance, row-major `dim × dim`.
    cov: Vec<f64>,
    path_sigma: Vec<f64>,
    path_c: Vec<f64>,
    generation: u64,
    /// The best merit since the last (re)start; `None` before the first generation (an
    /// infinite start value made `∞ − 1e-12·∞ = NaN`, so stalls were never detected, and
    /// was written to checkpoints as JSON null).
    best_merit: Option<f64>,
    stall: u32,
    rng: Rng,
}

const START_SIGMA: f64 = 0.3;

impl Cmaes {
    pub fn new(dim: usize, lambda: usize, mut rng: Rng) -> Self {
        let mean = rng.point(dim);
        Self {
            dim,
            lambda: lambda.max(4),
            mean,
            sigma: START_SIGMA,
            cov: identity(dim),
            path_sigma: vec![0.0; dim],
            path_c: vec![0.0; dim],
            generation: 0,
            best_merit: None,
            stall: 0,
            rng,
        }
    }

    fn restart(&mut self) {
        self.mean = self.rng.point(self.dim);
        self.sigma = START_SIGMA;
        self.cov = identity(self.dim);
        self.path_sigma = vec![0.0; self.dim];
        self.path_c = vec![0.0; self.dim];
        self.best_merit = None;
        self.stall = 0;
    }
}

impl SolverState for Cmaes {
    /// Checks a resumed state: sizes, a finite positive step, a finite covariance.
    fn check(&self, dim: usize, _goals: usize) -> crate::Result<()> {
        check_len("cmaes: dimension", self.dim, dim)?;
        check_len("cmaes: mean", self.mean.len(), dim)?;
        check_len("cmaes: covariance", self.cov.len(), dim * dim)?;
        check_len("cmaes: step-size path", self.path_sigma.len(), dim)?;
        check_len("cmaes: covariance path", self.path_c.len(), dim)?;
        if !(4..=MAX_POPULATION).contains(&self.lambda) {
            return Err(state_error(format!(
                "cmaes: population {} (from 4 to {})",
                self.lambda, MAX_POPULATION
            )));
        }
        if !(self.sigma.is_finite() && self.sigma > 0.0) {
            return Err(state_error(format!("cmaes: step size {}", self.sigma)));
        }
        let all = [&self.mean, &self.cov, &self.path_sigma, &self.path_c];
        if let Some(x) = all.iter().flat_map(|v| v.iter()).find(|x| !x.is_finite()) {
            return Err(state_error(format!("cmaes: a state value is {x}")));
        }
        Ok(())
    }

    fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        let d = self.dim;
        let df = d as f64;
        let mu = self.lambda / 2;
        let raw: Vec<f64> = (0..mu)
            .map(|i| (mu as f64 + 0.5).ln() - ((i + 1) as f64).ln())
            .collect();
        let total: f64 = raw.iter().sum();
        let w: Vec<f64> = raw.iter().map(|x| x / total).collect();
        let mu_eff = 1.0 / w.iter().map(|x| x * x).sum::<f64>();
        let c_sigma = (mu_eff + 2.0) / (df + mu_eff + 5.0);
        let d_sigma = 1.0 + 2.0 * (((mu_eff - 1.0) / (df + 1.0)).sqrt() - 1.0).max(0.0) + c_sigma;
        let c_c = (4.0 + mu_eff / df) / (df + 4.0 + 2.0 * mu_eff / df);
        let c1 = 2.0 / ((df + 1.3).powi(2) + mu_eff);
        let c_mu =
            (1.0 - c1).min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((df + 2.0).powi(2) + mu_eff));
        let chi_n = df.sqrt() * (1.0 - 1.0 / (4.0 * df) + 1.0 / (21.0 * df * df));

        let cov = DMatrix::from_row_slice(d, d, &self.cov);
        let eig = cov.clone().symmetric_eigen();
        let scales: Vec<f64> = eig
            .eigenvalues
            .iter()
            .map(|v| v.max(1e-300).sqrt())
            .collect();
        let b = &eig.eigenvectors;
        // Sample y = B D z, x = m + σ y; evaluate the clamped point, penalise the clamp.
        let mut ys = Vec::with_capacity(self.lambda);
        let mut points = Vec::with_capacity(self.lambda);
        let mut penalties = Vec::with_capacity(self.lambda);
        for _ in 0..self.lambda {
            let z: Vec<f64> = (0..d).map(|_| self.rng.normal()).collect();
            let dz = DVector::from_iterator(d, z.iter().zip(&scales).map(|(z, s)| z * s));
            let y = b * dz;
            let x: Vec<f64> = (0..d).map(|i| self.mean[i] + self.sigma * y[i]).collect();
            let clamped: Vec<f64> = x.iter().map(|v| v.clamp(0.0, 1.0)).collect();
            penalties.push(
                x.iter()
                    .zip(&clamped)
                    .map(|(a, b)| (a - b).powi(2))
                    .sum::<f64>(),
            );
            ys.push(y);
            points.push(clamped);
        }
        let evaluated = evaluate_all(eval, points);
        let mut order: Vec<usize> = (0..self.lambda).collect();
        let merit = |i: usize| evaluated[i].fitness.merit() + penalties[i];
        order.sort_by(|&a, &b| merit(a).total_cmp(&merit(b)));
        // Recombination.
        let mut y_w = DVector::zeros(d);
        for (k, &i) in order.iter().take(mu).enumerate() {
            y_w += &ys[i] * w[k];
        }
        for (m, dy) in self.mean.iter_mut().zip(y_w.iter()) {
            *m += self.sigma * dy;
        }
        // C^{-1/2} y_w = B D^{-1} Bᵀ y_w.
        let bt_y = b.transpose() * &y_w;
        let inv = DVector::from_iterator(d, bt_y.iter().zip(&scales).map(|(v, s)| v / s));
        let c_inv_half_y = b * inv;
        for i in 0..d {
            self.path_sigma[i] = (1.0 - c_sigma) * self.path_sigma[i]
                + (c_sigma * (2.0 - c_sigma) * mu_eff).sqrt() * c_inv_half_y[i];
        }
        self.generation += 1;
        let ps_norm = self.path_sigma.iter().map(|v| v * v).sum::<f64>().sqrt();
        let h_sigma = ps_norm / (1.0 - (1.0 - c_sigma).powf(2.0 * self.generation as f64)).sqrt()
            < (1.4 + 2.0 / (df + 1.0)) * chi_n;
        let h = if h_sigma { 1.0 } else { 0.0 };
        for i in 0..d {
            self.path_c[i] =
                (1.0 - c_c) * self.path_c[i] + h * (c_c * (2.0 - c_c) * mu_eff).sqrt() * y_w[i];
        }
        let mut next = cov * (1.0 - c1 - c_mu + (1.0 - h) * c1 * c_c * (2.0 - c_c));
        let pc = DVector::from_column_slice(&self.path_c);
        next += &pc * pc.transpose() * c1;
        for (k, &i) in order.iter().take(mu).enumerate() {
            next += &ys[i] * ys[i].transpose() * (c_mu * w[k]);
        }
        // Keep it exactly symmetric.
        let sym = (&next + next.transpose()) * 0.5;
        self.cov = sym.transpose().as_slice().to_vec();
        self.sigma *= ((c_sigma / d_sigma) * (ps_norm / chi_n - 1.0)).exp();
        // Stall detection and restart.
        let best = merit(order[0]);
        let improved = self
            .best_merit
            .is_none_or(|b| best < b - 1e-12 * b.abs().max(1.0));
        if improved {
            self.best_merit = Some(best);
            self.stall = 0;
        } else {
            self.stall += 1;
        }
        let spread = self.sigma * scales.iter().cloned().fold(0.0, f64::max);
        if spread < 1e-9 || self.stall > 20 + 3 * d as u32 || !self.sigma.is_finite() {
            self.restart();
        }
        evaluated
    }
}

fn identity(d: usize) -> Vec<f64> {
    (0..d * d)
        .map(|k| if k / d == k % d { 1.0 } else { 0.0 })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fitness::Fitness;
    use crate::test_problem::{sphere, FnProblem};

    /// A search that keeps improving keeps its distribution: no restart in 60 generations.
    #[test]
    fn an_improving_search_does_not_restart() {
        let mut cmaes = Cmaes::new(4, 8, Rng::new(3));
        let mut problem = sphere(4, 0.3);
        let mut previous = f64::INFINITY;
        for generation in 1..=60 {
            cmaes.step(&mut problem);
            let best = cmaes.best_merit.expect("a best merit after a generation");
            assert!(
                best.is_finite() && best <= previous,
                "generation {generation}"
            );
            previous = best;
        }
    }

    /// Without progress, the search restarts after exactly 21 + 3·dim stalled generations
    /// (the first generation sets the best merit; 33 more stall in 4 dimensions).
    #[test]
    fn a_stalled_search_restarts_after_the_stall_limit() {
        let mut cmaes = Cmaes::new(4, 8, Rng::new(3));
        let mut problem = FnProblem {
            dim: 4,
            goals: 1,
            score: |_: &[f64]| Fitness {
                cv: 0.0,
                f: vec![1.0],
            },
        };
        for generation in 1..=34 {
            cmaes.step(&mut problem);
            assert_eq!(
                cmaes.best_merit.is_none(),
                generation == 34,
                "generation {generation}: stall count {}",
                cmaes.stall
            );
        }
    }
}
