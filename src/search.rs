//! Running searches: parallel batch evaluation, progress, checkpoints, Ctrl-C, outputs.

use noncirc_core::{
    execute, non_dominated_fronts, stop_after_generations, Algorithm, BatchEvaluator, Candidate,
    Checkpoint, Control, Ending, Evaluation, Evaluator, Fitness, ModuleReading, Observer,
    Resolution, Scene, SceneProblem, SearchState, CHECKPOINT_FORMAT,
};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use crate::files::{create_dir, json_text, read_limited, toml_text, write_atomic, write_file};
use crate::report::RequirementRow;
use crate::{Error, Result};

/// Most designs per parallel piece of a batch of `len` on `threads` ([`map_batch`] passes
/// it to rayon's `with_max_len`): about 32 pieces per thread. Uncapped, rayon splits a
/// batch only until every thread has a part, one half each on 2 threads; designs differ in
/// cost, so one thread then idles at the end (10 % of a batch was measured). Small pieces
/// leave work to steal. Each piece clones a planned evaluator and the scene to edit, so a
/// small batch (48 designs) is cut into about 4 pieces per thread of up to 8 designs, not
/// into single designs. (A search's evaluator keeps one of each per thread instead, and
/// cuts its generations finer.)
pub fn batch_piece(len: usize, threads: usize) -> usize {
    len.div_ceil(32 * threads)
        .max(len.div_ceil(4 * threads).min(8))
        .max(1)
}

/// A worker thread's evaluator and scene to edit.
type Worker = (Evaluator, Scene);

/// Evaluates batches in parallel on a private rayon pool; results keep the input order,
/// so a run is bit-identical whatever the thread count.
pub struct ParallelEvaluator<'a> {
    problem: &'a SceneProblem,
    /// Shared with [`ParallelEvaluator::on_pool`]'s caller while it runs there.
    pool: Arc<rayon::ThreadPool>,
    confirm_at: Resolution,
    /// Evaluators planned for the screening and the confirming resolution, cloned by workers.
    planned: [Evaluator; 2],
    /// Per pool thread and per resolution (as `planned`), the thread's evaluator and
    /// scene to edit, made at its first design and kept from batch to batch: a search's
    /// generations are small batches, and a clone of each per piece of a batch (about
    /// 0.4 µs) kept the pieces large and one thread idle at the end of a generation.
    kept: [Vec<Mutex<Option<Worker>>>; 2],
    /// Once set (Ctrl-C), the designs of a batch not yet started are skipped.
    stop: Arc<AtomicBool>,
    /// Whether the last batch skipped any design.
    skipped: bool,
}

/// Most worker threads: more cannot help on any machine noncirc runs on, and thousands
/// exhaust the process's thread limit ("Resource temporarily unavailable").
pub const MAX_THREADS: usize = 256;

/// A private rayon pool of `threads` threads (checked as [`check_threads`] does).
pub fn thread_pool(threads: usize) -> Result<rayon::ThreadPool> {
    check_threads(threads)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::Threads {
            threads,
            message: e.to_string(),
        })
}

/// Checks a thread count (1 to [`MAX_THREADS`]).
pub fn check_threads(threads: usize) -> Result<usize> {
    if (1..=MAX_THREADS).contains(&threads) {
        Ok(threads)
    } else {
        Err(Error::Input(format!(
            "threads = {threads}: expected 1 to {MAX_THREADS}"
        )))
    }
}

impl<'a> ParallelEvaluator<'a> {
    /// An evaluator on `threads` threads.
    pub fn new(problem: &'a SceneProblem, threads: usize) -> Result<Self> {
        let pool = thread_pool(threads)?;
        let confirm_at = problem.base().resolution;
        Ok(Self {
            problem,
            pool: Arc::new(pool),
            confirm_at,
            planned: [problem.screening(), confirm_at].map(|r| Evaluator::planned(&r)),
            kept: [(); 2].map(|()| (0..threads).map(|_| Mutex::new(None)).collect()),
            stop: Arc::new(AtomicBool::new(false)),
            skipped: false,
        })
    }

    /// Skips the rest of a batch once `stop` is set: the executor then undoes that
    /// generation ([`BatchEvaluator::interrupted`]), so a stop is answered within one
    /// design's evaluation per thread, not at the end of the generation.
    pub fn stopped_by(self, stop: Arc<AtomicBool>) -> Self {
        Self { stop, ..self }
    }

