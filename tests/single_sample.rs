//! Single-sample soft shadows (Brabec & Seidel 2002) against independent
//! answers: its hard boundary against the exact point-light test, the id
//! test against a concave receiver, the interpolation against searching
//! every pixel, and its errors against the exact reference.

use softshadow::glam::{DVec2, DVec3};
use softshadow::method::single_sample::SingleSamplePasses;
use softshadow::method::{self, Exact, Method, SingleSample};
use softshadow::output::image::ErrorSummary;
use softshadow::render::{Fit, Frame, Stages};
use softshadow::scene::primitive::{merge, quad};
use softshadow::scene::{builtin, Camera, Light, LightKind, Scene, BUILTIN_NAMES};

fn camera_frame(scene: &Scene, side: u32) -> Frame {
    let camera = scene.camera().unwrap().with_resolution(side, side).unwrap();
    Frame::from_camera(&camera, Stages::new(scene).bvh())
}

fn passes(m: &SingleSample, stages: &Stages, frame: &Frame) -> SingleSamplePasses {
    let input = method::check(m, stages, frame).expect("a valid frame");
    m.passes(&input).expect("single-sample runs")
}

/// The built-in scenes the method handles.
fn scenes() -> impl Iterator<Item = (&'static str, Scene)> {
    BUILTIN_NAMES.iter().filter_map(|&name| {
        let scene = builtin(name).unwrap();
        SingleSample::default()
            .lights()
            .contains(&scene.light().kind())
            .then_some((name, scene))
    })
}

/// `V ≥ 0.5` exactly where the light map says lit, and the map says lit
/// where the exact point-light test at the light's centre does, except
/// within one light-map texel of where that test changes: for a receiver
/// the two disagree on, moving its projection by one texel (along each
/// axis and diagonal, on its tangent plane) reaches a point the exact test
/// puts on the other side.
#[test]
fn v_crosses_one_half_within_a_texel_of_the_hard_shadow_boundary() {
    let mut checked = 0;
    for (name, scene) in scenes() {
        if !matches!(scene.light().kind(), LightKind::Sphere | LightKind::Disk) {
            continue;
        }
        let stages = Stages::new(&scene);
        let frame = camera_frame(&scene, 96);
        let m = SingleSample::default();
        let p = passes(&m, &stages, &frame);
        let maps = stages.light_maps(&frame, m.resolution, m.resolution);
        let view = &maps.as_ref().as_ref().unwrap().view;
        let lf = view.frame();
        let centre = scene.light().center();
        let bvh = stages.bvh();
        let mut disagree = 0;
        for (i, r) in frame.receivers().iter().enumerate() {
            let v = p.visibility[i];
            assert_eq!(v >= 0.5, !p.shadowed[i], "{name}: receiver {i}, V = {v}");
            let lit = bvh.segment_unoccluded(r.position, centre);
            if lit != p.shadowed[i] {
                continue;
            }
            disagree += 1;
            // The receiver's tangent plane, in the light frame.
            let q = lf.to_light(r.position);
            let [ax, ay, az] = lf.axes();
            let n = r.normal.unwrap();
            let n = DVec3::new(n.dot(ax), n.dot(ay), n.dot(az));
            let u = DVec2::new(q.x / q.z, q.y / q.z);
            let s = view.texel_size();
            // The point of the tangent plane on the ray through image
            // point `w`, and the exact test there.
            let at = |w: DVec2| {
                let ray = DVec3::new(w.x, w.y, 1.0);
                let t = n.dot(q) / n.dot(ray);
                (t > 0.0).then(|| bvh.segment_unoccluded(lf.to_world(ray * t), centre))
            };
            // The texel the map sampled: its centre's ray, on the plane,
            // answers as the map did (the boundary passes between the
            // receiver and that centre, within a texel) ...
            let texel = view.to_pixel(u).floor();
            let sampled = view.pixel_center(texel.x as u32, texel.y as u32);
            let at_centre = at(sampled) == Some(!p.shadowed[i]);
            // ... or a step of one texel crosses the boundary.
            let steps = [
                (-1.0, 0.0),
                (1.0, 0.0),
                (0.0, -1.0),
                (0.0, 1.0),
                (-1.0, -1.0),
                (1.0, -1.0),
                (-1.0, 1.0),
                (1.0, 1.0),
            ];
            let flips = at_centre
                || steps
                    .iter()
                    .any(|&(dx, dy)| at(u + DVec2::new(dx, dy) * s) == Some(!lit));
            assert!(flips, "{name}: receiver {i} at {:?}: map and exact test disagree more than a texel from the boundary", r.position);
        }
        checked += frame.receivers().len();
        assert!(
            disagree < frame.receivers().len() / 10,
            "{name}: {disagree}"
        );
    }
    assert!(checked > 20_000);
}

