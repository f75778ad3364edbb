//! The built-in scenes, embedded so that no file is
//! needed: [`builtin`] builds one by name, [`BUILTIN_NAMES`] lists them.
//!
//! Units: the floor is the plane `y = 0` (a quad, mesh 0 in every scene,
//! normal +y), occluders are about one unit across, and every camera is a
//! 512 × 512, 45° pinhole looking at the occluders. Spheres have
//! [`DEFAULT_SEGMENTS`] longitudes (960 triangles). No receiver on any mesh
//! lies inside a sphere light or in the plane of a disk or rect light.
//!
//! | name | light | meshes | triangles | exercises |
//! |---|---|---|---|---|
//! | `default` | sphere, r 0.5, above-front | floor, bunny | 3676 | the Stanford bunny (1 unit tall, resting on the floor): a real mesh with many silhouette edges, ears over the body (self-shadowing) |
//! | `overlapping-penumbrae` | disk, r 0.6, facing down | floor, low plate, high ball | 964 | two occluders at heights 0.6 and 1.6 whose penumbrae overlap on the floor, where methods that add occlusion instead of combining it over-darken |
//! | `contact` | sphere, r 0.4 | floor, box, ball | 974 | a box resting on the floor (face contact) and a ball touching it at one point: the penumbra shrinks to zero width at the contact |
//! | `comb` | sphere, r 0.25 | floor, comb | 170 | 13 thin teeth (0.05 wide, gaps 0.046) 0.3 above the floor, gaps narrower than the penumbra: small concavities, fully penumbral shadows |
//! | `large-light` | sphere, r 2 | floor, ball, box | 974 | a light larger than its occluders: no umbra reaches the floor |
//! | `depth-complexity` | sphere, r 0.5 | floor, 16 layers | 2050 | 16 stacked perforated grids, each offset: many occluding layers per light ray, no straight gap through all |
//! | `linear-light` | segment, length 2.4 | floor, bar across, bar along, box, ball | 998 | a linear light (OESS) over occluders perpendicular and parallel to it |
//! | `several-objects` | sphere, r 0.4 | floor, ball, box, block on the box, card, small ball | 1948 | six object ids, two of them touching, for the object-id test of the single-sample method |
//! | `rect-light` | rect, 1.8 × 0.5 | floor, plate, ball, card rotated 45° | 976 | an elongated rectangular light: anisotropic penumbrae |
//!
//! The bunny is `data/bunny.obj` (npm `bunny@1.0.1`, from the Stanford 3D
//! Scanning Repository, y up, 9.66 units tall), scaled to one unit tall,
//! centred in x and z, its lowest vertex on the floor.

use super::file::{mesh_from_obj, DEFAULT_SEGMENTS};
use super::primitive::{cuboid, merge, quad, sphere, Transform};
use super::{Camera, Light, Mesh, Scene};
use glam::DVec3;
use std::error::Error;

/// The names [`builtin`] accepts, `default` first.
pub const BUILTIN_NAMES: &[&str] = &[
    "default",
    "overlapping-penumbrae",
    "contact",
    "comb",
    "large-light",
    "depth-complexity",
    "linear-light",
    "several-objects",
    "rect-light",
];

/// The built-in scene called `name` (one of [`BUILTIN_NAMES`]), `None` for
/// any other name. Each call builds the scene afresh (the bunny is parsed
/// from the embedded OBJ, about a millisecond).
#[must_use]
pub fn builtin(name: &str) -> Option<Scene> {
    let scene = match name {
        "default" => default(),
        "overlapping-penumbrae" => overlapping_penumbrae(),
        "contact" => contact(),
        "comb" => comb(),
        "large-light" => large_light(),
        "depth-complexity" => depth_complexity(),
        "linear-light" => linear_light(),
        "several-objects" => several_objects(),
        "rect-light" => rect_light(),
        _ => return None,
    };
    // The scenes are fixed data, validated by the tests: an error here is a
    // bug in this file, reported as a missing scene rather than a panic.
    scene.ok()
}

type Built = Result<Scene, Box<dyn Error>>;

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The floor: the square `[−half, half]²` of `y = 0`, normal +y.
fn floor(half: f64) -> Result<Mesh, Box<dyn Error>> {
    Ok(quad(DVec3::ZERO, DVec3::X * half, -DVec3::Z * half)?)
}

/// A 512 × 512, 45° camera, +y up.
fn camera(eye: DVec3, target: DVec3) -> Result<Camera, Box<dyn Error>> {
    Ok(Camera::new(eye, target, DVec3::Y, 45.0, 512, 512)?)
}

