//! The error of a scene or points file, naming the file and the place in it.

use std::borrow::Cow;
use std::path::Path;

/// Where in a file a [`FileError`] is.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Place {
    /// The file as a whole (missing, empty, UTF-16, not an OBJ mesh).
    Whole,
    /// A syntax error at a 1-based line and column.
    Position {
        /// Line, from 1.
        line: usize,
        /// Column, from 1 (0 at the very start of an empty line).
        column: usize,
    },
    /// A JSON path to the offending field, such as
    /// `meshes[2].triangles[5][1]`.
    Path(String),
}

/// A scene, points or OBJ file that could not be loaded.
///
/// Displayed on one line (control characters escaped) as
/// `FILE: PATH: MESSAGE`, `FILE:LINE:COLUMN: MESSAGE` or `FILE: MESSAGE`,
/// following [`Place`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileError {
    pub(super) file: String,
    pub(super) place: Place,
    pub(super) message: String,
}

impl FileError {
    /// The file's name as given.
    #[must_use]
    pub fn file(&self) -> &str {
        &self.file
    }

    /// Where in the file.
    #[must_use]
    pub fn place(&self) -> &Place {
        &self.place
    }

    /// What is wrong, without the file and the place.
    #[must_use]
    pub fn message(&self) -> &str {
        &self.message
    }
}

/// The longest prefix of `s` of at most `max` bytes that ends on a
/// character boundary.
pub(super) fn prefix(s: &str, max: usize) -> &str {
    let end = (0..=max.min(s.len()))
        .rev()
        .find(|&i| s.is_char_boundary(i))
        .unwrap_or(0);
    &s[..end]
}

/// `s` cut to about `max` bytes at its end, with what was cut counted.
pub(super) fn clip_end(s: &str, max: usize) -> Cow<'_, str> {
    if s.len() <= max {
        return Cow::Borrowed(s);
    }
    let kept = prefix(s, max);
    Cow::Owned(format!("{kept}… ({} more bytes)", s.len() - kept.len()))
}

/// `s` cut to about `max` bytes at its start (a path keeps its file name).
pub(super) fn clip_start(s: &str, max: usize) -> Cow<'_, str> {
    if s.len() <= max {
        return Cow::Borrowed(s);
    }
    let from = (s.len() - max..s.len())
        .find(|&i| s.is_char_boundary(i))
        .unwrap_or(s.len());
    Cow::Owned(format!("…{}", &s[from..]))
}

/// A path for a message: its display, cut to its last 160 bytes.
pub(super) fn short_path(path: &Path) -> String {
    clip_start(&path.display().to_string(), 160).into_owned()
}

/// `s` with control characters (newlines included) escaped, so that a
/// message stays on one line whatever a file name or key holds.
pub(super) fn one_line(s: &str) -> Cow<'_, str> {
    if s.chars().any(char::is_control) {
        Cow::Owned(
            s.chars()
                .map(|c| {
                    if c.is_control() {
                        c.escape_default().to_string()
                    } else {
                        c.to_string()
                    }
                })
                .collect(),
        )
    } else {
        Cow::Borrowed(s)
    }
}

impl_error!(FileError, |error, f| {
    // One line of bounded length, whatever the input quoted.
    let file = one_line(&error.file);
    let file = clip_start(&file, 160);
    let message = one_line(&error.message);
    let message = clip_end(&message, 400);
    match &error.place {
        Place::Whole => write!(f, "{file}: {message}"),
        Place::Position { line, column } => write!(f, "{file}:{line}:{column}: {message}"),
        Place::Path(path) => write!(f, "{file}: {}: {message}", clip_end(&one_line(path), 200)),
    }
});

/// An error about the whole file `name`.
pub(super) fn whole(name: &str, message: String) -> FileError {
    FileError {
        file: name.to_owned(),
        place: Place::Whole,
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_stay_on_one_line() {
        let e = FileError {
            file: "a\nb.json".to_owned(),
            place: Place::Path("x".to_owned()),
            message: "bad\r\nthing".to_owned(),
        };
        assert_eq!(e.to_string(), "a\\nb.json: x: bad\\r\\nthing");
    }
}
