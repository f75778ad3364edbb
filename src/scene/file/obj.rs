//! A mesh from the bytes of an OBJ file.

use super::error::{whole, FileError};
use crate::scene::{Mesh, MeshError};
use glam::DVec3;

/// Parses an OBJ file's bytes into one mesh: every object and group merged,
/// polygons fan-triangulated, points and lines ignored, materials ignored.
/// `name` is used in error messages only.
///
/// # Errors
/// [`FileError`] (place [`Place::Whole`](super::Place::Whole)) for an OBJ syntax error (tobj's
/// message: it gives no line), a vertex that is not finite, and a
/// file without faces.
pub fn mesh_from_obj(name: &str, bytes: &[u8]) -> Result<Mesh, FileError> {
    obj_mesh(bytes).map_err(|message| whole(name, message))
}

pub(super) fn obj_mesh(bytes: &[u8]) -> Result<Mesh, String> {
    // The struct update keeps this compiling when another crate enables
    // tobj's `merging` or `reordering` features (more fields, all false).
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // tobj reads lines as UTF-8 and fails on any other byte, even in a
    // comment, with "read error": bytes that are not UTF-8 become U+FFFD
    // here, harmless in a comment or a name, an error at their line
    // elsewhere.
    let text = String::from_utf8_lossy(bytes);
    let mut reader = std::io::Cursor::new(text.as_bytes());
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| {
        // tobj stops at the line it could not read: the last one taken.
        let taken = &text.as_bytes()[..reader.position() as usize];
        let line =
            taken.iter().filter(|&&b| b == b'\n').count() + usize::from(!taken.ends_with(b"\n"));
        obj_error(&text, line, &e)
    })?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for model in &models {
        let base = u32::try_from(positions.len()).map_err(|_| "too many vertices".to_owned())?;
        positions.extend(
            model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0], c[1], c[2])),
        );
        for t in model.mesh.indices.chunks_exact(3) {
            let shifted = [t[0], t[1], t[2]].map(|i| i.checked_add(base));
            match shifted {
                [Some(a), Some(b), Some(c)] => triangles.push([a, b, c]),
                _ => return Err("too many vertices".to_owned()),
            }
        }
    }
    if triangles.is_empty() {
        return Err("has no faces".to_owned());
    }
    Mesh::new(positions, triangles).map_err(|e| match e {
        MeshError::NonFinitePosition { vertex } => {
            format!("vertex {vertex} (after merging objects) is not finite")
        }
        e => e.to_string(),
    })
}

/// A one-line message for tobj's error `e`, at `line` (where tobj
/// stopped) or, for a face index out of range — which tobj finds only
/// when it closes an object — at the first face line that has one.
pub(super) fn obj_error(text: &str, line: usize, e: &tobj::LoadError) -> String {
    use tobj::LoadError as E;
    let what = match e {
        E::PositionParseError => "a vertex (v) that is not 3 or 4 numbers",
        E::NormalParseError => "a normal (vn) that is not 3 numbers",
        E::TexcoordParseError => "a texture coordinate (vt) that cannot be read",
        E::FaceParseError => "a face (f) that cannot be read",
        E::FaceVertexOutOfBounds => {
            let line = bad_face_line(text).unwrap_or(line);
            return format!("line {line}: a face (f) names a vertex that does not exist");
        }
        E::FaceTexCoordOutOfBounds | E::FaceNormalOutOfBounds | E::FaceColorOutOfBounds => {
            return format!("OBJ: {e}");
        }
        _ => return format!("line {line}: {e} (OBJ)"),
    };
    format!("line {line}: {what}")
}

/// The 1-based line of the first face whose vertex index is 0, beyond
/// the vertices of the file (positive) or before its first vertex
/// (negative, counted back from the vertices so far).
pub(super) fn bad_face_line(text: &str) -> Option<usize> {
    let total = text
        .lines()
        .filter(|l| l.split_whitespace().next() == Some("v"))
        .count() as i64;
    let mut vertices = 0i64;
    for (k, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => vertices += 1,
            Some("f") => {
                let bad = words.any(|w| {
                    let i: i64 = w
                        .split('/')
                        .next()
                        .and_then(|i| i.parse().ok())
                        .unwrap_or(0);
                    i == 0 || i > total || -i > vertices
                });
                if bad {
                    return Some(k + 1);
                }
            }
            _ => {}
        }
    }
    None
}
