//! `softshadow gbuffer` (the receivers our camera sees, as `.npy` arrays,
//! one `.exr` and `camera.json`) and `softshadow score` (an image of `V`
//! made elsewhere against the exact answer on the same receivers, with the
//! report's statistics).

use crate::memory::check_memory;
use crate::render::camera_frame;
use crate::visibility::{resolve_scene, run_method};
use softshadow::float_io::{
    self, exr_bytes, npy_bytes_f64, npy_bytes_i32, read_npy_f64, read_npy_i64, FloatIoError,
};
use softshadow::method::{Exact, MethodError};
use softshadow::output::gbuffer::{frame_from_arrays, CameraModel, GBuffer};
use softshadow::output::image::{error_heat_map, Rgb};
use softshadow::output::score::{self as scoring, McOptions, Score};
use softshadow::render::{Frame, Stages, BACKGROUND};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Exit status of `score --max-rmse X` when the image fails the gate.
pub const GATE_FAILED: u8 = 3;

/// Arguments of `softshadow gbuffer`.
#[derive(clap::Args)]
pub struct GbufferArgs {
    /// A built-in scene name (default, comb, …) or a scene file (JSON) with
    /// a camera.
    #[arg(long)]
    scene: String,
    /// Image width (default: the scene camera's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16384))]
    width: Option<u32>,
    /// Image height (default: the scene camera's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16384))]
    height: Option<u32>,
    /// The directory the files are written to (created if missing):
    /// position.npy, normal.npy, object.npy, exact.npy, gbuffer.exr,
    /// camera.json.
    #[arg(long)]
    out: PathBuf,
    /// Refuse a frame whose estimated peak memory exceeds this many GiB
    /// (default: half of this machine's memory).
    #[arg(long, value_parser = crate::memory::parse_gib)]
    max_memory: Option<f64>,
}

/// Arguments of `softshadow score`.
#[derive(clap::Args)]
#[command(
    after_help = "Exit status: 0 scored (and within --max-rmse); 2 bad input (one line on \
    stderr naming the file and the problem, nothing written); 3 the image fails --max-rmse X: \
    its RMSE is over X, or a surface pixel is NaN or infinite."
)]
pub struct ScoreArgs {
    /// A built-in scene name (default, comb, …) or a scene file (JSON).
    #[arg(long)]
    scene: String,
    /// The image of V: an H×W .npy (float32 or float64), an .exr (the
    /// channel named V, else its only channel) or a greyscale .pfm; row 0
    /// the top of the image.
    #[arg(long)]
    image: PathBuf,
    /// The receivers: a directory with position.npy, normal.npy and
    /// object.npy in the layout `softshadow gbuffer` writes (ours, or one's
    /// own rasteriser's); default: our camera's receivers at the image's
    /// size.
    #[arg(long)]
    gbuffer: Option<PathBuf>,
    /// Write the signed-error heat-map (score-error.png) and the error
    /// histogram (score-histogram.svg) to this directory.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    json: bool,
    /// Exit with status 3 when the RMSE over every receiver exceeds X or a
    /// surface pixel is NaN or infinite.
    #[arg(long, value_parser = parse_rmse)]
    max_rmse: Option<f64>,
    /// Also measure the Monte Carlo sample count of equal RMSE on the same
    /// receivers (the report's yardstick; a seeded subset when the image
    /// has more receivers than --yardstick-receivers).
    #[arg(long)]
    yardstick: bool,
    /// The most receivers the yardstick measures.
    #[arg(long, default_value_t = 16384, value_parser = clap::value_parser!(u64).range(16..=1 << 26))]
    yardstick_receivers: u64,
    /// The seed of the yardstick's subset and samples.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Refuse an image whose estimated peak memory exceeds this many GiB
    /// (default: half of this machine's memory).
    #[arg(long, value_parser = crate::memory::parse_gib)]
    max_memory: Option<f64>,
}

fn parse_rmse(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("expected a non-negative number, got {s:?}")),
    }
}

