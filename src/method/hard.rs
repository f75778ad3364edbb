//! The hard shadow: the point-light answer at the light's centre.

use super::options::{builders, field, Configurable, Field};
use super::{per_receiver, Horizon, Input, Method, MethodError, Output};
use crate::render::Needs;
use crate::scene::LightKind;

/// Hard shadows: `V(p) = 1` when the open segment from `p` to the light's
/// centre meets no triangle, else `0` — the answer for a point light at the
/// centre, decided exactly by the BVH ([`Bvh::segment_unoccluded`]), so it
/// equals the Monte Carlo and exact references for that point light bit for
/// bit. Any light.
///
/// [`Bvh::segment_unoccluded`]: crate::bvh::Bvh::segment_unoccluded
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct HardShadow {
    /// The [horizon bound](Horizon), `min(V, V_h)`; default off (ours, not
    /// a paper's).
    pub horizon: bool,
}

builders!(HardShadow {
    /// With or without the horizon bound.
    with_horizon => horizon: bool,
});

impl Configurable for HardShadow {
    const NAME: &'static str = "hard";
    const SUMMARY: &'static str = "hard shadows: the point light at the light's centre";
    const LIGHTS: &'static [LightKind] = LightKind::ALL;
    const DEFAULT_RUN: &'static [&'static str] = &["hard"];
    const COMPARE: &'static [&'static str] = &["hard", "hard:horizon"];
    const FIELDS: &'static [Field<HardShadow>] = &[field!(flag "horizon", horizon,
        "V ≤ the light's share above the receiver's tangent plane (ours)")];
}

impl Method for HardShadow {
    fn name(&self) -> String {
        super::options::print(self)
    }

    fn needs(&self) -> Needs {
        Needs::BVH
    }

    fn horizon(&self) -> Horizon {
        Horizon::clamp_if(self.horizon)
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        let bvh = input.stages().bvh();
        let center = input.light().center();
        let visibility = per_receiver(
            input,
            || (),
            |(), _, r| {
                Ok(if bvh.segment_unoccluded(r.position, center) {
                    1.0
                } else {
                    0.0
                })
            },
        )?;
        Ok(Output::values(visibility))
    }
}