fn ball(center: DVec3, radius: f64) -> Result<Mesh, Box<dyn Error>> {
    Ok(sphere(center, radius, DEFAULT_SEGMENTS)?)
}

fn block(min: DVec3, max: DVec3) -> Result<Mesh, Box<dyn Error>> {
    Ok(cuboid(min, max)?)
}

/// The bunny, one unit tall, centred in x and z, lowest vertex at `y = 0`.
fn bunny() -> Result<Mesh, Box<dyn Error>> {
    let raw = mesh_from_obj("bunny.obj", include_bytes!("data/bunny.obj"))?;
    let (lo, hi) = raw.bounds().ok_or("the bunny has no triangles")?;
    let scale = 1.0 / (hi.y - lo.y);
    let center = (lo + hi) * 0.5 * scale;
    let t = Transform::new(scale, 0.0, v(-center.x, -lo.y * scale, -center.z))?;
    Ok(t.apply(&raw)?)
}

fn default() -> Built {
    Ok(Scene::new(Light::sphere(v(1.5, 3.5, 2.0), 0.5)?)
        .with_mesh("floor", floor(3.0)?)
        .with_mesh("bunny", bunny()?)
        .with_camera(camera(v(0.0, 1.6, 3.4), v(0.0, 0.45, 0.0))?))
}

fn overlapping_penumbrae() -> Built {
    Ok(Scene::new(Light::disk(v(0.0, 4.0, 0.0), -DVec3::Y, 0.6)?)
        .with_mesh("floor", floor(3.0)?)
        .with_mesh(
            "low plate",
            quad(v(-0.3, 0.6, 0.0), DVec3::X * 0.4, -DVec3::Z * 0.4)?,
        )
        .with_mesh("high ball", ball(v(0.4, 1.6, 0.0), 0.35)?)
        .with_camera(camera(v(0.0, 2.2, 4.2), v(0.1, 0.6, 0.0))?))
}

fn contact() -> Built {
    Ok(Scene::new(Light::sphere(v(0.5, 3.0, 1.0), 0.4)?)
        .with_mesh("floor", floor(3.0)?)
        .with_mesh("box", block(v(-1.0, 0.0, -0.4), v(-0.2, 0.6, 0.4))?)
        // The south pole is exactly at y = 0.5 − 0.5 = 0.
        .with_mesh("ball", ball(v(0.6, 0.5, 0.0), 0.5)?)
        .with_camera(camera(v(0.0, 1.5, 3.5), v(0.0, 0.3, 0.0))?))
}

fn comb() -> Built {
    let (y0, y1) = (0.3, 0.36);
    let mut parts = vec![block(v(-0.6, y0, -0.5), v(0.6, y1, -0.4))?];
    let (teeth, width) = (13, 0.05);
    let pitch = (1.2 - width) / f64::from(teeth - 1);
    for i in 0..teeth {
        let x = -0.6 + pitch * f64::from(i);
        parts.push(block(v(x, y0, -0.4), v(x + width, y1, 0.5))?);
    }
    Ok(Scene::new(Light::sphere(v(0.0, 2.5, 0.3), 0.25)?)
        .with_mesh("floor", floor(3.0)?)
        .with_mesh("comb", merge(&parts)?)
        .with_camera(camera(v(0.0, 1.6, 1.8), v(0.0, 0.15, 0.0))?))
}

fn large_light() -> Built {
    // The light's lowest point is at y = 2.5, above every occluder.
    Ok(Scene::new(Light::sphere(v(0.0, 4.5, 0.0), 2.0)?)
        .with_mesh("floor", floor(4.0)?)
        .with_mesh("ball", ball(v(0.0, 1.0, 0.0), 0.3)?)
        .with_mesh("box", block(v(0.8, 0.0, -0.2), v(1.2, 0.4, 0.2))?)
        .with_camera(camera(v(0.0, 2.0, 4.0), v(0.2, 0.3, 0.0))?))
}

fn depth_complexity() -> Built {
    let mut scene = Scene::new(Light::sphere(v(0.0, 3.5, 0.0), 0.5)?)
        .with_mesh("floor", floor(3.0)?)
        .with_camera(camera(v(0.0, 2.6, 2.6), v(0.0, 0.6, 0.0))?);
    let (cells, side, pitch) = (8, 0.1, 0.16);
    for layer in 0..16u32 {
        let k = f64::from(layer);
        // Golden-ratio offsets: no two layers' holes line up.
        let golden = 0.618_033_988_749_895;
        let dx = (k * golden).fract() * pitch;
        let dz = (k * golden * golden).fract() * pitch;
        let y = 0.4 + 0.08 * k;
        let mut squares = Vec::with_capacity(cells * cells);
        for i in 0..cells {
            for j in 0..cells {
                let c = v(
                    (i as f64 - 3.5) * pitch + dx - pitch / 2.0,
                    y,
                    (j as f64 - 3.5) * pitch + dz - pitch / 2.0,
                );
                squares.push(quad(c, DVec3::X * (side / 2.0), -DVec3::Z * (side / 2.0))?);
            }
        }
        scene = scene.with_mesh(format!("layer{layer:02}"), merge(&squares)?);
    }
    Ok(scene)
}

