//! The exact composition option: the area of the *union* of the occluders
//! inside the light's footprint, instead of the sum of their areas
//! (Johnson et al. 2009 §5.2's `C`, computed rather than set to 0).
//!
//! Input, per receiver: the occluders' boundary chain mapped into the unit
//! disk (the light footprint scaled to radius 1, centred on the receiver),
//! each edge with its weight (the change of layer count across it, from its
//! right to its left), and the layer count `c0` at the centre from the
//! umbra pass. The covered region is where the layer count is at least one
//! (`> ½`: weights are halves for closed surfaces). Its boundary inside the
//! disk is made of pieces of chain edges, cut where edges cross one another
//! and the circle, each kept when the count is covered on one side only;
//! the rest of the boundary of (region ∩ disk) is covered arcs of the
//! circle. Green's theorem over that boundary, with the exact
//! [`segment_disk_area`] for the pieces and `½ Δφ` for the arcs, gives the
//! covered area. Bit-identical edges are merged first (their weights
//! added: the all-edges chain's interior edges cancel, a contour edge's two
//! copies become one); where edges still lie on one another, each takes the
//! share `weight / jump` of a piece, so the piece counts once. Cost:
//! `O(k³)` for `k` edges meeting the footprint (`k²` pieces, each probed
//! against every edge).
//!
//! Layer counts off the chain are the centre's count plus the signed
//! crossings of the straight path from the centre (floating-point side
//! tests: a point within rounding of an edge may be misjudged, which moves
//! the area by the rounding of that edge only).

use crate::kernel::disk::f64::segment_disk_area;
use glam::DVec2;
use std::f64::consts::PI;

/// One mapped chain edge: from `a` to `b`, covered side on the left, the
/// layer count rising by `weight` from its right to its left.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MappedEdge {
    pub a: DVec2,
    pub b: DVec2,
    pub weight: f64,
}

/// How far off a piece its sides are probed, in units of the disk radius.
const PROBE: f64 = 1e-9;

fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Whether segment `[a, b]` comes within the unit circle.
pub(crate) fn meets_disk(a: DVec2, b: DVec2) -> bool {
    if a.length_squared() < 1.0 || b.length_squared() < 1.0 {
        return true;
    }
    let d = b - a;
    let dd = d.length_squared();
    if dd == 0.0 {
        return false;
    }
    let t = (-a.dot(d) / dd).clamp(0.0, 1.0);
    (a + d * t).length_squared() < 1.0
}

/// The layer count at `x` (inside the disk).
fn coverage(c0: f64, edges: &[MappedEdge], x: DVec2) -> f64 {
    let mut c = c0;
    for e in edges {
        let d = e.b - e.a;
        let o1 = cross(d, -e.a);
        let o2 = cross(d, x - e.a);
        if (o1 < 0.0) == (o2 < 0.0) || o1 == 0.0 || o2 == 0.0 {
            continue;
        }
        let o3 = cross(x, e.a);
        let o4 = cross(x, e.b);
        if (o3 < 0.0) == (o4 < 0.0) || o3 == 0.0 || o4 == 0.0 {
            continue;
        }
        // From the centre's side to x's side: into the left adds the weight.
        c += if o2 > 0.0 { e.weight } else { -e.weight };
    }
    c
}

/// Parameters `t ∈ (0, 1)` where `a + t (b − a)` is on the unit circle.
fn circle_hits(a: DVec2, b: DVec2, out: &mut Vec<f64>) {
    let d = b - a;
    let qa = d.length_squared();
    let qb = a.dot(d);
    let qc = (a.length() - 1.0) * (a.length() + 1.0);
    let disc = qb * qb - qa * qc;
    if qa == 0.0 || disc <= 0.0 {
        return;
    }
    // Cancellation-free roots of qa t² + 2 qb t + qc.
    let q = -(qb + disc.sqrt().copysign(qb));
    for t in [q / qa, if q != 0.0 { qc / q } else { f64::NAN }] {
        if t > 0.0 && t < 1.0 {
            out.push(t);
        }
    }
}

/// Reusable buffers.
#[derive(Default)]
pub(crate) struct Scratch {
    kept: Vec<MappedEdge>,
    params: Vec<f64>,
    angles: Vec<f64>,
}

/// Whether a layer count is covered: at least one layer (`> ½`, weights
/// being halves for closed surfaces).
fn covered(c: f64) -> bool {
    c > 0.5
}

