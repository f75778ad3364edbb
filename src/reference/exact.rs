//! The exact visibility reference (DESIGN.md §2 "receiver view", §4).
//!
//! For a receiver `p` and the measure `M` a light presents to it
//! ([`Light::emitter`]):
//!
//! - **Disk, sphere (facing disk), rect.** A light point `x` is hidden by
//!   a triangle exactly when the direction `x − p` lies in the cone the
//!   triangle spans from `p` and `x` lies strictly beyond the triangle's
//!   plane. Each of those four half-spaces meets the light's plane in a
//!   half-plane, so a triangle's *image* on the light's plane is a square
//!   around the light cut by four half-planes: only what lies between `p`
//!   and the light occludes (projecting unclipped triangles is the classic
//!   bug), and no point near `p` or behind it is ever constructed. A
//!   triangle wholly between `p` and a disk light whose corners project
//!   inside the square takes a fast path: its projected corners, the same
//!   bits in every triangle sharing them. Images are split into triangles,
//!   each oriented counter-clockwise by the exact [`orient2d`]. Then
//!   `V = 1 − area(∪ images ∩ M) / area(M)`, where the area of the union is
//!   Green's theorem over the union's boundary: every edge of every image
//!   triangle is cut at the parameters where it enters and leaves each
//!   other one, and the pieces inside no other are summed with
//!   [`segment_disk_area`] (the disk) or `½ a × b` (the rect, in its own
//!   affine coordinates `x = c + s u + t v`, where it is the square
//!   `[−1, 1]²` and area ratios are unchanged; no normal of the rect's
//!   plane is ever computed).
//! - **Segment.** The plane through `p` and the segment cuts each triangle
//!   in a segment; clipped to the triangle `(p, a, b)` and projected from
//!   `p` onto the light it blocks one interval of the light's parameter.
//!   `V = 1 −` the length of the union of the blocked intervals.
//! - **Point.** One exact segment test.
//!
//! ## Why this construction and not a constrained Delaunay arrangement
//!
//! DESIGN §9 allows a direct boundary-edge construction in place of
//! `spade`'s arrangement. It is chosen because every topological decision
//! in it is an exact predicate — which side of a triangle's plane `p` lies
//! on, which side of an edge's line an endpoint lies on, whether two edges
//! are collinear — and no decision is taken on a rounded intersection
//! point. Where two edges cross, the cut parameters come from
//! [`orient2d_value`] (exact sign, relative error below `2⁻⁴⁰`), so the
//! two edges are cut at the same point even when nearly parallel; a
//! rounded cut only moves along its edge. The arrangement route would
//! instead insert rounded split points as vertices, which is the failure
//! spade's own documentation warns of.
//!
//! Degenerate input is defined, not avoided:
//!
//! - Edges that coincide exactly (copies of a triangle, fast-path images
//!   sharing corners, the clip square's sides) are detected by the exact
//!   predicate. A piece where two triangles lie on opposite sides is
//!   interior to the union and dropped from both; a piece where they lie on
//!   the same side is kept once, on the triangle with the lowest index.
//!   Edges that coincide only to rounding are cut consistently and leave
//!   slivers of rounding size.
//! - Triangles whose plane holds `p` (seen edge-on from a receiver lying on
//!   them), or that lie in the light's own plane, hide nothing, exactly as
//!   the open segment `(p, x)` of §1 meets them in at most a null set of
//!   light points.
//! - Touching at a point, and edges through a vertex, change no area.
//!
//! ## Accuracy
//!
//! The answer is exact up to the rounding of the half-planes, the crossing
//! parameters and the documented accuracy of [`segment_disk_area`]: about
//! `1e-15` absolute in `V` on ordinary scenes (so a fully covered light may
//! give `1e-16` rather than `0`), held within `1e-9` of closed forms by
//! the tests (`docs/accuracy/references.md`). Seen at a grazing elevation
//! `θ` (the light nearly in the occluder's plane as seen from `p`) the
//! error grows about as `ε/θ`: `4·10⁻¹⁰` at `θ = 10⁻⁶`
//! (`softshadow stability`, `docs/stability.md`).
//!
//! **Domain**: the predicates are exact for coordinates within `±1e30`
//! (every orientation determinant, a product of three coordinate
//! differences, stays within [`orient3d`]'s exact domain), and the
//! constructed points — crossings of edges with planes — are accurate when
//! the triangles' corners lie within about `10⁶` times the light's distance
//! from `p`. A corner `10²⁰` away whose long edge crosses the light's view
//! near the scene is located to only about `10⁻¹⁶ · 10²⁰` (found by the
//! `exact` fuzz target: a segment light answered 0.30 where Monte Carlo
//! says 0.73). Beyond the domain the answer is still in `[0, 1]` and never
//! NaN. Split or clip such triangles before asking.
//!
//! ## Cost
//!
//! The triangles are culled with the BVH to those whose bounds meet the
//! pyramid from `p` over the light's square; the union tests each image
//! edge against the images sharing a cell of a uniform grid with it, and
//! stops at the first that covers it whole (see `benches/README.md` for
//! measured costs against the number of occluders).
//!
//! [`orient2d`]: crate::kernel::predicate::orient2d
//! [`orient2d_value`]: crate::kernel::predicate::orient2d_value
//! [`orient3d`]: crate::kernel::predicate::orient3d
//! [`segment_disk_area`]: crate::kernel::disk::f64::segment_disk_area

