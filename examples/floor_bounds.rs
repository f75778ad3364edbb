//! The exact reference's certified bound on the built-in scenes' floor
//! grids: for each scene and each light kind (sphere, disk, rect and
//! segment of the scene's light's bounding radius at its centre), the
//! median and the largest bound over `side²` floor receivers, as the
//! table of `docs/accuracy/references.md`.
//!
//! `cargo run --release --example floor_bounds --features reference,scene-file -- [side]`
//! (default 64).

use softshadow::glam::DVec3;
use softshadow::reference::exact;
use softshadow::scene::builtin::{builtin, floor_receivers, BUILTIN_NAMES};
use softshadow::{Bvh, Light, Occluders};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let side: usize = std::env::args().nth(1).map_or(Ok(64), |s| s.parse())?;
    println!("| scene | light | receivers | median bound | largest bound |");
    println!("|---|---|---|---|---|");
    for name in BUILTIN_NAMES {
        let scene = builtin(name).ok_or("a built-in scene")?;
        let points = floor_receivers(&scene, side);
        let bvh = Bvh::new(Occluders::from_scene(&scene));
        let c = scene.light().center();
        let r = scene.light().bounding_radius();
        let lights = [
            ("sphere", Light::sphere(c, r)?),
            ("disk", Light::disk(c, DVec3::new(0.1, -1.0, 0.2), r)?),
            (
                "rect",
                Light::rect(
                    c,
                    DVec3::new(r, 0.0, 0.3 * r),
                    DVec3::new(0.1 * r, 0.05 * r, r),
                )?,
            ),
            (
                "segment",
                Light::segment(
                    c - DVec3::new(r, 0.0, 0.2 * r),
                    c + DVec3::new(r, 0.0, 0.2 * r),
                )?,
            ),
        ];
        for (kind, light) in lights {
            let mut bounds: Vec<f64> = exact::visibility_many_bounded(&bvh, &light, &points)
                .into_iter()
                .filter_map(|b| b.ok().map(|b| b.bound))
                .collect();
            bounds.sort_by(f64::total_cmp);
            let median = bounds.get(bounds.len() / 2).copied().unwrap_or(f64::NAN);
            let largest = bounds.last().copied().unwrap_or(f64::NAN);
            println!(
                "| {name} | {kind} | {} | {median:.1e} | {largest:.1e} |",
                bounds.len()
            );
        }
    }
    Ok(())
}
