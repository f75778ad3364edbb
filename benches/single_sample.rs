//! Single-sample soft shadows on the default scene at 512² (the paper's
//! image size, its 256² light map), as the paper measured it (§5, Fig. 6):
//! with and without the §4.3 interpolation, and against the search radius
//! `r_max` at the farthest receiver (5, 10, 20 — the paper's — and 40
//! texels), beside the hard shadow and PCSS on the same frame. Each
//! iteration is one `method::run` on fresh stages (the light maps included,
//! the shared BVH not).
//!
//! `cargo bench --bench single_sample --all-features`; the image side is
//! `SINGLE_SAMPLE_BENCH_SIDE` (default 512). Figures in `benches/README.md`.

#[path = "support/frame.rs"]
mod support;

use criterion::{criterion_group, criterion_main, Criterion};
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin;

fn default_frame(c: &mut Criterion) {
    let side = support::side("SINGLE_SAMPLE_BENCH_SIDE", 512);
    // r_scale for a given r_max at the farthest receiver: r_max / z_far.
    let scene = builtin("default").expect("the default scene");
    let camera = scene
        .camera()
        .expect("a camera")
        .with_resolution(side, side)
        .expect("a size");
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(&camera, stages.bvh());
    let light = stages.light_frame();
    let z_far = frame
        .receivers()
        .iter()
        .map(|r| light.to_light(r.position).z)
        .fold(0.0, f64::max);
    let mut methods: Vec<String> = [
        "single-sample",
        "single-sample:no-interpolate",
        "single-sample:light-aware",
        "hard",
        "pcss",
    ]
    .iter()
    .map(|s| (*s).to_owned())
    .collect();
    for r_max in [5.0, 10.0, 40.0] {
        methods.push(format!("single-sample:r-scale={:?}", r_max / z_far));
    }
    support::methods_on_frame(
        c,
        &format!("single_sample_{side}"),
        "default",
        side,
        &methods,
    );
}

criterion_group!(benches, default_frame);
criterion_main!(benches);
