//! The Monte Carlo reference and its BVH (`softshadow::reference`).
//!
//! - The exact segment–triangle test on its boundary cases (endpoint on a
//!   face, through a vertex or an edge, coplanar, zero area).
//! - The conservative `f32` traversal against brute force over every
//!   triangle, on near-degenerate soups far from the origin (proptest).
//! - The culling query returns a superset of the triangles meeting the hull
//!   (proptest against brute-force witnesses).
//! - Closed forms against the estimate, with a tolerance from the reported
//!   standard error: a Student-t quantile (the error is estimated from
//!   `K − 1` degrees of freedom) at a Šidák-corrected level over the checks
//!   of each test, so the false-failure rate per test is `ALPHA` whatever
//!   the number of checks.
//! - Exact zeros and ones (stderr 0), the watertight shared edge,
//!   determinism across seeds and thread pools, and the calibration of the
//!   standard error over many seeds.
//! - Every estimate is its rays counted, bit for bit, whatever samples it
//!   decides on the light's plane (proptest).

use proptest::prelude::*;
use softshadow::arbitrary::Rng;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::glam::DVec3;
use softshadow::kernel::segment::segment_blocked;
use softshadow::reference::monte_carlo::{
    visibility, visibility_many, Error, Estimate, Options, REPLICATES,
};
use softshadow::reference::stats::{
    normal_two_sided_quantile as z_quantile, sidak, student_t_coverage as t_coverage,
    student_t_two_sided_quantile as t_quantile,
};
use softshadow::scene::{Light, ReceiverError};
use std::f64::consts::PI;

/// Family-wise false-failure probability of each statistical test.
const ALPHA: f64 = 1e-4;

