//! The located JSON reader under the scene and points files: a parsed value
//! (`Json`) that keeps integers apart from other numbers and object keys in
//! file order, duplicates rejected while parsing, built only for the small
//! parts of a file (a light, a camera, one vertex, one point: at most
//! [`SMALL_VALUES`] values each); the streamed parts around them (`Array`,
//! `Object`: a file's lists are read one item at a time, never held as a
//! tree); a path into the file (`At`), rendered (`meshes[2].triangles[5][1]`)
//! only when an error needs it; an object's checked fields (`Fields`); and
//! the walk over one file (`Cx`), whose every accessor fails with a
//! [`FileError`] naming the file and the place. What the scene and points
//! files hold is read in the parent module.

use super::error::{whole, FileError, Place};
use glam::DVec3;
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::cell::{Cell, RefCell};
use std::fmt;

/// A parsed JSON value that keeps integers apart from other numbers and
/// object keys in file order (duplicates rejected while parsing, with their
/// line and column).
#[derive(Debug)]
pub(super) enum Json {
    Null,
    Bool(bool),
    UInt(u64),
    Int(i64),
    Float(f64),
    Str(String),
    Array(Vec<Json>),
    Object(Vec<(String, Json)>),
}

impl Json {
    pub(super) fn describe(&self) -> String {
        match self {
            Json::Null => "null".to_owned(),
            Json::Bool(b) => b.to_string(),
            Json::UInt(_) | Json::Int(_) | Json::Float(_) => "a number".to_owned(),
            Json::Str(s) => format!("the string {}", quoted(s)),
            Json::Array(a) => format!("an array of {}", a.len()),
            Json::Object(_) => "an object".to_owned(),
        }
    }
}

/// The most JSON values (numbers, strings, arrays, objects, …) one small
/// part of a file may hold — a light, a camera, a primitive, a transform,
/// one vertex, one triangle, one point — since its tree is built whole
/// (about 50 bytes a value): what a hostile file nests in one of them is
/// refused past 3 MB of tree, not built at 17 times its size.
pub(super) const SMALL_VALUES: usize = 1 << 16;

/// What is left of one small part's [`SMALL_VALUES`].
struct Budget {
    left: Cell<usize>,
    exceeded: Cell<bool>,
}

impl Budget {
    fn new() -> Budget {
        Budget {
            left: Cell::new(SMALL_VALUES),
            exceeded: Cell::new(false),
        }
    }

    /// Takes one value, or fails once the budget is spent.
    fn take<E: de::Error>(&self) -> Result<(), E> {
        match self.left.get().checked_sub(1) {
            Some(left) => {
                self.left.set(left);
                Ok(())
            }
            None => {
                self.exceeded.set(true);
                Err(E::custom("too many values"))
            }
        }
    }
}

/// A [`Json`] tree of one small part, within its [`Budget`].
#[derive(Clone, Copy)]
struct Small<'b>(&'b Budget);

