//! Monte Carlo's samples decided on the light's plane, without a ray where
//! the answer is certain: the same answers, bit for bit, as casting every
//! ray ([`Bvh::segment_unoccluded`]), at a fraction of the cost when many
//! samples share one receiver.
//!
//! # Construction
//!
//! For a receiver `p` and a disk or rect emitter, the light's points are
//! `center + e₀ q.x + e₁ q.y` for plane coordinates `q` ([`PlaneMap`]). A
//! segment emitter is `center + e₀ q.x` with `q.y = 0`: its plane is the one
//! through it normal to the perpendicular from `p` to its line (so that
//! all its points lie at one depth from `p`), `e₁` an axis of that plane
//! across the segment, and its grid a single row of cells. The
//! triangles whose boxes meet the pyramid from `p` over the square
//! `|q.x|, |q.y| ≤ half` (widened by `10⁻⁶` of it and `10⁻⁹` of the
//! coordinates, and deepened by `10⁻⁶` of the light's depth: far beyond the
//! rounding of the points, for a receiver not within 0.06° of the light's
//! plane, as seen from any of its points, and coordinates below a million
//! times its depth; for a segment, a pyramid as thin across the plane as
//! that widening) are found once
//! ([`Bvh::triangles_meeting_hull`]); every other triangle misses every
//! sample's segment. For a candidate
//! `v₀v₁v₂` not coplanar with `p` (a coplanar one blocks nothing by
//! [`segment_blocked`]'s convention: the receiver is not strictly on one
//! side of it), the points `y` whose ray from `p` meets the closed triangle
//! form the cone `σ det[vᵢ − p, vⱼ − p, y − p] ≥ 0` over its three edges
//! (`σ` the exact sign of `det[v₀ − p, v₁ − p, v₂ − p]`). On the light's
//! plane each of the three is a linear function of `q`, `F(q) = a + b q.x +
//! c q.y`, evaluated in `f64` within a margin `m` that bounds, with a
//! factor of more than 2 to spare, every rounding between it and the exact
//! determinant at the sample point `point_at` returns: the rounded
//! differences and cross product (`γ₅`), the three dot products, the
//! evaluation (`γ₃`), `point_at`'s own rounding (`γ₅` of the terms), and the
//! distance of the polynomial sample coordinates ([`PlaneMap::approx_grid`]) from
//! `point_at`'s.
//!
//! A sample is then, for each candidate,
//!
//! - **outside** when some `F < −m`: its ray misses the closed triangle;
//! - **inside** when every `F > m` and the triangle lies strictly between
//!   `p` and the light (every corner's depth along the light's normal
//!   certainly below every sample's): the open segment crosses the
//!   triangle's interior, so [`segment_blocked`] says blocked;
//! - **unsure** otherwise (within a margin of an edge, or a triangle not
//!   certainly in front of the light).
//!
//! The sample is unoccluded when every candidate is outside, occluded when
//! one is inside; an unsure candidate (a band about `10⁻⁵` of a disk's
//! radius wide around each image edge — the polynomial coordinates' error
//! — and far narrower on a rect, or a triangle reaching the light's depth)
//! sends it to [`Bvh::segment_unoccluded`]. The candidates are binned on a
//! uniform grid of the plane coordinates: the cells a candidate may touch
//! are those meeting the box of its corners' projections (where every
//! corner lies at least `10⁻³` of the light's depth in front of `p`: the
//! image is then the hull of the projections, located to about `10⁻¹³`
//! relative, and the box is widened by `10⁻⁶` of the coordinates and twice
//! the sample coordinates' error; else every cell), and of those a cell
//! lists it unless some `F` is certainly negative on the whole cell. A cell
//! inside one image certainly occluded needs no test at all, and once every
//! cell is such, no further candidate matters. A sample tests only its
//! cell's list.
//!
//! # Evaluation
//!
//! The work is laid out for vector instructions, compiled for AVX2 where
//! the processor has it (`lanes::vectorized`), the answers the same on
//! every path. Each cell keeps its candidates as a linked list, written as
//! they are found, and one verdict: *lit* (no list, not covered), *dark*
//! (covered) or *to test*. A candidate's three edge functions and margins
//! fill four lanes (the fourth `F = 1`, margin 0), so a verdict is one
//! vector operation per coefficient; the cells of one row of its box are
//! classified in one loop. A replicate's samples go through passes: their
//! cells on the `2³²` grid (the scrambled Sobol' points, computed
//! side by side), their approximate plane coordinates at those cells'
//! centres, and their cells on the light (floor and integer by adding
//! `2⁵²`, so that no conversion instruction stops the vectorising); then
//! the cells' verdicts are counted, and only the samples in cells to test
//! are tested against their cell's list, or cast their ray.
//!
//! Where this would cost more than it saves — more than `samples/2`
//! candidates, or more than 8 cell tests per sample — [`Binned::build`]
//! declines and every sample casts its ray.
//!
//! Both decisions are [`segment_blocked`]'s exact answer wherever its
//! predicates are exact: coordinates `0` or within `[10⁻⁹⁰, 10⁹⁰]` in
//! magnitude, which the receivers, the light and the candidates are held
//! to (`±10³⁰`, else every sample casts its ray); a sample point with a
//! nonzero coordinate below `10⁻⁹⁰` is outside that domain by chance only.
//!
//! [`segment_blocked`]: crate::kernel::segment::segment_blocked

