//! Searches from Python: `optimise` with its progress callback, Ctrl-C and checkpoints
//! (an observer of the core's executor), and the island model's migrants.

use crate::convert::summary_dict;
use crate::errors::{internal, invalid, parameter, warn, Result};
use crate::scene::Scene;
use crate::signals::watched;
use noncirc::core::{Algorithm, Control, Observer, SearchState};
use noncirc::search::{RunOptions, SearchSettings};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// The Python side of a search, an observer of the core's executor: after every
/// generation it takes the GIL for a moment to call the progress callback, which may stop
/// the search cleanly (the checkpoint, if asked, is written); its error is raised once the
/// search has stopped. Ctrl-C is watched by [`observed`].
struct PythonObserver {
    progress: Option<PyObject>,
    error: Option<PyErr>,
}

impl Observer for PythonObserver {
    fn poll(&mut self, state: &SearchState, budget: u64) -> Control {
        Python::with_gil(|py| {
            // The callback first, so that it sees the state the search stops in.
            let progress = || -> PyResult<bool> {
                let Some(callback) = &self.progress else {
                    return Ok(true);
                };
                let info = PyDict::new(py);
                info.set_item("generation", state.generation)?;
                info.set_item("evaluations", state.evaluations)?;
                info.set_item("budget", budget)?;
                info.set_item("best_violation", state.best.as_ref().map(|b| b.fitness.cv))?;
                info.set_item("feasible", state.best_confirmed.is_some())?;
                // Returning False stops the search; None or anything else goes on.
                let answer = callback.call1(py, (info,))?;
                let stop =
                    (answer.bind(py).downcast::<pyo3::types::PyBool>()).is_ok_and(|b| !b.is_true());
                Ok(!stop)
            };
            match progress() {
                Ok(true) => Control::Continue,
                Ok(false) => Control::Stop,
                Err(e) => {
                    self.error = Some(e);
                    Control::Stop
                }
            }
        })
    }
}

/// Runs `work` with a [`PythonObserver`] calling `progress`, watched for Ctrl-C
/// ([`watched`]): a signal sets `stop`, and the search abandons the generation in flight
/// and keeps the last complete one. The callback's error, or Ctrl-C's `KeyboardInterrupt`,
/// is raised once the work has stopped.
fn observed<T: Send>(
    py: Python<'_>,
    progress: Option<PyObject>,
    stop: &std::sync::atomic::AtomicBool,
    work: impl FnOnce(&mut PythonObserver) -> noncirc::Result<T> + Send,
) -> Result<T> {
    let mut observer = PythonObserver {
        progress,
        error: None,
    };
    let watching = &mut observer;
    let (outcome, interrupt) = watched(py, stop, move || work(watching));
    let outcome = outcome?;
    match interrupt.or(observer.error) {
        Some(e) => Err(e.into()),
        None => Ok(outcome),
    }
}

/// The search settings a call's keywords give (the algorithm by name).
fn search_settings(
    algorithm: Option<&str>,
    budget: Option<u64>,
    population: Option<usize>,
    seed: Option<u64>,
) -> Result<SearchSettings> {
    Ok(SearchSettings {
        algorithm: algorithm
            .map(Algorithm::parse)
            .transpose()
            .map_err(noncirc::core::Error::from)?,
        budget,
        population,
        seed,
        screening_samples_per_turn: None,
    })
}

