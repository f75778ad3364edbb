//! Falloff and SSOC distortion kernels: invariants and cross-checks on
//! fuzzed input.
//!
//! The first 8 bytes seed the stiff generators of `softshadow::arbitrary`
//! (positions a few ulps from the branch points, tiny `t`, receivers a few
//! ulps behind the silhouette); the following words are read as raw `f64`
//! and `f32` bit patterns (anything, NaN and ±∞ included).
#![no_main]

use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::light::{distortion_case, falloff_t, falloff_t_f32};
use softshadow::arbitrary::Rng;
use softshadow::kernel::{catalogue, distortion};
use softshadow::kernel::falloff::{self, Falloff};

const FALLOFFS: [Falloff; 3] = [Falloff::Linear, Falloff::Bernstein, Falloff::Exact];

/// The accuracy budgets of the falloff kernels (the kernel catalogue), in
/// ulps, subnormal results included: Linear, Bernstein, Exact.
const BUDGET: [f64; 3] = [
    catalogue::falloff::of(Falloff::Linear).bound,
    catalogue::falloff::of(Falloff::Bernstein).bound,
    catalogue::falloff::of(Falloff::Exact).bound,
];

fn word(data: &[u8], i: usize) -> u64 {
    let mut w = [0u8; 8];
    for (j, b) in w.iter_mut().enumerate() {
        *b = data.get(8 * i + j).copied().unwrap_or(0);
    }
    u64::from_le_bytes(w)
}

/// An ulp of the type with `digits` significand bits at `x` (x ≥ 0).
fn ulp(x: f64, digits: i32, min_exp: i32) -> f64 {
    let e = if x == 0.0 {
        min_exp
    } else {
        (((x.abs().to_bits() >> 52) & 0x7ff) as i32 - 1022).max(min_exp)
    };
    let k = e - digits;
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

fn check_falloff_f64(t: f64, t2: f64) {
    for (c, b) in FALLOFFS.into_iter().zip(BUDGET) {
        let v = falloff::f64::eval(c, t);
        assert!((0.0..=1.0).contains(&v), "{c:?}({t:e}) = {v}");
        if t.is_nan() || t <= 0.0 {
            assert_eq!(v, 0.0);
        }
        // Monotone pairs.
        if !t2.is_nan() {
            let w = falloff::f64::eval(c, t2);
            if t <= t2 {
                assert!(v <= w, "{c:?}: f({t:e}) = {v} > f({t2:e}) = {w}");
            } else if t >= t2 {
                assert!(v >= w, "{c:?}: f({t:e}) = {v} < f({t2:e}) = {w}");
            }
        }
        // Symmetry where 1 − t is exact (t ∈ [1/2, 1]): each value within its
        // budget of the exact one, and the exact values sum to 1. The sum is
        // formed exactly (TwoSum; `sum − 1` is exact by Sterbenz).
        if (0.5..=1.0).contains(&t) {
            let s = 1.0 - t;
            let w = falloff::f64::eval(c, s);
            let sum = v + w;
            let err = (v - (sum - (sum - v))) + (w - (sum - v));
            let excess = (sum - 1.0) + err;
            let bound = b * (ulp(v, 53, -1021) + ulp(w, 53, -1021));
            assert!(
                excess.abs() <= bound,
                "{c:?}: f({t}) + f({s}) − 1 = {excess:e}"
            );
        }
    }
}

fn check_falloff_f32(t: f32) {
    for (c, b) in FALLOFFS.into_iter().zip(BUDGET) {
        let v = falloff::f32::eval(c, t);
        assert!((0.0..=1.0).contains(&v), "{c:?}({t:e}) = {v}");
        // f32 against f64 on the same input, within both budgets.
        let w = falloff::f64::eval(c, t as f64);
        let bound = b * (ulp(w, 24, -125) + ulp(w, 53, -1021));
        assert!(
            (v as f64 - w).abs() <= bound,
            "{c:?}({t:e}): f32 {v} vs f64 {w}"
        );
    }
}

fuzz_target!(|data: &[u8]| {
    let mut rng = Rng::new(word(data, 0));

    // Falloff: generated and raw inputs.
    let (t, t2) = (falloff_t(&mut rng), falloff_t(&mut rng));
    check_falloff_f64(t, t2);
    check_falloff_f64(f64::from_bits(word(data, 1)), f64::from_bits(word(data, 2)));
    check_falloff_f32(falloff_t_f32(&mut rng));
    check_falloff_f32(f32::from_bits(word(data, 3) as u32));

    // The exact falloff against the closed form as written, where that is
    // well-conditioned (h = 1 − 2t exact, |h| ≤ 1/2: acos within an ulp of
    // π, the root within 2 ulp, so the formula is within ~2e-15 absolute).
    if (0.25..=0.75).contains(&t) {
        let h = 1.0 - 2.0 * t;
        let naive = (h.acos() - h * (4.0 * t * (1.0 - t)).sqrt()) / core::f64::consts::PI;
        let v = falloff::f64::disk_edge_falloff(t);
        assert!((v - naive).abs() <= 4e-15, "t = {t}: {v} vs {naive}");
    }

    // Distortion: dmax ≥ 0, never NaN, non-decreasing in the receiver depth.
    let c = distortion_case(&mut rng);
    let dmax = distortion::f64::max_distortion(c.light_radius, c.z_near, c.z_receiver);
    assert!(dmax >= 0.0, "{c:?}");
    let z2 = f64::from_bits(word(data, 4));
    let dmax2 = distortion::f64::max_distortion(c.light_radius, c.z_near, z2);
    if z2 >= c.z_receiver {
        assert!(dmax2 >= dmax, "{c:?} z2 = {z2:e}");
    } else if z2 <= c.z_receiver {
        assert!(dmax2 <= dmax, "{c:?} z2 = {z2:e}");
    }
    let raw = [5, 6, 7].map(|i| f64::from_bits(word(data, i)));
    assert!(distortion::f64::max_distortion(raw[0], raw[1], raw[2]) >= 0.0);

    // Intensity: in [0, 1], never NaN, the step conventions, non-increasing
    // in d, and the falloff at the penumbra position.
    for (d, m) in [(c.d, dmax), (raw[0], raw[1])] {
        let d2 = f64::from_bits(word(data, 8));
        for f in FALLOFFS {
            let i = distortion::f64::intensity(d, m, f);
            assert!((0.0..=1.0).contains(&i), "{f:?} d {d:e} dmax {m:e}");
            assert_eq!(
                i,
                falloff::f64::eval(f, distortion::f64::penumbra_position(d, m))
            );
            if d <= 0.0 {
                assert_eq!(i, 1.0);
            }
            if d > 0.0 && (m.is_nan() || m <= 0.0) {
                assert_eq!(i, 0.0);
            }
            if !d2.is_nan() && !d.is_nan() {
                let j = distortion::f64::intensity(d2, m, f);
                if d <= d2 {
                    assert!(i >= j, "{f:?}: d {d:e} d2 {d2:e} dmax {m:e}");
                } else {
                    assert!(i <= j, "{f:?}: d {d:e} d2 {d2:e} dmax {m:e}");
                }
            }
            let i32v = distortion::f32::intensity(d as f32, m as f32, f);
            assert!((0.0..=1.0).contains(&i32v));
        }
    }
});
