//! The pictures in the README: the default scene (sphere light) and the
//! `linear-light` scene (segment light), each shaded by every method of
//! its light's default set, and each method's signed error heat-map
//! against the exact answer, at 256 × 256.
//!
//! `cargo run --release --example readme_images -- docs/images`
//!
//! Writes `SCENE-METHOD-shaded.png` and `SCENE-METHOD-error.png` into the
//! folder given (default `docs/images`), and prints each method's errors,
//! so a reader can hold the pictures against the numbers. Methods that
//! report end weights (OESS) are shaded by them.

use softshadow::method::{self, Exact};
use softshadow::output::image::{error_heat_map, shaded, shaded_by_ends, ErrorRow};
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin;
use std::error::Error;
use std::path::{Path, PathBuf};

/// The pictures' side in pixels.
const SIDE: u32 = 256;

fn main() -> Result<(), Box<dyn Error>> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "docs/images".to_owned()),
    );
    std::fs::create_dir_all(&out)?;
    for name in ["default", "linear-light"] {
        pictures(name, &out)?;
    }
    println!("wrote {}", out.display());
    Ok(())
}

/// The pictures and the error table of built-in scene `name`.
fn pictures(name: &str, out: &Path) -> Result<(), Box<dyn Error>> {
    let scene = builtin(name).ok_or("the scene is built in")?;
    let camera = scene
        .camera()
        .ok_or("the built-in scene has a camera")?
        .with_resolution(SIDE, SIDE)?;
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(&camera, stages.bvh());
    let exact = method::run(&Exact, &stages, &frame)?.output.visibility;
    println!("\n`{name}`\n");
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
        let picture = match &run.output.end_weights {
            Some(w) => shaded_by_ends(&scene, &frame, w),
            None => shaded(&scene, &frame, v),
        };
        picture.write_png(&out.join(format!("{name}-{part}-shaded.png")))?;
        error_heat_map(&frame, v, &exact)
            .write_png(&out.join(format!("{name}-{part}-error.png")))?;
        let row = ErrorRow::new(&run.method, run.seconds, v, &exact);
        println!(
            "| {} | {:.5} | {:.5} | {:+.5} |",
            row.method, row.all.rmse, row.penumbra.rmse, row.all.mean_signed
        );
    }
    Ok(())
}