/// Runs a search (GIL released) and returns its summary and confirmed Pareto set.
/// `progress(info)` is called after every generation (return False to stop); Ctrl-C stops
/// the search at once, keeping the last complete generation, and raises
/// `KeyboardInterrupt`. With
/// `checkpoint`, the state is written there every `checkpoint_every` seconds and at the
/// end; `resume` continues a checkpoint (its scene and settings; `budget` may be raised).
#[pyfunction]
#[pyo3(signature = (scene = None, *, algorithm = None, seed = None, budget = None, population = None, threads = None, screening_samples_per_turn = None, progress = None, checkpoint = None, checkpoint_every = 10.0, resume = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn optimise<'py>(
    py: Python<'py>,
    scene: Option<&Scene>,
    algorithm: Option<&str>,
    seed: Option<u64>,
    budget: Option<u64>,
    population: Option<usize>,
    threads: Option<usize>,
    screening_samples_per_turn: Option<usize>,
    progress: Option<PyObject>,
    checkpoint: Option<std::path::PathBuf>,
    checkpoint_every: f64,
    resume: Option<std::path::PathBuf>,
) -> Result<Bound<'py, PyDict>> {
    let settings = search_settings(algorithm, budget, population, seed)?;
    let settings = SearchSettings {
        screening_samples_per_turn,
        ..settings
    };
    let s =
        match (scene, &resume) {
            (Some(scene), None) => {
                let mut s = scene.inner.clone();
                // The keywords override the scene's search settings, so the summary states
                // what ran.
                settings.apply(&mut s)?;
                s
            }
            // The checkpoint holds the scene; this one is not used.
            (None, Some(_)) if settings.ignored_by_resume().is_empty() => {
                noncirc::core::Scene::default()
            }
            (None, Some(_)) => {
                return Err(invalid(format!(
                    "resume continues the checkpoint's own scene and search; {} would be ignored \
                 (only budget, threads, progress and the checkpoint options apply)",
                    settings.ignored_by_resume().join(", ")
                )))
            }
            (Some(_), Some(_)) => return Err(invalid(
                "give a scene or resume=, not both: a resumed search uses the checkpoint's scene",
            )),
            (None, None) => return Err(invalid("optimise needs a scene, or resume= a checkpoint")),
        };
    let opts = RunOptions {
        checkpoint,
        checkpoint_every: noncirc::search::checkpoint_interval(checkpoint_every)?,
        resume_budget: resume.as_ref().and(budget),
        resume,
        ..RunOptions::new(threads)?
    };
    let outcome = observed(py, progress, &opts.stop, |observer| {
        noncirc::search::run(&s, &opts, &mut [observer])
    })?;
    let mut failures = outcome.checkpoint_failures.clone();
    failures.dedup();
    for failure in &failures {
        warn(
            py,
            format!("noncirc.optimise: {failure} (the search went on)"),
            2,
        )?;
    }
    let summary = outcome.summary();
    if !summary.feasible {
        // Said, not only flagged: a run that found nothing must not pass for a result.
        let missed = summary.missed();
        let message = format!(
            "noncirc.optimise: no design found meets {} (the best misses {}); a larger \
             budget, another seed or algorithm='de'|'cmaes' may find one",
            summary.requirements(),
            if missed.is_empty() {
                "all: the model refused it".to_string()
            } else {
                missed.join(", ")
            }
        );
        warn(py, message, 2)?;
    }
    let out = summary_dict(py, &summary)?;
    let names = outcome.problem.names();
    out.set_item("parameter_names", &names)?;
    out.set_item(
        "goal_names",
        (outcome.problem.goal_quantities().into_iter())
            .map(|q| q.name)
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "objective_names",
        (outcome.problem.base().objectives.iter())
            .map(|o| o.name())
            .collect::<Vec<_>>(),
    )?;
    let front = PyList::empty(py);
    for (x, f) in &outcome.confirmed.pareto {
        let d = PyDict::new(py);
        let params = PyDict::new(py);
        for (n, v) in names.iter().zip(x) {
            params.set_item(*n, *v)?;
        }
        d.set_item("parameters", params)?;
        d.set_item("goals", f.f.clone())?;
        d.set_item("goal_values", outcome.problem.goal_values(&f.f))?;
        d.set_item("cv", f.cv)?;
        front.append(d)?;
    }
    out.set_item("pareto", front)?;
    if let Some((best, _)) = &outcome.confirmed.best {
        out.set_item(
            "best_scene",
            Scene {
                inner: best.clone(),
            },
        )?;
    }
    Ok(out)
}