/// `softshadow gbuffer`.
pub fn gbuffer(args: &GbufferArgs) -> Result<(), String> {
    let scene = resolve_scene(&args.scene)?;
    let stages = Stages::new(&scene);
    let frame = camera_frame(
        &scene,
        &stages,
        &args.scene,
        args.width,
        args.height,
        Some((&Exact, args.max_memory)),
    )?;
    crate::out_dir(&args.out)?;
    let exact = run_method(&Exact, &stages, &frame)
        .map_err(|e| format!("the exact reference: {e}"))?
        .output
        .visibility;
    let (w, h) = frame.size();
    let camera = scene
        .camera()
        .and_then(|c| c.with_resolution(w, h).ok())
        .ok_or("the scene has no camera")?;
    let g = GBuffer::from_frame(&frame, &exact, CameraModel::new(&camera, scene.bounds()));
    let (wu, hu) = (w as usize, h as usize);
    let f32s = |x: &[f64], c: usize, k: usize| -> Vec<f32> {
        x.iter().skip(k).step_by(c).map(|&v| v as f32).collect()
    };
    let exr = exr_bytes(
        wu,
        hu,
        &[
            ("P.X", f32s(&g.position, 3, 0)),
            ("P.Y", f32s(&g.position, 3, 1)),
            ("P.Z", f32s(&g.position, 3, 2)),
            ("N.X", f32s(&g.normal, 3, 0)),
            ("N.Y", f32s(&g.normal, 3, 1)),
            ("N.Z", f32s(&g.normal, 3, 2)),
            ("V", f32s(&g.exact, 1, 0)),
            ("object", g.object.iter().map(|&o| o as f32).collect()),
        ],
    )
    .map_err(|e| e.to_string())?;
    let files: [(&str, Vec<u8>); 6] = [
        (
            "position.npy",
            npy_bytes_f64(&[hu, wu, 3], &g.position).map_err(|e| e.to_string())?,
        ),
        (
            "normal.npy",
            npy_bytes_f64(&[hu, wu, 3], &g.normal).map_err(|e| e.to_string())?,
        ),
        (
            "object.npy",
            npy_bytes_i32(&[hu, wu], &g.object).map_err(|e| e.to_string())?,
        ),
        (
            "exact.npy",
            npy_bytes_f64(&[hu, wu], &g.exact).map_err(|e| e.to_string())?,
        ),
        ("gbuffer.exr", exr),
        (
            "camera.json",
            (g.camera.to_json(&scene) + "\n").into_bytes(),
        ),
    ];
    for (name, bytes) in &files {
        crate::write_out(&args.out.join(name), bytes, false)?;
    }
    say!(
        "{w}×{h} pixels, {} receivers (object id ≥ 0), {} in the exact penumbra",
        frame.receivers().len(),
        exact
            .iter()
            .filter(|&&v| softshadow::definitions::in_penumbra(v))
            .count()
    );
    Ok(())
}

/// An array file of a G-buffer directory, read with its name on errors.
fn array<T>(
    dir: &Path,
    name: &str,
    read: fn(&[u8]) -> Result<float_io::Array<T>, float_io::FormatError>,
) -> Result<(PathBuf, float_io::Array<T>), String> {
    let path = dir.join(name);
    let bytes = float_io::read_bytes(&path).map_err(|e| e.to_string())?;
    let a = read(&bytes).map_err(|e| FloatIoError::new(&path, e.to_string()).to_string())?;
    Ok((path, a))
}

/// The receivers of a G-buffer directory for an image of `w × h`.
fn gbuffer_frame(
    dir: &Path,
    w: usize,
    h: usize,
    meshes: usize,
) -> Result<(Frame, PathBuf), String> {
    let (ppath, pos) = array(dir, "position.npy", read_npy_f64)?;
    let (npath, nrm) = array(dir, "normal.npy", read_npy_f64)?;
    let (opath, obj) = array(dir, "object.npy", read_npy_i64)?;
    for (path, shape, want) in [
        (&ppath, &pos.shape, vec![h, w, 3]),
        (&npath, &nrm.shape, vec![h, w, 3]),
        (&opath, &obj.shape, vec![h, w]),
    ] {
        if *shape != want {
            return Err(format!(
                "{}: shape {shape:?}, the image is {w}×{h} (expected {want:?})",
                path.display()
            ));
        }
    }
    let frame = frame_from_arrays(w, h, &pos.data, &nrm.data, &obj.data, meshes).map_err(|e| {
        let path = match e.array {
            "normal" => &npath,
            "object" => &opath,
            _ => &ppath,
        };
        format!("{}: {e}", path.display())
    })?;
    Ok((frame, ppath))
}

