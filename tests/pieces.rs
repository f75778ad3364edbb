//! The visible pieces of a segment light (`Pieces`, `exact::pieces`)
//! against independent answers: intervals whose pieces are known by hand,
//! ties included; scenes built so that their pieces are known by
//! construction; and random scenes against a dense sampling of the light,
//! each sample's visibility decided by an occlusion ray.

use proptest::prelude::*;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::glam::DVec3;
use softshadow::kernel::receiver_view::{Pieces, SegmentView};
use softshadow::reference::exact;
use softshadow::scene::Light;

fn of(intervals: &[(f64, f64)]) -> Pieces {
    Pieces::of(&mut intervals.to_vec())
}

#[test]
fn intervals_whose_pieces_are_known() {
    use Pieces::*;
    let third = 1.0 / 3.0;
    for (intervals, want) in [
        (&[][..], Whole),
        (&[(0.0, 1.0)][..], Hidden),
        (&[(0.25, third)][..], Several),
        (&[(0.0, third)][..], OneAtEnd),
        (&[(third, 1.0)][..], OneAtEnd),
        (&[(0.0, 0.1), (0.7, 1.0)][..], OneInside),
        (&[(0.7, 1.0), (0.0, 0.1)][..], OneInside),
        (&[(0.1, 0.2), (0.3, 0.4), (0.5, 0.6)][..], Several),
        // Touching intervals leave no piece between them.
        (&[(0.0, third), (third, 1.0)][..], Hidden),
        (&[(third, 0.6), (0.1, third)][..], Several),
        (&[(0.0, 0.1), (0.1, 0.2), (0.2, 0.9)][..], OneAtEnd),
        // Overlapping and nested intervals.
        (&[(0.0, 0.6), (0.2, 0.3), (0.5, 1.0)][..], Hidden),
        (&[(0.2, 0.9), (0.3, 0.4)][..], Several),
        // A piece however short counts.
        (&[(0.0, 0.5), (0.5 + f64::EPSILON, 1.0)][..], OneInside),
        (&[(0.0, 1.0 - f64::EPSILON / 2.0)][..], OneAtEnd),
        (&[(f64::MIN_POSITIVE, 1.0)][..], OneAtEnd),
        // An interval ending exactly at an end takes it; beyond, clamped.
        (&[(-0.5, 0.2), (0.8, 1.5)][..], OneInside),
        (&[(-1.0, 2.0)][..], Hidden),
        // Nothing hidden: empty, reversed, NaN, outside the light.
        (
            &[(0.4, 0.4), (0.6, 0.5), (f64::NAN, 0.5), (0.2, f64::NAN)][..],
            Whole,
        ),
        (&[(-1.0, 0.0), (1.0, 2.0), (-0.0, -0.0)][..], Whole),
        (
            &[(f64::NEG_INFINITY, 0.3), (0.6, f64::INFINITY)][..],
            OneInside,
        ),
    ] {
        assert_eq!(of(intervals), want, "{intervals:?}");
    }
}

/// The pieces do not depend on the order of the intervals.
#[test]
fn the_order_of_the_intervals_does_not_matter() {
    let intervals = [
        (0.15, 0.35),
        (0.0, 0.1),
        (0.3, 0.45),
        (0.6, 0.62),
        (0.9, 1.0),
    ];
    let want = of(&intervals);
    assert_eq!(want, Pieces::Several);
    let mut v = intervals.to_vec();
    for k in 0..v.len() {
        v.rotate_left(1);
        if k % 2 == 1 {
            v.reverse();
        }
        assert_eq!(of(&v), want, "{v:?}");
    }
}

/// A segment light `a b` seen from `p`, and a plate that hides exactly the
/// light's parameters `[s0, s1]` from `p`: the light's points scaled toward
/// `p` by `t` lie on a line parallel to the light, and the plate is a band
/// of half-width `w` about that line, across the plane of `p` and the
/// light.
struct Setup {
    p: DVec3,
    a: DVec3,
    b: DVec3,
}

impl Setup {
    fn plate(&self, s0: f64, s1: f64, t: f64, w: f64) -> [[DVec3; 3]; 2] {
        let across = (self.a - self.p).cross(self.b - self.p).normalize() * w;
        let at = |s: f64| self.p + t * (self.a.lerp(self.b, s) - self.p);
        let (c0, c1) = (at(s0), at(s1));
        [
            [c0 - across, c1 - across, c1 + across],
            [c0 - across, c1 + across, c0 + across],
        ]
    }

    fn pieces(&self, triangles: Vec<[DVec3; 3]>) -> Pieces {
        let light = Light::segment(self.a, self.b).unwrap();
        let bvh = Bvh::new(Occluders::from_triangles(triangles));
        let got = exact::pieces(&bvh, &light, self.p).unwrap().unwrap();
        // The same by the kernel over the triangles, none culled.
        let view = SegmentView::new(self.p, self.a, self.b).unwrap();
        let listed: Vec<_> = bvh.occluders().triangles().to_vec();
        let mut scratch = Default::default();
        assert_eq!(view.pieces(&listed, &mut scratch), got);
        got
    }
}

/// Ordinary coordinates: non-dyadic, around an offset.
fn setup(offset: f64) -> Setup {
    let o = DVec3::new(offset, 0.37 * offset, -0.61 * offset);
    Setup {
        p: o + DVec3::new(0.113, -0.271, 0.0917),
        a: o + DVec3::new(-1.217, 2.531, 0.3137),
        b: o + DVec3::new(1.193, 2.467, -0.2791),
    }
}

