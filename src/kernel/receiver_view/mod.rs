//! The [receiver view](crate::definitions#receiver-view): occluding
//! triangles seen from one receiver `p`, mapped onto the plane of the
//! light's measure and clipped to the slab between `p` and the light, and
//! the exact fraction of the light they hide. This is the construction of
//! the exact reference (`reference::exact` is this kernel over a BVH's
//! culling), public so that the exact visibility of a few triangles needs
//! the kernels alone:
//!
//! ```
//! use softshadow::glam::DVec3;
//! use softshadow::kernel::receiver_view::{AreaView, Scratch};
//!
//! // A disk light of radius 1 at height 4; a receiver at the origin; a
//! // plate at height 2 over the half x ≥ 0, which hides half the light.
//! let view = AreaView::disk(DVec3::ZERO, DVec3::new(0.0, 0.0, 4.0), DVec3::Z, 1.0).unwrap();
//! let plate = [
//!     [DVec3::new(0.0, -9.0, 2.0), DVec3::new(9.0, -9.0, 2.0), DVec3::new(9.0, 9.0, 2.0)],
//!     [DVec3::new(0.0, -9.0, 2.0), DVec3::new(9.0, 9.0, 2.0), DVec3::new(0.0, 9.0, 2.0)],
//! ];
//! let hidden = view.occluded_fraction(&plate, &mut Scratch::default());
//! assert!((hidden - 0.5).abs() < 1e-15);
//! ```
//!
//! For a whole [`Emitter`] (a sphere light's facing disk, a disk, a rect, a
//! segment or a point), [`occluded_fraction`] chooses the view; the exact
//! reference makes the same choice over the triangles its BVH culls, and
//! the scene's `Light::visibility_among` is `V(p)` of a light among a list
//! of triangles in one call.
//!
//! ## The construction
//!
//! - **Disk, sphere (facing disk), rect** ([`AreaView`]). A light point
//!   `x` is hidden by a triangle exactly when the direction `x − p` lies in
//!   the cone the triangle spans from `p` and `x` lies strictly beyond the
//!   triangle's plane. Each of those four half-spaces meets the light's
//!   plane in a half-plane, so a triangle's *image* ([`AreaView::image`]) is
//!   a square around the light cut by four half-planes: only what lies
//!   between `p` and the light occludes (projecting unclipped triangles is
//!   the classic bug), and no point near `p` or behind it is ever
//!   constructed — a corner `10⁻¹²` above the receiver is as exact as one
//!   far from it. Every half-plane's coefficients are 3×3 determinants of
//!   the inputs taken relative to the receiver (`det[u − p, v − u, ·]` for
//!   the plane through `p` and the edge `uv`, against the plane's axes and
//!   `center − p`; the triangle's own plane relative to a corner), each
//!   rounded with a bound on its error and computed exactly where that
//!   bound could move the line by more than `2⁻⁴³` of the light's radius —
//!   a receiver within `10⁻¹⁷` of an edge, whose plane through the edge
//!   a rounded cross product would turn at random, or a light of radius
//!   `10⁻⁶`. The disk's plane is spanned exactly (its normal crossed with
//!   two coordinate axes). A triangle wholly between `p` and the light whose
//!   corners project inside the square takes a fast path: its projected
//!   corners (`det[center − p, q − p, ·] / det[q − p, f₀, f₁]`, the same
//!   determinants), the same bits in every triangle sharing them. Every
//!   vertex of a clipped image is likewise computed from the two lines it
//!   lies on alone — a line and a side of the square from the line's
//!   coefficients, two planes through `p` at their common corner's image —
//!   not from the edge being cut, so two triangles sharing an edge and
//!   a corner (a mesh, a fan of slivers) get the same vertices whether
//!   clipped or not (where two lines are so nearly parallel that their
//!   meeting point is ill-conditioned, the crossing on the edge is taken).
//!   Images are
//!   split into triangles, each oriented counter-clockwise by the exact
//!   [`orient2d`]. Then the occluded fraction is
//!   `area(∪ images ∩ M) / area(M)`, where the area of the union is Green's
//!   theorem over the union's boundary: every edge of every image triangle
//!   is cut at the parameters where it enters and leaves each other one,
//!   and the pieces inside no other are summed with [`segment_disk_area`]
//!   (the disk) or `½ a × b` (the rect, in its own affine coordinates
//!   `x = c + s u + t v`, where it is the square `[−1, 1]²` and area ratios
//!   are unchanged; no normal of the rect's plane is ever computed). An
//!   edge that two images share in opposite directions (a mesh edge, the
//!   fast path's corners the same bits in both) lies between them and is
//!   dropped at once: on a mesh's images most edges are.
//! - **Segment** ([`SegmentView`]). The same four conditions, along the
//!   light `x(s) = a + s (b − a)`: each is `(1 − s) F(a) + s F(b)` with
//!   `F(a)`, `F(b)` determinants of the inputs with exact signs, so a
//!   triangle hides one interval of `s` ([`SegmentView::blocked`]), its
//!   ends the quotients `F(a) / (F(a) − F(b))` of values accurate to `2⁻⁵⁰`
//!   of their difference. No point is constructed: a receiver `10⁻¹⁷`
//!   behind a triangle, or a light `10⁻¹⁶` long, costs no accuracy. The
//!   occluded fraction is the length of the union of the blocked
//!   intervals.
//! - **Point.** One exact open-segment test ([`segment_blocked`]).
//!
//! Every topological decision is an exact predicate — which side of a
//! triangle's plane `p` lies on, which side of an edge's line an endpoint
//! lies on, whether two edges are collinear — and no decision is taken on
//! a rounded intersection point. Where two edges cross, the cut parameters
//! come from [`orient2d_value`] (exact sign, relative error below
//! `2⁻⁴⁰`), so the two edges are cut at the same point even when nearly
//! parallel; a rounded cut only moves along its edge. (A constrained
//! Delaunay arrangement of the images would instead insert rounded split
//! points as vertices; that is why this construction is used.)
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
//!   them: on a face, an edge or a vertex), or that lie in the light's own
//!   plane, hide nothing, exactly as the open segment `(p, x)` meets them
//!   in at most a null set of light points
//!   ([definitions](crate::definitions#receivers-on-an-occluder)); which
//!   side of a triangle `p` lies on is decided exactly, however close.
//!   Triangles with a non-finite corner hide nothing.
//! - Touching at a point, and edges through a vertex, change no area.
//!
//! ## The certified bound
//!
//! [`occluded_fraction_bounded`] (and each view's `…_bounded`) returns the
//! fraction with a bound `|value − exact| ≤ bound` ([`Fraction`]),
//! guaranteed for inputs in the domain below. It is a forward error
//! analysis of the construction, summed:
//!
//! - **Every constructed quantity** is a determinant of the inputs
//!   relative to the receiver, rounded with a running bound on its error
//!   (`γ₈` of the magnitudes of its terms: differences, cross product, dot
//!   product; see `bounded.rs`), or exact. A line's bound moves it by at
//!   most `δ` over the square, a projected corner by at most its own bound;
//!   a clipped vertex lies within `ρ` (measured a posteriori) of the lines
//!   it is on.
//! - **Images**: the exact image differs from the computed one by at most
//!   a band along each edge, `2 (δ + ρ)` wide and as long as the edge plus
//!   how far the exact edge may run on past each end (`(δ_in + δ_out +
//!   2ρ) / sin θ` at a corner of angle `θ`, capped at the square's
//!   diagonal); a line that passes within its error of a vertex without
//!   cutting adds a band along the diagonal. Each image also has a
//!   *reach* `R`: every band lies within `R` of its edge's line and runs
//!   at most `R` past its ends, and a point of the light more than `R`
//!   inside every edge line of one of the image's triangles lies in the
//!   exact image too (for the fast path's corners, each within `e` of the
//!   exact one, `R` is the largest `e`; for a clipped image, the largest
//!   band width and run, and for each line cut by, its error `δ` plus how
//!   far any vertex lies on its outer side `τ` — a point farther than `δ +
//!   τ` inside the triangle is farther than `δ` inside that line, so
//!   inside the exact one).
//! - **Bands held by other images.** The two unions differ only where
//!   some band is (every point of one image and not of its exact
//!   counterpart lies in one of its bands), and not where the computed
//!   and the exact union both hold the point: so a stretch of a band that
//!   lies inside both counts for nothing. Where the point `t` of an edge
//!   lies at least `2R` inside every edge line of another triangle `j`
//!   (`R` the largest reach of the images), the band's cross-section
//!   there lies more than `R` inside `j` — in the computed union, and in
//!   `j`'s exact image. The spans the union's search finds give, from the
//!   same signed areas with their bounds, the parameters where each
//!   triangle holds the edge that deep (each edge line's signed distance
//!   is linear along the edge); an edge's allowance is its band's times
//!   the measure of the parameters in `[−R/|e|, 1 + R/|e|]` (the band's
//!   length, past both ends) that none of them holds, at most 1. Most
//!   edges of a pile of images are covered whole with room to spare, and
//!   their bands drop out but for a few `R` where two covering triangles'
//!   edges cross them. The union's area then moves by at most those
//!   allowances: all but shared edges' (an edge and its exact reverse move
//!   together) and those of edges the raster of a deep pile covers with a
//!   margin far above the reach. Images that miss the light or are
//!   degenerate count if they come within their bands' spread of it (the
//!   band's half-width and run past the ends, combined; the disk itself,
//!   not its box); a single image covering the light leaves at most its
//!   bands uncovered.
//! - **The union**: each piece kept on the boundary moves by at most the
//!   error of its cut ends (the cut parameters' bounds, from the signed
//!   areas' own, times the edge's length: the area kernels are 1-Lipschitz
//!   in the pieces' ends, in the light's units), plus `3 ε` a piece for
//!   the area kernel ([`segment_disk_area`]'s tested accuracy; the
//!   square's `½ a × b` alike) and the compensated sum's error.
//! - **The frame**: the disk in the view's coordinates is the unit disk to
//!   the rounding of its map, and a sphere light's facing disk is turned by
//!   the rounding of its normal: `16 ε` of `V`, plus `2 ε` for the division
//!   by the light's area.
//! - **Segment lights**: each blocked interval's ends within their cuts'
//!   bounds (the two determinants' bounds over their difference); the
//!   union's length moves by at most their sum, plus the sum's rounding.
//! - **Point lights**: exact (bound 0).
//!
//! The bound is pessimistic by a factor of about 10–500 against the error
//! it certifies on ordinary scenes (tests/certified.rs measures it against
//! a 256-bit evaluation on stiff families: far offsets, tiny and huge
//! lights, grazing, contact, slivers, near-tangent chords), and it grows
//! where the construction's rounding does. The answer itself does not
//! depend on whether the bound is asked for: every decision (which
//! determinant is taken exactly) is made on the same cheap bounds, and the
//! bound reports the closer ones.
//!
//! **Domain**: coordinates `0` or of magnitude in `[1e-90, 1e90]` (the
//! exact predicates' and expansions' range, which keeps every product
//! clear of underflow; measured with lights from `10⁻⁶` to `10³` times
//! their distance), and no occluder crossing a sphere light's facing
//! disk's plane within the square around the light at a small angle: the
//! facing disk's normal is rounded, its plane turned by a few `ε`, and a
//! triangle crossing it at angle `θ` has its trace moved by about `ε / θ`
//! of the radius, which the bound does not count (corners `10⁻⁶` of the
//! radius off the plane across the light: an error of `4.5·10⁻¹³` against
//! a bound of `3.9·10⁻¹⁴`; the test
//! `a_triangle_crossing_a_sphere_light_s_facing_plane_at_a_small_angle`,
//! ignored while it fails). Disk and rect lights have no such limit.
//! Beyond the domain the answer stays in `[0, 1]` and the bound finite or
//! infinite, never NaN.
//!
//! Accuracy: every combinatorial decision is exact, and the constructions
//! are evaluated exactly wherever their rounding could move an image's
//! line or corner by more than `2⁻⁴³` of the light's radius (a segment
//! light's interval end by more than `2⁻⁵⁰` of its length): within a few
//! units in the last place of `V` on every family of `tests/certified.rs`
//! (docs/accuracy/references.md).
//!
//! [`orient2d`]: crate::kernel::predicate::orient2d
//! [`orient2d_value`]: crate::kernel::predicate::orient2d_value
//! [`segment_disk_area`]: crate::kernel::disk::f64::segment_disk_area
//! [`segment_blocked`]: crate::kernel::segment::segment_blocked
//! [`Emitter`]: crate::kernel::light::Emitter

