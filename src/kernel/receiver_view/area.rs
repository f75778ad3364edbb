//! The receiver view of a disk or rect ([`AreaView`]): each triangle
//! clipped to the part of space between the receiver and the light and
//! projected onto the light's plane ([`Image`]), and the area of the union
//! of those images within the light.

use super::bounded::{det3_exact, Bounded, Cross, Row};
use super::union::{union_area, Measure, Tri};
use super::Scratch;
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// The receiver view of a disk or rect light from one receiver `p`: the
/// light's plane with 2D coordinates `(X, Y)` for the point
/// `center + X e₀ + Y e₁` ([`AreaView::axes`]), in which the light is the
/// unit disk or the square `[−1, 1]²`, and the square `|X|, |Y| ≤ half`
/// that holds it.
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
///
/// Every coefficient of those half-planes, and every projected corner of
/// the fast path, is a ratio of 3×3 determinants of the inputs taken
/// relative to the receiver (`qⱼ − p`, `center − p`, the plane's axes),
/// each evaluated in `f64` with a bound on its error and evaluated exactly
/// where the bound would let the constructed line or corner stray by more
/// than `2⁻⁴⁸` of the light's radius (a receiver `10⁻¹⁷` from an edge, a
/// light of radius `10⁻⁶` four units away, a corner `10²⁰` away).
#[derive(Clone, Copy, Debug)]
pub struct AreaView {
    p: DVec3,
    center: DVec3,
    /// `center − p`.
    c: Row,
    /// The plane's axes `f₀`, `f₁`: exact vectors of the plane (a rect's
    /// half-axes; for a disk, the normal crossed with two coordinate axes,
    /// exact). The point `center + X f₀ + Y f₁` has the oblique coordinates
    /// `(X, Y)`.
    f: [DVec3; 2],
    /// `(X', Y') = M (X, Y)` maps the oblique coordinates to the view's,
    /// where the light is the unit disk or the square `[−1, 1]²`: `M =
    /// [[m₀₀, m₀₁], [0, m₁₁]]`, kept as `[m₀₀, m₀₁, m₁₁]`, and its inverse
    /// likewise.
    m: [f64; 3],
    inv: [f64; 3],
    half: f64,
    measure: Measure,
    /// For a disk: what projecting corners directly needs.
    direct: Option<Direct>,
}

/// A disk view's direct projection of a corner `q` (`d = q − p`): its
/// oblique coordinates are `X = det[c, d, f₁] / det[d, f₀, f₁]` and `Y =
/// −det[c, d, f₀] / det[d, f₀, f₁]`, `c = center − p` (the point where the
/// ray from `p` through `q` meets the plane), each determinant `d · w` with
/// `w` one of three cross products fixed for the view.
#[derive(Clone, Copy, Debug)]
struct Direct {
    /// `f₁ × c`, `f₀ × c`, `f₀ × f₁`.
    w: [Cross; 3],
    /// `±1`, making the light's depth `det[c, f₀, f₁]` positive.
    sgn: f64,
    /// `sgn · det[c, f₀, f₁]`: the light's depth (times `|f₀ × f₁|`).
    depth: Bounded,
}

/// A half-plane `a X + b Y + c ≥ 0` of the light's plane (view
/// coordinates), and a bound on how far its line may lie from the exact
/// one over the square.
#[derive(Clone, Copy, Debug)]
struct Line {
    a: f64,
    b: f64,
    c: f64,
    err: f64,
}

impl Line {
    fn at(&self, q: DVec2) -> f64 {
        self.a * q.x + self.b * q.y + self.c
    }
}

/// The largest error, in the view's coordinates (the light's radius or
/// half-width is 1), of an image's line or corner above which its
/// determinants are evaluated exactly.
const TOLERANCE: f64 = 1.0 / (1u64 << 40) as f64;

