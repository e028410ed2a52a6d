//! The `noncirc` command line.

/// `eprintln!` that never panics: a message to a standard error that is closed or full
/// (`2>/dev/full`) is lost, not a crash (exit 101) that hides the exit code.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

mod args;
mod commands;
mod fit;
mod optimise;
mod output;
mod studio;

use args::{Cli, Command};
use clap::Parser;
use output::is_broken_pipe;
use std::process::ExitCode;

/// mimalloc serves an evaluation's short-lived vectors faster than glibc (docs/performance.md).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// How a command ended, beyond success and error.
pub(crate) enum Finished {
    Completed,
    /// A signal stopped a search; its results so far were written.
    Interrupted,
}

/// Exit codes (docs/reliability.md).
const EXIT_RUNTIME: u8 = 1;
const EXIT_INPUT: u8 = 2;
/// The checked design fails: `noncirc teeth`'s teeth fail a check or cannot be cut.
pub(crate) const EXIT_VERDICT: u8 = 3;
pub(crate) const EXIT_INTERRUPTED: u8 = 130;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(Finished::Completed) => ExitCode::SUCCESS,
        Ok(Finished::Interrupted) => ExitCode::from(EXIT_INTERRUPTED),
        // A reader that went away (`| head`) is not an error of ours.
        Err(e) if is_broken_pipe(e.as_ref()) => ExitCode::SUCCESS,
        Err(e) if e.is::<commands::VerdictFailed>() => {
            say!("fails: {e}");
            ExitCode::from(EXIT_VERDICT)
        }
        Err(e) => {
            say!("error: {e}");
            let input = e.downcast_ref::<noncirc::Error>().map_or(
                e.is::<noncirc::scene_file::SceneError>() || e.is::<noncirc::core::Error>(),
                noncirc::Error::is_input,
            );
            ExitCode::from(if input { EXIT_INPUT } else { EXIT_RUNTIME })
        }
    }
}

/// Runs the command.
fn run(cli: Cli) -> Result<Finished, Box<dyn std::error::Error>> {
    match cli.command {
        Command::Optimise(args) => return optimise::optimise(args),
        Command::Fit(args) => return fit::fit(args),
        Command::Target(args) => fit::target(args)?,
        Command::Inverse(args) => return fit::inverse(args),
        Command::Repair(args) => return fit::repair(args),
        Command::Gear(args) => commands::gear(args)?,
        Command::Teeth(args) => commands::teeth(args)?,
        Command::Cad(args) => commands::cad(args)?,
        Command::Animate(args) => commands::animate(args)?,
        Command::Evaluate(args) => commands::evaluate(args)?,
        Command::Box(args) => commands::moving_box(args)?,
        Command::Dynamics(args) => commands::dynamics(args)?,
        Command::Accuracy(args) => commands::accuracy(args)?,
        Command::Sweep(args) => commands::sweep(args)?,
        Command::Compare(args) => commands::compare(args)?,
        Command::Robustness(args) => commands::robustness(args)?,
        Command::Sensitivity(args) => commands::sensitivity(args)?,
        Command::Measures => commands::measures()?,
        Command::Scenes(args) => commands::scenes(args)?,
        Command::Studio(args) => commands::studio(args)?,
    }
    Ok(Finished::Completed)
}
