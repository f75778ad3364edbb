//! `softshadow report` and `report --merge` on hostile and careless input
//! (issue 39): a part can make the merge read or write only inside its
//! folders; a part is checked whole before anything is written; parts of
//! different sweeps are refused; a scene that cannot be prepared ends
//! the program with an error status; `--out` is replaced as a set;
//! `--accuracy` is checked like every other input and output, before the
//! sweep.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::{Duration, Instant};

#[path = "support/cli.rs"]
mod cli_support;

use cli_support::{bin, refused, softshadow, write};

fn dir(name: &str) -> PathBuf {
    cli_support::dir("report", name)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A small sweep (`contact` at 16², `exact`, `hard` and Monte Carlo to 4,
/// pictures 8² wide) into `out`, with `extra` arguments.
fn small(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "report",
        "--scene",
        "contact",
        "--method",
        "hard",
        "--side",
        "16",
        "--runs",
        "1",
        "--mc-max",
        "4",
        "--pictures",
        "8",
        "--out",
    ];
    args.push(s(out));
    args.extend_from_slice(extra);
    softshadow(&args)
}

fn ok(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn results(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("results.json")).unwrap()).unwrap()
}

fn set_results(dir: &Path, v: &serde_json::Value) {
    std::fs::write(dir.join("results.json"), serde_json::to_vec(v).unwrap()).unwrap();
}

/// Every file under `dir`, relative, with its bytes.
fn tree(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries {
            let path = e.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap_or_default();
                out.push((path.strip_prefix(dir).unwrap().to_path_buf(), bytes));
            }
        }
    }
    out.sort();
    out
}

/// `report --merge PART --out OUT` is refused in one line naming every
/// needle, and nothing is written into `OUT`.
fn merge_refused(part: &Path, out: &Path, needles: &[&str]) {
    refused(
        &softshadow(&["report", "--merge", s(part), "--out", s(out)]),
        600,
        needles,
    );
    assert!(tree(out).is_empty(), "{:?}", tree(out));
}

/// The pictures a part's results name.
fn pictures(v: &serde_json::Value) -> Vec<String> {
    v["cells"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|c| c["picture"].as_str().map(str::to_owned))
        .collect()
}

#[test]
fn a_picture_path_leading_out_of_the_part_is_refused() {
    let d = dir("escape");
    let part = d.join("part");
    ok(&small(&part, &[]));
    let mut v = results(&part);
    // Outside the part, beside it: a file the merge must not read; and
    // outside `--out`, where it must not write.
    let first = pictures(&v)[0].clone();
    std::fs::copy(part.join(&first), d.join("leaked.png")).unwrap();
    for c in v["cells"].as_array_mut().unwrap() {
        if c["picture"].is_string() {
            c["picture"] = "../leaked.png".into();
        }
    }
    set_results(&part, &v);
    let out = d.join("deep").join("out");
    merge_refused(&part, &out, &["picture"]);
    assert!(!d.join("deep").join("leaked.png").exists());
}

#[test]
fn a_picture_linked_out_of_the_part_is_refused() {
    let d = dir("link");
    let part = d.join("part");
    ok(&small(&part, &[]));
    let first = pictures(&results(&part))[0].clone();
    let secret = d.join("secret.png");
    std::fs::copy(part.join(&first), &secret).unwrap();
    std::fs::remove_file(part.join(&first)).unwrap();
    std::os::unix::fs::symlink(&secret, part.join(&first)).unwrap();
    let out = d.join("out");
    merge_refused(&part, &out, &["outside"]);
}

/// A part whose profile is longer than its columns used to panic in the
/// plots with `--out` half-written.
#[test]
fn a_part_is_checked_whole_before_anything_is_written() {
    let d = dir("whole");
    let part = d.join("part");
    ok(&small(&part, &[]));
    let mut v = results(&part);
    v["scenes"][0]["profile_exact"]
        .as_array_mut()
        .unwrap()
        .push(0.5.into());
    set_results(&part, &v);
    let out = d.join("out");
    merge_refused(&part, &out, &["profile"]);
}

