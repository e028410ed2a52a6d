//! The command line's arguments (clap): one struct per command, and the options they share.

use clap::{Parser, Subcommand, ValueEnum};
use noncirc::core::Algorithm;

#[derive(Parser)]
#[command(
    name = "noncirc",
    version,
    about = "Design-space optimiser for rice-transplanting mechanisms driven by non-circular gears"
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub(crate) enum Format {
    Table,
    Json,
}

/// The scene a command reads.
#[derive(clap::Args)]
pub(crate) struct SceneSource {
    /// Scene file (TOML or JSON) or built-in scene name (`noncirc scenes`); default: the
    /// command's own (see its description; the three-arm paper's design for most).
    pub(crate) scene: Option<String>,
    /// Override any scene parameter, e.g. `--set resolution.samples_per_turn=720`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub(crate) set: Vec<String>,
}

/// Options shared by every command that reads a scene and reports on it.
#[derive(clap::Args)]
pub(crate) struct SceneArgs {
    #[command(flatten)]
    pub(crate) input: SceneSource,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub(crate) format: Format,
    /// Write figures (SVG and PNG) and CSV exports into this directory.
    #[arg(long, value_name = "DIR")]
    pub(crate) plot: Option<std::path::PathBuf>,
    /// Figure formats written by --plot (comma-separated): svg, png, pdf (vector with the
    /// font embedded, for a paper).
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = [FigureFormatArg::Svg, FigureFormatArg::Png])]
    pub(crate) figure_format: Vec<FigureFormatArg>,
    /// Figure size WIDTHxHEIGHT in CSS pixels (96 to the inch), e.g. 640x480; default:
    /// each figure's own. Text keeps its size, so a smaller figure reads larger.
    #[arg(long, value_name = "WxH")]
    pub(crate) figure_size: Option<String>,
    /// Resolution of the PNG figures (dots per inch; 300, for print, by default; 96 for a
    /// screen).
    #[arg(long, default_value_t = 300)]
    pub(crate) dpi: u32,
}

/// A figure format (`--figure-format`).
#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum FigureFormatArg {
    Svg,
    Png,
    Pdf,
}

