//! The pictures, pixel by pixel: each pixel of [`Frame::to_image`] and of
//! the PNG files `softshadow render` writes shows the receiver its own
//! primary ray hits, checked against answers computed here independently of
//! the frame's layout — the primary ray, its closest hit, the exact
//! reference at that hit point, and the shading and heat-map formulas
//! written out again.

use softshadow::glam::DVec3;
use softshadow::output::image::{BACKGROUND_RGB, HEAT_RANGE};
use softshadow::reference::exact;
use softshadow::render::{Frame, Stages, BACKGROUND, RECEIVER_OFFSET};
use softshadow::scene::{builtin, Light, Scene};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The scene with several objects per image row, at a size whose rows and
/// columns differ (so a transposed layout would show too).
const SCENE: &str = "several-objects";
const WIDTH: u32 = 56;
const HEIGHT: u32 = 42;

/// What the receiver of pixel `(col, row)` must be: the pixel's primary ray,
/// its closest hit, the hit point moved off the surface by the documented
/// [`RECEIVER_OFFSET`] of the scene's scale along the hit's normal — or
/// `None` for a background pixel.
struct Expected {
    position: DVec3,
    normal: DVec3,
    object: u32,
}

fn expected_receivers(scene: &Scene, width: u32, height: u32) -> Vec<Option<Expected>> {
    let stages = Stages::new(scene);
    let bvh = stages.bvh();
    let camera = scene
        .camera()
        .unwrap()
        .with_resolution(width, height)
        .unwrap();
    // The scene's scale: its largest coordinate magnitude.
    let extent = scene
        .meshes()
        .iter()
        .flat_map(|m| m.positions())
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    let mut out = Vec::new();
    for row in 0..height {
        for col in 0..width {
            let (eye, d) = camera.primary_ray(col, row);
            out.push(bvh.closest_hit(eye, d, f64::INFINITY).map(|hit| {
                let p = eye + d * hit.t;
                let scale = p.abs().max_element() + extent;
                Expected {
                    position: p + hit.normal * (scale * RECEIVER_OFFSET),
                    normal: hit.normal,
                    object: hit.object,
                }
            }));
        }
    }
    out
}

/// How many rows show at least `k` different objects: the test is not
/// vacuous when many rows have several receivers of several objects.
fn rows_with_objects(expected: &[Option<Expected>], width: u32, k: usize) -> usize {
    expected
        .chunks(width as usize)
        .filter(|row| {
            let mut objects: Vec<u32> = row.iter().flatten().map(|e| e.object).collect();
            objects.sort_unstable();
            objects.dedup();
            objects.len() >= k
        })
        .count()
}

#[test]
fn every_pixel_of_a_frame_is_the_receiver_its_primary_ray_hits() {
    let scene = builtin(SCENE).unwrap();
    let stages = Stages::new(&scene);
    let camera = scene
        .camera()
        .unwrap()
        .with_resolution(WIDTH, HEIGHT)
        .unwrap();
    let frame = Frame::from_camera(&camera, stages.bvh());
    let expected = expected_receivers(&scene, WIDTH, HEIGHT);
    assert!(rows_with_objects(&expected, WIDTH, 3) > 10);
    assert_eq!(frame.pixels().len(), expected.len());
    // Per receiver, values that tell receivers apart: its position.
    let xs: Vec<f64> = frame.receivers().iter().map(|r| r.position.x).collect();
    let zs: Vec<f64> = frame.receivers().iter().map(|r| r.position.z).collect();
    let (image_x, image_z) = (frame.to_image(&xs, f64::NAN), frame.to_image(&zs, f64::NAN));
    for (k, want) in expected.iter().enumerate() {
        let (col, row) = (k as u32 % WIDTH, k as u32 / WIDTH);
        let pixel = frame.pixels()[k];
        let Some(want) = want else {
            assert_eq!(pixel, BACKGROUND, "pixel ({col}, {row}) sees nothing");
            assert!(image_x[k].is_nan());
            continue;
        };
        assert_ne!(pixel, BACKGROUND, "pixel ({col}, {row}) sees a surface");
        let r = frame.receivers()[pixel as usize];
        assert_eq!(
            (r.object, r.normal),
            (Some(want.object), Some(want.normal)),
            "pixel ({col}, {row})"
        );
        assert!(
            r.position.distance(want.position) <= 1e-12,
            "pixel ({col}, {row}): receiver at {:?}, its ray hits {:?}",
            r.position,
            want.position
        );
        assert_eq!(
            (image_x[k], image_z[k]),
            (r.position.x, r.position.z),
            "pixel ({col}, {row})"
        );
    }
    // Every receiver is some pixel's, once.
    let mut seen = vec![0u32; frame.receivers().len()];
    for &p in frame.pixels().iter().filter(|&&p| p != BACKGROUND) {
        seen[p as usize] += 1;
    }
    assert!(seen.iter().all(|&n| n == 1));
}

