//! Mesh topology and silhouette edges.
//!
//! [`MeshTopology`] is built once from an indexed triangle mesh: every
//! undirected edge with its incident faces (stored flat, CSR-style), boundary
//! edges (one face) and non-manifold edges (three or more) flagged, faces
//! with a repeated vertex index flagged. It is precision-independent: the
//! queries take positions as `f32` ([`glam::Vec3`]) or `f64`
//! ([`glam::DVec3`]), promoted to `f64` (exactly) for the predicates.
//!
//! - [`MeshTopology::silhouettes_from_point`]: the silhouette (contour) edges
//!   seen from a point, each oriented, decided with the exact
//!   [`orient3d`] predicate.
//! - [`MeshTopology::potential_silhouettes`]: a conservative superset for a
//!   sphere light — it contains the silhouettes from every point of the ball.
//!
//! # Definition
//!
//! Occluders are two-sided ([visibility](crate::definitions#visibility)), so the definition does not rely on
//! the mesh being consistently oriented. Seen from `x`, a face `f = (a, b, c)`
//! is *front-facing* when `orient3d(a, b, c, x)` is [`Sign::Negative`] (`x`
//! is on the side the normal `(b − a) × (c − a)` points to, and sees
//! `a, b, c` counter-clockwise) and *back-facing* otherwise: **an edge-on face
//! (`orient3d = 0`: `x` in its plane, a collinear face, or a face with a
//! non-finite vertex) counts as back-facing**, everywhere, with no exception.
//!
//! Give every face the weight `w(f) = +1` (front) or `−1` (back) and let
//! `dir(f, e) = +1` when `f` traverses the edge `e = [v0, v1]` (stored with
//! `v0 < v1`) from `v0` to `v1`, `−1` otherwise. The edge's *multiplicity*
//! is
//!
//! ```text
//! m(e) = Σ_{f ∋ e} w(f) · dir(f, e).
//! ```
//!
//! The edge is a silhouette edge from `x` when `m(e) ≠ 0`; it is returned
//! oriented from `from` to `to` so that `m > 0`, together with `|m|`.
//! Geometrically, a front face traverses its edges counter-clockwise as seen
//! from `x`, so it lies on the *left* of each of them: **"left as seen from
//! `x`" means `orient3d(from, to, apex, x) = Negative`** — `x` sees
//! `from, to, apex` counter-clockwise, equivalently `orient2d` of the
//! central projection from `x` (onto a plane in front of `x`) of `from`,
//! `to`, `apex` is positive. `m(e)` is then the number of incident faces on
//! the left of the returned edge minus the number on its right, i.e. the
//! jump of the depth complexity seen from `x` (how many triangles a ray from
//! `x` crosses) when the ray sweeps across the edge from its right to its
//! left. So:
//!
//! - **manifold edge** (two faces): `m ∈ {−2, 0, 2}`. For a consistently
//!   oriented mesh `m ≠ 0` exactly when one face is front- and the other
//!   back-facing (the two faces face `x` differently), and the returned
//!   orientation is the front face's own traversal (front face on the left).
//!   For an inconsistently oriented pair it is the contour test (both faces
//!   on the same side of the edge), which is what shadows need.
//! - **boundary edge** (one face): always `|m| = 1`, so every boundary edge
//!   is returned, oriented with its face on the left. An open surface casts a
//!   shadow whichever side faces `x`, and its boundary bounds that shadow;
//!   this is the two-sided reading of "boundary edges facing `x`".
//!   The boundary edges of an *edge-on* face are returned too (the
//!   back-facing rule applies to them as to every face: they are oriented
//!   with the face on their right). Their projections are collinear and
//!   bound no area, so a signed-area kernel sums them to zero; keeping them
//!   keeps the invariant below free of exceptions.
//! - **non-manifold edge** (`k ≥ 3` faces): returned when `m ≠ 0`, oriented
//!   so that the majority of faces lies on its left, with multiplicity `|m|`
//!   (the net depth-complexity jump: e.g. two closed solids sharing an edge
//!   whose shadows lie on opposite sides of it give `m = 2 − 2 = 0`).
//!
//! **Invariant** (checked by the tests for every mesh and point): the
//! returned edges, counted `multiplicity` times, form a closed 1-cycle — at
//! every vertex the total multiplicity of outgoing edges equals that of the
//! incoming ones — because they are the boundary `Σ w(f) ∂f` of the faces.
//! In particular, on a closed edge-manifold mesh (every edge has two faces;
//! consistent orientation is not required) every vertex has even silhouette
//! degree. Faces with a repeated vertex index have a zero boundary chain and
//! are left out of the edge table.
//!
//! Sources: the silhouette test of shadow-volume algorithms (Crow 1977;
//! SISM, Johnson et al. 2009, §2.1, which needs silhouettes only for
//! performance: signed occlusion sums the edges with their orientation and
//! multiplicity).

