//! The receiver view of a disk or rect ([`AreaView`]): each triangle
//! clipped to the part of space between the receiver and the light and
//! projected onto the light's plane ([`Image`]), and the area of the union
//! of those images within the light.

use super::union::{union_area, Measure, Tri};
use super::Scratch;
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// The receiver view of a disk or rect light from one receiver `p`: the
/// light's plane with 2D coordinates `(X, Y)` for the point
/// `center + X e₀ + Y e₁` ([`AreaView::axes`]), and the square
/// `|X|, |Y| ≤ half` that holds the light.
///
/// A triangle's image is computed in that plane, not by projecting clipped
/// 3D points: the light point `x` is hidden by the triangle exactly when the
/// direction `x − p` lies in the cone the triangle spans from `p` (three
/// half-spaces through `p`, one per edge) and `x` lies strictly beyond the
/// triangle's plane (the open segment of
/// [visibility](crate::definitions#visibility)). Each half-space meets the
/// light's plane in a half-plane, so the image is the square cut by four
/// half-planes: a convex polygon of at most eight vertices, whatever the
/// triangle does behind the receiver or beyond the light, and however close
/// to `p` it passes — no point near `p` is ever constructed.
#[derive(Clone, Copy, Debug)]
pub struct AreaView {
    p: DVec3,
    center: DVec3,
    /// The plane's coordinate axes.
    e: [DVec3; 2],
    half: f64,
    measure: Measure,
    /// For a disk: what projecting corners directly needs.
    direct: Option<Direct>,
}

/// A disk view's direct projection: the unit normal toward the light, the
/// light's depth from `p` along it, the unit axes and the radius (the
/// view's axes are the unit axes times the radius).
#[derive(Clone, Copy, Debug)]
struct Direct {
    w: DVec3,
    depth: f64,
    unit: [DVec3; 2],
    radius: f64,
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

impl AreaView {
    /// The view of the disk (`center`, `normal`, `radius`) from `p`, in
    /// coordinates measured in radii about the centre: `e₀, e₁` are
    /// `normal.any_orthonormal_pair()` times `radius`, and the disk is the
    /// unit disk `X² + Y² ≤ 1` — so neither a radius of `10⁻³⁰⁰` nor one of
    /// `10³⁰⁰` under- or overflows an area.
    ///
    /// `None` when an argument is not finite, `radius ≤ 0`, `normal` is
    /// zero, or `p` lies in the disk's plane (where no triangle's image is
    /// defined; [`Light::emitter`](crate::scene::Light::emitter) refuses
    /// such a receiver too).
    #[must_use]
    pub fn disk(p: DVec3, center: DVec3, normal: DVec3, radius: f64) -> Option<AreaView> {
        if !(p.is_finite() && center.is_finite() && radius.is_finite() && radius > 0.0) {
            return None;
        }
        // Any finite non-zero normal, however long or short.
        let n = crate::kernel::eft::unit(normal)?;
        let d = n.dot(center - p);
        if !(d.is_finite() && d != 0.0) {
            return None;
        }
        let (w, depth) = if d > 0.0 { (n, d) } else { (-n, -d) };
        let (t, b) = n.any_orthonormal_pair();
        Some(AreaView {
            p,
            center,
            e: [t * radius, b * radius],
            // A square around the disk, with margin, so that clipping
            // happens well outside it.
            half: 1.5,
            measure: Measure::Disk(1.0),
            direct: Some(Direct {
                w,
                depth,
                unit: [t, b],
                radius,
            }),
        })
    }

