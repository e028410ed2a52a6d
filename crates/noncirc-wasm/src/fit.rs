//! A fit and a repair in the browser's worker: each box's search sliced as a search is
//! ([`Runner`]), then the CLI's own refinement ([`refine_search`]) in this thread, in one
//! call. The same pieces as `noncirc fit --threads 1` and `noncirc repair --threads 1`, so
//! the same results for the same scene and seed.

use noncirc::core::LocalSettings;
use noncirc::fit::{prepare_fit, refine_search, FitOutcome};
use noncirc::repair::{RepairOptions, RepairOutcome, RepairStages};
use noncirc::search::RunOptions;
use serde::Serialize;
use wasm_bindgen::prelude::*;

use crate::search::{scene_with_settings, Runner};
use crate::{js_error, to_json};

/// A fit being run: its search, then its refinement.
#[wasm_bindgen]
pub struct Fit {
    runner: Runner,
    outcome: Option<FitOutcome>,
}

/// A fit's result: the CLI's `fit.json` and `best.toml`.
#[derive(Serialize)]
struct FitResult {
    fit: noncirc::fit::FitSummary,
    best_toml: Option<String>,
}

#[wasm_bindgen]
impl Fit {
    /// A fit of the scene (text as in a file, with its `[target]`) with the page's search
    /// settings over the scene's; refused as the CLI refuses it (no target, a target out
    /// of the box's reach).
    #[wasm_bindgen(constructor)]
    pub fn new(
        scene_text: &str,
        algorithm: Option<String>,
        budget: Option<u64>,
        seed: Option<u64>,
    ) -> Result<Fit, JsError> {
        let scene = scene_with_settings(scene_text, algorithm, budget, seed)?;
        let scene = prepare_fit(&scene).map_err(js_error)?;
        Ok(Self {
            runner: Runner::new(&scene)?,
            outcome: None,
        })
    }

    /// Runs at most `generations` generations of the search; true once its budget is
    /// spent (or it was stopped).
    pub fn run(&mut self, generations: u32) -> bool {
        self.runner.stopped() || self.runner.run(generations)
    }

    /// Ends the search before its budget: the refinement is then skipped, as in the CLI.
    pub fn stop(&mut self) {
        self.runner.stop();
    }

    /// Where the search is, as JSON.
    pub fn progress(&self) -> Result<String, JsError> {
        self.runner.progress()
    }

    /// Confirms the search's designs and refines the best (one call: at most 10 000
    /// residual vectors); `seconds` is the search's time, for the summary.
    pub fn refine(&mut self, seconds: f64) -> Result<(), JsError> {
        let search = self.runner.outcome(seconds);
        let outcome = refine_search(search, None, &LocalSettings::default()).map_err(js_error)?;
        self.outcome = Some(outcome);
        Ok(())
    }

    /// The fit (after [`Fit::refine`]): the CLI's `fit.json` and `best.toml`, as JSON.
    pub fn result(&self) -> Result<String, JsError> {
        let outcome = (self.outcome.as_ref()).ok_or_else(|| js_error("the fit has not ended"))?;
        let best_toml = (outcome.fitted_scene())
            .map(|s| noncirc::files::toml_text(&s, "the fitted scene"))
            .transpose()
            .map_err(js_error)?;
        to_json(&FitResult {
            fit: outcome.summary(),
            best_toml,
        })
    }
}

/// A repair being run: box by box, each box's search sliced, then its refinement.
#[wasm_bindgen]
pub struct Repair {
    stages: Option<RepairStages>,
    local: LocalSettings,
    runner: Option<Runner>,
    stopped: bool,
    outcome: Option<RepairOutcome>,
}

/// Where a repair is: its box and the box's search.
#[derive(Serialize)]
struct RepairProgress {
    /// The box being searched (1-based) and the most there can be.
    stage: usize,
    stages: usize,
    done: bool,
    search: Option<serde_json::Value>,
}

/// A repair's result: the CLI's `repair.json` and `repaired.toml`.
#[derive(Serialize)]
struct RepairResult {
    repair: noncirc::repair::RepairSummary,
    repaired_toml: Option<String>,
}

#[wasm_bindgen]
impl Repair {
    /// A repair of the scene's design with the page's search settings over the scene's;
    /// refused as the CLI refuses it (a design that does not evaluate, a gear scene).
    #[wasm_bindgen(constructor)]
    pub fn new(
        scene_text: &str,
        algorithm: Option<String>,
        budget: Option<u64>,
        seed: Option<u64>,
    ) -> Result<Repair, JsError> {
        let scene = scene_with_settings(scene_text, algorithm, budget, seed)?;
        let options = RepairOptions::new(RunOptions::new(Some(1)).map_err(js_error)?);
        Ok(Self {
            stages: Some(RepairStages::new(&scene, &options).map_err(js_error)?),
            local: options.fit.local,
            runner: None,
            stopped: false,
            outcome: None,
        })
    }

    /// Runs at most `generations` generations of the current box's search, and ends the
    /// box (its refinement and teeth: one call) when its budget is spent; true once the
    /// repair is over.
    pub fn run(&mut self, generations: u32) -> Result<bool, JsError> {
        let Some(stages) = self.stages.as_mut() else {
            return Ok(true);
        };
        let runner = match &mut self.runner {
            Some(r) => r,
            None => match stages.next_scene() {
                Some(scene) => {
                    let scene = prepare_fit(&scene).map_err(js_error)?;
                    let mut runner = Runner::new(&scene)?;
                    if self.stopped {
                        runner.stop();
                    }
                    self.runner.insert(runner)
                }
                None => {
                    let stages = self.stages.take().expect("checked above");
                    self.outcome = Some(stages.outcome());
                    return Ok(true);
                }
            },
        };
        if runner.stopped() || runner.run(generations) {
            let search = runner.outcome(0.0);
            let fit = refine_search(search, None, &self.local).map_err(js_error)?;
            stages.finish_stage(fit).map_err(js_error)?;
            self.runner = None;
        }
        Ok(false)
    }

    /// Ends the current box's search before its budget, and the repair with it.
    pub fn stop(&mut self) {
        self.stopped = true;
        if let Some(r) = &mut self.runner {
            r.stop();
        }
    }

    /// Where the repair is, as JSON.
    pub fn progress(&self) -> Result<String, JsError> {
        let search = match &self.runner {
            Some(r) => Some(serde_json::from_str(&r.progress()?).map_err(js_error)?),
            None => None,
        };
        to_json(&RepairProgress {
            stage: self.stages.as_ref().map_or(0, RepairStages::boxes_searched) + 1,
            stages: RepairStages::MOST_BOXES,
            done: self.outcome.is_some(),
            search,
        })
    }

    /// The repair (once [`Repair::run`] says it is over): the CLI's `repair.json` and
    /// `repaired.toml`, as JSON.
    pub fn result(&self) -> Result<String, JsError> {
        let outcome =
            (self.outcome.as_ref()).ok_or_else(|| js_error("the repair has not ended"))?;
        let repaired_toml = (outcome.repaired_scene())
            .map(|s| noncirc::files::toml_text(&s, "the repaired scene"))
            .transpose()
            .map_err(js_error)?;
        to_json(&RepairResult {
            repair: outcome.summary(),
            repaired_toml,
        })
    }
}