use glam::{DVec2, DVec3};

use super::predicate::{orient2d, orient3d, Sign};

mod conservative;

/// The largest vertex count a [`MeshTopology`] accepts: vertex indices are
/// `u32` and the count itself must fit in one.
pub const MAX_VERTICES: usize = u32::MAX as usize;

/// The largest triangle count a [`MeshTopology`] accepts: every face
/// contributes three edge incidences, counted in `u32`.
pub const MAX_TRIANGLES: usize = (u32::MAX / 3) as usize;

/// Why a [`MeshTopology`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum TopologyError {
    /// More than [`MAX_VERTICES`] vertices.
    TooManyVertices {
        /// The vertex count given.
        vertex_count: usize,
    },
    /// More than [`MAX_TRIANGLES`] triangles.
    TooManyTriangles {
        /// The triangle count given.
        triangle_count: usize,
    },
    /// A vertex index `≥ vertex_count`.
    IndexOutOfRange {
        /// The triangle holding it.
        triangle: usize,
        /// Its corner (0, 1 or 2).
        corner: usize,
        /// The index.
        index: u32,
        /// The vertex count given.
        vertex_count: usize,
    },
}

impl_error!(TopologyError, |error, f| match *error {
    TopologyError::TooManyVertices { vertex_count } => {
        write!(
            f,
            "{vertex_count} vertices: at most {MAX_VERTICES} are supported"
        )
    }
    TopologyError::TooManyTriangles { triangle_count } => {
        write!(
            f,
            "{triangle_count} triangles: at most {MAX_TRIANGLES} are supported"
        )
    }
    TopologyError::IndexOutOfRange {
        triangle,
        corner,
        index,
        vertex_count,
    } => write!(
        f,
        "triangle {triangle}, corner {corner}: vertex index {index} out of range \
         (vertex count {vertex_count})"
    ),
});

/// Why a silhouette query could not be answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SilhouetteError {
    /// The position slice does not hold exactly one position per vertex.
    PositionCount {
        /// The topology's vertex count.
        expected: usize,
        /// The number of positions given.
        found: usize,
    },
    /// The viewpoint has a NaN or infinite coordinate.
    NonFinitePoint,
    /// The sphere's centre is not finite, or its radius is negative or not
    /// finite.
    InvalidSphere,
    /// An edge index is not below the topology's edge count.
    EdgeIndex {
        /// The index given.
        edge: u32,
        /// The topology's edge count.
        edges: usize,
    },
}

impl_error!(SilhouetteError, |error, f| match *error {
    SilhouetteError::PositionCount { expected, found } => {
        write!(f, "{found} positions given for {expected} vertices")
    }
    SilhouetteError::NonFinitePoint => write!(f, "the viewpoint is not finite"),
    SilhouetteError::InvalidSphere => {
        write!(
            f,
            "the sphere needs a finite centre and a finite radius ≥ 0"
        )
    }
    SilhouetteError::EdgeIndex { edge, edges } => {
        write!(f, "edge {edge} given for a topology of {edges} edges")
    }
});