impl AreaView {
    /// The view of the disk (`center`, `normal`, `radius`) from `p`, in
    /// coordinates measured in radii about the centre: the disk is the
    /// unit disk `X² + Y² ≤ 1`, and the axes (of length `radius`) are
    /// orthogonal to rounding — so neither a radius of `10⁻³⁰⁰` nor one of
    /// `10³⁰⁰` under- or overflows an area. The plane is spanned exactly:
    /// its oblique axes are `normal` crossed with two coordinate axes,
    /// whose components are the normal's own.
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
        let n = normal.try_normalize()?;
        // The normal's largest component k: the axes n × eᵢ, n × eⱼ for the
        // other two are independent (their cross product is n nₖ).
        let k = (0..3).fold(0, |m, k| if n[k].abs() > n[m].abs() { k } else { m });
        let axis = |i: usize| n.cross(DVec3::AXES[i]);
        let f = [axis((k + 1) % 3), axis((k + 2) % 3)];
        // The Gram matrix of the axes over r², and its Cholesky factor M
        // (Mᵀ M = G / r²): |M (X, Y)|² = |X f₀ + Y f₁|² / r².
        let (g00, g01, g11) = (f[0].dot(f[0]), f[0].dot(f[1]), f[1].dot(f[1]));
        let s0 = g00.sqrt();
        let m = [
            s0 / radius,
            g01 / s0 / radius,
            (g11 - g01 * g01 / g00).sqrt() / radius,
        ];
        Self::new(p, center, f, m, 1.5, Measure::Disk(1.0), true)
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
        Self::new(
            p,
            center,
            [u, v],
            [1.0, 0.0, 1.0],
            1.0,
            Measure::Square,
            false,
        )
    }

    /// The view with the oblique axes `f` and the map `m`; `None` when the
    /// axes are parallel or `p` lies in the plane (both decided exactly).
    fn new(
        p: DVec3,
        center: DVec3,
        f: [DVec3; 2],
        m: [f64; 3],
        half: f64,
        measure: Measure,
        direct: bool,
    ) -> Option<AreaView> {
        let inv = [1.0 / m[0], -(m[1] / m[0]) / m[2], 1.0 / m[2]];
        let regular = |x: f64| x.is_finite() && x != 0.0;
        let finite = m[1].is_finite() && inv[1].is_finite();
        if !(regular(m[0]) && regular(m[2]) && regular(inv[0]) && regular(inv[2]) && finite) {
            return None;
        }
        let c = Row::diff(center, p);
        let (r0, r1) = (Row::vector(f[0]), Row::vector(f[1]));
        // The light's depth from p, det[c, f₀, f₁]: zero when the axes are
        // parallel or p lies in the plane.
        let n = Cross::of(f[0], f[1]);
        let mut depth = n.dot(c.r);
        if depth.sign().is_none() {
            depth = det3_exact(&r0, &r1, &c);
        }
        if depth.value == 0.0 || !depth.value.is_finite() {
            return None;
        }
        let sgn = if depth.value > 0.0 { 1.0 } else { -1.0 };
        let direct = direct.then(|| Direct {
            w: [Cross::of(f[1], c.r), Cross::of(f[0], c.r), n],
            sgn,
            depth: depth.signed(sgn),
        });
        Some(AreaView {
            p,
            center,
            c,
            f,
            m,
            inv,
            half,
            measure,
            direct,
        })
    }

    /// The receiver.
    #[must_use]
    pub fn receiver(&self) -> DVec3 {
        self.p
    }

    /// The origin and axes of the plane's coordinates: `(X, Y)` is the
    /// point `center + X e₀ + Y e₁` (the axes rounded from the exact ones:
    /// a disk's orthogonal and of its radius's length, a rect's `u` and
    /// `v`).
    #[must_use]
    pub fn axes(&self) -> (DVec3, [DVec3; 2]) {
        let [i00, i01, i11] = self.inv;
        (
            self.center,
            [self.f[0] * i00, self.f[0] * i01 + self.f[1] * i11],
        )
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
        let (center, e) = self.axes();
        let corner = |sx: f64, sy: f64| center + e[0] * (sx * h) + e[1] * (sy * h);
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

    /// The corners' images when all three lie certainly strictly between
    /// `p` and the light's plane and project inside the square, each within
    /// [`TOLERANCE`] of the exact projection.
    fn projected(&self, tri: &[DVec3; 3]) -> Option<[DVec2; 3]> {
        let direct = self.direct.as_ref()?;
        let mut out = [DVec2::ZERO; 3];
        for (q, &v) in out.iter_mut().zip(tri) {
            *q = self.project(direct, &Row::diff(v, self.p))?;
        }
        Some(out)
    }

    /// One corner's image (`d` its row from `p`), if it lies certainly
    /// strictly between `p` and the light's plane and inside the square.
    #[inline(always)]
    fn project(&self, direct: &Direct, d: &Row) -> Option<DVec2> {
        let [wx, wy, wz] = direct.w;
        let z = wz.dot(d.r).signed(direct.sgn);
        match self.corner(direct, wx.dot(d.r), wy.dot(d.r), z) {
            Corner::Outside => None,
            Corner::At(q) => Some(q),
            Corner::Unsure => {
                let (c, f0, f1) = (&self.c, &Row::vector(self.f[0]), &Row::vector(self.f[1]));
                let z = det3_exact(d, f0, f1).signed(direct.sgn);
                match self.corner(direct, det3_exact(c, d, f1), det3_exact(c, d, f0), z) {
                    Corner::At(q) => Some(q),
                    // Within rounding of p's depth or the light's: left to
                    // the clipped path.
                    Corner::Outside | Corner::Unsure => None,
                }
            }
        }
    }

    /// The corner's image from the determinants `nx = det[c, d, f₁]`, `ny
    /// = det[c, d, f₀]` and its depth `z = sgn · det[d, f₀, f₁]`.
    #[inline(always)]
    fn corner(&self, direct: &Direct, nx: Bounded, ny: Bounded, z: Bounded) -> Corner {
        let depth = direct.depth;
        // Certainly in front of p and before the light.
        let gap = depth.value - z.value;
        if !(z.value > 2.0 * z.bound
            && gap > (depth.bound + z.bound) * 1.01 + f64::EPSILON * depth.value)
        {
            return Corner::Unsure;
        }
        let sz = direct.sgn / z.value;
        let (x, y) = (nx.value * sz, -ny.value * sz);
        let [m00, m01, m11] = self.m;
        let q = DVec2::new(m00 * x + m01 * y, m11 * y);
        // First order in the determinants' bounds (z's bound is below half
        // of z), and the roundings of the quotients and the map.
        let rel = z.bound / (z.value - z.bound);
        let ex = (nx.bound * sz.abs() + x.abs() * rel) * 1.01 + x.abs() * f64::EPSILON;
        let ey = (ny.bound * sz.abs() + y.abs() * rel) * 1.01 + y.abs() * f64::EPSILON;
        let err = (m00.abs() * ex + m01.abs() * ey).max(m11.abs() * ey)
            + 2.0 * f64::EPSILON * q.abs().max_element();
        if q.x.abs() + err < self.half && q.y.abs() + err < self.half {
            if err <= TOLERANCE {
                Corner::At(q)
            } else {
                Corner::Unsure
            }
        } else if q.x.abs() - err > self.half || q.y.abs() - err > self.half {
            Corner::Outside
        } else {
            Corner::Unsure
        }
    }

    /// The half-plane of light points `x` with `det[u, v, x − o] ≥ 0`
    /// (rows `u`, `v` relative to `o`, `center_o` the row `center − o`),
    /// with coefficients within [`TOLERANCE`] (exact determinants where the
    /// rounded ones are not), and `None` when its line certainly misses the
    /// square (then the square lies wholly on one side; `Some(true)` inside).
    fn line(&self, u: &Row, v: &Row, center_o: &Row) -> Result<Line, bool> {
        let cross = Cross::of(u.r, v.r);
        let (f0, f1) = (Row::vector(self.f[0]), Row::vector(self.f[1]));
        let line = self.in_view(cross.dot(f0.r), cross.dot(f1.r), cross.dot(center_o.r));
        if let Some(settled) = self.settled(line) {
            return settled;
        }
        let exact = self.in_view(
            det3_exact(u, v, &f0),
            det3_exact(u, v, &f1),
            det3_exact(u, v, center_o),
        );
        // Beyond the exact arithmetic's range (coordinates far outside the
        // domain, whose expansions overflow), the rounded line stands.
        let line = if exact.a.is_finite() && exact.b.is_finite() && exact.c.is_finite() {
            exact
        } else {
            line
        };
        self.settled(line).unwrap_or(Ok(line))
    }

    /// `line` if it is within [`TOLERANCE`], `Err` if it certainly misses
    /// the square (the centre's side: the distance from the centre to the
    /// line, at least `|c| / (√2 max(|a|, |b|))`, beyond half the square's
    /// diagonal and the line's error), `None` if neither.
    #[inline(always)]
    fn settled(&self, line: Line) -> Option<Result<Line, bool>> {
        let norm = line.a.abs().max(line.b.abs());
        if line.c.abs() > (2.0 * self.half + 1.5 * line.err) * norm {
            Some(Err(line.c > 0.0))
        } else if line.err <= TOLERANCE {
            Some(Ok(line))
        } else {
            None
        }
    }

    /// The line `A X + B Y + C = 0` in oblique coordinates, in the view's:
    /// `(a, b) = (A, B) M⁻¹`, and the bound on its distance from the exact
    /// line over the square.
    #[inline(always)]
    fn in_view(&self, a: Bounded, b: Bounded, c: Bounded) -> Line {
        let [i00, i01, i11] = self.inv;
        let (ta, tb) = (a.value * i01, b.value * i11);
        let line = Line {
            a: a.value * i00,
            b: ta + tb,
            c: c.value,
            err: 0.0,
        };
        let ea = a.bound * i00.abs() + f64::EPSILON * line.a.abs();
        let eb = a.bound * i01.abs() + b.bound * i11.abs() + f64::EPSILON * (ta.abs() + tb.abs());
        let norm = line.a.abs().max(line.b.abs());
        let shift = c.bound + self.half * (ea + eb);
        // Beyond a quarter of the coefficients' size the bound is not
        // first order: infinite (the caller then asks the exact values).
        let err = if ea + eb <= 0.25 * norm {
            shift / norm * 1.5
        } else {
            f64::INFINITY
        };
        Line { err, ..line }
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
        if let Some(corners) = self.projected(tri) {
            return Polygon::Corners(corners);
        }
        let mut poly = Image::square(self.half);
        // The cone: for the edge (j, k) opposite corner i, the plane through
        // p and the edge, oriented toward corner i (σ · det[qⱼ − p, qₖ − p,
        // qᵢ − p] = σ², a cyclic shift of the rows). The edge's ends are
        // taken in a canonical order, so that the two triangles sharing an
        // edge cut their images along the same line, bit for bit.
        for (j, k) in [(1, 2), (2, 0), (0, 1)] {
            let (u, v, s) = if lexicographic(tri[j], tri[k]) {
                (tri[j], tri[k], sigma)
            } else {
                (tri[k], tri[j], -sigma)
            };
            // det[u − p, v − p, ·] = det[u − p, v − u, ·]: the edge's own
            // direction cancels far less than a second direction from p
            // (small or distant edges subtend small angles).
            let (ru, e) = (Row::diff(u, self.p), Row::diff(v, u));
            if !poly.clip_by(self.line(&ru, &e, &self.c), s) {
                return Polygon::Clipped(poly);
            }
        }
        // Strictly beyond the triangle's plane: σ · det[q₁ − q₀, q₂ − q₀,
        // x − q₀] > 0 (at x = p it is −σ).
        let (e1, e2) = (Row::diff(tri[1], tri[0]), Row::diff(tri[2], tri[0]));
        poly.clip_by(self.line(&e1, &e2, &Row::diff(self.center, tri[0])), sigma);
        Polygon::Clipped(poly)
    }
}

/// A corner's image on the fast path: inside the square within
/// [`TOLERANCE`], certainly outside it (or not between `p` and the light),
/// or not yet settled by rounded determinants.
enum Corner {
    At(DVec2),
    Outside,
    Unsure,
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

    /// Cuts the polygon by the half-plane `s · line ≥ 0` (`s = ±1`), or
    /// by a line that misses the square (`Err(inside)`: keep all or none);
    /// whether anything is left.
    fn clip_by(&mut self, line: Result<Line, bool>, s: f64) -> bool {
        match line {
            Ok(l) => self.clip(Line {
                a: s * l.a,
                b: s * l.b,
                c: s * l.c,
                err: l.err,
            }),
            Err(inside) => {
                if (s > 0.0) != inside {
                    self.len = 0;
                }
            }
        }
        self.len > 0
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
