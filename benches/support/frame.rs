//! One frame of a built-in scene's camera receivers (built once, outside
//! the timing) and `method::run` of each method on fresh stages per
//! iteration: the method's own stages (light maps, grids, tiles) are paid,
//! the shared BVH is not.

use criterion::{BenchmarkId, Criterion, Throughput};
use softshadow::method::{self, Method};
use softshadow::render::{Frame, Needs, Stages};
use softshadow::scene::builtin;
use std::hint::black_box;
use std::time::Duration;

/// The image side from the environment variable `var`, else `default`.
pub fn side(var: &str, default: u32) -> u32 {
    std::env::var(var)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// Benchmarks `methods` (command-line names) on `scene`'s camera frame at
/// `side × side`, in the group `group`.
pub fn methods_on_frame(
    c: &mut Criterion,
    group: &str,
    scene: &str,
    side: u32,
    methods: &[String],
) {
    let scene = builtin(scene).expect("a built-in scene");
    let camera = scene
        .camera()
        .expect("a camera")
        .with_resolution(side, side)
        .expect("a valid resolution");
    let frame = Frame::from_camera(&camera, Stages::new(&scene).bvh());
    let mut g = c.benchmark_group(group);
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    g.throughput(Throughput::Elements(frame.receivers().len() as u64));
    for name in methods {
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
                // The stages are returned so that freeing their maps falls
                // outside the timing, as it does for a caller that keeps them.
                |stages| {
                    let run = black_box(method::run(m.as_ref(), &stages, &frame).ok());
                    (run, stages)
                },
                criterion::BatchSize::PerIteration,
            )
        });
    }
    g.finish();
}