fn v3(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn bvh(triangles: Vec<[DVec3; 3]>) -> Bvh {
    Bvh::new(Occluders::from_triangles(triangles))
}

/// Asserts `|estimate − exact| ≤ q · stderr`.
fn assert_agrees(e: Estimate, exact: f64, q: f64, what: &str) {
    assert!(
        (e.visibility - exact).abs() <= q * e.stderr,
        "{what}: estimate {e:?} vs exact {exact} (allowed {q} stderr)"
    );
    assert!((0.0..=1.0).contains(&e.visibility) && e.stderr.is_finite());
}

// ---------------------------------------------------------------------
// The exact segment–triangle test.

const FLOOR: [DVec3; 3] = [
    DVec3::new(-4.0, -4.0, 0.0),
    DVec3::new(4.0, -4.0, 0.0),
    DVec3::new(0.0, 4.0, 0.0),
];

#[test]
fn segment_ending_on_a_triangle_is_not_blocked() {
    let on = v3(0.25, 0.5, 0.0);
    assert!(!segment_blocked(on, v3(0.3, 0.1, 5.0), &FLOOR));
    assert!(!segment_blocked(v3(0.3, 0.1, -5.0), on, &FLOOR));
    // On an edge and on a vertex of it, too.
    assert!(!segment_blocked(
        v3(0.0, -4.0, 0.0),
        v3(1.0, 1.0, 3.0),
        &FLOOR
    ));
    assert!(!segment_blocked(FLOOR[2], v3(1.0, 1.0, 3.0), &FLOOR));
}

#[test]
fn segment_through_a_vertex_or_an_edge_is_blocked() {
    // Through the edge (−4,−4,0)–(4,−4,0) at (1,−4,0).
    assert!(segment_blocked(
        v3(1.0, -4.0, -1.0),
        v3(1.0, -4.0, 1.0),
        &FLOOR
    ));
    // Slanted, through the same edge point.
    assert!(segment_blocked(
        v3(0.0, -5.0, -1.0),
        v3(2.0, -3.0, 1.0),
        &FLOOR
    ));
    // Through the vertex (0,4,0).
    assert!(segment_blocked(
        v3(-1.0, 3.0, -2.0),
        v3(1.0, 5.0, 2.0),
        &FLOOR
    ));
    // Through the interior; just outside the edge is not blocked.
    assert!(segment_blocked(
        v3(0.0, 0.0, -1.0),
        v3(0.0, 0.0, 1.0),
        &FLOOR
    ));
    let outside = -4.0 - f64::EPSILON * 4.0;
    assert!(!segment_blocked(
        v3(1.0, outside, -1.0),
        v3(1.0, outside, 1.0),
        &FLOOR
    ));
}

#[test]
fn coplanar_and_degenerate_cases_are_not_blocked() {
    // In the plane, across the whole triangle.
    assert!(!segment_blocked(
        v3(-10.0, 0.0, 0.0),
        v3(10.0, 0.0, 0.0),
        &FLOOR
    ));
    // Zero-area triangles: collinear corners and a repeated corner.
    let line = [v3(-1.0, 0.0, 0.0), v3(0.0, 0.0, 0.0), v3(1.0, 0.0, 0.0)];
    let point = [v3(0.0, 0.0, 0.0); 3];
    for t in [&line, &point] {
        assert!(!segment_blocked(v3(0.0, 0.0, -1.0), v3(0.0, 0.0, 1.0), t));
    }
    // Non-finite corners block nothing, and the BVH leaves them out.
    let nan = [v3(f64::NAN, 0.0, 0.0), v3(1.0, 0.0, 0.0), v3(0.0, 1.0, 0.0)];
    assert!(!segment_blocked(
        v3(0.1, 0.1, -1.0),
        v3(0.1, 0.1, 1.0),
        &nan
    ));
    let b = bvh(vec![nan, FLOOR]);
    assert!(!b.segment_unoccluded(v3(0.1, 0.1, -1.0), v3(0.1, 0.1, 1.0)));
    let mut out = Vec::new();
    b.triangles_meeting_hull(
        &[v3(0.0, 0.0, -1.0), v3(0.0, 0.0, 1.0), v3(1.0, 0.0, 1.0)],
        &mut out,
    );
    assert_eq!(out, vec![1]);
}

#[test]
fn empty_bvh_occludes_nothing() {
    let b = bvh(Vec::new());
    assert!(b.segment_unoccluded(v3(0.0, 0.0, 0.0), v3(1.0, 1.0, 1.0)));
    let mut out = vec![7];
    b.triangles_meeting_hull(&[v3(0.0, 0.0, 0.0)], &mut out);
    assert!(out.is_empty());
}

/// The contract of `segment_blocked`, written directly on Shewchuk's
/// predicates (the `robust` crate): an independent implementation.
fn blocked_by_spec(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> bool {
    let q = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    let o = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| {
        let v = robust::orient3d(q(a), q(b), q(c), q(d));
        i32::from(v > 0.0) - i32::from(v < 0.0)
    };
    let [a, b, c] = *t;
    let (sp, sx) = (o(a, b, c, p), o(a, b, c, x));
    let e = [o(p, x, a, b), o(p, x, b, c), o(p, x, c, a)];
    let opposite = |s: i32, t: i32| s * t < 0;
    sp != 0
        && sx == -sp
        && !(opposite(e[0], e[1]) || opposite(e[1], e[2]) || opposite(e[0], e[2]))
        && e != [0, 0, 0]
}

// ---------------------------------------------------------------------
// The traversal against brute force.

/// A soup of near-degenerate triangles around a segment `(p, x)`, all
/// offset by `offset`: triangles through the endpoints, through a point of
/// the segment, tiny ones next to an endpoint, big ones, slivers.
fn soup(rng: &mut Rng) -> (Vec<[DVec3; 3]>, DVec3, DVec3) {
    let offset = if rng.chance(0.5) {
        v3(3e4, -3e4, 2e4) * rng.uniform(0.0, 1.0)
    } else {
        DVec3::ZERO
    };
    let scale = rng.log_uniform(-4.0, 1.0);
    let point = |rng: &mut Rng| {
        offset
            + v3(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            ) * scale
    };
    let p = point(rng);
    let x = point(rng);
    let mut triangles = Vec::new();
    for _ in 0..rng.below(40) + 1 {
        let kind = rng.below(6);
        let size = scale * rng.log_uniform(-6.0, 0.5);
        let jitter = |rng: &mut Rng| {
            v3(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            ) * size
        };
        let anchor = match kind {
            0 => p,
            1 => x,
            2 => p.lerp(x, rng.unit()),
            _ => point(rng),
        };
        let t = match kind {
            // A corner exactly at the anchor.
            0..=2 if rng.chance(0.5) => [anchor, anchor + jitter(rng), anchor + jitter(rng)],
            // An edge exactly through the anchor (the anchor its midpoint).
            0..=2 => {
                let d = jitter(rng);
                [anchor - d, anchor + d, anchor + jitter(rng)]
            }
            // A sliver.
            3 => {
                let d = jitter(rng);
                [anchor, anchor + d, anchor + d * 2.0 + jitter(rng) * 1e-9]
            }
            _ => [
                anchor + jitter(rng),
                anchor + jitter(rng),
                anchor + jitter(rng),
            ],
        };
        triangles.push(t);
    }
    (triangles, p, x)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn traversal_agrees_with_brute_force(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let (triangles, p, x) = soup(&mut rng);
        let b = bvh(triangles.clone());
        // The segment, its reverse, and segments to other soup corners.
        let mut ends = vec![(p, x), (x, p)];
        for t in triangles.iter().take(8) {
            ends.push((p, t[(rng.below(3)) as usize]));
        }
        for (p, x) in ends {
            for t in &triangles {
                prop_assert_eq!(segment_blocked(p, x, t), blocked_by_spec(p, x, t));
            }
            let brute = !triangles.iter().any(|t| segment_blocked(p, x, t));
            prop_assert_eq!(b.segment_unoccluded(p, x), brute, "p {:?} x {:?}", p, x);
        }
    }

    #[test]
    fn deep_traversal_agrees_with_brute_force(seed in any::<u64>()) {
        // Several soups in one tree (up to 320 triangles, several levels of
        // quantised nodes), each soup near or far from the origin, queried
        // by every soup's segments.
        let mut rng = Rng::new(seed);
        let (mut triangles, mut ends) = (Vec::new(), Vec::new());
        for _ in 0..1 + rng.below(8) {
            let (t, p, x) = soup(&mut rng);
            triangles.extend(t);
            ends.extend([(p, x), (x, p)]);
        }
        let b = bvh(triangles.clone());
        for (p, x) in ends {
            let brute = !triangles.iter().any(|t| segment_blocked(p, x, t));
            prop_assert_eq!(b.segment_unoccluded(p, x), brute, "p {:?} x {:?}", p, x);
        }
    }

    #[test]
    fn culling_returns_a_superset(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let (triangles, apex, centre) = soup(&mut rng);
        let b = bvh(triangles.clone());
        // A pyramid: the apex and a convex base polygon of 3..8 corners
        // around `centre`.
        let n = 3 + rng.below(6) as usize;
        let axis = (centre - apex).normalize_or(DVec3::Z);
        let (u, v) = axis.any_orthonormal_pair();
        let radius = (centre - apex).length() * rng.log_uniform(-3.0, 0.0);
        let phase = rng.uniform(0.0, 1.0);
        let base: Vec<DVec3> = (0..n)
            .map(|k| {
                let a = 2.0 * PI * (k as f64 + phase) / n as f64;
                centre + (u * a.cos() + v * a.sin()) * radius
            })
            .collect();
        let mut points = vec![apex];
        points.extend(&base);
        let mut out = Vec::new();
        b.triangles_meeting_hull(&points, &mut out);
        prop_assert!(out.windows(2).all(|w| w[0] < w[1]));
        // Witnesses: triangles a segment from the apex to a point of the
        // hull blocks, and triangles with a corner or a point on the base.
        let mut witnesses = Vec::new();
        for _ in 0..64 {
            let w: Vec<f64> = (0..n).map(|_| rng.unit() + 1e-3).collect();
            let total: f64 = w.iter().sum();
            let q = base.iter().zip(&w).fold(DVec3::ZERO, |acc, (c, w)| acc + *c * (w / total));
            let q = apex.lerp(q, rng.unit().sqrt());
            for (i, t) in triangles.iter().enumerate() {
                if segment_blocked(apex, q, t) {
                    witnesses.push(i as u32);
                }
            }
        }
        for (i, t) in triangles.iter().enumerate() {
            // A corner at the apex, or a triangle through the apex–base
            // segments' ends (the soup puts corners there).
            if t.contains(&apex) || base.iter().any(|c| t.contains(c)) {
                witnesses.push(i as u32);
            }
        }
        for w in witnesses {
            prop_assert!(out.binary_search(&w).is_ok(), "triangle {} missed", w);
        }
    }
}

#[test]
fn tiny_triangles_next_to_a_far_receiver_are_found() {
    // 3e4 from the origin, a triangle 1e-6 across, 1e-7 from the receiver:
    // obvhs's CWBVH test would skip boxes within t < 1e-4 of the origin.
    let p = v3(3e4, 3e4, 3e4);
    let x = p + v3(0.0, 0.0, 1e-3);
    let c = p + v3(0.0, 0.0, 1e-7);
    let tiny = [
        c + v3(-1e-6, -1e-6, 0.0),
        c + v3(1e-6, -1e-6, 0.0),
        c + v3(0.0, 1e-6, 0.0),
    ];
    let b = bvh(vec![tiny, FLOOR]);
    assert!(!b.segment_unoccluded(p, x));
    assert!(b.segment_unoccluded(p, p + v3(0.1, 0.0, 1e-3)));
}

// ---------------------------------------------------------------------
// Closed forms.

/// A big triangle in the plane `z = 5` covering the half-plane
/// `n · q > c` (`n` unit, in the xy-plane), as seen from the origin.
fn half_plane_blocker(angle: f64, c: f64) -> [DVec3; 3] {
    let n = v3(angle.cos(), angle.sin(), 0.0);
    let t = v3(-n.y, n.x, 0.0);
    let o = n * c + v3(0.0, 0.0, 5.0);
    [o - t * 100.0, o + t * 100.0, o + n * 100.0]
}

#[test]
fn half_covered_lights_give_one_half() {
    // The blocker's edge line and the receiver span a plane through every
    // light's centre: exactly half of each measure is hidden.
    let q = t_quantile(sidak(ALPHA, 10), REPLICATES - 1);
    let centre = v3(0.0, 0.0, 10.0);
    let n = v3(0.4f64.cos(), 0.4f64.sin(), 0.0);
    let b = bvh(vec![half_plane_blocker(0.4, 0.0)]);
    let lights = [
        Light::disk(centre, DVec3::Z, 1.0).unwrap(),
        Light::disk(centre, v3(0.3, 0.2, 1.0), 0.7).unwrap(),
        Light::sphere(centre, 1.5).unwrap(),
        Light::rect(centre, v3(1.0, 0.2, 0.0), v3(-0.3, 0.8, 0.1)).unwrap(),
        // Its midpoint is the centre, on the plane separating the halves.
        Light::segment(
            centre - n * 2.0 + DVec3::Y * 0.1,
            centre + n * 2.0 - DVec3::Y * 0.1,
        )
        .unwrap(),
    ];
    for (k, light) in lights.iter().enumerate() {
        for seed in 0..2 {
            let options = Options::new(4096).with_seed(seed);
            let e = visibility(&b, light, DVec3::ZERO, &options).unwrap();
            assert_agrees(e, 0.5, q, &format!("light {k} seed {seed}"));
        }
    }
}

#[test]
fn circular_segment_matches_its_area() {
    // Edge at distance h (in the light's plane) from the centre of a unit
    // disk light: the hidden part is a circular segment of area
    // acos(h) − h √(1 − h²).
    let q = t_quantile(sidak(ALPHA, 6), REPLICATES - 1);
    for (k, &h) in [-0.7, -0.2, 0.1, 0.45, 0.8, 0.95].iter().enumerate() {
        let b = bvh(vec![half_plane_blocker(1.1 + k as f64, h / 2.0)]);
        let light = Light::disk(v3(0.0, 0.0, 10.0), DVec3::Z, 1.0).unwrap();
        let hidden = (h.acos() - h * (1.0 - h * h).sqrt()) / PI;
        let e = visibility(&b, &light, DVec3::ZERO, &Options::new(1024)).unwrap();
        assert_agrees(e, 1.0 - hidden, q, &format!("h = {h}"));
    }
}

#[test]
fn fully_covered_light_is_exactly_dark() {
    let light = Light::disk(v3(0.0, 0.0, 10.0), DVec3::Z, 1.0).unwrap();
    let big = [
        v3(-50.0, -50.0, 5.0),
        v3(50.0, -50.0, 5.0),
        v3(0.0, 50.0, 5.0),
    ];
    let e = visibility(&bvh(vec![big]), &light, DVec3::ZERO, &Options::new(1000)).unwrap();
    assert_eq!(
        e,
        Estimate {
            visibility: 0.0,
            stderr: 0.0
        }
    );
}

#[test]
fn occluders_behind_the_receiver_or_the_light_or_touching_it_hide_nothing() {
    let light = Light::disk(v3(0.0, 0.0, 10.0), DVec3::Z, 1.0).unwrap();
    let slab = |z: f64| [v3(-50.0, -50.0, z), v3(50.0, -50.0, z), v3(0.0, 50.0, z)];
    // Below the receiver, beyond the light, and in the light's own plane
    // (every light point lies on it: a segment ending on a triangle is not
    // blocked by it).
    let b = bvh(vec![slab(-1.0), slab(10.5), slab(10.0)]);
    for p in [DVec3::ZERO, v3(3.0, -2.0, 1.0)] {
        let e = visibility(&b, &light, p, &Options::new(777)).unwrap();
        assert_eq!(
            e,
            Estimate {
                visibility: 1.0,
                stderr: 0.0
            }
        );
    }
}

#[test]
fn receiver_on_a_floor_triangle_is_not_self_shadowed() {
    let light = Light::sphere(v3(0.5, 0.25, 6.0), 0.5).unwrap();
    let b = bvh(vec![FLOOR]);
    for p in [v3(0.25, 0.5, 0.0), FLOOR[0], v3(0.0, -4.0, 0.0)] {
        let e = visibility(&b, &light, p, &Options::new(512)).unwrap();
        assert_eq!(
            e,
            Estimate {
                visibility: 1.0,
                stderr: 0.0
            }
        );
    }
}

#[test]
fn shared_edge_leaks_no_light() {
    // Two triangles sharing an edge over the light's centre, and the same
    // scene 3e4 from the origin with a light of radius 1e-3: not one ray of
    // 2^16 passes, and neither do rays aimed exactly at the shared edge and
    // at its end vertex.
    for (offset, scale) in [(DVec3::ZERO, 1.0), (v3(3e4, -3e4, 3e4), 1e-3)] {
        let at = |q: DVec3| offset + q * scale;
        let (a, c) = (at(v3(-100.0, 0.0, 5.0)), at(v3(100.0, 0.0, 5.0)));
        let t1 = [a, c, at(v3(0.0, 100.0, 5.0))];
        let t2 = [c, a, at(v3(0.0, -100.0, 5.0))];
        let b = bvh(vec![t1, t2]);
        let p = at(DVec3::ZERO);
        let light = Light::disk(at(v3(0.0, 0.0, 10.0)), DVec3::Z, scale).unwrap();
        let e = visibility(&b, &light, p, &Options::new(1 << 16)).unwrap();
        assert_eq!(
            e,
            Estimate {
                visibility: 0.0,
                stderr: 0.0
            }
        );
        let mut rng = Rng::new(5);
        for _ in 0..10_000 {
            // Through the edge's midpoint line (y = 0) and through `a`.
            let s = rng.uniform(-0.99, 0.99);
            assert!(!b.segment_unoccluded(p, at(v3(s, 0.0, 10.0))));
        }
        if offset == DVec3::ZERO {
            // Exactly through the shared vertex `a` = (−100, 0, 5).
            assert!(!b.segment_unoccluded(p, v3(-200.0, 0.0, 10.0)));
        }
    }
}

#[test]
fn point_lights_and_small_sample_counts() {
    let b = bvh(vec![half_plane_blocker(0.0, 0.0)]);
    let lit = Light::point(v3(-1.0, 0.0, 10.0)).unwrap();
    let dark = Light::point(v3(1.0, 0.0, 10.0)).unwrap();
    let o = Options::new(2);
    assert_eq!(
        visibility(&b, &lit, DVec3::ZERO, &o).unwrap(),
        Estimate {
            visibility: 1.0,
            stderr: 0.0
        }
    );
    assert_eq!(
        visibility(&b, &dark, DVec3::ZERO, &o).unwrap(),
        Estimate {
            visibility: 0.0,
            stderr: 0.0
        }
    );
    let disk = Light::disk(v3(0.0, 0.0, 10.0), DVec3::Z, 1.0).unwrap();
    for samples in [0, 1] {
        assert_eq!(
            visibility(&b, &disk, DVec3::ZERO, &Options::new(samples)),
            Err(Error::TooFewSamples { samples })
        );
    }
    for samples in [2, 3, 5, 15, 17, 33] {
        let e = visibility(&b, &disk, DVec3::ZERO, &Options::new(samples)).unwrap();
        assert!((0.0..=1.0).contains(&e.visibility) && e.stderr.is_finite() && e.stderr >= 0.0);
    }
    assert_eq!(
        visibility(&b, &disk, v3(5.0, 5.0, 10.0), &o),
        Err(Error::Receiver(ReceiverError::InLightPlane))
    );
}

// ---------------------------------------------------------------------
// Determinism and calibration.

fn receivers() -> Vec<DVec3> {
    let mut rng = Rng::new(9);
    (0..64)
        .map(|_| {
            v3(
                rng.uniform(-2.0, 2.0),
                rng.uniform(-2.0, 2.0),
                rng.uniform(-0.5, 0.5),
            )
        })
        .collect()
}

/// An estimate recomputed from its rays: `sample_points` lists the
/// segments, replicate by replicate; each is cast through the BVH and the
/// replicate means averaged as the module documents.
fn estimate_from_rays(b: &Bvh, light: &Light, p: DVec3, options: &Options) -> f64 {
    let emitter = light.emitter(p).expect("an emitter");
    let points: Vec<DVec3> =
        softshadow::reference::monte_carlo::sample_points(&emitter, p, options).collect();
    let k = REPLICATES.min(options.samples) as usize;
    let m = points.len() / k;
    let means: Vec<f64> = points
        .chunks(m)
        .map(|c| c.iter().filter(|&&x| b.segment_unoccluded(p, x)).count() as f64 / m as f64)
        .collect();
    (means.iter().sum::<f64>() / k as f64).clamp(0.0, 1.0)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Whatever shortcut the estimate takes (from 32 samples most are
    /// decided on the light's plane), it is the count of its rays, bit for
    /// bit: random soups between a receiver and a sphere, disk, rect or
    /// segment light, sample counts on both sides of that threshold,
    /// receivers in turn on one thread (so a receiver never reuses
    /// another's set-up).
    #[test]
    fn estimates_are_their_rays_counted(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let height = rng.uniform(1.0, 5.0);
        let size = rng.uniform(0.1, 1.0);
        let light = match rng.below(4) {
            0 => Light::sphere(v3(0.0, 0.0, height), size),
            1 => Light::disk(v3(0.0, 0.0, height), v3(rng.uniform(-0.5, 0.5), 0.3, 1.0), size),
            2 => Light::segment(v3(-size, 0.1, height), v3(size, -0.1, height + 0.2)),
            _ => Light::rect(v3(0.0, 0.0, height), v3(size, 0.1, 0.0), v3(0.0, size, 0.2)),
        }
        .expect("a light");
        let triangles: Vec<[DVec3; 3]> = (0..rng.below(200) + 1)
            .map(|_| {
                let c = v3(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(0.0, height));
                let s = rng.log_uniform(-3.0, 0.0);
                let mut corner = || c + v3(rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-s, s));
                [corner(), corner(), corner()]
            })
            .collect();
        let b = bvh(triangles);
        for samples in [4096, 100, 16, 256, 1000, 2, 32, 512] {
            let p = v3(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.0);
            let options = Options::new(samples).with_seed(rng.below(1 << 40));
            let e = visibility(&b, &light, p, &options).expect("an estimate");
            let counted = estimate_from_rays(&b, &light, p, &options);
            prop_assert_eq!(e.visibility.to_bits(), counted.to_bits(), "{} samples", samples);
        }
    }
}

#[test]
fn same_seed_same_bits_in_any_thread_pool() {
    let b = bvh(vec![
        half_plane_blocker(0.3, 0.2),
        half_plane_blocker(2.0, 0.9),
    ]);
    let light = Light::sphere(v3(0.0, 0.0, 10.0), 2.0).unwrap();
    let points = receivers();
    let options = Options::new(300).with_seed(42);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| visibility_many(&b, &light, &points, &options))
    };
    let one = run(1);
    assert_eq!(one, run(3));
    let serial: Vec<_> = points
        .iter()
        .map(|&p| visibility(&b, &light, p, &options))
        .collect();
    assert_eq!(one, serial);
    let other = visibility_many(&b, &light, &points, &options.with_seed(43));
    assert_ne!(one, other);
}

