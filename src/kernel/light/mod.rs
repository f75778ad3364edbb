//! The light's geometry: the five shapes of
//! [visibility](crate::definitions#visibility), validated at construction,
//! and the emitting measure each presents to a receiver.
//!
//! `V(p)` is the fraction of a light's emitting measure visible from `p`:
//!
//! | shape | measure |
//! |---|---|
//! | [`Sphere`] | the area of the *facing disk*: centre `c`, radius `r`, normal `(c − p)/‖c − p‖` |
//! | [`Disk`] | its area |
//! | [`Rect`] | its area (centre and half-axes `u`, `v`) |
//! | [`Segment`] | its length |
//! | [`Point`] | a single point: `V ∈ {0, 1}` |
//!
//! - `shape`: the five shapes; their constructors return [`LightError`]
//!   for non-finite or degenerate input.
//! - `emitter`: the measure one receiver sees ([`Emitter`], from each
//!   shape's `seen_from`, which returns [`ReceiverError`] for a receiver
//!   inside a sphere, in the plane of a disk or rect, or on the light: an
//!   error, not a NaN); its uniform-by-area sample points and the share
//!   of it above a plane (the horizon bound).
//! - `error`: [`LightError`] and [`ReceiverError`].
//!
//! The exact fraction of an [`Emitter`] that triangles hide is the
//! [receiver view](crate::kernel::receiver_view)'s. The scene's light (one
//! of these shapes, named by its kind) is built on them.

mod emitter;
mod error;
mod shape;

pub use emitter::Emitter;
#[cfg_attr(not(feature = "reference"), allow(unused_imports))] // Monte Carlo's
pub(crate) use emitter::PlaneMap;
pub use error::{LightError, ReceiverError};
pub use shape::{Disk, Point, Rect, Segment, Sphere};
