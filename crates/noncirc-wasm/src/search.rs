//! A search in the browser's worker: the core's executor and solvers on the serial
//! evaluator, run a few generations at a time so that the worker stays responsive (a stop
//! asked for between two calls ends the run cleanly, as Ctrl-C does in the CLI). Stopping
//! and going on is the same run (the executor's tests), so the result is the CLI's
//! one-thread run with the same scene and seed.

use noncirc::core::{
    execute, stop_after_generations, Algorithm, BatchEvaluator, Checkpoint, Ending, Scene,
    SceneProblem, SearchState, SerialEvaluator,
};
use noncirc::scene_file::parse_scene;
use noncirc::search::{best_scene, Confirmed, Outcome as SearchOutcome, SearchSettings, Summary};
use serde::Serialize;
use wasm_bindgen::prelude::*;

use crate::{js_error, to_json};

/// A search being run.
#[wasm_bindgen]
pub struct Search {
    runner: Runner,
}

/// A search run a few generations at a time on the serial evaluator (a search's, a fit's
/// and each of a repair's boxes).
pub(crate) struct Runner {
    evaluator: SerialEvaluator,
    state: SearchState,
    budget: u64,
    stopped: bool,
}

/// The studio's scene text with the search settings the page gives over the scene's own
/// (`algorithm` by name, `budget`, `seed`; `None` keeps the scene's), checked as the CLI
/// checks its flags.
pub(crate) fn scene_with_settings(
    scene_text: &str,
    algorithm: Option<String>,
    budget: Option<u64>,
    seed: Option<u64>,
) -> Result<Scene, JsError> {
    let mut scene = parse_scene(scene_text, "the studio's scene").map_err(js_error)?;
    let settings = SearchSettings {
        algorithm: algorithm
            .map(|a| Algorithm::parse(&a))
            .transpose()
            .map_err(js_error)?,
        budget,
        seed,
        ..SearchSettings::default()
    };
    settings.apply(&mut scene).map_err(js_error)?;
    Ok(scene)
}

impl Runner {
    /// A new search of `scene` (its `[search]` settings).
    pub(crate) fn new(scene: &Scene) -> Result<Self, JsError> {
        scene.validate_search().map_err(js_error)?;
        let problem = SceneProblem::new(scene).map_err(js_error)?;
        let search = &scene.search;
        let state = SearchState::new(
            search.algorithm,
            problem.dim(),
            problem.goals(),
            search.population,
            search.seed,
        );
        Ok(Self {
            budget: search.budget,
            evaluator: SerialEvaluator::new(problem),
            state,
            stopped: false,
        })
    }

    /// Runs at most `generations` generations; true once the budget is spent.
    pub(crate) fn run(&mut self, generations: u32) -> bool {
        let mut limit = stop_after_generations(u64::from(generations));
        let ending = execute(
            &mut self.state,
            &mut self.evaluator as &mut dyn BatchEvaluator,
            self.budget,
            &mut [&mut limit],
        );
        ending == Ending::Budget
    }

    pub(crate) fn stop(&mut self) {
        self.stopped = true;
    }

    pub(crate) fn stopped(&self) -> bool {
        self.stopped
    }

    pub(crate) fn progress(&self) -> Result<String, JsError> {
        to_json(&Progress {
            generation: self.state.generation,
            evaluations: self.state.evaluations,
            budget: self.budget,
            done: self.state.evaluations >= self.budget,
            first_feasible_evaluations: self.state.first_feasible_at,
            last: self.state.history.last(),
        })
    }

    fn stopped_early(&self) -> bool {
        self.stopped && self.state.evaluations < self.budget
    }

