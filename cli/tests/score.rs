//! `gbuffer`, `score`, `render --format` and `visibility` with `.npy`
//! files, end to end: the round trip from `render` to `score` for every
//! method of the default set, the file formats agreeing with one another,
//! and bad or hostile input refused with one line, status 2, nothing
//! written and memory bounded by the file's size.
#![cfg(unix)]

use softshadow::float_io::{
    exr_bytes, npy_bytes_f32, npy_bytes_f64, npy_bytes_i32, pfm_bytes, read_exr, read_npy_f64,
    read_npy_i64,
};
use softshadow::method;
use softshadow::scene::LightKind;
use std::path::{Path, PathBuf};

#[path = "support/cli.rs"]
mod cli_support;

use cli_support::{bin, refused, softshadow};

fn dir(name: &str) -> PathBuf {
    cli_support::dir("score", name)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn json(out: &std::process::Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stdout)))
}

/// Every number in `a` equals the one at the same place in `b` to `tol`
/// (`skip`: top-level keys only in one).
fn same_numbers(a: &serde_json::Value, b: &serde_json::Value, tol: f64, at: &str) {
    use serde_json::Value;
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for (k, v) in x {
                if ["method", "seconds"].contains(&k.as_str()) {
                    continue;
                }
                let w = y.get(k).unwrap_or_else(|| panic!("{at}.{k} missing"));
                same_numbers(v, w, tol, &format!("{at}.{k}"));
            }
        }
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!((x - y).abs() <= tol, "{at}: {x} vs {y}");
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

#[test]
fn render_npy_then_score_reproduces_render_s_table_for_every_default_method() {
    let d = dir("round-trip");
    let names: Vec<String> = method::default_set(LightKind::Sphere)
        .iter()
        .map(|m| m.name())
        .collect();
    assert!(names.len() >= 5, "{names:?}");
    for name in &names {
        let rendered = json(&softshadow(&[
            "render",
            "--scene",
            "default",
            "--method",
            name,
            "--width",
            "48",
            "--height",
            "36",
            "--format",
            "npy",
            "--json",
            "--out",
            s(&d),
        ]));
        assert_eq!(rendered["method"], name.as_str());
        let file: String = name
            .chars()
            .filter(|c| c.is_ascii_alphanumeric() || *c == '-')
            .collect();
        let image = d.join(format!("default-{file}-visibility.npy"));
        let scored = json(&softshadow(&[
            "score",
            "--scene",
            "default",
            "--image",
            s(&image),
            "--json",
        ]));
        same_numbers(&rendered, &scored, 1e-12, name);
        same_numbers(&scored, &rendered, 1e-12, name);
        // The error array render wrote is V − V_exact: its RMSE is the
        // table's, computed here from the file alone.
        let e = read_npy_f64(&std::fs::read(d.join(format!("default-{file}-error.npy"))).unwrap())
            .unwrap();
        let finite: Vec<f64> = e.data.iter().copied().filter(|x| x.is_finite()).collect();
        let rmse = (finite.iter().map(|x| x * x).sum::<f64>() / finite.len() as f64).sqrt();
        let table = scored["rmse"].as_f64().unwrap();
        assert!((rmse - table).abs() <= 1e-12, "{name}: {rmse} vs {table}");
        assert_eq!(finite.len() as u64, scored["pixels"].as_u64().unwrap());
    }
}

