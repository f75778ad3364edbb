//! Silhouettes of a sphere mesh moved far away, seen from near and far:
//! the kernel's edges against a facing test per face (the same exact
//! predicate, but no shared topology).

use super::Row;
use crate::kernel::catalogue::Stiff;
use crate::kernel::predicate::{orient3d, Sign};
use crate::kernel::silhouette::{MeshTopology, SilhouetteEdge};
use glam::DVec3;
use std::collections::BTreeMap;

/// One row per offset: the edges that differ from the facing test,
/// counted over views from 1.5 to 10⁶ radii.
pub(super) fn rows(rows: &mut Vec<Row>) {
    let sphere = crate::scene::primitive::sphere(DVec3::ZERO, 1.0, 24).ok();
    if let Some(mesh) = sphere {
        let tris = mesh.triangles();
        if let Ok(topo) = MeshTopology::new(tris, mesh.positions().len()) {
            for e in [0, 4, 8] {
                let shift = DVec3::splat(2f64.powi(e * 10 / 3));
                let positions: Vec<DVec3> = mesh.positions().iter().map(|&q| q + shift).collect();
                let mut mismatched = 0usize;
                let mut views = 0usize;
                for (k, d) in [1.5, 3.0, 1e3, 1e6].iter().enumerate() {
                    let x = shift
                        + DVec3::new(0.3, 0.8, -0.5).normalize() * *d
                        + DVec3::X * (k as f64 * 1e-3);
                    let Ok(edges) = topo.silhouettes_from_point(&positions, x) else {
                        continue;
                    };
                    views += 1;
                    mismatched += mismatch(&positions, tris, x, &edges);
                }
                rows.push(Row::new(
                    "f64",
                    "silhouette::silhouettes_from_point (edges wrong)",
                    Stiff::FarOffset.name(),
                    format!(
                        "sphere of 24 bands moved 2^{}, seen from 1.5 to 1e6 radii",
                        e * 10 / 3
                    ),
                    views,
                    mismatched as f64,
                    "inside",
                ));
            }
        }
    }
}

/// How many silhouette edges differ from a per-face facing test: an edge
/// is a silhouette when its two faces face `x` differently (the exact
/// `orient3d`), each face visited once, no topology shared with the kernel.
fn mismatch(positions: &[DVec3], tris: &[[u32; 3]], x: DVec3, edges: &[SilhouetteEdge]) -> usize {
    let mut sum: BTreeMap<(u32, u32), i64> = BTreeMap::new();
    for t in tris {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let w = if orient3d(a, b, c, x) == Sign::Negative {
            1
        } else {
            -1
        };
        for k in 0..3 {
            let (from, to) = (t[k], t[(k + 1) % 3]);
            let (key, sign) = if from < to {
                ((from, to), 1)
            } else {
                ((to, from), -1)
            };
            *sum.entry(key).or_insert(0) += w * sign;
        }
    }
    let brute: BTreeMap<(u32, u32), u32> = sum
        .into_iter()
        .filter(|&(_, v)| v != 0)
        .map(|((a, b), v)| (if v > 0 { (a, b) } else { (b, a) }, v.unsigned_abs() as u32))
        .collect();
    let kernel: BTreeMap<(u32, u32), u32> = edges
        .iter()
        .map(|e| ((e.from, e.to), e.multiplicity))
        .collect();
    brute
        .iter()
        .filter(|(k, v)| kernel.get(k) != Some(v))
        .count()
        + kernel
            .iter()
            .filter(|(k, v)| brute.get(k) != Some(v))
            .count()
}
