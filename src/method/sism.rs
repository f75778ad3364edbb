//! Soft irregular shadow mapping (Johnson, Hunt, Mark, Burns, Junkins,
//! "Soft Irregular Shadow Mapping: Fast, High-Quality, and Robust Soft
//! Shadows", I3D 2009): [`Sism`].
//!
//! # The algorithm (the paper's §2, step by step)
//!
//! Everything happens on the light image plane `z = 1` of a light frame
//! (DESIGN §2): a point at light-frame `(x, y, z)` projects to
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
//!    depth and `Z` the greatest receiver depth (DESIGN §2's footprint
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
//! Occluders are two-sided (DESIGN §1). The kernel's silhouette edges
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

mod grid;
mod union;

use super::{Method, MethodError, Output};
use crate::kernel::disk::f64::circle_segment_occlusion;
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use crate::kernel::silhouette::MeshTopology;
use crate::kernel::wedge::f64::{penumbra_quad, PenumbraWedge, QuadBound};
use crate::render::{Frame, Needs, Stages};
use crate::scene::Light;
use glam::{DVec2, DVec3};
use grid::{Entry, Grid};
use rayon::prelude::*;
use union::MappedEdge;

/// Which edges get a penumbra quad (§2.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeSource {
    /// The silhouette edges seen from the light's centre, with their
    /// multiplicity (the paper's choice, "silhouettes improve performance").
    Silhouettes,
    /// Every edge of every triangle (the paper's fallback "in the absence of
    /// adjacency information we assume all edges are silhouettes"): the same
    /// values up to rounding, more work.
    AllEdges,
}

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
    /// [`penumbra_quad`] and, with [`Sism::wedge_column`],
    /// [`PenumbraWedge::contains`] per receiver. They contain the paper's
    /// region, so the values do not change (the paper's footprint, not its
    /// quad, is what misses true penumbrae); only the evaluation count does.
    Conservative,
}

/// Soft irregular shadow mapping: see the [module docs](self).
///
/// Sphere lights, and disk lights with the light frame along the disk's
/// normal; other lights are [`MethodError::UnsupportedLight`]. Needs neither
/// normals nor object ids.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sism {
    /// Which edges are processed; default [`EdgeSource::Silhouettes`]
    /// (§2.1).
    pub edges: EdgeSource,
    /// How occlusion is combined; default [`Composition::Independent`]
    /// (eq. 4, `C = 0`, §5.2).
    pub composition: Composition,
    /// Which quad/wedge selects receivers; default [`Bound::Paper`] (§2.2).
    pub bound: Bound,
    /// §2.5's first optimisation, the per-bin maximum receiver depth for the
    /// quad width; default `true` (the paper uses it).
    pub bin_depth: bool,
    /// §2.5's second optimisation, the wedge/column intersection; default
    /// `true` (the paper uses it).
    pub wedge_column: bool,
    /// Grid cells per receiver, in `(0, 64]`; default
    /// [`Sism::DEFAULT_CELLS_PER_RECEIVER`] = 1 (ours: the paper sizes its
    /// grid like the light-view image of hard irregular shadow mapping, one
    /// sample per pixel on average, without a figure).
    pub cells_per_receiver: f64,
    /// Cells per side of a bin, `1..=1024`; default
    /// [`Sism::DEFAULT_BIN_CELLS`] = 16 (ours: the paper's bins are the
    /// Larrabee rasteriser's tiles, Seiler et al. 2008, size not stated).
    pub bin_cells: u32,
    /// Depth slices of the perspective grid, `1..=256`; default
    /// [`Sism::DEFAULT_DEPTH_SLICES`] = 8 (ours: Fig. 3 shows a 3D grid
    /// without a count).
    ///
    /// The three grid sizes change only the work, never a value; the grid
    /// lowers them where needed to stay within `2²⁶` keys (512 MiB of
    /// offsets), so no valid option can exhaust memory.
    pub depth_slices: u32,
}

impl Sism {
    /// Default [`Sism::cells_per_receiver`].
    pub const DEFAULT_CELLS_PER_RECEIVER: f64 = 1.0;
    /// Default [`Sism::bin_cells`].
    pub const DEFAULT_BIN_CELLS: u32 = 16;
    /// Default [`Sism::depth_slices`].
    pub const DEFAULT_DEPTH_SLICES: u32 = 8;

