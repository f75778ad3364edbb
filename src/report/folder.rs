//! A report folder written as a set, and the merge of parts' folders.
//!
//! [`Staged`] gives a fresh hidden folder beside the report's folder; the
//! run writes every file of the report there, and [`Staged::commit`]
//! renames it into place, the previous report moved aside and removed. A
//! reader of the folder sees the previous report or the new one, never a
//! mix; a run stopped before the commit leaves the previous report as it
//! was (and, killed, its hidden folder beside it). Only a folder that is
//! new, empty or a report (`results.json`, `index.md`, `plots/`,
//! `pictures/`) is replaced.
//!
//! [`merge_into`] reads parts' folders: each `results.json` a regular file
//! within [`MAX_TEXT_BYTES`], [checked whole](Results::check) before
//! anything is written, and each picture a cell names read from inside
//! its own part (a link leading out of the part is refused) as a PNG of
//! the size the sweep gives it.

use super::check::quote;
use super::names::{file_part, picture_size, Names};
use super::{merge_labelled, write, ReportError, Results};
use crate::output::image::write_atomically;
use crate::scene::file::{read_input, MAX_TEXT_BYTES};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The entries a report folder holds.
const ENTRIES: [&str; 4] = ["results.json", "index.md", "plots", "pictures"];

/// A report folder being written: files go into [`Staged::path`], a
/// fresh folder beside the report's, which [`Staged::commit`] renames into
/// place. Dropped without a commit, the staged folder is removed.
#[derive(Debug)]
pub struct Staged {
    out: PathBuf,
    tmp: PathBuf,
    old: PathBuf,
    committed: bool,
}

impl Staged {
    /// Stages the report folder `out` (created if missing; a link to a
    /// folder stands for that folder): a fresh hidden folder beside it.
    ///
    /// # Errors
    /// `out` that is not a folder, holds anything but a report's entries
    /// (hidden temporaries of an earlier run aside), or has no writable
    /// folder around it; one line naming it.
    pub fn new(out: &Path) -> Result<Staged, ReportError> {
        let fail = |why: String| ReportError::file(out, why);
        std::fs::create_dir_all(out).map_err(|e| fail(e.to_string()))?;
        let abs = std::fs::canonicalize(out).map_err(|e| fail(e.to_string()))?;
        if !abs.is_dir() {
            return Err(fail("not a directory".to_owned()));
        }
        for entry in std::fs::read_dir(&abs).map_err(|e| fail(e.to_string()))? {
            let entry = entry.map_err(|e| fail(e.to_string()))?;
            let name = entry.file_name();
            let name = name.to_string_lossy();
            let temporary = name.starts_with('.') && name.ends_with(".tmp");
            if !ENTRIES.contains(&name.as_ref()) && !temporary {
                return Err(fail(format!(
                    "holds {}, which is not a report's: name a new or empty folder, or an earlier report's",
                    quote(&name)
                )));
            }
        }
        let (Some(parent), Some(name)) = (abs.parent(), abs.file_name()) else {
            return Err(fail(
                "cannot be replaced (it has no parent folder)".to_owned(),
            ));
        };
        let stem = match file_part(&name.to_string_lossy()) {
            s if s.is_empty() => "report".to_owned(),
            mut s => {
                s.truncate(64);
                s
            }
        };
        let pid = std::process::id();
        let tmp = parent.join(format!(".{stem}.{pid}.new.tmp"));
        let old = parent.join(format!(".{stem}.{pid}.old.tmp"));
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir(&tmp).map_err(|e| {
            fail(format!(
                "cannot write beside it ({}: {e}); the report is written there and renamed into place",
                tmp.display()
            ))
        })?;
        Ok(Staged {
            out: abs,
            tmp,
            old,
            committed: false,
        })
    }

    /// Where the report's files go until the commit.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// Renames the staged folder into place: the previous report is moved
    /// aside, the staged folder renamed to it, the previous one removed.
    ///
    /// # Errors
    /// A rename or removal that fails (the previous report is put back
    /// when the new one cannot take its place).
    pub fn commit(mut self) -> Result<(), ReportError> {
        let _ = std::fs::remove_dir_all(&self.old);
        let had = std::fs::symlink_metadata(&self.out).is_ok();
        if had {
            std::fs::rename(&self.out, &self.old)
                .map_err(|e| ReportError::file(&self.out, format!("cannot move it aside: {e}")))?;
        }
        if let Err(e) = std::fs::rename(&self.tmp, &self.out) {
            if had {
                let _ = std::fs::rename(&self.old, &self.out);
            }
            return Err(ReportError::file(
                &self.out,
                format!("cannot rename into place: {e}"),
            ));
        }
        self.committed = true;
        if had {
            std::fs::remove_dir_all(&self.old).map_err(|e| {
                ReportError::file(
                    &self.old,
                    format!("cannot remove the previous report moved aside: {e}"),
                )
            })?;
        }
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.tmp);
        }
    }
}

