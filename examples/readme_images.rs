//! The pictures in the README: the default scene shaded by every method of
//! the default set, and each method's signed error heat-map against the
//! exact answer, at 256 × 256.
//!
//! `cargo run --release --example readme_images -- docs/images`
//!
//! Writes `default-METHOD-shaded.png` and `default-METHOD-error.png` into
//! the folder given (default `docs/images`), and prints each method's
//! errors, so a reader can hold the pictures against the numbers.

use softshadow::method::{self, Exact};
use softshadow::render::image::{error_heat_map, shaded, ErrorSummary};
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin;
use std::error::Error;
use std::path::PathBuf;

/// The pictures' side in pixels.
const SIDE: u32 = 256;

fn main() -> Result<(), Box<dyn Error>> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "docs/images".to_owned()),
    );
    std::fs::create_dir_all(&out)?;
    let scene = builtin("default").ok_or("the default scene is built in")?;
    let camera = scene
        .camera()
        .ok_or("the default scene has a camera")?
        .with_resolution(SIDE, SIDE)?;
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(&camera, stages.bvh());
    let exact = method::run(&Exact, &stages, &frame)?.output.visibility;
    let penumbra = |i: usize| exact[i] > 0.0 && exact[i] < 1.0;
    println!("| method | RMSE | RMSE penumbra | mean signed |");
    println!("|---|---:|---:|---:|");
    for m in method::default_set(scene.light().kind()) {
        let run = method::run(m.as_ref(), &stages, &frame)?;
        let v = &run.output.visibility;
        let part: String = run
            .method
            .chars()
            .filter(|c| c.is_ascii_alphanumeric() || *c == '-')
            .collect();
        shaded(&scene, &frame, v).write_png(&out.join(format!("default-{part}-shaded.png")))?;
        error_heat_map(&frame, v, &exact)
            .write_png(&out.join(format!("default-{part}-error.png")))?;
        let all = ErrorSummary::new(v, &exact, |_| true);
        let pen = ErrorSummary::new(v, &exact, penumbra);
        println!(
            "| {} | {:.5} | {:.5} | {:+.5} |",
            run.method, all.rmse, pen.rmse, all.mean_signed
        );
    }
    println!("wrote {}", out.display());
    Ok(())
}