    /// The method named `sism` or `sism:OPT,OPT,…` on the command line, with
    /// `OPT` one of `all-edges`, `exact-union`, `conservative`,
    /// `no-bin-depth`, `no-wedge-column`, `cells=X`, `bin=N`, `slices=N`.
    ///
    /// # Errors
    /// A message naming the option that is not understood.
    pub fn from_name(name: &str) -> Result<Sism, String> {
        let mut s = Sism::default();
        let options =
            super::option_list(name, "sism").ok_or_else(|| format!("unknown method '{name}'"))?;
        for opt in options {
            let bad = || {
                format!(
                    "'{name}': option '{opt}' is not one of all-edges, exact-union, \
                     conservative, no-bin-depth, no-wedge-column, cells=X, bin=N, slices=N"
                )
            };
            match opt {
                "all-edges" => s.edges = EdgeSource::AllEdges,
                "exact-union" => s.composition = Composition::ExactUnion,
                "conservative" => s.bound = Bound::Conservative,
                "no-bin-depth" => s.bin_depth = false,
                "no-wedge-column" => s.wedge_column = false,
                _ => {
                    let (k, v) = opt.split_once('=').ok_or_else(bad)?;
                    match k {
                        "cells" => s.cells_per_receiver = v.parse().map_err(|_| bad())?,
                        "bin" => s.bin_cells = v.parse().map_err(|_| bad())?,
                        "slices" => s.depth_slices = v.parse().map_err(|_| bad())?,
                        _ => return Err(bad()),
                    }
                }
            }
        }
        Ok(s)
    }

    fn check(&self) -> Result<(), MethodError> {
        let invalid = |message: &str| MethodError::InvalidOption {
            method: self.name(),
            message: message.to_owned(),
        };
        if !(self.cells_per_receiver > 0.0 && self.cells_per_receiver <= 64.0) {
            return Err(invalid("cells per receiver must be in (0, 64]"));
        }
        if !(1..=1024).contains(&self.bin_cells) {
            return Err(invalid("bin cells must be from 1 to 1024"));
        }
        if !(1..=256).contains(&self.depth_slices) {
            return Err(invalid("depth slices must be from 1 to 256"));
        }
        Ok(())
    }
}

