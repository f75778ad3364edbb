//! STUB — being written (helper B). Interface fixed here.
//! A bounding volume hierarchy over [`Occluders`] for occlusion rays and for
//! culling the triangles a receiver's view of the light can meet.

use super::Occluders;
use glam::DVec3;

/// A BVH over a scene's occluders (owns them).
#[derive(Debug)]
pub struct Bvh {
    occluders: Occluders,
}

impl Bvh {
    /// Builds the hierarchy.
    #[must_use]
    pub fn new(occluders: Occluders) -> Bvh {
        Bvh { occluders }
    }

    /// The triangles it was built over.
    #[must_use]
    pub fn occluders(&self) -> &Occluders {
        &self.occluders
    }

    /// Whether the open segment `(p, x)` meets no triangle.
    #[must_use]
    pub fn segment_unoccluded(&self, p: DVec3, x: DVec3) -> bool {
        let _ = (p, x);
        unimplemented!()
    }

    /// Appends to `out` (after clearing it) the index of every triangle whose
    /// bounds may meet the convex hull of `points`: a superset of the
    /// triangles that meet the hull.
    pub fn triangles_meeting_hull(&self, points: &[DVec3], out: &mut Vec<u32>) {
        let _ = points;
        out.clear();
        out.extend(0..self.occluders.len() as u32);
    }
}
