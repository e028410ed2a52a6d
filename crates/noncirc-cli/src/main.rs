//! The `noncirc` command line.

use clap::{Parser, Subcommand, ValueEnum};
use noncirc::core::Algorithm;
use noncirc::core::Measure;
use noncirc::core::SceneKind;
use noncirc::core::SearchState;
use noncirc::core::{Control, Observer};
use noncirc::report::{EvaluationReport, GearReport};
use noncirc::scene_file::{load_scene_with, BUILTIN};
use noncirc::search::{RunOptions, SearchSettings};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

mod studio;

#[derive(Parser)]
#[command(
    name = "noncirc",
    version,
    about = "Design-space optimiser for rice-transplanting mechanisms driven by non-circular gears"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Format {
    Table,
    Json,
}

/// The scene a command reads.
#[derive(clap::Args)]
struct SceneSource {
    /// Scene file (TOML or JSON) or built-in scene name (`noncirc scenes`); default: the
    /// command's own (see its description; the three-arm paper's design for most).
    scene: Option<String>,
    /// Override any scene parameter, e.g. `--set resolution.samples_per_turn=720`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

/// Options shared by every command that reads a scene and reports on it.
#[derive(clap::Args)]
struct SceneArgs {
    #[command(flatten)]
    input: SceneSource,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    format: Format,
    /// Write figures (SVG and PNG) and CSV exports into this directory.
    #[arg(long, value_name = "DIR")]
    plot: Option<std::path::PathBuf>,
    /// Figure formats written by --plot (comma-separated): svg, png, pdf (vector with the
    /// font embedded, for a paper).
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = [FigureFormatArg::Svg, FigureFormatArg::Png])]
    figure_format: Vec<FigureFormatArg>,
    /// Figure size WIDTHxHEIGHT in CSS pixels (96 to the inch), e.g. 640x480; default:
    /// each figure's own. Text keeps its size, so a smaller figure reads larger.
    #[arg(long, value_name = "WxH")]
    figure_size: Option<String>,
    /// Resolution of the PNG figures (dots per inch; 300 for print).
    #[arg(long, default_value_t = 96)]
    dpi: u32,
}

/// A figure format (`--figure-format`).
#[derive(Clone, Copy, clap::ValueEnum)]
enum FigureFormatArg {
    Svg,
    Png,
    Pdf,
}

impl SceneArgs {
    /// The figure options asked for, checked.
    fn figures(&self) -> Result<noncirc::figures::FigureOptions, Box<dyn std::error::Error>> {
        use noncirc::figures::FigureFormat;
        let size_px = match &self.figure_size {
            None => None,
            Some(text) => {
                let parsed = text
                    .split_once(['x', 'X'])
                    .and_then(|(w, h)| Some((w.trim().parse().ok()?, h.trim().parse().ok()?)));
                Some(parsed.ok_or_else(|| {
                    noncirc::Error::Input(format!(
                        "--figure-size '{text}': expected WIDTHxHEIGHT in pixels, e.g. 640x480"
                    ))
                })?)
            }
        };
        let options = noncirc::figures::FigureOptions {
            formats: (self.figure_format.iter())
                .map(|f| match f {
                    FigureFormatArg::Svg => FigureFormat::Svg,
                    FigureFormatArg::Png => FigureFormat::Png,
                    FigureFormatArg::Pdf => FigureFormat::Pdf,
                })
                .collect(),
            size_px,
            dpi: self.dpi,
        };
        options.validate()?;
        Ok(options)
    }
}

#[derive(clap::Args)]
struct OptimiseArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Algorithm: guided, de, cmaes, nsga2 or nsga3 (default: the scene's, `de`).
    #[arg(long)]
    algorithm: Option<Algorithm>,
    /// Evaluation budget (default: the scene's).
    #[arg(long)]
    budget: Option<u64>,
    /// Population size (default: the scene's).
    #[arg(long)]
    population: Option<usize>,
    /// Random seed (default: the scene's).
    #[arg(long)]
    seed: Option<u64>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Write a checkpoint to this file at intervals and at the end.
    #[arg(long, value_name = "FILE")]
    checkpoint: Option<std::path::PathBuf>,
    /// Seconds between checkpoints.
    #[arg(long, default_value_t = noncirc::search::DEFAULT_CHECKPOINT_EVERY_S)]
    checkpoint_every: f64,
    /// Resume from a checkpoint file (its scene and settings are used).
    #[arg(long, value_name = "FILE")]
    resume: Option<std::path::PathBuf>,
    /// Write best.toml, pareto.csv/json, history.csv and summary.json here.
    #[arg(long, value_name = "DIR")]
    out: Option<std::path::PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(clap::Args)]
