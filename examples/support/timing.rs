//! Timing helpers shared by the ray-corpus examples (`ray_corpus.rs`,
//! `primary_corpus.rs`), included with `#[path]`.

/// CPU time consumed so far by all threads of this process, in
/// nanoseconds (Linux: the first field of `/proc/self/task/*/schedstat`);
/// `None` where that is unavailable.
pub fn cpu_ns() -> Option<u64> {
    let mut total = 0;
    for entry in std::fs::read_dir("/proc/self/task").ok()? {
        let text = std::fs::read_to_string(entry.ok()?.path().join("schedstat")).ok()?;
        total += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total)
}

/// The median (the upper one for an even count) of a non-empty list.
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
