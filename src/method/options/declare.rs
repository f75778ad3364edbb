//! How a method declares its options: the field constructors of a
//! [`Configurable::FIELDS`](super::Configurable::FIELDS) table and the
//! macros that make the options struct, its `Default`, builders and table
//! from one declaration per field.

use super::field::{Field, Kind};

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

/// One entry of a method's `Configurable::FIELDS` table, from the field
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
/// `field!`) and a builder `with_x(value)` (its doc generated, linking the
/// field's), one line a field; then the method's registry
/// constants. Yields the struct, its `Default`, the builders and the
/// `Configurable` implementation, whose `FIELDS` list the fields with an
/// option in declaration order (the order names print them).
///
/// ```text
/// method_options! {
///     /// Docs of the method.
///     #[derive(Clone, Copy, Debug, PartialEq)]
///     pub struct Pcss {
///         /// Side of the map; default 1024.
///         pub resolution: u32 = 1024, option(int "map", (1, 16384), "side of the map (ours)"), builder(with_resolution);
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
                $(, builder($b:ident))?
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
                #[doc = concat!(
                    "With [`", stringify!($f), "`](", stringify!($T), "::", stringify!($f),
                    ") set to `value`."
                )]
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
/// `print`ed name, and `lights()`, its `Configurable::LIGHTS`.
///
/// A map method (one with a `resolution` field, the side of its light-view
/// maps) writes `from_options! { map_bytes_per_texel: N, needs: STAGES }`,
/// preceded by the doc of `map_bytes()` (where `N` was measured), and also
/// takes `needs()`, `STAGES`, `hides_back_faces()`, `true`, and
/// `map_bytes()`, `N · resolution²`.
macro_rules! from_options {
    () => {
        fn name(&self) -> String {
            $crate::method::options::print(self)
        }

        fn lights(&self) -> &'static [$crate::scene::LightKind] {
            <Self as $crate::method::options::Configurable>::LIGHTS
        }
    };
    ($(#[$doc:meta])* map_bytes_per_texel: $bytes:expr, needs: $needs:expr $(,)?) => {
        $crate::method::options::from_options!();

        fn needs(&self) -> $crate::render::Needs {
            $needs
        }

        /// Yes: see the trait's doc (no option of the paper asks otherwise).
        fn hides_back_faces(&self) -> bool {
            true
        }

        $(#[$doc])*
        fn map_bytes(&self) -> u64 {
            $bytes * u64::from(self.resolution).pow(2)
        }
    };
}
pub(crate) use from_options;
