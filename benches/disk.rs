//! Disk-occlusion kernels against a Möller–Trumbore ray–triangle test in the
//! same group: the kernel's goal is to cost at most twice one ray–triangle
//! test, the unit of work of the Monte Carlo reference it replaces. The
//! batched `segment_disk_areas` writes its areas to a reused vector (the
//! vector is the result; nothing is summed), the per-edge loops sum theirs.
//!
//! `cargo bench --bench disk`; figures in `benches/README.md`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use softshadow::arbitrary::disk::{clipped_edge, disk_edge};
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3, Vec2, Vec3};
use softshadow::kernel::disk::{f32 as k32, f64 as k64};
use std::hint::black_box;
use std::time::Duration;

const N: usize = 4096;

/// Edges of a typical receiver view: endpoints uniform in a box four radii
/// wide around the unit disk (a mix of edges inside, crossing and outside).
fn box_edges() -> Vec<(DVec2, DVec2)> {
    let mut rng = Rng::new(1);
    let mut p = move || DVec2::new(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0));
    (0..N).map(|_| (p(), p())).collect()
}

/// The stiff generator of the property tests, scaled to the unit disk.
fn stiff_edges() -> Vec<(DVec2, DVec2)> {
    let mut rng = Rng::new(2);
    (0..N)
        .map(|_| {
            let c = disk_edge(&mut rng);
            (c.a / c.r, c.b / c.r)
        })
        .collect()
}

struct Ray {
    origin: DVec3,
    dir: DVec3,
}

/// Rays from around the origin toward triangles near `z = 5`: about half hit.
fn rays_and_triangles() -> Vec<(Ray, [DVec3; 3])> {
    let mut rng = Rng::new(3);
    (0..N)
        .map(|_| {
            let mut v = || {
                DVec3::new(
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(-1.0, 1.0),
                    5.0 + rng.uniform(-0.5, 0.5),
                )
            };
            let tri = [v(), v(), v()];
            let origin = DVec3::new(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 0.0);
            let target = DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 5.0);
            (
                Ray {
                    origin,
                    dir: target - origin,
                },
                tri,
            )
        })
        .collect()
}

macro_rules! moller_trumbore {
    ($name:ident, $T:ty, $V3:ty) => {
        /// Möller–Trumbore (1997): the hit distance in `(0, t_max)`, if any.
        #[inline]
        fn $name(origin: $V3, dir: $V3, t_max: $T, v: &[$V3; 3]) -> Option<$T> {
            let e1 = v[1] - v[0];
            let e2 = v[2] - v[0];
            let p = dir.cross(e2);
            let det = e1.dot(p);
            if det == 0.0 {
                return None;
            }
            let inv = 1.0 / det;
            let s = origin - v[0];
            let u = s.dot(p) * inv;
            if !(0.0..=1.0).contains(&u) {
                return None;
            }
            let q = s.cross(e1);
            let w = dir.dot(q) * inv;
            if w < 0.0 || u + w > 1.0 {
                return None;
            }
            let t = e2.dot(q) * inv;
            (t > 0.0 && t < t_max).then_some(t)
        }
    };
}
moller_trumbore!(moller_trumbore_f64, f64, DVec3);
moller_trumbore!(moller_trumbore_f32, f32, Vec3);