/// A part claiming fewer cells than it holds used to print that
/// 18446744073709551615 cells were in other parts (or panic).
#[test]
fn a_miscounted_part_is_refused() {
    let d = dir("miscounted");
    let part = d.join("part");
    ok(&small(&part, &[]));
    let mut v = results(&part);
    v["config"]["cells"] = 1.into();
    set_results(&part, &v);
    merge_refused(&part, &d.join("out"), &["cells"]);
}

/// The parts of a sweep merge into the sweep, and the merge takes its own
/// output.
#[test]
fn shards_merge_and_the_merge_takes_its_own_output() {
    let d = dir("shards");
    let (p1, p2, m, m2) = (d.join("p1"), d.join("p2"), d.join("m"), d.join("m2"));
    ok(&small(&p1, &["--shard", "1/2"]));
    ok(&small(&p2, &["--shard", "2/2"]));
    ok(&softshadow(&[
        "report",
        "--merge",
        s(&p1),
        s(&p2),
        "--out",
        s(&m),
    ]));
    ok(&softshadow(&["report", "--merge", s(&m), "--out", s(&m2)]));
    assert_eq!(results(&m), results(&m2));
    let whole = d.join("whole");
    ok(&small(&whole, &[]));
    let v = results(&m);
    assert_eq!(
        v["cells"].as_array().unwrap().len(),
        results(&whole)["cells"].as_array().unwrap().len()
    );
    // Every picture the merged results name is there, and nothing else.
    let mut named = pictures(&v);
    named.sort();
    let mut present: Vec<String> = tree(&m)
        .into_iter()
        .map(|(p, _)| p.to_str().unwrap().to_owned())
        .filter(|p| p.ends_with(".png"))
        .collect();
    present.sort();
    assert_eq!(named, present);
}

const INSIDE: &str = r#"{"light": {"type": "sphere", "center": [0, 0.2, 0], "radius": 0.5},
 "camera": {"eye": [0, 2, 6], "target": [0, 0, 0], "fov_y_deg": 40, "width": 24, "height": 18},
 "meshes": [{"name": "floor", "primitive": {"type": "quad", "center": [0, 0, 0], "u": [4, 0, 0], "v": [0, 0, 4]}}]}"#;