use super::Replicate;
use crate::bvh::Bvh;
use crate::kernel::footprint::f64::gamma;
use crate::kernel::lanes;
use crate::kernel::light::{Emitter, PlaneMap};
use crate::kernel::predicate::{orient3d, Sign};
use glam::{DVec2, DVec3};

/// `γ(16)`: more roundings than any bound below needs.
const G16: f64 = gamma(16);

/// The fewest samples per receiver decided on the light's plane; fewer
/// cast every ray (measured, 512² frames: at 32 samples the plane takes
/// half the time of the rays on the default scene and 0.8 of it on
/// `linear-light`; at 16 about the same on the first, 1.3 times on the
/// second).
const BINNED_FROM: u32 = 32;

/// Cells per axis of the light's grid for `samples` samples: about four
/// samples per cell, 4 to 64 per axis.
pub(super) fn grid_cells(samples: u32) -> usize {
    ((f64::from(samples).sqrt() / 2.0) as usize).clamp(4, 64)
}

/// The largest coordinate magnitude of the fast path (far inside the exact
/// predicates' domain, and far from overflow in the products below).
const BIG: f64 = 1e30;

/// The smallest nonzero coordinate magnitude of the fast path.
const TINY: f64 = 1e-90;

/// How the triangle's image decides a sample.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Verdict {
    Outside,
    Inside,
    Unsure,
}

/// One candidate's image on the light's plane: its edges in four lanes,
/// the three edges and one that holds everywhere (`F = 1`, margin 0), so
/// that a verdict is one vector operation per coefficient.
#[derive(Clone, Copy, Debug)]
struct Image {
    /// Per edge, `F(q) = a + b q.x + c q.y`, positive inside.
    a: [f64; 4],
    b: [f64; 4],
    c: [f64; 4],
    /// Per edge, the margin `m` beyond which the sign of `F` is certain.
    margins: [f64; 4],
    /// Every corner certainly between the receiver and the light.
    between: bool,
}

impl Image {
    /// The verdict at `q`, given each edge's margin: [`Image::margins`]
    /// for a sample, or those widened by the most `F` varies over a cell
    /// around `q` for every point of the cell. Without branches, so that
    /// loops of it vectorise.
    #[inline(always)]
    // Indexed: zipped array iterators are not always inlined into the
    // AVX2 code, and a call per lane undoes the lanes.
    #[allow(clippy::needless_range_loop)]
    fn classify(&self, q: DVec2, margins: &[f64; 4]) -> Verdict {
        let (mut outside, mut inside) = (false, self.between);
        for e in 0..4 {
            let f = self.a[e] + self.b[e] * q.x + self.c[e] * q.y;
            outside |= f < -margins[e];
            inside &= f > margins[e];
        }
        if outside {
            Verdict::Outside
        } else if inside {
            Verdict::Inside
        } else {
            Verdict::Unsure
        }
    }
}

