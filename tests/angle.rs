//! The portable `atan2` against a 256-bit evaluation, in ulps of the true
//! angle, over stiff input: magnitudes across many decades, ratios at the
//! reduction boundaries, near the axes and the diagonals, signed zeros.
//!
//! `SOFTSHADOW_PRINT_ACCURACY=1 cargo test --release --test angle -- --nocapture`
//! prints the rows of `docs/accuracy/kernels.md`; `SOFTSHADOW_EXHAUSTIVE=1`
//! multiplies the sample count by 50.

mod support;
use support::{printing, samples, Big, Ctx};

use proptest::prelude::*;
use softshadow::arbitrary::Rng;
use softshadow::kernel::angle::{f32 as a32, f64 as a64};

/// The kernel catalogue's budget (ulps).
const BUDGET_ULPS: f64 = softshadow::kernel::catalogue::angle::ATAN2.bound;

fn ulp64(x: f64) -> f64 {
    let a = x.abs();
    a.next_up() - a
}

fn ulp32(x: f64) -> f64 {
    let a = x.abs() as f32;
    (a.next_up() - a) as f64
}

/// A point whose angle is stiff: near an axis, a diagonal, or a reduction
/// boundary, at any magnitude, any quadrant.
fn stiff_point(rng: &mut Rng) -> (f64, f64) {
    let t = match rng.below(7) {
        0 => rng.log_uniform(-20.0, 0.0),
        // The reduction boundaries (tan ¼ and (√10 − 1)/3), the reduction
        // centres (½ and 1), and tan(π/8).
        1 => rng.nudge(0.255_341_921_221_036_27, 4),
        2 => rng.nudge(0.720_759_220_056_126_5, 4),
        3 => rng.nudge(1.0, 4),
        4 => 0.0,
        5 => {
            let centre = [0.5, 0.414_213_562_373_095][rng.below(2) as usize];
            rng.nudge(centre, 4)
        }
        _ => rng.unit(),
    };
    let m = rng.log_uniform(-100.0, 100.0);
    let (mut x, mut y) = (m, t * m);
    if rng.chance(0.5) {
        std::mem::swap(&mut x, &mut y);
    }
    (x * rng.sign(), y * rng.sign())
}

#[test]
fn atan2_accuracy() {
    let mut ctx = Ctx::new();
    let n = samples(20_000);
    let mut rng = Rng::new(0xa7a2);
    let (mut worst64, mut worst32) = (0.0f64, 0.0f64);
    let (mut case64, mut case32) = ((0.0, 0.0), (0.0f32, 0.0f32));
    for _ in 0..n {
        let (x, y) = stiff_point(&mut rng);
        // The error is measured in 256 bits, before any rounding of the
        // reference. (The reference has no signed zero: y's sign carries it.)
        let exact = ctx.atan2(&Big::new(y), &Big::new(x));
        let exact = if y.is_sign_negative() && y == 0.0 {
            exact.neg()
        } else {
            exact
        };
        let err = Big::new(a64::atan2(y, x)).sub(&exact).to_f64().abs() / ulp64(exact.to_f64());
        if err > worst64 {
            (worst64, case64) = (err, (y, x));
        }
        let (x32, y32) = (x as f32, y as f32);
        if x32.is_finite() && y32.is_finite() && (x32 != 0.0 || y32 != 0.0) {
            let exact = ctx.atan2(&Big::new(y32 as f64), &Big::new(x32 as f64));
            let exact = if y32.is_sign_negative() && y32 == 0.0 {
                exact.neg()
            } else {
                exact
            };
            let got = a32::atan2(y32, x32) as f64;
            let err = Big::new(got).sub(&exact).to_f64().abs() / ulp32(exact.to_f64());
            if err > worst32 {
                (worst32, case32) = (err, (y32, x32));
            }
        }
    }
    if printing() {
        println!("| angle::atan2 | f64 | {worst64:.2} ulp | stiff_point | {n} |");
        println!("| angle::atan2 | f32 | {worst32:.2} ulp | stiff_point | {n} |");
        println!("worst: atan2{case64:?} / atan2{case32:?}");
    }
    assert!(
        worst64 <= BUDGET_ULPS,
        "f64: {worst64} ulp at atan2{case64:?}"
    );
    assert!(
        worst32 <= BUDGET_ULPS,
        "f32: {worst32} ulp at atan2{case32:?}"
    );
}

#[test]
fn reference_converts_subnormals_exactly() {
    // 2⁻¹⁰⁷⁴ · 2¹⁰⁷⁴ = 1 and 3·2⁻¹⁰⁷⁴ · 2¹⁰⁷⁴ = 3, computed in 256 bits.
    let scale = Big::new(2f64.powi(1000)).mul(&Big::new(2f64.powi(74)));
    assert_eq!(Big::new(f64::from_bits(1)).mul(&scale).to_f64(), 1.0);
    assert_eq!(Big::new(f64::from_bits(3)).mul(&scale).to_f64(), 3.0);
    assert_eq!(Big::new(-f64::from_bits(3)).mul(&scale).to_f64(), -3.0);
}

#[test]
fn special_values_match_ieee() {
    for (y, x) in [
        (0.0, 0.0),
        (-0.0, 0.0),
        (0.0, -0.0),
        (-0.0, -0.0),
        (1.0, 0.0),
        (-1.0, -0.0),
        (0.0, -1.0),
        (-0.0, -1.0),
        (f64::INFINITY, 1.0),
        (1.0, f64::NEG_INFINITY),
        (f64::INFINITY, f64::INFINITY),
    ] {
        let (got, want) = (a64::atan2(y, x), y.atan2(x));
        assert!(
            got == want && got.is_sign_negative() == want.is_sign_negative(),
            "atan2({y}, {x}) = {got}, IEEE {want}"
        );
    }
    // NaN in, the documented total answer out.
    assert_eq!(a64::atan2(f64::NAN, 1.0), 0.0);
    assert_eq!(a32::atan2(1.0, f32::NAN), 0.0);
    assert_eq!(a64::atan2(f64::NAN, f64::INFINITY), 0.0);
}

proptest! {
    #[test]
    fn odd_and_quadrant_consistent(seed in any::<u64>()) {
        let (x, y) = stiff_point(&mut Rng::new(seed));
        let a = a64::atan2(y, x);
        prop_assert_eq!(a64::atan2(-y, x), -a);
        prop_assert!(a.abs() <= std::f64::consts::PI);
        // The quadrant of the angle is that of the point.
        if y != 0.0 {
            prop_assert_eq!(a > 0.0, y > 0.0);
        }
        if x > 0.0 {
            prop_assert!(a.abs() <= std::f64::consts::FRAC_PI_2);
        }
        prop_assert!(!a.is_nan());
        let b = a32::atan2(y as f32, x as f32);
        prop_assert_eq!(a32::atan2(-(y as f32), x as f32), -b);
    }
}

proptest! {
    #[test]
    fn total_on_any_bits(y in any::<u64>(), x in any::<u64>()) {
        let a = a64::atan2(f64::from_bits(y), f64::from_bits(x));
        prop_assert!(!a.is_nan() && a.abs() <= std::f64::consts::PI);
        let b = a32::atan2(f32::from_bits(y as u32), f32::from_bits(x as u32));
        prop_assert!(!b.is_nan() && b.abs() <= std::f32::consts::PI);
    }
}
