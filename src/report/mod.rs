//! The accuracy-against-run-time report (`softshadow report`): every
//! scene × method setting × Monte Carlo yardstick, timed and measured
//! against the exact reference, written as Markdown tables, SVG plots,
//! side-by-side pictures and `results.json`.
//!
//! # The sweep
//!
//! A *cell* is one (scene, method setting). The settings are the
//! registry's: every built method's [`Entry::compare`](crate::method::registry::Entry::compare) list (so a method
//! registered tomorrow is in the next report with no list here), `exact`
//! (the reference itself, for its time), and the yardstick `mc:N` for each
//! `N` of [`Config::mc`]. A setting whose method does not handle the
//! scene's light is a cell reading "n/a (segment light)". Cells are
//! numbered in a fixed order (scenes, then settings); shard `i/n` runs the
//! cells whose number is `i − 1` modulo `n`.
//!
//! # What a cell measures
//!
//! - **Time**: the wall time of [`method::run`] on fresh [`Stages`] whose BVH
//!   is built beforehand (so the maps a method builds are paid, the shared
//!   BVH and primary rays not; those are in [`SceneRecord`]), the median of
//!   [`Config::runs`] runs — fewer when a run takes more than
//!   [`SLOW_RUN`] seconds, the count kept per cell.
//! - **Error** of `V` against [`Exact`](struct@Exact): mean absolute, RMSE,
//!   99th percentile, maximum, mean signed, share over 0.05
//!   ([`ErrorSummary`]) over four groups ([`GROUPS`]): every receiver, the
//!   exact penumbra ([`in_penumbra`](crate::definitions::in_penumbra)), the ground (object 0, the floor of
//!   every built-in scene) and the occluders (every other object); and the
//!   same for the shaded value `V·max(0, n·l̂)` (`l̂` toward the light's
//!   centre), which is what the papers' pictures show.
//! - **Error by the light's pieces** of a segment light: of `V` over the
//!   receivers grouped by the light's visible pieces as the exact
//!   reference sees them ([`PIECES`],
//!   [`Pieces`](crate::kernel::receiver_view::Pieces)).
//! - **The falloff profile**: `V` along the scene's profile row, the image
//!   row with the most exact-penumbra receivers.
//! - **The yardstick** (derived when the parts are finished, [`finish`]):
//!   per scene, Monte Carlo's RMSE against `N` fitted by a power law (least
//!   squares in log–log) and its time against `N` by a line; per cell, the
//!   `N` at which the fitted RMSE equals the cell's ([`Equal`]: stated as
//!   below or above the measured range rather than extrapolated) and the
//!   speed-up, Monte Carlo's fitted time at that `N` over the cell's time.
//!
//! # `results.json`
//!
//! [`Results`] serialized with `serde_json`: `format` ([`FORMAT`]),
//! `config` ([`ConfigRecord`]: `side`, `runs`, `mc`, `pictures`, the
//! sweep's `scenes` and `settings` in cell order, and `cells`, their
//! product), `machines` (one line per machine that ran a part), `scenes`
//! ([`SceneRecord`]), `cells` ([`CellRecord`]) and `yardsticks` (per
//! scene, [`Yardstick`]). Times are seconds. Every number is finite:
//! what is written reads back, bit for bit. The `pieces` of a scene and
//! of its cells are optional (segment lights only): older results read.
//!
//! # The report's folder
//!
//! `results.json`, `index.md`, `plots/SCENE/WHAT.svg` and
//! `pictures/SCENE/SETTING.png`, where `SCENE` and `SETTING` are the
//! names flattened to letters, digits and `-`, at most 64 bytes, made
//! unique within the sweep (ignoring case) by a suffix `-2`, `-3`, … The
//! folder is written as a set ([`Staged`]): a reader sees the previous
//! report or the new one, never a mix.
//!
//! # Parts and the merge
//!
//! A part is the results of one shard. [`merge`] (and [`merge_into`], from
//! the parts' folders) takes parts only when each is [whole](Results::check)
//! and all are of one sweep (the same [`ConfigRecord`]), and no cell is in
//! two of them; it is linear in the parts' size.