#[test]
fn stderr_is_calibrated() {
    // Over many seeds, |V̂ − V| < 2 stderr as often as Student's t with
    // K − 1 degrees of freedom says (≈ 93.6 %), within a binomial
    // tolerance; and the estimates average to V within their spread.
    let h: f64 = 0.3;
    let b = bvh(vec![half_plane_blocker(0.7, h / 2.0)]);
    let light = Light::disk(v3(0.0, 0.0, 10.0), DVec3::Z, 1.0).unwrap();
    let exact = 1.0 - (h.acos() - h * (1.0 - h * h).sqrt()) / PI;
    let runs = 2000;
    let mut inside = 0;
    for seed in 0..runs {
        let options = Options::new(256).with_seed(seed);
        let e = visibility(&b, &light, v3(0.01, -0.02, 0.0), &options).unwrap();
        if (e.visibility - exact).abs() < 2.0 * e.stderr {
            inside += 1;
        }
    }
    let expected = t_coverage(2.0, REPLICATES - 1);
    let fraction = f64::from(inside) / runs as f64;
    let sd = (expected * (1.0 - expected) / runs as f64).sqrt();
    let z = z_quantile(ALPHA);
    assert!(
        (fraction - expected).abs() <= z * sd,
        "coverage {fraction} vs expected {expected} ± {}",
        z * sd
    );
}

