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
//! the tests (`docs/accuracy/references.md`).
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

use crate::bvh::Bvh;
use crate::kernel::disk::f64::segment_disk_area;
use crate::kernel::predicate::{orient2d, orient2d_value, orient3d, orient3d_value, Sign};
use crate::kernel::segment::segment_blocked;
use crate::scene::{Emitter, Light, ReceiverError};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

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

/// A projected triangle, counter-clockwise, with its bounds.
#[derive(Clone, Copy, Debug)]
struct Tri {
    v: [DVec2; 3],
    lo: DVec2,
    hi: DVec2,
}

impl Tri {
    /// The triangle oriented counter-clockwise; `None` when it is
    /// degenerate (decided exactly).
    fn new(a: DVec2, b: DVec2, c: DVec2) -> Option<Tri> {
        let v = match orient2d(a, b, c) {
            Sign::Positive => [a, b, c],
            Sign::Negative => [a, c, b],
            Sign::Zero => return None,
        };
        Some(Tri {
            v,
            lo: a.min(b).min(c),
            hi: a.max(b).max(c),
        })
    }

    fn edge(&self, k: usize) -> (DVec2, DVec2) {
        (self.v[k], self.v[(k + 1) % 3])
    }
}

/// What area the union is measured with.
#[derive(Clone, Copy, Debug)]
enum Measure {
    /// The disk of this radius about the origin.
    Disk(f64),
    /// The square `[−1, 1]²`, inside which every projected triangle lies.
    Square,
}

impl Measure {
    /// The signed area the directed boundary piece `a → b` contributes.
    fn piece(self, a: DVec2, b: DVec2) -> f64 {
        match self {
            Measure::Disk(r) => segment_disk_area(r, a, b),
            Measure::Square => 0.5 * a.perp_dot(b),
        }
    }

    /// Whether the triangle certainly misses the measure (bounds apart).
    /// Whether the triangle misses the measure's interior (the disk: the
    /// centre outside it and every edge at least `r` away; so a lit
    /// receiver gets `V = 1` exactly, with no boundary pieces to sum).
    fn misses(self, t: &Tri) -> bool {
        let r = match self {
            Measure::Disk(r) => r,
            Measure::Square => 1.0,
        };
        if t.lo.x >= r || t.lo.y >= r || t.hi.x <= -r || t.hi.y <= -r {
            return true;
        }
        let Measure::Disk(r) = self else {
            return false;
        };
        let centre_outside = (0..3).any(|k| {
            let (a, b) = t.edge(k);
            orient2d(a, b, DVec2::ZERO) == Sign::Negative
        });
        centre_outside
            && (0..3).all(|k| {
                let (a, b) = t.edge(k);
                let d = b - a;
                let s = (-a.dot(d) / d.length_squared()).clamp(0.0, 1.0);
                (a + d * s).length_squared() >= r * r
            })
    }

