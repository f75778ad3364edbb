//! What stops a report from being run, written, read or merged.

use crate::method::ParseError;
use std::fmt;
use std::path::{Path, PathBuf};

/// Why a report could not be run, written, read or merged. Each displays
/// as one line, naming the file, the part or the field at fault.
#[derive(Debug)]
#[non_exhaustive]
pub enum ReportError {
    /// A setting that is neither a method name with valid options nor one
    /// of [`Config::own`](super::Config::own).
    Method(ParseError),
    /// A file or folder that cannot be read or written, or is not what the
    /// report needs there (not a folder, not a report's folder, not a PNG
    /// of the sweep's size, a link leading out of its part, not UTF-8).
    File {
        /// The file or folder.
        path: PathBuf,
        /// What is wrong with it, one line.
        what: String,
    },
    /// Results that are not whole ([`Results::check`](super::Results::check)):
    /// where (`cells[3].profile`) and what.
    NotWhole {
        /// The part or file the results came from, when there is one.
        part: Option<String>,
        /// The first field at fault and what is wrong with it.
        what: String,
    },
    /// Whole parts that do not join into one sweep: none at all, parts of
    /// different sweeps, disagreeing on a scene or sharing a cell.
    Parts {
        /// What keeps them apart, naming the parts.
        what: String,
    },
}

impl ReportError {
    /// A [`ReportError::File`] about `path`.
    pub(crate) fn file(path: &Path, what: impl fmt::Display) -> ReportError {
        ReportError::File {
            path: path.to_owned(),
            what: what.to_string(),
        }
    }

    /// A [`ReportError::NotWhole`] from no particular part.
    pub(crate) fn not_whole(what: String) -> ReportError {
        ReportError::NotWhole { part: None, what }
    }

    /// The same error, said of the part `part` (a label or a file).
    #[must_use]
    pub(crate) fn of_part(self, part: &str) -> ReportError {
        match self {
            ReportError::NotWhole { part: None, what } => ReportError::NotWhole {
                part: Some(part.to_owned()),
                what,
            },
            other => other,
        }
    }
}

impl_error!(
    ReportError,
    |error, f| match error {
        ReportError::Method(e) => write!(f, "{e}"),
        ReportError::File { path, what } => write!(f, "{}: {what}", path.display()),
        ReportError::NotWhole {
            part: Some(part),
            what,
        } => write!(f, "{part}: {what}"),
        ReportError::NotWhole { part: None, what } | ReportError::Parts { what } => {
            f.write_str(what)
        }
    },
    source = |error| match error {
        ReportError::Method(e) => Some(e),
        _ => None,
    }
);
