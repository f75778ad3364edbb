//! What can be wrong with a method's name or its options table.

use super::field::{real_string, Kind};
use std::fmt;

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
    /// accepts; from [`parse`](super::parse) (the text given) or [`check`](super::check) (the value a
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

impl_error!(OptionError, |error, f| match error {
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
});

/// Why a method name (`base[:item,…]`) could not be read: by
/// [`registry::parse`](crate::method::registry::parse) and
/// [`parse`](super::parse).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ParseError {
    /// No registered method has the name's base.
    UnknownMethod {
        /// The name given (at most 60 characters of it).
        name: String,
        /// The available methods, as [`registry::available`](crate::method::registry::available) lists them.
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

impl_error!(ParseError, |error, f| match error {
    ParseError::UnknownMethod { name, available } => {
        write!(f, "unknown method '{name}'; available: {available}")
    }
    ParseError::Option {
        name,
        error,
        accepts,
    } => write!(f, "'{name}': {error}; {accepts}"),
});

/// Why a method's options table breaks a promise of this module
/// ([`round_trip`](super::round_trip)).
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
    /// A method whose options lie in their ranges fails [`check`](super::check).
    Check {
        /// The name printed.
        name: String,
        /// What [`check`](super::check) found.
        error: OptionError,
    },
}

impl_error!(TableError, |error, f| match error {
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
});
