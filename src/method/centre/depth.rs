//! The shadow-map test of a receiver against a light-map texel, with the
//! receiver-plane depth bias: shared by PCSS and the single-sample method.
//!
//! A texel of depth `d` *blocks* the receiver `p` (light frame, depth
//! `z_p`) when `d < z − m`: `z` is the depth, along the texel centre's ray,
//! of the receiver's tangent plane (the plane through `p` with its
//! normal), so that the receiver's own surface is never its blocker however
//! far the texel is, on any slope ("receiver plane depth bias", a known
//! improvement on a constant bias); `m` is a margin for rounding and
//! curvature. A receiver whose normal faces away from the light's centre is
//! behind its own surface, which hides the centre: for it a texel blocks
//! when `d < z_p + m`, so its own surface, at its own depth, counts. Without
//! a normal (the constant bias) `z = z_p`.

use crate::render::raster::LightView;
use glam::DVec3;

/// The largest depth margin, as a share of the receiver's depth: `0.05`
/// (ours). However coarse the map, a blocker nearer the light than the
/// receiver by more than 5 % of the receiver's depth is always found (a
/// 1000 × 1000 ceiling one unit above a floor point five units from the
/// light made texels of 1.2 units at the receiver, and a margin of one
/// texel lit the point).
pub(crate) const MAX_MARGIN_SHARE: f64 = 0.05;

/// The margin `m` of a receiver at depth `z`: `relative` of its depth plus
/// `texels` texels of side `texel` (on the image plane) at its depth,
/// capped at [`MAX_MARGIN_SHARE`] of its depth.
pub(crate) fn margin(z: f64, relative: f64, texels: f64, texel: f64) -> f64 {
    z * (relative + texels * texel).min(MAX_MARGIN_SHARE)
}

/// One receiver's depth test against the texels of a light view.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DepthTest {
    /// The receiver in light-frame coordinates.
    p: DVec3,
    /// Its light-frame normal, when it faces the light's centre and the
    /// receiver-plane bias is used.
    facing: Option<DVec3>,
    /// The margin `m`.
    margin: f64,
    /// The receiver faces away from the light's centre.
    own_surface_blocks: bool,
}

impl DepthTest {
    /// The test for the receiver at light-frame `p` with light-frame normal
    /// `normal` (`None`: the constant bias), margin `margin`.
    pub(crate) fn new(p: DVec3, normal: Option<DVec3>, margin: f64) -> DepthTest {
        let facing = normal.filter(|n| n.dot(p) < 0.0);
        DepthTest {
            p,
            facing,
            margin,
            own_surface_blocks: normal.is_some() && facing.is_none(),
        }
    }

    /// The margin `m`.
    pub(crate) fn margin(&self) -> f64 {
        self.margin
    }

    /// The depth texel `(col, row)` of `view` is compared with: the tangent
    /// plane's along the texel centre's ray, or the receiver's own.
    pub(crate) fn reference_depth(&self, view: &LightView, col: u32, row: u32) -> f64 {
        match self.facing {
            Some(n) => {
                // The tangent plane n·X = n·p along the ray (c, 1).
                let c = view.pixel_center(col, row);
                let z = n.dot(self.p) / n.dot(DVec3::new(c.x, c.y, 1.0));
                if z.is_finite() && z > 0.0 {
                    z
                } else {
                    self.p.z
                }
            }
            None => self.p.z,
        }
    }

    /// `z_p − m`: texels nearer than this are in front of the receiver
    /// (the single-sample method's "virtual layers" in front of `P′_z`).
    pub(crate) fn in_front(&self) -> f64 {
        self.p.z - self.margin
    }

    /// The depth below which a texel whose reference depth is `z` blocks
    /// the receiver: `z − m`, or `z + m` for a receiver facing away (whose
    /// reference depth is its own).
    pub(crate) fn threshold(&self, z: f64) -> f64 {
        if self.own_surface_blocks {
            z + self.margin
        } else {
            z - self.margin
        }
    }

    /// Whether a texel of depth `d` at `(col, row)` blocks the receiver.
    pub(crate) fn blocks(&self, view: &LightView, col: u32, row: u32, d: f64) -> bool {
        d < self.threshold(self.reference_depth(view, col, row))
    }

    /// Bounds `(lo, hi)` of [`DepthTest::reference_depth`] over the texels
    /// `c0..=c1` × `r0..=r1`: the tangent plane's depth `k/(n·(c, 1))` is a
    /// monotone function of a linear denominator, so where that keeps its
    /// sign over the box its extremes are at the corner texels; a box the
    /// plane is seen edge-on from gets `(−∞, +∞)`.
    pub(crate) fn reference_range(
        &self,
        view: &LightView,
        (c0, r0): (u32, u32),
        (c1, r1): (u32, u32),
    ) -> (f64, f64) {
        let Some(n) = self.facing else {
            return (self.p.z, self.p.z);
        };
        let mut sign = 0.0f64;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (c, r) in [(c0, r0), (c1, r0), (c0, r1), (c1, r1)] {
            let u = view.pixel_center(c, r);
            let den = n.dot(DVec3::new(u.x, u.y, 1.0));
            let raw = n.dot(self.p) / den;
            if !raw.is_finite() || (sign != 0.0 && den.signum() != sign) {
                return (f64::NEG_INFINITY, f64::INFINITY);
            }
            sign = den.signum();
            let z = self.reference_depth(view, c, r);
            lo = lo.min(z);
            hi = hi.max(z);
        }
        (lo, hi)
    }
}
