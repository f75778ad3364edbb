//! Receivers at contact (issue 39, items 1–3): exactly on a triangle — on
//! its face, on an edge (shared with a neighbour, as on a mesh), at a
//! vertex — and a hair off it (±1 ulp in each coordinate, ±10⁻¹⁷ along the
//! triangle's normal and across the edge), for every light kind (sphere,
//! disk, rect, segment, point), with ordinary (non-round) coordinates at
//! three scales (contact near the origin, where 10⁻¹⁷ is more than an ulp;
//! ordinary; a million away), against the independent 256-bit evaluation
//! of the definition in `support::view` (its own half-spaces, clipping,
//! union and areas, and `robust`'s signs). A receiver *on* a triangle
//! is hidden nothing by it (the open segment from the receiver meets its
//! plane only at the receiver, or lies in it), whatever side the light is
//! on; a hair behind it, the triangle hides what it covers.
//!
//! The exact reference (over a BVH), the kernel alone
//! (`Light::visibility_among`) and Monte Carlo (within its statistical
//! tolerance) are each held to that evaluation, and the exact reference's
//! certified bound (`visibility_bounded`, the same value bit for bit) must
//! contain its error.
#![cfg(all(feature = "reference", feature = "arbitrary"))]

mod support;

use proptest::prelude::*;
use softshadow::arbitrary::{step_ulps, Rng};
use softshadow::glam::DVec3;
use softshadow::reference::stats::{agreement_tolerance, sidak, student_t_two_sided_quantile};
use softshadow::reference::{exact, monte_carlo};
use softshadow::scene::Light;
use softshadow::{Bvh, Occluders};
use support::view;

/// How far the exact reference may be from the 256-bit answer.
const TOLERANCE: f64 = 1e-13;

/// A scene around a contact point: the receiver's exact place on the
/// triangle(s), the triangles, and a light on either side.
#[derive(Clone, Debug)]
struct Contact {
    /// The receiver exactly on the first triangle.
    on: DVec3,
    /// The occluders: the triangle the receiver is on, and a neighbour
    /// sharing an edge (for an edge contact), and one more triangle.
    tris: Vec<[DVec3; 3]>,
    /// The first triangle's unit normal, and the direction across the edge
    /// in its plane (for hair-off receivers).
    normal: DVec3,
    across: DVec3,
    what: &'static str,
}

/// Where on the triangle the receiver is.
#[derive(Clone, Copy, Debug)]
enum Place {
    Face,
    Edge,
    Vertex,
}

/// A double on the grid of `ulp` (a power of two): `x` rounded to it.
fn on_grid(x: f64, ulp: f64) -> f64 {
    (x / ulp).round() * ulp
}

/// A contact scene at `scale` (the binade `[scale, 2 scale)` of every
/// coordinate of the receiver, whose ulp the triangle's offsets are
/// multiples of, so that the receiver lies exactly on the triangle).
fn contact(rng: &mut Rng, place: Place, scale: f64) -> Contact {
    let ulp = scale * f64::EPSILON;
    // The receiver: ordinary coordinates in [1.25, 1.75) × scale.
    let on = DVec3::new(
        on_grid(rng.uniform(1.25, 1.75) * scale, ulp),
        on_grid(rng.uniform(1.25, 1.75) * scale, ulp),
        on_grid(rng.uniform(1.25, 1.75) * scale, ulp),
    );
    // Offsets below a quarter of the scale keep every corner in the
    // binade, so that each sum is exact.
    let offset = |rng: &mut Rng| {
        let w = 0.11 * scale;
        DVec3::new(
            on_grid(rng.uniform(-w, w), ulp),
            on_grid(rng.uniform(-w, w), ulp),
            on_grid(rng.uniform(-w, w), ulp),
        )
    };
    let (d0, d1, d2) = (offset(rng), offset(rng), offset(rng));
    let (tri, neighbour, what) = match place {
        // The receiver is the centroid: its offsets sum to zero.
        Place::Face => ([on + d0, on + d1, on - d0 - d1], None, "face"),
        // The receiver halves the edge q₀q₁; the neighbour shares the edge.
        Place::Edge => (
            [on + d0, on - d0, on + d1],
            Some([on - d0, on + d0, on + d2]),
            "edge",
        ),
        Place::Vertex => (
            [on, on + d0, on + d1],
            Some([on, on + d1, on + d2]),
            "vertex",
        ),
    };
    let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
    let edge = (tri[1] - tri[0]).normalize();
    let mut tris = vec![tri];
    tris.extend(neighbour);
    // One more triangle somewhere between the receiver and the lights.
    let far = |rng: &mut Rng| {
        on + DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        ) * scale
    };
    if rng.chance(0.5) {
        tris.push([far(rng), far(rng), far(rng)]);
    }
    Contact {
        on,
        tris,
        normal: n,
        across: n.cross(edge),
        what,
    }
}

