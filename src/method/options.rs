//! One options layer for every method: the name `base[:item,item,…]` a
//! method has on the command line, in tables and in file names, parsed and
//! printed from one table of fields per method, so that names round-trip
//! by construction.
//!
//! An item is one of
//! - a **flag**, `key` (e.g. `exact-union`): present turns it on; every
//!   flag is off by default, so a default that is "on" is spelled as its
//!   negation (`no-bin-depth`);
//! - a **value**, `key=value`: an integer or a real number within a stated
//!   range, or one of a list of words (`falloff=exact`);
//! - a **positional** value, `value` alone (Monte Carlo's sample count,
//!   `mc:256`), at most one per method.
//!
//! [`print()`] writes the positional value first, then the fields that differ
//! from the default in table order; [`parse()`] reads items in any order. For
//! every method and every field, `parse(print(m)) == m`: integers print
//! exactly, reals in Rust's shortest round-trip form. Unknown keys, bad
//! values and an option given twice (`seed=3,seed=4`, as the scene files
//! refuse a duplicate key) are [`ParseError`]s that name what the method
//! accepts.

use super::Method;
use crate::scene::LightKind;
use std::fmt::{self, Write as _};

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

/// A method that has a name and options on the command line: what the
/// [registry](super::registry) needs to parse, print, list and describe
/// it. Implemented by every method of the crate; a user's method need not.
pub trait Configurable: Method + Default + Clone + PartialEq + 'static {
    /// The method's base name (`pcss`).
    const NAME: &'static str;
    /// One line: what the method is and where it comes from.
    const SUMMARY: &'static str;
    /// The light kinds the method handles; [`run`](super::run) refuses
    /// the others.
    const LIGHTS: &'static [LightKind];
    /// The settings (names) the default run compares, on every light kind
    /// of [`LIGHTS`](Configurable::LIGHTS); empty when the method is not
    /// in the default set.
    const DEFAULT_RUN: &'static [&'static str];
    /// The settings worth comparing in a report (the default first).
    const COMPARE: &'static [&'static str];
    /// The options' fields, in the order names print them.
    const FIELDS: &'static [Field<Self>];
}

/// What a field accepts.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Expected {
    /// An integer in `min..=max`.
    Int {
        /// The least value accepted.
        min: u64,
        /// The greatest value accepted.
        max: u64,
    },
    /// A finite real number in `min..=max`.
    Real {
        /// The least value accepted.
        min: f64,
        /// The greatest value accepted.
        max: f64,
    },
    /// One of these words.
    Choice(&'static [&'static str]),
}

impl<T> From<&Kind<T>> for Expected {
    fn from(kind: &Kind<T>) -> Expected {
        match kind {
            Kind::Int { min, max, .. } => Expected::Int {
                min: *min,
                max: *max,
            },
            Kind::Real { min, max, .. } => Expected::Real {
                min: *min,
                max: *max,
            },
            Kind::Choice { choices, .. } => Expected::Choice(choices),
            // A flag takes no value; asked what it accepts, it is on or off.
            Kind::Flag { .. } => Expected::Choice(&[]),
        }
    }
}

impl fmt::Display for Expected {
    /// `an integer from 1 to 16384`, `a number from 0 to 1`, `one of exact,
    /// linear`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Expected::Int { min, max } => write!(f, "an integer from {min} to {max}"),
            Expected::Real { min, max } => write!(
                f,
                "a number from {} to {}",
                real_string(*min),
                real_string(*max)
            ),
            Expected::Choice(choices) => write!(f, "one of {}", choices.join(", ")),
        }
    }
}

/// What is wrong with one option of a method.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum OptionError {
    /// An item that names no option of the method.
    Unknown {
        /// The item (`sideways`), or its key (`sideways` of `sideways=1`).
        item: String,
    },
    /// An option that takes a value, written alone (`map`).
    NeedsValue {
        /// The option's key.
        key: &'static str,
        /// What its value may be.
        expected: Expected,
    },
    /// A flag written with a value (`exact-union=1`).
    FlagWithValue {
        /// The flag.
        key: &'static str,
    },
    /// A value that does not parse as, or lies outside, what the option
    /// accepts; from [`parse`] (the text given) or [`check`] (the value a
    /// method built in code holds).
    Invalid {
        /// The option's key (the positional value's word, `N`, for it).
        key: &'static str,
        /// The value, as given or as printed.
        value: String,
        /// What it may be.
        expected: Expected,
    },
    /// An option given twice (`seed=3,seed=4`; `mc:256,512` for the
    /// positional value), which the name could only resolve by dropping
    /// one.
    Repeated {
        /// The option's key (`N` for the positional value).
        key: &'static str,
    },
}

