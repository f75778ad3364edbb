//! Soft irregular shadow mapping (Johnson, Hunt, Mark, Burns, Junkins,
//! "Soft Irregular Shadow Mapping: Fast, High-Quality, and Robust Soft
//! Shadows", I3D 2009): [`Sism`].
//!
//! # The algorithm (the paper's §2, step by step)
//!
//! Everything happens on the light image plane `z = 1` of a light frame
//! ([light image plane](crate::definitions#light-image-plane)): a point at light-frame `(x, y, z)` projects to
//! `π = (x/z, y/z)`, from the light's centre (the paper's *single point of
//! projection*, §5.1).
//!
//! 1. **Grid** (§2, Fig. 3; stage `sism grid`): the receivers are sorted by
//!    image-plane cell and depth slice into one contiguous array by a
//!    counting sort, `O(n)`. Cells are grouped in square bins (the sort-middle
//!    rasteriser's bins of §2.5); depth slices are uniform in `1/z`.
//! 2. **Umbra** (§2.4; stage `sism umbra`): every triangle is projected and
//!    rasterised over the grid; for each stored receiver of a covered cell,
//!    an exact point-in-triangle test (`orient2d` on the projected vertices,
//!    with a tie rule that gives a point on an edge shared by two triangles
//!    to exactly one of them) and a depth test (the triangle's plane
//!    separates the receiver from the light's centre, so triangles beyond
//!    the receiver do not count: decided by the triangle's depth range
//!    where it clears the receiver's depth by a relative `1e-12`, far above
//!    the rounding of light-frame depths, else by the exact `orient3d`).
//!    The result is the depth complexity between the receiver and the
//!    light's centre, weighted per surface as below: the *layer count*
//!    `U(p)`.
//! 3. **Penumbra** (§2.2, §2.3; stage `sism penumbra`): for each silhouette
//!    edge seen from the light's centre, a *penumbra quad*: the projected edge
//!    extended on all sides by `R = r (1/z_e − 1/Z)`, `z_e` the edge's least
//!    depth and `Z` the greatest receiver depth (the [footprint](crate::definitions#footprint-radius)
//!    radius). For every receiver `p` of a cell the quad covers, the light's
//!    footprint on the image plane is the disk of radius
//!    `R_p = r (1/z_q − 1/z_p)` around `π(p)`, `q` the point of the edge
//!    whose projection is nearest `π(p)` (Fig. 4; `1/z` is interpolated
//!    linearly along the projected edge, which is exact for perspective).
//!    `R_p ≤ 0` (the edge is not in front of the receiver) contributes
//!    nothing. Otherwise eq. 3, [`circle_segment_occlusion`], gives the
//!    signed normalised area `Ṽ` of the circular segment the edge cuts off
//!    the footprint.
//! 4. **Composition** (§2.4, eq. 4 with `C = 0`; stage `sism compose`):
//!    `V = 1 − U(p) − Σ_edges m_e Ṽ_e`, clamped to `[0, 1]` only here, at
//!    the end (counter `sism clamp fired`).
//!
//! # Signs (eq. 3 and eq. 4)
//!
//! Every chain edge is oriented so that the occluder lies on its **left** on
//! the image plane. The paper's "the sign of the dot product of the edge
//! equation and p" is the side of `π(p)`: on the right (outside the
//! occluder) the centre of the footprint is not counted by the umbra pass
//! and the minor segment the edge cuts off is *occluded* light, so `Ṽ > 0`
//! is added to the occlusion; on the left (inside), the umbra pass counted
//! the whole footprint as blocked and the minor segment on the far side of
//! the edge is *visible* light, so `Ṽ < 0` gives it back. This side is
//! decided by the same exact predicate and tie rule as the umbra pass's
//! point-in-triangle test, so the two passes never disagree about it. Summed
//! over the closed boundary of a polygon, `[π(p) inside] + Σ Ṽ` is exactly
//! the polygon's share of the footprint (Green's theorem: each edge's fan
//! from the centre is its sector minus the segment), which is why the
//! composition is correct for any single occluder whose silhouette is at one
//! depth, and why "every edge is a silhouette" (§2.1's fallback) gives the
//! same sum: an interior edge appears twice, in opposite directions, with
//! the same footprint, and its two terms cancel.
//!
//! # Layers: how surfaces are counted
//!
//! Occluders are two-sided ([visibility](crate::definitions#visibility)). The kernel's silhouette edges
//! ([`MeshTopology::silhouettes_from_point`]) carry a multiplicity `m`: the
//! jump in the number of triangles a ray from the light crosses — 2 across
//! the contour of a closed surface (its front and back sheets), 1 across the
//! boundary of an open one. A closed surface is crossed twice per layer, so
//! eq. 4's "depth complexity" over every triangle would count a solid twice
//! and darken its inner penumbra to black. Each connected component of a
//! mesh therefore has a weight `ω`: `½` when it is closed (every edge has
//! an even number of faces), `1` when it is open; the umbra pass adds `ω`
//! per covering triangle and each edge counts `ω m` (1 for the contour of a
//! solid, as a silhouette edge counts once in the paper). For one convex
//! solid or one open sheet `U + Σ` is then exact in the paper's model.
//! Components are found on the topology stage's *welded* vertices
//! ([`Stages::topology`]: corners at bit-identical positions are one), so a
//! solid stored as a triangle soup is still closed. A component that is
//! closed but for one odd edge — a hole, a fin, corners that differ in the
//! last bit — counts as open, which doubles its layers: its penumbra comes
//! out up to twice too deep (measured: errors near 0.5). Such meshes want
//! `sism:exact-union`, whose union does not count layers.
//! A receiver on or inside a closed surface (resting on the floor under a
//! box, say) sees an odd number of that surface's faces, a half layer; the
//! count is rounded up to whole layers, since the light's centre is blocked
//! there.
//!
//! # The known approximations (the paper's §5)
//!
//! - *Single point of projection* (§5.1): silhouettes are found from the
//!   light's centre, the footprint is a disk of the light frame's `z = 0`
//!   plane (the facing disk of a sphere light tilts off-axis), and one depth
//!   `z_q` stands for the whole edge.
//! - *Independent occluders* (§5.2): `C = 0`, overlapping occluders inside
//!   one footprint are added, which biases penumbrae darker.
//!   [`Composition::ExactUnion`] computes the union instead; it maps each
//!   edge endpoint with its own depth's footprint radius (so that the chain
//!   stays closed), where eq. 3 uses one radius per edge, so on a single
//!   occluder with a sloped silhouette the two differ slightly.
//!
//! # The quad is conservative for the paper's footprint, not for the light
//!
//! Every receiver whose footprint (radius `R_p ≤ R`) reaches the edge lies
//! within `R` of the projected edge, so [`Bound::Paper`]'s quad never drops
//! an edge term the paper's model would compute; [`Bound::Conservative`]
//! (the kernel's rigorous quad and wedge for the true, tilted facing disk)
//! therefore changes no value, only the work. What the paper's model misses
//! is in the footprint itself: a receiver can be partly shadowed by an edge
//! that no footprint of radius `r (1/z_q − 1/z_p)` around `π(p)` reaches
//! (the facing disk tilts; the edge's depth varies; surfaces near the
//! receiver's own depth). `docs/accuracy/sism.md` counts, per built-in
//! scene, the exact-penumbra receivers no edge term reaches and the largest
//! error there; it is measured, not changed, since changing it would no
//! longer be the paper's method.
//!
//! # Disk lights
//!
//! A disk light is handled with the light frame's `z` axis along the disk's
//! normal (toward the scene): its footprint is then exactly the disk of
//! radius `r (1/z_q − 1/z_p)`, the same formula as the sphere's. Receivers
//! behind the light's plane (`z ≤ 0`) are outside the light view; they read
//! `V = 1` and are counted (`sism receivers behind the light`).
//!
//! # The overdraw optimisations (§2.5)
//!
//! - [`Sism::bin_depth`]: each bin narrows the quad with its own greatest
//!   receiver depth instead of `Z`;
//! - [`Sism::wedge_column`]: for each covered cell, the depth where the
//!   edge's penumbra enters the cell's column, `1/z = 1/z_e − d/r` with `d`
//!   the distance from the cell to the projected edge; only the depth slices
//!   from there on are evaluated.
//!
//! Both skip only receivers whose footprint cannot reach the edge, so they
//! change no value; `sism evaluations saved by bin depth` and
//! `… by wedge column` count what they saved.
//!
//! [`circle_segment_occlusion`]: crate::kernel::disk::f64::circle_segment_occlusion
//! [`MeshTopology::silhouettes_from_point`]: crate::kernel::silhouette::MeshTopology::silhouettes_from_point
//! [`Stages::topology`]: crate::render::Stages::topology