mod segment;
mod union;
mod view;

use crate::bvh::Bvh;
use crate::scene::{Emitter, Light, ReceiverError};
use glam::DVec3;
use segment::segment_visibility;
use std::f64::consts::PI;
use union::{Measure, Tri, UnionScratch};
use view::View;

/// Reusable buffers for [`visibility_with`]: one per thread avoids all
/// allocation after the first few receivers.
#[derive(Debug, Default)]
pub struct Scratch {
    candidates: Vec<u32>,
    triangles: Vec<Tri>,
    intervals: Vec<(f64, f64)>,
    union: UnionScratch,
}

/// The exact `V(p)` for the scene `bvh` was built over.
///
/// # Errors
/// [`ReceiverError`] as [`Light::emitter`]: a non-finite receiver, one
/// inside a sphere light, in a disk or rect light's plane, or on the light.
pub fn visibility(bvh: &Bvh, light: &Light, p: DVec3) -> Result<f64, ReceiverError> {
    visibility_with(bvh, light, p, &mut Scratch::default())
}

/// [`visibility`] for every point, in parallel over the points (rayon's
/// global pool), one [`Scratch`] per worker. The result is independent of
/// the number of threads.
#[must_use]
pub fn visibility_many(
    bvh: &Bvh,
    light: &Light,
    points: &[DVec3],
) -> Vec<Result<f64, ReceiverError>> {
    use rayon::prelude::*;
    points
        .par_iter()
        .map_init(Scratch::default, |scratch, &p| {
            visibility_with(bvh, light, p, scratch)
        })
        .collect()
}

/// [`visibility`] with caller-provided buffers.
///
/// # Errors
/// As [`visibility`].
pub fn visibility_with(
    bvh: &Bvh,
    light: &Light,
    p: DVec3,
    scratch: &mut Scratch,
) -> Result<f64, ReceiverError> {
    Ok(emitter_visibility(bvh, &light.emitter(p)?, p, scratch))
}

/// [`visibility_with`] for a receiver whose view of the light is already
/// known: `emitter` must be `light.emitter(p)` for the scene's light (the
/// renderer's methods get it once per receiver from
/// [`method::run`](crate::method::run)).
#[must_use]
pub fn emitter_visibility(bvh: &Bvh, emitter: &Emitter, p: DVec3, scratch: &mut Scratch) -> f64 {
    let v = match *emitter {
        Emitter::Point(x) => {
            if bvh.segment_unoccluded(p, x.position()) {
                1.0
            } else {
                0.0
            }
        }
        Emitter::Segment(s) => segment_visibility(bvh, p, s.a(), s.b(), scratch),
        Emitter::Disk(d) => {
            let (center, radius) = (d.center(), d.radius());
            let (t, b) = d.normal().any_orthonormal_pair();
            // Orthonormal coordinates about the centre; a square around the
            // disk, with margin, so that clipping happens well outside it.
            let view = View::orthonormal(p, center, [t, b], 1.5 * radius);
            let covered = view.covered_area(bvh, scratch, Measure::Disk(radius));
            1.0 - covered / (PI * radius * radius)
        }
        Emitter::Rect(r) => {
            // The rect's own affine coordinates: x = c + s u + t v, the
            // light is the square [−1, 1]², and area ratios are kept.
            let view = View::new(p, r.center(), [r.u(), r.v()], 1.0);
            let covered = view.covered_area(bvh, scratch, Measure::Square);
            1.0 - covered / 4.0
        }
    };
    v.clamp(0.0, 1.0)
}
