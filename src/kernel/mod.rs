//! Geometry kernels: pure functions and small value types, no allocation in
//! the hot paths, total on every input (documented answers for degenerate and
//! non-finite input, never a panic or a NaN).
//!
//! | module | what |
//! |---|---|
//! | [`predicate`] | exact `orient2d` / `orient3d` for every side decision |
//! | [`angle`] | a portable, platform-independent `atan2` (1.5 ulp) |
//! | [`catalogue`] | each kernel family's contract declared once: domain, error budgets, stiff cases |
//! | [`silhouette`] | mesh topology, silhouette edges from a point, conservative silhouettes for a sphere light |
//! | [`wedge`] | penumbra wedges and the light-image-plane penumbra quad (SISM's coarse test) |
//! | [`disk`] | area of a polygon ∩ a disk, signed circle-segment occlusion (SISM eq. 3); many edges at once, bit for bit the one-edge kernel |
//! | [`falloff`] | Bernstein smoothstep and the exact straight-edge disk falloff |
//! | [`footprint`] | the light's footprint on the light image plane: its radius, the projection, near and far clips, an edge mapped into the footprint; the rounding bound `γ(n)` |
//! | [`distortion`] | SSOC: distortion magnitude to shadow intensity |
//! | [`linear_light`] | OESS: visible fraction of a segment light and its endpoint weights |
//! | [`light`] | the light's geometry: the five shapes (sphere, disk, rect, segment, point), validated, and the emitting measure each presents to a receiver ([`light::Emitter`]): its sample points and its share above a plane |
//! | [`segment`] | exact open-segment–triangle test (`f64`): blocked or not, and where it crosses |
//! | [`receiver_view`] | the exact receiver view: a triangle's image on the light's plane clipped to the slab between receiver and light, and the exact fraction of a light a set of triangles hides (`f64`) |
//!
//! Scalar kernels exist in `f32` and `f64` as submodules generated from one
//! body (`disk::f32`, `disk::f64`, …).

/// For each generic test function `name::<T>()`, a module `name` of two
/// `#[test]`s, `in_f64` and `in_f32`, that run it in each precision.
#[cfg(test)]
macro_rules! test_in_both_precisions {
    ($name:ident) => {
        mod $name {
            #[test]
            fn in_f64() {
                super::$name::<f64>();
            }
            #[test]
            fn in_f32() {
                super::$name::<f32>();
            }
        }
    };
}

pub mod angle;
pub mod catalogue;
pub mod disk;
pub mod distortion;
pub(crate) mod eft;
pub mod falloff;
pub(crate) mod float;
pub mod footprint;
pub(crate) mod lanes;
pub mod light;
pub mod linear_light;
pub mod predicate;
pub mod receiver_view;
pub mod segment;
pub mod silhouette;
pub mod wedge;
