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
}

/// The scene's camera at the requested size, and the receivers it sees.
fn camera_frame(
    scene: &Scene,
    stages: &Stages,
    name: &str,
    width: Option<u32>,
    height: Option<u32>,
) -> Result<Frame, String> {
    let camera = scene
        .camera()
        .ok_or_else(|| format!("--scene {name}: the scene has no camera; rendering needs one"))?;
    let (w, h) = camera.resolution();
    let camera = camera
        .with_resolution(width.unwrap_or(w), height.unwrap_or(h))
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
    let frame = camera_frame(&scene, &stages, &args.scene, args.width, args.height)?;
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
    let frame = camera_frame(&scene, &stages, name, None, None)?;
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