/// A scene whose receivers are inside the light used to be reported as
/// success, the index silent.
#[test]
fn a_scene_that_cannot_be_prepared_fails_the_run() {
    let d = dir("unprepared");
    let scene = write(&d, "inside.json", INSIDE);
    let out = d.join("out");
    let run = softshadow(&[
        "report",
        "--scene",
        "contact",
        "--scene",
        &scene,
        "--method",
        "hard",
        "--side",
        "16",
        "--runs",
        "1",
        "--mc-max",
        "4",
        "--pictures",
        "0",
        "--out",
        s(&out),
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_ne!(run.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("inside.json"), "{stderr}");
    let index = std::fs::read_to_string(out.join("index.md")).unwrap();
    assert!(index.contains("could not be prepared"), "{index}");
    assert!(index.contains("inside the sphere light"), "{index}");
}

/// A scene without a camera is refused before any work.
#[test]
fn a_scene_without_a_camera_is_refused_before_any_work() {
    let d = dir("nocamera");
    let scene = write(
        &d,
        "nocam.json",
        r#"{"light": {"type": "point", "position": [0, 3, 0]}, "meshes": []}"#,
    );
    let out = d.join("out");
    refused(
        &softshadow(&[
            "report",
            "--scene",
            &scene,
            "--side",
            "16",
            "--out",
            s(&out),
        ]),
        600,
        &["nocam.json", "camera"],
    );
    assert!(!out.join("results.json").exists());
}

/// A second report into the same `--out` used to keep the first one's
/// pictures beside its own.
#[test]
fn a_report_replaces_the_previous_one_whole() {
    let d = dir("replace");
    let out = d.join("out");
    ok(&small(&out, &[]));
    let run = softshadow(&[
        "report",
        "--scene",
        "comb",
        "--method",
        "hard",
        "--side",
        "16",
        "--runs",
        "1",
        "--mc-max",
        "4",
        "--pictures",
        "8",
        "--out",
        s(&out),
    ]);
    ok(&run);
    let v = results(&out);
    let mut named = pictures(&v);
    named.sort();
    let mut present: Vec<String> = tree(&out)
        .into_iter()
        .map(|(p, _)| p.to_str().unwrap().to_owned())
        .filter(|p| p.ends_with(".png") || p.ends_with(".svg"))
        .collect();
    present.sort();
    assert!(
        present.iter().all(|p| !p.contains("contact")),
        "{present:?}"
    );
    assert!(named.iter().all(|p| present.contains(p)), "{named:?}");
    // Nothing is left beside `--out`.
    let beside: Vec<String> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(beside, ["out"]);
}

/// A folder holding anything but a report is not replaced.
#[test]
fn an_out_holding_other_files_is_refused() {
    let d = dir("foreign");
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    write(&out, "notes.txt", "mine");
    refused(&small(&out, &[]), 600, &["--out", "notes.txt"]);
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
}

/// A report stopped half-way used to leave its pictures beside the
/// previous report's: `--out` is now the previous report until the new
/// one is whole.
#[test]
fn an_interrupted_report_leaves_the_previous_one_untouched() {
    let d = dir("interrupted");
    let out = d.join("out");
    ok(&small(&out, &[]));
    let before = tree(&out);
    let seen: std::collections::HashSet<PathBuf> = tree(&d).into_iter().map(|(p, _)| p).collect();
    let mut child = bin()
        .args([
            "report",
            "--scene",
            "default",
            "--scene",
            "comb",
            "--side",
            "96",
            "--runs",
            "1",
            "--mc-max",
            "64",
            "--pictures",
            "48",
            "--out",
            s(&out),
        ])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Stop it as soon as it has written a picture anywhere.
    let start = Instant::now();
    let stopped = loop {
        if tree(&d)
            .into_iter()
            .any(|(p, _)| p.extension().is_some_and(|e| e == "png") && !seen.contains(&p))
        {
            child.kill().unwrap();
            break true;
        }
        if child.try_wait().unwrap().is_some() || start.elapsed() > Duration::from_secs(300) {
            let _ = child.kill();
            break false;
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let _ = child.wait();
    assert!(stopped, "the report ended before it could be stopped");
    let after = tree(&out);
    let listing = |t: &[(PathBuf, Vec<u8>)]| t.iter().map(|(p, _)| p.clone()).collect::<Vec<_>>();
    assert_eq!(listing(&after), listing(&before));
    assert!(after == before, "a file of the earlier report changed");
}

/// A FIFO where an accuracy page goes used to hang the report for ever,
/// after the sweep.
#[test]
fn an_accuracy_page_that_is_a_fifo_is_refused_before_the_sweep() {
    let d = dir("fifo");
    let acc = d.join("accuracy");
    std::fs::create_dir_all(&acc).unwrap();
    let fifo = acc.join("methods.md");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let out = d.join("out");
    let mut child = bin()
        .args([
            "report",
            "--scene",
            "contact",
            "--method",
            "hard",
            "--side",
            "16",
            "--runs",
            "1",
            "--mc-max",
            "4",
            "--out",
            s(&out),
            "--accuracy",
            s(&acc),
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("the report hangs on a FIFO");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let run = child.wait_with_output().unwrap();
    refused(&run, 600, &["methods.md"]);
    assert!(!out.join("results.json").exists());
}

/// `--accuracy` naming a file used to be found out after the sweep.
#[test]
fn an_accuracy_folder_that_is_a_file_is_refused_before_the_sweep() {
    let d = dir("accuracy-file");
    let file = write(&d, "a-file", "x");
    let out = d.join("out");
    refused(&small(&out, &["--accuracy", &file]), 600, &["--accuracy"]);
    assert!(!out.join("results.json").exists());
}

/// `--pictures 2147483648` used to overflow to a 9 × 2 picture.
#[test]
fn pictures_has_a_range() {
    let d = dir("pictures");
    let out = d.join("out");
    for bad in ["2147483648", "4097", "-1"] {
        let pictures = format!("--pictures={bad}");
        refused(
            &softshadow(&[
                "report",
                "--scene",
                "contact",
                "--method",
                "hard",
                "--side",
                "16",
                "--runs",
                "1",
                "--mc-max",
                "4",
                &pictures,
                "--out",
                s(&out),
            ]),
            600,
            &["--pictures"],
        );
    }
}
