//! `softshadow visibility`: V(p) for each receiver of a points file, by any
//! method.

use crate::progress::Progress;
use softshadow::method::{self, Method, MethodError};
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin::{builtin, BUILTIN_NAMES};
use softshadow::scene::file::{load_points, load_scene};
use softshadow::scene::Scene;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Arguments of `softshadow visibility`.
#[derive(clap::Args)]
pub struct Args {
    /// A built-in scene name (default, comb, …) or a scene file (JSON).
    #[arg(long)]
    scene: String,
    /// The points file: {"points": [{"p": [x, y, z], "object": i, "normal": [x, y, z]}, …]}.
    #[arg(long)]
    points: PathBuf,
    /// The method, NAME or NAME:OPTION,… (the list is below).
    #[arg(long, value_parser = parse_method)]
    method: String,
    /// Seed of the Monte Carlo samples (the same as the option seed=S of
    /// mc:N; default the method's own).
    #[arg(long)]
    seed: Option<u64>,
}

/// Checks a method name (clap's value parser), keeping the name.
pub fn parse_method(s: &str) -> Result<String, String> {
    method::parse(s).map(|_| s.to_owned())
}

/// The method `name`, with `seed=S` added to a Monte Carlo method's
/// options when a seed is given.
pub fn method_with_seed(name: &str, seed: Option<u64>) -> Result<Box<dyn Method>, String> {
    match seed {
        Some(seed) if name == "mc" || name.starts_with("mc:") => {
            let sep = if name.contains(':') { ',' } else { ':' };
            method::parse(&format!("{name}{sep}seed={seed}"))
        }
        _ => method::parse(name),
    }
}

/// A built-in scene by name, else a scene file.
pub fn resolve_scene(name: &str) -> Result<Scene, String> {
    if let Some(scene) = builtin(name) {
        return Ok(scene);
    }
    let path = Path::new(name);
    if !path.exists() && !name.contains(['/', '.', '\\']) {
        return Err(format!(
            "--scene {name}: no such built-in scene ({}) and no such file",
            BUILTIN_NAMES.join(", ")
        ));
    }
    load_scene(path).map_err(|e| e.to_string())
}

/// Runs `method` on `frame` with a progress bar (shown after a second on a
/// terminal).
pub fn run_method(
    method: &dyn Method,
    stages: &Stages,
    frame: &Frame,
) -> Result<method::Run, MethodError> {
    let progress = Arc::new(Progress::new(frame.receivers().len(), method.name()));
    let bar = Arc::clone(&progress);
    stages.set_progress(Some(Arc::new(move |n| bar.inc(n))));
    let run = method::run(method, stages, frame);
    stages.set_progress(None);
    if let Ok(p) = Arc::try_unwrap(progress) {
        p.finish();
    }
    run
}

pub fn run(args: &Args) -> Result<(), String> {
    let scene = resolve_scene(&args.scene)?;
    let method = method_with_seed(&args.method, args.seed)?;
    let points = load_points(&args.points, scene.meshes().len()).map_err(|e| e.to_string())?;
    let frame = Frame::from_receivers(points);
    let stages = Stages::new(&scene);
    let file = args.points.display();
    let run = run_method(method.as_ref(), &stages, &frame).map_err(|e| match e {
        MethodError::Receiver { index, error } => format!("{file}: points[{index}].p: {error}"),
        MethodError::NeedsNormal { index, .. } => format!("{file}: points[{index}].normal: {e}"),
        MethodError::NeedsObject { index, .. } => format!("{file}: points[{index}].object: {e}"),
        MethodError::Tolerance { index, .. } => format!("{file}: points[{index}].p: {e}"),
        e => format!("{file}: {e}"),
    })?;
    // The BVH is built inside the run: the time a user waits for the answer.
    let seconds = run.seconds;
    let out = &run.output;
    if let Some(i) = out
        .visibility
        .iter()
        .chain(out.stderr.iter().flatten())
        .chain(out.bound.iter().flatten().filter(|b| b.is_nan()))
        .position(|v| !v.is_finite())
    {
        // Never reached: methods are total. A NaN must not be printed as if
        // it were an answer.
        return Err(format!("internal error: a non-finite result at index {i}"));
    }
    let mut json = serde_json::json!({
        "method": run.method,
        "visibility": out.visibility,
        "seconds": seconds,
    });
    if let Some(stderr) = &out.stderr {
        json["stderr"] = serde_json::json!(stderr);
    }
    if let Some(bound) = &out.bound {
        // The exact reference's certified bounds, finite in its domain;
        // beyond it a bound may be infinite, which JSON cannot hold: the
        // largest double stands for it (still a true bound).
        let finite: Vec<f64> = bound.iter().map(|b| b.min(f64::MAX)).collect();
        json["bound"] = serde_json::json!(finite);
    }
    say!("{json}");
    Ok(())
}
