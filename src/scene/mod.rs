//! The scene: lights, the light frame, meshes (and, with the references
//! issue, the camera, the built-in scenes and the scene file). Depends on
//! `glam` alone.
//!
//! - [`light`]: the five light kinds of DESIGN.md §1, validated, and the
//!   emitting measure each presents to a receiver.
//! - [`frame`]: the light frame and the light image plane of §2.
//! - [`mesh`]: occluder meshes, validated.
//! - [`scene`](mod@scene): the whole scene (meshes, light, camera).

pub mod frame;
pub mod light;
pub mod mesh;
#[allow(clippy::module_inception)]
pub mod scene;

pub use frame::{FrameError, LightFrame, Projected};
pub use light::{Emitter, Light, LightError, ReceiverError};
pub use mesh::{Mesh, MeshError};
pub use scene::{Camera, CameraError, Scene};
