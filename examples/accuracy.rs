//! Errors of methods against the exact answer on every built-in scene, as
//! the markdown rows of `docs/accuracy/methods.md`:
//!
//! `cargo run --release --example accuracy -- [SIDE] [METHOD …]`
//!
//! `SIDE` is the image side in pixels (default 256); the methods are
//! command-line names (default: every method of `method::default_set`
//! except `exact`). Scenes whose light a method does not handle get a row
//! saying so. The statistics are DESIGN §7's, over every receiver, and the
//! RMSE over the exact penumbra (`0 < V < 1`).

use softshadow::method::{self, Exact, Method, MethodError};
use softshadow::render::image::ErrorSummary;
use softshadow::render::{Frame, Stages};
use softshadow::scene::{builtin, BUILTIN_NAMES};
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let side: u32 = match args.next() {
        Some(s) => s.parse()?,
        None => 256,
    };
    let names: Vec<String> = args.collect();
    let methods: Vec<Box<dyn Method>> = if names.is_empty() {
        method::default_set(softshadow::scene::LightKind::Sphere)
            .into_iter()
            .filter(|m| m.name() != "exact")
            .collect()
    } else {
        names
            .iter()
            .map(|n| method::parse(n))
            .collect::<Result<_, _>>()?
    };
    println!("| scene | method | time (ms) | mean abs | RMSE | p99 abs | max | mean signed | share > 0.05 | RMSE penumbra |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for name in BUILTIN_NAMES {
        let scene = builtin(name).ok_or("a built-in scene is missing")?;
        let camera = scene
            .camera()
            .ok_or("built-in scenes have cameras")?
            .with_resolution(side, side)?;
        let stages = Stages::new(&scene);
        let frame = Frame::from_camera(&camera, stages.bvh());
        let exact = method::run(&Exact, &stages, &frame)?.output.visibility;
        let penumbra = |i: usize| exact[i] > 0.0 && exact[i] < 1.0;
        for m in &methods {
            let run = match method::run(m.as_ref(), &stages, &frame) {
                Ok(run) => run,
                Err(e @ MethodError::UnsupportedLight { .. }) => {
                    println!("| {name} | {} | {e} | | | | | | | |", m.name());
                    continue;
                }
                Err(e) => return Err(e.into()),
            };
            let v = &run.output.visibility;
            let all = ErrorSummary::new(v, &exact, |_| true);
            let pen = ErrorSummary::new(v, &exact, penumbra);
            println!(
                "| {name} | {} | {:.1} | {:.5} | {:.5} | {:.4} | {:.4} | {:+.5} | {:.4} | {:.5} |",
                run.method,
                run.seconds * 1e3,
                all.mean_abs,
                all.rmse,
                all.p99_abs,
                all.max_abs,
                all.mean_signed,
                all.share_over_0_05,
                pen.rmse
            );
        }
    }
    Ok(())
}
