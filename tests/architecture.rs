//! `docs/ARCHITECTURE.md` is the map of the source, and these tests hold
//! it to the code: every path it names exists; every folder of `src/`,
//! every file directly under `src/` and every file of `cli/src/` is named
//! in it; and no module of the library imports from a layer its table of
//! layers does not list (test code aside).

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn map() -> String {
    fs::read_to_string(root().join("docs/ARCHITECTURE.md")).expect("docs/ARCHITECTURE.md")
}

/// The backquoted spans of the map that are repository paths.
fn named_paths(text: &str) -> BTreeSet<String> {
    const TOPS: [&str; 8] = [
        "src/",
        "cli/",
        "tests/",
        "benches/",
        "examples/",
        "fuzz/",
        "python/",
        "docs/",
    ];
    text.split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| !span.contains(' ') && TOPS.iter().any(|top| span.starts_with(top)))
        .map(|span| span.trim_end_matches('/').to_owned())
        .collect()
}

fn relative(path: &Path) -> String {
    path.strip_prefix(root())
        .expect("under the root")
        .to_string_lossy()
        .replace('\\', "/")
}

/// Every `.rs` file under `dir`, and every folder (`dirs`).
fn walk(dir: &Path, files: &mut Vec<PathBuf>, dirs: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = fs::read_dir(dir)
        .expect("a readable folder")
        .map(|e| e.expect("an entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            dirs.push(path.clone());
            walk(&path, files, dirs);
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
}

#[test]
fn every_path_the_map_names_exists() {
    let missing: Vec<String> = named_paths(&map())
        .into_iter()
        .filter(|p| !root().join(p).exists())
        .collect();
    assert!(
        missing.is_empty(),
        "docs/ARCHITECTURE.md names paths that do not exist: {missing:?}"
    );
}

#[test]
fn every_folder_and_top_file_is_on_the_map() {
    let named = named_paths(&map());
    let (mut files, mut dirs) = (Vec::new(), Vec::new());
    walk(&root().join("src"), &mut files, &mut dirs);
    let mut wanted: Vec<String> = dirs.iter().map(|d| relative(d)).collect();
    wanted.extend(
        files
            .iter()
            .filter(|f| f.parent() == Some(&root().join("src")))
            .map(|f| relative(f)),
    );
    let (mut cli, mut none) = (Vec::new(), Vec::new());
    walk(&root().join("cli/src"), &mut cli, &mut none);
    wanted.extend(cli.iter().map(|f| relative(f)));
    let absent: Vec<&String> = wanted.iter().filter(|w| !named.contains(*w)).collect();
    assert!(
        absent.is_empty(),
        "docs/ARCHITECTURE.md does not name: {absent:?}"
    );
}

/// The layers table: each library folder `src/NAME` and the modules it
/// may import (`crate::MODULE`).
fn layers(text: &str) -> Vec<(String, BTreeSet<String>)> {
    let section = text
        .split("## Layers")
        .nth(1)
        .expect("a section on layers")
        .split("\n## ")
        .next()
        .expect("its text");
    section
        .lines()
        .filter(|l| l.starts_with("| "))
        .filter_map(|row| {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            let folder = cells
                .get(2)?
                .trim_matches('`')
                .strip_prefix("src/")?
                .to_owned();
            let imports = cells
                .get(4)?
                .split(',')
                .map(|m| m.trim().trim_matches('`').to_owned())
                .filter(|m| !m.is_empty())
                .collect();
            Some((folder, imports))
        })
        .collect()
}

#[test]
fn no_module_imports_from_a_layer_it_does_not_list() {
    let table = layers(&map());
    assert!(
        table.len() >= 8,
        "the layers table was not found: {table:?}"
    );
    let names: BTreeSet<&str> = table.iter().map(|(f, _)| f.as_str()).collect();
    let mut wrong = Vec::new();
    for (folder, allowed) in &table {
        let (mut files, mut dirs) = (Vec::new(), Vec::new());
        let dir = root().join("src").join(folder);
        if dir.is_dir() {
            walk(&dir, &mut files, &mut dirs);
        }
        let single = root().join("src").join(format!("{folder}.rs"));
        if single.is_file() {
            files.push(single);
        }
        for file in files {
            let rel = relative(&file);
            if rel.ends_with("/tests.rs") || rel.contains("/tests/") {
                continue;
            }
            let text = fs::read_to_string(&file).expect("a readable source file");
            for (n, line) in text.lines().enumerate() {
                let code = line.trim_start();
                if code.starts_with("#[cfg(test)]") {
                    break;
                }
                if code.starts_with("//") {
                    continue;
                }
                for (at, _) in code.match_indices("crate::") {
                    let module: String = code[at + 7..]
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    if module != *folder
                        && names.contains(module.as_str())
                        && !allowed.contains(&module)
                    {
                        wrong.push(format!("{rel}:{}: crate::{module}", n + 1));
                    }
                }
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports from layers the map does not list:\n{}",
        wrong.join("\n")
    );
}
