//! `softshadow._native`: the Python package's binding of the softshadow
//! library (PyO3 and rust-numpy). The Python part (`softshadow/` beside
//! this crate) re-exports it; the stubs there (`__init__.pyi`) are the
//! documented API.
//!
//! Rules every function here keeps:
//! - arrays are read in place when they are C-contiguous `float64` (or the
//!   integer dtype asked for); `float32` and narrower integers are widened
//!   (exactly); other dtypes, non-contiguous arrays, wrong shapes and
//!   non-finite values are refused with `ValueError` and the library's
//!   one-line message; nothing is copied silently to fix a layout;
//! - results are moved into numpy arrays without a copy
//!   ([`PyArray1::from_vec`]);
//! - the library computes with the GIL released, on a thread of its own,
//!   while the calling thread checks for signals every 50 ms: Ctrl-C
//!   cancels the run ([`Stages::cancel`]) and raises `KeyboardInterrupt`;
//! - no panic crosses into Python: a panic of the library (a bug) is a
//!   `RuntimeError`.

mod arrays;

use arrays::{as_array, floats, integers, receivers, value_error};
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyFileNotFoundError, PyIsADirectoryError, PyOSError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use softshadow::glam::DVec3;
use softshadow::method::registry::{self, SeedError, REGISTRY};
use softshadow::method::{self, Exact, Method, MethodError};
use softshadow::output::gbuffer::{frame_from_arrays, CameraModel, GBuffer};
use softshadow::output::score::Score;
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin::{builtin, BUILTIN_NAMES};
use softshadow::scene::file::{load_scene, DOMAIN};
use softshadow::scene::{self, Mesh, Scene as LibScene};
use std::path::PathBuf;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How often the calling thread checks for signals while the library
/// computes.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// The largest image side `gbuffer` and `score` take (as the command line).
const MAX_SIDE: usize = 16384;

/// A float64 array handed to Python.
type Array<'py> = Bound<'py, PyArray1<f64>>;

/// An integer argument as `T`: a Python int out of `T`'s range (a negative
/// seed, say) is a `ValueError` naming it, not an `OverflowError`.
fn int_arg<'py, T: FromPyObjectOwned<'py>>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    range: &str,
) -> PyResult<T> {
    obj.extract::<T>().map_err(|_| {
        let shown = obj
            .repr()
            .map_or_else(|_| "the value".to_owned(), |r| r.to_string());
        value_error(format!("{what}={shown}: expected an integer from {range}"))
    })
}

/// `seed=`: an integer from 0 to 2⁶⁴ − 1, or None.
fn seed_arg(seed: Option<&Bound<'_, PyAny>>) -> PyResult<Option<u64>> {
    seed.map(|s| int_arg::<u64>(s, "seed", "0 to 18446744073709551615"))
        .transpose()
}

// ------------------------------------------------------------- computing

/// Runs `work` on `scene`'s fresh stages with the GIL released, on a
/// thread of its own, while this thread checks for signals: a signal
/// handler's exception (`KeyboardInterrupt` for Ctrl-C) cancels the run
/// and is raised once the run has stopped. A panic of the library is a
/// `RuntimeError`.
fn compute<T: Send>(
    py: Python<'_>,
    scene: &LibScene,
    work: impl FnOnce(&Stages) -> T + Send,
) -> PyResult<T> {
    py.detach(|| {
        let stages = Stages::new(scene);
        let (done, finished) = mpsc::channel::<()>();
        std::thread::scope(|s| {
            let stages = &stages;
            let worker = s.spawn(move || {
                let out = work(stages);
                let _ = done.send(());
                out
            });
            let mut interrupted = None;
            // Ends when the worker sends or, having panicked, drops `done`.
            while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(SIGNAL_POLL) {
                if interrupted.is_none() {
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        stages.cancel();
                        interrupted = Some(e);
                    }
                }
            }
            let out = worker.join();
            match (interrupted, out) {
                (Some(e), _) => Err(e),
                (None, Ok(out)) => Ok(out),
                (None, Err(_)) => Err(PyRuntimeError::new_err(
                    "internal error: the library panicked (a bug; please report it with the input)",
                )),
            }
        })
    })
}

