//! Hostile input and a hostile environment, one test per case: an answer
//! that cannot be delivered (stdout closed, full, its reader gone) ends
//! with status 1 after every file is written, a full stderr panics
//! nothing; files are replaced whole (a symlink is
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

use cli_support::{pictures_whole, refused, softshadow, visibility, write};

fn dir(name: &str) -> PathBuf {
    cli_support::dir("hostile", name)
}

const SCENE: &str = r#"{"light": {"type": "sphere", "center": [0, 3, 0], "radius": 0.5},
 "camera": {"eye": [0, 2, 6], "target": [0, 0, 0], "fov_y_deg": 40, "width": 24, "height": 18},
 "meshes": [{"name": "floor", "primitive": {"type": "quad", "center": [0, 0, 0], "u": [4, 0, 0], "v": [0, 0, 4]}},
            {"name": "card", "positions": [[-1,1,-1],[1,1,-1],[0,1,1]], "triangles": [[0,1,2]]}]}"#;

/// Runs `softshadow args` with the reading end of its stdout closed before
/// it starts. A shell waits for its stdin to close, then becomes the
/// program; the test closes the pipe's reading end first, so every write
/// the program makes fails with a broken pipe however the threads are
/// scheduled (closing it just after starting the program raced with a
/// program that wrote first, under load).
fn with_stdout_closed(args: &[&str]) -> Output {
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(r#"read -r _; exec "$0" "$@""#)
        .arg(env!("CARGO_BIN_EXE_softshadow"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    // The end of its stdin lets the shell go on to the program.
    drop(child.stdin.take());
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

/// Runs `softshadow args` under `sh -c` with `redirect` appended (`>&-`,
/// `2>/dev/full`, …).
fn with_redirect(args: &[&str], redirect: &str) -> Output {
    let quoted: Vec<String> = args.iter().map(|a| format!("'{a}'")).collect();
    let script = format!(
        "exec '{}' {} {redirect}",
        env!("CARGO_BIN_EXE_softshadow"),
        quoted.join(" ")
    );
    Command::new("sh").arg("-c").arg(&script).output().unwrap()
}

/// The three pictures of `render --method hard` of `scene.json` in `d`,
/// each present and whole.
fn three_pictures(d: &std::path::Path) {
    pictures_whole(d, false);
    for kind in ["visibility", "shaded", "error"] {
        let p = d.join(format!("scene-hard-{kind}.png"));
        assert!(p.exists(), "{} is missing", p.display());
    }
}

/// An answer that cannot be delivered ends with exit status 1 and one line
/// saying so — a pipe whose reader left, a full device, and for a command
/// whose answer is printed, a stdout closed before the start (`>&-`, which
/// Rust's runtime turns into a read-write `/dev/null`) — and `render`
/// writes all three pictures first; a `>/dev/null` chosen by the user is
/// an answer delivered.
#[test]
fn an_answer_that_cannot_be_delivered_ends_with_status_1() {
    let d = dir("pipe");
    let scene = write(&d, "scene.json", SCENE);
    let points = write(&d, "points.json", r#"{"points": [{"p": [0.2, 0.0, 0.1]}]}"#);
    let visibility = [
        "visibility",
        "--scene",
        &scene,
        "--points",
        &points,
        "--method",
        "hard",
    ];
    let lost = |out: &Output, what: &str| {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{what}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{what}: {stderr}");
        assert!(
            stderr.starts_with("softshadow: stdout: "),
            "{what}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
    };
    lost(&with_stdout_closed(&visibility), "broken pipe");
    lost(&with_redirect(&visibility, ">&-"), ">&-");
    lost(&with_redirect(&visibility, ">/dev/full"), ">/dev/full");
    lost(&with_redirect(&["--help"], ">&-"), "--help >&-");
    let quiet = with_redirect(&visibility, ">/dev/null");
    assert!(quiet.status.success(), "{quiet:?}");
    assert!(quiet.stderr.is_empty(), "{quiet:?}");
    // `render` with its stdout gone still writes every picture.
    for (k, how) in ["pipe", ">/dev/full"].into_iter().enumerate() {
        let out = dir(&format!("pipe-render-{k}"));
        let render = [
            "render",
            "--scene",
            &scene,
            "--method",
            "hard",
            "--out",
            out.to_str().unwrap(),
        ];
        let run = match how {
            "pipe" => with_stdout_closed(&render),
            redirect => with_redirect(&render, redirect),
        };
        lost(&run, how);
        three_pictures(&out);
    }
    // A stdout closed from the start cannot be told from a read-write
    // /dev/null chosen by the parent (Python's subprocess.DEVNULL): a
    // command whose answer is files writes them and succeeds.
    let out = dir("pipe-render-closed");
    let render = [
        "render",
        "--scene",
        &scene,
        "--method",
        "hard",
        "--out",
        out.to_str().unwrap(),
    ];
    for redirect in [">&-", "1<>/dev/null"] {
        let run = with_redirect(&render, redirect);
        assert!(run.status.success(), "{redirect}: {run:?}");
        three_pictures(&out);
    }
    lost(&with_redirect(&visibility, "1<>/dev/null"), "1<>/dev/null");
}

/// A stderr that cannot be written (`2>/dev/full`) is no reason to panic:
/// bad input still ends with exit status 2, a good run with 0.
#[test]
fn a_full_stderr_changes_nothing_but_the_lines_lost() {
    let d = dir("full-stderr");
    let scene = write(&d, "scene.json", SCENE);
    let points = write(&d, "points.json", r#"{"points": [{"p": [0.2, 0.0, 0.1]}]}"#);
    let full_stderr = |scene: &str| {
        let args = [
            "visibility",
            "--scene",
            scene,
            "--points",
            &points,
            "--method",
            "hard",
        ];
        with_redirect(&args, "2>/dev/full")
    };
    let bad = full_stderr("nope.json");
    assert_eq!(bad.status.code(), Some(2), "{bad:?}");
    let args = with_redirect(&["render", "--width", "0"], "2>/dev/full");
    assert_eq!(args.status.code(), Some(2), "{args:?}");
    let good = full_stderr(&scene);
    assert_eq!(good.status.code(), Some(0), "{good:?}");
    assert!(String::from_utf8_lossy(&good.stdout).starts_with("{\"method\""));
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
    // A segment light of length 1e-300, which the loader takes, is
    // answered by every method that handles segments (OESS said "no light
    // frame"): under the card 0, in the open 1, as the point light.
    let segment = r#"{"type": "segment", "a": [0, 3, 0], "b": [1e-300, 3, 0]}"#;
    let light_at = SCENE.find("{\"type\": \"sphere\"").unwrap();
    let light_end = light_at + SCENE[light_at..].find('}').unwrap() + 1;
    let scene = write(
        &d,
        "short.json",
        &format!("{}{segment}{}", &SCENE[..light_at], &SCENE[light_end..]),
    );
    let points = write(
        &d,
        "points.json",
        r#"{"points": [{"p": [0.05, 0.0, 0.1]}, {"p": [3.5, 0.0, 0.0]}]}"#,
    );
    let segment_methods = softshadow::method::REGISTRY
        .iter()
        .filter(|m| m.lights.contains(&softshadow::scene::LightKind::Segment))
        .map(|m| m.name);
    for method in segment_methods {
        let method = if method == "pcss" {
            "pcss:constant"
        } else {
            method
        };
        let out = visibility(&scene, &points, method, &[]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{method}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            stdout.contains(r#""visibility":[0.0,1.0]"#),
            "{method}: {stdout}"
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

/// A method's own maps count toward the memory limit: `oess:map=16384`
/// (two endpoint maps, about 16 GiB) is refused in one line with the
/// maps' share, by `render` and `visibility` alike, before any map is
/// allocated (it aborted with a backtrace); the same method at its default
/// side runs under the same limit.
#[test]
fn a_method_s_maps_count_toward_the_memory_limit() {
    let d = dir("memory-maps");
    let out = d.to_str().unwrap();
    let points = write(
        &d,
        "points.json",
        r#"{"points": [{"p": [0.1, 0.02, 0.3]}]}"#,
    );
    let big = "oess:map=16384";
    let render = |method: &str| {
        softshadow(&[
            "render",
            "--scene",
            "linear-light",
            "--method",
            method,
            "--width",
            "32",
            "--height",
            "24",
            "--out",
            out,
            "--max-memory",
            "8",
        ])
    };
    refused(
        &render(big),
        400,
        &["16.0 GiB of the method's maps", "--max-memory", big],
    );
    let limited =
        |method: &str| visibility("linear-light", &points, method, &["--max-memory", "8"]);
    refused(
        &limited(big),
        400,
        &["points.json (1 point)", "16.0 GiB of the method's maps"],
    );
    // 2 × 1024² × 64 bytes: the maps' estimate grows with the side squared.
    assert!(render("oess").status.success());
    assert!(limited("oess:map=1024").status.success());
    let pcss = visibility(
        "linear-light",
        &points,
        "pcss:map=8192",
        &["--max-memory", "0.4"],
    );
    refused(&pcss, 400, &["1.0 GiB of the method's maps"]);
}

/// A method's message speaks the program's words: the PCSS hint for a
/// receiver without a normal names the option, not a type of the library.
#[test]
fn method_messages_name_options_not_types() {
    let d = dir("pcss-words");
    let points = write(&d, "points.json", r#"{"points": [{"p": [0.1, 0.0, 0.3]}]}"#);
    let out = visibility("default", &points, "pcss", &[]);
    let needles = [
        "points[0].normal",
        "pcss needs receiver normals",
        "pcss:constant",
    ];
    refused(&out, 400, &needles);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("PcssBias"));
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
