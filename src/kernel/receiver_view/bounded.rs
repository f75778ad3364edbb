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

use crate::kernel::footprint::f64::gamma;
pub(super) use crate::kernel::predicate::{det3_exact, Bounded, Row};
use glam::{DVec3, Vec3Swizzles};

/// `γ₈`: the factor of [`Cross::dot`]'s bound.
const G8: f64 = gamma(8);

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