fn linear_light() -> Built {
    Ok(
        Scene::new(Light::segment(v(-1.2, 2.5, 0.0), v(1.2, 2.5, 0.0))?)
            .with_mesh("floor", floor(3.0)?)
            .with_mesh("bar across", block(v(-0.05, 0.8, -0.6), v(0.05, 0.9, 0.6))?)
            .with_mesh("bar along", block(v(-0.5, 1.2, 0.5), v(0.5, 1.3, 0.6))?)
            .with_mesh("box", block(v(-0.9, 0.0, -0.3), v(-0.5, 0.5, 0.1))?)
            .with_mesh("ball", ball(v(0.8, 0.5, 0.4), 0.3)?)
            .with_camera(camera(v(0.0, 2.2, 3.5), v(0.0, 0.3, 0.0))?),
    )
}

fn several_objects() -> Built {
    let card = Transform::new(1.0, 30.0, v(-0.1, 0.45, 0.7))?.apply(&quad(
        DVec3::ZERO,
        DVec3::X * 0.25,
        v(0.0, 0.2, -0.2),
    )?)?;
    Ok(Scene::new(Light::sphere(v(-1.0, 3.0, 1.5), 0.4)?)
        .with_mesh("floor", floor(3.0)?)
        .with_mesh("ball", ball(v(-0.7, 0.35, 0.0), 0.35)?)
        .with_mesh("box", block(v(0.2, 0.0, -0.3), v(0.7, 0.5, 0.2))?)
        // Rests on the box: two object ids share the face y = 0.5.
        .with_mesh("block", block(v(0.3, 0.5, -0.2), v(0.6, 0.8, 0.1))?)
        .with_mesh("card", card)
        .with_mesh("small ball", ball(v(0.0, 1.2, -0.5), 0.2)?)
        .with_camera(camera(v(0.0, 1.8, 3.2), v(0.0, 0.4, 0.0))?))
}

fn rect_light() -> Built {
    let card = Transform::new(1.0, 45.0, v(-0.9, 0.8, 0.0))?.apply(&quad(
        DVec3::ZERO,
        DVec3::X * 0.3,
        -DVec3::Z * 0.3,
    )?)?;
    Ok(Scene::new(Light::rect(
        v(0.0, 3.0, 0.0),
        v(0.9, 0.0, 0.0),
        v(0.0, 0.0, 0.25),
    )?)
    .with_mesh("floor", floor(3.0)?)
    .with_mesh("plate", block(v(-0.3, 0.6, -0.3), v(0.3, 0.7, 0.3))?)
    .with_mesh("ball", ball(v(0.9, 0.4, 0.4), 0.4)?)
    .with_mesh("card", card)
    .with_camera(camera(v(0.0, 2.0, 3.5), v(0.0, 0.3, 0.0))?))
}

/// A `side × side` grid of receivers on the floor (`y = 0`, mesh 0 of every
/// built-in scene) centred on the shadow that the other meshes cast from the
/// light's centre, spanning 2.4 times their largest extent: most of a
/// built-in scene's penumbrae, for checks and benchmarks. Empty when the
/// scene has no occluder besides the floor, or the light is not above the
/// occluders.
#[must_use]
pub fn floor_receivers(scene: &Scene, side: usize) -> Vec<DVec3> {
    let Some((lo, hi)) = scene
        .meshes()
        .iter()
        .skip(1)
        .filter_map(Mesh::bounds)
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
    else {
        return Vec::new();
    };
    let c = scene.light().center();
    let m = (lo + hi) * 0.5;
    if c.y <= m.y || c.y.is_nan() || side == 0 {
        return Vec::new();
    }
    // The light-centre shadow of the occluders' centre on the floor.
    let s = c + (m - c) * (c.y / (c.y - m.y));
    let half = (hi - lo).max_element() * 1.2;
    let step = if side > 1 {
        2.0 * half / (side - 1) as f64
    } else {
        0.0
    };
    (0..side * side)
        .map(|k| {
            let (i, j) = ((k % side) as f64, (k / side) as f64);
            DVec3::new(s.x - half + step * i, 0.0, s.z - half + step * j)
        })
        .collect()
}