/// How many faces an edge has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EdgeKind {
    /// One face: the edge lies on the boundary of an open surface.
    Boundary,
    /// Two faces.
    Manifold,
    /// Three or more faces.
    NonManifold,
}

/// One face incident to an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeFace {
    /// The face (triangle) index.
    pub face: u32,
    /// `true` when the face traverses the edge from its second vertex to its
    /// first (the edge is stored as `[v0, v1]` with `v0 < v1`).
    pub reversed: bool,
}

/// A silhouette edge seen from a point, oriented (see the [module
/// docs](self)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SilhouetteEdge {
    /// The edge index in [`MeshTopology::edges`].
    pub edge: u32,
    /// The first vertex of the oriented edge.
    pub from: u32,
    /// The second vertex: the faces that are front-facing (or, in general,
    /// the majority of the incident faces) lie on the left of `from → to` as
    /// seen from the viewpoint.
    pub to: u32,
    /// `|m(e)| ≥ 1`: faces on the left minus faces on the right; 2 for a
    /// manifold contour edge, 1 for a boundary edge.
    pub multiplicity: u32,
}

/// The edge and face adjacency of an indexed triangle mesh (see the [module
/// docs](self)).
///
/// Edges are numbered in lexicographic order of their sorted vertex pair
/// `[v0, v1]`, `v0 < v1`; the faces of an edge are listed in increasing face
/// index. Both orders depend on the triangle list alone, so the topology is
/// deterministic.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshTopology {
    vertex_count: u32,
    triangles: Vec<[u32; 3]>,
    edges: Vec<[u32; 2]>,
    /// `incidences[offsets[e]..offsets[e + 1]]` are the faces of edge `e`.
    offsets: Vec<u32>,
    /// `face << 1 | reversed`: `face < 2³¹` because of [`MAX_TRIANGLES`].
    incidences: Vec<u32>,
    repeated_index_faces: Vec<u32>,
}