/// Fits a design to a target (GIL released): the scene's search with the goal `fit`, then
/// Levenberg–Marquardt. `target` is a file (CSV of `x_mm,y_mm`, or TOML with a `[target]`
/// table) replacing the scene's own `[target]`; `tolerance_mm` sets the path's tolerance.
/// Progress, Ctrl-C, checkpoints and resume as for `optimise`. Returns the fit's summary
/// (`noncirc fit --format json`) and `best_scene`.
#[pyfunction]
#[pyo3(signature = (scene = None, *, target = None, tolerance_mm = None, algorithm = None, seed = None, budget = None, population = None, threads = None, progress = None, checkpoint = None, checkpoint_every = 10.0, resume = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit<'py>(
    py: Python<'py>,
    scene: Option<&Scene>,
    target: Option<std::path::PathBuf>,
    tolerance_mm: Option<f64>,
    algorithm: Option<&str>,
    seed: Option<u64>,
    budget: Option<u64>,
    population: Option<usize>,
    threads: Option<usize>,
    progress: Option<PyObject>,
    checkpoint: Option<std::path::PathBuf>,
    checkpoint_every: f64,
    resume: Option<std::path::PathBuf>,
) -> Result<Bound<'py, PyDict>> {
    let settings = search_settings(algorithm, budget, population, seed)?;
    let mut s = match (scene, &resume) {
        (Some(scene), None) => {
            let mut s = scene.inner.clone();
            settings.apply(&mut s)?;
            s
        }
        (None, Some(_))
            if settings.ignored_by_resume().is_empty()
                && target.is_none()
                && tolerance_mm.is_none() =>
        {
            noncirc::core::Scene::default()
        }
        (None, Some(_)) => {
            return Err(invalid(
                "resume continues the checkpoint's own scene, target and search; only budget, \
                 threads, progress and the checkpoint options apply",
            ))
        }
        (Some(_), Some(_)) => {
            return Err(invalid(
                "give a scene or resume=, not both: a resumed fit uses the checkpoint's scene",
            ))
        }
        (None, None) => return Err(invalid("fit needs a scene, or resume= a checkpoint")),
    };
    if let Some(path) = &target {
        s = noncirc::fit::with_target(s, noncirc::fit::read_target(path)?);
    }
    if let Some(tolerance) = tolerance_mm {
        let t = s.target.as_mut().ok_or_else(|| {
            parameter("tolerance_mm sets the target path's tolerance: the scene has no target")
        })?;
        std::sync::Arc::make_mut(t).tolerance_mm = tolerance;
        t.validate()?;
    }
    let run = RunOptions {
        checkpoint,
        checkpoint_every: noncirc::search::checkpoint_interval(checkpoint_every)?,
        resume_budget: resume.as_ref().and(budget),
        resume,
        ..RunOptions::new(threads)?
    };
    let options = noncirc::fit::FitOptions {
        run,
        local: noncirc::core::LocalSettings::default(),
    };
    let outcome = observed(py, progress, &options.run.stop, |observer| {
        noncirc::fit::fit_scene(&s, &options, &mut [observer])
    })?;
    let summary = outcome.summary();
    let out = summary_dict(py, &summary)?;
    if let Some((best, _)) = &outcome.best {
        out.set_item(
            "best_scene",
            Scene {
                inner: best.clone(),
            },
        )?;
    }
    Ok(out)
}

