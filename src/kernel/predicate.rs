//! Exact orientation predicates.
//!
//! Which side of a line or a plane a point lies on is a topological decision:
//! it must never be made by comparing a rounded value with an epsilon. These
//! predicates return the sign of the orientation determinant *exactly* as
//! long as no intermediate product, nor the rounding error of one, leaves the
//! normal floating-point range. A sufficient condition: every nonzero input
//! coordinate has magnitude in `[1e-140, 1e150]` for [`orient2d`] (products
//! of two differences) and in `[1e-90, 1e90]` for [`orient3d`] (products of
//! three). Exact zeros are always fine. Outside that range the answer may be
//! wrong (for instance a `z` of `1e-300` next to coordinates near 100 makes
//! the error terms of triple products underflow). `f32` callers promote their
//! inputs; the promotion is exact, and every finite `f32` (`1.4e-45` to
//! `3.4e38`) lies inside both ranges, so for `f32` input the predicates are
//! exact without condition.
//!
//! Method: a floating-point filter with Shewchuk's static error bounds
//! ("Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//! Predicates", 1997, §4.3: `ccwerrboundA = (3 + 16ε)ε`,
//! `o3derrboundA = (7 + 56ε)ε`, `ε = 2⁻⁵³`) answers almost every call with
//! one rounded evaluation; when the rounded determinant is within the bound
//! of zero, the determinant is re-evaluated exactly as a floating-point
//! expansion (error-free `two_sum` / `two_prod` transformations). The
//! exact path allocates nothing (fixed stack arrays).
//!
//! Non-finite input (NaN or ±∞ in any coordinate) has no meaningful side: the
//! predicates return [`Sign::Zero`] for it, the documented total answer.

use super::lanes::{Lanes, Real};
use glam::{DVec2, DVec3};

/// The sign of an orientation determinant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Clockwise (2D); for [`orient3d`], `d` on the side the face normal
    /// points to (see there).
    Negative,
    /// Collinear (2D), coplanar (3D), or non-finite input.
    Zero,
    /// Counter-clockwise (2D); for [`orient3d`], `d` behind the face.
    Positive,
}

impl Sign {
    /// `-1`, `0` or `1`.
    #[must_use]
    #[inline]
    pub fn to_i32(self) -> i32 {
        match self {
            Sign::Negative => -1,
            Sign::Zero => 0,
            Sign::Positive => 1,
        }
    }

    /// The opposite sign.
    #[must_use]
    #[inline]
    pub fn flip(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }

    /// The sign of `x` (`Zero` for ±0 and NaN).
    #[must_use]
    #[inline]
    pub fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
}

const EPS: f64 = f64::EPSILON / 2.0; // 2^-53, the unit roundoff
const CCW_ERR_BOUND_A: f64 = (3.0 + 16.0 * EPS) * EPS;
const O3D_ERR_BOUND_A: f64 = (7.0 + 56.0 * EPS) * EPS;

/// The sign of `(a − c) × (b − c)`: [`Sign::Positive`] when `a, b, c` turn
/// counter-clockwise, [`Sign::Negative`] clockwise, [`Sign::Zero`] collinear.
///
/// Exact for every nonzero coordinate in `[1e-140, 1e150]` in magnitude (see
/// the module docs); [`Sign::Zero`] for non-finite input.
///
/// ```
/// use softshadow::glam::DVec2;
/// use softshadow::kernel::predicate::{orient2d, Sign};
///
/// // A point a few ulps off the line y = x, where the rounded determinant
/// // is unreliable: the exact answer is still "left of the line".
/// let p = DVec2::new(0.5, 0.5 + f64::EPSILON);
/// let (b, c) = (DVec2::new(12.0, 12.0), DVec2::new(24.0, 24.0));
/// assert_eq!(orient2d(p, b, c), Sign::Positive);
/// ```
#[must_use]
#[inline]
pub fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Sign {
    if !(a.is_finite() && b.is_finite() && c.is_finite()) {
        return Sign::Zero;
    }
    let (det, detleft, detright, exact_zero) = orient2d_rounded(a, b, c);
    let bound = CCW_ERR_BOUND_A * (detleft.abs() + detright.abs());
    if det > bound || -det > bound {
        return Sign::of(det);
    }
    if exact_zero {
        return Sign::Zero;
    }
    orient2d_exact(a, b, c)
}

