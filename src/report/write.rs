//! Writing a report: `results.json`, `index.md`, the plots, and the
//! accuracy pages under `docs/accuracy/`.

use super::names::{Names, GAP};
use super::papers::PAPERS;
use super::plots;
use super::ReportError;
use super::{CellRecord, Errors, Results, SceneRecord, GROUPS, PIECES, SLOW_RUN};
use crate::method::registry::REGISTRY;
use crate::output::image::Rgb;
use crate::scene::file::{read_input, MAX_TEXT_BYTES};
use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;
use std::path::Path;

/// The line of an accuracy page under which the report writes; what is
/// above it (the page's title and prose) is kept.
pub const ACCURACY_MARKER: &str =
    "<!-- Tables below are written by `softshadow report --accuracy`: edit above this line. -->";

/// `a` and `b` side by side, `b` on the right, a white gap between.
pub(crate) fn side_by_side(a: &Rgb, b: &Rgb) -> Rgb {
    let (w, h) = (a.width + GAP + b.width, a.height.max(b.height));
    let mut data = vec![255u8; (3 * w * h) as usize];
    for (img, x0) in [(a, 0), (b, a.width + GAP)] {
        for y in 0..img.height {
            let src = &img.data[(3 * y * img.width) as usize..(3 * (y + 1) * img.width) as usize];
            let at = (3 * (y * w + x0)) as usize;
            data[at..at + src.len()].copy_from_slice(src);
        }
    }
    Rgb {
        width: w,
        height: h,
        data,
    }
}

fn write_file(path: &Path, text: &str) -> Result<(), ReportError> {
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| ReportError::file(parent, e))?;
    }
    // Atomically: a reader never sees half a report, a symlink is replaced.
    crate::output::image::write_atomically(path, text.as_bytes())
        .map_err(|e| ReportError::file(path, e))
}

/// The cells of each scene, by name, in the results' order.
fn by_scene(results: &Results) -> HashMap<&str, Vec<&CellRecord>> {
    let mut out: HashMap<&str, Vec<&CellRecord>> = HashMap::new();
    for c in &results.cells {
        out.entry(c.scene.as_str()).or_default().push(c);
    }
    out
}

/// Writes `results.json`, `index.md` and `plots/` into `dir` (the
/// pictures were written by the run): into a fresh folder
/// ([`Staged::path`](super::Staged::path)), or what an earlier report left
/// there stays beside. The results are [checked whole](Results::check)
/// first: nothing is written from results that are not.
///
/// # Errors
/// Results that are not whole; a file that cannot be written.
pub fn write(results: &Results, dir: &Path) -> Result<(), ReportError> {
    results
        .check()
        .map_err(|e| e.of_part("the results are not whole"))?;
    let path = dir.join("results.json");
    let json = serde_json::to_string_pretty(results).map_err(|e| ReportError::file(&path, e))?;
    write_file(&path, &json)?;
    let names = Names::new(&results.config);
    let number = results.config.scene_numbers();
    let cells = by_scene(results);
    let mut plots_written: HashMap<&str, Vec<String>> = HashMap::new();
    for scene in &results.scenes {
        let k = number[scene.name.as_str()];
        let mine = cells
            .get(scene.name.as_str())
            .map_or(&[][..], Vec::as_slice);
        let written = plots_written.entry(&scene.name).or_default();
        for (g, group) in GROUPS.iter().enumerate() {
            if let Some(svg) = plots::error_against_time(&results.config, scene, mine, g) {
                let name = names.plot(k, group);
                write_file(&dir.join(&name), &svg)?;
                written.push(name);
            }
        }
        if let Some(svg) = plots::profile(scene, mine) {
            let name = names.plot(k, "profile");
            write_file(&dir.join(&name), &svg)?;
            written.push(name);
        }
    }
    write_file(
        &dir.join("index.md"),
        &index(results, &cells, &plots_written),
    )
}

fn ms(c: &CellRecord) -> String {
    c.seconds
        .map_or("—".to_owned(), |s| format!("{:.1}", s * 1e3))
}

