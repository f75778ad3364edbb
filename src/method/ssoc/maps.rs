//! The soft shadow occlusion camera's distortion maps (Mo, Popescu & Wyman
//! §3.2.1, §4): two maps over the shadow map's texels, one inside and one
//! outside the hard shadow, each texel naming the nearest silhouette edge
//! whose distortion region covers it.
//!
//! Each silhouette edge from the light's centre (the shared projected,
//! clipped and oriented edges of `method::centre`, occluder on the left) is
//! extruded on the light image plane into a quad of half-width
//! `W = r(1/z_near − 1/Z)` around it — `z_near` the edge's depth at the
//! point nearest the texel (`1/z` interpolated along the edge), `Z` the
//! greatest receiver depth, so that `W` is the largest footprint radius any
//! receiver can have there (the paper gives no width; ours). A texel whose
//! centre lies within `W` of the edge belongs to the region: the half on the
//! occluder's side goes to the inside map, the other half to the outside
//! map. Where regions overlap, the texel keeps the edge nearest its centre
//! on the image plane (§3.2.1's depth test "based upon the distance to the
//! silhouette", not on light depth), ties to the lower edge index.
//!
//! A texel stores only the edge's index (its distance is kept per row while
//! the row is built); the nearest silhouette point `s`, the outward normal
//! `n̂` (the right-hand side of the oriented edge, away from the occluder),
//! `z_near` and `z_far` are taken from the edge when a receiver reads it,
//! so that two 1024² maps cost 8 MB rather than the paper's six floats per
//! texel. The maps are allocated zeroed (index `0` is "no edge", an edge is
//! stored plus one), so their pages are first touched by the rows that
//! write them, in parallel, rather than all by one thread.

use crate::kernel::footprint::f64 as footprint;
use crate::method::centre::{left, ProjectedEdge};
use crate::render::raster::LightView;
use glam::DVec2;
use rayon::prelude::*;

/// No edge covers the texel.
pub(crate) const NONE: u32 = u32::MAX;

/// The two distortion maps of a light view.
#[derive(Clone, Debug)]
pub(crate) struct DistortionMaps {
    width: u32,
    height: u32,
    /// Texels on the occluder's side of their edge (inside the hard
    /// shadow): the covering edge's index plus one, `0` for none.
    inside: Vec<u32>,
    /// Texels on the other side, stored as `inside`.
    outside: Vec<u32>,
}

