//! Occlusion-ray corpus and throughput of [`Bvh::segment_unoccluded`]: the
//! Rust half of the opt-in comparison with Intel Embree 4
//! (`benches/compare_embree.sh` runs both halves; not part of CI).
//!
//! `cargo run --release --example ray_corpus --features reference,arbitrary -- [outdir] [rays] [seed]`
//!
//! (defaults: `target/ray_corpus`, 1,000,000 rays per scene, seed 2026).
//!
//! For each of two scenes, deterministically from the seed:
//!
//! - `soup`: 100,000 random triangles of moderate size (corners within
//!   ±0.03 of a centre drawn uniformly in `[-1, 1]² × [0.1, 0.9]`);
//! - `sphere`: a closed geodesic sphere (icosahedron, every face split into
//!   71² triangles: 100,820 triangles, shared corners bit-identical) of
//!   radius 0.45 centred at `(0, 0, 0.5)`;
//!
//! and one batch of occlusion rays: origins uniform on the floor square
//! `[-1.5, 1.5]² × {-0.5}`, ends uniform on the area light `[-0.5, 0.5]² ×
//! {1.5}`; the query is whether the open segment `(p, x)` meets a triangle.
//! Neither endpoint plane meets the geometry, so the open/closed distinction
//! is moot for this corpus.
//!
//! Every coordinate (triangle corners, ray origins and ends) is rounded to
//! `f32` before use and stored as the exactly equal `f64`, so an `f32` engine
//! sees the very same triangles and endpoints; the only differences left are
//! its arithmetic (and the `f32` rounding of the direction `x - p`).
//!
//! # Files written to `outdir`
//!
//! `<scene>.rays` (little-endian throughout):
//!
//! | offset | type | content |
//! |---|---|---|
//! | 0 | `[u8; 8]` | magic `b"SSRAYC1\0"` |
//! | 8 | `u32` | format version, 1 |
//! | 12 | `u32` | reserved, 0 |
//! | 16 | `u64` | seed |
//! | 24 | `u64` | number of triangles `T` |
//! | 32 | `u64` | number of rays `R` |
//! | 40 | `[u8; 8]` | reserved, 0 |
//! | 48 | `[u8; 16]` | scene name, ASCII, NUL-padded |
//! | 64 | `[[[f64; 3]; 3]; T]` | triangle corners (triangle, corner, xyz) |
//! | 64 + 72 T | `[[f64; 3]; R]` | ray origins `p` |
//! | 64 + 72 T + 24 R | `[[f64; 3]; R]` | ray ends `x` |
//!
//! `<scene>.ours.occluded`: `R` bytes, 1 where the open segment is occluded
//! (`segment_unoccluded` returned `false`), 0 where it is not.
//!
//! # Timing
//!
//! The BVH is built once (its build time is printed); then, on a rayon pool
//! of exactly 2 threads, `segment_unoccluded` runs over all rays
//! (`par_chunks` of 4096 rays, one result byte written per ray) once to warm
//! up and 7 more times; the median wall time gives rays/s. As the machine
//! may be shared, the CPU time of the process over each repetition (Linux
//! schedstat, all threads) is measured too: rays per CPU-second is the less
//! noisy measure of per-ray cost when other work competes for the cores.
//! One line per scene starting with `RESULT` is meant for scripts.

use softshadow::arbitrary::mesh::icosphere;
use softshadow::arbitrary::Rng;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::glam::DVec3;
use std::fs;
use std::path::PathBuf;

#[path = "support/corpus.rs"]
mod corpus;
use corpus::{time_occlusion, to_f32, write_rays, THREADS};
use std::time::Instant;

const SOUP_TRIANGLES: usize = 100_000;
const SOUP_HALF_SIZE: f64 = 0.01;
const SPHERE_FREQUENCY: usize = 71;
const SPHERE_CENTRE: DVec3 = DVec3::new(0.0, 0.0, 0.5);
const SPHERE_RADIUS: f64 = 0.45;
const FLOOR_HALF: f64 = 1.5;
const FLOOR_Z: f64 = -0.5;
const LIGHT_HALF: f64 = 0.5;
const LIGHT_Z: f64 = 1.5;

