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
//!   [--seed S] [--fit scene|frame]`: the visibility of each receiver point
//!   as JSON on stdout (maps fitted to the scene by default: each point's
//!   value independent of the others).
//! - `softshadow gbuffer --scene NAME|FILE [--width W --height H] --out
//!   DIR`: the receivers our camera sees as `.npy` arrays, one `.exr` and
//!   `camera.json`.
//! - `softshadow score --scene NAME|FILE --image FILE [--gbuffer DIR]
//!   [--out DIR] [--json] [--max-rmse X] [--yardstick]`: an image of `V`
//!   made elsewhere against the exact answer (exit status 3 when it fails
//!   `--max-rmse`).
//! - `softshadow report [--scene S]… [--method M]… [--out DIR] [--shard
//!   i/n] [--merge DIR…]`: the accuracy-against-run-time report.
//! - `softshadow stability [--out DIR]`: the stability suite.
//!
//! Bad input ends with one line on stderr naming the file, the place and
//! the field, exit status 2, and nothing on stdout. An answer that could
//! not be delivered — stdout full, a pipe whose reader left (`| head -1`),
//! or closed from the start (`>&-`) for a command whose answer is all
//! printed — ends with one line on stderr and exit status 1, after every
//! file the command started is written whole. A stderr that
//! cannot be written (`2>/dev/full`) changes nothing but the lines lost:
//! the exit status still tells.

/// `println!` for what the program prints as its answer. A failed write is
/// remembered, not fatal: the command goes on and writes every file it
/// started (each to a temporary name, renamed when whole), then
/// [`main`] ends with exit status 1 and says what was lost.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::stdout_line(format_args!($($arg)*))
    };
}

/// `eprintln!` that never panics: a line to stderr, dropped when stderr
/// cannot be written (full or closed), since there is nowhere else to say
/// it; the exit status still tells.
macro_rules! note {
    ($($arg:tt)*) => {
        $crate::stderr_line(format_args!($($arg)*))
    };
}

mod check;
mod memory;
mod progress;
mod render;
mod report;
mod score;
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
    writable_dir("--out", dir)
}

