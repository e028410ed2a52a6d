//! The resumable search: a solver's state with the best designs so far (screened and
//! confirmed), counters and history, stepped one generation at a time.

use crate::algorithm::{Algorithm, Solver};
use crate::check::{check_candidate, check_len, state_error};
use crate::fitness::{BatchEvaluator, Candidate};
use serde::{Deserialize, Serialize};

/// One row of the search history.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HistoryRow {
    pub generation: u64,
    pub evaluations: u64,
    pub best_cv: f64,
    pub best_goal: f64,
    pub feasible_in_generation: usize,
}

/// Everything a search needs to resume exactly where it stopped.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SearchState {
    pub algorithm: Algorithm,
    pub solver: Solver,
    pub generation: u64,
    /// Screening evaluations so far.
    pub evaluations: u64,
    /// Confirming evaluations so far (at the default resolution).
    pub confirmations: u64,
    /// Best candidate at the screening resolution.
    pub best: Option<Candidate>,
    /// Best candidate confirmed feasible at the default resolution (fitness as confirmed).
    pub best_confirmed: Option<Candidate>,
    /// Screening evaluations when the first confirmed-feasible design appeared.
    pub first_feasible_at: Option<u64>,
    pub history: Vec<HistoryRow>,
}

impl SearchState {
    /// The design to report: the best confirmed-feasible one, else the best screened.
    pub fn reported(&self) -> Option<&Candidate> {
        self.best_confirmed.as_ref().or(self.best.as_ref())
    }

    pub fn new(
        algorithm: Algorithm,
        dim: usize,
        goals: usize,
        population: usize,
        seed: u64,
    ) -> Self {
        Self {
            algorithm,
            solver: Solver::new(algorithm, dim, goals, population, seed),
            generation: 0,
            evaluations: 0,
            confirmations: 0,
            best: None,
            best_confirmed: None,
            first_feasible_at: None,
            history: Vec::new(),
        }
    }

    /// Checks a state read from outside (a checkpoint) against a problem of `dim`
    /// parameters and `goals` goals: every length, every point in the unit cube, counters
    /// in order. A state that passes cannot panic or loop in [`SearchState::step`].
    pub fn check(&self, dim: usize, goals: usize) -> crate::Result<()> {
        let algorithm = self.solver.algorithm();
        if algorithm != self.algorithm {
            return Err(state_error(format!(
                "the state names algorithm '{}' but holds a '{}' solver",
                self.algorithm.name(),
                algorithm.name()
            )));
        }
        self.solver.check(dim, goals)?;
        for (what, c) in [
            ("best", &self.best),
            ("best_confirmed", &self.best_confirmed),
        ] {
            if let Some(c) = c {
                check_candidate(what, c, dim, goals)?;
            }
        }
        check_len("history", self.history.len(), self.generation as usize)?;
        if let Some(at) = self.first_feasible_at {
            if at > self.evaluations || self.best_confirmed.is_none() {
                return Err(state_error(format!(
                    "first_feasible_at = {at} with {} evaluations and {} confirmed design",
                    self.evaluations,
                    if self.best_confirmed.is_some() {
                        "a"
                    } else {
                        "no"
                    }
                )));
            }
        }
        Ok(())
    }

    /// The `count` best members of the population, to send to another island (fewer if
    /// the population is smaller; none before the first generation or for a solver
    /// without a population).
    pub fn emigrants(&self, count: usize) -> Vec<Candidate> {
        let mut ranked = self.solver.state().ranked_population();
        ranked.truncate(count);
        ranked
    }

    /// Takes `migrants` from another island of the same problem in place of the worst
    /// members, and as the best screened design when one is better. Checked as a
    /// checkpoint is: a migrant of another problem is refused. The confirmed best stays
    /// this island's own, as do the counters: a migrant was evaluated elsewhere.
    pub fn immigrate(
        &mut self,
        migrants: &[Candidate],
        dim: usize,
        goals: usize,
    ) -> crate::Result<()> {
        for (i, m) in migrants.iter().enumerate() {
            check_candidate(&format!("migrant {i}"), m, dim, goals)?;
        }
        if migrants.is_empty() {
            return Ok(());
        }
        if self.generation == 0 {
            return Err(state_error(
                "an island takes migrants after its first generation, not before".into(),
            ));
        }
        self.solver.state_mut().immigrate(migrants)?;
        for m in migrants {
            if (self.best.as_ref()).is_none_or(|b| m.fitness.better_than(&b.fitness)) {
                self.best = Some(m.clone());
            }
        }
        Ok(())
    }

    /// Runs one generation, tracks the best, and confirms new feasible bests.
    pub fn step(&mut self, eval: &mut dyn BatchEvaluator) {
        let batch = self.solver.step(eval);
        // Saturating: a resumed count near 2^64 ends the run at its budget, not wrapping
        // round to zero and running for ever.
        self.generation = self.generation.saturating_add(1);
        self.evaluations = self.evaluations.saturating_add(batch.len() as u64);
        let mut improved = false;
        for c in &batch {
            if self
                .best
                .as_ref()
                .is_none_or(|b| c.fitness.better_than(&b.fitness))
            {
                self.best = Some(c.clone());
                improved = true;
            }
        }
        // Confirm the generation's feasible candidates that could beat the confirmed best.
        let mut pending: Vec<&Candidate> = batch
            .iter()
            .filter(|c| c.fitness.feasible())
            .filter(|c| {
                self.best_confirmed
                    .as_ref()
                    .is_none_or(|b| c.fitness.f[0] < b.fitness.f[0])
            })
            .collect();
        pending.sort_by(|a, b| a.fitness.f[0].total_cmp(&b.fitness.f[0]));
        pending.truncate(if improved { 4 } else { 2 });
        if !pending.is_empty() {
            let points: Vec<Vec<f64>> = pending.iter().map(|c| c.u.clone()).collect();
            let confirmed = eval.confirm(&points);
            self.confirmations += points.len() as u64;
            for (u, fitness) in points.into_iter().zip(confirmed) {
                if fitness.feasible()
                    && self
                        .best_confirmed
                        .as_ref()
                        .is_none_or(|b| fitness.better_than(&b.fitness))
                {
                    self.first_feasible_at.get_or_insert(self.evaluations);
                    self.best_confirmed = Some(Candidate { u, fitness });
                }
            }
        }
        let best = self.best.as_ref().map(|b| &b.fitness);
        self.history.push(HistoryRow {
            generation: self.generation,
            evaluations: self.evaluations,
            best_cv: best.map_or(f64::INFINITY, |f| f.cv),
            best_goal: best.map_or(f64::INFINITY, |f| f.f[0]),
            feasible_in_generation: batch.iter().filter(|c| c.fitness.feasible()).count(),
        });
    }
}
