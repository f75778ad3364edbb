//! The hard shadow: the point-light answer at the light's centre.

use super::{per_receiver, Method, MethodError, Output};
use crate::render::{Frame, Needs, Stages};
use crate::scene::Light;

/// Hard shadows: `V(p) = 1` when the open segment from `p` to the light's
/// centre meets no triangle, else `0` — the answer for a point light at the
/// centre, decided exactly by the BVH ([`Bvh::segment_unoccluded`]), so it
/// equals the Monte Carlo and exact references for that point light bit for
/// bit. Receivers the light itself cannot be seen from (inside a sphere
/// light, …) are errors, as for every method.
///
/// [`Bvh::segment_unoccluded`]: crate::bvh::Bvh::segment_unoccluded
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HardShadow;

impl Method for HardShadow {
    fn name(&self) -> String {
        "hard".to_owned()
    }

    fn needs(&self, _: &Light) -> Result<Needs, MethodError> {
        Ok(Needs::BVH)
    }

    fn visibility(&self, stages: &Stages, frame: &Frame) -> Result<Output, MethodError> {
        let (bvh, light) = (stages.bvh(), stages.scene().light());
        let center = light.center();
        let visibility = per_receiver(
            stages,
            frame,
            || (),
            |(), index, r| {
                light
                    .emitter(r.position)
                    .map_err(|error| MethodError::Receiver { index, error })?;
                Ok(if bvh.segment_unoccluded(r.position, center) {
                    1.0
                } else {
                    0.0
                })
            },
        )?;
        Ok(Output {
            visibility,
            stderr: None,
        })
    }
}
