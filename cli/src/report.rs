//! `softshadow report`: the accuracy-against-run-time report
//! (`softshadow::report`), one part of it (`--shard i/n`), or the merge of
//! parts (`--merge DIR…`).

use crate::visibility::resolve_scene;
use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use softshadow::report::{self, Case, Config, Shard, Staged};
use softshadow::scene::BUILTIN_NAMES;
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(ClapArgs)]
pub struct Args {
    /// A scene to sweep (built-in name or JSON file with a camera); repeat
    /// for several. Default: every built-in scene.
    #[arg(long = "scene")]
    scenes: Vec<String>,
    /// A method setting to run instead of the registry's comparison
    /// settings (NAME or NAME:OPTION,…); repeat for several. `exact` and
    /// the Monte Carlo yardstick always run.
    #[arg(long = "method")]
    methods: Vec<String>,
    /// The folder the report is written to (created if missing): a new or
    /// empty folder, or an earlier report's, which is replaced whole once
    /// the new report is complete.
    #[arg(long, default_value = "report")]
    out: PathBuf,
    /// Run the i-th of n disjoint parts of the sweep (1 ≤ i ≤ n).
    #[arg(long)]
    shard: Option<Shard>,
    /// Join the parts written to these folders (each holds a results.json,
    /// checked whole, and the pictures it names) into --out, instead of
    /// running.
    #[arg(long, num_args = 1.., conflicts_with_all = ["scenes", "methods", "shard"])]
    merge: Vec<PathBuf>,
    /// The side of every scene's camera frame.
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(8..=4096))]
    side: u32,
    /// Timed runs per cell (the median is reported).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=100))]
    runs: u32,
    /// The largest Monte Carlo sample count of the yardstick (2, 4, … up to
    /// this power of two).
    #[arg(long, default_value_t = 4096, value_parser = clap::value_parser!(u32).range(2..=1_048_576))]
    mc_max: u32,
    /// The side of the pictures (the default scene's: twice this, up to
    /// --side); 0 for none.
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(0..=4096))]
    pictures: u32,
    /// Also write the accuracy pages (methods.md, one per method) into this
    /// folder, keeping each page's text above its marker line.
    #[arg(long)]
    accuracy: Option<PathBuf>,
}

/// A progress bar on stderr, when it is a terminal.
fn bar() -> ProgressBar {
    let bar = ProgressBar::with_draw_target(
        None,
        if std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        },
    );
    if let Ok(style) =
        ProgressStyle::with_template("{wide_bar} {pos}/{len} cells, {elapsed} · {msg}")
    {
        bar.set_style(style);
    }
    bar
}

pub fn run(args: &Args) -> Result<(), String> {
    // Every input and output is checked before the sweep: --out (written
    // as a set: staged beside it, renamed into place), --accuracy and its
    // pages, the scenes (each with a camera) and the methods.
    crate::out_dir(&args.out)?;
    let staged = Staged::new(&args.out).map_err(|e| format!("--out {e}"))?;
    if let Some(dir) = &args.accuracy {
        crate::writable_dir("--accuracy", dir)?;
        report::check_accuracy(dir).map_err(|e| format!("--accuracy {e}"))?;
    }
    let results = if args.merge.is_empty() {
        let names: Vec<String> = if args.scenes.is_empty() {
            BUILTIN_NAMES.iter().map(|s| (*s).to_owned()).collect()
        } else {
            args.scenes.clone()
        };
        let cases = names
            .iter()
            .map(|n| {
                let scene = resolve_scene(n)?;
                if scene.camera().is_none() {
                    return Err(format!(
                        "--scene {n}: the scene has no camera (the report renders each scene from its camera)"
                    ));
                }
                Ok(Case {
                    name: n.clone(),
                    scene,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        for m in &args.methods {
            softshadow::method::parse(m).map_err(|e| format!("--method {m}: {e}"))?;
        }
        let config = Config {
            side: args.side,
            runs: args.runs,
            mc: (1..=20)
                .map(|k| 1u32 << k)
                .take_while(|&n| n <= args.mc_max)
                .collect(),
            methods: args.methods.clone(),
            shard: args.shard,
            picture_side: args.pictures,
            own: Vec::new(),
        };
        let bar = bar();
        let progress = |done: usize, total: usize, what: &str| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
            bar.set_message(what.to_owned());
        };
        let part = report::run(&cases, &config, Some(staged.path()), &progress)?;
        bar.finish_and_clear();
        let results = report::finish(part);
        report::write(&results, staged.path())?;
        results
    } else {
        report::merge_into(&args.merge, staged.path())?
    };
    staged.commit().map_err(|e| format!("--out {e}"))?;
    if let Some(dir) = &args.accuracy {
        let command = std::iter::once("softshadow".to_owned())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>()
            .join(" ");
        report::write_accuracy(&results, dir, &command)?;
    }
    let missing = results.config.cells.saturating_sub(results.cells.len());
    say!(
        "wrote {} ({} cells{})",
        args.out.join("index.md").display(),
        results.cells.len(),
        if missing > 0 {
            format!(", {missing} of the sweep's in other parts")
        } else {
            String::new()
        }
    );
    // A scene that could not be prepared is in the index, and fails the
    // run.
    let unprepared = results.unprepared();
    if let Some((scene, why)) = unprepared.first() {
        return Err(format!(
            "{} of {} scenes could not be prepared (listed in {}): {scene}: {why}",
            unprepared.len(),
            results.config.scenes.len(),
            args.out.join("index.md").display()
        ));
    }
    Ok(())
}