/// A V-shaped groove (one object) on the floor under a light straight
/// above: every receiver on its slopes sees the whole light, but each slope
/// rises in front of the other's tangent plane. With the id test the
/// groove never shadows itself; without it, it darkens itself.
#[test]
fn the_id_test_keeps_a_concave_receiver_from_darkening_itself() {
    let slope = |x: f64| {
        quad(
            DVec3::new(x, 0.25, 0.0),
            // Down toward the middle: a V, not a ridge.
            DVec3::new(0.25, 0.25 * x.signum(), 0.0),
            DVec3::new(0.0, 0.0, 0.6),
        )
        .unwrap()
    };
    let groove = merge(&[slope(-0.25), slope(0.25)]).unwrap();
    let floor = quad(DVec3::new(0.0, -0.01, 0.0), DVec3::X * 3.0, -DVec3::Z * 3.0).unwrap();
    let camera = Camera::new(
        DVec3::new(0.0, 1.6, 1.6),
        DVec3::new(0.0, 0.1, 0.0),
        DVec3::Y,
        45.0,
        96,
        96,
    )
    .unwrap();
    let scene = Scene::new(Light::sphere(DVec3::new(0.0, 3.0, 0.0), 0.1).unwrap())
        .with_mesh("floor", floor)
        .with_mesh("groove", groove)
        .with_camera(camera);
    let stages = Stages::new(&scene);
    let frame = camera_frame(&scene, 96);
    let exact = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    let on_groove: Vec<usize> = (0..exact.len())
        .filter(|&i| frame.receivers()[i].object == Some(1) && exact[i] == 1.0)
        .collect();
    assert!(on_groove.len() > 300, "{}", on_groove.len());
    // A penumbra that grows fast with the depth gap (the paper leaves
    // r_shrink to the user), so that a slope's own texels would show.
    let m = SingleSample::default().with_r_shrink(5.0);
    let with = method::run(&m, &stages, &frame).unwrap().output.visibility;
    let m = m.with_id_test(false);
    let without = method::run(&m, &stages, &frame).unwrap().output.visibility;
    let dark = |v: &[f64]| on_groove.iter().filter(|&&i| v[i] < 0.99).count();
    assert_eq!(dark(&with), 0, "with the id test");
    assert!(
        dark(&without) > on_groove.len() / 20,
        "without: {}",
        dark(&without)
    );
}

