//! Per-stage cost of a frame of the default scene at 512² (the camera's
//! resolution), on the rayon pool (2 threads on the project's machine):
//!
//! - `stages/bvh`: building the BVH over the 3676 triangles;
//! - `stages/receivers`: the 512² primary rays (closest hit) that find the
//!   receivers;
//! - `stages/light_maps_1024`: PCSS's light-view depth map at 1024²
//!   (fitting and rasterising);
//! - `methods/*`: each method's visibility pass on the receivers, stages
//!   already built (`hard`: one exact shadow ray per receiver; `pcss`: 32
//!   blocker-search and 64 filter reads per receiver; `exact`).
//! - `frame/hard`: the whole hard-shadow frame from nothing: BVH, primary
//!   rays, shadow rays.
//!
//! `cargo bench --bench render`; figures in `benches/README.md`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use softshadow::bvh::{Bvh, Occluders};
use softshadow::method::{self, Exact, HardShadow, Method, Pcss};
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin;
use std::hint::black_box;
use std::time::Duration;

fn stages(c: &mut Criterion) {
    let scene = builtin("default").expect("the default scene");
    let camera = *scene.camera().expect("a camera");
    let mut g = c.benchmark_group("stages");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    g.bench_function("bvh", |b| {
        b.iter(|| black_box(Bvh::new(Occluders::from_scene(&scene))))
    });
    let bvh = Bvh::new(Occluders::from_scene(&scene));
    g.throughput(Throughput::Elements(512 * 512));
    g.bench_function("receivers", |b| {
        b.iter(|| black_box(Frame::from_camera(&camera, &bvh)))
    });
    g.throughput(Throughput::Elements(1));
    let frame = Frame::from_camera(&camera, &bvh);
    g.bench_function("light_maps_1024", |b| {
        b.iter(|| {
            // A fresh `Stages` so the maps are built, not fetched.
            let stages = Stages::new(&scene);
            stages.bvh();
            black_box(stages.light_maps(&frame, 1024, 1024))
        })
    });
    g.finish();
}

fn methods(c: &mut Criterion) {
    let scene = builtin("default").expect("the default scene");
    let camera = *scene.camera().expect("a camera");
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(&camera, stages.bvh());
    let mut g = c.benchmark_group("methods");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    g.throughput(Throughput::Elements(frame.receivers().len() as u64));
    let list: [&dyn Method; 3] = [&HardShadow::default(), &Pcss::default(), &Exact];
    for m in list {
        method::run(m, &stages, &frame).expect("runs"); // builds its stages
                                                        // The visibility pass alone: the frame checked once, outside.
        let input = method::check(m, &stages, &frame).expect("a valid frame");
        g.bench_function(m.name(), |b| {
            b.iter(|| black_box(m.visibility(&input).expect("runs")))
        });
    }
    g.finish();
    let mut g = c.benchmark_group("frame");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    g.bench_function("hard", |b| {
        b.iter(|| {
            let stages = Stages::new(&scene);
            let frame = Frame::from_camera(&camera, stages.bvh());
            black_box(method::run(&HardShadow::default(), &stages, &frame).expect("runs"))
        })
    });
    g.finish();
}

criterion_group!(benches, stages, methods);
criterion_main!(benches);
