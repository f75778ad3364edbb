//! The exact orientation predicates against Shewchuk's adaptive ones (the
//! `robust` crate, an independent implementation), on near-degenerate input
//! where a rounded determinant gets the sign wrong.

mod support;

use proptest::prelude::*;
use robust::{Coord, Coord3D};
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3};
use softshadow::kernel::predicate::{orient2d, orient2d_value, orient3d, Sign};
use support::Big;

fn shewchuk2(a: DVec2, b: DVec2, c: DVec2) -> Sign {
    let p = |v: DVec2| Coord { x: v.x, y: v.y };
    Sign::of(robust::orient2d(p(a), p(b), p(c)))
}

fn shewchuk3(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    let p = |v: DVec3| Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    Sign::of(robust::orient3d(p(a), p(b), p(c), p(d)))
}

/// A point at a log-uniform scale (1e-40 … 1e40) around a random centre.
fn point2(rng: &mut Rng, scale: f64) -> DVec2 {
    DVec2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * scale
}

fn point3(rng: &mut Rng, scale: f64) -> DVec3 {
    DVec3::new(
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
    ) * scale
}

/// Three points on a line (to rounding), then nudged by a few ulps.
fn near_collinear(rng: &mut Rng) -> (DVec2, DVec2, DVec2) {
    let scale = rng.log_uniform(-40.0, 40.0);
    let (a, b) = (point2(rng, scale), point2(rng, scale));
    let t = match rng.below(3) {
        0 => rng.uniform(-2.0, 3.0),
        1 => 0.5,
        _ => rng.log_uniform(-8.0, 3.0),
    };
    let c = a + (b - a) * t;
    let c = DVec2::new(rng.nudge(c.x, 3), rng.nudge(c.y, 3));
    (a, b, c)
}

/// Four points on a plane (to rounding), then nudged by a few ulps.
fn near_coplanar(rng: &mut Rng) -> (DVec3, DVec3, DVec3, DVec3) {
    let scale = rng.log_uniform(-30.0, 30.0);
    let (a, b, c) = (point3(rng, scale), point3(rng, scale), point3(rng, scale));
    let (s, t) = (rng.uniform(-1.0, 2.0), rng.uniform(-1.0, 2.0));
    let d = a + (b - a) * s + (c - a) * t;
    let d = DVec3::new(rng.nudge(d.x, 2), rng.nudge(d.y, 2), rng.nudge(d.z, 2));
    (a, b, c, d)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn orient2d_value_is_accurate_to_2_pow_minus_40(seed in any::<u64>()) {
        // Against the determinant in 256-bit arithmetic (exact here: the
        // inputs are doubles within astro-float's range, four products of
        // exact differences fit in 256 bits for these scales).
        let mut rng = Rng::new(seed);
        let (a, b, c) = if rng.chance(0.5) {
            near_collinear(&mut rng)
        } else {
            (point2(&mut rng, 1.0), point2(&mut rng, 1.0), point2(&mut rng, 1.0))
        };
        let d = |x: f64, y: f64| Big::new(x).sub(&Big::new(y));
        let exact = d(a.x, c.x)
            .mul(&d(b.y, c.y))
            .sub(&d(a.y, c.y).mul(&d(b.x, c.x)))
            .to_f64();
        let v = orient2d_value(a, b, c);
        prop_assert_eq!(Sign::of(v), orient2d(a, b, c));
        prop_assert!(
            (v - exact).abs() <= exact.abs() * 2f64.powi(-40),
            "{:?} {:?} {:?}: {} vs {}", a, b, c, v, exact
        );
    }

    #[test]
    fn orient2d_agrees_with_shewchuk(seed in any::<u64>()) {
        let (a, b, c) = near_collinear(&mut Rng::new(seed));
        let s = orient2d(a, b, c);
        prop_assert_eq!(s, shewchuk2(a, b, c), "{:?} {:?} {:?}", a, b, c);
        // Antisymmetric under a swap, invariant under rotation of the roles.
        prop_assert_eq!(orient2d(b, a, c), s.flip());
        prop_assert_eq!(orient2d(b, c, a), s);
    }

    #[test]
    fn orient3d_agrees_with_shewchuk(seed in any::<u64>()) {
        let (a, b, c, d) = near_coplanar(&mut Rng::new(seed));
        let s = orient3d(a, b, c, d);
        prop_assert_eq!(s, shewchuk3(a, b, c, d), "{:?} {:?} {:?} {:?}", a, b, c, d);
        prop_assert_eq!(orient3d(b, a, c, d), s.flip());
    }

    #[test]
    fn orient3d_on_and_near_axis_planes_agrees_with_shewchuk(seed in any::<u64>()) {
        // Four points in a plane `x_k = h` (a receiver on a floor against
        // the floor's triangles: the exact path's zero-column shortcut),
        // or with one of them nudged off it by a few ulps, or with a
        // repeated corner — differences exact or not.
        let mut rng = Rng::new(seed);
        let scale = rng.log_uniform(-30.0, 30.0);
        let k = rng.below(3) as usize;
        let h = if rng.chance(0.3) { 0.0 } else { rng.uniform(-2.0, 2.0) * scale };
        let mut pts = [0, 1, 2, 3].map(|_| {
            let mut v = point3(&mut rng, scale).to_array();
            v[k] = h;
            v
        });
        if rng.chance(0.5) {
            let i = rng.below(4) as usize;
            let ulps = 1 + rng.below(4);
            // Off the plane by a few ulps of `h`, or by a tiny in-domain
            // offset when `h = 0` (an ulp of 0 is subnormal: outside the
            // predicates' exact domain).
            pts[i][k] = if h == 0.0 {
                rng.sign() * scale * 2f64.powi(-60 - ulps as i32)
            } else {
                rng.nudge(h, ulps)
            };
        }
        if rng.chance(0.2) {
            pts[3] = pts[rng.below(3) as usize];
        }
        let [a, b, c, d] = pts.map(DVec3::from_array);
        let s = orient3d(a, b, c, d);
        prop_assert_eq!(s, shewchuk3(a, b, c, d), "{:?} {:?} {:?} {:?}", a, b, c, d);
        prop_assert_eq!(orient3d(a, c, b, d), s.flip());
    }

    #[test]
    fn total_on_any_bits(bits in proptest::collection::vec(any::<u64>(), 12)) {
        let f = |i: usize| f64::from_bits(bits[i]);
        let v2 = |i: usize| DVec2::new(f(i), f(i + 1));
        let v3 = |i: usize| DVec3::new(f(i), f(i + 1), f(i + 2));
        let s2 = orient2d(v2(0), v2(2), v2(4));
        let s3 = orient3d(v3(0), v3(3), v3(6), v3(9));
        if !(0..6).all(|i| f(i).is_finite()) {
            prop_assert_eq!(s2, Sign::Zero);
        }
        if !(0..12).all(|i| f(i).is_finite()) {
            prop_assert_eq!(s3, Sign::Zero);
        }
    }
}

