//! Differential evolution, rand/1/bin with dithered F, feasibility-first selection.

use crate::check::{check_candidate, check_len, state_error};
use crate::fitness::{evaluate_all, BatchEvaluator, Candidate};
use crate::rng::Rng;
use crate::solver::{SolverState, MAX_POPULATION};
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
    /// Checks a resumed state: mutation needs four distinct members, so at least 5; at
    /// most what a scene may ask (a damaged size would allocate without end).
    fn check(&self, dim: usize, goals: usize) -> crate::Result<()> {
        check_len("de: dimension", self.dim, dim)?;
        if !(5..=MAX_POPULATION).contains(&self.size) {
            return Err(state_error(format!(
                "de: population size {} (from 5 to {MAX_POPULATION})",
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

    fn ranked_population(&self) -> Vec<Candidate> {
        let mut ranked = self.population.clone();
        // Stable: equal members keep their order, so the ranking is deterministic.
        ranked.sort_by(|a, b| a.fitness.merit().total_cmp(&b.fitness.merit()));
        ranked
    }

    fn immigrate(&mut self, migrants: &[Candidate]) -> crate::Result<()> {
        let mut order: Vec<usize> = (0..self.population.len()).collect();
        order.sort_by(|&a, &b| {
            let (fa, fb) = (&self.population[a].fitness, &self.population[b].fitness);
            fb.merit().total_cmp(&fa.merit()).then(b.cmp(&a))
        });
        for (&worst, m) in order.iter().zip(migrants) {
            self.population[worst] = m.clone();
        }
        Ok(())
    }

    fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        if self.population.is_empty() {
            let points = (0..self.size).map(|_| self.rng.point(self.dim)).collect();
            self.population = evaluate_all(eval, points);
            return self.population.clone();
        }
        let trials = (0..self.population.len())
            .map(|i| trial(&self.population, i, self.crossover, &mut self.rng))
            .collect();
        let evaluated = evaluate_all(eval, trials);
        for (i, t) in evaluated.iter().enumerate() {
            if !self.population[i].fitness.better_than(&t.fitness) {
                self.population[i] = t.clone();
            }
        }
        evaluated
    }
}

/// The rand/1/bin trial of member `i` of `population` (at least 4 members): a random
/// member plus a dithered difference of two others (F in [0.5, 1)), crossed with member
/// `i` at rate `crossover` (one coordinate always from the mutant), repaired into the unit
/// cube halfway towards the violated bound. NSGA's feasibility phase uses it too.
pub(super) fn trial(population: &[Candidate], i: usize, crossover: f64, rng: &mut Rng) -> Vec<f64> {
    let n = population.len();
    let pick = |rng: &mut Rng, not: &[usize]| loop {
        let r = rng.below(n);
        if !not.contains(&r) {
            break r;
        }
    };
    let r1 = pick(rng, &[i]);
    let r2 = pick(rng, &[i, r1]);
    let r3 = pick(rng, &[i, r1, r2]);
    let f = 0.5 + 0.5 * rng.uniform();
    let target = &population[i].u;
    let dim = target.len();
    let forced = rng.below(dim);
    let (a, b, c) = (&population[r1].u, &population[r2].u, &population[r3].u);
    (0..dim)
        .map(|j| {
            if j == forced || rng.uniform() < crossover {
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
        .collect()
}