/// `softshadow score`: the exit status (0, 2 or [`GATE_FAILED`]).
pub fn score(args: &ScoreArgs) -> ExitCode {
    match score_inner(args) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(GATE_FAILED),
        Err(message) => {
            eprintln!("softshadow: {}", crate::one_line(&message, 600));
            ExitCode::from(crate::BAD_INPUT)
        }
    }
}

/// Scores; `Ok(false)` when the gate fails.
fn score_inner(args: &ScoreArgs) -> Result<bool, String> {
    let scene = resolve_scene(&args.scene)?;
    let image = float_io::read_image(&args.image).map_err(|e| e.to_string())?;
    let (w, h) = (image.width, image.height);
    let file = args.image.display();
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!(
            "{file}: {w}×{h} pixels; an image is 1 to 16384 pixels a side"
        ));
    }
    check_memory(
        &format!("{file} ({w}×{h} pixels) scored against exact"),
        w as u64 * h as u64,
        &Exact,
        args.max_memory,
    )?;
    let stages = Stages::new(&scene);
    let (frame, receivers_file) = match &args.gbuffer {
        Some(dir) => gbuffer_frame(dir, w, h, scene.meshes().len())?,
        None => (
            camera_frame(
                &scene,
                &stages,
                &args.scene,
                Some(w as u32),
                Some(h as u32),
                None,
            )?,
            PathBuf::from(format!("--scene {}", args.scene)),
        ),
    };
    if let Some(dir) = &args.out {
        crate::out_dir(dir)?;
    }
    let at_pixel = |index: usize| {
        frame
            .pixels()
            .iter()
            .position(|&i| i as usize == index)
            .map_or(String::new(), |k| {
                format!("pixel (row {}, column {})", k / w, k % w)
            })
    };
    let exact = run_method(&Exact, &stages, &frame)
        .map_err(|e| match e {
            MethodError::Receiver { index, error } => format!(
                "{}: {}: the receiver {error}",
                receivers_file.display(),
                at_pixel(index)
            ),
            e => format!("the exact reference: {e}"),
        })?
        .output
        .visibility;
    let (mut score, values) = Score::new(&frame, scene.light(), &image.data, &exact);
    if args.yardstick {
        let scored = scoring::Scored {
            score: score.clone(),
            exact: exact.clone(),
            values: values.clone(),
        };
        let options = McOptions {
            receivers: args.yardstick_receivers as usize,
            seed: args.seed,
            ..McOptions::default()
        };
        score.mc_equal = Some(
            scoring::mc_equal(&scene, &frame, &scored, &options)
                .map_err(|e| format!("the Monte Carlo yardstick: {e}"))?,
        );
    }
    if let Some(dir) = &args.out {
        // With --json, stdout is the JSON object alone.
        let png = dir.join("score-error.png");
        heat_map(&frame, &values, &exact)
            .write_png(&png)
            .map_err(|e| format!("{}: {e}", png.display()))?;
        let svg = dir.join("score-histogram.svg");
        let text = histogram(&values, &exact, &frame, &score);
        crate::write_out(&svg, text.as_bytes(), true)?;
        if !args.json {
            say!("wrote {}\nwrote {}", png.display(), svg.display());
        }
    }
    if args.json {
        say!("{}", score.to_json());
    } else {
        print_score(&args.image, &score);
    }
    let pass = args.max_rmse.is_none_or(|x| score.passes(x));
    if !pass {
        let x = args.max_rmse.unwrap_or(0.0);
        if score.nan_pixels > 0 {
            eprintln!(
                "softshadow: {file}: {} surface pixels are NaN or infinite (failing --max-rmse {x})",
                score.nan_pixels
            );
        } else {
            eprintln!(
                "softshadow: {file}: RMSE {:.6} over --max-rmse {x}",
                score.rmse()
            );
        }
    }
    Ok(pass)
}