mod grid;
mod penumbra;
mod umbra;

pub use crate::method::centre::EdgeSource;

use super::centre;
use super::options::{from_options, method_options};
use super::{Horizon, Input, Method, MethodError, Output};
use crate::kernel::footprint::f64::project;
use crate::render::Needs;
use crate::scene::LightKind;
use glam::DVec3;
use grid::{Entry, Grid};
use rayon::prelude::*;

/// How umbral and penumbral occlusion are combined (§2.4, §5.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Composition {
    /// The paper's eq. 4 with `C = 0`: `V = 1 − U − Σ Ṽ`; overlapping
    /// occluders are added (biased darker where penumbrae overlap).
    Independent,
    /// The exact composition: the boundary chain of the occluders in the
    /// footprint, each endpoint scaled by its own depth's footprint radius,
    /// cut at its crossings; `segment_disk_area` summed over the pieces that
    /// bound the union, plus the covered arcs. Removes the overlap bias of
    /// §5.2; the single point of projection remains.
    ExactUnion,
}

/// The bound that selects the receivers evaluated per edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// The paper's quad (`R = r (1/z_e − 1/Z)`) and, with
    /// [`Sism::wedge_column`], the column depth from the same footprint.
    /// Exactly the receivers the paper's footprint can reach.
    Paper,
    /// The kernel's rigorous bounds for the true (tilted) facing disk:
    /// [`penumbra_quad`](crate::kernel::wedge::f64::penumbra_quad) and, with
    /// [`Sism::wedge_column`],
    /// [`PenumbraWedge::contains`](crate::kernel::wedge::f64::PenumbraWedge::contains)
    /// per receiver. They contain the paper's
    /// region, so the values do not change (the paper's footprint, not its
    /// quad, is what misses true penumbrae); only the evaluation count does.
    Conservative,
}

