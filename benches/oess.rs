//! Occluding edges soft shadows on the `linear-light` scene at 512² with
//! 800² endpoint maps, beside the hard shadow and Monte Carlo with 2 and 4
//! samples on the same frame: one `method::run` per iteration on fresh
//! stages (the endpoint maps included, the shared BVH not).
//! `benches/README.md` quotes the stages from the run's `Stats` and the
//! penumbra RMSE of each from `docs/accuracy/oess.md`.
//!
//! `cargo bench --bench oess --all-features`; the image side is
//! `OESS_BENCH_SIDE` (default 512).

#[path = "support/frame.rs"]
mod support;

use criterion::{criterion_group, criterion_main, Criterion};

fn linear_light_frame(c: &mut Criterion) {
    let side = support::side("OESS_BENCH_SIDE", 512);
    let methods: Vec<String> = ["oess", "oess:depth-check", "hard", "mc:2", "mc:4"]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
    support::methods_on_frame(c, &format!("oess_{side}"), "linear-light", side, &methods);
}

criterion_group!(benches, linear_light_frame);
criterion_main!(benches);
