//! Every method of the sphere light's default set on stiff versions of
//! the default scene: RMSE against the exact reference there, values out
//! of `[0, 1]` or not finite, and the method's RMSE on the scene as built
//! in.

use super::Row;
use crate::kernel::catalogue::Stiff;
use crate::method::{self, Exact, Method};
use crate::output::image::ErrorSummary;
use crate::render::{Frame, Stages};
use crate::scene::primitive::Transform;
use crate::scene::{builtin, Camera, Light, Mesh, Scene};
use glam::DVec3;
use std::fmt::Write as _;

/// A built-in scene moved by `offset`, its light scaled by `light_scale`.
fn moved(name: &str, offset: DVec3, light_scale: f64) -> Option<Scene> {
    let scene = builtin(name)?;
    let t = Transform::new(1.0, 0.0, offset).ok()?;
    let light = match scene.light() {
        Light::Sphere(s) => Light::sphere(s.center() + offset, s.radius() * light_scale).ok()?,
        other => *other,
    };
    let camera = scene.camera()?;
    let (w, h) = camera.resolution();
    let camera = Camera::new(
        camera.eye() + offset,
        camera.target() + offset,
        camera.up(),
        camera.fov_y_deg(),
        w,
        h,
    )
    .ok()?;
    let mut out = Scene::new(light).with_camera(camera);
    for (mesh, name) in scene.meshes().iter().zip(scene.names()) {
        let m: Mesh = t.apply(mesh).ok()?;
        out = out.with_mesh(name.clone(), m);
    }
    Some(out)
}

/// The default scene with its light at elevation `deg` over the floor.
fn grazing(deg: f64) -> Option<Scene> {
    let scene = builtin("default")?;
    let a = deg.to_radians();
    let light = Light::sphere(DVec3::new(6.0 * a.cos(), 6.0 * a.sin() + 0.3, 0.0), 0.5).ok()?;
    Some(scene.with_light(light))
}

/// The scene's camera frame at `side²` and the exact answer there.
fn frame_and_exact(scene: &Scene, side: u32) -> Option<(Frame, Vec<f64>)> {
    let stages = Stages::new(scene);
    let camera = scene.camera()?.with_resolution(side, side).ok()?;
    let frame = Frame::from_camera(&camera, stages.bvh());
    let exact = method::run(&Exact, &stages, &frame).ok()?.output.visibility;
    Some((frame, exact))
}

/// The stiff scenes: their family, case, and the scene (`None` if it
/// could not be built).
fn cases() -> Vec<(&'static str, String, Option<Scene>)> {
    vec![
        (
            Stiff::FarOffset.name(),
            "moved by 2^10".to_owned(),
            moved("default", DVec3::splat(1024.0), 1.0),
        ),
        (
            Stiff::FarOffset.name(),
            "moved by 2^20".to_owned(),
            moved("default", DVec3::splat(1_048_576.0), 1.0),
        ),
        (
            Stiff::LightSize.name(),
            "light radius × 2^-10".to_owned(),
            moved("default", DVec3::ZERO, 1.0 / 1024.0),
        ),
        (
            Stiff::LightSize.name(),
            "light radius × 4".to_owned(),
            moved("default", DVec3::ZERO, 4.0),
        ),
        (
            Stiff::Grazing.name(),
            "light 2° over the floor".to_owned(),
            grazing(2.0),
        ),
        (
            Stiff::Contact.name(),
            "the contact scene".to_owned(),
            builtin("contact"),
        ),
    ]
}

/// Each method's RMSE on the default scene as built in, at `side²`.
fn unmoved(side: u32) -> Vec<(String, f64)> {
    let mut unmoved: Vec<(String, f64)> = Vec::new();
    if let Some(scene) = builtin("default") {
        if let Some((frame, exact)) = frame_and_exact(&scene, side) {
            let stages = Stages::new(&scene);
            for m in method::default_set(scene.light().kind()) {
                if let Ok(run) = method::run(m.as_ref(), &stages, &frame) {
                    let rmse = ErrorSummary::new(&run.output.visibility, &exact, |_| true).rmse;
                    unmoved.push((m.name(), rmse));
                }
            }
        }
    }
    unmoved
}

/// The rows of every method on every stiff scene, at `side²`.
pub(super) fn rows(rows: &mut Vec<Row>, side: u32) {
    let unmoved = unmoved(side);
    for (family, case, scene) in cases() {
        let Some(scene) = scene else {
            rows.push(Row::new(
                "f64",
                "(scene)",
                family,
                case,
                0,
                f64::NAN,
                "the scene could not be built",
            ));
            continue;
        };
        let Some((frame, exact)) = frame_and_exact(&scene, side) else {
            rows.push(Row::new(
                "f64",
                "exact reference",
                family,
                case,
                0,
                f64::NAN,
                "refused (a receiver inside the light, or no camera)",
            ));
            continue;
        };
        let stages = Stages::new(&scene);
        for m in method::default_set(scene.light().kind()) {
            if m.name() == "exact" || m.name().starts_with("mc") {
                continue;
            }
            rows.push(method_row(
                m.as_ref(),
                &stages,
                &frame,
                &exact,
                &unmoved,
                family,
                &case,
            ));
        }
    }
}

/// One method's row on one stiff scene: its RMSE against `exact`, the
/// values out of `[0, 1]`, its RMSE on the scene as built in.
fn method_row(
    m: &dyn Method,
    stages: &Stages,
    frame: &Frame,
    exact: &[f64],
    unmoved: &[(String, f64)],
    family: &'static str,
    case: &str,
) -> Row {
    let mut note = String::new();
    let (max, count) = match method::run(m, stages, frame) {
        Ok(run) => {
            let v = run.output.visibility;
            let bad = v.iter().filter(|x| !(0.0..=1.0).contains(*x)).count();
            let rmse = ErrorSummary::new(&v, exact, |_| true).rmse;
            let before = unmoved.iter().find(|(n, _)| *n == m.name()).map(|x| x.1);
            match before {
                Some(b) => {
                    let _ = write!(note, "RMSE {b:.4} on the scene as built in");
                }
                None => note.push_str("inside"),
            }
            if bad > 0 {
                let _ = write!(note, "; {bad} values outside [0, 1] or not finite");
            }
            (rmse, v.len())
        }
        Err(e) => {
            let _ = write!(note, "refused: {e}");
            (f64::NAN, 0)
        }
    };
    Row {
        subject: m.name(),
        family,
        case: case.to_owned(),
        precision: "f64",
        count,
        max,
        bound: None,
        note,
    }
}