    /// The view of the parallelogram `center + s u + t v`, `s, t ∈ [−1, 1]`
    /// (half-axes `u`, `v`, as for a rect light) from `p`, in its own affine
    /// coordinates: `e₀ = u`, `e₁ = v`, the light is the square `[−1, 1]²`,
    /// and area ratios are kept (no normal of the plane is ever used).
    ///
    /// `None` when an argument is not finite, `u` and `v` are parallel, or
    /// `p` lies in the rect's plane.
    #[must_use]
    pub fn rect(p: DVec3, center: DVec3, u: DVec3, v: DVec3) -> Option<AreaView> {
        if !(p.is_finite() && center.is_finite() && u.is_finite() && v.is_finite()) {
            return None;
        }
        // `u × v` scaled by a power of two: an area beyond `f64`'s range
        // (half-axes of 1e200 or 1e-200) still has a plane.
        let (n, _) = crate::kernel::eft::scaled_cross(u, v)?;
        let d = n.dot(center - p);
        if !(d.is_finite() && d != 0.0) {
            return None;
        }
        Some(AreaView {
            p,
            center,
            e: [u, v],
            half: 1.0,
            measure: Measure::Square,
            direct: None,
        })
    }

    /// The receiver.
    #[must_use]
    pub fn receiver(&self) -> DVec3 {
        self.p
    }

    /// The origin and axes of the plane's coordinates: `(X, Y)` is the
    /// point `center + X e₀ + Y e₁`.
    #[must_use]
    pub fn axes(&self) -> (DVec3, [DVec3; 2]) {
        (self.center, self.e)
    }

    /// The light's area in the plane's coordinates: `π` for a disk (the
    /// unit disk), 4 for a rect (the square `[−1, 1]²`).
    #[must_use]
    pub fn light_area(&self) -> f64 {
        match self.measure {
            Measure::Disk(r) => PI * r * r,
            Measure::Square => 4.0,
        }
    }

    /// The pyramid from `p` over a square around the light: every triangle
    /// that hides some light point from `p` meets its convex hull, so a
    /// culling structure may skip the triangles that miss it.
    #[must_use]
    pub fn hull(&self) -> [DVec3; 5] {
        let h = self.half;
        let corner = |sx: f64, sy: f64| self.center + self.e[0] * (sx * h) + self.e[1] * (sy * h);
        [
            self.p,
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
        ]
    }

    /// The fraction of the light the triangles hide from `p`, in `[0, 1]`:
    /// `area(∪ images ∩ light) / area(light)`. Non-finite triangles hide
    /// nothing.
    #[must_use]
    pub fn occluded_fraction<'t>(
        &self,
        triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
        scratch: &mut Scratch,
    ) -> f64 {
        // The generic loop is kept to a call per triangle, so that the work
        // is compiled once, here, not in every caller.
        scratch.triangles.clear();
        for tri in triangles {
            if self.add_image(tri, &mut scratch.triangles) {
                return 1.0;
            }
        }
        let covered = union_area(
            &scratch.triangles,
            self.measure,
            self.half,
            &mut scratch.union,
        );
        (covered / self.light_area()).clamp(0.0, 1.0)
    }

    /// Appends the parts of the triangle's image that meet the light; true
    /// when the image covers the whole light (checked on the convex image
    /// before it is split, so that a covering image ends the work however
    /// many images came before it).
    fn add_image(&self, tri: &[DVec3; 3], out: &mut Vec<Tri>) -> bool {
        let measure = self.measure;
        let mut keep = |t: Tri| {
            if !measure.misses(&t) {
                out.push(t);
            }
        };
        match self.polygon(tri) {
            Polygon::Corners([a, b, c]) => {
                if let Some(t) = Tri::new(a, b, c) {
                    if measure.covered_by(&t) {
                        return true;
                    }
                    keep(t);
                }
            }
            Polygon::Clipped(image) => {
                let v = image.vertices();
                if measure.covered_by_convex(v) {
                    return true;
                }
                for k in 1..v.len().saturating_sub(1) {
                    if let Some(t) = Tri::new(v[0], v[k], v[k + 1]) {
                        keep(t);
                    }
                }
            }
        }
        false
    }

    /// The image of a triangle on the light's plane: the light points it
    /// hides from `p` form the image's interior intersected with the light.
    /// Cut to the square `|X|, |Y| ≤ half` around the light (`half` is 1.5
    /// for a disk, 1 for a rect), counter-clockwise; empty when the
    /// triangle hides nothing there (it lies behind `p` or beyond the light,
    /// its plane holds `p`, or it has a non-finite corner).
    #[must_use]
    pub fn image(&self, tri: &[DVec3; 3]) -> Image {
        match self.polygon(tri) {
            Polygon::Corners([a, b, c]) => match orient2d(a, b, c) {
                Sign::Positive => Image::from_slice(&[a, b, c]),
                Sign::Negative => Image::from_slice(&[a, c, b]),
                Sign::Zero => Image::EMPTY,
            },
            Polygon::Clipped(image) => image,
        }
    }

