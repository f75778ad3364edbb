//! Properties and measured accuracy of `kernel::distortion` (SSOC's maximal
//! distortion and distortion-to-intensity), both precisions.
//!
//! References: `dmax = 2r(z_p − z_n)/(z_n z_p)` and `t = (dmax − d)/dmax`
//! evaluated in double-double from the exact difference (TwoSum) and the
//! exact product (FMA TwoProd) of the inputs.
//!
//! `SOFTSHADOW_PRINT_ACCURACY=1 cargo test --test distortion -- --nocapture`
//! prints the accuracy table rows; `SOFTSHADOW_EXHAUSTIVE=1` runs more
//! samples.

mod support;
use support::{exhaustive, printing, ulp_at};

use proptest::prelude::*;
use softshadow::arbitrary::light::{distortion_case, DistortionCase};
use softshadow::arbitrary::Rng;
use softshadow::kernel::falloff::{self, Falloff};
use softshadow::kernel::{catalogue, distortion};

use support::dd::{two_prod, two_sum, Dd};

/// The exact `dmax` in double-double (the domain conventions as the kernel).
fn exact_dmax(r: f64, zn: f64, zp: f64) -> Dd {
    if !(r > 0.0 && zn > 0.0 && zp > zn && zn.is_finite()) {
        return Dd::new(0.0);
    }
    let two_r = Dd::new(2.0 * r);
    if zp == f64::INFINITY {
        return two_r.div(Dd::new(zn));
    }
    two_r.mul(two_sum(zp, -zn)).div(two_prod(zn, zp))
}

/// The exact `(dmax − d)/dmax` for `0 < d < dmax` (finite).
fn exact_position(d: f64, dmax: f64) -> Dd {
    two_sum(dmax, -d).div(Dd::new(dmax))
}

fn ulps(got: f64, exact: Dd, digits: i32, min_exp: i32) -> f64 {
    ((got - exact.hi) - exact.lo).abs() / ulp_at(exact.to_f64(), digits, min_exp)
}

/// A case in `f32`: the `f64` case rounded, and half the time the receiver
/// moved to a few `f32` ulps from the silhouette (rounding would otherwise
/// merge them).
fn to_f32(case: &DistortionCase, rng: &mut Rng) -> (f32, f32, f32, f32) {
    let (r, zn) = (case.light_radius as f32, case.z_near as f32);
    let mut zp = case.z_receiver as f32;
    if rng.chance(0.5) {
        zp = zn;
        let k = rng.below(17) as i64 - 8;
        for _ in 0..k.unsigned_abs() {
            zp = if k > 0 { zp.next_up() } else { zp.next_down() };
        }
    }
    (r, zn, zp, case.d as f32)
}

/// Slopes of the falloff curves (`max |f'|`): 1, 3/2 (at t = 1/2), 4/π
/// (`F'(t) = (8/π)√(t(1 − t))`, at t = 1/2).
const FALLOFFS: [(Falloff, f64); 3] = [
    (Falloff::Linear, 1.0),
    (Falloff::Bernstein, 1.5),
    (Falloff::Exact, 4.0 / core::f64::consts::PI),
];

/// Accuracy budgets of `kernel::falloff` (the kernel catalogue), in ulps,
/// including subnormal results.
fn falloff_budget(f: Falloff) -> f64 {
    catalogue::falloff::of(f).bound
}