/// A [`MethodError`] as a Python exception: a receiver's fault names its
/// row of `points`.
fn method_error(e: MethodError) -> PyErr {
    match e {
        MethodError::Receiver { index, error } => {
            value_error(format!("points: row {index}: {error}"))
        }
        MethodError::NeedsNormal { .. } => value_error(format!("{e}; give normals=(n, 3) array")),
        MethodError::NeedsObject { .. } => {
            value_error(format!("{e}; give objects=(n,) array of mesh indices"))
        }
        MethodError::Contract { .. } => PyRuntimeError::new_err(e.to_string()),
        MethodError::Cancelled => pyo3::exceptions::PyKeyboardInterrupt::new_err("cancelled"),
        e => value_error(e.to_string()),
    }
}

/// The method `name` with `seed`, as the command line's `--method NAME
/// --seed S`.
fn parse_method(name: &str, seed: Option<u64>) -> PyResult<Box<dyn Method>> {
    registry::parse_with_seed(name, seed).map_err(|e| match e {
        SeedError::Parse(e) => value_error(e.to_string()),
        SeedError::Repeated => value_error(format!(
            "seed={}: method {name} sets seed= already; give the seed once",
            seed.unwrap_or_default()
        )),
        e => value_error(format!("seed={}: {e}", seed.unwrap_or_default())),
    })
}

/// A method's run on a frame of receivers: its output, and the seconds
/// the library's run took (the binding's overhead is the rest).
fn run_on(
    py: Python<'_>,
    scene: &LibScene,
    method: &dyn Method,
    frame: &Frame,
) -> PyResult<method::Run> {
    compute(py, scene, |stages| method::run(method, stages, frame))?.map_err(method_error)
}

// ---------------------------------------------------------------- lights

/// A light: one of `SphereLight`, `DiskLight`, `RectLight`,
/// `SegmentLight`, `PointLight`.
#[pyclass(subclass, frozen, module = "softshadow")]
struct Light {
    light: scene::Light,
}

#[pymethods]
impl Light {
    /// The light's kind: `"sphere"`, `"disk"`, `"rect"`, `"segment"` or
    /// `"point"`.
    #[getter]
    fn kind(&self) -> &'static str {
        self.light.kind().name()
    }

    /// The light's centre.
    #[getter]
    fn center(&self) -> [f64; 3] {
        self.light.center().to_array()
    }

    fn __repr__(&self) -> String {
        format!("<softshadow {} light at {:?}>", self.kind(), self.center())
    }
}

fn light(made: Result<scene::Light, scene::LightError>) -> PyResult<PyClassInitializer<Light>> {
    made.map(|light| PyClassInitializer::from(Light { light }))
        .map_err(|e| value_error(e.to_string()))
}

fn v3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// A sphere light: `SphereLight(center, radius)`; emits from its whole
/// surface. Raises `ValueError` for a non-finite centre or a radius not
/// positive and finite.
#[pyclass(extends = Light, frozen, module = "softshadow")]
struct SphereLight;

#[pymethods]
impl SphereLight {
    #[new]
    fn new(center: [f64; 3], radius: f64) -> PyResult<PyClassInitializer<Self>> {
        Ok(light(scene::Light::sphere(v3(center), radius))?.add_subclass(SphereLight))
    }
}

/// A disk light: `DiskLight(center, normal, radius)`, emitting on both
/// sides. Raises `ValueError` for a zero normal or a radius not positive.
#[pyclass(extends = Light, frozen, module = "softshadow")]
struct DiskLight;

#[pymethods]
impl DiskLight {
    #[new]
    fn new(center: [f64; 3], normal: [f64; 3], radius: f64) -> PyResult<PyClassInitializer<Self>> {
        Ok(light(scene::Light::disk(v3(center), v3(normal), radius))?.add_subclass(DiskLight))
    }
}

/// A rectangle light: `RectLight(center, u, v)`, the half-extent vectors
/// `u` and `v` perpendicular, emitting on both sides. Raises `ValueError`
/// for degenerate or non-perpendicular half-extents.
#[pyclass(extends = Light, frozen, module = "softshadow")]
struct RectLight;

#[pymethods]
impl RectLight {
    #[new]
    fn new(center: [f64; 3], u: [f64; 3], v: [f64; 3]) -> PyResult<PyClassInitializer<Self>> {
        Ok(light(scene::Light::rect(v3(center), v3(u), v3(v)))?.add_subclass(RectLight))
    }
}