fn disk_vs_ray(c: &mut Criterion) {
    let mut group = c.benchmark_group("disk_vs_ray");
    group
        .throughput(Throughput::Elements(N as u64))
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_secs(1))
        .sample_size(30);

    let rays = rays_and_triangles();
    group.bench_function("moller_trumbore/f64", |b| {
        b.iter(|| {
            let mut hits = 0usize;
            for (ray, tri) in black_box(&rays) {
                hits += moller_trumbore_f64(ray.origin, ray.dir, 1.0, tri).is_some() as usize;
            }
            hits
        })
    });
    let rays32: Vec<(Vec3, Vec3, [Vec3; 3])> = rays
        .iter()
        .map(|(r, t)| (r.origin.as_vec3(), r.dir.as_vec3(), t.map(|v| v.as_vec3())))
        .collect();
    group.bench_function("moller_trumbore/f32", |b| {
        b.iter(|| {
            let mut hits = 0usize;
            for (o, d, tri) in black_box(&rays32) {
                hits += moller_trumbore_f32(*o, *d, 1.0, tri).is_some() as usize;
            }
            hits
        })
    });

    for (label, edges) in [("box", box_edges()), ("stiff", stiff_edges())] {
        group.bench_with_input(
            BenchmarkId::new("segment_disk_area/f64", label),
            &edges,
            |b, e| {
                b.iter(|| {
                    let mut sum = 0.0;
                    for &(p, q) in black_box(e) {
                        sum += k64::segment_disk_area(1.0, p, q);
                    }
                    sum
                })
            },
        );
        let mut areas = Vec::with_capacity(N);
        group.bench_with_input(
            BenchmarkId::new("segment_disk_areas/f64", label),
            &edges,
            |b, e| {
                b.iter(|| {
                    k64::segment_disk_areas(1.0, black_box(e), &mut areas);
                    black_box(&areas);
                })
            },
        );
        let edges32: Vec<(Vec2, Vec2)> = edges
            .iter()
            .map(|(p, q)| (p.as_vec2(), q.as_vec2()))
            .collect();
        group.bench_with_input(
            BenchmarkId::new("segment_disk_area/f32", label),
            &edges32,
            |b, e| {
                b.iter(|| {
                    let mut sum = 0.0f32;
                    for &(p, q) in black_box(e) {
                        sum += k32::segment_disk_area(1.0, p, q);
                    }
                    sum
                })
            },
        );
        let mut areas32 = Vec::with_capacity(N);
        group.bench_with_input(
            BenchmarkId::new("segment_disk_areas/f32", label),
            &edges32,
            |b, e| {
                b.iter(|| {
                    k32::segment_disk_areas(1.0, black_box(e), &mut areas32);
                    black_box(&areas32);
                })
            },
        );
    }

    let mut rng = Rng::new(4);
    let clipped: Vec<(f64, f64, f64)> = (0..N).map(|_| clipped_edge(&mut rng)).collect();
    group.bench_function("circle_segment_occlusion/f64", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for &(d, w0, w1) in black_box(&clipped) {
                sum += k64::circle_segment_occlusion(d, w0, w1);
            }
            sum
        })
    });
    let clipped32: Vec<(f32, f32, f32)> = clipped
        .iter()
        .map(|&(d, a, b)| (d as f32, a as f32, b as f32))
        .collect();
    group.bench_function("circle_segment_occlusion/f32", |b| {
        b.iter(|| {
            let mut sum = 0.0f32;
            for &(d, w0, w1) in black_box(&clipped32) {
                sum += k32::circle_segment_occlusion(d, w0, w1);
            }
            sum
        })
    });
    let mut occlusions = Vec::with_capacity(N);
    group.bench_function("circle_segment_occlusions/f64", |b| {
        b.iter(|| {
            k64::circle_segment_occlusions(black_box(&clipped), &mut occlusions);
            black_box(&occlusions);
        })
    });
    let mut occlusions32 = Vec::with_capacity(N);
    group.bench_function("circle_segment_occlusions/f32", |b| {
        b.iter(|| {
            k32::circle_segment_occlusions(black_box(&clipped32), &mut occlusions32);
            black_box(&occlusions32);
        })
    });
    group.finish();

    // Whole polygons: projected triangles (3 edges each) in the box.
    let mut group = c.benchmark_group("polygon_disk_area");
    group
        .throughput(Throughput::Elements(N as u64))
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_secs(1))
        .sample_size(30);
    let mut rng = Rng::new(5);
    let triangles: Vec<[DVec2; 3]> = (0..N)
        .map(|_| {
            let mut p = || DVec2::new(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0));
            [p(), p(), p()]
        })
        .collect();
    group.bench_function("triangle/f64", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for t in black_box(&triangles) {
                sum += k64::polygon_disk_area(1.0, t);
            }
            sum
        })
    });
    group.finish();
}

criterion_group!(benches, disk_vs_ray);
criterion_main!(benches);
