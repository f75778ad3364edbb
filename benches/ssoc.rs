//! The soft shadow occlusion camera and its backprojected variant on the
//! default scene at 512², beside SISM and the hard shadow on the same
//! frame: one `method::run` per iteration on fresh stages (the shadow map
//! and the distortion maps included, the shared BVH not). The paper's
//! Table 1 splits its frame into silhouettes, shadow map, SSOC maps and the
//! eye pass; `benches/README.md` quotes our stages from the run's `Stats`.
//!
//! `cargo bench --bench ssoc --all-features`; the image side is
//! `SSOC_BENCH_SIDE` (default 512).

#[path = "support/frame.rs"]
mod support;

use criterion::{criterion_group, criterion_main, Criterion};

fn default_frame(c: &mut Criterion) {
    let side = support::side("SSOC_BENCH_SIDE", 512);
    let methods: Vec<String> = [
        "ssoc",
        "ssoc:lookups=1",
        "backprojected-ssoc",
        "backprojected-ssoc:walk",
        "backprojected-ssoc:potential",
        "backprojected-ssoc:walk,potential",
        "sism",
        "hard",
    ]
    .iter()
    .map(|s| (*s).to_owned())
    .collect();
    support::methods_on_frame(c, &format!("ssoc_{side}"), "default", side, &methods);
}

criterion_group!(benches, default_frame);
criterion_main!(benches);