/// The per-receiver structure, reused between receivers (one per thread).
#[derive(Debug, Default)]
pub(super) struct Binned {
    map: Option<PlaneMap>,
    images: Vec<Image>,
    /// The light's grid of cells.
    grid: Grid,
    /// Per cell, its first entry in `links` ([`NONE`] for none): the
    /// images listed in the cell, as a linked list, latest first.
    head: Vec<u32>,
    links: Vec<Link>,
    /// Cells inside one image certainly occluded.
    covered: Vec<bool>,
    candidates: Vec<u32>,
    /// Every sample's answer, where one answer holds for all of them.
    all: Option<bool>,
    /// The pyramid the candidates were culled to: the receiver, then the
    /// base's corners in order around it.
    hull: [DVec3; 5],
    /// The cells' centres on each axis.
    centers: [Vec<f64>; 2],
    /// One row's verdicts.
    verdicts: Vec<Verdict>,
    /// What each cell says of its samples, and one more entry (`Test`)
    /// for samples outside the grid.
    state: Vec<Cell>,
    /// A replicate's samples, in [`Binned::count_unoccluded`].
    scratch: Scratch,
}

/// A replicate's samples, one entry each: their cells on the `2³²` grid,
/// approximate plane coordinates and cells on the light; and the samples
/// their cells leave to their images (`pending`).
#[derive(Debug, Default)]
struct Scratch {
    gx: Vec<u32>,
    gy: Vec<u32>,
    qx: Vec<f64>,
    qy: Vec<f64>,
    cell: Vec<u32>,
    pending: Vec<u32>,
}

impl Binned {
    /// Prepares the decisions for receiver `p` and `samples` samples on a
    /// grid of `cells²` cells (on a segment, one row of `cells²`); `false`
    /// when they do not apply (fewer than [`BINNED_FROM`] samples, a point
    /// emitter, coordinates outside the fast path's domain, a receiver not
    /// certainly in front of the light, a set-up past its budget): then
    /// every sample casts its ray. Compiled for AVX2 where the processor
    /// has it ([`lanes::vectorized`]).
    pub(super) fn build(
        &mut self,
        bvh: &Bvh,
        emitter: &Emitter,
        p: DVec3,
        samples: u32,
        cells: usize,
    ) -> bool {
        lanes::vectorized(
            #[inline(always)]
            |_| {
                self.map = None;
                self.all = None;
                if samples < BINNED_FROM {
                    return false;
                }
                let Some(map) = emitter.plane_map() else {
                    return false;
                };
                let Some(view) = View::new(&map, p) else {
                    return false;
                };
                self.hull = view.hull(p);
                // Worth it only while the set-up costs less than the rays
                // it saves: a candidate costs about half a ray to prepare,
                // finding one a tenth of a ray, a cell test a tenth
                // (measured on piles of occluders over one receiver,
                // `benches/references.rs`: 4096 candidates prepared and
                // their samples decided took 0.6 of the time of 4096 rays).
                // So at most `samples/2` candidates: the set-up never costs
                // much more than the rays, and a query past the cap is
                // abandoned after a twentieth of their cost.
                let cap = samples as usize / 2;
                if !bvh.triangles_meeting_hull_at_most(&self.hull, &mut self.candidates, cap) {
                    return false;
                }
                let grid = if view.segment {
                    [cells * cells, 1]
                } else {
                    [cells, cells]
                };
                let Some(uncovered) = self.list_images(bvh, &view, p, samples, grid) else {
                    return false;
                };
                self.finish(map, grid, uncovered);
                true
            },
        )
    }

