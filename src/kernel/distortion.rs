//! SSOC: from the distortion of a fragment to its shadow intensity.
//!
//! The soft shadow occlusion camera (Mo, Popescu, Wyman, "The Soft Shadow
//! Occlusion Camera", §3.2) places a depth-discontinuity occlusion camera at
//! the centre of a sphere light. Near a silhouette edge at depth `z_n` it
//! distorts the light image so that geometry hidden behind the edge becomes
//! visible; the distortion grows linearly in `1/z` from zero at the edge.
//! A fragment at depth `z_p` that lies in the edge's penumbra must be
//! distorted by some `d` to reach the outer edge of the distortion region,
//! and the largest distortion that can occur at its depth is
//!
//! `dmax(z_p) = 2R = 2r·(1/z_n − 1/z_p)` ([`f64::max_distortion`]),
//!
//! twice the footprint radius `R` of a light of radius `r` ([footprint radius](crate::definitions#footprint-radius)), in light-image-plane units. The paper's eq. 1
//! turns the ratio into an intensity,
//!
//! `intensity = falloff(1 − d/dmax)` ([`f64::intensity`]),
//!
//! with the paper's Bernstein falloff or the exact disk falloff
//! ([`Falloff`]): `d = 0` (the outer edge of the
//! penumbra) is fully lit, `d = dmax` (the inner edge) fully shadowed.
//!
//! ## Conventions at the edge of the domain
//!
//! - A receiver not behind the edge (`z_p ≤ z_n`) has no penumbra from it:
//!   `dmax = 0`.
//! - `dmax = 0` is a hard shadow boundary, not a NaN: `d ≤ 0` is lit (`1`),
//!   `d > 0` is shadowed (`0`). This is the limit of the smooth case as
//!   `dmax → 0⁺` for every fixed `d`, so [`f64::intensity`] is continuous in
//!   `dmax` everywhere, including at `0`; the only discontinuity is the step
//!   in `d` at `d = 0` when `dmax = 0`.
//! - `d < 0` clamps to the outer edge (`1`), `d > dmax` to the inner edge
//!   (`0`).
//!
//! Both functions are in [`f32`](mod@f32) and [`f64`](mod@f64) from one body.

use crate::kernel::falloff::{self, Falloff, FalloffFloat};
use crate::kernel::float::{both_precisions, Float};

/// [`f64::max_distortion`] in either precision.
#[inline]
pub(crate) fn max_distortion<T: Float>(light_radius: T, z_near: T, z_receiver: T) -> T {
    // Exactly twice the footprint radius (the doubling is exact).
    T::of(2.0) * crate::kernel::footprint::radius(light_radius, z_near, z_receiver)
}

/// [`f64::penumbra_position`] in either precision.
#[inline]
pub(crate) fn penumbra_position<T: Float>(d: T, dmax: T) -> T {
    if d <= T::of(0.0) {
        return T::of(1.0);
    }
    // Here d > 0 or d is NaN. `d >= dmax` also covers dmax ≤ 0.
    if d.is_nan() || dmax.is_nan() || d >= dmax {
        return T::of(0.0);
    }
    if dmax == T::INFINITY {
        return T::of(1.0);
    }
    (dmax - d) / dmax
}

/// [`f64::intensity`] in either precision.
#[inline]
pub(crate) fn intensity<T: FalloffFloat>(d: T, dmax: T, falloff: Falloff) -> T {
    falloff::eval(falloff, penumbra_position(d, dmax))
}

