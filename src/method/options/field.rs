//! One field of a method's options: its key, what it is, how it is read
//! and written.

/// How one field of a method's options is read and written.
pub enum Kind<T: 'static> {
    /// A flag: `key` present sets it to `true`; its default is `false`.
    Flag {
        /// The field's value.
        get: fn(&T) -> bool,
        /// Sets the field.
        set: fn(&mut T, bool),
    },
    /// An integer in `min..=max`.
    Int {
        /// The field's value.
        get: fn(&T) -> u64,
        /// Sets the field (called with values in range only).
        set: fn(&mut T, u64),
        /// The least value accepted.
        min: u64,
        /// The greatest value accepted.
        max: u64,
    },
    /// A finite real number in `min..=max`.
    Real {
        /// The field's value.
        get: fn(&T) -> f64,
        /// Sets the field (called with values in range only).
        set: fn(&mut T, f64),
        /// The least value accepted.
        min: f64,
        /// The greatest value accepted.
        max: f64,
    },
    /// One of `choices`, by index.
    Choice {
        /// The index of the field's value in `choices`.
        get: fn(&T) -> usize,
        /// Sets the field to `choices[i]`.
        set: fn(&mut T, usize),
        /// The words accepted.
        choices: &'static [&'static str],
    },
}

/// One field of a method's options: its key, what it is, how it is read
/// and written.
pub struct Field<T: 'static> {
    /// The key on the command line (`map`, `exact-union`, …); for the
    /// positional field, the word its value is described by (`N`).
    pub key: &'static str,
    /// One line for `--help`: what the field is, and its source (paper
    /// and section, or "ours").
    pub doc: &'static str,
    /// Whether the value stands alone (`mc:256`), without `key=`.
    pub positional: bool,
    /// How it is read and written.
    pub kind: Kind<T>,
}

/// The shortest text that parses back to the same `f64` (Rust's `{:?}`,
/// which keeps exponents for very small and large values), without a
/// trailing `.0`: `2`, `0.3`, `1e-300`.
pub(super) fn real_string(x: f64) -> String {
    let s = format!("{x:?}");
    match s.strip_suffix(".0") {
        Some(integral) => integral.to_owned(),
        None => s,
    }
}
