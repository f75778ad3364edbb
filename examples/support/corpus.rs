//! What the ray-corpus examples (`ray_corpus.rs`, `primary_corpus.rs`,
//! `mc_corpus.rs`) share, included with `#[path]`: the rounding of the corpus to `f32`, and
//! the timing — warm-up runs, then the median wall and CPU time of repeated
//! runs on the same thread count, and the two report lines the comparison
//! scripts read.

use softshadow::glam::DVec3;
use std::io::Write;

/// Threads our side runs on (Embree's side runs as many processes).
pub const THREADS: usize = 2;
/// Untimed runs before the timed ones.
pub const WARMUPS: usize = 1;
/// Timed runs; the medians are reported.
pub const REPETITIONS: usize = 7;

/// The nearest `f32` value, as an `f64` (exactly representable in both).
pub fn to_f32(v: DVec3) -> DVec3 {
    DVec3::new(
        f64::from(v.x as f32),
        f64::from(v.y as f32),
        f64::from(v.z as f32),
    )
}

/// CPU time consumed so far by all threads of this process, in
/// nanoseconds (Linux: the first field of `/proc/self/task/*/schedstat`);
/// `None` where that is unavailable.
fn cpu_ns() -> Option<u64> {
    let mut total = 0;
    for entry in std::fs::read_dir("/proc/self/task").ok()? {
        let text = std::fs::read_to_string(entry.ok()?.path().join("schedstat")).ok()?;
        total += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total)
}

/// The median (the upper one for an even count) of a non-empty list.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Wall and CPU seconds of repeated runs.
pub struct Timing {
    /// Median wall time.
    pub median: f64,
    /// Least wall time.
    pub min: f64,
    /// Greatest wall time.
    pub max: f64,
    /// Median CPU time over all threads, where the platform reports it.
    pub cpu: Option<f64>,
    repetitions: usize,
}

/// Runs `run` `warmups` times untimed, then `repetitions` times timed.
pub fn time_runs(warmups: usize, repetitions: usize, mut run: impl FnMut()) -> Timing {
    for _ in 0..warmups {
        run();
    }
    let (times, cpus): (Vec<f64>, Vec<Option<f64>>) = (0..repetitions)
        .map(|_| {
            let cpu = cpu_ns();
            let start = std::time::Instant::now();
            run();
            let wall = start.elapsed().as_secs_f64();
            (wall, cpu_ns().zip(cpu).map(|(b, a)| (b - a) as f64 * 1e-9))
        })
        .unzip();
    Timing {
        median: median(times.clone()),
        min: times.iter().copied().fold(f64::INFINITY, f64::min),
        max: times.iter().copied().fold(0.0, f64::max),
        cpu: cpus.into_iter().collect::<Option<Vec<f64>>>().map(median),
        repetitions,
    }
}

impl Timing {
    /// Prints the human line and the `RESULT` line of `scene`: `count` rays
    /// of which `hits` hit (`what`: "hit", "occluded"), on `threads`
    /// threads, over `triangles` triangles.
    pub fn report(
        &self,
        scene: &str,
        what: &str,
        count: usize,
        hits: usize,
        threads: usize,
        triangles: usize,
    ) {
        let rate = count as f64 / self.median;
        println!(
            "{scene}: {what} {hits} of {count} ({:.2}%), median {:.1} ms over {} \
             (min {:.1}, max {:.1}) on {threads} threads: {:.3} Mrays/s; CPU time {}",
            100.0 * hits as f64 / count as f64,
            self.median * 1e3,
            self.repetitions,
            self.min * 1e3,
            self.max * 1e3,
            rate / 1e6,
            self.cpu.map_or("unknown".into(), |c| format!(
                "{:.1} ms: {:.3} Mrays per CPU-second",
                c * 1e3,
                count as f64 / c / 1e6
            ))
        );
        println!(
            "RESULT scene={scene} triangles={triangles} rays={count} hits={hits} median_s={:.6} \
             min_s={:.6} rays_per_s={rate:.0} cpu_s={} rays_per_cpu_s={} threads={threads}",
            self.median,
            self.min,
            self.cpu.map_or("-".into(), |c| format!("{c:.6}")),
            self.cpu
                .map_or("-".into(), |c| format!("{:.0}", count as f64 / c)),
        );
    }
}

/// The tail every corpus file shares after its own header fields: a
/// 16-byte NUL-padded `label`, then every triangle corner and every point
/// of `points` (in order) as three little-endian `f64`s; flushes `w`.
pub fn write_label_and_points<'a>(
    w: &mut impl Write,
    label: &str,
    triangles: &'a [[DVec3; 3]],
    points: impl IntoIterator<Item = &'a DVec3>,
) -> std::io::Result<()> {
    let mut padded = [0u8; 16];
    padded[..label.len()].copy_from_slice(label.as_bytes());
    w.write_all(&padded)?;
    for &v in triangles.iter().flatten().chain(points) {
        for c in v.to_array() {
            w.write_all(&c.to_le_bytes())?;
        }
    }
    w.flush()
}

/// Writes an occlusion-ray corpus (the format in `ray_corpus.rs`): the
/// header, the triangles, then the ray origins and the ray ends.
#[allow(dead_code)] // primary_corpus.rs writes its own format
pub fn write_rays(
    path: &std::path::Path,
    name: &str,
    seed: u64,
    triangles: &[[DVec3; 3]],
    origins: &[DVec3],
    ends: &[DVec3],
) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    w.write_all(b"SSRAYC1\0")?;
    w.write_all(&1u32.to_le_bytes())?;
    w.write_all(&0u32.to_le_bytes())?;
    w.write_all(&seed.to_le_bytes())?;
    w.write_all(&(triangles.len() as u64).to_le_bytes())?;
    w.write_all(&(origins.len() as u64).to_le_bytes())?;
    w.write_all(&[0u8; 8])?;
    write_label_and_points(&mut w, name, triangles, origins.iter().chain(ends))
}

/// Times `Bvh::segment_unoccluded` over the segments `origins[i] → ends[i]`
/// on `pool` (chunks of 4096), writes the answers to
/// `outdir/<name>.ours.occluded` (one byte per ray, 1 where occluded) and
/// prints the report lines.
#[allow(dead_code)] // primary_corpus.rs times closest hits
pub fn time_occlusion(
    pool: &rayon::ThreadPool,
    bvh: &softshadow::bvh::Bvh,
    origins: &[DVec3],
    ends: &[DVec3],
    outdir: &std::path::Path,
    name: &str,
) {
    use rayon::prelude::*;
    const CHUNK: usize = 4096;
    let segments: Vec<(DVec3, DVec3)> = origins.iter().copied().zip(ends.iter().copied()).collect();
    let mut occluded = vec![0u8; segments.len()];
    let timing = time_runs(WARMUPS, REPETITIONS, || {
        pool.install(|| {
            occluded
                .par_chunks_mut(CHUNK)
                .zip(segments.par_chunks(CHUNK))
                .for_each(|(out, segs)| {
                    for (o, &(p, x)) in out.iter_mut().zip(segs) {
                        *o = u8::from(!bvh.segment_unoccluded(p, x));
                    }
                });
        });
    });
    let hits = occluded.iter().filter(|&&o| o == 1).count();
    std::fs::write(outdir.join(format!("{name}.ours.occluded")), &occluded).expect("write results");
    let triangles = bvh.occluders().len();
    timing.report(name, "occluded", segments.len(), hits, THREADS, triangles);
}
