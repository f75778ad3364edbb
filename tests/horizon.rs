//! The horizon bound: `V_h`, the light's share above a receiver's tangent
//! plane, against an independent estimate, and the bound itself — no
//! exact answer exceeds it on any camera receiver of any built-in scene,
//! and `run` applies it as `min(V, V_h)`.

use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3};
use softshadow::method::{self, Exact, HardShadow, Method, Pcss, Sism};
use softshadow::render::{Frame, Stages};
use softshadow::scene::{builtin, Light, BUILTIN_NAMES};

fn camera_frame(name: &str, side: u32) -> (softshadow::scene::Scene, Frame) {
    let scene = builtin(name).unwrap();
    let camera = scene.camera().unwrap().with_resolution(side, side).unwrap();
    let frame = Frame::from_camera(&camera, Stages::new(&scene).bvh());
    (scene, frame)
}

/// `V_h` against the share of 4096 jittered samples of the measure above
/// the plane: the stratified share is within `1/64` of the true one for a
/// disk or rect cut by a straight line (at most 2·64 of the 64×64 strata
/// straddle a line, each off by at most 1/4096), and for a segment within
/// `1/4096`.
#[test]
fn the_share_above_a_plane_matches_a_stratified_count() {
    let mut rng = Rng::new(0x40_5e);
    let v = |rng: &mut Rng| {
        DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        )
    };
    let mut checked = 0;
    for case in 0..600 {
        let c = v(&mut rng) * 2.0;
        let light = match case % 4 {
            0 => Light::sphere(c, rng.uniform(0.1, 1.0)),
            1 => Light::disk(c, v(&mut rng), rng.uniform(0.1, 1.0)),
            2 => Light::rect(c, v(&mut rng), v(&mut rng)),
            _ => Light::segment(c, c + v(&mut rng)),
        };
        let Ok(light) = light else { continue };
        let p = v(&mut rng) * 3.0;
        let n = v(&mut rng);
        let Ok(emitter) = light.emitter(p) else {
            continue;
        };
        let share = emitter.share_above(p, n);
        const K: u32 = 64;
        let mut above = 0u32;
        for i in 0..K {
            for j in 0..K {
                let s = DVec2::new(
                    (f64::from(i) + rng.unit()) / f64::from(K),
                    (f64::from(j) + rng.unit()) / f64::from(K),
                );
                let s = if case % 4 == 3 {
                    DVec2::new((f64::from(i * K + j) + rng.unit()) / f64::from(K * K), 0.5)
                } else {
                    s
                };
                above += u32::from(n.dot(emitter.point_at(s) - p) > 0.0);
            }
        }
        let count = f64::from(above) / f64::from(K * K);
        let tol = if case % 4 == 3 {
            1.0 / 4096.0
        } else {
            2.0 / 64.0
        };
        assert!(
            (share - count).abs() <= tol,
            "case {case}: {light:?}, p {p}, n {n}: V_h {share}, count {count}"
        );
        checked += 1;
    }
    assert!(checked > 400);
}