impl MeshTopology {
    /// Builds the topology of `triangles` over `vertex_count` vertices.
    ///
    /// Faces with a repeated vertex index (`[a, a, b]`) are recorded in
    /// [`repeated_index_faces`](Self::repeated_index_faces) and contribute no
    /// edges (their boundary chain is zero: they neither occlude nor bound
    /// anything). Unreferenced vertices are allowed.
    ///
    /// Cost: `O(F log F)` time (one sort of the `3F` edge incidences) and
    /// `O(F)` memory, independent of `vertex_count`.
    ///
    /// # Errors
    ///
    /// [`TopologyError::TooManyVertices`], [`TopologyError::TooManyTriangles`]
    /// (see [`MAX_VERTICES`], [`MAX_TRIANGLES`]), or
    /// [`TopologyError::IndexOutOfRange`] for the first out-of-range index.
    pub fn new(triangles: &[[u32; 3]], vertex_count: usize) -> Result<MeshTopology, TopologyError> {
        if vertex_count > MAX_VERTICES {
            return Err(TopologyError::TooManyVertices { vertex_count });
        }
        if triangles.len() > MAX_TRIANGLES {
            return Err(TopologyError::TooManyTriangles {
                triangle_count: triangles.len(),
            });
        }
        for (triangle, t) in triangles.iter().enumerate() {
            for (corner, &index) in t.iter().enumerate() {
                if index as usize >= vertex_count {
                    return Err(TopologyError::IndexOutOfRange {
                        triangle,
                        corner,
                        index,
                        vertex_count,
                    });
                }
            }
        }

        let mut repeated_index_faces = Vec::new();
        // (edge key, incidence): the key orders edges, the incidence (which
        // holds the face index) orders the faces of one edge.
        let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(3 * triangles.len());
        for (face, t) in triangles.iter().enumerate() {
            if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                repeated_index_faces.push(face as u32);
                continue;
            }
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let (lo, hi, reversed) = if a < b { (a, b, 0) } else { (b, a, 1) };
                let key = (u64::from(lo) << 32) | u64::from(hi);
                keyed.push((key, ((face as u32) << 1) | reversed));
            }
        }
        keyed.sort_unstable();

        let mut edges = Vec::new();
        let mut offsets = Vec::new();
        let mut incidences = Vec::with_capacity(keyed.len());
        let mut previous = None;
        for &(key, incidence) in &keyed {
            if previous != Some(key) {
                previous = Some(key);
                edges.push([(key >> 32) as u32, key as u32]);
                offsets.push(incidences.len() as u32);
            }
            incidences.push(incidence);
        }
        offsets.push(incidences.len() as u32);

        Ok(MeshTopology {
            vertex_count: vertex_count as u32,
            triangles: triangles.to_vec(),
            edges,
            offsets,
            incidences,
            repeated_index_faces,
        })
    }

    /// The vertex count given at construction.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.vertex_count as usize
    }

    /// The triangles given at construction (including those with a repeated
    /// index).
    #[must_use]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The undirected edges `[v0, v1]`, `v0 < v1`, in lexicographic order;
    /// an edge's index in this slice is its edge index.
    #[must_use]
    pub fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// The faces of edge `edge` in increasing face index, with the direction
    /// in which each traverses it; empty when `edge` is out of range.
    #[must_use]
    pub fn edge_faces(&self, edge: usize) -> EdgeFaces<'_> {
        EdgeFaces {
            inner: self.incidence_slice(edge).iter(),
        }
    }

    /// Whether edge `edge` is a boundary, manifold or non-manifold edge;
    /// `None` when `edge` is out of range.
    #[must_use]
    pub fn edge_kind(&self, edge: usize) -> Option<EdgeKind> {
        if edge >= self.edges.len() {
            return None;
        }
        Some(match self.incidence_slice(edge).len() {
            1 => EdgeKind::Boundary,
            2 => EdgeKind::Manifold,
            _ => EdgeKind::NonManifold,
        })
    }

    /// The boundary edges (one face), in edge order.
    pub fn boundary_edges(&self) -> impl Iterator<Item = u32> + '_ {
        self.edges_of_kind(EdgeKind::Boundary)
    }

    /// The non-manifold edges (three or more faces), in edge order.
    pub fn non_manifold_edges(&self) -> impl Iterator<Item = u32> + '_ {
        self.edges_of_kind(EdgeKind::NonManifold)
    }

    /// `true` when every edge has exactly two faces (vacuously for a mesh
    /// without edges). Consistent orientation is not checked; the even-degree
    /// property of silhouettes does not need it.
    #[must_use]
    pub fn is_closed_manifold(&self) -> bool {
        self.offsets.windows(2).all(|w| w[1] - w[0] == 2)
    }

    /// The faces with a repeated vertex index, in increasing order. They have
    /// no edges in this topology.
    #[must_use]
    pub fn repeated_index_faces(&self) -> &[u32] {
        &self.repeated_index_faces
    }

    /// Appends to `out`, in increasing order, the faces that are
    /// geometrically degenerate for `positions`: a repeated vertex index, a
    /// non-finite vertex, or three collinear vertices (coincident ones
    /// included). Collinearity is decided exactly — the cross product
    /// `(b − a) × (c − a)` is zero exactly when `orient2d` is zero on all
    /// three coordinate projections. These are the faces that are edge-on
    /// from every point, so they never count as front-facing.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::PositionCount`] when `positions.len()` is not the
    /// vertex count (nothing is appended).
    pub fn degenerate_faces_into<P>(
        &self,
        positions: &[P],
        out: &mut Vec<u32>,
    ) -> Result<(), SilhouetteError>
    where
        P: Copy + Into<DVec3>,
    {
        self.check_positions(positions)?;
        for (face, t) in self.triangles.iter().enumerate() {
            let [a, b, c] = t.map(|i| positions[i as usize].into());
            let repeated = t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
            let finite = a.is_finite() && b.is_finite() && c.is_finite();
            if repeated || !finite || collinear(a, b, c) {
                out.push(face as u32);
            }
        }
        Ok(())
    }

    /// Appends to `out`, in edge order, the silhouette edges of the mesh seen
    /// from `x`, each oriented (see the [module docs](self) for the exact
    /// definition, orientation and multiplicity). `out` is not cleared, so
    /// one `Vec` can be reused across calls without allocating once it has
    /// grown.
    ///
    /// Exact: every facing decision is one [`orient3d`] call (exact within
    /// its domain — measured: coordinates of magnitude between `1e-90` and
    /// `1e90`, or zero, where its cubic products neither overflow nor
    /// underflow;
    /// `f32` positions are promoted exactly). A face with a non-finite vertex
    /// is edge-on, hence back-facing. Cost: `O(E)`, one `orient3d` per edge
    /// incidence (`3F`).
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::PositionCount`] when `positions.len()` is not the
    /// vertex count, [`SilhouetteError::NonFinitePoint`] when `x` is not
    /// finite; nothing is appended then.
    pub fn silhouettes_from_point_into<P, X>(
        &self,
        positions: &[P],
        x: X,
        out: &mut Vec<SilhouetteEdge>,
    ) -> Result<(), SilhouetteError>
    where
        P: Copy + Into<DVec3>,
        X: Into<DVec3>,
    {
        let x = self.check_viewpoint(positions, x)?;
        out.extend(
            (0..self.edges.len()).filter_map(|edge| self.silhouette_from(edge, positions, x)),
        );
        Ok(())
    }

    /// Edge `edge` of the topology as a silhouette edge from `x`, oriented
    /// and with its multiplicity as in
    /// [`silhouettes_from_point_into`](Self::silhouettes_from_point_into),
    /// or `None` when it is not one (multiplicity 0): the same answer for
    /// one edge, in `O(faces of the edge)` — for a caller that keeps a
    /// superset of the silhouettes (say
    /// [`potential_silhouettes`](Self::potential_silhouettes)) and asks
    /// which of them a given point sees.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::PositionCount`] when `positions.len()` is not the
    /// vertex count, [`SilhouetteError::NonFinitePoint`] when `x` is not
    /// finite, [`SilhouetteError::EdgeIndex`] when `edge` is not below
    /// [`edges`](Self::edges)`().len()`.
    pub fn silhouette_edge_from_point<P, X>(
        &self,
        edge: u32,
        positions: &[P],
        x: X,
    ) -> Result<Option<SilhouetteEdge>, SilhouetteError>
    where
        P: Copy + Into<DVec3>,
        X: Into<DVec3>,
    {
        let x = self.check_viewpoint(positions, x)?;
        if edge as usize >= self.edges.len() {
            return Err(SilhouetteError::EdgeIndex {
                edge,
                edges: self.edges.len(),
            });
        }
        Ok(self.silhouette_from(edge as usize, positions, x))
    }

    /// The positions' count and the viewpoint checked; the viewpoint.
    fn check_viewpoint<P>(
        &self,
        positions: &[P],
        x: impl Into<DVec3>,
    ) -> Result<DVec3, SilhouetteError> {
        self.check_positions(positions)?;
        let x: DVec3 = x.into();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(SilhouetteError::NonFinitePoint)
        }
    }

    /// The silhouette test of one edge from `x` (checked arguments).
    fn silhouette_from<P: Copy + Into<DVec3>>(
        &self,
        edge: usize,
        positions: &[P],
        x: DVec3,
    ) -> Option<SilhouetteEdge> {
        let [v0, v1] = self.edges[edge];
        let m = self
            .multiplicity(edge, positions, |[a, b, c]| {
                Some(if orient3d(a, b, c, x) == Sign::Negative {
                    1
                } else {
                    -1
                })
            })
            .unwrap_or(0);
        if m == 0 {
            return None;
        }
        let (from, to) = if m > 0 { (v0, v1) } else { (v1, v0) };
        Some(SilhouetteEdge {
            edge: edge as u32,
            from,
            to,
            multiplicity: m.unsigned_abs() as u32,
        })
    }

    /// [`silhouettes_from_point_into`](Self::silhouettes_from_point_into)
    /// into a new `Vec`.
    ///
    /// # Errors
    ///
    /// As [`silhouettes_from_point_into`](Self::silhouettes_from_point_into).
    pub fn silhouettes_from_point<P, X>(
        &self,
        positions: &[P],
        x: X,
    ) -> Result<Vec<SilhouetteEdge>, SilhouetteError>
    where
        P: Copy + Into<DVec3>,
        X: Into<DVec3>,
    {
        let mut out = Vec::new();
        self.silhouettes_from_point_into(positions, x, &mut out)?;
        Ok(out)
    }

    /// The edge's multiplicity `m(e) = Σ w(f) · dir(f, e)` (module docs)
    /// for the face weights `weight` gives (`±1`); `None` as soon as a face
    /// has no certain weight.
    fn multiplicity<P: Copy + Into<DVec3>>(
        &self,
        edge: usize,
        positions: &[P],
        mut weight: impl FnMut([DVec3; 3]) -> Option<i64>,
    ) -> Option<i64> {
        let mut m = 0;
        for &incidence in self.incidence_slice(edge) {
            let t = self.triangles[(incidence >> 1) as usize];
            let w = weight(t.map(|i| positions[i as usize].into()))?;
            m += if incidence & 1 == 0 { w } else { -w };
        }
        Some(m)
    }

    fn incidence_slice(&self, edge: usize) -> &[u32] {
        match (self.offsets.get(edge), self.offsets.get(edge + 1)) {
            (Some(&lo), Some(&hi)) => &self.incidences[lo as usize..hi as usize],
            _ => &[],
        }
    }

    fn edges_of_kind(&self, kind: EdgeKind) -> impl Iterator<Item = u32> + '_ {
        (0..self.edges.len())
            .filter(move |&e| self.edge_kind(e) == Some(kind))
            .map(|e| e as u32)
    }

    fn check_positions<P>(&self, positions: &[P]) -> Result<(), SilhouetteError> {
        if positions.len() == self.vertex_count as usize {
            Ok(())
        } else {
            Err(SilhouetteError::PositionCount {
                expected: self.vertex_count as usize,
                found: positions.len(),
            })
        }
    }
}