impl Default for Sism {
    fn default() -> Sism {
        Sism {
            edges: EdgeSource::Silhouettes,
            composition: Composition::Independent,
            bound: Bound::Paper,
            bin_depth: true,
            wedge_column: true,
            cells_per_receiver: Sism::DEFAULT_CELLS_PER_RECEIVER,
            bin_cells: Sism::DEFAULT_BIN_CELLS,
            depth_slices: Sism::DEFAULT_DEPTH_SLICES,
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
    fn name(&self) -> String {
        let d = Sism::default();
        let mut opts: Vec<String> = Vec::new();
        if self.edges == EdgeSource::AllEdges {
            opts.push("all-edges".into());
        }
        if self.composition == Composition::ExactUnion {
            opts.push("exact-union".into());
        }
        if self.bound == Bound::Conservative {
            opts.push("conservative".into());
        }
        if !self.bin_depth {
            opts.push("no-bin-depth".into());
        }
        if !self.wedge_column {
            opts.push("no-wedge-column".into());
        }
        if self.cells_per_receiver != d.cells_per_receiver {
            opts.push(format!("cells={}", self.cells_per_receiver));
        }
        if self.bin_cells != d.bin_cells {
            opts.push(format!("bin={}", self.bin_cells));
        }
        if self.depth_slices != d.depth_slices {
            opts.push(format!("slices={}", self.depth_slices));
        }
        if opts.is_empty() {
            "sism".to_owned()
        } else {
            format!("sism:{}", opts.join(","))
        }
    }

    fn needs(&self, light: &Light) -> Result<Needs, MethodError> {
        match light {
            Light::Sphere { .. } | Light::Disk { .. } => Ok(Needs::TOPOLOGY | Needs::LIGHT_FRAME),
            _ => Err(MethodError::UnsupportedLight {
                method: self.name(),
                light: super::light_kind(light),
            }),
        }
    }

    fn visibility(&self, stages: &Stages, frame: &Frame) -> Result<Output, MethodError> {
        let passes = self.passes(stages, frame)?;
        Ok(Output {
            visibility: passes.visibility,
            stderr: None,
        })
    }
}

/// One triangle of the umbra pass, projected.
struct UmbraTri {
    /// Projected corners, counter-clockwise.
    p: [DVec2; 3],
    lo: DVec2,
    hi: DVec2,
    /// The world triangle (for the exact depth test).
    world: [DVec3; 3],
    /// `orient3d(world, light centre)`, never zero.
    light_side: Sign,
    /// Least and greatest light-frame depth of the corners.
    z_min: f64,
    z_max: f64,
    weight: f64,
}

/// Relative margin on light-frame depths (each rounded a few times) when
/// they decide a depth order without the exact test.
const DEPTH_MARGIN: f64 = 1e-12;

/// One chain edge of the penumbra pass.
struct PenEdge {
    /// Projected endpoints (clipped in front of the light), occluder on the
    /// left.
    a: DVec2,
    b: DVec2,
    /// Light-frame endpoints, as projected.
    la: DVec3,
    lb: DVec3,
    z_min: f64,
    weight: f64,
    wedge: Option<PenumbraWedge>,
}

/// `true` when `s` is on the left of `a → b`, ties (`s` on the line) broken
/// by the edge's direction so that the two directions of an edge disagree.
fn left(a: DVec2, b: DVec2, s: DVec2) -> bool {
    match orient2d(a, b, s) {
        Sign::Positive => true,
        Sign::Negative => false,
        Sign::Zero => (b.y, b.x) < (a.y, a.x),
    }
}

fn project(q: DVec3) -> DVec2 {
    DVec2::new(q.x / q.z, q.y / q.z)
}

/// The part of segment `[a, b]` at depth `z ≥ near` (light frame).
fn clip_near(a: DVec3, b: DVec3, near: f64) -> Option<(DVec3, DVec3)> {
    match (a.z >= near, b.z >= near) {
        (true, true) => Some((a, b)),
        (false, false) => None,
        (ina, _) => {
            let t = (near - a.z) / (b.z - a.z);
            let mut c = a + (b - a) * t;
            c.z = near;
            Some(if ina { (a, c) } else { (c, b) })
        }
    }
}

/// Distance from point `p` to segment `[a, b]`.
fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let dd = d.length_squared();
    let t = if dd > 0.0 {
        ((p - a).dot(d) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * t - p).length()
}

/// The layer weights `ω` of the module docs, per face and per edge: `½` in
/// closed connected components (every edge with an even number of faces),
/// `1` in open ones.
fn component_weights(topo: &MeshTopology) -> (Vec<f64>, Vec<f64>) {
    let faces = topo.triangles().len();
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    let edges = topo.edges().len();
    for e in 0..edges {
        let mut it = topo.edge_faces(e);
        if let Some(f0) = it.next() {
            for f in it {
                let (a, b) = (find(&mut parent, f0.face), find(&mut parent, f.face));
                if a != b {
                    parent[a as usize] = b;
                }
            }
        }
    }
    let mut open = vec![false; faces];
    let mut edge_root = vec![u32::MAX; edges];
    for (e, root) in edge_root.iter_mut().enumerate() {
        let faces_of = topo.edge_faces(e);
        let odd = faces_of.len() % 2 == 1;
        if let Some(f) = topo.edge_faces(e).next() {
            let r = find(&mut parent, f.face);
            *root = r;
            if odd {
                open[r as usize] = true;
            }
        }
    }
    let weight = |open: bool| if open { 1.0 } else { 0.5 };
    let face_w = (0..faces as u32)
        .map(|f| weight(open[find(&mut parent, f) as usize]))
        .collect();
    let edge_w = edge_root
        .iter()
        .map(|&r| {
            if r == u32::MAX {
                1.0
            } else {
                weight(open[r as usize])
            }
        })
        .collect();
    (face_w, edge_w)
}

/// Splits `data` into the consecutive ranges of the grid's bins.
fn split_bins<'a, T>(grid: &Grid, mut data: &'a mut [T]) -> Vec<&'a mut [T]> {
    let mut out = Vec::with_capacity(grid.bins());
    for b in 0..grid.bins() {
        let len = grid.bin_range(b).len();
        let (head, tail) = std::mem::take(&mut data).split_at_mut(len);
        out.push(head);
        data = tail;
    }
    out
}

