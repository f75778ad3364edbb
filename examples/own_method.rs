//! A method of one's own, through the library like the built-in ones:
//!
//! 1. implement [`Method`] (here: `n × n` samples at the centres of the
//!    strata of the light, each an exact occlusion ray through the BVH);
//! 2. property-test it against the exact reference on the crate's random
//!    stiff scenes (`arbitrary::scene::visibility_case`), with a tolerance
//!    derived from its sample count;
//! 3. check Monte Carlo against exact on the same frame in one call
//!    (`reference::agree`, at a stated family-wise false-failure rate);
//! 4. run it on a built-in scene with `method::run`, print its row of the
//!    README's error table (`ErrorRow`), write its shaded picture and error
//!    heat-map;
//! 5. sweep it in a small accuracy-against-run-time report beside `hard`
//!    and Monte Carlo (`report::Config::own`).
//!
//! Run with `cargo run --release --example own_method [OUT_DIR]` (CI runs
//! it in debug: a few seconds).

use softshadow::arbitrary::{scene::visibility_case, Rng};
use softshadow::glam::DVec2;
use softshadow::method::{self, Exact, Input, MethodError, MonteCarlo, Output};
use softshadow::output::image::{error_heat_map, shaded, ErrorRow};
use softshadow::reference::{self, exact, monte_carlo::Estimate};
use softshadow::render::Needs;
use softshadow::report::{self, Case, Config};
use softshadow::scene::builtin;
use softshadow::{Bvh, Frame, Method, Occluders, Stages};
use std::error::Error;
use std::path::PathBuf;
use std::sync::Arc;

/// `V` as the share of `n × n` stratum centres of the emitter the receiver
/// sees: a deterministic estimator whose error is at most what `n²` random
/// samples would give.
#[derive(Debug)]
struct Strata {
    n: u32,
}

impl Strata {
    fn value(&self, bvh: &Bvh, emitter: &softshadow::Emitter, p: softshadow::glam::DVec3) -> f64 {
        let n = self.n;
        let mut seen = 0;
        for i in 0..n {
            for j in 0..n {
                let s = DVec2::new(f64::from(i) + 0.5, f64::from(j) + 0.5) / f64::from(n);
                seen += u32::from(bvh.segment_unoccluded(p, emitter.point_at(s)));
            }
        }
        f64::from(seen) / f64::from(n * n)
    }
}

impl Method for Strata {
    /// Any short, distinctive name: it labels tables, plots and files.
    fn name(&self) -> String {
        format!("strata-{}", self.n)
    }

    /// The BVH, and each receiver's view of the light (`run` computes it
    /// once and checks every receiver against the light first).
    fn needs(&self) -> Needs {
        Needs::BVH.union(Needs::EMITTERS)
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        let bvh = input.stages().bvh();
        let values = input
            .receivers()
            .iter()
            .zip(input.emitters())
            .map(|(r, e)| self.value(bvh, e, r.position))
            .collect();
        Ok(Output::values(values))
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "out/own_method".into()),
    );
    std::fs::create_dir_all(&out)?;
    let method = Strata { n: 4 };

    // 2. Property: on random stiff scenes (every light kind), the error's
    // RMSE stays below what 16 independent samples would give at worst,
    // sqrt(V(1 − V)/16) ≤ 1/8.
    let mut rng = Rng::new(7);
    let (mut sum, mut count) = (0.0, 0);
    for _ in 0..400 {
        let case = visibility_case(&mut rng, 12);
        let bvh = Bvh::new(Occluders::from_triangles(case.triangles.clone()));
        let (Ok(e), Ok(emitter)) = (
            exact::visibility(&bvh, &case.light, case.receiver),
            case.light.emitter(case.receiver),
        ) else {
            continue;
        };
        let v = method.value(&bvh, &emitter, case.receiver);
        assert!((0.0..=1.0).contains(&v));
        sum += (v - e) * (v - e);
        count += 1;
    }
    let rmse = (sum / f64::from(count)).sqrt();
    println!("{count} random scenes: RMSE against exact {rmse:.4} (at most 1/8 = 0.125 allowed)");
    assert!(rmse <= 0.125, "RMSE {rmse}");

    // 3 and 4. A built-in scene: the method, exact and Monte Carlo.
    let scene = builtin("several-objects").ok_or("no such scene")?;
    let camera = scene.camera().ok_or("no camera")?.with_resolution(96, 72)?;
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(&camera, stages.bvh());
    let exact = method::run(&Exact, &stages, &frame)?;
    let mc = method::run(&MonteCarlo::new(256), &stages, &frame)?;
    let estimates: Vec<Estimate> = mc
        .output
        .visibility
        .iter()
        .zip(mc.output.stderr.as_deref().unwrap_or_default())
        .map(|(&visibility, &stderr)| Estimate { visibility, stderr })
        .collect();
    let agreement = reference::agree(&estimates, &exact.output.visibility, 256, 1e-3)?;
    println!(
        "Monte Carlo (256 samples) against exact at a family-wise rate of 1e-3: {} of {} outside q = {:.2} standard errors",
        agreement.failures.len(),
        agreement.checked,
        agreement.quantile
    );
    assert!(agreement.passed());

    let run = method::run(&method, &stages, &frame)?;
    println!("\n{}", ErrorRow::HEADER);
    for r in [&run, &mc, &exact] {
        println!(
            "{}",
            ErrorRow::new(
                &r.method,
                r.seconds,
                &r.output.visibility,
                &exact.output.visibility
            )
        );
    }
    shaded(&scene, &frame, &run.output.visibility).write_png(&out.join("strata-shaded.png"))?;
    error_heat_map(&frame, &run.output.visibility, &exact.output.visibility)
        .write_png(&out.join("strata-error.png"))?;
    println!(
        "\nwrote {0}/strata-shaded.png and {0}/strata-error.png",
        out.display()
    );

    // 5. The report, with the method beside the registry's `hard`.
    let config = Config {
        side: 48,
        runs: 1,
        mc: vec![2, 4, 8, 16, 32, 64],
        methods: vec!["hard".into()],
        own: vec![Arc::new(Strata { n: 4 })],
        picture_side: 0,
        ..Config::default()
    };
    let case = Case {
        name: "several-objects".into(),
        scene: scene.clone(),
    };
    let results = report::finish(report::run(&[case], &config, None, &|_, _, _| {})?);
    let cell = results
        .cells
        .iter()
        .find(|c| c.method == method.name())
        .ok_or("the report has no cell for the method")?;
    let errors = cell.errors.ok_or("the method failed in the report")?;
    println!(
        "report: {} on several-objects at 48²: RMSE {:.4}, Monte Carlo of equal RMSE: {:?}",
        cell.method, errors[0].rmse, cell.mc_equal
    );
    Ok(())
}
