//! STUB — being written (lead). Interface fixed here.

use super::bvh::Bvh;
use crate::scene::{Light, ReceiverError};
use glam::DVec3;

/// The exact `V(p)`.
///
/// # Errors
/// [`ReceiverError`] as [`Light::emitter`].
pub fn visibility(bvh: &Bvh, light: &Light, p: DVec3) -> Result<f64, ReceiverError> {
    let _ = (bvh, light, p);
    unimplemented!()
}

/// [`visibility`] for every point, in parallel.
#[must_use]
pub fn visibility_many(
    bvh: &Bvh,
    light: &Light,
    points: &[DVec3],
) -> Vec<Result<f64, ReceiverError>> {
    points.iter().map(|&p| visibility(bvh, light, p)).collect()
}
