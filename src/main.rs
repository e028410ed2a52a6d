//! The `noncirc` command line.

use clap::{Parser, Subcommand, ValueEnum};
use noncirc::core::SceneKind;
use noncirc::report::{EvaluationReport, GearReport};
use noncirc::scene_file::{apply_overrides, load_scene, BUILTIN};
use std::process::ExitCode;

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

/// Options shared by every command that reads a scene.
#[derive(clap::Args)]
struct SceneArgs {
    /// Scene file (TOML or JSON) or built-in scene name; default: the three-arm paper's design.
    scene: Option<String>,
    /// Override any scene parameter, e.g. `--set resolution.samples_per_turn=720`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    format: Format,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a non-circular gear pair: centre distance, perimeter, ratio, largest module.
    Gear(SceneArgs),
    /// Evaluate a three-arm design: trajectory, events and the eight agronomic objectives.
    Evaluate(SceneArgs),
    /// The variable-speed moving box: box travel while picking, speeds, forces.
    /// With no scene: the moving-box paper's setting.
    Box(SceneArgs),
    /// Measure each output's error and the time per evaluation over a resolution ladder.
    Accuracy(SceneArgs),
    /// List the built-in scenes.
    Scenes,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), Box<dyn std::error::Error>> {
    match cli.command {
        Command::Gear(args) => {
            let scene = apply_overrides(load_scene(args.scene.as_deref())?, &args.set)?;
            let (report, _) = GearReport::from_scene(&scene)?;
            match args.format {
                Format::Json => println!("{}", serde_json::to_string_pretty(&report)?),
                Format::Table => print!("{}", report.table()),
            }
        }
        Command::Evaluate(args) => {
            let scene = apply_overrides(load_scene(args.scene.as_deref())?, &args.set)?;
            let (report, _) = EvaluationReport::from_scene(&scene)?;
            match args.format {
                Format::Json => println!("{}", serde_json::to_string_pretty(&report)?),
                Format::Table => print!("{}", report.table()),
            }
        }
        Command::Box(args) => {
            let scene = apply_overrides(
                load_scene(Some(args.scene.as_deref().unwrap_or("moving-box")))?,
                &args.set,
            )?;
            let mut box_scene = scene.clone();
            if box_scene.kind != SceneKind::Transplanter {
                box_scene.kind = SceneKind::MovingBox;
            }
            let (report, _) = EvaluationReport::from_scene(&box_scene)?;
            let b = report.moving_box.ok_or("this scene has no moving box")?;
            match args.format {
                Format::Json => println!("{}", serde_json::to_string_pretty(&b)?),
                Format::Table => print!("{}", noncirc::report::box_table(&b)),
            }
        }
        Command::Accuracy(args) => {
            let scene = apply_overrides(load_scene(args.scene.as_deref())?, &args.set)?;
            let report = noncirc::accuracy::measure(&scene, 720)?;
            match args.format {
                Format::Json => println!("{}", serde_json::to_string_pretty(&report)?),
                Format::Table => print!("{}", report.table()),
            }
        }
        Command::Scenes => {
            for (name, text) in BUILTIN {
                let scene = noncirc::scene_file::parse_scene(text, name)?;
                println!("{name:<12} {}", scene.description);
            }
        }
    }
    Ok(())
}