#[test]
fn accuracy_budget() {
    let n = if exhaustive() { 4_000_000 } else { 200_000 };
    let mut rng = Rng::new(0xD157);
    let (mut dmax64, mut dmax32, mut pos64, mut pos32) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut worst = [None; 4];
    for _ in 0..n {
        let c = distortion_case(&mut rng);
        let exact = exact_dmax(c.light_radius, c.z_near, c.z_receiver);
        let got = distortion::f64::max_distortion(c.light_radius, c.z_near, c.z_receiver);
        let e = ulps(got, exact, 53, -1021);
        if e > dmax64 {
            (dmax64, worst[0]) = (e, Some(c));
        }
        if got > 0.0 && c.d > 0.0 && c.d < got {
            let e = ulps(
                distortion::f64::penumbra_position(c.d, got),
                exact_position(c.d, got),
                53,
                -1021,
            );
            if e > pos64 {
                (pos64, worst[1]) = (e, Some(c));
            }
        }
        let (r, zn, zp, d) = to_f32(&c, &mut rng);
        let exact = exact_dmax(r as f64, zn as f64, zp as f64);
        let got = distortion::f32::max_distortion(r, zn, zp);
        let e = ulps(got as f64, exact, 24, -125);
        if e > dmax32 {
            (dmax32, worst[2]) = (e, Some(c));
        }
        if got > 0.0 && d > 0.0 && d < got {
            let exact = exact_position(d as f64, got as f64);
            let e = ulps(
                distortion::f32::penumbra_position(d, got) as f64,
                exact,
                24,
                -125,
            );
            if e > pos32 {
                (pos32, worst[3]) = (e, Some(c));
            }
        }
    }
    if printing() {
        for (name, precision, e) in [
            ("max_distortion", "f64", dmax64),
            ("max_distortion", "f32", dmax32),
            ("penumbra_position", "f64", pos64),
            ("penumbra_position", "f32", pos32),
        ] {
            println!(
                "| distortion::{name} | {precision} | {e:.2} | ulp | `distortion_case` | {n} |"
            );
        }
    }
    // Budgets from the analysis (the measured maxima are 2.54/2.66 and
    // 1.39/1.45 ulp over 4e6 samples): max_distortion rounds at most four
    // times, relative error ≤ 4·2^-p, which is ≤ 4 ulp of the result;
    // penumbra_position at most twice, ≤ 2 ulp.
    let dmax = catalogue::distortion::MAX_DISTORTION.bound;
    let pos = catalogue::distortion::PENUMBRA_POSITION.bound;
    assert!(dmax64 <= dmax, "{dmax64} {:?}", worst[0]);
    assert!(dmax32 <= dmax, "{dmax32} {:?}", worst[2]);
    assert!(pos64 <= pos, "{pos64} {:?}", worst[1]);
    assert!(pos32 <= pos, "{pos32} {:?}", worst[3]);
}

/// The f32 intensity against the f64 intensity on the same (f32) input.
/// `t₃₂ = t(1 + δ₁)(1 + δ₂)` with `|δ| ≤ 2⁻²⁴` (penumbra_position rounds at
/// most twice), the f64 `t` likewise with `2⁻⁵³`; the falloff has slope at
/// most `L` and its own error budget `b` (ulps), so
/// `|I₃₂ − I₆₄| ≤ 2.0001·L·t·(2⁻²⁴ + 2⁻⁵³) + b·(ulp₃₂ + ulp₆₄)`.
#[test]
fn f32_intensity_agrees_with_f64() {
    let n = if exhaustive() { 2_000_000 } else { 200_000 };
    let mut rng = Rng::new(0x3264);
    let mut max_abs = 0.0f64;
    for _ in 0..n {
        let c = distortion_case(&mut rng);
        let (r, zn, zp, d) = to_f32(&c, &mut rng);
        let dmax = distortion::f32::max_distortion(r, zn, zp);
        let t = distortion::f64::penumbra_position(d as f64, dmax as f64);
        for (f, slope) in FALLOFFS {
            let i32v = distortion::f32::intensity(d, dmax, f) as f64;
            let i64v = distortion::f64::intensity(d as f64, dmax as f64, f);
            let b = falloff_budget(f);
            let bound = 2.0001 * slope * t * (2f64.powi(-24) + 2f64.powi(-53))
                + b * (ulp_at(i64v, 24, -125) + ulp_at(i64v, 53, -1021));
            assert!(
                (i32v - i64v).abs() <= bound,
                "{f:?} {c:?}: {i32v} vs {i64v}"
            );
            max_abs = max_abs.max((i32v - i64v).abs());
        }
    }
    if printing() {
        println!("| distortion::intensity (f32 vs f64, all falloffs) | f32 | {max_abs:.2e} | abs | `distortion_case` | {n} |");
    }
}