/// Iterator over the faces of one edge ([`MeshTopology::edge_faces`]).
#[derive(Clone, Debug)]
pub struct EdgeFaces<'a> {
    inner: core::slice::Iter<'a, u32>,
}

impl Iterator for EdgeFaces<'_> {
    type Item = EdgeFace;

    fn next(&mut self) -> Option<EdgeFace> {
        self.inner.next().map(|&i| EdgeFace {
            face: i >> 1,
            reversed: i & 1 == 1,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.inner.size_hint()
    }
}

impl ExactSizeIterator for EdgeFaces<'_> {}

/// Exact collinearity of three points in 3D (coincident points included).
fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let xy = |p: DVec3| DVec2::new(p.x, p.y);
    let yz = |p: DVec3| DVec2::new(p.y, p.z);
    let zx = |p: DVec3| DVec2::new(p.z, p.x);
    orient2d(xy(a), xy(b), xy(c)) == Sign::Zero
        && orient2d(yz(a), yz(b), yz(c)) == Sign::Zero
        && orient2d(zx(a), zx(b), zx(c)) == Sign::Zero
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron with outward (counter-clockwise from outside) faces.
    fn tetrahedron() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let p = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        let t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        (p, t)
    }

    #[test]
    fn tetrahedron_topology() {
        let (_, t) = tetrahedron();
        let topo = MeshTopology::new(&t, 4).unwrap();
        assert_eq!(topo.edges().len(), 6);
        assert!(topo.is_closed_manifold());
        assert_eq!(topo.edges()[0], [0, 1]);
        let faces: Vec<EdgeFace> = topo.edge_faces(0).collect();
        // Face 0 = [0, 2, 1] traverses 1 → 0, face 1 = [0, 1, 3] traverses 0 → 1.
        assert_eq!(
            faces,
            vec![
                EdgeFace {
                    face: 0,
                    reversed: true
                },
                EdgeFace {
                    face: 1,
                    reversed: false
                }
            ]
        );
        assert_eq!(topo.edge_faces(99).count(), 0);
        assert_eq!(topo.edge_kind(99), None);
    }

    #[test]
    fn tetrahedron_from_below_sees_the_bottom_triangle_outline() {
        let (p, t) = tetrahedron();
        let topo = MeshTopology::new(&t, 4).unwrap();
        // From far below only face 0 (z = 0, normal −z) is front-facing: its
        // three edges are the silhouette, oriented as face 0 traverses them.
        let s = topo
            .silhouettes_from_point(&p, DVec3::new(0.2, 0.2, -5.0))
            .unwrap();
        let mut directed: Vec<(u32, u32)> = s.iter().map(|e| (e.from, e.to)).collect();
        directed.sort_unstable();
        assert_eq!(directed, vec![(0, 2), (1, 0), (2, 1)]);
        assert!(s.iter().all(|e| e.multiplicity == 2));
    }

    #[test]
    fn errors_are_typed() {
        assert_eq!(
            MeshTopology::new(&[[0, 1, 5]], 3),
            Err(TopologyError::IndexOutOfRange {
                triangle: 0,
                corner: 2,
                index: 5,
                vertex_count: 3
            })
        );
        assert_eq!(
            MeshTopology::new(&[], MAX_VERTICES + 1),
            Err(TopologyError::TooManyVertices {
                vertex_count: MAX_VERTICES + 1
            })
        );
        let (p, t) = tetrahedron();
        let topo = MeshTopology::new(&t, 4).unwrap();
        assert_eq!(
            topo.silhouettes_from_point(&p[..3], DVec3::ZERO),
            Err(SilhouetteError::PositionCount {
                expected: 4,
                found: 3
            })
        );
        assert_eq!(
            topo.silhouettes_from_point(&p, DVec3::new(f64::NAN, 0.0, 0.0)),
            Err(SilhouetteError::NonFinitePoint)
        );
        assert_eq!(
            topo.potential_silhouettes(&p, DVec3::ZERO, -1.0),
            Err(SilhouetteError::InvalidSphere)
        );
    }

    #[test]
    fn collinear_is_exact() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(0.4, 0.5, 0.6);
        assert!(collinear(a, b, a));
        assert!(collinear(a, b, b));
        let c = DVec3::new(0.7, 0.8, 0.9);
        // 0.1, 0.4, 0.7 are not equally spaced in binary: decided exactly.
        assert_eq!(
            collinear(a, b, c),
            orient2d(
                DVec2::new(a.x, a.y),
                DVec2::new(b.x, b.y),
                DVec2::new(c.x, c.y)
            ) == Sign::Zero
                && orient2d(
                    DVec2::new(a.y, a.z),
                    DVec2::new(b.y, b.z),
                    DVec2::new(c.y, c.z)
                ) == Sign::Zero
                && orient2d(
                    DVec2::new(a.z, a.x),
                    DVec2::new(b.z, b.x),
                    DVec2::new(c.z, c.x)
                ) == Sign::Zero
        );
        assert!(collinear(DVec3::ZERO, DVec3::ONE, 3.0 * DVec3::ONE));
    }
}
