//! The renderer and the first methods, end to end: receivers from the
//! camera, the methods on them, against the references.

use softshadow::glam::DVec3;
use softshadow::method::{self, Exact, HardShadow, Method, MonteCarlo, Pcss, PcssBias};
use softshadow::output::image::{error_heat_map, shaded, visibility_image, ErrorSummary};
use softshadow::render::{Fit, Frame, Receiver, Stages, BACKGROUND};
use softshadow::scene::primitive::{cuboid, quad};
use softshadow::scene::{builtin, Camera, Light, LightKind, Scene, BUILTIN_NAMES};

/// The scene's camera at `side × side`.
fn frame(scene: &Scene, stages: &Stages, side: u32) -> Frame {
    let camera = scene.camera().unwrap().with_resolution(side, side).unwrap();
    Frame::from_camera(&camera, stages.bvh())
}

fn values(m: &dyn Method, stages: &Stages, frame: &Frame) -> Vec<f64> {
    let run = method::run(m, stages, frame).unwrap();
    let v = run.output.visibility;
    assert_eq!(v.len(), frame.receivers().len(), "{}", m.name());
    assert!(
        v.iter().all(|x| (0.0..=1.0).contains(x)),
        "{}: a value outside [0, 1]",
        m.name()
    );
    v
}

#[test]
fn hard_shadow_is_monte_carlo_with_a_point_light_bit_for_bit() {
    for name in BUILTIN_NAMES {
        let scene = builtin(name).unwrap();
        let point = scene
            .clone()
            .with_light(Light::point(scene.light().center()).unwrap());
        let (stages, point_stages) = (Stages::new(&scene), Stages::new(&point));
        let frame = frame(&scene, &stages, 48);
        let hard = values(&HardShadow::default(), &stages, &frame);
        for m in [&MonteCarlo::new(4) as &dyn Method, &Exact] {
            let reference = values(m, &point_stages, &frame);
            assert_eq!(
                hard,
                reference,
                "{name}: hard vs {} at the centre",
                m.name()
            );
        }
        // Not vacuous: the scene has shadowed and lit receivers.
        assert!(hard.contains(&0.0) && hard.contains(&1.0), "{name}");
    }
}

#[test]
fn pcss_errors_are_finite_on_every_builtin_scene_and_beat_hard_shadows_in_the_penumbra() {
    for name in BUILTIN_NAMES {
        let scene = builtin(name).unwrap();
        let stages = Stages::new(&scene);
        let frame = frame(&scene, &stages, 64);
        let exact = values(&Exact, &stages, &frame);
        let pcss = values(&Pcss::default(), &stages, &frame);
        let e = ErrorSummary::new(&pcss, &exact, |_| true);
        assert!(e.rmse.is_finite() && e.max_abs <= 1.0, "{name}: {e:?}");
    }
    // The reason PCSS exists: on the default scene's penumbra (exact V
    // strictly between 0 and 1) it is closer to the exact answer than the
    // hard shadow.
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let frame = frame(&scene, &stages, 128);
    let exact = values(&Exact, &stages, &frame);
    let penumbra = |i: usize| exact[i] > 0.0 && exact[i] < 1.0;
    assert!((0..exact.len()).filter(|&i| penumbra(i)).count() > 200);
    let hard = ErrorSummary::new(
        &values(&HardShadow::default(), &stages, &frame),
        &exact,
        penumbra,
    );
    let pcss = ErrorSummary::new(&values(&Pcss::default(), &stages, &frame), &exact, penumbra);
    assert!(
        pcss.rmse < 0.75 * hard.rmse && pcss.mean_abs < hard.mean_abs,
        "pcss {pcss:?}\nhard {hard:?}"
    );
}