    /// Whether the triangle alone covers the whole measure.
    fn covered_by(self, t: &Tri) -> bool {
        match self {
            Measure::Disk(r) => (0..3).all(|k| {
                let (a, b) = t.edge(k);
                let d = b - a;
                // Signed distance of the centre from the edge's line.
                d.perp_dot(-a) >= r * d.length()
            }),
            Measure::Square => [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .all(|&(x, y)| {
                    let c = DVec2::new(x, y);
                    (0..3).all(|k| {
                        let (a, b) = t.edge(k);
                        orient2d(a, b, c) != Sign::Negative
                    })
                }),
        }
    }
}

/// The receiver view of a disk or rect light: the light's plane with 2D
/// coordinates `(X, Y)` for the point `center + X e₀ + Y e₁`, and the square
/// `|X|, |Y| ≤ half` that holds the light.
///
/// A triangle's image is computed in that plane, not by projecting clipped
/// 3D points: the light point `x` is hidden by the triangle exactly when the
/// direction `x − p` lies in the cone the triangle spans from `p` (three
/// half-spaces through `p`, one per edge) and `x` lies strictly beyond the
/// triangle's plane (DESIGN §1's open segment). Each half-space meets the
/// light's plane in a half-plane, so the image is the square cut by four
/// half-planes: a convex polygon of at most eight vertices, whatever the
/// triangle does behind the receiver or beyond the light, and however close
/// to `p` it passes — no point near `p` is ever constructed.
struct View {
    p: DVec3,
    center: DVec3,
    /// The plane's coordinate axes.
    e: [DVec3; 2],
    half: f64,
    /// For orthonormal axes (a disk): the unit normal toward the light and
    /// the light's depth from `p` along it, for projecting corners directly.
    depth: Option<(DVec3, f64)>,
}

/// A half-plane `a X + b Y + c ≥ 0` of the light's plane.
#[derive(Clone, Copy, Debug)]
struct Line {
    a: f64,
    b: f64,
    c: f64,
}

impl Line {
    fn at(&self, q: DVec2) -> f64 {
        self.a * q.x + self.b * q.y + self.c
    }
}

impl View {
    fn new(p: DVec3, center: DVec3, e: [DVec3; 2], half: f64) -> View {
        View {
            p,
            center,
            e,
            half,
            depth: None,
        }
    }

    /// A view with orthonormal axes: triangles wholly between `p` and the
    /// light whose corners project inside the square take a fast path (the
    /// projected corners themselves, the same bits in every triangle that
    /// shares them, so shared edges coincide exactly).
    fn orthonormal(p: DVec3, center: DVec3, e: [DVec3; 2], half: f64) -> View {
        let n = e[0].cross(e[1]);
        let d = n.dot(center - p);
        let (w, depth) = if d >= 0.0 { (n, d) } else { (-n, -d) };
        View {
            depth: Some((w, depth)),
            ..View::new(p, center, e, half)
        }
    }

    /// The corners' images when all three lie strictly between `p` and the
    /// light's plane and project inside the square.
    fn projected(&self, rel: &[DVec3; 3]) -> Option<[DVec2; 3]> {
        let (w, depth) = self.depth?;
        let c = self.center - self.p;
        let mut out = [DVec2::ZERO; 3];
        for (q, &d) in out.iter_mut().zip(rel) {
            let z = w.dot(d);
            if !(z > 0.0 && z < depth) {
                return None;
            }
            let x = d * (depth / z) - c;
            *q = DVec2::new(x.dot(self.e[0]), x.dot(self.e[1]));
            if !(q.x.abs() < self.half && q.y.abs() < self.half) {
                return None;
            }
        }
        Some(out)
    }

    /// The half-plane of light points `x` with `m · (x − q) ≥ 0`, given
    /// `center − q`.
    fn line(&self, m: DVec3, center_minus_q: DVec3) -> Line {
        Line {
            a: m.dot(self.e[0]),
            b: m.dot(self.e[1]),
            c: m.dot(center_minus_q),
        }
    }

    /// The area of the union of the triangles' images within the measure.
    fn covered_area(&self, bvh: &Bvh, scratch: &mut Scratch, measure: Measure) -> f64 {
        let h = self.half;
        let corner = |sx: f64, sy: f64| self.center + self.e[0] * (sx * h) + self.e[1] * (sy * h);
        let hull = [
            self.p,
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
        ];
        bvh.triangles_meeting_hull(&hull, &mut scratch.candidates);
        scratch.triangles.clear();
        let triangles = bvh.occluders().triangles();
        for &i in &scratch.candidates {
            let Some(tri) = triangles.get(i as usize) else {
                continue;
            };
            let first = scratch.triangles.len();
            self.image(tri, &mut scratch.triangles);
            // Cull what misses the measure; stop early under a full cover.
            let mut k = first;
            while k < scratch.triangles.len() {
                let t = scratch.triangles[k];
                if measure.covered_by(&t) {
                    return match measure {
                        Measure::Disk(r) => PI * r * r,
                        Measure::Square => 4.0,
                    };
                }
                if measure.misses(&t) {
                    scratch.triangles.swap_remove(k);
                } else {
                    k += 1;
                }
            }
        }
        union_area(&scratch.triangles, measure, self.half, &mut scratch.union)
    }

