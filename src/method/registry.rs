//! The one list of methods: each registered once, with its name, options,
//! summary, the light kinds it handles, the settings the default run and
//! the report compare. [`parse`], `softshadow --help`, the "available: …"
//! message and [`default_set`] all read it. Adding a method is one file
//! plus one line of [`REGISTRY`].
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
//! | `exact` | every light | [`Exact`](struct@Exact): the exact reference |

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
    build: Build,
    usage: fn() -> String,
    help: fn() -> Vec<String>,
    round_trip: fn() -> Result<(), TableError>,
    accepts: fn(&str) -> bool,
}

impl std::fmt::Debug for Entry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Entry")
            .field("name", &self.name)
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
            build: build::<T>,
            usage: usage::<T>,
            help: options::help::<T>,
            round_trip: options::round_trip::<T>,
            accepts: accepts::<T>,
        }
    }

    /// How the name is written alone: `mc:N`, `pcss`.
    #[must_use]
    pub fn usage(&self) -> String {
        (self.usage)()
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
/// [`ParseError`], one line: an unknown method (and the available ones),
/// or an option that is not understood or given twice (and what the method
/// accepts).
pub fn parse(name: &str) -> Result<Box<dyn Method>, ParseError> {
    let base = name.split(':').next().unwrap_or(name);
    let Some(entry) = entry(base) else {
        return Err(ParseError::UnknownMethod {
            name: short(name),
            available: available(),
        });
    };
    let items = options::items(name, base).unwrap_or_default();
    (entry.build)(name, &items)
}

/// Why [`parse_with_seed`] refused a name with a seed.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SeedError {
    /// The name is not a method ([`parse`]'s error).
    Parse(ParseError),
    /// The method has no option `seed`.
    NoSeed {
        /// Its base name.
        base: &'static str,
        /// The methods that have one, as their usage (`mc:N`).
        seeded: String,
    },
    /// The name sets `seed=` already.
    Repeated,
}

impl_error!(SeedError, |error, f| match error {
    SeedError::Parse(e) => write!(f, "{e}"),
    SeedError::NoSeed { base, seeded } => {
        write!(f, "method {base} has no seed (methods with one: {seeded})")
    }
    SeedError::Repeated => write!(f, "the name sets seed= already; give the seed once"),
});

/// [`parse`] with the option `seed=S` added when `seed` is given: the
/// command line's `--seed S` and the Python package's `seed=S`. Refused,
/// rather than one of them silently dropped: a seed for a method without
/// one, and a seed beside a `seed=` of the name.
///
/// # Errors
/// [`SeedError`].
pub fn parse_with_seed(name: &str, seed: Option<u64>) -> Result<Box<dyn Method>, SeedError> {
    let Some(seed) = seed else {
        return parse(name).map_err(SeedError::Parse);
    };
    let base = name.split(':').next().unwrap_or(name);
    let Some(entry) = entry(base) else {
        return parse(name).map_err(SeedError::Parse);
    };
    if !entry.accepts("seed") {
        let seeded: Vec<String> = REGISTRY
            .iter()
            .filter(|e| e.accepts("seed"))
            .map(Entry::usage)
            .collect();
        return Err(SeedError::NoSeed {
            base: entry.name,
            seeded: seeded.join(", "),
        });
    }
    let sep = if name.contains(':') { ',' } else { ':' };
    parse(&format!("{name}{sep}seed={seed}")).map_err(|e| match e.option() {
        Some(options::OptionError::Repeated { .. }) => SeedError::Repeated,
        _ => SeedError::Parse(e),
    })
}

/// At most 60 characters of `s`, for messages.
fn short(s: &str) -> String {
    match s.char_indices().nth(60) {
        Some((i, _)) => format!("{}…", &s[..i]),
        None => s.to_owned(),
    }
}

/// The methods the default run compares for a light of `kind`, in
/// registry order: every setting of every method's
/// [`Entry::default_run`] that handles `kind`.
#[must_use]
pub fn default_set(kind: LightKind) -> Vec<Box<dyn Method>> {
    REGISTRY
        .iter()
        .filter(|e| e.handles(kind))
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
        out.push_str(&format!(
            "  {:<20} {} [{}]\n",
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_seed_is_the_option_seed_and_is_refused_where_it_cannot_apply() {
        for (name, seed, want) in [
            ("mc:16", Some(3), "mc:16,seed=3"),
            ("mc", Some(3), "mc:64,seed=3"),
            ("mc:16", None, "mc:16"),
            ("hard", None, "hard"),
        ] {
            let m = parse_with_seed(name, seed).unwrap();
            assert_eq!(m.name(), parse(want).unwrap().name(), "{name} {seed:?}");
        }
        // The seed changes the answer's name, hence the method.
        assert_ne!(
            parse_with_seed("mc:16", Some(3)).unwrap().name(),
            parse_with_seed("mc:16", Some(4)).unwrap().name()
        );
        match parse_with_seed("hard", Some(1)) {
            Err(SeedError::NoSeed { base, seeded }) => {
                assert_eq!((base, seeded.as_str()), ("hard", "mc:N"));
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            parse_with_seed("mc:16,seed=2", Some(1)).err(),
            Some(SeedError::Repeated)
        );
        assert!(matches!(
            parse_with_seed("nope", Some(1)),
            Err(SeedError::Parse(ParseError::UnknownMethod { .. }))
        ));
        assert!(matches!(
            parse_with_seed("mc:1", Some(1)),
            Err(SeedError::Parse(ParseError::Option { .. }))
        ));
    }
}