    /// Lists the candidates' images in the cells of the light's `grid`
    /// they may decide, and marks the cells one image covers; the number of
    /// cells left uncovered, or `None` where the set-up does not apply (a
    /// candidate outside the fast path's domain, more cell tests than a
    /// budget of 8 a sample).
    #[inline(always)]
    fn list_images(
        &mut self,
        bvh: &Bvh,
        view: &View,
        p: DVec3,
        samples: u32,
        grid: [usize; 2],
    ) -> Option<usize> {
        let half = view.half;
        self.images.clear();
        self.links.clear();
        let width = DVec2::new(2.0 * half / grid[0] as f64, 2.0 * half / grid[1] as f64);
        // Half a cell, widened past the rounding of the cell index and
        // centre (a few ulps of `half`).
        let h = 0.5 * width * (1.0 + 1e-9) + 1e-12 * half;
        for ((centers, &n), width) in self.centers.iter_mut().zip(&grid).zip(width.to_array()) {
            centers.clear();
            centers.extend((0..n as u32).map(|i| -half + (f64::from(i) + 0.5) * width));
        }
        self.verdicts.resize(grid[0], Verdict::Outside);
        let mut budget = 8 * samples as usize;
        let n = grid[0] * grid[1];
        self.covered.clear();
        self.covered.resize(n, false);
        self.head.clear();
        self.head.resize(n, NONE);
        let mut uncovered = n;
        let triangles = bvh.occluders().triangles();
        for &id in &self.candidates {
            if uncovered == 0 {
                // Every sample is blocked: no other candidate matters.
                break;
            }
            let Some(t) = triangles.get(id as usize) else {
                continue;
            };
            let (image, rel, depth) = match view.image(t, p) {
                Candidate::Skip => continue,
                Candidate::Refuse => return None,
                Candidate::Image(image, rel, depth) => (image, rel, depth),
            };
            let Some(((x0, x1), (y0, y1))) = view.cells(&rel, &depth, grid) else {
                continue;
            };
            // A row or column of cells: each meets the image's box, and
            // none is inside the image (it cannot hold a cell whole; on a
            // segment, whose one row is a line, only a column counts).
            let tested = (x1 - x0 + 1) * (y1 - y0 + 1);
            if tested > budget {
                return None;
            }
            budget -= tested;
            let strip = x0 == x1 || (y0 == y1 && !view.segment);
            // Each margin widened by the most `F` varies over a cell.
            let cell_margins: [f64; 4] = std::array::from_fn(|e| {
                image.margins[e] + (image.b[e].abs() * h.x + image.c[e].abs() * h.y)
            });
            let index = self.images.len() as u32;
            let columns = &self.centers[0][x0..x1 + 1];
            let verdicts = &mut self.verdicts[..columns.len()];
            for iy in y0..=y1 {
                let y = self.centers[1][iy];
                if strip {
                    verdicts.fill(Verdict::Unsure);
                } else {
                    for (v, &x) in verdicts.iter_mut().zip(columns) {
                        *v = image.classify(DVec2::new(x, y), &cell_margins);
                    }
                }
                for (k, &verdict) in (iy * grid[0] + x0..).zip(&*verdicts) {
                    match verdict {
                        Verdict::Outside => {}
                        Verdict::Inside => {
                            uncovered -= usize::from(!self.covered[k]);
                            self.covered[k] = true;
                        }
                        Verdict::Unsure => {
                            let next =
                                std::mem::replace(&mut self.head[k], self.links.len() as u32);
                            self.links.push(Link { image: index, next });
                        }
                    }
                }
            }
            self.images.push(image);
        }
        Some(uncovered)
    }

    /// The light's grid and each cell's state, after [`Binned::list_images`]
    /// left `uncovered` cells uncovered.
    #[inline(always)]
    fn finish(&mut self, map: PlaneMap, grid: [usize; 2], uncovered: usize) {
        let (half, n) = (map.half, grid[0] * grid[1]);
        self.grid = Grid {
            half,
            inv_width: grid.map(|n| n as f64 / (2.0 * half)),
            bounds: grid.map(|n| n as f64),
        };
        self.state.clear();
        self.state.extend((0..n).map(|k| {
            if self.covered[k] {
                Cell::Dark
            } else if self.head[k] == NONE {
                Cell::Lit
            } else {
                Cell::Test
            }
        }));
        self.state.push(Cell::Test);
        self.map = Some(map);
        // No image listed and no cell covered: every sample is unoccluded
        // (with no cell covered, every listing is still in its cell's
        // list); every cell covered: every sample is occluded (a sample on
        // the grid's far edge, which `decide` leaves to its ray, lies in
        // the last cell's widened box all the same). Either way no sample
        // need be computed.
        self.all = if uncovered == 0 {
            Some(false)
        } else if uncovered == n && self.links.is_empty() {
            Some(true)
        } else {
            None
        };
    }

    /// How many of the first `m` points of `replicate` are unoccluded from
    /// the prepared receiver: each decided on the plane where certain, else
    /// by `ray`, the sample's own ray. Every sample casts its ray when
    /// [`Binned::build`] returned `false`.
    pub(super) fn count_unoccluded(
        &mut self,
        replicate: &Replicate,
        m: u32,
        ray: impl Fn(DVec2) -> bool,
    ) -> u32 {
        let Some(map) = self.map else {
            return (0..m).map(|i| u32::from(ray(replicate.point(i)))).sum();
        };
        if let Some(unoccluded) = self.all {
            return if unoccluded { m } else { 0 };
        }
        lanes::vectorized(
            #[inline(always)]
            |_| self.count_here(&map, replicate, m, &ray),
        )
    }

