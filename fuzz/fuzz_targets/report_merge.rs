//! `report --merge` on fuzzed parts' folders: the library's
//! [`Staged`] + [`merge_into`] + commit, which is all the command does.
//!
//! The parts are made from real ones: at start-up, a small sweep (the
//! `contact` and `linear-light` scenes at 16², `exact`, `hard`, PCSS and
//! the yardstick to 8 samples, 8-pixel pictures) is run in three shards,
//! and a fourth part comes from another sweep (`contact` and a scene whose
//! floor is inside its light, which cannot be prepared). The first byte
//! picks the mode:
//!
//! - raw (`% 4 == 0`): the rest, split at `0xFF` bytes, is up to three
//!   `results.json` texts, each in a folder holding the real part's
//!   pictures (seed the corpus with real parts joined by `0xFF`);
//! - structured: the next bytes pick parts (any of the four, repeats
//!   allowed), then mutations of their JSON — a value anywhere replaced by
//!   a hostile one (`"../x.png"`, `1e308`, huge integers, control
//!   characters, other types…), array elements repeated or removed, a
//!   cell copied into another part — and of their folders — a picture
//!   replaced by a link out of the part, a link within it, a directory, a
//!   truncated or foreign file, or removed — and the state of `--out`
//!   (missing, an earlier report, a folder holding a foreign file).
//!
//! Asserted, whatever the input: no panic; either a refusal — one line —
//! with `--out` exactly as it was, the parts untouched and nothing left
//! beside them; or a merged report whose `results.json` reads back equal
//! to the merged results, which are whole (`Results::check`), hold exactly
//! the parts' cells (each once) and merge to themselves again, whose
//! folder holds exactly `results.json`, `index.md`, plots and the pictures
//! its cells name — each the bytes of that cell's picture in its part,
//! never one reached through a link out of the part — and whose index
//! names every scene.
#![no_main]

use libfuzzer_sys::fuzz_target;
use serde_json::Value;
use softshadow::report::{self, merge_into, read_part, Case, Config, Results, Shard, Staged};
use softshadow::scene::builtin;
use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// One real part: its results as JSON and its pictures.
struct Part {
    json: Value,
    pictures: Vec<(String, Vec<u8>)>,
}

/// Every file under `dir` (relative path → bytes; a link as `link:TARGET`,
/// a folder as `dir`).
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries {
            let path = e.unwrap().path();
            let rel = path.strip_prefix(dir).unwrap().to_path_buf();
            let meta = std::fs::symlink_metadata(&path).unwrap();
            if meta.file_type().is_symlink() {
                let target = std::fs::read_link(&path).unwrap();
                out.insert(rel, format!("link:{}", target.display()).into_bytes());
            } else if meta.is_dir() {
                out.insert(rel, b"dir".to_vec());
                stack.push(path);
            } else {
                out.insert(rel, std::fs::read(&path).unwrap());
            }
        }
    }
    out
}

