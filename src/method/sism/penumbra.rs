//! SISM's penumbra pass (§2.2, §2.3, §2.5): a quad per silhouette edge
//! from the light's centre, binned over the receiver grid; for every
//! receiver a quad covers, eq. 3's signed circle-segment occlusion of its
//! footprint ([`Composition::Independent`]) or the edge mapped into the
//! footprint for the exact union ([`Composition::ExactUnion`]).

use super::grid::Grid;
use super::{Bound, Composition, Sism};
use crate::kernel::disk::f64::circle_segment_occlusion;
use crate::kernel::footprint::f64 as footprint;
use crate::kernel::wedge::f64::{penumbra_quad, PenumbraWedge, QuadBound};
use crate::method::centre::union::{self, MappedEdge};
use crate::method::centre::{left, projected_edges, HorizonEdge, ProjectedEdge};
use crate::render::Stages;
use glam::DVec2;
use rayon::prelude::*;

/// One edge of the penumbra pass: the shared projected edge, and its wedge
/// for [`Bound::Conservative`].
pub(super) struct PenEdge {
    edge: ProjectedEdge,
    wedge: Option<PenumbraWedge>,
}

impl std::ops::Deref for PenEdge {
    type Target = ProjectedEdge;
    fn deref(&self) -> &ProjectedEdge {
        &self.edge
    }
}

/// The edges of `sism`'s source in front of the deepest receiver, with
/// their wedges when the bound needs them.
pub(super) fn edges(
    sism: &Sism,
    stages: &Stages,
    grid: &Grid,
    z_near: f64,
    r: f64,
) -> Vec<PenEdge> {
    let center = stages.scene().light().center();
    projected_edges(stages, sism.edges.into(), z_near)
        .iter()
        .filter(|e| e.z_min < grid.z_max)
        .map(|&edge| PenEdge {
            edge,
            wedge: if sism.bound == Bound::Conservative {
                PenumbraWedge::new(edge.wa, edge.wb, center, r).ok()
            } else {
                None
            },
        })
        .collect()
}

/// What the penumbra pass reads.
pub(super) struct Pass<'a> {
    pub sism: &'a Sism,
    pub grid: &'a Grid,
    pub edges: &'a [PenEdge],
    /// The light's radius.
    pub r: f64,
    /// The umbra pass's layer count per stored receiver.
    pub umbra: &'a [f64],
    /// Per stored receiver, its tangent plane for the exact union (the
    /// `horizon` option with [`Composition::ExactUnion`]); empty otherwise.
    pub horizons: &'a [HorizonEdge],
}

/// The penumbra pass over every bin, in parallel; adds to `occlusion`
/// (or replaces it by the union, for [`Composition::ExactUnion`]).
pub(super) fn pass(pass: &Pass<'_>, occlusion: &mut [f64], evaluations: &mut [u32]) -> Counts {
    let (sism, grid, r) = (pass.sism, pass.grid, pass.r);
    // Bin the edges by their quad for the global greatest depth.
    let mut bin_edges: Vec<Vec<u32>> = vec![Vec::new(); grid.bins()];
    for (i, e) in pass.edges.iter().enumerate() {
        let Some(q) = quad(sism, e, r, grid.z_max) else {
            continue;
        };
        if let Some((x0, y0, x1, y1)) = grid.cell_range(q.lo, q.hi) {
            for by in y0 / grid.bin..=y1 / grid.bin {
                for bx in x0 / grid.bin..=x1 / grid.bin {
                    bin_edges[by as usize * grid.bx as usize + bx as usize].push(i as u32);
                }
            }
        }
    }
    let occ_bins = grid.split_bins(occlusion);
    let eval_bins = grid.split_bins(evaluations);
    occ_bins
        .into_par_iter()
        .zip(eval_bins)
        .enumerate()
        .map(|(b, (occ, evals))| penumbra_bin(pass, &bin_edges[b], b, occ, evals))
        .reduce(Counts::default, Counts::add)
}

