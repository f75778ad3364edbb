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
//! Every combinatorial decision is an exact predicate: which side of each
//! triangle's plane the receiver lies on (however close: a receiver on a
//! triangle is hidden nothing by it, one a hair behind it everything it
//! covers; [definitions](crate::definitions#receivers-on-an-occluder)),
//! which side of each image edge the light's points lie on. The images are
//! built from determinants of the inputs taken relative to the receiver,
//! each evaluated exactly where its rounding could move an image edge or
//! corner by more than `2⁻⁴³` of the light's radius (segment lights: an
//! interval's end by `2⁻⁵⁰` of the light), so a receiver `10⁻¹⁷` from an
//! edge, a light `10⁻¹⁶` long or a corner `10²⁰` away costs no accuracy.
//! What is left is rounding: a few units in the last place of `V` (so a
//! fully covered light may give `1e-16` rather than `0`), the same far
//! from the origin as at it, held to a 256-bit evaluation on stiff
//! families by the tests (`tests/certified.rs`, `tests/contact.rs`;
//! `docs/accuracy/references.md`). An edge whose rounding comes near
//! that `2⁻⁴³` without passing it moves `V` by up to about `10⁻¹³`: on
//! the fuzz targets' scenes, where a triangle reaches from behind the
//! receiver to beyond the light at many times the light's size, 5 of
//! 30,000 answers are off by more than `4·10⁻¹⁵`, at most `6·10⁻¹⁴`,
//! each within its certified bound.
//!
//! **Certified bound**: [`visibility_bounded`] (and `visibility_many_bounded`,
//! `emitter_visibility_bounded`) returns `V` with a bound `|V − V_true| ≤
//! bound` guaranteed in the domain below ([`Bounded`]; the analysis is in
//! the [receiver view's documentation](crate::kernel::receiver_view#the-certified-bound)).
//! The value is bit for bit [`visibility`]'s. The bound is typically
//! `10⁻¹⁴`–`10⁻¹²` where some edge crosses the light, `≈ 10⁻¹⁶` where
//! none does, 0 for a point light.
//!
//! **Domain**: the predicates are exact for coordinates `0` or of
//! magnitude within `[1e-90, 1e90]` (every orientation determinant, a
//! product of three coordinate differences, stays within [`orient3d`]'s
//! exact domain), and the bound is certified there. With `T` the largest
//! coordinate magnitude of the receiver and the occluders and `L` the
//! light's (its centre's plus its extent), a receiver where `T²(T + L)`
//! exceeds `f64::MAX / 2¹⁰` (a scene of size `~10¹⁰²`, or `10¹⁵³` around
//! the origin with the light as far) would overflow the determinants: the
//! functions that return a `Result` refuse it
//! ([`ReceiverError::OutOfRange`]), and [`emitter_visibility_bounded`]
//! answers it with `bound = 1` (no information). Between the two (a light
//! `10²⁰⁰` away over ordinary occluders) the answer is computed, in
//! `[0, 1]` and never NaN, but its bound is 1: not certified. At the other
//! end, a scene whose every coordinate (receiver, occluders and light,
//! `max(T, L)`) is below `10⁻⁹⁰` — a whole scene `10⁻¹¹⁰` across — lies
//! wholly below the predicates' exact range (its determinants, products
//! of three differences, underflow): refused likewise, and answered with
//! `bound = 1` by [`emitter_visibility_bounded`]. (A tiny scene is the
//! same scene scaled by a power of two: scale it up to answer it.)
//!
//! ## Cost
//!
//! The triangles are culled with the BVH to those whose bounds meet the
//! pyramid from `p` over the light's square; the union tests each image
//! edge against the images that may cover it, and stops once they cover
//! it whole (see `benches/README.md` for measured costs against the
//! number of occluders). Which images an edge meets is decided per
//! answer ([`UnionSearch::Auto`](receiver_view::UnionSearch::Auto), the
//! default): a uniform grid of the images' bounds, where an edge is
//! tested against the images sharing a cell with it, unless at least
//! [`TREE_FROM`](receiver_view::UnionSearch::TREE_FROM) (8192) image
//! triangles are too large for the grid's fine cells — layers stacked
//! many deep, or a polygon given as a fan of long slivers — where the
//! grid tests an edge against every large image its coarse cells hold.
//! There a tree of bounding boxes that leaves out the subtrees whose
//! boxes miss the edge or whose part of it is covered already is used:
//! on the layers stacked and the sliver fans in `benches/README.md` it
//! costs at most 1.8 times the grid where the grid does well, while the
//! grid costs up to 10 times the tree on stacks beyond about 10⁴ images
//! and 11 times on a fan of 10⁵ slivers covering part of the light. The
//! statistic is one pass over the images' bounds before either search
//! is built, no predicate; a pile of small images never reaches it.
//! Every choice gives the same value bit for bit and its own search's
//! certified bound.
//!
//! [`orient3d`]: crate::kernel::predicate::orient3d