    /// Runs `work` on one of the pool's own threads, so that the batches it evaluates are
    /// shared from there: the other threads take parts of each batch as they wait for work,
    /// not from a caller outside the pool that sleeps until the batch comes back. A
    /// search's generations are small batches (48 designs, about 0.2 ms of work): handed
    /// to the pool and back, each cost three context switches, about 3 700 in a DE search
    /// on two threads against about 300 from the pool's thread (docs/performance.md).
    pub fn on_pool<R: Send>(&mut self, work: impl FnOnce(&mut Self) -> R + Send) -> R {
        let pool = Arc::clone(&self.pool);
        pool.install(|| work(self))
    }

    /// Each point's fitness at `resolution`; with `rivals`, each against its rival
    /// ([`SceneProblem::fitness_against`]).
    fn run(
        &mut self,
        points: &[Vec<f64>],
        rivals: Option<&[Fitness]>,
        resolution: Resolution,
    ) -> Vec<Fitness> {
        let problem = self.problem;
        let which = usize::from(resolution == self.confirm_at);
        let (planned, kept) = (&self.planned[which], &self.kept[which]);
        let (stop, skipped) = (&*self.stop, AtomicBool::new(false));
        let items: Vec<(&[f64], Option<&Fitness>)> = (points.iter().enumerate())
            .map(|(i, u)| (&u[..], rivals.and_then(|r| r.get(i))))
            .collect();
        let fresh = || {
            let mut evaluator = planned.clone();
            evaluator.prepare_target(problem.base());
            (evaluator, problem.base().clone())
        };
        let evaluate = |(evaluator, scratch): &mut Worker,
                        &(u, rival): &(&[f64], Option<&Fitness>)| {
            if stop.load(Ordering::Relaxed) {
                skipped.store(true, Ordering::Relaxed);
                Fitness {
                    cv: f64::INFINITY,
                    f: vec![f64::INFINITY; problem.goals()],
                }
            } else if let Some(rival) = rival {
                problem.fitness_against(u, rival, evaluator, scratch, &resolution)
            } else {
                problem.fitness_alone(u, evaluator, scratch, &resolution)
            }
        };
        let fitness = if kept.len() == 1 {
            let mut slot = lock(&kept[0]);
            let state = slot.get_or_insert_with(fresh);
            items.iter().map(|item| evaluate(state, item)).collect()
        } else {
            // About 32 pieces a thread: a piece clones nothing, so a generation goes in
            // single designs, and the threads finish it together.
            let piece = items.len().div_ceil(32 * kept.len());
            self.pool.install(|| {
                (items.par_iter().with_max_len(piece))
                    .map(|item| {
                        // Inside `install`, each design runs on one of the pool's threads.
                        let thread = rayon::current_thread_index().unwrap_or(0);
                        let mut slot = lock(kept.get(thread).unwrap_or(&kept[0]));
                        evaluate(slot.get_or_insert_with(fresh), item)
                    })
                    .collect()
            })
        };
        self.skipped = skipped.into_inner();
        fitness
    }
}

/// A thread's kept evaluator and scene; a panic there ends the search, so a poisoned lock
/// is not met again.
fn lock<T>(slot: &Mutex<T>) -> MutexGuard<'_, T> {
    slot.lock().unwrap_or_else(|e| e.into_inner())
}

/// Maps `f` over `items` on `pool`, keeping their order. The batch is cut into pieces of at
/// most [`batch_piece`] items, and each piece's worker starts from its own clones of a
/// `planned` evaluator and of the `base` scene to edit.
pub fn map_batch<T: Sync, R: Send>(
    pool: &rayon::ThreadPool,
    planned: &Evaluator,
    base: &Scene,
    items: &[T],
    f: impl Fn(&mut (Evaluator, Scene), &T) -> R + Sync + Send,
) -> Vec<R> {
    let piece = batch_piece(items.len(), pool.current_num_threads());
    // The scene's target prepared once for the batch, not once per piece.
    let mut planned = planned.clone();
    planned.prepare_target(base);
    // One thread: on the caller's, with no hand-over to the pool's worker and back per
    // batch (a search's generations are small batches: the hand-over cost about 10 % of a
    // one-thread DE run in kernel scheduling).
    if pool.current_num_threads() == 1 {
        let mut state = (planned, base.clone());
        return items.iter().map(|item| f(&mut state, item)).collect();
    }
    pool.install(|| {
        items
            .par_iter()
            .with_max_len(piece)
            .map_init(|| (planned.clone(), base.clone()), f)
            .collect()
    })
}

