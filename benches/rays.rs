//! Occlusion rays per second of the Monte Carlo reference's BVH, on two
//! threads (rayon), over a batch of 64k rays from points on a floor below
//! the geometry to points on a disk light above it.
//!
//! Scenes: a soup of 100k random small triangles, and a closed UV sphere of
//! 100k triangles. Each is traced by
//!
//! - `softshadow`: [`Bvh::segment_unoccluded`], our conservative 4-wide
//!   traversal over obvhs's PLOC tree, exact `f64` triangle test;
//! - `obvhs_bvh2`, `obvhs_cwbvh`: obvhs 0.4's own `ray_traverse_miss` over its
//!   `Bvh2` / `CwBvh` with the same exact triangle test (for comparison only:
//!   their `f32` node tests are not conservative).
//!
//! Closest hits ([`Bvh::closest_hit`]), also on two threads:
//!
//! - `closest/primary`: the renderer's primary rays, one per pixel of the
//!   default scene's 512 × 512 camera (pinhole through pixel centres, as in
//!   `examples/primary_corpus.rs`), rayon over rows, one call per ray;
//! - `closest/primary_rows`: the same rays, one [`Bvh::closest_hits`] batch
//!   per row, as the renderer calls it;
//! - `closest/soup`, `closest/sphere`: the occlusion rays above as rays
//!   (origin `p`, direction `x − p`, `t_max = 1`).
//!
//! `cargo bench --features reference,scene-file --bench rays`; figures in
//! `benches/README.md`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::ray::Ray;
use obvhs::BvhBuildParams;
use rayon::prelude::*;
use softshadow::arbitrary::Rng;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::glam::{DVec3, Vec3A};
use softshadow::kernel::segment::segment_blocked;
use softshadow::scene::Camera;
use std::hint::black_box;
use std::time::Duration;

const RAYS: usize = 1 << 16;
const TRIANGLES: usize = 100_000;
const THREADS: usize = 2;

/// 100k triangles, centres uniform in `[−1, 1]² × [0, 2]`, corners within
/// ±0.03 of the centre.
fn soup() -> Vec<[DVec3; 3]> {
    let mut rng = Rng::new(1);
    (0..TRIANGLES)
        .map(|_| {
            let c = DVec3::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(0.0, 2.0),
            );
            let mut corner = || {
                c + DVec3::new(
                    rng.uniform(-0.03, 0.03),
                    rng.uniform(-0.03, 0.03),
                    rng.uniform(-0.03, 0.03),
                )
            };
            [corner(), corner(), corner()]
        })
        .collect()
}

/// A closed UV sphere of radius 1 around `(0, 0, 1)`: 224 rings of 224
/// quads, fans at the poles (100 352 triangles).
fn sphere() -> Vec<[DVec3; 3]> {
    let (rings, segments) = (224usize, 224usize);
    let at = |i: usize, j: usize| {
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        let phi = 2.0 * std::f64::consts::PI * (j % segments) as f64 / segments as f64;
        DVec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            1.0 + theta.cos(),
        )
    };
    let mut out = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if i != 0 {
                out.push([a, b, d]);
            }
            if i != rings - 1 {
                out.push([b, c, d]);
            }
        }
    }
    out
}

/// Rays from the floor `z = −0.5` (`[−1.5, 1.5]²`) to a disk light of radius
/// 0.5 at height 3.
fn rays() -> Vec<(DVec3, DVec3)> {
    let mut rng = Rng::new(2);
    (0..RAYS)
        .map(|_| {
            let p = DVec3::new(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), -0.5);
            let (r, a) = (
                0.5 * rng.unit().sqrt(),
                2.0 * std::f64::consts::PI * rng.unit(),
            );
            (p, DVec3::new(r * a.cos(), r * a.sin(), 3.0))
        })
        .collect()
}

fn boxes(triangles: &[[DVec3; 3]]) -> Vec<Aabb> {
    triangles
        .iter()
        .map(|t| {
            let v = t.map(|v| Vec3A::from(v.as_vec3()));
            Aabb::new(v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]))
        })
        .collect()
}

/// The obvhs ray of a segment, `t ∈ [0, 1)`.
fn ray(p: DVec3, x: DVec3) -> Ray {
    Ray::new(
        Vec3A::from(p.as_vec3()),
        Vec3A::from((x - p).as_vec3()),
        0.0,
        1.0,
    )
}

/// Counts the unoccluded rays, in parallel chunks.
fn count(rays: &[(DVec3, DVec3)], unoccluded: impl Fn(DVec3, DVec3) -> bool + Sync) -> usize {
    rays.par_chunks(1024)
        .map(|c| c.iter().filter(|&&(p, x)| unoccluded(p, x)).count())
        .sum()
}