mod check;
mod error;
mod folder;
mod machine;
mod names;
mod papers;
mod plots;
pub mod stability;
mod write;

pub use crate::output::yardstick::{default_mc, Equal, Line, PowerLaw, Yardstick};
pub use check::{MAX_LINE, MAX_NAME, MAX_SIDE};
pub use error::ReportError;
pub use folder::{merge_into, read_part, Staged};
pub use machine::machine_line;
pub use write::{check_accuracy, write, write_accuracy, ACCURACY_MARKER};

use crate::method::registry::{self, REGISTRY};
use crate::method::{self, Exact, Method};
use crate::output::image::ErrorSummary;
use crate::output::score::{group_errors, group_masks, pieces_masks, scaled, shading_factors};
use crate::render::{Frame, Stages};
use crate::scene::{Light, LightKind, Scene};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::sync::Arc;
use std::time::Instant;

/// The format tag of `results.json`.
pub const FORMAT: &str = "softshadow-report/2";

/// A run longer than this many seconds is not repeated.
pub const SLOW_RUN: f64 = 2.0;

/// The receiver groups, in table order (the renderer's, shared with
/// `softshadow score`).
pub use crate::output::score::GROUPS;

/// The groups by the visible pieces of a segment light, in table order.
pub use crate::output::score::PIECES;

/// One part of a sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Which part, from 1.
    pub index: u32,
    /// Of how many.
    pub count: u32,
}

/// Why a text is not a [`Shard`].
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ShardError {
    /// Not two whole numbers `i/n`.
    Syntax {
        /// The text given.
        text: String,
    },
    /// `i` is 0 or greater than `n`.
    OutOfRange {
        /// Which part.
        index: u32,
        /// Of how many.
        count: u32,
    },
}

impl_error!(ShardError, |error, f| {
    match error {
        ShardError::Syntax { text } => write!(f, "'{text}'"),
        ShardError::OutOfRange { index, count } => write!(f, "'{index}/{count}'"),
    }?;
    write!(f, ": a shard is i/n with 1 ≤ i ≤ n")
});

impl std::str::FromStr for Shard {
    type Err = ShardError;

    /// `i/n` with `1 ≤ i ≤ n`.
    fn from_str(s: &str) -> Result<Shard, ShardError> {
        let syntax = || ShardError::Syntax { text: s.to_owned() };
        let (i, n) = s.split_once('/').ok_or_else(syntax)?;
        let (index, count): (u32, u32) = (
            i.trim().parse().map_err(|_| syntax())?,
            n.trim().parse().map_err(|_| syntax())?,
        );
        if index == 0 || index > count {
            return Err(ShardError::OutOfRange { index, count });
        }
        Ok(Shard { index, count })
    }
}

/// What to sweep.
#[derive(Clone, Debug)]
pub struct Config {
    /// The image side of every scene's camera frame (default 256).
    pub side: u32,
    /// Timed runs per cell (default 3).
    pub runs: u32,
    /// The yardstick's Monte Carlo sample counts (default [`default_mc`]).
    pub mc: Vec<u32>,
    /// Method settings to run instead of the registry's (empty: the
    /// registry's); the yardstick and `exact` are always run.
    pub methods: Vec<String>,
    /// The part of the sweep to run (`None`: all of it).
    pub shard: Option<Shard>,
    /// The side of the pictures (`0`: none); the scene named `default`
    /// gets twice this; never more than [`Config::side`].
    pub picture_side: u32,
    /// Methods of one's own (outside the registry), swept after the
    /// registry's settings like any other: tables, error-against-time plots
    /// and pictures, named by [`Method::name`] (which must be distinct from
    /// every other setting's name and contain no `/`).
    pub own: Vec<Arc<dyn Method>>,
}

