//! The emitting measure a light presents to one receiver ([`Emitter`]):
//! which measure a receiver sees of each shape, or why it sees none
//! ([`Sphere::seen_from`] and the other kinds' alike); uniform-by-area
//! sample points ([`Emitter::point_at`]) and the share of the measure
//! above a plane ([`Emitter::share_above`], the horizon bound).

use super::error::ReceiverError;
use super::shape::{Disk, Point, Rect, Segment, Sphere};
use crate::kernel::predicate::{orient2d, Sign};
use glam::{DVec2, DVec3};

/// A light's emitting measure as one receiver sees it: the kinds' own
/// validated structs, so an emitter is as valid as the light it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Emitter {
    /// A uniform disk (a disk light, or a sphere light's facing disk).
    Disk(Disk),
    /// A uniform parallelogram.
    Rect(Rect),
    /// A uniform segment.
    Segment(Segment),
    /// A point.
    Point(Point),
}

impl Emitter {
    /// The point of the measure at the sample `s ∈ [0, 1)²`, uniform by
    /// area (length for a segment) when `s` is uniform: the disk by
    /// Shirley and Chiu's concentric map (low distortion, so stratified
    /// samples stay stratified), the rect and segment affinely. A point
    /// light ignores `s`.
    #[must_use]
    pub fn point_at(&self, s: DVec2) -> DVec3 {
        match *self {
            Emitter::Disk(d) => {
                let (t, b) = d.normal().any_orthonormal_pair();
                let q = concentric_disk(s) * d.radius();
                d.center() + t * q.x + b * q.y
            }
            Emitter::Rect(r) => r.center() + r.u() * (2.0 * s.x - 1.0) + r.v() * (2.0 * s.y - 1.0),
            Emitter::Segment(g) => g.a().lerp(g.b(), s.x),
            Emitter::Point(p) => p.position(),
        }
    }
}

impl Sphere {
    /// The measure `p` sees: the facing disk (centre and radius the
    /// sphere's, normal `(c − p)/‖c − p‖`).
    ///
    /// # Errors
    /// [`ReceiverError::NonFinite`] for a non-finite `p`,
    /// [`ReceiverError::InsideSphere`] for `p` inside or on the sphere.
    pub fn seen_from(&self, p: DVec3) -> Result<Emitter, ReceiverError> {
        finite(p)?;
        let (center, radius) = (self.center(), self.radius());
        // Halved, so that the difference cannot overflow; then scaled to
        // its largest component, so that its length cannot either (a centre
        // 3e300 away is not "inside").
        let half = center * 0.5 - p * 0.5;
        let scale = half.abs().max_element();
        if scale == 0.0 {
            return Err(ReceiverError::InsideSphere);
        }
        let unit = half / scale;
        let normal = unit.try_normalize().ok_or(ReceiverError::InsideSphere)?;
        if unit.length() * scale * 2.0 <= radius {
            return Err(ReceiverError::InsideSphere);
        }
        Ok(Emitter::Disk(Disk::facing(center, normal, radius)))
    }
}

impl Disk {
    /// The measure `p` sees: the disk itself.
    ///
    /// # Errors
    /// [`ReceiverError::NonFinite`] for a non-finite `p`,
    /// [`ReceiverError::InLightPlane`] for `p` in the disk's plane (the
    /// signed distance within its own rounding bound of zero).
    pub fn seen_from(&self, p: DVec3) -> Result<Emitter, ReceiverError> {
        finite(p)?;
        off_plane(p, self.center(), self.normal())?;
        Ok(Emitter::Disk(*self))
    }
}

impl Rect {
    /// The measure `p` sees: the rect itself.
    ///
    /// # Errors
    /// [`ReceiverError::NonFinite`] for a non-finite `p`,
    /// [`ReceiverError::InLightPlane`] for `p` in the rect's plane (the
    /// signed distance within its own rounding bound of zero).
    pub fn seen_from(&self, p: DVec3) -> Result<Emitter, ReceiverError> {
        finite(p)?;
        off_plane(p, self.center(), self.plane_direction())?;
        Ok(Emitter::Rect(*self))
    }
}