#[test]
fn regression_triangles_beyond_2_pow_60_do_not_break_the_build() {
    // Found by the `exact` fuzz target: these three triangles' boxes clamp
    // to ±f32::MAX, their f32 surface areas are infinite, and obvhs's PLOC
    // builder paired a node with itself (its debug assertion fired). Such
    // triangles now stay out of the tree and every query tests them.
    // The fuzzed corners (the third triangle reuses the others' corners).
    let c = [
        v3(
            3.5524472633703996e59,
            4.589835288096e-312,
            3.552593419146299e59,
        ),
        v3(
            3.552593421376493e59,
            1.1945304990063844e103,
            1.1945305291614955e103,
        ),
        v3(
            1.1945305291614955e103,
            1.1945305291614971e103,
            1.1945305291614955e103,
        ),
        v3(
            4.914013573986382e165,
            1.194530791709902e103,
            1.1945305291614955e103,
        ),
        v3(
            1.1945305291614955e103,
            -3.3623045287589954e117,
            -2.937446528084375e-306,
        ),
        v3(
            3.5525934213824536e59,
            1.1945304990063844e103,
            1.1945305291614955e103,
        ),
    ];
    let far = [[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[2], c[3], c[4]]];
    let _ = bvh(far.to_vec());
    // With ordinary triangles beside them, every query still agrees with
    // brute force, and culling returns every triangle the hull meets.
    let mut tris = far.to_vec();
    tris.extend([
        [
            v3(7.5e20, 7.5e20, 1.0),
            v3(-0.04, -0.44, 0.68),
            v3(-0.01, -0.50, 0.74),
        ],
        [v3(-1.0, -1.0, 1.0), v3(1.0, -1.0, 1.0), v3(0.0, 1.0, 1.0)],
        [v3(-1.0, -1.0, 2.0), v3(1.0, -1.0, 2.0), v3(0.0, 1.0, 2.0)],
    ]);
    let scene = bvh(tris.clone());
    let mut rng = Rng::new(9);
    for _ in 0..2000 {
        let p = v3(
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
            rng.uniform(-1.0, 0.5),
        );
        let x = v3(
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
            rng.uniform(2.5, 4.0),
        );
        let brute = !tris.iter().any(|t| segment_blocked(p, x, t));
        assert_eq!(scene.segment_unoccluded(p, x), brute, "{p} {x}");
    }
    let mut out = Vec::new();
    scene.triangles_meeting_hull(
        &[v3(0.0, 0.0, 0.0), v3(0.1, 0.0, 3.0), v3(0.0, 0.1, 3.0)],
        &mut out,
    );
    assert!([3, 4, 5].iter().all(|i| out.contains(i)), "{out:?}");
}
