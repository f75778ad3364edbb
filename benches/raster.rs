//! The scalar light-view rasterizer on the default scene (the bunny over
//! its floor, 3676 triangles), seen from the sphere light's centre toward
//! the centre of the scene's bounding box, the window fitted to every
//! occluder vertex, at 512² and 1024². One thread. `rasterize` allocates
//! fresh maps per call (for a 1024² view, 16 MiB of page faults);
//! `rasterize_into` reuses them, as a renderer does from frame to frame.
//!
//! `cargo bench --features render,scene-file --bench raster`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use softshadow::bvh::Occluders;
use softshadow::render::raster::{rasterize_into, rasterize_occluders, LightMaps, LightView};
use softshadow::scene::builtin::builtin;
use softshadow::scene::LightFrame;
use std::hint::black_box;
use std::time::Duration;

fn default_scene(c: &mut Criterion) {
    let scene = builtin("default").expect("the default scene");
    let occluders = Occluders::from_scene(&scene);
    let (lo, hi) = scene.bounds().expect("a scene with meshes");
    let frame = LightFrame::toward(scene.light().center(), 0.5 * (lo + hi)).expect("a light frame");
    let vertices: Vec<_> = occluders.triangles().iter().flatten().copied().collect();
    let mut g = c.benchmark_group("raster_default_scene");
    g.sample_size(20).measurement_time(Duration::from_secs(5));
    for size in [512u32, 1024] {
        let view = LightView::fit(frame, vertices.iter().copied(), size, size, 1e-3)
            .expect("the scene is in front of the light");
        g.throughput(Throughput::Elements(view.len() as u64));
        g.bench_function(BenchmarkId::new("rasterize", size), |b| {
            b.iter(|| black_box(rasterize_occluders(black_box(&view), &occluders)))
        });
        // The same into maps kept from frame to frame: no page faults.
        g.bench_function(BenchmarkId::new("rasterize_into", size), |b| {
            let mut maps = LightMaps::empty(size, size);
            b.iter(|| {
                let (t, o) = (occluders.triangles(), occluders.objects());
                rasterize_into(black_box(&view), t, o, &mut maps).expect("same lengths");
                black_box(maps.depth()[0])
            })
        });
    }
    g.finish();
}

criterion_group!(benches, default_scene);
criterion_main!(benches);
