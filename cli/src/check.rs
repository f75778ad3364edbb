//! `softshadow check`, the default run: the kernel self-check, then the two
//! references side by side on the embedded default scene — exact against
//! Monte Carlo on the floor receivers in the bunny's penumbra, with the
//! time each takes.

use crate::selfcheck;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::definitions::in_penumbra;
use softshadow::glam::DVec3;
use softshadow::reference::exact;
use softshadow::reference::monte_carlo::{self, Options, REPLICATES};
use softshadow::reference::stats::{agreement_tolerance, sidak, student_t_two_sided_quantile};
use softshadow::scene::builtin::floor_receivers;
use softshadow::scene::{builtin, Scene};
use std::process::ExitCode;
use std::time::Instant;

/// Receivers per side of the floor grid.
const GRID: usize = 32;
/// Monte Carlo samples per receiver.
const SAMPLES: u32 = 4096;
/// Family-wise false-failure rate of the agreement check.
const ALPHA: f64 = 1e-3;

pub fn run() -> ExitCode {
    let kernels = selfcheck::run();
    say!("");
    let references = match builtin("default") {
        Some(scene) => references(&scene),
        None => {
            say!("the default scene is missing");
            false
        }
    };
    if kernels && references {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn references(scene: &Scene) -> bool {
    let bvh = Bvh::new(Occluders::from_scene(scene));
    let light = scene.light();
    let grid = floor_receivers(scene, GRID);
    let t = Instant::now();
    let exact_all = exact::visibility_many(&bvh, light, &grid);
    let exact_seconds = t.elapsed().as_secs_f64();
    // The penumbra group: where the exact answer is between 0 and 1 by more
    // than its accuracy.
    let (points, exact): (Vec<DVec3>, Vec<f64>) = grid
        .iter()
        .zip(&exact_all)
        .filter_map(|(&p, v)| match v {
            Ok(v) if in_penumbra(*v) => Some((p, *v)),
            _ => None,
        })
        .unzip();
    let errors = exact_all.iter().filter(|v| v.is_err()).count();
    // Timed again on the penumbra alone: the same receivers as Monte Carlo.
    let t = Instant::now();
    let _ = exact::visibility_many(&bvh, light, &points);
    let penumbra_seconds = t.elapsed().as_secs_f64();
    let options = Options::new(SAMPLES);
    let t = Instant::now();
    let mc = monte_carlo::visibility_many(&bvh, light, &points, &options);
    let mc_seconds = t.elapsed().as_secs_f64();
    let mc_per = mc_seconds / points.len().max(1) as f64;
    let exact_per = exact_seconds / grid.len().max(1) as f64;
    let penumbra_per = penumbra_seconds / points.len().max(1) as f64;
    // Tolerance: Student's t with K − 1 degrees of freedom (the standard
    // error comes from K replicates), Šidák-corrected over the receivers
    // (one replicate's resolution where the standard error is zero).
    let q = student_t_two_sided_quantile(sidak(ALPHA, points.len().max(1)), REPLICATES - 1);
    let mut worst: f64 = 0.0;
    let mut disagree = 0;
    for (e, m) in exact.iter().zip(&mc) {
        let Ok(m) = m else {
            disagree += 1;
            continue;
        };
        let allowed = agreement_tolerance(m, SAMPLES, q);
        let d = (m.visibility - e).abs();
        worst = worst.max(d / allowed);
        disagree += usize::from(d > allowed);
    }
    say!(
        "references on the default scene ({} triangles, sphere light): {} floor receivers, {} in the penumbra, {} receiver errors",
        scene.triangle_count(),
        grid.len(),
        points.len(),
        errors
    );
    say!(
        "  exact:   {:>8.1} µs per receiver over all {} receivers, {:.1} µs in the penumbra ({} threads)",
        exact_per * 1e6,
        grid.len(),
        penumbra_per * 1e6,
        rayon::current_num_threads()
    );
    say!(
        "  mc:{SAMPLES}: {:>8.1} µs per receiver in the penumbra; there exact costs {:.3} of Monte Carlo",
        mc_per * 1e6,
        penumbra_per / mc_per
    );
    say!(
        "  agreement: largest |mc − exact| is {worst:.2} of its tolerance (t·stderr, t = {q:.2} for a family-wise false-failure rate {ALPHA}); {disagree} disagree"
    );
    errors == 0 && disagree == 0 && !points.is_empty()
}