impl fmt::Display for OptionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OptionError::Unknown { item } => write!(f, "unknown option '{item}'"),
            OptionError::NeedsValue { key, expected } => {
                write!(f, "'{key}' needs a value, {expected}")
            }
            OptionError::FlagWithValue { key } => {
                write!(f, "'{key}' is a flag, written alone: {key}")
            }
            OptionError::Invalid {
                key,
                value,
                expected,
            } => write!(f, "{key} must be {expected}, got '{value}'"),
            OptionError::Repeated { key } => {
                write!(f, "{key} is given twice (give each option once)")
            }
        }
    }
}

impl std::error::Error for OptionError {}

/// Why a method name (`base[:item,…]`) could not be read: by
/// [`registry::parse`](super::registry::parse) and [`parse`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ParseError {
    /// No registered method has the name's base.
    UnknownMethod {
        /// The name given (at most 60 characters of it).
        name: String,
        /// The available methods, as [`registry::available`](super::registry::available) lists them.
        available: String,
    },
    /// An option of a known method.
    Option {
        /// The whole name given.
        name: String,
        /// What is wrong.
        error: OptionError,
        /// Every option the method accepts, for the message:
        /// `pcss accepts map=N (1–16384), …`.
        accepts: String,
    },
}

impl ParseError {
    /// The option error, when the method was known and one of its options
    /// was not.
    #[must_use]
    pub fn option(&self) -> Option<&OptionError> {
        match self {
            ParseError::Option { error, .. } => Some(error),
            _ => None,
        }
    }
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParseError::UnknownMethod { name, available } => {
                write!(f, "unknown method '{name}'; available: {available}")
            }
            ParseError::Option {
                name,
                error,
                accepts,
            } => write!(f, "'{name}': {error}; {accepts}"),
        }
    }
}

impl std::error::Error for ParseError {}

/// Why a method's options table breaks a promise of this module
/// ([`round_trip`]).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum TableError {
    /// A flag that is on in the default method.
    FlagOnByDefault {
        /// The flag.
        key: &'static str,
    },
    /// The default method prints as more than its base name (and has no
    /// positional value).
    DefaultNotBare {
        /// What it prints as.
        printed: String,
    },
    /// A printed name that does not parse.
    Unparsable {
        /// The name printed.
        name: String,
        /// Why it does not parse.
        error: Box<ParseError>,
    },
    /// A printed name that parses to another method.
    ParsesDifferently {
        /// The name printed.
        name: String,
        /// The method it parses to, `{:?}`.
        parsed: String,
        /// The method printed, `{:?}`.
        printed: String,
    },
    /// A method whose options lie in their ranges fails [`check`].
    Check {
        /// The name printed.
        name: String,
        /// What [`check`] found.
        error: OptionError,
    },
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableError::FlagOnByDefault { key } => write!(f, "flag {key} is on by default"),
            TableError::DefaultNotBare { printed } => {
                write!(f, "the default prints as '{printed}'")
            }
            TableError::Unparsable { name, error } => {
                write!(f, "'{name}' does not parse back: {error}")
            }
            TableError::ParsesDifferently {
                name,
                parsed,
                printed,
            } => write!(f, "'{name}' parses to {parsed}, not {printed}"),
            TableError::Check { name, error } => write!(f, "'{name}': {error}"),
        }
    }
}

impl std::error::Error for TableError {}

/// The items of a method name `base[:item,…]`: `None` when `name` is not of
/// that form for `base`.
#[must_use]
pub fn items<'a>(name: &'a str, base: &str) -> Option<Vec<&'a str>> {
    match name.strip_prefix(base)? {
        "" => Some(Vec::new()),
        rest => Some(rest.strip_prefix(':')?.split(',').collect()),
    }
}

