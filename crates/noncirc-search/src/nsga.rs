//! NSGA-II (Deb et al. 2002) and NSGA-III (Deb & Jain 2014) with constraint domination:
//! binary tournaments, SBX crossover, polynomial mutation, elitist survival by
//! non-dominated fronts; while no member is feasible, differential-evolution trials
//! instead of SBX (a feasibility phase). They differ only in how the last front that fits is cut: NSGA-II
//! keeps the least crowded members, NSGA-III the members that fill the emptiest niches
//! around a fixed set of reference directions, which keeps the front spread out when more
//! than three goals compete.

use crate::check::{check_candidate, check_len, state_error};
use crate::fitness::{evaluate_all, BatchEvaluator, Candidate};
use crate::rng::Rng;
use crate::solver::{SolverState, MAX_POPULATION};
use serde::{Deserialize, Serialize};

/// How the last front that fits into the next population is cut.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Survival {
    /// NSGA-II: largest crowding distance first.
    Crowding,
    /// NSGA-III: niching around these reference directions (points on the unit simplex).
    ReferenceDirections(Vec<Vec<f64>>),
}

/// NSGA-II or NSGA-III, by its survival rule.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Nsga {
    dim: usize,
    size: usize,
    survival: Survival,
    population: Vec<Candidate>,
    rank: Vec<usize>,
    #[serde(with = "super::nonfinite::vec")]
    crowding: Vec<f64>,
    rng: Rng,
}

const ETA_CROSSOVER: f64 = 15.0;
/// Crossover rate of the feasibility phase's trials (the DE solver's).
const FEASIBILITY_CROSSOVER: f64 = 0.9;
const ETA_MUTATION: f64 = 20.0;

impl Nsga {
    /// NSGA-II with a population of `size` (made even, at least 4).
    pub fn nsga2(dim: usize, size: usize, rng: Rng) -> Self {
        Self::new(dim, size, Survival::Crowding, rng)
    }

    /// NSGA-III for `goals` goals: Das–Dennis reference directions, as many as fit in the
    /// population (at least the `goals` axes), the population at least that many.
    pub fn nsga3(dim: usize, size: usize, goals: usize, rng: Rng) -> Self {
        let directions = das_dennis(goals.max(1), size.max(4));
        let size = size.max(directions.len());
        Self::new(dim, size, Survival::ReferenceDirections(directions), rng)
    }

    fn new(dim: usize, size: usize, survival: Survival, rng: Rng) -> Self {
        let size = size.max(4) + size % 2;
        Self {
            dim,
            size,
            survival,
            population: Vec::new(),
            rank: Vec::new(),
            crowding: Vec::new(),
            rng,
        }
    }

    fn tournament(&mut self) -> usize {
        let (a, b) = (
            self.rng.below(self.population.len()),
            self.rng.below(self.population.len()),
        );
        // NSGA-III has no crowding: there its values are all zero and ties go either way.
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

    /// The Pareto phase's children: binary tournaments, SBX and polynomial mutation.
    fn pareto_children(&mut self) -> Vec<Vec<f64>> {
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
        children
    }

    fn rank_and_crowd(&mut self) {
        let n = self.population.len();
        self.rank = vec![0; n];
        self.crowding = vec![0.0; n];
        for (r, front) in non_dominated_fronts(&self.population)
            .into_iter()
            .enumerate()
        {
            let crowd = match self.survival {
                Survival::Crowding => crowding(&self.population, &front),
                Survival::ReferenceDirections(_) => vec![0.0; front.len()],
            };
            for (k, &i) in front.iter().enumerate() {
                self.rank[i] = r;
                self.crowding[i] = crowd[k];
            }
        }
    }
}

impl SolverState for Nsga {
    /// Checks a resumed state: an even population of at least 4, ranks and crowding per
    /// member, reference directions with one coordinate per goal.
    fn check(&self, dim: usize, goals: usize) -> crate::Result<()> {
        check_len("nsga: dimension", self.dim, dim)?;
        if !(4..=MAX_POPULATION).contains(&self.size) || self.size % 2 == 1 {
            return Err(state_error(format!(
                "nsga: population size {} (even, from 4 to {MAX_POPULATION})",
                self.size
            )));
        }
        if !self.population.is_empty() {
            check_len("nsga: population", self.population.len(), self.size)?;
        }
        check_len("nsga: ranks", self.rank.len(), self.population.len())?;
        check_len("nsga: crowding", self.crowding.len(), self.population.len())?;
        if let Survival::ReferenceDirections(directions) = &self.survival {
            if directions.is_empty() {
                return Err(state_error("nsga3: no reference directions".into()));
            }
            for d in directions {
                check_len("nsga3: reference direction", d.len(), goals)?;
            }
        }
        for (i, c) in self.population.iter().enumerate() {
            check_candidate(&format!("nsga: member {i}"), c, dim, goals)?;
        }
        Ok(())
    }