impl BatchEvaluator for ParallelEvaluator<'_> {
    fn dim(&self) -> usize {
        self.problem.dim()
    }
    fn goals(&self) -> usize {
        self.problem.goals()
    }
    fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        self.run(points, None, self.problem.screening())
    }
    fn evaluate_against(&mut self, points: &[Vec<f64>], rivals: &[Fitness]) -> Vec<Fitness> {
        self.run(points, Some(rivals), self.problem.screening())
    }
    fn confirm(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        self.run(points, None, self.confirm_at)
    }
    fn interrupted(&self) -> bool {
        self.skipped
    }
}

/// Search settings a front end sets over the scene's own (the CLI's flags, Python's
/// keywords): each one given replaces the scene's value, so the scene states what ran.
#[derive(Debug, Clone, Default)]
pub struct SearchSettings {
    pub algorithm: Option<Algorithm>,
    pub budget: Option<u64>,
    pub population: Option<usize>,
    pub seed: Option<u64>,
    pub screening_samples_per_turn: Option<usize>,
}

impl SearchSettings {
    /// Writes the settings given into the scene and checks its search as a scene file's own
    /// search is checked (the flags are scene values too).
    pub fn apply(&self, scene: &mut Scene) -> noncirc_core::Result<()> {
        let search = &mut scene.search;
        search.algorithm = self.algorithm.unwrap_or(search.algorithm);
        search.budget = self.budget.unwrap_or(search.budget);
        search.population = self.population.unwrap_or(search.population);
        search.seed = self.seed.unwrap_or(search.seed);
        search.screening.samples_per_turn = self
            .screening_samples_per_turn
            .unwrap_or(search.screening.samples_per_turn);
        scene.validate_search()
    }

    /// The settings given that a resumed search would ignore (it runs the checkpoint's own
    /// scene and settings; only the budget applies), by name: a front end refuses them.
    pub fn ignored_by_resume(&self) -> Vec<&'static str> {
        [
            ("algorithm", self.algorithm.is_some()),
            ("population", self.population.is_some()),
            ("seed", self.seed.is_some()),
            (
                "screening samples per turn",
                self.screening_samples_per_turn.is_some(),
            ),
        ]
        .into_iter()
        .filter_map(|(name, given)| given.then_some(name))
        .collect()
    }
}

/// Largest interval between checkpoints (s): a year.
pub const MAX_CHECKPOINT_EVERY_S: f64 = 3.2e7;

/// The interval between checkpoints, from seconds (0 to [`MAX_CHECKPOINT_EVERY_S`]).
pub fn checkpoint_interval(seconds: f64) -> Result<Duration> {
    if seconds.is_finite() && (0.0..=MAX_CHECKPOINT_EVERY_S).contains(&seconds) {
        Ok(Duration::from_secs_f64(seconds))
    } else {
        Err(Error::Input(format!(
            "checkpoint interval {seconds} s: expected seconds from 0 to {MAX_CHECKPOINT_EVERY_S:e}"
        )))
    }
}

/// How to run a search (what to search is the scene's: its `[search]` table).
pub struct RunOptions {
    pub threads: usize,
    /// Write a checkpoint here every `checkpoint_every` and at the end. An existing file
    /// there must be a noncirc checkpoint (nothing else is overwritten).
    pub checkpoint: Option<PathBuf>,
    pub checkpoint_every: Duration,
    /// Resume from this checkpoint: its scene, algorithm, population and seed are used.
    pub resume: Option<PathBuf>,
    /// With `resume`: a new budget (`None` keeps the checkpoint's).
    pub resume_budget: Option<u64>,
    /// Set by Ctrl-C: the run stops cleanly, within one design's evaluation per thread,
    /// with the state of the last complete generation.
    pub stop: Arc<AtomicBool>,
    /// Stop after this many generations (for tests of interrupted runs).
    pub max_generations: Option<u64>,
    /// Told at once of a checkpoint write that failed, once while it fails the same way
    /// (the search goes on; every failure is also in the outcome): a front end prints it.
    pub on_checkpoint_failure: fn(&str),
}

/// A thread count given or, for `None`, one per core; checked as [`check_threads`] does.
pub fn threads_or_all(threads: Option<usize>) -> Result<usize> {
    check_threads(
        threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())),
    )
}

/// The interval between checkpoints unless the caller sets one (s).
pub const DEFAULT_CHECKPOINT_EVERY_S: f64 = 10.0;