/// Reads the part in the folder `dir`: its `results.json`, a regular file
/// of at most [`MAX_TEXT_BYTES`], [checked whole](Results::check).
///
/// # Errors
/// One line naming the file: it cannot be read, is not the results'
/// JSON, or is not whole.
pub fn read_part(dir: &Path) -> Result<Results, ReportError> {
    let path = dir.join("results.json");
    let bytes = read_input(&path, MAX_TEXT_BYTES).map_err(|e| ReportError::file(&path, e))?;
    let results: Results =
        serde_json::from_slice(&bytes).map_err(|e| ReportError::file(&path, e))?;
    results
        .check()
        .map_err(|e| e.of_part(&path.display().to_string()))?;
    Ok(results)
}

/// Merges the parts in the folders `dirs` ([`merge`](super::merge)) into
/// the folder `out` — `results.json`, `index.md`, the plots and each
/// part's pictures — and returns the merged results. Every part is read
/// and checked before anything is written; `out` should be a fresh folder
/// ([`Staged::path`]).
///
/// # Errors
/// One line: a part that cannot be read or is not whole, parts of
/// different sweeps or sharing a cell, a picture that is missing, leads
/// out of its part or is not a PNG of its size, a file that cannot be
/// written.
pub fn merge_into(dirs: &[PathBuf], out: &Path) -> Result<Results, ReportError> {
    let parts: Vec<(String, Results)> = dirs
        .iter()
        .map(|d| Ok((d.join("results.json").display().to_string(), read_part(d)?)))
        .collect::<Result<_, ReportError>>()?;
    let mut from: HashMap<usize, usize> = HashMap::new();
    for (p, (_, part)) in parts.iter().enumerate() {
        for c in part.cells.iter().filter(|c| c.picture.is_some()) {
            from.insert(c.index, p);
        }
    }
    let merged = merge_labelled(parts)?;
    let names = Names::new(&merged.config);
    let mut roots: Vec<Option<PathBuf>> = vec![None; dirs.len()];
    for c in &merged.cells {
        let Some(name) = &c.picture else { continue };
        debug_assert_eq!(*name, names.picture(c.index));
        let p = from[&c.index];
        let root = match &roots[p] {
            Some(r) => r.clone(),
            None => {
                let r =
                    std::fs::canonicalize(&dirs[p]).map_err(|e| ReportError::file(&dirs[p], e))?;
                roots[p] = Some(r.clone());
                r
            }
        };
        let size = picture_size(merged.config.side, merged.config.pictures, &c.scene);
        let bytes = read_picture(&dirs[p].join(name), &root, size)?;
        let to = out.join(name);
        if let Some(parent) = to.parent() {
            std::fs::create_dir_all(parent).map_err(|e| ReportError::file(parent, e))?;
        }
        write_atomically(&to, &bytes).map_err(|e| ReportError::file(&to, e))?;
    }
    write(&merged, out)?;
    Ok(merged)
}

/// The picture at `path`, which must lie inside `root` (links resolved),
/// be a regular file of at most [`MAX_TEXT_BYTES`] and a PNG of `size`.
fn read_picture(path: &Path, root: &Path, size: (u32, u32)) -> Result<Vec<u8>, ReportError> {
    let fail = |e: String| ReportError::file(path, e);
    let real = std::fs::canonicalize(path).map_err(|e| fail(format!("picture: {e}")))?;
    if !real.starts_with(root) {
        return Err(fail(format!(
            "picture: a link leading outside its part, to {}",
            real.display()
        )));
    }
    let bytes = read_input(&real, MAX_TEXT_BYTES).map_err(|e| fail(format!("picture: {e}")))?;
    let info = png::Decoder::new(std::io::Cursor::new(&bytes[..]))
        .read_info()
        .map_err(|e| fail(format!("picture: not a PNG: {e}")))?
        .info()
        .size();
    if info != size {
        return Err(fail(format!(
            "picture: {}×{}, not the {}×{} the sweep gives it",
            info.0, info.1, size.0, size.1
        )));
    }
    Ok(bytes)
}
