//! Running the `softshadow` binary from the command-line tests
//! (`tests/cli.rs`, `tests/hostile.rs`, each with `#[path]`): the process,
//! a fresh folder per test, files in it, the one-line refusal every bad
//! input must end with, and pictures that must be whole.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary, ready for arguments.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_softshadow"))
}

/// Runs the binary with `args`, its output captured.
pub fn softshadow(args: &[&str]) -> Output {
    bin()
        .args(args)
        .output()
        .expect("the softshadow binary runs")
}

/// Runs `visibility --scene scene --points points --method method` and
/// any `more` arguments.
pub fn visibility(scene: &str, points: &str, method: &str, more: &[&str]) -> Output {
    let args = [
        "visibility",
        "--scene",
        scene,
        "--points",
        points,
        "--method",
        method,
    ];
    softshadow(&[&args[..], more].concat())
}

/// A fresh folder for one test's files (`group` keeps test files apart).
pub fn dir(group: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softshadow-{group}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `text` to `dir/name` and returns the path as a string.
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

/// Exit 2, one line on stderr of at most `max` bytes containing every
/// needle, nothing on stdout, no panic.
pub fn refused(out: &Output, max: usize, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(out.stdout.is_empty(), "partial output: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.len() <= max,
        "{} bytes: {}",
        stderr.len(),
        &stderr[..200.min(stderr.len())]
    );
    for n in needles {
        assert!(stderr.contains(n), "{stderr:?} lacks {n:?}");
    }
}

/// Every PNG under its final name in `dir` decodes whole; no temporary
/// file is left unless `temporaries_allowed`.
pub fn pictures_whole(dir: &Path, temporaries_allowed: bool) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.starts_with('.') {
            assert!(temporaries_allowed, "left behind: {name}");
            continue;
        }
        if name.ends_with(".png") {
            let file = std::io::BufReader::new(std::fs::File::open(&path).unwrap());
            let mut reader = png::Decoder::new(file).read_info().unwrap();
            let mut buf = vec![0; reader.output_buffer_size().unwrap()];
            reader.next_frame(&mut buf).unwrap();
        }
    }
}
