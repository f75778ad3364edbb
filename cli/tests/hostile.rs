//! Hostile input and a hostile environment, one test per case: a closed
//! stdout ends the program quietly; files are replaced whole (a symlink is
//! replaced, never written through); `--out` is checked before any work;
//! special and oversized input files are refused without being read; error
//! messages stay one short line whatever the input quoted; option values
//! beyond their range are refused; lights at the edge of `f64` (a far
//! sphere, a radius of 1e-170) give answers, not false errors or NaN.
#![cfg(unix)]

use softshadow::glam::DVec3;
use softshadow::reference::exact;
use softshadow::{Bvh, Light, Occluders};
use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

#[path = "support/cli.rs"]
mod cli_support;

use cli_support::{bin, pictures_whole, refused, softshadow, write};

fn dir(name: &str) -> PathBuf {
    cli_support::dir("hostile", name)
}

const SCENE: &str = r#"{"light": {"type": "sphere", "center": [0, 3, 0], "radius": 0.5},
 "camera": {"eye": [0, 2, 6], "target": [0, 0, 0], "fov_y_deg": 40, "width": 24, "height": 18},
 "meshes": [{"name": "floor", "primitive": {"type": "quad", "center": [0, 0, 0], "u": [4, 0, 0], "v": [0, 0, 4]}},
            {"name": "card", "positions": [[-1,1,-1],[1,1,-1],[0,1,1]], "triangles": [[0,1,2]]}]}"#;

/// Starts `softshadow args` with its stdout closed before it writes.
fn with_stdout_closed(args: &[&str]) -> Output {
    let mut child = bin()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Close the reading end at once: every write the program makes fails
    // with a broken pipe.
    drop(child.stdout.take());
    let mut stderr = Vec::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_end(&mut stderr)
        .unwrap();
    let status = child.wait().unwrap();
    Output {
        status,
        stdout: Vec::new(),
        stderr,
    }
}

#[test]
fn a_closed_stdout_ends_the_program_quietly() {
    let d = dir("pipe");
    let scene = write(&d, "scene.json", SCENE);
    let points = write(&d, "points.json", r#"{"points": [{"p": [0.2, 0.0, 0.1]}]}"#);
    for args in [
        vec![
            "visibility",
            "--scene",
            &scene,
            "--points",
            &points,
            "--method",
            "hard",
        ],
        vec![
            "render",
            "--scene",
            &scene,
            "--method",
            "hard",
            "--out",
            d.to_str().unwrap(),
        ],
    ] {
        let out = with_stdout_closed(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {stderr}");
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
    }
    // Whatever `render` wrote before it stopped is whole: every PNG
    // decodes, and no temporary file is left.
    pictures_whole(&d, false);
}

#[test]
fn out_is_checked_before_any_work_and_symlinks_are_replaced() {
    let d = dir("out");
    let scene = write(
        &d,
        "nocam.json",
        r#"{"light": {"type": "point", "position": [0, 3, 0]}, "meshes": []}"#,
    );
    let file = write(&d, "a-file", "x");
    // Before the scene is even looked at (it has no camera, which `render`
    // would report): `--out` names a file.
    refused(
        &softshadow(&[
            "render", "--scene", &scene, "--method", "hard", "--out", &file,
        ]),
        300,
        &["--out", "a-file"],
    );
    refused(
        &softshadow(&["report", "--scene", "default", "--out", &file]),
        300,
        &["--out"],
    );
    refused(&softshadow(&["stability", "--out", &file]), 300, &["--out"]);

    // A symlink where a picture goes is replaced; its target is untouched.
    let out = dir("out-link");
    let target = write(&d, "precious.txt", "keep me");
    let scene = write(&d, "scene.json", SCENE);
    let link = out.join("scene-hard-visibility.png");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let run = softshadow(&[
        "render",
        "--scene",
        &scene,
        "--method",
        "hard",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep me");
    assert!(!std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
}

#[test]
fn special_and_oversized_files_are_refused_without_reading_them() {
    let d = dir("special");
    let scene = write(&d, "scene.json", SCENE);
    let start = Instant::now();
    refused(
        &softshadow(&[
            "render",
            "--scene",
            "/dev/zero",
            "--method",
            "hard",
            "--out",
            d.to_str().unwrap(),
        ]),
        300,
        &["/dev/zero", "not a regular file"],
    );
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            &scene,
            "--points",
            "/dev/zero",
            "--method",
            "hard",
        ]),
        300,
        &["not a regular file"],
    );
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            &scene,
            "--points",
            d.to_str().unwrap(),
            "--method",
            "hard",
        ]),
        300,
        &["a directory"],
    );
    let obj = write(
        &d,
        "obj.json",
        r#"{"light": {"type": "point", "position": [0, 3, 0]}, "meshes": [{"obj": "/dev/zero"}]}"#,
    );
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            &obj,
            "--points",
            &scene,
            "--method",
            "hard",
        ]),
        400,
        &["obj", "not a regular file"],
    );
    // A FIFO would block the reader until a writer came: refused first.
    let fifo = d.join("fifo.json");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        refused(
            &softshadow(&[
                "visibility",
                "--scene",
                fifo.to_str().unwrap(),
                "--points",
                &scene,
                "--method",
                "hard",
            ]),
            300,
            &["not a regular file"],
        );
    }
    // A sparse file over the size limit: refused by its size, not read.
    let big = d.join("big.json");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(300 << 20)
        .unwrap();
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            big.to_str().unwrap(),
            "--points",
            &scene,
            "--method",
            "hard",
        ]),
        300,
        &["over the limit"],
    );
    assert!(
        start.elapsed() < Duration::from_secs(60),
        "something was read whole"
    );
}