/// One ray per pixel of `camera`, row by row: pinhole, pixel centres, row 0
/// at the top (as `examples/primary_corpus.rs` documents).
fn camera_rays(camera: &Camera) -> Vec<(DVec3, DVec3)> {
    camera
        .primary_rays()
        .map(|(eye, d)| (eye, d.normalize()))
        .collect()
}

/// Counts the hits of `rays` (`t_max`), rayon over chunks of `chunk` rays.
fn count_hits(bvh: &Bvh, rays: &[(DVec3, DVec3)], t_max: f64, chunk: usize) -> usize {
    rays.par_chunks(chunk)
        .map(|c| {
            c.iter()
                .filter(|&&(o, d)| bvh.closest_hit(o, d, t_max).is_some())
                .count()
        })
        .sum()
}

fn closest(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(THREADS)
        .build()
        .unwrap();
    let scene = softshadow::scene::builtin("default").expect("default scene");
    let camera = *scene.camera().expect("camera");
    let width = camera.resolution().0 as usize;
    let primary = camera_rays(&camera);
    let bvh = Bvh::new(Occluders::from_scene(&scene));
    let mut group = c.benchmark_group("closest");
    group
        .throughput(Throughput::Elements(primary.len() as u64))
        .measurement_time(Duration::from_secs(4))
        .sample_size(20);
    group.bench_function("primary", |b| {
        b.iter(|| pool.install(|| count_hits(&bvh, black_box(&primary), f64::INFINITY, width)))
    });
    group.bench_function("primary_rows", |b| {
        b.iter(|| {
            pool.install(|| {
                black_box(&primary)
                    .par_chunks(width)
                    .map_init(Vec::new, |hits, row| {
                        bvh.closest_hits(row, f64::INFINITY, hits);
                        hits.iter().filter(|h| h.is_some()).count()
                    })
                    .sum::<usize>()
            })
        })
    });
    let segments: Vec<(DVec3, DVec3)> = rays().into_iter().map(|(p, x)| (p, x - p)).collect();
    group.throughput(Throughput::Elements(RAYS as u64));
    for (name, triangles) in [("soup", soup()), ("sphere", sphere())] {
        let bvh = Bvh::new(Occluders::from_triangles(triangles));
        group.bench_function(name, |b| {
            b.iter(|| pool.install(|| count_hits(&bvh, black_box(&segments), 1.0, 1024)))
        });
    }
    group.finish();
}

fn bench(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(THREADS)
        .build()
        .unwrap();
    let rays = rays();
    for (name, triangles) in [("soup", soup()), ("sphere", sphere())] {
        let bvh = Bvh::new(Occluders::from_triangles(triangles.clone()));
        let aabbs = boxes(&triangles);
        let params = BvhBuildParams::medium_build();
        let bvh2 = build_bvh2(&aabbs, params, &mut Duration::default());
        let cwbvh = build_cwbvh(&aabbs, params, &mut Duration::default());
        let exact = |p: DVec3, x: DVec3, i: u32| {
            if segment_blocked(p, x, &triangles[i as usize]) {
                0.5
            } else {
                f32::INFINITY
            }
        };
        // The three traversals must agree here (rays far from grazing).
        let ours = pool.install(|| count(&rays, |p, x| bvh.segment_unoccluded(p, x)));
        let theirs = pool.install(|| {
            count(&rays, |p, x| {
                cwbvh.ray_traverse_miss(ray(p, x), |_, i| exact(p, x, cwbvh.primitive_indices[i]))
            })
        });
        assert_eq!(ours, theirs, "{name}");
        println!(
            "{name}: {} triangles, {:.1} % of rays unoccluded",
            triangles.len(),
            100.0 * ours as f64 / RAYS as f64
        );

        let mut group = c.benchmark_group(format!("rays/{name}"));
        group
            .throughput(Throughput::Elements(RAYS as u64))
            .measurement_time(Duration::from_secs(4))
            .sample_size(20);
        group.bench_function("softshadow", |b| {
            b.iter(|| pool.install(|| count(black_box(&rays), |p, x| bvh.segment_unoccluded(p, x))))
        });
        group.bench_function("obvhs_bvh2", |b| {
            b.iter(|| {
                pool.install(|| {
                    count(black_box(&rays), |p, x| {
                        bvh2.ray_traverse_miss(ray(p, x), |_, i| {
                            exact(p, x, bvh2.primitive_indices[i])
                        })
                    })
                })
            })
        });
        group.bench_function("obvhs_cwbvh", |b| {
            b.iter(|| {
                pool.install(|| {
                    count(black_box(&rays), |p, x| {
                        cwbvh.ray_traverse_miss(ray(p, x), |_, i| {
                            exact(p, x, cwbvh.primitive_indices[i])
                        })
                    })
                })
            })
        });
        group.finish();
    }
}

criterion_group!(benches, bench, closest);
criterion_main!(benches);