/// The value of the determinant `(a − c) × (b − c)` whose sign [`orient2d`]
/// gives: its sign exact, its relative error below `2⁻⁴⁰` (the rounded
/// determinant where its error bound allows, else the exact expansion
/// summed). Where two nearly parallel edges cross, a crossing parameter
/// `va / (va − vb)` formed from these values is accurate, so two edges cut
/// at their crossing are cut at the same point. Same domain as
/// [`orient2d`]; `0` for non-finite input.
#[must_use]
pub fn orient2d_value(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    if !(a.is_finite() && b.is_finite() && c.is_finite()) {
        return 0.0;
    }
    orient2d_value_finite(a, b, c)
}

/// [`orient2d_value`] for finite points (the caller's guarantee: the same
/// value, without the check).
#[inline]
pub(crate) fn orient2d_value_finite(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    debug_assert!(a.is_finite() && b.is_finite() && c.is_finite());
    let (det, detleft, detright, exact_zero) = orient2d_rounded(a, b, c);
    if value_is_rounded(det, detleft, detright) {
        return det;
    }
    if exact_zero {
        return 0.0;
    }
    orient2d_expansion(a, b, c).approximate()
}

/// [`orient2d_value_finite`] (the same value, bit for bit) and a bound on
/// its error: the filter's where the rounded determinant is taken, else
/// the expansion's rounding.
pub(crate) fn orient2d_value_bounded(a: DVec2, b: DVec2, c: DVec2) -> Bounded {
    let (det, detleft, detright, exact_zero) = orient2d_rounded(a, b, c);
    if value_is_rounded(det, detleft, detright) {
        return Bounded {
            value: det,
            bound: CCW_ERR_BOUND_A * (detleft.abs() + detright.abs()) + 1e-300,
        };
    }
    if exact_zero {
        return Bounded {
            value: 0.0,
            bound: 0.0,
        };
    }
    let sum = orient2d_expansion(a, b, c);
    let terms = &sum.terms[..sum.len];
    let magnitude: f64 = terms.iter().map(|t| t.abs()).sum();
    Bounded {
        value: sum.approximate(),
        bound: terms.len() as f64 * EPS * 1.01 * magnitude + 1e-300,
    }
}

/// Whether the rounded determinant is within `2⁻⁴⁰` of the exact one,
/// relatively: its error is at most the filter's bound, and the bound is
/// `2⁻⁴⁰` of it.
#[inline(always)]
fn value_is_rounded<R: Real<Scalar = f64>>(det: R, detleft: R, detright: R) -> R::Mask {
    let bound = R::splat(CCW_ERR_BOUND_A)
        * (detleft.abs() + detright.abs())
        * R::splat((1u64 << 40) as f64);
    det.gt(bound) | (-det).gt(bound)
}

/// [`orient2d_value_finite`]`(a_l, b_l, c_l)` for the lanes `l` of
/// `a = [ax, ay]`, `b` and `c` alike: the same values bit for bit, the
/// rounded determinants of all lanes evaluated side by side (the exact
/// expansion, rarely needed, lane by lane).
#[inline(always)]
pub(crate) fn orient2d_values_finite<const N: usize>(
    a: [[f64; N]; 2],
    b: [[f64; N]; 2],
    c: [[f64; N]; 2],
) -> [f64; N] {
    let (det, detleft, detright, _) = orient2d_products(
        [Lanes(a[0]), Lanes(a[1])],
        [Lanes(b[0]), Lanes(b[1])],
        [Lanes(c[0]), Lanes(c[1])],
    );
    let rounded = value_is_rounded(det, detleft, detright);
    let mut value = det.0;
    if Lanes::<f64, N>::any(!rounded) {
        for (l, v) in value.iter_mut().enumerate() {
            if rounded.0[l] == 0 {
                // This lane as `orient2d_value_finite` goes on.
                let point = |p: [[f64; N]; 2]| DVec2::new(p[0][l], p[1][l]);
                let (a, b, c) = (point(a), point(b), point(c));
                let (_, _, _, exact_zero) = orient2d_rounded(a, b, c);
                *v = if exact_zero {
                    0.0
                } else {
                    orient2d_expansion(a, b, c).approximate()
                };
            }
        }
    }
    value
}

