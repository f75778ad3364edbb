//! # softshadow
//!
//! Geometry kernels for soft shadows from area and linear lights, with the
//! published algorithms built on them, exact and Monte Carlo references, and
//! an accuracy-against-run-time report. Pure CPU, deterministic, and meant to
//! be the trusted reference a GPU implementation is validated against.
//!
//! Every part computes the same quantity: the fraction `V(p) ∈ [0, 1]` of a
//! light's emitting measure visible from a receiver point `p` (see
//! `DESIGN.md` §1 in the repository).
//!
//! ## Modules
//!
//! - [`scene`]: lights, meshes, the camera and the scene, validated at
//!   construction; primitives; with `scene-file`, the JSON scene and points
//!   files and the built-in scenes.
//! - `bvh` (feature `bvh`): the scene's triangles in one flat list
//!   (`Occluders`) and the BVH over them (`Bvh`): conservative occlusion
//!   rays, watertight closest hits, culling; shared by the references, the
//!   renderer and the methods.
//! - `reference` (feature `reference`): the exact and Monte Carlo
//!   visibility references and the statistics that compare them.
//! - `render` (feature `render`): the scalar renderer — receivers from the
//!   camera's primary rays or a points file (`Frame`), the light-view
//!   rasterizer, the lazily built stages every method draws on, shading,
//!   error heat-maps and PNG files.
//! - `method` (feature `render`): the shadow methods behind one `Method`
//!   trait (exact, Monte Carlo, hard shadows, PCSS, SISM), listed once in
//!   `method::registry` with their options, and `method::run`, which checks
//!   a frame once, runs a method on it and times it.
//! - [`kernel`]: the pure geometry kernels (silhouettes, penumbra wedges,
//!   disk occlusion, falloff, the light's footprint on the image plane, SSOC
//!   distortion, the linear-light kernel, the exact segment–triangle test)
//!   and the exact orientation predicates they decide topology with.
//!   Depends on `glam` alone.
//!
//! ## Example
//!
//! The visibility of a disk light of radius ½ past one occluding triangle,
//! already projected onto the light's plane from the receiver (the receiver
//! view of `DESIGN.md` §2): `V = 1 − area(triangle ∩ disk) / πr²`.
//!
//! ```
//! use glam::DVec2;
//! use softshadow::kernel::disk::f64::polygon_disk_area;
//!
//! let r = 0.5;
//! // A triangle covering exactly the half y ≥ 0 of the light (and more).
//! let triangle = [DVec2::new(-10.0, 0.0), DVec2::new(10.0, 0.0), DVec2::new(0.0, 10.0)];
//! let covered = polygon_disk_area(r, &triangle);
//! let visibility = 1.0 - covered / (std::f64::consts::PI * r * r);
//! assert!((visibility - 0.5).abs() < 1e-15);
//! ```
//!
//! ## Precision
//!
//! Scalar kernels come in both `f32` and `f64`, generated from one body:
//! `kernel::disk::f64::segment_disk_area` and
//! `kernel::disk::f32::segment_disk_area` are the same code. Each kernel's
//! documentation states its domain, its behaviour at the edge of that domain,
//! its measured accuracy (see `docs/accuracy/kernels.md`) and its source.
//!
//! ## Feature flags
//!
//! With `--no-default-features` the crate is the kernels alone, on `glam`.
//!
//! - `cli` (default): the `softshadow` command-line program (turns on
//!   `render` and `scene-file`).
//! - `bvh`: `softshadow::bvh`, the occluders and the BVH over them
//!   (`obvhs` for the build, `rayon`).
//! - `reference`: `softshadow::reference`, the visibility references
//!   (turns on `bvh`).
//! - `render`: `softshadow::render` and `softshadow::method`, the renderer
//!   and the shadow methods (turns on `bvh` and `reference`; `png`).
//! - `scene-file`: `scene::file` and `scene::builtin`: JSON scene and points
//!   files, OBJ meshes, the built-in scenes (`serde`, `serde_json`, `tobj`).
//! - `report`: [`report`], the accuracy-against-run-time report (turns on
//!   `render` and `scene-file`; `plotters` for the SVG plots). On by
//!   default through `cli`.
//! - `arbitrary`: [`arbitrary`], deterministic generators of near-degenerate
//!   inputs, shared by the property tests, the fuzz targets and the
//!   benchmarks.

#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(any(test, feature = "arbitrary"))]
pub mod arbitrary;
#[cfg(feature = "bvh")]
pub mod bvh;
pub mod kernel;
#[cfg(feature = "render")]
pub mod method;
#[cfg(feature = "reference")]
pub mod reference;
#[cfg(feature = "render")]
pub mod render;
#[cfg(feature = "report")]
pub mod report;
pub mod scene;
