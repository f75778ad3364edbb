//! `softshadow stability`: the stability suite (`softshadow::report::
//! stability`), written as `stability.md`.

use clap::Args as ClapArgs;
use softshadow::output::image::write_atomically;
use softshadow::report::{machine_line, stability};
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(ClapArgs)]
pub struct Args {
    /// The folder `stability.md` is written to (created if missing).
    #[arg(long, default_value = "docs")]
    out: PathBuf,
    /// The side of the camera frames of the methods' scenes.
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(8..=2048))]
    side: u32,
}

pub fn run(args: &Args) -> Result<(), String> {
    crate::out_dir(&args.out)?;
    let terminal = std::io::stderr().is_terminal();
    let rows = stability::run(args.side, &|what| {
        if terminal {
            note!("stability: {what} …");
        }
    });
    let command = std::iter::once("softshadow".to_owned())
        .chain(std::env::args().skip(1))
        .collect::<Vec<_>>()
        .join(" ");
    let text = stability::markdown(&rows, &machine_line(), &command);
    let path = args.out.join("stability.md");
    write_atomically(&path, text.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
    say!("wrote {} ({} rows)", path.display(), rows.len());
    Ok(())
}
