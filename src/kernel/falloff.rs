//! Falloff: the lit fraction of a light across a straight-edged penumbra.
//!
//! A straight silhouette edge sweeping across a uniform disk light uncovers
//! it gradually. With `t ∈ [0, 1]` the normalised position across the
//! penumbra (`0` at its inner edge, where the light is just hidden, `1` at its
//! outer edge, where it is just wholly visible), the visible fraction is
//!
//! - [`f64::disk_edge_falloff`]: the exact answer, the fraction of a uniform
//!   disk on one side of a chord,
//!   `F(t) = (acos(1 − 2t) − (1 − 2t)·√(4t(1 − t))) / π`
//!   (DESIGN.md §3 "Falloff"; it is the regularised incomplete beta function
//!   `I_t(3/2, 3/2)`);
//! - [`f64::bernstein`]: the cubic `3t² − 2t³` that SSOC (Mo, Popescu,
//!   Wyman, §3.2.2) and the penumbra-map family use "to approximate the
//!   sinusoidal falloff of a spherical light source".
//!
//! [`Falloff`] selects one of them (or SSOC's unsmoothed linear ramp, eq. 1).
//!
//! ## How far apart the two curves are
//!
//! `max |F − bernstein| = 0.039412` (0.0394 to four decimals), attained at
//! `t* = 0.235664` and `1 − t* = 0.764336`, where `F` is brighter near the
//! inner edge and darker near the outer edge. Setting the derivative of the
//! difference to zero, `(8/π)√(t(1 − t)) = 6t(1 − t)`, gives the closed form
//! `t* = (1 − √(1 − 64/(9π²)))/2`. `tests/falloff.rs` finds the maximiser
//! independently (golden-section search) and checks both numbers.
//!
//! Both curves are in [`f32`] and [`f64`] from one body. Measured accuracy:
//! see the function docs and `docs/accuracy/kernels.md`.

/// Which curve maps the normalised penumbra position `t` to a lit fraction.
///
/// Every variant maps `[0, 1]` onto `[0, 1]`, is non-decreasing, and takes
/// the values `0`, `1/2`, `1` at `t = 0, 1/2, 1`; below `0` it is `0`, above
/// `1` it is `1`, and NaN gives `0`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Falloff {
    /// `t` itself (clamped): SSOC's eq. 1 before the paper smooths it.
    Linear,
    /// `3t² − 2t³` ([`f64::bernstein`]): SSOC §3.2.2, the paper's choice and
    /// the default.
    #[default]
    Bernstein,
    /// The exact straight-edge falloff of a uniform disk
    /// ([`f64::disk_edge_falloff`]).
    Exact,
}