/// Distance from `q` to segment `[a, b]`.
fn segment_distance(q: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let t = ((q - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    (a + d * t - q).length()
}

/// The bound, on every camera receiver: `V ≤ V_h` where the light points
/// below the tangent plane are hidden by the receiver's own surface. A
/// camera receiver sits `δ` (2⁻³² of the scene's scale) above its face;
/// a ray that leaves it at an angle `α` below the face's plane crosses
/// that plane `δ/sin α` away, inside the face unless the face's edge is
/// nearer, `e`. So only directions less than `α₀ = asin(δ/e)` below the
/// plane can escape (past a convex edge), and a light point in such a
/// direction lies less than `L·sin α₀ = L·δ/e` below the plane, `L` the
/// farthest light point: `V ≤ V_h` of the plane lowered by `L·δ/e` — at
/// most a few 10⁻⁷ here, and exactly `V_h` away from edges.
#[test]
fn no_exact_answer_exceeds_the_horizon_share_on_any_builtin_camera_receiver() {
    let (mut worst, mut worst_plain) = (0.0f64, 0.0f64);
    let mut cut = 0;
    for name in BUILTIN_NAMES {
        let scene = builtin(name).unwrap();
        let camera = scene.camera().unwrap().with_resolution(64, 64).unwrap();
        let stages = Stages::new(&scene);
        let bvh = stages.bvh();
        let frame = Frame::from_camera(&camera, bvh);
        let exact = method::run(&Exact, &stages, &frame)
            .unwrap()
            .output
            .visibility;
        let light = scene.light();
        let reach = match *light {
            Light::Sphere(s) => s.radius(),
            Light::Disk(d) => d.radius(),
            Light::Rect(r) => r.u().length() + r.v().length(),
            Light::Segment(g) => 0.5 * (g.b() - g.a()).length(),
            Light::Point(_) => 0.0,
        };
        let mut below = 0;
        let mut k = 0;
        for row in 0..64 {
            for col in 0..64 {
                let (eye, d) = camera.primary_ray(col, row);
                let Some(hit) = bvh.closest_hit(eye, d, f64::INFINITY) else {
                    continue;
                };
                let (r, v) = (&frame.receivers()[k], exact[k]);
                k += 1;
                let n = r.normal.unwrap();
                let t = bvh.occluders().triangles()[hit.triangle as usize];
                let delta = n.dot(r.position - t[0]).abs();
                let foot = r.position - n * delta;
                let e = (0..3)
                    .map(|i| segment_distance(foot, t[i], t[(i + 1) % 3]))
                    .fold(f64::INFINITY, f64::min);
                let emitter = light.emitter(r.position).unwrap();
                let share = emitter.share_above(r.position, n);
                let far = (light.center() - r.position).length() + reach;
                let lowered = if e > delta {
                    r.position - n * (far * delta / e * (1.0 + 1e-9))
                } else {
                    r.position - n * far
                };
                let bound = emitter.share_above(lowered, n);
                worst = worst.max(v - bound);
                worst_plain = worst_plain.max(v - share);
                below += usize::from(share < 1.0);
                assert!(
                    v <= bound + 1e-12,
                    "{name}: exact {v} above the bound {bound} (V_h {share}) at {:?}",
                    r.position
                );
            }
        }
        assert_eq!(k, exact.len());
        cut += below;
    }
    // Not vacuous: receivers whose tangent plane cuts the light.
    assert!(cut > 500, "{cut}");
    println!("largest exact − V_h: {worst_plain:.3e}; largest exact − bound: {worst:.3e}");
}

#[test]
fn run_applies_the_bound_as_the_minimum() {
    let (scene, frame) = camera_frame("default", 48);
    let stages = Stages::new(&scene);
    let light = scene.light();
    let share: Vec<f64> = frame
        .receivers()
        .iter()
        .map(|r| {
            light
                .emitter(r.position)
                .unwrap()
                .share_above(r.position, r.normal.unwrap())
        })
        .collect();
    let pairs: [(&dyn Method, &dyn Method); 3] = [
        (
            &HardShadow::default(),
            &HardShadow::default().with_horizon(true),
        ),
        (&Pcss::default(), &Pcss::default().with_horizon(true)),
        (&Sism::default(), &Sism::default().with_horizon(true)),
    ];
    for (plain, bounded) in pairs {
        let a = method::run(plain, &stages, &frame)
            .unwrap()
            .output
            .visibility;
        let b = method::run(bounded, &stages, &frame)
            .unwrap()
            .output
            .visibility;
        let want: Vec<f64> = a.iter().zip(&share).map(|(v, h)| v.min(*h)).collect();
        assert_eq!(b, want, "{}", bounded.name());
        assert!(a != b, "{}: the bound bites somewhere", bounded.name());
    }
}

#[test]
fn the_horizon_needs_normals() {
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let frame = Frame::from_receivers(vec![softshadow::render::Receiver {
        position: DVec3::new(0.5, 0.0, 0.5),
        normal: None,
        object: None,
    }]);
    let e = method::run(&HardShadow::default().with_horizon(true), &stages, &frame).unwrap_err();
    assert!(e.to_string().contains("normals"), "{e}");
    assert!(method::run(&HardShadow::default(), &stages, &frame).is_ok());
}