mod area;
mod bounded;
mod segment;
mod union;

pub use area::{AreaView, Image};
pub use segment::{Pieces, SegmentView};
pub use union::Search as UnionSearch;

use crate::kernel::light::Emitter;
use crate::kernel::segment::segment_blocked;
use glam::DVec3;
use union::{Tri, UnionScratch};

/// Reusable buffers for the occluded fractions: one per thread avoids all
/// allocation after the first few receivers.
#[derive(Debug, Default)]
pub struct Scratch {
    triangles: Vec<Tri>,
    /// Per triangle, its edges' area allowances (for the bound).
    weights: Vec<[f64; 3]>,
    intervals: Vec<(f64, f64)>,
    union: UnionScratch,
}

impl Scratch {
    /// Chooses how the union of the images finds, for each image edge, the
    /// images that may cover it ([`UnionSearch`]; by default
    /// [`UnionSearch::Auto`], decided per answer from the images' sizes).
    /// Every choice gives the same value bit for bit, with its own
    /// search's certified bound; the explicit ones are there so that
    /// benchmarks and tests can compare the two designs.
    pub fn set_union_search(&mut self, search: UnionSearch) {
        self.union.search = search;
    }
}

/// An occluded fraction and a certified bound on its error:
/// `|value − exact| ≤ bound`, for inputs in the documented domain
/// ([module documentation](self#the-certified-bound)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fraction {
    /// The fraction, in `[0, 1]`.
    pub value: f64,
    /// The bound, `≥ 0`.
    pub bound: f64,
}