/// The sign of the determinant `| a−d ; b−d ; c−d |` (rows): [`Sign::Positive`]
/// when `d` lies *below* the plane through `a, b, c`, i.e. on the side from
/// which `a, b, c` appear clockwise; [`Sign::Negative`] when `d` sees them
/// counter-clockwise; [`Sign::Zero`] when the four points are coplanar.
///
/// In other words, with the face normal `n = (b − a) × (c − a)`,
/// `orient3d(a, b, c, d)` is the sign of `−n · (d − a)`. Exact for every
/// nonzero coordinate in `[1e-90, 1e90]` in magnitude (see the module docs);
/// [`Sign::Zero`] for non-finite input.
#[must_use]
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    if !(a.is_finite() && b.is_finite() && c.is_finite() && d.is_finite()) {
        return Sign::Zero;
    }
    let (det, permanent) = orient3d_rounded(a, b, c, d);
    let bound = O3D_ERR_BOUND_A * permanent;
    if det > bound || -det > bound {
        return Sign::of(det);
    }
    orient3d_exact(a, b, c, d)
}

/// The value of the determinant whose sign [`orient3d`] gives
/// (`−n · (d − a)` with `n = (b − a) × (c − a)`): its sign exact, its
/// relative error below `2⁻⁴⁰` (the rounded determinant where its error
/// bound allows, else the exact expansion summed). A crossing parameter
/// `fa / (fa − fb)` formed from two such values lands on the plane even
/// when the segment is nearly parallel to it. Same domain as [`orient3d`];
/// `0` for non-finite input.
#[must_use]
pub fn orient3d_value(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    if !(a.is_finite() && b.is_finite() && c.is_finite() && d.is_finite()) {
        return 0.0;
    }
    let (det, permanent) = orient3d_rounded(a, b, c, d);
    let bound = O3D_ERR_BOUND_A * permanent * (1u64 << 40) as f64;
    if det > bound || -det > bound {
        return det;
    }
    orient3d_expansion(a, b, c, d).approximate()
}

/// A row of a 3×3 determinant taken on the inputs as given: the exact
/// difference `a − b` of two points (a vector `v` is the row
/// [`Row::vector`], the difference `v − 0`), kept with its rounded value
/// for the rounded evaluations, and its two points for the exact one
/// ([`det3_exact`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Row {
    a: DVec3,
    b: DVec3,
    /// `a − b` rounded.
    pub(crate) r: DVec3,
}

impl Row {
    /// The row `a − b`.
    #[inline(always)]
    pub(crate) fn diff(a: DVec3, b: DVec3) -> Row {
        Row { a, b, r: a - b }
    }

    /// The row `v` (exact).
    #[inline(always)]
    pub(crate) fn vector(v: DVec3) -> Row {
        Row {
            a: v,
            b: DVec3::ZERO,
            r: v,
        }
    }

    /// The exact row, each coordinate a `(hi, lo)` pair (`hi` the rounded
    /// row [`Row::r`]).
    pub(crate) fn exact(&self) -> [[f64; 2]; 3] {
        let (a, b) = (self.a, self.b);
        [diff(a.x, b.x), diff(a.y, b.y), diff(a.z, b.z)]
    }
}

/// A value and a bound on its distance from the exact value it stands
/// for: `|value − exact| ≤ bound`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Bounded {
    pub(crate) value: f64,
    pub(crate) bound: f64,
}

impl Bounded {
    /// The value times `s = ±1` (exactly).
    #[inline(always)]
    pub(crate) fn signed(self, s: f64) -> Bounded {
        Bounded {
            value: s * self.value,
            bound: self.bound,
        }
    }

    /// The exact value's sign, when the bound settles it (an exact zero
    /// is certain).
    #[inline(always)]
    pub(crate) fn sign(self) -> Option<Sign> {
        if self.value > self.bound {
            Some(Sign::Positive)
        } else if -self.value > self.bound {
            Some(Sign::Negative)
        } else if self.value == 0.0 && self.bound == 0.0 {
            Some(Sign::Zero)
        } else {
            None
        }
    }
}

/// `det[r0; r1; r2]` of the exact rows, as the exact expansion rounded to
/// a double: the value and a bound on its rounding (the components summed
/// smallest first, each addition rounded at most once: `len·u` of the sum
/// of their magnitudes, the non-overlapping components adding at most a
/// part in `2⁵²` to the largest). An exact zero comes back as `(0, 0)`.
/// Same domain as [`orient3d`]; the caller guarantees finite rows.
#[cold]
pub(crate) fn det3_exact(r0: &Row, r1: &Row, r2: &Row) -> Bounded {
    let sum = triple_products(&r0.exact(), &r1.exact(), &r2.exact(), true);
    let terms = &sum.terms[..sum.len];
    let value = sum.approximate();
    let magnitude: f64 = terms.iter().map(|t| t.abs()).sum();
    Bounded {
        value,
        // `len` roundings of at most `u` of the running sum, each below
        // the magnitude (with a floor for gradual underflow).
        bound: terms.len() as f64 * EPS * 1.01 * magnitude
            + if terms.is_empty() { 0.0 } else { 1e-300 },
    }
}

