//! Every method on fuzzed scenes, through the renderer: no panic, no NaN,
//! values in `[0, 1]`, deterministic.
//!
//! The first 8 bytes seed `arbitrary::scene::visibility_case` (every light
//! kind; occluders straddling the receiver's side or the light's plane,
//! shared edges, coincident copies, corners at the receiver, edge-on
//! triangles); the following words, read as raw `f64` bit patterns, replace
//! occluder coordinates (finite ones are kept: a mesh must be finite, and
//! huge and tiny magnitudes are the point). The occluders are one mesh as
//! given and, welded by position, a second copy offset from it; receivers
//! are the case's receiver and points around it with fuzzed normals, plus
//! an 8 × 6 camera frame looking at the receiver from above the light.
//!
//! Asserted: every method either returns one value in `[0, 1]` per receiver
//! (and, for OESS, end weights in `[0, 1]` that sum to it) or a typed error
//! that is not a contract breach; the same bits on a second
//! run; the images build; and the hard shadow equals the exact answer for a
//! point light.
#![no_main]

use glam::DVec3;
use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::scene::visibility_case;
use softshadow::arbitrary::Rng;
use softshadow::method::{self, Method, MethodError};
use softshadow::output::image::{error_heat_map, shaded, shaded_by_ends};
use softshadow::render::{Frame, Receiver, Stages};
use softshadow::scene::{Camera, Light, Mesh, Scene};

fn word(data: &[u8], i: usize) -> Option<u64> {
    let bytes = data.get(8 * i..8 * i + 8)?;
    Some(u64::from_le_bytes(bytes.try_into().ok()?))
}

const METHODS: &[&str] = &[
    "exact",
    "mc:4",
    "hard",
    "pcss:map=48,search=8,filter=8",
    "pcss:map=16,constant",
    "sism",
    "sism:exact-union",
    "sism:all-edges,conservative",
    "sism:exact-union,horizon",
    "hard:horizon",
    "single-sample:map=32",
    "single-sample:map=16,no-interpolate,no-id",
    "single-sample:map=24,light-aware,falloff=exact",
    "ssoc:map=32",
    "ssoc:map=24,lookups=1,bilinear,falloff=exact,horizon",
    "backprojected-ssoc:map=32",
    "backprojected-ssoc:map=16,search=2,walk,horizon",
    "backprojected-ssoc:map=24,search=1,walk,horizon,potential",
    "backprojected-ssoc:map=32,potential",
    "oess:map=32",
    "oess:map=24,no-tilt,depth-check,law-of-sines,bias=0",
    "oess:map=16,no-corr,bias=1",
];

fn check(scene: &Scene, frame: &Frame) {
    let stages = Stages::new(scene);
    for name in METHODS {
        let m = method::parse(name).expect("a valid name");
        let first = method::run(m.as_ref(), &stages, frame);
        let again = method::run(m.as_ref(), &Stages::new(scene), frame);
        match (&first, &again) {
            (Ok(a), Ok(b)) => {
                let v = &a.output.visibility;
                assert_eq!(v.len(), frame.receivers().len());
                assert!(v.iter().all(|x| (0.0..=1.0).contains(x)), "{name}: {v:?}");
                assert_eq!(a.output, b.output, "{name}: not deterministic");
                let _ = shaded(scene, frame, v);
                if let Some(w) = &a.output.end_weights {
                    assert_eq!(w.len(), v.len());
                    for (&[l, r], &x) in w.iter().zip(v) {
                        assert!((0.0..=1.0).contains(&l) && (0.0..=1.0).contains(&r));
                        assert!(
                            (l + r - x).abs() <= 1e-12,
                            "{name}: weights {l} + {r} vs {x}"
                        );
                    }
                    let _ = shaded_by_ends(scene, frame, w);
                }
                let _ = error_heat_map(frame, v, v);
            }
            (Err(MethodError::Contract { .. }), _) | (_, Err(MethodError::Contract { .. })) => {
                panic!("{name}: {first:?}")
            }
            (Err(a), Err(b)) => assert_eq!(a, b, "{name}: errors differ"),
            _ => panic!("{name}: one run failed, the other did not: {first:?} {again:?}"),
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let seed = word(data, 0).unwrap_or(0);
    let mut rng = Rng::new(seed);
    let mut case = visibility_case(&mut rng, 6);
    let mut k = 1;
    'raw: for t in case.triangles.iter_mut() {
        for v in t.iter_mut() {
            for c in 0..3 {
                match word(data, k) {
                    Some(w) => {
                        let x = f64::from_bits(w);
                        if x.is_finite() {
                            v[c] = x;
                        }
                    }
                    None => break 'raw,
                }
                k += 1;
            }
        }
    }
    let positions: Vec<DVec3> = case.triangles.iter().flatten().copied().collect();
    let triangles: Vec<[u32; 3]> = (0..case.triangles.len() as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    let Ok(mesh) = Mesh::new(positions.clone(), triangles.clone()) else {
        return;
    };
    let offset = DVec3::new(rng.uniform(-0.5, 0.5), 0.0, rng.uniform(-0.5, 0.5));
    let copy = Mesh::new(positions.iter().map(|&p| p + offset).collect(), triangles)
        .unwrap_or_else(|_| mesh.clone());
    let light = case.light;
    let mut scene = Scene::new(light).with_mesh("a", mesh).with_mesh("b", copy);
    let p = case.receiver;
    let mut receivers = vec![Receiver {
        position: p,
        normal: Some(DVec3::Y),
        object: Some(0),
    }];
    for _ in 0..4 {
        let n = DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        )
        .try_normalize();
        receivers.push(Receiver {
            position: p + DVec3::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-0.2, 0.2),
                rng.uniform(-1.0, 1.0),
            ),
            normal: n,
            object: Some(1),
        });
    }
    let points = Frame::from_receivers(receivers);
    check(&scene, &points);
    let eye = light.center() + DVec3::new(0.3, 1.0, 0.2);
    if let Ok(camera) = Camera::new(eye, p, DVec3::Y, 60.0, 8, 6) {
        scene = scene.with_camera(camera);
        let stages = Stages::new(&scene);
        let frame = Frame::from_camera(&camera, stages.bvh());
        check(&scene, &frame);
    }
    // The hard shadow is the exact answer for a point light at the centre.
    if let Ok(point) = Light::point(light.center()) {
        let scene = scene.clone().with_light(point);
        let stages = Stages::new(&scene);
        let hard = method::run(&method::HardShadow::default(), &stages, &points);
        let exact = method::run(&method::Exact, &stages, &points);
        if let (Ok(h), Ok(e)) = (hard, exact) {
            assert_eq!(h.output.visibility, e.output.visibility);
        }
    }
    let _: &dyn Method = &method::Exact;
});
