//! One exact frame of a built-in scene — every camera receiver's `V` —
//! with or without the certified bound, for timing whole processes
//! (`farm-bench`, `valgrind --tool=callgrind`); prints the answers' sum
//! (and the largest bound) so that two builds can be compared.
//!
//! `cargo run --release --example exact_frame -- [scene] [side] [plain|bounded]`
//! (defaults: `default 256 bounded`).

use softshadow::bvh::{Bvh, Occluders};
use softshadow::reference::exact;
use softshadow::render::Frame;
use softshadow::scene::builtin::builtin;
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map_or("default", String::as_str);
    let side: u32 = args.get(1).map_or(Ok(256), |s| s.parse())?;
    let bounded = args.get(2).is_none_or(|m| m != "plain");
    let scene = builtin(name).ok_or("no such built-in scene")?;
    let camera = scene
        .camera()
        .ok_or("the scene has no camera")?
        .with_resolution(side, side)?;
    let bvh = Bvh::new(Occluders::from_scene(&scene));
    let frame = Frame::from_camera(&camera, &bvh);
    let points = frame.positions();
    let light = scene.light();
    let (sum, worst) = if bounded {
        exact::visibility_many_bounded(&bvh, light, &points)
            .into_iter()
            .flatten()
            .fold((0.0, 0.0_f64), |(s, w), b| {
                (s + b.visibility, w.max(b.bound))
            })
    } else {
        let sum = exact::visibility_many(&bvh, light, &points)
            .into_iter()
            .flatten()
            .sum();
        (sum, f64::NAN)
    };
    println!(
        "{name} {side}² ({} receivers): ΣV = {sum:.17e}, largest bound {worst:.3e}",
        points.len()
    );
    Ok(())
}