    /// [`Binned::count_unoccluded`] on the plane, compiled where it is
    /// called.
    #[inline(always)]
    fn count_here(
        &mut self,
        map: &PlaneMap,
        replicate: &Replicate,
        m: u32,
        ray: &impl Fn(DVec2) -> bool,
    ) -> u32 {
        // In passes, each a loop without branches on the data: the samples'
        // cells on the `2³²` grid, their plane coordinates (at the centre
        // of that cell: `PlaneMap::approx_grid` allows for it) and their
        // cells on the light; then the samples whose cell decides them
        // counted, and the others listed for their images' tests. The
        // sample's own point, jitter and all, only where its ray is cast.
        let n = m as usize;
        let s = &mut self.scratch;
        for v in [&mut s.gx, &mut s.gy, &mut s.cell, &mut s.pending] {
            v.resize(n, 0);
        }
        for v in [&mut s.qx, &mut s.qy] {
            v.resize(n, 0.0);
        }
        // A segment's points depend on `s.x` alone: its second grid
        // coordinate is left at 0.
        let gy = if self.grid.bounds[1] == 1.0 {
            s.gy.fill(0);
            &mut [][..]
        } else {
            &mut s.gy[..n]
        };
        replicate.grids(&mut s.gx[..n], gy);
        map.approx_grid(&s.gx[..n], gy, &mut s.qx[..n], &mut s.qy[..n]);
        for ((k, &x), &y) in s.cell[..n].iter_mut().zip(&s.qx[..n]).zip(&s.qy[..n]) {
            *k = self.grid.cell_of(x, y);
        }
        let mut visible = 0;
        let mut listed = 0;
        for (j, &k) in (0..).zip(&s.cell[..n]) {
            let state = self.state.get(k as usize).copied().unwrap_or(Cell::Test);
            visible += u32::from(state == Cell::Lit);
            if let Some(slot) = s.pending.get_mut(listed) {
                *slot = j;
            }
            listed += usize::from(state == Cell::Test);
        }
        let s = &self.scratch;
        for &j in &s.pending[..listed] {
            let j = j as usize;
            let q = DVec2::new(s.qx[j], s.qy[j]);
            let known = self.test_cell(s.cell[j], q);
            visible += u32::from(
                known.unwrap_or_else(|| ray(replicate.point_in(j as u32, [s.gx[j], s.gy[j]]))),
            );
        }
        visible
    }

    /// Whether the sample at approximate plane coordinates `q` is
    /// unoccluded, when certain; `None` when its ray must decide.
    #[cfg(test)]
    fn decide(&self, q: DVec2) -> Option<bool> {
        let k = self.grid.cell_of(q.x, q.y);
        match self.state.get(k as usize) {
            Some(Cell::Lit) => Some(true),
            Some(Cell::Dark) => Some(false),
            _ => self.test_cell(k, q),
        }
    }

    /// Whether a sample at approximate plane coordinates `q` in cell `k`
    /// (the grid's cell count for one outside it) that its cell alone
    /// does not decide is unoccluded, from its cell's images; `None` when
    /// its ray must decide.
    #[inline(always)]
    fn test_cell(&self, k: u32, q: DVec2) -> Option<bool> {
        let mut at = *self.head.get(k as usize)?;
        let mut unsure = false;
        while let Some(link) = self.links.get(at as usize) {
            let image = &self.images[link.image as usize];
            match image.classify(q, &image.margins) {
                Verdict::Outside => {}
                Verdict::Inside => return Some(false),
                Verdict::Unsure => unsure = true,
            }
            at = link.next;
        }
        (!unsure).then_some(true)
    }
}

/// The light's plane as seen from a receiver `p`, for [`Binned::build`]:
/// the plane's axes and extent, the light's unit normal toward its side of
/// `p` and the bounds on every sample point's depth along it, and the dual
/// axes that give a point of the plane its coordinates `q`.
#[derive(Clone, Copy, Debug)]
struct View {
    /// The light's centre and its axes ([`PlaneMap`]); for a segment,
    /// `ey_plane` spans its plane with `ex`.
    c: DVec3,
    ex: DVec3,
    ey: DVec3,
    ey_plane: DVec3,
    half: f64,
    /// [`PlaneMap::error`].
    error: f64,
    /// `c − p`.
    d: DVec3,
    /// The unit normal, `w · d`, and the bounds on the samples' depths.
    w: DVec3,
    wd: f64,
    depth_lo: f64,
    depth_hi: f64,
    /// The dual axes, and the larger of their lengths.
    dual: [DVec3; 2],
    to_q: f64,
    /// The coordinates' scale: every rounding below is a few ulps of it.
    scale: f64,
    /// The size, in plane coordinates, of a rounding of `c` or `d`.
    reach_q: f64,
    segment: bool,
}