    /// Appends the image of a triangle, split into a fan of triangles.
    fn image(&self, tri: &[DVec3; 3], out: &mut Vec<Tri>) {
        if !tri.iter().all(|v| v.is_finite()) {
            return;
        }
        // σ: the sign of det[a − p, b − p, c − p]. Zero: the plane holds p,
        // the image is a segment or a point.
        let sigma = match orient3d(tri[0], tri[1], tri[2], self.p) {
            Sign::Positive => 1.0,
            Sign::Negative => -1.0,
            Sign::Zero => return,
        };
        let rel = tri.map(|v| v - self.p);
        if let Some([a, b, c]) = self.projected(&rel) {
            out.extend(Tri::new(a, b, c));
            return;
        }
        let mut poly = Poly::square(self.half);
        // The cone: for the edge (j, k) opposite corner i, the plane through
        // p and the edge, oriented toward corner i (σ · rel_j × rel_k does:
        // rel_i · (rel_j × rel_k) = det). The cross product is formed with
        // the edge's ends in a canonical order, so the two triangles sharing
        // an edge cut their images along the same line, bit for bit.
        for (j, k) in [(1, 2), (2, 0), (0, 1)] {
            let m = if lexicographic(tri[j], tri[k]) {
                rel[j].cross(rel[k])
            } else {
                -rel[k].cross(rel[j])
            };
            poly.clip(self.line(m * sigma, self.center - self.p));
            if poly.len == 0 {
                return;
            }
        }
        // Strictly beyond the triangle's plane: σ · n · (x − a) > 0 with
        // n = (b − a) × (c − a) (det = (a − p) · n, so p has the other sign).
        // n is formed from the two shortest edges and the plane is measured
        // from the corner nearest the light, so that a far corner (10²⁰
        // away) costs no cancellation.
        let e = [tri[1] - tri[0], tri[2] - tri[1], tri[0] - tri[2]];
        let len = e.map(|v| v.abs().max_element());
        let longest = (0..3).fold(0, |m, k| if len[k] > len[m] { k } else { m });
        let n = e[(longest + 1) % 3].cross(e[(longest + 2) % 3]);
        let nearest = (0..3).fold(0, |m, k| {
            let d = |i: usize| (self.center - tri[i]).abs().max_element();
            if d(k) < d(m) {
                k
            } else {
                m
            }
        });
        poly.clip(self.line(n * sigma, self.center - tri[nearest]));
        for k in 1..poly.len.saturating_sub(1) {
            if let Some(t) = Tri::new(poly.v[0], poly.v[k], poly.v[k + 1]) {
                out.push(t);
            }
        }
    }
}

/// Whether `a` precedes `b` in lexicographic order of coordinates.
fn lexicographic(a: DVec3, b: DVec3) -> bool {
    (a.x, a.y, a.z) <= (b.x, b.y, b.z)
}

/// A convex polygon of the light's plane with at most eight vertices (the
/// square cut by four half-planes).
struct Poly {
    v: [DVec2; Poly::CAP],
    len: usize,
}

impl Poly {
    const CAP: usize = 8;

    fn square(h: f64) -> Poly {
        let mut v = [DVec2::ZERO; Poly::CAP];
        v[..4].copy_from_slice(&[
            DVec2::new(-h, -h),
            DVec2::new(h, -h),
            DVec2::new(h, h),
            DVec2::new(-h, h),
        ]);
        Poly { v, len: 4 }
    }