impl Default for Config {
    fn default() -> Config {
        Config {
            side: 256,
            runs: 3,
            mc: default_mc(),
            methods: Vec::new(),
            shard: None,
            picture_side: 128,
            own: Vec::new(),
        }
    }
}

/// A scene to sweep: its name (a built-in name or a file) and the scene.
#[derive(Clone, Debug)]
pub struct Case {
    /// How the report names it: one line of at most [`MAX_NAME`] bytes,
    /// distinct from the other cases' names.
    pub name: String,
    /// The scene; without a camera (or with receivers the exact reference
    /// refuses, inside the light), its cells record why and the scene is
    /// listed by [`Results::unprepared`].
    pub scene: Scene,
}

/// What the report records of a scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneRecord {
    /// The scene's name.
    pub name: String,
    /// Its light's kind (`sphere`, `segment`, …).
    pub light: String,
    /// The frame's size.
    pub width: u32,
    /// The frame's height.
    pub height: u32,
    /// Receivers (eye-visible points).
    pub receivers: usize,
    /// Receivers in the exact penumbra.
    pub penumbra: usize,
    /// Receivers per group, [`GROUPS`] order.
    pub groups: [usize; 4],
    /// Receivers per group by the light's pieces, [`PIECES`] order: on a
    /// segment-light scene (`None` on others, and in parts written before
    /// it was recorded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pieces: Option<[usize; 5]>,
    /// The shared stages' seconds: BVH build, primary rays.
    pub shared: [f64; 2],
    /// The profile row (image row) and its pixels' columns.
    pub profile_row: u32,
    /// The profile's columns, one per receiver on the row.
    pub profile_columns: Vec<u32>,
    /// The exact `V` along the profile.
    pub profile_exact: Vec<f64>,
    /// The largest certified bound of the exact answers over the frame's
    /// receivers (`|V − V_true| ≤ bound` for each:
    /// [`exact::visibility_bounded`](crate::reference::exact::visibility_bounded));
    /// `None` in parts written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exact_bound: Option<f64>,
    /// The machine (index into [`Results::machines`]) that built this
    /// record.
    pub machine: usize,
}

/// One error summary, as recorded: [`ErrorSummary`].
pub type Errors = ErrorSummary;

/// One cell of the sweep, as recorded.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CellRecord {
    /// Its number in the sweep.
    pub index: usize,
    /// The scene's name.
    pub scene: String,
    /// The method setting (`sism:exact-union`).
    pub method: String,
    /// The method's base name (`sism`).
    pub base: String,
    /// `ok`, `n/a (segment light)`, or the error.
    pub status: String,
    /// The machine (index into [`Results::machines`]) that ran it.
    pub machine: usize,
    /// Seconds of each timed run.
    pub runs: Vec<f64>,
    /// Their median.
    pub seconds: Option<f64>,
    /// Errors of `V` per group ([`GROUPS`] order).
    pub errors: Option<[Errors; 4]>,
    /// Errors of the shaded value per group.
    pub shaded: Option<[Errors; 4]>,
    /// Errors of `V` per group by the light's pieces ([`PIECES`] order),
    /// where the scene records them ([`SceneRecord::pieces`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pieces: Option<[Errors; 5]>,
    /// `V` along the scene's profile.
    pub profile: Vec<f64>,
    /// The side-by-side picture, relative to the report's folder.
    pub picture: Option<String>,
    /// The Monte Carlo sample count of equal RMSE over every receiver
    /// (derived).
    pub mc_equal: Option<Equal>,
    /// The same over the penumbra (derived).
    pub mc_equal_penumbra: Option<Equal>,
    /// Monte Carlo's time at `mc_equal` over this cell's (derived).
    pub speedup: Option<f64>,
}