/// The fraction of `emitter` the triangles hide from `p`, in `[0, 1]`
/// (so `V(p) = 1 −` it): the receiver view the emitter calls for —
/// [`AreaView::disk`] for a disk (a sphere light's facing disk included),
/// [`AreaView::rect`], [`SegmentView`], or the open-segment test for a
/// point.
///
/// `None` when `p` has no view of the emitter: not finite, in the plane of
/// a disk or rect, or on a segment or point light (the shapes' `seen_from`,
/// e.g. [`Disk::seen_from`](crate::kernel::light::Disk::seen_from), refuses
/// each of these with a
/// [`ReceiverError`](crate::kernel::light::ReceiverError)).
#[must_use]
pub fn occluded_fraction<'t>(
    emitter: &Emitter,
    p: DVec3,
    triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
    scratch: &mut Scratch,
) -> Option<f64> {
    occluded::<false>(emitter, p, Listed(triangles), scratch).map(|f| f.value)
}

/// [`occluded_fraction`] with a certified bound on its error
/// ([`Fraction`]; a point light's answer is exact, its bound 0).
#[must_use]
pub fn occluded_fraction_bounded<'t>(
    emitter: &Emitter,
    p: DVec3,
    triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
    scratch: &mut Scratch,
) -> Option<Fraction> {
    occluded::<true>(emitter, p, Listed(triangles), scratch)
}