fn opt<T: std::fmt::Display>(x: Option<T>) -> String {
    x.map_or("—".to_owned(), |x| x.to_string())
}

/// The report's `index.md`.
fn index(
    results: &Results,
    cells: &HashMap<&str, Vec<&CellRecord>>,
    plots: &HashMap<&str, Vec<String>>,
) -> String {
    let mut s = String::new();
    preamble(&mut s, results);
    let unprepared = results.unprepared();
    if !unprepared.is_empty() {
        let _ = writeln!(s, "## Scenes that could not be prepared\n");
        let _ = writeln!(
            s,
            "These scenes have no results: their frame or their exact answer could not be made.\n"
        );
        for (scene, why) in &unprepared {
            let _ = writeln!(s, "- `{scene}`: {why}");
        }
        let _ = writeln!(s);
    }
    summary(&mut s, results);
    papers(&mut s, results);
    for scene in &results.scenes {
        let mine = cells
            .get(scene.name.as_str())
            .map_or(&[][..], Vec::as_slice);
        let plots = plots
            .get(scene.name.as_str())
            .map_or(&[][..], Vec::as_slice);
        scene_section(&mut s, results, scene, mine, plots);
    }
    s
}

/// The title, the machines and what the columns mean.
fn preamble(s: &mut String, results: &Results) {
    let c = &results.config;
    let _ = writeln!(s, "# Soft shadows: accuracy against run time\n");
    let _ = writeln!(
        s,
        "Every scene × method setting of the registry, on each scene's camera at {0}×{0}, \
         against the exact reference; Monte Carlo at {1} samples as the yardstick. Written by \
         `softshadow report`; every number is in [`results.json`](results.json).\n",
        c.side,
        c.mc.iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        s,
        "Machine{}:\n",
        if results.machines.len() > 1 {
            "s (cells timed on different machines are marked with the machine's number)"
        } else {
            ""
        }
    );
    for (k, m) in results.machines.iter().enumerate() {
        let _ = writeln!(s, "{}. {m}", k + 1);
    }
    let _ = writeln!(
        s,
        "\n**Time** is the wall time of `method::run` on fresh stages whose BVH is built \
         beforehand — the maps a method builds are paid, the BVH and the primary rays (shared, \
         listed per scene) are not — the median of {} runs (one where a run takes over {SLOW_RUN} \
         s; each cell's count is in `results.json`). **Error** is `V − V_exact` (negative: too \
         dark) over four receiver groups: all, the exact penumbra (`{margin:e} < V_exact < 1 − {margin:e}`), the \
         ground (object 0) and the occluders (the other objects); \"shaded\" is the error of \
         `V·max(0, n·l̂)` (`l̂` toward the light's centre), what the papers' pictures show. \
         **MC N** is the Monte Carlo sample count of equal RMSE: per scene, Monte Carlo's RMSE \
         over N = {} is fitted by a power law `a·N^b` (least squares in log–log), and the N \
         where it meets the method's RMSE is given, or \"< {}\" / \"> {}\" outside the measured \
         range (not extrapolated). **Speed-up** is Monte Carlo's time at that N — its measured \
         times fitted by a line in N — over the method's time.\n",
        c.runs,
        c.mc.iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(", "),
        c.mc.first().copied().unwrap_or(0),
        c.mc.last().copied().unwrap_or(0),
        margin = crate::definitions::PENUMBRA_MARGIN,
    );
}