/// A report, or one part of one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// [`FORMAT`].
    pub format: String,
    /// The sweep's settings.
    pub config: ConfigRecord,
    /// One line per machine that ran a part (CPU, cores, load).
    pub machines: Vec<String>,
    /// The scenes, in sweep order.
    pub scenes: Vec<SceneRecord>,
    /// The cells, by number.
    pub cells: Vec<CellRecord>,
    /// Per scene name, Monte Carlo's fitted curves (derived).
    pub yardsticks: BTreeMap<String, Yardstick>,
}

/// What of [`Config`] a report records: what makes a sweep one sweep.
/// Cell `k` is scene `scenes[k / settings.len()]` under setting
/// `settings[k % settings.len()]`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ConfigRecord {
    /// The frames' side.
    pub side: u32,
    /// Timed runs per cell (at most).
    pub runs: u32,
    /// The yardstick's sample counts.
    pub mc: Vec<u32>,
    /// The side of the pictures ([`Config::picture_side`]).
    pub pictures: u32,
    /// The sweep's scenes, in order.
    pub scenes: Vec<String>,
    /// The sweep's settings, in order ([`settings`]).
    pub settings: Vec<String>,
    /// The sweep's cell count, scenes × settings.
    pub cells: usize,
}

impl ConfigRecord {
    /// Each scene's number in the sweep, by name.
    pub(crate) fn scene_numbers(&self) -> HashMap<&str, usize> {
        self.scenes
            .iter()
            .enumerate()
            .map(|(k, s)| (s.as_str(), k))
            .collect()
    }
}

/// The settings a sweep runs on every scene: `exact`, the registry's
/// comparison settings (or `config.methods`), then the yardstick.
#[must_use]
pub fn settings(config: &Config) -> Vec<String> {
    let mut out = vec!["exact".to_owned()];
    if config.methods.is_empty() {
        for entry in REGISTRY {
            out.extend(entry.compare.iter().map(|s| (*s).to_owned()));
        }
    } else {
        out.extend(config.methods.iter().filter(|m| *m != "exact").cloned());
    }
    out.extend(config.own.iter().map(|m| m.name()));
    out.extend(config.mc.iter().map(|n| format!("mc:{n}")));
    let mut seen = std::collections::HashSet::new();
    out.retain(|s| seen.insert(s.clone()));
    out
}

/// Whether `setting` is a registered method's defaults (the first of its
/// comparison settings): the one setting per method that gets a picture
/// and a profile line.
pub(crate) fn is_default_setting(setting: &str) -> bool {
    REGISTRY
        .iter()
        .any(|e| e.compare.first().is_some_and(|s| *s == setting))
}

/// The settings that get a picture: `exact`, each method's defaults, and
/// the methods of one's own.
fn pictured(setting: &str, config: &Config) -> bool {
    setting == "exact"
        || config.own.iter().any(|m| m.name() == setting)
        || is_default_setting(setting)
}

/// Progress: called with the cells done, the cells of this part, and what
/// runs now.
pub type Progress<'a> = &'a (dyn Fn(usize, usize, &str) + Sync);

/// One scene's shared state in a run: its frame, the exact answer, the
/// groups and the shading factors.
struct Prepared {
    frame: Frame,
    exact: Vec<f64>,
    groups: [Vec<bool>; 4],
    pieces: Option<[Vec<bool>; 5]>,
    shading: Vec<f64>,
    profile: Vec<usize>,
    record: SceneRecord,
}

