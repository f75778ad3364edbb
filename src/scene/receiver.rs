//! [`Receiver`]: a point where `V` is wanted, with what is known of the
//! surface it lies on. The points file gives receivers
//! (`file::load_points`, feature `scene-file`); the renderer lays them out
//! as an image (`render::Frame`, feature `render`).

use glam::DVec3;

/// A receiver: a point where `V` is wanted, with what is known of the
/// surface it lies on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Receiver {
    /// The point, finite.
    pub position: DVec3,
    /// The unit geometric normal of the surface, on the side the point is
    /// seen from, when known. Camera receivers always have one.
    pub normal: Option<DVec3>,
    /// The object id (mesh index) of the surface, when known. Camera
    /// receivers always have one.
    pub object: Option<u32>,
}