use crate::bvh::Bvh;
use crate::kernel::light::{Emitter, ReceiverError};
use crate::kernel::receiver_view::{self, Fraction, Occluders, Pieces, SegmentView};
use crate::scene::Light;
use glam::DVec3;

/// Reusable buffers for [`visibility_with`]: one per thread avoids all
/// allocation after the first few receivers.
#[derive(Debug, Default)]
pub struct Scratch {
    candidates: Vec<u32>,
    view: receiver_view::Scratch,
}

impl Scratch {
    /// Chooses the union's search ([`UnionSearch`](receiver_view::UnionSearch)):
    /// by default `Auto`, decided per answer (module documentation, Cost);
    /// every choice gives the same value bit for bit, each with its own
    /// search's certified bound.
    pub fn set_union_search(&mut self, search: receiver_view::UnionSearch) {
        self.view.set_union_search(search);
    }
}

/// An exact answer with its certified bound: `|visibility − V(p)| ≤ bound`
/// for inputs in the documented domain (module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Bounded {
    /// `V(p)`, in `[0, 1]`.
    pub visibility: f64,
    /// The bound, `≥ 0` (0 for a point light, whose answer is exact).
    pub bound: f64,
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
    many(points, |p, scratch| visibility_with(bvh, light, p, scratch))
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
    in_range(bvh, light, p, |e| emitter_visibility(bvh, e, p, scratch))
}

/// `answer` of the emitter `light` presents to `p`; an error where it
/// presents none ([`Light::emitter`]) or where the determinants could
/// overflow ([`ReceiverError::OutOfRange`]).
fn in_range<T>(
    bvh: &Bvh,
    light: &Light,
    p: DVec3,
    answer: impl FnOnce(&Emitter) -> T,
) -> Result<T, ReceiverError> {
    let emitter = light.emitter(p)?;
    if domain(bvh, &emitter, p).refused() {
        return Err(ReceiverError::OutOfRange);
    }
    Ok(answer(&emitter))
}

/// Where a receiver lies against the exact reference's domain (module
/// documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Domain {
    /// Every coordinate within `10⁹⁰`: the bound is certified.
    Inside,
    /// No determinant overflows, but some coordinate is beyond `10⁹⁰`.
    Uncertified,
    /// `T²(T + L) > f64::MAX / 2¹⁰` (or not finite): the determinants
    /// (each below `24 T²(T + L)` in magnitude, its running bounds a few
    /// times more) could overflow.
    Overflow,
    /// `max(T, L) < 10⁻⁹⁰`: every coordinate below the predicates' exact
    /// range, the determinants underflowing.
    Underflow,
}

impl Domain {
    /// Whether the receiver is refused ([`ReceiverError::OutOfRange`]).
    pub(crate) fn refused(self) -> bool {
        matches!(self, Domain::Overflow | Domain::Underflow)
    }
}

/// The largest magnitude the predicates are exact for.
const DOMAIN: f64 = 1e90;

/// The smallest non-zero magnitude they are exact for.
const DOMAIN_LOW: f64 = 1e-90;

/// `(T, L)`: the largest coordinate magnitude of the receiver and the
/// occluders, and of the emitter's points (centre plus extent, per
/// coordinate).
pub(crate) fn magnitudes(bvh: &Bvh, emitter: &Emitter, p: DVec3) -> (f64, f64) {
    let l = emitter.magnitude();
    (bvh.max_coordinate().max(p.abs().max_element()), l)
}

/// Where `p` lies against the domain, for the scene of `bvh` and the
/// light's `emitter`.
pub(crate) fn domain(bvh: &Bvh, emitter: &Emitter, p: DVec3) -> Domain {
    let (t, l) = magnitudes(bvh, emitter, p);
    let weight = t * t * (t + l);
    if weight.is_nan() || weight > f64::MAX / 1024.0 {
        Domain::Overflow
    } else if t.max(l) < DOMAIN_LOW {
        Domain::Underflow
    } else if t.max(l) > DOMAIN {
        Domain::Uncertified
    } else {
        Domain::Inside
    }
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
    let hidden = receiver_view::occluded::<false>(emitter, p, Culled { bvh, candidates }, view)
        .map_or(0.0, |f| f.value);
    (1.0 - hidden).clamp(0.0, 1.0)
}

/// [`visibility`] with its certified bound ([`Bounded`]).
///
/// # Errors
/// As [`visibility`].
pub fn visibility_bounded(bvh: &Bvh, light: &Light, p: DVec3) -> Result<Bounded, ReceiverError> {
    visibility_bounded_with(bvh, light, p, &mut Scratch::default())
}

