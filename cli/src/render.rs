//! `softshadow render` (one method, PNG files) and the default run (every
//! available method on the default scene, a table of errors against the
//! exact answer).

use crate::visibility::{method_with_seed, parse_method, resolve_scene, run_method};
use softshadow::method::{self, Exact, Method};
use softshadow::render::image::{
    error_heat_map, in_penumbra, shaded, shaded_by_ends, visibility_image, ErrorRow,
};
use softshadow::render::{Frame, Stages, Stats};
use softshadow::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `softshadow render`.
#[derive(clap::Args)]
pub struct Args {
    /// A built-in scene name (default, comb, …) or a scene file (JSON) with
    /// a camera.
    #[arg(long)]
    scene: String,
    /// The method, NAME or NAME:OPTION,… (the list is below).
    #[arg(long, value_parser = parse_method)]
    method: String,
    /// The directory the PNG files are written to (created if missing).
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Image width (default: the scene camera's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16384))]
    width: Option<u32>,
    /// Image height (default: the scene camera's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16384))]
    height: Option<u32>,
    /// Seed of the Monte Carlo samples (the same as the option seed=S of
    /// mc:N; default the method's own).
    #[arg(long)]
    seed: Option<u64>,
    /// Print each stage's time and what was built.
    #[arg(long)]
    stats: bool,
    /// Refuse a render whose estimated peak memory exceeds this many GiB
    /// (default: half of this machine's memory).
    #[arg(long, value_parser = parse_gib)]
    max_memory: Option<f64>,
}

fn parse_gib(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(g) if g.is_finite() && g > 0.0 => Ok(g),
        _ => Err(format!("expected a positive number of GiB, got {s:?}")),
    }
}

/// Measured peak memory of `render` (`/usr/bin/time -f %M`, 1024² and
/// 2048², hard, exact, sism, oess): 103–117 bytes per pixel over a fixed
/// part of at most about 130 MiB (SISM's and OESS's maps).
const BYTES_PER_PIXEL: f64 = 120.0;
const FIXED_BYTES: f64 = 256.0 * MIB;
const MIB: f64 = (1u64 << 20) as f64;
const GIB: f64 = (1u64 << 30) as f64;

/// Half of the machine's memory (`/proc/meminfo`), or 8 GiB when unknown.
fn default_memory_limit() -> f64 {
    let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|t| {
        t.lines()
            .find(|l| l.starts_with("MemTotal:"))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<f64>().ok())
            .map(|kb| kb * 1024.0)
    });
    total.map_or(8.0 * GIB, |b| 0.5 * b)
}

/// Refuses a frame of `w × h` whose estimated peak exceeds the limit.
fn check_memory(w: u32, h: u32, max_gib: Option<f64>) -> Result<(), String> {
    let estimate = BYTES_PER_PIXEL * f64::from(w) * f64::from(h) + FIXED_BYTES;
    let (limit, whence) = match max_gib {
        Some(g) => (g * GIB, "--max-memory"),
        None => (
            default_memory_limit(),
            "half this machine's memory; --max-memory to change",
        ),
    };
    if estimate > limit {
        return Err(format!(
            "--width {w} --height {h}: about {:.1} GiB estimated ({BYTES_PER_PIXEL} bytes per pixel \
             and {:.0} MiB of maps), over the limit of {:.1} GiB ({whence})",
            estimate / GIB,
            FIXED_BYTES / MIB,
            limit / GIB
        ));
    }
    Ok(())
}

/// The scene's camera at the requested size, and the receivers it sees.
fn camera_frame(
    scene: &Scene,
    stages: &Stages,
    name: &str,
    width: Option<u32>,
    height: Option<u32>,
    max_memory: Option<f64>,
) -> Result<Frame, String> {
    let camera = scene
        .camera()
        .ok_or_else(|| format!("--scene {name}: the scene has no camera; rendering needs one"))?;
    let (w, h) = camera.resolution();
    let (w, h) = (width.unwrap_or(w), height.unwrap_or(h));
    check_memory(w, h, max_memory)?;
    let camera = camera
        .with_resolution(w, h)
        .map_err(|e| format!("--width/--height: {e}"))?;
    let bvh = stages.bvh();
    Ok(stages.timed("receivers", || {
        let frame = Frame::from_camera(&camera, bvh);
        let (w, h) = frame.size();
        let detail = format!(
            "{w}×{h} primary rays, {} receivers",
            frame.receivers().len()
        );
        (frame, detail)
    }))
}

/// A file name part for a method name (`mc:64` → `mc64`).
fn file_part(name: &str) -> String {
    name.chars()
        .filter(|c| c.is_ascii_alphanumeric() || *c == '-')
        .collect()
}

