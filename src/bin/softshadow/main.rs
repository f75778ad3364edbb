//! The `softshadow` command-line program (the commands are in the README).
//!
//! - `softshadow`: the main job — the default scene rendered with every
//!   available method, a table of time and error against the exact answer.
//! - `softshadow render --scene NAME|FILE --method M [--out DIR] [--width W
//!   --height H] [--stats]`: one method, PNG files (visibility, shaded, error
//!   heat-map) and its errors.
//! - `softshadow check`: the kernel self-check against closed forms, then the
//!   exact and Monte Carlo references side by side on the default scene.
//! - `softshadow visibility --scene NAME|FILE --points FILE --method M
//!   [--seed S]`: the visibility of each receiver point as JSON on stdout.
//! - `softshadow report [--scene S]… [--method M]… [--out DIR] [--shard
//!   i/n] [--merge DIR…]`: the accuracy-against-run-time report.
//! - `softshadow stability [--out DIR]`: the stability suite.
//!
//! Bad input ends with one line on stderr naming the file, the place and
//! the field, exit status 2, and nothing on stdout.

mod check;
mod progress;
mod render;
mod report;
mod selfcheck;
mod stability;
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
    /// The kernel self-check and the references on the default scene.
    Check,
    /// Render a scene with one method: PNG images and errors against exact.
    Render(render::Args),
    /// The visibility V(p) of each receiver of a points file, as JSON.
    Visibility(visibility::Args),
    /// The accuracy-against-run-time report: every scene × method setting,
    /// timed and measured against exact, with the Monte Carlo yardstick.
    Report(report::Args),
    /// The stability suite: the kernels, the exact reference and the methods
    /// on stiff and extreme input, written as stability.md.
    Stability(stability::Args),
}

/// Exit status for bad input (a file, an argument).
const BAD_INPUT: u8 = 2;

/// The command with the registry's list of methods under `--help`.
fn command() -> clap::Command {
    use clap::CommandFactory;
    let methods = format!(
        "Methods (--method NAME, or NAME:OPTION,… with the options listed):\n{}",
        softshadow::method::registry::help()
    );
    Cli::command()
        .after_help(methods.clone())
        .mut_subcommand("render", |c| c.after_help(methods.clone()))
        .mut_subcommand("visibility", |c| c.after_help(methods.clone()))
}

fn main() -> ExitCode {
    use clap::FromArgMatches;
    let parsed = command()
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m));
    let cli = match parsed {
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
    let result = match cli.command {
        None => render::default_run(),
        Some(Command::Check) => return check::run(),
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Visibility(args)) => visibility::run(&args),
        Some(Command::Report(args)) => report::run(&args),
        Some(Command::Stability(args)) => stability::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("softshadow: {message}");
            ExitCode::from(BAD_INPUT)
        }
    }
}