#[test]
fn max_distortion_edge_cases() {
    use distortion::f64::max_distortion as dmax;
    // Zero at the silhouette's depth, and in front of it.
    assert_eq!(dmax(1.0, 2.0, 2.0), 0.0);
    assert_eq!(dmax(1.0, 2.0, 1.0), 0.0);
    assert_eq!(dmax(1.0, 2.0, 2f64.next_down()), 0.0);
    // One ulp behind: the exact difference, not the cancelled reciprocals.
    let zp = 2f64.next_up();
    let want = exact_dmax(1.0, 2.0, zp).to_f64();
    assert!(want > 0.0);
    assert!((dmax(1.0, 2.0, zp) - want).abs() <= 2.0 * ulp_at(want, 53, -1021));
    // Closed forms: 2r(1/z_n − 1/z_p) with exact reciprocals.
    assert_eq!(dmax(1.0, 1.0, 2.0), 1.0);
    assert_eq!(dmax(0.5, 0.25, 0.5), 2.0);
    assert_eq!(dmax(3.0, 1.0, f64::INFINITY), 6.0);
    // Outside the domain.
    for (r, zn, zp) in [
        (0.0, 1.0, 2.0),
        (-1.0, 1.0, 2.0),
        (1.0, 0.0, 2.0),
        (1.0, -1.0, 2.0),
        (f64::NAN, 1.0, 2.0),
        (1.0, f64::NAN, 2.0),
        (1.0, 1.0, f64::NAN),
        (1.0, f64::INFINITY, f64::INFINITY),
    ] {
        assert_eq!(dmax(r, zn, zp), 0.0, "{r} {zn} {zp}");
    }
    // Overflow only when the true value overflows.
    assert_eq!(dmax(1e300, 1e-10, 1.0), f64::INFINITY);
    assert!(dmax(1e300, 1e10, 2e10).is_finite());
    assert_eq!(dmax(f64::INFINITY, 1.0, 2.0), f64::INFINITY);
}

#[test]
fn intensity_edge_cases() {
    use distortion::f64::intensity;
    for (f, _) in FALLOFFS {
        for dmax in [1e-300, 0.5, 3.0, 1e300, f64::MIN_POSITIVE / 8.0] {
            // Endpoints: outer edge lit, inner edge shadowed.
            assert_eq!(intensity(0.0, dmax, f), 1.0);
            assert_eq!(intensity(-0.0, dmax, f), 1.0);
            assert_eq!(intensity(dmax, dmax, f), 0.0);
            // Clamped beyond them.
            assert_eq!(intensity(-dmax, dmax, f), 1.0);
            assert_eq!(intensity(f64::NEG_INFINITY, dmax, f), 1.0);
            assert_eq!(intensity(dmax.next_up(), dmax, f), 0.0);
            assert_eq!(intensity(f64::INFINITY, dmax, f), 0.0);
            // Halfway: every falloff gives exactly 1/2 (t = 1/2 exactly).
            assert_eq!(intensity(dmax / 2.0, dmax, f), 0.5);
        }
        // The hard step at dmax = 0 (and for dmax < 0 or NaN).
        for dmax in [0.0, -0.0, -1.0, f64::NAN] {
            assert_eq!(intensity(0.0, dmax, f), 1.0);
            assert_eq!(intensity(-1.0, dmax, f), 1.0);
            assert_eq!(intensity(f64::from_bits(1), dmax, f), 0.0);
            assert_eq!(intensity(1.0, dmax, f), 0.0);
        }
        // dmax = +∞: finite d is at the outer edge.
        assert_eq!(intensity(1e300, f64::INFINITY, f), 1.0);
        assert_eq!(intensity(f64::INFINITY, f64::INFINITY, f), 0.0);
        // NaN d.
        assert_eq!(intensity(f64::NAN, 1.0, f), 0.0);
    }
}