struct GearArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Export the pitch curves (CSV, SVG, DXF in mm) into this directory.
    #[arg(long, value_name = "DIR")]
    export: Option<std::path::PathBuf>,
}

#[derive(clap::Args)]
struct TeethArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Export DXF (lines and arcs, mm), SVG and CSV of each gear and of the assembled
    /// train into this directory.
    #[arg(long, value_name = "DIR")]
    export: Option<std::path::PathBuf>,
    /// Carrier angle of the assembled train (degrees).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    carrier_deg: f64,
    /// Largest distance of the exported lines and arcs from the computed outline (mm).
    #[arg(long, default_value_t = 1e-3)]
    tolerance_mm: f64,
}

#[derive(clap::Args)]
struct AnimateArgs {
    #[command(flatten)]
    scene: SceneSource,
    /// The GIF to write.
    #[arg(long, value_name = "FILE.gif")]
    out: std::path::PathBuf,
    /// Frames per carrier turn.
    #[arg(long, default_value_t = 72)]
    frames: usize,
    /// Draw the gears' teeth (`noncirc teeth`'s, with the scene's tooth count).
    #[arg(long)]
    teeth: bool,
}

#[derive(clap::Args)]
struct SweepArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Parameter path, e.g. `gear.curve.radii_mm[0]` or `train.phi0_deg`.
    #[arg(long)]
    param: String,
    /// First value of the parameter (negative values are values: `--from -60`).
    #[arg(long, allow_negative_numbers = true)]
    from: f64,
    /// Last value of the parameter.
    #[arg(long, allow_negative_numbers = true)]
    to: f64,
    #[arg(long, default_value_t = 11)]
    steps: usize,
    /// A measure to report beside the objectives (repeatable), e.g. `loop_height_mm`;
    /// `noncirc measures` lists them.
    #[arg(long = "measure")]
    measures: Vec<String>,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a non-circular gear pair: centre distance, perimeter, ratio, largest module.
    Gear(GearArgs),
    /// Animate the mechanism turning (GIF).
    Animate(AnimateArgs),
    /// Evaluate a three-arm design: trajectory, events and the eight agronomic objectives.
    Evaluate(SceneArgs),
    /// The variable-speed moving box: box travel while picking, speeds, forces.
    /// With no scene: the moving-box paper's setting.
    Box(SceneArgs),
    /// Measure each output's error and the time per evaluation over a resolution ladder.
    Accuracy(SceneArgs),
    /// Search the scene's design space for designs that meet every objective.
    /// With no scene: the built-in `paper-search` scene.
    Optimise(OptimiseArgs),
    /// The response of every objective to one parameter (three-arm paper §4.2).
    Sweep(SweepArgs),
    /// Cut teeth on the scene's gears (every gear of the train), check them over a full
    /// turn (undercut, tip land, clearance, backlash, contact ratio) and export them for
    /// manufacturing. The tooth count is `gear.module.teeth` or the module rule's.
    Teeth(TeethArgs),
    /// How the design fares once cut and assembled with the scene's tolerances
    /// (`[tolerances]`): each objective's probability of being met, its margin's
    /// distribution, a linearised worst case checked at its corner, and branch switches.
    /// docs/robustness.md
    Robustness(RobustnessArgs),
    /// First-order and total Sobol indices of every objective and trajectory measure over
    /// the scene's search box (Saltelli sampling, Jansen estimators, bootstrap intervals).
    /// docs/robustness.md
    Sensitivity(SensitivityArgs),
    /// Two arms against three: for each arm count, the least speed of the tip relative to
    /// the seedling while it picks (the mean over its pass through the tray, unless
    /// --measure says otherwise) of a design meeting every objective with a clear gearbox,
    /// at one picking rate (a search per seed); and the paper's design with each arm count.
    /// With no scene: `paper-search`. docs/replication.md
    Compare(CompareArgs),
    /// List the built-in scenes; with --reference, every field of a scene (docs/scenes.md).
    Scenes(ScenesArgs),
    /// List every measure (`sweep --measure`, goals `min:NAME`/`max:NAME`) with its unit.
    Measures,
    /// Serve the design studio (build it first: `bash studio/build.sh`) on 127.0.0.1 and
    /// print its address. docs/studio.md
    Studio(StudioArgs),
}

