//! Prints `docs/accuracy/oess-random.md`: occluding edges soft shadows
//! against the exact reference on random segment-light scenes, with the
//! hard shadow and PCSS beside it (the built-in `linear-light` is in the
//! report, `docs/accuracy/oess.md`).
//!
//! ```text
//! cargo run --release --all-features --example oess_accuracy -- 256 24 > docs/accuracy/oess-random.md
//! ```
//!
//! The arguments are the side of the camera image (default 256) and the
//! number of random scenes (default 24).

use softshadow::glam::DVec3;
use softshadow::method::{self, Exact};
use softshadow::output::image::ErrorRow;
use softshadow::render::{Frame, Stages};
use softshadow::scene::primitive::{cuboid, quad, sphere, Transform};
use softshadow::scene::{Camera, Light, Scene};

/// The methods compared on the random scenes.
const RANDOM: &[&str] = &["oess", "oess:depth-check", "hard", "pcss"];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let side: u32 = args.next().map_or(Ok(256), |s| s.parse())?;
    let count: u64 = args.next().map_or(Ok(24), |s| s.parse())?;
    println!("# Occluding edges soft shadows on random segment-light scenes\n");
    println!(
        "Occluding edges soft shadows (`softshadow::method::Oess`) against `Exact` on {count} \
         random segment-light scenes, beside `oess:depth-check`, the hard shadow and PCSS; \
         receivers the eye-visible points of each scene's camera at {side}×{side}, 800² \
         endpoint maps. The built-in `linear-light` is in [`oess.md`](oess.md). Regenerate \
         with:\n"
    );
    println!(
        "    cargo run --release --all-features --example oess_accuracy -- {side} {count} > docs/accuracy/oess-random.md\n"
    );
    random_scenes(side, count)
}

/// A small deterministic generator (SplitMix64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Random scene `seed`: a floor, a segment light of length 1–3 at height
/// 2–3.5 turned about the vertical, and 2–5 occluders (boxes on the floor
/// or floating, balls, tilted plates) within `[−1.2, 1.2]²`, a camera
/// looking down at the middle from the side.
fn random_scene(seed: u64) -> Result<Scene, Box<dyn std::error::Error>> {
    let mut rng = Rng(seed);
    let half = rng.range(0.5, 1.5);
    let turn = rng.range(0.0, std::f64::consts::PI);
    let height = rng.range(2.0, 3.5);
    let along = DVec3::new(turn.cos(), 0.0, turn.sin()) * half;
    let centre = DVec3::new(rng.range(-0.3, 0.3), height, rng.range(-0.3, 0.3));
    let mut scene = Scene::new(Light::segment(centre - along, centre + along)?)
        .with_mesh("floor", quad(DVec3::ZERO, DVec3::X * 3.0, -DVec3::Z * 3.0)?);
    let count = 2 + (rng.next() * 4.0) as usize;
    for k in 0..count {
        let at = DVec3::new(rng.range(-1.2, 1.2), 0.0, rng.range(-1.2, 1.2));
        let mesh = match (rng.next() * 3.0) as u32 {
            0 => {
                let size = DVec3::new(
                    rng.range(0.1, 0.6),
                    rng.range(0.1, 0.8),
                    rng.range(0.1, 0.6),
                );
                let lift = if rng.next() < 0.5 {
                    0.0
                } else {
                    rng.range(0.2, 0.8)
                };
                cuboid(at + DVec3::Y * lift, at + DVec3::Y * lift + size)?
            }
            1 => {
                let r = rng.range(0.1, 0.4);
                sphere(at + DVec3::Y * rng.range(r, 1.2), r, 24)?
            }
            _ => {
                let plate = quad(
                    DVec3::ZERO,
                    DVec3::X * rng.range(0.1, 0.5),
                    -DVec3::Z * rng.range(0.1, 0.5),
                )?;
                Transform::new(
                    1.0,
                    rng.range(0.0, 90.0),
                    at + DVec3::Y * rng.range(0.3, 1.5),
                )?
                .apply(&plate)?
            }
        };
        scene = scene.with_mesh(format!("occluder {k}"), mesh);
    }
    let camera = Camera::new(
        DVec3::new(0.0, 3.0, 3.5),
        DVec3::new(0.0, 0.2, 0.0),
        DVec3::Y,
        50.0,
        256,
        256,
    )?;
    Ok(scene.with_camera(camera))
}

/// The random scenes' table: per method the median and the mean over the
/// scenes of the RMSE over every receiver and over the penumbra, and in
/// how many scenes OESS's penumbra RMSE is below the method's.
fn random_scenes(side: u32, count: u64) -> Result<(), Box<dyn std::error::Error>> {
    let mut rmse: Vec<Vec<(f64, f64)>> = vec![Vec::new(); RANDOM.len()];
    for seed in 0..count {
        let scene = random_scene(seed)?;
        let camera = scene
            .camera()
            .ok_or("a camera")?
            .with_resolution(side, side)?;
        let stages = Stages::new(&scene);
        let frame = Frame::from_camera(&camera, stages.bvh());
        let exact = method::run(&Exact, &stages, &frame)?.output.visibility;
        for (k, name) in RANDOM.iter().enumerate() {
            let m = method::parse(name)?;
            let run = method::run(m.as_ref(), &stages, &frame)?;
            let row = ErrorRow::new(*name, run.seconds, &run.output.visibility, &exact);
            rmse[k].push((row.all.rmse, row.penumbra.rmse));
        }
    }
    println!("## {count} random segment-light scenes\n");
    println!(
        "Each: a floor, a segment light of length 1–3 at height 2–3.5 turned at random about \
         the vertical, 2–5 occluders (boxes standing or floating, balls, tilted plates) in \
         `[−1.2, 1.2]²`, seeds 0–{} of `random_scene` in `examples/oess_accuracy.rs`; \
         {side}×{side} receivers.\n",
        count.saturating_sub(1)
    );
    println!("| method | RMSE median | RMSE mean | RMSE penumbra median | RMSE penumbra mean | scenes where OESS's penumbra RMSE is lower |");
    println!("|---|---:|---:|---:|---:|---:|");
    let median = |mut x: Vec<f64>| {
        x.sort_by(f64::total_cmp);
        let n = x.len();
        if n == 0 {
            f64::NAN
        } else if n % 2 == 1 {
            x[n / 2]
        } else {
            0.5 * (x[n / 2 - 1] + x[n / 2])
        }
    };
    let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len().max(1) as f64;
    for (k, name) in RANDOM.iter().enumerate() {
        let all: Vec<f64> = rmse[k].iter().map(|r| r.0).collect();
        let pen: Vec<f64> = rmse[k].iter().map(|r| r.1).collect();
        let wins = rmse[0]
            .iter()
            .zip(&rmse[k])
            .filter(|(o, m)| o.1 < m.1)
            .count();
        println!(
            "| `{name}` | {:.4} | {:.4} | {:.4} | {:.4} | {} |",
            median(all.clone()),
            mean(&all),
            median(pen.clone()),
            mean(&pen),
            if k == 0 {
                "—".to_owned()
            } else {
                format!("{wins} of {count}")
            }
        );
    }
    println!();
    Ok(())
}