/// The receivers: on the triangle, each coordinate ±1 ulp off, and ±10⁻¹⁷
/// (in units of the scale's binade near the origin: wherever that is more
/// than an ulp) along the normal and across the edge.
fn receivers(c: &Contact) -> Vec<(String, DVec3)> {
    let mut out = vec![("on".to_owned(), c.on)];
    for k in 0..3 {
        for s in [-1, 1] {
            let mut p = c.on;
            p[k] = step_ulps(p[k], s);
            out.push((format!("axis {k} {s:+} ulp"), p));
        }
    }
    for (name, dir) in [("normal", c.normal), ("across", c.across)] {
        for s in [-1.0, 1.0] {
            let p = c.on + dir * (s * 1e-17);
            if p != c.on {
                out.push((format!("{name} {s:+}e-17"), p));
            }
        }
    }
    out
}

/// A light of each kind with ordinary parameters, at about `dist` from
/// the receiver in the direction `dir` (either side of the triangle).
fn lights(rng: &mut Rng, on: DVec3, dir: DVec3, dist: f64) -> Vec<Light> {
    let c = on + dir * dist;
    let r = dist * rng.uniform(0.05, 0.4);
    let jitter = |rng: &mut Rng| {
        DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        ) * r
    };
    let normal = (-dir + jitter(rng) / r * 0.5).normalize();
    let (u, v) = (jitter(rng), jitter(rng));
    [
        Light::sphere(c, r),
        Light::disk(c, normal, r),
        Light::rect(c, u, v),
        Light::segment(c + u, c - v),
        Light::point(c + jitter(rng)),
    ]
    .into_iter()
    .filter_map(Result::ok)
    .collect()
}

/// A direction toward the light: through the first triangle (so that
/// behind it the triangle hides the light), or anywhere.
fn toward(rng: &mut Rng, c: &Contact) -> DVec3 {
    let t = c.tris[0];
    let (a, b) = (rng.unit(), rng.unit());
    let (a, b) = if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    };
    let inside = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
    let through = inside - c.on;
    let side = if rng.chance(0.5) { 1.0 } else { -1.0 };
    let d = if rng.chance(0.7) && through.length() > 0.0 {
        through.normalize() + c.normal * (side * rng.uniform(0.05, 1.0))
    } else {
        DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        )
    };
    d.try_normalize().unwrap_or(DVec3::Z)
}

/// Every receiver of the case against the 256-bit answer: the exact
/// reference and the kernel alone. Returns the failures.
fn check(c: &Contact, lights: &[Light], failures: &mut Vec<String>) -> f64 {
    let bvh = Bvh::new(Occluders::from_triangles(c.tris.clone()));
    let mut worst = 0.0_f64;
    for light in lights {
        for (name, p) in receivers(c) {
            if light.emitter(p).is_err() {
                continue;
            }
            let truth = view::visibility(light, p, &c.tris);
            let e = exact::visibility(&bvh, light, p).expect("receiver accepted");
            let k = light
                .visibility_among(p, &c.tris)
                .expect("receiver accepted");
            let b = exact::visibility_bounded(&bvh, light, p).expect("receiver accepted");
            let err = (e - truth).abs().max((k - truth).abs());
            worst = worst.max(err);
            if b.visibility.to_bits() != e.to_bits() || (b.visibility - truth).abs() > b.bound {
                failures.push(format!(
                    "{} {name}, {light:?}: bounded {b:?}, exact {e}, 256-bit {truth}\n  p = {p:?}\n  tris = {:?}",
                    c.what, c.tris
                ));
            }
            if err > TOLERANCE {
                failures.push(format!(
                    "{} {name}, {light:?}: exact {e}, kernel {k}, 256-bit {truth}\n  p = {p:?}\n  tris = {:?}",
                    c.what, c.tris
                ));
            }
        }
    }
    worst
}