/// The summary table: per scene and method, time, errors and Monte Carlo
/// equivalents.
fn summary(s: &mut String, results: &Results) {
    let multi = results.machines.len() > 1;
    let _ = writeln!(s, "## Summary\n");
    let _ = writeln!(
        s,
        "| scene | method | time (ms) | RMSE | RMSE penumbra | RMSE shaded | MC N of equal RMSE | (penumbra) | speed-up over MC |{}",
        if multi { " machine |" } else { "" }
    );
    let _ = writeln!(
        s,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|{}",
        if multi { "---:|" } else { "" }
    );
    for cell in results.cells.iter().filter(|c| c.base != "mc") {
        let Some(e) = cell.errors else { continue };
        let shaded = cell.shaded.map_or(0.0, |x| x[0].rmse);
        let _ = writeln!(
            s,
            "| {} | `{}` | {} | {:.4} | {:.4} | {:.4} | {} | {} | {} |{}",
            cell.scene,
            cell.method,
            ms(cell),
            e[0].rmse,
            e[1].rmse,
            shaded,
            opt(cell.mc_equal),
            opt(cell.mc_equal_penumbra),
            cell.speedup.map_or("—".to_owned(), |x| format!("{x:.2}×")),
            if multi {
                format!(" {} |", cell.machine + 1)
            } else {
                String::new()
            }
        );
    }
}

/// The papers' own speed figures beside ours.
fn papers(s: &mut String, results: &Results) {
    let c = &results.config;
    let _ = writeln!(s, "\n## What the papers report\n");
    let _ = writeln!(
        s,
        "Each paper's own speed figures beside our time on our closest scene. Different hardware \
         (GPUs of 2002–2016 against this CPU), different scenes and resolutions: the rows place \
         the orders of magnitude side by side, no more. The papers give no error figures.\n"
    );
    let _ = writeln!(s, "| method | paper | scene | resolution | hardware | the paper's speed | ours: scene, time at {0}² |", c.side);
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for p in PAPERS {
        let ours = results
            .cells
            .iter()
            .find(|x| x.scene == p.ours && x.method == p.method && x.seconds.is_some())
            .map_or("—".to_owned(), |x| format!("`{}`, {} ms", p.ours, ms(x)));
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | {} | {} |",
            p.method, p.paper, p.scene, p.resolution, p.hardware, p.speed, ours
        );
    }
}

/// One row of the errors table.
fn error_row(s: &mut String, method: &str, group: &str, e: &Errors) {
    let _ = writeln!(
        s,
        "| `{method}` | {group} | {} | {:.5} | {:.5} | {:.4} | {:.4} | {:+.5} | {:.4} |",
        e.count, e.mean_abs, e.rmse, e.p99_abs, e.max_abs, e.mean_signed, e.share_over_0_05
    );
}