/// Continuity as `dmax → 0⁺`: for `d = λ·dmax` with `λ` fixed the intensity
/// is the same at every scale (powers of two, into the subnormals) — no
/// NaN and no jump on the way to the step; for fixed `d > 0` it reaches the
/// step value `0` once `dmax ≤ d`, and for `d ≤ 0` it is `1` throughout.
#[test]
fn continuous_as_dmax_vanishes() {
    for (f, _) in FALLOFFS {
        for lambda in [0.0, 0.125, 0.3, 0.5, 0.75, 0.999] {
            let at_one = distortion::f64::intensity(lambda, 1.0, f);
            let mut dmax = 1.0f64;
            while dmax > 0.0 {
                let d = lambda * dmax;
                if d == 0.0 && lambda > 0.0 {
                    // λ·dmax underflowed: the scale is no longer exact.
                    break;
                }
                if (d / dmax) == lambda {
                    assert_eq!(
                        distortion::f64::intensity(d, dmax, f),
                        at_one,
                        "{f:?} λ {lambda} dmax {dmax:e}"
                    );
                }
                dmax /= 2.0;
            }
        }
        let d = 1e-10;
        for dmax in [1e-9, 2e-10, 1e-10, 1e-11, 1e-300, 0.0] {
            let v = distortion::f64::intensity(d, dmax, f);
            if dmax <= d {
                assert_eq!(v, 0.0);
            } else {
                assert!(v > 0.0 && v < 1.0);
            }
            assert_eq!(distortion::f64::intensity(-d, dmax, f), 1.0);
        }
    }
}

proptest! {
    /// Any bit patterns: dmax ≥ 0 and never NaN; intensity and position in
    /// `[0, 1]`, never NaN.
    #[test]
    fn total_on_any_bits(a in any::<u64>(), b in any::<u64>(), c in any::<u64>(), a32 in any::<u32>(), b32 in any::<u32>(), c32 in any::<u32>()) {
        let (x, y, z) = (f64::from_bits(a), f64::from_bits(b), f64::from_bits(c));
        let m = distortion::f64::max_distortion(x, y, z);
        prop_assert!(m >= 0.0, "{x:e} {y:e} {z:e} -> {m}");
        let p = distortion::f64::penumbra_position(x, y);
        prop_assert!((0.0..=1.0).contains(&p));
        for (f, _) in FALLOFFS {
            let v = distortion::f64::intensity(x, y, f);
            prop_assert!((0.0..=1.0).contains(&v), "{f:?} {x:e} {y:e} -> {v}");
        }
        let (x, y, z) = (f32::from_bits(a32), f32::from_bits(b32), f32::from_bits(c32));
        let m = distortion::f32::max_distortion(x, y, z);
        prop_assert!(m >= 0.0);
        for (f, _) in FALLOFFS {
            let v = distortion::f32::intensity(x, y, f);
            prop_assert!((0.0..=1.0).contains(&v));
        }
    }

    /// Non-increasing in `d` for a fixed `dmax`, and equal to the falloff at
    /// the penumbra position.
    #[test]
    fn monotone_in_d_and_consistent_with_falloff(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let c1 = distortion_case(&mut rng);
        let dmax = distortion::f64::max_distortion(c1.light_radius, c1.z_near, c1.z_receiver);
        let d2 = match rng.below(3) {
            0 => dmax * rng.unit(),
            1 => rng.nudge(c1.d, 4),
            _ => distortion_case(&mut rng).d,
        };
        let (lo, hi) = (c1.d.min(d2), c1.d.max(d2));
        for (f, _) in FALLOFFS {
            prop_assert!(distortion::f64::intensity(lo, dmax, f) >= distortion::f64::intensity(hi, dmax, f));
            let t = distortion::f64::penumbra_position(c1.d, dmax);
            prop_assert_eq!(distortion::f64::intensity(c1.d, dmax, f), falloff::f64::eval(f, t));
            let (lo, hi, dmax) = (lo as f32, hi as f32, dmax as f32);
            prop_assert!(distortion::f32::intensity(lo, dmax, f) >= distortion::f32::intensity(hi, dmax, f));
        }
        // The position is 1 − d/dmax within its budget (1 ulp of t, plus the
        // rounding of the comparison value 1 − d/dmax itself, 1 ulp of 1).
        if dmax > 0.0 && c1.d > 0.0 && c1.d < dmax {
            let t = distortion::f64::penumbra_position(c1.d, dmax);
            let naive = 1.0 - c1.d / dmax;
            prop_assert!((t - naive).abs() <= ulp_at(t, 53, -1021) + 2.0 * f64::EPSILON);
        }
    }

    /// dmax is non-decreasing in the receiver depth (fixed r, z_n), zero up
    /// to z_n, and affine in 1/z_p: at the harmonic midpoint z_m of z_a, z_b
    /// it is the mean of dmax(z_a) and dmax(z_b) within the kernels' 2-ulp
    /// errors plus the effect of rounding z_m (relative 2⁻⁵³·3, slope
    /// 2r/z_m²).
    #[test]
    fn max_distortion_in_depth(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let c = distortion_case(&mut rng);
        let (r, zn) = (c.light_radius, c.z_near);
        let za = c.z_receiver;
        let zb = if rng.chance(0.5) {
            rng.nudge(za, 3)
        } else {
            let other = distortion_case(&mut rng);
            other.z_receiver / other.z_near * zn
        };
        let (lo, hi) = (za.min(zb), za.max(zb));
        let dm = |z: f64| distortion::f64::max_distortion(r, zn, z);
        prop_assert!(dm(lo) <= dm(hi), "{r} {zn} {lo} {hi}");
        if lo <= zn {
            prop_assert_eq!(dm(lo), 0.0);
        }
        if lo > zn && hi.is_finite() {
            let zm = 2.0 / (1.0 / lo + 1.0 / hi);
            let mean = 0.5 * (dm(lo) + dm(hi));
            let u = f64::EPSILON / 2.0;
            let tol = 2.0 * (ulp_at(dm(lo), 53, -1021) + ulp_at(dm(hi), 53, -1021) + ulp_at(mean, 53, -1021))
                + 3.0 * u * 2.0 * r / zm;
            prop_assert!((dm(zm) - mean).abs() <= tol, "{r} {zn} {lo} {hi}: {} vs {mean}", dm(zm));
        }
    }
}

