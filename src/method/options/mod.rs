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
//!
//! The crate's methods declare their options once each (the `declare`
//! module's `method_options!`): per field its doc, type, default, option and
//! builder, from which the struct, its `Default`, the builders and the
//! [`Configurable`] table are made.

mod declare;
mod error;
mod field;

pub use declare::{choice, flag, int, positional, real};
pub(crate) use declare::{field, from_options, method_options};
pub use error::{Expected, OptionError, ParseError, TableError};
pub use field::{Field, Kind};

use field::real_string;

use super::Method;
use crate::scene::LightKind;
use std::fmt::Write as _;

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