#[test]
fn renders_are_bit_identical_across_runs_and_thread_counts() {
    let scene = builtin("default").unwrap();
    let render = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let stages = Stages::new(&scene);
            let frame = frame(&scene, &stages, 40);
            let mut out: Vec<Vec<u64>> = vec![frame
                .receivers()
                .iter()
                .flat_map(|r| r.position.to_array())
                .map(f64::to_bits)
                .collect()];
            for m in method::default_set(scene.light().kind()) {
                let v = values(m.as_ref(), &stages, &frame);
                out.push(v.into_iter().map(f64::to_bits).collect());
            }
            (frame.pixels().to_vec(), out)
        })
    };
    let one = render(1);
    assert_eq!(one, render(1));
    assert_eq!(one, render(2));
    assert_eq!(one, render(3));
}

fn all_methods() -> Vec<Box<dyn Method>> {
    let mut m = method::default_set(LightKind::Sphere);
    m.push(Box::new(Pcss::default().with_bias(PcssBias::Constant)));
    m
}

/// Every method on the frame: values in [0, 1] (checked by `values`), and
/// the images build with the frame's size.
fn renders_everywhere(scene: &Scene, side: u32) -> (Frame, Vec<f64>) {
    let stages = Stages::new(scene);
    let frame = frame(scene, &stages, side);
    let exact = values(&Exact, &stages, &frame);
    for m in all_methods() {
        let v = values(m.as_ref(), &stages, &frame);
        let images = [
            visibility_image(&frame, &v),
            shaded(scene, &frame, &v),
            error_heat_map(&frame, &v, &exact),
        ];
        for image in images {
            assert!(image.width >= side && image.height >= side);
            assert_eq!(image.data.len(), 3 * (image.width * image.height) as usize);
        }
    }
    (frame, exact)
}

#[test]
fn a_camera_inside_a_closed_box_sees_only_umbra() {
    let light = Light::sphere(DVec3::new(0.0, 5.0, 0.0), 0.5).unwrap();
    let camera = Camera::new(
        DVec3::ZERO,
        DVec3::new(0.3, -1.0, 0.2),
        DVec3::Y,
        100.0,
        24,
        24,
    )
    .unwrap();
    let scene = Scene::new(light)
        .with_mesh(
            "box",
            cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)).unwrap(),
        )
        .with_camera(camera);
    let (frame, exact) = renders_everywhere(&scene, 24);
    // The walls are seen from inside, every receiver is enclosed.
    assert_eq!(frame.receivers().len(), 24 * 24);
    assert!(exact.iter().all(|&v| v == 0.0));
}

#[test]
fn a_scene_without_occluders_is_all_background() {
    let camera = Camera::new(
        DVec3::new(0.0, 1.0, 3.0),
        DVec3::ZERO,
        DVec3::Y,
        45.0,
        16,
        16,
    )
    .unwrap();
    let scene = Scene::new(Light::sphere(DVec3::Y * 3.0, 0.5).unwrap()).with_camera(camera);
    let (frame, _) = renders_everywhere(&scene, 16);
    assert!(frame.receivers().is_empty());
    assert!(frame.pixels().iter().all(|&p| p == BACKGROUND));
}

#[test]
fn a_lone_floor_is_fully_lit_by_every_method() {
    let camera = Camera::new(
        DVec3::new(0.0, 1.0, 3.0),
        DVec3::ZERO,
        DVec3::Y,
        60.0,
        32,
        32,
    )
    .unwrap();
    let floor = quad(DVec3::ZERO, DVec3::X * 3.0, -DVec3::Z * 3.0).unwrap();
    let scene = Scene::new(Light::sphere(DVec3::new(1.0, 3.0, 0.5), 0.5).unwrap())
        .with_mesh("floor", floor)
        .with_camera(camera);
    let stages = Stages::new(&scene);
    let frame = frame(&scene, &stages, 32);
    assert!(frame.receivers().len() > 500);
    for m in all_methods() {
        let v = values(m.as_ref(), &stages, &frame);
        assert!(v.iter().all(|&x| x == 1.0), "{}", m.name());
    }
}

#[test]
fn a_one_pixel_image_and_a_light_behind_the_camera_are_defined() {
    let scene = builtin("default").unwrap();
    renders_everywhere(&scene, 1);
    // The light behind the eye: the camera looks away from it at the floor.
    let camera = Camera::new(
        DVec3::new(2.0, 2.5, 3.0),
        DVec3::new(-1.0, 0.0, -1.0),
        DVec3::Y,
        50.0,
        20,
        20,
    )
    .unwrap();
    let behind = scene.with_camera(camera);
    let (frame, _) = renders_everywhere(&behind, 20);
    assert!(!frame.receivers().is_empty());
}