/// A segment (linear) light: `SegmentLight(a, b)`. Raises `ValueError`
/// for coincident ends.
#[pyclass(extends = Light, frozen, module = "softshadow")]
struct SegmentLight;

#[pymethods]
impl SegmentLight {
    #[new]
    fn new(a: [f64; 3], b: [f64; 3]) -> PyResult<PyClassInitializer<Self>> {
        Ok(light(scene::Light::segment(v3(a), v3(b)))?.add_subclass(SegmentLight))
    }
}

/// A point light: `PointLight(position)`; `V` is 0 or 1.
#[pyclass(extends = Light, frozen, module = "softshadow")]
struct PointLight;

#[pymethods]
impl PointLight {
    #[new]
    fn new(position: [f64; 3]) -> PyResult<PyClassInitializer<Self>> {
        Ok(light(scene::Light::point(v3(position)))?.add_subclass(PointLight))
    }
}

// ----------------------------------------------------------------- scene

/// A scene: occluder meshes and one light (and, for a built-in scene or a
/// scene file with one, a camera). Immutable; safe to share between
/// threads.
#[pyclass(frozen, module = "softshadow")]
struct Scene {
    scene: Arc<LibScene>,
}

/// A mesh's triangles as `u32` vertex indices.
fn triangles(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[u32; 3]>> {
    let (t, _) = integers(obj, what, "(m, 3)", 2)?;
    t.chunks_exact(3)
        .enumerate()
        .map(|(k, c)| {
            let mut out = [0u32; 3];
            for (o, &i) in out.iter_mut().zip(c) {
                *o = u32::try_from(i).map_err(|_| {
                    value_error(format!(
                        "{what}: row {k}: vertex index {i} is negative or too large"
                    ))
                })?;
            }
            Ok(out)
        })
        .collect()
}

#[pymethods]
impl Scene {
    /// `Scene(meshes, light, names=None)`: `meshes` a list of `(positions,
    /// triangles)` pairs, positions an (n, 3) float array, triangles an
    /// (m, 3) integer array of vertex indices; `light` one of the light
    /// classes. Raises `ValueError` for a non-finite or out-of-domain
    /// (beyond ±1e30) position, an index out of range, a wrong shape or
    /// dtype.
    #[new]
    #[pyo3(signature = (meshes, light, names = None))]
    fn new(
        meshes: &Bound<'_, PyAny>,
        light: &Bound<'_, Light>,
        names: Option<Vec<String>>,
    ) -> PyResult<Self> {
        let mut scene = LibScene::new(light.get().light);
        let list: Vec<Bound<'_, PyAny>> = meshes
            .try_iter()
            .map_err(|_| value_error("meshes: expected a list of (positions, triangles) pairs"))?
            .collect::<PyResult<_>>()?;
        if let Some(names) = &names {
            if names.len() != list.len() {
                return Err(value_error(format!(
                    "names: {} names for {} meshes",
                    names.len(),
                    list.len()
                )));
            }
        }
        for (k, item) in list.iter().enumerate() {
            let (positions, tris): (Bound<'_, PyAny>, Bound<'_, PyAny>) =
                item.extract().map_err(|_| {
                    value_error(format!(
                        "meshes[{k}]: expected a (positions, triangles) pair"
                    ))
                })?;
            let what = format!("meshes[{k}] positions");
            let (p, _) = floats(&positions, &what, "(n, 3)", 2)?;
            let p = p.as_slice();
            if let Some(x) = p.iter().find(|x| !x.is_finite() || x.abs() > DOMAIN) {
                let row = p
                    .iter()
                    .position(|y| y.to_bits() == x.to_bits())
                    .unwrap_or(0)
                    / 3;
                return Err(value_error(format!(
                    "{what}: row {row}: {x} is not a finite number within ±1e30"
                )));
            }
            let positions: Vec<DVec3> = p
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0], c[1], c[2]))
                .collect();
            let tris = triangles(&tris, &format!("meshes[{k}] triangles"))?;
            let mesh =
                Mesh::new(positions, tris).map_err(|e| value_error(format!("meshes[{k}]: {e}")))?;
            let name = names
                .as_ref()
                .map_or_else(|| format!("mesh{k}"), |n| n[k].clone());
            scene = scene.with_mesh(name, mesh);
        }
        Ok(Scene {
            scene: Arc::new(scene),
        })
    }

    /// `Scene.from_file(path)`: a scene file (our JSON format; the OBJ
    /// meshes it names are read relative to it). Raises `OSError`
    /// (`FileNotFoundError`) when the file cannot be read, `ValueError`
    /// for its content, each with the library's one-line message.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let loaded = py.detach(|| load_scene(&path));
        match loaded {
            Ok(scene) => Ok(Scene {
                scene: Arc::new(scene),
            }),
            Err(e) => Err(match std::fs::metadata(&path) {
                Err(io) if io.kind() == std::io::ErrorKind::NotFound => {
                    PyFileNotFoundError::new_err(e.to_string())
                }
                Err(_) => PyOSError::new_err(e.to_string()),
                Ok(m) if m.is_dir() => PyIsADirectoryError::new_err(e.to_string()),
                Ok(m) if !m.is_file() => PyOSError::new_err(e.to_string()),
                Ok(_) => value_error(e.to_string()),
            }),
        }
    }

    /// `Scene.builtin(name)`: a built-in scene (`builtin_names()` lists
    /// them). Raises `ValueError` for an unknown name.
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        builtin(name)
            .map(|scene| Scene {
                scene: Arc::new(scene),
            })
            .ok_or_else(|| {
                value_error(format!(
                    "no built-in scene {name:?} (built-in: {})",
                    BUILTIN_NAMES.join(", ")
                ))
            })
    }

    /// The light's kind (`"sphere"`, …).
    #[getter]
    fn light_kind(&self) -> &'static str {
        self.scene.light().kind().name()
    }

    /// The mesh names, in object-id order.
    #[getter]
    fn mesh_names(&self) -> Vec<String> {
        self.scene.names().to_vec()
    }

    /// The number of triangles of every mesh.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.scene.triangle_count()
    }

    /// The camera's resolution `(width, height)`, or None without a camera.
    #[getter]
    fn camera_resolution(&self) -> Option<(u32, u32)> {
        self.scene
            .camera()
            .map(softshadow::scene::Camera::resolution)
    }

    fn __repr__(&self) -> String {
        format!(
            "<softshadow.Scene: {} meshes, {} triangles, a {} light>",
            self.scene.meshes().len(),
            self.scene.triangle_count(),
            self.light_kind()
        )
    }

    /// `V` at each receiver by `method` (a name of the registry:
    /// `"exact"`, `"mc:256"`, `"sism:horizon"`, …; `methods()` lists
    /// them), as an (n,) float64 array. `points` (n, 3) float64;
    /// `normals` (n, 3) (normalised here; some methods need them),
    /// `objects` (n,) integer mesh ids (some methods need them); `seed`
    /// the Monte Carlo seed (the option `seed=` of `mc:N`).
    #[pyo3(signature = (points, normals = None, objects = None, method = "exact", seed = None))]
    fn visibility<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        normals: Option<&Bound<'py, PyAny>>,
        objects: Option<&Bound<'py, PyAny>>,
        method: &str,
        seed: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (v, _, _) = self.timed_visibility(py, points, normals, objects, method, seed)?;
        Ok(v)
    }

    /// `visibility`, the seconds the library's run took (checks, stages
    /// and the method's pass: `method::run`) and the seconds the receivers
    /// and their frame took to build from the arrays (what a Rust caller
    /// holding the same arrays does too), for measuring the binding's
    /// overhead.
    #[pyo3(signature = (points, normals = None, objects = None, method = "exact", seed = None))]
    fn timed_visibility<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        normals: Option<&Bound<'py, PyAny>>,
        objects: Option<&Bound<'py, PyAny>>,
        method: &str,
        seed: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, f64, f64)> {
        let m = parse_method(method, seed_arg(seed)?)?;
        let start = Instant::now();
        let frame = Frame::from_receivers(receivers(
            py,
            points,
            normals,
            objects,
            self.scene.meshes().len(),
        )?);
        let building = start.elapsed().as_secs_f64();
        let run = run_on(py, &self.scene, m.as_ref(), &frame)?;
        Ok((
            PyArray1::from_vec(py, run.output.visibility),
            run.seconds,
            building,
        ))
    }

    /// Monte Carlo light sampling with `samples` samples per receiver
    /// (method `mc:samples`): `(V, stderr)`, two (n,) float64 arrays, the
    /// estimate and its standard error. `seed` as the method's option.
    #[pyo3(signature = (points, samples, seed = None, normals = None))]
    fn monte_carlo<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        samples: &Bound<'py, PyAny>,
        seed: Option<&Bound<'py, PyAny>>,
        normals: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<(Array<'py>, Array<'py>)> {
        let samples: u32 = int_arg(samples, "samples", "2 to 4294967295")?;
        let m = parse_method(&format!("mc:{samples}"), seed_arg(seed)?)?;
        let r = receivers(py, points, normals, None, self.scene.meshes().len())?;
        let run = run_on(py, &self.scene, m.as_ref(), &Frame::from_receivers(r))?;
        let stderr = run.output.stderr.ok_or_else(|| {
            PyRuntimeError::new_err("internal error: Monte Carlo gave no standard errors")
        })?;
        Ok((
            PyArray1::from_vec(py, run.output.visibility),
            PyArray1::from_vec(py, stderr),
        ))
    }

    /// The receivers the scene's camera sees at `width` × `height`, as a
    /// dict of arrays (row 0 the top of the image): `position` (h, w, 3),
    /// `normal` (h, w, 3) (unit, facing the camera), `object` (h, w)
    /// int32 (−1 where no surface), `exact` (h, w) the exact `V` (NaN
    /// where no surface), and `camera` (the camera model, as the command
    /// line's camera.json). Raises `ValueError` for a scene without a
    /// camera or a size outside 1 to 16384.
    fn gbuffer<'py>(
        &self,
        py: Python<'py>,
        width: &Bound<'py, PyAny>,
        height: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let side = |v, what| int_arg::<usize>(v, what, &format!("1 to {MAX_SIDE}"));
        let camera = self.camera(side(width, "width")?, side(height, "height")?)?;
        let scene = &self.scene;
        let g = compute(py, scene, |stages| {
            let frame = Frame::from_camera(&camera, stages.bvh());
            method::run(&Exact, stages, &frame).map(|run| {
                GBuffer::from_frame(
                    &frame,
                    &run.output.visibility,
                    CameraModel::new(&camera, scene.bounds()),
                )
            })
        })?
        .map_err(method_error)?;
        let (w, h) = (g.width as usize, g.height as usize);
        let out = PyDict::new(py);
        out.set_item(
            "position",
            PyArray1::from_vec(py, g.position).reshape([h, w, 3])?,
        )?;
        out.set_item(
            "normal",
            PyArray1::from_vec(py, g.normal).reshape([h, w, 3])?,
        )?;
        out.set_item("object", PyArray1::from_vec(py, g.object).reshape([h, w])?)?;
        out.set_item("exact", PyArray1::from_vec(py, g.exact).reshape([h, w])?)?;
        let json = py.import("json")?;
        out.set_item(
            "camera",
            json.call_method1("loads", (g.camera.to_json(scene),))?,
        )?;
        Ok(out)
    }
}

