//! The hard shadow: the point-light answer at the light's centre.

use super::options::{from_options, method_options};
use super::{per_receiver, Horizon, Input, Method, MethodError, Output};
use crate::render::Needs;
use crate::scene::LightKind;

method_options! {
    /// Hard shadows: `V(p) = 1` when the open segment from `p` to the light's
    /// centre meets no triangle, else `0` — the answer for a point light at the
    /// centre, decided exactly by the BVH ([`Bvh::segment_unoccluded`]), so it
    /// equals the Monte Carlo and exact references for that point light bit for
    /// bit. Any light.
    ///
    /// [`Bvh::segment_unoccluded`]: crate::bvh::Bvh::segment_unoccluded
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    #[non_exhaustive]
    pub struct HardShadow {
        /// The [horizon bound](Horizon), `min(V, V_h)`; default off (ours, not
        /// a paper's).
        pub horizon: bool = false, option(flag "horizon", "V ≤ the light's share above the receiver's tangent plane (ours)"), builder(with_horizon);
    }
    name: "hard",
    summary: "hard shadows: the point light at the light's centre",
    lights: LightKind::ALL,
    default_run: &["hard"],
    compare: &["hard", "hard:horizon"],
}

impl Method for HardShadow {
    from_options!();

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
