//! What the methods build on (feature `render`): the receivers a frame
//! holds, the lazily built stages every method draws on, and the
//! light-view rasterizer. The data flows scene → these stages → a
//! [method](crate::method) → [output](crate::output).
//!
//! - [`Frame`]: the receivers, one per pixel of a camera image
//!   ([`Frame::from_camera`], primary rays through the BVH) or one per
//!   point of a points file ([`Frame::from_receivers`]).
//! - [`Receiver`]: one receiver; the scene's type
//!   ([`crate::scene::Receiver`]), re-exported here.
//! - [`Stages`]: the BVH, mesh topology, light frame and light maps, built
//!   lazily and once, timed into [`Stats`].
//! - [`raster`]: the light-view rasterizer every shadow-map method uses.
//!
//! What is done with a method's answers (shading, heat-maps, error
//! summaries, image files, the G-buffer, scores) is in [`crate::output`].

pub(crate) mod frame;
pub mod raster;
pub(crate) mod stages;

pub use crate::scene::Receiver;
pub use frame::{Fit, Frame, BACKGROUND, RECEIVER_OFFSET};
pub use stages::{FittedMaps, Needs, Progress, SharedMaps, StageTime, Stages, Stats};
