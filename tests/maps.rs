//! What every map method (`pcss`, `sism`, `single-sample`, `ssoc`,
//! `backprojected-ssoc`, `oess`) owes a point query, against independent
//! answers: a receiver on a closed mesh that faces away from the whole
//! light is hidden by its own mesh (`V = 0`, as the exact reference says);
//! and a receiver's `V` does not depend on the other receivers of the call
//! (maps fitted to the scene), bit for bit.

use softshadow::glam::DVec3;
use softshadow::method::{self, default_set, parse, Exact, Method};
use softshadow::render::{Fit, Frame, Receiver, Stages};
use softshadow::scene::primitive::{quad, sphere};
use softshadow::scene::{builtin, Camera, Light, LightKind, Scene};

/// The six map methods that handle `kind`, at their defaults.
fn map_methods(kind: LightKind) -> Vec<Box<dyn Method>> {
    [
        "pcss",
        "sism",
        "single-sample",
        "ssoc",
        "backprojected-ssoc",
        "oess",
    ]
    .iter()
    .map(|n| parse(n).unwrap())
    .filter(|m| m.lights().contains(&kind))
    .collect()
}

fn values(m: &dyn Method, stages: &Stages, frame: &Frame) -> Vec<f64> {
    method::run(m, stages, frame).unwrap().output.visibility
}

/// A small deterministic generator of non-dyadic numbers in `[0, 1)`.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Points on the faces of mesh `object` of `scene` whose geometric normal
/// `n` leaves the whole light below the tangent plane, moved `1e-9` off
/// the face along `n` (as camera receivers are): random barycentric
/// positions, at most `count`.
fn back_face_receivers(scene: &Scene, object: u32, count: usize, rng: &mut Lcg) -> Vec<Receiver> {
    let mesh = &scene.meshes()[object as usize];
    let pos = mesh.positions();
    let light = scene.light();
    let mut out = Vec::new();
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|i| pos[i as usize]);
        let n = (b - a).cross(c - a).normalize();
        let (mut u, mut v) = (rng.next(), rng.next());
        if u + v > 1.0 {
            (u, v) = (1.0 - u, 1.0 - v);
        }
        let p = a + (b - a) * u + (c - a) * v + n * 1e-9;
        let e = light.emitter(p).unwrap();
        if e.share_above(p, n) == 0.0 {
            out.push(Receiver {
                position: p,
                normal: Some(n),
                object: Some(object),
            });
        }
        if out.len() == count {
            break;
        }
    }
    out
}