#[test]
fn exactly_collinear_and_coplanar_points_are_zero() {
    // Small integers: every determinant is exact, so the truth is known.
    let mut rng = Rng::new(11);
    for _ in 0..10_000 {
        let mut i = || rng.below(2001) as f64 - 1000.0;
        let (a, b) = (DVec2::new(i(), i()), DVec2::new(i(), i()));
        let k = i();
        assert_eq!(orient2d(a, b, a + (b - a) * k), Sign::Zero);
        let (p, q, r) = (
            DVec3::new(i(), i(), i()),
            DVec3::new(i(), i(), i()),
            DVec3::new(i(), i(), i()),
        );
        let (s, t) = (i(), i());
        assert_eq!(orient3d(p, q, r, p + (q - p) * s + (r - p) * t), Sign::Zero);
    }
}

#[test]
fn classic_rounding_failure_is_decided_exactly() {
    // Kettner et al.'s example family: points near (0.5, 0.5) on the line
    // y = x, a few ulps apart, where the rounded determinant's sign is wrong
    // for a large fraction of the grid. Truth from the exact `robust`.
    let (b, c) = (DVec2::new(12.0, 12.0), DVec2::new(24.0, 24.0));
    let mut disagreements_of_naive = 0;
    for i in 0..64 {
        for j in 0..64 {
            let a = DVec2::new(
                0.5 + i as f64 * f64::EPSILON / 2.0,
                0.5 + j as f64 * f64::EPSILON / 2.0,
            );
            let truth = shewchuk2(a, b, c);
            assert_eq!(orient2d(a, b, c), truth, "{a:?}");
            let naive = (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
            disagreements_of_naive += (Sign::of(naive) != truth) as usize;
        }
    }
    // The grid does defeat the rounded evaluation (so the test has teeth).
    assert!(disagreements_of_naive > 0);
}