/// `a + b = s + e` exactly (Knuth's branch-free TwoSum).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

use crate::kernel::eft::f64::two_prod;

/// A floating-point expansion: an exact sum of non-overlapping components of
/// increasing magnitude, held in a fixed array.
struct Expansion<const N: usize> {
    terms: [f64; N],
    len: usize,
}

impl<const N: usize> Expansion<N> {
    fn new() -> Self {
        Expansion {
            terms: [0.0; N],
            len: 0,
        }
    }

    /// Adds `b` exactly (Shewchuk's GROW-EXPANSION with zero elimination).
    /// Zero elimination keeps `len ≤` the number of additions, so an `N` at
    /// least the number of calls can never overflow.
    fn add(&mut self, b: f64) {
        let mut q = b;
        let mut out = 0;
        for i in 0..self.len {
            let (s, e) = two_sum(q, self.terms[i]);
            q = s;
            if e != 0.0 {
                self.terms[out] = e;
                out += 1;
            }
        }
        if q != 0.0 {
            self.terms[out] = q;
            out += 1;
        }
        self.len = out;
    }

    /// Adds the exact product `x · y · z` (each factor a double).
    fn add_product3(&mut self, x: f64, y: f64, z: f64, negate: bool) {
        let (p, e) = two_prod(x, y);
        let (pz, pze) = two_prod(p, z);
        let (ez, eze) = two_prod(e, z);
        let s = if negate { -1.0 } else { 1.0 };
        for t in [pze, eze, ez, pz] {
            self.add(s * t);
        }
    }

    /// The exact sum rounded: the components added smallest first, each
    /// sum exact but the last few, so the error is a few ulps.
    fn approximate(&self) -> f64 {
        self.terms[..self.len].iter().fold(0.0, |s, &t| s + t)
    }

    /// The sign of the exact sum: that of its largest component.
    fn sign(&self) -> Sign {
        if self.len == 0 {
            Sign::Zero
        } else {
            Sign::of(self.terms[self.len - 1])
        }
    }
}

/// The rounded `(a − c) × (b − c)`, its two products, and whether it is
/// exactly zero because a factor of each product is: a computed difference
/// is zero only when its operands are equal (gradual underflow), so this
/// holds for the exact differences too. The common degenerate case — a
/// shared vertex, `a = c` or `b = c` — and axis-aligned collinear points
/// then skip the expansion.
#[inline]
fn orient2d_rounded(a: DVec2, b: DVec2, c: DVec2) -> (f64, f64, f64, bool) {
    let (det, detleft, detright, [acx, bcy, acy, bcx]) =
        orient2d_products([a.x, a.y], [b.x, b.y], [c.x, c.y]);
    let exact_zero = (acx == 0.0 || bcy == 0.0) && (acy == 0.0 || bcx == 0.0);
    (det, detleft, detright, exact_zero)
}

/// The rounded `(a − c) × (b − c)`, its two products and the four
/// differences, on one value or on lanes (points as `[x, y]`): the
/// arithmetic of [`orient2d_rounded`].
#[inline(always)]
fn orient2d_products<R: Real>(a: [R; 2], b: [R; 2], c: [R; 2]) -> (R, R, R, [R; 4]) {
    let (acx, bcy, acy, bcx) = (a[0] - c[0], b[1] - c[1], a[1] - c[1], b[0] - c[0]);
    let detleft = acx * bcy;
    let detright = acy * bcx;
    (detleft - detright, detleft, detright, [acx, bcy, acy, bcx])
}

