//! # softshadow
//!
//! Geometry kernels for soft shadows from area and linear lights, with the
//! published algorithms built on them, exact and Monte Carlo references, and
//! an accuracy-against-run-time report. Pure CPU, deterministic, and meant to
//! be the trusted reference a GPU implementation is validated against.
//!
//! Every part computes the same quantity: the fraction `V(p) ∈ [0, 1]` of a
//! light's emitting measure visible from a receiver point `p` (see
//! [`definitions`], which defines every quantity the crate computes).
//!
//! ## Modules
//!
//! | module | feature | what |
//! |---|---|---|
//! | [`definitions`] | — | the quantity `V`, shading, the frames, the footprint, the receiver view, the error statistics and receiver groups, in words: what every other module refers to |
//! | [`kernel`] | — | the pure geometry kernels: silhouettes, penumbra wedges, disk occlusion, falloffs, the light's footprint, SSOC distortion, the linear-light kernel, the exact segment–triangle test, the receiver view (exact visibility of a few triangles), and the exact orientation predicates they decide topology with. Depends on `glam` alone |
//! | [`scene`] | — (file and built-ins: `scene-file`) | lights (validated; each receiver's [`Emitter`]), meshes, primitives, the camera and the scene, validated at construction; with `scene-file`, the JSON scene and points files and the built-in scenes |
//! | `bvh` | `bvh` | the scene's triangles in one flat list ([`Occluders`]) and the BVH over them ([`Bvh`]): conservative occlusion rays, watertight closest hits, culling |
//! | `reference` | `reference` | the exact and Monte Carlo visibility references and the statistics that compare them ([`reference::agree`]) |
//! | `render` | `render` | what the methods build on: receivers from the camera's primary rays or a points file ([`Frame`]), the lazily built [`Stages`] every method draws on, the light-view rasterizer |
//! | `method` | `render` | the shadow methods behind one [`Method`] trait (exact, Monte Carlo, hard shadows, PCSS, SISM, single-sample, SSOC and its backprojected variant, OESS), listed once in `method::registry` with their options, and [`method::run`], which checks a frame once, runs a method on it and times it |
//! | `output` | `render` | what is done with a method's answers: shading, error heat-maps and summaries ([`ErrorSummary`]), PNG files, scores of images made elsewhere, the G-buffer |
//! | `report` | `report` | the accuracy-against-run-time report and the stability suite |
//! | `arbitrary` | `arbitrary` | deterministic generators of near-degenerate input, shared by the property tests, the fuzz targets and the benchmarks |
//!
//! The main types are re-exported here: [`Scene`], [`Light`], [`Mesh`],
//! [`Emitter`], [`Receiver`], [`Occluders`], [`Bvh`], [`Frame`],
//! [`Stages`], [`Method`], [`ErrorSummary`], and `glam` itself
//! ([`glam`], version 0.34, whose `DVec3` and `Vec3` every signature uses),
//! so a dependant needs no `glam` line of its own and cannot get a second,
//! incompatible copy.
//!
//! From a scene to the references in one step:
//!
//! ```
//! # #[cfg(feature = "reference")] {
//! use softshadow::glam::DVec3;
//! use softshadow::{reference, scene::primitive, Bvh, Light, Scene};
//!
//! let light = Light::sphere(DVec3::new(0.0, 4.0, 0.0), 0.5)?;
//! let plate = primitive::quad(DVec3::new(0.0, 2.0, 0.0), DVec3::X, DVec3::Z)?;
//! let scene = Scene::new(light).with_mesh("plate", plate);
//! let bvh = Bvh::from_scene(&scene);
//! // Right under the plate's centre, which covers the whole light.
//! let v = reference::exact::visibility(&bvh, scene.light(), DVec3::ZERO)?;
//! assert_eq!(v, 0.0);
//! # }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Example
//!
//! The visibility of a disk light of radius ½ past one occluding triangle,
//! already projected onto the light's plane from the receiver (the receiver
//! view of [`definitions`]): `V = 1 − area(triangle ∩ disk) / πr²`.
//!
//! ```
//! use softshadow::glam::DVec2;
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
//! The default features are what a library user needs: `simd`, `render`
//! (hence `bvh` and `reference`) and `scene-file`. The command-line program
//! is the crate `softshadow-cli`, whose crates (`clap`, `indicatif`) a
//! dependant never builds. With `--no-default-features` the crate is the
//! kernels alone, on `glam`.
//!
//! - `simd` (default): the batched kernels, Monte Carlo's passes, the
//!   culling query and the occlusion rays in AVX2 registers with FMA where
//!   the processor has them, chosen at run time (`pulp`); the same bits
//!   without it.
//! - `bvh`: `softshadow::bvh`, the occluders and the BVH over them
//!   (`obvhs` for the build, `rayon`).
//! - `reference`: `softshadow::reference`, the visibility references
//!   (turns on `bvh`).
//! - `render`: `softshadow::render` and `softshadow::method`, the renderer
//!   and the shadow methods (turns on `bvh` and `reference`; `png`).
//! - `scene-file`: `scene::file` and `scene::builtin`: JSON scene and points
//!   files, OBJ meshes, the built-in scenes (`serde`, `serde_json`, `tobj`).
//! - `report`: [`report`], the accuracy-against-run-time report (turns on
//!   `render` and `scene-file`; `plotters` for the SVG plots). Not on by
//!   default; the command line turns it on.
//! - `arbitrary`: `softshadow::arbitrary`, deterministic generators of near-degenerate
//!   inputs, shared by the property tests, the fuzz targets and the
//!   benchmarks.

