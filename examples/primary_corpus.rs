//! Primary-ray corpus and throughput of [`Bvh::closest_hits`] on the default
//! scene: the Rust half of the opt-in closest-hit comparison with Intel
//! Embree 4 (`benches/compare_embree_primary.sh` runs both halves; not part
//! of CI).
//!
//! `cargo run --release --example primary_corpus --features reference,scene-file -- [outdir]`
//!
//! (default `target/ray_corpus`).
//!
//! # The rays
//!
//! One ray per pixel of the default scene's camera (the Stanford bunny over
//! a floor, 3676 triangles; camera 512 × 512, 45° vertical field of view),
//! the renderer's own primary rays (`Camera::primary_ray`: pinhole, pixel
//! centres, row 0 at the top), directions normalised. Rays are stored row by
//! row. The
//! query is the closest hit with `t ∈ (0, ∞)`.
//!
//! As in `examples/ray_corpus.rs`, every coordinate (triangle corners, the
//! eye, the directions) is rounded to `f32` before use and stored as the
//! exactly equal `f64`, so Embree sees the very same triangles and rays.
//!
//! # Files written to `outdir`
//!
//! `primary.rays` (little-endian throughout):
//!
//! | offset | type | content |
//! |---|---|---|
//! | 0 | `[u8; 8]` | magic `b"SSPRIM1\0"` |
//! | 8 | `u32` | format version, 1 |
//! | 12 | `u32` | reserved, 0 |
//! | 16 | `u32`, `u32` | image width, height |
//! | 24 | `u64` | number of triangles `T` |
//! | 32 | `u64` | number of rays `R` (width × height) |
//! | 40 | `[u8; 8]` | reserved, 0 |
//! | 48 | `[u8; 16]` | scene name, ASCII, NUL-padded |
//! | 64 | `[[[f64; 3]; 3]; T]` | triangle corners (triangle, corner, xyz) |
//! | 64 + 72 T | `[[f64; 3]; R]` | ray origins |
//! | 64 + 72 T + 24 R | `[[f64; 3]; R]` | ray directions (unit length before rounding) |
//!
//! `primary.ours.hits`: `[f64; R]`, the hit's `t` (`+∞` for a miss), then
//! `[u32; R]`, the triangle (`u32::MAX` for a miss).
//!
//! # Timing
//!
//! The BVH is built once (its build time is printed); then, on a rayon pool
//! of exactly 2 threads, [`Bvh::closest_hits`] runs for every image row,
//! rayon over rows, as the renderer calls it (one `Hit` stored per pixel;
//! the same answers as [`Bvh::closest_hit`] per ray), once to warm up
//! and 7 more times; the median wall time gives rays/s, and the median CPU
//! time of the process over each repetition (Linux schedstat, all threads)
//! rays per CPU-second. One line starting with `RESULT` is meant for
//! scripts.

use rayon::prelude::*;
use softshadow::bvh::{Bvh, Hit, Occluders};
use softshadow::glam::DVec3;
use softshadow::scene::Camera;
use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

#[path = "support/corpus.rs"]
mod corpus;
use corpus::{time_runs, to_f32, write_label_and_points, REPETITIONS, THREADS, WARMUPS};
use std::time::Instant;

const MAGIC: &[u8; 8] = b"SSPRIM1\0";
const VERSION: u32 = 1;

/// The camera's rays, row by row (see the module docs), rounded to `f32`.
fn camera_rays(camera: &Camera) -> Vec<(DVec3, DVec3)> {
    camera
        .primary_rays()
        .map(|(eye, d)| (to_f32(eye), to_f32(d.normalize())))
        .collect()
}

fn write_corpus(
    path: &Path,
    (width, height): (u32, u32),
    triangles: &[[DVec3; 3]],
    rays: &[(DVec3, DVec3)],
) -> std::io::Result<()> {
    let mut w = BufWriter::new(File::create(path)?);
    w.write_all(MAGIC)?;
    w.write_all(&VERSION.to_le_bytes())?;
    w.write_all(&0u32.to_le_bytes())?;
    w.write_all(&width.to_le_bytes())?;
    w.write_all(&height.to_le_bytes())?;
    w.write_all(&(triangles.len() as u64).to_le_bytes())?;
    w.write_all(&(rays.len() as u64).to_le_bytes())?;
    w.write_all(&[0u8; 8])?;
    let origins: Vec<DVec3> = rays.iter().map(|&(o, _)| o).collect();
    let directions = rays.iter().map(|(_, d)| d);
    write_label_and_points(
        &mut w,
        "default",
        triangles,
        origins.iter().chain(directions),
    )
}

fn write_hits(path: &Path, hits: &[Option<Hit>]) -> std::io::Result<()> {
    let mut w = BufWriter::new(File::create(path)?);
    for h in hits {
        w.write_all(&h.map_or(f64::INFINITY, |h| h.t).to_le_bytes())?;
    }
    for h in hits {
        w.write_all(&h.map_or(u32::MAX, |h| h.triangle).to_le_bytes())?;
    }
    w.flush()
}

fn main() {
    let outdir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "target/ray_corpus".into()),
    );
    fs::create_dir_all(&outdir).expect("create outdir");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(THREADS)
        .build()
        .expect("thread pool");

    let scene = softshadow::scene::builtin("default").expect("the default scene");
    let camera = *scene.camera().expect("the default scene's camera");
    let (width, height) = camera.resolution();
    let triangles: Vec<[DVec3; 3]> = Occluders::from_scene(&scene)
        .triangles()
        .iter()
        .map(|t| t.map(to_f32))
        .collect();
    let rays = camera_rays(&camera);
    let corpus = outdir.join("primary.rays");
    write_corpus(&corpus, (width, height), &triangles, &rays).expect("write corpus");
    println!(
        "default: {} triangles, {width} x {height} primary rays -> {}",
        triangles.len(),
        corpus.display()
    );

    let start = Instant::now();
    let bvh = Bvh::new(Occluders::from_triangles(triangles));
    println!(
        "default: BVH built in {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );

    let count = rays.len();
    // One buffer per row, reused by every repetition.
    let mut rows: Vec<Vec<Option<Hit>>> = vec![Vec::new(); height as usize];
    let timing = time_runs(WARMUPS, REPETITIONS, || {
        pool.install(|| {
            rows.par_iter_mut()
                .zip(rays.par_chunks(width as usize))
                .for_each(|(out, row)| bvh.closest_hits(row, f64::INFINITY, out));
        });
    });
    let hits: Vec<Option<Hit>> = rows.concat();
    let hit_count = hits.iter().filter(|h| h.is_some()).count();
    write_hits(&outdir.join("primary.ours.hits"), &hits).expect("write results");
    let triangles = bvh.occluders().len();
    timing.report("primary", "hit", count, hit_count, THREADS, triangles);
}