impl Segment {
    /// The measure `p` sees: the segment itself.
    ///
    /// # Errors
    /// [`ReceiverError::NonFinite`] for a non-finite `p`,
    /// [`ReceiverError::OnLight`] for `p` on the segment (exactly
    /// collinear, decided by the exact predicates, and between its ends).
    pub fn seen_from(&self, p: DVec3) -> Result<Emitter, ReceiverError> {
        finite(p)?;
        let (a, b) = (self.a(), self.b());
        // Collinear exactly: all three coordinate projections are.
        let on_line = [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
            let q = |v: DVec3| DVec2::new(v[i], v[j]);
            orient2d(q(a), q(b), q(p)) == Sign::Zero
        });
        let between = (p - a).dot(b - a) >= 0.0 && (p - b).dot(a - b) >= 0.0;
        if on_line && between {
            return Err(ReceiverError::OnLight);
        }
        Ok(Emitter::Segment(*self))
    }
}

impl Point {
    /// The measure `p` sees: the point itself.
    ///
    /// # Errors
    /// [`ReceiverError::NonFinite`] for a non-finite `p`,
    /// [`ReceiverError::OnLight`] for `p` at the point.
    pub fn seen_from(&self, p: DVec3) -> Result<Emitter, ReceiverError> {
        finite(p)?;
        if p == self.position() {
            return Err(ReceiverError::OnLight);
        }
        Ok(Emitter::Point(*self))
    }
}

/// `p` must be finite.
fn finite(p: DVec3) -> Result<(), ReceiverError> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(ReceiverError::NonFinite)
    }
}

/// `p` must be off the plane through `c` with normal `n`: the computed
/// `n · (p − c)` must exceed its own rounding bound, `γ(5) |n| · |p − c|`
/// (the rounded difference, three products and two sums; `γ(k) =
/// kε/(1 − kε)`, Higham).
fn off_plane(p: DVec3, c: DVec3, n: DVec3) -> Result<(), ReceiverError> {
    let d = p - c;
    let bound = crate::kernel::footprint::f64::gamma(5) * n.abs().dot(d.abs());
    if n.dot(d).abs() > bound {
        Ok(())
    } else {
        Err(ReceiverError::InLightPlane)
    }
}

/// A disk, rect or segment emitter's sample points as an affine image of
/// plane coordinates: [`Emitter::point_at`]`(s)` is `center + axes[0] q.x +
/// axes[1] q.y` for the plane coordinates `q` of `s`, each coordinate
/// within a few roundings (`γ₅` relative to the terms' magnitudes). For
/// Monte Carlo's decisions on the light (`reference::monte_carlo`).
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(feature = "reference"), allow(dead_code))] // Monte Carlo's
pub(crate) struct PlaneMap {
    /// The point at `q = 0`.
    pub(crate) center: DVec3,
    /// The vectors `q.x` and `q.y` scale: the disk's unit axes, the rect's
    /// half-axes, the segment's half-difference and zero.
    pub(crate) axes: [DVec3; 2],
    /// `|q.x|, |q.y| ≤ half` for every sample.
    pub(crate) half: f64,
    /// [`PlaneMap::approx_grid`] is within `error` of `q` on each axis,
    /// also when given an `s` within `2⁻³³` of the sample's on each axis.
    pub(crate) error: f64,
    /// Which map from `s` to `q`.
    kind: MapKind,
}

/// The map from a sample `s` to plane coordinates.
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(feature = "reference"), allow(dead_code))] // Monte Carlo's
enum MapKind {
    /// The concentric map onto the disk of this radius.
    Disk(f64),
    /// `q = 2s − 1`.
    Rect,
    /// `q = (2 s.x − 1, 0)`: the segment is the `q.x` axis.
    Segment,
}