method_options! {
    /// Soft irregular shadow mapping: see the [module docs](self).
    ///
    /// Sphere lights, and disk lights with the light frame along the disk's
    /// normal. Needs neither normals nor object ids (normals with the
    /// `horizon` option).
    ///
    /// It fits no map to the receivers: its grid holds the receivers
    /// themselves and each edge reaches every receiver its footprint meets, so
    /// a receiver's `V` does not depend on the other receivers of the call
    /// (`tests/maps.rs`), whatever the frame's [`Fit`](crate::render::Fit). A
    /// receiver on a closed mesh that faces away from the whole
    /// light reads `V = 0` ([`Method::hides_back_faces`]).
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[non_exhaustive]
    pub struct Sism {
        /// Which edges are processed; default [`EdgeSource::Silhouettes`]
        /// (§2.1).
        pub edges: EdgeSource = EdgeSource::Silhouettes, option(flag "all-edges" == EdgeSource::AllEdges, else EdgeSource::Silhouettes, "every triangle edge instead of the silhouettes (§2.1's fallback)"), builder(with_edges);
        /// How occlusion is combined; default [`Composition::Independent`]
        /// (eq. 4, `C = 0`, §5.2).
        pub composition: Composition = Composition::Independent, option(flag "exact-union" == Composition::ExactUnion, else Composition::Independent, "the union of the occluders in the footprint instead of C = 0 (§5.2, computed)"), builder(with_composition);
        /// Which quad/wedge selects receivers; default [`Bound::Paper`] (§2.2).
        pub bound: Bound = Bound::Paper, option(flag "conservative" == Bound::Conservative, else Bound::Paper, "the kernel's rigorous quad and wedge (changes the work, not the values)"), builder(with_bound);
        /// §2.5's first optimisation, the per-bin maximum receiver depth for the
        /// quad width; default `true` (the paper uses it).
        pub bin_depth: bool = true, option(flag ! "no-bin-depth", "without §2.5's per-bin depth optimisation");
        /// §2.5's second optimisation, the wedge/column intersection; default
        /// `true` (the paper uses it).
        pub wedge_column: bool = true, option(flag ! "no-wedge-column", "without §2.5's wedge/column optimisation");
        /// Grid cells per receiver, in `[1e-6, 64]`; default
        /// [`Sism::DEFAULT_CELLS_PER_RECEIVER`] = 1 (ours: the paper sizes its
        /// grid like the light-view image of hard irregular shadow mapping, one
        /// sample per pixel on average, without a figure).
        pub cells_per_receiver: f64 = Sism::DEFAULT_CELLS_PER_RECEIVER, option(real "cells", (1e-6, 64.0), "grid cells per receiver (ours)");
        /// Cells per side of a bin, `1..=1024`; default
        /// [`Sism::DEFAULT_BIN_CELLS`] = 16 (ours: the paper's bins are the
        /// Larrabee rasteriser's tiles, Seiler et al. 2008, size not stated).
        pub bin_cells: u32 = Sism::DEFAULT_BIN_CELLS, option(int "bin", (1, 1024), "cells per side of a bin (ours)");
        /// Depth slices of the perspective grid, `1..=256`; default
        /// [`Sism::DEFAULT_DEPTH_SLICES`] = 8 (ours: Fig. 3 shows a 3D grid
        /// without a count).
        ///
        /// The three grid sizes change only the work, never a value; the grid
        /// lowers them where needed to stay within `2²⁶` keys (512 MiB of
        /// offsets), so no valid option can exhaust memory.
        pub depth_slices: u32 = Sism::DEFAULT_DEPTH_SLICES, option(int "slices", (1, 256), "depth slices of the grid (ours)");
        /// The [horizon bound](Horizon), `V ≤ V_h`; default off (ours). With
        /// [`Composition::Independent`] it is `min(V, V_h)`; with
        /// [`Composition::ExactUnion`] the receiver's tangent plane is one more
        /// edge of the union.
        pub horizon: bool = false, option(flag "horizon", "V ≤ the light's share above the receiver's tangent plane (ours)"), builder(with_horizon);
    }
    name: "sism",
    summary: "soft irregular shadow mapping (Johnson et al. 2009)",
    lights: &[LightKind::Sphere, LightKind::Disk],
    default_run: &["sism"],
    compare: &["sism", "sism:exact-union", "sism:horizon", "sism:exact-union,horizon",
        "sism:all-edges", "sism:conservative"],
}