impl RunOptions {
    /// A run on `threads` threads (`None`: every core), without checkpoints.
    pub fn new(threads: Option<usize>) -> Result<Self> {
        Ok(Self {
            threads: threads_or_all(threads)?,
            checkpoint: None,
            checkpoint_every: Duration::from_secs_f64(DEFAULT_CHECKPOINT_EVERY_S),
            resume: None,
            resume_budget: None,
            stop: Arc::new(AtomicBool::new(false)),
            max_generations: None,
            on_checkpoint_failure: |_| {},
        })
    }
}

/// A finished (or stopped) search.
pub struct Outcome {
    pub problem: SceneProblem,
    pub state: SearchState,
    pub budget: u64,
    pub seconds: f64,
    pub seconds_to_first_feasible: Option<f64>,
    pub threads: usize,
    pub stopped_early: bool,
    /// Checkpoint writes that failed (the search went on): say them to the user.
    pub checkpoint_failures: Vec<String>,
    /// The reported designs confirmed at the scene's resolution, once, when the run ended.
    pub confirmed: Confirmed,
}

/// The reported designs re-evaluated at the scene's own resolution. Each design is
/// evaluated once; the summary, the files, the figures and Python all read this.
pub struct Confirmed {
    /// The reported design (best confirmed-feasible, else best screened): its scene and its
    /// evaluation (`None` if it failed to evaluate at the scene's resolution).
    pub best: Option<(Scene, Option<Evaluation>)>,
    /// The reported design's parameter values, as `pareto` gives them (with `best`).
    pub best_values: Option<Vec<f64>>,
    /// The confirmed first front (multi-objective), else the best design; only those still
    /// feasible at the scene's resolution (or the best design if none is): parameter values
    /// and fitness.
    pub pareto: Vec<(Vec<f64>, Fitness)>,
}

impl Confirmed {
    /// Confirms the reported designs of `state` at the problem's base resolution.
    pub fn new(problem: &SceneProblem, state: &SearchState) -> Self {
        // Under `search.confirm_with_teeth`, the same problem with the module rule `teeth`.
        let with_teeth = problem.base().search.confirm_with_teeth.then(|| {
            let mut scene = problem.base().clone();
            scene.gear.module.rule = ModuleReading::Teeth;
            SceneProblem::new(&scene)
        });
        // (It cannot fail: only the rule changed, and `validate_search` saw the count.)
        let problem = match &with_teeth {
            Some(Ok(teeth)) => teeth,
            _ => problem,
        };
        let base = problem.base();
        let mut ev = Evaluator::new();
        let mut scratch = base.clone();
        let reported = state.reported();
        let several_goals = problem.goals() >= 2;
        let mut members: Vec<Candidate> = state.solver.front();
        if members.is_empty() {
            members.extend(reported.cloned());
        } else if let Some(r) =
            reported.filter(|r| several_goals && members.iter().all(|c| c.u != r.u))
        {
            // The run's best on the first goal joins the solver's last front (whose crowding
            // may have dropped it), so that the reported design is a member of the front.
            members.push(r.clone());
        }
        let mut best = None;
        let mut best_u = None;
        let mut confirmed = Vec::with_capacity(members.len());
        let mut evals = Vec::with_capacity(members.len());
        for c in &members {
            let (fitness, eval) = problem.fitness(&c.u, &mut ev, &mut scratch, &base.resolution);
            if !several_goals && best.is_none() && reported.is_some_and(|r| r.u == c.u) {
                best = Some((problem.scene_at(&c.u), eval.clone()));
                best_u = Some(c.u.clone());
            }
            confirmed.push((problem.decode(&c.u), fitness));
            evals.push(eval);
        }
        let feasible: Vec<usize> = (0..confirmed.len())
            .filter(|&i| confirmed[i].1.feasible())
            .collect();
        let mut pareto: Vec<usize> = if feasible.is_empty() {
            (0..confirmed.len().min(1)).collect()
        } else {
            // Confirmation moves the goals slightly: keep the non-dominated confirmed designs.
            let candidates: Vec<Candidate> = (feasible.iter())
                .map(|&i| Candidate {
                    u: confirmed[i].0.clone(),
                    fitness: confirmed[i].1.clone(),
                })
                .collect();
            let front = non_dominated_fronts(&candidates)
                .into_iter()
                .next()
                .unwrap_or_default();
            front.into_iter().map(|k| feasible[k]).collect()
        };
        // Sorted by the first goal's value (in its unit, ascending).
        let first = |i: &usize| problem.goal_values(&confirmed[*i].1.f)[0];
        pareto.sort_by(|a, b| first(a).total_cmp(&first(b)));
        if several_goals && !feasible.is_empty() {
            // Two goals or more: the reported design is the confirmed front's best on the
            // first goal (Deb's rule, as with one goal), printed and drawn as such.
            let top = (pareto.iter().copied())
                .min_by(|&a, &b| confirmed[a].1.f[0].total_cmp(&confirmed[b].1.f[0]));
            if let Some(i) = top {
                best = Some((problem.scene_at(&members[i].u), evals[i].take()));
                best_u = Some(members[i].u.clone());
            }
        }
        if let (None, Some(r)) = (&best, reported) {
            let (_, eval) = problem.fitness(&r.u, &mut ev, &mut scratch, &base.resolution);
            best = Some((problem.scene_at(&r.u), eval));
            best_u = Some(r.u.clone());
        }
        let pareto = pareto.into_iter().map(|i| confirmed[i].clone()).collect();
        Self {
            best,
            best_values: best_u.map(|u| problem.decode(&u)),
            pareto,
        }
    }
}

