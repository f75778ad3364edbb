//! The speed figures of `benches/README.md` for soft irregular shadow
//! mapping: per-stage times and edge–receiver evaluations with and without
//! each overdraw optimisation, the hard-shadow frame, and Monte Carlo at
//! increasing sample counts until it matches SISM's RMSE against `Exact`.
//!
//! ```text
//! cargo run --release --all-features --example sism_speed -- 512
//! ```
//!
//! The argument is the side of the default scene's camera image (default
//! 512). Receivers are built once; every time is one method's run
//! (`method::run`: its own stages and its pass), the median of `RUNS`.

use softshadow::method::{self, Method, Run};
use softshadow::output::image::ErrorSummary;
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin;
use std::time::Instant;

const RUNS: usize = 5;

/// The median-time run of `m` over `RUNS` runs, each on fresh stages (so
/// that the method's own stages are timed every time; the shared BVH is
/// built before the clock starts when the method needs it).
fn timed(scene: &softshadow::scene::Scene, frame: &Frame, m: &dyn Method, runs: usize) -> Run {
    let mut all: Vec<Run> = (0..runs)
        .map(|_| {
            let stages = Stages::new(scene);
            if m.needs().contains(softshadow::render::Needs::BVH) {
                stages.bvh();
            }
            method::run(m, &stages, frame).expect("the method runs")
        })
        .collect();
    all.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    all.swap_remove(all.len() / 2)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let side: u32 = match std::env::args().nth(1) {
        Some(s) => s.parse()?,
        None => 512,
    };
    let scene = builtin("default").ok_or("no default scene")?;
    let camera = scene
        .camera()
        .ok_or("no camera")?
        .with_resolution(side, side)?;
    let stages = Stages::new(&scene);
    let start = Instant::now();
    let frame = Frame::from_camera(&camera, stages.bvh());
    eprintln!(
        "{} receivers in {:.1} s",
        frame.receivers().len(),
        start.elapsed().as_secs_f64()
    );
    let exact = method::run(&method::Exact, &stages, &frame)?;
    let reference = &exact.output.visibility;
    let rmse = |run: &Run| ErrorSummary::new(&run.output.visibility, reference, |_| true).rmse;

    println!(
        "default scene, {side}×{side} camera, {} receivers, {} threads; exact {:.2} s\n",
        frame.receivers().len(),
        rayon::current_num_threads(),
        exact.seconds
    );
    println!(
        "| method | time (ms) | RMSE | evaluations | saved by bin depth | saved by wedge column |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    let mut sism_run = None;
    for name in [
        "sism",
        "sism:no-bin-depth",
        "sism:no-wedge-column",
        "sism:no-bin-depth,no-wedge-column",
        "sism:conservative",
        "sism:all-edges",
        "sism:exact-union",
        "hard",
    ] {
        let m = method::parse(name)?;
        let run = timed(&scene, &frame, m.as_ref(), RUNS);
        let s = &run.stats;
        println!(
            "| `{name}` | {:.1} | {:.5} | {} | {} | {} |",
            run.seconds * 1e3,
            rmse(&run),
            s.counter("sism edge-receiver evaluations"),
            s.counter("sism evaluations saved by bin depth"),
            s.counter("sism evaluations saved by wedge column"),
        );
        if name == "sism" {
            sism_run = Some(run);
        }
    }
    let sism = sism_run.ok_or("no sism run")?;
    println!("\n`sism` stages (median run):\n\n```\n{}```\n", sism.stats);
    let hard = timed(&scene, &frame, &method::HardShadow::default(), RUNS);
    println!(
        "sism / hard frame time: {:.2}× ({:.1} ms / {:.1} ms)\n",
        sism.seconds / hard.seconds,
        sism.seconds * 1e3,
        hard.seconds * 1e3
    );
    println!("| Monte Carlo | time (ms) | RMSE |");
    println!("|---|---:|---:|");
    let target = rmse(&sism);
    let mut n = 2u32;
    loop {
        let run = timed(&scene, &frame, &method::MonteCarlo::new(n), 1);
        let e = rmse(&run);
        println!("| `mc:{n}` | {:.1} | {e:.5} |", run.seconds * 1e3);
        if e <= target {
            println!(
                "\nMonte Carlo first reaches SISM's RMSE ({target:.5}) at N = {n}: \
                 SISM is {:.1}× faster than that run.",
                run.seconds / sism.seconds
            );
            break;
        }
        if n >= 4096 {
            println!("\nMonte Carlo does not reach SISM's RMSE ({target:.5}) by N = 4096.");
            break;
        }
        n *= 2;
    }
    Ok(())
}
