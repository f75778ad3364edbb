//! The located JSON reader under the scene and points files: a parsed value
//! (`Json`) that keeps integers apart from other numbers and object keys in
//! file order, duplicates rejected while parsing (serde's `Deserialize` and
//! `Visitor`); a path into it (`At`), rendered (`meshes[2].triangles[5][1]`)
//! only when an error needs it; an object's checked fields (`Fields`); and
//! the walk over one file (`Cx`), whose every accessor fails with a
//! [`FileError`] naming the file and the place. What the scene and points
//! files hold is read in the parent module.

use super::{FileError, Place};
use glam::DVec3;
use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
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

impl<'de> Deserialize<'de> for Json {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Json, D::Error> {
        d.deserialize_any(JsonVisitor)
    }
}

struct JsonVisitor;

impl<'de> Visitor<'de> for JsonVisitor {
    type Value = Json;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_unit<E>(self) -> Result<Json, E> {
        Ok(Json::Null)
    }

    fn visit_bool<E>(self, b: bool) -> Result<Json, E> {
        Ok(Json::Bool(b))
    }

    fn visit_u64<E>(self, v: u64) -> Result<Json, E> {
        Ok(Json::UInt(v))
    }

    fn visit_i64<E>(self, v: i64) -> Result<Json, E> {
        Ok(u64::try_from(v).map_or(Json::Int(v), Json::UInt))
    }

    fn visit_f64<E>(self, v: f64) -> Result<Json, E> {
        Ok(Json::Float(v))
    }

    fn visit_str<E>(self, v: &str) -> Result<Json, E> {
        Ok(Json::Str(v.to_owned()))
    }

    fn visit_string<E>(self, v: String) -> Result<Json, E> {
        Ok(Json::Str(v))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Json, A::Error> {
        let mut items = Vec::new();
        while let Some(v) = seq.next_element()? {
            items.push(v);
        }
        Ok(Json::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Json, A::Error> {
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
                return Err(de::Error::custom(format!("duplicate key {}", quoted(&key))));
            }
            let value = map.next_value()?;
            entries.push((key, value));
        }
        Ok(Json::Object(entries))
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
}

impl Cx<'_> {
    pub(super) fn err(&self, at: &At, message: impl Into<String>) -> FileError {
        FileError {
            file: self.file.to_owned(),
            place: at.place(),
            message: message.into(),
        }
    }

    pub(super) fn parse(&self, text: &str) -> Result<Json, FileError> {
        if text.trim().is_empty() {
            return Err(super::whole(self.file, "file is empty".to_owned()));
        }
        serde_json::from_str(text).map_err(|e| self.json_error(&e))
    }

    /// A JSON syntax error at its line and column.
    pub(super) fn json_error(&self, e: &serde_json::Error) -> FileError {
        {
            let full = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            let mut message = full.strip_suffix(&suffix).unwrap_or(&full).to_owned();
            if message == "number out of range" {
                message.push_str(" (not a finite f64)");
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

    pub(super) fn array<'v>(&self, v: &'v Json, at: &At) -> Result<&'v [Json], FileError> {
        match v {
            Json::Array(items) => Ok(items),
            _ => Err(self.err(at, format!("expected an array, got {}", v.describe()))),
        }
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
        f.get(key)
            .map_or(Ok(default), |v| self.vec3(v, &at.key(key)))
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
