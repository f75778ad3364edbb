//! The receiver view of a disk or rect ([`AreaView`]): each triangle
//! clipped to the part of space between the receiver and the light and
//! projected onto the light's plane ([`Image`]), and the area of the union
//! of those images within the light.

mod clip;
mod image;
mod project;

use crate::kernel::receiver_view::bounded::{det3_exact, max_abs, Bounded, Cross, Row};
use crate::kernel::receiver_view::union::{union_area, Measure, Tri, SWEEP_FROM};
use crate::kernel::receiver_view::{Fraction, Scratch};
use glam::DVec3;
pub use image::Image;
use image::Polygon;
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
    /// defined; [`Disk::seen_from`](crate::kernel::light::Disk::seen_from) refuses
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
        let (mut extra, mut reach) = (0.0, 0.0);
        for tri in triangles {
            if let Some(bound) = self.add_image::<B>(
                tri,
                &mut scratch.triangles,
                &mut scratch.weights,
                (&mut extra, &mut reach),
            ) {
                // One image covers the whole light.
                let bound = bound / self.light_area() + 2.0 * f64::EPSILON;
                return Fraction { value: 1.0, bound };
            }
        }
        let (covered, bound) = union_area::<B>(
            &scratch.triangles,
            &scratch.weights,
            reach,
            self.measure,
            self.half,
            &mut scratch.union,
            SWEEP_FROM,
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
    /// of them to `extra`, and the image's [reach](Image::reach) to the
    /// largest of those appended, `reach`); `Some(bound)` when the image covers the whole
    /// light (checked on the convex image before it is split, so that a
    /// covering image ends the work however many images came before it),
    /// with a bound on the area it may leave uncovered.
    fn add_image<const B: bool>(
        &self,
        tri: &[DVec3; 3],
        out: &mut Vec<Tri>,
        weights: &mut Vec<[f64; 3]>,
        (extra, reach): (&mut f64, &mut f64),
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
                        *reach = reach.max(image.reach());
                        // Oriented as given, or reversed (a, c, b).
                        weights.push(if t.first_edge_is(v[0], v[k]) {
                            wk
                        } else {
                            [wk[2], wk[1], wk[0]]
                        });
                    }
                }
                // Missing the light, or degenerate: what its edges' bands
                // may hold of the light, if it comes within their spread of
                // the light (no point of a band lies farther from its edge).
                _ if B && measure.near(&[v[0], v[k], v[k + 1]], image.spread()) => {
                    *extra += wk.iter().sum::<f64>();
                }
                _ => {}
            }
        }
        None
    }
}

/// How much wider than a disk light's box (relative) the culling pyramid
/// is ([`AreaView::hull`]).
const HULL_SLACK: f64 = 1.0 / (1u64 << 20) as f64;