/// The quad of edge `e` for receivers up to depth `z_max`; `None` when
/// no receiver that deep can be reached.
fn quad(sism: &Sism, e: &PenEdge, r: f64, z_max: f64) -> Option<Quad> {
    match sism.bound {
        Bound::Paper => {
            let radius = footprint::radius(r, e.z_min, z_max);
            if radius <= 0.0 {
                return None;
            }
            let d = e.b - e.a;
            let len = d.length();
            let axis = if len > 0.0 { d / len } else { DVec2::X };
            // A relative hair for the rounding of the footprint radii.
            let radius = radius * (1.0 + 1e-9);
            Some(Quad::new(
                (e.a + e.b) * 0.5,
                axis,
                0.5 * len + radius,
                radius,
            ))
        }
        Bound::Conservative => match penumbra_quad(e.la, e.lb, r, z_max) {
            Ok(QuadBound::Quad(q)) => {
                Some(Quad::new(q.center, q.axis, q.half_length, q.half_width))
            }
            Ok(QuadBound::Empty) | Err(_) => None,
            Ok(QuadBound::Unbounded) => Some(Quad::everything()),
        },
    }
}

/// The penumbra pass over bin `b`, whose edges are `list`.
fn penumbra_bin(
    pass: &Pass<'_>,
    list: &[u32],
    b: usize,
    occ: &mut [f64],
    evals: &mut [u32],
) -> Counts {
    let (sism, grid, edges, r) = (pass.sism, pass.grid, pass.edges, pass.r);
    let start = grid.bin_range(b).start;
    let (bx0, by0, bx1, by1) = grid.bin_cells(b);
    let mut counts = Counts::default();
    let union = sism.composition == Composition::ExactUnion;
    let mut mapped: Vec<Vec<MappedEdge>> = if union {
        vec![Vec::new(); occ.len()]
    } else {
        Vec::new()
    };
    let bin_zmax = grid.bin_zmax[b];
    for &ei in list {
        let e = &edges[ei as usize];
        let Some(global) = quad(sism, e, r, grid.z_max) else {
            continue;
        };
        let local = if sism.bin_depth {
            quad(sism, e, r, bin_zmax)
        } else {
            Some(global)
        };
        let Some((_, y0, _, y1)) = grid.cell_range(global.lo, global.hi) else {
            continue;
        };
        // Row by row, the cells the quad's rectangle meets: one span per
        // row (the rectangle is convex).
        for cy in y0.max(by0)..=y1.min(by1) {
            let (ylo, yhi) = grid.row_band(cy);
            let span = |q: &Quad| {
                q.row_span(ylo, yhi)
                    .and_then(|(a, b)| grid.col_range(a, b))
                    .map(|(a, b)| (a.max(bx0), b.min(bx1)))
                    .filter(|(a, b)| a <= b)
            };
            let hit = local.as_ref().and_then(span);
            if sism.bin_depth {
                let all = span(&global).map_or(0, |(a, b)| grid.row_count(cy, a, b));
                let kept = hit.map_or(0, |(a, b)| grid.row_count(cy, a, b));
                counts.saved_bin += all.saturating_sub(kept);
            }
            let Some((cx0, cx1)) = hit else {
                continue;
            };
            for cx in cx0..=cx1 {
                let mut first = 0;
                if sism.wedge_column && sism.bound == Bound::Paper {
                    // A lower bound of the distance from the cell to the
                    // projected edge: from its centre, less its half
                    // diagonal.
                    let (lo, hi) = grid.cell_box(cx, cy);
                    let dmin = (segment_distance((lo + hi) * 0.5, e.a, e.b)
                        - 0.5 * (hi - lo).length())
                    .max(0.0);
                    // The depth where the footprint reaches the cell;
                    // shallower receivers cannot.
                    let reach = footprint::reach_depth(r, e.z_min, dmin);
                    first = grid.first_slice_deeper(reach * (1.0 - 1e-9));
                    counts.saved_wedge +=
                        (grid.column(cx, cy, 0).len() - grid.column(cx, cy, first).len()) as u64;
                }
                for i in grid.column(cx, cy, first) {
                    if sism.wedge_column && sism.bound == Bound::Conservative {
                        if let Some(w) = &e.wedge {
                            if !w.contains(grid.world[i]) {
                                counts.saved_wedge += 1;
                                continue;
                            }
                        }
                    }
                    counts.evaluations += 1;
                    let k = i - start;
                    evals[k] += 1;
                    let (s, zp) = (grid.s[i], grid.z[i]);
                    if union {
                        if let Some(me) = map_edge(e, s, zp, r) {
                            mapped[k].push(me);
                        }
                    } else {
                        occ[k] += e.weight * segment_occlusion(e, s, zp, r);
                    }
                }
            }
        }
    }
    if union {
        let mut scratch = union::Scratch::default();
        for (k, list) in mapped.iter_mut().enumerate() {
            let mut centre = pass.umbra[start + k];
            if let Some(h) = pass.horizons.get(start + k) {
                centre += h.centre;
                list.extend(h.edge);
            }
            occ[k] = union::union_occlusion(centre, list, &mut scratch);
        }
    }
    counts
}

