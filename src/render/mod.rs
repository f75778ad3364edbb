//! The scalar renderer (feature `render`): receivers from the camera, the
//! light-view rasterizer, the lazily built stages every method draws on, and
//! image output.
//!
//! - [`Frame`]: the receivers, one per pixel of a camera image
//!   ([`Frame::from_camera`], primary rays through the BVH) or one per
//!   point of a points file ([`Frame::from_receivers`]).
//! - [`Receiver`]: one receiver; the scene's type
//!   ([`crate::scene::Receiver`]), re-exported here.
//! - [`Stages`]: the BVH, mesh topology, light frame and light maps, built
//!   lazily and once, timed into [`Stats`].
//! - [`raster`]: the light-view rasterizer every shadow-map method uses.
//! - [`gbuffer`]: the receivers of a camera as arrays (position, normal,
//!   object id, exact `V`) and the camera as a rasteriser's matrices.
//! - [`score`]: an image of `V` made elsewhere scored against the exact
//!   answer on the same receivers, with the report's statistics.
//! - [`image`]: [shading](crate::definitions#shading), the error heat-map, error summaries
//!   and PNG files.
//!
//! The methods themselves are in [`crate::method`].

mod frame;
pub mod gbuffer;
pub mod image;
pub mod raster;
pub mod score;
mod stages;

pub use crate::scene::Receiver;
pub use frame::{Frame, BACKGROUND, RECEIVER_OFFSET};
pub use stages::{FittedMaps, Needs, Progress, SharedMaps, StageTime, Stages, Stats};