impl PlaneMap {
    /// [`PlaneMap::approx_grid`] of one sample `s` (the Monte Carlo tests'
    /// form).
    #[cfg(all(test, feature = "reference"))]
    pub(crate) fn approx(&self, s: DVec2) -> DVec2 {
        match self.kind {
            MapKind::Disk(r) => disk_q(s, r),
            MapKind::Rect => rect_q(s),
            MapKind::Segment => segment_q(s),
        }
    }

    /// The plane coordinates of many samples, within [`PlaneMap::error`] of
    /// those [`Emitter::point_at`] uses, without its cosine and sine: each
    /// sample `s` given by its cell on the `2³²` grid (`gx[i]`, and `gy[i]`
    /// unless `gy` is empty, as for a segment) and taken at the cell's
    /// centre, within `2⁻³³` of it on each axis; into `qx`, `qy` (as long
    /// as `gx`). Straight loops the compiler vectorises.
    #[inline(always)]
    #[cfg_attr(not(feature = "reference"), allow(dead_code))] // Monte Carlo's
    pub(crate) fn approx_grid(&self, gx: &[u32], gy: &[u32], qx: &mut [f64], qy: &mut [f64]) {
        // One loop per kind: the kind is not re-examined per sample.
        #[inline(always)]
        fn each(
            gx: &[u32],
            gy: &[u32],
            qx: &mut [f64],
            qy: &mut [f64],
            map: impl Fn(DVec2) -> DVec2,
        ) {
            let centre = |g: u32| (f64::from(g) + 0.5) / 4_294_967_296.0;
            let q = qx.iter_mut().zip(qy.iter_mut()).zip(gx);
            if gy.is_empty() {
                for ((x, y), &gx) in q {
                    (*x, *y) = map(DVec2::new(centre(gx), 0.5)).into();
                }
            } else {
                for (((x, y), &gx), &gy) in q.zip(gy) {
                    (*x, *y) = map(DVec2::new(centre(gx), centre(gy))).into();
                }
            }
        }
        match self.kind {
            MapKind::Disk(r) => each(gx, gy, qx, qy, |s| disk_q(s, r)),
            MapKind::Rect => each(gx, gy, qx, qy, rect_q),
            MapKind::Segment => each(gx, gy, qx, qy, segment_q),
        }
    }
}

/// The plane coordinates of `s` on a disk of radius `r` (see
/// [`PlaneMap::approx_grid`]).
#[inline(always)]
fn disk_q(s: DVec2, r: f64) -> DVec2 {
    concentric_disk_approx(s) * r
}

/// The plane coordinates of `s` on a rect: `q = 2s − 1`.
#[inline(always)]
fn rect_q(s: DVec2) -> DVec2 {
    s * 2.0 - DVec2::ONE
}

/// The plane coordinates of `s` on a segment: `q = (2 s.x − 1, 0)`.
#[inline(always)]
fn segment_q(s: DVec2) -> DVec2 {
    DVec2::new(s.x * 2.0 - 1.0, 0.0)
}

