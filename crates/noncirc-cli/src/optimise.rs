//! `noncirc optimise`: the search with its progress bar, signals, checkpoints and outputs.

use crate::args::{Format, OptimiseArgs};
use crate::output::{json, out, out_interrupted};
use crate::Finished;
use noncirc::core::{Control, Observer, Scene, SearchState};
use noncirc::scene_file::load_scene_with;
use noncirc::search::{RunOptions, SearchSettings};
use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// The search's progress bar (indicatif), an observer of the core's executor.
pub(crate) struct ProgressBar {
    pub(crate) bar: Option<indicatif::ProgressBar>,
    show: bool,
}

impl Observer for ProgressBar {
    fn poll(&mut self, state: &SearchState, budget: u64) -> Control {
        if !self.show {
            return Control::Continue;
        }
        let bar = self.bar.get_or_insert_with(|| {
            let bar = indicatif::ProgressBar::new(budget);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:30} {pos}/{len} evals  {rate}  eta {eta}  {msg}",
                )
                .expect("valid template")
                // Whole designs per second (indicatif's own `per_sec` prints 4 decimals).
                .with_key(
                    "rate",
                    |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                        let _ = write!(w, "{:.0}/s", state.per_sec());
                    },
                ),
            );
            bar
        });
        bar.set_position(state.evaluations.min(budget));
        let best = state.best.as_ref().map_or(f64::INFINITY, |b| b.fitness.cv);
        let feasible = if state.best_confirmed.is_some() {
            "yes"
        } else {
            "not yet"
        };
        bar.set_message(format!("best violation {best:.4}  feasible {feasible}"));
        Control::Continue
    }
}

/// A search as the flags ask for it.
pub(crate) struct PreparedSearch {
    /// The scene with the flags' settings.
    pub(crate) scene: Scene,
    pub(crate) opts: RunOptions,
    /// Set by SIGINT, SIGTERM and SIGHUP.
    pub(crate) stop: Arc<AtomicBool>,
    pub(crate) progress: ProgressBar,
}

/// The search the flags ask for on their scene (`default` without one). A resume refuses
/// the flags it would ignore.
pub(crate) fn prepare_search(
    args: &OptimiseArgs,
    default: &str,
) -> Result<PreparedSearch, Box<dyn std::error::Error>> {
    let settings = SearchSettings {
        algorithm: args.algorithm,
        budget: args.budget,
        population: args.population,
        seed: args.seed,
        screening_samples_per_turn: None,
    };
    if args.resume.is_some() {
        // The checkpoint carries the scene and the search settings: a flag that would
        // change them is refused rather than silently ignored.
        let mut ignored: Vec<String> = [
            ("a scene argument", args.scene.input.scene.is_some()),
            ("--set", !args.scene.input.set.is_empty()),
        ]
        .into_iter()
        .filter(|&(_, given)| given)
        .map(|(name, _)| name.to_string())
        .collect();
        ignored.extend(
            settings
                .ignored_by_resume()
                .iter()
                .map(|n| format!("--{n}")),
        );
        if !ignored.is_empty() {
            return Err(noncirc::Error::Input(format!(
                "--resume continues the checkpoint's own scene and search; {} would be \
                 ignored (only --budget, --threads and the output options apply to a resume)",
                ignored.join(", ")
            ))
            .into());
        }
    }
    let name = args.scene.input.scene.as_deref().unwrap_or(default);
    let mut scene = load_scene_with(Some(name), &args.scene.input.set)?;
    settings.apply(&mut scene)?;
    let checkpoint_every = noncirc::search::checkpoint_interval(args.checkpoint_every)?;
    // SIGINT, SIGTERM and SIGHUP all stop the search at once, keeping the last complete
    // generation (its results are written); a second signal ends the process at once.
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            // A failed write to standard error must not keep the process alive.
            let _ = writeln!(
                std::io::stderr(),
                "second signal: exiting now (the last checkpoint written is kept)"
            );
            std::process::exit(crate::EXIT_INTERRUPTED.into());
        }
    })?;
    let opts = RunOptions {
        checkpoint: args.checkpoint.clone(),
        checkpoint_every,
        resume: args.resume.clone(),
        resume_budget: args.budget,
        stop: stop.clone(),
        on_checkpoint_failure: |failure| say!("warning: {failure} (the search goes on)"),
        ..RunOptions::new(args.threads)?
    };
    let progress = ProgressBar {
        bar: None,
        show: !args.quiet && args.scene.format == Format::Table,
    };
    Ok(PreparedSearch {
        scene,
        opts,
        stop,
        progress,
    })
}

/// Search the scene's design space; a signal stops it at once, keeping the last complete
/// generation, with its results written.
pub(crate) fn optimise(args: OptimiseArgs) -> Result<Finished, Box<dyn std::error::Error>> {
    let PreparedSearch {
        scene,
        opts,
        stop,
        mut progress,
    } = prepare_search(&args, "paper-search")?;
    if let Some(dir) = &args.out {
        let name = args.resume.is_none().then_some(scene.name.as_str());
        noncirc::search::check_out_dir(dir, name, args.force)?;
    }
    let outcome = noncirc::search::run(&scene, &opts, &mut [&mut progress])?;
    if let Some(bar) = progress.bar {
        bar.finish_and_clear();
    }
    if let Some(dir) = &args.out {
        outcome.write(dir)?;
    }
    if let Some(dir) = &args.scene.plot {
        for f in noncirc::plots::search_figures(&outcome, dir, &args.scene.figures()?)? {
            say!("wrote {}", f.display());
        }
    }
    let summary = outcome.summary();
    noncirc::report::check_finite(&summary)?;
    let text = match args.scene.format {
        Format::Json => json(&summary)?,
        Format::Table => noncirc::report::summary_table(&summary),
    };
    if stop.load(Ordering::SeqCst) {
        out_interrupted(&text)?;
        say!("interrupted: the results so far are above (and in the checkpoint and --out)");
        return Ok(Finished::Interrupted);
    }
    out(&text)?;
    Ok(Finished::Completed)
}
