//! The cost of the exact reference per receiver, against Monte Carlo at
//! 4096 samples on the same receivers, and how it grows with the number of
//! occluders whose projection meets the light. One thread each (the
//! references parallelise over receivers, so ratios carry over).
//!
//! - `default_scene`: the default scene's floor receivers in the bunny's
//!   penumbra (`definitions::in_penumbra`), and the whole floor grid (a
//!   frame).
//! - `occluders`: a receiver under a sphere light behind `n` random small
//!   triangles, every one of which projects onto the light.
//!
//! `cargo bench --bench references`; figures in `benches/README.md`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
#[path = "support/pile.rs"]
mod pile;
use pile::occluders;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::definitions::in_penumbra;
use softshadow::glam::DVec3;
use softshadow::reference::exact::{self, Scratch};
use softshadow::reference::monte_carlo::{self, Options};
use softshadow::scene::builtin::{builtin, floor_receivers};
use softshadow::scene::Light;
use std::hint::black_box;
use std::time::Duration;

fn default_scene(c: &mut Criterion) {
    let scene = builtin("default").expect("the default scene");
    let bvh = Bvh::new(Occluders::from_scene(&scene));
    let light = *scene.light();
    let grid = floor_receivers(&scene, 32);
    let penumbra: Vec<DVec3> = grid
        .iter()
        .copied()
        .filter(|&p| matches!(exact::visibility(&bvh, &light, p), Ok(v) if in_penumbra(v)))
        .collect();
    let mut g = c.benchmark_group("default_scene");
    g.sample_size(10).measurement_time(Duration::from_secs(4));
    for (name, points) in [("penumbra", &penumbra), ("frame", &grid)] {
        g.throughput(Throughput::Elements(points.len() as u64));
        g.bench_function(BenchmarkId::new("exact", name), |b| {
            let mut scratch = Scratch::default();
            b.iter(|| {
                for &p in points {
                    black_box(exact::visibility_with(&bvh, &light, p, &mut scratch).ok());
                }
            })
        });
        let options = Options::new(4096);
        g.bench_function(BenchmarkId::new("mc4096", name), |b| {
            b.iter(|| {
                for &p in points {
                    black_box(monte_carlo::visibility(&bvh, &light, p, &options).ok());
                }
            })
        });
    }
    g.finish();
}

fn growth(c: &mut Criterion) {
    let light = Light::sphere(DVec3::new(0.0, 0.0, 4.0), 0.5).expect("a valid light");
    let mut g = c.benchmark_group("occluders");
    g.sample_size(10).measurement_time(Duration::from_secs(2));
    for n in [1, 4, 16, 64, 256, 1024, 4096, 16384] {
        let bvh = Bvh::new(Occluders::from_triangles(occluders(n)));
        g.bench_function(BenchmarkId::new("exact", n), |b| {
            let mut scratch = Scratch::default();
            b.iter(|| {
                black_box(exact::visibility_with(&bvh, &light, DVec3::ZERO, &mut scratch).ok())
            })
        });
        if n <= 256 || n >= 4096 {
            let options = Options::new(4096);
            g.bench_function(BenchmarkId::new("mc4096", n), |b| {
                b.iter(|| {
                    black_box(monte_carlo::visibility(&bvh, &light, DVec3::ZERO, &options).ok())
                })
            });
        }
    }
    g.finish();
}

