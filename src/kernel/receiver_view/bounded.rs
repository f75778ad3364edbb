//! The rounded constructions of the receiver view with their error
//! bounds: 3×3 determinants of rows taken relative to the receiver (or to
//! a triangle's corner), each a dot product with a shared cross product,
//! and a bound on its distance from the exact determinant of the inputs as
//! given; where that bound is too wide for its use, the exact value
//! ([`det3_exact`]).
//!
//! The bound of [`Cross::dot`]: with `u = 2⁻⁵³`, the rows' rounded
//! differences (one rounding each), the cross product's two products and
//! difference put each component `m̂ₖ` within `γ₅ Mₖ` of the exact one,
//! `Mₖ` the sum of the magnitudes of its two products (computed from the
//! rounded rows: `γ₄` of the exact sum and one more for that); the dot
//! product with a row `ŵ` (rounded once, or exact) adds `γ₄ Σ|m̂ₖ ŵₖ|`. So
//! `|dot − det| ≤ γ₆ Σ |ŵₖ| (|m̂ₖ| + Mₖ)`, and `γ₈` covers the rounding of
//! that sum itself. A floor of `10⁻³⁰⁰` covers gradual underflow, which
//! the domain of the exact predicates (coordinates `0` or of magnitude in
//! `[10⁻⁹⁰, 10⁹⁰]`) keeps out of every product.

use crate::kernel::eft::f64::two_prod;
use crate::kernel::footprint::f64::gamma;
use crate::kernel::predicate::two_sum;
pub(super) use crate::kernel::predicate::{det3_exact, Bounded, Row};
use glam::{DVec3, Vec3Swizzles};

/// `γ₈`: the factor of [`Cross::dot`]'s bound.
const G8: f64 = gamma(8);

/// The unit roundoff `u = 2⁻⁵³`.
const U: f64 = f64::EPSILON / 2.0;

/// How much larger than `Σₖ |m̂ₖ|` a rounded cross product's weight may be
/// before [`Cross::compensated`] replaces it ([`Cross::cancels`]).
const CANCELS: f64 = 4.0;

/// Covers gradual underflow in a bound.
pub(super) const FLOOR: f64 = 1e-300;

/// A cross product `u × v` of two rows, rounded, with the sum of the
/// magnitudes of its components and of their two products each (which
/// scales its error).
#[derive(Clone, Copy, Debug)]
pub(super) struct Cross {
    pub(super) m: DVec3,
    /// `|m̂ₖ| + Mₖ` per component.
    abs: DVec3,
    /// `Σₖ |m̂ₖ| + Mₖ`.
    scale: f64,
}

impl Cross {
    #[inline(always)]
    pub(super) fn of(u: DVec3, v: DVec3) -> Cross {
        let (a, b) = (u.yzx() * v.zxy(), u.zxy() * v.yzx());
        let m = a - b;
        let abs = m.abs() + a.abs() + b.abs();
        Cross {
            m,
            abs,
            scale: abs.element_sum(),
        }
    }

    /// Whether the rounded product's two products cancel so much (the
    /// weight `Σₖ |m̂ₖ| + Mₖ` above [`CANCELS`] times `Σₖ |m̂ₖ|`: a long
    /// edge seen nearly end-on, a sliver's normal) that
    /// [`Cross::compensated`] is worth its cost.
    #[inline(always)]
    pub(super) fn cancels(&self) -> bool {
        self.scale > CANCELS * self.m.abs().element_sum()
    }

    /// The cross product `u × v` of the exact rows to about an ulp of each
    /// component however much its two products cancel: each product
    /// error-free ([`two_prod`]), their difference by [`two_sum`], the
    /// rows' own rounding (`u = û + δu` exactly) to first order. Its
    /// weights `|m̂ₖ| + 4u Mₖ` make [`Cross::dot`]'s and
    /// [`Cross::precise`]'s bounds hold as they are:
    ///
    /// with `m = û×v̂ + (û×δv + δu×v̂) + δu×δv`, the component is
    /// `s + t + e₁ − e₂ + C + D` exactly (`p₁ − p₂ = s + t`, `e` the
    /// products' errors, `C` the first-order terms, `|C| ≤ 2u Mₖ(1 + u)`,
    /// computed within `γ₃` of their magnitudes, `|D| ≤ u² Mₖ`); the low
    /// part's two additions err by `γ₂ (u|s| + 3u Mₖ)`, the final sum by
    /// `u |m̂ₖ|`: in all `|m̂ₖ − mₖ| ≤ 2u |m̂ₖ| + 16u² Mₖ`. The dot product
    /// with a row `ŵ` rounded at most once (`|δw| ≤ u|ŵ|`) then errs by
    /// `γ₃ Σ|m̂ₖ ŵₖ| + Σ (2u|m̂ₖ| + 16u² Mₖ)|ŵₖ| + u Σ |mₖ||ŵₖ| ≤ 7u Σ
    /// |m̂ₖ||ŵₖ| + 17u² Σ Mₖ |ŵₖ|`, within `γ₈ Σ |ŵₖ| (|m̂ₖ| + 4u Mₖ)`.
    #[inline(never)]
    pub(super) fn compensated(u: &Row, v: &Row) -> Cross {
        let (a, b) = (u.exact(), v.exact());
        let mut m = [0.0; 3];
        let mut abs = [0.0; 3];
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let (p1, e1) = two_prod(a[i][0], b[j][0]);
            let (p2, e2) = two_prod(a[j][0], b[i][0]);
            let (s, t) = two_sum(p1, -p2);
            let first =
                (a[i][0] * b[j][1] + a[i][1] * b[j][0]) - (a[j][0] * b[i][1] + a[j][1] * b[i][0]);
            let value = s + ((t + (e1 - e2)) + first);
            m[k] = value;
            abs[k] = value.abs() + 4.0 * U * (p1.abs() + p2.abs());
        }
        let abs = DVec3::from(abs);
        Cross {
            m: DVec3::from(m),
            abs,
            scale: abs.element_sum(),
        }
    }

    /// The bound of [`Cross::dot`] itself, `γ₈ Σₖ |ŵₖ| (|m̂ₖ| + Mₖ)`: never
    /// above the one `dot` gives (which decides; this one is reported).
    #[inline(always)]
    pub(super) fn precise(&self, w: DVec3) -> f64 {
        G8 * w.abs().dot(self.abs) + FLOOR
    }

    /// `(u × v) · w` and its bound against the exact determinant
    /// `det[u; v; w]` of the exact rows (`w` rounded at most once from
    /// its exact value; `w_max` its largest magnitude): `γ₈ Σₖ |ŵₖ| (|m̂ₖ| +
    /// Mₖ)` (module docs), taken at most `γ₈ |ŵ|∞ Σₖ (|m̂ₖ| + Mₖ)` — one
    /// product per dot product, the sum being the cross product's.
    #[inline(always)]
    pub(super) fn dot(&self, w: DVec3, w_max: f64) -> Bounded {
        Bounded {
            value: self.m.dot(w),
            bound: G8 * self.scale * w_max + FLOOR,
        }
    }
}

/// The largest magnitude of a vector's components.
#[inline(always)]
pub(super) fn max_abs(w: DVec3) -> f64 {
    w.abs().max_element()
}
