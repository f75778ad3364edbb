//! The `softshadow` command-line program (DESIGN.md §8).
//!
//! - `softshadow` (or `softshadow check`): the main job until the renderer
//!   lands — the kernel self-check against closed forms, then the exact and
//!   Monte Carlo references side by side on the embedded default scene.
//! - `softshadow visibility --scene NAME|FILE --points FILE --method M
//!   [--seed S]`: the visibility of each receiver point as JSON on stdout.
//!
//! Bad input ends with one line on stderr naming the file, the place and
//! the field, exit status 2, and nothing on stdout.

mod check;
mod progress;
mod selfcheck;
mod visibility;

use clap::{Parser, Subcommand};

use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "softshadow",
    version,
    about = "Soft-shadow kernels, references and methods"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// The kernel self-check and the references on the default scene (what
    /// `softshadow` with no arguments runs).
    Check,
    /// The visibility V(p) of each receiver of a points file, as JSON.
    Visibility(visibility::Args),
}

/// Exit status for bad input (a file, an argument).
const BAD_INPUT: u8 = 2;

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion)
                || matches!(
                    e.kind(),
                    ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
                )
            {
                e.exit();
            }
            // One line, as for every other bad input (clap's own message
            // adds a usage block and a hint).
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("bad arguments");
            eprintln!(
                "softshadow: {} (see softshadow --help)",
                first.trim_start_matches("error: ")
            );
            return ExitCode::from(BAD_INPUT);
        }
    };
    match cli.command.unwrap_or(Command::Check) {
        Command::Check => check::run(),
        Command::Visibility(args) => match visibility::run(&args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(message) => {
                eprintln!("softshadow: {message}");
                ExitCode::from(BAD_INPUT)
            }
        },
    }
}