impl DistortionMaps {
    /// The maps of `edges` over `view`, for a light of radius `r` and
    /// receivers no deeper than `z_max`. Rows in parallel; the result does
    /// not depend on the thread count.
    pub(crate) fn new(
        view: &LightView,
        edges: &[ProjectedEdge],
        r: f64,
        z_max: f64,
    ) -> DistortionMaps {
        let (w, h) = (view.width(), view.height());
        // Per edge: its widest half-width (at its nearest depth) and the
        // texel rows it can reach.
        let reach: Vec<Option<(f64, u32, u32)>> = edges
            .iter()
            .map(|e| {
                let half = footprint::radius(r, e.z_min, z_max);
                if !(half > 0.0 && half.is_finite()) {
                    return None;
                }
                let lo = view.to_pixel(e.a.min(e.b) - half);
                let hi = view.to_pixel(e.a.max(e.b) + half);
                if !(lo.y < f64::from(h) && hi.y >= 0.0 && lo.x < f64::from(w) && hi.x >= 0.0) {
                    return None;
                }
                let r0 = lo.y.max(0.0) as u32;
                let r1 = (hi.y.min(f64::from(h - 1))) as u32;
                Some((half, r0, r1))
            })
            .collect();
        let n = w as usize * h as usize;
        // Zeroed: pages the rows below never write are never touched.
        let (mut inside, mut outside) = (vec![0u32; n], vec![0u32; n]);
        inside
            .par_chunks_mut(w as usize)
            .zip(outside.par_chunks_mut(w as usize))
            .enumerate()
            .for_each_init(
                || (Vec::new(), Vec::new()),
                |(near_in, near_out), (row, (inside, outside))| {
                    // The distance of each texel's edge so far, this row only.
                    for near in [&mut *near_in, &mut *near_out] {
                        near.clear();
                        near.resize(w as usize, f32::INFINITY);
                    }
                    let row = row as u32;
                    for (k, (e, reach)) in edges.iter().zip(&reach).enumerate() {
                        let Some((half, r0, r1)) = *reach else {
                            continue;
                        };
                        if row < r0 || row > r1 {
                            continue;
                        }
                        // The columns the capsule spans on this row's centre line.
                        let y = view.pixel_center(0, row).y;
                        let (x0, x1) = row_span(e.a, e.b, half, y);
                        if x0 > x1 {
                            continue;
                        }
                        let c0 = view.to_pixel(DVec2::new(x0, y)).x.floor().max(0.0);
                        let c1 = view
                            .to_pixel(DVec2::new(x1, y))
                            .x
                            .ceil()
                            .min(f64::from(w - 1));
                        if c0 > c1 {
                            continue;
                        }
                        let (inv_a, inv_b) = (1.0 / e.la.z, 1.0 / e.lb.z);
                        let seg = e.b - e.a;
                        let seg2 = seg.length_squared();
                        let inv_far = 1.0 / z_max;
                        for col in c0 as u32..=c1 as u32 {
                            let c = view.pixel_center(col, row);
                            let t = if seg2 > 0.0 {
                                ((c - e.a).dot(seg) / seg2).clamp(0.0, 1.0)
                            } else {
                                0.0
                            };
                            let dist2 = (e.a + seg * t - c).length_squared();
                            if dist2 > half * half {
                                continue;
                            }
                            // The region's half-width at the nearest point: the
                            // footprint radius there of the deepest receiver
                            // (`1/z` interpolated along the edge).
                            let width = r * (((1.0 - t) * inv_a + t * inv_b) - inv_far);
                            if width.is_nan() || dist2 > width * width {
                                continue;
                            }
                            let d = dist2.sqrt() as f32;
                            let (map, near) = if left(e.a, e.b, c) {
                                (&mut *inside, &mut *near_in)
                            } else {
                                (&mut *outside, &mut *near_out)
                            };
                            let col = col as usize;
                            if d < near[col] {
                                near[col] = d;
                                map[col] = k as u32 + 1;
                            }
                        }
                    }
                },
            );
        DistortionMaps {
            width: w,
            height: h,
            inside,
            outside,
        }
    }

    /// The edge index map `inside`/outside names at texel `(col, row)`;
    /// [`NONE`] where no edge covers it or off the map.
    pub(crate) fn at(&self, inside: bool, col: i64, row: i64) -> u32 {
        if col < 0 || row < 0 || col >= i64::from(self.width) || row >= i64::from(self.height) {
            return NONE;
        }
        let i = (row as usize) * self.width as usize + col as usize;
        let stored = if inside {
            self.inside[i]
        } else {
            self.outside[i]
        };
        stored.wrapping_sub(1)
    }

    /// How many texels of each map an edge covers (inside, outside).
    pub(crate) fn coverage(&self) -> (usize, usize) {
        let n = |m: &[u32]| m.iter().filter(|&&e| e != 0).count();
        (n(&self.inside), n(&self.outside))
    }
}

/// The x-range where the line `y` meets the capsule of radius `half`
/// around `[a, b]` (empty: `x0 > x1`).
fn row_span(a: DVec2, b: DVec2, half: f64, y: f64) -> (f64, f64) {
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    // The two end disks.
    for c in [a, b] {
        let dy = y - c.y;
        if dy.abs() <= half {
            let dx = (half * half - dy * dy).max(0.0).sqrt();
            x0 = x0.min(c.x - dx);
            x1 = x1.max(c.x + dx);
        }
    }
    // The band around the segment: points at distance ≤ half from the line
    // whose projection falls inside the segment. Its boundary is a
    // parallelogram; its row span is found from its four corners' edges.
    let d = b - a;
    let len = d.length();
    if len > 0.0 {
        let n = d.perp() / len * half;
        let corners = [a + n, b + n, b - n, a - n];
        for k in 0..4 {
            let (p, q) = (corners[k], corners[(k + 1) % 4]);
            if (p.y - y) * (q.y - y) <= 0.0 && p.y != q.y {
                let x = p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y);
                x0 = x0.min(x);
                x1 = x1.max(x);
            } else if p.y == q.y && p.y == y {
                x0 = x0.min(p.x.min(q.x));
                x1 = x1.max(p.x.max(q.x));
            }
        }
    }
    (x0, x1)
}