macro_rules! falloff_kernels {
    ($T:ident, $SERIES_TERMS:expr) => {
        use super::Falloff;

        /// `16/(3π)`: the leading coefficient of `F(t)` at `t → 0`.
        const SIXTEEN_OVER_THREE_PI: $T = 1.697_652_726_313_550_248_201_426_809_306_82;
        const FRAC_1_PI: $T = core::$T::consts::FRAC_1_PI;

        /// Series coefficients `c_k = (3/2)·a_k/(k + 3/2)` with
        /// `a_k = (−1)^k·C(1/2, k)`, so that
        /// `F(t) = (16/(3π))·t^(3/2)·Σ c_k t^k`: integrate
        /// `F(t) = (8/π)∫₀ᵗ √s·√(1 − s) ds` term by term after expanding
        /// `√(1 − s)` binomially. All `c_k`, `k ≥ 1`, are negative and
        /// `|c_k| t^k` decreases; the tail after `K` terms is below
        /// `|c_K| t^K / (1 − t)`. For `t ≤ 1/4` that is below 0.03 ulp of the
        /// sum with 23 terms in `f64` and 10 terms in `f32`.
        const SERIES: [$T; 23] = [
            1.0,
            -3.0 / 10.0,
            -3.0 / 56.0,
            -1.0 / 48.0,
            -15.0 / 1408.0,
            -21.0 / 3328.0,
            -21.0 / 5120.0,
            -99.0 / 34816.0,
            -1287.0 / 622592.0,
            -715.0 / 458752.0,
            -7293.0 / 6029312.0,
            -12597.0 / 13107200.0,
            -29393.0 / 37748736.0,
            -156009.0 / 243269632.0,
            -557175.0 / 1040187392.0,
            -334305.0 / 738197504.0,
            -5816907.0 / 15032385536.0,
            -53036505.0 / 158913789952.0,
            -64822395.0 / 223338299392.0,
            -358229025.0 / 1408749273088.0,
            -2650894785.0 / 11819749998592.0,
            -109402007.0 / 549755813888.0,
            -18349700265.0 / 103354093010944.0,
        ];
        /// Terms of [`SERIES`] this precision needs on `t ≤ 1/4`.
        const SERIES_TERMS: usize = $SERIES_TERMS;

        /// The Bernstein smoothstep `3t² − 2t³` (SSOC, Mo, Popescu, Wyman,
        /// §3.2.2: "the Bernstein interpolant s = 3t² − 2t³").
        ///
        /// **Domain**: `[0, 1]`; below `0` the result is `0`, above `1` it is
        /// `1` (clamped). NaN gives `0`. Never NaN.
        ///
        /// **Properties**: `bernstein(0) = 0`, `bernstein(1/2) = 1/2`,
        /// `bernstein(1) = 1` exactly; `t > 1/2` is evaluated as
        /// `1 − bernstein(1 − t)` with `1 − t` exact, so the symmetry
        /// `bernstein(t) + bernstein(1 − t) = 1` holds to half an ulp of 1.
        ///
        /// **Accuracy**: within 1.5 ulp of the exact cubic on `[0, 1]`
        /// (measured against a double-double evaluation, `tests/falloff.rs`;
        /// table in `docs/accuracy/kernels.md`).
        #[must_use]
        #[inline]
        pub fn bernstein(t: $T) -> $T {
            if t.is_nan() || t <= 0.0 {
                return 0.0;
            }
            if t >= 1.0 {
                return 1.0;
            }
            if t <= 0.5 {
                t * t * (3.0 - 2.0 * t)
            } else {
                // 1 − t is exact for t ≥ 1/2 (Sterbenz).
                let s = 1.0 - t;
                1.0 - s * s * (3.0 - 2.0 * s)
            }
        }

        /// The exact fraction of a uniform disk on the lit side of a straight
        /// edge, `t` the normalised position across the penumbra (DESIGN.md
        /// §3 "Falloff"):
        ///
        /// `F(t) = (acos(1 − 2t) − (1 − 2t)·√(4t(1 − t))) / π`,
        ///
        /// the area of the circular segment of height `2t` of the unit disk
        /// over `π`.
        ///
        /// **Domain**: `[0, 1]`; below `0` the result is `0`, above `1` it is
        /// `1`, NaN gives `0`. Never NaN. Non-decreasing; `F(0) = 0`,
        /// `F(1/2) = 1/2` and `F(1) = 1` exactly.
        ///
        /// **Numerics**: the formula as written takes `acos` near `±1` and
        /// cancels catastrophically for thin slivers. Instead:
        /// - `t ≤ 1/4`: the series `F = (16/(3π)) t^(3/2) Σ c_k t^k` (see
        ///   `SERIES` in the source: truncation below 0.03 ulp), full relative
        ///   accuracy down to the smallest `t` whose `t^(3/2)` is normal;
        /// - `1/4 < t < 3/4`: with `h = 1 − 2t` (exact there, Sterbenz),
        ///   `F = 1/2 − (asin h + h√(1 − h²))/π`: `asin` of an exact argument
        ///   `|h| ≤ 1/2`, a sum of like-signed terms, and a final subtraction
        ///   that at worst halves the result (no cancellation beyond one bit);
        /// - `t ≥ 3/4`: `1 − F(1 − t)`, with `1 − t` exact, so the symmetry
        ///   `F(t) + F(1 − t) = 1` holds to about an ulp of 1.
        ///
        /// **Accuracy**: within 2 ulp (`f64`) and 2 ulp (`f32`) of the exact
        /// value over the stiff generators (measured against a
        /// double-double series evaluation, `tests/falloff.rs`; table in
        /// `docs/accuracy/kernels.md`).
        ///
        /// **Source**: circular-segment area; DESIGN.md §3.
        #[must_use]
        #[inline]
        pub fn disk_edge_falloff(t: $T) -> $T {
            if t.is_nan() || t <= 0.0 {
                return 0.0;
            }
            if t >= 1.0 {
                return 1.0;
            }
            if t <= 0.25 {
                thin_sliver(t)
            } else if t >= 0.75 {
                // 1 − t is exact for t ≥ 1/2 (Sterbenz).
                1.0 - thin_sliver(1.0 - t)
            } else {
                // h = 1 − 2t is exact for 1/4 ≤ t ≤ 1 (Sterbenz), |h| ≤ 1/2.
                let h = 1.0 - 2.0 * t;
                let w = (-h).mul_add(h, 1.0).sqrt();
                0.5 - (h.asin() + h * w) * FRAC_1_PI
            }
        }

        /// `F(t)` for `0 < t ≤ 1/4` by the series (see [`SERIES`]).
        #[inline]
        fn thin_sliver(t: $T) -> $T {
            // Horner from the highest kept term; the leading 1 is added last,
            // so the rounding of the tail is damped by |c₁|t ≤ 0.075.
            let mut tail: $T = SERIES[SERIES_TERMS - 1];
            let mut k = SERIES_TERMS - 1;
            while k > 1 {
                k -= 1;
                tail = tail * t + SERIES[k];
            }
            let sum = 1.0 + t * tail;
            SIXTEEN_OVER_THREE_PI * (t * t.sqrt()) * sum
        }

        /// The chosen falloff curve at `t` (see [`Falloff`]): `t` clamped to
        /// `[0, 1]` for [`Falloff::Linear`], [`bernstein`] or
        /// [`disk_edge_falloff`]. NaN gives `0`; never NaN.
        #[must_use]
        #[inline]
        pub fn eval(falloff: Falloff, t: $T) -> $T {
            match falloff {
                Falloff::Linear => {
                    if t > 0.0 {
                        t.min(1.0)
                    } else {
                        0.0
                    }
                }
                Falloff::Bernstein => bernstein(t),
                Falloff::Exact => disk_edge_falloff(t),
            }
        }

        #[cfg(test)]
        mod tests {
            use super::*;

            /// The series coefficients are the exact rationals of the
            /// recurrence `a_k = a_{k−1}(k − 3/2)/k`, `c_k = (3/2)a_k/(k + 3/2)`,
            /// each rounded once (numerator and denominator are exact below
            /// 2⁵³, so the `f64` division rounds correctly).
            #[test]
            fn series_coefficients_match_the_recurrence() {
                // a_k = num/den with a_0 = 1.
                let (mut num, mut den): (i128, i128) = (1, 1);
                for k in 0..SERIES.len() as i128 {
                    if k > 0 {
                        num *= 2 * k - 3;
                        den *= 2 * k;
                    }
                    // c_k = 3 a_k / (2k + 3)
                    let (mut cn, mut cd) = (3 * num, den * (2 * k + 3));
                    let g = gcd(cn.abs(), cd);
                    cn /= g;
                    cd /= g;
                    assert!(cn.abs() < 1 << 53 && cd < 1 << 53);
                    let expected = (cn as f64) / (cd as f64);
                    let got = SERIES[k as usize] as f64;
                    if <$T>::MANTISSA_DIGITS == 53 {
                        assert_eq!(got, expected, "k = {k}");
                    } else {
                        // f32 literals may round twice (numerator, then the
                        // quotient): within 2 ulp.
                        let tol = 2.0 * (<$T>::EPSILON as f64) * expected.abs();
                        assert!((got - expected).abs() <= tol, "k = {k}");
                    }
                }
            }

            fn gcd(mut a: i128, mut b: i128) -> i128 {
                while b != 0 {
                    (a, b) = (b, a % b);
                }
                a
            }

            #[test]
            fn fixed_points() {
                for f in [bernstein as fn($T) -> $T, disk_edge_falloff] {
                    assert_eq!(f(0.0), 0.0);
                    assert_eq!(f(0.5), 0.5);
                    assert_eq!(f(1.0), 1.0);
                    assert_eq!(f(<$T>::NAN), 0.0);
                    assert_eq!(f(-1.0), 0.0);
                    assert_eq!(f(2.0), 1.0);
                }
            }
        }
    };
}

/// `f64` versions.
pub mod f64 {
    falloff_kernels!(f64, 23);
}

/// `f32` versions.
pub mod f32 {
    falloff_kernels!(f32, 10);
}
