//! `softshadow visibility`: V(p) for each receiver of a points file, by any
//! method.

use crate::progress::Progress;
use softshadow::float_io::{self, npy_bytes_f64, read_npy_f64, read_npy_i64, ImageKind};
use softshadow::method::registry::SeedError;
use softshadow::method::{self, registry, Method, MethodError, ParseError};
use softshadow::render::{Fit, Frame, Receiver, Stages};
use softshadow::scene::builtin::{builtin, BUILTIN_NAMES};
use softshadow::scene::file::{load_points, load_scene, receiver_from, ReceiverField};
use softshadow::scene::Scene;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Arguments of `softshadow visibility`.
#[derive(clap::Args)]
pub struct Args {
    /// A built-in scene name (default, comb, …) or a scene file (JSON).
    #[arg(long)]
    scene: String,
    /// The points file: JSON, {"points": [{"p": [x, y, z], "object": i,
    /// "normal": [x, y, z]}, …]}; or a NumPy .npy of N×3 positions or N×6
    /// positions and normals (float32 or float64).
    #[arg(long)]
    points: PathBuf,
    /// With an .npy points file: the object id of each point, an .npy of N
    /// integers (int32 or int64).
    #[arg(long)]
    objects: Option<PathBuf>,
    /// Write V (and, for Monte Carlo, its standard error to FILE's stem
    /// + .stderr.npy) as an .npy of N float64 instead of JSON on stdout.
    #[arg(long)]
    out: Option<PathBuf>,
    /// The method, NAME or NAME:OPTION,… (the list is below).
    #[arg(long, value_parser = parse_method)]
    method: String,
    /// Seed of the Monte Carlo samples: the option seed=S of mc:N (not
    /// both; refused for a method without a seed); default the method's
    /// own.
    #[arg(long)]
    seed: Option<u64>,
    /// Refuse a run whose estimated peak memory exceeds this many GiB
    /// (default: half of this machine's memory).
    #[arg(long, value_parser = crate::memory::parse_gib)]
    max_memory: Option<f64>,
    /// What the map methods fit their light-view maps to: scene (the
    /// occluders; each point's V independent of the other points, so a
    /// split or sharded run gives the same values) or frame (the scene and
    /// these points, as `render` does with its camera's receivers).
    #[arg(long, value_enum, default_value_t = FitArg::Scene)]
    fit: FitArg,
}

/// `--fit`: [`Fit`] on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FitArg {
    /// The scene's occluders.
    Scene,
    /// The scene's occluders and the points.
    Frame,
}

/// Checks a method name (clap's value parser), keeping the name.
pub fn parse_method(s: &str) -> Result<String, ParseError> {
    method::parse(s).map(|_| s.to_owned())
}

/// The method `name`, with `seed=S` added to its options when `--seed S`
/// is given ([`registry::parse_with_seed`]).
pub fn method_with_seed(name: &str, seed: Option<u64>) -> Result<Box<dyn Method>, String> {
    registry::parse_with_seed(name, seed).map_err(|e| match e {
        SeedError::Parse(e) => e.to_string(),
        SeedError::Repeated => format!(
            "--seed {}: --method {name} sets seed= already; give the seed once",
            seed.unwrap_or_default()
        ),
        e => format!("--seed {}: {e}", seed.unwrap_or_default()),
    })
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
    let points = read_points(&args.points, args.objects.as_deref(), scene.meshes().len())?;
    let what = format!(
        "{} ({} point{}) --method {}",
        args.points.display(),
        points.len(),
        if points.len() == 1 { "" } else { "s" },
        method.name()
    );
    crate::memory::check_memory(&what, points.len() as u64, method.as_ref(), args.max_memory)?;
    let frame = Frame::from_receivers(points).with_fit(match args.fit {
        FitArg::Scene => Fit::Scene,
        FitArg::Frame => Fit::Frame,
    });
    let stages = Stages::new(&scene);
    let file = args.points.display();
    let npy = args.points.extension().is_some_and(|x| x == "npy");
    let place = |index: usize, field: &str| {
        if npy {
            format!("row {index} ({field})")
        } else {
            format!("points[{index}].{field}")
        }
    };
    let run = run_method(method.as_ref(), &stages, &frame).map_err(|e| match e {
        MethodError::Receiver { index, error } => format!("{file}: {}: {error}", place(index, "p")),
        MethodError::NeedsNormal { index, .. } => {
            format!("{file}: {}: {e}", place(index, "normal"))
        }
        MethodError::NeedsObject { index, .. } => {
            format!("{file}: {}: {e}", place(index, "object"))
        }
        MethodError::Tolerance { index, .. } => format!("{file}: {}: {e}", place(index, "p")),
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
    if let Some(path) = &args.out {
        let n = out.visibility.len();
        let write = |path: &Path, data: &[f64]| {
            crate::write_out(
                path,
                &npy_bytes_f64(&[n], data).map_err(|e| e.to_string())?,
                false,
            )
        };
        write(path, &out.visibility)?;
        if let Some(stderr) = &out.stderr {
            write(&path.with_extension("stderr.npy"), stderr)?;
        }
        say!("{n} receivers, method {}, {:.3} s", run.method, seconds);
        return Ok(());
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

/// The receivers of a points file: JSON, or an `.npy` of N×3 positions or
/// N×6 positions and normals with object ids from `objects`. Every number
/// finite and within the scene file's domain (10³⁰), normals non-zero
/// (normalised), object ids of the scene's meshes.
fn read_points(
    path: &Path,
    objects: Option<&Path>,
    meshes: usize,
) -> Result<Vec<Receiver>, String> {
    let bytes = float_io::read_bytes(path).map_err(|e| e.to_string())?;
    let file = path.display();
    if ImageKind::sniff(&bytes) != Some(ImageKind::Npy) {
        if objects.is_some() {
            return Err(format!(
                "--objects goes with an .npy points file; {file} is not one (give \"object\" in the JSON points)"
            ));
        }
        return load_points(path, meshes).map_err(|e| e.to_string());
    }
    let a = read_npy_f64(&bytes).map_err(|m| format!("{file}: {m}"))?;
    let (n, cols) = match a.shape[..] {
        [n, c @ (3 | 6)] => (n, c),
        _ => {
            return Err(format!(
                "{file}: shape {:?}: points are N×3 (positions) or N×6 (positions, normals)",
                a.shape
            ))
        }
    };
    let ids = match objects {
        Some(o) => {
            let bytes = float_io::read_bytes(o).map_err(|e| e.to_string())?;
            let ids = read_npy_i64(&bytes).map_err(|m| format!("{}: {m}", o.display()))?;
            if ids.shape != [n] {
                return Err(format!(
                    "{}: shape {:?}, {file} has {n} points (expected [{n}])",
                    o.display(),
                    ids.shape
                ));
            }
            Some(ids.data)
        }
        None => None,
    };
    (0..n)
        .map(|i| {
            let row = &a.data[i * cols..(i + 1) * cols];
            let normal = (cols == 6).then(|| [row[3], row[4], row[5]]);
            let object = ids.as_ref().map(|ids| ids[i]);
            receiver_from([row[0], row[1], row[2]], normal, object, meshes).map_err(
                |(field, what)| match (field, objects) {
                    (ReceiverField::Object, Some(o)) => format!("{}: row {i}: {what}", o.display()),
                    _ => format!("{file}: row {i}: {what}"),
                },
            )
        })
        .collect()
}
