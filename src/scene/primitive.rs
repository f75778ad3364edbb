//! Mesh generators: a UV sphere, an axis-aligned box, a quad, the merge of
//! several meshes, and the similarity [`Transform`] of the scene file
//! (the scene file's `primitive` meshes). Validated at the door: every generator returns a typed
//! [`PrimitiveError`], never panics, and never yields a non-finite vertex.
//!
//! The sphere and the box are closed and outward: every edge is shared by
//! exactly two triangles that traverse it in opposite directions, vertices
//! are shared (no duplicated seam or pole vertices), and every triangle's
//! normal `(b − a) × (c − a)` points out of the solid.

use super::{Mesh, MeshError};
use glam::{DVec2, DVec3};

/// The fewest longitudes [`sphere`] accepts: three give a triangular
/// bipyramid.
pub const MIN_SEGMENTS: u32 = 3;

/// The most longitudes [`sphere`] accepts: 1024 give 1 044 480 triangles.
pub const MAX_SEGMENTS: u32 = 1024;

/// Why a primitive mesh or a transform could not be built.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum PrimitiveError {
    /// An input is NaN or infinite; the field is named (`"center"`,
    /// `"radius"`, `"min"`, `"u"`, `"scale"`, `"rotate_y_deg"`, …).
    NonFinite {
        /// The offending field.
        field: &'static str,
    },
    /// A sphere's radius is zero or negative.
    NonPositiveRadius {
        /// The radius given.
        radius: f64,
    },
    /// A sphere's segment count is outside
    /// [`MIN_SEGMENTS`]`..=`[`MAX_SEGMENTS`].
    Segments {
        /// The count given.
        segments: u32,
    },
    /// A box's `max` does not exceed its `min` in some coordinate.
    EmptyBox {
        /// The coordinate: 0 for x, 1 for y, 2 for z.
        axis: usize,
        /// `min` in that coordinate.
        min: f64,
        /// `max` in that coordinate.
        max: f64,
    },
    /// A quad's half-axes `u`, `v` are zero or parallel (`u × v` is zero or
    /// overflows): the quad has no area.
    DegenerateQuad,
    /// A transform's scale is zero or negative (a negative scale would turn
    /// outward triangles inward).
    NonPositiveScale {
        /// The scale given.
        scale: f64,
    },
    /// The generated or merged mesh is invalid: a vertex overflowed to a
    /// non-finite position, or there are more vertices than `u32` indices
    /// address.
    Mesh(MeshError),
}

impl_error!(
    PrimitiveError,
    |error, f| match error {
        PrimitiveError::NonFinite { field } => write!(f, "`{field}` is not finite"),
        PrimitiveError::NonPositiveRadius { radius } => {
            write!(f, "sphere radius must be positive, got {radius}")
        }
        PrimitiveError::Segments { segments } => write!(
            f,
            "sphere segments must be in {MIN_SEGMENTS}..={MAX_SEGMENTS}, got {segments}"
        ),
        PrimitiveError::EmptyBox { axis, min, max } => write!(
            f,
            "box max must exceed min in every coordinate, got {} {max} <= {min}",
            axis_name(*axis)
        ),
        PrimitiveError::DegenerateQuad => {
            write!(f, "quad half-axes u and v are zero or parallel")
        }
        PrimitiveError::NonPositiveScale { scale } => {
            write!(f, "scale must be positive, got {scale}")
        }
        PrimitiveError::Mesh(e) => write!(f, "generated mesh: {e}"),
    },
    source = |error| match error {
        PrimitiveError::Mesh(e) => Some(e),
        _ => None,
    }
);

impl From<MeshError> for PrimitiveError {
    fn from(e: MeshError) -> PrimitiveError {
        PrimitiveError::Mesh(e)
    }
}

/// `"x"`, `"y"` or `"z"` for a coordinate index (`"?"` beyond).
#[must_use]
pub fn axis_name(axis: usize) -> &'static str {
    ["x", "y", "z"].get(axis).copied().unwrap_or("?")
}

fn finite(v: DVec3, field: &'static str) -> Result<DVec3, PrimitiveError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(PrimitiveError::NonFinite { field })
    }
}