/// [`out_dir`] for the folder given to `flag`.
///
/// # Errors
/// One line naming `flag`.
fn writable_dir(flag: &str, dir: &std::path::Path) -> Result<(), String> {
    let fail = |why: String| format!("{flag} {}: {why}", dir.display());
    std::fs::create_dir_all(dir).map_err(|e| fail(e.to_string()))?;
    if !dir.is_dir() {
        return Err(fail("not a directory".into()));
    }
    let probe = dir.join(format!(".softshadow-probe-{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(|e| fail(format!("not writable: {e}")))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Writes `bytes` to `path` atomically (a temporary file renamed) and,
/// unless `quiet`, says so on stdout.
///
/// # Errors
/// One line naming the file.
fn write_out(path: &std::path::Path, bytes: &[u8], quiet: bool) -> Result<(), String> {
    softshadow::output::image::write_atomically(path, bytes)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    if !quiet {
        say!("wrote {}", path.display());
    }
    Ok(())
}

/// Why stdout lost what was printed: the first failed write. Set once;
/// [`say!`] prints nothing more after it.
static STDOUT_LOST: std::sync::OnceLock<String> = std::sync::OnceLock::new();

/// Writes one line to stdout for [`say!`], or remembers why it could not.
fn stdout_line(args: std::fmt::Arguments<'_>) {
    use std::io::Write;
    if STDOUT_LOST.get().is_some() {
        return;
    }
    let mut out = std::io::stdout().lock();
    if let Err(e) = writeln!(out, "{args}").and_then(|()| out.flush()) {
        let why = if e.kind() == std::io::ErrorKind::BrokenPipe {
            "broken pipe, its reader has gone".to_owned()
        } else {
            e.to_string()
        };
        let _ = STDOUT_LOST.set(why);
    }
}

/// Whether something [`say!`] printed was lost: a command that only
/// prints stops early.
fn stdout_lost() -> bool {
    STDOUT_LOST.get().is_some()
}

/// Writes one line to stderr for [`note!`]; a failed write is dropped.
fn stderr_line(args: std::fmt::Arguments<'_>) {
    use std::io::Write;
    let mut err = std::io::stderr().lock();
    let _ = writeln!(err, "{args}").and_then(|()| err.flush());
}

/// Whether stdout may have been closed when the program started (`>&-`).
/// Rust's runtime puts `/dev/null`, opened for reading and writing, in
/// place of a closed standard descriptor, so that every write would
/// "succeed" into nothing; a shell's `>/dev/null` opens it for writing
/// only. But a parent may choose a read-write `/dev/null` too (Python's
/// `subprocess.DEVNULL`), and nothing tells the two apart: so only a
/// command whose whole answer is printed refuses to run on it. Read from
/// `/proc` (Linux); elsewhere `false`.
fn stdout_closed_at_start() -> bool {
    let null = std::fs::read_link("/proc/self/fd/1")
        .is_ok_and(|target| target == std::path::Path::new("/dev/null"));
    null && std::fs::read_to_string("/proc/self/fdinfo/1").is_ok_and(|info| {
        info.lines()
            .find_map(|l| l.strip_prefix("flags:"))
            .and_then(|f| u32::from_str_radix(f.trim(), 8).ok())
            .is_some_and(|flags| flags & 0o3 == 0o2)
    })
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
    /// The receivers our camera sees as float arrays (.npy), one .exr and
    /// camera.json, for scoring an implementation written elsewhere.
    Gbuffer(score::GbufferArgs),
    /// Score an image of V made elsewhere (.npy, .exr, .pfm) against the
    /// exact answer on the same receivers: the report's error table.
    Score(score::ScoreArgs),
    /// The accuracy-against-run-time report: every scene × method setting,
    /// timed and measured against exact, with the Monte Carlo yardstick.
    Report(report::Args),
    /// The stability suite: the kernels, the exact reference and the methods
    /// on stiff and extreme input, written as stability.md.
    Stability(stability::Args),
}

/// Exit status for bad input (a file, an argument).
const BAD_INPUT: u8 = 2;

/// Exit status for an answer that could not be delivered (stdout closed,
/// full or its reader gone).
const NOT_DELIVERED: u8 = 1;

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
                // The help is the answer: printed, or said to be lost.
                if stdout_closed_at_start() {
                    return not_delivered(CLOSED);
                }
                return match e.print() {
                    Ok(()) => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(0)),
                    Err(err) => not_delivered(&err.to_string()),
                };
            }
            // One line, as for every other bad input (clap's own message
            // adds a usage block and a hint).
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("bad arguments");
            note!(
                "softshadow: {} (see softshadow --help)",
                one_line(first.trim_start_matches("error: "), 600)
            );
            return ExitCode::from(BAD_INPUT);
        }
    };
    // A command whose whole answer is printed does no work for a stdout
    // closed from the start; one whose answer is files writes them (its
    // stdout may be a read-write /dev/null by choice).
    let prints_only = matches!(
        cli.command,
        None | Some(Command::Check | Command::Visibility(_))
    );
    if prints_only && stdout_closed_at_start() {
        return not_delivered(CLOSED);
    }
    let result = match cli.command {
        None => render::default_run(),
        Some(Command::Check) => {
            let status = check::run();
            return match STDOUT_LOST.get() {
                Some(why) => not_delivered(why),
                None => status,
            };
        }
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Visibility(args)) => visibility::run(&args),
        Some(Command::Gbuffer(args)) => score::gbuffer(&args),
        Some(Command::Score(args)) => {
            let status = score::score(&args);
            return match STDOUT_LOST.get() {
                Some(why) => not_delivered(why),
                None => status,
            };
        }
        Some(Command::Report(args)) => report::run(&args),
        Some(Command::Stability(args)) => stability::run(&args),
    };
    match (result, STDOUT_LOST.get()) {
        (Err(message), _) => {
            note!("softshadow: {}", one_line(&message, 600));
            ExitCode::from(BAD_INPUT)
        }
        (Ok(()), Some(why)) => not_delivered(why),
        (Ok(()), None) => ExitCode::SUCCESS,
    }
}

/// Why a stdout closed from the start is lost.
const CLOSED: &str = "closed (or /dev/null opened for reading and writing, which is what a \
                      closed stdout becomes) when the program started";

/// Says that what was to be printed is lost, and why; exit status 1.
fn not_delivered(why: &str) -> ExitCode {
    note!(
        "softshadow: stdout: {}; the printed output is lost or incomplete",
        one_line(why, 200)
    );
    ExitCode::from(NOT_DELIVERED)
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