/// What a candidate's image is, from [`View::image`].
// Made and matched at once in the inlined loop, never stored: boxing the
// image would cost an allocation a candidate.
#[allow(clippy::large_enum_variant)]
enum Candidate {
    /// It hides no sample (not finite, coplanar with `p`, behind `p` or
    /// beyond the light).
    Skip,
    /// It is outside the fast path's domain: every sample casts its ray.
    Refuse,
    /// Its image, its corners relative to `p`, and their depths' bounds.
    Image(Image, [DVec3; 3], [(f64, f64); 3]),
}

impl View {
    /// The view of `map` from `p`; `None` outside the fast path's domain
    /// or for a receiver not certainly in front of the light.
    #[inline(always)]
    fn new(map: &PlaneMap, p: DVec3) -> Option<View> {
        let [ex, ey] = map.axes;
        let (c, half) = (map.center, map.half);
        if !in_domain(p) || !in_domain(c) || !(ex * half).is_finite() || !(ey * half).is_finite() {
            return None;
        }
        let reach = (ex.abs() + ey.abs()) * half;
        if !in_domain(c.abs() + reach) {
            return None;
        }
        // The light's unit normal toward its side of `p` — for a segment
        // (`ey = 0`), the unit perpendicular from `p` to its line, so that
        // the segment lies in the plane through `c` normal to `w`, spanned
        // by `ex` and `ey_plane` — and the depth along it of every sample
        // point `x`: `w · (x − p)` within `[depth_lo, depth_hi]` (the
        // in-plane spread `|w · eᵢ| half`, `point_at`'s rounding and the
        // dot products' bounded by the `G16` term).
        let d = c - p;
        let segment = ey == DVec3::ZERO;
        let w = if segment {
            (d - ex * (d.dot(ex) / ex.length_squared())).try_normalize()
        } else {
            ex.cross(ey)
                .try_normalize()
                .map(|w| if w.dot(d) < 0.0 { -w } else { w })
        };
        let w = w?;
        let ey_plane = if segment { w.cross(ex) } else { ey };
        let wd = w.dot(d);
        let spread = (w.dot(ex).abs() + w.dot(ey).abs()) * half;
        let err = 2.0 * G16 * (w.abs().dot(d.abs() + c.abs() + 2.0 * reach));
        let (depth_lo, depth_hi) = (wd - spread - err, wd + spread + err);
        if !(depth_lo > 0.0 && depth_hi.is_finite()) {
            return None;
        }

        // The dual axes: `q = (e₀* · (y − c), e₁* · (y − c))` for a point
        // `y` of the plane; their length turns lengths into plane
        // coordinates.
        let dual = [
            ey_plane.cross(w) / ex.dot(ey_plane.cross(w)),
            w.cross(ex) / ey_plane.dot(w.cross(ex)),
        ];
        let to_q = dual[0].length().max(dual[1].length());
        let scale = (p.abs() + c.abs() + reach).max_element();
        // Held away from grazing views (the receiver within 0.06° of the
        // light's plane, as seen from any of its points) and from
        // coordinates a million times the depth, every segment from `p` to
        // a sample point lies in the pyramid of [`View::hull`].
        if !(wd >= 1e-3 * (d.length() + reach.length()) && 1e-6 * scale <= wd && to_q.is_finite()) {
            return None;
        }
        let reach_q =
            (d.abs() + c.abs()).max_element() * (dual[0].abs() + dual[1].abs()).max_element();
        Some(View {
            c,
            ex,
            ey,
            ey_plane,
            half,
            error: map.error,
            d,
            w,
            wd,
            depth_lo,
            depth_hi,
            dual,
            to_q,
            scale,
            reach_q,
            segment,
        })
    }

