//! Checking results whole before anything is written from them: a part
//! read from a file may hold anything JSON can. [`Results::check`] says
//! whether the results are of one sweep and consistent throughout — every
//! cell where its number puts it, every record's lengths and counts in
//! agreement, every number finite and in its range, every picture the one
//! name the sweep gives the cell — in one pass over them.

use super::names::Names;
use super::ReportError;
use super::{base, CellRecord, ConfigRecord, Errors, Results, SceneRecord, Yardstick, FORMAT};
use crate::scene::LightKind;
use std::collections::{HashMap, HashSet};

/// The longest scene or setting name, in bytes (a path may be 4096).
pub const MAX_NAME: usize = 4096;

/// The longest status or machine line, in bytes.
pub const MAX_LINE: usize = 1000;

/// The largest frame side a report records.
pub const MAX_SIDE: u32 = 1 << 16;

/// A string of the input as a message quotes it: escaped (control
/// characters and quotes) and cut to its first 60 characters.
pub(crate) fn quote(s: &str) -> String {
    const MAX: usize = 60;
    let cut: String = s.chars().take(MAX).collect();
    let more = if cut.len() < s.len() { "…" } else { "" };
    format!("{cut:?}{more}")
}

/// `s` as one line of at most `max` bytes: control characters escaped,
/// the rest cut at a character boundary with `…`.
pub(crate) fn one_line(s: &str, max: usize) -> String {
    let mut out = String::with_capacity(s.len().min(max));
    for c in s.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    if out.len() > max {
        let cut = (0..=max.saturating_sub(3))
            .rev()
            .find(|&i| out.is_char_boundary(i))
            .unwrap_or(0);
        out.truncate(cut);
        out.push('…');
    }
    out
}

/// A name or line: not empty, at most `max` bytes, one line.
fn text(at: &str, s: &str, max: usize) -> Result<(), String> {
    if s.is_empty() {
        return Err(format!("{at}: empty"));
    }
    if s.len() > max {
        return Err(format!("{at}: {} bytes, over the limit of {max}", s.len()));
    }
    if s.chars().any(char::is_control) {
        return Err(format!("{at}: {} holds a control character", quote(s)));
    }
    Ok(())
}

fn finite_at_least(at: &str, x: f64, lo: f64) -> Result<(), String> {
    if x.is_finite() && x >= lo {
        Ok(())
    } else {
        Err(format!("{at}: {x} is not a finite number ≥ {lo}"))
    }
}

fn within(at: &str, x: f64, lo: f64, hi: f64) -> Result<(), String> {
    if x >= lo && x <= hi {
        Ok(())
    } else {
        Err(format!("{at}: {x} is not within [{lo}, {hi}]"))
    }
}

impl ConfigRecord {
    /// Whether the sweep's settings are whole: a frame side within
    /// `1..=`[`MAX_SIDE`], at least one run, increasing positive sample
    /// counts, distinct one-line scene and setting names of at most
    /// [`MAX_NAME`] bytes, `exact` first and each `mc:N` among the
    /// settings, and `cells` their product.
    ///
    /// # Errors
    /// [`ReportError::NotWhole`]: the first thing that is not, naming the
    /// field.
    pub fn check(&self) -> Result<(), ReportError> {
        self.first_fault().map_err(ReportError::not_whole)
    }