#[derive(clap::Args)]
struct CompareArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Arm counts to compare (comma-separated, each 1 to 4).
    #[arg(long, value_delimiter = ',', default_values_t = [2, 3])]
    arms: Vec<usize>,
    /// Search seeds: one search per arm count and seed.
    #[arg(long, value_delimiter = ',', default_values_t = [1, 2, 3, 4, 5])]
    seeds: Vec<u64>,
    /// The picking rate every train runs at (the paper's rig: 180).
    #[arg(long, default_value_t = 180.0)]
    picks_per_minute: f64,
    /// The speed compared and minimised by each search, a measure in m/s (`noncirc
    /// measures`): the mean speed while the tip is inside the tray, or
    /// `picking_tip_speed_m_s`, the speed at the picking instant (a cusp can bring it to 0).
    #[arg(long, default_value = noncirc::compare::DEFAULT_MEASURE)]
    measure: String,
    /// Each search's evaluation budget: at 200 000 the least speeds over seeds agree to a
    /// few per cent on `paper-search` (at its own 60 000 they spread by half).
    #[arg(long, default_value_t = 200_000)]
    budget: u64,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
}

#[derive(clap::Args)]
struct RobustnessArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Samples (default: the scene's `tolerances.samples`, 64).
    #[arg(long)]
    samples: Option<usize>,
    /// Seed of the deviations (default: the scene's `tolerances.seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Skip the linearised worst case (it costs two evaluations per toleranced quantity).
    #[arg(long)]
    no_worst_case: bool,
}

#[derive(clap::Args)]
struct SensitivityArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Base points N: N (k + 2) designs are evaluated for k free parameters.
    #[arg(long, default_value_t = 1024)]
    base_samples: usize,
    /// Bootstrap resamples for the confidence intervals.
    #[arg(long, default_value_t = 100)]
    bootstrap: usize,
    /// The box's share of the search box's widths, about the scene's design (1: the whole
    /// search box, where the model refuses about a third of the designs).
    #[arg(long, default_value_t = 0.25)]
    box_scale: f64,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
}

#[derive(clap::Args)]
struct ScenesArgs {
    /// Print the scene reference instead (Markdown: every field with the papers' symbol,
    /// unit, default, admissible values and meaning; docs/scenes.md is this output).
    #[arg(long)]
    reference: bool,
}

#[derive(clap::Args)]
struct StudioArgs {
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 8737)]
    port: u16,
    /// The studio's folder (default: this repository's `studio/`).
    #[arg(long, value_name = "DIR")]
    dir: Option<std::path::PathBuf>,
}

/// The search's progress bar (indicatif), an observer of the core's executor.
struct ProgressBar {
    bar: Option<indicatif::ProgressBar>,
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

/// How a command ended, beyond success and error.
enum Finished {
    Completed,
    /// A signal stopped a search; its results so far were written.
    Interrupted,
}

/// Exit codes (docs/reliability.md).
const EXIT_RUNTIME: u8 = 1;
const EXIT_INPUT: u8 = 2;
const EXIT_INTERRUPTED: u8 = 130;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(Finished::Completed) => ExitCode::SUCCESS,
        Ok(Finished::Interrupted) => ExitCode::from(EXIT_INTERRUPTED),
        // A reader that went away (`| head`) is not an error of ours.
        Err(e) if is_broken_pipe(e.as_ref()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            let input = e.downcast_ref::<noncirc::Error>().map_or(
                e.is::<noncirc::scene_file::SceneError>() || e.is::<noncirc::core::Error>(),
                noncirc::Error::is_input,
            );
            ExitCode::from(if input { EXIT_INPUT } else { EXIT_RUNTIME })
        }
    }
}

