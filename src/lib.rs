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
//! - `reference` (feature `reference`): the exact and Monte Carlo
//!   visibility references, the BVH they share, and the statistics that
//!   compare them.
//! - [`kernel`]: the pure geometry kernels (silhouettes, penumbra wedges,
//!   disk occlusion, falloff, SSOC distortion, the linear-light kernel) and
//!   the exact orientation predicates they decide topology with. Depends on
//!   `glam` alone.
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
//!   `reference` and `scene-file`).
//! - `reference`: `softshadow::reference`, the visibility references
//!   (`obvhs`, `rayon`).
//! - `scene-file`: `scene::file` and `scene::builtin`: JSON scene and points
//!   files, OBJ meshes, the built-in scenes (`serde`, `serde_json`, `tobj`).
//! - `arbitrary`: [`arbitrary`], deterministic generators of near-degenerate
//!   inputs, shared by the property tests, the fuzz targets and the
//!   benchmarks.

#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(any(test, feature = "arbitrary"))]
pub mod arbitrary;
pub mod kernel;
#[cfg(feature = "render")]
pub mod method;
#[cfg(feature = "reference")]
pub mod reference;
#[cfg(feature = "render")]
pub mod render;
pub mod scene;