/// Reads and checks a checkpoint file.
pub fn read_checkpoint(path: &Path) -> Result<Checkpoint> {
    let bytes = read_limited(path, MAX_CHECKPOINT_BYTES)?;
    Checkpoint::from_json(&bytes).map_err(|source| Error::Content {
        path: path.into(),
        source,
    })
}

/// The `count` best members of the search in the checkpoint at `path`, to send to another
/// island of the same search (an island model's migration).
pub fn emigrants(path: &Path, count: usize) -> Result<noncirc_core::Migrants> {
    Ok(read_checkpoint(path)?.emigrants(count))
}

/// Takes `migrants` into the search in the checkpoint at `path`, in place of its worst
/// members, and writes the checkpoint back (atomically); a resumed search goes on with
/// them. Migrants of another scene's search are refused, naming both.
pub fn immigrate(path: &Path, migrants: &noncirc_core::Migrants) -> Result<()> {
    let mut checkpoint = read_checkpoint(path)?;
    checkpoint
        .immigrate(migrants)
        .map_err(|source| Error::Content {
            path: path.into(),
            source,
        })?;
    write_atomic(path, &checkpoint.to_json())
        .map_err(|e| Error::file("write the checkpoint", path, e))
}

/// Largest checkpoint read (bytes): a state of the largest accepted population.
pub const MAX_CHECKPOINT_BYTES: u64 = 1 << 30;

/// Refuses a checkpoint path that holds something other than a noncirc checkpoint (a
/// scene file, say), so that a typo never overwrites the user's work.
fn check_checkpoint_target(path: &Path) -> Result<()> {
    if !path.exists() {
        return Ok(());
    }
    let is_checkpoint = std::fs::metadata(path).is_ok_and(|m| m.is_file())
        && std::fs::read(path)
            .ok()
            .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
            .is_some_and(|v| v.get("format").is_some_and(|f| f == CHECKPOINT_FORMAT));
    if is_checkpoint {
        Ok(())
    } else {
        Err(Error::Input(format!(
            "--checkpoint {}: the file exists and is not a noncirc checkpoint; \
             refusing to overwrite it (choose another path)",
            path.display()
        )))
    }
}

/// The files a search writes into `--out` (a fit adds `fit.json`).
pub const OUTPUT_FILES: [&str; 6] = [
    "best.toml",
    "pareto.csv",
    "pareto.json",
    "history.csv",
    "summary.json",
    "fit.json",
];

/// Refuses an `--out` directory that holds files of [`OUTPUT_FILES`]' names which are not
/// noncirc's own outputs of the scene `scene` (any scene's on a resume, `None`): beside them
/// a `summary.json` of noncirc's for that scene. Checked before the search, so that
/// nothing is lost; `force` writes over them anyway.
pub fn check_out_dir(dir: &Path, scene: Option<&str>, force: bool) -> Result<()> {
    if force || !dir.exists() {
        return Ok(());
    }
    let refuse = |why: String| {
        Err(Error::Input(format!(
            "--out {}: {why}; refusing to overwrite it (choose another directory, or --force)",
            dir.display()
        )))
    };
    if !dir.is_dir() {
        return refuse("the path exists and is not a directory".into());
    }
    let present: Vec<&str> = (OUTPUT_FILES.iter().copied())
        .filter(|name| dir.join(name).exists())
        .collect();
    if present.is_empty() {
        return Ok(());
    }
    let summary = crate::files::read_limited(&dir.join("summary.json"), 1 << 26)
        .ok()
        .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
        .filter(|v| v.get("algorithm").is_some() && v.get("evaluations").is_some());
    let written_for = summary
        .as_ref()
        .and_then(|v| v.get("scene"))
        .and_then(|v| v.as_str());
    match (written_for, scene) {
        (None, _) => refuse(format!(
            "it holds {} without a noncirc summary.json beside them",
            present.join(", ")
        )),
        (Some(theirs), Some(ours)) if theirs != ours => refuse(format!(
            "it holds the outputs of a search of scene '{theirs}', not '{ours}'"
        )),
        _ => Ok(()),
    }
}

