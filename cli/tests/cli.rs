//! The command-line program: the default run prints the table of every
//! method against the exact answer, `check` (kernel self-check and the
//! references on the default scene) passes, `render` writes its three PNG
//! files, `visibility` prints its documented JSON with answers that agree
//! with the library for every method, and every kind of bad input ends with
//! one line naming the file, the place and the field, exit status 2, nothing
//! on stdout and no panic.

use std::path::PathBuf;

#[path = "support/cli.rs"]
mod cli_support;

use cli_support::{refused, softshadow, visibility, write};

fn dir(name: &str) -> PathBuf {
    cli_support::dir("cli", name)
}

/// Runs `visibility`, expects bad input: exit 2, one line on stderr that
/// contains every one of `needles`, nothing on stdout.
fn rejects(args: &[&str], needles: &[&str]) {
    cli_support::refused(&softshadow(args), 1000, needles);
}

const POINTS: &str =
    r#"{"points": [{"p": [0.2, 0.0, 0.1]}, {"p": [-0.3, 0.0, -0.4], "object": 0}]}"#;

fn scene_with_light(light: &str) -> String {
    format!(
        r#"{{"light": {light}, "meshes": [{{"name": "card", "positions": [[-1,1,-1],[1,1,-1],[0,1,1]], "triangles": [[0,1,2]]}}]}}"#
    )
}