/// A closed ball (and a closed box) over a floor, lit from above and to
/// the side: the receivers on their faces that turn away from the whole
/// light read `V = 0` with every map method, as with the exact reference.
/// Before, `single-sample` read some of them as lit: their texel sees the
/// floor past the silhouette, and the paper's ID test forbids the ball to
/// shadow itself.
#[test]
fn back_faces_of_a_closed_mesh_read_dark_with_every_map_method() {
    let mut wrong = Vec::new();
    for light in [
        Light::sphere(DVec3::new(-1.37, 2.91, 0.43), 0.35).unwrap(),
        Light::disk(
            DVec3::new(-1.9, 2.2, 0.1),
            DVec3::new(0.82, -0.57, 0.03),
            0.4,
        )
        .unwrap(),
        Light::segment(DVec3::new(-1.31, 2.53, -0.27), DVec3::new(0.93, 2.71, 0.19)).unwrap(),
    ] {
        let kind = light.kind();
        let scene = Scene::new(light)
            .with_mesh(
                "floor",
                quad(DVec3::ZERO, DVec3::X * 3.0, -DVec3::Z * 3.0).unwrap(),
            )
            .with_mesh(
                "ball",
                sphere(DVec3::new(0.213, 0.71, -0.137), 0.33, 32).unwrap(),
            )
            .with_mesh(
                "box",
                softshadow::scene::primitive::cuboid(
                    DVec3::new(0.61, 0.0, 0.37),
                    DVec3::new(1.03, 0.47, 0.83),
                )
                .unwrap(),
            );
        let mut rng = Lcg(45);
        let mut receivers = back_face_receivers(&scene, 1, 200, &mut rng);
        receivers.extend(back_face_receivers(&scene, 2, 200, &mut rng));
        assert!(
            receivers.len() > 100,
            "{kind:?}: {} receivers",
            receivers.len()
        );
        let stages = Stages::new(&scene);
        let frame = Frame::from_receivers(receivers);
        let exact = values(&Exact, &stages, &frame);
        // Zero up to the rounding of the segment's visible length.
        assert!(
            exact.iter().all(|&v| v < 1e-12),
            "{kind:?}: exact {exact:?}"
        );
        let methods = map_methods(kind);
        assert!(!methods.is_empty());
        for m in methods {
            assert!(m.hides_back_faces(), "{}", m.name());
            let v = values(m.as_ref(), &stages, &frame);
            let lit = v.iter().filter(|&&v| v != 0.0).count();
            if let Some(k) = v.iter().position(|&v| v != 0.0) {
                let r = &frame.receivers()[k];
                wrong.push(format!(
                    "{} ({kind:?}): {lit} of {} receivers not dark, e.g. at {:?} facing {:?}: V = {}",
                    m.name(),
                    v.len(),
                    r.position,
                    r.normal,
                    v[k]
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// Receivers of `scene`'s camera at 48 × 48, every third, as points.
fn camera_points(scene: &Scene, stages: &Stages) -> Vec<Receiver> {
    let camera: &Camera = scene.camera().unwrap();
    let frame = Frame::from_camera(&camera.with_resolution(48, 48).unwrap(), stages.bvh());
    frame.receivers().iter().step_by(3).copied().collect()
}

/// The same receivers asked all at once, one at a time, and in a shuffled
/// split of three parts (each part with stages of its own, as separate
/// processes would have) get bit-identical `V` from every method of the
/// default set, on a sphere-light scene and the segment-light scene.
#[test]
fn a_receiver_s_value_does_not_depend_on_the_batch() {
    for name in ["default", "linear-light"] {
        let scene = builtin(name).unwrap();
        let stages = Stages::new(&scene);
        let receivers = camera_points(&scene, &stages);
        assert!(receivers.len() > 200, "{name}: {}", receivers.len());
        let n = receivers.len();
        // A shuffle (Fisher–Yates with the generator) and three unequal parts.
        let mut order: Vec<usize> = (0..n).collect();
        let mut rng = Lcg(7);
        for i in (1..n).rev() {
            let j = (rng.next() * (i + 1) as f64) as usize;
            order.swap(i, j);
        }
        let cuts = [0, n / 7, n / 2 + 3, n];
        let mut methods = default_set(scene.light().kind());
        methods.extend(map_methods(scene.light().kind()));
        for m in &methods {
            let all = values(
                m.as_ref(),
                &stages,
                &Frame::from_receivers(receivers.clone()),
            );
            let mut split = vec![f64::NAN; n];
            for part in cuts.windows(2) {
                let idx = &order[part[0]..part[1]];
                let own = Stages::new(&scene);
                let frame = Frame::from_receivers(idx.iter().map(|&i| receivers[i]).collect());
                for (&i, v) in idx.iter().zip(values(m.as_ref(), &own, &frame)) {
                    split[i] = v;
                }
            }
            for (i, r) in receivers.iter().enumerate() {
                let one = values(m.as_ref(), &stages, &Frame::from_receivers(vec![*r]))[0];
                assert!(
                    all[i].to_bits() == one.to_bits() && all[i].to_bits() == split[i].to_bits(),
                    "{} on {name}, receiver {i} at {:?}: {} in the whole batch, {} alone, {} in a split",
                    m.name(),
                    r.position,
                    all[i],
                    one,
                    split[i]
                );
            }
        }
    }
}

/// With [`Fit::Frame`] the maps follow the batch (the real-time practice
/// `render` keeps); the frames of a camera are fitted so by default, and
/// point frames to the scene.
#[test]
fn the_fit_is_chosen_per_frame() {
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let receivers = camera_points(&scene, &stages);
    assert_eq!(Frame::from_receivers(receivers.clone()).fit(), Fit::Scene);
    let camera = scene.camera().unwrap().with_resolution(8, 8).unwrap();
    assert_eq!(Frame::from_camera(&camera, stages.bvh()).fit(), Fit::Frame);
    let framed = Frame::from_receivers(receivers).with_fit(Fit::Frame);
    assert_eq!(framed.fit(), Fit::Frame);
}
