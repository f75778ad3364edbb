//! STUB — being written (helper B). Interface fixed here.

use super::bvh::Bvh;
use crate::scene::{Light, ReceiverError};
use glam::DVec3;

/// A Monte Carlo estimate of `V(p)` and its standard error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The estimate of `V(p)`, in `[0, 1]`.
    pub visibility: f64,
    /// Its standard error.
    pub stderr: f64,
}

/// Monte Carlo options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Samples per receiver.
    pub samples: u32,
    /// Seed of the sample sequence.
    pub seed: u64,
}

/// `V(p)` by light sampling.
///
/// # Errors
/// [`ReceiverError`] as [`Light::emitter`].
pub fn visibility(
    bvh: &Bvh,
    light: &Light,
    p: DVec3,
    options: &Options,
) -> Result<Estimate, ReceiverError> {
    let _ = (bvh, light, p, options);
    unimplemented!()
}

/// [`visibility`] for every point, in parallel.
#[must_use]
pub fn visibility_many(
    bvh: &Bvh,
    light: &Light,
    points: &[DVec3],
    options: &Options,
) -> Vec<Result<Estimate, ReceiverError>> {
    points
        .iter()
        .map(|&p| visibility(bvh, light, p, options))
        .collect()
}