/// Runs this part of the sweep over `cases`, writing pictures under
/// `out/pictures` (when `out` is given: a fresh folder, [`Staged::path`]);
/// the derived columns are left empty ([`finish`] fills them).
///
/// # Errors
/// Before any work: a method setting that does not parse, case or setting
/// names that are not distinct one-line names of at most [`MAX_NAME`]
/// bytes, a side beyond `1..=`[`MAX_SIDE`]. Then a picture that cannot be
/// written. A scene that cannot be prepared (no camera, receivers inside
/// the light), a method that fails, are recorded in the cells, not
/// returned ([`Results::unprepared`]).
pub fn run(
    cases: &[Case],
    config: &Config,
    out: Option<&std::path::Path>,
    progress: Progress<'_>,
) -> Result<Results, ReportError> {
    let settings = settings(config);
    let methods: Vec<Arc<dyn Method>> = settings
        .iter()
        .map(|s| match config.own.iter().find(|m| m.name() == *s) {
            Some(own) => Ok(Arc::clone(own)),
            None => registry::parse(s)
                .map(Arc::from)
                .map_err(ReportError::Method),
        })
        .collect::<Result<_, _>>()?;
    let machine = check::one_line(&machine_line(), MAX_LINE);
    let total = cases.len() * settings.len();
    let record = ConfigRecord {
        side: config.side,
        runs: config.runs.max(1),
        mc: config.mc.clone(),
        pictures: config.picture_side,
        scenes: cases.iter().map(|c| c.name.clone()).collect(),
        settings: settings.clone(),
        cells: total,
    };
    record.check()?;
    let names = names::Names::new(&record);
    let mine: Vec<usize> = (0..total)
        .filter(|k| {
            config
                .shard
                .is_none_or(|s| k % s.count as usize == s.index as usize - 1)
        })
        .collect();
    let mut results = Results {
        format: FORMAT.to_owned(),
        config: record,
        machines: vec![machine],
        scenes: Vec::new(),
        cells: Vec::new(),
        yardsticks: BTreeMap::new(),
    };
    let mut done = 0;
    for (s, case) in cases.iter().enumerate() {
        let cells: Vec<usize> = mine
            .iter()
            .copied()
            .filter(|k| k / settings.len() == s)
            .collect();
        if cells.is_empty() {
            continue;
        }
        progress(done, mine.len(), &format!("{}: exact", case.name));
        let prepared = match prepare(case, config) {
            Ok(p) => p,
            Err(e) => {
                for k in cells {
                    results
                        .cells
                        .push(failed(k, case, &settings[k % settings.len()], &e));
                    done += 1;
                }
                continue;
            }
        };
        results.scenes.push(prepared.record.clone());
        for k in cells {
            let setting = &settings[k % settings.len()];
            progress(done, mine.len(), &format!("{}: {setting}", case.name));
            let method = methods[k % settings.len()].as_ref();
            let mut cell = run_cell(k, case, &prepared, method, config);
            if cell.status == "ok" && pictured(setting, config) && config.picture_side > 0 {
                if let Some(dir) = out {
                    let name = names.picture(k);
                    picture(case, &prepared, method, config, &dir.join(&name))?;
                    cell.picture = Some(name);
                }
            }
            results.cells.push(cell);
            done += 1;
        }
    }
    progress(done, mine.len(), "done");
    Ok(results)
}

/// A cell that could not run.
fn failed(index: usize, case: &Case, setting: &str, why: &str) -> CellRecord {
    CellRecord {
        index,
        scene: case.name.clone(),
        method: setting.to_owned(),
        base: base(setting),
        status: error(why),
        machine: 0,
        runs: Vec::new(),
        seconds: None,
        errors: None,
        shaded: None,
        pieces: None,
        profile: Vec::new(),
        picture: None,
        mc_equal: None,
        mc_equal_penumbra: None,
        speedup: None,
    }
}

/// An error's status: one line, at most [`MAX_LINE`] bytes.
fn error(why: &str) -> String {
    check::one_line(&format!("error: {why}"), MAX_LINE)
}

fn base(setting: &str) -> String {
    setting.split(':').next().unwrap_or(setting).to_owned()
}