/// The covered fraction of the unit disk (see the module docs).
pub(crate) fn union_occlusion(c0: f64, edges: &[MappedEdge], scratch: &mut Scratch) -> f64 {
    let Scratch {
        kept,
        params,
        angles,
    } = scratch;
    merge_edges(edges, kept);
    if kept.is_empty() {
        return centre_only(c0);
    }
    angles.clear();
    let mut area = 0.0;
    for i in 0..kept.len() {
        add_pieces(c0, kept, i, params, angles, &mut area);
    }
    add_arcs(c0, kept, angles, &mut area);
    let share = area / PI;
    if share.is_finite() {
        share
    } else {
        // Only reachable through overflow in the side tests of edges mapped
        // absurdly far; the centre's count is then the best answer.
        centre_only(c0)
    }
}

/// The covered fraction from the centre's layer count alone: the whole
/// disk or none of it.
fn centre_only(c0: f64) -> f64 {
    if covered(c0) {
        1.0
    } else {
        0.0
    }
}

/// Into `kept`, the edges of `edges` that meet the disk, each once: one
/// direction per segment, bit-identical copies merged (their weights
/// added), those of weight 0 left out.
fn merge_edges(edges: &[MappedEdge], kept: &mut Vec<MappedEdge>) {
    kept.clear();
    kept.extend(
        edges
            .iter()
            .filter(|e| e.a.is_finite() && e.b.is_finite() && e.a != e.b && e.weight != 0.0)
            .filter(|e| meets_disk(e.a, e.b))
            .map(|e| {
                // One direction per segment (lexicographically ordered
                // endpoints), the weight signed accordingly, so that copies
                // of one edge can be merged below.
                if (e.a.x, e.a.y) <= (e.b.x, e.b.y) {
                    *e
                } else {
                    MappedEdge {
                        a: e.b,
                        b: e.a,
                        weight: -e.weight,
                    }
                }
            }),
    );
    // Merge bit-identical segments (an interior edge of the all-edges chain
    // appears once per face, in opposite directions, and cancels; a
    // contour edge appears once per sheet): the chain is the same, and the
    // arrangement costs O(k³) in the number of edges.
    kept.sort_by(|e, f| {
        (e.a.x, e.a.y, e.b.x, e.b.y)
            .partial_cmp(&(f.a.x, f.a.y, f.b.x, f.b.y))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut merged = 0;
    for k in 0..kept.len() {
        if merged > 0 && kept[merged - 1].a == kept[k].a && kept[merged - 1].b == kept[k].b {
            kept[merged - 1].weight += kept[k].weight;
        } else {
            kept[merged] = kept[k];
            merged += 1;
        }
    }
    kept.truncate(merged);
    kept.retain(|e| e.weight != 0.0);
}

/// Adds to `area` Green's sum over the boundary pieces of edge `kept[i]`
/// (the edge cut where it crosses the circle and the other edges, each
/// piece inside the disk kept when covered on one side only), and pushes
/// the angles where the edge crosses the circle onto `angles`.
fn add_pieces(
    c0: f64,
    kept: &[MappedEdge],
    i: usize,
    params: &mut Vec<f64>,
    angles: &mut Vec<f64>,
    area: &mut f64,
) {
    let e = &kept[i];
    let d = e.b - e.a;
    params.clear();
    params.extend([0.0, 1.0]);
    let before = params.len();
    circle_hits(e.a, e.b, params);
    for &t in &params[before..] {
        let p = e.a + d * t;
        angles.push(p.y.atan2(p.x));
    }
    for (j, f) in kept.iter().enumerate() {
        if i == j {
            continue;
        }
        let g = f.b - f.a;
        let den = cross(d, g);
        if den == 0.0 {
            continue;
        }
        let t = cross(f.a - e.a, g) / den;
        let u = cross(f.a - e.a, d) / den;
        if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u) {
            params.push(t);
        }
    }
    params.sort_by(f64::total_cmp);
    let n = d.try_normalize().map_or(DVec2::ZERO, DVec2::perp);
    for w in params.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t1 <= t0 {
            continue;
        }
        let m = e.a + d * (0.5 * (t0 + t1));
        if m.length_squared() >= 1.0 {
            continue;
        }
        let c_left = coverage(c0, kept, m + n * PROBE);
        let c_right = coverage(c0, kept, m - n * PROBE);
        let jump = c_left - c_right;
        if covered(c_left) != covered(c_right) && jump != 0.0 {
            // Edges lying on top of each other (the front and back
            // faces of a contour in the all-edges chain) share the
            // piece: each takes its weight's share of the jump, so the
            // piece is counted once whatever their number and direction.
            let (p, q) = (e.a + d * t0, e.a + d * t1);
            let side = if covered(c_left) { 1.0 } else { -1.0 };
            *area += side * segment_disk_area(1.0, p, q) * (e.weight / jump);
        }
    }
}

