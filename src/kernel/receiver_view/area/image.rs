//! A triangle's image on the light's plane, a convex polygon with its
//! vertices' error bounds.

use glam::DVec2;

/// A triangle's image before it is handed out: the fast path's corners (in
/// either orientation) or the clipped polygon.
#[allow(clippy::large_enum_variant)] // Returned once per triangle: boxing would allocate.
pub(super) enum Polygon {
    /// The corners' images and their error bounds.
    Corners([DVec2; 3], [f64; 3]),
    Clipped(Image),
}

/// A triangle's image on the light's plane ([`AreaView::image`](super::AreaView::image)): a convex
/// polygon of at most eight vertices (the square around the light cut by
/// four half-planes), counter-clockwise, in the view's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Image {
    pub(super) v: [DVec2; Image::CAP],
    /// A bound on each vertex's distance from the lines of its two edges
    /// as computed (the lines' own errors apart).
    pub(super) err: [f64; Image::CAP],
    /// Per edge (from each vertex to the next), a bound on the area by
    /// which the exact image differs from this one along it
    /// (set with its vertices: [`Image::from_slice`], or the clip).
    pub(super) w: [f64; Image::CAP],
    /// A bound on the area the exact image may hold beyond all edges'
    /// (lines passing within their error of a vertex without cutting).
    pub(super) extra: f64,
    /// A bound on how far the exact image's difference from this one
    /// reaches ([`Image::reach`]).
    pub(super) reach: f64,
    /// A bound on how far any band lies from its edge ([`Image::spread`]).
    pub(super) spread: f64,
    pub(super) len: usize,
}

impl Image {
    pub(super) const CAP: usize = 8;
    pub(super) const EMPTY: Image = Image {
        v: [DVec2::ZERO; Image::CAP],
        err: [0.0; Image::CAP],
        w: [0.0; Image::CAP],
        extra: 0.0,
        reach: 0.0,
        spread: 0.0,
        len: 0,
    };

    /// The vertices, counter-clockwise; none when the image is empty.
    #[must_use]
    pub fn vertices(&self) -> &[DVec2] {
        &self.v[..self.len]
    }

    /// Whether the triangle hides nothing in the square.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len < 3
    }

    /// The polygon's area (shoelace), in the view's coordinates; not cut
    /// to the light.
    #[must_use]
    pub fn area(&self) -> f64 {
        let v = self.vertices();
        let n = v.len();
        0.5 * (0..n).map(|k| v[k].perp_dot(v[(k + 1) % n])).sum::<f64>()
    }

    /// Per edge (from each vertex to the next), a bound on the area by
    /// which the exact image may differ from this one along it.
    pub(super) fn weights(&self) -> &[f64] {
        &self.w[..self.len]
    }

    /// A bound on the exact image's area beyond its edges' allowances.
    pub(super) fn extra(&self) -> f64 {
        self.extra
    }

    /// A bound `R` on how far the two images' difference reaches, in the
    /// view's units (with `B`; else 0): each edge's band lies within `R`
    /// of the edge's line and runs at most `R` past either end, and a
    /// point of the light at least `R` inside every edge's line of one of
    /// this image's triangles lies in the exact image too. Infinite where
    /// no such bound is known.
    pub(in crate::kernel::receiver_view) fn reach(&self) -> f64 {
        self.reach
    }

    /// A bound on the distance from an edge to any point of its band (with
    /// `B`; else 0): `hypot` of the band's half-width and its run past the
    /// nearer end, the largest over the edges. Infinite where unknown.
    pub(in crate::kernel::receiver_view) fn spread(&self) -> f64 {
        self.spread
    }

    /// The triangle of the corners' images `v`, each within its `err` of
    /// the exact one. The exact triangle's boundary then lies within the
    /// largest error of this one's, point for point (each point of an edge
    /// the same combination of its ends), so their difference lies within
    /// that error of this one's edges: the reach is the largest error
    /// (see [`Image::reach`]; a point farther inside than that keeps its
    /// winding number under the straight-line deformation of one boundary
    /// into the other).
    #[inline(always)]
    pub(super) fn from_slice<const B: bool>(v: &[DVec2], err: &[f64]) -> Image {
        let mut image = Image::EMPTY;
        let n = v.len();
        image.v[..n].copy_from_slice(v);
        image.err[..n].copy_from_slice(err);
        if B {
            for k in 0..n {
                let j = (k + 1) % n;
                image.w[k] = corner_edge_weight(v[k], v[j], err[k], err[j]);
            }
            let most = err.iter().fold(0.0_f64, |m, &e| m.max(e));
            image.reach = if most.is_finite() {
                most * (1.0 + 4.0 * f64::EPSILON)
            } else {
                f64::INFINITY
            };
            image.spread = image.reach * std::f64::consts::SQRT_2;
        }
        image.len = n;
        image
    }
}

/// The area allowance of an edge between two corners' images, each within
/// its error of the exact one: the exact edge lies within the larger error
/// of this one, so the two images differ along it by at most a band of
/// twice that width.
pub(super) fn corner_edge_weight(a: DVec2, b: DVec2, ea: f64, eb: f64) -> f64 {
    2.0 * ea.max(eb) * (b - a).length() * (1.0 + 4.0 * f64::EPSILON)
}