    /// Sutherland–Hodgman against the half-plane. Nothing is left when no
    /// vertex is strictly inside: the rest has no area (a triangle lying in
    /// the light's own plane hides nothing, as the open segment says).
    fn clip(&mut self, line: Line) {
        let mut f = [0.0; Poly::CAP];
        let (mut any_in, mut all_in) = (false, true);
        for (fk, &v) in f.iter_mut().zip(&self.v[..self.len]) {
            *fk = line.at(v);
            any_in |= *fk > 0.0;
            all_in &= *fk >= 0.0;
        }
        if !any_in {
            self.len = 0;
            return;
        }
        if all_in {
            return;
        }
        let mut out = [DVec2::ZERO; Poly::CAP];
        let mut n = 0;
        let mut push = |v: DVec2| {
            if n < Poly::CAP {
                out[n] = v;
                n += 1;
            }
        };
        for k in 0..self.len {
            let j = (k + 1) % self.len;
            let (a, fa, b, fb) = (self.v[k], f[k], self.v[j], f[j]);
            if fa >= 0.0 {
                push(a);
            }
            if (fa > 0.0 && fb < 0.0) || (fa < 0.0 && fb > 0.0) {
                push(crossing(a, fa, b, fb));
            }
        }
        self.v = out;
        self.len = n;
    }
}

/// The point where the segment `a b` crosses a line (or plane) with values
/// `fa`, `fb` of strictly opposite signs at its ends; symmetric in its
/// arguments. Measured from the end nearer the line (`t ≤ ½`), so that the
/// rounding is relative to the distance from that end, not to the far end's
/// magnitude.
fn crossing<V>(a: V, fa: f64, b: V, fb: f64) -> V
where
    V: Copy
        + std::ops::Add<Output = V>
        + std::ops::Sub<Output = V>
        + std::ops::Mul<f64, Output = V>,
{
    let (a, fa, b, fb) = if fa.abs() <= fb.abs() {
        (a, fa, b, fb)
    } else {
        (b, fb, a, fa)
    };
    let t = (fa / (fa - fb)).clamp(0.0, 1.0);
    a + (b - a) * t
}

/// The area of `∪ triangles ∩ measure`, by Green's theorem over the
/// union's boundary (see the module documentation). `half` bounds every
/// coordinate (the clip square's half-width): the triangles are binned in a
/// uniform grid over it so that an edge is tested only against triangles
/// sharing a cell with its bounds.
fn union_area(tris: &[Tri], measure: Measure, half: f64, scratch: &mut UnionScratch) -> f64 {
    let grid = &mut scratch.grid;
    grid.build(tris, half);
    scratch.stamp.clear();
    scratch.stamp.resize(tris.len(), u32::MAX);
    let mut sum = Sum::default();
    let mut edge_id = 0_u32;
    for (i, ti) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = ti.edge(k);
            let (lo, hi) = (a.min(b), a.max(b));
            scratch.intervals.clear();
            let mut whole = false;
            grid.for_each_near(lo, hi, |j| {
                let j = j as usize;
                if j == i || scratch.stamp[j] == edge_id {
                    return true;
                }
                scratch.stamp[j] = edge_id;
                let tj = &tris[j];
                if tj.hi.x < lo.x || tj.lo.x > hi.x || tj.hi.y < lo.y || tj.lo.y > hi.y {
                    return true;
                }
                if let Some(span) = covered_span(a, b, tj, j < i) {
                    // A span of the whole edge settles it (a shared edge,
                    // a copy): nothing of the edge is on the boundary. So
                    // do spans that together cover it, checked at every
                    // power of two to keep the check's cost linear.
                    scratch.intervals.push(span);
                    let n = scratch.intervals.len();
                    whole = span == (0.0, 1.0)
                        || (n >= 4 && n.is_power_of_two() && covers_unit(&mut scratch.intervals));
                }
                !whole
            });
            edge_id = edge_id.wrapping_add(1);
            if !whole {
                add_uncovered(a, b, &mut scratch.intervals, measure, &mut sum);
            }
        }
    }
    sum.value()
}

/// Buffers of [`union_area`].
#[derive(Debug, Default)]
struct UnionScratch {
    grid: Grid,
    /// The last edge each triangle was tested against.
    stamp: Vec<u32>,
    intervals: Vec<(f64, f64)>,
}