/// Work counters of the penumbra pass.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Counts {
    pub evaluations: u64,
    pub saved_bin: u64,
    pub saved_wedge: u64,
}

impl Counts {
    fn add(self, o: Counts) -> Counts {
        Counts {
            evaluations: self.evaluations + o.evaluations,
            saved_bin: self.saved_bin + o.saved_bin,
            saved_wedge: self.saved_wedge + o.saved_wedge,
        }
    }
}

/// An oriented rectangle on the image plane and its bounding box.
#[derive(Clone, Copy, Debug)]
struct Quad {
    center: DVec2,
    axis: DVec2,
    half_length: f64,
    half_width: f64,
    lo: DVec2,
    hi: DVec2,
}

impl Quad {
    fn new(center: DVec2, axis: DVec2, half_length: f64, half_width: f64) -> Quad {
        let perp = axis.perp();
        let ex = half_length * axis.x.abs() + half_width * perp.x.abs();
        let ey = half_length * axis.y.abs() + half_width * perp.y.abs();
        let e = DVec2::new(ex, ey);
        Quad {
            center,
            axis,
            half_length,
            half_width,
            lo: center - e,
            hi: center + e,
        }
    }

    fn everything() -> Quad {
        Quad {
            center: DVec2::ZERO,
            axis: DVec2::X,
            half_length: f64::INFINITY,
            half_width: f64::INFINITY,
            lo: DVec2::splat(f64::MIN),
            hi: DVec2::splat(f64::MAX),
        }
    }

    /// The x-range of the rectangle's part in the band `ylo ≤ y ≤ yhi`,
    /// `None` when it misses the band.
    fn row_span(&self, ylo: f64, yhi: f64) -> Option<(f64, f64)> {
        if self.half_length.is_infinite() || self.half_width.is_infinite() {
            return Some((f64::MIN, f64::MAX));
        }
        if self.hi.y < ylo || self.lo.y > yhi {
            return None;
        }
        let (along, across) = (
            self.axis * self.half_length,
            self.axis.perp() * self.half_width,
        );
        let corners = [
            self.center - along - across,
            self.center + along - across,
            self.center + along + across,
            self.center - along + across,
        ];
        let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..4 {
            let (p, q) = (corners[k], corners[(k + 1) % 4]);
            // The part of side p→q inside the band.
            let (t0, t1) = if p.y == q.y {
                if p.y < ylo || p.y > yhi {
                    continue;
                }
                (0.0, 1.0)
            } else {
                let ta = (ylo - p.y) / (q.y - p.y);
                let tb = (yhi - p.y) / (q.y - p.y);
                (ta.min(tb).max(0.0), ta.max(tb).min(1.0))
            };
            if t0 > t1 {
                continue;
            }
            for t in [t0, t1] {
                let x = p.x + (q.x - p.x) * t;
                x0 = x0.min(x);
                x1 = x1.max(x);
            }
        }
        (x0 <= x1).then_some((x0, x1))
    }
}

