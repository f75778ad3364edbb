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

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use softshadow::method::{self, Method};
use softshadow::render::{Frame, Needs, Stages};
use softshadow::scene::builtin;
use std::hint::black_box;
use std::time::Duration;

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
    let side: u32 = std::env::var("SISM_BENCH_SIDE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(256);
    let scene = builtin("default").expect("the default scene");
    let camera = scene
        .camera()
        .expect("a camera")
        .with_resolution(side, side)
        .expect("a valid resolution");
    let frame = Frame::from_camera(&camera, Stages::new(&scene).bvh());
    let mut g = c.benchmark_group(format!("default_{side}"));
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    g.throughput(Throughput::Elements(frame.receivers().len() as u64));
    for &name in VARIANTS {
        let m: Box<dyn Method> = method::parse(name).expect("a method name");
        g.bench_function(BenchmarkId::new("frame", name), |b| {
            b.iter_batched(
                || {
                    let stages = Stages::new(&scene);
                    if m.needs().contains(Needs::BVH) {
                        stages.bvh();
                    }
                    stages
                },
                |stages| black_box(method::run(m.as_ref(), &stages, &frame).ok()),
                criterion::BatchSize::PerIteration,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, default_frame);
criterion_main!(benches);