/// Runs (or resumes) a search on `scene` with the core's executor: the stop flag, the
/// generation limit, the timed checkpoints and the caller's `observers` (a progress bar, a
/// signal check) are its observers.
pub fn run(
    scene: &Scene,
    opts: &RunOptions,
    observers: &mut [&mut (dyn Observer + Send)],
) -> Result<Outcome> {
    if let Some(path) = &opts.checkpoint {
        check_checkpoint_target(path)?;
    }
    let (scene, budget, mut state) = match &opts.resume {
        Some(path) => {
            let cp = read_checkpoint(path)?;
            (cp.scene, opts.resume_budget.unwrap_or(cp.budget), cp.state)
        }
        None => {
            scene.validate_search()?;
            let problem = SceneProblem::new(scene)?;
            let state = SearchState::new(
                scene.search.algorithm,
                problem.dim(),
                problem.goals(),
                scene.search.population,
                scene.search.seed,
            );
            (scene.clone(), scene.search.budget, state)
        }
    };
    let problem = SceneProblem::new(&scene)?;
    if let Some(path) = &opts.checkpoint {
        // Written before the first evaluation: a path that cannot be written is said now,
        // not after the run, and a killed run leaves a state to resume.
        save_checkpoint(path, &problem, budget, &state).map_err(|e| {
            Error::Input(format!(
                "--checkpoint {}: cannot be written ({e}); choose a path in a directory \
                 that exists and can be written",
                path.display()
            ))
        })?;
    }
    let mut evaluator =
        ParallelEvaluator::new(&problem, opts.threads)?.stopped_by(opts.stop.clone());
    let start = Instant::now();
    let mut seconds_to_first = None;
    let mut first_feasible = |state: &SearchState, _: u64| {
        if seconds_to_first.is_none() && state.first_feasible_at.is_some() {
            seconds_to_first = Some(start.elapsed().as_secs_f64());
        }
        Control::Continue
    };
    let stop = &opts.stop;
    let mut interrupted = |_: &SearchState, _: u64| {
        if stop.load(Ordering::SeqCst) {
            Control::Stop
        } else {
            Control::Continue
        }
    };
    let mut generation_limit = stop_after_generations(opts.max_generations.unwrap_or(u64::MAX));
    let mut last_checkpoint = Instant::now();
    let mut failures = Vec::new();
    let mut checkpoints = |state: &SearchState, budget: u64| {
        if let Some(path) = &opts.checkpoint {
            if last_checkpoint.elapsed() >= opts.checkpoint_every {
                last_checkpoint = Instant::now();
                if let Err(e) = save_checkpoint(path, &problem, budget, state) {
                    tell_once(&mut failures, e.to_string(), opts.on_checkpoint_failure);
                }
            }
        }
        Control::Continue
    };
    // The whole search on a thread of the evaluator's pool (`on_pool`), observers too.
    let ending = evaluator.on_pool(|evaluator| {
        let mut all: Vec<&mut dyn Observer> = vec![
            &mut first_feasible,
            &mut interrupted,
            &mut generation_limit,
            &mut checkpoints,
        ];
        all.extend(observers.iter_mut().map(|o| &mut **o as &mut dyn Observer));
        execute(&mut state, evaluator, budget, &mut all)
    });
    if let Some(path) = &opts.checkpoint {
        if let Err(e) = save_checkpoint(path, &problem, budget, &state) {
            tell_once(&mut failures, e.to_string(), opts.on_checkpoint_failure);
        }
    }
    let confirmed = Confirmed::new(&problem, &state);
    Ok(Outcome {
        problem,
        state,
        budget,
        seconds: start.elapsed().as_secs_f64(),
        seconds_to_first_feasible: seconds_to_first,
        threads: opts.threads,
        stopped_early: ending == Ending::Stopped,
        checkpoint_failures: failures,
        confirmed,
    })
}