fn scene_section(
    s: &mut String,
    results: &Results,
    scene: &SceneRecord,
    cells: &[&CellRecord],
    plots: &[String],
) {
    let _ = writeln!(s, "\n## `{}`\n", scene.name);
    let _ = writeln!(
        s,
        "{} light; {}×{}, {} receivers ({} in the exact penumbra, {} on the ground, {} on \
         occluders){}. Shared, not in the times: BVH {:.1} ms, primary rays {:.1} ms.\n",
        scene.light,
        scene.width,
        scene.height,
        scene.receivers,
        scene.penumbra,
        scene.groups[2],
        scene.groups[3],
        scene.exact_bound.map_or(String::new(), |b| format!(
            "; the exact answers' largest certified bound {b:.1e}"
        )),
        scene.shared[0] * 1e3,
        scene.shared[1] * 1e3
    );
    if let Some(y) = results.yardsticks.get(&scene.name) {
        let _ =
            writeln!(
            s,
            "Monte Carlo: RMSE ≈ {:.3}·N^{:.3} (all receivers){}; time ≈ {:.2} ms + {:.4} ms·N.\n",
            y.rmse.a,
            y.rmse.b,
            y.rmse_penumbra
                .map_or(String::new(), |p| format!(", {:.3}·N^{:.3} (penumbra)", p.a, p.b)),
            y.seconds.c * 1e3,
            y.seconds.d * 1e3
        );
    }
    for name in plots {
        let _ = writeln!(s, "![{name}]({name})\n");
    }
    let pictures: Vec<&CellRecord> = cells
        .iter()
        .copied()
        .filter(|c| c.picture.is_some())
        .collect();
    if !pictures.is_empty() {
        let _ = writeln!(s, "Shaded (left) and the signed error against exact (right: blue too dark, red too bright, ±0.25 saturates):\n");
        let _ = writeln!(s, "| method | shaded · error |\n|---|---|");
        for c in pictures {
            let p = c.picture.as_deref().unwrap_or_default();
            let _ = writeln!(s, "| `{}` | ![{}]({p}) |", c.method, c.method);
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(s, "| method | receivers | count | mean abs | RMSE | p99 abs | max | mean signed | share > 0.05 |");
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for c in cells {
        match (&c.errors, &c.shaded) {
            (Some(e), Some(sh)) => {
                for (g, name) in GROUPS.iter().enumerate() {
                    if e[g].count > 0 {
                        error_row(s, &c.method, name, &e[g]);
                    }
                }
                error_row(s, &c.method, "shaded, all", &sh[0]);
                error_row(s, &c.method, "shaded, penumbra", &sh[1]);
            }
            _ => {
                let _ = writeln!(s, "| `{}` | {} | | | | | | | |", c.method, c.status);
            }
        }
    }
    let lead = format!("{PIECES_INTRO} RMSE of `V`:");
    pieces_rmse(s, scene, cells, &lead);
}

/// What the groups by the light's pieces are, before their tables.
const PIECES_INTRO: &str = "By the visible pieces of the light: each receiver in one group by how \
     the exact reference sees the segment light from it — one piece holding an end of the light \
     (the view occluding edges soft shadows models: one occluding edge per end), one piece \
     inside, two or more pieces, none (umbra), the whole light.";

/// The RMSE of `V` per group by the light's pieces ([`PIECES`]) after
/// the `lead` line: the groups' receivers, then one row per cell that has
/// them (but `exact`, 0 throughout); nothing on a scene without them.
fn pieces_rmse(s: &mut String, scene: &SceneRecord, cells: &[&CellRecord], lead: &str) {
    let Some(counts) = scene.pieces else { return };
    let rows: Vec<(&str, [Errors; 5])> = cells
        .iter()
        .filter(|c| c.method != "exact")
        .filter_map(|c| Some((c.method.as_str(), c.pieces?)))
        .collect();
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(s, "\n{lead}\n");
    let counts: Vec<String> = counts.iter().map(usize::to_string).collect();
    let _ = writeln!(s, "| method | {} |", PIECES.join(" | "));
    let _ = writeln!(s, "|---|{}", "---:|".repeat(PIECES.len()));
    let _ = writeln!(s, "| receivers | {} |", counts.join(" | "));
    for (method, e) in rows {
        let cols: Vec<String> = e
            .iter()
            .map(|g| {
                if g.count > 0 {
                    format!("{:.4}", g.rmse)
                } else {
                    "—".to_owned()
                }
            })
            .collect();
        let _ = writeln!(s, "| `{method}` | {} |", cols.join(" | "));
    }
}

/// The settings a method's accuracy page compares by the light's pieces
/// besides its own and `hard`: every other method's defaults and Monte
/// Carlo at these sample counts.
const PIECES_BESIDE_MC: [&str; 2] = ["mc:4", "mc:16"];

/// The accuracy pages' file names: `methods.md` and one per method with
/// comparison settings (but `hard`, beside every other).
fn accuracy_pages() -> impl Iterator<Item = String> {
    std::iter::once("methods.md".to_owned()).chain(
        REGISTRY
            .iter()
            .filter(|e| !e.compare.is_empty() && e.name != "hard")
            .map(|e| format!("{}.md", e.name)),
    )
}

/// Checks, before a sweep, that the accuracy pages in `dir` can be
/// updated: each page there is a regular UTF-8 file of at most
/// [`MAX_TEXT_BYTES`] (a missing page is written new). The folder itself
/// is the caller's to make and check.
///
/// # Errors
/// One line naming the page.
pub fn check_accuracy(dir: &Path) -> Result<(), ReportError> {
    for page in accuracy_pages() {
        read_page(&dir.join(page))?;
    }
    Ok(())
}

/// An accuracy page's text (`None`: there is none), read as every input
/// is: a regular file (never a FIFO or device) within [`MAX_TEXT_BYTES`].
fn read_page(path: &Path) -> Result<Option<String>, ReportError> {
    let fail = |e: String| ReportError::file(path, e);
    match std::fs::metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(fail(format!("cannot read: {e}"))),
        Ok(_) => {}
    }
    let bytes = read_input(path, MAX_TEXT_BYTES).map_err(|e| fail(e.to_string()))?;
    String::from_utf8(bytes)
        .map(Some)
        .map_err(|_| fail("not UTF-8 text".to_owned()))
}

/// Writes the accuracy pages into `dir`: `methods.md` (every setting on
/// every scene, all receivers and the penumbra) and one page per method
/// (its comparison settings by receiver group, the hard shadow beside).
/// Each page keeps what is above [`ACCURACY_MARKER`]; each is read as
/// [`check_accuracy`] reads it.
///
/// # Errors
/// A page that cannot be read or written.
pub fn write_accuracy(results: &Results, dir: &Path, command: &str) -> Result<(), ReportError> {
    let cells = by_scene(results);
    let mut methods = String::new();
    let _ = writeln!(
        methods,
        "Regenerate with `{command}` ({}).\n",
        results.machines.join("; ")
    );
    let _ = writeln!(methods, "| scene | method | time (ms) | mean abs | RMSE | p99 abs | max | mean signed | share > 0.05 | RMSE penumbra |");
    let _ = writeln!(methods, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let keep_mc = ["mc:16", "mc:256"];
    for c in &results.cells {
        if c.base == "mc" && !keep_mc.contains(&c.method.as_str()) {
            continue;
        }
        match c.errors {
            Some(e) => {
                let _ = writeln!(
                    methods,
                    "| {} | {} | {} | {:.5} | {:.5} | {:.4} | {:.4} | {:+.5} | {:.4} | {:.5} |",
                    c.scene,
                    c.method,
                    ms(c),
                    e[0].mean_abs,
                    e[0].rmse,
                    e[0].p99_abs,
                    e[0].max_abs,
                    e[0].mean_signed,
                    e[0].share_over_0_05,
                    e[1].rmse
                );
            }
            None => {
                let _ = writeln!(
                    methods,
                    "| {} | {} | {} | | | | | | | |",
                    c.scene, c.method, c.status
                );
            }
        }
    }
    horizon_table(&mut methods, results);
    update_page(
        &dir.join("methods.md"),
        "Accuracy of the methods against the exact answer",
        &methods,
    )?;
    for entry in REGISTRY.iter().filter(|e| !e.compare.is_empty()) {
        if entry.name == "hard" {
            continue;
        }
        let mut page = String::new();
        let _ = writeln!(
            page,
            "Regenerate with `{command}` ({}).\n",
            results.machines.join("; ")
        );
        let mut wanted: HashSet<&str> = entry.compare.iter().copied().collect();
        wanted.insert("hard");
        for scene in &results.scenes {
            let mine = cells
                .get(scene.name.as_str())
                .map_or(&[][..], Vec::as_slice);
            let rows: Vec<&CellRecord> = mine
                .iter()
                .copied()
                .filter(|c| wanted.contains(c.method.as_str()) && c.errors.is_some())
                .collect();
            if rows.iter().all(|c| c.base == "hard") {
                continue;
            }
            let _ = writeln!(
                page,
                "## `{}` ({} receivers, {} in the exact penumbra)\n",
                scene.name, scene.receivers, scene.penumbra
            );
            let _ = writeln!(page, "| method | receivers | count | mean abs | RMSE | p99 abs | max | mean signed | share > 0.05 |");
            let _ = writeln!(page, "|---|---|---:|---:|---:|---:|---:|---:|---:|");
            for c in &rows {
                let e = c.errors.unwrap_or_default();
                for (g, name) in GROUPS.iter().enumerate() {
                    if e[g].count > 0 {
                        error_row(&mut page, &c.method, name, &e[g]);
                    }
                }
            }
            let _ = writeln!(page);
            pieces_page(&mut page, scene, &rows, mine);
        }
        let title = format!("`{}` against the exact reference", entry.name);
        update_page(&dir.join(format!("{}.md", entry.name)), &title, &page)?;
    }
    Ok(())
}

/// A method page's errors by the light's pieces: the full summaries of
/// its `rows` per group, then the RMSE per group of the rows beside the
/// other methods' defaults and Monte Carlo at [`PIECES_BESIDE_MC`] among
/// the scene's `cells`. Nothing on a scene without them.
fn pieces_page(s: &mut String, scene: &SceneRecord, rows: &[&CellRecord], cells: &[&CellRecord]) {
    if scene.pieces.is_none() {
        return;
    }
    let _ = writeln!(s, "{PIECES_INTRO}\n");
    let _ = writeln!(s, "| method | receivers | count | mean abs | RMSE | p99 abs | max | mean signed | share > 0.05 |");
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for c in rows {
        for (name, e) in PIECES.iter().zip(c.pieces.unwrap_or_default()) {
            if e.count > 0 {
                error_row(s, &c.method, name, &e);
            }
        }
    }
    let mut beside: Vec<&CellRecord> = rows.to_vec();
    beside.extend(cells.iter().copied().filter(|c| {
        let other =
            super::is_default_setting(&c.method) || PIECES_BESIDE_MC.contains(&c.method.as_str());
        other && !rows.iter().any(|r| r.method == c.method)
    }));
    let lead = format!(
        "RMSE of `V` by the pieces, beside the other methods' defaults and Monte Carlo (`{}`):",
        PIECES_BESIDE_MC.join("`, `")
    );
    pieces_rmse(s, scene, &beside, &lead);
    let _ = writeln!(s);
}

/// The horizon option's effect: per scene, each setting `M` beside
/// `M,horizon` (or `M:horizon`), RMSE over every receiver, without → with.
fn horizon_table(s: &mut String, results: &Results) {
    let with_horizon = |m: &str| {
        if m.contains(':') {
            format!("{m},horizon")
        } else {
            format!("{m}:horizon")
        }
    };
    let by_cell: HashMap<(&str, &str), f64> = results
        .cells
        .iter()
        .filter_map(|c| Some(((c.scene.as_str(), c.method.as_str()), c.errors?[0].rmse)))
        .collect();
    let rmse = |scene: &str, m: &str| by_cell.get(&(scene, m)).copied();
    let settings: HashSet<&str> = results.config.settings.iter().map(String::as_str).collect();
    let pairs: Vec<&str> = results
        .config
        .settings
        .iter()
        .map(String::as_str)
        .filter(|m| !m.contains("horizon") && settings.contains(with_horizon(m).as_str()))
        .collect();
    if pairs.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "\n## The horizon option: RMSE over every receiver, without → with\n"
    );
    let _ = writeln!(s, "| scene | {} |", pairs.join(" | "));
    let _ = writeln!(s, "|---|{}", "---|".repeat(pairs.len()));
    for scene in &results.scenes {
        let cols: Vec<String> = pairs
            .iter()
            .map(
                |m| match (rmse(&scene.name, m), rmse(&scene.name, &with_horizon(m))) {
                    (Some(a), Some(b)) => format!("{a:.4} → {b:.4}"),
                    _ => "—".to_owned(),
                },
            )
            .collect();
        let _ = writeln!(s, "| {} | {} |", scene.name, cols.join(" | "));
    }
}

/// Rewrites what is below the marker of the page at `path` (a new page
/// gets `title` and the marker).
fn update_page(path: &Path, title: &str, tables: &str) -> Result<(), ReportError> {
    let head = match read_page(path)? {
        Some(text) => match text.find(ACCURACY_MARKER) {
            Some(k) => text[..k].to_owned(),
            None => format!("{}\n\n", text.trim_end()),
        },
        None => format!("# {title}\n\n"),
    };
    write_file(path, &format!("{head}{ACCURACY_MARKER}\n\n{tables}"))
}