impl Emitter {
    /// The plane map of a disk, rect or segment emitter (a segment's
    /// second axis is zero); `None` for a point.
    #[cfg_attr(not(feature = "reference"), allow(dead_code))] // Monte Carlo's
    pub(crate) fn plane_map(&self) -> Option<PlaneMap> {
        match *self {
            Emitter::Disk(d) => {
                let (t, b) = d.normal().any_orthonormal_pair();
                let r = d.radius();
                Some(PlaneMap {
                    center: d.center(),
                    axes: [t, b],
                    // The signed radius and |cos|, |sin| within 1, two
                    // roundings.
                    half: r * (1.0 + CONCENTRIC_APPROX_ERROR + 1e-15),
                    // The polynomials' error, one rounding of each
                    // product on both sides, and `2⁻³³` on each axis of
                    // `s` through the map's Lipschitz constant: in the
                    // wedge `|a| ≥ |b|` of `(a, b) = 2s − 1` the point is
                    // `a (cos φ, sin φ)`, `φ = π/4 · b/a`, whose Jacobian
                    // in `(a, b)` turned by `−φ` is `[[1, 0], [−φ, π/4]]`,
                    // of norm at most `√((1 + 2k + √(1 + 4k²))/2) =
                    // 1.38236` (`k = π²/16`, at `|φ| = π/4`); so in `s`
                    // at most `2.7648`, and `2.77 · √2 · 2⁻³³ < 10⁻⁹` of
                    // the radius.
                    error: r * (CONCENTRIC_APPROX_ERROR + 1e-9),
                    kind: MapKind::Disk(r),
                })
            }
            // The same operations as `point_at`: the same `q` for the
            // same `s`, and `2 · 2⁻³³` for an `s` that far.
            Emitter::Rect(r) => Some(PlaneMap {
                center: r.center(),
                axes: [r.u(), r.v()],
                half: 1.0,
                error: 1e-9,
                kind: MapKind::Rect,
            }),
            // `a (1 − s) + b s` is `c + e q.x` with `c`, `e` the midpoint and
            // the half-difference (one rounding each, and three in `lerp`:
            // within the same `γ` of the terms), and no second axis.
            Emitter::Segment(g) => Some(PlaneMap {
                center: (g.a() + g.b()) * 0.5,
                axes: [(g.b() - g.a()) * 0.5, DVec3::ZERO],
                half: 1.0,
                error: 1e-9,
                kind: MapKind::Segment,
            }),
            Emitter::Point(_) => None,
        }
    }