fn root() -> &'static Path {
    static ROOT: OnceLock<PathBuf> = OnceLock::new();
    ROOT.get_or_init(|| {
        let shm = Path::new("/dev/shm");
        let base = if shm.is_dir() {
            shm.to_path_buf()
        } else {
            std::env::temp_dir()
        };
        let d = base.join(format!("softshadow-fuzz-merge-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    })
}

/// Runs one shard of a sweep into a folder and reads it back.
fn real_part(name: &str, cases: &[Case], config: &Config) -> Part {
    let dir = root().join("seed").join(name);
    let staged = Staged::new(&dir).unwrap();
    let results =
        report::finish(report::run(cases, config, Some(staged.path()), &|_, _, _| {}).unwrap());
    report::write(&results, staged.path()).unwrap();
    staged.commit().unwrap();
    let pictures = results
        .cells
        .iter()
        .filter_map(|c| c.picture.clone())
        .map(|p| {
            let bytes = std::fs::read(dir.join(&p)).unwrap();
            (p, bytes)
        })
        .collect();
    let json = serde_json::from_slice(&std::fs::read(dir.join("results.json")).unwrap()).unwrap();
    Part { json, pictures }
}

fn seeds() -> &'static Vec<Part> {
    static SEEDS: OnceLock<Vec<Part>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let case = |n: &str| Case {
            name: n.to_owned(),
            scene: builtin(n).unwrap(),
        };
        let config = Config {
            side: 16,
            runs: 2,
            mc: vec![2, 4, 8],
            methods: vec!["hard".to_owned(), "pcss:map=64".to_owned()],
            shard: None,
            picture_side: 8,
            own: Vec::new(),
        };
        let cases = [case("contact"), case("linear-light")];
        let mut parts: Vec<Part> = (1..=3)
            .map(|index| {
                let config = Config {
                    shard: Some(Shard { index, count: 3 }),
                    ..config.clone()
                };
                real_part(&format!("p{index}"), &cases, &config)
            })
            .collect();
        let inside = softshadow::scene::file::scene_from_str(
            "inside.json",
            r#"{"light": {"type": "sphere", "center": [0, 0.2, 0], "radius": 0.5},
                "camera": {"eye": [0, 2, 6], "target": [0, 0, 0], "fov_y_deg": 40, "width": 24, "height": 18},
                "meshes": [{"name": "floor", "primitive": {"type": "quad", "center": [0, 0, 0], "u": [4, 0, 0], "v": [0, 0, 4]}}]}"#,
            Path::new("."),
        )
        .unwrap();
        let other = [
            case("contact"),
            Case {
                name: "inside.json".to_owned(),
                scene: inside,
            },
        ];
        let config = Config {
            methods: vec!["hard".to_owned()],
            ..config
        };
        parts.push(real_part("other", &other, &config));
        parts
    })
}

/// A byte reader that gives zeros once the input is used up.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (usize::from(self.byte()) << 8 | usize::from(self.byte())) % n
        }
    }
}

/// A hostile value.
fn hostile(b: &mut Bytes<'_>) -> Value {
    use serde_json::json;
    match b.byte() % 26 {
        0 => Value::Null,
        1 => json!(0),
        2 => json!(-1),
        3 => json!(1),
        4 => json!(9_007_199_254_740_993u64),
        5 => json!(u64::MAX),
        6 => json!(1e308),
        7 => json!(-1e308),
        8 => json!(0.5),
        9 => json!(1.5),
        10 => json!(5e-324),
        11 => json!(""),
        12 => json!("../x.png"),
        13 => json!("pictures/../../x.png"),
        14 => json!("/etc/passwd"),
        15 => json!("a\nb"),
        16 => Value::String("x".repeat(5000)),
        17 => json!("ok"),
        18 => json!("error: x"),
        19 => json!("n/a (sphere light)"),
        20 => json!("softshadow-report/1"),
        21 => json!([]),
        22 => json!({}),
        23 => json!(true),
        24 => json!(u32::MAX),
        _ => json!(f64::from(b.byte()) / 255.0),
    }
}

/// A step into a JSON value.
enum Step {
    Key(String),
    Item(usize),
}

/// A value somewhere in `v`, walked to by the bytes.
fn pick<'v>(v: &'v mut Value, b: &mut Bytes<'_>) -> &'v mut Value {
    let mut path = Vec::new();
    let mut at: &Value = v;
    while !b.byte().is_multiple_of(4) {
        let step = match at {
            Value::Object(map) if !map.is_empty() => {
                Step::Key(map.keys().nth(b.below(map.len())).unwrap().clone())
            }
            Value::Array(items) if !items.is_empty() => Step::Item(b.below(items.len())),
            _ => break,
        };
        at = match &step {
            Step::Key(k) => &at[k.as_str()],
            Step::Item(i) => &at[*i],
        };
        path.push(step);
    }
    path.iter().fold(v, |at, step| match step {
        Step::Key(k) => &mut at[k.as_str()],
        Step::Item(i) => &mut at[*i],
    })
}