// ---------------------------------------------------------------------------
// The PNG files `softshadow render` writes.

/// The 8-bit sRGB code of a linear value in `[0, 1]`, IEC 61966-2-1, written
/// out again here.
fn srgb(linear: f64) -> i32 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as i32
}

struct Picture {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Picture {
    fn read(path: &Path) -> Picture {
        let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut reader = png::Decoder::new(std::io::BufReader::new(file))
            .read_info()
            .unwrap();
        let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut rgb).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        rgb.truncate(info.buffer_size());
        Picture {
            width: info.width,
            height: info.height,
            rgb,
        }
    }

    fn at(&self, col: u32, row: u32) -> [u8; 3] {
        let i = 3 * (row * self.width + col) as usize;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

/// Runs `softshadow render` on [`SCENE`] with `method` into a fresh folder
/// of its own (`test` names the caller: tests run in parallel); the folder
/// and the file stem.
fn render(test: &str, method: &str) -> (PathBuf, String) {
    let dir = std::env::temp_dir().join(format!(
        "softshadow-pictures-{}-{test}-{method}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_softshadow"))
        .args(["render", "--scene", SCENE, "--method", method, "--out"])
        .arg(&dir)
        .args(["--width", &WIDTH.to_string()])
        .args(["--height", &HEIGHT.to_string()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (dir, format!("{SCENE}-{method}"))
}

/// `V` at each pixel's receiver by the exact reference for `light`, `None`
/// for background pixels.
fn exact_per_pixel(
    scene: &Scene,
    light: &Light,
    expected: &[Option<Expected>],
) -> Vec<Option<f64>> {
    let stages = Stages::new(scene);
    expected
        .iter()
        .map(|e| {
            e.as_ref()
                .map(|e| exact::visibility(stages.bvh(), light, e.position).unwrap())
        })
        .collect()
}

#[test]
fn the_visibility_and_shaded_pictures_show_the_exact_answer_at_each_pixel() {
    let scene = builtin(SCENE).unwrap();
    let expected = expected_receivers(&scene, WIDTH, HEIGHT);
    let v = exact_per_pixel(&scene, scene.light(), &expected);
    assert!(v.iter().flatten().any(|&v| v > 0.0 && v < 1.0));
    assert!(v.iter().flatten().any(|&v| v == 0.0));
    let (dir, stem) = render("pictures", "exact");
    let visibility = Picture::read(&dir.join(format!("{stem}-visibility.png")));
    let shaded = Picture::read(&dir.join(format!("{stem}-shaded.png")));
    assert_eq!((visibility.width, visibility.height), (WIDTH, HEIGHT));
    assert_eq!((shaded.width, shaded.height), (WIDTH, HEIGHT));

    // Shading of a sphere light (cos θ_l = 1): max(0, n·l̂) / |l|², exposed
    // so the brightest unshadowed receiver is white.
    let center = scene.light().center();
    let unshadowed = |e: &Expected| {
        let l = center - e.position;
        e.normal.dot(l.normalize()).max(0.0) / l.length_squared()
    };
    let top = expected
        .iter()
        .flatten()
        .map(unshadowed)
        .fold(0.0, f64::max);
    for (k, (want, v)) in expected.iter().zip(&v).enumerate() {
        let (col, row) = (k as u32 % WIDTH, k as u32 / WIDTH);
        let (got_v, got_s) = (visibility.at(col, row), shaded.at(col, row));
        let (Some(e), Some(v)) = (want, v) else {
            assert_eq!(got_v, BACKGROUND_RGB, "pixel ({col}, {row})");
            assert_eq!(got_s, BACKGROUND_RGB, "pixel ({col}, {row})");
            continue;
        };
        // One code of slack: the picture's receiver and the one here agree
        // to rounding, not necessarily bit for bit.
        let want_v = srgb(*v);
        let want_s = srgb(unshadowed(e) / top * v);
        for c in 0..3 {
            assert!(
                (i32::from(got_v[c]) - want_v).abs() <= 1,
                "visibility at ({col}, {row}): {got_v:?}, exact V = {v} → {want_v}"
            );
            assert!(
                (i32::from(got_s[c]) - want_s).abs() <= 1,
                "shaded at ({col}, {row}): {got_s:?}, want {want_s}"
            );
        }
    }
}

#[test]
fn the_heat_maps_show_no_error_for_exact_and_the_sign_of_the_hard_shadows_error() {
    let scene = builtin(SCENE).unwrap();
    let expected = expected_receivers(&scene, WIDTH, HEIGHT);
    let v = exact_per_pixel(&scene, scene.light(), &expected);
    // The hard shadow is the exact answer for a point light at the centre.
    let point = Light::point(scene.light().center()).unwrap();
    let hard = exact_per_pixel(&scene, &point, &expected);

    let (dir, stem) = render("heat", "exact");
    let heat = Picture::read(&dir.join(format!("{stem}-error.png")));
    for (k, v) in v.iter().enumerate() {
        let (col, row) = (k as u32 % WIDTH, k as u32 / WIDTH);
        let want = if v.is_some() {
            [255, 255, 255]
        } else {
            BACKGROUND_RGB
        };
        assert_eq!(
            heat.at(col, row),
            want,
            "exact's heat-map at ({col}, {row})"
        );
    }

    let (dir, stem) = render("heat", "hard");
    let heat = Picture::read(&dir.join(format!("{stem}-error.png")));
    let (mut too_bright, mut too_dark) = (0, 0);
    for (k, (v, h)) in v.iter().zip(&hard).enumerate() {
        let (col, row) = (k as u32 % WIDTH, k as u32 / WIDTH);
        let [r, g, b] = heat.at(col, row);
        let (Some(v), Some(h)) = (v, h) else {
            assert_eq!([r, g, b], BACKGROUND_RGB, "({col}, {row})");
            continue;
        };
        let e = h - v;
        // Below 1/50 of the scale's range the tint may round away.
        let visible = e.abs() >= 0.02 * HEAT_RANGE * 4.0;
        if e == 0.0 {
            assert_eq!([r, g, b], [255, 255, 255], "({col}, {row})");
        } else if e > 0.0 {
            assert!(
                r >= b && r >= g,
                "too bright is red at ({col}, {row}): e = {e}"
            );
            if visible {
                too_bright += 1;
                assert!(r > b, "({col}, {row}): e = {e}, {:?}", [r, g, b]);
            }
        } else {
            assert!(
                b >= r && b >= g,
                "too dark is blue at ({col}, {row}): e = {e}"
            );
            if visible {
                too_dark += 1;
                assert!(b > r, "({col}, {row}): e = {e}, {:?}", [r, g, b]);
            }
        }
    }
    // Both signs occur: the hard shadow is too bright in the outer
    // penumbra and too dark in the inner.
    assert!(too_bright > 10 && too_dark > 10, "{too_bright} {too_dark}");
}