    /// The finished (or stopped) search as the CLI's one-thread run gives it, the reported
    /// designs confirmed.
    pub(crate) fn outcome(&self, seconds: f64) -> SearchOutcome {
        let problem = self.evaluator.problem().clone();
        let confirmed = Confirmed::new(&problem, &self.state);
        SearchOutcome {
            problem,
            state: self.state.clone(),
            budget: self.budget,
            seconds,
            seconds_to_first_feasible: None,
            threads: 1,
            stopped_early: self.stopped_early(),
            checkpoint_failures: Vec::new(),
            confirmed,
        }
    }
}

/// Where a search is, for the progress bar and the convergence plot.
#[derive(Serialize)]
struct Progress<'a> {
    generation: u64,
    evaluations: u64,
    budget: u64,
    done: bool,
    first_feasible_evaluations: Option<u64>,
    /// The last generation's row of the history (`None` before the first).
    last: Option<&'a noncirc::core::HistoryRow>,
}

/// The reported design, confirmed at the scene's resolution.
#[derive(Serialize)]
struct Outcome {
    /// The CLI's `summary.json`.
    summary: Summary,
    /// The CLI's `best.toml`.
    best_toml: Option<String>,
    history: Vec<noncirc::core::HistoryRow>,
}

#[wasm_bindgen]
impl Search {
    /// A search of the scene (text as in a file) with the given settings over the scene's
    /// own (`algorithm` by name, `budget`, `seed`; `undefined` keeps the scene's), checked
    /// as the CLI checks its flags.
    #[wasm_bindgen(constructor)]
    pub fn new(
        scene_text: &str,
        algorithm: Option<String>,
        budget: Option<u64>,
        seed: Option<u64>,
    ) -> Result<Search, JsError> {
        let scene = scene_with_settings(scene_text, algorithm, budget, seed)?;
        Ok(Self {
            runner: Runner::new(&scene)?,
        })
    }

    /// Resumes from a checkpoint's text (its scene and settings; `budget` may replace its
    /// budget).
    pub fn resume(checkpoint: &str, budget: Option<u64>) -> Result<Search, JsError> {
        let cp = Checkpoint::from_json(checkpoint.as_bytes()).map_err(js_error)?;
        let problem = SceneProblem::new(&cp.scene).map_err(js_error)?;
        cp.state
            .check(problem.dim(), problem.goals())
            .map_err(js_error)?;
        Ok(Self {
            runner: Runner {
                budget: budget.unwrap_or(cp.budget),
                evaluator: SerialEvaluator::new(problem),
                state: cp.state,
                stopped: false,
            },
        })
    }

    /// Runs at most `generations` generations; true once the budget is spent.
    pub fn run(&mut self, generations: u32) -> bool {
        self.runner.run(generations)
    }

    /// Ends the run before its budget (the result says it stopped early).
    pub fn stop(&mut self) {
        self.runner.stop();
    }

    /// Where the run is, as JSON.
    pub fn progress(&self) -> Result<String, JsError> {
        self.runner.progress()
    }

    /// A checkpoint of the run (the CLI's format: `noncirc optimise --resume` reads it).
    pub fn checkpoint(&self) -> String {
        let r = &self.runner;
        let cp = Checkpoint::new(r.evaluator.problem(), r.budget, &r.state);
        String::from_utf8_lossy(&cp.to_json()).into_owned()
    }

    /// The reported design confirmed at the scene's resolution: the CLI's summary (with the
    /// page's `seconds`) and best scene, and the history, as JSON.
    pub fn result(&self, seconds: f64) -> Result<String, JsError> {
        let r = &self.runner;
        let problem = r.evaluator.problem();
        let confirmed = Confirmed::new(problem, &r.state);
        let summary = Summary::new(
            problem,
            &r.state,
            &confirmed,
            1,
            seconds,
            None,
            r.stopped_early(),
        );
        let best_toml = best_scene(problem, &confirmed)
            .map(|s| noncirc::files::toml_text(&s, "the best scene"))
            .transpose()
            .map_err(js_error)?;
        to_json(&Outcome {
            summary,
            best_toml,
            history: r.state.history.clone(),
        })
    }
}