/// The public items of one precision `($T, $V2, $V3)`, declared once
/// with their contracts, each forwarding to the generic body above;
/// `both_precisions!` makes the modules `f64` and `f32` of them.
macro_rules! precision {
    ($T:ident, $V2:ident, $V3:ident) => {
        use crate::kernel::falloff::Falloff;

        /// SSOC's maximal distortion at receiver depth `z_receiver` for a
        /// silhouette edge at depth `z_near` and a sphere light of radius
        /// `light_radius`: `dmax = 2r·(1/z_n − 1/z_p)`, in light-image-plane
        /// units (SSOC §3.2.1; [footprint radius](crate::definitions#footprint-radius)).
        ///
        /// **Domain**: `r ≥ 0`, `0 < z_n < z_p ≤ +∞`, depths along the light
        /// frame's `+z`. `z_p = +∞` gives the limit `2r/z_n`.
        ///
        /// **Edge of the domain**: a receiver not behind the edge
        /// (`z_p ≤ z_n`) gives `0` (no penumbra from this edge), and so does
        /// any input outside the domain: `r ≤ 0`, `z_n ≤ 0`, `z_n = +∞`, or a
        /// NaN anywhere. Never NaN, never negative; `+∞` only when the true
        /// value exceeds the largest finite number (or `r = +∞`).
        ///
        /// **Numerics**: the difference of reciprocals cancels as `z_p → z_n`;
        /// it is evaluated as `(w·r/z_n)·2` with `w = 1 − z_n/z_p` formed as
        /// `(z_p − z_n)/z_p` for `z_p ≤ 2z_n`, where the difference is exact
        /// (Sterbenz: a receiver a few ulps behind the edge keeps a relative
        /// error of a few ulps), and as `1 − z_n/z_p` beyond, where nothing
        /// cancels. No product `z_n·z_p` can overflow. Each step is a
        /// correctly rounded monotone function, so `dmax` is non-decreasing
        /// in `z_p` at every float, not only up to rounding.
        ///
        /// **Accuracy**: `w` is within `2·2⁻⁵³` relative (`f32`: `2·2⁻²⁴`),
        /// the product and the quotient round once each and the doubling is
        /// exact: relative error at most `4·2⁻⁵³`, i.e. 4 ulp, when
        /// `r·(1 − z_n/z_p)` is a normal number. Measured against a
        /// double-double evaluation over the stiff generator
        /// (`tests/distortion.rs`, 4·10⁶ samples): max 2.54 ulp (`f64`),
        /// 2.66 ulp (`f32`); table in `docs/accuracy/kernels.md`.
        #[must_use]
        #[inline]
        pub fn max_distortion(light_radius: $T, z_near: $T, z_receiver: $T) -> $T {
            super::max_distortion(light_radius, z_near, z_receiver)
        }

        /// The normalised penumbra position `t = 1 − d/dmax ∈ [0, 1]` of a
        /// fragment whose distortion to the outer edge of the distortion
        /// region is `d`, when the largest distortion at its depth is `dmax`
        /// (SSOC eq. 1): `1` at the outer edge of the penumbra (`d = 0`),
        /// `0` at the inner edge (`d = dmax`).
        ///
        /// **Domain**: `0 ≤ d ≤ dmax`, `dmax > 0`; evaluated as
        /// `(dmax − d)/dmax`, the subtraction exact for `d ≥ dmax/2`
        /// (Sterbenz), so at most two roundings (relative error ≤ `2·2⁻⁵³`,
        /// i.e. 2 ulp; measured max 1.39 ulp in `f64`, 1.45 ulp in `f32`),
        /// and the quotient never leaves `[0, 1]` (no division of a large
        /// `d` by a tiny `dmax`).
        ///
        /// **Edge of the domain** (total, never NaN):
        /// - `d ≤ 0` (including `−0` and `−∞`): `1`, whatever `dmax` is;
        /// - `d ≥ dmax`, or `d > 0` with `dmax ≤ 0` or NaN: `0` — the hard step
        ///   of a zero-width penumbra;
        /// - `dmax = +∞` with finite `d`: `1` (the limit);
        /// - `d` NaN: `0`.
        #[must_use]
        #[inline]
        pub fn penumbra_position(d: $T, dmax: $T) -> $T {
            super::penumbra_position(d, dmax)
        }

        /// SSOC's shadow intensity (eq. 1 with the paper's smoothing,
        /// §3.2.2): `falloff(1 − d/dmax)` = `falloff(`[`penumbra_position`]`)`,
        /// `1` fully lit, `0` fully shadowed.
        ///
        /// **Domain and edge of the domain**: as [`penumbra_position`]:
        /// `d ≤ 0` gives `1`; `dmax = 0` (a receiver at the edge's depth or in
        /// front of it, see [`max_distortion`]) is a hard step, `1` for
        /// `d ≤ 0` and `0` for `d > 0`; `d` beyond `dmax` gives `0`; NaN `d`
        /// gives `0`. Never NaN; always in `[0, 1]`; non-increasing in `d`.
        ///
        /// **Accuracy**: the error of `t` (≤ 2 ulp relative) times the
        /// falloff's slope (≤ 1.5 for Bernstein, ≤ 4/π for the exact
        /// falloff), plus the falloff's own error (see
        /// [`falloff::bernstein`](crate::kernel::falloff::f64::bernstein),
        /// [`falloff::disk_edge_falloff`](crate::kernel::falloff::f64::disk_edge_falloff)); measured:
        /// `tests/distortion.rs`, `docs/accuracy/kernels.md`.
        #[must_use]
        #[inline]
        pub fn intensity(d: $T, dmax: $T, falloff: Falloff) -> $T {
            super::intensity(d, dmax, falloff)
        }
    };
}

both_precisions!(precision);