/// A uniform grid of triangle indices over the square `[−half, half]²`, in
/// compressed rows: cell `c` holds `items[start[c]..start[c + 1]]`.
#[derive(Debug, Default)]
struct Grid {
    n: usize,
    half: f64,
    inv_cell: f64,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    /// The most cells along a side: beyond it, building costs more than the
    /// tests it saves (large triangles are inserted into many cells).
    const MAX_SIDE: usize = 64;

    fn build(&mut self, tris: &[Tri], half: f64) {
        let n = ((tris.len() as f64).sqrt().ceil() as usize).clamp(1, Grid::MAX_SIDE);
        self.n = n;
        self.half = half;
        self.inv_cell = n as f64 / (2.0 * half);
        self.start.clear();
        self.start.resize(n * n + 1, 0);
        for t in tris {
            let (x0, y0, x1, y1) = self.range(t.lo, t.hi);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    self.start[y * n + x + 1] += 1;
                }
            }
        }
        for c in 0..n * n {
            self.start[c + 1] += self.start[c];
        }
        self.items.clear();
        self.items.resize(self.start[n * n] as usize, 0);
        let mut fill: Vec<u32> = self.start[..n * n].to_vec();
        for (i, t) in tris.iter().enumerate() {
            let (x0, y0, x1, y1) = self.range(t.lo, t.hi);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let c = y * n + x;
                    self.items[fill[c] as usize] = i as u32;
                    fill[c] += 1;
                }
            }
        }
    }

    /// The cells `x0..=x1`, `y0..=y1` the box `lo..hi` overlaps (clamped:
    /// rounding may put a clipped vertex a hair outside the square).
    fn range(&self, lo: DVec2, hi: DVec2) -> (usize, usize, usize, usize) {
        let cell = |v: f64| {
            let c = ((v + self.half) * self.inv_cell).floor();
            if c >= 0.0 {
                (c as usize).min(self.n - 1)
            } else {
                0
            }
        };
        (cell(lo.x), cell(lo.y), cell(hi.x), cell(hi.y))
    }

    /// Calls `f` with every triangle in a cell the box `lo..hi` overlaps
    /// (a triangle in several cells more than once) until it returns
    /// `false`.
    fn for_each_near(&self, lo: DVec2, hi: DVec2, mut f: impl FnMut(u32) -> bool) {
        let (x0, y0, x1, y1) = self.range(lo, hi);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = y * self.n + x;
                for &j in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    if !f(j) {
                        return;
                    }
                }
            }
        }
    }
}

/// Whether the intervals cover all of `[0, 1]` (sorts them).
fn covers_unit(intervals: &mut [(f64, f64)]) -> bool {
    intervals.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let mut reach = 0.0_f64;
    for &(s, e) in intervals.iter() {
        if s > reach {
            return false;
        }
        reach = reach.max(e);
    }
    reach >= 1.0
}

/// Adds the pieces of `a → b` outside every interval of `intervals`.
fn add_uncovered(
    a: DVec2,
    b: DVec2,
    intervals: &mut [(f64, f64)],
    measure: Measure,
    sum: &mut Sum,
) {
    if intervals.is_empty() {
        sum.add(measure.piece(a, b));
        return;
    }
    intervals.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let at = |t: f64| if t >= 1.0 { b } else { a + (b - a) * t };
    let mut t = 0.0;
    let mut from = a;
    for &(s, e) in intervals.iter() {
        if s > t {
            let to = at(s);
            sum.add(measure.piece(from, to));
        }
        if e > t {
            t = e;
            from = at(t);
        }
        if t >= 1.0 {
            return;
        }
    }
    sum.add(measure.piece(from, b));
}

