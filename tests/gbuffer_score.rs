//! G-buffers out, float images in: the camera model against the primary
//! rays, the score against closed forms (the exact image itself, a
//! constant offset), and the round trip through `.npy` files reproducing
//! the renderer's own error table for every method of the default sets.

use softshadow::float_io::{npy_bytes_f64, npy_bytes_i32, read_npy_f64, read_npy_i64};
use softshadow::glam::DVec3;
use softshadow::method::{self, Exact};
use softshadow::output::gbuffer::{frame_from_arrays, CameraModel, GBuffer};
use softshadow::output::image::{ErrorRow, ErrorSummary};
use softshadow::output::score::{score, shading_factors, Score};
use softshadow::render::{Frame, Stages};
use softshadow::scene::{builtin, Camera, Scene};

fn camera(scene: &Scene, w: u32, h: u32) -> Camera {
    scene.camera().unwrap().with_resolution(w, h).unwrap()
}

#[test]
fn the_camera_model_projects_each_receiver_onto_its_pixel_centre() {
    for (name, w, h) in [
        ("default", 61, 37),
        ("comb", 40, 40),
        ("linear-light", 33, 50),
    ] {
        let scene = builtin(name).unwrap();
        let cam = camera(&scene, w, h);
        let g = GBuffer::compute(&scene, &cam).unwrap();
        let model = g.camera;
        let mut surface = 0;
        for row in 0..h as usize {
            for col in 0..w as usize {
                let k = row * w as usize + col;
                if g.object[k] < 0 {
                    assert!(g.position[3 * k].is_nan() && g.exact[k].is_nan());
                    continue;
                }
                surface += 1;
                let p = DVec3::from_slice(&g.position[3 * k..3 * k + 3]);
                let (x, y, z) = model.project(p).unwrap();
                // The receiver is on the pixel's primary ray, moved 2⁻³²
                // of the scene's scale off its surface: far below 10⁻⁶ of a
                // pixel.
                assert!(
                    (x - (col as f64 + 0.5)).abs() < 1e-6 && (y - (row as f64 + 0.5)).abs() < 1e-6,
                    "{name} ({row}, {col}): projects to ({x}, {y})"
                );
                assert!(z > 0.0 && z < 1.0, "{name}: depth {z}");
                let n = DVec3::from_slice(&g.normal[3 * k..3 * k + 3]);
                assert!((n.length() - 1.0).abs() < 1e-12);
                // Facing the camera.
                assert!(
                    n.dot(DVec3::from(model.eye) - p) > 0.0,
                    "{name}: normal away from the eye"
                );
            }
        }
        assert!(
            surface > (w * h) as usize / 4,
            "{name}: {surface} surface pixels"
        );
        // The view matrix is a rigid motion taking the eye to the origin
        // and the target onto −z.
        let m = |r: &[[f64; 4]; 4]| softshadow::glam::DMat4::from_cols_array_2d(r).transpose();
        let view = m(&model.view);
        assert!(view.transform_point3(DVec3::from(model.eye)).length() < 1e-12);
        let t = view.transform_point3(DVec3::from(model.target));
        assert!(t.x.abs() < 1e-12 && t.y.abs() < 1e-12 && t.z < 0.0, "{t}");
        assert!((view.determinant() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn camera_json_carries_the_matrices_light_and_conventions() {
    let scene = builtin("default").unwrap();
    let model = CameraModel::new(&camera(&scene, 8, 6), scene.bounds());
    let text = model.to_json(&scene);
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["width"], 8);
    assert_eq!(json["light"]["type"], "sphere");
    assert_eq!(json["light"]["radius"], 0.5);
    assert_eq!(json["view"][2][3].as_f64(), Some(model.view[2][3]));
    assert_eq!(json["projection"][3][2].as_f64(), Some(-1.0));
    for (k, _) in CameraModel::CONVENTIONS {
        assert!(json["conventions"][k].is_string(), "{k}");
    }
    assert_eq!(json["objects"][0], "floor");
}

/// The exact G-buffer of a scene and its frame.
fn setup(name: &str, w: u32, h: u32) -> (Scene, Frame, Vec<f64>, Vec<f64>) {
    let scene = builtin(name).unwrap();
    let (frame, exact) = {
        let stages = Stages::new(&scene);
        let frame = Frame::from_camera(&camera(&scene, w, h), stages.bvh());
        let exact = method::run(&Exact, &stages, &frame)
            .unwrap()
            .output
            .visibility;
        (frame, exact)
    };
    let image = frame.to_image(&exact, f64::NAN);
    (scene, frame, exact, image)
}

#[test]
fn the_exact_image_scores_zero_and_an_offset_scores_the_offset() {
    let (scene, frame, exact, image) = setup("default", 72, 54);
    let s = score(&scene, &frame, &image).unwrap();
    assert_eq!(s.exact, exact);
    let sc = &s.score;
    assert_eq!((sc.pixels, sc.nan_pixels), (frame.receivers().len(), 0));
    for e in sc.v.iter().chain(&sc.shaded) {
        assert_eq!((e.rmse, e.max_abs, e.mean_signed), (0.0, 0.0, 0.0));
    }
    assert!(sc.v[1].count > 50, "penumbra {}", sc.v[1].count);
    assert!(sc.passes(0.0));
    // Off by c everywhere: every statistic of V is c (closed form), the
    // shaded RMSE is c·√(mean of the squared shading factors).
    let c = 0.013_7;
    let off: Vec<f64> = image.iter().map(|v| v + c).collect();
    let (o, _) = Score::new(&frame, scene.light(), &off, &exact);
    for (g, e) in o.v.iter().enumerate() {
        for x in [e.rmse, e.mean_abs, e.max_abs, e.mean_signed, e.p99_abs] {
            assert!((x - c).abs() < 1e-15, "group {g}: {x} for {c}");
        }
        assert_eq!(e.share_over_0_05, 0.0);
    }
    let f = shading_factors(scene.light(), frame.receivers());
    let want = c * (f.iter().map(|x| x * x).sum::<f64>() / f.len() as f64).sqrt();
    assert!(
        (o.shaded[0].rmse - want).abs() < 1e-15 * want.max(1.0),
        "{} {want}",
        o.shaded[0].rmse
    );
    assert!(!o.passes(c * 0.999) && o.passes(c * 1.001));
    // −c: the bias is negative.
    let (neg, _) = Score::new(
        &frame,
        scene.light(),
        &image.iter().map(|v| v - c).collect::<Vec<_>>(),
        &exact,
    );
    assert!((neg.v[0].mean_signed + c).abs() < 1e-15);
}

#[test]
fn nan_and_infinite_pixels_are_counted_and_left_out_background_ignored() {
    let (scene, frame, exact, mut image) = setup("default", 40, 30);
    let surface: Vec<usize> = (0..image.len()).filter(|&k| image[k].is_finite()).collect();
    let background = (0..image.len()).find(|&k| image[k].is_nan()).unwrap();
    image[background] = 7.0;
    let bad = [surface[3], surface[100], surface[surface.len() - 1]];
    image[bad[0]] = f64::NAN;
    image[bad[1]] = f64::INFINITY;
    image[bad[2]] = f64::NEG_INFINITY;
    let (s, _) = Score::new(&frame, scene.light(), &image, &exact);
    assert_eq!(s.nan_pixels, 3);
    assert_eq!(s.pixels, surface.len() - 3);
    assert_eq!(
        s.first_nan,
        Some(((bad[0] / 40) as u32, (bad[0] % 40) as u32))
    );
    assert_eq!(s.rmse(), 0.0);
    assert!(!s.passes(1.0), "a NaN pixel fails every gate");
    let json: serde_json::Value = serde_json::from_str(&s.to_json()).unwrap();
    assert_eq!(json["nan_pixels"], 3);
    assert_eq!(json["rmse"].as_f64(), Some(0.0));
}

fn assert_close(a: &ErrorSummary, b: &ErrorSummary, what: &str) {
    assert_eq!(a.count, b.count, "{what}");
    for (x, y) in [
        (a.mean_abs, b.mean_abs),
        (a.rmse, b.rmse),
        (a.p99_abs, b.p99_abs),
        (a.max_abs, b.max_abs),
        (a.mean_signed, b.mean_signed),
        (a.share_over_0_05, b.share_over_0_05),
    ] {
        assert!((x - y).abs() <= 1e-12, "{what}: {x} vs {y}");
    }
}

#[test]
fn render_then_npy_then_score_reproduces_the_error_table_for_every_default_method() {
    for (name, w, h) in [("default", 64, 48), ("linear-light", 48, 40)] {
        let (scene, frame, exact, _) = setup(name, w, h);
        // The G-buffer through its .npy files, as another renderer reads it.
        let g = GBuffer::from_frame(
            &frame,
            &exact,
            CameraModel::new(&camera(&scene, w, h), scene.bounds()),
        );
        let (wu, hu) = (w as usize, h as usize);
        let pos = read_npy_f64(&npy_bytes_f64(&[hu, wu, 3], &g.position).unwrap()).unwrap();
        let nrm = read_npy_f64(&npy_bytes_f64(&[hu, wu, 3], &g.normal).unwrap()).unwrap();
        let obj = read_npy_i64(&npy_bytes_i32(&[hu, wu], &g.object).unwrap()).unwrap();
        let read_back = frame_from_arrays(
            wu,
            hu,
            &pos.data,
            &nrm.data,
            &obj.data,
            scene.meshes().len(),
        )
        .unwrap();
        assert_eq!(read_back.receivers(), frame.receivers(), "{name}");
        assert_eq!(read_back.pixels(), frame.pixels(), "{name}");
        let methods = method::default_set(scene.light().kind());
        assert!(methods.len() >= 3, "{name}");
        for m in methods {
            let run = method::run(m.as_ref(), &Stages::new(&scene), &frame).unwrap();
            let v = &run.output.visibility;
            let row = ErrorRow::new(m.name(), run.seconds, v, &exact);
            // What `render --format npy` writes: H×W float64, NaN background.
            let file = npy_bytes_f64(&[hu, wu], &frame.to_image(v, f64::NAN)).unwrap();
            let image = read_npy_f64(&file).unwrap();
            // Scored on our camera's receivers at the image's size, and on
            // the G-buffer read back.
            let fresh = Frame::from_camera(&camera(&scene, w, h), Stages::new(&scene).bvh());
            for (route, f) in [("camera", &fresh), ("gbuffer", &read_back)] {
                let s = score(&scene, f, &image.data).unwrap().score;
                let what = format!("{name} {} via {route}", m.name());
                assert_eq!(s.nan_pixels, 0, "{what}");
                assert_close(&s.v[0], &row.all, &what);
                assert_close(&s.v[1], &row.penumbra, &what);
            }
        }
    }
}

#[test]
fn bad_gbuffer_arrays_name_the_array_and_pixel() {
    let (w, h) = (3, 2);
    let mut pos = vec![0.5; 18];
    let mut nrm: Vec<f64> = [0.0, 1.0, 0.0].repeat(6);
    let mut obj = vec![0i64, 1, -1, 0, 0, 0];
    assert!(frame_from_arrays(w, h, &pos, &nrm, &obj, 2).is_ok());
    let e = frame_from_arrays(w, h, &pos[..17], &nrm, &obj, 2).unwrap_err();
    assert_eq!(e.array, "position");
    pos[3 * 4 + 1] = f64::NAN;
    let e = frame_from_arrays(w, h, &pos, &nrm, &obj, 2).unwrap_err();
    assert_eq!((e.array, e.pixel), ("position", Some((1, 1))));
    assert!(e.to_string().contains("surface"), "{e}");
    // NaN where there is no surface is the convention, not an error.
    obj[4] = -1;
    assert!(frame_from_arrays(w, h, &pos, &nrm, &obj, 2).is_ok());
    obj[5] = 2;
    let e = frame_from_arrays(w, h, &pos, &nrm, &obj, 2).unwrap_err();
    assert_eq!((e.array, e.pixel), ("object", Some((1, 2))));
    obj[5] = 0;
    nrm[0] = 0.5;
    let e = frame_from_arrays(w, h, &pos, &nrm, &obj, 2).unwrap_err();
    assert_eq!((e.array, e.pixel), ("normal", Some((0, 0))));
}

/// An image that is Monte Carlo with N samples (another seed) measures at
/// about N on the yardstick; on a subset, the bootstrap interval holds it.
#[cfg(feature = "report")]
#[test]
fn the_yardstick_finds_monte_carlo_s_own_sample_count() {
    use softshadow::method::MonteCarlo;
    use softshadow::output::score::{mc_equal, McOptions};
    let (scene, frame, _, _) = setup("default", 96, 72);
    let n = 32;
    let mc = method::run(
        &MonteCarlo::new(n).with_seed(977),
        &Stages::new(&scene),
        &frame,
    )
    .unwrap()
    .output
    .visibility;
    let image = frame.to_image(&mc, f64::NAN);
    let scored = score(&scene, &frame, &image).unwrap();
    let counts: Vec<u32> = (1..=8).map(|k| 1 << k).collect();
    for receivers in [usize::MAX, 1500] {
        let options = McOptions {
            counts: counts.clone(),
            receivers,
            seed: 5,
            resamples: 100,
        };
        let m = mc_equal(&scene, &frame, &scored, &options).unwrap();
        let found = m.n.unwrap_or_else(|| panic!("{}", m.text));
        assert!(
            found > f64::from(n) / 1.5 && found < f64::from(n) * 1.5,
            "{receivers}: equal-RMSE N {found} for Monte Carlo with {n}"
        );
        if receivers < frame.receivers().len() {
            let (lo, hi) = m.interval.unwrap();
            assert_eq!(m.receivers, receivers);
            assert!(lo <= found && found <= hi && lo < hi, "{lo} {found} {hi}");
            assert!(
                lo < f64::from(n) && f64::from(n) < hi,
                "[{lo}, {hi}] misses {n}"
            );
        } else {
            assert_eq!((m.receivers, m.interval), (frame.receivers().len(), None));
        }
        // Monte Carlo's RMSE falls with N.
        assert!(m.mc_rmse.first() > m.mc_rmse.last());
    }
}
