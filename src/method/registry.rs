//! The one list of methods: each registered once, with its name, options,
//! summary, the light kinds it handles, the settings the default run and
//! the report compare. [`parse`], `softshadow --help`, the "available: …"
//! message, [`default_set`] and the refusal of methods not built yet all
//! read it. Adding a method is one file plus one line of [`REGISTRY`].
//!
//! | name | handles | what |
//! |---|---|---|
//! | `hard` | every light | [`HardShadow`]: the point light at the light's centre |
//! | `pcss` | every light | [`Pcss`]: percentage-closer soft shadows (Fernando 2005) |
//! | `sism` | sphere, disk | [`Sism`]: soft irregular shadow mapping (Johnson et al. 2009) |
//! | `single-sample` | sphere, disk, rect | [`SingleSample`]: single-sample soft shadows (Brabec & Seidel 2002) |
//! | `ssoc`, `backprojected-ssoc` | sphere, disk | [`Ssoc`], [`BackprojectedSsoc`]: the soft shadow occlusion camera (Mo, Popescu & Wyman 2007) and its backprojected variant (Mo & Wyman 2007) |
//! | `oess` | segment | [`Oess`]: occluding edges soft shadows (Reimann & Dreier 2016) |
//! | `mc:N` | every light | [`MonteCarlo`]: Monte Carlo light sampling, `N` samples |
//! | `exact` | every light | [`Exact`]: the exact reference |

use super::options::{self, Configurable, ParseError, TableError};
use super::{
    BackprojectedSsoc, Exact, HardShadow, Method, MonteCarlo, Oess, Pcss, SingleSample, Sism, Ssoc,
};
use crate::scene::LightKind;

/// Builds a method from the items of its name.
type Build = fn(&str, &[&str]) -> Result<Box<dyn Method>, ParseError>;

/// One registered method.
pub struct Entry {
    /// The base name (`pcss`).
    pub name: &'static str,
    /// One line: what it is and where it comes from.
    pub summary: &'static str,
    /// The light kinds it handles.
    pub lights: &'static [LightKind],
    /// The settings the default run compares (empty: not in the default
    /// set), on each light kind of `lights`.
    pub default_run: &'static [&'static str],
    /// The settings worth comparing in a report, default first.
    pub compare: &'static [&'static str],
    build: Option<Build>,
    usage: fn() -> String,
    help: fn() -> Vec<String>,
    round_trip: fn() -> Result<(), TableError>,
    accepts: fn(&str) -> bool,
}

impl std::fmt::Debug for Entry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Entry")
            .field("name", &self.name)
            .field("built", &self.is_built())
            .finish_non_exhaustive()
    }
}

fn build<T: Configurable>(name: &str, items: &[&str]) -> Result<Box<dyn Method>, ParseError> {
    options::parse::<T>(name, items).map(|m| Box::new(m) as Box<dyn Method>)
}

/// `mc:N` for a method with a positional value, else the base name.
fn usage<T: Configurable>() -> String {
    match T::FIELDS.iter().find(|f| f.positional) {
        Some(f) => format!("{}:{}", T::NAME, f.key),
        None => T::NAME.to_owned(),
    }
}

fn no_help() -> Vec<String> {
    Vec::new()
}

/// Whether `T` has the named (not positional) option `key`.
fn accepts<T: Configurable>(key: &str) -> bool {
    T::FIELDS.iter().any(|f| !f.positional && f.key == key)
}

impl Entry {
    /// The entry of the method `T`, from its [`Configurable`] constants.
    #[must_use]
    pub const fn of<T: Configurable>() -> Entry {
        Entry {
            name: T::NAME,
            summary: T::SUMMARY,
            lights: T::LIGHTS,
            default_run: T::DEFAULT_RUN,
            compare: T::COMPARE,
            build: Some(build::<T>),
            usage: usage::<T>,
            help: options::help::<T>,
            round_trip: options::round_trip::<T>,
            accepts: accepts::<T>,
        }
    }

    /// A method of the design not built yet: [`parse`] names it and says
    /// so.
    #[must_use]
    pub const fn later(
        name: &'static str,
        summary: &'static str,
        lights: &'static [LightKind],
    ) -> Entry {
        Entry {
            name,
            summary,
            lights,
            default_run: &[],
            compare: &[],
            build: None,
            usage: || String::new(),
            help: no_help,
            round_trip: || Ok(()),
            accepts: |_| false,
        }
    }

