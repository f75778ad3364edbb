//! Occluder meshes: positions and triangles, validated at construction.

use glam::DVec3;

/// Why a mesh could not be built.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum MeshError {
    /// A vertex position has a NaN or infinite coordinate.
    NonFinitePosition {
        /// The vertex index.
        vertex: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The index it holds.
        index: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// More vertices than a `u32` index can address.
    TooManyVertices {
        /// The number given.
        count: usize,
    },
}

impl_error!(MeshError, |error, f| match error {
    MeshError::NonFinitePosition { vertex } => {
        write!(f, "vertex {vertex} has a non-finite coordinate")
    }
    MeshError::IndexOutOfRange {
        triangle,
        index,
        vertex_count,
    } => write!(
        f,
        "triangle {triangle} refers to vertex {index}, but there are {vertex_count} vertices"
    ),
    MeshError::TooManyVertices { count } => {
        write!(f, "{count} vertices are more than u32 indices can address")
    }
});

/// An indexed triangle mesh of opaque, two-sided occluders. Every position
/// is finite and every index in range (checked by [`Mesh::new`]).
/// Degenerate triangles are allowed: they occlude nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// A mesh from its positions and triangles.
    ///
    /// # Errors
    /// [`MeshError::NonFinitePosition`], [`MeshError::IndexOutOfRange`],
    /// [`MeshError::TooManyVertices`]: the first problem found, in order.
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Mesh, MeshError> {
        if u32::try_from(positions.len()).is_err() {
            return Err(MeshError::TooManyVertices {
                count: positions.len(),
            });
        }
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinitePosition { vertex });
        }
        for (triangle, t) in triangles.iter().enumerate() {
            if let Some(&index) = t.iter().find(|&&i| i as usize >= positions.len()) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertex_count: positions.len(),
                });
            }
        }
        Ok(Mesh {
            positions,
            triangles,
        })
    }

    /// The vertex positions.
    #[must_use]
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// The triangles, as vertex indices.
    #[must_use]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The three corners of triangle `t`; `None` when there is no such
    /// triangle.
    #[must_use]
    pub fn corners(&self, t: usize) -> Option<[DVec3; 3]> {
        let tri = self.triangles.get(t)?;
        Some(tri.map(|i| self.positions[i as usize]))
    }

    /// The axis-aligned bounds of the vertices actually used by a triangle,
    /// `None` for a mesh without triangles.
    #[must_use]
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.triangles
            .iter()
            .flatten()
            .map(|&i| self.positions[i as usize])
            .fold(None, |b, p| match b {
                None => Some((p, p)),
                Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_meshes_are_typed_errors() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
        assert_eq!(
            Mesh::new(p.clone(), vec![[0, 1, 3]]),
            Err(MeshError::IndexOutOfRange {
                triangle: 0,
                index: 3,
                vertex_count: 3
            })
        );
        let mut q = p.clone();
        q[1].y = f64::NAN;
        assert_eq!(
            Mesh::new(q, vec![]),
            Err(MeshError::NonFinitePosition { vertex: 1 })
        );
        let m = Mesh::new(p, vec![[0, 1, 2]]).unwrap();
        assert_eq!(m.corners(0), Some([DVec3::ZERO, DVec3::X, DVec3::Y]));
        assert_eq!(m.corners(1), None);
        assert_eq!(m.bounds(), Some((DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0))));
    }

    #[test]
    fn unused_vertices_do_not_count_in_the_bounds() {
        let m = Mesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::splat(100.0)],
            vec![[0, 1, 2]],
        )
        .unwrap();
        assert_eq!(m.bounds(), Some((DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0))));
        assert_eq!(Mesh::new(vec![DVec3::ONE], vec![]).unwrap().bounds(), None);
    }
}