/// The scene's frame, exact answer, groups and profile.
fn prepare(case: &Case, config: &Config) -> Result<Prepared, String> {
    let scene = &case.scene;
    let camera = scene
        .camera()
        .ok_or("the scene has no camera")?
        .with_resolution(config.side, config.side)
        .map_err(|e| e.to_string())?;
    let stages = Stages::new(scene);
    let bvh = stages.bvh();
    let frame = stages.timed("receivers", || {
        let f = Frame::from_camera(&camera, bvh);
        (f, String::new())
    });
    let exact = method::run(&Exact, &stages, &frame)
        .map_err(|e| format!("exact: {e}"))?
        .output;
    let exact_bound = exact
        .bound
        .as_ref()
        .map(|b| b.iter().copied().fold(0.0, f64::max));
    let exact = exact.visibility;
    let receivers = frame.receivers();
    let groups = group_masks(receivers, &exact);
    let penumbra = groups[1].clone();
    let light = scene.light();
    let pieces = pieces_masks(bvh, light, receivers);
    let shading = shading_factors(light, receivers);
    // The profile: the image row with the most exact-penumbra receivers.
    let (w, h) = frame.size();
    let pixels = frame.pixels();
    let row_count = |row: u32| {
        (0..w)
            .filter(|&c| {
                let k = pixels[(row * w + c) as usize] as usize;
                penumbra.get(k).copied().unwrap_or(false)
            })
            .count()
    };
    let profile_row = (0..h)
        .max_by_key(|&r| (row_count(r), std::cmp::Reverse(r)))
        .unwrap_or(0);
    let (profile, profile_columns): (Vec<usize>, Vec<u32>) = (0..w)
        .filter_map(|c| {
            let k = pixels[(profile_row * w + c) as usize] as usize;
            (k < receivers.len()).then_some((k, c))
        })
        .unzip();
    let stats = stages.stats();
    let record = SceneRecord {
        name: case.name.clone(),
        light: light.kind().name().to_owned(),
        width: w,
        height: h,
        receivers: receivers.len(),
        penumbra: penumbra.iter().filter(|p| **p).count(),
        groups: groups.each_ref().map(|g| g.iter().filter(|x| **x).count()),
        pieces: pieces
            .as_ref()
            .map(|p| p.each_ref().map(|g| g.iter().filter(|x| **x).count())),
        shared: [stats.seconds("bvh"), stats.seconds("receivers")],
        profile_row,
        profile_columns,
        profile_exact: profile.iter().map(|&k| exact[k]).collect(),
        exact_bound,
        machine: 0,
    };
    Ok(Prepared {
        frame,
        exact,
        groups,
        pieces,
        shading,
        profile,
        record,
    })
}

/// The light kind's name for "n/a (… light)".
fn light_name(light: &Light) -> &'static str {
    light.kind().name()
}

/// Times and measures one cell.
fn run_cell(
    index: usize,
    case: &Case,
    prepared: &Prepared,
    method: &dyn Method,
    config: &Config,
) -> CellRecord {
    let setting = method.name();
    let mut cell = failed(index, case, &setting, "");
    let kind: LightKind = case.scene.light().kind();
    if !method.lights().contains(&kind) {
        cell.status = format!("n/a ({} light)", light_name(case.scene.light()));
        return cell;
    }
    let mut visibility = None;
    for _ in 0..config.runs.max(1) {
        let stages = Stages::new(&case.scene);
        stages.bvh();
        let start = Instant::now();
        let run = method::run(method, &stages, &prepared.frame);
        let seconds = start.elapsed().as_secs_f64();
        match run {
            Ok(r) => {
                cell.runs.push(seconds);
                visibility = Some(r.output.visibility);
            }
            Err(e) => {
                cell.status = error(&e.to_string());
                cell.runs.clear();
                return cell;
            }
        }
        if seconds > SLOW_RUN {
            break;
        }
    }
    let Some(v) = visibility else {
        return cell;
    };
    cell.status = "ok".to_owned();
    cell.seconds = Some(median(&cell.runs));
    let exact = &prepared.exact;
    let all = |_| true;
    cell.errors = Some(group_errors(&v, exact, &prepared.groups, all));
    let shade = |x: &[f64]| scaled(x, &prepared.shading);
    cell.shaded = Some(group_errors(
        &shade(&v),
        &shade(exact),
        &prepared.groups,
        all,
    ));
    cell.pieces = prepared
        .pieces
        .as_ref()
        .map(|p| group_errors(&v, exact, p, all));
    cell.profile = prepared.profile.iter().map(|&k| v[k]).collect();
    cell
}

