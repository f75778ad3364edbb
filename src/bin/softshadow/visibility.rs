//! `softshadow visibility`: V(p) for each receiver of a points file.

use crate::progress::Progress;
use glam::DVec3;
use softshadow::reference::bvh::Bvh;
use softshadow::reference::{exact, monte_carlo, Occluders};
use softshadow::scene::builtin::{builtin, BUILTIN_NAMES};
use softshadow::scene::file::{load_points, load_scene};
use softshadow::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `softshadow visibility`.
#[derive(clap::Args)]
pub struct Args {
    /// A built-in scene name (default, comb, …) or a scene file (JSON).
    #[arg(long)]
    scene: String,
    /// The points file: {"points": [{"p": [x, y, z]}, …]}.
    #[arg(long)]
    points: PathBuf,
    /// `exact`, or `mc:N` for Monte Carlo with N samples per receiver.
    #[arg(long, value_parser = parse_method)]
    method: Method,
    /// Seed of the Monte Carlo samples.
    #[arg(long, default_value_t = 0)]
    seed: u64,
}

/// The methods `visibility` runs.
#[derive(Clone, Copy, Debug)]
pub enum Method {
    /// The exact reference.
    Exact,
    /// Monte Carlo with this many samples per receiver.
    MonteCarlo(u32),
}

impl Method {
    fn name(self) -> String {
        match self {
            Method::Exact => "exact".to_owned(),
            Method::MonteCarlo(n) => format!("mc:{n}"),
        }
    }
}

/// The methods of DESIGN §8 that are not built yet.
const LATER: &[&str] = &[
    "sism",
    "single-sample",
    "ssoc",
    "backprojected-ssoc",
    "oess",
    "pcss",
    "hard",
];

pub fn parse_method(s: &str) -> Result<Method, String> {
    if s == "exact" {
        return Ok(Method::Exact);
    }
    if let Some(n) = s.strip_prefix("mc:") {
        return match n.parse::<u32>() {
            Ok(n) if n >= monte_carlo::MIN_SAMPLES => Ok(Method::MonteCarlo(n)),
            _ => Err(format!(
                "'{s}': the sample count must be an integer from {} to {}",
                monte_carlo::MIN_SAMPLES,
                u32::MAX
            )),
        };
    }
    if LATER.contains(&s) {
        return Err(format!(
            "method '{s}' is not available for visibility yet; use exact or mc:N"
        ));
    }
    Err(format!("unknown method '{s}'; use exact or mc:N"))
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

pub fn run(args: &Args) -> Result<(), String> {
    let scene = resolve_scene(&args.scene)?;
    let receivers = load_points(&args.points, scene.meshes().len()).map_err(|e| e.to_string())?;
    let points: Vec<DVec3> = receivers.iter().map(|r| r.p).collect();
    let start = Instant::now();
    let bvh = Bvh::new(Occluders::from_scene(&scene));
    let light = scene.light();
    let mut progress = Progress::new(points.len(), "visibility");
    let chunk = 64;
    let mut visibility = Vec::with_capacity(points.len());
    let mut stderr = Vec::new();
    let file = args.points.display();
    let fail = |i: usize, e: &dyn std::fmt::Display| format!("{file}: points[{i}].p: {e}");
    for (c, block) in points.chunks(chunk).enumerate() {
        let base = c * chunk;
        match args.method {
            Method::Exact => {
                for (k, r) in exact::visibility_many(&bvh, light, block)
                    .into_iter()
                    .enumerate()
                {
                    visibility.push(r.map_err(|e| fail(base + k, &e))?);
                }
            }
            Method::MonteCarlo(samples) => {
                let options = monte_carlo::Options {
                    samples,
                    seed: args.seed,
                };
                for (k, r) in monte_carlo::visibility_many(&bvh, light, block, &options)
                    .into_iter()
                    .enumerate()
                {
                    let e = r.map_err(|e| fail(base + k, &e))?;
                    visibility.push(e.visibility);
                    stderr.push(e.stderr);
                }
            }
        }
        progress.set(base + block.len());
    }
    progress.finish();
    let seconds = start.elapsed().as_secs_f64();
    if let Some(i) = visibility
        .iter()
        .chain(&stderr)
        .position(|v| !v.is_finite())
    {
        // Never reached: both references are total. A NaN must not be
        // printed as if it were an answer.
        return Err(format!("internal error: a non-finite result at index {i}"));
    }
    let mut out = serde_json::json!({
        "method": args.method.name(),
        "visibility": visibility,
        "seconds": seconds,
    });
    if matches!(args.method, Method::MonteCarlo(_)) {
        out["stderr"] = serde_json::json!(stderr);
    }
    println!("{out}");
    Ok(())
}
