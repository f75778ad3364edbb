//! Prints `docs/accuracy/sism.md`: the errors of soft irregular shadow
//! mapping and its options against the exact reference on every built-in
//! scene with a sphere or disk light.
//!
//! ```text
//! cargo run --release --all-features --example sism_accuracy -- 128 > docs/accuracy/sism.md
//! ```
//!
//! The argument is the side of the camera image (default 128); receivers are
//! the camera's eye-visible points.

use softshadow::method::{self, Method};
use softshadow::render::image::ErrorSummary;
use softshadow::render::{Frame, Stages};
use softshadow::scene::{builtin, Light, BUILTIN_NAMES};
use std::time::Instant;

const VARIANTS: &[&str] = &[
    "sism",
    "sism:exact-union",
    "sism:all-edges",
    "sism:conservative",
    "hard",
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let side: u32 = match std::env::args().nth(1) {
        Some(s) => s.parse()?,
        None => 128,
    };
    let start = Instant::now();
    println!("# SISM accuracy against the exact reference\n");
    println!(
        "Soft irregular shadow mapping (`softshadow::method::Sism`, Johnson et al. 2009) and \
         its options against `Exact`, on every built-in scene with a sphere or disk light, \
         receivers the eye-visible points of each scene's camera at {side}×{side}. \
         Errors are `V − V_exact` (negative: too dark); \"penumbra\" rows keep the receivers \
         whose exact `V` is strictly between 0 and 1. `hard` (the point light at the centre) \
         is the baseline.\n"
    );
    println!("Regenerate with:\n");
    println!(
        "    cargo run --release --all-features --example sism_accuracy -- {side} > docs/accuracy/sism.md\n"
    );
    for &name in BUILTIN_NAMES {
        let Some(scene) = builtin(name) else { continue };
        if !matches!(scene.light(), Light::Sphere { .. } | Light::Disk { .. }) {
            continue;
        }
        let Some(camera) = scene.camera() else {
            continue;
        };
        let camera = camera.with_resolution(side, side)?;
        let stages = Stages::new(&scene);
        let frame = Frame::from_camera(&camera, stages.bvh());
        let exact = method::run(&method::Exact, &stages, &frame)?;
        let reference = &exact.output.visibility;
        let penumbra = |i: usize| reference[i] > 0.0 && reference[i] < 1.0;
        let pen_count = (0..reference.len()).filter(|&i| penumbra(i)).count();
        println!(
            "## `{name}` ({} receivers, {pen_count} in the exact penumbra)\n",
            frame.receivers().len()
        );
        println!("| method | receivers | mean abs | RMSE | max | mean signed | share > 0.05 |");
        println!("|---|---|---:|---:|---:|---:|---:|");
        for &variant in VARIANTS {
            let m: Box<dyn Method> = method::parse(variant)?;
            let run = method::run(m.as_ref(), &stages, &frame)?;
            let v = &run.output.visibility;
            for (label, summary) in [
                ("all", ErrorSummary::new(v, reference, |_| true)),
                ("penumbra", ErrorSummary::new(v, reference, penumbra)),
            ] {
                println!(
                    "| `{variant}` | {label} | {:.5} | {:.5} | {:.4} | {:+.5} | {:.4} |",
                    summary.mean_abs,
                    summary.rmse,
                    summary.max_abs,
                    summary.mean_signed,
                    summary.share_over_0_05
                );
            }
        }
        println!();
    }
    eprintln!("done in {:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}