/// The median of `x` (0 for none).
fn median(x: &[f64]) -> f64 {
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    match s.len() {
        0 => 0.0,
        n if n % 2 == 1 => s[n / 2],
        n => 0.5 * (s[n / 2 - 1] + s[n / 2]),
    }
}

/// Writes the cell's side-by-side picture (shaded | signed error) to
/// `path`, of [`names::picture_size`].
fn picture(
    case: &Case,
    prepared: &Prepared,
    method: &dyn Method,
    config: &Config,
    path: &std::path::Path,
) -> Result<(), ReportError> {
    use crate::output::image::{error_heat_map, shaded, shaded_by_ends};
    let stages = Stages::new(&case.scene);
    let run = method::run(method, &stages, &prepared.frame).map_err(|e| {
        ReportError::file(path, format!("the picture's run of {}: {e}", method.name()))
    })?;
    let v = &run.output.visibility;
    let scene = &case.scene;
    let left = match &run.output.end_weights {
        Some(w) => shaded_by_ends(scene, &prepared.frame, w),
        None => shaded(scene, &prepared.frame, v),
    };
    let right = error_heat_map(&prepared.frame, v, &prepared.exact);
    let factor = names::picture_factor(config.side, config.picture_side, &case.name);
    let image = write::side_by_side(&left.downsample(factor), &right.downsample(factor));
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| ReportError::file(parent, e))?;
    }
    image
        .write_png(path)
        .map_err(|e| ReportError::file(path, e))
}

/// Joins parts of one sweep into one, keeping each cell's machine, and
/// fills the derived columns ([`finish`]). Each part must be
/// [whole](Results::check), all of one sweep (the same [`ConfigRecord`]),
/// agree on the scenes they share, and hold no cell another holds. Linear
/// in the parts' size.
///
/// # Errors
/// One line: no part, a part that is not whole, parts of different
/// sweeps, disagreeing on a scene or sharing a cell.
pub fn merge(parts: Vec<Results>) -> Result<Results, ReportError> {
    merge_labelled(
        parts
            .into_iter()
            .enumerate()
            .map(|(k, p)| (format!("part {}", k + 1), p))
            .collect(),
    )
}

/// [`merge`], the parts named by their labels in messages.
pub(crate) fn merge_labelled(parts: Vec<(String, Results)>) -> Result<Results, ReportError> {
    for (label, part) in &parts {
        part.check().map_err(|e| e.of_part(label))?;
    }
    let parted = |what: String| ReportError::Parts { what };
    let mut parts = parts.into_iter();
    let (first, mut all) = parts
        .next()
        .ok_or_else(|| parted("nothing to merge".to_owned()))?;
    let mut machines: HashMap<String, usize> = all
        .machines
        .iter()
        .enumerate()
        .map(|(k, m)| (m.clone(), k))
        .collect();
    let mut scenes: HashMap<String, usize> = all
        .scenes
        .iter()
        .enumerate()
        .map(|(k, s)| (s.name.clone(), k))
        .collect();
    let mut cells: HashSet<usize> = all.cells.iter().map(|c| c.index).collect();
    for (label, part) in parts {
        if let Some(what) = all.config.differs(&part.config) {
            return Err(parted(format!(
                "{label} is of another sweep than {first}: {what}"
            )));
        }
        let remap: Vec<usize> = part
            .machines
            .into_iter()
            .map(|m| {
                let next = all.machines.len();
                *machines.entry(m.clone()).or_insert_with(|| {
                    all.machines.push(m);
                    next
                })
            })
            .collect();
        for mut s in part.scenes {
            if let Some(&k) = scenes.get(&s.name) {
                if !check::same_scene(&all.scenes[k], &s) {
                    return Err(parted(format!(
                        "{label} and {first} disagree on scene {} (its receivers or exact profile)",
                        check::quote(&s.name)
                    )));
                }
                continue;
            }
            s.machine = remap[s.machine];
            scenes.insert(s.name.clone(), all.scenes.len());
            all.scenes.push(s);
        }
        for mut c in part.cells {
            if !cells.insert(c.index) {
                return Err(parted(format!(
                    "cell {} ({}, {}) is in two parts ({label} and one before it)",
                    c.index,
                    check::quote(&c.scene),
                    check::quote(&c.method)
                )));
            }
            c.machine = remap[c.machine];
            all.cells.push(c);
        }
    }
    let merged = finish(all);
    merged
        .check()
        .map_err(|e| e.of_part("the merged results"))?;
    Ok(merged)
}