#[test]
fn messages_stay_one_short_line_whatever_the_input_quotes() {
    let d = dir("long");
    let long = "7".repeat(2 << 20);
    let radius = write(
        &d,
        "radius.json",
        &format!(
            r#"{{"light": {{"type": "sphere", "center": [0, 3, 0], "radius": "{long}"}}, "meshes": []}}"#
        ),
    );
    let key = write(
        &d,
        "key.json",
        &format!(
            r#"{{"light": {{"type": "point", "position": [0, 3, 0], "{long}": 1}}, "meshes": []}}"#
        ),
    );
    let ty = write(
        &d,
        "type.json",
        &format!(r#"{{"light": {{"type": "{long}"}}, "meshes": []}}"#),
    );
    for file in [&radius, &key, &ty] {
        refused(
            &softshadow(&[
                "visibility",
                "--scene",
                file,
                "--points",
                file,
                "--method",
                "hard",
            ]),
            1000,
            &["bytes"],
        );
    }
    let name = "n".repeat(100_000);
    refused(
        &softshadow(&["render", "--scene", &name, "--method", "hard"]),
        1000,
        &["--scene"],
    );
    // A path with a newline in it, under a file: one line all the same.
    let odd = write(&d, "odd\nname", "x");
    let under = format!("{odd}/sub");
    refused(
        &softshadow(&[
            "render", "--scene", "default", "--method", "hard", "--out", &under,
        ]),
        1000,
        &["--out", "odd\\nname"],
    );
}

#[test]
fn option_values_beyond_their_range_are_refused() {
    for (m, needle) in [
        ("pcss:search=4294967295", "search"),
        ("pcss:filter=4294967295", "filter"),
        ("mc:4294967296", "mc"),
    ] {
        refused(
            &softshadow(&["render", "--scene", "default", "--method", m]),
            1000,
            &[needle],
        );
    }
}

/// A sphere light 3e300 away is not "inside", and a radius of 1e-170 (whose
/// square underflows) gives the point light's answer, not NaN.
#[test]
fn lights_at_the_edge_of_f64() {
    let far = Light::sphere(DVec3::new(3e300, 0.0, 0.0), 5e299).unwrap();
    assert!(far.emitter(DVec3::ZERO).is_ok());
    let empty = Bvh::new(Occluders::from_triangles(Vec::new()));
    assert_eq!(exact::visibility(&empty, &far, DVec3::ZERO), Ok(1.0));
    // A wall at x = 1 hides all of it.
    let wall = vec![[
        DVec3::new(1.0, -10.0, -10.0),
        DVec3::new(1.0, 10.0, -10.0),
        DVec3::new(1.0, 0.0, 20.0),
    ]];
    let bvh = Bvh::new(Occluders::from_triangles(wall.clone()));
    assert_eq!(exact::visibility(&bvh, &far, DVec3::ZERO), Ok(0.0));
    assert_eq!(far.visibility_among(DVec3::ZERO, &wall), Ok(0.0));

    let d = dir("tiny");
    let scene = write(
        &d,
        "tiny.json",
        &SCENE.replace("\"radius\": 0.5", "\"radius\": 1e-170"),
    );
    for method in ["exact", "hard", "mc:16"] {
        let out = softshadow(&[
            "render",
            "--scene",
            &scene,
            "--method",
            method,
            "--out",
            d.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{method}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// Exact copies of one triangle are indexed once (10⁶ of them took the
/// BVH build minutes and every ray 10⁶ tests), and every answer is the one
/// triangle's; nested triangles whose largest hides the whole light give
/// V = 0 from the exact reference without measuring their union.
#[test]
fn copies_and_nested_triangles_are_answered_as_one() {
    let t = [
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, -1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    let light = Light::sphere(DVec3::new(0.0, 3.0, 0.0), 0.5).unwrap();
    let one = Bvh::new(Occluders::from_triangles(vec![t]));
    let copies = Bvh::new(Occluders::from_triangles(vec![t; 1_000_000]));
    let mut ids = Vec::new();
    copies.triangles_meeting_hull(
        &[DVec3::new(0.9, 0.0, 0.0), DVec3::new(0.0, 3.0, 0.0)],
        &mut ids,
    );
    assert_eq!(ids, vec![0]);
    for k in 0..50 {
        let p = DVec3::new(-1.0 + 0.04 * f64::from(k), 0.0, 0.1);
        assert_eq!(
            exact::visibility(&copies, &light, p),
            exact::visibility(&one, &light, p)
        );
        let x = DVec3::new(0.0, 3.0, 0.0);
        assert_eq!(
            copies.segment_unoccluded(p, x),
            one.segment_unoccluded(p, x)
        );
        let hit = copies
            .closest_hit(p, x - p, f64::INFINITY)
            .map(|h| (h.t, h.triangle));
        assert_eq!(
            hit,
            one.closest_hit(p, x - p, f64::INFINITY)
                .map(|h| (h.t, h.triangle))
        );
    }

    let centre = (t[0] + t[1] + t[2]) / 3.0;
    let n = 2000;
    let nested: Vec<[DVec3; 3]> = (0..n)
        .map(|k| t.map(|v| centre + (v - centre) * (1.0 + f64::from(k) / f64::from(n))))
        .collect();
    let largest = Bvh::new(Occluders::from_triangles(vec![nested[n as usize - 1]]));
    let all = Bvh::new(Occluders::from_triangles(nested));
    let p = DVec3::new(0.9, 0.0, 0.0);
    assert_eq!(exact::visibility(&largest, &light, p), Ok(0.0));
    assert_eq!(exact::visibility(&all, &light, p), Ok(0.0));
}

/// A triangle spanning ±1e155 over the receiver (every reference and method
/// answered V = 1, where it is 0: the predicates' products overflow) is
/// refused at load, naming the field, its value and the domain; so is a
/// transform that carries a vertex out of it.
#[test]
fn coordinates_beyond_the_domain_are_refused_at_load() {
    let d = dir("domain");
    let points = write(&d, "points.json", r#"{"points": [{"p": [0, 0, 0]}]}"#);
    let huge = write(
        &d,
        "huge.json",
        r#"{"light": {"type": "sphere", "center": [0, 3, 0], "radius": 0.5},
            "meshes": [{"positions": [[-1e155, 1, -1e155], [1e155, 1, -1e155], [0, 1, 1e155]], "triangles": [[0, 1, 2]]}]}"#,
    );
    for method in ["exact", "hard", "mc:16"] {
        refused(
            &softshadow(&[
                "visibility",
                "--scene",
                &huge,
                "--points",
                &points,
                "--method",
                method,
            ]),
            400,
            &["meshes[0].positions[0][0]", "-1e155", "domain"],
        );
    }
    let moved = write(
        &d,
        "moved.json",
        r#"{"light": {"type": "sphere", "center": [0, 3, 0], "radius": 0.5},
            "meshes": [{"primitive": {"type": "sphere", "center": [0, 0, 0], "radius": 1e20},
                        "transform": {"scale": 1e20}}]}"#,
    );
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            &moved,
            "--points",
            &points,
            "--method",
            "hard",
        ]),
        400,
        &["meshes[0]", "domain"],
    );
    let far_point = write(&d, "far.json", r#"{"points": [{"p": [0, 2e30, 0]}]}"#);
    let ok = write(&d, "ok.json", SCENE);
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            &ok,
            "--points",
            &far_point,
            "--method",
            "hard",
        ]),
        400,
        &["points[0].p[1]", "domain"],
    );
}