// Links to the items of a feature that is off lead to the list above, so
// that the page documents every feature set without a broken link (each
// `doc = ""` ends the paragraph before the link definitions).
#![cfg_attr(
    not(feature = "bvh"),
    doc = "",
    doc = "[`Occluders`]: #feature-flags",
    doc = "[`Bvh`]: #feature-flags"
)]
#![cfg_attr(
    not(feature = "reference"),
    doc = "",
    doc = "[`reference::agree`]: #feature-flags"
)]
#![cfg_attr(
    not(feature = "render"),
    doc = "",
    doc = "[`Frame`]: #feature-flags",
    doc = "[`Stages`]: #feature-flags",
    doc = "[`ErrorSummary`]: #feature-flags",
    doc = "[`Method`]: #feature-flags",
    doc = "[`method::run`]: #feature-flags"
)]
#![cfg_attr(not(feature = "report"), doc = "", doc = "[`report`]: #feature-flags")]
#![cfg_attr(docsrs, feature(doc_cfg))]

// Under its own name for dependants (and for the crate's own modules: an
// `extern crate` at the root is in every module's scope); see `glam_dep`
// in Cargo.toml.
pub extern crate glam_dep as glam;

/// `Display` and `std::error::Error` for an error type: the message is
/// the closure's body (`|error, f| match error { … }`, each arm writing
/// to the formatter `f`), the error's `source` the optional
/// `source = |error| …` (none without it). Defined before the modules so
/// that every one of them can use it.
macro_rules! impl_error {
    ($Error:ty, |$error:ident, $f:ident| $message:expr
        $(, source = |$inner:ident| $source:expr)? $(,)?) => {
        impl ::std::fmt::Display for $Error {
            fn fmt(&self, $f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                let $error = self;
                $message
            }
        }

        impl ::std::error::Error for $Error {
            $(fn source(&self) -> Option<&(dyn ::std::error::Error + 'static)> {
                let $inner = self;
                $source
            })?
        }
    };
}

#[doc = include_str!("../docs/definitions.md")]
pub mod definitions {
    /// How far the exact `V` must be from 0 and from 1 for a receiver to
    /// be in the [penumbra group](self#receiver-groups): `10⁻⁹`, above the
    /// exact reference's error (at most `3.4·10⁻¹²` against every closed
    /// form of `docs/accuracy/references.md`; a light covered by several
    /// triangles may leave `~10⁻¹⁶` instead of 0), far below any visible
    /// shade. Without it the group would move with the exact answer's
    /// last bits.
    pub const PENUMBRA_MARGIN: f64 = 1e-9;

    /// Whether a receiver whose exact visibility is `v_exact` is in the
    /// [penumbra group](self#receiver-groups):
    /// `PENUMBRA_MARGIN < v_exact < 1 − PENUMBRA_MARGIN` (false for NaN).
    /// The report, the renderer's error table and the benches all decide
    /// the group here.
    #[must_use]
    pub fn in_penumbra(v_exact: f64) -> bool {
        v_exact > PENUMBRA_MARGIN && v_exact < 1.0 - PENUMBRA_MARGIN
    }
}

#[cfg(any(test, feature = "arbitrary"))]
pub mod arbitrary;
#[cfg(feature = "bvh")]
pub mod bvh;
#[cfg(feature = "float-io")]
pub mod float_io;
pub mod kernel;
#[cfg(feature = "render")]
pub mod method;
#[cfg(feature = "render")]
pub mod output;
#[cfg(feature = "reference")]
pub mod reference;
#[cfg(feature = "render")]
pub mod render;
#[cfg(feature = "report")]
pub mod report;
pub mod scene;

pub use scene::{Emitter, Light, Mesh, Receiver, Scene};

#[cfg(feature = "bvh")]
pub use bvh::{Bvh, Occluders};
#[cfg(feature = "render")]
pub use method::Method;
#[cfg(feature = "render")]
pub use output::image::ErrorSummary;
#[cfg(feature = "render")]
pub use render::{Fit, Frame, Stages};
