//! The receiver view of a disk or rect light ([`View`]): each triangle
//! clipped to the part of space between the receiver and the light and
//! projected onto the light's plane, as a fan of [`Tri`]s whose union
//! [`union_area`] measures.

use super::union::{union_area, Measure, Tri};
use super::Scratch;
use crate::bvh::Bvh;
use crate::kernel::predicate::{orient3d, Sign};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

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
pub(super) struct View {
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
    pub(super) fn new(p: DVec3, center: DVec3, e: [DVec3; 2], half: f64) -> View {
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
    pub(super) fn orthonormal(p: DVec3, center: DVec3, e: [DVec3; 2], half: f64) -> View {
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
    pub(super) fn covered_area(&self, bvh: &Bvh, scratch: &mut Scratch, measure: Measure) -> f64 {
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