/// At the built-in cameras' 512², the image size the paper chose its 4×4
/// blocks for (§4.3; on smaller images the same blocks span more of the
/// scene: up to 0.017 RMSE at 128²).
#[test]
fn interpolation_changes_little_and_never_crosses_an_id_or_hard_boundary() {
    for (name, scene) in scenes() {
        let stages = Stages::new(&scene);
        let frame = camera_frame(&scene, 512);
        let searched = passes(
            &SingleSample::default().with_interpolation(false),
            &stages,
            &frame,
        );
        let p = passes(&SingleSample::default(), &stages, &frame);
        let e = ErrorSummary::new(&p.visibility, &searched.visibility, |_| true);
        assert!(
            e.rmse <= 0.01,
            "{name}: interpolation moved the buffer by RMSE {}",
            e.rmse
        );
        let mut interpolated = 0;
        for (i, from) in p.interpolated_from.iter().enumerate() {
            let Some((a, b)) = *from else { continue };
            interpolated += 1;
            for k in [a as usize, b as usize] {
                assert_eq!(
                    (p.id[k], p.shadowed[k]),
                    (p.id[i], p.shadowed[i]),
                    "{name}: receiver {i} from {k}"
                );
            }
            // Between its interpolants' values.
            let (va, vb) = (p.visibility[a as usize], p.visibility[b as usize]);
            assert!(p.visibility[i] >= va.min(vb) - 1e-15 && p.visibility[i] <= va.max(vb) + 1e-15);
        }
        assert!(
            interpolated > frame.receivers().len() / 2,
            "{name}: {interpolated}"
        );
        assert!(searched.interpolated_from.iter().all(Option::is_none));
    }
}

#[test]
fn points_files_are_never_interpolated() {
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let camera = camera_frame(&scene, 64);
    // Fitted as the camera's frame is, so that only the interpolation
    // differs.
    let points = Frame::from_receivers(camera.receivers().to_vec()).with_fit(Fit::Frame);
    let p = passes(&SingleSample::default(), &stages, &points);
    assert!(p.interpolated_from.iter().all(Option::is_none));
    let all = passes(
        &SingleSample::default().with_interpolation(false),
        &stages,
        &camera,
    );
    assert_eq!(p.visibility, all.visibility);
}

#[test]
fn lights_it_cannot_handle_and_missing_ids_are_refused() {
    let segment = builtin("linear-light").unwrap();
    let stages = Stages::new(&segment);
    let frame = camera_frame(&segment, 16);
    let e = method::run(&SingleSample::default(), &stages, &frame).unwrap_err();
    assert!(e.to_string().contains("segment"), "{e}");
    let rect = builtin("rect-light").unwrap();
    let stages = Stages::new(&rect);
    let frame = camera_frame(&rect, 16);
    assert!(method::run(&SingleSample::default(), &stages, &frame).is_ok());
    let e = method::run(
        &SingleSample::default().with_light_aware(true),
        &stages,
        &frame,
    )
    .unwrap_err();
    assert!(e.to_string().contains("light-aware"), "{e}");
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let no_id = Frame::from_receivers(vec![softshadow::render::Receiver {
        position: DVec3::new(0.3, 0.0, 0.3),
        normal: Some(DVec3::Y),
        object: None,
    }]);
    let e = method::run(&SingleSample::default(), &stages, &no_id).unwrap_err();
    assert!(e.to_string().contains("object ids"), "{e}");
    assert!(method::run(
        &SingleSample::default().with_id_test(false),
        &stages,
        &no_id
    )
    .is_ok());
}

/// The light-aware radii follow the light: on the sphere-light scenes
/// their penumbra RMSE is below the paper's constants'.
#[test]
fn light_aware_radii_lower_the_penumbra_error_on_sphere_light_scenes() {
    for name in ["default", "contact", "large-light", "several-objects"] {
        let scene = builtin(name).unwrap();
        let stages = Stages::new(&scene);
        let frame = camera_frame(&scene, 128);
        let exact = method::run(&Exact, &stages, &frame)
            .unwrap()
            .output
            .visibility;
        let penumbra = |i: usize| exact[i] > 0.0 && exact[i] < 1.0;
        let rmse = |m: &SingleSample| {
            let v = method::run(m, &stages, &frame).unwrap().output.visibility;
            ErrorSummary::new(&v, &exact, penumbra).rmse
        };
        let paper = rmse(&SingleSample::default());
        let aware = rmse(&SingleSample::default().with_light_aware(true));
        assert!(aware < paper, "{name}: light-aware {aware} against {paper}");
    }
}
