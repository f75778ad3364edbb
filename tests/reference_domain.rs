//! The references at the ends of their domains: a scene so large that the
//! exact reference's determinants (products of three coordinate
//! differences) would overflow is refused with `ReceiverError::OutOfRange`
//! (an `Err`, never a wrong answer with a small bound), and so is a whole
//! scene below `10⁻⁹⁰` (whose determinants underflow); a scene beyond
//! `10⁹⁰` that does not overflow is answered with bound 1 (no certified
//! information), and Monte Carlo refuses a light `10¹⁵⁰` away, whose rays
//! its exact segment test cannot decide.
#![cfg(feature = "render")]

use softshadow::glam::DVec3;
use softshadow::method::{self, Exact, MethodError, MonteCarlo};
use softshadow::reference::{exact, monte_carlo};
use softshadow::scene::{Light, Mesh, ReceiverError};
use softshadow::{Bvh, Frame, Receiver, Scene, Stages};

/// A plate `x ≥ 0` at height `s` (reaching `5 s`) over the receiver at the
/// origin, and a light of each kind of size `s/2` centred at `(0, 2 s, 0)`:
/// the plate's edge passes through the light's centre as seen from the
/// receiver, so it hides exactly half of every light but the point
/// (`V = 1/2`; the point light, at `x = −s/2`, is seen: `V = 1`).
fn scene(s: f64) -> (Vec<Light>, Mesh) {
    let c = DVec3::new(0.0, 2.0, 0.0) * s;
    let lights = vec![
        Light::sphere(c, 0.5 * s).unwrap(),
        Light::disk(c, -DVec3::Y, 0.5 * s).unwrap(),
        Light::rect(c, DVec3::X * 0.5 * s, DVec3::Z * 0.5 * s).unwrap(),
        Light::segment(c - DVec3::X * 0.5 * s, c + DVec3::X * 0.5 * s).unwrap(),
        Light::point(c - DVec3::X * 0.5 * s).unwrap(),
    ];
    let plate = Mesh::new(
        vec![
            DVec3::new(0.0, 1.0, -5.0) * s,
            DVec3::new(5.0, 1.0, -5.0) * s,
            DVec3::new(5.0, 1.0, 5.0) * s,
            DVec3::new(0.0, 1.0, 5.0) * s,
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    (lights, plate)
}

fn truth(light: &Light) -> f64 {
    if matches!(light, Light::Point(_)) {
        1.0
    } else {
        0.5
    }
}

fn frame() -> Frame {
    Frame::from_receivers(vec![Receiver {
        position: DVec3::ZERO,
        normal: Some(DVec3::Y),
        object: None,
    }])
}

#[test]
fn exact_refuses_scenes_whose_determinants_overflow_or_underflow() {
    // 1e80: inside the domain, certified. 1e100: beyond 1e90 but no
    // determinant overflows (answered, bound 1). 1e110 and 1e153: the
    // products of three differences overflow (refused). 1e-80: inside.
    // 1e-110: every coordinate below 1e-90, the products underflow
    // (refused).
    for (s, domain) in [
        (1e-110, "underflow"),
        (1e-80, "inside"),
        (1e80, "inside"),
        (1e100, "beyond"),
        (1e110, "overflow"),
        (1e153, "overflow"),
    ] {
        let (lights, plate) = scene(s);
        for light in lights {
            let scene = Scene::new(light).with_mesh("plate", plate.clone());
            let bvh = Bvh::from_scene(&scene);
            let p = DVec3::ZERO;
            let want = truth(&light);
            let bounded = exact::visibility_bounded(&bvh, &light, p);
            let plain = exact::visibility(&bvh, &light, p);
            let emitter = light.emitter(p).unwrap();
            let direct = exact::emitter_visibility_bounded(
                &bvh,
                &emitter,
                p,
                &mut exact::Scratch::default(),
            );
            // Whatever the domain: the emitter's answer's bound holds.
            assert!(
                (direct.visibility - want).abs() <= direct.bound,
                "{s:e} {light:?}: {direct:?}"
            );
            let run = method::run(&Exact, &Stages::new(&scene), &frame());
            match domain {
                "inside" | "beyond" => {
                    let b = bounded.unwrap();
                    assert_eq!(plain, Ok(b.visibility));
                    assert!(
                        (b.visibility - want).abs() <= b.bound,
                        "{s:e} {light:?}: {b:?}"
                    );
                    if domain == "inside" {
                        assert!(b.bound < 1e-12, "{s:e} {light:?}: {b:?}");
                    } else {
                        assert_eq!(b.bound, 1.0, "{s:e} {light:?}");
                    }
                    assert_eq!(run.unwrap().output.visibility, vec![b.visibility]);
                }
                _ => {
                    assert_eq!(bounded, Err(ReceiverError::OutOfRange), "{s:e} {light:?}");
                    assert_eq!(plain, Err(ReceiverError::OutOfRange), "{s:e} {light:?}");
                    assert_eq!(direct.bound, 1.0);
                    assert!(
                        matches!(
                            run,
                            Err(MethodError::Receiver {
                                index: 0,
                                error: ReceiverError::OutOfRange
                            })
                        ),
                        "{s:e} {light:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn monte_carlo_refuses_lights_beyond_its_segment_tests_domain() {
    // The plate at height 1 over the receiver, a light of radius 1e149
    // 1e150 above: half of it hidden. Monte Carlo's rays to points 1e150
    // away are beyond its exact segment test's domain (coordinates within
    // 1e90): refused. Within it (a light 1e80 away), answered within its
    // tolerance (4096 samples).
    let plate = Mesh::new(
        vec![
            DVec3::new(0.0, 1.0, -5.0),
            DVec3::new(5.0, 1.0, -5.0),
            DVec3::new(5.0, 1.0, 5.0),
            DVec3::new(0.0, 1.0, 5.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    for (far, refused) in [(1e80, false), (1e150, true), (1e250, true)] {
        let c = DVec3::Y * far;
        for light in [
            Light::sphere(c, far / 10.0).unwrap(),
            Light::disk(c, -DVec3::Y, far / 10.0).unwrap(),
            Light::rect(c, DVec3::X * far / 10.0, DVec3::Z * far / 10.0).unwrap(),
        ] {
            let scene = Scene::new(light).with_mesh("plate", plate.clone());
            let bvh = Bvh::from_scene(&scene);
            let options = monte_carlo::Options::new(4096);
            let got = monte_carlo::visibility(&bvh, &light, DVec3::ZERO, &options);
            let run = method::run(&MonteCarlo::new(64), &Stages::new(&scene), &frame());
            if refused {
                assert!(
                    matches!(
                        got,
                        Err(monte_carlo::Error::Receiver(ReceiverError::OutOfRange))
                    ),
                    "{far:e} {light:?}: {got:?}"
                );
                assert!(
                    matches!(
                        run,
                        Err(MethodError::Receiver {
                            index: 0,
                            error: ReceiverError::OutOfRange
                        })
                    ),
                    "{far:e} {light:?}"
                );
            } else {
                let e = got.unwrap();
                // 16 replicates: |t₁₅| < 5 fails with probability ~1e-4
                // (or one replicate's resolution where all agree).
                let tol = (5.0 * e.stderr).max(16.0 / 4096.0);
                assert!(
                    (e.visibility - 0.5).abs() <= tol,
                    "{far:e} {light:?}: {e:?}"
                );
                assert!(run.is_ok());
            }
        }
    }
}