/// The rounded determinant of [`orient3d`] and its permanent (the sum of
/// the magnitudes of its terms), which scales the filter's error bound.
#[inline]
fn orient3d_rounded(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> (f64, f64) {
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let bdxcdy = bd.x * cd.y;
    let cdxbdy = cd.x * bd.y;
    let cdxady = cd.x * ad.y;
    let adxcdy = ad.x * cd.y;
    let adxbdy = ad.x * bd.y;
    let bdxady = bd.x * ad.y;
    let det = ad.z * (bdxcdy - cdxbdy) + bd.z * (cdxady - adxcdy) + cd.z * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * ad.z.abs()
        + (cdxady.abs() + adxcdy.abs()) * bd.z.abs()
        + (adxbdy.abs() + bdxady.abs()) * cd.z.abs();
    (det, permanent)
}

/// An exact difference `a − b` as the pair `(hi, lo)`.
#[inline]
fn diff(a: f64, b: f64) -> [f64; 2] {
    let (s, e) = two_sum(a, -b);
    [s, e]
}

#[cold]
fn orient2d_exact(a: DVec2, b: DVec2, c: DVec2) -> Sign {
    orient2d_expansion(a, b, c).sign()
}

/// `(a − c) × (b − c)` as an exact expansion.
fn orient2d_expansion(a: DVec2, b: DVec2, c: DVec2) -> Expansion<16> {
    let (acx, bcy) = (diff(a.x, c.x), diff(b.y, c.y));
    let (acy, bcx) = (diff(a.y, c.y), diff(b.x, c.x));
    // 2 products of (2-term × 2-term) → 8 exact partial products → 16 doubles.
    let mut sum = Expansion::<16>::new();
    for (l, r, negate) in [(acx, bcy, false), (acy, bcx, true)] {
        for x in l {
            for y in r {
                let (p, e) = two_prod(x, y);
                let s = if negate { -1.0 } else { 1.0 };
                sum.add(s * e);
                sum.add(s * p);
            }
        }
    }
    sum
}

/// The sign of [`orient3d`]'s determinant, exactly. Two shortcuts, each
/// exact: an axis on which the three differences all vanish is a zero
/// column, so the determinant is zero (four points in one axis-aligned
/// plane: a receiver on a floor, tested against the floor's triangles by
/// every ray it casts); and the zero parts of the exact differences add
/// nothing, so their products are skipped (the differences of nearby
/// coordinates are exact, their low parts zero: 6 products instead of 48).
/// The sign of an exact sum does not depend on how it was accumulated.
#[cold]
fn orient3d_exact(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    let (ad, bd, cd) = differences(a, b, c, d);
    let zero = |r: &[[f64; 2]; 3], k: usize| r[k] == [0.0, 0.0];
    if (0..3).any(|k| zero(&ad, k) && zero(&bd, k) && zero(&cd, k)) {
        return Sign::Zero;
    }
    triple_products(&ad, &bd, &cd, true).sign()
}

/// The exact differences `a − d`, `b − d`, `c − d`, each coordinate a
/// `(hi, lo)` pair.
type Differences = ([[f64; 2]; 3], [[f64; 2]; 3], [[f64; 2]; 3]);

fn differences(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Differences {
    (
        [diff(a.x, d.x), diff(a.y, d.y), diff(a.z, d.z)],
        [diff(b.x, d.x), diff(b.y, d.y), diff(b.z, d.z)],
        [diff(c.x, d.x), diff(c.y, d.y), diff(c.z, d.z)],
    )
}

/// The determinant of [`orient3d`] as an exact expansion.
fn orient3d_expansion(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Expansion<192> {
    let (ad, bd, cd) = differences(a, b, c, d);
    triple_products(&ad, &bd, &cd, false)
}

/// The determinant of the exact differences as an expansion; with
/// `skip_zeros` the zero parts' products are left out (the same exact
/// value, accumulated differently: for its sign only, since the rounded
/// sum of the components may then differ in its last bits).
fn triple_products(
    ad: &[[f64; 2]; 3],
    bd: &[[f64; 2]; 3],
    cd: &[[f64; 2]; 3],
    skip_zeros: bool,
) -> Expansion<192> {
    // det = Σ over the 6 permutations of sign · u_x · v_y · w_z, each factor a
    // 2-term difference: 6 · 8 triple products, 4 doubles each.
    // Rows of exact differences, each coordinate a (hi, lo) pair.
    type Row<'a> = &'a [[f64; 2]; 3];
    let terms: [(Row, Row, Row, bool); 6] = [
        (ad, bd, cd, false), // ad.z · bd.x · cd.y
        (ad, cd, bd, true),  // − ad.z · cd.x · bd.y
        (bd, cd, ad, false), // bd.z · cd.x · ad.y
        (bd, ad, cd, true),  // − bd.z · ad.x · cd.y
        (cd, ad, bd, false), // cd.z · ad.x · bd.y
        (cd, bd, ad, true),  // − cd.z · bd.x · ad.y
    ];
    let mut sum = Expansion::<192>::new();
    for (z_row, x_row, y_row, negate) in terms {
        for z in z_row[2] {
            for x in x_row[0] {
                for y in y_row[1] {
                    if skip_zeros && (z == 0.0 || x == 0.0 || y == 0.0) {
                        continue;
                    }
                    sum.add_product3(z, x, y, negate);
                }
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orient2d_basic() {
        let (a, b) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
        assert_eq!(orient2d(a, b, DVec2::new(0.5, 1.0)), Sign::Positive);
        assert_eq!(orient2d(a, b, DVec2::new(0.5, -1.0)), Sign::Negative);
        assert_eq!(orient2d(a, b, DVec2::new(7.0, 0.0)), Sign::Zero);
        assert_eq!(orient2d(a, b, DVec2::new(f64::NAN, 0.0)), Sign::Zero);
    }

    #[test]
    fn orient3d_matches_normal_convention() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y); // normal +z
        assert_eq!(orient3d(a, b, c, DVec3::new(0.2, 0.2, 1.0)), Sign::Negative);
        assert_eq!(
            orient3d(a, b, c, DVec3::new(0.2, 0.2, -1.0)),
            Sign::Positive
        );
        assert_eq!(orient3d(a, b, c, DVec3::new(5.0, -3.0, 0.0)), Sign::Zero);
    }

    #[test]
    fn exact_paths_agree_with_filter_on_clear_cases() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(1.7, -0.2, 0.9);
        let c = DVec3::new(-0.4, 1.1, 0.5);
        for d in [DVec3::new(0.3, 0.3, 2.0), DVec3::new(0.3, 0.3, -2.0)] {
            assert_eq!(orient3d_exact(a, b, c, d), orient3d(a, b, c, d));
        }
        let (p, q, r) = (
            DVec2::new(0.1, 0.7),
            DVec2::new(2.3, -1.1),
            DVec2::new(0.0, 0.0),
        );
        assert_eq!(orient2d_exact(p, q, r), orient2d(p, q, r));
        assert_eq!(orient2d_exact(q, p, r), orient2d(q, p, r));
    }

    /// Each lane of [`orient2d_values_finite`] is [`orient2d_value_finite`]
    /// of that lane's points, bit for bit, on the paths the scalar function
    /// takes: clear signs (the rounded value), points a few ulps off a line
    /// (the expansion), exact zeros (a shared point, collinear points on an
    /// axis), mixed in one call.
    #[test]
    fn lanes_of_values_are_the_scalar_values() {
        let mut rng = crate::arbitrary::Rng::new(97);
        let point = |rng: &mut crate::arbitrary::Rng| {
            DVec2::new(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0))
        };
        let (mut rounded, mut expanded, mut zero) = (0, 0, 0);
        for _ in 0..4000 {
            let lanes: [(DVec2, DVec2, DVec2); 4] = core::array::from_fn(|_| {
                let (a, b) = (point(&mut rng), point(&mut rng));
                let c = match rng.below(4) {
                    // On the line through a and b, or an ulp or two off it.
                    0 => {
                        let t = rng.uniform(-1.0, 2.0);
                        let c = a + (b - a) * t;
                        DVec2::new(c.x, f64::from_bits(c.y.to_bits() + rng.below(3)))
                    }
                    1 => a,
                    2 => DVec2::new(rng.uniform(-2.0, 2.0), a.y),
                    _ => point(&mut rng),
                };
                let b = if rng.chance(0.3) {
                    DVec2::new(b.x, a.y)
                } else {
                    b
                };
                (a, b, c)
            });
            let coords = |f: fn(&(DVec2, DVec2, DVec2)) -> DVec2| {
                [lanes.map(|l| f(&l).x), lanes.map(|l| f(&l).y)]
            };
            let got = orient2d_values_finite(coords(|l| l.0), coords(|l| l.1), coords(|l| l.2));
            for (l, &(a, b, c)) in lanes.iter().enumerate() {
                let want = orient2d_value_finite(a, b, c);
                assert_eq!(got[l].to_bits(), want.to_bits(), "{a} {b} {c}");
                let (det, left, right, exact_zero) = orient2d_rounded(a, b, c);
                if value_is_rounded(det, left, right) {
                    rounded += 1;
                } else if exact_zero {
                    zero += 1;
                } else {
                    expanded += 1;
                }
            }
        }
        // Every path was taken often.
        assert!(
            rounded > 1000 && expanded > 1000 && zero > 1000,
            "{rounded} {expanded} {zero}"
        );
    }
}