    /// [`ConfigRecord::check`]'s test, its fault as text.
    fn first_fault(&self) -> Result<(), String> {
        if self.side == 0 || self.side > MAX_SIDE {
            return Err(format!(
                "config.side: {} is not within 1..={MAX_SIDE}",
                self.side
            ));
        }
        if self.runs == 0 {
            return Err("config.runs: 0, at least one run is made".to_owned());
        }
        if self.mc.first().is_some_and(|&n| n == 0) || self.mc.windows(2).any(|w| w[0] >= w[1]) {
            return Err("config.mc: the sample counts are not positive and increasing".to_owned());
        }
        distinct_names("config.scenes", &self.scenes)?;
        let seen = distinct_names("config.settings", &self.settings)?;
        if self.settings.first().is_none_or(|s| s != "exact") {
            return Err("config.settings: the first is not \"exact\"".to_owned());
        }
        if let Some(n) = self
            .mc
            .iter()
            .find(|n| !seen.contains(format!("mc:{n}").as_str()))
        {
            return Err(format!(
                "config.settings: the yardstick's mc:{n} is not among them"
            ));
        }
        if self.scenes.len().checked_mul(self.settings.len()) != Some(self.cells) {
            return Err(format!(
                "config.cells: {} is not the sweep's {} scenes × {} settings",
                self.cells,
                self.scenes.len(),
                self.settings.len()
            ));
        }
        Ok(())
    }

    /// Which of the sweep's settings differ from `other`'s, if any.
    pub(crate) fn differs(&self, other: &ConfigRecord) -> Option<&'static str> {
        [
            (self.scenes != other.scenes, "the scenes differ"),
            (
                self.settings != other.settings,
                "the settings (methods) differ",
            ),
            (self.side != other.side, "the frame sides differ"),
            (self.runs != other.runs, "the runs per cell differ"),
            (self.mc != other.mc, "the yardstick's sample counts differ"),
            (self.pictures != other.pictures, "the picture sides differ"),
            (self.cells != other.cells, "the cell counts differ"),
        ]
        .into_iter()
        .find_map(|(differ, why)| differ.then_some(why))
    }
}

impl Results {
    /// Whether the results are whole and of one sweep: the [`FORMAT`], the
    /// [settings](ConfigRecord::check), and every record consistent with
    /// them — each scene one of the sweep's with its frame's size, counts
    /// that add up and a profile as long as its columns; each cell where
    /// its number puts it (that scene and setting, within the sweep, once),
    /// measured cells with runs, errors over their scene's groups and a
    /// profile as long as the scene's, other cells with none; every number
    /// finite and in its range; every picture the cell's own name
    /// (`pictures/SCENE/SETTING.png`, nothing else); each machine one
    /// line. Linear in the size of the results.
    ///
    /// # Errors
    /// [`ReportError::NotWhole`]: the first thing that is not, naming
    /// where (`cells[3].profile`).
    pub fn check(&self) -> Result<(), ReportError> {
        self.first_fault().map_err(ReportError::not_whole)
    }

    /// [`Results::check`]'s test, its fault as text.
    fn first_fault(&self) -> Result<(), String> {
        if self.format != FORMAT {
            return Err(format!(
                "format: {} is not {FORMAT:?} (another version's report, or not a report)",
                quote(&self.format)
            ));
        }
        let config = &self.config;
        config.first_fault()?;
        if self.machines.is_empty() {
            return Err("machines: none".to_owned());
        }
        for (k, m) in self.machines.iter().enumerate() {
            text(&format!("machines[{k}]"), m, MAX_LINE)?;
        }
        let scenes = config.scene_numbers();
        let mut records: HashMap<&str, &SceneRecord> = HashMap::with_capacity(self.scenes.len());
        for (k, s) in self.scenes.iter().enumerate() {
            let at = format!("scenes[{k}]");
            if !scenes.contains_key(s.name.as_str()) {
                return Err(format!(
                    "{at}.name: {} is not one of the sweep's scenes",
                    quote(&s.name)
                ));
            }
            if records.insert(&s.name, s).is_some() {
                return Err(format!("{at}: scene {} is recorded twice", quote(&s.name)));
            }
            scene(&at, s, config.side, self.machines.len())?;
        }
        let names = Names::new(config);
        let per_scene = config.settings.len();
        let mut seen: HashSet<usize> = HashSet::with_capacity(self.cells.len());
        for (k, c) in self.cells.iter().enumerate() {
            let at = format!("cells[{k}]");
            if c.index >= config.cells {
                return Err(format!(
                    "{at}.index: {} is beyond the sweep's {} cells",
                    c.index, config.cells
                ));
            }
            if !seen.insert(c.index) {
                return Err(format!("{at}.index: cell {} is recorded twice", c.index));
            }
            let (scene, setting) = (
                &config.scenes[c.index / per_scene],
                &config.settings[c.index % per_scene],
            );
            if c.scene != *scene || c.method != *setting {
                return Err(format!(
                    "{at}: ({}, {}) is not cell {}, which is ({}, {})",
                    quote(&c.scene),
                    quote(&c.method),
                    c.index,
                    quote(scene),
                    quote(setting)
                ));
            }
            let record = records.get(c.scene.as_str()).copied();
            cell(&at, c, record, config, &names, self.machines.len())?;
        }
        for (name, y) in &self.yardsticks {
            if !scenes.contains_key(name.as_str()) {
                return Err(format!(
                    "yardsticks: {} is not one of the sweep's scenes",
                    quote(name)
                ));
            }
            yardstick(&format!("yardsticks[{}]", quote(name)), y, &config.mc)?;
        }
        Ok(())
    }