/// Repairs the scene's design (GIL released; `noncirc repair`): the design nearest it that
/// meets every objective and whose teeth cut and mesh. `path_tolerance_mm` and
/// `design_scale` weigh the tip path against the parameters. Progress and Ctrl-C as for
/// `optimise`. Returns the summary (`noncirc repair --format json`) and `repaired_scene`.
#[pyfunction]
#[pyo3(signature = (scene, *, path_tolerance_mm = noncirc::repair::RepairOptions::PATH_TOLERANCE_MM, design_scale = noncirc::repair::RepairOptions::DESIGN_SCALE, algorithm = None, seed = None, budget = None, population = None, threads = None, progress = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn repair<'py>(
    py: Python<'py>,
    scene: &Scene,
    path_tolerance_mm: f64,
    design_scale: f64,
    algorithm: Option<&str>,
    seed: Option<u64>,
    budget: Option<u64>,
    population: Option<usize>,
    threads: Option<usize>,
    progress: Option<PyObject>,
) -> Result<Bound<'py, PyDict>> {
    let mut s = scene.inner.clone();
    search_settings(algorithm, budget, population, seed)?.apply(&mut s)?;
    let options = noncirc::repair::RepairOptions {
        path_tolerance_mm,
        design_scale,
        ..noncirc::repair::RepairOptions::new(RunOptions::new(threads)?)
    };
    let outcome = observed(py, progress, &options.fit.run.stop, |observer| {
        noncirc::repair::repair_scene(&s, &options, &mut [observer])
    })?;
    let out = summary_dict(py, &outcome.summary())?;
    if let Some(r) = &outcome.repaired {
        out.set_item(
            "repaired_scene",
            Scene {
                inner: r.scene.clone(),
            },
        )?;
    }
    Ok(out)
}

/// The `count` best members of the search in the checkpoint file `checkpoint`, as JSON
/// text, to send to another island of the same search (`noncirc.dask.islands`).
#[pyfunction]
pub(crate) fn emigrants(checkpoint: std::path::PathBuf, count: usize) -> Result<String> {
    let migrants = noncirc::search::emigrants(&checkpoint, count)?;
    serde_json::to_string(&migrants).map_err(internal)
}

/// Takes `migrants` (the JSON text of `emigrants` from another island of the same search)
/// into the search in the checkpoint file `checkpoint`, in place of its worst members; a
/// search resumed from it goes on with them.
#[pyfunction]
pub(crate) fn immigrate(checkpoint: std::path::PathBuf, migrants: &str) -> Result<()> {
    let migrants: noncirc::core::Migrants = serde_json::from_str(migrants)
        .map_err(|e| parameter(format!("migrants: not the text of emigrants(): {e}")))?;
    Ok(noncirc::search::immigrate(&checkpoint, &migrants)?)
}

/// The train with two pairs from a target (`noncirc inverse`): the summary
/// (`noncirc inverse --format json`) and `scene`, the design, when one was built.
#[pyfunction]
#[pyo3(signature = (scene = None, *, target = None, split = "equal", centre_ratio = None, branch = None, samples_per_turn = 720))]
pub(crate) fn inverse<'py>(
    py: Python<'py>,
    scene: Option<&Scene>,
    target: Option<std::path::PathBuf>,
    split: &str,
    centre_ratio: Option<f64>,
    branch: Option<&str>,
    samples_per_turn: usize,
) -> Result<Bound<'py, PyDict>> {
    let s = match scene {
        Some(scene) => scene.inner.clone(),
        None => noncirc::scene_file::load_scene_with(Some("paper"), &[])?,
    };
    let target = match (&target, &s.target) {
        (Some(path), _) => noncirc::fit::read_target(path)?,
        (None, Some(t)) => (**t).clone(),
        (None, None) => {
            return Err(parameter(
                "inverse needs a target: target= a file, or a scene with a [target]",
            ))
        }
    };
    let split = noncirc::inverse::parse_split(split).map_err(parameter)?;
    let branch = match branch {
        None => None,
        Some("plus") => Some(noncirc::core::Branch::Plus),
        Some("minus") => Some(noncirc::core::Branch::Minus),
        Some(other) => {
            return Err(parameter(format!(
                "branch={other:?}: expected \"plus\", \"minus\" or None (both tried)"
            )))
        }
    };
    let outcome = py.allow_threads(|| {
        noncirc::inverse::inverse_scene(&s, &target, centre_ratio, split, branch, samples_per_turn)
    })?;
    let summary = noncirc::inverse::summary(&outcome, split);
    let out = summary_dict(py, &summary)?;
    if let Some(design) = &outcome.scene {
        out.set_item(
            "scene",
            Scene {
                inner: design.clone(),
            },
        )?;
    }
    Ok(out)
}