/// The human-readable report of a score.
fn print_score(image: &Path, s: &Score) {
    say!(
        "{}: {}×{} pixels, {} see a surface: {} scored, {} NaN or infinite (not scored){}",
        image.display(),
        s.width,
        s.height,
        s.surface_pixels,
        s.pixels,
        s.nan_pixels,
        s.first_nan.map_or(String::new(), |(r, c)| format!(
            ", the first at row {r}, column {c}"
        ))
    );
    say!("errors of V against exact (V − V_exact; negative: too dark)\n");
    say!("{}", s.table());
    if let Some(m) = &s.mc_equal {
        let subset = if m.receivers < m.of {
            format!(
                "on a seeded random subset of {} of the {} receivers (seed {}; image RMSE there {:.5}); 95% interval over bootstrap resamples of the subset: {}",
                m.receivers,
                m.of,
                m.seed,
                m.rmse,
                m.interval
                    .map_or("n/a".to_owned(), |(a, b)| format!("{a:.1} to {b:.1}"))
            )
        } else {
            format!("on all {} scored receivers (seed {})", m.of, m.seed)
        };
        say!(
            "Monte Carlo sample count of equal RMSE: {} ({subset})",
            m.text
        );
    }
}

/// The report's signed-error heat-map of the values against exact, with
/// NaN or infinite surface pixels in magenta.
fn heat_map(frame: &Frame, values: &[f64], exact: &[f64]) -> Rgb {
    let finite: Vec<f64> = values
        .iter()
        .zip(exact)
        .map(|(v, e)| if v.is_finite() { *v } else { *e })
        .collect();
    let mut img = error_heat_map(frame, &finite, exact);
    let (w, _) = frame.size();
    for (k, &i) in frame.pixels().iter().enumerate() {
        if i != BACKGROUND && !values[i as usize].is_finite() {
            let (x, y) = (k % w as usize, k / w as usize);
            let at = 3 * (y * img.width as usize + x);
            img.data[at..at + 3].copy_from_slice(&[255, 0, 255]);
        }
    }
    img
}

/// The histogram of the signed error over the scored receivers (all, and
/// the exact penumbra), log counts, as SVG.
fn histogram(values: &[f64], exact: &[f64], frame: &Frame, s: &Score) -> String {
    use plotters::prelude::*;
    let masks = scoring::group_masks(frame.receivers(), exact);
    let errors: Vec<(f64, bool)> = values
        .iter()
        .zip(exact)
        .enumerate()
        .filter(|(_, (v, _))| v.is_finite())
        .map(|(i, (v, e))| (v - e, masks[1][i]))
        .collect();
    let range = errors
        .iter()
        .fold(0.0f64, |m, (e, _)| m.max(e.abs()))
        .max(1e-3);
    const BINS: usize = 81;
    let bin = |e: f64| (((e + range) / (2.0 * range) * BINS as f64) as usize).min(BINS - 1);
    let mut all = [0u64; BINS];
    let mut pen = [0u64; BINS];
    for &(e, p) in &errors {
        all[bin(e)] += 1;
        if p {
            pen[bin(e)] += 1;
        }
    }
    let top = all.iter().copied().max().unwrap_or(1).max(1) as f64;
    let width = 2.0 * range / BINS as f64;
    let x = |k: usize| -range + k as f64 * width;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (820, 480)).into_drawing_area();
        let _ = root.fill(&WHITE);
        let Ok(mut chart) = ChartBuilder::on(&root)
            .caption(
                format!(
                    "signed error V − V_exact: {} pixels, RMSE {:.5} (penumbra {:.5})",
                    s.pixels, s.v[0].rmse, s.v[1].rmse
                ),
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(-range..range, (0.5..top * 2.0).log_scale())
        else {
            return String::new();
        };
        let _ = chart
            .configure_mesh()
            .x_desc("V − V_exact (negative: too dark)")
            .y_desc("pixels (log)")
            .x_label_formatter(&|v| format!("{:.2}", v + 0.0))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .draw();
        for (counts, colour, label) in [
            (&all, RGBColor(120, 120, 120), "all scored receivers"),
            (&pen, RGBColor(230, 120, 20), "the exact penumbra"),
        ] {
            let bars = counts
                .iter()
                .enumerate()
                .filter(|(_, &c)| c > 0)
                .map(|(k, &c)| {
                    Rectangle::new(
                        [(x(k), 0.5), (x(k + 1), c as f64)],
                        colour.mix(0.75).filled(),
                    )
                });
            if let Ok(series) = chart.draw_series(bars) {
                series.label(label).legend(move |(x, y)| {
                    Rectangle::new([(x, y - 5), (x + 12, y + 5)], colour.filled())
                });
            }
        }
        let _ = chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw();
        let _ = root.present();
    }
    svg
}