#[test]
fn receivers_lie_on_the_surface_they_see_on_its_visible_side() {
    // The floor y = 0 seen from above: every receiver is just above it,
    // by the documented offset, with the +y normal and object 0.
    let scene = builtin("comb").unwrap();
    let stages = Stages::new(&scene);
    let frame = frame(&scene, &stages, 32);
    let on_floor: Vec<&Receiver> = frame
        .receivers()
        .iter()
        .filter(|r| r.object == Some(0))
        .collect();
    assert!(on_floor.len() > 100);
    for r in on_floor {
        assert_eq!(r.normal, Some(DVec3::Y));
        assert!(
            r.position.y > 0.0 && r.position.y < 1e-8,
            "{:?}",
            r.position
        );
    }
}

#[test]
fn pcss_without_normals_says_which_receiver_lacks_one() {
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let at = |normal| Receiver {
        position: DVec3::new(0.5, 0.0, 0.5),
        normal,
        object: Some(0),
    };
    let frame = Frame::from_receivers(vec![at(Some(DVec3::Y)), at(None)]);
    let e = method::run(&Pcss::default(), &stages, &frame).unwrap_err();
    assert!(e.to_string().contains("receiver 1"), "{e}");
    let constant = Pcss::default().with_bias(PcssBias::Constant);
    assert_eq!(values(&constant, &stages, &frame).len(), 2);
}

#[test]
fn stages_are_built_only_when_needed_and_once() {
    let scene = builtin("contact").unwrap();
    let stages = Stages::new(&scene);
    let frame = frame(&scene, &stages, 16);
    let names = |s: &softshadow::render::Stats| -> Vec<String> {
        s.stages.iter().map(|t| t.name.clone()).collect()
    };
    assert_eq!(names(&stages.stats()), ["bvh"]);
    // The hard shadow needs the BVH only, already built for the receivers.
    let hard = method::run(&HardShadow::default(), &stages, &frame).unwrap();
    assert!(hard.stats.stages.is_empty(), "{:?}", hard.stats);
    // PCSS builds its light maps once (and, when some receiver faces away
    // from the whole light, the topology that tells whether its mesh is
    // closed, `Method::hides_back_faces`); a second run on the same frame
    // reuses them, a new frame fitted to itself gets its own maps.
    let first = method::run(&Pcss::default(), &stages, &frame).unwrap();
    let built = names(&first.stats);
    assert!(
        built == ["light maps"] || built == ["light maps", "topology", "layer weights"],
        "{built:?}"
    );
    let second = method::run(&Pcss::default(), &stages, &frame).unwrap();
    assert!(second.stats.stages.is_empty());
    assert_eq!(first.output, second.output);
    let other = Frame::from_receivers(frame.receivers().to_vec()).with_fit(Fit::Frame);
    let third = method::run(&Pcss::default(), &stages, &other).unwrap();
    assert_eq!(names(&third.stats), ["light maps"]);
    // Fitted to the same receivers, so the same answer.
    assert_eq!(third.output, first.output);
    // A frame of points fitted to the scene (the default) gets the maps
    // every such frame shares.
    let points = Frame::from_receivers(frame.receivers().to_vec());
    let fourth = method::run(&Pcss::default(), &stages, &points).unwrap();
    assert_eq!(names(&fourth.stats), ["light maps"]);
    let mut all = vec!["bvh".to_owned()];
    all.extend(built);
    all.extend(["light maps".to_owned(), "light maps".to_owned()]);
    assert_eq!(names(&stages.stats()), all);
    assert!(stages
        .stats()
        .stages
        .iter()
        .all(|s| s.seconds >= 0.0 && !s.detail.is_empty()));
}