/// Where the triangles a view is computed over come from: a list, or a
/// culling structure that keeps those near the view.
pub(crate) trait Occluders<'t> {
    /// The triangles that may hide part of the light: at least every one
    /// that meets the convex hull of `hull()`'s points (the view's
    /// [`AreaView::hull`] or [`SegmentView::hull`]).
    fn near<const N: usize>(
        self,
        hull: impl FnOnce() -> [DVec3; N],
    ) -> impl Iterator<Item = &'t [DVec3; 3]>;

    /// Whether some triangle blocks the open segment `(p, x)`, decided
    /// exactly ([`segment_blocked`]).
    fn block(self, p: DVec3, x: DVec3) -> bool;
}

/// Every triangle of a list, none culled.
struct Listed<I>(I);

impl<'t, I: IntoIterator<Item = &'t [DVec3; 3]>> Occluders<'t> for Listed<I> {
    fn near<const N: usize>(
        self,
        _hull: impl FnOnce() -> [DVec3; N],
    ) -> impl Iterator<Item = &'t [DVec3; 3]> {
        self.0.into_iter()
    }

    fn block(self, p: DVec3, x: DVec3) -> bool {
        self.0.into_iter().any(|t| segment_blocked(p, x, t))
    }
}

/// The one dispatcher over the emitter's kinds: the fraction of `emitter`
/// that `occluders` hide from `p` by the view the kind calls for, with its
/// bound if `B` (without, the bound is only what comes free: a segment's,
/// else 0); `None` when `p` has no view of the emitter
/// ([`occluded_fraction`]).
#[inline]
pub(crate) fn occluded<'t, const B: bool>(
    emitter: &Emitter,
    p: DVec3,
    occluders: impl Occluders<'t>,
    scratch: &mut Scratch,
) -> Option<Fraction> {
    let view = match *emitter {
        Emitter::Disk(d) => AreaView::disk(p, d.center(), d.normal(), d.radius())?,
        Emitter::Rect(r) => AreaView::rect(p, r.center(), r.u(), r.v())?,
        Emitter::Segment(s) => {
            // Its bound costs nothing more than its fraction.
            let view = SegmentView::new(p, s.a(), s.b())?;
            let triangles = occluders.near(|| view.hull());
            return Some(view.occluded_fraction_bounded(triangles, scratch));
        }
        Emitter::Point(x) => {
            let x = x.position();
            if !p.is_finite() || p == x {
                return None;
            }
            let value = if occluders.block(p, x) { 1.0 } else { 0.0 };
            return Some(Fraction { value, bound: 0.0 });
        }
    };
    let triangles = occluders.near(|| view.hull());
    Some(if B {
        view.occluded_fraction_bounded(triangles, scratch)
    } else {
        Fraction {
            value: view.occluded_fraction(triangles, scratch),
            bound: 0.0,
        }
    })
}