    /// The share `V_h ∈ [0, 1]` of the measure strictly on the side of the
    /// plane through `p` with normal `n` that `n` points to — for a
    /// receiver's tangent plane, the part of the light its own surface does
    /// not hide, so `V(p) ≤ V_h` (the methods' `horizon` option).
    ///
    /// - **Disk**: with `h = n·(c − p)` the height of the centre above the
    ///   plane and `s = ‖n − (n·m)m‖` the slope between the two planes
    ///   (`m` the disk's normal), the plane cuts the disk along a chord at
    ///   `−h/s` from its centre; the share beyond it is the straight-edge
    ///   disk falloff ([`disk_edge_falloff`]) at `(1 + h/(r s))/2`, exact
    ///   to its ulp. A plane parallel to the disk gives 1 above it, 0 below,
    ///   1 in it.
    /// - **Rect**: the area of the unit square `[−1, 1]²` of the rect's own
    ///   coordinates where `h + s (n·u) + t (n·v) > 0` (the square clipped
    ///   by a half-plane, shoelace area), over 4.
    /// - **Segment**: the length fraction above the plane, where the
    ///   heights of the ends change sign.
    /// - **Point**: 1 when strictly above, else 0.
    ///
    /// `n` need not be unit length; a zero or non-finite `n` (or `p`) puts
    /// no bound: 1.
    ///
    /// [`disk_edge_falloff`]: crate::kernel::falloff::f64::disk_edge_falloff
    #[must_use]
    pub fn share_above(&self, p: DVec3, n: DVec3) -> f64 {
        if !(n.is_finite() && p.is_finite()) || n == DVec3::ZERO {
            return 1.0;
        }
        let share = match *self {
            Emitter::Disk(d) => {
                let h = n.dot(d.center() - p);
                let slope = (n - d.normal() * n.dot(d.normal())).length() * d.radius();
                let k = h / slope;
                if k.is_nan() || k >= 1.0 {
                    1.0
                } else if k <= -1.0 {
                    0.0
                } else {
                    crate::kernel::falloff::f64::disk_edge_falloff(0.5 + 0.5 * k)
                }
            }
            Emitter::Rect(r) => {
                square_share_above(n.dot(r.center() - p), n.dot(r.u()), n.dot(r.v()))
            }
            Emitter::Segment(g) => {
                let (ha, hb) = (n.dot(g.a() - p), n.dot(g.b() - p));
                match (ha > 0.0, hb > 0.0) {
                    (true, true) => 1.0,
                    (false, false) => 0.0,
                    // The crossing at t = ha / (ha − hb), a difference of
                    // opposite signs: no cancellation.
                    (true, false) => ha / (ha - hb),
                    (false, true) => hb / (hb - ha),
                }
            }
            Emitter::Point(x) => {
                if n.dot(x.position() - p) > 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
        };
        if share.is_nan() {
            1.0
        } else {
            share.clamp(0.0, 1.0)
        }
    }
}

impl Emitter {
    /// The largest coordinate magnitude of the measure's points, bounded
    /// per coordinate by its centre's plus its extent (a segment's or
    /// point's own): the light's part of a reference's domain.
    #[cfg_attr(not(feature = "reference"), allow(dead_code))] // the references'
    pub(crate) fn magnitude(&self) -> f64 {
        let m = |v: DVec3| v.abs().max_element();
        match self {
            Emitter::Disk(d) => m(d.center()) + d.radius(),
            Emitter::Rect(r) => m(r.center()) + m(r.u()) + m(r.v()),
            Emitter::Segment(s) => m(s.a()).max(m(s.b())),
            Emitter::Point(x) => m(x.position()),
        }
    }
}

/// The share of the square `[−1, 1]²` where `h + a x + b y > 0`:
/// Sutherland–Hodgman against the half-plane, shoelace area over 4.
fn square_share_above(h: f64, a: f64, b: f64) -> f64 {
    let f = |q: DVec2| h + a * q.x + b * q.y;
    let corners = [
        DVec2::new(-1.0, -1.0),
        DVec2::new(1.0, -1.0),
        DVec2::new(1.0, 1.0),
        DVec2::new(-1.0, 1.0),
    ];
    let mut poly: Vec<DVec2> = Vec::with_capacity(5);
    for k in 0..4 {
        let (p, q) = (corners[k], corners[(k + 1) % 4]);
        let (fp, fq) = (f(p), f(q));
        if fp > 0.0 {
            poly.push(p);
        }
        if (fp > 0.0) != (fq > 0.0) {
            let t = fp / (fp - fq);
            poly.push(p + (q - p) * t);
        }
    }
    let twice: f64 = (0..poly.len())
        .map(|k| poly[k].perp_dot(poly[(k + 1) % poly.len()]))
        .sum();
    0.125 * twice
}

/// Shirley and Chiu's concentric map from `[0, 1)²` to the unit disk
/// ("A Low Distortion Map Between Disk and Square", 1997): area-preserving
/// up to the constant `π/4`.
fn concentric_disk(s: DVec2) -> DVec2 {
    let o = s * 2.0 - DVec2::ONE;
    if o == DVec2::ZERO {
        return DVec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, std::f64::consts::FRAC_PI_4 * (o.y / o.x))
    } else {
        (
            o.y,
            std::f64::consts::FRAC_PI_2 - std::f64::consts::FRAC_PI_4 * (o.x / o.y),
        )
    };
    DVec2::new(theta.cos(), theta.sin()) * r
}