/// Orders the scenes (as the sweep lists them) and the cells (by number)
/// and fills the derived columns afresh: the yardstick per scene, each
/// cell's equal-RMSE sample counts and speed-up. Linear in the cells.
#[must_use]
pub fn finish(mut results: Results) -> Results {
    results.cells.sort_by_key(|c| c.index);
    let order = results.config.scene_numbers();
    results
        .scenes
        .sort_by_key(|s| order.get(s.name.as_str()).copied().unwrap_or(usize::MAX));
    let mut points: BTreeMap<String, Vec<(u32, f64, f64, f64)>> = BTreeMap::new();
    for c in &mut results.cells {
        c.mc_equal = None;
        c.mc_equal_penumbra = None;
        c.speedup = None;
        if c.base != "mc" || c.status != "ok" {
            continue;
        }
        let (Some(n), Some(e), Some(t)) = (
            c.method.strip_prefix("mc:").and_then(|n| n.parse().ok()),
            c.errors,
            c.seconds,
        ) else {
            continue;
        };
        points
            .entry(c.scene.clone())
            .or_default()
            .push((n, e[0].rmse, e[1].rmse, t));
    }
    results.yardsticks = points
        .into_iter()
        .filter_map(|(scene, p)| Some((scene, Yardstick::new(&p)?)))
        .collect();
    for c in &mut results.cells {
        let (Some(y), Some(e), Some(t)) = (results.yardsticks.get(&c.scene), c.errors, c.seconds)
        else {
            continue;
        };
        c.mc_equal = y.equal(&y.rmse, e[0].rmse);
        c.mc_equal_penumbra = y.rmse_penumbra.and_then(|law| y.equal(&law, e[1].rmse));
        c.speedup = c.mc_equal.and_then(|n| y.speedup(n, t));
    }
    results
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_parse_and_refuse() {
        assert_eq!("2/3".parse::<Shard>(), Ok(Shard { index: 2, count: 3 }));
        for bad in ["0/3", "4/3", "3", "a/b", "1/0"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        assert_eq!(
            "4/3".parse::<Shard>(),
            Err(ShardError::OutOfRange { index: 4, count: 3 })
        );
        let e = "a/b".parse::<Shard>().unwrap_err();
        assert_eq!(e, ShardError::Syntax { text: "a/b".into() });
        assert_eq!(e.to_string(), "'a/b': a shard is i/n with 1 ≤ i ≤ n");
    }

    #[test]
    fn the_settings_come_from_the_registry() {
        let s = settings(&Config::default());
        assert_eq!(s[0], "exact");
        for entry in REGISTRY {
            for c in entry.compare {
                assert!(s.iter().any(|x| x == c), "{c} missing");
            }
        }
        assert!(s.iter().any(|x| x == "mc:4096"));
    }
}