/// The parameter interval of the edge `a → b` that the triangle covers,
/// `None` when it covers none of positive length. Closed triangle; where
/// the edge runs along an edge of `t` the rule of the module documentation
/// applies: covered when `t` lies on the other side, or on the same side
/// and `t_first` (it comes first in index order).
fn covered_span(a: DVec2, b: DVec2, t: &Tri, t_first: bool) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for k in 0..3 {
        let (f0, f1) = t.edge(k);
        // Signed areas with exact signs and accurate values: the cut of
        // this edge by `f` and the cut of `f` by this edge land on the same
        // point even for nearly parallel edges.
        let (va, vb) = (orient2d_value(f0, f1, a), orient2d_value(f0, f1, b));
        match (Sign::of(va), Sign::of(vb)) {
            (Sign::Zero, Sign::Zero) => {
                let same_side = (b - a).dot(f1 - f0) > 0.0;
                if same_side && !t_first {
                    return None;
                }
            }
            (Sign::Negative, Sign::Negative | Sign::Zero) | (Sign::Zero, Sign::Negative) => {
                return None;
            }
            (Sign::Positive | Sign::Zero, Sign::Positive | Sign::Zero) => {}
            (sa, _) => {
                // A strict crossing: va and vb have opposite signs, so
                // va − vb does not cancel.
                let s = (va / (va - vb)).clamp(0.0, 1.0);
                if sa == Sign::Negative {
                    t0 = t0.max(s);
                } else {
                    t1 = t1.min(s);
                }
            }
        }
    }
    (t0 < t1).then_some((t0, t1))
}

/// The visibility of a segment light `a b` from `p`.
fn segment_visibility(bvh: &Bvh, p: DVec3, a: DVec3, b: DVec3, scratch: &mut Scratch) -> f64 {
    let (ra, rb) = (a - p, b - p);
    let n = ra.cross(rb);
    let collinear = [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
        let q = |v: DVec3| DVec2::new(v[i], v[j]);
        orient2d(q(a), q(b), q(p)) == Sign::Zero
    });
    bvh.triangles_meeting_hull(&[p, a, b], &mut scratch.candidates);
    let triangles = bvh.occluders().triangles();
    if collinear || n == DVec3::ZERO {
        return collinear_segment_visibility(bvh, p, a, b, &scratch.candidates);
    }
    // The plane's unit normal (scaled to its largest component first, so
    // that neither a light of size 1e-77 nor one of 1e77 under- or overflows
    // the products below).
    let n = (n / n.abs().max_element()).normalize();
    scratch.intervals.clear();
    for &i in &scratch.candidates {
        let Some(tri) = triangles.get(i as usize) else {
            continue;
        };
        if let Some(span) = blocked_interval(p, a, b, n, tri) {
            scratch.intervals.push(span);
        }
    }
    1.0 - union_length(&mut scratch.intervals)
}