    /// The scenes that could not be prepared (no camera, a receiver inside
    /// the light, …), in sweep order, each with the reason: the scenes
    /// with cells here, every one an error, and no record.
    #[must_use]
    pub fn unprepared(&self) -> Vec<(&str, &str)> {
        let recorded: HashSet<&str> = self.scenes.iter().map(|s| s.name.as_str()).collect();
        let mut why: HashMap<&str, &str> = HashMap::new();
        for c in &self.cells {
            if recorded.contains(c.scene.as_str()) {
                continue;
            }
            if let Some(reason) = c.status.strip_prefix("error: ") {
                why.entry(c.scene.as_str()).or_insert(reason);
            }
        }
        self.config
            .scenes
            .iter()
            .filter_map(|s| why.get(s.as_str()).map(|r| (s.as_str(), *r)))
            .collect()
    }
}

/// One scene record.
fn scene(at: &str, s: &SceneRecord, side: u32, machines: usize) -> Result<(), String> {
    if !LightKind::ALL.iter().any(|k| k.name() == s.light) {
        return Err(format!(
            "{at}.light: {} is not a light kind",
            quote(&s.light)
        ));
    }
    if (s.width, s.height) != (side, side) {
        return Err(format!(
            "{at}: a {}×{} frame, not the sweep's {side}×{side}",
            s.width, s.height
        ));
    }
    let pixels = u64::from(side) * u64::from(side);
    if s.receivers as u64 > pixels {
        return Err(format!(
            "{at}.receivers: {} in a frame of {pixels} pixels",
            s.receivers
        ));
    }
    if s.groups[0] != s.receivers
        || s.groups[1] != s.penumbra
        || s.penumbra > s.receivers
        || s.groups[2].checked_add(s.groups[3]) != Some(s.receivers)
    {
        return Err(format!(
            "{at}.groups: {:?} do not add up to {} receivers, {} in the penumbra",
            s.groups, s.receivers, s.penumbra
        ));
    }
    if let Some(pieces) = s.pieces {
        if s.light != "segment" {
            return Err(format!(
                "{at}.pieces: recorded for a {} light, not a segment",
                quote(&s.light)
            ));
        }
        if pieces.iter().try_fold(0usize, |n, &k| n.checked_add(k)) != Some(s.receivers) {
            return Err(format!(
                "{at}.pieces: {pieces:?} do not add up to {} receivers",
                s.receivers
            ));
        }
    }
    for (k, &t) in s.shared.iter().enumerate() {
        finite_at_least(&format!("{at}.shared[{k}]"), t, 0.0)?;
    }
    if s.machine >= machines {
        return Err(format!(
            "{at}.machine: {} of {machines} machines",
            s.machine
        ));
    }
    if s.profile_row >= s.height {
        return Err(format!(
            "{at}.profile_row: {} of a frame {} high",
            s.profile_row, s.height
        ));
    }
    if s.profile_columns.windows(2).any(|w| w[0] >= w[1])
        || s.profile_columns.last().is_some_and(|&c| c >= s.width)
    {
        return Err(format!(
            "{at}.profile_columns: not increasing columns of a frame {} wide",
            s.width
        ));
    }
    profile(
        &format!("{at}.profile_exact"),
        &s.profile_exact,
        s.profile_columns.len(),
    )?;
    if let Some(b) = s.exact_bound {
        within(&format!("{at}.exact_bound"), b, 0.0, 1.0)?;
    }
    Ok(())
}