fn is_broken_pipe(e: &(dyn std::error::Error + 'static)) -> bool {
    e.downcast_ref::<std::io::Error>()
        .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
}

/// Writes `text` to standard output and flushes, returning write errors (a closed pipe, a
/// full disk) instead of panicking as `print!` does.
fn out(text: &str) -> Result<(), Box<dyn std::error::Error>> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                e.into()
            } else {
                format!("cannot write to standard output: {e}").into()
            }
        })
}

/// Pretty JSON with a final newline.
fn json(value: &impl serde::Serialize) -> Result<String, Box<dyn std::error::Error>> {
    Ok(serde_json::to_string_pretty(value)? + "\n")
}

fn optimise(args: OptimiseArgs) -> Result<Finished, Box<dyn std::error::Error>> {
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
    let name = args.scene.input.scene.as_deref().unwrap_or("paper-search");
    let mut scene = load_scene_with(Some(name), &args.scene.input.set)?;
    settings.apply(&mut scene)?;
    let checkpoint_every = noncirc::search::checkpoint_interval(args.checkpoint_every)?;
    // SIGINT, SIGTERM and SIGHUP all stop the search after the current generation.
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst))?;
    let opts = RunOptions {
        checkpoint: args.checkpoint,
        checkpoint_every,
        resume: args.resume,
        resume_budget: args.budget,
        stop: stop.clone(),
        ..RunOptions::new(args.threads)?
    };
    let mut progress = ProgressBar {
        bar: None,
        show: !args.quiet && args.scene.format == Format::Table,
    };
    let outcome = noncirc::search::run(&scene, &opts, &mut [&mut progress])?;
    if let Some(bar) = progress.bar {
        bar.finish_and_clear();
    }
    for failure in &outcome.checkpoint_failures {
        eprintln!("warning: {failure} (the search went on)");
    }
    if let Some(dir) = &args.out {
        outcome.write(dir)?;
    }
    if let Some(dir) = &args.scene.plot {
        for f in noncirc::plots::search_figures(&outcome, dir, &args.scene.figures()?)? {
            eprintln!("wrote {}", f.display());
        }
    }
    let summary = outcome.summary();
    noncirc::report::check_finite(&summary)?;
    match args.scene.format {
        Format::Json => out(&json(&summary)?)?,
        Format::Table => out(&noncirc::report::summary_table(&summary))?,
    }
    if stop.load(Ordering::SeqCst) {
        eprintln!("interrupted: the results so far are above (and in the checkpoint and --out)");
        return Ok(Finished::Interrupted);
    }
    Ok(Finished::Completed)
}

fn plot_evaluation(
    scene: &noncirc::core::Scene,
    eval: &noncirc::core::Evaluation,
    dir: &std::path::Path,
    options: &noncirc::figures::FigureOptions,
) -> Result<(), Box<dyn std::error::Error>> {
    for f in noncirc::plots::evaluation_outputs(scene, eval, dir, options)? {
        eprintln!("wrote {}", f.display());
    }
    Ok(())
}

