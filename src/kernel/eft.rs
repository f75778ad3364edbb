//! Error-free transformations shared by the kernels and the predicates.
//!
//! `two_prod(a, b)` returns `(p, e)` with `p = fl(a · b)` and `a · b = p + e`
//! exactly (barring underflow of `e` and overflow of the split). With a
//! hardware FMA enabled at build time it is `e = fma(a, b, −p)`; otherwise
//! Dekker's product with Veltkamp's split. Both are exact, so both give the
//! same bits and no result depends on the target features. (Calling
//! `mul_add` without hardware FMA goes through a software routine that costs
//! more than a whole kernel.)

macro_rules! eft {
    ($T:ident) => {
        use crate::kernel::lanes::Real;

        /// `a · b = p + e` exactly; see the module docs.
        #[inline(always)]
        pub(crate) fn two_prod<R: Real<Scalar = $T>>(a: R, b: R) -> (R, R) {
            #[cfg(target_feature = "fma")]
            {
                two_prod_fma(a, b)
            }
            #[cfg(not(target_feature = "fma"))]
            {
                let p = a * b;
                // Veltkamp's split: x = hi + lo with half-width halves.
                const SPLIT: $T = ((1u64 << <$T>::MANTISSA_DIGITS.div_ceil(2)) + 1) as $T;
                let split = |x: R| {
                    let c = R::splat(SPLIT) * x;
                    let hi = c - (c - x);
                    (hi, x - hi)
                };
                let (ah, al) = split(a);
                let (bh, bl) = split(b);
                (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
            }
        }

        /// [`two_prod`] by a fused multiply-add: the same bits, fast only
        /// where a hardware FMA is enabled (at build time, or in a function
        /// compiled for it); elsewhere `mul_add` is a software routine.
        #[inline(always)]
        pub(crate) fn two_prod_fma<R: Real<Scalar = $T>>(a: R, b: R) -> (R, R) {
            let p = a * b;
            (p, a.mul_add(b, -p))
        }
    };
}

pub(crate) mod f64 {
    eft!(f64);
}

pub(crate) mod f32 {
    eft!(f32);
}

#[cfg(test)]
mod tests {
    #[test]
    fn two_prod_is_exact() {
        // (1 + 2⁻³⁰)² = 1 + 2⁻²⁹ + 2⁻⁶⁰: the last term is the error.
        let x = 1.0 + 2f64.powi(-30);
        assert_eq!(
            super::f64::two_prod(x, x),
            (1.0 + 2f64.powi(-29), 2f64.powi(-60))
        );
        let y = 1.0 + 2f32.powi(-13);
        assert_eq!(
            super::f32::two_prod(y, y),
            (1.0 + 2f32.powi(-12), 2f32.powi(-26))
        );
    }
}