/// The number of latitude bands [`sphere`] uses for `segments` longitudes:
/// `max(2, segments / 2)`, so that the quads near the equator are about
/// square.
#[must_use]
pub fn sphere_bands(segments: u32) -> u32 {
    (segments / 2).max(2)
}

/// A UV sphere, poles on the y axis: `segments` longitudes (`n`) and
/// `m = `[`sphere_bands`]`(n)` latitude bands; `n (m − 1) + 2` vertices all
/// on the sphere (one per pole) and `2 n (m − 1)` triangles, closed and
/// outward.
///
/// Its volume, inscribed in the sphere, is the closed form
/// `V(n, m) = (2n/3) r³ sin(2π/n) cos²(π/2m)` (each band of `n` planar
/// trapezoids, summed as tetrahedra on the centre), which tends to `4πr³/3`
/// from below; the poles are exactly at `center ± r ŷ`.
///
/// # Errors
/// [`PrimitiveError::NonFinite`], [`PrimitiveError::NonPositiveRadius`],
/// [`PrimitiveError::Segments`], and [`PrimitiveError::Mesh`] when a vertex
/// overflows (a radius and centre near `f64::MAX`).
pub fn sphere(center: DVec3, radius: f64, segments: u32) -> Result<Mesh, PrimitiveError> {
    let center = finite(center, "center")?;
    if !radius.is_finite() {
        return Err(PrimitiveError::NonFinite { field: "radius" });
    }
    if radius <= 0.0 {
        return Err(PrimitiveError::NonPositiveRadius { radius });
    }
    if !(MIN_SEGMENTS..=MAX_SEGMENTS).contains(&segments) {
        return Err(PrimitiveError::Segments { segments });
    }
    let n = segments;
    let m = sphere_bands(n);
    let tau = std::f64::consts::TAU;
    // Longitude directions in the xz plane, one table for every ring.
    let around: Vec<DVec2> = (0..n)
        .map(|j| {
            let (s, c) = (tau * f64::from(j) / f64::from(n)).sin_cos();
            DVec2::new(c, s)
        })
        .collect();
    let mut positions = Vec::with_capacity((n * (m - 1) + 2) as usize);
    positions.push(center + DVec3::Y * radius);
    for k in 1..m {
        let (sin_t, cos_t) = (std::f64::consts::PI * f64::from(k) / f64::from(m)).sin_cos();
        for d in &around {
            positions.push(center + DVec3::new(d.x * sin_t, cos_t, d.y * sin_t) * radius);
        }
    }
    positions.push(center - DVec3::Y * radius);
    let south = n * (m - 1) + 1;
    // Vertex j of ring k (1-based rings), longitude wrapping at the seam.
    let ring = |k: u32, j: u32| 1 + (k - 1) * n + j % n;
    let mut triangles = Vec::with_capacity((2 * n * (m - 1)) as usize);
    for j in 0..n {
        // With x = cos φ, z = sin φ, increasing φ turns from +x to +z, i.e.
        // clockwise seen from +y: (pole, φ_{j+1}, φ_j) is outward.
        triangles.push([0, ring(1, j + 1), ring(1, j)]);
        for k in 1..m - 1 {
            let (a, b) = (ring(k, j), ring(k, j + 1));
            let (c, d) = (ring(k + 1, j), ring(k + 1, j + 1));
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
        triangles.push([south, ring(m - 1, j), ring(m - 1, j + 1)]);
    }
    Ok(Mesh::new(positions, triangles)?)
}

/// The axis-aligned box `[min, max]`: 8 shared corners and 12 triangles,
/// closed and outward.
///
/// # Errors
/// [`PrimitiveError::NonFinite`], [`PrimitiveError::EmptyBox`] when
/// `max ≤ min` in a coordinate.
pub fn cuboid(min: DVec3, max: DVec3) -> Result<Mesh, PrimitiveError> {
    let (min, max) = (finite(min, "min")?, finite(max, "max")?);
    if let Some(axis) = (0..3).find(|&a| max[a] <= min[a]) {
        return Err(PrimitiveError::EmptyBox {
            axis,
            min: min[axis],
            max: max[axis],
        });
    }
    // Corner i takes x from bit 0, y from bit 1, z from bit 2.
    let positions = (0..8u32)
        .map(|i| {
            let pick = |bit: u32, a: usize| if i >> bit & 1 == 1 { max[a] } else { min[a] };
            DVec3::new(pick(0, 0), pick(1, 1), pick(2, 2))
        })
        .collect();
    // Each face as a quad counter-clockwise seen from outside.
    let faces: [[u32; 4]; 6] = [
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
    ];
    let triangles = faces
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    Ok(Mesh::new(positions, triangles)?)
}

/// The parallelogram `center + s u + t v`, `s, t ∈ [−1, 1]` (half-axes, as
/// for a rect light), as two triangles whose normal is along `u × v`.
///
/// # Errors
/// [`PrimitiveError::NonFinite`], [`PrimitiveError::DegenerateQuad`], and
/// [`PrimitiveError::Mesh`] when a corner overflows.
pub fn quad(center: DVec3, u: DVec3, v: DVec3) -> Result<Mesh, PrimitiveError> {
    let center = finite(center, "center")?;
    let (u, v) = (finite(u, "u")?, finite(v, "v")?);
    let n = u.cross(v);
    if !(n.is_finite() && n.length_squared() > 0.0) {
        return Err(PrimitiveError::DegenerateQuad);
    }
    let positions = vec![
        center - u - v,
        center + u - v,
        center + u + v,
        center - u + v,
    ];
    Ok(Mesh::new(positions, vec![[0, 1, 2], [0, 2, 3]])?)
}

/// All the meshes' vertices and triangles in one mesh, in order (the
/// triangles of `meshes[1]` follow those of `meshes[0]`, re-indexed).
///
/// # Errors
/// [`PrimitiveError::Mesh`] with [`MeshError::TooManyVertices`] when the
/// total exceeds what `u32` indices address.
pub fn merge(meshes: &[Mesh]) -> Result<Mesh, PrimitiveError> {
    let count: usize = meshes.iter().map(|m| m.positions().len()).sum();
    if u32::try_from(count).is_err() {
        return Err(MeshError::TooManyVertices { count }.into());
    }
    let mut positions = Vec::with_capacity(count);
    let mut triangles = Vec::new();
    for mesh in meshes {
        // In range: the total vertex count fits in u32, checked above.
        let base = positions.len() as u32;
        positions.extend_from_slice(mesh.positions());
        triangles.extend(mesh.triangles().iter().map(|t| t.map(|i| i + base)));
    }
    Ok(Mesh::new(positions, triangles)?)
}

/// A similarity transform: scale about the origin, then rotate about the y
/// axis, then translate (the scene file's `transform`). Validated by
/// [`Transform::new`]: the scale is finite and positive, so orientation and
/// closedness are kept.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    scale: f64,
    rotate_y_deg: f64,
    translate: DVec3,
}