/// A 1000 × 1000 ceiling one unit above a floor point, five below the
/// light: PCSS's map, fitted to the ceiling, has texels 1.2 units wide at
/// the receiver, and its depth margin in texels lit the point (V = 1 where
/// exact says 0). The margin is capped at `Pcss::MAX_BIAS_SHARE` of the
/// receiver's depth.
#[test]
fn shadow_maps_find_a_large_blocker_close_above_the_receiver() {
    use softshadow::method::{self, Exact, Pcss, PcssBias};
    use softshadow::scene::primitive;
    use softshadow::{Frame, Receiver, Scene, Stages};
    let light = Light::sphere(DVec3::new(0.0, 5.0, 0.0), 0.5).unwrap();
    let floor = primitive::quad(DVec3::ZERO, DVec3::X * 3.0, DVec3::Z * 3.0).unwrap();
    let ceiling = primitive::quad(
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::X * 500.0,
        DVec3::Z * 500.0,
    )
    .unwrap();
    let scene = Scene::new(light)
        .with_mesh("floor", floor)
        .with_mesh("ceiling", ceiling);
    let receivers = [
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(-2.0, 0.0, 0.5),
    ]
    .map(|position| Receiver {
        position,
        normal: Some(DVec3::Y),
        object: Some(0),
    })
    .to_vec();
    let frame = Frame::from_receivers(receivers);
    let stages = Stages::new(&scene);
    let exact = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    assert_eq!(exact, vec![0.0; 3]);
    for pcss in [
        Pcss::default(),
        Pcss::default().with_bias(PcssBias::Constant),
    ] {
        let v = method::run(&pcss, &stages, &frame)
            .unwrap()
            .output
            .visibility;
        assert_eq!(v, exact, "{pcss:?}");
    }
    // The other shadow-map methods share the capped margin.
    for name in ["single-sample", "ssoc", "backprojected-ssoc"] {
        let m = method::parse(name).unwrap();
        let v = method::run(m.as_ref(), &stages, &frame)
            .unwrap()
            .output
            .visibility;
        assert_eq!(v, exact, "{name}");
    }
}

