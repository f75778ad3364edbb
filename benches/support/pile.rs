//! The pile of occluders the exact reference is measured on at depth,
//! shared by `benches/references.rs` and `examples/union_depth.rs` so that
//! both measure the same triangles.

use softshadow::arbitrary::Rng;
use softshadow::glam::DVec3;

/// `n` triangles of size about a tenth of the light's image, centred on
/// segments from the receiver at the origin to points of a sphere light of
/// radius 0.5 at height 4, at depths 0.2–0.8 of the way.
pub fn occluders(n: usize) -> Vec<[DVec3; 3]> {
    let mut rng = Rng::new(7);
    let light = DVec3::new(0.0, 0.0, 4.0);
    (0..n)
        .map(|_| {
            let target = light + DVec3::new(rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4), 0.0);
            let depth = rng.uniform(0.2, 0.8);
            let q = target * depth;
            let s = 0.05 * depth;
            let mut corner =
                || q + DVec3::new(rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-s, s));
            [corner(), corner(), corner()]
        })
        .collect()
}