/// The first depth slice whose receivers can be deeper than `z` (the grid's
/// per-slice maxima grow with the slice; empty slices read 0).
fn first_slice_deeper(grid: &Grid, z: f64) -> u32 {
    grid.slice_zmax
        .iter()
        .position(|&m| m > z)
        .map_or(grid.slices, |k| k as u32)
}

impl Sism {
    /// Runs the passes and returns their per-receiver results (the
    /// visibility, the umbra layer count, the occlusion before clamping,
    /// the edge evaluations), for tests and diagnostics.
    ///
    /// # Errors
    /// As [`Method::visibility`]: an unsupported light, an invalid option,
    /// a receiver inside a sphere light or in a disk light's plane.
    pub fn passes(&self, stages: &Stages, frame: &Frame) -> Result<SismPasses, MethodError> {
        self.check()?;
        let scene = stages.scene();
        let light = scene.light();
        self.needs(light)?;
        // The stages' light frame lies along a disk light's normal, where
        // the footprint radius `R` is exact for edges parallel to it.
        let r = match *light {
            Light::Sphere { radius, .. } | Light::Disk { radius, .. } => radius,
            _ => {
                return Err(MethodError::UnsupportedLight {
                    method: self.name(),
                    light: super::light_kind(light),
                })
            }
        };
        let light_frame = stages.light_frame();
        let receivers = frame.receivers();
        let n = receivers.len();
        let center = light.center();

        // 1. The grid: receivers checked and projected (in parallel), then
        // sorted.
        let grid_start = std::time::Instant::now();
        let projected: Vec<Result<Option<Entry>, MethodError>> = receivers
            .par_iter()
            .enumerate()
            .map(|(index, rec)| {
                light
                    .emitter(rec.position)
                    .map_err(|error| MethodError::Receiver { index, error })?;
                let q = light_frame.to_light(rec.position);
                let s = project(q);
                Ok((q.z > 0.0 && s.is_finite()).then_some(Entry {
                    s,
                    z: q.z,
                    world: rec.position,
                    index: index as u32,
                }))
            })
            .collect();
        let mut entries = Vec::with_capacity(n);
        for p in projected {
            if let Some(e) = p? {
                entries.push(e);
            }
        }
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
        let m = grid.s.len();
        let z_near = grid.z_max * 1e-9;

        // The occluders in the light frame: per mesh, the projected vertices
        // (one rounding per vertex, shared by both passes).
        let topology = stages.topology();
        let cover_left = orient3d(
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::ZERO,
        ) == Sign::Negative;

        let (tris, edges) = stages.timed("sism edges", || {
            let mut tris = Vec::new();
            let mut edges = Vec::new();
            let mut sil = Vec::new();
            for (mesh_index, mesh) in scene.meshes().iter().enumerate() {
                let pos = mesh.positions();
                let lf: Vec<DVec3> = pos.iter().map(|&p| light_frame.to_light(p)).collect();
                let topo = topology.get(mesh_index).and_then(Option::as_ref);
                let (face_w, edge_w) = match topo {
                    Some(t) => component_weights(t),
                    None => (vec![1.0; mesh.triangles().len()], Vec::new()),
                };
                for (f, t) in mesh.triangles().iter().enumerate() {
                    push_umbra_tri(&mut tris, t, pos, &lf, center, face_w[f], z_near);
                }
                let mut push_edge = |from: u32, to: u32, weight: f64| {
                    let (from, to) = if cover_left { (from, to) } else { (to, from) };
                    let (wa, wb) = (pos[from as usize], pos[to as usize]);
                    let Some((la, lb)) = clip_near(lf[from as usize], lf[to as usize], z_near)
                    else {
                        return;
                    };
                    let z_min = la.z.min(lb.z);
                    if z_min >= grid.z_max {
                        return;
                    }
                    let (a, b) = (project(la), project(lb));
                    if a == b || !a.is_finite() || !b.is_finite() {
                        return;
                    }
                    let wedge = if self.bound == Bound::Conservative {
                        PenumbraWedge::new(wa, wb, center, r).ok()
                    } else {
                        None
                    };
                    edges.push(PenEdge {
                        a,
                        b,
                        la,
                        lb,
                        z_min,
                        weight,
                        wedge,
                    });
                };
                match (self.edges, topo) {
                    (EdgeSource::Silhouettes, Some(topo)) => {
                        sil.clear();
                        if topo
                            .silhouettes_from_point_into(pos, center, &mut sil)
                            .is_ok()
                        {
                            for e in &sil {
                                let w = edge_w.get(e.edge as usize).copied().unwrap_or(1.0);
                                push_edge(e.from, e.to, w * f64::from(e.multiplicity));
                            }
                        }
                    }
                    _ => {
                        for (f, t) in mesh.triangles().iter().enumerate() {
                            if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                                continue;
                            }
                            let [a, b, c] = t.map(|i| pos[i as usize]);
                            let front = orient3d(a, b, c, center) == Sign::Negative;
                            let w = face_w[f];
                            for k in 0..3 {
                                let (u, v) = (t[k], t[(k + 1) % 3]);
                                if front {
                                    push_edge(u, v, w);
                                } else {
                                    push_edge(v, u, w);
                                }
                            }
                        }
                    }
                }
            }
            let detail = format!("{} triangles, {} edges", tris.len(), edges.len());
            ((tris, edges), detail)
        });
        stages.count("sism penumbra edges", edges.len() as u64);

