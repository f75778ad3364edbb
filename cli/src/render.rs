//! `softshadow render` (one method, PNG files) and the default run (every
//! available method on the default scene, a table of errors against the
//! exact answer).

use crate::memory::{check_memory, parse_gib};
use crate::visibility::{method_with_seed, parse_method, resolve_scene, run_method};
use softshadow::definitions::in_penumbra;
use softshadow::float_io::{exr_bytes, npy_bytes_f64};
use softshadow::method::{self, Exact, Method};
use softshadow::output::image::{
    error_heat_map, irradiance_factor, shaded, shaded_by_ends, visibility_image, ErrorRow,
};
use softshadow::output::score::Score;
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
    /// Seed of the Monte Carlo samples: the option seed=S of mc:N (not
    /// both; refused for a method without a seed); default the method's
    /// own.
    #[arg(long)]
    seed: Option<u64>,
    /// Print each stage's time and what was built.
    #[arg(long)]
    stats: bool,
    /// What to write, one or more of png (8-bit pictures), npy (H×W
    /// float64 arrays: visibility, shaded, error; NaN where no surface) and
    /// exr (one float32 file with the channels V, shaded and error).
    #[arg(long, value_delimiter = ',', default_value = "png")]
    format: Vec<Format>,
    /// Print the errors as one JSON object (the fields of `softshadow
    /// score --json`, with the method and its time) instead of the table.
    #[arg(long)]
    json: bool,
    /// Refuse a render whose estimated peak memory exceeds this many GiB
    /// (default: half of this machine's memory).
    #[arg(long, value_parser = parse_gib)]
    max_memory: Option<f64>,
}

/// An output format of `render`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// 8-bit sRGB pictures.
    Png,
    /// NumPy float64 arrays.
    Npy,
    /// One OpenEXR file of float32 channels.
    Exr,
}

/// The scene's camera at the requested size, and the receivers it sees.
pub(crate) fn camera_frame(
    scene: &Scene,
    stages: &Stages,
    name: &str,
    width: Option<u32>,
    height: Option<u32>,
    memory: Option<(&dyn Method, Option<f64>)>,
) -> Result<Frame, String> {
    let camera = scene
        .camera()
        .ok_or_else(|| format!("--scene {name}: the scene has no camera; rendering needs one"))?;
    let (w, h) = camera.resolution();
    let (w, h) = (width.unwrap_or(w), height.unwrap_or(h));
    if let Some((method, max_gib)) = memory {
        let what = format!("--width {w} --height {h} --method {}", method.name());
        check_memory(&what, u64::from(w) * u64::from(h), method, max_gib)?;
    }
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
        Some((method.as_ref(), args.max_memory)),
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
    let exact_v = &exact.output.visibility;
    if args.format.contains(&Format::Png) {
        let images = [
            ("visibility", visibility_image(&frame, v)),
            (
                "shaded",
                match &run.output.end_weights {
                    Some(w) => shaded_by_ends(&scene, &frame, w),
                    None => shaded(&scene, &frame, v),
                },
            ),
            ("error", error_heat_map(&frame, v, exact_v)),
        ];
        for (kind, image) in &images {
            let path = args.out.join(format!("{stem}-{kind}.png"));
            image
                .write_png(&path)
                .map_err(|e| format!("{}: {e}", path.display()))?;
            if !args.json {
                say!("wrote {}", path.display());
            }
        }
    }
    // With --json, stdout is the JSON object alone.
    let quiet = args.json;
    write_floats(
        &args.out,
        &stem,
        &args.format,
        &scene,
        &frame,
        v,
        exact_v,
        quiet,
    )?;
    if args.json {
        let image = frame.to_image(v, f64::NAN);
        let (score, _) = Score::new(&frame, scene.light(), &image, exact_v);
        let mut json: serde_json::Value =
            serde_json::from_str(&score.to_json()).map_err(|e| e.to_string())?;
        json["method"] = run.method.clone().into();
        json["seconds"] = run.seconds.into();
        say!("{json}");
    } else {
        print_table(&frame, &exact, std::slice::from_ref(&run));
    }
    if args.stats {
        say!("\nstages:\n{}", stages.stats());
    }
    Ok(())
}

/// The float outputs of `render`: per pixel `V`, the shaded value
/// (irradiance factor · `V`, `Φ = 1`) and the error `V − V_exact`, NaN
/// where no surface; as `.npy` (float64) and/or one `.exr` (float32).
#[allow(clippy::too_many_arguments)]
fn write_floats(
    dir: &Path,
    stem: &str,
    formats: &[Format],
    scene: &Scene,
    frame: &Frame,
    v: &[f64],
    exact: &[f64],
    quiet: bool,
) -> Result<(), String> {
    if !formats.iter().any(|f| *f != Format::Png) {
        return Ok(());
    }
    let light = scene.light();
    let shaded_v: Vec<f64> = frame
        .receivers()
        .iter()
        .zip(v)
        .map(|(r, v)| {
            let n = r
                .normal
                .unwrap_or_else(|| (light.center() - r.position).normalize_or_zero());
            irradiance_factor(light, r.position, n) * v
        })
        .collect();
    let error: Vec<f64> = v.iter().zip(exact).map(|(a, b)| a - b).collect();
    let channels = [
        ("visibility", "V", frame.to_image(v, f64::NAN)),
        ("shaded", "shaded", frame.to_image(&shaded_v, f64::NAN)),
        ("error", "error", frame.to_image(&error, f64::NAN)),
    ];
    let (w, h) = frame.size();
    let (w, h) = (w as usize, h as usize);
    let write = |name: String, bytes: Vec<u8>| crate::write_out(&dir.join(name), &bytes, quiet);
    if formats.contains(&Format::Npy) {
        for (kind, _, data) in &channels {
            write(
                format!("{stem}-{kind}.npy"),
                npy_bytes_f64(&[h, w], data).map_err(|e| e.to_string())?,
            )?;
        }
    }
    if formats.contains(&Format::Exr) {
        let list: Vec<(&str, Vec<f32>)> = channels
            .iter()
            .map(|(_, name, data)| (*name, data.iter().map(|&x| x as f32).collect()))
            .collect();
        write(
            format!("{stem}.exr"),
            exr_bytes(w, h, &list).map_err(|e| e.to_string())?,
        )?;
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
        if crate::stdout_lost() {
            // Nothing more would get through: the exit status says so.
            return Ok(());
        }
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
    let frame = camera_frame(&scene, &stages, name, None, None, Some((&Exact, None)))?;
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