fn value_string<T>(field: &Field<T>, m: &T) -> Option<String> {
    match &field.kind {
        Kind::Flag { get, .. } => get(m).then(String::new),
        Kind::Int { get, .. } => Some(get(m).to_string()),
        Kind::Real { get, .. } => Some(real_string(get(m))),
        Kind::Choice { get, choices, .. } => choices.get(get(m)).map(|c| (*c).to_owned()),
    }
}

/// The shortest text that parses back to the same `f64` (Rust's `{:?}`,
/// which keeps exponents for very small and large values), without a
/// trailing `.0`: `2`, `0.3`, `1e-300`.
fn real_string(x: f64) -> String {
    let s = format!("{x:?}");
    match s.strip_suffix(".0") {
        Some(integral) => integral.to_owned(),
        None => s,
    }
}

fn same<T>(field: &Field<T>, a: &T, b: &T) -> bool {
    match &field.kind {
        Kind::Flag { get, .. } => get(a) == get(b),
        Kind::Int { get, .. } => get(a) == get(b),
        Kind::Real { get, .. } => get(a).to_bits() == get(b).to_bits(),
        Kind::Choice { get, .. } => get(a) == get(b),
    }
}

/// The name of `m`: its base name, then its positional value, then every
/// field that differs from the default, in [`Configurable::FIELDS`] order.
#[must_use]
pub fn print<T: Configurable>(m: &T) -> String {
    let d = T::default();
    let mut items = Vec::new();
    for f in T::FIELDS.iter().filter(|f| f.positional) {
        items.extend(value_string(f, m));
    }
    for f in T::FIELDS.iter().filter(|f| !f.positional) {
        if same(f, m, &d) {
            continue;
        }
        match (&f.kind, value_string(f, m)) {
            (Kind::Flag { .. }, Some(_)) => items.push(f.key.to_owned()),
            (Kind::Flag { .. }, None) => {}
            (_, Some(v)) => items.push(format!("{}={v}", f.key)),
            (_, None) => {}
        }
    }
    if items.is_empty() {
        T::NAME.to_owned()
    } else {
        format!("{}:{}", T::NAME, items.join(","))
    }
}

/// What a field accepts, for messages and `--help`: `map=N (1–16384)`,
/// `falloff=exact|linear`, `exact-union`, `N (2–4294967295)`.
fn syntax<T>(f: &Field<T>) -> String {
    let (word, range) = match &f.kind {
        Kind::Flag { .. } => return f.key.to_owned(),
        Kind::Int { min, max, .. } => ("N", format!(" ({min}–{max})")),
        Kind::Real { min, max, .. } => (
            "X",
            format!(" ({}–{})", real_string(*min), real_string(*max)),
        ),
        Kind::Choice { choices, .. } => return format!("{}={}", f.key, choices.join("|")),
    };
    if f.positional {
        format!("{}{range}", f.key)
    } else {
        format!("{}={word}{range}", f.key)
    }
}

/// Every item the method `T` accepts, for error messages.
fn accepted<T: Configurable>() -> String {
    let list: Vec<String> = T::FIELDS.iter().map(syntax).collect();
    if list.is_empty() {
        format!("{} takes no options", T::NAME)
    } else {
        format!("{} accepts {}", T::NAME, list.join(", "))
    }
}

/// Sets `field` of `m` from the text `value`.
fn set_from<T>(field: &Field<T>, m: &mut T, value: &str) -> Result<(), OptionError> {
    let invalid = || OptionError::Invalid {
        key: field.key,
        value: value.to_owned(),
        expected: Expected::from(&field.kind),
    };
    match &field.kind {
        Kind::Flag { set, .. } => set(m, true),
        Kind::Int { set, min, max, .. } => match value.parse::<u64>() {
            Ok(v) if (*min..=*max).contains(&v) => set(m, v),
            _ => return Err(invalid()),
        },
        Kind::Real { set, min, max, .. } => match value.parse::<f64>() {
            Ok(v) if v.is_finite() && *min <= v && v <= *max => set(m, v),
            _ => return Err(invalid()),
        },
        Kind::Choice { set, choices, .. } => match choices.iter().position(|c| *c == value) {
            Some(i) => set(m, i),
            None => return Err(invalid()),
        },
    }
    Ok(())
}