        // 2. Umbra: triangles binned, then per bin in parallel.
        let mut umbra = vec![0.0f64; m];
        stages.timed("sism umbra", || {
            let mut bin_tris: Vec<Vec<u32>> = vec![Vec::new(); grid.bins()];
            for (i, t) in tris.iter().enumerate() {
                if t.z_min >= grid.z_max {
                    continue;
                }
                if let Some((x0, y0, x1, y1)) = grid.cell_range(t.lo, t.hi) {
                    for by in y0 / grid.bin..=y1 / grid.bin {
                        for bx in x0 / grid.bin..=x1 / grid.bin {
                            bin_tris[by as usize * grid.bx as usize + bx as usize].push(i as u32);
                        }
                    }
                }
            }
            let tests: u64 = split_bins(&grid, &mut umbra)
                .into_par_iter()
                .enumerate()
                .map(|(b, acc)| {
                    let start = grid.bin_range(b).start;
                    let (bx0, by0, bx1, by1) = grid.bin_cells(b);
                    let mut tests = 0u64;
                    for &ti in &bin_tris[b] {
                        let t = &tris[ti as usize];
                        let Some((x0, y0, x1, y1)) = grid.cell_range(t.lo, t.hi) else {
                            continue;
                        };
                        let first = first_slice_deeper(&grid, t.z_min);
                        for cy in y0.max(by0)..=y1.min(by1) {
                            for cx in x0.max(bx0)..=x1.min(bx1) {
                                for i in grid.column(cx, cy, first) {
                                    let s = grid.s[i];
                                    if s.x < t.lo.x || s.x > t.hi.x || s.y < t.lo.y || s.y > t.hi.y
                                    {
                                        continue;
                                    }
                                    let zp = grid.z[i];
                                    if zp < t.z_min * (1.0 - DEPTH_MARGIN) {
                                        // The whole triangle is beyond the
                                        // receiver.
                                        continue;
                                    }
                                    tests += 1;
                                    let [p0, p1, p2] = t.p;
                                    if !(left(p0, p1, s) && left(p1, p2, s) && left(p2, p0, s)) {
                                        continue;
                                    }
                                    // The ray meets the triangle: it is in
                                    // front of the receiver when wholly
                                    // nearer, else the exact plane test.
                                    let between = zp * (1.0 - DEPTH_MARGIN) > t.z_max
                                        || orient3d(
                                            t.world[0],
                                            t.world[1],
                                            t.world[2],
                                            grid.world[i],
                                        ) == t.light_side.flip();
                                    if between {
                                        acc[i - start] += t.weight;
                                    }
                                }
                            }
                        }
                    }
                    tests
                })
                .sum();
            (
                (),
                format!("{} triangles, {tests} point-in-triangle tests", tris.len()),
            )
        });

