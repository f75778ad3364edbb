//! Monte Carlo's own rays as a corpus, and its throughput as a workload:
//! the Rust half of the opt-in comparison with Intel Embree 4 on the rays
//! the Monte Carlo reference casts (`benches/compare_embree_mc.sh` runs
//! both halves; not part of CI).
//!
//! `cargo run --release --example mc_corpus --features reference,scene-file -- [outdir] [receivers] [samples] [with-floor]`
//!
//! (defaults: `target/mc_corpus`, 256 receivers, 4096 samples each, no
//! floor).
//!
//! The scene is the default one (the bunny under a sphere light) without
//! its floor, which holds the receivers (a segment from a floor point to
//! the light meets the floor only at that point, which the open segment
//! excludes, but Embree's robust mode counts hits at `t = 0`; `with-floor`
//! keeps it, for timing ours as the reference runs: every ray then starts
//! on a floor triangle and tests it), every
//! triangle corner rounded to `f32` (so that an `f32` engine sees the very
//! same triangles); the receivers are floor points of a 64 × 64 grid around
//! the bunny's shadow (`scene::builtin::floor_receivers`, rounded to `f32`)
//! that lie in the exact penumbra (`definitions::in_penumbra` on the rounded
//! triangles), evenly spaced among them. The rays are the segments from
//! each receiver to the light points `monte_carlo::sample_points` lists
//! for it — the rays `monte_carlo::visibility` casts, in its order — their
//! ends rounded to `f32` for the corpus.
//!
//! Writes `outdir/mc-default.rays` in the format of `examples/ray_corpus.rs`
//! (scene name `mc-default`, seed field = the Monte Carlo seed) and
//! `outdir/mc-default.ours.occluded` (one byte per ray, 1 where occluded).
//!
//! Timing, on a rayon pool of exactly 2 threads, one warm-up and 7 timed
//! runs, medians (wall and CPU time, as `ray_corpus`):
//!
//! - `mc-default`: `Bvh::segment_unoccluded` over the corpus rays, chunks
//!   of 4096 — the figure the script sets beside Embree's on the same rays;
//! - `mc-default-workload`: `monte_carlo::visibility_many` over the
//!   receivers (sample generation, the light's point mapping and the
//!   estimate included): the reference as users run it, per ray cast.

use softshadow::bvh::{Bvh, Occluders};
use softshadow::definitions::in_penumbra;
use softshadow::glam::DVec3;
use softshadow::reference::exact;
use softshadow::reference::monte_carlo::{self, Options};
use softshadow::scene::builtin::{builtin, floor_receivers};
use std::fs;
use std::path::PathBuf;

#[path = "support/corpus.rs"]
mod corpus;
use corpus::{time_occlusion, time_runs, to_f32, write_rays, REPETITIONS, THREADS, WARMUPS};

const NAME: &str = "mc-default";
const GRID: usize = 64;

fn main() {
    let mut args = std::env::args().skip(1);
    let outdir = PathBuf::from(args.next().unwrap_or_else(|| "target/mc_corpus".into()));
    let wanted: usize = args.next().map_or(256, |s| s.parse().expect("receivers"));
    let samples: u32 = args.next().map_or(4096, |s| s.parse().expect("samples"));
    let with_floor = args.next().is_some_and(|s| s == "with-floor");
    fs::create_dir_all(&outdir).expect("create outdir");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(THREADS)
        .build()
        .expect("thread pool");

    let scene = builtin("default").expect("the default scene");
    let light = *scene.light();
    // Without the floor (mesh 0), which holds every receiver: it cannot
    // meet a segment from a point on it to the light above it except at
    // that point, which the open segment excludes — but a ray tracer that
    // counts hits at `t = 0` (Embree in its robust mode) would find it on
    // every ray.
    let first = usize::from(!with_floor);
    let triangles: Vec<[DVec3; 3]> = Occluders::from_meshes(&scene.meshes()[first..])
        .triangles()
        .iter()
        .map(|t| t.map(to_f32))
        .collect();
    let bvh = Bvh::new(Occluders::from_triangles(triangles.clone()));
    let penumbra: Vec<DVec3> = floor_receivers(&scene, GRID)
        .into_iter()
        .map(to_f32)
        .filter(|&p| matches!(exact::visibility(&bvh, &light, p), Ok(v) if in_penumbra(v)))
        .collect();
    let step = (penumbra.len() as f64 / wanted as f64).max(1.0);
    let receivers: Vec<DVec3> = (0..wanted.min(penumbra.len()))
        .map(|k| penumbra[(k as f64 * step) as usize])
        .collect();
    let options = Options::new(samples);
    let (mut origins, mut ends) = (Vec::new(), Vec::new());
    for &p in &receivers {
        let emitter = light.emitter(p).expect("a receiver outside the light");
        for x in monte_carlo::sample_points(&emitter, p, &options) {
            origins.push(p);
            ends.push(to_f32(x));
        }
    }
    let count = origins.len();
    let path = outdir.join(format!("{NAME}.rays"));
    write_rays(&path, NAME, options.seed, &triangles, &origins, &ends).expect("write corpus");
    println!(
        "{NAME}: {} triangles, {} penumbra receivers of {} floor points, {} rays ({} samples each) -> {}",
        triangles.len(),
        receivers.len(),
        GRID * GRID,
        count,
        samples,
        path.display()
    );

    time_occlusion(&pool, &bvh, &origins, &ends, &outdir, NAME);

    let mut estimates = Vec::new();
    let timing = time_runs(WARMUPS, REPETITIONS, || {
        estimates =
            pool.install(|| monte_carlo::visibility_many(&bvh, &light, &receivers, &options));
    });
    // The workload's rays unoccluded, from the estimates: each is its
    // replicates' mean, so `V · rays` per receiver, summed.
    let per = count / receivers.len().max(1);
    let lit: f64 = estimates
        .iter()
        .map(|e| e.as_ref().expect("an estimate").visibility * per as f64)
        .sum();
    let hits = count - lit.round() as usize;
    timing.report(
        &format!("{NAME}-workload"),
        "occluded",
        count,
        hits,
        THREADS,
        triangles.len(),
    );
}
