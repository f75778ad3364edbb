//! The receiver view of a disk or rect ([`AreaView`]): each triangle
//! clipped to the part of space between the receiver and the light and
//! projected onto the light's plane ([`Image`]), and the area of the union
//! of those images within the light.

use super::bounded::{det3_exact, max_abs, Bounded, Cross, Row};
use super::union::{union_area, Measure, Tri};
use super::{Fraction, Scratch};
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, SQRT_2};

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
/// than `2⁻⁴³` of the light's radius (a receiver `10⁻¹⁷` from an edge, a
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
    /// The axes as rows, and their largest magnitudes.
    rows: [Row; 2],
    rows_max: [f64; 2],
    half: f64,
    measure: Measure,
    /// What projecting corners needs.
    direct: Direct,
    /// Whether a triangle wholly between `p` and the light whose corners
    /// project inside the square is taken as its projected corners.
    fast: bool,
}

/// The projection of a corner `q` (`d = q − p`) onto the light's plane: its
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
const TOLERANCE: f64 = 1.0 / (1u64 << 43) as f64;

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
        // Any finite non-zero normal, however long or short.
        let n = crate::kernel::eft::unit(normal)?;
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
        // Half-axes far from 1 (1e200, 1e-200: an area beyond `f64`) are
        // scaled by a common power of two `2^k` into `[1, 4)`, the map `M
        // = 2^k I` taking the scaled oblique coordinates back: every
        // product then stays in range, and both scalings are exact.
        let big = u.abs().max_element().max(v.abs().max_element());
        let (f, scale) = if (2f64.powi(-100)..=2f64.powi(100)).contains(&big) {
            ([u, v], 1.0)
        } else {
            let (_, k) =
                crate::kernel::eft::pow2_scaled(if big == u.abs().max_element() { u } else { v })?;
            let at = |w: DVec3| w.map(|x| crate::kernel::eft::times_pow2(x, k));
            ([at(u), at(v)], crate::kernel::eft::times_pow2(1.0, k))
        };
        Self::new(
            p,
            center,
            f,
            [scale, 0.0, scale],
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
        fast: bool,
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
        let mut depth = n.dot(c.r, max_abs(c.r));
        if depth.sign().is_none() {
            depth = det3_exact(&r0, &r1, &c);
        }
        if depth.value == 0.0 || !depth.value.is_finite() {
            return None;
        }
        let sgn = if depth.value > 0.0 { 1.0 } else { -1.0 };
        let direct = Direct {
            w: [Cross::of(f[1], c.r), Cross::of(f[0], c.r), n],
            sgn,
            depth: depth.signed(sgn),
        };
        Some(AreaView {
            p,
            center,
            c,
            f,
            m,
            inv,
            rows: [r0, r1],
            rows_max: [max_abs(f[0]), max_abs(f[1])],
            half,
            measure,
            direct,
            fast,
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
    ///
    /// The square is the light's own box (`|X|, |Y| ≤ 1`), widened by what
    /// the rounding of its corners (3D points, each within `2ε` of its
    /// magnitude) may move them, over the light's smallest height, in the
    /// view's units — so that a light of radius `10⁻⁶` at `10⁹` is held
    /// whole — and, for a disk, by `2⁻²⁰` more, the unit disk being the
    /// light only to the rounding of the view's map.
    #[must_use]
    pub fn hull(&self) -> [DVec3; 5] {
        let (center, e) = self.axes();
        let height = e[0].cross(e[1]).length() / e[0].length().max(e[1].length());
        let size = max_abs(center) + 2.0 * (max_abs(e[0]) + max_abs(e[1]));
        let rounding = 8.0 * f64::EPSILON * size / height;
        let h = match self.measure {
            Measure::Disk(r) => r * (1.0 + HULL_SLACK) + rounding,
            Measure::Square => 1.0 + rounding,
        };
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
        self.occluded::<false>(triangles, scratch).value
    }

    /// [`AreaView::occluded_fraction`] and a bound on its error
    /// ([module documentation](super#the-certified-bound)).
    #[must_use]
    pub fn occluded_fraction_bounded<'t>(
        &self,
        triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
        scratch: &mut Scratch,
    ) -> Fraction {
        self.occluded::<true>(triangles, scratch)
    }

    /// The occluded fraction, with its bound if `B`.
    fn occluded<'t, const B: bool>(
        &self,
        triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
        scratch: &mut Scratch,
    ) -> Fraction {
        // The generic loop is kept to a call per triangle, so that the work
        // is compiled once, here, not in every caller.
        scratch.triangles.clear();
        scratch.weights.clear();
        let mut extra = 0.0;
        for tri in triangles {
            if let Some(bound) = self.add_image::<B>(
                tri,
                &mut scratch.triangles,
                &mut scratch.weights,
                &mut extra,
            ) {
                // One image covers the whole light.
                let bound = bound / self.light_area() + 2.0 * f64::EPSILON;
                return Fraction { value: 1.0, bound };
            }
        }
        let (covered, bound) = union_area::<B>(
            &scratch.triangles,
            &scratch.weights,
            self.measure,
            self.half,
            &mut scratch.union,
        );
        let area = self.light_area();
        let value = (covered / area).clamp(0.0, 1.0);
        let bound = if B {
            // The union's bound and the images' extras in the view's area,
            // the division, and the frame: the disk in the view's
            // coordinates is the unit disk only to the rounding of the map
            // `M` (its entries within a few ulps), and a sphere's facing
            // disk turned by the rounding of its normal, each moving the
            // answer by a few ulps.
            (bound + extra) / area * (1.0 + 4.0 * f64::EPSILON)
                + 16.0 * f64::EPSILON * value.max(1e-300)
                + 2.0 * f64::EPSILON
        } else {
            0.0
        };
        Fraction { value, bound }
    }

    /// Appends the parts of the triangle's image that meet the light (and,
    /// if `B`, their edges' area allowances to `weights`, what is dropped
    /// of them to `extra`); `Some(bound)` when the image covers the whole
    /// light (checked on the convex image before it is split, so that a
    /// covering image ends the work however many images came before it),
    /// with a bound on the area it may leave uncovered.
    fn add_image<const B: bool>(
        &self,
        tri: &[DVec3; 3],
        out: &mut Vec<Tri>,
        weights: &mut Vec<[f64; 3]>,
        extra: &mut f64,
    ) -> Option<f64> {
        let measure = self.measure;
        let image = match self.polygon::<B>(tri) {
            // Without the bound, the corners go straight to a triangle.
            Polygon::Corners([a, b, c], _) if !B => {
                if let Some(t) = Tri::new(a, b, c) {
                    if measure.covered_by(&t) {
                        return Some(0.0);
                    }
                    if !measure.misses(&t) {
                        out.push(t);
                    }
                }
                return None;
            }
            Polygon::Corners([a, b, c], [ea, eb, ec]) => {
                Image::from_slice::<B>(&[a, b, c], &[ea, eb, ec])
            }
            Polygon::Clipped(image) => image,
        };
        let (v, w) = (image.vertices(), image.weights());
        if B {
            *extra += image.extra();
        }
        if measure.covered_by_convex(v) {
            // Covered but for what its edges' bands may leave: each band
            // within the light is at most its edge's allowance.
            return Some(if B { w.iter().sum::<f64>() } else { 0.0 });
        }
        let n = v.len();
        for k in 1..n.saturating_sub(1) {
            // The fan's diagonals are shared with the neighbouring pieces
            // of the same image: no allowance.
            let wk = [
                if k == 1 { w[0] } else { 0.0 },
                w[k],
                if k + 2 == n { w[n - 1] } else { 0.0 },
            ];
            let t = Tri::new(v[0], v[k], v[k + 1]);
            match t {
                Some(t) if !measure.misses(&t) => {
                    out.push(t);
                    if B {
                        // Oriented as given, or reversed (a, c, b).
                        weights.push(if t.first_edge_is(v[0], v[k]) {
                            wk
                        } else {
                            [wk[2], wk[1], wk[0]]
                        });
                    }
                }
                // Missing the light, or degenerate: what its edges' bands
                // may hold of the light, if it comes within their width of
                // the light's box (each allowance is at least twice the
                // width times the edge's length).
                _ if B => {
                    let (p, q, r) = (v[0], v[k], v[k + 1]);
                    let width = [(p, q, wk[0]), (q, r, wk[1]), (r, p, wk[2])]
                        .iter()
                        .map(|&(a, b, w)| w / (2.0 * (b - a).length()))
                        .fold(0.0_f64, |m, x| if x.is_nan() { m } else { m.max(x) });
                    let (lo, hi) = (p.min(q).min(r), p.max(q).max(r));
                    let reach = measure.radius() + width;
                    if lo.cmplt(DVec2::splat(reach)).all() && hi.cmpgt(DVec2::splat(-reach)).all() {
                        *extra += wk.iter().sum::<f64>();
                    }
                }
                _ => {}
            }
        }
        None
    }

    /// The image of a triangle on the light's plane: the light points it
    /// hides from `p` form the image's interior intersected with the light.
    /// Cut to the square `|X|, |Y| ≤ half` around the light (`half` is 1.5
    /// for a disk, 1 for a rect), counter-clockwise; empty when the
    /// triangle hides nothing there (it lies behind `p` or beyond the light,
    /// its plane holds `p`, or it has a non-finite corner).
    #[must_use]
    pub fn image(&self, tri: &[DVec3; 3]) -> Image {
        match self.polygon::<true>(tri) {
            Polygon::Corners([a, b, c], [ea, eb, ec]) => match orient2d(a, b, c) {
                Sign::Positive => Image::from_slice::<true>(&[a, b, c], &[ea, eb, ec]),
                Sign::Negative => Image::from_slice::<true>(&[a, c, b], &[ea, ec, eb]),
                Sign::Zero => Image::EMPTY,
            },
            Polygon::Clipped(image) => image,
        }
    }

    /// One corner's image (`d` its row from `p`) and a bound on its error,
    /// if the corner lies certainly in front of `p`, and its depth's
    /// rounded value (`sgn · det[d, f₀, f₁]`, with its bound): the point
    /// where the ray from `p` through the corner meets the plane, within
    /// [`TOLERANCE`] where it lies in the square (exact determinants where
    /// the rounded ones are not that close). With `refine` false, the
    /// rounded image only (`exact` false where it is not within the
    /// tolerance, or its depth is uncertain).
    #[inline(always)]
    fn corner<const B: bool>(&self, d: &Row, refine: bool) -> CornerImage {
        let direct = &self.direct;
        let [wx, wy, wz] = direct.w;
        let d_max = max_abs(d.r);
        let z = wz.dot(d.r, d_max).signed(direct.sgn);
        let (nx, ny) = (wx.dot(d.r, d_max), wy.dot(d.r, d_max));
        let first = self.corner_from(nx, ny, z);
        let settled = match first {
            Some((q, err)) => err <= TOLERANCE || q.abs().max_element() - err > self.half,
            None => false,
        };
        if settled || !refine {
            // Decided on the cheap bounds; the bound reports the closer ones.
            let at = match first {
                Some((q, _)) if B => {
                    let closer = |w: &Cross, b: Bounded| Bounded {
                        bound: w.precise(d.r),
                        ..b
                    };
                    let z = closer(&wz, z);
                    self.corner_from(closer(&wx, nx), closer(&wy, ny), z)
                        .map(|(_, err)| (q, err))
                        .or(first)
                }
                _ => first,
            };
            return CornerImage { at, z, settled };
        }
        let (c, f0, f1) = (&self.c, &self.rows[0], &self.rows[1]);
        let z = det3_exact(d, f0, f1).signed(direct.sgn);
        let at = self.corner_from(det3_exact(c, d, f1), det3_exact(c, d, f0), z);
        // Beyond the exact arithmetic's range, the rounded image.
        CornerImage {
            at: at.or(first),
            z,
            settled: true,
        }
    }

    /// The corner's image from the determinants `nx = det[c, d, f₁]`, `ny
    /// = det[c, d, f₀]` and its depth `z = sgn · det[d, f₀, f₁]`, with a
    /// bound on its error; `None` unless `z` is certainly positive (above
    /// twice its bound).
    #[inline(always)]
    fn corner_from(&self, nx: Bounded, ny: Bounded, z: Bounded) -> Option<(DVec2, f64)> {
        if z.value <= 2.0 * z.bound || z.value.is_nan() {
            return None;
        }
        let sz = self.direct.sgn / z.value;
        let (x, y) = (nx.value * sz, -ny.value * sz);
        let [m00, m01, m11] = self.m;
        let q = DVec2::new(m00 * x + m01 * y, m11 * y);
        // First order in the determinants' bounds (z's bound is below half
        // of z, so the quotient's relative error is below twice it), and
        // the roundings of the quotients and the map.
        let rel = z.bound / (z.value - z.bound);
        let ex = (nx.bound * sz.abs() + x.abs() * rel) * 1.01 + x.abs() * f64::EPSILON;
        let ey = (ny.bound * sz.abs() + y.abs() * rel) * 1.01 + y.abs() * f64::EPSILON;
        let err = (m00.abs() * ex + m01.abs() * ey).max(m11.abs() * ey)
            + 2.0 * f64::EPSILON * q.abs().max_element();
        (q.is_finite() && err.is_finite()).then_some((q, err))
    }

    /// The half-plane of light points `x` with `det[u, v, x − o] ≥ 0`
    /// (rows `u`, `v` relative to `o`, `center_o` the row `center − o`),
    /// with coefficients within [`TOLERANCE`] (exact determinants where
    /// the rounded ones are not), or `Err` when its line certainly misses
    /// the square (then the square lies wholly on one side; `Err(true)`
    /// inside).
    fn line<const B: bool>(&self, u: &Row, v: &Row, center_o: &Row) -> Result<Line, bool> {
        let mut cross = Cross::of(u.r, v.r);
        if cross.cancels() {
            cross = Cross::compensated(u, v);
        }
        let [f0, f1] = &self.rows;
        let [m0, m1] = self.rows_max;
        let (a, b, c) = (
            cross.dot(f0.r, m0),
            cross.dot(f1.r, m1),
            cross.dot(center_o.r, max_abs(center_o.r)),
        );
        let line = self.in_view(a, b, c);
        if let Some(settled) = self.settled(line) {
            // Decided on the cheap bounds; the bound reports the closer ones.
            return match settled {
                Ok(line) if B => Ok(Line {
                    err: self
                        .in_view(
                            Bounded {
                                bound: cross.precise(f0.r),
                                ..a
                            },
                            Bounded {
                                bound: cross.precise(f1.r),
                                ..b
                            },
                            Bounded {
                                bound: cross.precise(center_o.r),
                                ..c
                            },
                        )
                        .err,
                    ..line
                }),
                other => other,
            };
        }
        let exact = self.in_view(
            det3_exact(u, v, f0),
            det3_exact(u, v, f1),
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

    /// Whether the half-plane `s · line ≥ 0` (`s = ±1`) certainly leaves
    /// out the whole light (the unit disk, or the square `[−1, 1]²`) by more
    /// than [`MISS_MARGIN`]: then the triangle's image hides none of it, and
    /// its clipping is skipped. The largest value of `s · line` over the
    /// light (`s c + |(a, b)|` on the disk, `s c + |a| + |b|` on the
    /// square), rounded up, plus the line's own error (within `err ·
    /// max(|a|, |b|)` of the exact line's values over the square), below
    /// minus the margin. Most images of a frame that are clipped at all lie
    /// beside the light (culling keeps whatever meets the pyramid over the
    /// square `|X|, |Y| ≤ half`).
    #[inline(always)]
    fn excludes_light(&self, line: &Result<Line, bool>, s: f64) -> bool {
        let line = match line {
            Ok(line) => line,
            // The line misses the square: all or nothing of it is kept.
            &Err(inside) => return (s > 0.0) != inside,
        };
        let (a, b) = (line.a.abs(), line.b.abs());
        let reach = match self.measure {
            Measure::Disk(r) => r * a.hypot(b),
            Measure::Square => a + b,
        };
        let top = s * line.c + reach;
        let rounding = 4.0 * f64::EPSILON * (line.c.abs() + reach);
        top + rounding + 2.0 * (line.err + MISS_MARGIN) * a.max(b) < 0.0
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
    fn polygon<const B: bool>(&self, tri: &[DVec3; 3]) -> Polygon {
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
        // The fast path: every corner certainly between p and the light's
        // plane and inside the square. Its corners' images serve the
        // clipped path too (where two cone planes meet, at a corner).
        // The corners' images, settled (within the tolerance, or refined)
        // or not yet.
        let mut corners: [Option<Option<(DVec2, f64)>>; 3] = [None; 3];
        let depth = self.direct.depth;
        let mut fast = self.fast;
        for (k, &v) in tri.iter().enumerate() {
            if !fast {
                break;
            }
            let d = Row::diff(v, self.p);
            // Rounded first: a corner near p's depth, or outside the
            // square, ends the fast path without being refined (the
            // clipped path asks for it only if two cone planes meet there).
            let mut corner = self.corner::<B>(&d, false);
            let plausible = |c: &CornerImage| {
                let before = depth.value - c.z.value
                    > (depth.bound + c.z.bound) * 1.01 + f64::EPSILON * depth.value;
                before
                    && c.at.is_some_and(|(q, err)| {
                        q.x.abs() + err.min(1.0) < self.half && q.y.abs() + err.min(1.0) < self.half
                    })
            };
            if !corner.settled && corner.at.is_some() && plausible(&corner) {
                corner = self.corner::<B>(&d, true);
            }
            fast = corner.settled && plausible(&corner) && {
                let (q, err) = corner.at.expect("plausible");
                q.x.abs() + err < self.half && q.y.abs() + err < self.half
            };
            if corner.settled {
                corners[k] = Some(corner.at);
            }
        }
        if fast {
            let at = corners.map(|c| c.flatten().expect("every corner projected"));
            return Polygon::Corners(at.map(|a| a.0), at.map(|a| a.1));
        }
        // The cone: for the edge (j, k) opposite corner i, the plane through
        // p and the edge, oriented toward corner i (σ · det[qⱼ − p, qₖ − p,
        // qᵢ − p] = σ², a cyclic shift of the rows). The edge's ends are
        // taken in a canonical order, so that the two triangles sharing an
        // edge cut their images along the same line, bit for bit.
        let mut lines = [(Err(true), 0.0); 4];
        for (i, (j, k)) in [(1, 2), (2, 0), (0, 1)].into_iter().enumerate() {
            let (u, v, s) = if lexicographic(tri[j], tri[k]) {
                (tri[j], tri[k], sigma)
            } else {
                (tri[k], tri[j], -sigma)
            };
            // det[u − p, v − p, ·] = det[u − p, v − u, ·]: the edge's own
            // direction cancels far less than a second direction from p
            // (small or distant edges subtend small angles).
            let (ru, e) = (Row::diff(u, self.p), Row::diff(v, u));
            let line = self.line::<B>(&ru, &e, &self.c);
            if self.excludes_light(&line, s) {
                return Polygon::Clipped(Image::EMPTY);
            }
            lines[i] = (line, s);
        }
        // Strictly beyond the triangle's plane: σ · det[q₁ − q₀, q₂ − q₀,
        // x − q₀] > 0 (at x = p it is −σ).
        let (e1, e2) = (Row::diff(tri[1], tri[0]), Row::diff(tri[2], tri[0]));
        let line = self.line::<B>(&e1, &e2, &Row::diff(self.center, tri[0]));
        if self.excludes_light(&line, sigma) {
            return Polygon::Clipped(Image::EMPTY);
        }
        lines[3] = (line, sigma);
        // Every line leaves some of the light: cut the square by each.
        let mut clip = Clip::new(self.half, self.measure);
        for (i, &(line, s)) in lines[..3].iter().enumerate() {
            if !clip.cut(On::Cone(i as u8), line, s, |corner| {
                *corners[corner].get_or_insert_with(|| {
                    self.corner::<B>(&Row::diff(tri[corner], self.p), true).at
                })
            }) {
                return Polygon::Clipped(clip.finish::<B>());
            }
        }
        let (line, s) = lines[3];
        clip.cut(On::Plane, line, s, |_| None);
        Polygon::Clipped(clip.finish::<B>())
    }
}

/// How much wider than a disk light's box (relative) the culling pyramid
/// is ([`AreaView::hull`]).
const HULL_SLACK: f64 = 1.0 / (1u64 << 20) as f64;

/// How far (in the view's coordinates) a half-plane must leave out the
/// whole light for [`AreaView::excludes_light`] to skip the triangle: far
/// beyond any vertex's error, so that nothing the clipping would have kept
/// can lie in the light.
const MISS_MARGIN: f64 = 1.0 / (1u64 << 20) as f64;

/// The largest error, in half-widths of the square, of a vertex computed
/// from its two lines alone (beyond it, as where two lines are nearly
/// parallel, the vertex is the crossing on the edge being cut).
const WELL_PLACED: f64 = 1.0 / (1u64 << 30) as f64;

/// A corner's image, if it lies certainly in front of `p`, with its error
/// bound; its depth `sgn · det[d, f₀, f₁]`; and whether the image is
/// settled (within the tolerance, certainly outside the square, or
/// refined).
#[derive(Clone, Copy, Debug)]
struct CornerImage {
    at: Option<(DVec2, f64)>,
    z: Bounded,
    settled: bool,
}

/// The line a clipped image's edge lies on: a side of the square (bottom,
/// right, top, left), the plane through `p` and the edge opposite a corner,
/// or the triangle's own plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum On {
    Side(u8),
    Cone(u8),
    Plane,
}

/// The square cut by half-planes, each vertex computed from the two lines
/// it lies on — a line and a side of the square from the line's
/// coefficients, two planes through `p` at their common corner's image —
/// never from the segment being cut, so that two triangles sharing an edge
/// (the same line, bit for bit) and a corner get the same vertices: their
/// shared edges are exactly reverse and drop out of the union. Each vertex
/// carries a bound on its error.
struct Clip {
    image: Image,
    /// The line of the edge from each vertex to the next.
    on: [On; Image::CAP],
    /// The lines cut by so far (cone planes 0–2, the plane 3).
    lines: [Option<Line>; 4],
    half: f64,
    /// The light in the view's coordinates: a disk of this radius, or
    /// (`None`) the square `[−1, 1]²`.
    disk: Option<f64>,
    /// The allowance of a thin image within its lines' errors of being
    /// cut away whole (see [`Image::extra`]).
    extra: f64,
}

impl Clip {
    fn new(h: f64, measure: Measure) -> Clip {
        let z = DVec2::ZERO;
        let image = Image {
            v: [
                DVec2::new(-h, -h),
                DVec2::new(h, -h),
                DVec2::new(h, h),
                DVec2::new(-h, h),
                z,
                z,
                z,
                z,
            ],
            len: 4,
            ..Image::EMPTY
        };
        let mut on = [On::Plane; Image::CAP];
        on[..4].copy_from_slice(&[On::Side(0), On::Side(1), On::Side(2), On::Side(3)]);
        Clip {
            image,
            on,
            lines: [None; 4],
            half: h,
            disk: match measure {
                Measure::Disk(r) => Some(r),
                Measure::Square => None,
            },
            extra: 0.0,
        }
    }

    /// Cuts by the half-plane `s · line ≥ 0` (`s = ±1`), or by a line that
    /// misses the square (`Err(inside)`: keep all or none); whether
    /// anything is left. `corner(k)` is the image of the triangle's corner
    /// `k` (where two cone planes meet), if it lies in front of `p`.
    /// Sutherland–Hodgman: nothing is left when no vertex is strictly
    /// inside (the rest has no area: a triangle lying in the light's own
    /// plane hides nothing, as the open segment says).
    fn cut(
        &mut self,
        id: On,
        line: Result<Line, bool>,
        s: f64,
        mut corner: impl FnMut(usize) -> Option<(DVec2, f64)>,
    ) -> bool {
        let line = match line {
            Ok(l) => Line {
                a: s * l.a,
                b: s * l.b,
                c: s * l.c,
                err: l.err,
            },
            Err(inside) => {
                if (s > 0.0) != inside {
                    self.image.len = 0;
                }
                return self.image.len > 0;
            }
        };
        let slot = match id {
            On::Cone(i) => usize::from(i),
            _ => 3,
        };
        self.lines[slot] = Some(line);
        let n = self.image.len;
        let mut f = [0.0; Image::CAP];
        let (mut any_in, mut all_in) = (false, true);
        for (fk, &v) in f.iter_mut().zip(&self.image.v[..n]) {
            *fk = line.at(v);
            any_in |= *fk > 0.0;
            all_in &= *fk >= 0.0;
        }
        if !any_in {
            // The exact image may still be a sliver within the lines'
            // errors of the vertices left.
            let norm = line.a.abs().max(line.b.abs());
            let (most, err) = (0..n).fold((f64::NEG_INFINITY, 0.0_f64), |(m, e), k| {
                (m.max(f[k] / norm), e.max(self.image.err[k]))
            });
            if most > -(line.err + err) * 2.0 {
                let band = self.band(&self.image.v[..n], &line, 1.0, line.err, err);
                self.extra += band.min(self.wedge(slot, &line, 1.0, 0.0));
            }
            self.image.len = 0;
            return false;
        }
        if all_in {
            return true;
        }
        // The new polygon, into local arrays (copied back at the end).
        let mut v = [DVec2::ZERO; Image::CAP];
        let mut errs = [0.0; Image::CAP];
        let mut on = [On::Plane; Image::CAP];
        let mut len = 0;
        let mut push = |q: DVec2, err: f64, id: On| {
            if len < Image::CAP {
                (v[len], errs[len], on[len]) = (q, err, id);
                len += 1;
            }
        };
        for k in 0..n {
            // The next vertex, without a division.
            let j = if k + 1 == n { 0 } else { k + 1 };
            let (fa, fb) = (f[k], f[j]);
            if fa >= 0.0 {
                push(self.image.v[k], self.image.err[k], self.on[k]);
            }
            if (fa > 0.0 && fb < 0.0) || (fa < 0.0 && fb > 0.0) {
                let (a, b) = (self.image.v[k], self.image.v[j]);
                let (mut q, mut err) = self.meet(id, self.on[k], &mut corner);
                // Where the two lines are so nearly parallel (or the
                // corner so ill-placed) that their meeting point falls off
                // the edge being cut, the crossing on the edge: within its
                // ends' and the line's errors over the sine of the angle,
                // and the edge's length.
                let (lo, hi) = (a.min(b), a.max(b));
                let slack = WELL_PLACED * self.half;
                let on_edge = q.cmpge(lo - slack).all() && q.cmple(hi + slack).all();
                if !(err <= slack && on_edge) {
                    q = crossing(a, fa, b, fb);
                    err = err.min(
                        (b - a).abs().max_element() + self.image.err[k].max(self.image.err[j]),
                    );
                }
                // Leaving: the boundary follows the new line; entering: the
                // rest of the edge.
                push(q, err, if fa > 0.0 { id } else { self.on[k] });
            }
        }
        self.image.v[..len].copy_from_slice(&v[..len]);
        self.image.err[..len].copy_from_slice(&errs[..len]);
        self.on[..len].copy_from_slice(&on[..len]);
        self.image.len = len;
        len >= 3
    }

    /// The image with each vertex's distance from its edges' computed
    /// lines (a posteriori, in place of the construction's errors), and
    /// each edge's area allowance: an edge on a line whose error is `δ`
    /// (a side of the square: 0), its ends within `ρ` of their lines, lies
    /// within `δ + ρ` of the exact image's edge on that line, which may run
    /// on past either end by `(δ_in + δ_out + 2ρ) / sin θ` (`θ` the angle of
    /// the two lines there, at most the square's diagonal): a band of twice
    /// `δ + ρ` along that length holds what the two images differ by near
    /// the edge. A line passing within its error of a vertex without
    /// cutting the image adds a band along the square's diagonal
    /// ([`Image::extra`]).
    fn finish<const B: bool>(mut self) -> Image {
        let n = self.image.len;
        let mut image = self.image;
        image.extra = self.extra;
        if n < 3 {
            image.len = 0;
            return image;
        }
        if !B {
            return image;
        }
        let diagonal = 2.0 * SQRT_2 * self.half;
        let line = |id: On| match id {
            On::Cone(i) => self.lines[usize::from(i)],
            On::Plane => self.lines[3],
            On::Side(_) => None,
        };
        // Per edge: its line, the line's error and normal.
        let mut lines = [None; Image::CAP];
        let mut delta = [0.0; Image::CAP];
        let mut normal = [DVec2::ZERO; Image::CAP];
        for k in 0..n {
            let id = self.on[k];
            lines[k] = line(id);
            (delta[k], normal[k]) = match (id, lines[k]) {
                (On::Side(0 | 2), _) => (0.0, DVec2::Y),
                (On::Side(_), _) => (0.0, DVec2::X),
                (_, Some(l)) => (l.err, DVec2::new(l.a, l.b)),
                (_, None) => (0.0, DVec2::ZERO),
            };
        }
        // On a side, a vertex is exactly on it (its coordinate ±half is
        // kept exactly by every construction).
        let dist = |q: DVec2, l: &Option<Line>| l.as_ref().map_or(0.0, |l| distance(l, q));
        let prev = |k: usize| if k == 0 { n - 1 } else { k - 1 };
        let mut rho = [0.0; Image::CAP];
        for (k, (r, &q)) in rho.iter_mut().zip(&image.v[..n]).enumerate() {
            *r = dist(q, &lines[prev(k)]).max(dist(q, &lines[k]));
        }
        let mut ext = [0.0; Image::CAP];
        for k in 0..n {
            let (a, b) = (prev(k), k);
            let (na, nb) = (normal[a], normal[b]);
            let sin = na.perp_dot(nb).abs() / (na.length() * nb.length());
            let e = (delta[a] + delta[b] + 2.0 * rho[k]) / sin;
            ext[k] = if e < diagonal { e } else { diagonal };
        }
        for k in 0..n {
            let j = if k + 1 == n { 0 } else { k + 1 };
            image.err[k] = rho[k];
            image.w[k] = match self.on[k] {
                On::Side(_) => 0.0,
                _ => {
                    let width = delta[k] + rho[k].max(rho[j]);
                    let length = (image.v[j] - image.v[k]).length() + ext[k] + ext[j];
                    2.0 * width
                        * length.min(diagonal + ext[k] + ext[j])
                        * (1.0 + 8.0 * f64::EPSILON)
                }
            };
        }
        let most_rho = rho[..n].iter().fold(0.0_f64, |m, &r| m.max(r));
        for (slot, l) in self.lines.iter().enumerate() {
            let Some(l) = l else { continue };
            let id = if slot == 3 {
                On::Plane
            } else {
                On::Cone(slot as u8)
            };
            if self.on[..n].contains(&id) {
                continue;
            }
            let near = image.v[..n]
                .iter()
                .map(|&q| {
                    let norm = l.a.abs().max(l.b.abs());
                    let terms = (l.a * q.x).abs() + (l.b * q.y).abs() + l.c.abs();
                    (l.at(q) - 4.0 * f64::EPSILON * terms) / norm
                })
                .fold(f64::INFINITY, f64::min);
            if near < (l.err + most_rho) * 2.0 {
                let band = self.band(&image.v[..n], l, -1.0, l.err, most_rho);
                image.extra += band.min(self.wedge(slot, l, -1.0, most_rho));
            }
        }
        self.image = image;
        self.image
    }

    /// The area the exact image may differ by near a line that the
    /// convex polygon `v` (vertices within `e` of the exact ones) lies
    /// within `2(δ + e)` of without being cut by it (`σ = 1`: `v` on the
    /// line's negative side, the image may be a sliver across it; `σ = −1`:
    /// `v` on its positive side, the exact line may cut a sliver off), the
    /// line within `δ` of the exact one over the square: a band of width
    /// `2(δ + e)` along the part `Q` of `v` where `σ · line ≥ −2(δ + e)`
    /// (in units of its larger coefficient), that part grown by `e`;
    /// nothing where `Q` so grown misses the light. `Q` lies in the box of
    /// the vertices in that slab and the edges' crossings of its side,
    /// each crossing within the rounding of its parameter (the lines'
    /// values are within `4u` of their terms, as in [`distance`]).
    fn band(&self, v: &[DVec2], line: &Line, sigma: f64, delta: f64, e: f64) -> f64 {
        const U4: f64 = 4.0 * f64::EPSILON;
        let level = -2.0 * (delta + e);
        let norm = line.a.abs().max(line.b.abs());
        let value = |q: DVec2| {
            let terms = (line.a * q.x).abs() + (line.b * q.y).abs() + line.c.abs();
            (sigma * line.at(q) / norm, U4 * terms / norm)
        };
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        let mut margin = 0.0_f64;
        let n = v.len();
        for k in 0..n {
            let j = if k + 1 == n { 0 } else { k + 1 };
            let ((ga, ea), (gb, eb)) = (value(v[k]), value(v[j]));
            let (a_in, b_in) = (ga >= level - ea, gb >= level - eb);
            if a_in {
                (lo, hi) = (lo.min(v[k]), hi.max(v[k]));
            }
            if a_in != b_in {
                // The crossing of the slab's side, from the end inside.
                let ((a, ga), (b, gb)) = if a_in {
                    ((v[k], ga), (v[j], gb))
                } else {
                    ((v[j], gb), (v[k], ga))
                };
                let t = ((ga - level) / (ga - gb)).clamp(0.0, 1.0);
                let q = a + (b - a) * t;
                let dt = (ea + eb) / (ga - gb).abs() + U4;
                (lo, hi) = (lo.min(q), hi.max(q));
                margin = margin.max((b - a).length() * dt + U4 * q.abs().max_element());
            }
        }
        let diagonal = 2.0 * SQRT_2 * self.half;
        let width = 2.0 * (delta + e);
        let grow = DVec2::splat(e + margin);
        let (lo, hi) = (lo - grow, hi + grow);
        if !(lo.x <= hi.x && lo.y <= hi.y && margin.is_finite()) {
            // No box (values not finite): the band along the whole square.
            return width * diagonal;
        }
        let misses = match self.disk {
            Some(r) => DVec2::ZERO.clamp(lo, hi).length() > r * (1.0 + U4),
            None => lo.x > 1.0 || lo.y > 1.0 || hi.x < -1.0 || hi.y < -1.0,
        };
        if misses {
            return 0.0;
        }
        width * (hi - lo).length().min(diagonal) * (1.0 + U4)
    }

    /// A second bound on the area of [`Clip::band`]'s sliver, from the
    /// lines alone (the vertices' errors left out, which are large where
    /// nearly parallel lines meet): the sliver lies where `σ · line ≥ −(δ
    /// + e)` and, for every other line cut by, `line_j ≥ −(δ_j + e)` (`e`
    /// the computed vertices' distance from their lines, 0 for the exact
    /// image) — for one other line nearly opposite to this one, a wedge
    /// whose width `A + B t` is linear along the line; its area over the
    /// light's circumscribed disk (radius `ρ`: `|t| ≤ ρ`) is the integral
    /// of `max(0, A + B t)`. The least over the other lines; infinite where
    /// none is nearly opposite. The rounding of the normalised lines
    /// (a few ulps of each term) is added to `A`.
    fn wedge(&self, slot: usize, line: &Line, sigma: f64, e: f64) -> f64 {
        const SLACK: f64 = 64.0 * f64::EPSILON;
        let rho = match self.disk {
            Some(r) => r,
            None => SQRT_2,
        };
        let unit = |l: &Line, s: f64| {
            let h = l.a.hypot(l.b);
            (DVec2::new(s * l.a / h, s * l.b / h), s * l.c / h)
        };
        let (n, c) = unit(line, sigma);
        let delta = line.err + e;
        let mut least = f64::INFINITY;
        for (j, other) in self.lines.iter().enumerate() {
            let Some(other) = other.filter(|_| j != slot) else {
                continue;
            };
            let (m, d) = unit(&other, 1.0);
            // m = μ n + ν n⊥; x = s n + t n⊥: s ≥ −c − δ and
            // μ s + ν t ≥ −d − δⱼ, so for μ < 0 the width in s is
            // (d + δⱼ + ν t) / (−μ) + c + δ.
            let (mu, nu) = (m.dot(n), -m.perp_dot(n));
            if !(mu < -0.5) {
                continue;
            }
            let dj = other.err + e;
            let a = (d + dj) / -mu + c + delta;
            let b = nu / -mu;
            let slack = SLACK * ((d.abs() + dj) / -mu + c.abs() + delta + rho * (1.0 + b.abs()));
            let a = a + slack;
            let (y0, y1) = (a - b * rho, a + b * rho);
            let area = if y0 <= 0.0 && y1 <= 0.0 {
                0.0
            } else if y0 >= 0.0 && y1 >= 0.0 {
                2.0 * rho * a
            } else {
                y0.max(y1).powi(2) / (2.0 * b.abs())
            };
            if area.is_finite() {
                least = least.min(area * (1.0 + SLACK));
            }
        }
        least
    }

    /// The point where the lines `l` and `e` meet, and a bound on its
    /// error, from the two lines alone.
    fn meet(
        &self,
        l: On,
        e: On,
        corner: &mut impl FnMut(usize) -> Option<(DVec2, f64)>,
    ) -> (DVec2, f64) {
        let line = |id: On| match id {
            On::Cone(i) => self.lines[usize::from(i)],
            On::Plane => self.lines[3],
            On::Side(_) => None,
        };
        match (l, e) {
            (On::Side(s), other) | (other, On::Side(s)) => match line(other) {
                Some(m) => side_crossing(&m, s, self.half),
                // Two sides meet at a corner of the square.
                None => (square_corner(l, e, self.half), 0.0),
            },
            (On::Cone(i), On::Cone(j)) => {
                // The planes through p and two edges meet along the ray
                // through their common corner.
                let k = 3 - usize::from(i) - usize::from(j);
                match corner(k) {
                    Some(at) => at,
                    None => cramer(&line(l).expect("cut"), &line(e).expect("cut")),
                }
            }
            _ => cramer(&line(l).expect("cut"), &line(e).expect("cut")),
        }
    }
}

/// The area allowance of an edge between two corners' images, each within
/// its error of the exact one: the exact edge lies within the larger error
/// of this one, so the two images differ along it by at most a band of
/// twice that width.
fn corner_edge_weight(a: DVec2, b: DVec2, ea: f64, eb: f64) -> f64 {
    2.0 * ea.max(eb) * (b - a).length() * (1.0 + 4.0 * f64::EPSILON)
}

/// A bound on the distance from `q` to the line: the rounded value over
/// the larger coefficient (at most the gradient's length), its rounding
/// included.
fn distance(line: &Line, q: DVec2) -> f64 {
    let norm = line.a.abs().max(line.b.abs());
    let terms = (line.a * q.x).abs() + (line.b * q.y).abs() + line.c.abs();
    ((line.at(q).abs() + 4.0 * f64::EPSILON * terms) / norm) * (1.0 + 4.0 * f64::EPSILON)
}

/// Where the line crosses side `s` of the square `|X|, |Y| ≤ h` (bottom,
/// right, top, left), from its coefficients alone (the same bits for the
/// line negated), clamped to the side; and a bound on its error: the
/// line's own moved along the side (by `|(a, b)| / |b|` for a vertical
/// side), and the rounding of the quotient.
fn side_crossing(m: &Line, s: u8, h: f64) -> (DVec2, f64) {
    let (fixed, along_x) = match s {
        0 => (-h, true),
        1 => (h, false),
        2 => (h, true),
        _ => (-h, false),
    };
    // On a horizontal side y = fixed: x = −(b·fixed + c) / a; on a vertical
    // one x = fixed: y = −(a·fixed + c) / b.
    let (num, den, across) = if along_x {
        (m.b * fixed + m.c, m.a, m.b)
    } else {
        (m.a * fixed + m.c, m.b, m.a)
    };
    let t = (-num / den).clamp(-h, h);
    let err = m.err * (den.abs() + across.abs()) / den.abs()
        + 2.0 * f64::EPSILON * ((across * fixed).abs() + m.c.abs()) / den.abs()
        + f64::EPSILON * t.abs();
    let q = if along_x {
        DVec2::new(t, fixed)
    } else {
        DVec2::new(fixed, t)
    };
    (q, if err.is_finite() { err } else { f64::INFINITY })
}

/// The corner of the square where the sides `l` and `e` meet.
fn square_corner(l: On, e: On, h: f64) -> DVec2 {
    let mut q = DVec2::ZERO;
    for id in [l, e] {
        match id {
            On::Side(0) => q.y = -h,
            On::Side(1) => q.x = h,
            On::Side(2) => q.y = h,
            On::Side(3) => q.x = -h,
            _ => {}
        }
    }
    q
}

/// Where two lines meet (Cramer's rule), and a bound on its error: the
/// lines' own over the sine of their angle, and the roundings of the
/// three 2×2 determinants.
fn cramer(l1: &Line, l2: &Line) -> (DVec2, f64) {
    let det = l1.a * l2.b - l2.a * l1.b;
    let q = DVec2::new(
        (l1.b * l2.c - l2.b * l1.c) / det,
        (l1.c * l2.a - l2.c * l1.a) / det,
    );
    let n1 = l1.a.abs() + l1.b.abs();
    let n2 = l2.a.abs() + l2.b.abs();
    let perm = (l1.a * l2.b).abs() + (l2.a * l1.b).abs();
    let err = (l1.err + l2.err) * n1 * n2 / det.abs()
        + 4.0
            * f64::EPSILON
            * ((l1.b * l2.c).abs()
                + (l2.b * l1.c).abs()
                + (l1.c * l2.a).abs()
                + (l2.c * l1.a).abs()
                + q.abs().max_element() * perm)
            / det.abs();
    if q.is_finite() && err.is_finite() {
        (q, err)
    } else {
        (DVec2::ZERO, f64::INFINITY)
    }
}

/// A triangle's image before it is handed out: the fast path's corners (in
/// either orientation) or the clipped polygon.
enum Polygon {
    /// The corners' images and their error bounds.
    Corners([DVec2; 3], [f64; 3]),
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
    /// A bound on each vertex's distance from the lines of its two edges
    /// as computed (the lines' own errors apart).
    err: [f64; Image::CAP],
    /// Per edge (from each vertex to the next), a bound on the area by
    /// which the exact image differs from this one along it
    /// ([`AreaView::image_weights`]).
    w: [f64; Image::CAP],
    /// A bound on the area the exact image may hold beyond all edges'
    /// (lines passing within their error of a vertex without cutting).
    extra: f64,
    len: usize,
}

impl Image {
    const CAP: usize = 8;
    const EMPTY: Image = Image {
        v: [DVec2::ZERO; Image::CAP],
        err: [0.0; Image::CAP],
        w: [0.0; Image::CAP],
        extra: 0.0,
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

    fn from_slice<const B: bool>(v: &[DVec2], err: &[f64]) -> Image {
        let mut image = Image::EMPTY;
        let n = v.len();
        image.v[..n].copy_from_slice(v);
        image.err[..n].copy_from_slice(err);
        if B {
            for k in 0..n {
                let j = (k + 1) % n;
                image.w[k] = corner_edge_weight(v[k], v[j], err[k], err[j]);
            }
        }
        image.len = n;
        image
    }
}

/// The point where the segment `a b` crosses a line with values `fa`,
/// `fb` of strictly opposite signs at its ends; symmetric in its
/// arguments. Measured from the end nearer the line (`t ≤ ½`), so that the
/// rounding is relative to the distance from that end.
fn crossing(a: DVec2, fa: f64, b: DVec2, fb: f64) -> DVec2 {
    let (a, fa, b, fb) = if fa.abs() <= fb.abs() {
        (a, fa, b, fb)
    } else {
        (b, fb, a, fa)
    };
    let t = (fa / (fa - fb)).clamp(0.0, 1.0);
    a + (b - a) * t
}
