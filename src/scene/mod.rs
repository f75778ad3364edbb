//! The scene: lights, the light frame, meshes, mesh generators, the camera,
//! and (feature `scene-file`) the scene and points files and the built-in
//! scenes. Without `scene-file` it depends on `glam` alone.
//!
//! - [`light`]: the scene's light, one of the five shapes of
//!   [visibility](crate::definitions#visibility), named by its kind; the
//!   shapes themselves, their errors and the emitting measure each
//!   presents to a receiver are the kernels' ([`kernel::light`](crate::kernel::light)),
//!   named here too.
//! - [`emitter`]: that measure as one receiver sees it
//!   ([`Emitter`]), named here too.
//! - [`frame`]: the light frame and the light image plane of §2.
//! - [`mesh`]: occluder meshes, validated.
//! - [`receiver`]: a receiver point with its surface normal and object id,
//!   when known (from a points file or the renderer's camera).
//! - [`primitive`]: closed, outward sphere and box meshes, quads, merging,
//!   and the similarity transform of the scene file.
//! - [`scene`](mod@scene): the whole scene (meshes, light, camera).
//! - `file` (feature `scene-file`): the JSON scene file and points file of
//!   §8, with OBJ meshes; one-line errors naming the file, the place and
//!   the field.
//! - `builtin` (feature `scene-file`): the built-in scenes of §5, embedded
//!   (the Stanford bunny included), by name.

#[cfg(feature = "scene-file")]
pub mod builtin;
pub mod emitter;
#[cfg(feature = "scene-file")]
pub mod file;
pub mod frame;
pub mod light;
pub mod mesh;
pub mod primitive;
pub mod receiver;
#[allow(clippy::module_inception)]
pub mod scene;

#[cfg(feature = "scene-file")]
pub use builtin::{builtin, BUILTIN_NAMES};
pub use emitter::Emitter;
#[cfg(feature = "scene-file")]
pub use file::{FileError, InputError, Place};
pub use frame::{FrameError, LightFrame, Projected};
pub use light::{Light, LightError, LightKind, ReceiverError};
pub use mesh::{Mesh, MeshError};
pub use primitive::{PrimitiveError, Transform};
pub use receiver::Receiver;
pub use scene::{Camera, CameraError, Scene};