/// The names of the field `at`, each a line of text and none twice; the
/// set of them.
fn distinct_names<'a>(at: &str, names: &'a [String]) -> Result<HashSet<&'a str>, String> {
    let mut seen = HashSet::with_capacity(names.len());
    for (k, s) in names.iter().enumerate() {
        let at = format!("{at}[{k}]");
        text(&at, s, MAX_NAME)?;
        if !seen.insert(s.as_str()) {
            return Err(format!("{at}: {} is twice in the sweep", quote(s)));
        }
    }
    Ok(seen)
}

/// A profile, the field `at`: one `V` in `[0, 1]` for each of the
/// scene's `columns` profile columns.
fn profile(at: &str, values: &[f64], columns: usize) -> Result<(), String> {
    if values.len() != columns {
        return Err(format!(
            "{at}: {} values for the scene's {columns} profile columns",
            values.len()
        ));
    }
    for (k, &v) in values.iter().enumerate() {
        within(&format!("{at}[{k}]"), v, 0.0, 1.0)?;
    }
    Ok(())
}

/// One cell, already known to be where its number puts it.
fn cell(
    at: &str,
    c: &CellRecord,
    record: Option<&SceneRecord>,
    config: &ConfigRecord,
    names: &Names,
    machines: usize,
) -> Result<(), String> {
    if c.base != base(&c.method) {
        return Err(format!(
            "{at}.base: {} is not {}'s",
            quote(&c.base),
            quote(&c.method)
        ));
    }
    if c.machine >= machines {
        return Err(format!(
            "{at}.machine: {} of {machines} machines",
            c.machine
        ));
    }
    text(&format!("{at}.status"), &c.status, MAX_LINE)?;
    if c.status == "ok" {
        let Some(record) = record else {
            return Err(format!(
                "{at}: measured, but its scene {} has no record",
                quote(&c.scene)
            ));
        };
        if c.runs.is_empty() || c.runs.len() > config.runs as usize {
            return Err(format!(
                "{at}.runs: {} runs of at most {}",
                c.runs.len(),
                config.runs
            ));
        }
        for (k, &t) in c.runs.iter().enumerate() {
            finite_at_least(&format!("{at}.runs[{k}]"), t, 0.0)?;
        }
        let (lo, hi) = c
            .runs
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &t| (a.min(t), b.max(t)));
        match c.seconds {
            Some(t) if t >= lo && t <= hi => {}
            _ => {
                return Err(format!(
                    "{at}.seconds: {:?} is not the median of its runs",
                    c.seconds
                ))
            }
        }
        for (what, errors) in [("errors", &c.errors), ("shaded", &c.shaded)] {
            let Some(errors) = errors else {
                return Err(format!("{at}.{what}: missing from a measured cell"));
            };
            for (g, e) in errors.iter().enumerate() {
                summary(&format!("{at}.{what}[{g}]"), e, record.groups[g])?;
            }
        }
        pieces(at, c, record)?;
        profile(
            &format!("{at}.profile"),
            &c.profile,
            record.profile_columns.len(),
        )?;
        if let Some(p) = &c.picture {
            let own = names.picture(c.index);
            if *p != own {
                return Err(format!(
                    "{at}.picture: {} is not this cell's picture, {}",
                    quote(p),
                    quote(&own)
                ));
            }
        }
    } else {
        if !c.status.starts_with("n/a (") && !c.status.starts_with("error: ") {
            return Err(format!(
                "{at}.status: {} is neither ok, n/a nor an error",
                quote(&c.status)
            ));
        }
        if !c.runs.is_empty()
            || c.seconds.is_some()
            || c.errors.is_some()
            || c.shaded.is_some()
            || c.pieces.is_some()
            || !c.profile.is_empty()
            || c.picture.is_some()
        {
            return Err(format!(
                "{at}: not measured ({}), yet with measurements or a picture",
                quote(&c.status)
            ));
        }
    }
    for (what, e) in [
        ("mc_equal", c.mc_equal),
        ("mc_equal_penumbra", c.mc_equal_penumbra),
    ] {
        if let Some(super::Equal::At(n)) = e {
            finite_at_least(&format!("{at}.{what}"), n, 0.0)?;
        }
    }
    if let Some(s) = c.speedup {
        finite_at_least(&format!("{at}.speedup"), s, 0.0)?;
    }
    Ok(())
}