#[test]
fn scenes_whose_pieces_are_known_by_construction() {
    use Pieces::*;
    for offset in [0.0, 1.0e6, -3.7e7, 1.0e9] {
        let s = setup(offset);
        let plate = |s0, s1, t| s.plate(s0, s1, t, 0.173).to_vec();
        let cases: [(&str, Vec<[DVec3; 3]>, Pieces); 7] = [
            ("nothing", Vec::new(), Whole),
            // Away from the triangle (p, a, b): hides nothing.
            (
                "a plate aside",
                s.plate(0.2, 0.7, 0.5, 0.173)
                    .map(|t| t.map(|v| v + DVec3::new(0.0, 0.0, 2.3)))
                    .to_vec(),
                Whole,
            ),
            ("a bar across the middle", plate(0.41, 0.57, 0.43), Several),
            ("one end hidden", plate(-0.3, 0.37, 0.52), OneAtEnd),
            ("the other end hidden", plate(0.71, 1.3, 0.61), OneAtEnd),
            (
                "both ends hidden",
                [plate(-0.3, 0.29, 0.47), plate(0.77, 1.3, 0.38)].concat(),
                OneInside,
            ),
            (
                "everything, by two plates that overlap",
                [plate(-0.3, 0.53, 0.47), plate(0.49, 1.3, 0.61)].concat(),
                Hidden,
            ),
        ];
        for (what, triangles, want) in cases {
            assert_eq!(s.pieces(triangles), want, "{what}, offset {offset}");
        }
        // Two bars across: three pieces, two of them at the ends.
        let two = [plate(0.21, 0.33, 0.5), plate(0.59, 0.83, 0.4)].concat();
        assert_eq!(s.pieces(two), Several, "two bars, offset {offset}");
    }
}

/// A light of another kind has no pieces; a receiver on the light has no
/// view (as the exact reference refuses it).
#[test]
fn other_lights_and_refused_receivers() {
    let s = setup(0.0);
    let bvh = Bvh::new(Occluders::from_triangles(
        s.plate(0.2, 0.6, 0.5, 0.1).to_vec(),
    ));
    let sphere = Light::sphere(s.a, 0.31).unwrap();
    assert_eq!(exact::pieces(&bvh, &sphere, s.p), Ok(None));
    let light = Light::segment(s.a, s.b).unwrap();
    for end in [s.a, s.b] {
        let refused = exact::visibility(&bvh, &light, end).map(|_| None);
        assert!(refused.is_err());
        assert_eq!(exact::pieces(&bvh, &light, end), refused);
    }
}

/// The kinds a sampled run of visible (`true`) and hidden samples shows.
fn sampled(visible: &[bool]) -> Pieces {
    let runs = visible
        .iter()
        .zip(std::iter::once(&false).chain(visible))
        .filter(|(now, before)| **now && !**before)
        .count();
    let at_end = visible.first() == Some(&true) || visible.last() == Some(&true);
    match runs {
        0 => Pieces::Hidden,
        1 if visible.iter().all(|v| *v) => Pieces::Whole,
        1 if at_end => Pieces::OneAtEnd,
        1 => Pieces::OneInside,
        _ => Pieces::Several,
    }
}

/// Samples of the light's parameter.
const SAMPLES: usize = 2000;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Random plates between a receiver and the light: the pieces are
    /// those a dense sampling of the light shows, each sample's visibility
    /// an exact occlusion ray (`Bvh::segment_unoccluded`), wherever every
    /// piece and every hidden run spans several samples (cases with two
    /// ends of intervals, or an end and an end of the light, within three
    /// sample spacings are left out).
    #[test]
    fn pieces_are_what_dense_sampling_sees(
        offset in prop_oneof![Just(0.0), -1.0e6..1.0e6],
        plates in prop::collection::vec((-0.4..1.2f64, 0.05..0.6f64, 0.2..0.8f64, 0.03..0.3f64), 0..5),
        tilt in -0.3..0.3f64,
    ) {
        let s = setup(offset);
        let mut triangles = Vec::new();
        for (s0, len, t, w) in plates {
            let mut plate = s.plate(s0, s0 + len, t, w);
            // Tilted about its centre line: the plate still holds the line.
            let across = (s.a - s.p).cross(s.b - s.p).normalize();
            for tri in &mut plate {
                for v in tri.iter_mut() {
                    let side = (*v - s.p).dot(across);
                    *v += tilt * side * (s.b - s.a).normalize();
                }
            }
            triangles.extend(plate);
        }
        let view = SegmentView::new(s.p, s.a, s.b).unwrap();
        let mut ends = vec![0.0, 1.0];
        for tri in &triangles {
            if let Some((lo, hi)) = view.blocked(tri) {
                ends.extend([lo, hi]);
            }
        }
        ends.sort_by(f64::total_cmp);
        let spacing = 1.0 / SAMPLES as f64;
        // Ends that are equal (intervals that touch, or reach an end of the
        // light) are one event; ends apart are apart by several samples.
        prop_assume!(ends.windows(2).all(|w| w[1] == w[0] || w[1] - w[0] > 3.0 * spacing));
        let bvh = Bvh::new(Occluders::from_triangles(triangles));
        let visible: Vec<bool> = (0..SAMPLES)
            .map(|k| {
                let x = s.a.lerp(s.b, (k as f64 + 0.5) * spacing);
                bvh.segment_unoccluded(s.p, x)
            })
            .collect();
        let light = Light::segment(s.a, s.b).unwrap();
        let got = exact::pieces(&bvh, &light, s.p).unwrap().unwrap();
        prop_assert_eq!(got, sampled(&visible));
    }
}