/// The largest image the options allow, 16384², needs about 30 GiB: it is
/// refused before any allocation, with the estimate, when it exceeds the
/// memory limit (here 4 GiB); a small render under the same limit runs.
#[test]
fn a_render_beyond_the_memory_limit_is_refused_with_its_estimate() {
    let d = dir("memory");
    let out = d.to_str().unwrap();
    let args = [
        "render", "--scene", "default", "--method", "hard", "--out", out,
    ];
    let big = [
        &args[..],
        &["--width", "16384", "--height", "16384", "--max-memory", "4"],
    ]
    .concat();
    refused(&softshadow(&big), 400, &["30.2 GiB", "--max-memory"]);
    let small = [
        &args[..],
        &["--width", "32", "--height", "24", "--max-memory", "4"],
    ]
    .concat();
    assert!(softshadow(&small).status.success());
    refused(
        &softshadow(&[&args[..], &["--max-memory=0"]].concat()),
        400,
        &["--max-memory"],
    );
}

/// A full disk, simulated by a file-size limit of 2 KiB (two of the pictures of a
/// 200 × 150 render are larger): the program stops, and no picture is
/// left under its final name unless whole.
#[test]
fn a_full_disk_leaves_no_partial_picture() {
    let d = dir("full");
    let script = format!(
        "ulimit -f 4 && exec '{}' render --scene default --method hard --width 200 --height 150 --out '{}'",
        env!("CARGO_BIN_EXE_softshadow"),
        d.display()
    );
    let out = Command::new("sh").arg("-c").arg(&script).output().unwrap();
    assert!(!out.status.success(), "the limit did not bite");
    // The process killed mid-write may leave its hidden temporary.
    pictures_whole(&d, true);
}