#[test]
fn exr_pfm_and_float32_npy_images_score_as_the_float64_one_does() {
    let d = dir("formats");
    let out = softshadow(&[
        "render",
        "--scene",
        "default",
        "--method",
        "pcss",
        "--width",
        "40",
        "--height",
        "30",
        "--format",
        "npy,exr",
        "--out",
        s(&d),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v = read_npy_f64(&std::fs::read(d.join("default-pcss-visibility.npy")).unwrap()).unwrap();
    let v32: Vec<f32> = v.data.iter().map(|&x| x as f32).collect();
    std::fs::write(d.join("v32.npy"), npy_bytes_f32(&[30, 40], &v32).unwrap()).unwrap();
    std::fs::write(d.join("v.pfm"), pfm_bytes(40, 30, &v32)).unwrap();
    // The exr render wrote: channels V, error, shaded; V is picked.
    let exr = read_exr(&std::fs::read(d.join("default-pcss.exr")).unwrap()).unwrap();
    let names: Vec<&str> = exr.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["V", "error", "shaded"]);
    let score = |f: &str| {
        json(&softshadow(&[
            "score", "--scene", "default", "--image", f, "--json",
        ]))
    };
    let want = score(s(&d.join("v32.npy")));
    for f in ["default-pcss.exr", "v.pfm"] {
        same_numbers(&score(s(&d.join(f))), &want, 0.0, f);
    }
    let full = score(s(&d.join("default-pcss-visibility.npy")));
    let (a, b) = (
        full["rmse"].as_f64().unwrap(),
        want["rmse"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-7 && a > 0.01, "{a} {b}");
}

#[test]
fn gbuffer_exr_holds_the_npy_arrays_as_float32() {
    let d = dir("gbuffer-exr");
    let out = softshadow(&[
        "gbuffer",
        "--scene",
        "comb",
        "--width",
        "30",
        "--height",
        "20",
        "--out",
        s(&d),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |n: &str| read_npy_f64(&std::fs::read(d.join(n)).unwrap()).unwrap();
    let (pos, exact) = (read("position.npy"), read("exact.npy"));
    let obj = read_npy_i64(&std::fs::read(d.join("object.npy")).unwrap()).unwrap();
    let exr = read_exr(&std::fs::read(d.join("gbuffer.exr")).unwrap()).unwrap();
    let ch = |n: &str| &exr.channels.iter().find(|c| c.name == n).unwrap().data;
    let same = |a: f64, b: f64| (a.is_nan() && b.is_nan()) || (a as f32) as f64 == b;
    for k in 0..600 {
        assert!(same(pos.data[3 * k + 1], ch("P.Y")[k]), "{k}");
        assert!(same(exact.data[k], ch("V")[k]), "{k}");
        assert_eq!(obj.data[k] as f64, ch("object")[k]);
    }
    assert!(obj.data.contains(&-1) && obj.data.contains(&0));
}

/// Writes `bytes` to `dir/name`, returning the path.
fn put(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p.to_string_lossy().into_owned()
}

/// A G-buffer of the default scene at 24×18 in `dir/gb`.
fn gbuffer(d: &Path) -> PathBuf {
    let gb = d.join("gb");
    let out = softshadow(&[
        "gbuffer",
        "--scene",
        "default",
        "--width",
        "24",
        "--height",
        "18",
        "--out",
        s(&gb),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    gb
}

/// `score` with `image` (and `--gbuffer gb` when given) and an `--out`
/// directory that must not be created.
fn score_refused(d: &Path, image: &str, gb: Option<&Path>, needles: &[&str]) {
    let out_dir = d.join("must-not-exist");
    let mut args = vec![
        "score",
        "--scene",
        "default",
        "--image",
        image,
        "--out",
        s(&out_dir),
    ];
    if let Some(g) = gb {
        args.extend(["--gbuffer", s(g)]);
    }
    refused(&softshadow(&args), 400, needles);
    assert!(!out_dir.exists(), "{image}: --out written on bad input");
}

#[test]
fn bad_images_and_gbuffers_are_refused_with_one_line_and_nothing_written() {
    let d = dir("bad");
    let gb = gbuffer(&d);
    let exact = read_npy_f64(&std::fs::read(gb.join("exact.npy")).unwrap()).unwrap();
    let good = put(
        &d,
        "good.npy",
        &npy_bytes_f64(&[18, 24], &exact.data).unwrap(),
    );
    // The good one passes, so each refusal below is the case's own.
    assert!(softshadow(&[
        "score",
        "--scene",
        "default",
        "--image",
        &good,
        "--gbuffer",
        s(&gb)
    ])
    .status
    .success());
    let small = put(
        &d,
        "small.npy",
        &npy_bytes_f64(&[17, 24], &exact.data[..17 * 24]).unwrap(),
    );
    score_refused(&d, &small, Some(&gb), &["position.npy", "[17, 24, 3]"]);
    let ints = put(
        &d,
        "ints.npy",
        &npy_bytes_i32(&[18, 24], &[0; 18 * 24]).unwrap(),
    );
    score_refused(&d, &ints, None, &["ints.npy", "<i4"]);
    let rank = put(
        &d,
        "rank.npy",
        &npy_bytes_f64(&[18, 24, 2], &[0.5; 18 * 24 * 2]).unwrap(),
    );
    score_refused(&d, &rank, None, &["rank.npy", "H×W"]);
    let bytes = std::fs::read(&good).unwrap();
    let cut = put(&d, "cut.npy", &bytes[..bytes.len() - 5]);
    score_refused(&d, &cut, None, &["cut.npy", "truncated"]);
    let two = put(
        &d,
        "two.exr",
        &exr_bytes(24, 18, &[("R", vec![0.5; 432]), ("G", vec![0.5; 432])]).unwrap(),
    );
    score_refused(&d, &two, None, &["two.exr", "no channel named V"]);
    score_refused(&d, s(&d), None, &["not a regular file"]);
    score_refused(&d, "/nonexistent/v.npy", None, &["/nonexistent/v.npy"]);
    // A G-buffer whose position is NaN where its object id says surface.
    let bad_gb = d.join("bad-gb");
    std::fs::create_dir_all(&bad_gb).unwrap();
    for f in ["normal.npy", "object.npy"] {
        std::fs::copy(gb.join(f), bad_gb.join(f)).unwrap();
    }
    let obj = read_npy_i64(&std::fs::read(gb.join("object.npy")).unwrap()).unwrap();
    let mut pos = read_npy_f64(&std::fs::read(gb.join("position.npy")).unwrap()).unwrap();
    let k = obj.data.iter().position(|&o| o >= 0).unwrap();
    pos.data[3 * k + 2] = f64::NAN;
    put(
        &bad_gb,
        "position.npy",
        &npy_bytes_f64(&pos.shape, &pos.data).unwrap(),
    );
    let pixel = format!("(row {}, column {})", k / 24, k % 24);
    score_refused(
        &d,
        &good,
        Some(&bad_gb),
        &["position.npy", &pixel, "not finite"],
    );
    // An object id of no mesh.
    let mut ids: Vec<i32> = obj.data.iter().map(|&o| o as i32).collect();
    ids[k] = 9;
    put(
        &bad_gb,
        "object.npy",
        &npy_bytes_i32(&[18, 24], &ids).unwrap(),
    );
    score_refused(&d, &good, Some(&bad_gb), &["object.npy", "object id 9"]);
    // A missing array.
    std::fs::remove_file(bad_gb.join("normal.npy")).unwrap();
    score_refused(&d, &good, Some(&bad_gb), &["normal.npy"]);
}

/// Runs the binary under a 1 GiB address-space limit: an allocation of
/// what a hostile header declares (several GiB) aborts it.
fn bounded(args: &[&str]) -> std::process::Output {
    let mut line = String::from("ulimit -v 1048576; exec \"$0\"");
    for k in 1..=args.len() {
        line.push_str(&format!(" \"${k}\""));
    }
    std::process::Command::new("sh")
        .arg("-c")
        .arg(line)
        .arg(bin().get_program())
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn hostile_headers_are_refused_within_the_file_s_size() {
    let d = dir("hostile");
    // Control: the limit lets an honest run through.
    let ok = put(&d, "ok.npy", &npy_bytes_f64(&[6, 8], &[0.5; 48]).unwrap());
    let out = bounded(&["score", "--scene", "default", "--image", &ok, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // 16000 × 16000 float64 (2 GB) declared in a file of 200 bytes.
    let mut npy = npy_bytes_f64(&[1], &[0.5]).unwrap();
    let text = String::from_utf8_lossy(&npy[10..]).into_owned();
    let at = text.find("(1,)").unwrap() + 10;
    let header_end = npy.len() - 8;
    let mut header = npy[..at].to_vec();
    header.extend(b"(16000, 16000)");
    header.extend(&npy[at + 4..header_end]);
    // Keep the header's declared length: trim the padding by the growth.
    let grow = header.len() - header_end;
    let newline = header.len() - 1;
    header.drain(newline - grow..newline);
    npy = header;
    npy.extend([0u8; 8]);
    let hostile = put(&d, "hostile.npy", &npy);
    let out = bounded(&["score", "--scene", "default", "--image", &hostile]);
    refused(&out, 300, &["hostile.npy", "16000"]);
    // An .exr declaring 16000 × 16000 pixels in a few hundred bytes.
    let mut exr = exr_bytes(4, 4, &[("V", vec![0.5; 16])]).unwrap();
    let key = b"dataWindow\0box2i\0";
    let at = exr.windows(key.len()).position(|w| w == key).unwrap() + key.len() + 4;
    exr[at + 8..at + 12].copy_from_slice(&15_999i32.to_le_bytes());
    exr[at + 12..at + 16].copy_from_slice(&15_999i32.to_le_bytes());
    let hostile = put(&d, "hostile.exr", &exr);
    let out = bounded(&["score", "--scene", "default", "--image", &hostile]);
    refused(&out, 300, &["hostile.exr", "hostile"]);
    // A PFM the same.
    let hostile = put(&d, "hostile.pfm", b"Pf\n16000 16000\n-1.0\n\0\0\0\0");
    let out = bounded(&["score", "--scene", "default", "--image", &hostile]);
    refused(&out, 300, &["hostile.pfm", "the file has 4"]);
}

#[test]
fn visibility_reads_npy_points_and_writes_npy_values() {
    let d = dir("visibility");
    let pts = [
        [0.3, 0.001, 0.2, 0.0, 1.0, 0.0],
        [-1.1, 0.001, 0.7, 0.0, 2.0, 0.0],
        [0.05, 0.001, -0.4, 0.0, 1.0, 0.0],
    ];
    let flat: Vec<f64> = pts.iter().flatten().copied().collect();
    let npy = put(&d, "p.npy", &npy_bytes_f64(&[3, 6], &flat).unwrap());
    let ids = put(&d, "o.npy", &npy_bytes_i32(&[3], &[0, 0, 0]).unwrap());
    let points_json = serde_json::json!({"points": pts.iter().map(|p| serde_json::json!({
        "p": [p[0], p[1], p[2]], "normal": [p[3], p[4], p[5]], "object": 0})).collect::<Vec<_>>()});
    let jpath = put(&d, "p.json", points_json.to_string().as_bytes());
    for m in ["exact", "single-sample"] {
        let from_json = json(&softshadow(&[
            "visibility",
            "--scene",
            "default",
            "--points",
            &jpath,
            "--method",
            m,
        ]));
        let from_npy = json(&softshadow(&[
            "visibility",
            "--scene",
            "default",
            "--points",
            &npy,
            "--objects",
            &ids,
            "--method",
            m,
        ]));
        assert_eq!(from_json["visibility"], from_npy["visibility"], "{m}");
    }
    let out_file = d.join("v.npy");
    let out = softshadow(&[
        "visibility",
        "--scene",
        "default",
        "--points",
        &npy,
        "--method",
        "mc:64",
        "--out",
        s(&out_file),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v = read_npy_f64(&std::fs::read(&out_file).unwrap()).unwrap();
    let se = read_npy_f64(&std::fs::read(d.join("v.stderr.npy")).unwrap()).unwrap();
    assert_eq!((v.shape.clone(), se.shape.clone()), (vec![3], vec![3]));
    assert!(v.data.iter().all(|x| (0.0..=1.0).contains(x)));
    // N×4 is no layout; an id of no mesh; --objects with JSON points.
    let bad = put(&d, "bad.npy", &npy_bytes_f64(&[2, 4], &[0.0; 8]).unwrap());
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            "default",
            "--points",
            &bad,
            "--method",
            "exact",
        ]),
        300,
        &["bad.npy", "N×3"],
    );
    let ids9 = put(&d, "o9.npy", &npy_bytes_i32(&[3], &[0, 9, 0]).unwrap());
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            "default",
            "--points",
            &npy,
            "--objects",
            &ids9,
            "--method",
            "exact",
        ]),
        300,
        &["o9.npy", "row 1", "object id 9"],
    );
    refused(
        &softshadow(&[
            "visibility",
            "--scene",
            "default",
            "--points",
            &jpath,
            "--objects",
            &ids,
            "--method",
            "exact",
        ]),
        300,
        &["--objects"],
    );
}