/// Adds to `area` the covered arcs of the circle, `½ Δφ` each, between
/// the `angles` where edges cross it (sorted here); the whole disk's `π`
/// when no edge crosses it and it is covered.
fn add_arcs(c0: f64, kept: &[MappedEdge], angles: &mut [f64], area: &mut f64) {
    let probe = |phi: f64| covered(coverage(c0, kept, DVec2::from_angle(phi) * (1.0 - PROBE)));
    if angles.is_empty() {
        if probe(0.0) {
            *area += PI;
        }
        return;
    }
    angles.sort_by(f64::total_cmp);
    for k in 0..angles.len() {
        let a0 = angles[k];
        let a1 = if k + 1 < angles.len() {
            angles[k + 1]
        } else {
            angles[0] + 2.0 * PI
        };
        if a1 > a0 && probe(0.5 * (a0 + a1)) {
            *area += 0.5 * (a1 - a0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(c: DVec2, h: f64, weight: f64) -> Vec<MappedEdge> {
        let v = [
            c + DVec2::new(-h, -h),
            c + DVec2::new(h, -h),
            c + DVec2::new(h, h),
            c + DVec2::new(-h, h),
        ];
        (0..4)
            .map(|i| MappedEdge {
                a: v[i],
                b: v[(i + 1) % 4],
                weight,
            })
            .collect()
    }

    #[test]
    fn one_square_is_its_area_in_the_disk() {
        let mut s = Scratch::default();
        // Inside the disk entirely: its area / π.
        let e = square(DVec2::new(0.5, 0.0), 0.2, 1.0);
        let v = union_occlusion(0.0, &e, &mut s);
        assert!((v - 0.16 / PI).abs() < 1e-14, "{v}");
        // Partly outside the disk (x from 0.2 to 1.2): arcs and pieces,
        // against polygon_disk_area (one Green sum, no arrangement).
        let e = square(DVec2::new(0.7, 0.0), 0.5, 1.0);
        let corners: Vec<DVec2> = e.iter().map(|m| m.a).collect();
        let want = crate::kernel::disk::f64::polygon_disk_area(1.0, &corners) / PI;
        let v = union_occlusion(0.0, &e, &mut s);
        assert!((v - want).abs() < 1e-14, "{v} {want}");
        // Covering the centre.
        let e = square(DVec2::ZERO, 0.3, 1.0);
        let v = union_occlusion(1.0, &e, &mut s);
        assert!((v - 0.36 / PI).abs() < 1e-14, "{v}");
        // Containing the disk: no edge meets it.
        let e = square(DVec2::ZERO, 3.0, 1.0);
        assert_eq!(union_occlusion(1.0, &e, &mut s), 1.0);
    }

    #[test]
    fn overlapping_squares_count_once() {
        let mut s = Scratch::default();
        // Two squares of half side `h` and edge weight `weight` at `x0`
        // and `x1` on the x axis, the layer count `c0` at the disk's
        // centre; their union's area, and the tolerance.
        for (x0, x1, h, weight, c0, area, tolerance) in [
            // A solid's contour in the all-edges chain: the front and the
            // back face each bring the same edge, weight ½ each, and the
            // layer count inside is ½ + ½. The piece must count once, not
            // once per copy (which doubles the occluded area).
            (0.5, 0.5, 0.2, 0.5, 0.0, 0.16, 1e-14),
            // Union: a 0.75 × 0.6 rectangle from x = −0.2 to 0.55, y ± 0.3.
            (0.1, 0.25, 0.3, 1.0, 2.0, 0.45, 1e-13),
        ] {
            let mut e = square(DVec2::new(x0, 0.0), h, weight);
            e.extend(square(DVec2::new(x1, 0.0), h, weight));
            let v = union_occlusion(c0, &e, &mut s);
            assert!((v - area / PI).abs() < tolerance, "{v}");
        }
    }
}