impl Scene {
    /// The scene's camera at `width` × `height`.
    fn camera(&self, width: usize, height: usize) -> PyResult<softshadow::scene::Camera> {
        if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
            return Err(value_error(format!(
                "{width}×{height} pixels; an image is 1 to {MAX_SIDE} pixels a side"
            )));
        }
        let camera = self
            .scene
            .camera()
            .ok_or_else(|| value_error("the scene has no camera"))?;
        camera
            .with_resolution(width as u32, height as u32)
            .map_err(|e| value_error(e.to_string()))
    }
}

// ----------------------------------------------------------------- score

/// `score(scene, image, gbuffer=None)`: an image of `V` made elsewhere,
/// (h, w) float, scored against the exact answer on the same receivers:
/// our camera's at the image's size, or those of `gbuffer` (a dict with
/// `position` (h, w, 3), `normal` (h, w, 3), `object` (h, w) integers, −1
/// where no surface: ours from `Scene.gbuffer`, or one's own
/// rasteriser's). Returns the dict `softshadow score --json` prints.
/// NaN or infinite pixels are counted (`nan_pixels`), not scored.
#[pyfunction]
#[pyo3(signature = (scene, image, gbuffer = None))]
fn score<'py>(
    py: Python<'py>,
    scene: &Scene,
    image: &Bound<'py, PyAny>,
    gbuffer: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let a = as_array(image, "image")?;
    if a.ndim() != 2 {
        return Err(value_error(format!(
            "image: shape {:?}, expected (height, width)",
            a.shape()
        )));
    }
    let (h, w) = (a.shape()[0], a.shape()[1]);
    // NaN pixels are part of what is scored: not refused here.
    let (img, _) = floats(a.as_any(), "image", "(height, width)", 2)?;
    let frame = match gbuffer {
        None => {
            let camera = scene.camera(w, h)?;
            let lib = &scene.scene;
            compute(py, lib, |stages| Frame::from_camera(&camera, stages.bvh()))?
        }
        Some(g) => {
            let item = |key: &str| -> PyResult<Bound<'py, PyAny>> {
                g.get_item(key)
                    .map_err(|_| value_error(format!("gbuffer: no '{key}' array")))
            };
            let shape3 = format!("({h}, {w}, 3)");
            let (pos, ps) = floats(&item("position")?, "gbuffer['position']", &shape3, 3)?;
            let (nrm, ns) = floats(&item("normal")?, "gbuffer['normal']", &shape3, 3)?;
            let (obj, os) = integers(
                &item("object")?,
                "gbuffer['object']",
                &format!("({h}, {w})"),
                2,
            )?;
            for (name, s, want) in [
                ("position", ps, vec![h, w, 3]),
                ("normal", ns, vec![h, w, 3]),
                ("object", os, vec![h, w]),
            ] {
                if s != want {
                    return Err(value_error(format!(
                        "gbuffer['{name}']: shape {s:?}, the image is {w}×{h} (expected {want:?})"
                    )));
                }
            }
            frame_from_arrays(
                w,
                h,
                pos.as_slice(),
                nrm.as_slice(),
                &obj,
                scene.scene.meshes().len(),
            )
            .map_err(|e| value_error(format!("gbuffer['{}']: {e}", e.array)))?
        }
    };
    let lib = &scene.scene;
    let image = img.as_slice();
    let json = compute(py, lib, |stages| {
        method::run(&Exact, stages, &frame).map(|run| {
            let (score, _) = Score::new(&frame, lib.light(), image, &run.output.visibility);
            score.to_json()
        })
    })?
    .map_err(|e| match e {
        MethodError::Receiver { index, error } => {
            let at = frame
                .pixels()
                .iter()
                .position(|&i| i as usize == index)
                .map_or(String::new(), |k| {
                    format!(" (row {}, column {})", k / w.max(1), k % w.max(1))
                });
            value_error(format!("gbuffer: the receiver at pixel{at}: {error}"))
        }
        e => method_error(e),
    })?;
    py.import("json")?.call_method1("loads", (json,))
}