    /// The pyramid that holds every segment from `p` to a sample point: its
    /// base `10⁻⁶` of the depth beyond the light, `10⁻⁶` of the light and
    /// `10⁻⁹` of the scale wider than the square `|q| ≤ half` — the points'
    /// and the corners' rounding, a few ulps of the scale, moves them by
    /// under `10⁻¹²` of it across and `10⁻⁹` of the depth along the view. A
    /// segment's pyramid is as thin across its plane as that widening.
    #[inline(always)]
    fn hull(&self, p: DVec3) -> [DVec3; 5] {
        let (half, scale, to_q) = (self.half, self.scale, self.to_q);
        let wide = half * (1.0 + 1e-6) + 1e-9 * scale * to_q;
        let across = if self.segment {
            self.ey_plane * ((1e-6 * half + 1e-9 * scale * to_q) / self.ey_plane.length())
        } else {
            self.ey * wide
        };
        let corner = |sx: f64, sy: f64| {
            let k = self.c + self.ex * (sx * wide) + across * sy;
            p + (k - p) * (1.0 + 1e-6)
        };
        [
            p,
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
        ]
    }

    /// The image of the candidate `t` on the light's plane, seen from `p`.
    #[inline(always)]
    fn image(&self, t: &[DVec3; 3], p: DVec3) -> Candidate {
        let (w, d, ex, ey, c, half) = (self.w, self.d, self.ex, self.ey, self.c, self.half);
        if each3(t, |v| v.is_finite()) != [true; 3] {
            return Candidate::Skip;
        }
        if each3(t, in_domain) != [true; 3] {
            return Candidate::Refuse;
        }
        let sigma = match orient3d(t[0], t[1], t[2], p) {
            Sign::Zero => return Candidate::Skip,
            Sign::Positive => 1.0,
            Sign::Negative => -1.0,
        };
        let rel = each3(t, |v| v - p);
        let depth = each3(&rel, |r| {
            let e = 2.0 * G16 * w.abs().dot(r.abs());
            let z = w.dot(r);
            (z - e, z + e)
        });
        if depth.iter().all(|z| z.1 <= 0.0) || depth.iter().all(|z| z.0 >= self.depth_hi) {
            return Candidate::Skip;
        }
        let between = depth.iter().all(|z| z.1 < self.depth_lo);
        let mut image = Image {
            a: [1.0; 4],
            b: [0.0; 4],
            c: [0.0; 4],
            margins: [0.0; 4],
            between,
        };
        for k in 0..3 {
            let (a, b) = (rel[k], rel[(k + 1) % 3]);
            let n = a.cross(b) * sigma;
            let (aa, ba) = (a.abs(), b.abs());
            // `|fl(n) − n| ≤ γ₅ nn` per component, `|n| ≤ 2 nn`.
            let nn = DVec3::new(
                aa.y * ba.z + aa.z * ba.y,
                aa.z * ba.x + aa.x * ba.z,
                aa.x * ba.y + aa.y * ba.x,
            );
            let (fa, fb, fc) = (n.dot(d), n.dot(ex), n.dot(ey));
            let axes = nn.dot(ex.abs() + ey.abs());
            image.margins[k] = 2.0
                * (G16
                    * (fa.abs()
                        + (fb.abs() + fc.abs()) * half
                        + 3.0 * nn.dot(d.abs())
                        + 2.0 * axes * half
                        + 2.0 * (nn.dot(c.abs()) + axes * half))
                    + 2.0 * axes * self.error);
            (image.a[k], image.b[k], image.c[k]) = (fa, fb, fc);
        }
        // Every coefficient finite, tested on their sum: with every
        // coordinate within `BIG`, a finite one is below `10¹⁰⁰`, so
        // the sum overflows only where a term is not finite.
        let sum: f64 = (0..4)
            .map(|e| image.a[e] + image.b[e] + image.c[e] + image.margins[e])
            .sum();
        if !sum.is_finite() {
            return Candidate::Refuse;
        }
        Candidate::Image(image, rel, depth)
    }

    /// The cells of `grid` to test for an image whose corners relative to
    /// `p` are `rel` at depths `depth`: around the corners' projections
    /// where every corner is well in front of `p` (the image is their hull,
    /// located far better than the cell added around it), else all; `None`
    /// where it misses the grid.
    #[inline(always)]
    fn cells(
        &self,
        rel: &[DVec3; 3],
        depth: &[(f64, f64); 3],
        grid: [usize; 2],
    ) -> Option<((usize, usize), (usize, usize))> {
        if depth.iter().all(|z| z.0 > 1e-3 * self.depth_lo) {
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for (r, z) in rel.iter().zip(depth) {
                let y = *r * (self.wd / (0.5 * (z.0 + z.1))) - self.d;
                let q = DVec2::new(self.dual[0].dot(y), self.dual[1].dot(y));
                lo = lo.min(q);
                hi = hi.max(q);
            }
            let pad = 2.0 * self.error
                + 1e-6 * (self.half + lo.abs().max(hi.abs()).max_element() + self.reach_q);
            // A segment's samples lie on `q.y = 0`.
            if self.segment && !(lo.y - pad <= 0.0 && hi.y + pad >= 0.0) {
                return None;
            }
            cell_range(lo - pad, hi + pad, self.half, grid)
        } else {
            Some(((0, grid[0] - 1), (0, grid[1] - 1)))
        }
    }
}

