//! Using the renderer from code: build a scene, render it with a method,
//! read the visibility buffer, compare with the exact answer and write the
//! pictures.
//!
//! `cargo run --release --example render`

use softshadow::glam::DVec3;
use softshadow::method::{self, Exact, Pcss};
use softshadow::output::image::{error_heat_map, shaded, ErrorSummary};
use softshadow::render::{Frame, Stages, BACKGROUND};
use softshadow::scene::primitive::{quad, sphere};
use softshadow::scene::{Camera, Light, Scene};
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    // A ball hovering over a floor, a sphere light above, a camera.
    let scene = Scene::new(Light::sphere(DVec3::new(1.0, 4.0, 1.0), 0.6)?)
        .with_mesh("floor", quad(DVec3::ZERO, DVec3::X * 3.0, -DVec3::Z * 3.0)?)
        .with_mesh("ball", sphere(DVec3::new(0.0, 0.8, 0.0), 0.5, 48)?)
        .with_camera(Camera::new(
            DVec3::new(0.0, 2.5, 4.0),
            DVec3::new(0.0, 0.3, 0.0),
            DVec3::Y,
            45.0,
            256,
            256,
        )?);

    // The stages are built lazily and shared by every method run on them.
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(scene.camera().expect("set above"), stages.bvh());

    let pcss = method::run(&Pcss::default(), &stages, &frame)?;
    let exact = method::run(&Exact, &stages, &frame)?;

    // One value per receiver; the frame maps pixels to receivers.
    let (width, _) = frame.size();
    let centre = frame.pixels()[(128 * width + 128) as usize];
    if centre != BACKGROUND {
        let i = centre as usize;
        println!(
            "centre pixel: V = {:.4} by PCSS, {:.4} exactly, at {:?} on object {:?}",
            pcss.output.visibility[i],
            exact.output.visibility[i],
            frame.receivers()[i].position,
            frame.receivers()[i].object,
        );
    }
    let e = ErrorSummary::new(&pcss.output.visibility, &exact.output.visibility, |_| true);
    println!(
        "PCSS against exact over {} receivers: RMSE {:.4}, max {:.3}, bias {:+.4}; {:.1} ms vs {:.1} ms",
        e.count,
        e.rmse,
        e.max_abs,
        e.mean_signed,
        pcss.seconds * 1e3,
        exact.seconds * 1e3
    );
    println!("stages:\n{}", stages.stats());

    let out = std::env::temp_dir();
    let shaded_path = out.join("softshadow-example-shaded.png");
    shaded(&scene, &frame, &pcss.output.visibility).write_png(&shaded_path)?;
    let error_path = out.join("softshadow-example-error.png");
    error_heat_map(&frame, &pcss.output.visibility, &exact.output.visibility)
        .write_png(&error_path)?;
    println!(
        "wrote {} and {}",
        shaded_path.display(),
        error_path.display()
    );
    Ok(())
}