impl<'de> DeserializeSeed<'de> for Small<'_> {
    type Value = Json;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Json, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Small<'_> {
    type Value = Json;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_unit<E: de::Error>(self) -> Result<Json, E> {
        self.0.take()?;
        Ok(Json::Null)
    }

    fn visit_bool<E: de::Error>(self, b: bool) -> Result<Json, E> {
        self.0.take()?;
        Ok(Json::Bool(b))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Json, E> {
        self.0.take()?;
        Ok(Json::UInt(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Json, E> {
        self.0.take()?;
        Ok(u64::try_from(v).map_or(Json::Int(v), Json::UInt))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Json, E> {
        self.0.take()?;
        Ok(Json::Float(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Json, E> {
        self.0.take()?;
        Ok(Json::Str(v.to_owned()))
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<Json, E> {
        self.0.take()?;
        Ok(Json::Str(v))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Json, A::Error> {
        self.0.take()?;
        let mut items = Vec::new();
        while let Some(v) = seq.next_element_seed(self)? {
            items.push(v);
        }
        Ok(Json::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Json, A::Error> {
        self.0.take()?;
        let mut entries: Vec<(String, Json)> = Vec::new();
        // Linear search for the usual few keys, a set past that.
        let mut seen: Option<std::collections::HashSet<String>> = None;
        while let Some(key) = map.next_key::<String>()? {
            let duplicate = match &mut seen {
                Some(set) => !set.insert(key.clone()),
                None if entries.len() < 16 => entries.iter().any(|(k, _)| *k == key),
                None => {
                    let mut set: std::collections::HashSet<String> =
                        entries.iter().map(|(k, _)| k.clone()).collect();
                    let dup = !set.insert(key.clone());
                    seen = Some(set);
                    dup
                }
            };
            if duplicate {
                return Err(duplicate_key(&key));
            }
            let value = map.next_value_seed(self)?;
            entries.push((key, value));
        }
        Ok(Json::Object(entries))
    }
}

/// The error of a key given twice in one object, placed by serde_json at
/// its line and column.
fn duplicate_key<E: de::Error>(key: &str) -> E {
    E::custom(format!("duplicate key {}", quoted(key)))
}

/// What a value is, for "expected …, got …", when it is read as a stream:
/// scalars by what they are, an array by its length (counted without
/// keeping it), an object as one.
struct Describe;

impl<'de> Visitor<'de> for Describe {
    type Value = String;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_unit<E>(self) -> Result<String, E> {
        Ok("null".to_owned())
    }

    fn visit_bool<E>(self, b: bool) -> Result<String, E> {
        Ok(b.to_string())
    }

    fn visit_u64<E>(self, _: u64) -> Result<String, E> {
        Ok("a number".to_owned())
    }

    fn visit_i64<E>(self, _: i64) -> Result<String, E> {
        Ok("a number".to_owned())
    }

    fn visit_f64<E>(self, _: f64) -> Result<String, E> {
        Ok("a number".to_owned())
    }

    fn visit_str<E>(self, v: &str) -> Result<String, E> {
        Ok(format!("the string {}", quoted(v)))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<String, A::Error> {
        let mut n = 0usize;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            n += 1;
        }
        Ok(format!("an array of {n}"))
    }

    fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<String, A::Error> {
        Ok("an object".to_owned())
    }
}

/// The rest of an array, read one item at a time ([`Array`]).
pub(super) trait Items<'de> {
    type Out;
    fn items<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Out, A::Error>;
}

/// The entries of an object, read one at a time ([`Object`]).
pub(super) trait Entries<'de> {
    type Out;
    fn entries<A: MapAccess<'de>>(self, map: A) -> Result<Self::Out, A::Error>;
}

/// A streamed array at `at`: its items go to `I`; any other value fails
/// with "expected an array, got …".
pub(super) struct Array<'c, 'f, 'a, I> {
    pub(super) cx: &'c Cx<'f>,
    pub(super) at: &'a At<'a>,
    pub(super) items: I,
}

/// A streamed object at `at`: its entries go to `N`; any other value
/// fails with "expected an object, got …".
pub(super) struct Object<'c, 'f, 'a, N> {
    pub(super) cx: &'c Cx<'f>,
    pub(super) at: &'a At<'a>,
    pub(super) entries: N,
}

/// The `DeserializeSeed` and `Visitor` of a streamed value `$T` whose
/// payload `$P` reads the rest: the visits of any other kind fail with
/// "expected `$expected`, got …" (the value described as [`Describe`]
/// does), reported at the value's place; the two visits of arrays and
/// objects, `$visits`, are the type's own.
macro_rules! streamed {
    ($T:ident<$P:ident: $Reads:ident>, $expected:literal, $($visits:item)*) => {
        impl<'de, $P: $Reads<'de>> DeserializeSeed<'de> for $T<'_, '_, '_, $P> {
            type Value = $P::Out;

            fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<$P::Out, D::Error> {
                d.deserialize_any(self)
            }
        }

        impl<$P> $T<'_, '_, '_, $P> {
            fn wrong<T, E: de::Error>(&self, got: String) -> Result<T, E> {
                Err(self.cx.fail(self.cx.err(
                    self.at,
                    format!(concat!("expected ", $expected, ", got {}"), got),
                )))
            }
        }

        impl<'de, $P: $Reads<'de>> Visitor<'de> for $T<'_, '_, '_, $P> {
            type Value = $P::Out;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str($expected)
            }
            fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
                self.wrong(Describe.visit_unit()?)
            }
            fn visit_bool<E: de::Error>(self, v: bool) -> Result<Self::Value, E> {
                self.wrong(Describe.visit_bool(v)?)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
                self.wrong(Describe.visit_u64(v)?)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
                self.wrong(Describe.visit_i64(v)?)
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
                self.wrong(Describe.visit_f64(v)?)
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
                self.wrong(Describe.visit_str(v)?)
            }

            $($visits)*
        }
    };
}

streamed! {
    Array<I: Items>, "an array",

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<I::Out, A::Error> {
        self.wrong(Describe.visit_map(map)?)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<I::Out, A::Error> {
        self.items.items(seq)
    }
}

streamed! {
    Object<N: Entries>, "an object",

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<N::Out, A::Error> {
        self.cx.started.set(true);
        self.wrong(Describe.visit_seq(seq)?)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<N::Out, A::Error> {
        self.cx.started.set(true);
        self.entries.entries(map)
    }
}

/// A path into the JSON tree, rendered only when an error needs it.
#[derive(Clone, Copy)]
pub(super) struct At<'a> {
    parent: Option<&'a At<'a>>,
    seg: Seg<'a>,
}

#[derive(Clone, Copy)]
enum Seg<'a> {
    Root,
    Key(&'a str),
    Index(usize),
}

impl<'a> At<'a> {
    pub(super) const ROOT: At<'static> = At {
        parent: None,
        seg: Seg::Root,
    };

    pub(super) fn key(&'a self, key: &'a str) -> At<'a> {
        At {
            parent: Some(self),
            seg: Seg::Key(key),
        }
    }

    pub(super) fn index(&'a self, i: usize) -> At<'a> {
        At {
            parent: Some(self),
            seg: Seg::Index(i),
        }
    }

    fn place(&self) -> Place {
        let mut segs = Vec::new();
        let mut at = Some(self);
        while let Some(a) = at {
            segs.push(a.seg);
            at = a.parent;
        }
        let mut s = String::new();
        for seg in segs.iter().rev() {
            match *seg {
                Seg::Root => {}
                Seg::Key(k) if is_identifier(k) => {
                    if !s.is_empty() {
                        s.push('.');
                    }
                    s.push_str(k);
                }
                Seg::Key(k) => s.push_str(&format!("[{}]", quoted(k))),
                Seg::Index(i) => s.push_str(&format!("[{i}]")),
            }
        }
        if s.is_empty() {
            Place::Whole
        } else {
            Place::Path(s)
        }
    }
}

fn is_identifier(k: &str) -> bool {
    !k.is_empty() && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// An object's fields, every key checked against the allowed list.
pub(super) struct Fields<'v>(&'v [(String, Json)]);

impl<'v> Fields<'v> {
    pub(super) fn get(&self, key: &str) -> Option<&'v Json> {
        self.0.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }
}

/// The walk over one file: every error names the file and the place.
pub(super) struct Cx<'a> {
    pub(super) file: &'a str,
    /// The first error found while serde_json walks the file, kept while
    /// it unwinds (serde's own error carries a message only).
    stash: RefCell<Option<FileError>>,
    /// Whether the file's top-level value began (else an end of input is
    /// an empty file).
    started: Cell<bool>,
}

impl<'a> Cx<'a> {
    pub(super) fn new(file: &'a str) -> Cx<'a> {
        Cx {
            file,
            stash: RefCell::new(None),
            started: Cell::new(false),
        }
    }
}

impl Cx<'_> {
    pub(super) fn err(&self, at: &At, message: impl Into<String>) -> FileError {
        FileError {
            file: self.file.to_owned(),
            place: at.place(),
            message: message.into(),
        }
    }

    /// Keeps `e` (the first error wins) and gives serde the error that
    /// unwinds its walk; [`Cx::finish`] returns `e`.
    pub(super) fn fail<E: de::Error>(&self, e: FileError) -> E {
        let mut stash = self.stash.borrow_mut();
        if stash.is_none() {
            *stash = Some(e);
        }
        E::custom("see the stashed error")
    }

    /// The outcome of a walk: its value, the error kept by [`Cx::fail`], an
    /// empty file, or serde_json's syntax error at its line and column.
    pub(super) fn finish<T>(&self, r: Result<T, serde_json::Error>) -> Result<T, FileError> {
        r.map_err(|e| {
            if let Some(kept) = self.stash.borrow_mut().take() {
                kept
            } else if e.is_eof() && !self.started.get() {
                whole(self.file, "file is empty".to_owned())
            } else {
                self.json_error(&e)
            }
        })
    }

    /// One small part of the file, the value of `map`'s current entry, as
    /// a [`Json`] tree within [`SMALL_VALUES`].
    pub(super) fn small_value<'de, A: MapAccess<'de>>(
        &self,
        map: &mut A,
        at: &At,
    ) -> Result<Json, A::Error> {
        let budget = Budget::new();
        map.next_value_seed(Small(&budget))
            .map_err(|e| self.over_budget(&budget, at, e))
    }

    /// The next item of `seq` (at `at`) as a [`Json`] tree within
    /// [`SMALL_VALUES`].
    pub(super) fn small_item<'de, A: SeqAccess<'de>>(
        &self,
        seq: &mut A,
        at: &At,
    ) -> Result<Option<Json>, A::Error> {
        let budget = Budget::new();
        seq.next_element_seed(Small(&budget))
            .map_err(|e| self.over_budget(&budget, at, e))
    }

    fn over_budget<E: de::Error>(&self, budget: &Budget, at: &At, e: E) -> E {
        if budget.exceeded.get() {
            self.fail(self.err(
                at,
                format!("holds more than {SMALL_VALUES} JSON values, far more than it can"),
            ))
        } else {
            e
        }
    }

    /// The next key of the streamed object `map` at `at`, as its index in
    /// `keys`; a key not in `keys`, or one already marked in `seen` (a
    /// duplicate, reported at its line and column), fails the walk.
    pub(super) fn next_key<'de, A: MapAccess<'de>>(
        &self,
        map: &mut A,
        at: &At,
        keys: &[&str],
        seen: &mut [bool],
    ) -> Result<Option<usize>, A::Error> {
        let Some(key) = map.next_key::<String>()? else {
            return Ok(None);
        };
        let Some(k) = keys.iter().position(|&k| k == key) else {
            return Err(self.fail(self.err(
                &at.key(&key),
                format!("unknown key (expected one of: {})", keys.join(", ")),
            )));
        };
        if std::mem::replace(&mut seen[k], true) {
            return Err(duplicate_key(&key));
        }
        Ok(Some(k))
    }

    /// A JSON syntax error at its line and column.
    pub(super) fn json_error(&self, e: &serde_json::Error) -> FileError {
        let full = e.to_string();
        let suffix = format!(" at line {} column {}", e.line(), e.column());
        let mut message = full.strip_suffix(&suffix).unwrap_or(&full).to_owned();
        if message == "number out of range" {
            message.push_str(" (not a finite f64)");
        }
        if e.classify() == serde_json::error::Category::Io {
            // A read error (or invalid UTF-8 found by the reader, which
            // says where) has no position of serde's.
            return whole(self.file, message);
        }
        FileError {
            file: self.file.to_owned(),
            place: Place::Position {
                line: e.line(),
                column: e.column(),
            },
            message,
        }
    }

    pub(super) fn object<'v>(
        &self,
        v: &'v Json,
        at: &At,
        allowed: &[&str],
    ) -> Result<Fields<'v>, FileError> {
        let Json::Object(entries) = v else {
            return Err(self.err(at, format!("expected an object, got {}", v.describe())));
        };
        if let Some((k, _)) = entries.iter().find(|(k, _)| !allowed.contains(&k.as_str())) {
            return Err(self.err(
                &at.key(k),
                format!("unknown key (expected one of: {})", allowed.join(", ")),
            ));
        }
        Ok(Fields(entries))
    }

    /// An object tagged by its `"type"` string: the type, one of `kinds`
    /// (each with the keys it allows, `"type"` included), and its fields.
    pub(super) fn tagged<'v, 'k>(
        &self,
        v: &'v Json,
        at: &At,
        what: &str,
        kinds: &[(&'k str, &[&str])],
    ) -> Result<(&'k str, Fields<'v>), FileError> {
        let names: Vec<String> = kinds.iter().map(|(k, _)| format!("{k:?}")).collect();
        let expected = match names.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
            _ => names.join(""),
        };
        let Json::Object(entries) = v else {
            return Err(self.err(at, format!("expected an object, got {}", v.describe())));
        };
        let ty_at = at.key("type");
        let ty = match Fields(entries).get("type") {
            Some(t) => self.string(t, &ty_at)?,
            None => {
                return Err(self.err(&ty_at, format!("required but missing (one of {expected})")))
            }
        };
        let Some(&(kind, keys)) = kinds.iter().find(|(k, _)| *k == ty) else {
            return Err(self.err(
                &ty_at,
                format!("unknown {what} type {} (expected {expected})", quoted(ty)),
            ));
        };
        Ok((kind, self.object(v, at, keys)?))
    }

    pub(super) fn required<'v>(
        &self,
        f: &Fields<'v>,
        at: &At,
        key: &str,
    ) -> Result<&'v Json, FileError> {
        f.get(key)
            .ok_or_else(|| self.err(&at.key(key), "required but missing"))
    }

    pub(super) fn string<'v>(&self, v: &'v Json, at: &At) -> Result<&'v str, FileError> {
        match v {
            Json::Str(s) => Ok(s),
            _ => Err(self.err(at, format!("expected a string, got {}", v.describe()))),
        }
    }

    pub(super) fn number(&self, v: &Json, at: &At) -> Result<f64, FileError> {
        let x = match *v {
            Json::UInt(u) => u as f64,
            Json::Int(i) => i as f64,
            Json::Float(x) => x,
            _ => return Err(self.err(at, format!("expected a number, got {}", v.describe()))),
        };
        if !x.is_finite() {
            return Err(self.err(at, format!("must be finite, got {x}")));
        }
        if x.abs() > super::DOMAIN {
            return Err(self.err(
                at,
                format!(
                    "{x:e} is outside the domain |x| ≤ 1e30 (where the exact predicates are exact)"
                ),
            ));
        }
        Ok(x)
    }

    pub(super) fn uint(&self, v: &Json, at: &At) -> Result<u64, FileError> {
        match *v {
            Json::UInt(u) => Ok(u),
            Json::Int(i) => Err(self.err(at, format!("must be a non-negative integer, got {i}"))),
            Json::Float(x) => Err(self.err(at, format!("must be an integer, got {x:?}"))),
            _ => Err(self.err(
                at,
                format!("expected a non-negative integer, got {}", v.describe()),
            )),
        }
    }

    pub(super) fn vec3(&self, v: &Json, at: &At) -> Result<DVec3, FileError> {
        match v {
            Json::Array(items) if items.len() == 3 => Ok(DVec3::new(
                self.number(&items[0], &at.index(0))?,
                self.number(&items[1], &at.index(1))?,
                self.number(&items[2], &at.index(2))?,
            )),
            _ => Err(self.err(at, format!("expected [x, y, z], got {}", v.describe()))),
        }
    }

    pub(super) fn optional_vec3(
        &self,
        f: &Fields,
        at: &At,
        key: &str,
        default: DVec3,
    ) -> Result<DVec3, FileError> {
        Ok(self
            .optional(f, at, key, |v, at| self.vec3(v, at))?
            .unwrap_or(default))
    }

    /// The field `key` of `f`, read by `read` at its place; `None` when
    /// absent.
    pub(super) fn optional<'v, T>(
        &self,
        f: &Fields<'v>,
        at: &At,
        key: &str,
        read: impl FnOnce(&'v Json, &At) -> Result<T, FileError>,
    ) -> Result<Option<T>, FileError> {
        f.get(key).map(|v| read(v, &at.key(key))).transpose()
    }
}

/// A string of the input for a message: quoted, and cut to its first 60
/// bytes with the rest counted, so that a 200 MB key or value never makes
/// a 200 MB message.
pub(super) fn quoted(s: &str) -> String {
    const MAX: usize = 60;
    if s.len() <= MAX {
        return format!("{s:?}");
    }
    format!("{:?}… ({} bytes)", super::prefix(s, MAX), s.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_render_keys_and_indices() {
        let root = At::ROOT;
        let m = root.key("meshes");
        let i = m.index(2);
        let t = i.key("triangles");
        let j = t.index(5);
        assert_eq!(
            j.index(1).place(),
            Place::Path("meshes[2].triangles[5][1]".to_owned())
        );
        assert_eq!(root.key("a b").place(), Place::Path("[\"a b\"]".to_owned()));
        assert_eq!(root.place(), Place::Whole);
    }
}