pub fn run(args: &Args) -> Result<(), String> {
    crate::out_dir(&args.out)?;
    let scene = resolve_scene(&args.scene)?;
    let method = method_with_seed(&args.method, args.seed)?;
    let stages = Stages::new(&scene);
    let frame = camera_frame(
        &scene,
        &stages,
        &args.scene,
        args.width,
        args.height,
        args.max_memory,
    )?;
    let fail = |e: method::MethodError| format!("--method {}: {e}", args.method);
    let run = run_method(method.as_ref(), &stages, &frame).map_err(fail)?;
    let exact = if run.method == "exact" {
        run.clone()
    } else {
        run_method(&Exact, &stages, &frame).map_err(|e| format!("the exact reference: {e}"))?
    };
    let stem = format!(
        "{}-{}",
        Path::new(&args.scene)
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy()),
        file_part(&run.method)
    );
    let v = &run.output.visibility;
    let images = [
        ("visibility", visibility_image(&frame, v)),
        (
            "shaded",
            match &run.output.end_weights {
                Some(w) => shaded_by_ends(&scene, &frame, w),
                None => shaded(&scene, &frame, v),
            },
        ),
        ("error", error_heat_map(&frame, v, &exact.output.visibility)),
    ];
    for (kind, image) in &images {
        let path = args.out.join(format!("{stem}-{kind}.png"));
        image
            .write_png(&path)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        say!("wrote {}", path.display());
    }
    print_table(&frame, &exact, std::slice::from_ref(&run));
    if args.stats {
        say!("\nstages:\n{}", stages.stats());
    }
    Ok(())
}

/// The default run: the default scene at its camera's resolution with
/// every method of its light's default set, one table; then the same for
/// the segment-light scene (`linear-light`) and the methods that handle a
/// segment light.
pub fn default_run() -> Result<(), String> {
    let start = Instant::now();
    for (name, what) in [
        (
            "default",
            "the Stanford bunny over a floor, sphere light r = 0.5",
        ),
        (
            "linear-light",
            "bars, a box and a ball under a segment light of length 2.4",
        ),
    ] {
        scene_table(name, what)?;
    }
    say!("\ntotal run {:.2} s", start.elapsed().as_secs_f64());
    say!("render one method to PNG: softshadow render --scene default --method pcss --out out");
    Ok(())
}

/// One scene's table: every method of the default set for its light, each
/// timed on stages of its own (so that no method is timed without the maps
/// it builds because another built them first), the BVH and the receivers
/// shared and reported apart.
fn scene_table(name: &str, what: &str) -> Result<(), String> {
    let scene = resolve_scene(name)?;
    let stages = Stages::new(&scene);
    let frame = camera_frame(&scene, &stages, name, None, None, None)?;
    let (w, h) = frame.size();
    say!(
        "softshadow: `{name}` ({what}), {w}×{h}, {} receivers, {} threads",
        frame.receivers().len(),
        rayon::current_num_threads()
    );
    let exact = run_method(&Exact, &stages, &frame).map_err(|e| format!("exact: {e}"))?;
    let mut runs = Vec::new();
    for m in method::default_set(scene.light().kind()) {
        if m.name() == "exact" {
            runs.push(exact.clone());
            continue;
        }
        let own = Stages::new(&scene);
        own.bvh();
        runs.push(run_method(m.as_ref(), &own, &frame).map_err(|e| format!("{}: {e}", m.name()))?);
    }
    print_table(&frame, &exact, &runs);
    let shared: Stats = stages.stats();
    say!(
        "\nshared (not in the times above): bvh {:.1} ms, receivers {:.1} ms\n",
        shared.seconds("bvh") * 1e3,
        shared.seconds("receivers") * 1e3,
    );
    Ok(())
}

/// Errors of each run against `exact`, over all receivers and over the
/// penumbra (receivers whose exact `V` is strictly between 0 and 1).
fn print_table(frame: &Frame, exact: &method::Run, runs: &[method::Run]) {
    let reference = &exact.output.visibility;
    say!(
        "\n{} receivers, {} in the exact penumbra; errors of V against exact\n",
        frame.receivers().len(),
        reference.iter().filter(|&&v| in_penumbra(v)).count()
    );
    say!("{}", ErrorRow::HEADER);
    for run in runs {
        say!(
            "{}",
            ErrorRow::new(&run.method, run.seconds, &run.output.visibility, reference)
        );
    }
}

#[allow(dead_code)]
fn _assert_object_safe(_: &dyn Method) {}
