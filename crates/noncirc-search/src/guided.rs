//! The parameter-guided heuristic of the papers (Zhao et al. 2013): from a design, measure
//! each parameter's effect by probing it up and down, move the parameters that help most
//! together (weighted by their gain), adapt each parameter's step, restart when stuck.

use crate::check::{check_candidate, check_len, state_error};
use crate::fitness::{clamp_unit, evaluate_all, BatchEvaluator, Candidate};
use crate::rng::Rng;
use crate::solver::SolverState;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ParameterGuided {
    dim: usize,
    current: Option<Candidate>,
    steps: Vec<f64>,
    stall: u32,
    rng: Rng,
}

const START_STEP: f64 = 0.1;
const MIN_STEP: f64 = 1e-4;
const MAX_STALL: u32 = 12;

impl ParameterGuided {
    pub fn new(dim: usize, rng: Rng) -> Self {
        Self {
            dim,
            current: None,
            steps: vec![START_STEP; dim],
            stall: 0,
            rng,
        }
    }

    fn restart(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        self.steps = vec![START_STEP; self.dim];
        self.stall = 0;
        let start = evaluate_all(eval, vec![self.rng.point(self.dim)]);
        self.current = start.first().cloned();
        start
    }
}

impl SolverState for ParameterGuided {
    /// Checks a resumed state.
    fn check(&self, dim: usize, goals: usize) -> crate::Result<()> {
        check_len("guided: dimension", self.dim, dim)?;
        check_len("guided: steps", self.steps.len(), dim)?;
        if let Some(s) = self.steps.iter().find(|s| !(s.is_finite() && **s >= 0.0)) {
            return Err(state_error(format!("guided: step {s} is not a length")));
        }
        if let Some(c) = &self.current {
            check_candidate("guided: current design", c, dim, goals)?;
        }
        Ok(())
    }

    fn step(&mut self, eval: &mut dyn BatchEvaluator) -> Vec<Candidate> {
        let Some(current) = self.current.clone() else {
            return self.restart(eval);
        };
        if self.stall >= MAX_STALL || self.steps.iter().all(|&s| s < MIN_STEP) {
            return self.restart(eval);
        }
        // Probe every parameter up and down.
        let mut probes = Vec::with_capacity(2 * self.dim);
        for i in 0..self.dim {
            for sign in [1.0, -1.0] {
                let mut u = current.u.clone();
                u[i] += sign * self.steps[i];
                clamp_unit(&mut u);
                probes.push(u);
            }
        }
        let mut evaluated = evaluate_all(eval, probes);
        let base = current.fitness.merit();
        // Each parameter's gain and helpful direction.
        let gains: Vec<(f64, f64)> = (0..self.dim)
            .map(|i| {
                let (up, down) = (
                    evaluated[2 * i].fitness.merit(),
                    evaluated[2 * i + 1].fitness.merit(),
                );
                if up < down {
                    (base - up, 1.0)
                } else {
                    (base - down, -1.0)
                }
            })
            .collect();
        let top = gains.iter().map(|g| g.0).fold(0.0, f64::max);
        let mut best = evaluated
            .iter()
            .min_by(|a, b| a.fitness.merit().total_cmp(&b.fitness.merit()))
            .cloned()
            .expect("at least one probe");
        if top > 0.0 {
            // Move the helpful parameters together, each in proportion to its gain.
            let mut u = current.u.clone();
            for (i, &(g, dir)) in gains.iter().enumerate() {
                if g > 0.0 {
                    u[i] += dir * self.steps[i] * (g / top);
                }
            }
            clamp_unit(&mut u);
            let combined = evaluate_all(eval, vec![u]);
            if combined[0].fitness.better_than(&best.fitness) {
                best = combined[0].clone();
            }
            evaluated.extend(combined);
        }
        if best.fitness.better_than(&current.fitness) {
            for (i, &(g, _)) in gains.iter().enumerate() {
                self.steps[i] = if g > 0.0 {
                    (self.steps[i] * 1.5).min(0.5)
                } else {
                    self.steps[i] * 0.7
                };
            }
            self.current = Some(best);
            self.stall = 0;
        } else {
            for s in &mut self.steps {
                *s *= 0.5;
            }
            self.stall += 1;
        }
        evaluated
    }
}