    /// The corners' images when all three lie strictly between `p` and the
    /// light's plane and project inside the square.
    fn projected(&self, rel: &[DVec3; 3]) -> Option<[DVec2; 3]> {
        let Direct {
            w,
            depth,
            unit,
            radius,
        } = self.direct?;
        let c = self.center - self.p;
        let mut out = [DVec2::ZERO; 3];
        for (q, &d) in out.iter_mut().zip(rel) {
            let z = w.dot(d);
            if !(z > 0.0 && z < depth) {
                return None;
            }
            let x = d * (depth / z) - c;
            *q = DVec2::new(x.dot(unit[0]) / radius, x.dot(unit[1]) / radius);
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

    /// The image of a triangle: its projected corners on the fast path,
    /// else the square cut by the four half-planes.
    fn polygon(&self, tri: &[DVec3; 3]) -> Polygon {
        if !tri.iter().all(|v| v.is_finite()) {
            return Polygon::Clipped(Image::EMPTY);
        }
        // σ: the sign of det[a − p, b − p, c − p]. Zero: the plane holds p,
        // the image is a segment or a point.
        let sigma = match orient3d(tri[0], tri[1], tri[2], self.p) {
            Sign::Positive => 1.0,
            Sign::Negative => -1.0,
            Sign::Zero => return Polygon::Clipped(Image::EMPTY),
        };
        let rel = tri.map(|v| v - self.p);
        if let Some(corners) = self.projected(&rel) {
            return Polygon::Corners(corners);
        }
        let mut poly = Image::square(self.half);
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
                return Polygon::Clipped(poly);
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
        Polygon::Clipped(poly)
    }
}

/// A triangle's image before it is handed out: the fast path's corners (in
/// either orientation) or the clipped polygon.
enum Polygon {
    Corners([DVec2; 3]),
    Clipped(Image),
}

/// Whether `a` precedes `b` in lexicographic order of coordinates.
fn lexicographic(a: DVec3, b: DVec3) -> bool {
    (a.x, a.y, a.z) <= (b.x, b.y, b.z)
}

/// A triangle's image on the light's plane ([`AreaView::image`]): a convex
/// polygon of at most eight vertices (the square around the light cut by
/// four half-planes), counter-clockwise, in the view's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Image {
    v: [DVec2; Image::CAP],
    len: usize,
}

impl Image {
    const CAP: usize = 8;
    const EMPTY: Image = Image {
        v: [DVec2::ZERO; Image::CAP],
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

    fn from_slice(v: &[DVec2]) -> Image {
        let mut image = Image::EMPTY;
        image.v[..v.len()].copy_from_slice(v);
        image.len = v.len();
        image
    }

    fn square(h: f64) -> Image {
        let mut v = [DVec2::ZERO; Image::CAP];
        v[..4].copy_from_slice(&[
            DVec2::new(-h, -h),
            DVec2::new(h, -h),
            DVec2::new(h, h),
            DVec2::new(-h, h),
        ]);
        Image { v, len: 4 }
    }

    /// Sutherland–Hodgman against the half-plane. Nothing is left when no
    /// vertex is strictly inside: the rest has no area (a triangle lying in
    /// the light's own plane hides nothing, as the open segment says).
    fn clip(&mut self, line: Line) {
        let mut f = [0.0; Image::CAP];
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
        let mut out = [DVec2::ZERO; Image::CAP];
        let mut n = 0;
        let mut push = |v: DVec2| {
            if n < Image::CAP {
                out[n] = v;
                n += 1;
            }
        };
        for k in 0..self.len {
            // The next vertex, without a division.
            let j = if k + 1 == self.len { 0 } else { k + 1 };
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
pub(super) fn crossing<V>(a: V, fa: f64, b: V, fb: f64) -> V
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
