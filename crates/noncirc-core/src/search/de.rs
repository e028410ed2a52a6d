//! Differential evolution, rand/1/bin with dithered F, feasibility-first selection.

use super::{
    check_candidate, check_len, evaluate_all, state_error, BatchEvaluator, Candidate, Rng,
    SolverState,
};
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct DifferentialEvolution {
    dim: usize,
    size: usize,
    crossover: f64,
    population: Vec<Candidate>,
    rng: Rng,
}

impl DifferentialEvolution {
    pub fn new(dim: usize, size: usize, rng: Rng) -> Self {
        Self {
            dim,
            size: size.max(5),
            crossover: 0.9,
            population: Vec::new(),
            rng,
        }
    }
}

impl SolverState for DifferentialEvolution {
    /// Checks a resumed state: mutation needs four distinct members, so at least 5.
    fn check(&self, dim: usize, goals: usize) -> crate::Result<()> {
        check_len("de: dimension", self.dim, dim)?;
        if self.size < 5 {
            return Err(state_error(format!(
                "de: population size {} (at least 5)",
                self.size
            )));
        }
        if !self.population.is_empty() {
            check_len("de: population", self.population.len(), self.size)?;
        }
        if !(0.0..=1.0).contains(&self.crossover) {
            return Err(state_error(format!(
                "de: crossover rate {} outside [0, 1]",
                self.crossover
            )));
        }
        for (i, c) in self.population.iter().enumerate() {
            check_candidate(&format!("de: member {i}"), c, dim, goals)?;
        }
        Ok(())
    }

    fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        if self.population.is_empty() {
            let points = (0..self.size).map(|_| self.rng.point(self.dim)).collect();
            self.population = evaluate_all(eval, points);
            return self.population.clone();
        }
        let n = self.population.len();
        let mut trials = Vec::with_capacity(n);
        for i in 0..n {
            let pick = |rng: &mut Rng, not: &[usize]| loop {
                let r = rng.below(n);
                if !not.contains(&r) {
                    break r;
                }
            };
            let r1 = pick(&mut self.rng, &[i]);
            let r2 = pick(&mut self.rng, &[i, r1]);
            let r3 = pick(&mut self.rng, &[i, r1, r2]);
            let f = 0.5 + 0.5 * self.rng.uniform();
            let forced = self.rng.below(self.dim);
            let target = &self.population[i].u;
            let (a, b, c) = (
                &self.population[r1].u,
                &self.population[r2].u,
                &self.population[r3].u,
            );
            let trial: Vec<f64> = (0..self.dim)
                .map(|j| {
                    if j == forced || self.rng.uniform() < self.crossover {
                        let v = a[j] + f * (b[j] - c[j]);
                        // Midpoint repair towards the violated bound.
                        if v < 0.0 {
                            0.5 * target[j]
                        } else if v > 1.0 {
                            0.5 * (target[j] + 1.0)
                        } else {
                            v
                        }
                    } else {
                        target[j]
                    }
                })
                .collect();
            trials.push(trial);
        }
        let evaluated = evaluate_all(eval, trials);
        for (i, t) in evaluated.iter().enumerate() {
            if !self.population[i].fitness.better_than(&t.fitness) {
                self.population[i] = t.clone();
            }
        }
        evaluated
    }
}