// ---------------------------------------------------------------- registry

/// The registry of methods, one dict per method: `name` (the base name),
/// `usage` (`mc:N`), `summary`, `lights` (the light kinds it handles),
/// `options` (one line per option: what it accepts, its default),
/// `default_run` (the settings the default run compares, on each light
/// kind of `lights`) and `compare` (the settings a report compares).
#[pyfunction]
fn methods(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for e in REGISTRY {
        let d = PyDict::new(py);
        d.set_item("name", e.name)?;
        d.set_item("usage", e.usage())?;
        d.set_item("summary", e.summary)?;
        d.set_item(
            "lights",
            e.lights.iter().map(|k| k.name()).collect::<Vec<_>>(),
        )?;
        d.set_item("options", e.options())?;
        d.set_item("default_run", e.default_run.to_vec())?;
        d.set_item("compare", e.compare.to_vec())?;
        out.append(d)?;
    }
    Ok(out)
}

/// The names of the built-in scenes.
#[pyfunction]
fn builtin_names() -> Vec<&'static str> {
    BUILTIN_NAMES.to_vec()
}

/// The module `softshadow._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Light>()?;
    m.add_class::<SphereLight>()?;
    m.add_class::<DiskLight>()?;
    m.add_class::<RectLight>()?;
    m.add_class::<SegmentLight>()?;
    m.add_class::<PointLight>()?;
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(score, m)?)?;
    m.add_function(wrap_pyfunction!(methods, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_names, m)?)?;
    Ok(())
}
