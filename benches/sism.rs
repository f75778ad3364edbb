//! Soft irregular shadow mapping on the default scene: one frame of the
//! camera's receivers (built once, outside the timing), per variant — the
//! paper's defaults, each overdraw optimisation off, both off, the kernel's
//! conservative bounds, the exact composition — beside the hard-shadow
//! frame. Each iteration is one `method::run` on fresh stages (the method's
//! own stages included, the shared BVH excluded).
//!
//! `cargo bench --bench sism --all-features`; the image side is
//! `SISM_BENCH_SIDE` (default 256; `benches/README.md` quotes 512, with the
//! per-stage times and evaluation counts from
//! `cargo run --release --all-features --example sism_speed -- 512`).

#[path = "support/frame.rs"]
mod support;

use criterion::{criterion_group, criterion_main, Criterion};

const VARIANTS: &[&str] = &[
    "sism",
    "sism:no-bin-depth",
    "sism:no-wedge-column",
    "sism:no-bin-depth,no-wedge-column",
    "sism:conservative",
    "sism:exact-union",
    "hard",
];

fn default_frame(c: &mut Criterion) {
    let side = support::side("SISM_BENCH_SIDE", 256);
    let methods: Vec<String> = VARIANTS.iter().map(|s| (*s).to_owned()).collect();
    support::methods_on_frame(c, &format!("default_{side}"), "default", side, &methods);
}

criterion_group!(benches, default_frame);
criterion_main!(benches);