fn soup(rng: &mut Rng) -> Vec<[DVec3; 3]> {
    (0..SOUP_TRIANGLES)
        .map(|_| {
            let c = DVec3::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(0.1, 0.9),
            );
            let mut corner = || {
                let h = SOUP_HALF_SIZE;
                to_f32(c + DVec3::new(rng.uniform(-h, h), rng.uniform(-h, h), rng.uniform(-h, h)))
            };
            [corner(), corner(), corner()]
        })
        .collect()
}

/// A geodesic sphere: each icosahedron face split into `n²` triangles. A
/// grid point is the normalised weighted sum of its face's corners with the
/// non-zero weights taken in global corner order, so a point on an edge or
/// corner shared by two faces comes out bit-identical in both: the mesh is
/// closed (no cracks) after rounding too.
fn geodesic_sphere(n: usize) -> Vec<[DVec3; 3]> {
    // The icosahedron: the level-0 icosphere of the shared generators.
    let base = icosphere(0);
    let corners = base.positions.clone();
    let faces: Vec<[usize; 3]> = base
        .triangles
        .iter()
        .map(|t| t.map(|i| i as usize))
        .collect();
    // Grid point with integer weights `w` on face corners `f`.
    let point = |f: [usize; 3], w: [usize; 3]| {
        let mut terms: Vec<(usize, usize)> = (0..3)
            .filter(|&k| w[k] != 0)
            .map(|k| (f[k], w[k]))
            .collect();
        terms.sort_unstable();
        let mut s = DVec3::ZERO;
        for (v, wv) in terms {
            s += corners[v] * wv as f64;
        }
        to_f32(SPHERE_CENTRE + s.normalize() * SPHERE_RADIUS)
    };
    let mut out = Vec::with_capacity(20 * n * n);
    for f in faces {
        // Point (i, j): weight i on corner 1, j on corner 2, n - i - j on 0.
        let p = |i: usize, j: usize| point(f, [n - i - j, i, j]);
        for i in 0..n {
            for j in 0..n - i {
                out.push([p(i, j), p(i + 1, j), p(i, j + 1)]);
                if i + j + 1 < n {
                    out.push([p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)]);
                }
            }
        }
    }
    out
}

fn rays(rng: &mut Rng, count: usize) -> (Vec<DVec3>, Vec<DVec3>) {
    let mut origins = Vec::with_capacity(count);
    let mut ends = Vec::with_capacity(count);
    for _ in 0..count {
        origins.push(to_f32(DVec3::new(
            rng.uniform(-FLOOR_HALF, FLOOR_HALF),
            rng.uniform(-FLOOR_HALF, FLOOR_HALF),
            FLOOR_Z,
        )));
        ends.push(to_f32(DVec3::new(
            rng.uniform(-LIGHT_HALF, LIGHT_HALF),
            rng.uniform(-LIGHT_HALF, LIGHT_HALF),
            LIGHT_Z,
        )));
    }
    (origins, ends)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let outdir = PathBuf::from(args.next().unwrap_or_else(|| "target/ray_corpus".into()));
    let count: usize = args.next().map_or(1_000_000, |s| s.parse().expect("rays"));
    let seed: u64 = args.next().map_or(2026, |s| s.parse().expect("seed"));
    fs::create_dir_all(&outdir).expect("create outdir");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(THREADS)
        .build()
        .expect("thread pool");

    // Write every corpus first, then time: the files do not depend on the BVH.
    let mut scenes = Vec::new();
    for (index, name) in ["soup", "sphere"].into_iter().enumerate() {
        // One independent stream per scene, so either can change alone.
        let mut rng = Rng::new(seed ^ (0xA076_1D64_78BD_642F_u64.wrapping_mul(index as u64 + 1)));
        let triangles = match name {
            "soup" => soup(&mut rng),
            _ => geodesic_sphere(SPHERE_FREQUENCY),
        };
        let (origins, ends) = rays(&mut rng, count);
        let corpus = outdir.join(format!("{name}.rays"));
        write_rays(&corpus, name, seed, &triangles, &origins, &ends).expect("write corpus");
        println!(
            "{name}: {} triangles, {} rays -> {}",
            triangles.len(),
            count,
            corpus.display()
        );
        scenes.push((name, triangles, origins, ends));
    }

    for (name, triangles, origins, ends) in scenes {
        let start = Instant::now();
        let bvh = Bvh::new(Occluders::from_triangles(triangles));
        println!(
            "{name}: BVH built in {:.1} ms",
            start.elapsed().as_secs_f64() * 1e3
        );

        time_occlusion(&pool, &bvh, &origins, &ends, &outdir, name);
    }
}