/// The interval of the segment light's parameter `s ∈ [0, 1]` (the point
/// `a + s (b − a)`) that the triangle blocks from `p`; `n` the unit normal
/// along `(a − p) × (b − p)`.
fn blocked_interval(
    p: DVec3,
    a: DVec3,
    b: DVec3,
    n: DVec3,
    tri: &[DVec3; 3],
) -> Option<(f64, f64)> {
    if !tri.iter().all(|v| v.is_finite()) {
        return None;
    }
    // A triangle whose plane holds p (a receiver on it), or holds the
    // light: every open segment (p, x) meets its plane at most at an end.
    let [t0, t1, t2] = *tri;
    if orient3d(t0, t1, t2, p) == Sign::Zero
        || (orient3d(t0, t1, t2, a) == Sign::Zero && orient3d(t0, t1, t2, b) == Sign::Zero)
    {
        return None;
    }
    // Each corner's side of the plane (p, a, b): exact signs, and values
    // accurate enough that an edge crossing the plane is cut on it even
    // when the edge is within ulps of the plane.
    let dist = tri.map(|v| orient3d_value(p, a, b, v));
    let side = dist.map(Sign::of);
    if side.iter().all(|&s| s == Sign::Zero) {
        // In the plane: the open segments graze it and are not blocked.
        return None;
    }
    let rel = tri.map(|v| v - p);
    // The triangle's trace on the plane: corners on it and edge crossings.
    let mut pts = [DVec3::ZERO; 3];
    let mut m = 0;
    for k in 0..3 {
        let j = (k + 1) % 3;
        if side[k] == Sign::Zero {
            pts[m] = rel[k];
            m += 1;
        } else if side[j] != Sign::Zero && side[k] != side[j] && m < 3 {
            pts[m] = crossing(rel[k], dist[k], rel[j], dist[j]);
            m += 1;
        }
    }
    if m < 2 {
        return None;
    }
    let (mut e0, mut e1) = (pts[0], pts[1]);
    let (ra, rb) = (a - p, b - p);
    // In the plane, with p at the origin: f ≥ 0 on b's side of the ray to
    // a, g ≥ 0 on a's side of the ray to b, h ≥ 0 on p's side of the light.
    let f = |q: DVec3| n.dot(ra.cross(q));
    let g = |q: DVec3| n.dot(q.cross(rb));
    let h = |q: DVec3| n.dot((rb - ra).cross(q - ra));
    // Clip the trace to the triangle (p, a, b); each cut measured from the
    // end nearer the cutting line (a trace end 10²⁰ away must not set the
    // rounding of a cut near the light).
    for fun in [&f as &dyn Fn(DVec3) -> f64, &g, &h] {
        let (v0, v1) = (fun(e0), fun(e1));
        if v0.is_nan() || v1.is_nan() || (v0 < 0.0 && v1 < 0.0) || (v0 <= 0.0 && v1 <= 0.0) {
            // Outside, or on the line: nothing of positive length is left.
            return None;
        }
        if v0 < 0.0 {
            e0 = crossing(e0, v0, e1, v1);
        } else if v1 < 0.0 {
            e1 = crossing(e0, v0, e1, v1);
        }
    }
    // Project both ends from p onto the light: s = f / (f + g).
    let param = |q: DVec3| {
        let (fq, gq) = (f(q), g(q));
        let den = fq + gq;
        (den > 0.0).then(|| (fq / den).clamp(0.0, 1.0))
    };
    let (s0, s1) = match (param(e0), param(e1)) {
        (Some(x), Some(y)) => (x, y),
        // An end at p itself: the trace runs along a ray from p, one point.
        _ => return None,
    };
    let (lo, hi) = (s0.min(s1), s0.max(s1));
    (lo < hi).then_some((lo, hi))
}

/// A receiver on the segment light's line (but not on the light): every
/// open segment `(p, x)` lies on that line, and `x` is blocked beyond the
/// first crossing.
fn collinear_segment_visibility(
    bvh: &Bvh,
    p: DVec3,
    a: DVec3,
    b: DVec3,
    candidates: &[u32],
) -> f64 {
    let (near, far) = if (a - p).length_squared() <= (b - p).length_squared() {
        (a, b)
    } else {
        (b, a)
    };
    if !bvh.segment_unoccluded(p, near) {
        return 0.0;
    }
    // The first crossing beyond `near`, as a fraction of the light: what
    // lies before it is visible.
    let dir = far - near;
    let mut first = 1.0_f64;
    for &i in candidates {
        let Some(tri) = bvh.occluders().triangles().get(i as usize) else {
            continue;
        };
        if segment_blocked(p, far, tri) {
            let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
            let s = n.dot(tri[0] - near) / n.dot(dir);
            first = first.min(if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) });
        }
    }
    first
}

/// The total length of a union of intervals of `[0, 1]`.
fn union_length(intervals: &mut [(f64, f64)]) -> f64 {
    intervals.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let mut total = 0.0;
    let mut reach = 0.0_f64;
    for &(s, e) in intervals.iter() {
        let s = s.max(reach);
        if e > s {
            total += e - s;
            reach = e;
        }
    }
    total.min(1.0)
}

/// Neumaier's compensated sum.
#[derive(Default)]
struct Sum {
    sum: f64,
    c: f64,
}

impl Sum {
    fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.c += (self.sum - t) + x;
        } else {
            self.c += (x - t) + self.sum;
        }
        self.sum = t;
    }

    fn value(&self) -> f64 {
        self.sum + self.c
    }
}