#[test]
fn default_run_prints_every_method_against_exact() {
    let out = softshadow(&[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "exit {:?}\n{stdout}", out.status);
    let rows: Vec<Vec<&str>> = stdout
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| method"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    let names: Vec<&str> = rows.iter().map(|r| r[1]).collect();
    for m in softshadow::method::default_set(softshadow::scene::LightKind::Sphere) {
        assert!(
            names.contains(&m.name().as_str()),
            "{} missing:\n{stdout}",
            m.name()
        );
    }
    for r in &rows {
        // Time, mean abs, RMSE, max: finite numbers, errors within [0, 1].
        let numbers: Vec<f64> = r[2..6].iter().map(|x| x.parse().unwrap()).collect();
        assert!(numbers.iter().all(|x| x.is_finite() && *x >= 0.0), "{r:?}");
        assert!(numbers[1..].iter().all(|x| *x <= 1.0), "{r:?}");
        if r[1] == "exact" {
            assert!(numbers[1..].iter().all(|x| *x == 0.0), "{r:?}");
        }
    }
}

#[test]
fn render_writes_the_three_pictures_and_the_errors() {
    let d = dir("render");
    let out = softshadow(&[
        "render",
        "--scene",
        "contact",
        "--method",
        "pcss",
        "--out",
        d.to_str().unwrap(),
        "--width",
        "40",
        "--height",
        "30",
        "--stats",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("| pcss |") && stdout.contains("light maps"),
        "{stdout}"
    );
    for kind in ["visibility", "shaded", "error"] {
        let file = std::fs::File::open(d.join(format!("contact-pcss-{kind}.png"))).unwrap();
        let reader = png::Decoder::new(std::io::BufReader::new(file))
            .read_info()
            .unwrap();
        let info = reader.info();
        // The heat-map has its legend below and is at least 64 wide.
        let (w, h) = if kind == "error" {
            (64, 30 + 18)
        } else {
            (40, 30)
        };
        assert_eq!((info.width, info.height), (w, h), "{kind}");
    }
}

#[test]
fn render_rejects_bad_arguments_in_one_line() {
    let d = dir("render-bad");
    let nocam = write(
        &d,
        "nocam.json",
        &scene_with_light(r#"{"type": "sphere", "center": [0, 3, 0], "radius": 0.5}"#),
    );
    rejects(
        &["render", "--scene", &nocam, "--method", "hard"],
        &["nocam.json", "camera"],
    );
    rejects(
        &[
            "render", "--scene", "default", "--method", "hard", "--width", "0",
        ],
        &["--width"],
    );
    rejects(
        &["render", "--scene", "default", "--method", "nope"],
        &["nope"],
    );
}

#[test]
fn check_passes_its_self_check() {
    let out = softshadow(&["check"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "exit {:?}\n{stdout}", out.status);
    assert!(stdout.contains(" 0 over budget"), "{stdout}");
    assert!(stdout.contains("; 0 disagree"), "{stdout}");
    assert!(!stdout.contains("NaN"), "{stdout}");
}

#[test]
fn visibility_prints_the_json_of_the_design() {
    let d = dir("json");
    let points = write(
        &d,
        "points.json",
        r#"{"points": [{"p": [0.2, 0.0, 0.1], "normal": [0, 1, 0]}, {"p": [-0.3, 0.0, -0.4], "object": 0, "normal": [0, 1, 0]}]}"#,
    );
    for method in [
        "exact",
        "mc:256",
        "hard",
        "pcss",
        "sism",
        "sism:exact-union",
    ] {
        let out = softshadow(&[
            "visibility",
            "--scene",
            "default",
            "--points",
            &points,
            "--method",
            method,
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(json["method"], method);
        let v = json["visibility"].as_array().unwrap();
        assert_eq!(v.len(), 2);
        assert!(v.iter().all(|x| (0.0..=1.0).contains(&x.as_f64().unwrap())));
        assert!(json["seconds"].as_f64().unwrap() >= 0.0);
        assert_eq!(
            json.get("stderr").is_some(),
            method.starts_with("mc:"),
            "{json}"
        );
        assert_eq!(json.get("bound").is_some(), method == "exact", "{json}");
    }
}

/// The library's side of `scene_with_light` with the sphere light of
/// radius 0.5 at `(0, 3, 0)`: the light and the BVH over the card.
fn card_under_sphere() -> (softshadow::scene::Light, softshadow::bvh::Bvh) {
    use softshadow::bvh::{Bvh, Occluders};
    use softshadow::glam::DVec3;
    use softshadow::scene::{Light, Mesh, Scene};
    let mesh = Mesh::new(
        vec![
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(1.0, 1.0, -1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let light = Light::sphere(DVec3::new(0.0, 3.0, 0.0), 0.5).unwrap();
    let scene = Scene::new(light).with_mesh("card", mesh);
    (light, Bvh::new(Occluders::from_scene(&scene)))
}

#[test]
fn visibility_answers_match_the_library() {
    // A card at height 1 between a sphere light and two receivers: the
    // CLI's exact answer, through the scene file, the points file and the
    // JSON printer, is the library's, bit for bit.
    let d = dir("match");
    let scene = write(
        &d,
        "scene.json",
        &scene_with_light(r#"{"type": "sphere", "center": [0, 3, 0], "radius": 0.5}"#),
    );
    let points = write(
        &d,
        "points.json",
        r#"{"points": [{"p": [0, 0, 0]}, {"p": [0.1, 0, -0.2]}]}"#,
    );
    let out = softshadow(&[
        "visibility",
        "--scene",
        &scene,
        "--points",
        &points,
        "--method",
        "exact",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let got: Vec<f64> = json["visibility"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();

    use softshadow::glam::DVec3;
    use softshadow::reference::exact;
    let (light, bvh) = card_under_sphere();
    // The bounds as printed, read with Rust's correctly rounded parser
    // (serde_json's default reader may be an ulp off).
    let text = String::from_utf8_lossy(&out.stdout);
    let list = text.split("\"bound\":[").nth(1).unwrap();
    let bounds: Vec<f64> = list[..list.find(']').unwrap()]
        .split(',')
        .map(|x| x.trim().parse().unwrap())
        .collect();
    for (k, p) in [DVec3::ZERO, DVec3::new(0.1, 0.0, -0.2)]
        .into_iter()
        .enumerate()
    {
        assert_eq!(got[k], exact::visibility(&bvh, &light, p).unwrap());
        // The bound printed is the library's, for the same value.
        let b = exact::visibility_bounded(&bvh, &light, p).unwrap();
        assert_eq!((got[k], bounds[k]), (b.visibility, b.bound));
    }
}

/// `exact:tolerance=X` refuses, in one line with exit 2, a receiver whose
/// certified bound exceeds `X` (naming the point), and answers when every
/// bound is within it.
#[test]
fn exact_tolerance_refuses_weak_answers() {
    let d = dir("tolerance");
    let scene = write(
        &d,
        "scene.json",
        &scene_with_light(r#"{"type": "sphere", "center": [0, 3, 0], "radius": 0.5}"#),
    );
    // The first point sees no occluder (its bound a few ulps); the second
    // sees the card's edge cross the light (its bound above 1e-15, far
    // below 1e-6).
    let points = write(
        &d,
        "points.json",
        r#"{"points": [{"p": [5, 0, 5]}, {"p": [0.3, 0, 0.9]}]}"#,
    );
    let run = |method: &str| {
        softshadow(&[
            "visibility",
            "--scene",
            &scene,
            "--points",
            &points,
            "--method",
            method,
        ])
    };
    refused(
        &run("exact:tolerance=1e-15"),
        300,
        &["points.json", "points[1]", "certified bound", "tolerance"],
    );
    let out = run("exact:tolerance=1e-6");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let bound = json["bound"].as_array().unwrap();
    assert!(bound[0].as_f64().unwrap() <= 1e-15, "{json}");
    assert!(bound[1].as_f64().unwrap() > 1e-15, "{json}");
    assert!(bound.iter().all(|b| b.as_f64().unwrap() <= 1e-6), "{json}");
    refused(&run("exact:tolerance=0"), 300, &["tolerance"]);
    refused(&run("exact:tolerance=2"), 300, &["tolerance"]);
}

/// Numbers cross the program exactly both ways: points given as random
/// 17-digit literals are read as the doubles nearest them (Rust's
/// correctly rounded `str::parse`), and the `V` printed reads back, by the
/// same `str::parse`, as the library's value bit for bit (penumbra
/// receivers under the card, where `V` takes every value).
#[test]
fn visibility_numbers_cross_the_json_exactly() {
    use softshadow::glam::DVec3;
    use softshadow::reference::exact;
    let d = dir("exact-numbers");
    let light_json = r#"{"type": "sphere", "center": [0, 3, 0], "radius": 0.5}"#;
    let scene = write(&d, "scene.json", &scene_with_light(light_json));
    // splitmix64: random doubles in [lo, hi), printed with 17 digits.
    let mut state = 17u64;
    let mut digits = |lo: f64, hi: f64| {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        let u = (z ^ (z >> 31)) as f64 / 2f64.powi(64);
        format!("{:.16e}", lo + (hi - lo) * u)
    };
    let literals: Vec<[String; 3]> = (0..200)
        .map(|_| [digits(-1.6, 1.6), digits(-0.3, 0.3), digits(-1.6, 1.6)])
        .collect();
    let list: Vec<String> = literals
        .iter()
        .map(|[x, y, z]| format!(r#"{{"p": [{x}, {y}, {z}]}}"#))
        .collect();
    let points = write(
        &d,
        "points.json",
        &format!(r#"{{"points": [{}]}}"#, list.join(", ")),
    );
    let out = visibility(&scene, &points, "exact", &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (_, rest) = stdout
        .split_once(r#""visibility":["#)
        .expect("a visibility list");
    let (list, _) = rest.split_once(']').unwrap();
    let got: Vec<f64> = list.split(',').map(|x| x.parse().unwrap()).collect();

    let (light, bvh) = card_under_sphere();
    assert_eq!(got.len(), literals.len());
    let mut penumbra = 0;
    for (k, [x, y, z]) in literals.iter().enumerate() {
        let p = DVec3::new(x.parse().unwrap(), y.parse().unwrap(), z.parse().unwrap());
        let want = exact::visibility(&bvh, &light, p).unwrap();
        assert_eq!(got[k].to_bits(), want.to_bits(), "points[{k}] = {p}");
        penumbra += usize::from(want > 0.0 && want < 1.0);
    }
    assert!(penumbra >= 40, "only {penumbra} receivers in the penumbra");
}

#[test]
fn bad_scene_files_are_one_line_errors() {
    let d = dir("scenes");
    let points = write(&d, "points.json", POINTS);
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "malformed.json",
            r#"{"light": {"type": "point""#,
            &["malformed.json:1:"],
        ),
        ("empty.json", "", &["empty.json", "empty"]),
        (
            "huge.json",
            &scene_with_light(r#"{"type": "point", "position": [0, 1e999, 0]}"#),
            &["huge.json:1:"],
        ),
        (
            "negative.json",
            &scene_with_light(r#"{"type": "sphere", "center": [0, 3, 0], "radius": -1}"#),
            &["negative.json", "light.radius", "-1"],
        ),
        (
            "zero.json",
            &scene_with_light(
                r#"{"type": "disk", "center": [0, 3, 0], "normal": [0, -1, 0], "radius": 0}"#,
            ),
            &["zero.json", "light.radius"],
        ),
        (
            "unknown.json",
            &scene_with_light(r#"{"type": "spot", "position": [0, 3, 0]}"#),
            &["unknown.json", "light.type", "spot"],
        ),
        (
            "degenerate.json",
            &scene_with_light(r#"{"type": "segment", "a": [0, 3, 0], "b": [0, 3, 0]}"#),
            &["degenerate.json", "light"],
        ),
        (
            "arity.json",
            &scene_with_light(r#"{"type": "point", "position": [0, 3]}"#),
            &["arity.json", "light.position"],
        ),
        (
            "index.json",
            r#"{"light": {"type": "point", "position": [0, 3, 0]}, "meshes": [{"positions": [[0,0,0],[1,0,0],[0,0,1]], "triangles": [[0,1,3]]}]}"#,
            &["index.json", "meshes[0].triangles[0][2]", "3"],
        ),
    ];
    for (name, text, needles) in cases {
        let scene = write(&d, name, text);
        rejects(
            &[
                "visibility",
                "--scene",
                &scene,
                "--points",
                &points,
                "--method",
                "exact",
            ],
            needles,
        );
    }
}

#[test]
fn bad_points_and_arguments_are_one_line_errors() {
    let d = dir("points");
    let inside = write(
        &d,
        "inside.json",
        r#"{"points": [{"p": [0, 0, 0]}, {"p": [1.5, 3.5, 2.1]}]}"#,
    );
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &inside,
            "--method",
            "exact",
        ],
        &["inside.json", "points[1].p", "inside the sphere light"],
    );
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &inside,
            "--method",
            "mc:64",
        ],
        &["inside.json", "points[1].p", "inside the sphere light"],
    );
    let missing = d.join("missing.json");
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            missing.to_str().unwrap(),
            "--method",
            "exact",
        ],
        &["missing.json"],
    );
    let object = write(
        &d,
        "object.json",
        r#"{"points": [{"p": [0, 0, 0], "object": 7}]}"#,
    );
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &object,
            "--method",
            "exact",
        ],
        &["object.json", "points[0].object", "7"],
    );
    let nan = write(&d, "nan.json", r#"{"points": [{"p": [0, "NaN", 0]}]}"#);
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &nan,
            "--method",
            "exact",
        ],
        &["nan.json", "points[0].p[1]"],
    );
    let empty = write(&d, "empty.json", "");
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &empty,
            "--method",
            "exact",
        ],
        &["empty.json"],
    );
    let ok = write(&d, "ok.json", POINTS);
    rejects(
        &[
            "visibility",
            "--scene",
            "nowhere",
            "--points",
            &ok,
            "--method",
            "exact",
        ],
        &["nowhere", "default"],
    );
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &ok,
            "--method",
            "mc:1",
        ],
        &["mc:1"],
    );
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &ok,
            "--method",
            "oess",
        ],
        &["oess", "does not handle a sphere light"],
    );
    // The points file gives no normals, which PCSS's default bias needs.
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &ok,
            "--method",
            "pcss",
        ],
        &["ok.json", "points[0].normal", "pcss"],
    );
    rejects(
        &[
            "visibility",
            "--scene",
            "default",
            "--points",
            &ok,
            "--method",
            "sism:sideways",
        ],
        &["sism:sideways", "sideways"],
    );
}
