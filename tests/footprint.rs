//! The footprint kernel against closed forms and independent
//! constructions: the radius against the difference of reciprocals and
//! SSOC's distortion, the reach depth against the radius, the clips, and a
//! mapped edge against the light point it hides, built by hand.

use softshadow::glam::{DVec2, DVec3};
use softshadow::kernel::footprint::f64::*;

#[test]
fn the_radius_is_the_difference_of_reciprocals_and_zero_in_front() {
    let (r, zq, zp) = (0.5, 2.0, 5.0);
    assert!((radius(r, zq, zp) - r * (1.0 / zq - 1.0 / zp)).abs() < 1e-16);
    assert_eq!(radius(r, 5.0, 2.0), 0.0);
    assert_eq!(radius(r, 2.0, 2.0), 0.0);
    assert_eq!(radius(f64::NAN, 2.0, 3.0), 0.0);
    assert_eq!(radius(r, 2.0, f64::INFINITY), r / 2.0);
    // A receiver one ulp behind keeps its relative accuracy.
    let zp = 2f64.next_up();
    let want = r * (zp - 2.0) / (zp * 2.0);
    assert!((radius(r, 2.0, zp) / want - 1.0).abs() < 4.0 * f64::EPSILON);
    // Twice the radius is SSOC's maximal distortion, bit for bit.
    for (zq, zp) in [(1.0, 3.0), (2.5, 2.6), (0.3, 1e9)] {
        assert_eq!(
            2.0 * radius(0.7, zq, zp),
            softshadow::kernel::distortion::f64::max_distortion(0.7, zq, zp)
        );
    }
}

#[test]
fn the_reach_depth_inverts_the_radius() {
    let (r, zq) = (0.5, 2.0);
    for reach in [0.01, 0.1, 0.2] {
        let zp = reach_depth(r, zq, reach);
        assert!((radius(r, zq, zp) - reach).abs() < 1e-15, "{reach}");
    }
    assert_eq!(reach_depth(r, zq, 0.25), f64::INFINITY);
    assert_eq!(reach_depth(r, zq, 0.0), zq);
}

#[test]
fn clips_keep_ends_bit_for_bit_and_cut_at_the_plane() {
    let (a, b) = (DVec3::new(0.1, 0.2, 0.5), DVec3::new(0.7, -0.3, 3.0));
    assert_eq!(clip_near(a, b, 0.1), Some((a, b)));
    assert_eq!(clip_near(a, b, 4.0), None);
    let (c, d) = clip_near(a, b, 1.0).unwrap();
    assert_eq!((c.z, d), (1.0, b));
    let (c, d) = clip_near(b, a, 1.0).unwrap();
    assert_eq!((c, d.z), (b, 1.0));
    let (c, d) = clip_far(a, b, 1.0).unwrap();
    assert_eq!((c, d.z), (a, 1.0));
    assert_eq!(clip_far(a, b, 0.5), None);
    assert_eq!(gamma(1), (f64::EPSILON / 2.0) / (1.0 - f64::EPSILON / 2.0));
}

#[test]
fn a_mapped_edge_hides_the_light_points_it_hides_from_the_receiver() {
    // A receiver at light-frame p, an occluder edge at depth 2 through
    // the image point s + R·u: the light point r·u is hidden.
    let (r, zp) = (0.5, 5.0);
    let p = DVec3::new(0.3, -0.2, zp);
    let s = project(p);
    let rad = radius(r, 2.0, zp);
    let u = DVec2::new(0.4, -0.1);
    // The occluder point hiding light point ℓ = r·u: on the segment
    // from ℓ (depth 0) to p, at depth 2.
    let l = DVec3::new(r * u.x, r * u.y, 0.0);
    let q = l + (p - l) * (2.0 / zp);
    assert!((project(q) - (s + u * rad)).length() < 1e-15);
    let q2 = q + DVec3::new(0.1, 0.0, 0.0);
    let (ma, mb) = map_edge(project(q), project(q2), q, q2, s, zp, r).unwrap();
    assert!((ma - u).length() < 1e-14, "{ma}");
    assert!((mb - (u + DVec2::new(0.1 / 2.0 / rad, 0.0))).length() < 1e-13);
    // An edge behind the receiver maps to nothing.
    let behind = DVec3::new(0.0, 0.0, 6.0);
    assert_eq!(
        map_edge(
            project(behind),
            project(behind + DVec3::X),
            behind,
            behind + DVec3::X,
            s,
            zp,
            r
        ),
        None
    );
}

#[test]
fn a_cut_is_the_same_both_ways_and_not_swamped_by_a_far_end() {
    // One end just behind the near plane, the other 10⁶⁶ beyond it: the
    // cut, by hand, is at x = a.x + (near − a.z)/(b.z − a.z)·(b.x − a.x)
    // from the near end, about −30.2 (the far end's parameter rounds to 1
    // and would put it near 0).
    let a = DVec3::new(
        -1.0920388876787268,
        -0.8949689611650419,
        -4.9403953462796935,
    );
    let b = DVec3::new(
        -6.18817473522882e66,
        5.776022231042852e64,
        1.053276841691022e66,
    );
    let near = 0.006;
    let want = a.x + (near - a.z) / (b.z - a.z) * (b.x - a.x);
    let (cut, end) = clip_near(a, b, near).unwrap();
    assert_eq!(end, b);
    assert!(
        (cut.x - want).abs() <= 1e-12 * want.abs(),
        "{} vs {want}",
        cut.x
    );
    assert_eq!(cut.z, near);
    // The other way round: the same bits.
    let (end, cut2) = clip_near(b, a, near).unwrap();
    assert_eq!(end, b);
    assert_eq!(cut2, cut);
}