impl Default for Transform {
    fn default() -> Transform {
        Transform::IDENTITY
    }
}

impl Transform {
    /// Scale 1, no rotation, no translation.
    pub const IDENTITY: Transform = Transform {
        scale: 1.0,
        rotate_y_deg: 0.0,
        translate: DVec3::ZERO,
    };

    /// A transform that scales by `scale`, rotates by `rotate_y_deg`
    /// degrees about +y (right-handed: +x turns toward −z, as
    /// `glam::DMat3::from_rotation_y`), then translates by `translate`.
    ///
    /// # Errors
    /// [`PrimitiveError::NonFinite`] (fields `"scale"`, `"rotate_y_deg"`,
    /// `"translate"`), [`PrimitiveError::NonPositiveScale`].
    pub fn new(
        scale: f64,
        rotate_y_deg: f64,
        translate: DVec3,
    ) -> Result<Transform, PrimitiveError> {
        if !scale.is_finite() {
            return Err(PrimitiveError::NonFinite { field: "scale" });
        }
        if scale <= 0.0 {
            return Err(PrimitiveError::NonPositiveScale { scale });
        }
        if !rotate_y_deg.is_finite() {
            return Err(PrimitiveError::NonFinite {
                field: "rotate_y_deg",
            });
        }
        Ok(Transform {
            scale,
            rotate_y_deg,
            translate: finite(translate, "translate")?,
        })
    }

    /// The scale factor, `> 0`.
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The rotation about +y, in degrees.
    #[must_use]
    pub fn rotate_y_deg(&self) -> f64 {
        self.rotate_y_deg
    }