/// Keeps a failed checkpoint write in `failures` and tells `tell` of it unless the one
/// before failed the same way (a lost directory fails at every generation).
fn tell_once(failures: &mut Vec<String>, failure: String, tell: fn(&str)) {
    if failures.last() != Some(&failure) {
        tell(&failure);
    }
    failures.push(failure);
}

fn save_checkpoint(
    path: &Path,
    problem: &SceneProblem,
    budget: u64,
    state: &SearchState,
) -> Result<()> {
    write_atomic(path, &Checkpoint::new(problem, budget, state).to_json())
        .map_err(|e| Error::file("write the checkpoint", path, e))
}

/// A search goal in physical terms, and the reported design's value of it.
#[derive(Debug, Clone, Serialize)]
pub struct GoalReading {
    /// The quantity, named with its unit (`module_mm`).
    pub name: String,
    pub unit: &'static str,
    /// Whether the search made it larger.
    pub maximised: bool,
    /// The reported design's value, in `unit` (none if it could not be confirmed).
    pub value: Option<f64>,
}

/// A parameter map serialised in the scene's order ([`crate::report::keys_in_scene_order`]).
fn in_scene_order<S: serde::Serializer>(
    values: &BTreeMap<String, f64>,
    serializer: S,
) -> std::result::Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let keys = crate::report::keys_in_scene_order(values);
    let mut map = serializer.serialize_map(Some(keys.len()))?;
    for k in keys {
        map.serialize_entry(k, &values[k])?;
    }
    map.end()
}

/// The summary `--format json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub scene: String,
    pub algorithm: &'static str,
    pub seed: u64,
    pub threads: usize,
    /// Whether the reported design meets every objective and search constraint at the
    /// scene's (default) resolution.
    pub feasible: bool,
    /// The reported design's parameters, written in the scene's order (`radii_mm[2]` before
    /// `radii_mm[10]`, the curve before the train).
    #[serde(serialize_with = "in_scene_order")]
    pub best: BTreeMap<String, f64>,
    pub violations: BTreeMap<String, f64>,
    pub objectives: BTreeMap<String, f64>,
    /// The reported design's search constraints (`search.constraints`), in the scene's order.
    pub constraints: Vec<RequirementRow>,
    pub evaluations: u64,
    pub confirmations: u64,
    pub first_feasible_evaluations: Option<u64>,
    pub seconds: f64,
    pub seconds_to_first_feasible: Option<f64>,
    pub screening_samples_per_turn: usize,
    pub confirming_samples_per_turn: usize,
    pub stopped_early: bool,
    /// The goals, in physical terms.
    pub goals: Vec<GoalReading>,
    /// Whether the scene has search constraints (known even when no design was read).
    #[serde(skip)]
    pub constrained: bool,
}

impl Summary {
    /// The objectives the reported design misses, in the paper's order, then the search
    /// constraints it misses, as written.
    pub fn missed(&self) -> Vec<String> {
        let objectives = (noncirc_core::ObjectiveKind::ALL.iter())
            .map(|k| k.name())
            .filter(|name| self.violations.get(*name).is_some_and(|&v| v > 0.0))
            .map(String::from);
        let constraints = (self.constraints.iter())
            .filter(|c| c.violation != 0.0)
            .map(|c| c.label.clone());
        objectives.chain(constraints).collect()
    }

