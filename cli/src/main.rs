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

/// `println!` that ends the program quietly (status 0) when stdout is
/// closed — `softshadow … | head -1` — as a pipeline's reader expects, and
/// with a one-line error (status 1) when it cannot be written otherwise.
/// Every file the program writes is written to a temporary name and
/// renamed, so stopping here leaves no partial file.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::stdout_line(format_args!($($arg)*))
    };
}

mod check;
mod progress;
mod render;
mod report;
mod selfcheck;
mod stability;
mod visibility;

use clap::{Parser, Subcommand};

use std::process::ExitCode;

/// Makes `dir` ready for the files a command writes, before any work:
/// created if missing, a directory, and writable (a file is created in it
/// and removed).
///
/// # Errors
/// One line naming `--out`.
fn out_dir(dir: &std::path::Path) -> Result<(), String> {
    let fail = |why: String| format!("--out {}: {why}", dir.display());
    std::fs::create_dir_all(dir).map_err(|e| fail(e.to_string()))?;
    if !dir.is_dir() {
        return Err(fail("not a directory".into()));
    }
    let probe = dir.join(format!(".softshadow-probe-{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(|e| fail(format!("not writable: {e}")))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Writes one line to stdout for [`say!`].
fn stdout_line(args: std::fmt::Arguments<'_>) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = writeln!(out, "{args}").and_then(|()| out.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("softshadow: cannot write to stdout: {e}");
        std::process::exit(1);
    }
}

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
                one_line(first.trim_start_matches("error: "), 600)
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
            eprintln!("softshadow: {}", one_line(&message, 600));
            ExitCode::from(BAD_INPUT)
        }
    }
}

/// A message as one line of at most about `max` bytes: control characters
/// (a newline in a path, say) escaped, the rest cut with its length stated.
fn one_line(message: &str, max: usize) -> String {
    let mut escaped = String::with_capacity(message.len().min(max + 16));
    for c in message.chars() {
        if c.is_control() {
            escaped.extend(c.escape_default());
        } else {
            escaped.push(c);
        }
    }
    if escaped.len() <= max {
        return escaped;
    }
    let cut = (0..=max)
        .rev()
        .find(|&i| escaped.is_char_boundary(i))
        .unwrap_or(0);
    format!("{}… ({} bytes in all)", &escaped[..cut], escaped.len())
}