/// Degenerate input: `n` exact copies of one triangle over the receiver
/// (the BVH indexes one), and `n` nested triangles about one centre, the
/// largest of which hides the whole light (the exact reference stops at the
/// first image that covers it; the BVH indexes the nested run as one box
/// for PLOC and splits it in halves): the BVH builds and one exact answer;
/// copies shifted by 1e-9 and layers stacked 1e-4 apart (near-coincident
/// and nearly nested boxes); and nested triangles none of which covers a
/// larger light, whose images cross one side of the clip square (swept,
/// not searched).
fn degenerate(c: &mut Criterion) {
    let light = Light::sphere(DVec3::new(0.0, 3.0, 0.0), 0.5).expect("a valid light");
    let t = [
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, -1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    let centre = (t[0] + t[1] + t[2]) / 3.0;
    let p = DVec3::new(0.9, 0.0, 0.0);
    let mut g = c.benchmark_group("degenerate");
    g.sample_size(10).measurement_time(Duration::from_secs(2));
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        let copies = vec![t; n];
        let nested: Vec<[DVec3; 3]> = (0..n)
            .map(|k| t.map(|v| centre + (v - centre) * (1.0 + k as f64 / n as f64)))
            .collect();
        g.bench_function(BenchmarkId::new("copies_build", n), |b| {
            b.iter(|| black_box(Bvh::new(Occluders::from_triangles(copies.clone()))))
        });
        let bvh = Bvh::new(Occluders::from_triangles(copies));
        g.bench_function(BenchmarkId::new("copies_exact", n), |b| {
            b.iter(|| black_box(exact::visibility(&bvh, &light, p).ok()))
        });
        g.bench_function(BenchmarkId::new("nested_build", n), |b| {
            b.iter(|| black_box(Bvh::new(Occluders::from_triangles(nested.clone()))))
        });
        let bvh = Bvh::new(Occluders::from_triangles(nested));
        g.bench_function(BenchmarkId::new("nested_exact", n), |b| {
            b.iter(|| black_box(exact::visibility(&bvh, &light, p).ok()))
        });
        // Copies shifted by 1e-9 a copy (near-coincident: every image's
        // edges nearly on every other's) and layers stacked 1e-4 apart
        // (flat boxes PLOC chained on; their images are homothets about a
        // point outside them, which no one image covers).
        let shifted: Vec<[DVec3; 3]> = (0..n)
            .map(|k| t.map(|v| v + DVec3::new(1e-9 * k as f64, 0.0, 0.0)))
            .collect();
        let stacked: Vec<[DVec3; 3]> = (0..n)
            .map(|k| t.map(|v| v + DVec3::new(0.0, 1e-4 * k as f64, 0.0)))
            .collect();
        g.bench_function(BenchmarkId::new("shifted_build", n), |b| {
            b.iter(|| black_box(Bvh::new(Occluders::from_triangles(shifted.clone()))))
        });
        g.bench_function(BenchmarkId::new("stacked_build", n), |b| {
            b.iter(|| black_box(Bvh::new(Occluders::from_triangles(stacked.clone()))))
        });
        let bvh = Bvh::new(Occluders::from_triangles(shifted));
        g.bench_function(BenchmarkId::new("shifted_exact", n), |b| {
            b.iter(|| black_box(exact::visibility(&bvh, &light, p).ok()))
        });
        if n <= 1_000 {
            let bvh = Bvh::new(Occluders::from_triangles(stacked));
            g.bench_function(BenchmarkId::new("stacked_exact", n), |b| {
                b.iter(|| black_box(exact::visibility(&bvh, &light, p).ok()))
            });
        }
        if n <= 10_000 {
            // Smaller nested triangles under a larger light: none covers it,
            // and their images all cross one side of the clip square.
            let open = Light::sphere(DVec3::new(0.0, 3.0, 0.0), 1.0).expect("a valid light");
            let small: Vec<[DVec3; 3]> = (0..n)
                .map(|k| t.map(|v| centre + (v - centre) * 0.2 * (1.0 + k as f64 / n as f64)))
                .collect();
            let bvh = Bvh::new(Occluders::from_triangles(small));
            let q = DVec3::new(0.3, 0.0, 0.1);
            g.bench_function(BenchmarkId::new("nested_open_exact", n), |b| {
                b.iter(|| black_box(exact::visibility(&bvh, &open, q).ok()))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, default_scene, growth, degenerate);
criterion_main!(benches);
