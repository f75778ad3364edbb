//! The scene: lights (and, with the references issue, meshes, cameras and
//! the scene file). Depends on `glam` alone.
//!
//! - [`light`]: the five light kinds of DESIGN.md §1, validated, and the
//!   emitting measure each presents to a receiver.
//! - [`frame`]: the light frame and the light image plane of §2.

pub mod frame;
pub mod light;

pub use frame::{FrameError, LightFrame, Projected};
pub use light::{Emitter, Light, LightError, ReceiverError};