/// [`concentric_disk`] with the cosine and sine replaced by polynomials:
/// within [`CONCENTRIC_APPROX_ERROR`] of it on each axis (the same radius
/// and ratio; Taylor polynomials of degree 6 and 7 at `φ = π/4 · ratio`,
/// `|φ| ≤ π/4`, taking `cos θ = sin φ`, `sin θ = cos φ` in the wedges around
/// the y axis, where `θ = π/2 − φ`), at a fraction of the cost — for
/// deciding where a sample lands before its exact point is needed.
#[inline(always)]
fn concentric_disk_approx(s: DVec2) -> DVec2 {
    // Selections rather than branches (the wedge is a coin toss per
    // sample): `r` and the ratio as `concentric_disk` takes them, `φ` its
    // angle in the x wedges and `π/2 − θ` in the y wedges.
    let o = s * 2.0 - DVec2::ONE;
    let wide = o.x.abs() > o.y.abs();
    let (r, other) = if wide { (o.x, o.y) } else { (o.y, o.x) };
    let den = if r == 0.0 { 1.0 } else { r };
    let phi = std::f64::consts::FRAC_PI_4 * (other / den);
    let (c, s) = (cos_poly(phi), sin_poly(phi));
    let (x, y) = if wide { (c, s) } else { (s, c) };
    DVec2::new(x * r, y * r)
}

/// A bound on `|concentric_disk_approx(s) − concentric_disk(s)|` per axis:
/// the Taylor remainders `(π/4)⁸/8! < 3.6·10⁻⁶` and `(π/4)⁹/9! < 3.2·10⁻⁷`
/// dominate; the `f64` evaluation, the libm functions' ulp and the
/// rounding of `θ = FRAC_PI_2 − φ` in the y wedges add under `10⁻¹⁵`.
#[cfg_attr(not(feature = "reference"), allow(dead_code))] // Monte Carlo's
pub(crate) const CONCENTRIC_APPROX_ERROR: f64 = 4e-6;

/// `cos φ` by its Taylor polynomial of degree 6.
#[inline(always)]
fn cos_poly(x: f64) -> f64 {
    let z = x * x;
    1.0 + z * (-0.5 + z * (1.0 / 24.0 + z * (-1.0 / 720.0)))
}

/// `sin φ` by its Taylor polynomial of degree 7.
#[inline(always)]
fn sin_poly(x: f64) -> f64 {
    let z = x * x;
    x + x * z * (-1.0 / 6.0 + z * (1.0 / 120.0 + z * (-1.0 / 5_040.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform by area: with N uniform samples, the share landing inside
    /// half the radius is binomial with p = ¼; it must lie within 5σ,
    /// σ = √(p(1 − p)/N) (fixed seed). Every sample lies on the disk.
    #[test]
    fn disk_samples_are_uniform_by_area() {
        let emitter = Emitter::Disk(
            Disk::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(1.0, 1.0, 0.0), 2.0).unwrap(),
        );
        let mut rng = crate::arbitrary::Rng::new(3);
        const N: usize = 200_000;
        let mut inner = 0;
        for _ in 0..N {
            let q =
                emitter.point_at(DVec2::new(rng.unit(), rng.unit())) - DVec3::new(1.0, 2.0, 3.0);
            assert!(q.length() <= 2.0 * (1.0 + 1e-15));
            assert!(q.dot(DVec3::new(1.0, 1.0, 0.0).normalize()).abs() < 1e-15);
            inner += (q.length() < 1.0) as usize;
        }
        let (p, n) = (0.25, N as f64);
        let sigma = (p * (1.0 - p) / n).sqrt();
        assert!((inner as f64 / n - p).abs() < 5.0 * sigma, "{inner}");
    }

    #[test]
    fn rect_and_segment_samples_cover_the_measure() {
        let rect =
            Emitter::Rect(Rect::new(DVec3::ZERO, DVec3::X, DVec3::new(0.5, 2.0, 0.0)).unwrap());
        assert_eq!(
            rect.point_at(DVec2::ZERO),
            -DVec3::X - DVec3::new(0.5, 2.0, 0.0)
        );
        assert_eq!(rect.point_at(DVec2::splat(0.5)), DVec3::ZERO);
        let seg = Emitter::Segment(Segment::new(DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0)).unwrap());
        assert_eq!(seg.point_at(DVec2::new(0.25, 0.9)), DVec3::X);
    }
}
