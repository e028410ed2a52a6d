//! Differential evolution, rand/1/bin with dithered F, feasibility-first selection.

use crate::check::{check_candidate, check_len, state_error};
use crate::fitness::{evaluate_all, BatchEvaluator, Candidate, Fitness};
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
        let trials: Vec<Vec<f64>> = (0..self.population.len())
            .map(|i| trial(&self.population, i, self.crossover, &mut self.rng))
            .collect();
        // Each trial against its target: a trial that loses may be scored part-way.
        let rivals: Vec<Fitness> = self.population.iter().map(|c| c.fitness.clone()).collect();
        let fitness = eval.evaluate_against(&trials, &rivals);
        let evaluated: Vec<Candidate> = (trials.into_iter().zip(fitness))
            .map(|(u, fitness)| Candidate { u, fitness })
            .collect();
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{execute, Algorithm, SearchState};

    /// The sphere about 0.3 as the goal, outside the ball of radius 0.4 about 0.7 as the
    /// violation: the search meets both feasible and infeasible trials.
    fn score(p: &[f64]) -> Fitness {
        let dist = |c: f64| p.iter().map(|x| (x - c).powi(2)).sum::<f64>().sqrt();
        Fitness {
            cv: (dist(0.7) - 0.4).max(0.0),
            f: vec![dist(0.3)],
        }
    }

    /// Scores the trials that lose to their target by a bound halfway between the
    /// target's violation and their own, as a problem that stops part-way may.
    struct Bounding {
        bounded: usize,
    }

    impl BatchEvaluator for Bounding {
        fn dim(&self) -> usize {
            4
        }
        fn goals(&self) -> usize {
            1
        }
        fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
            points.iter().map(|p| score(p)).collect()
        }
        fn evaluate_against(&mut self, points: &[Vec<f64>], rivals: &[Fitness]) -> Vec<Fitness> {
            (points.iter().zip(rivals))
                .map(|(p, rival)| {
                    let full = score(p);
                    if full.cv > rival.cv {
                        self.bounded += 1;
                        Fitness {
                            cv: rival.cv + 0.5 * (full.cv - rival.cv),
                            f: vec![1e5],
                        }
                    } else {
                        full
                    }
                })
                .collect()
        }
    }

    /// Plain fitness only (the trait's default `evaluate_against`).
    struct Plain;

    impl BatchEvaluator for Plain {
        fn dim(&self) -> usize {
            4
        }
        fn goals(&self) -> usize {
            1
        }
        fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
            points.iter().map(|p| score(p)).collect()
        }
    }

    /// Trials scored by a bound where they lose leave the search as it is: the same
    /// population, best designs, confirmations and history, generation by generation.
    #[test]
    fn trials_scored_by_a_bound_leave_the_search_unchanged() {
        let mut bounding = Bounding { bounded: 0 };
        let mut bounded = SearchState::new(Algorithm::De, 4, 1, 12, 3);
        let mut plain = SearchState::new(Algorithm::De, 4, 1, 12, 3);
        for budget in (120..=2400).step_by(120) {
            execute(&mut bounded, &mut bounding, budget, &mut []);
            execute(&mut plain, &mut Plain, budget, &mut []);
            assert_eq!(format!("{bounded:?}"), format!("{plain:?}"), "at {budget}");
        }
        assert!(
            bounding.bounded > 200,
            "{} trials bounded",
            bounding.bounded
        );
        let best = plain.best.unwrap().fitness;
        // The nearest point of the ball to 0.3 is 0.4 away (the centres are 0.8 apart).
        assert!(
            best.feasible() && (best.f[0] - 0.4).abs() < 1e-3,
            "{best:?}"
        );
    }
}