/// A measured cell's errors by the light's pieces: there exactly when its
/// scene records the groups, each over its group's receivers.
fn pieces(at: &str, c: &CellRecord, record: &SceneRecord) -> Result<(), String> {
    match (&c.pieces, record.pieces) {
        (Some(errors), Some(counts)) => {
            for (g, e) in errors.iter().enumerate() {
                summary(&format!("{at}.pieces[{g}]"), e, counts[g])?;
            }
            Ok(())
        }
        (None, None) => Ok(()),
        (Some(_), None) => Err(format!(
            "{at}.pieces: errors by the light's pieces, of a scene without them"
        )),
        (None, Some(_)) => Err(format!(
            "{at}.pieces: missing from a measured cell of a scene with them"
        )),
    }
}

/// One error summary over a group of `count` receivers: values of `V` and
/// the exact answer both lie in `[0, 1]`.
fn summary(at: &str, e: &Errors, count: usize) -> Result<(), String> {
    if e.count != count {
        return Err(format!(
            "{at}.count: {} of a group of {count} receivers",
            e.count
        ));
    }
    within(&format!("{at}.mean_abs"), e.mean_abs, 0.0, 1.0)?;
    within(&format!("{at}.rmse"), e.rmse, 0.0, 1.0)?;
    within(&format!("{at}.p99_abs"), e.p99_abs, 0.0, 1.0)?;
    within(&format!("{at}.max_abs"), e.max_abs, 0.0, 1.0)?;
    within(&format!("{at}.mean_signed"), e.mean_signed, -1.0, 1.0)?;
    within(
        &format!("{at}.share_over_0_05"),
        e.share_over_0_05,
        0.0,
        1.0,
    )
}

/// One yardstick: finite fits over counts of the sweep.
fn yardstick(at: &str, y: &Yardstick, mc: &[u32]) -> Result<(), String> {
    if y.counts.windows(2).any(|w| w[0] >= w[1])
        || y.counts.iter().any(|n| mc.binary_search(n).is_err())
    {
        return Err(format!("{at}.counts: not increasing counts of the sweep's"));
    }
    for law in std::iter::once(&y.rmse).chain(y.rmse_penumbra.as_ref()) {
        if !(law.a.is_finite() && law.a > 0.0 && law.b.is_finite()) {
            return Err(format!(
                "{at}: a fitted law {law:?} not finite and positive"
            ));
        }
    }
    if !(y.seconds.c.is_finite() && y.seconds.d.is_finite()) {
        return Err(format!("{at}.seconds: {:?} not finite", y.seconds));
    }
    Ok(())
}

/// Whether two parts' records of one scene agree (all but the machine
/// that made them and its times).
pub(crate) fn same_scene(a: &SceneRecord, b: &SceneRecord) -> bool {
    a.name == b.name
        && a.light == b.light
        && (a.width, a.height) == (b.width, b.height)
        && a.receivers == b.receivers
        && a.penumbra == b.penumbra
        && a.groups == b.groups
        && a.pieces == b.pieces
        && a.profile_row == b.profile_row
        && a.profile_columns == b.profile_columns
        && a.profile_exact == b.profile_exact
        && a.exact_bound == b.exact_bound
}
