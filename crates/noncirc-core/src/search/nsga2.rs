//! NSGA-II (Deb et al. 2002) with constraint domination: binary tournaments on rank and
//! crowding, SBX crossover, polynomial mutation, elitist survival.

use super::{evaluate_all, BatchEvaluator, Candidate, Rng};
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Nsga2 {
    dim: usize,
    size: usize,
    population: Vec<Candidate>,
    rank: Vec<usize>,
    crowding: Vec<f64>,
    rng: Rng,
}

const ETA_CROSSOVER: f64 = 15.0;
const ETA_MUTATION: f64 = 20.0;

impl Nsga2 {
    pub fn new(dim: usize, size: usize, rng: Rng) -> Self {
        let size = size.max(4) + size % 2;
        Self {
            dim,
            size,
            population: Vec::new(),
            rank: Vec::new(),
            crowding: Vec::new(),
            rng,
        }
    }

    /// The feasible first front of the current population.
    pub fn front(&self) -> Vec<Candidate> {
        self.population
            .iter()
            .zip(&self.rank)
            .filter(|(c, &r)| r == 0 && c.fitness.feasible())
            .map(|(c, _)| c.clone())
            .collect()
    }

    fn tournament(&mut self) -> usize {
        let (a, b) = (
            self.rng.below(self.population.len()),
            self.rng.below(self.population.len()),
        );
        if self.rank[a] < self.rank[b]
            || (self.rank[a] == self.rank[b] && self.crowding[a] > self.crowding[b])
        {
            a
        } else {
            b
        }
    }

    fn sbx(&mut self, p1: &[f64], p2: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (mut c1, mut c2) = (p1.to_vec(), p2.to_vec());
        if self.rng.uniform() < 0.9 {
            for i in 0..self.dim {
                if self.rng.uniform() < 0.5 {
                    let u = self.rng.uniform();
                    let beta = if u <= 0.5 {
                        (2.0 * u).powf(1.0 / (ETA_CROSSOVER + 1.0))
                    } else {
                        (1.0 / (2.0 * (1.0 - u))).powf(1.0 / (ETA_CROSSOVER + 1.0))
                    };
                    c1[i] = (0.5 * ((1.0 + beta) * p1[i] + (1.0 - beta) * p2[i])).clamp(0.0, 1.0);
                    c2[i] = (0.5 * ((1.0 - beta) * p1[i] + (1.0 + beta) * p2[i])).clamp(0.0, 1.0);
                }
            }
        }
        (c1, c2)
    }

    fn mutate(&mut self, x: &mut [f64]) {
        let rate = 1.0 / self.dim as f64;
        for v in x.iter_mut() {
            if self.rng.uniform() < rate {
                let u = self.rng.uniform();
                let delta = if u < 0.5 {
                    (2.0 * u).powf(1.0 / (ETA_MUTATION + 1.0)) - 1.0
                } else {
                    1.0 - (2.0 * (1.0 - u)).powf(1.0 / (ETA_MUTATION + 1.0))
                };
                *v = (*v + delta).clamp(0.0, 1.0);
            }
        }
    }

    pub fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        if self.population.is_empty() {
            let points = (0..self.size).map(|_| self.rng.point(self.dim)).collect();
            self.population = evaluate_all(eval, points);
            self.rank_and_crowd();
            return self.population.clone();
        }
        let mut children = Vec::with_capacity(self.size);
        while children.len() < self.size {
            let (a, b) = (self.tournament(), self.tournament());
            let (p1, p2) = (self.population[a].u.clone(), self.population[b].u.clone());
            let (mut c1, mut c2) = self.sbx(&p1, &p2);
            self.mutate(&mut c1);
            self.mutate(&mut c2);
            children.push(c1);
            children.push(c2);
        }
        let offspring = evaluate_all(eval, children);
        let mut merged = std::mem::take(&mut self.population);
        merged.extend(offspring.iter().cloned());
        let fronts = non_dominated_fronts(&merged);
        let mut next = Vec::with_capacity(self.size);
        for front in fronts {
            if next.len() + front.len() <= self.size {
                next.extend(front);
            } else {
                let crowd = crowding(&merged, &front);
                let mut order: Vec<usize> = (0..front.len()).collect();
                order.sort_by(|&a, &b| crowd[b].total_cmp(&crowd[a]).then(a.cmp(&b)));
                next.extend(
                    order
                        .into_iter()
                        .take(self.size - next.len())
                        .map(|k| front[k]),
                );
                break;
            }
        }
        self.population = next.into_iter().map(|i| merged[i].clone()).collect();
        self.rank_and_crowd();
        offspring
    }

    fn rank_and_crowd(&mut self) {
        let n = self.population.len();
        self.rank = vec![0; n];
        self.crowding = vec![0.0; n];
        for (r, front) in non_dominated_fronts(&self.population)
            .into_iter()
            .enumerate()
        {
            let crowd = crowding(&self.population, &front);
            for (k, &i) in front.iter().enumerate() {
                self.rank[i] = r;
                self.crowding[i] = crowd[k];
            }
        }
    }
}

/// Fast non-dominated sort under constraint domination: fronts of indices.
pub fn non_dominated_fronts(pop: &[Candidate]) -> Vec<Vec<usize>> {
    let n = pop.len();
    let mut dominated: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut count = vec![0usize; n];
    for i in 0..n {
        for j in 0..n {
            if i != j && pop[i].fitness.dominates(&pop[j].fitness) {
                dominated[i].push(j);
            } else if i != j && pop[j].fitness.dominates(&pop[i].fitness) {
                count[i] += 1;
            }
        }
    }
    let mut fronts = Vec::new();
    let mut current: Vec<usize> = (0..n).filter(|&i| count[i] == 0).collect();
    while !current.is_empty() {
        let mut next = Vec::new();
        for &i in &current {
            for &j in &dominated[i] {
                count[j] -= 1;
                if count[j] == 0 {
                    next.push(j);
                }
            }
        }
        next.sort_unstable();
        fronts.push(current);
        current = next;
    }
    fronts
}

/// Crowding distance of each member of `front` (infinite at the extremes).
fn crowding(pop: &[Candidate], front: &[usize]) -> Vec<f64> {
    let m = front.len();
    let mut dist = vec![0.0; m];
    if m <= 2 {
        return vec![f64::INFINITY; m];
    }
    let goals = pop[front[0]].fitness.f.len();
    for g in 0..goals {
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&a, &b| {
            pop[front[a]].fitness.f[g]
                .total_cmp(&pop[front[b]].fitness.f[g])
                .then(a.cmp(&b))
        });
        let (lo, hi) = (
            pop[front[order[0]]].fitness.f[g],
            pop[front[order[m - 1]]].fitness.f[g],
        );
        dist[order[0]] = f64::INFINITY;
        dist[order[m - 1]] = f64::INFINITY;
        if hi > lo {
            for k in 1..m - 1 {
                let gap =
                    pop[front[order[k + 1]]].fitness.f[g] - pop[front[order[k - 1]]].fitness.f[g];
                dist[order[k]] += gap / (hi - lo);
            }
        }
    }
    dist
}
