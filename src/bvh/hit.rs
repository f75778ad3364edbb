//! What a closest-hit query returns ([`Hit`]) and what its answer is made
//! of, shared by the one-ray walk (`closest.rs`) and the packet walk
//! (`packet.rs`): the triangles' unit normals, turned against the ray, and
//! the culling slack of a crossing's parameter.

use super::Bvh;
use glam::DVec3;
use rayon::prelude::*;

/// The nearest crossing of a ray with the occluders: what
/// [`Bvh::closest_hit`] returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The ray parameter of the hit point `origin + t · direction`,
    /// `0 < t ≤ t_max`.
    pub t: f64,
    /// The triangle hit: its index in [`Bvh::occluders`].
    pub triangle: u32,
    /// Its object id, `occluders().objects()[triangle]`.
    pub object: u32,
    /// The triangle's unit geometric normal, turned against the ray
    /// (`normal · direction ≤ 0`; see [`Bvh::closest_hit`]).
    pub normal: DVec3,
}

impl Bvh {
    /// Every occluder's [`unit_normal`], computed (in parallel) on first
    /// use: a hit's record then costs a load, a dot product and a flip
    /// instead of a square root and a division per hit. Only closest-hit
    /// queries pay its 24 bytes per triangle.
    pub(super) fn normals(&self) -> &[DVec3] {
        self.normals.get_or_init(|| {
            self.occluders
                .triangles()
                .par_iter()
                .map(unit_normal)
                .collect()
        })
    }
}

/// A bound on the relative error of a crossing's `u` (what
/// [`segment_crossing`](crate::kernel::segment::segment_crossing)
/// promises), for culling.
pub(super) const U_SLACK: f64 = 1.0 / (1u64 << 23) as f64;

/// The unit normal of `t`, either way round; zero for a triangle too thin
/// for its normal to be computed.
///
/// The cross product of the two edges at the triangle's largest angle (the
/// corner opposite the longest edge) is the best conditioned of the three;
/// where it under- or overflows (tiny or huge triangles), each edge is first
/// divided by its max-norm.
fn unit_normal(t: &[DVec3; 3]) -> DVec3 {
    let [a, b, c] = *t;
    let (ab, bc, ca) = (b - a, c - b, a - c);
    let (lab, lbc, lca) = (
        ab.abs().max_element(),
        bc.abs().max_element(),
        ca.abs().max_element(),
    );
    let (u, v, lu, lv) = if lab >= lbc && lab >= lca {
        (bc, ca, lbc, lca)
    } else if lbc >= lca {
        (ca, ab, lca, lab)
    } else {
        (ab, bc, lab, lbc)
    };
    u.cross(v)
        .try_normalize()
        .or_else(|| (u / lu).cross(v / lv).try_normalize())
        .unwrap_or(DVec3::ZERO)
}

/// The unit normal `n` (from [`unit_normal`]) turned against `direction`
/// (finite, nonzero): the flip is decided by the rounded `n · direction`
/// itself, so that a caller evaluating it finds it `≤ 0`. Where `n` is
/// zero, `−direction` normalised.
#[inline(always)]
pub(super) fn facing(n: DVec3, direction: DVec3) -> DVec3 {
    let n = if n == DVec3::ZERO {
        (-direction / direction.abs().max_element()).normalize()
    } else {
        n
    };
    // Branch-free: which way a normal faces is unpredictable per pixel.
    DVec3::select(glam::BVec3::splat(n.dot(direction) > 0.0), -n, n)
}
