//! `docs/ARCHITECTURE.md` is the map of the source, and these tests hold
//! it to the code: every path it names exists; every folder of `src/`,
//! every file directly under `src/` and every file of `cli/src/` is named
//! in it; no module of the library imports from a layer its table of
//! layers does not list (test code aside); and no source file is over 900
//! lines, no function over 120.

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

/// The source with comments, strings and character literals blanked (line
/// breaks kept), so that braces can be matched and lines counted.
fn code_only(text: &str) -> Vec<u8> {
    let b = text.as_bytes();
    let mut out = b.to_vec();
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for c in &mut out[from..to] {
            if *c != b'\n' {
                *c = b' ';
            }
        }
    };
    let mut i = 0;
    while i < b.len() {
        let rest = &b[i..];
        let end = if rest.starts_with(b"//") {
            i + rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len())
        } else if rest.starts_with(b"/*") {
            i + rest
                .windows(2)
                .position(|w| w == b"*/")
                .map_or(rest.len(), |k| k + 2)
        } else if rest.starts_with(b"r\"") || rest.starts_with(b"r#") {
            let hashes = rest[1..].iter().take_while(|&&c| c == b'#').count();
            if rest.get(1 + hashes) != Some(&b'"')
                || (i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'))
            {
                i += 1;
                continue;
            }
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            let body = i + 2 + hashes;
            body + b[body..]
                .windows(close.len())
                .position(|w| w == close.as_slice())
                .map_or(b.len() - body, |k| k + close.len())
        } else if rest[0] == b'"' {
            let mut j = i + 1;
            while j < b.len() && b[j] != b'"' {
                j += if b[j] == b'\\' { 2 } else { 1 };
            }
            (j + 1).min(b.len())
        } else if rest[0] == b'\'' {
            // A character literal ('x', '\n', '\u{..}'), not a lifetime.
            match rest.iter().skip(1).take(12).position(|&c| c == b'\'') {
                Some(k) if k == 1 || rest[1] == b'\\' => i + k + 2,
                _ => {
                    i += 1;
                    continue;
                }
            }
        } else {
            i += 1;
            continue;
        };
        blank(&mut out, i, end.min(b.len()));
        i = end.max(i + 1);
    }
    out
}

/// Library, program and Python-binding source files: none over 900 lines,
/// no function (from its `fn` line to its closing brace) over 120.
#[test]
fn no_source_file_over_900_lines_nor_function_over_120() {
    let mut long = Vec::new();
    for dir in ["src", "cli/src", "python/src"] {
        let (mut files, mut dirs) = (Vec::new(), Vec::new());
        walk(&root().join(dir), &mut files, &mut dirs);
        for file in files {
            let text = fs::read_to_string(&file).expect("a readable source file");
            let rel = relative(&file);
            let lines = text.lines().count();
            if lines > 900 {
                long.push(format!("{rel}: {lines} lines"));
            }
            let code = code_only(&text);
            let line_of = |at: usize| code[..at].iter().filter(|&&c| c == b'\n').count() + 1;
            let mut at = 0;
            while let Some(k) = code[at..].windows(3).position(|w| w == b"fn ") {
                let start = at + k;
                at = start + 3;
                if start > 0 && (code[start - 1].is_ascii_alphanumeric() || code[start - 1] == b'_')
                {
                    continue;
                }
                let (Some(open), semi) = (
                    code[at..].iter().position(|&c| c == b'{'),
                    code[at..].iter().position(|&c| c == b';'),
                ) else {
                    continue;
                };
                if semi.is_some_and(|s| s < open) {
                    continue;
                }
                let mut depth = 0_usize;
                let mut close = at + open;
                for (j, &c) in code[at + open..].iter().enumerate() {
                    if c == b'{' {
                        depth += 1;
                    } else if c == b'}' {
                        depth -= 1;
                        if depth == 0 {
                            close = at + open + j;
                            break;
                        }
                    }
                }
                let n = line_of(close) - line_of(start) + 1;
                if n > 120 {
                    let name: String = text[at..]
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    long.push(format!("{rel}:{}: fn {name}, {n} lines", line_of(start)));
                }
            }
        }
    }
    assert!(
        long.is_empty(),
        "over the size limits:\n{}",
        long.join("\n")
    );
}
