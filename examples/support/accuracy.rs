//! What the per-method accuracy examples (`single_sample_accuracy.rs`,
//! `ssoc_accuracy.rs`) share, included with `#[path]`: one table per
//! built-in scene of each method's errors against the exact reference,
//! split into receiver groups, and a summary table.

use softshadow::method::{self, Exact};
use softshadow::render::image::ErrorSummary;
use softshadow::render::{Frame, Stages};
use softshadow::scene::{builtin, LightKind, BUILTIN_NAMES};

/// One scene's frame and exact answer.
pub struct Case {
    /// The scene's name.
    #[allow(dead_code)] // not every example reads it
    pub name: &'static str,
    /// Its camera's receivers.
    pub stages_frame: Frame,
    /// The exact answer at each.
    pub exact: Vec<f64>,
}

/// Which receivers a row keeps.
type Keep<'a> = Box<dyn Fn(usize) -> bool + 'a>;

/// The rows' groups: every receiver, the exact penumbra, the floor
/// (object 0), the other objects.
fn groups(case: &Case) -> [(&'static str, Keep<'_>); 4] {
    let exact = &case.exact;
    let frame = &case.stages_frame;
    [
        ("all", Box::new(|_| true)),
        (
            "penumbra",
            Box::new(move |i| exact[i] > 0.0 && exact[i] < 1.0),
        ),
        (
            "floor",
            Box::new(move |i| frame.receivers()[i].object == Some(0)),
        ),
        (
            "occluders",
            Box::new(move |i| frame.receivers()[i].object != Some(0)),
        ),
    ]
}

/// Prints, per built-in scene whose light is one of `lights`, a table of
/// every method of `methods` (command-line names) by receiver group, at
/// `side × side`; then the summary (RMSE over all and over the penumbra).
/// `extra` runs after each scene's table with the case and its stages.
pub fn tables(
    side: u32,
    lights: &[LightKind],
    methods: &[&str],
    mut extra: impl FnMut(&Case, &Stages),
) -> Result<(), Box<dyn std::error::Error>> {
    let mut summary = Vec::new();
    for &name in BUILTIN_NAMES {
        let Some(scene) = builtin(name) else { continue };
        if !lights.contains(&scene.light().kind()) {
            continue;
        }
        let Some(camera) = scene.camera() else {
            continue;
        };
        let camera = camera.with_resolution(side, side)?;
        let stages = Stages::new(&scene);
        let frame = Frame::from_camera(&camera, stages.bvh());
        let exact = method::run(&Exact, &stages, &frame)?.output.visibility;
        let case = Case {
            name,
            stages_frame: frame,
            exact,
        };
        let penumbra = case.exact.iter().filter(|v| **v > 0.0 && **v < 1.0).count();
        println!(
            "## `{name}` ({} receivers, {penumbra} in the exact penumbra)\n",
            case.exact.len()
        );
        println!(
            "| method | receivers | count | mean abs | RMSE | max | mean signed | share > 0.05 |"
        );
        println!("|---|---|---:|---:|---:|---:|---:|---:|");
        for &m in methods {
            let parsed = method::parse(m)?;
            let v = match method::run(parsed.as_ref(), &stages, &case.stages_frame) {
                Ok(run) => run.output.visibility,
                Err(e) => {
                    println!("| `{m}` | {e} | | | | | | |");
                    continue;
                }
            };
            let mut all_pen = (0.0, 0.0);
            for (label, keep) in groups(&case) {
                let s = ErrorSummary::new(&v, &case.exact, keep);
                println!(
                    "| `{m}` | {label} | {} | {:.5} | {:.5} | {:.4} | {:+.5} | {:.4} |",
                    s.count, s.mean_abs, s.rmse, s.max_abs, s.mean_signed, s.share_over_0_05
                );
                match label {
                    "all" => all_pen.0 = s.rmse,
                    "penumbra" => all_pen.1 = s.rmse,
                    _ => {}
                }
            }
            summary.push((name, m, all_pen.0, all_pen.1));
        }
        extra(&case, &stages);
        println!();
    }
    println!("## Summary: RMSE, all receivers and penumbra\n");
    println!("| scene | method | RMSE | RMSE penumbra |");
    println!("|---|---|---:|---:|");
    for (scene, m, all, pen) in summary {
        println!("| {scene} | `{m}` | {all:.5} | {pen:.5} |");
    }
    Ok(())
}