    /// What a feasible design meets: "every objective", and "and search constraint" when
    /// the scene has some (said even when the model refused every design, which leaves no
    /// constraint reading).
    pub fn requirements(&self) -> &'static str {
        noncirc_core::requirements(self.constrained)
    }

    /// The summary of a search's `state` on `problem`, with its `confirmed` designs; the
    /// front end that ran it gives the threads, times and whether it stopped early.
    pub fn new(
        problem: &SceneProblem,
        state: &SearchState,
        confirmed: &Confirmed,
        threads: usize,
        seconds: f64,
        seconds_to_first_feasible: Option<f64>,
        stopped_early: bool,
    ) -> Self {
        let base = problem.base();
        let mut best = BTreeMap::new();
        let mut violations = BTreeMap::new();
        let mut objectives = BTreeMap::new();
        let mut constraints = Vec::new();
        let mut feasible = false;
        // The confirmed reported design: with several goals, the confirmed front's best on
        // the first goal, which need not be the solver's (confirmation moves the goals).
        if let Some(values) = &confirmed.best_values {
            for (name, &x) in problem.names().iter().zip(values) {
                best.insert(name.to_string(), x);
            }
        }
        let mut goal_values = vec![None; problem.goals()];
        if let Some((scene, Some(eval))) = &confirmed.best {
            goal_values = (problem.goal_values_of(eval, scene).into_iter())
                .map(|v| v.is_finite().then_some(v))
                .collect();
            feasible = eval.total_violation() == 0.0;
            for o in &eval.objectives {
                violations.insert(o.kind.name().to_string(), o.violation);
                objectives.insert(o.kind.name().to_string(), o.value);
            }
            constraints = eval.constraints.iter().map(RequirementRow::from).collect();
        }
        Summary {
            scene: base.name.clone(),
            algorithm: state.algorithm.name(),
            seed: base.search.seed,
            threads,
            feasible,
            best,
            violations,
            objectives,
            constraints,
            evaluations: state.evaluations,
            confirmations: state.confirmations,
            first_feasible_evaluations: state.first_feasible_at,
            seconds,
            seconds_to_first_feasible,
            screening_samples_per_turn: problem.screening().samples_per_turn,
            confirming_samples_per_turn: base.resolution.samples_per_turn,
            stopped_early,
            goals: (problem.goal_quantities().into_iter())
                .zip(goal_values)
                .map(|(q, value)| GoalReading {
                    name: q.name,
                    unit: q.unit,
                    maximised: q.maximised,
                    value,
                })
                .collect(),
            constrained: !base.search.constraints.is_empty(),
        }
    }
}

/// The reported design's scene as `best.toml` holds it: named `<scene>-best`, with the
/// search's space and settings kept, so that it evaluates as the design and searches again
/// (`noncirc optimise best.toml`) over the same space.
pub fn best_scene(problem: &SceneProblem, confirmed: &Confirmed) -> Option<Scene> {
    let (scene, _) = confirmed.best.as_ref()?;
    let mut scene = scene.clone();
    scene.name = format!("{}-best", problem.base().name);
    Some(scene)
}

impl Outcome {
    /// Summary with the reported design confirmed at the scene's resolution.
    pub fn summary(&self) -> Summary {
        Summary::new(
            &self.problem,
            &self.state,
            &self.confirmed,
            self.threads,
            self.seconds,
            self.seconds_to_first_feasible,
            self.stopped_early,
        )
    }

    /// Writes best.toml, pareto.csv/json, history.csv and summary.json into `dir`.
    pub fn write(&self, dir: &Path) -> Result<()> {
        create_dir(dir)?;
        if let Some(scene) = best_scene(&self.problem, &self.confirmed) {
            write_file(
                &dir.join("best.toml"),
                toml_text(&scene, "the best scene")?.as_bytes(),
            )?;
        }
        let names = self.problem.names();
        let pareto = &self.confirmed.pareto;
        let mut csv = names.join(",");
        // Goals as the quantities they are, in their units (`module_mm`,
        // `picking_tip_speed_m_s`); which way each was optimised is in docs/search.md and
        // summary.json's `goals`.
        let quantities = self.problem.goal_quantities();
        for q in &quantities {
            csv += &format!(",{}", q.name);
        }
        csv += ",cv\n";
        for (x, f) in pareto {
            let row: Vec<String> = x
                .iter()
                .chain(&self.problem.goal_values(&f.f))
                .chain(std::iter::once(&f.cv))
                .map(|v| v.to_string())
                .collect();
            csv += &(row.join(",") + "\n");
        }
        write_file(&dir.join("pareto.csv"), csv.as_bytes())?;
        let json: Vec<_> = pareto
            .iter()
            .map(|(x, f)| {
                serde_json::json!({
                    "parameters": names.iter().zip(x).map(|(n, v)| (n.to_string(), *v)).collect::<BTreeMap<_, _>>(),
                    "goals": quantities.iter().map(|q| q.name.clone())
                        .zip(self.problem.goal_values(&f.f)).collect::<BTreeMap<_, _>>(),
                    "cv": f.cv,
                })
            })
            .collect();
        write_file(
            &dir.join("pareto.json"),
            json_text(&json, "the Pareto set")?.as_bytes(),
        )?;
        let mut hist =
            String::from("generation,evaluations,best_cv,best_goal,feasible_in_generation\n");
        for h in &self.state.history {
            hist += &format!(
                "{},{},{},{},{}\n",
                h.generation, h.evaluations, h.best_cv, h.best_goal, h.feasible_in_generation
            );
        }
        write_file(&dir.join("history.csv"), hist.as_bytes())?;
        write_file(
            &dir.join("summary.json"),
            json_text(&self.summary(), "the summary")?.as_bytes(),
        )?;
        Ok(())
    }
}
