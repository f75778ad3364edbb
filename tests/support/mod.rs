//! Shared test support: 256-bit reference arithmetic and Monte Carlo
//! statistics. Included with `mod support;` by the test files that need it.
//! (`raster.rs` and `scene_file.rs` here are not part of it: the
//! rasterizer's and the scene file's tests include each on its own, with
//! `#[path]`.)
#![allow(dead_code)]

pub mod dd;
pub mod view;

use astro_float::{BigFloat, Consts, RoundingMode, Sign};

/// `true` when the environment variable is set to anything but `0` or empty.
fn flag(name: &str) -> bool {
    std::env::var_os(name).is_some_and(|v| !v.is_empty() && v != "0")
}

/// `SOFTSHADOW_EXHAUSTIVE`: the long, opt-in runs.
pub fn exhaustive() -> bool {
    flag("SOFTSHADOW_EXHAUSTIVE")
}

/// `SOFTSHADOW_PRINT_ACCURACY`: print the rows of `docs/accuracy/kernels.md`.
pub fn printing() -> bool {
    flag("SOFTSHADOW_PRINT_ACCURACY")
}

/// A sample count: `default`, or 50 times it in exhaustive runs.
pub fn samples(default: usize) -> usize {
    if exhaustive() {
        default * 50
    } else {
        default
    }
}

/// Working precision of the references, in bits.
pub const P: usize = 256;
const RM: RoundingMode = RoundingMode::ToEven;

/// A 256-bit float with the few operations the references need.
#[derive(Clone, Debug)]
pub struct Big(pub BigFloat);

impl Big {
    pub fn new(x: f64) -> Big {
        if x != 0.0 && x.abs() < f64::MIN_POSITIVE {
            // astro-float converts subnormals wrongly: scale into the normal
            // range (exactly), convert, and scale back in 256 bits.
            let scaled = Big(BigFloat::from_f64(x * 2f64.powi(128), P));
            return scaled.div(&Big(BigFloat::from_f64(2f64.powi(128), P)));
        }
        Big(BigFloat::from_f64(x, P))
    }
    pub fn zero() -> Big {
        Big::new(0.0)
    }
    pub fn add(&self, o: &Big) -> Big {
        Big(self.0.add(&o.0, P, RM))
    }
    pub fn sub(&self, o: &Big) -> Big {
        Big(self.0.sub(&o.0, P, RM))
    }
    pub fn mul(&self, o: &Big) -> Big {
        Big(self.0.mul(&o.0, P, RM))
    }
    pub fn div(&self, o: &Big) -> Big {
        Big(self.0.div(&o.0, P, RM))
    }
    pub fn sqrt(&self) -> Big {
        Big(self.0.sqrt(P, RM))
    }
    pub fn neg(&self) -> Big {
        Big(self.0.neg())
    }
    pub fn is_zero(&self) -> bool {
        self.0.is_zero()
    }
    pub fn is_negative(&self) -> bool {
        !self.is_zero() && self.0.sign() == Some(Sign::Neg)
    }
    pub fn is_positive(&self) -> bool {
        !self.is_zero() && self.0.sign() == Some(Sign::Pos)
    }
    pub fn lt(&self, o: &Big) -> bool {
        self.0.cmp(&o.0).is_some_and(|c| c < 0)
    }

    /// The nearest `f64` (to within one rounding of the leading word).
    pub fn to_f64(&self) -> f64 {
        if self.is_zero() {
            return 0.0;
        }
        let (words, _, sign, exp, _) = self.0.as_raw_parts().expect("a finite value");
        let top = *words.last().expect("a mantissa word");
        let next = if words.len() > 1 {
            words[words.len() - 2]
        } else {
            0
        };
        // value = 0.top next … × 2^exp: fold 128 bits, round once.
        let m = ((top as u128) << 64) | next as u128;
        let v = (m as f64) * 2f64.powi(exp - 128);
        if sign == Sign::Neg {
            -v
        } else {
            v
        }
    }
}

/// `2^k` for `-1074 ≤ k ≤ 1023`, exactly (`powi` would overflow in its
/// reciprocal for very negative `k`).
pub fn pow2(k: i32) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

/// The spacing of the floating-point type with `digits` significand bits and
/// smallest normal exponent `min_exp` at `x` (an ulp of the exact value):
/// `(53, -1021)` for `f64`, `(24, -125)` for `f32`.
pub fn ulp_at(x: f64, digits: i32, min_exp: i32) -> f64 {
    let x = x.abs();
    let e = if x == 0.0 {
        min_exp
    } else {
        (((x.to_bits() >> 52) & 0x7ff) as i32 - 1022).max(min_exp)
    };
    pow2(e - digits)
}

/// Constants cache for π and the transcendental functions.
pub struct Ctx(pub Consts);

impl Ctx {
    pub fn new() -> Ctx {
        Ctx(Consts::new().expect("astro-float constants"))
    }
    pub fn pi(&mut self) -> Big {
        Big(self.0.pi(P, RM))
    }
    pub fn atan(&mut self, x: &Big) -> Big {
        Big(x.0.atan(P, RM, &mut self.0))
    }
    /// `atan2(y, x)` in `(−π, π]`.
    pub fn atan2(&mut self, y: &Big, x: &Big) -> Big {
        if x.is_positive() {
            return self.atan(&y.div(x));
        }
        let pi = self.pi();
        if x.is_negative() {
            let base = self.atan(&y.div(x));
            return if y.is_negative() {
                base.sub(&pi)
            } else {
                base.add(&pi)
            };
        }
        let half_pi = pi.div(&Big::new(2.0));
        if y.is_positive() {
            half_pi
        } else if y.is_negative() {
            half_pi.neg()
        } else {
            Big::zero()
        }
    }
}

// The statistics (normal and Student-t quantiles, Šidák) live in the
// library, shared with the `check` command.
#[allow(unused_imports)]
pub use softshadow::reference::stats::{normal_two_sided_quantile, sidak};