/// The end of a cell's list of images.
const NONE: u32 = u32::MAX;

/// An entry of a cell's list of images: the image, and the list's next
/// entry.
#[derive(Clone, Copy, Debug)]
struct Link {
    image: u32,
    next: u32,
}

/// What a sample's cell on the light says of it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
enum Cell {
    /// No image listed, none covering: unoccluded.
    #[default]
    Lit,
    /// Inside an image certainly occluding: occluded.
    Dark,
    /// The cell's images decide, or the ray.
    Test,
}

/// The light's grid of cells: `bounds[0] × bounds[1]` cells over
/// `[−half, half]²` in plane coordinates.
#[derive(Clone, Copy, Debug, Default)]
struct Grid {
    half: f64,
    /// Cells per unit of plane coordinate on each axis.
    inv_width: [f64; 2],
    /// Cells along each axis, `[columns, rows]` (one row on a segment), as
    /// `f64`.
    bounds: [f64; 2],
}

impl Grid {
    /// The index `row · columns + column` of the cell holding `(x, y)`; the
    /// cell count for a point outside the grid (or NaN).
    #[inline(always)]
    fn cell_of(&self, x: f64, y: f64) -> u32 {
        let (x, y) = (
            (x + self.half) * self.inv_width[0],
            (y + self.half) * self.inv_width[1],
        );
        // Without branches or conversion instructions, so that loops of it
        // vectorise (`&`, not `&&`; a float-to-integer conversion, which
        // must saturate, does not). For `0 ≤ v < 2⁵¹`, adding and
        // subtracting `2⁵²` rounds `v` to an integer, exactly; one less
        // where that rounded up is the floor; and an integer below `2³²`
        // plus `2⁵²` holds it in its low bits.
        const TWO_52: f64 = 4_503_599_627_370_496.0;
        let floor = |v: f64| {
            let r = (v + TWO_52) - TWO_52;
            if r > v {
                r - 1.0
            } else {
                r
            }
        };
        let inside = (x >= 0.0) & (x < self.bounds[0]) & (y >= 0.0) & (y < self.bounds[1]);
        let k = if inside {
            floor(y) * self.bounds[0] + floor(x)
        } else {
            self.bounds[0] * self.bounds[1]
        };
        (k + TWO_52).to_bits() as u32
    }
}

/// `f` of each of three values (written out: a generic helper the
/// compiler keeps apart would cost a call in the AVX2 code).
#[inline(always)]
fn each3<T: Copy, U>(v: &[T; 3], f: impl Fn(T) -> U) -> [U; 3] {
    [f(v[0]), f(v[1]), f(v[2])]
}

/// Finite, and each coordinate `0` or within `[TINY, BIG]` in magnitude.
#[inline(always)]
fn in_domain(v: DVec3) -> bool {
    let in_range = |x: f64| x == 0.0 || (x.abs() >= TINY && x.abs() <= BIG);
    in_range(v.x) && in_range(v.y) && in_range(v.z)
}

/// The cells `(x0, x1), (y0, y1)` (inclusive) a box `[lo, hi]` of plane
/// coordinates meets on the grid of `cells[0] × cells[1]` over
/// `[−half, half]²`; `None` when it misses the grid.
fn cell_range(
    lo: DVec2,
    hi: DVec2,
    half: f64,
    cells: [usize; 2],
) -> Option<((usize, usize), (usize, usize))> {
    if !(lo.cmple(DVec2::splat(half)).all() && hi.cmpge(DVec2::splat(-half)).all()) {
        return None;
    }
    // Truncation is the floor for the non-negative values kept.
    let index = |x: f64, n: usize| {
        let scale = n as f64 / (2.0 * half);
        (((x + half) * scale).max(0.0) as u32 as usize).min(n - 1)
    };
    let (columns, rows) = (cells[0], cells[1]);
    Some((
        (index(lo.x, columns), index(hi.x, columns)),
        (index(lo.y, rows), index(hi.y, rows)),
    ))
}

#[cfg(test)]
mod tests;