/// Regression (found by `max_distortion_in_depth`): with `z_p > 2z_n` the
/// rounded difference `z_p − z_n` made `dmax` decrease by an ulp from one
/// receiver depth to the next float. Now non-decreasing at every float.
#[test]
fn regression_dmax_monotone_at_adjacent_depths() {
    let (r, zn) = (0.004697649401245598, 109.72262243280412);
    let (lo, hi) = (377.2746833061876, 377.2746833061877);
    assert_eq!(hi, f64::next_up(lo));
    assert!(
        distortion::f64::max_distortion(r, zn, lo) <= distortion::f64::max_distortion(r, zn, hi)
    );
}

/// Walks of consecutive receiver depths from just in front of the
/// silhouette, across `2z_n` (where the evaluation switches form), and far
/// behind: `dmax` never decreases.
#[test]
fn dmax_monotone_walking_the_depth() {
    let mut rng = Rng::new(0xDEE9);
    for _ in 0..200 {
        let c = distortion_case(&mut rng);
        let (r, zn) = (c.light_radius.max(1e-3), c.z_near);
        for start in [zn, 2.0 * zn, 10.0 * zn] {
            let mut z = start;
            for _ in 0..64 {
                z = z.next_down();
            }
            let mut prev = distortion::f64::max_distortion(r, zn, z);
            for _ in 0..128 {
                z = z.next_up();
                let v = distortion::f64::max_distortion(r, zn, z);
                assert!(v >= prev, "r {r} z_n {zn} z_p {z}");
                prev = v;
            }
            let (r32, zn32) = (r as f32, zn as f32);
            let mut z = (start as f32).next_down().next_down();
            let mut prev = distortion::f32::max_distortion(r32, zn32, z);
            for _ in 0..64 {
                z = z.next_up();
                let v = distortion::f32::max_distortion(r32, zn32, z);
                assert!(v >= prev, "f32: r {r32} z_n {zn32} z_p {z}");
                prev = v;
            }
        }
    }
}