/// Eq. 3 for edge `e` and the receiver at image point `s`, depth `zp`: the
/// signed normalised area of the minor segment the edge cuts off the
/// footprint of radius `R = r (1/z_q − 1/z_p)`, `q` the edge point whose
/// projection is nearest `s`. Positive when `s` is outside the occluder
/// (right of the edge), negative inside.
fn segment_occlusion(e: &PenEdge, s: DVec2, zp: f64, r: f64) -> f64 {
    let d = e.b - e.a;
    let len2 = d.length_squared();
    if len2.is_nan() || len2 <= 0.0 {
        return 0.0;
    }
    let t = ((s - e.a).dot(d) / len2).clamp(0.0, 1.0);
    // 1/z is linear along the projected edge.
    let inv_zq = (1.0 - t) / e.la.z + t / e.lb.z;
    let radius = footprint::radius(r, 1.0 / inv_zq, zp);
    if radius <= 0.0 {
        return 0.0;
    }
    let len = len2.sqrt();
    let u = d / len;
    let dist = d.perp_dot(s - e.a).abs() / len;
    if dist.is_nan() || dist >= radius {
        return 0.0;
    }
    let dn = dist / radius;
    let signed = if left(e.a, e.b, s) { -dn } else { dn };
    let w0 = -(e.a - s).dot(u) / radius;
    let w1 = (e.b - s).dot(u) / radius;
    circle_segment_occlusion(signed, w0, w1)
}

/// Edge `e` mapped into the unit footprint of the receiver at image point
/// `s`, depth `zp`, for the exact composition ([`footprint::map_edge`]).
fn map_edge(e: &ProjectedEdge, s: DVec2, zp: f64, r: f64) -> Option<MappedEdge> {
    let (a, b) = footprint::map_edge(e.a, e.b, e.la, e.lb, s, zp, r)?;
    Some(MappedEdge {
        a,
        b,
        weight: e.weight,
    })
}

/// Distance from point `p` to segment `[a, b]`.
fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    (crate::method::centre::nearest_on(a, b, p).0 - p).length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arbitrary::Rng;

    #[test]
    fn row_spans_contain_the_rectangle() {
        let mut rng = Rng::new(0x5ba9);
        for _ in 0..2000 {
            let axis = DVec2::from_angle(rng.uniform(0.0, 6.3));
            let q = Quad::new(
                DVec2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
                axis,
                rng.uniform(0.0, 0.5),
                rng.uniform(0.0, 0.3),
            );
            let ylo = rng.uniform(-1.5, 1.5);
            let yhi = ylo + rng.uniform(0.0, 0.2);
            let span = q.row_span(ylo, yhi);
            for _ in 0..50 {
                let (u, v) = (rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
                let p = q.center + axis * (u * q.half_length) + axis.perp() * (v * q.half_width);
                if p.y < ylo || p.y > yhi {
                    continue;
                }
                let (x0, x1) = span.expect("the band meets the rectangle");
                let slack = 1e-12;
                assert!(p.x >= x0 - slack && p.x <= x1 + slack, "{p} {x0} {x1}");
            }
        }
    }

    #[test]
    fn the_tie_rule_gives_a_shared_edge_to_one_side() {
        let (a, b) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 2.0));
        let on = DVec2::new(0.5, 1.0);
        assert_ne!(left(a, b, on), left(b, a, on));
        assert!(left(a, b, DVec2::new(0.0, 1.0)));
        assert!(!left(b, a, DVec2::new(0.0, 1.0)));
    }
}