impl Sism {
    /// Default [`Sism::cells_per_receiver`].
    pub const DEFAULT_CELLS_PER_RECEIVER: f64 = 1.0;
    /// Default [`Sism::bin_cells`].
    pub const DEFAULT_BIN_CELLS: u32 = 16;
    /// Default [`Sism::depth_slices`].
    pub const DEFAULT_DEPTH_SLICES: u32 = 8;

    /// With or without §2.5's two overdraw optimisations.
    #[must_use]
    pub fn with_optimisations(self, bin_depth: bool, wedge_column: bool) -> Sism {
        Sism {
            bin_depth,
            wedge_column,
            ..self
        }
    }

    /// With the grid sizes (cells per receiver, bin side, depth slices).
    #[must_use]
    pub fn with_grid(self, cells_per_receiver: f64, bin_cells: u32, depth_slices: u32) -> Sism {
        Sism {
            cells_per_receiver,
            bin_cells,
            depth_slices,
            ..self
        }
    }
}

/// Everything [`Sism::passes`] computed, per receiver in the frame's order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SismPasses {
    /// The clamped visibility (what [`Method::visibility`] returns).
    pub visibility: Vec<f64>,
    /// The umbra pass: the layer count `U(p)` between the receiver and the
    /// light's centre, in whole layers (`0` for receivers behind the
    /// light).
    pub umbra: Vec<f64>,
    /// The total occlusion before clamping: `U + Σ Ṽ`
    /// ([`Composition::Independent`]) or the union's share of the footprint
    /// ([`Composition::ExactUnion`]); `V = clamp(1 − occlusion)`.
    pub occlusion: Vec<f64>,
    /// How many edges were evaluated at the receiver.
    pub evaluations: Vec<u32>,
}

impl Method for Sism {
    from_options!();

    /// Yes: see the trait's doc (no option of the paper asks otherwise).
    fn hides_back_faces(&self) -> bool {
        true
    }

    fn needs(&self) -> Needs {
        Needs::TOPOLOGY | Needs::LIGHT_FRAME
    }

    fn horizon(&self) -> Horizon {
        match (self.horizon, self.composition) {
            (false, _) => Horizon::Off,
            (true, Composition::Independent) => Horizon::Clamp,
            (true, Composition::ExactUnion) => Horizon::Within,
        }
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        Ok(Output::values(self.passes(input)?.visibility))
    }
}