/// The method `T` with the options `items` (the parts of its name after
/// `base:`, split at commas), starting from the defaults. `name` is the
/// whole name, for messages.
///
/// # Errors
/// [`ParseError::Option`]: an item that is not understood, or an option
/// given twice (each named, with what the method accepts).
pub fn parse<T: Configurable>(name: &str, items: &[&str]) -> Result<T, ParseError> {
    let mut m = T::default();
    let mut given: Vec<&'static str> = Vec::new();
    for &item in items {
        let (key, value) = match item.split_once('=') {
            Some((k, v)) => (k, Some(v)),
            None => (item, None),
        };
        let named = T::FIELDS.iter().find(|f| !f.positional && f.key == key);
        let field = match (named, value) {
            (Some(f), None) if matches!(f.kind, Kind::Flag { .. }) => Ok(f),
            (Some(f), Some(_)) if !matches!(f.kind, Kind::Flag { .. }) => Ok(f),
            (Some(f), None) => Err(OptionError::NeedsValue {
                key: f.key,
                expected: Expected::from(&f.kind),
            }),
            (Some(f), Some(_)) => Err(OptionError::FlagWithValue { key: f.key }),
            (None, None) => {
                T::FIELDS
                    .iter()
                    .find(|f| f.positional)
                    .ok_or_else(|| OptionError::Unknown {
                        item: item.to_owned(),
                    })
            }
            (None, Some(_)) => Err(OptionError::Unknown {
                item: key.to_owned(),
            }),
        };
        let result = field.and_then(|f| {
            if given.contains(&f.key) {
                return Err(OptionError::Repeated { key: f.key });
            }
            given.push(f.key);
            set_from(
                f,
                &mut m,
                if f.positional {
                    item
                } else {
                    value.unwrap_or("")
                },
            )
        });
        if let Err(error) = result {
            return Err(ParseError::Option {
                name: name.to_owned(),
                error,
                accepts: accepted::<T>(),
            });
        }
    }
    Ok(m)
}

/// Checks that every field of `m` is in its documented range (methods
/// built in code, not parsed, may hold anything); the error names the
/// first that is not.
///
/// # Errors
/// [`OptionError::Invalid`]: `map must be an integer from 1 to 16384, got '0'`.
pub fn check<T: Configurable>(m: &T) -> Result<(), OptionError> {
    for f in T::FIELDS {
        let value = match &f.kind {
            Kind::Int { get, min, max, .. } => {
                let v = get(m);
                (!(*min..=*max).contains(&v)).then(|| v.to_string())
            }
            Kind::Real { get, min, max, .. } => {
                let v = get(m);
                (!(v.is_finite() && *min <= v && v <= *max)).then(|| format!("{v:?}"))
            }
            Kind::Choice { get, choices, .. } => {
                let i = get(m);
                (i >= choices.len()).then(|| format!("choice {i}"))
            }
            Kind::Flag { .. } => None,
        };
        if let Some(value) = value {
            return Err(OptionError::Invalid {
                key: f.key,
                value,
                expected: Expected::from(&f.kind),
            });
        }
    }
    Ok(())
}

/// The options of `T` for `--help`: one line each, with what it accepts,
/// its default and its doc.
#[must_use]
pub fn help<T: Configurable>() -> Vec<String> {
    let d = T::default();
    T::FIELDS
        .iter()
        .map(|f| {
            let mut line = syntax(f);
            if !matches!(f.kind, Kind::Flag { .. }) {
                if let Some(v) = value_string(f, &d) {
                    let _ = write!(line, ", default {v}");
                }
            }
            let _ = write!(line, ": {}", f.doc);
            line
        })
        .collect()
}

/// A static string (a key, a doc line, a word).
type Str = &'static str;
/// A field's getter.
type Get<T, V> = fn(&T) -> V;
/// A field's setter.
type Set<T, V> = fn(&mut T, V);

const fn named<T>(key: Str, doc: Str, kind: Kind<T>) -> Field<T> {
    Field {
        key,
        doc,
        positional: false,
        kind,
    }
}