impl SceneArgs {
    /// The figure options asked for, checked.
    pub(crate) fn figures(
        &self,
    ) -> Result<noncirc::figures::FigureOptions, Box<dyn std::error::Error>> {
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
pub(crate) struct OptimiseArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// Algorithm: guided, de, cmaes, nsga2 or nsga3 (default: the scene's, `de`).
    #[arg(long)]
    pub(crate) algorithm: Option<Algorithm>,
    /// Evaluation budget (default: the scene's).
    #[arg(long)]
    pub(crate) budget: Option<u64>,
    /// Population size (default: the scene's).
    #[arg(long)]
    pub(crate) population: Option<usize>,
    /// Random seed (default: the scene's).
    #[arg(long)]
    pub(crate) seed: Option<u64>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    pub(crate) threads: Option<usize>,
    /// Write a checkpoint to this file at intervals and at the end.
    #[arg(long, value_name = "FILE")]
    pub(crate) checkpoint: Option<std::path::PathBuf>,
    /// Seconds between checkpoints.
    #[arg(long, default_value_t = noncirc::search::DEFAULT_CHECKPOINT_EVERY_S)]
    pub(crate) checkpoint_every: f64,
    /// Resume from a checkpoint file (its scene and settings are used).
    #[arg(long, value_name = "FILE")]
    pub(crate) resume: Option<std::path::PathBuf>,
    /// Write best.toml, pareto.csv/json, history.csv and summary.json here.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<std::path::PathBuf>,
    /// optimise and fit: write --out over files of those names that are not noncirc's
    /// outputs of this scene.
    #[arg(long)]
    pub(crate) force: bool,
    /// No progress bar.
    #[arg(long)]
    pub(crate) quiet: bool,
}

#[derive(clap::Args)]
pub(crate) struct FitArgs {
    #[command(flatten)]
    pub(crate) search: OptimiseArgs,
    /// The target: a CSV of `x_mm,y_mm` points (machine frame, a closed path in the order
    /// of motion) or a TOML file with a `[target]` table (docs/inverse.md).
    #[arg(long, value_name = "FILE")]
    pub(crate) target: Option<std::path::PathBuf>,
    /// The target path's tolerance (mm): met when the Hausdorff distance is at most this.
    #[arg(long)]
    pub(crate) tolerance_mm: Option<f64>,
}

#[derive(clap::Args)]
pub(crate) struct RepairArgs {
    #[command(flatten)]
    pub(crate) search: OptimiseArgs,
    /// The tip path's tolerance (mm): a path off by this (RMS) costs as much as a
    /// parameter moved by its scale.
    #[arg(long, default_value_t = noncirc::repair::RepairOptions::PATH_TOLERANCE_MM)]
    pub(crate) path_tolerance_mm: f64,
    /// Each parameter's scale as a fraction of its search interval: a move of this much
    /// costs as much as the path off by its tolerance.
    #[arg(long, default_value_t = noncirc::repair::RepairOptions::DESIGN_SCALE)]
    pub(crate) design_scale: f64,
}

#[derive(clap::Args)]
pub(crate) struct InverseArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// The target: a CSV of `x_mm,y_mm` points or a TOML file with a `[target]` table
    /// (docs/inverse.md); default: the scene's own `[target]`.
    #[arg(long, value_name = "FILE")]
    pub(crate) target: Option<std::path::PathBuf>,
    /// How the overall ratio is shared between the pairs: equal, first-circular,
    /// second-circular, or the first pair's share λ from 0 to 1.
    #[arg(long, default_value = "equal")]
    pub(crate) split: String,
    /// a_B/a_A, the intermediate–planet centre distance over the sun–intermediate one;
    /// default: the scene's own (1 for the paper's train).
    #[arg(long)]
    pub(crate) centre_ratio: Option<f64>,
    /// The elbow's branch from the path's farthest point to its nearest; default: both
    /// tried, the better kept.
    #[arg(long, value_enum)]
    pub(crate) branch: Option<BranchArg>,
    /// Samples per turn of the curves written (and of the design's resolution).
    #[arg(long, default_value_t = 720)]
    pub(crate) samples: usize,
    /// Write inverse.json and, when a design is built, inverse.toml into this directory.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<std::path::PathBuf>,
}

/// An elbow branch (`--branch`).
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum BranchArg {
    Plus,
    Minus,
}

#[derive(clap::Args)]
pub(crate) struct TargetArgs {
    #[command(flatten)]
    pub(crate) scene: SceneSource,
    /// Points of the path, equally spaced in carrier angle.
    #[arg(long, default_value_t = 512)]
    pub(crate) points: usize,
}

#[derive(clap::Args)]
pub(crate) struct GearArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// Export the pitch curves (CSV, SVG, DXF in mm) into this directory.
    #[arg(long, value_name = "DIR")]
    pub(crate) export: Option<std::path::PathBuf>,
}

#[derive(clap::Args)]
pub(crate) struct TeethArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// Export DXF (lines and arcs, mm), SVG and CSV of each gear and of the assembled
    /// train into this directory.
    #[arg(long, value_name = "DIR")]
    pub(crate) export: Option<std::path::PathBuf>,
    /// Carrier angle of the assembled train (degrees).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub(crate) carrier_deg: f64,
    /// Largest distance of the exported lines and arcs from the computed outline (mm).
    #[arg(long, default_value_t = 1e-3)]
    pub(crate) tolerance_mm: f64,
    /// Export the gears even when they fail a check (the exit code is still 3).
    #[arg(long)]
    pub(crate) force: bool,
}

/// A file format of `noncirc cad`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum CadFormat {
    /// STEP AP214: the assembly and each part.
    Step,
    /// Binary STL, each part in its own frame.
    Stl,
    /// Only `assembly.json` (written with every format): the parts' volumes and where
    /// each copy stands.
    Json,
}

