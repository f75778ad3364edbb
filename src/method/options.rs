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
//! exactly, reals in Rust's shortest round-trip form. Unknown keys and bad
//! values are errors that name what the method accepts.

use super::Method;
use crate::scene::LightKind;
use std::fmt::Write as _;

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
fn set_from<T>(field: &Field<T>, m: &mut T, value: &str) -> Result<(), String> {
    match &field.kind {
        Kind::Flag { set, .. } => {
            set(m, true);
            Ok(())
        }
        Kind::Int { set, min, max, .. } => match value.parse::<u64>() {
            Ok(v) if (*min..=*max).contains(&v) => {
                set(m, v);
                Ok(())
            }
            _ => Err(format!(
                "{} must be an integer from {min} to {max}",
                field.key
            )),
        },
        Kind::Real { set, min, max, .. } => match value.parse::<f64>() {
            Ok(v) if v.is_finite() && *min <= v && v <= *max => {
                set(m, v);
                Ok(())
            }
            _ => Err(format!(
                "{} must be a number from {} to {}",
                field.key,
                real_string(*min),
                real_string(*max)
            )),
        },
        Kind::Choice { set, choices, .. } => match choices.iter().position(|c| *c == value) {
            Some(i) => {
                set(m, i);
                Ok(())
            }
            None => Err(format!(
                "{} must be one of {}",
                field.key,
                choices.join(", ")
            )),
        },
    }
}

/// The method `T` with the options `items` (the parts of its name after
/// `base:`, split at commas), starting from the defaults. `name` is the
/// whole name, for messages.
///
/// # Errors
/// A one-line message naming the item that is not understood and what the
/// method accepts.
pub fn parse<T: Configurable>(name: &str, items: &[&str]) -> Result<T, String> {
    let mut m = T::default();
    for &item in items {
        let bad = |why: String| format!("'{name}': {why}; {}", accepted::<T>());
        let (key, value) = match item.split_once('=') {
            Some((k, v)) => (k, Some(v)),
            None => (item, None),
        };
        let named = T::FIELDS.iter().find(|f| !f.positional && f.key == key);
        match (named, value) {
            (Some(f), None) if matches!(f.kind, Kind::Flag { .. }) => set_from(f, &mut m, "")?,
            (Some(f), Some(v)) if !matches!(f.kind, Kind::Flag { .. }) => {
                set_from(f, &mut m, v).map_err(bad)?;
            }
            (Some(f), None) => return Err(bad(format!("'{key}' needs a value, {}", syntax(f)))),
            (Some(f), Some(_)) => {
                return Err(bad(format!("'{key}' is a flag, written alone: {}", f.key)))
            }
            (None, None) => match T::FIELDS.iter().find(|f| f.positional) {
                Some(f) => set_from(f, &mut m, item).map_err(bad)?,
                None => return Err(bad(format!("unknown option '{item}'"))),
            },
            (None, Some(_)) => return Err(bad(format!("unknown option '{key}'"))),
        }
    }
    Ok(m)
}

/// Checks that every field of `m` is in its documented range (methods
/// built in code, not parsed, may hold anything); the message names the
/// first that is not.
///
/// # Errors
/// `"map is 0; it must be an integer from 1 to 16384"`.
pub fn check<T: Configurable>(m: &T) -> Result<(), String> {
    for f in T::FIELDS {
        match &f.kind {
            Kind::Int { get, min, max, .. } => {
                let v = get(m);
                if !(*min..=*max).contains(&v) {
                    return Err(format!(
                        "{} is {v}; it must be an integer from {min} to {max}",
                        f.key
                    ));
                }
            }
            Kind::Real { get, min, max, .. } => {
                let v = get(m);
                if !(v.is_finite() && *min <= v && v <= *max) {
                    return Err(format!(
                        "{} is {v:?}; it must be a number from {} to {}",
                        f.key,
                        real_string(*min),
                        real_string(*max)
                    ));
                }
            }
            Kind::Choice { get, choices, .. } => {
                if get(m) >= choices.len() {
                    return Err(format!("{} is not one of {}", f.key, choices.join(", ")));
                }
            }
            Kind::Flag { .. } => {}
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
pub fn round_trip<T: Configurable>() -> Result<(), String> {
    let d = T::default();
    let back = |m: &T| -> Result<(), String> {
        let name = print(m);
        let items = items(&name, T::NAME).ok_or_else(|| format!("'{name}' lacks its base"))?;
        let parsed = parse::<T>(&name, &items)?;
        if parsed != *m {
            return Err(format!("'{name}' parses to {parsed:?}, not {m:?}"));
        }
        check(m).map_err(|e| format!("'{name}': {e}"))
    };
    if print(&d) != T::NAME && !T::FIELDS.iter().any(|f| f.positional) {
        return Err(format!("the default prints as '{}'", print(&d)));
    }
    back(&d)?;
    for f in T::FIELDS {
        let mut variants = Vec::new();
        match &f.kind {
            Kind::Flag { get, set } => {
                if get(&d) {
                    return Err(format!("flag {} is on by default", f.key));
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
            back(m).map_err(|e| format!("{}: {e}", f.key))?;
        }
    }
    Ok(())
}

/// One entry of a method's [`Configurable::FIELDS`] table, on one line:
///
/// - `field!(flag "key", field, "doc")`: a `bool` field, on when present;
/// - `field!(flag "key", !field, "doc")`: a `bool` field on by default,
///   off when the flag is present (`no-bin-depth`);
/// - `field!(flag "key", field == ON else OFF, "doc")`: a two-valued field,
///   `ON` when present;
/// - `field!(int "key", field: u32, (min, max), "doc")`: an integer field;
/// - `field!(real "key", field, (min, max), "doc")`: an `f64` field.
macro_rules! field {
    (flag $key:literal, !$f:ident, $doc:literal) => {
        $crate::method::options::flag($key, $doc, |m| !m.$f, |m, v| m.$f = !v)
    };
    (flag $key:literal, $f:ident == $on:path, else $off:path, $doc:literal) => {
        $crate::method::options::flag(
            $key,
            $doc,
            |m| m.$f == $on,
            |m, v| m.$f = if v { $on } else { $off },
        )
    };
    (flag $key:literal, $f:ident, $doc:literal) => {
        $crate::method::options::flag($key, $doc, |m| m.$f, |m, v| m.$f = v)
    };
    (int $key:literal, $f:ident: $t:ty, $r:expr, $doc:literal) => {
        $crate::method::options::int($key, $doc, $r, |m| m.$f as u64, |m, v| m.$f = v as $t)
    };
    (real $key:literal, $f:ident, $r:expr, $doc:literal) => {
        $crate::method::options::real($key, $doc, $r, |m| m.$f, |m, v| m.$f = v)
    };
}
pub(crate) use field;

/// Builder methods `with_x(value)` for fields of a method's options, each
/// documented: `builders!(Pcss { /// With a … map. with_resolution =>
/// resolution: u32, … })`.
macro_rules! builders {
    ($T:ident { $($(#[$doc:meta])* $name:ident => $f:ident: $t:ty),* $(,)? }) => {
        impl $T {
            $(
                $(#[$doc])*
                #[must_use]
                pub fn $name(mut self, value: $t) -> $T {
                    self.$f = value;
                    self
                }
            )*
        }
    };
}
pub(crate) use builders;