    /// The feasible first front of the current population.
    fn front(&self) -> Vec<Candidate> {
        self.population
            .iter()
            .zip(&self.rank)
            .filter(|(c, &r)| r == 0 && c.fitness.feasible())
            .map(|(c, _)| c.clone())
            .collect()
    }

    fn ranked_population(&self) -> Vec<Candidate> {
        let mut order: Vec<usize> = (0..self.population.len()).collect();
        order.sort_by(|&a, &b| {
            (self.rank[a].cmp(&self.rank[b]))
                .then(self.crowding[b].total_cmp(&self.crowding[a]))
                .then(a.cmp(&b))
        });
        order
            .into_iter()
            .map(|i| self.population[i].clone())
            .collect()
    }

    fn immigrate(&mut self, migrants: &[Candidate]) -> crate::Result<()> {
        let mut order: Vec<usize> = (0..self.population.len()).collect();
        order.sort_by(|&a, &b| {
            (self.rank[b].cmp(&self.rank[a]))
                .then(self.crowding[a].total_cmp(&self.crowding[b]))
                .then(b.cmp(&a))
        });
        for (&worst, m) in order.iter().zip(migrants) {
            self.population[worst] = m.clone();
        }
        self.rank_and_crowd();
        Ok(())
    }

    fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        if self.population.is_empty() {
            let points = (0..self.size).map(|_| self.rng.point(self.dim)).collect();
            self.population = evaluate_all(eval, points);
            self.rank_and_crowd();
            return self.population.clone();
        }
        let children = if self.population.iter().any(|c| c.fitness.feasible()) {
            self.pareto_children()
        } else {
            // Feasibility phase: until a member meets every constraint, the children are
            // differential-evolution trials (one per member), whose long moves find the
            // feasible region where SBX and polynomial mutation, local around parents that
            // are all infeasible, seldom do (1 of 10 runs on the default scene).
            (0..self.population.len())
                .map(|i| {
                    super::de::trial(&self.population, i, FEASIBILITY_CROSSOVER, &mut self.rng)
                })
                .collect()
        };
        let offspring = evaluate_all(eval, children);
        let mut merged = std::mem::take(&mut self.population);
        merged.extend(offspring.iter().cloned());
        let fronts = non_dominated_fronts(&merged);
        let mut next = Vec::with_capacity(self.size);
        for (r, front) in fronts.iter().enumerate() {
            if next.len() + front.len() <= self.size {
                next.extend(front);
                continue;
            }
            let room = self.size - next.len();
            let chosen = match &self.survival {
                Survival::Crowding => {
                    let crowd = crowding(&merged, front);
                    let mut order: Vec<usize> = (0..front.len()).collect();
                    order.sort_by(|&a, &b| crowd[b].total_cmp(&crowd[a]).then(a.cmp(&b)));
                    order.into_iter().take(room).map(|k| front[k]).collect()
                }
                Survival::ReferenceDirections(directions) => {
                    let kept: Vec<usize> = fronts[..r].concat();
                    niching(
                        &merged,
                        &kept,
                        front,
                        &fronts[0],
                        directions,
                        room,
                        &mut self.rng,
                    )
                }
            };
            next.extend(chosen);
            break;
        }
        self.population = next.into_iter().map(|i| merged[i].clone()).collect();
        self.rank_and_crowd();
        offspring
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

/// Das–Dennis reference directions on the unit simplex in `goals` dimensions: all points
/// with coordinates `k/p` summing to 1, for the largest `p` that gives at most `limit`
/// points (at least `p = 1`: the axes).
pub(crate) fn das_dennis(goals: usize, limit: usize) -> Vec<Vec<f64>> {
    let count = |p: usize| binomial(goals + p - 1, p);
    let mut p = 1;
    while count(p + 1) <= limit as u64 && p < 1000 {
        p += 1;
    }
    let mut out = Vec::new();
    let mut point = vec![0usize; goals];
    fill_simplex(&mut point, 0, p, p, &mut out);
    out
}

fn fill_simplex(point: &mut [usize], at: usize, left: usize, p: usize, out: &mut Vec<Vec<f64>>) {
    if at + 1 == point.len() {
        point[at] = left;
        out.push(point.iter().map(|&k| k as f64 / p as f64).collect());
        return;
    }
    for k in 0..=left {
        point[at] = k;
        fill_simplex(point, at + 1, left - k, p, out);
    }
}

fn binomial(n: usize, k: usize) -> u64 {
    (0..k).fold(1u64, |acc, i| {
        acc.saturating_mul((n - i) as u64) / (i as u64 + 1)
    })
}

/// NSGA-III's niching: picks `room` members of `last` so that, together with `kept`, the
/// reference directions' niches fill as evenly as possible. Goals are normalised by the
/// ideal point of `kept ∪ last` and the worst values of the first front (the intercepts
/// Deb & Jain fall back to when the extreme-point hyperplane is degenerate); each member
/// joins the direction nearest to it (perpendicular distance).
fn niching(
    pop: &[Candidate],
    kept: &[usize],
    last: &[usize],
    first_front: &[usize],
    directions: &[Vec<f64>],
    room: usize,
    rng: &mut Rng,
) -> Vec<usize> {
    let goals = directions[0].len();
    let goal = |i: usize, g: usize| pop[i].fitness.f[g];
    let mut ideal = vec![f64::INFINITY; goals];
    for &i in kept.iter().chain(last) {
        for (g, v) in ideal.iter_mut().enumerate() {
            *v = v.min(goal(i, g));
        }
    }
    let mut span = vec![0.0f64; goals];
    for &i in first_front {
        for (g, s) in span.iter_mut().enumerate() {
            *s = s.max(goal(i, g) - ideal[g]);
        }
    }
    for s in &mut span {
        if !(*s > 1e-12 && s.is_finite()) {
            *s = 1.0;
        }
    }
    // Nearest direction and the distance to it, for one member.
    let associate = |i: usize| {
        let x: Vec<f64> = (0..goals)
            .map(|g| (goal(i, g) - ideal[g]) / span[g])
            .collect();
        let norm2 = x.iter().map(|v| v * v).sum::<f64>();
        let mut best = (0, f64::INFINITY);
        for (d, w) in directions.iter().enumerate() {
            let w2 = w.iter().map(|v| v * v).sum::<f64>();
            let along = x.iter().zip(w).map(|(a, b)| a * b).sum::<f64>();
            let dist2 = (norm2 - along * along / w2).max(0.0);
            if dist2 < best.1 {
                best = (d, dist2);
            }
        }
        best
    };
    let mut niche_count = vec![0usize; directions.len()];
    for &i in kept {
        niche_count[associate(i).0] += 1;
    }
    let mut members: Vec<Vec<(f64, usize)>> = vec![Vec::new(); directions.len()];
    for &i in last {
        let (d, dist2) = associate(i);
        members[d].push((dist2, i));
    }
    let mut chosen = Vec::with_capacity(room);
    let mut open: Vec<usize> = (0..directions.len())
        .filter(|&d| !members[d].is_empty())
        .collect();
    while chosen.len() < room && !open.is_empty() {
        let least = open.iter().map(|&d| niche_count[d]).min().unwrap_or(0);
        let ties: Vec<usize> = open
            .iter()
            .copied()
            .filter(|&d| niche_count[d] == least)
            .collect();
        let d = ties[rng.below(ties.len())];
        let pool = &mut members[d];
        let k = if niche_count[d] == 0 {
            // The member nearest to an empty niche's direction.
            (0..pool.len())
                .min_by(|&a, &b| pool[a].0.total_cmp(&pool[b].0).then(a.cmp(&b)))
                .unwrap_or(0)
        } else {
            rng.below(pool.len())
        };
        chosen.push(pool.swap_remove(k).1);
        niche_count[d] += 1;
        if pool.is_empty() {
            open.retain(|&o| o != d);
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::das_dennis;
    use crate::test_problem::FnProblem;
    use crate::{Algorithm, Candidate, Fitness, SearchState};

    #[test]
    fn das_dennis_directions_fill_the_simplex() {
        // p = 7 partitions for 4 goals: C(10, 7) = 120 points with coordinates k/7 summing to 1.
        let dirs = das_dennis(4, 120);
        assert_eq!(dirs.len(), 120);
        for d in &dirs {
            assert!((d.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(d
                .iter()
                .all(|&v| (v * 7.0 - (v * 7.0).round()).abs() < 1e-12));
        }
        assert_eq!(das_dennis(3, 91).len(), 91); // p = 12
        assert_eq!(das_dennis(2, 5).len(), 5); // p = 4
    }

    #[test]
    fn nsga3_converges_to_the_dtlz2_front_with_four_goals() {
        // DTLZ2 (4 goals, d = 8): the front is the unit sphere's positive orthant, reached with
        // u_3.. = 0.5.
        let goals = 4;
        let dtlz2 = move |u: &[f64]| {
            let g: f64 = u[goals - 1..].iter().map(|x| (x - 0.5).powi(2)).sum();
            let angle = |x: f64| x * std::f64::consts::FRAC_PI_2;
            let f = (0..goals)
                .map(|i| {
                    let mut v = 1.0 + g;
                    for x in &u[..goals - 1 - i] {
                        v *= angle(*x).cos();
                    }
                    if i > 0 {
                        v *= angle(u[goals - 1 - i]).sin();
                    }
                    v
                })
                .collect();
            Fitness { cv: 0.0, f }
        };
        let mut eval = FnProblem {
            dim: 8,
            goals,
            score: dtlz2,
        };
        let mut state = SearchState::new(Algorithm::Nsga3, 8, goals, 120, 5);
        while state.evaluations < 36_000 {
            state.step(&mut eval);
        }
        let front = state.solver.front();
        assert!(front.len() >= 100, "front of {}", front.len());
        let radius = |c: &Candidate| c.fitness.f.iter().map(|v| v * v).sum::<f64>().sqrt();
        let worst = front.iter().map(|c| radius(c) - 1.0).fold(0.0, f64::max);
        assert!(worst < 0.05, "distance to the true front {worst}");
        // Spread: the members' nearest reference directions cover most of the 120.
        let dirs = das_dennis(goals, 120);
        let mut covered = std::collections::BTreeSet::new();
        for c in &front {
            let r = radius(c);
            let nearest = (0..dirs.len())
                .min_by(|&a, &b| {
                    let cos = |d: &Vec<f64>| {
                        let n = d.iter().map(|v| v * v).sum::<f64>().sqrt();
                        d.iter().zip(&c.fitness.f).map(|(x, y)| x * y).sum::<f64>() / (n * r)
                    };
                    cos(&dirs[b]).total_cmp(&cos(&dirs[a]))
                })
                .unwrap();
            covered.insert(nearest);
        }
        assert!(
            covered.len() >= 90,
            "{} of 120 directions covered",
            covered.len()
        );
    }
}