        // A half layer comes only from a receiver on or inside a closed
        // surface (an odd number of its faces in front of it): the centre is
        // blocked, so it counts as a whole layer.
        for u in &mut umbra {
            *u = u.ceil();
        }

        // 3. Penumbra.
        let mut occlusion = umbra.clone();
        let mut evaluations = vec![0u32; m];
        let counts = stages.timed("sism penumbra", || {
            let counts = self.penumbra(&grid, &edges, r, &umbra, &mut occlusion, &mut evaluations);
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
            for i in 0..m {
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

    /// The penumbra pass over every bin, in parallel; adds to `occlusion`
    /// (or replaces it by the union, for [`Composition::ExactUnion`]).
    fn penumbra(
        &self,
        grid: &Grid,
        edges: &[PenEdge],
        r: f64,
        umbra: &[f64],
        occlusion: &mut [f64],
        evaluations: &mut [u32],
    ) -> Counts {
        // Bin the edges by their quad for the global greatest depth.
        let mut bin_edges: Vec<Vec<u32>> = vec![Vec::new(); grid.bins()];
        for (i, e) in edges.iter().enumerate() {
            let Some(q) = self.quad(e, r, grid.z_max) else {
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
        let occ_bins = split_bins(grid, occlusion);
        let eval_bins = split_bins(grid, evaluations);
        occ_bins
            .into_par_iter()
            .zip(eval_bins)
            .enumerate()
            .map(|(b, (occ, evals))| {
                self.penumbra_bin(grid, edges, &bin_edges[b], b, r, umbra, occ, evals)
            })
            .reduce(Counts::default, Counts::add)
    }

    /// The quad of edge `e` for receivers up to depth `z_max`; `None` when
    /// no receiver that deep can be reached.
    fn quad(&self, e: &PenEdge, r: f64, z_max: f64) -> Option<Quad> {
        match self.bound {
            Bound::Paper => {
                let radius = r * (1.0 / e.z_min - 1.0 / z_max);
                if radius.is_nan() || radius <= 0.0 {
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

    #[allow(clippy::too_many_arguments)]
    fn penumbra_bin(
        &self,
        grid: &Grid,
        edges: &[PenEdge],
        list: &[u32],
        b: usize,
        r: f64,
        umbra: &[f64],
        occ: &mut [f64],
        evals: &mut [u32],
    ) -> Counts {
        let start = grid.bin_range(b).start;
        let (bx0, by0, bx1, by1) = grid.bin_cells(b);
        let mut counts = Counts::default();
        let union = self.composition == Composition::ExactUnion;
        let mut mapped: Vec<Vec<MappedEdge>> = if union {
            vec![Vec::new(); occ.len()]
        } else {
            Vec::new()
        };
        let bin_zmax = grid.bin_zmax[b];
        for &ei in list {
            let e = &edges[ei as usize];
            let Some(global) = self.quad(e, r, grid.z_max) else {
                continue;
            };
            let local = if self.bin_depth {
                self.quad(e, r, bin_zmax)
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
                if self.bin_depth {
                    let all = span(&global).map_or(0, |(a, b)| grid.row_count(cy, a, b));
                    let kept = hit.map_or(0, |(a, b)| grid.row_count(cy, a, b));
                    counts.saved_bin += all.saturating_sub(kept);
                }
                let Some((cx0, cx1)) = hit else {
                    continue;
                };
                for cx in cx0..=cx1 {
                    let mut first = 0;
                    if self.wedge_column && self.bound == Bound::Paper {
                        // A lower bound of the distance from the cell to the
                        // projected edge: from its centre, less its half
                        // diagonal.
                        let (lo, hi) = grid.cell_box(cx, cy);
                        let dmin = (point_segment_distance((lo + hi) * 0.5, e.a, e.b)
                            - 0.5 * (hi - lo).length())
                        .max(0.0);
                        let inv = 1.0 / e.z_min - dmin / r;
                        first = if inv > 0.0 {
                            first_slice_deeper(grid, (1.0 / inv) * (1.0 - 1e-9))
                        } else {
                            grid.slices
                        };
                        counts.saved_wedge += (grid.column(cx, cy, 0).len()
                            - grid.column(cx, cy, first).len())
                            as u64;
                    }
                    for i in grid.column(cx, cy, first) {
                        if self.wedge_column && self.bound == Bound::Conservative {
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
            for (k, list) in mapped.iter().enumerate() {
                occ[k] = union::union_occlusion(umbra[start + k], list, &mut scratch);
            }
        }
        counts
    }
}

/// Work counters of the penumbra pass.
#[derive(Clone, Copy, Debug, Default)]
struct Counts {
    evaluations: u64,
    saved_bin: u64,
    saved_wedge: u64,
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

/// The triangle `t` of a mesh, clipped in front of the light and projected,
/// as umbra triangles (one, or two for a clipped quadrilateral).
fn push_umbra_tri(
    out: &mut Vec<UmbraTri>,
    t: &[u32; 3],
    pos: &[DVec3],
    lf: &[DVec3],
    center: DVec3,
    weight: f64,
    z_near: f64,
) {
    let world = t.map(|i| pos[i as usize]);
    let light_side = orient3d(world[0], world[1], world[2], center);
    if light_side == Sign::Zero {
        return;
    }
    let q = t.map(|i| lf[i as usize]);
    let z_min = q[0].z.min(q[1].z).min(q[2].z);
    // Sutherland–Hodgman against z ≥ z_near, keeping unclipped vertices'
    // projections bit for bit.
    let mut poly: Vec<DVec2> = Vec::with_capacity(4);
    for k in 0..3 {
        let (a, b) = (q[k], q[(k + 1) % 3]);
        if a.z >= z_near {
            poly.push(project(a));
        }
        if (a.z >= z_near) != (b.z >= z_near) {
            if let Some((c, d)) = clip_near(a, b, z_near) {
                poly.push(project(if a.z >= z_near { d } else { c }));
            }
        }
    }
    if poly.len() < 3 || poly.iter().any(|p| !p.is_finite()) {
        return;
    }
    for k in 1..poly.len() - 1 {
        let (p0, mut p1, mut p2) = (poly[0], poly[k], poly[k + 1]);
        match orient2d(p0, p1, p2) {
            Sign::Zero => continue,
            Sign::Negative => std::mem::swap(&mut p1, &mut p2),
            Sign::Positive => {}
        }
        out.push(UmbraTri {
            p: [p0, p1, p2],
            lo: p0.min(p1).min(p2),
            hi: p0.max(p1).max(p2),
            world,
            light_side,
            z_min: z_min.max(z_near),
            z_max: q[0].z.max(q[1].z).max(q[2].z),
            weight,
        });
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
    let inv_zq = (1.0 - t) / e.la.z + t / e.lb.z;
    let radius = r * (inv_zq - 1.0 / zp);
    if radius.is_nan() || radius <= 0.0 {
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

/// Edge `e` seen from the receiver at image point `s`, depth `zp`, mapped
/// into the unit footprint for the exact composition: clipped to the part
/// in front of the receiver, each endpoint scaled by its own depth's
/// footprint radius.
fn map_edge(e: &PenEdge, s: DVec2, zp: f64, r: f64) -> Option<MappedEdge> {
    let zc = zp * (1.0 - 1e-6);
    let (la, lb) = match (e.la.z < zc, e.lb.z < zc) {
        (true, true) => (e.la, e.lb),
        (false, false) => return None,
        (ina, _) => {
            let t = (zc - e.la.z) / (e.lb.z - e.la.z);
            let mut c = e.la + (e.lb - e.la) * t;
            c.z = zc;
            if ina {
                (e.la, c)
            } else {
                (c, e.lb)
            }
        }
    };
    let pa = if la == e.la { e.a } else { project(la) };
    let pb = if lb == e.lb { e.b } else { project(lb) };
    let ra = r * (1.0 / la.z - 1.0 / zp);
    let rb = r * (1.0 / lb.z - 1.0 / zp);
    if !(ra > 0.0 && rb > 0.0) {
        return None;
    }
    Some(MappedEdge {
        a: (pa - s) / ra,
        b: (pb - s) / rb,
        weight: e.weight,
    })
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