#[test]
fn pcss_names_round_trip_through_parse() {
    let variants = [
        Pcss::default(),
        Pcss::default().with_resolution(256).with_filter_samples(17),
        Pcss::default()
            .with_bias(PcssBias::Constant)
            .with_bias_margins(0.1 + 0.2, 2.5)
            .with_blocker_samples(5),
    ];
    for p in variants {
        let name = p.name();
        let back = method::parse(&name).unwrap();
        assert_eq!(format!("{back:?}"), format!("{p:?}"), "{name}");
        assert_eq!(method::parse(&name).unwrap().name(), name);
    }
    assert!(method::parse("pcss:map=").is_err());
    assert!(method::parse("pcss:sideways").is_err());
    assert!(method::parse("pcssx").is_err());
}

#[test]
fn pcss_shadows_a_receiver_right_behind_its_own_sheet() {
    // The underside of a plate lit from above, just below it (where camera
    // receivers sit, 2⁻³² of the scale off the surface) and a little lower:
    // the plate hides the whole light, as the exact reference says.
    let light = Light::disk(DVec3::new(0.0, 4.0, 0.0), -DVec3::Y, 0.6).unwrap();
    let scene = Scene::new(light)
        .with_mesh(
            "floor",
            quad(DVec3::ZERO, DVec3::X * 3.0, -DVec3::Z * 3.0).unwrap(),
        )
        .with_mesh(
            "plate",
            quad(DVec3::Y, DVec3::X * 0.4, -DVec3::Z * 0.3).unwrap(),
        );
    let under = |depth: f64, x: f64| Receiver {
        position: DVec3::new(x, 1.0 - depth, 0.05),
        normal: Some(-DVec3::Y),
        object: Some(1),
    };
    let receivers = vec![
        under(4.0 / 4_294_967_296.0, 0.0),
        under(1e-4, 0.1),
        under(1e-2, -0.1),
    ];
    let frame = Frame::from_receivers(receivers);
    let stages = Stages::new(&scene);
    let exact = values(&Exact, &stages, &frame);
    assert_eq!(exact, [0.0, 0.0, 0.0]);
    assert_eq!(values(&Pcss::default(), &stages, &frame), exact);
}

#[test]
fn a_cancelled_run_stops_early_and_returns_no_values() {
    use std::sync::{mpsc, Arc, Mutex};
    let scene = builtin("default").unwrap();
    // Refused at once on stages cancelled before the run.
    let stages = Stages::new(&scene);
    let frame = frame(&scene, &stages, 64);
    let total = frame.receivers().len();
    stages.cancel();
    assert_eq!(
        method::run(&Exact, &stages, &frame).unwrap_err(),
        method::MethodError::Cancelled
    );
    // Cancelled from another thread after the first chunk: the progress
    // callback waits until the cancel is made, so the run cannot finish
    // before it, and fewer receivers than the frame's are computed.
    let stages = Stages::new(&scene);
    let done = Arc::new(Mutex::new(0usize));
    let (first, cancelled) = (mpsc::channel::<()>(), mpsc::channel::<()>());
    let (tell, ack) = (Mutex::new(first.0), Mutex::new(cancelled.1));
    let counted = Arc::clone(&done);
    stages.set_progress(Some(Arc::new(move |n| {
        let mut d = counted.lock().unwrap();
        *d += n;
        if *d == n {
            tell.lock().unwrap().send(()).unwrap();
            ack.lock().unwrap().recv().unwrap();
        }
    })));
    let (first_rx, cancelled_tx) = (first.1, cancelled.0);
    let shared = &stages;
    let result = std::thread::scope(|s| {
        s.spawn(move || {
            first_rx.recv().unwrap();
            shared.cancel();
            cancelled_tx.send(()).unwrap();
        });
        method::run(&MonteCarlo::new(256), &stages, &frame)
    });
    assert_eq!(result.unwrap_err(), method::MethodError::Cancelled);
    let computed = *done.lock().unwrap();
    assert!(
        computed < total / 2,
        "{computed} of {total} receivers computed"
    );
    // New stages compute again, and the same values as without a cancel.
    let again = Stages::new(&scene);
    assert_eq!(
        values(&Exact, &again, &frame),
        values(&Exact, &Stages::new(&scene), &frame)
    );
}
