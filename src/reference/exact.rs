//! The exact visibility reference ([receiver view](crate::definitions#receiver-view)).
//!
//! For a receiver `p`, the measure `M` the light presents to it
//! ([`Light::emitter`]) and every triangle of the scene whose bounds meet
//! the pyramid from `p` over the light: `V = 1 −` the fraction of `M` the
//! triangles hide, by the [receiver view](crate::kernel::receiver_view)
//! kernel — images on the light's plane clipped to the slab between `p`
//! and the light, their exact union by Green's theorem with exact
//! predicates; for a segment, the union of blocked intervals; for a point,
//! one exact segment test (an occlusion ray through the BVH). The kernel's
//! documentation gives the construction and its degenerate cases;
//! [`Light::visibility_among`] is the same answer for a list of triangles
//! without a BVH.
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
//! [`orient3d`]: crate::kernel::predicate::orient3d
//! [`segment_disk_area`]: crate::kernel::disk::f64::segment_disk_area

use crate::bvh::Bvh;
use crate::kernel::receiver_view::{self, AreaView, SegmentView};
use crate::scene::{Emitter, Light, ReceiverError};
use glam::DVec3;

/// Reusable buffers for [`visibility_with`]: one per thread avoids all
/// allocation after the first few receivers.
#[derive(Debug, Default)]
pub struct Scratch {
    candidates: Vec<u32>,
    view: receiver_view::Scratch,
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
/// `method::run`).
#[must_use]
pub fn emitter_visibility(bvh: &Bvh, emitter: &Emitter, p: DVec3, scratch: &mut Scratch) -> f64 {
    let Scratch { candidates, view } = scratch;
    // The views refuse only receivers `Light::emitter` refuses (in the
    // light's plane, on the light): then nothing is hidden.
    let hidden = match *emitter {
        Emitter::Point(x) => {
            if bvh.segment_unoccluded(p, x.position()) {
                0.0
            } else {
                1.0
            }
        }
        Emitter::Segment(s) => SegmentView::new(p, s.a(), s.b()).map_or(0.0, |v| {
            v.occluded_fraction(culled(bvh, &v.hull(), candidates), view)
        }),
        Emitter::Disk(d) => AreaView::disk(p, d.center(), d.normal(), d.radius())
            .map_or(0.0, |v| {
                v.occluded_fraction(culled(bvh, &v.hull(), candidates), view)
            }),
        Emitter::Rect(r) => AreaView::rect(p, r.center(), r.u(), r.v()).map_or(0.0, |v| {
            v.occluded_fraction(culled(bvh, &v.hull(), candidates), view)
        }),
    };
    (1.0 - hidden).clamp(0.0, 1.0)
}

/// The triangles whose bounds meet the hull of `points`.
fn culled<'t>(
    bvh: &'t Bvh,
    points: &[DVec3],
    candidates: &'t mut Vec<u32>,
) -> impl Iterator<Item = &'t [DVec3; 3]> + 't {
    bvh.triangles_meeting_hull(points, candidates);
    let triangles = bvh.occluders().triangles();
    candidates
        .iter()
        .filter_map(move |&i| triangles.get(i as usize))
}