/// [`visibility_bounded`] for every point, in parallel over the points
/// (as [`visibility_many`]).
#[must_use]
pub fn visibility_many_bounded(
    bvh: &Bvh,
    light: &Light,
    points: &[DVec3],
) -> Vec<Result<Bounded, ReceiverError>> {
    many(points, |p, scratch| {
        visibility_bounded_with(bvh, light, p, scratch)
    })
}

/// `one` of every point, in parallel over the points (rayon's global
/// pool), one [`Scratch`] per worker.
fn many<T: Send>(
    points: &[DVec3],
    one: impl Fn(DVec3, &mut Scratch) -> Result<T, ReceiverError> + Sync + Send,
) -> Vec<Result<T, ReceiverError>> {
    use rayon::prelude::*;
    points
        .par_iter()
        .map_init(Scratch::default, |scratch, &p| one(p, scratch))
        .collect()
}

/// [`visibility_bounded`] with caller-provided buffers.
///
/// # Errors
/// As [`visibility`].
pub fn visibility_bounded_with(
    bvh: &Bvh,
    light: &Light,
    p: DVec3,
    scratch: &mut Scratch,
) -> Result<Bounded, ReceiverError> {
    in_range(bvh, light, p, |e| {
        emitter_visibility_bounded(bvh, e, p, scratch)
    })
}

/// [`emitter_visibility`] with its certified bound ([`Bounded`]); outside
/// the domain where the bound is certified (module documentation), the
/// bound is 1.
#[must_use]
pub fn emitter_visibility_bounded(
    bvh: &Bvh,
    emitter: &Emitter,
    p: DVec3,
    scratch: &mut Scratch,
) -> Bounded {
    let Scratch { candidates, view } = scratch;
    let hidden: Fraction =
        receiver_view::occluded::<true>(emitter, p, Culled { bvh, candidates }, view)
            .unwrap_or_default();
    // 1 − hidden rounds once; clamping to [0, 1] only moves toward V.
    Bounded {
        visibility: (1.0 - hidden.value).clamp(0.0, 1.0),
        bound: if domain(bvh, emitter, p) != Domain::Inside {
            1.0
        } else if hidden.bound > 0.0 {
            hidden.bound + f64::EPSILON / 2.0
        } else {
            0.0
        },
    }
}

/// How `p` sees the scene's segment light: its visible pieces
/// ([`Pieces::of`]) on the exact reference's own blocked intervals, over
/// the triangles the BVH culls for [`visibility`] (the culling keeps every
/// triangle that hides anything, so the answer is the one over every
/// triangle); `Ok(None)` for a light of another kind.
///
/// # Errors
/// As [`visibility`].
pub fn pieces(bvh: &Bvh, light: &Light, p: DVec3) -> Result<Option<Pieces>, ReceiverError> {
    pieces_with(bvh, light, p, &mut Scratch::default())
}

/// [`pieces`] for every point, in parallel over the points (as
/// [`visibility_many`]).
#[must_use]
pub fn pieces_many(
    bvh: &Bvh,
    light: &Light,
    points: &[DVec3],
) -> Vec<Result<Option<Pieces>, ReceiverError>> {
    many(points, |p, scratch| pieces_with(bvh, light, p, scratch))
}

/// [`pieces`] with caller-provided buffers.
fn pieces_with(
    bvh: &Bvh,
    light: &Light,
    p: DVec3,
    scratch: &mut Scratch,
) -> Result<Option<Pieces>, ReceiverError> {
    in_range(bvh, light, p, |e| {
        let Emitter::Segment(s) = *e else {
            return None;
        };
        let view = SegmentView::new(p, s.a(), s.b())?;
        let Scratch {
            candidates,
            view: buffers,
        } = scratch;
        let triangles = Culled { bvh, candidates }.near(|| view.hull());
        Some(view.pieces(triangles, buffers))
    })
}

/// The scene's triangles near a view: those whose bounds meet the view's
/// hull, culled by the BVH into `candidates`; a point light's segment
/// traced through the BVH.
struct Culled<'t> {
    bvh: &'t Bvh,
    candidates: &'t mut Vec<u32>,
}

impl<'t> Occluders<'t> for Culled<'t> {
    fn near<const N: usize>(
        self,
        hull: impl FnOnce() -> [DVec3; N],
    ) -> impl Iterator<Item = &'t [DVec3; 3]> {
        let Culled { bvh, candidates } = self;
        bvh.triangles_meeting_hull(&hull(), candidates);
        let triangles = bvh.occluders().triangles();
        candidates
            .iter()
            .filter_map(move |&i| triangles.get(i as usize))
    }

    fn block(self, p: DVec3, x: DVec3) -> bool {
        !self.bvh.segment_unoccluded(p, x)
    }
}