/// What was done to the parts' folders that the merge must refuse to use.
#[derive(Default)]
struct Traps {
    /// Pictures (part, name) replaced by a link out of their part.
    escaping: HashSet<(usize, String)>,
}

fn write_part(dir: &Path, text: &[u8], pictures: &[(String, Vec<u8>)]) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("results.json"), text).unwrap();
    for (name, bytes) in pictures {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
}

fn structured(b: &mut Bytes<'_>, run: &Path, traps: &mut Traps) -> Vec<PathBuf> {
    let seeds = seeds();
    let count = 1 + b.below(3);
    let chosen: Vec<usize> = (0..count).map(|_| b.below(seeds.len())).collect();
    let mut jsons: Vec<Value> = chosen.iter().map(|&k| seeds[k].json.clone()).collect();
    for _ in 0..b.below(4) {
        let p = b.below(jsons.len());
        match b.byte() % 5 {
            0 | 1 => *pick(&mut jsons[p], b) = hostile(b),
            2 => {
                if let Value::Array(items) = pick(&mut jsons[p], b) {
                    if !items.is_empty() {
                        let k = b.below(items.len());
                        let item = items[k].clone();
                        items.push(item);
                    }
                }
            }
            3 => {
                if let Value::Array(items) = pick(&mut jsons[p], b) {
                    if !items.is_empty() {
                        let k = b.below(items.len());
                        items.remove(k);
                    }
                }
            }
            _ => {
                // A cell of one part copied into another.
                let q = b.below(jsons.len());
                let cells = jsons[q]["cells"].as_array().cloned().unwrap_or_default();
                if !cells.is_empty() {
                    let cell = cells[b.below(cells.len())].clone();
                    let cells = jsons[p].get_mut("cells").and_then(Value::as_array_mut);
                    if let Some(items) = cells {
                        items.push(cell);
                    }
                }
            }
        }
    }
    let mut dirs = Vec::new();
    for (p, (&k, json)) in chosen.iter().zip(&jsons).enumerate() {
        let dir = run.join(format!("part{p}"));
        write_part(&dir, &serde_json::to_vec(json).unwrap(), &seeds[k].pictures);
        dirs.push(dir);
    }
    // The folders.
    for _ in 0..b.below(3) {
        let p = b.below(dirs.len());
        let pictures = &seeds[chosen[p]].pictures;
        if pictures.is_empty() {
            continue;
        }
        let (name, bytes) = &pictures[b.below(pictures.len())];
        let path = dirs[p].join(name);
        let _ = std::fs::remove_file(&path);
        let _ = std::fs::remove_dir_all(&path);
        traps.escaping.remove(&(p, name.clone()));
        match b.byte() % 6 {
            0 => {
                std::os::unix::fs::symlink(run.join("outside.png"), &path).unwrap();
                traps.escaping.insert((p, name.clone()));
            }
            1 => {
                let other = &pictures[b.below(pictures.len())].0;
                if other != name {
                    std::os::unix::fs::symlink(dirs[p].join(other), &path).unwrap();
                }
            }
            2 => std::fs::create_dir_all(&path).unwrap(),
            3 => std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap(),
            4 => std::fs::write(&path, b"not a picture").unwrap(),
            _ => {}
        }
    }
    dirs
}

fn raw(data: &[u8], run: &Path) -> Vec<PathBuf> {
    let seeds = seeds();
    data.split(|&x| x == 0xFF)
        .take(3)
        .enumerate()
        .map(|(p, text)| {
            let dir = run.join(format!("part{p}"));
            write_part(&dir, text, &seeds[p].pictures);
            dir
        })
        .collect()
}