    /// The translation.
    #[must_use]
    pub fn translate(&self) -> DVec3 {
        self.translate
    }

    /// `(sin, cos)` of the rotation: exact at multiples of 90° (where
    /// `to_radians` followed by `sin_cos` would leave a residue of about
    /// 1e-16 instead of 0).
    fn sin_cos(&self) -> (f64, f64) {
        let deg = self.rotate_y_deg.rem_euclid(360.0);
        match deg {
            // 360 after rounding a tiny negative angle up.
            0.0 | 360.0 => (0.0, 1.0),
            90.0 => (1.0, 0.0),
            180.0 => (0.0, -1.0),
            270.0 => (-1.0, 0.0),
            _ => deg.to_radians().sin_cos(),
        }
    }

    /// The image of the point `p` (possibly non-finite when `p` is near
    /// `f64::MAX`; [`Transform::apply`] checks).
    #[must_use]
    pub fn apply_point(&self, p: DVec3) -> DVec3 {
        let (s, c) = self.sin_cos();
        let q = p * self.scale;
        DVec3::new(c * q.x + s * q.z, q.y, c * q.z - s * q.x) + self.translate
    }

    /// The mesh with every vertex transformed; triangles unchanged.
    ///
    /// # Errors
    /// [`MeshError::NonFinitePosition`] when a vertex overflows.
    pub fn apply(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        let positions = mesh
            .positions()
            .iter()
            .map(|&p| self.apply_point(p))
            .collect();
        Mesh::new(positions, mesh.triangles().to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn signed_volume(m: &Mesh) -> f64 {
        (0..m.triangles().len())
            .filter_map(|t| m.corners(t))
            .map(|[a, b, c]| a.dot(b.cross(c)) / 6.0)
            .sum()
    }

    #[test]
    fn sphere_volume_matches_its_closed_form() {
        for n in [3, 4, 5, 8, 32, 101] {
            let m = sphere(DVec3::new(0.5, -1.0, 2.0), 2.0, n).unwrap();
            let bands = f64::from(sphere_bands(n));
            let n = f64::from(n);
            let expect = 2.0 * n / 3.0
                * 8.0
                * (std::f64::consts::TAU / n).sin()
                * (std::f64::consts::PI / (2.0 * bands)).cos().powi(2);
            let v = signed_volume(&m);
            assert!((v - expect).abs() < 1e-12 * expect, "{n}: {v} vs {expect}");
        }
    }

    #[test]
    fn bad_input_is_a_typed_error() {
        assert_eq!(
            sphere(DVec3::ZERO, -1.0, 8),
            Err(PrimitiveError::NonPositiveRadius { radius: -1.0 })
        );
        assert_eq!(
            sphere(DVec3::ZERO, 1.0, u32::MAX),
            Err(PrimitiveError::Segments { segments: u32::MAX })
        );
        assert!(matches!(
            sphere(DVec3::splat(f64::MAX), f64::MAX, 8),
            Err(PrimitiveError::Mesh(MeshError::NonFinitePosition { .. }))
        ));
        assert_eq!(
            cuboid(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)),
            Err(PrimitiveError::EmptyBox {
                axis: 1,
                min: 0.0,
                max: 0.0
            })
        );
        assert_eq!(
            quad(DVec3::ZERO, DVec3::X, DVec3::X * 2.0),
            Err(PrimitiveError::DegenerateQuad)
        );
        assert_eq!(
            Transform::new(0.0, 0.0, DVec3::ZERO),
            Err(PrimitiveError::NonPositiveScale { scale: 0.0 })
        );
        assert_eq!(
            Transform::new(1.0, f64::INFINITY, DVec3::ZERO),
            Err(PrimitiveError::NonFinite {
                field: "rotate_y_deg"
            })
        );
    }

    #[test]
    fn right_angles_rotate_exactly() {
        let t = Transform::new(2.0, 90.0, DVec3::Y).unwrap();
        assert_eq!(t.apply_point(DVec3::X), DVec3::new(0.0, 1.0, -2.0));
        let t = Transform::new(1.0, -90.0, DVec3::ZERO).unwrap();
        assert_eq!(t.apply_point(DVec3::X), DVec3::Z);
    }
}