/// A flag field.
pub const fn flag<T>(key: Str, doc: Str, get: Get<T, bool>, set: Set<T, bool>) -> Field<T> {
    named(key, doc, Kind::Flag { get, set })
}

/// The constructor of a numeric field, `key=N` for `u64` or `key=X` for
/// `f64`, the value in `r.0..=r.1`.
macro_rules! number_field {
    ($(#[$doc:meta])* $name:ident, $V:ty, $kind:ident) => {
        $(#[$doc])*
        pub const fn $name<T>(key: Str, doc: Str, r: ($V, $V), get: Get<T, $V>, set: Set<T, $V>) -> Field<T> {
            named(key, doc, Kind::$kind { get, set, min: r.0, max: r.1 })
        }
    };
}

number_field!(
    /// An integer field `key=N`, `N` in `r.0..=r.1`.
    int, u64, Int
);
number_field!(
    /// A real field `key=X`, `X` finite in `r.0..=r.1`.
    real, f64, Real
);

/// A choice field `key=word`, the word one of `choices`.
pub const fn choice<T>(
    key: Str,
    doc: Str,
    choices: &'static [Str],
    get: Get<T, usize>,
    set: Set<T, usize>,
) -> Field<T> {
    named(key, doc, Kind::Choice { get, set, choices })
}

/// `field` (an integer) made the positional field: its value stands alone
/// (`mc:256`) and is always printed; its key is the word it is described
/// by.
pub const fn positional<T>(field: Field<T>) -> Field<T> {
    Field {
        positional: true,
        ..field
    }
}

/// Checks the options table of `T` against the promises of this module:
/// every flag is off by default; the default prints as the bare name; and
/// for every field, set to each end of its range, to a value inside it
/// and to every choice, the name printed parses back to an equal method
/// that passes [`check`]. The registry's tests run it for every method.
///
/// # Errors
/// The first broken promise, named.
pub fn round_trip<T: Configurable>() -> Result<(), TableError> {
    let d = T::default();
    let back = |m: &T| -> Result<(), TableError> {
        let name = print(m);
        let unparsable = |error| TableError::Unparsable {
            name: name.clone(),
            error: Box::new(error),
        };
        let items = items(&name, T::NAME).ok_or_else(|| {
            unparsable(ParseError::UnknownMethod {
                name: name.clone(),
                available: T::NAME.to_owned(),
            })
        })?;
        let parsed = parse::<T>(&name, &items).map_err(unparsable)?;
        if parsed != *m {
            return Err(TableError::ParsesDifferently {
                name,
                parsed: format!("{parsed:?}"),
                printed: format!("{m:?}"),
            });
        }
        check(m).map_err(|error| TableError::Check { name, error })
    };
    if print(&d) != T::NAME && !T::FIELDS.iter().any(|f| f.positional) {
        return Err(TableError::DefaultNotBare { printed: print(&d) });
    }
    back(&d)?;
    for f in T::FIELDS {
        let mut variants = Vec::new();
        match &f.kind {
            Kind::Flag { get, set } => {
                if get(&d) {
                    return Err(TableError::FlagOnByDefault { key: f.key });
                }
                let mut m = d.clone();
                set(&mut m, true);
                variants.push(m);
            }
            Kind::Int { set, min, max, .. } => {
                for v in [*min, *max, min + (max - min) / 3] {
                    let mut m = d.clone();
                    set(&mut m, v);
                    variants.push(m);
                }
            }
            Kind::Real { set, min, max, .. } => {
                for v in [*min, *max, min + (max - min) * 0.3] {
                    let mut m = d.clone();
                    set(&mut m, v);
                    variants.push(m);
                }
            }
            Kind::Choice { set, choices, .. } => {
                for i in 0..choices.len() {
                    let mut m = d.clone();
                    set(&mut m, i);
                    variants.push(m);
                }
            }
        }
        for m in &variants {
            back(m)?;
        }
    }
    Ok(())
}

/// One entry of a method's [`Configurable::FIELDS`] table, from the field
/// `f: t` and the option written after it in `method_options!`:
///
/// - `flag "key"`: a `bool` field, on when present;
/// - `flag ! "key"`: a `bool` field on by default, off when the flag is
///   present (`no-bin-depth`);
/// - `flag "key" == ON, else OFF`: a two-valued field, `ON` when present;
/// - `int "key", (min, max)`: an integer field;
/// - `positional int "N", (min, max)`: the integer that stands alone
///   (`mc:256`);
/// - `real "key", (min, max)`: an `f64` field;
/// - `choice "key", ["word" = VALUE, …]`: one of a list of values, each
///   named by a word;
///
/// each followed by `, "doc"`.
macro_rules! field {
    ($f:ident: $t:ty; flag ! $key:literal, $doc:literal) => {
        $crate::method::options::flag($key, $doc, |m| !m.$f, |m, v| m.$f = !v)
    };
    ($f:ident: $t:ty; flag $key:literal == $on:path, else $off:path, $doc:literal) => {
        $crate::method::options::flag(
            $key,
            $doc,
            |m| m.$f == $on,
            |m, v| m.$f = if v { $on } else { $off },
        )
    };
    ($f:ident: $t:ty; flag $key:literal, $doc:literal) => {
        $crate::method::options::flag($key, $doc, |m| m.$f, |m, v| m.$f = v)
    };
    ($f:ident: $t:ty; positional int $key:literal, $r:expr, $doc:literal) => {
        $crate::method::options::positional($crate::method::options::field!(
            $f: $t; int $key, $r, $doc
        ))
    };
    ($f:ident: $t:ty; int $key:literal, $r:expr, $doc:literal) => {
        $crate::method::options::int($key, $doc, $r, |m| m.$f as u64, |m, v| m.$f = v as $t)
    };
    ($f:ident: $t:ty; real $key:literal, $r:expr, $doc:literal) => {
        $crate::method::options::real($key, $doc, $r, |m| m.$f, |m, v| m.$f = v)
    };
    ($f:ident: $t:ty; choice $key:literal, [$($word:literal = $v:path),+ $(,)?], $doc:literal) => {
        $crate::method::options::choice(
            $key,
            $doc,
            &[$($word),+],
            |m| {
                [$($v),+]
                    .iter()
                    .position(|c| *c == m.$f)
                    .unwrap_or(usize::MAX)
            },
            |m, i| m.$f = [$($v),+][i],
        )
    };
}
pub(crate) use field;

/// A method's options declared once: each field with its doc, type and
/// default, then optionally its command-line option (the forms of
/// `field!`) and a builder `with_x(value)`; then the method's registry
/// constants. Yields the struct, its `Default`, the builders and the
/// [`Configurable`] implementation, whose `FIELDS` list the fields with an
/// option in declaration order (the order names print them).
///
/// ```text
/// method_options! {
///     /// Docs of the method.
///     #[derive(Clone, Copy, Debug, PartialEq)]
///     pub struct Pcss {
///         /// Side of the map; default 1024.
///         pub resolution: u32 = 1024,
///             option(int "map", (1, 16384), "side of the map (ours)"),
///             builder(/// With a map of `value × value` texels.
///                 with_resolution);
///         …
///     }
///     name: "pcss",
///     summary: "percentage-closer soft shadows (Fernando 2005)",
///     lights: LightKind::ALL,
///     default_run: &["pcss"],
///     compare: &["pcss", "pcss:map=256"],
/// }
/// ```
///
/// The method's `impl Method` takes its `name()` and `lights()` from
/// `from_options!`.
macro_rules! method_options {
    (
        $(#[$attr:meta])*
        pub struct $T:ident {
            $(
                $(#[$fdoc:meta])*
                pub $f:ident: $t:ty = $default:expr
                $(, option($($opt:tt)*))?
                $(, builder($(#[$bdoc:meta])* $b:ident))?
                ;
            )*
        }
        name: $name:literal,
        summary: $summary:expr,
        lights: $lights:expr,
        default_run: $run:expr,
        compare: $compare:expr $(,)?
    ) => {
        $(#[$attr])*
        pub struct $T {
            $(
                $(#[$fdoc])*
                pub $f: $t,
            )*
        }

        impl Default for $T {
            fn default() -> $T {
                $T {
                    $($f: $default,)*
                }
            }
        }

        impl $T {
            $($(
                $(#[$bdoc])*
                #[must_use]
                pub fn $b(mut self, value: $t) -> $T {
                    self.$f = value;
                    self
                }
            )?)*
        }

        impl $crate::method::options::Configurable for $T {
            const NAME: &'static str = $name;
            const SUMMARY: &'static str = $summary;
            const LIGHTS: &'static [$crate::scene::LightKind] = $lights;
            const DEFAULT_RUN: &'static [&'static str] = $run;
            const COMPARE: &'static [&'static str] = $compare;
            const FIELDS: &'static [$crate::method::options::Field<$T>] = &[
                $($(
                    $crate::method::options::field!($f: $t; $($opt)*),
                )?)*
            ];
        }
    };
}
pub(crate) use method_options;

/// The items of `impl Method` that a method declared with
/// `method_options!` takes from its declaration: `name()`, its
/// [`print`]ed name, and `lights()`, its [`Configurable::LIGHTS`].
macro_rules! from_options {
    () => {
        fn name(&self) -> String {
            $crate::method::options::print(self)
        }

        fn lights(&self) -> &'static [$crate::scene::LightKind] {
            <Self as $crate::method::options::Configurable>::LIGHTS
        }
    };
}
pub(crate) use from_options;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::method::registry::parse as parse_name;
    use crate::method::{MonteCarlo, Pcss, Sism};

    fn option_error(name: &str) -> OptionError {
        match parse_name(name) {
            Err(ParseError::Option { error, .. }) => error,
            other => panic!("{name}: {other:?}"),
        }
    }

    #[test]
    fn an_option_given_twice_is_refused_whichever_kind() {
        // A value, the positional value, a flag: each given twice, equal
        // or not, is refused (the scene files refuse duplicate keys).
        for (name, key) in [
            ("mc:256,seed=3,seed=4", "seed"),
            ("mc:256,seed=3,seed=3", "seed"),
            ("mc:256,512", "N"),
            ("pcss:map=256,filter=9,map=512", "map"),
            ("sism:exact-union,exact-union", "exact-union"),
        ] {
            assert_eq!(option_error(name), OptionError::Repeated { key }, "{name}");
            let message = parse_name(name).unwrap_err().to_string();
            assert!(
                message.contains("given twice") && !message.contains('\n'),
                "{message}"
            );
        }
        // Given once each, in any order: accepted.
        let m = parse_name("mc:seed=4,256").unwrap();
        assert_eq!(m.name(), MonteCarlo::new(256).with_seed(4).name());
        assert!(parse_name("pcss:filter=9,map=512").is_ok());
    }

    #[test]
    fn parse_errors_are_typed_and_name_what_is_wrong() {
        assert!(matches!(
            parse_name("no-such-method"),
            Err(ParseError::UnknownMethod { .. })
        ));
        assert_eq!(
            option_error("pcss:sideways"),
            OptionError::Unknown {
                item: "sideways".into()
            }
        );
        assert_eq!(
            option_error("pcss:sideways=1"),
            OptionError::Unknown {
                item: "sideways".into()
            }
        );
        assert!(matches!(
            option_error("pcss:map"),
            OptionError::NeedsValue { key: "map", .. }
        ));
        assert_eq!(
            option_error("sism:exact-union=1"),
            OptionError::FlagWithValue { key: "exact-union" }
        );
        let e = option_error("pcss:map=0");
        assert_eq!(
            e,
            OptionError::Invalid {
                key: "map",
                value: "0".into(),
                expected: Expected::Int { min: 1, max: 16384 }
            }
        );
        assert_eq!(
            e.to_string(),
            "map must be an integer from 1 to 16384, got '0'"
        );
        let full = parse_name("pcss:map=0").unwrap_err();
        assert!(full.to_string().starts_with("'pcss:map=0': map must be"));
        assert!(full.to_string().contains("pcss accepts map=N (1–16384)"));
        // A method built in code with a field out of range.
        let bad = Sism::default().with_grid(1.0, 16, 0);
        assert!(matches!(
            check(&bad),
            Err(OptionError::Invalid { key: "slices", .. })
        ));
        assert_eq!(check(&Pcss::default()), Ok(()));
    }
}