#[derive(clap::Args)]
pub(crate) struct CadArgs {
    #[command(flatten)]
    pub(crate) scene: SceneSource,
    /// The formats to write, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "step,stl")]
    pub(crate) format: Vec<CadFormat>,
    /// Carrier angle of the assembled train (degrees).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub(crate) carrier_deg: f64,
    /// The directory to write the files into.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: std::path::PathBuf,
    /// Largest distance of the STEP's lines and arcs from the cut outline, and of the
    /// STL's chords from those arcs (mm).
    #[arg(long, default_value_t = 1e-3)]
    pub(crate) tolerance_mm: f64,
    /// Write the solids even when the teeth fail a check (the exit code is still 3).
    #[arg(long)]
    pub(crate) force: bool,
}

#[derive(clap::Args)]
pub(crate) struct AnimateArgs {
    #[command(flatten)]
    pub(crate) scene: SceneSource,
    /// The GIF to write.
    #[arg(long, value_name = "FILE.gif")]
    pub(crate) out: std::path::PathBuf,
    /// Frames per carrier turn.
    #[arg(long, default_value_t = 72)]
    pub(crate) frames: usize,
    /// Draw the gears' teeth (`noncirc teeth`'s, with the scene's tooth count).
    #[arg(long)]
    pub(crate) teeth: bool,
}

#[derive(clap::Args)]
pub(crate) struct SweepArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// Parameter path, e.g. `gear.curve.radii_mm[0]` or `train.phi0_deg`.
    #[arg(long)]
    pub(crate) param: String,
    /// First value of the parameter (negative values are values: `--from -60`).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) from: f64,
    /// Last value of the parameter.
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) to: f64,
    #[arg(long, default_value_t = 11)]
    pub(crate) steps: usize,
    /// A measure to report beside the objectives (repeatable), e.g. `loop_height_mm`;
    /// `noncirc measures` lists them.
    #[arg(long = "measure")]
    pub(crate) measures: Vec<String>,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Solve a non-circular gear pair: centre distance, perimeter, ratio, largest module.
    Gear(GearArgs),
    /// Animate the mechanism turning (GIF).
    Animate(AnimateArgs),
    /// Evaluate a three-arm design: trajectory, events and the eight agronomic objectives.
    Evaluate(SceneArgs),
    /// The train at its working speed: the input torque, the mesh forces, the axle loads
    /// and the shaking force over a carrier turn, from the scene's `[dynamics]` bodies and
    /// loads (Newton–Euler, checked against the energy balance), and the teeth's root and
    /// contact stresses and safety factors where they can be cut. docs/dynamics.md
    Dynamics(SceneArgs),
    /// The variable-speed moving box: box travel while picking, speeds, forces.
    /// With no scene: the moving-box paper's setting.
    Box(SceneArgs),
    /// Measure each output's error and the time per evaluation over a resolution ladder.
    Accuracy(SceneArgs),
    /// Search the scene's design space for designs that meet every objective.
    /// With no scene: the built-in `paper-search` scene.
    Optimise(OptimiseArgs),
    /// Find the design whose tip path and key poses come nearest a target (the scene's
    /// `[target]` or --target FILE) while it meets every objective: the scene's search with
    /// the goal `fit`, then Levenberg–Marquardt. With no scene: `paper-search`.
    /// docs/inverse.md
    Fit(FitArgs),
    /// Print the scene's own tip path and its picking and planting poses as a `[target]`
    /// table (TOML): a start for a target to edit, or a design to fit again.
    Target(TargetArgs),
    /// The train with two pairs from a target tip path: the arm length and planet circle
    /// the path fixes, the carrier angle and arm direction along it, and both pitch
    /// curves by closure (written as tables). Names each condition that fails and where.
    /// With no scene: the paper's train. docs/inverse.md
    Inverse(InverseArgs),
    /// The design nearest the scene's that meets every objective and whose teeth cut and
    /// mesh: a fit to the design's own tip path and events with each free parameter pulled
    /// towards its value, in boxes about it within the scene's search box; the changes
    /// listed. With no scene: `paper-search` (the paper's design in the box it searched).
    /// docs/inverse.md
    Repair(RepairArgs),
    /// The response of every objective to one parameter (three-arm paper §4.2).
    Sweep(SweepArgs),
    /// Cut teeth on the scene's gears (every gear of the train), check them over a full
    /// turn (undercut, tip land, clearance, backlash, contact ratio) and export them for
    /// manufacturing. The tooth count is `gear.module.teeth` or the module rule's.
    Teeth(TeethArgs),
    /// Solid models of the scene's gears and train for CAD and printing: each gear's cut
    /// teeth extruded by the face width with its bore, keyway and phase mark, the
    /// carrier's plates, the arms and pushers, assembled at a carrier angle; STEP AP214
    /// (the assembly and each part) and STL (each part), with the `[cad]` dimensions.
    /// docs/cad.md
    Cad(CadArgs),
    /// How the design fares once cut and assembled with the scene's tolerances
    /// (`[tolerances]`): each objective's probability of being met, its margin's
    /// distribution, a linearised worst case checked at its corner, and branch switches.
    /// docs/robustness.md
    Robustness(RobustnessArgs),
    /// First-order and total Sobol indices of every objective and trajectory measure over
    /// the scene's search box (Saltelli sampling, SALib's estimators, bootstrap intervals),
    /// with a warning naming the indices that cannot be read at the samples taken.
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
pub(crate) struct CompareArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// Arm counts to compare (comma-separated, each 1 to 4).
    #[arg(long, value_delimiter = ',', default_values_t = [2, 3])]
    pub(crate) arms: Vec<usize>,
    /// Search seeds: one search per arm count and seed.
    #[arg(long, value_delimiter = ',', default_values_t = [1, 2, 3, 4, 5])]
    pub(crate) seeds: Vec<u64>,
    /// The picking rate every train runs at (the paper's rig: 180).
    #[arg(long, default_value_t = 180.0)]
    pub(crate) picks_per_minute: f64,
    /// The speed compared and minimised by each search, a measure in m/s (`noncirc
    /// measures`): the mean speed while the tip is inside the tray, or
    /// `picking_tip_speed_m_s`, the speed at the picking instant (a cusp can bring it to 0).
    #[arg(long, default_value = noncirc::compare::DEFAULT_MEASURE)]
    pub(crate) measure: String,
    /// Each search's evaluation budget: at 200 000 the least speeds over seeds agree to a
    /// few per cent on `paper-search` (at its own 60 000 they spread by half).
    #[arg(long, default_value_t = 200_000)]
    pub(crate) budget: u64,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    pub(crate) threads: Option<usize>,
}