fn run(cli: Cli) -> Result<Finished, Box<dyn std::error::Error>> {
    match cli.command {
        Command::Gear(args) => {
            let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
            let (report, pair) = GearReport::from_scene(&scene)?;
            noncirc::report::check_finite(&report)?;
            for dir in [&args.export, &args.scene.plot].into_iter().flatten() {
                for f in noncirc::export::export_gears(&pair, dir)? {
                    eprintln!("wrote {}", f.display());
                }
            }
            match args.scene.format {
                Format::Json => out(&json(&report)?)?,
                Format::Table => out(&report.table())?,
            }
        }
        Command::Teeth(args) => {
            let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
            if !(args.tolerance_mm > 0.0 && args.tolerance_mm.is_finite()) {
                return Err(Box::new(noncirc::core::Error::OutOfRange {
                    name: "--tolerance-mm".into(),
                    value: args.tolerance_mm,
                    expected: "a positive number of mm".into(),
                }));
            }
            let run = noncirc::teeth::TeethRun::from_scene(&scene, args.carrier_deg)?;
            noncirc::report::check_finite(&run.summary())?;
            if let Some(dir) = &args.export {
                for f in run.export(dir, args.tolerance_mm)? {
                    eprintln!("wrote {}", f.display());
                }
            }
            if let Some(dir) = &args.scene.plot {
                for f in noncirc::figures::teeth_figures(&run, dir, &args.scene.figures()?)? {
                    eprintln!("wrote {}", f.display());
                }
            }
            match args.scene.format {
                Format::Json => out(&json(&run.summary())?)?,
                Format::Table => out(&run.table())?,
            }
        }
        Command::Animate(args) => {
            let scene = load_scene_with(args.scene.scene.as_deref(), &args.scene.set)?;
            let kin = noncirc::core::Kinematics::solve(
                &scene.gear.curve.build()?,
                &scene.train,
                &scene.resolution,
            )?;
            let teeth = if args.teeth {
                Some(noncirc::teeth::TeethRun::from_scene(&scene, 0.0)?.pair)
            } else {
                None
            };
            noncirc::figures::animate(&kin, teeth.as_ref(), &args.out, args.frames)?;
            eprintln!("wrote {}", args.out.display());
        }
        Command::Evaluate(args) => {
            let scene = load_scene_with(args.input.scene.as_deref(), &args.input.set)?;
            let (report, eval) = EvaluationReport::from_scene(&scene)?;
            noncirc::report::check_finite(&report)?;
            if let Some(dir) = &args.plot {
                plot_evaluation(&scene, &eval, dir, &args.figures()?)?;
            }
            match args.format {
                Format::Json => out(&json(&report)?)?,
                Format::Table => out(&report.table())?,
            }
        }
        Command::Box(args) => {
            let scene = load_scene_with(
                Some(args.input.scene.as_deref().unwrap_or("moving-box")),
                &args.input.set,
            )?;
            let mut box_scene = scene.clone();
            if box_scene.kind != SceneKind::Transplanter {
                box_scene.kind = SceneKind::MovingBox;
            }
            let (report, _) = EvaluationReport::from_scene(&box_scene)?;
            let b = report.moving_box.ok_or("this scene has no moving box")?;
            noncirc::report::check_finite(&b)?;
            if let Some(dir) = &args.plot {
                noncirc::files::create_dir(dir)?;
                let fig = noncirc::figures::BoxFigure {
                    spec: &box_scene.moving_box,
                    report: &b,
                };
                for f in noncirc::figures::save(&fig, &dir.join("moving_box"), &args.figures()?)? {
                    eprintln!("wrote {}", f.display());
                }
            }
            match args.format {
                Format::Json => out(&json(&b)?)?,
                Format::Table => out(&noncirc::report::box_table(&b))?,
            }
        }
        Command::Accuracy(args) => {
            let scene = load_scene_with(args.input.scene.as_deref(), &args.input.set)?;
            let report = noncirc::accuracy::measure(&scene, 720)?;
            match args.format {
                Format::Json => out(&json(&report)?)?,
                Format::Table => out(&report.table())?,
            }
        }
        Command::Optimise(args) => return optimise(args),
        Command::Sweep(args) => {
            let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
            let measures = (args.measures.iter())
                .map(|m| Measure::parse(m))
                .collect::<Result<Vec<_>, _>>()?;
            let rows = noncirc::search::sweep(
                &scene,
                &args.param,
                args.from,
                args.to,
                args.steps,
                &measures,
            )?;
            if let Some(dir) = &args.scene.plot {
                for f in noncirc::plots::sweep_figures(
                    &scene,
                    &args.param,
                    &rows,
                    dir,
                    &args.scene.figures()?,
                )? {
                    eprintln!("wrote {}", f.display());
                }
            }
            match args.scene.format {
                Format::Json => out(&json(&rows)?)?,
                Format::Table => out(&noncirc::report::sweep_table(&args.param, &rows))?,
            }
        }
        Command::Compare(args) => {
            let source = args.scene.input.scene.as_deref().or(Some("paper-search"));
            let scene = load_scene_with(source, &args.scene.input.set)?;
            let paper = load_scene_with(Some("paper"), &[])?;
            let options = noncirc::compare::CompareOptions {
                arms: args.arms.clone(),
                seeds: args.seeds.clone(),
                picks_per_minute: args.picks_per_minute,
                measure: noncirc::core::Measure::parse(&args.measure)?,
                budget: Some(args.budget),
                threads: noncirc::search::threads_or_all(args.threads)?,
            };
            let c = noncirc::compare::compare(&scene, &paper, &options, &mut |r| {
                eprintln!(
                    "{} arms, seed {}: {} in {:.1} s",
                    r.arms,
                    r.seed,
                    (r.speeds.compared_m_s)
                        .filter(|_| r.speeds.feasible)
                        .map_or("no feasible design".into(), |v| format!("{v:.4} m/s")),
                    r.seconds
                );
            })?;
            if let Some(dir) = &args.scene.plot {
                let figures = args.scene.figures()?;
                let mut designs = Vec::new();
                for &arms in &args.arms {
                    if let Some(best) = noncirc::compare::best_scene(&c, arms) {
                        let (_, eval) = EvaluationReport::from_scene(&best)?;
                        designs.push((best, eval));
                    }
                }
                let files = noncirc::plots::comparison_outputs(
                    &designs,
                    c.picks_per_minute,
                    dir,
                    &figures,
                )?;
                for f in files {
                    eprintln!("wrote {}", f.display());
                }
            }
            match args.scene.format {
                Format::Json => out(&json(&c)?)?,
                Format::Table => out(&noncirc::compare::comparison_table(&c))?,
            }
        }
        Command::Robustness(args) => {
            let mut set = args.scene.input.set.clone();
            if let Some(n) = args.samples {
                set.push(format!("tolerances.samples={n}"));
            }
            if let Some(seed) = args.seed {
                set.push(format!("tolerances.seed={seed}"));
            }
            let scene = load_scene_with(args.scene.input.scene.as_deref(), &set)?;
            let analysis = noncirc::robustness::robustness(&scene, !args.no_worst_case)?;
            if let Some(dir) = &args.scene.plot {
                let options = args.scene.figures()?;
                for f in noncirc::plots::robustness_figures(&analysis, dir, &options)? {
                    eprintln!("wrote {}", f.display());
                }
            }
            match args.scene.format {
                Format::Json => out(&json(&analysis)?)?,
                Format::Table => out(&noncirc::robustness::robustness_table(&analysis))?,
            }
        }
        Command::Sensitivity(args) => {
            let scene = load_scene_with(args.scene.input.scene.as_deref(), &args.scene.input.set)?;
            let threads = noncirc::search::threads_or_all(args.threads)?;
            let s = noncirc::robustness::sensitivity(
                &scene,
                args.base_samples,
                args.bootstrap,
                args.box_scale,
                threads,
            )?;
            if let Some(dir) = &args.scene.plot {
                let options = args.scene.figures()?;
                for f in noncirc::plots::sensitivity_figures(&s, dir, &options)? {
                    eprintln!("wrote {}", f.display());
                }
            }
            match args.scene.format {
                Format::Json => out(&json(&s)?)?,
                Format::Table => out(&noncirc::robustness::sensitivity_table(&s))?,
            }
        }
        Command::Measures => {
            let lines: String = Measure::all()
                .iter()
                .map(|m| format!("{:<32} {:<4} {}\n", m.name(), m.unit(), m.description()))
                .collect();
            out(&lines)?;
        }
        Command::Studio(args) => {
            let dir = args.dir.unwrap_or_else(studio::default_dir);
            studio::serve(&dir, args.port)?;
        }
        Command::Scenes(args) if args.reference => {
            out(&noncirc::scene_reference::markdown())?;
        }
        Command::Scenes(_) => {
            let mut lines = String::new();
            for (name, text) in BUILTIN {
                let scene = noncirc::scene_file::parse_scene(text, name)?;
                lines += &format!("{name:<12} {}\n", scene.description);
            }
            out(&lines)?;
        }
    }
    Ok(Finished::Completed)
}