fn place_of(k: u8) -> Place {
    match k % 3 {
        0 => Place::Face,
        1 => Place::Edge,
        _ => Place::Vertex,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(support::samples(48) as u32))]

    /// Every receiver at contact, every light kind, three scales: the
    /// exact reference and the kernel within `TOLERANCE` of the 256-bit
    /// evaluation.
    #[test]
    fn receivers_on_and_a_hair_off_triangles(
        seed in any::<u64>(),
        place in 0u8..3,
        scale_k in 0usize..3,
    ) {
        // Contact near the origin (10⁻¹⁷ is several ulps there), ordinary,
        // and a million away.
        let scale = [2f64.powi(-6), 1.0, 2f64.powi(20)][scale_k];
        let mut rng = Rng::new(seed);
        let c = contact(&mut rng, place_of(place), scale);
        let dir = toward(&mut rng, &c);
        let dist = scale * rng.uniform(2.0, 6.0);
        let lights = lights(&mut rng, c.on, dir, dist);
        let mut failures = Vec::new();
        check(&c, &lights, &mut failures);
        prop_assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
    }
}

/// The issue's cases, written out: a segment light wholly beyond a
/// triangle from a receiver 2.2·10⁻¹⁷ behind it (truth 0); receivers
/// 10⁻¹⁰ … 10⁻¹² below an axis-aligned plate (truth 0); segment lights
/// 10⁻¹² … 10⁻⁶⁰ long behind a plate (truth 0); and a receiver within
/// 10⁻¹⁷ of a triangle's edge and plane under a disk and a sphere light.
#[test]
fn the_issues_cases() {
    let mut failures = Vec::new();
    let mut compare = |what: String, light: Light, p: DVec3, tris: Vec<[DVec3; 3]>| {
        let truth = view::visibility(&light, p, &tris);
        let bvh = Bvh::new(Occluders::from_triangles(tris.clone()));
        let e = exact::visibility(&bvh, &light, p).expect("receiver accepted");
        if (e - truth).abs() > TOLERANCE {
            failures.push(format!("{what}: exact {e}, 256-bit {truth}"));
        }
    };
    // A tilted triangle through the origin region; the receiver 2.2e-17
    // behind it along its normal, the segment light wholly beyond it.
    let tri = [
        DVec3::new(-1.3, -0.9, 0.31),
        DVec3::new(1.7, -1.1, -0.27),
        DVec3::new(0.2, 1.9, 0.13),
    ];
    let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
    let inside = (tri[0] + tri[1] + tri[2]) / 3.0;
    let on_plane = inside - n * n.dot(inside - tri[0]);
    let light = Light::segment(
        on_plane + n * 3.0 + DVec3::X * 0.4,
        on_plane + n * 3.5 - DVec3::Y * 0.3,
    )
    .unwrap();
    compare(
        "behind a tilted triangle by 2.2e-17".into(),
        light,
        on_plane - n * 2.2e-17,
        vec![tri],
    );
    // Near the origin, where 2.2e-17 is representable.
    let small = tri.map(|v| v * 0.01);
    let on_plane = on_plane * 0.01;
    let light =
        Light::segment(on_plane + n * 0.03 + DVec3::X * 0.004, on_plane + n * 0.035).unwrap();
    compare(
        "behind a small triangle by 2.2e-17".into(),
        light,
        on_plane - n * 2.2e-17,
        vec![small],
    );
    // Under an axis-aligned plate.
    let plate = |z: f64| {
        vec![
            [
                DVec3::new(-3.0, -3.0, z),
                DVec3::new(3.0, -3.0, z),
                DVec3::new(3.0, 3.0, z),
            ],
            [
                DVec3::new(-3.0, -3.0, z),
                DVec3::new(3.0, 3.0, z),
                DVec3::new(-3.0, 3.0, z),
            ],
        ]
    };
    let segment = Light::segment(DVec3::new(-0.5, 0.1, 4.0), DVec3::new(0.7, -0.2, 4.3)).unwrap();
    for h in [1e-10, 1e-11, 1e-12, 1e-15, 2.2e-17] {
        compare(
            format!("{h} under a plate at 0"),
            segment,
            DVec3::new(0.1, 0.2, -h),
            plate(0.0),
        );
        compare(
            format!("{h} under a plate at 1"),
            segment,
            DVec3::new(0.1, 0.2, 1.0 - h),
            plate(1.0),
        );
    }
    // Short segment lights behind a plate.
    for len in [1e-12, 1e-15, 1e-16] {
        let a = DVec3::new(0.3, 0.1, 4.0);
        let light = Light::segment(a, a + DVec3::new(len, 0.5 * len, 0.0)).unwrap();
        compare(
            format!("segment {len} long"),
            light,
            DVec3::new(0.1, 0.2, 0.0),
            plate(1.0),
        );
    }
    for len in [1e-55, 1e-60] {
        let a = DVec3::new(3e-51, 1e-51, 4.0e-50);
        let light = Light::segment(a, a + DVec3::new(len, 0.5 * len, 0.0)).unwrap();
        let tiny = plate(1e-50);
        compare(
            format!("segment {len} long near the origin"),
            light,
            DVec3::new(1e-51, 2e-51, 0.0),
            tiny,
        );
    }
    // On a triangle's edge to within 1e-17 (and of its plane).
    let tri = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(0.02, 0.003, 0.01),
        DVec3::new(-0.01, 0.02, 0.015),
    ];
    let disk = Light::disk(DVec3::new(0.002, 0.008, 0.04), DVec3::Z, 0.005).unwrap();
    let sphere = Light::sphere(DVec3::new(0.002, 0.008, 0.04), 0.005).unwrap();
    for t in [0.3, 0.5, 0.7] {
        let p = tri[0] + (tri[1] - tri[0]) * t;
        for dz in [0.0, 1e-17, -1e-17] {
            let q = p + DVec3::new(0.0, 0.0, dz);
            compare(format!("disk, edge {t} {dz}"), disk, q, vec![tri]);
            compare(format!("sphere, edge {t} {dz}"), sphere, q, vec![tri]);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Monte Carlo at contact: on and a hair off the triangles, every light
/// kind, within its Student-t/Šidák tolerance of the 256-bit answer (one
/// case per light and receiver: the tolerance is corrected for all of
/// them).
#[test]
fn monte_carlo_at_contact() {
    const N: u32 = 4096;
    let mut rng = Rng::new(39);
    let mut cases = Vec::new();
    for i in 0..support::samples(12) {
        let c = contact(&mut rng, place_of(i as u8), [2f64.powi(-6), 1.0][i % 2]);
        let dir = toward(&mut rng, &c);
        let scale = c.on.abs().max_element();
        let dist = scale * rng.uniform(2.0, 6.0);
        let lights = lights(&mut rng, c.on, dir, dist);
        for light in lights {
            for (name, p) in receivers(&c) {
                if light.emitter(p).is_ok() {
                    cases.push((c.clone(), light, name, p));
                }
            }
        }
    }
    let q = student_t_two_sided_quantile(sidak(1e-3, cases.len()), monte_carlo::REPLICATES - 1);
    let mut failures = Vec::new();
    for (i, (c, light, name, p)) in cases.iter().enumerate() {
        let bvh = Bvh::new(Occluders::from_triangles(c.tris.clone()));
        let truth = view::visibility(light, *p, &c.tris);
        let m = monte_carlo::visibility(
            &bvh,
            light,
            *p,
            &monte_carlo::Options::new(N).with_seed(i as u64),
        )
        .expect("receiver accepted");
        let tol = agreement_tolerance(&m, N, q);
        if (m.visibility - truth).abs() > tol {
            failures.push(format!(
                "{} {name} {light:?}: mc {m:?}, 256-bit {truth}",
                c.what
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {}:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// The methods that answer the definition exactly or statistically —
/// `exact`, `mc:N` and `hard` (a point light's answer) — through
/// `method::run` on receivers given as in a points file (no offset): the
/// corners of a tetrahedron with ordinary coordinates (exactly on three of
/// its faces), points exactly on an axis-aligned floor, and points an ulp
/// and 10⁻¹⁷ off them. `exact` within `TOLERANCE` of the 256-bit answer,
/// `mc` within its statistical tolerance, and for a point light all three
/// give the 256-bit answer bit for bit.
#[cfg(feature = "render")]
#[test]
fn methods_agree_at_contact() {
    use softshadow::method::{self, Exact, HardShadow, Method, MonteCarlo};
    use softshadow::render::{Frame, Receiver, Stages};
    use softshadow::scene::{Mesh, Scene};

    let tetra = [
        DVec3::new(0.0132, 0.0071, 0.0093),
        DVec3::new(0.0371, 0.0113, 0.0157),
        DVec3::new(0.0201, 0.0313, 0.0109),
        DVec3::new(0.0224, 0.0167, 0.0341),
    ];
    let faces = [[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    let floor = [
        DVec3::new(-0.1, 0.0, -0.1),
        DVec3::new(0.1, 0.0, -0.1),
        DVec3::new(0.1, 0.0, 0.1),
        DVec3::new(-0.1, 0.0, 0.1),
    ];
    // The floor at y = 0 and the tetrahedron standing above it (y up).
    let lift = |v: DVec3| DVec3::new(v.x, v.z, v.y);
    let tetra: Vec<DVec3> = tetra.iter().map(|&v| lift(v)).collect();
    let mut points: Vec<DVec3> = tetra.clone();
    points.push(DVec3::new(0.0243, 0.0, 0.0197));
    points.push(DVec3::new(0.0311, 0.0, 0.0221));
    let base = points.clone();
    for &q in &base {
        points.push(DVec3::new(q.x, step_ulps(q.y, -1), q.z));
        points.push(DVec3::new(q.x, step_ulps(q.y, 1), q.z));
        points.push(q + DVec3::new(1e-17, -1e-17, 1e-17));
        points.push(q - DVec3::new(1e-17, -1e-17, 1e-17));
    }
    let mut tris: Vec<[DVec3; 3]> = faces.iter().map(|f| f.map(|i| tetra[i as usize])).collect();
    tris.push([floor[0], floor[1], floor[2]]);
    tris.push([floor[0], floor[2], floor[3]]);
    let frame = Frame::from_receivers(
        points
            .iter()
            .map(|&position| Receiver {
                position,
                normal: None,
                object: None,
            })
            .collect(),
    );
    const N: u32 = 4096;
    for light in [
        Light::point(DVec3::new(0.0412, 0.0623, 0.0281)).unwrap(),
        Light::disk(
            DVec3::new(0.0312, 0.0581, 0.0244),
            DVec3::new(0.1, -1.0, 0.2),
            0.0093,
        )
        .unwrap(),
        Light::sphere(DVec3::new(0.0212, 0.0681, 0.0144), 0.0121).unwrap(),
    ] {
        let scene = Scene::new(light)
            .with_mesh(
                "floor",
                Mesh::new(floor.to_vec(), vec![[0, 1, 2], [0, 2, 3]]).unwrap(),
            )
            .with_mesh(
                "tetrahedron",
                Mesh::new(tetra.clone(), faces.to_vec()).unwrap(),
            );
        let stages = Stages::new(&scene);
        let run = |m: &dyn Method| method::run(m, &stages, &frame).unwrap().output;
        let exact = run(&Exact).visibility;
        let mc = run(&MonteCarlo::new(N));
        let hard = run(&HardShadow::default()).visibility;
        let q =
            student_t_two_sided_quantile(sidak(1e-3, points.len()), monte_carlo::REPLICATES - 1);
        for (i, &p) in points.iter().enumerate() {
            let truth = view::visibility(&light, p, &tris);
            assert!(
                (exact[i] - truth).abs() <= TOLERANCE,
                "exact at {p:?}: {} vs {truth}",
                exact[i]
            );
            let estimate = monte_carlo::Estimate {
                visibility: mc.visibility[i],
                stderr: mc.stderr.as_ref().expect("Monte Carlo's errors")[i],
            };
            let tol = agreement_tolerance(&estimate, N, q);
            assert!(
                (estimate.visibility - truth).abs() <= tol,
                "mc at {p:?}: {estimate:?} vs {truth}"
            );
            if matches!(light, Light::Point(_)) {
                assert_eq!(
                    [exact[i], mc.visibility[i], hard[i]],
                    [truth; 3],
                    "point light at {p:?}"
                );
            }
        }
    }
}

/// Issue 39, item 19: one convex polygon given as a fan of slivers from
/// an apex (a mesh's fan, every sliver sharing its corners with its
/// neighbours) hides what the polygon hides: exactly the whole light when
/// it covers it (the answer was 1.95·10⁻¹³ at 10⁵ slivers), and within
/// `TOLERANCE` of the 256-bit polygon's answer when it covers part, with
/// the apex in view and out of it, disk and rect lights.
#[test]
fn a_convex_polygon_as_a_fan_of_slivers() {
    let n = if support::exhaustive() {
        100_000
    } else {
        10_000
    };
    let p = DVec3::new(0.0137, 0.0213, 0.0);
    let lights = [
        Light::disk(
            DVec3::new(0.1031, 0.2017, 4.0),
            DVec3::new(0.03, 0.01, 1.0),
            0.5,
        )
        .unwrap(),
        Light::rect(
            DVec3::new(0.1031, 0.2017, 4.0),
            DVec3::new(0.5, 0.01, 0.0),
            DVec3::new(0.02, 0.4, 0.01),
        )
        .unwrap(),
    ];
    // (centre of the ring, its radius, apex): covering wholly with the
    // apex in view and far out of it; covering part of the light.
    let cases = [
        (
            DVec3::new(0.0, 0.0, 2.0),
            50.0,
            DVec3::new(0.0313, 0.0271, 2.0),
        ),
        (DVec3::new(0.0, 0.0, 2.0), 50.0, DVec3::new(30.3, 20.1, 2.0)),
        (
            DVec3::new(0.35, 0.2, 2.0),
            0.23,
            DVec3::new(0.3513, 0.1871, 2.0),
        ),
    ];
    for (case, (center, radius, apex)) in cases.into_iter().enumerate() {
        // The 256-bit reference clips the image by every edge: fewer
        // slivers where the polygon's edges cross the light.
        let n = if case == 2 { n / 10 } else { n };
        let ring: Vec<DVec3> = (0..n)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / n as f64;
                center + DVec3::new(a.cos(), a.sin(), 0.0) * radius
            })
            .collect();
        let tris: Vec<[DVec3; 3]> = (0..n).map(|k| [apex, ring[k], ring[(k + 1) % n]]).collect();
        for light in lights {
            let v = light.visibility_among(p, &tris).unwrap();
            let truth = view::visibility_polygon(&light, p, &ring);
            if truth == 0.0 {
                assert_eq!(v, 0.0, "{light:?}, apex {apex}");
            } else {
                assert!(
                    (v - truth).abs() <= TOLERANCE,
                    "{light:?}, apex {apex}: {v} vs {truth}"
                );
            }
        }
    }
}
