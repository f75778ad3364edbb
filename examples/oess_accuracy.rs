//! Prints `docs/accuracy/oess.md`: the errors of occluding edges soft
//! shadows against the exact reference on the built-in segment-light scene
//! and on random segment-light scenes, with the hard shadow and PCSS
//! beside it.
//!
//! ```text
//! cargo run --release --all-features --example oess_accuracy -- 256 24 > docs/accuracy/oess.md
//! ```
//!
//! The arguments are the side of the camera image (default 256) and the
//! number of random scenes (default 24).

#[path = "support/accuracy.rs"]
mod support;

use glam::DVec3;
use softshadow::method::{self, Exact, Method, Oess};
use softshadow::render::image::ErrorSummary;
use softshadow::render::{Frame, Stages};
use softshadow::scene::primitive::{cuboid, quad, sphere, Transform};
use softshadow::scene::{Camera, Light, Scene};

const VARIANTS: &[&str] = &[
    "oess",
    "oess:no-tilt",
    "oess:no-corr",
    "oess:depth-check",
    "oess:law-of-sines",
    "oess:map=400",
    "oess:map=1600",
    "hard",
    "pcss",
];

/// The methods compared on the random scenes.
const RANDOM: &[&str] = &["oess", "oess:depth-check", "hard", "pcss"];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let side: u32 = args.next().map_or(Ok(256), |s| s.parse())?;
    let count: u64 = args.next().map_or(Ok(24), |s| s.parse())?;
    println!("# Occluding edges soft shadows against the exact reference\n");
    println!(
        "Occluding edges soft shadows (`softshadow::method::Oess`, Reimann & Dreier 2016) \
         against `Exact` on the built-in segment-light scene and on {count} random \
         segment-light scenes, receivers the eye-visible points of each scene's camera at \
         {side}×{side}, 800² endpoint maps unless named. Errors are `V − V_exact` (negative: \
         too dark); \"penumbra\" keeps the receivers whose exact `V` is strictly between 0 \
         and 1; \"floor\" the receivers on the floor (object 0), \"occluders\" the others. \
         `hard` (the light's midpoint) and `pcss` are the baselines.\n"
    );
    println!(
        "Reading it: where one straight edge casts the shadow OESS is the closed form within \
         what moving the edge by one map texel changes (`tests/oess.rs`). Elsewhere the \
         method's own limits dominate, as the paper says: (1) a receiver that sees both ends \
         but not the middle of the light (a thin occluder across the light, the bar of \
         `linear-light`) is lit, because no map holds an edge for it; (2) a receiver seen by \
         one end only and reached by no outreach (the penumbra of an occluder that casts no \
         umbra is not next to it in the map) takes the nearest edge toward the occluder in \
         its row (ours), which is right for a straight edge and too dark for a thin \
         occluder; (3) an outreach hands its edge to every texel behind it that the other end \
         cannot see, whoever hides them (object alternation), and to receivers beyond the \
         surface it reached (receiver penetration: the lower half of the ball, the box's \
         face turned away). `depth-check` removes the last at the price of the seam the \
         paper describes. Against the goal of a penumbra RMSE below both the hard shadow's \
         and PCSS's on `linear-light`: the default (the paper's final substep 4.1) is below \
         the hard shadow and above PCSS; `depth-check` is below both. On the random scenes \
         OESS beats the hard shadow in most scenes and PCSS in few: PCSS's blur is never \
         far off, where OESS's edge, when it is the wrong one, is far off.\n"
    );
    println!("Regenerate with:\n");
    println!(
        "    cargo run --release --all-features --example oess_accuracy -- {side} {count} > docs/accuracy/oess.md\n"
    );
    support::tables(side, Oess::default().lights(), VARIANTS, |_, _| {})?;
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
        let penumbra = |i: usize| exact[i] > 0.0 && exact[i] < 1.0;
        for (k, name) in RANDOM.iter().enumerate() {
            let m = method::parse(name)?;
            let v = method::run(m.as_ref(), &stages, &frame)?.output.visibility;
            let all = ErrorSummary::new(&v, &exact, |_| true);
            let pen = ErrorSummary::new(&v, &exact, penumbra);
            rmse[k].push((all.rmse, pen.rmse));
        }
    }
    println!("\n## {count} random segment-light scenes\n");
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