fuzz_target!(|data: &[u8]| {
    let seeds = seeds();
    let run = root().join("run");
    let _ = std::fs::remove_dir_all(&run);
    std::fs::create_dir_all(&run).unwrap();
    // Outside every part: a picture a link may lead to.
    std::fs::write(run.join("outside.png"), &seeds[0].pictures[0].1).unwrap();
    let mut b = Bytes(data);
    let mode = b.byte();
    let mut traps = Traps::default();
    let dirs = if mode % 4 == 0 {
        raw(b.0, &run)
    } else {
        structured(&mut b, &run, &mut traps)
    };
    // --out: missing, an earlier report, or a folder with a foreign file.
    let out = run.join("out");
    match b.byte() % 3 {
        0 => {}
        1 => write_part(
            &out,
            &serde_json::to_vec(&seeds[3].json).unwrap(),
            &seeds[3].pictures,
        ),
        _ => {
            std::fs::create_dir_all(&out).unwrap();
            std::fs::write(out.join("notes.txt"), b"mine").unwrap();
        }
    }
    let parts_before: Vec<_> = dirs.iter().map(|d| snapshot(d)).collect();
    let out_before = snapshot(&out);
    let merged = (|| {
        let staged = Staged::new(&out)?;
        let merged = merge_into(&dirs, staged.path())?;
        staged.commit()?;
        Ok::<Results, String>(merged)
    })();
    // The parts are only read; nothing is left beside them.
    for (d, before) in dirs.iter().zip(&parts_before) {
        assert_eq!(&snapshot(d), before, "part {} changed", d.display());
    }
    let mut beside: Vec<String> = std::fs::read_dir(&run)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    beside.sort();
    let mut expected: Vec<String> = (0..dirs.len()).map(|p| format!("part{p}")).collect();
    expected.push("outside.png".to_owned());
    if out.exists() {
        expected.push("out".to_owned());
    }
    expected.sort();
    assert_eq!(beside, expected);
    let merged = match merged {
        Err(e) => {
            assert!(!e.contains('\n') && !e.contains('\r'), "{e:?}");
            assert!(e.len() <= 8192, "{} bytes", e.len());
            assert_eq!(
                snapshot(&out),
                out_before,
                "--out changed on a refusal: {e}"
            );
            return;
        }
        Ok(m) => m,
    };
    // Whole, read back equal, and a merge of itself.
    merged.check().unwrap();
    let back = read_part(&out).unwrap();
    assert_eq!(back, merged);
    assert_eq!(report::merge(vec![back]).unwrap(), merged);
    // Exactly the parts' cells, each once.
    let parts: Vec<Results> = dirs.iter().map(|d| read_part(d).unwrap()).collect();
    let all: usize = parts.iter().map(|p| p.cells.len()).sum();
    assert_eq!(merged.cells.len(), all);
    let indices: HashSet<usize> = merged.cells.iter().map(|c| c.index).collect();
    assert_eq!(indices.len(), all);
    assert!(merged.cells.iter().all(|c| c.index < merged.config.cells));
    // The folder: results.json, index.md, plots and the named pictures,
    // each its part's own bytes, none reached through a link out.
    let files = snapshot(&out);
    let mut named: HashSet<PathBuf> = HashSet::new();
    for c in &merged.cells {
        let Some(p) = &c.picture else { continue };
        let (k, part) = parts
            .iter()
            .enumerate()
            .find(|(_, part)| part.cells.iter().any(|x| x.index == c.index))
            .unwrap();
        assert!(
            !traps.escaping.contains(&(k, p.clone())),
            "{p} read through a link out of its part"
        );
        let _ = part;
        let theirs = std::fs::read(dirs[k].join(p)).unwrap();
        assert_eq!(files.get(Path::new(p)), Some(&theirs), "{p}");
        named.insert(PathBuf::from(p));
    }
    for (path, bytes) in &files {
        let s = path.to_str().unwrap();
        let ok = s == "results.json"
            || s == "index.md"
            || (s.starts_with("plots/") && s.ends_with(".svg"))
            || named.contains(path)
            || bytes == b"dir";
        assert!(ok, "{s} in the merged report");
    }
    let index = String::from_utf8(files[Path::new("index.md")].clone()).unwrap();
    for s in &merged.scenes {
        assert!(index.contains(&format!("## `{}`", s.name)), "{}", s.name);
    }
    for (s, _) in merged.unprepared() {
        assert!(index.contains(&format!("- `{s}`")), "{s}");
    }
});