impl Sism {
    /// Runs the passes and returns their per-receiver results (the
    /// visibility, the umbra layer count, the occlusion before clamping,
    /// the edge evaluations), for tests and diagnostics; `input` comes from
    /// [`method::check`](super::check).
    ///
    /// # Errors
    /// An invalid option.
    pub fn passes(&self, input: &Input<'_, '_>) -> Result<SismPasses, MethodError> {
        super::check_options(self)?;
        let stages = input.stages();
        // The stages' light frame lies along a disk light's normal, where
        // the footprint radius `R` is exact for edges parallel to it.
        let r = input.light().equivalent_radius();
        let light_frame = stages.light_frame();
        let receivers = input.receivers();
        let n = receivers.len();

        // 1. The grid: receivers projected (in parallel), then sorted.
        let grid_start = std::time::Instant::now();
        let entries: Vec<Entry> = receivers
            .par_iter()
            .enumerate()
            .filter_map(|(index, rec)| {
                let q = light_frame.to_light(rec.position);
                let s = project(q);
                (q.z > 0.0 && s.is_finite()).then_some(Entry {
                    s,
                    z: q.z,
                    world: rec.position,
                    index: index as u32,
                })
            })
            .collect();
        let behind = (n - entries.len()) as u64;
        let grid = Grid::build(
            &entries,
            self.cells_per_receiver,
            self.bin_cells,
            self.depth_slices,
        );
        stages.record(
            "sism grid",
            format!(
                "{} receivers, {}×{} cells, {} bins, {} slices",
                entries.len(),
                grid.nx,
                grid.ny,
                grid.bins(),
                grid.slices
            ),
            grid_start.elapsed(),
        );
        drop(entries);
        stages.count("sism receivers behind the light", behind);
        let z_near = grid.z_max * 1e-9;

        // 2. Umbra: the layer count between each receiver and the centre.
        let umbra = umbra::pass(stages, &grid, z_near);

        // 3. Penumbra: the edges from the centre, then per bin.
        let edges = penumbra::edges(self, stages, &grid, z_near, r);
        stages.count("sism penumbra edges", edges.len() as u64);
        let horizons = if self.horizon && self.composition == Composition::ExactUnion {
            horizon_edges(input, &grid, r)
        } else {
            Vec::new()
        };
        let mut occlusion = umbra.clone();
        let mut evaluations = vec![0u32; grid.s.len()];
        let counts = stages.timed("sism penumbra", || {
            let pass = penumbra::Pass {
                sism: self,
                grid: &grid,
                edges: &edges,
                r,
                umbra: &umbra,
                horizons: &horizons,
            };
            let counts = penumbra::pass(&pass, &mut occlusion, &mut evaluations);
            let detail = format!(
                "{} edges, {} edge-receiver evaluations",
                edges.len(),
                counts.evaluations
            );
            (counts, detail)
        });
        stages.count("sism edge-receiver evaluations", counts.evaluations);
        stages.count("sism evaluations saved by bin depth", counts.saved_bin);
        stages.count("sism evaluations saved by wedge column", counts.saved_wedge);

        // 4. Composition, back in the frame's order.
        let passes = stages.timed("sism compose", || {
            let mut out = SismPasses {
                visibility: vec![1.0; n],
                umbra: vec![0.0; n],
                occlusion: vec![0.0; n],
                evaluations: vec![0; n],
            };
            let mut clamped = 0u64;
            for i in 0..grid.s.len() {
                let k = grid.index[i] as usize;
                let v = 1.0 - occlusion[i];
                if !(0.0..=1.0).contains(&v) {
                    clamped += 1;
                }
                out.visibility[k] = if v.is_nan() { 1.0 } else { v.clamp(0.0, 1.0) };
                out.umbra[k] = umbra[i];
                out.occlusion[k] = occlusion[i];
                out.evaluations[k] = evaluations[i];
            }
            stages.count("sism clamp fired", clamped);
            (out, format!("{clamped} clamped"))
        });
        stages.advance(n);
        Ok(passes)
    }
}

/// Per stored receiver of `grid`, its tangent plane in its unit footprint
/// (receivers without a normal put no bound).
fn horizon_edges(input: &Input<'_, '_>, grid: &Grid, r: f64) -> Vec<centre::HorizonEdge> {
    let frame = input.stages().light_frame();
    let [ax, ay, az] = frame.axes();
    let receivers = input.receivers();
    (0..grid.s.len())
        .into_par_iter()
        .map(|i| {
            let rec = &receivers[grid.index[i] as usize];
            rec.normal.map_or_else(centre::HorizonEdge::default, |n| {
                let n = DVec3::new(n.dot(ax), n.dot(ay), n.dot(az));
                centre::horizon_edge(n, frame.to_light(rec.position), r)
            })
        })
        .collect()
}