    /// Whether the method is built (else [`parse`] refuses it).
    #[must_use]
    pub fn is_built(&self) -> bool {
        self.build.is_some()
    }

    /// How the name is written alone: `mc:N`, `pcss`.
    #[must_use]
    pub fn usage(&self) -> String {
        let u = (self.usage)();
        if u.is_empty() {
            self.name.to_owned()
        } else {
            u
        }
    }

    /// One line per option: what it accepts, its default, its doc.
    #[must_use]
    pub fn options(&self) -> Vec<String> {
        (self.help)()
    }

    /// [`options::round_trip`] of the method's options table.
    ///
    /// # Errors
    /// The first broken promise.
    pub fn check_options_table(&self) -> Result<(), TableError> {
        (self.round_trip)()
    }

    /// Whether the method has the named option `key` (`seed`, `map`; not
    /// the positional value).
    #[must_use]
    pub fn accepts(&self, key: &str) -> bool {
        (self.accepts)(key)
    }

    /// Whether the method handles `kind`.
    #[must_use]
    pub fn handles(&self, kind: LightKind) -> bool {
        self.lights.contains(&kind)
    }
}

/// Every method, in the order tables list them.
pub static REGISTRY: &[Entry] = &[
    Entry::of::<HardShadow>(),
    Entry::of::<Pcss>(),
    Entry::of::<Sism>(),
    Entry::of::<SingleSample>(),
    Entry::of::<Ssoc>(),
    Entry::of::<BackprojectedSsoc>(),
    Entry::of::<Oess>(),
    Entry::of::<MonteCarlo>(),
    Entry::of::<Exact>(),
];

/// The available methods, as a message lists them: `hard, pcss, …, mc:N,
/// exact`.
#[must_use]
pub fn available() -> String {
    REGISTRY
        .iter()
        .filter(|e| e.is_built())
        .map(Entry::usage)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The entry called `base`.
#[must_use]
pub fn entry(base: &str) -> Option<&'static Entry> {
    REGISTRY.iter().find(|e| e.name == base)
}

/// The method called `name` on the command line: a registered base name,
/// then optionally `:` and its options separated by commas
/// (`sism:exact-union,slices=4`, `mc:256`).
///
/// # Errors
/// [`ParseError`], one line: an unknown method (and the available ones), a
/// method not built yet, or an option that is not understood or given
/// twice (and what the method accepts).
pub fn parse(name: &str) -> Result<Box<dyn Method>, ParseError> {
    let base = name.split(':').next().unwrap_or(name);
    let Some(entry) = entry(base) else {
        return Err(ParseError::UnknownMethod {
            name: short(name),
            available: available(),
        });
    };
    let Some(build) = entry.build else {
        return Err(ParseError::NotBuilt {
            base: entry.name,
            available: available(),
        });
    };
    let items = options::items(name, base).unwrap_or_default();
    build(name, &items)
}

/// At most 60 characters of `s`, for messages.
fn short(s: &str) -> String {
    match s.char_indices().nth(60) {
        Some((i, _)) => format!("{}…", &s[..i]),
        None => s.to_owned(),
    }
}

/// The methods the default run compares for a light of `kind`, in
/// registry order: every setting of every built method's
/// [`Entry::default_run`] that handles `kind`.
#[must_use]
pub fn default_set(kind: LightKind) -> Vec<Box<dyn Method>> {
    REGISTRY
        .iter()
        .filter(|e| e.is_built() && e.handles(kind))
        .flat_map(|e| e.default_run.iter())
        .filter_map(|name| parse(name).ok())
        .collect()
}

/// `--help`'s list: per method its usage, the lights it handles, its
/// summary, and its options.
#[must_use]
pub fn help() -> String {
    let mut out = String::new();
    for e in REGISTRY {
        let lights: Vec<&str> = e.lights.iter().map(|k| k.name()).collect();
        let built = if e.is_built() {
            ""
        } else {
            " — not built yet"
        };
        out.push_str(&format!(
            "  {:<20} {} [{}]{built}\n",
            e.usage(),
            e.summary,
            lights.join(", ")
        ));
        for o in e.options() {
            out.push_str(&format!("      {o}\n"));
        }
    }
    out
}