#[derive(clap::Args)]
pub(crate) struct RobustnessArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// Samples (default: the scene's `tolerances.samples`, 64).
    #[arg(long)]
    pub(crate) samples: Option<usize>,
    /// Seed of the deviations (default: the scene's `tolerances.seed`).
    #[arg(long)]
    pub(crate) seed: Option<u64>,
    /// Skip the linearised worst case (it costs two evaluations per toleranced quantity).
    #[arg(long)]
    pub(crate) no_worst_case: bool,
}

#[derive(clap::Args)]
pub(crate) struct SensitivityArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    /// Base points N: N (k + 2) designs are evaluated for k free parameters.
    #[arg(long, default_value_t = 1024)]
    pub(crate) base_samples: usize,
    /// Bootstrap resamples for the confidence intervals.
    #[arg(long, default_value_t = 100)]
    pub(crate) bootstrap: usize,
    /// The box's share of the search box's widths, about the scene's design, 1e-6 to 1 (1:
    /// the whole search box, where the model refuses about a third of the designs).
    #[arg(long, default_value_t = 0.25)]
    pub(crate) box_scale: f64,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    pub(crate) threads: Option<usize>,
}

#[derive(clap::Args)]
pub(crate) struct ScenesArgs {
    /// Print the scene reference instead (Markdown: every field with the papers' symbol,
    /// unit, default, admissible values and meaning; docs/scenes.md is this output).
    #[arg(long)]
    pub(crate) reference: bool,
}

#[derive(clap::Args)]
pub(crate) struct StudioArgs {
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 8737)]
    pub(crate) port: u16,
    /// The studio's folder (default: this repository's `studio/`).
    #[arg(long, value_name = "DIR")]
    pub(crate) dir: Option<std::path::PathBuf>,
}
