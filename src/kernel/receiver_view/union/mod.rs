//! The area of the union of the projected triangles within the light's
//! measure ([`union_area`]), by Green's theorem over the union's boundary
//! with exact predicates (the construction and its degenerate cases are in
//! the [parent module's documentation](super)).

mod tree;

use crate::kernel::disk::f64::segment_disk_area;
use crate::kernel::predicate::{orient2d, orient2d_value_bounded, orient2d_values_finite, Sign};
use glam::DVec2;
use tree::{Ray, Spans, Tree};

/// A projected triangle, counter-clockwise, with its bounds; its corners
/// are finite (the orientation of a non-finite point is zero, so
/// [`Tri::new`] refuses it).
#[derive(Clone, Copy, Debug)]
pub(super) struct Tri {
    v: [DVec2; 3],
    lo: DVec2,
    hi: DVec2,
}

impl Tri {
    /// The triangle oriented counter-clockwise; `None` when it is
    /// degenerate (decided exactly).
    pub(super) fn new(a: DVec2, b: DVec2, c: DVec2) -> Option<Tri> {
        let v = match orient2d(a, b, c) {
            Sign::Positive => [a, b, c],
            Sign::Negative => [a, c, b],
            Sign::Zero => return None,
        };
        Some(Tri {
            v,
            lo: a.min(b).min(c),
            hi: a.max(b).max(c),
        })
    }

    /// Whether the triangle's first edge runs `a → b` (it was given
    /// counter-clockwise, not reversed).
    pub(super) fn first_edge_is(&self, a: DVec2, b: DVec2) -> bool {
        self.v[0] == a && self.v[1] == b
    }

    fn edge(&self, k: usize) -> (DVec2, DVec2) {
        (self.v[k], self.v[(k + 1) % 3])
    }

    /// Twice the area, rounded (positive, or zero where it underflows).
    fn doubled_area(&self) -> f64 {
        let [a, b, c] = self.v;
        (b - a).perp_dot(c - a)
    }
}

/// What area the union is measured with.
#[derive(Clone, Copy, Debug)]
pub(super) enum Measure {
    /// The disk of this radius about the origin.
    Disk(f64),
    /// The square `[−1, 1]²`, inside which every projected triangle lies.
    Square,
}

impl Measure {
    /// The half-width of the measure's box.
    pub(super) fn radius(self) -> f64 {
        match self {
            Measure::Disk(r) => r,
            Measure::Square => 1.0,
        }
    }

    /// The signed area the directed boundary piece `a → b` contributes.
    fn piece(self, a: DVec2, b: DVec2) -> f64 {
        match self {
            Measure::Disk(r) => segment_disk_area(r, a, b),
            Measure::Square => 0.5 * a.perp_dot(b),
        }
    }

    /// Whether the triangle certainly misses the measure (bounds apart).
    /// Whether the triangle misses the measure's interior (the disk: the
    /// centre outside it and every edge at least `r` away; so a lit
    /// receiver gets `V = 1` exactly, with no boundary pieces to sum).
    pub(super) fn misses(self, t: &Tri) -> bool {
        let r = match self {
            Measure::Disk(r) => r,
            Measure::Square => 1.0,
        };
        if t.lo.x >= r || t.lo.y >= r || t.hi.x <= -r || t.hi.y <= -r {
            return true;
        }
        let Measure::Disk(r) = self else {
            return false;
        };
        let centre_outside = (0..3).any(|k| {
            let (a, b) = t.edge(k);
            orient2d(a, b, DVec2::ZERO) == Sign::Negative
        });
        centre_outside
            && (0..3).all(|k| {
                let (a, b) = t.edge(k);
                let d = b - a;
                let s = (-a.dot(d) / d.length_squared()).clamp(0.0, 1.0);
                (a + d * s).length_squared() >= r * r
            })
    }

    /// Whether the triangle alone covers the whole measure.
    pub(super) fn covered_by(self, t: &Tri) -> bool {
        self.covered_by_convex(&t.v)
    }

    /// Whether the convex polygon `v` (counter-clockwise) alone covers the
    /// whole measure: the disk's centre at least `r` inside every edge, or
    /// every corner of the square on the inner side of every edge.
    pub(super) fn covered_by_convex(self, v: &[DVec2]) -> bool {
        let n = v.len();
        if n < 3 {
            return false;
        }
        let edges = (0..n).map(|k| (v[k], v[(k + 1) % n]));
        match self {
            Measure::Disk(r) => edges.clone().all(|(a, b)| {
                let d = b - a;
                // Signed distance of the centre from the edge's line.
                d.perp_dot(-a) >= r * d.length()
            }),
            Measure::Square => [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .all(|&(x, y)| {
                    let c = DVec2::new(x, y);
                    edges
                        .clone()
                        .all(|(a, b)| orient2d(a, b, c) != Sign::Negative)
                }),
        }
    }
}

/// The area of `∪ triangles ∩ measure`, by Green's theorem over the
/// union's boundary (see the [module documentation](super)). `half` bounds
/// every coordinate (the clip square's half-width): the triangles are
/// binned in grids over it (a fine grid, and coarse levels for the large
/// triangles) so that an edge is tested only against triangles sharing a
/// cell with its bounds. An edge's search ends as soon as the spans it has
/// found cover it whole ([`Cover`]), so the order of the search decides
/// only how soon; an edge that is not covered collects the span of every
/// triangle it meets (its covered start as one interval), the same union
/// in any order, so the area does not depend on it. A span test computes
/// its signed areas two and four at a time
/// ([`orient2d_values_finite`], each lane the one-at-a-time value). An
/// edge whose reverse is an edge of another triangle
/// (two images sharing a mesh edge, their corners the same bits) lies
/// between the two and is dropped before any search ([`Edges`]), as the
/// search would find: on a mesh's images most edges are shared. Under a
/// deep pile of images, so is an edge whose every point lies in a cell of
/// a raster marked as inside some image ([`Interior`]), and the fine grid
/// lists its images by decreasing area.
///
/// An edge lying on a side of the clip square can be covered only by the
/// edges of other triangles on that side (every triangle lies in the closed
/// square), and by the rule of coinciding edges only by those of lower
/// index. Where at least [`SWEEP_FROM`] edges lie on one side — images
/// crossing the same side of the square, each edge overlapping all the
/// others, which made the search quadratic — that side is swept instead:
/// its edges, in index order, take what the earlier ones leave uncovered
/// from a set of merged intervals, cut at the earlier edges' own corners
/// (exact) rather than at parameters computed along the edge (rounded):
/// the same set, its pieces' ends differing in the last bits.
pub(super) fn union_area<const B: bool>(
    tris: &[Tri],
    weights: &[[f64; 3]],
    measure: Measure,
    half: f64,
    scratch: &mut UnionScratch,
) -> (f64, f64) {
    union_area_sweeping_from::<B>(tris, weights, measure, half, scratch, SWEEP_FROM)
}

/// Sides holding at least this many edges are swept ([`union_area`]; ours:
/// no built-in scene's receiver has a side that full).
pub(super) const SWEEP_FROM: usize = 64;

/// [`union_area`], sweeping the sides that hold `sweep_from` edges or more.
/// With `B`, also a bound on the area's error (else 0): `weights` holds
/// each triangle's edges' area allowances (how far the exact images may
/// differ from these along each edge; see [`union_area_in`]).
pub(super) fn union_area_sweeping_from<const B: bool>(
    tris: &[Tri],
    weights: &[[f64; 3]],
    measure: Measure,
    half: f64,
    scratch: &mut UnionScratch,
    sweep_from: usize,
) -> (f64, f64) {
    // Two copies of the loop: the test of [`Interior`] left out of the
    // one most receivers run (in it, the choice cost 1 % of the built-in
    // scenes' instructions).
    let deep = scratch.interior.build(tris, half);
    match (scratch.search, deep) {
        (Search::Grid, true) => {
            union_area_in::<true, B>(tris, weights, measure, half, scratch, sweep_from)
        }
        (Search::Grid, false) => {
            union_area_in::<false, B>(tris, weights, measure, half, scratch, sweep_from)
        }
        (Search::Tree, true) => {
            union_area_tree::<true, B>(tris, weights, measure, half, scratch, sweep_from)
        }
        (Search::Tree, false) => {
            union_area_tree::<false, B>(tris, weights, measure, half, scratch, sweep_from)
        }
    }
}

/// [`union_area_sweeping_from`], with `DEEP` whether [`Interior`] is built
/// (and the grid lists the fine level by area). The helpers it calls per
/// edge, per candidate and per triangle are `#[inline(always)]`: with two
/// copies of this loop the compiler kept them out of line, and the
/// built-in scenes' exact frames took up to 4 % more instructions.
///
/// The bound (`B`) sums: each edge's allowance unless it is shared (an
/// edge and its exact reverse move together, both sides covered) or
/// covered whole by the raster with a margin far above its width — the
/// exact union's boundary lies within those bands of the computed one;
/// for each piece kept on the boundary, the error of its ends where they
/// are cuts by other edges (`|e| Δt`: the pieces' areas move by at most
/// the distance their ends move, the disk's and the square's pieces being
/// 1-Lipschitz in their ends in the view's coordinates) and the area
/// kernel's (`3 ε` a piece for the unit disk; the square's `½ a × b`
/// likewise); and the compensated sum's (`2 ε` of the sum and `4 n ε²` of
/// the terms' magnitudes).
fn union_area_in<const DEEP: bool, const B: bool>(
    tris: &[Tri],
    weights: &[[f64; 3]],
    measure: Measure,
    half: f64,
    scratch: &mut UnionScratch,
    sweep_from: usize,
) -> (f64, f64) {
    let grid = &mut scratch.grid;
    grid.build::<DEEP>(tris, half);
    scratch.edges.build(tris, half);
    scratch.stamp.clear();
    scratch.stamp.resize(tris.len(), u32::MAX);
    let widest =
        prepare_sides_and_bands::<DEEP, B>(tris, weights, half, &mut scratch.sides, sweep_from);
    let mut sum = Sum::default();
    let mut bound = 0.0;
    let mut edge_id = 0_u32;
    for (i, ti) in tris.iter().enumerate() {
        #[allow(clippy::needless_range_loop)] // `k` names the edge and its weight.
        for k in 0..3 {
            let (a, b) = ti.edge(k);
            if let Some(side) = Side::of(a, b, half) {
                let set = &mut scratch.sides[side as usize];
                if set.active {
                    // On a side of the square exactly: no allowance.
                    set.add_uncovered(side, a, b, half, measure, &mut sum);
                    continue;
                }
            }
            if scratch.edges.has_reverse(tris, a, b) {
                continue;
            }
            if DEEP && scratch.interior.covers(a, b) {
                // Covered whole, as the search would find (see
                // [`Interior`]), with a margin: if the edge's band is far
                // narrower, the exact edge is covered too.
                if B && (widest >= 0.25 * scratch.interior.margin() || widest.is_nan()) {
                    bound += weights[i][k];
                }
                continue;
            }
            if B {
                bound += weights[i][k];
            }
            let (lo, hi) = (a.min(b), a.max(b));
            scratch.intervals.clear();
            if B {
                scratch.bounded.clear();
            }
            let mut cover = Cover::default();
            let mut whole = false;
            let (fx0, fy0, fx1, fy1) = grid.fine.range(lo, hi, half);
            if DEEP {
                let cells = (fx0, fy0, fx1, fy1);
                let (interior, searched) = (&scratch.interior, &mut scratch.searched);
                let bounded = &mut scratch.bounded;
                whole = searched_cells(&grid.fine, interior, (a, b), cells, half, searched, |u| {
                    if B {
                        // A covered passage: its ends are never a piece's.
                        bounded.push([u.0, u.1, 0.0, 0.0]);
                    }
                    cover.add(u, &mut scratch.intervals)
                });
            }
            let searched = &scratch.searched;
            let keep =
                |x: usize, y: usize| !DEEP || searched[(y - fy0) * (fx1 - fx0 + 1) + x - fx0];
            grid.for_each_near(lo, hi, keep, |j| {
                let j = j as usize;
                if j == i || scratch.stamp[j] == edge_id {
                    return true;
                }
                scratch.stamp[j] = edge_id;
                let tj = &tris[j];
                if tj.hi.x < lo.x || tj.lo.x > hi.x || tj.hi.y < lo.y || tj.lo.y > hi.y {
                    return true;
                }
                if let Some(span) = covered_span(a, b, tj, j < i) {
                    // Spans that together cover the edge settle it: nothing
                    // of it is on the boundary. Most edges are covered
                    // whole, and their search ends at the span that
                    // completes the cover (see [`Cover`]).
                    whole = cover.add(span, &mut scratch.intervals);
                    if B {
                        // The same span again, with its ends' errors.
                        if let Some(bounded) = covered_span_bounded(a, b, tj, j < i) {
                            scratch.bounded.push(bounded);
                        }
                    }
                }
                !whole
            });
            edge_id = edge_id.wrapping_add(1);
            if !whole {
                // The covered start as one interval: the same pieces.
                if cover.reach > 0.0 {
                    scratch.intervals.push((0.0, cover.reach));
                }
                add_uncovered(a, b, &mut scratch.intervals, measure, &mut sum);
                if B {
                    bound += cut_errors(a, b, &mut scratch.bounded);
                }
            }
        }
    }
    if B {
        bound += sum.bound();
    }
    (sum.value(), bound)
}

/// The common start of [`union_area_in`] and [`union_area_tree`]: each
/// side of the square swept if it holds `sweep_from` edges or more, and
/// (with `B` under a deep pile) the widest band of any edge — each
/// allowance is at least twice its width times its length: the raster's
/// margin covers an edge's exact position only if the covering
/// triangle's and its own are within it.
fn prepare_sides_and_bands<const DEEP: bool, const B: bool>(
    tris: &[Tri],
    weights: &[[f64; 3]],
    half: f64,
    sides: &mut [SideSet; 4],
    sweep_from: usize,
) -> f64 {
    let mut counts = [0usize; 4];
    for t in tris {
        for k in 0..3 {
            let (a, b) = t.edge(k);
            if let Some(side) = Side::of(a, b, half) {
                counts[side as usize] += 1;
            }
        }
    }
    for (set, &count) in sides.iter_mut().zip(&counts) {
        set.clear();
        set.active = count >= sweep_from;
    }
    if B && DEEP {
        tris.iter()
            .zip(weights)
            .flat_map(|(t, w)| {
                (0..3).map(move |k| {
                    let (a, b) = t.edge(k);
                    w[k] / (2.0 * (b - a).length())
                })
            })
            .fold(0.0_f64, |m, x| if x.is_nan() { m } else { m.max(x) })
    } else {
        0.0
    }
}

/// [`union_area_in`] with the edges' searches in a [`Tree`] instead of the
/// grids: the same spans' union for every edge (the tree leaves out only
/// triangles whose spans lie inside the cover already found; see
/// [`tree`]), so the same pieces, summed in the same order: the same area
/// and bound, bit for bit. The side sweep, the table of shared edges and
/// the raster of a deep pile settle the same edges first.
fn union_area_tree<const DEEP: bool, const B: bool>(
    tris: &[Tri],
    weights: &[[f64; 3]],
    measure: Measure,
    half: f64,
    scratch: &mut UnionScratch,
    sweep_from: usize,
) -> (f64, f64) {
    scratch.tree.build(tris, half);
    scratch.edges.build(tris, half);
    let widest =
        prepare_sides_and_bands::<DEEP, B>(tris, weights, half, &mut scratch.sides, sweep_from);
    let mut sum = Sum::default();
    let mut bound = 0.0;
    for (i, ti) in tris.iter().enumerate() {
        #[allow(clippy::needless_range_loop)] // `k` names the edge and its weight.
        for k in 0..3 {
            let (a, b) = ti.edge(k);
            if let Some(side) = Side::of(a, b, half) {
                let set = &mut scratch.sides[side as usize];
                if set.active {
                    set.add_uncovered(side, a, b, half, measure, &mut sum);
                    continue;
                }
            }
            if scratch.edges.has_reverse(tris, a, b) {
                continue;
            }
            if DEEP && scratch.interior.covers(a, b) {
                if B && (widest >= 0.25 * scratch.interior.margin() || widest.is_nan()) {
                    bound += weights[i][k];
                }
                continue;
            }
            if B {
                bound += weights[i][k];
                scratch.bounded.clear();
            }
            let (lo, hi) = (a.min(b), a.max(b));
            let spans = &mut scratch.spans;
            spans.clear();
            let bounded = &mut scratch.bounded;
            let whole = scratch.tree.search(&Ray::new(a, b), spans, |j| {
                span_of::<B>(a, b, i, j as usize, tris, (lo, hi), bounded)
            });
            if !whole {
                add_uncovered(a, b, &mut spans.list, measure, &mut sum);
                if B {
                    bound += cut_errors(a, b, &mut scratch.bounded);
                }
            }
        }
    }
    if B {
        bound += sum.bound();
    }
    (sum.value(), bound)
}

/// The span of the edge `a → b` (of triangle `i`, its bounds `lo..hi`)
/// that triangle `j` covers, as the grid's search finds it; with `B`, the
/// same span with its ends' errors pushed to `bounded`.
#[inline(always)]
fn span_of<const B: bool>(
    a: DVec2,
    b: DVec2,
    i: usize,
    j: usize,
    tris: &[Tri],
    (lo, hi): (DVec2, DVec2),
    bounded: &mut Vec<[f64; 4]>,
) -> Option<(f64, f64)> {
    let tj = &tris[j];
    if j == i || tj.hi.x < lo.x || tj.lo.x > hi.x || tj.hi.y < lo.y || tj.lo.y > hi.y {
        return None;
    }
    let span = covered_span(a, b, tj, j < i);
    if B && span.is_some() {
        bounded.extend(covered_span_bounded(a, b, tj, j < i));
    }
    span
}

/// For an edge `a → b` with pieces on the boundary, the sum of `|b − a|
/// Δt` over the pieces' ends that are cuts by other edges, `Δt` a bound on
/// each cut's error, from every span its search found (each computed
/// again with its ends' errors: the pieces are the complement of their
/// union, whatever the order; the raster's covered passages, whose ends
/// are never a piece's, with none).
#[inline(never)]
fn cut_errors(a: DVec2, b: DVec2, spans: &mut [[f64; 4]]) -> f64 {
    // The complement of the union of the spans, in order: its interior
    // ends are span ends, each with its error (the larger where ends
    // coincide).
    // Spans starting at the same point: the largest error first (so that
    // the bound does not depend on the order the search found them in).
    spans.sort_unstable_by(|x, y| x[0].total_cmp(&y[0]).then(y[2].total_cmp(&x[2])));
    let mut total = 0.0;
    let (mut reach, mut reach_err) = (0.0_f64, 0.0_f64);
    for &[s, e, es, ee] in spans.iter() {
        if s > reach {
            // A piece (reach, s): its start a cut unless at 0, its end a cut.
            total += reach_err + es;
            reach = e;
            reach_err = ee;
        } else if e > reach {
            reach = e;
            reach_err = ee;
        } else if e == reach {
            reach_err = reach_err.max(ee);
        }
    }
    if reach < 1.0 {
        total += reach_err;
    }
    total * (b - a).length() * (1.0 + 4.0 * f64::EPSILON)
}

/// Under a deep pile ([`Interior`]), which fine cells of the range
/// `x0..=x1, y0..=y1` (row by row) the search of the edge `a → b` must look
/// in, into `searched`; the passage of each other one ([`Level::passage`]),
/// if any, goes to `covered` (which returns whether the edge is now covered
/// whole: then so is the answer). A cell is left out where the edge does
/// not pass through it, or where [`Interior::covers`] the passage.
///
/// That changes no bit of the area. Every point of a covered passage lies
/// in a marked cell, so inside some triangle whose span covers it with
/// `2⁻³¹` of the parameter to spare (the argument of [`Interior`]): the
/// passage lies within the union of the search's spans. A triangle listed
/// only in left-out cells has its span inside their passages (its points,
/// and the points within rounding of them, lie in cells it is listed in,
/// and a passage takes every such point): leaving it out changes no point
/// of the union. And no end of a covered passage becomes an end of a
/// piece: the triangle covering the points just past it has them in a cell
/// whose passage is not covered, and that cell is searched.
fn searched_cells(
    fine: &Level,
    interior: &Interior,
    (a, b): (DVec2, DVec2),
    (x0, y0, x1, y1): (usize, usize, usize, usize),
    half: f64,
    searched: &mut Vec<bool>,
    mut covered: impl FnMut((f64, f64)) -> bool,
) -> bool {
    searched.clear();
    let mut whole = false;
    for y in y0..=y1 {
        for x in x0..=x1 {
            let search = fine.passage(x, y, a, b, half).is_some_and(|(u0, u1)| {
                let (p, q) = (a + (b - a) * u0, a + (b - a) * u1);
                if interior.covers(p, q) {
                    whole |= covered((u0, u1));
                    false
                } else {
                    true
                }
            });
            searched.push(search);
        }
    }
    whole
}

/// How an edge finds the triangles that may cover it: the two designs,
/// kept side by side so that they can be compared (the same area, bit for
/// bit; see `union_area_tree`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Search {
    /// Uniform grids of the triangles' bounds (fine, and coarse levels for
    /// large triangles), every triangle sharing a cell with the edge tested
    /// until the edge is covered whole.
    #[default]
    Grid,
    /// A hierarchy of bounding boxes, each node holding its subtree's
    /// largest triangle, searched with the edge's cover so far: subtrees
    /// whose part of the edge is covered already are left out.
    Tree,
}

/// Buffers of [`union_area`].
#[derive(Debug, Default)]
pub(super) struct UnionScratch {
    /// The search the union uses.
    pub(super) search: Search,
    tree: Tree,
    spans: Spans,
    grid: Grid,
    edges: Edges,
    /// The last edge each triangle was tested against.
    stamp: Vec<u32>,
    intervals: Vec<(f64, f64)>,
    /// Per side of the clip square, the swept edges so far.
    sides: [SideSet; 4],
    /// The cells inside some triangle, under a deep pile.
    interior: Interior,
    /// Under [`Interior`], per fine cell of the searched edge's range,
    /// whether the search looks in it ([`searched_cells`]).
    searched: Vec<bool>,
    /// The spans with their ends' errors ([`cut_errors`]).
    bounded: Vec<[f64; 4]>,
}

/// The triangles' distinct directed edges, hashed by their ends, to find
/// an edge's reverse: two counter-clockwise triangles with an edge `a → b`
/// and `b → a` lie on its two sides, so the edge is covered whole and
/// neither keeps any of it. The search would find that too (the other
/// triangle's span is the whole edge); on a mesh's images, where most
/// edges are shared, finding it here is what saves the search.
#[derive(Debug, Default)]
struct Edges {
    /// Open addressing, linear probing: `3 i + k` for edge `k` of triangle
    /// `i`, the first with its ends (copies of an edge — images cut by the
    /// same corner of the clip square, copies of a triangle — are one
    /// entry, so that a probe never walks past them), [`Edges::EMPTY`] for
    /// a free slot. Empty when there are fewer than [`Edges::FEWEST`]
    /// triangles or more than [`Edges::MOST`].
    slots: Vec<u32>,
    /// `64 −` the number of index bits.
    shift: u32,
}

impl Edges {
    const EMPTY: u32 = u32::MAX;

    /// The most triangles the table is built for (a bound on its memory:
    /// 32 MiB of slots at most). It was once 2¹⁶, since on images that
    /// share no edge the table cost more than the search it was to save
    /// (10⁵ near-coincident copies of a triangle, an earlier hash: a fifth
    /// more); but a convex polygon given as a fan of 10⁵ slivers, every
    /// inner edge shared, then went to the search edge by edge and took
    /// minutes for one answer, against about 0.1 s with the table
    /// (`examples/union_depth.rs`, `one fan0 100000`).
    const MOST: usize = 1 << 20;

    /// The fewest triangles the table is built for: below, the search is
    /// short, and the table cost more than it saved where no edge is
    /// shared (16 random images, an earlier hash: 3 % slower with it).
    const FEWEST: usize = 32;

    /// The table of `tris`' edges, but for those on a side of the clip
    /// square (`half` its half-width), whose reverse no triangle in the
    /// square can have (a side edge's reverse would lie on the side too:
    /// left out, so never found).
    #[inline(always)]
    fn build(&mut self, tris: &[Tri], half: f64) {
        self.slots.clear();
        if !(Edges::FEWEST..=Edges::MOST).contains(&tris.len()) {
            return;
        }
        let bits = (6 * tris.len()).next_power_of_two().trailing_zeros();
        self.shift = 64 - bits;
        self.slots.resize(1 << bits, Edges::EMPTY);
        for (t, i) in tris.iter().zip(0_u32..) {
            for k in 0..3 {
                let (a, b) = t.edge(k);
                if Side::of(a, b, half).is_some() {
                    continue;
                }
                if let Err(s) = self.probe(tris, a, b) {
                    self.slots[s] = 3 * i + k as u32;
                }
            }
        }
    }

    /// The slot holding the edge `a → b` (`Ok`), or else the free slot the
    /// probe ends at, where it would go (`Err`). The table is not empty.
    fn probe(&self, tris: &[Tri], a: DVec2, b: DVec2) -> Result<usize, usize> {
        let mask = self.slots.len() - 1;
        let mut s = self.slot(a, b);
        loop {
            let e = self.slots[s];
            if e == Edges::EMPTY {
                return Err(s);
            }
            if tris[(e / 3) as usize].edge((e % 3) as usize) == (a, b) {
                return Ok(s);
            }
            s = (s + 1) & mask;
        }
    }

    /// The first slot to probe for the edge `a → b`: each end's bits
    /// (`0.0` and `−0.0` alike) multiplied up, which carries a difference
    /// in the last bits (images of shifted copies) into the high ones, the
    /// two ends combined in order and multiplied again; the slot is the
    /// top bits. Three independent products, then one.
    fn slot(&self, a: DVec2, b: DVec2) -> usize {
        const K: [u64; 3] = [
            0x9e37_79b9_7f4a_7c15,
            0xbf58_476d_1ce4_e5b9,
            0x94d0_49bb_1331_11eb,
        ];
        let end = |v: DVec2| {
            (v.x + 0.0).to_bits().wrapping_mul(K[0]) ^ (v.y + 0.0).to_bits().wrapping_mul(K[1])
        };
        let h = end(a).rotate_left(29) ^ end(b);
        ((h ^ h >> 31).wrapping_mul(K[2]) >> self.shift) as usize
    }

    /// Whether some triangle of `tris` (those of the last
    /// [`Edges::build`]) has the edge `b → a`.
    fn has_reverse(&self, tris: &[Tri], a: DVec2, b: DVec2) -> bool {
        !self.slots.is_empty() && self.probe(tris, b, a).is_ok()
    }
}

/// A side of the clip square.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    /// `y = −half`.
    Bottom,
    /// `x = half`.
    Right,
    /// `y = half`.
    Top,
    /// `x = −half`.
    Left,
}

impl Side {
    /// The side both ends of `a → b` lie on (exactly: the clip leaves the
    /// square's coordinates as they are), if any.
    fn of(a: DVec2, b: DVec2, half: f64) -> Option<Side> {
        if a.y == b.y && a.y == -half {
            Some(Side::Bottom)
        } else if a.x == b.x && a.x == half {
            Some(Side::Right)
        } else if a.y == b.y && a.y == half {
            Some(Side::Top)
        } else if a.x == b.x && a.x == -half {
            Some(Side::Left)
        } else {
            None
        }
    }

    /// The coordinate that varies along the side.
    fn along(self, v: DVec2) -> f64 {
        match self {
            Side::Bottom | Side::Top => v.x,
            Side::Right | Side::Left => v.y,
        }
    }

    /// The point of the side at `u` along it.
    fn at(self, u: f64, half: f64) -> DVec2 {
        match self {
            Side::Bottom => DVec2::new(u, -half),
            Side::Top => DVec2::new(u, half),
            Side::Right => DVec2::new(half, u),
            Side::Left => DVec2::new(-half, u),
        }
    }
}

/// The union of the edges swept so far on one side: disjoint closed
/// intervals along it, keyed by their start's order-preserving bits.
#[derive(Debug, Default)]
struct SideSet {
    active: bool,
    intervals: std::collections::BTreeMap<u64, (f64, f64)>,
    /// Scratch for the uncovered pieces of one edge.
    pieces: Vec<(f64, f64)>,
    /// Scratch for the keys of the intervals one edge meets.
    met: Vec<u64>,
}

/// An order-preserving key of a finite `f64`.
fn key(u: f64) -> u64 {
    let bits = u.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    }
}

impl SideSet {
    fn clear(&mut self) {
        self.intervals.clear();
    }

    /// Adds the pieces of the side edge `a → b` that no earlier edge on the
    /// side covers, in order from `a`, then takes the edge into the set.
    fn add_uncovered(
        &mut self,
        side: Side,
        a: DVec2,
        b: DVec2,
        half: f64,
        measure: Measure,
        sum: &mut Sum,
    ) {
        let (ua, ub) = (side.along(a), side.along(b));
        let (lo, hi) = (ua.min(ub), ua.max(ub));
        // The intervals meeting [lo, hi]: from the last one starting at or
        // before `lo` on; merged into one afterwards.
        let first = self
            .intervals
            .range(..=key(lo))
            .next_back()
            .filter(|(_, &(_, e))| e >= lo)
            .map(|(&k, _)| k);
        let from = first.unwrap_or_else(|| key(lo));
        self.met.clear();
        self.met
            .extend(self.intervals.range(from..=key(hi)).map(|(&k, _)| k));
        self.pieces.clear();
        let (mut t, mut new_lo, mut new_hi) = (lo, lo, hi);
        for k in &self.met {
            let (s, e) = self.intervals.remove(k).expect("listed");
            if s > t {
                self.pieces.push((t, s));
            }
            t = t.max(e);
            (new_lo, new_hi) = (new_lo.min(s), new_hi.max(e));
        }
        if t < hi {
            self.pieces.push((t, hi));
        }
        self.intervals.insert(key(new_lo), (new_lo, new_hi));
        // In the edge's direction, from its exact ends and the earlier
        // edges' exact corners.
        let point = |u: f64| {
            if u == ua {
                a
            } else if u == ub {
                b
            } else {
                side.at(u, half)
            }
        };
        if ua <= ub {
            for &(s, e) in &self.pieces {
                sum.add(measure.piece(point(s), point(e)));
            }
        } else {
            for &(s, e) in self.pieces.iter().rev() {
                sum.add(measure.piece(point(e), point(s)));
            }
        }
    }
}

/// Uniform grids of triangle indices over the square `[−half, half]²`: a
/// fine grid of about one cell per triangle, in which a triangle is listed
/// in every cell its bounds overlap, in index order (by decreasing area
/// under a deep pile of images, where a larger triangle is likelier to
/// cover the searched edge and end its search: 16.2 tests per covered
/// edge instead of 19.6 on the pile of 4096 images in
/// `benches/references.rs`); and above it coarse
/// levels, level `k` with `2^k` cells a side, for the triangles that would
/// span more than [`Grid::LARGE`] fine cells along an axis, each listed at
/// the finest level whose cells are at least as wide as its bounds (at most
/// four cells), larger bounds first. Without the coarse levels a large
/// image was listed in most fine cells, and building the grid dominated
/// under many large overlapping images (nested or near-coincident ones); a
/// search visits the coarse levels first, coarsest first, since an edge
/// is most often covered whole by a large triangle, which ends its search.
/// Where no triangle is large, the grid is the fine grid alone.
#[derive(Debug, Default)]
struct Grid {
    half: f64,
    /// The fine grid.
    fine: Level,
    /// Coarse level `k` (kept between builds, cleared when used).
    coarse: Vec<Level>,
    /// The coarse levels that hold a triangle, coarsest first.
    occupied: Vec<usize>,
    /// The coarse levels' triangles: the level, a key (decreasing area of
    /// the bounds) and the index; sorted, each level's a run, larger first.
    large: Vec<(u8, u64, u32)>,
    /// Where each cell's next item goes, while filling a level.
    fill: Vec<u32>,
    /// The fine level's triangles by decreasing area (a key and the
    /// index), when they are listed in that order.
    order: Vec<(u64, u32)>,
}

/// One level of a [`Grid`], in compressed rows: cell `c` holds
/// `items[start[c]..start[c + 1]]`.
#[derive(Debug, Default)]
struct Level {
    n: usize,
    inv_cell: f64,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    /// The most cells along a side of the fine grid: beyond it, building
    /// costs more than the tests it saves.
    const MAX_SIDE: usize = 64;

    /// A triangle whose bounds span more than this many fine cells along
    /// an axis goes to a coarse level (ours: an ordinary image stays in the
    /// fine grid, as before; the nested and near-coincident images that
    /// made building it quadratic, each many fine cells wide, go up).
    const LARGE: f64 = 4.0;

    /// The fine grid's cells a side for `n` triangles.
    fn side(n: usize) -> usize {
        ((n as f64).sqrt().ceil() as usize).clamp(1, Grid::MAX_SIDE)
    }

    fn build<const BY_AREA: bool>(&mut self, tris: &[Tri], half: f64) {
        let side = Grid::side(tris.len());
        self.half = half;
        // The coarse levels' sides are the powers of two below the fine
        // grid's.
        let levels = side.next_power_of_two().trailing_zeros() as usize;
        let large = |t: &Tri| {
            let width = (t.hi - t.lo).max_element() / (2.0 * half);
            (levels > 0 && width * side as f64 > Grid::LARGE).then(|| {
                // The finest coarse level with cells at least `width` wide.
                let mut k = levels - 1;
                while k > 0 && width * (1_u64 << k) as f64 > 1.0 {
                    k -= 1;
                }
                k as u8
            })
        };
        self.fine.reset(side, half);
        self.large.clear();
        for (t, i) in tris.iter().zip(0_u32..) {
            match large(t) {
                Some(k) => {
                    let d = t.hi - t.lo;
                    self.large.push((k, !(d.x * d.y).to_bits(), i));
                }
                None => self.fine.count(t, half),
            }
        }
        self.fine.prefix(&mut self.fill);
        if BY_AREA {
            self.put_by_area(tris, half, |t| large(t).is_none());
        } else {
            for (t, i) in tris.iter().zip(0_u32..) {
                if large(t).is_none() {
                    self.fine.put(t, i, half, &mut self.fill);
                }
            }
        }
        self.occupied.clear();
        if self.large.is_empty() {
            return;
        }
        self.large.sort_unstable();
        if self.coarse.len() < levels {
            self.coarse.resize_with(levels, Level::default);
        }
        for run in self.large.chunk_by(|a, b| a.0 == b.0) {
            let k = usize::from(run[0].0);
            let level = &mut self.coarse[k];
            level.reset(1 << k, half);
            for &(_, _, i) in run {
                level.count(&tris[i as usize], half);
            }
            level.prefix(&mut self.fill);
            for &(_, _, i) in run {
                level.put(&tris[i as usize], i, half, &mut self.fill);
            }
            self.occupied.push(k);
        }
    }

    /// Lists the triangles `fine` takes in the fine level, by decreasing
    /// area.
    fn put_by_area(&mut self, tris: &[Tri], half: f64, fine: impl Fn(&Tri) -> bool) {
        self.order.clear();
        self.order.extend(
            tris.iter()
                .zip(0_u32..)
                .filter(|(t, _)| fine(t))
                .map(|(t, i)| (!t.doubled_area().to_bits(), i)),
        );
        self.order.sort_unstable();
        for &(_, i) in &self.order {
            self.fine.put(&tris[i as usize], i, half, &mut self.fill);
        }
    }

    /// Calls `f` with every triangle in a cell the box `lo..hi` overlaps,
    /// the coarse levels first, coarsest first (a triangle in several cells
    /// more than once), until it returns `false`; of the fine level, only
    /// in the cells `(x, y)` that `keep` keeps.
    fn for_each_near(
        &self,
        lo: DVec2,
        hi: DVec2,
        keep: impl Fn(usize, usize) -> bool,
        mut f: impl FnMut(u32) -> bool,
    ) {
        let levels = self.occupied.iter().map(|&k| &self.coarse[k]);
        for level in levels.chain(std::iter::once(&self.fine)) {
            let fine = std::ptr::eq(level, &self.fine);
            let (x0, y0, x1, y1) = level.range(lo, hi, self.half);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if fine && !keep(x, y) {
                        continue;
                    }
                    let c = y * level.n + x;
                    for &j in &level.items[level.start[c] as usize..level.start[c + 1] as usize] {
                        if !f(j) {
                            return;
                        }
                    }
                }
            }
        }
    }
}

impl Level {
    /// Empties the level and gives it `n` cells a side.
    fn reset(&mut self, n: usize, half: f64) {
        self.n = n;
        self.inv_cell = n as f64 / (2.0 * half);
        self.start.clear();
        self.start.resize(n * n + 1, 0);
    }

    /// Counts the triangle in the cells it overlaps.
    #[inline(always)]
    fn count(&mut self, t: &Tri, half: f64) {
        let (x0, y0, x1, y1) = self.range(t.lo, t.hi, half);
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.start[y * self.n + x + 1] += 1;
            }
        }
    }

    /// Turns the counts into starts, and the cells' fill positions into
    /// `fill`.
    fn prefix(&mut self, fill: &mut Vec<u32>) {
        let cells = self.n * self.n;
        for c in 0..cells {
            self.start[c + 1] += self.start[c];
        }
        self.items.clear();
        self.items.resize(self.start[cells] as usize, 0);
        fill.clear();
        fill.extend_from_slice(&self.start[..cells]);
    }

    /// Lists the triangle in the cells it overlaps (after [`Level::prefix`]
    /// of this level: `fill` is this level's).
    #[inline(always)]
    fn put(&mut self, t: &Tri, i: u32, half: f64, fill: &mut [u32]) {
        let (x0, y0, x1, y1) = self.range(t.lo, t.hi, half);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = y * self.n + x;
                self.items[fill[c] as usize] = i;
                fill[c] += 1;
            }
        }
    }

    /// The parameters `u ∈ [0, 1]` at which the point `a + u (b − a)` may
    /// lie in the cell `(x, y)`, as an interval: `None` where it never does.
    /// The cell is taken grown by `10⁻⁹` of the square on every side, and
    /// unbounded beyond the outer cells (as [`cell_of`] clamps): a point
    /// [`Level::put`] would list in the cell, or within rounding of one,
    /// lies in the interval by a margin far above the rounding of `u`.
    fn passage(&self, x: usize, y: usize, a: DVec2, b: DVec2, half: f64) -> Option<(f64, f64)> {
        let grow = 2e-9 * half;
        let w = 2.0 * half / self.n as f64;
        let mut u = (0.0_f64, 1.0_f64);
        for (c, pa, pb) in [(x, a.x, b.x), (y, a.y, b.y)] {
            let lo = if c == 0 {
                f64::NEG_INFINITY
            } else {
                -half + c as f64 * w - grow
            };
            let hi = if c + 1 >= self.n {
                f64::INFINITY
            } else {
                -half + (c + 1) as f64 * w + grow
            };
            let d = pb - pa;
            if d == 0.0 {
                if pa < lo || pa > hi {
                    return None;
                }
            } else {
                let (t0, t1) = ((lo - pa) / d, (hi - pa) / d);
                u = (u.0.max(t0.min(t1)), u.1.min(t0.max(t1)));
            }
        }
        (u.0 <= u.1).then_some(u)
    }

    /// The cells `x0..=x1`, `y0..=y1` the box `lo..hi` overlaps (clamped:
    /// rounding may put a clipped vertex a hair outside the square).
    fn range(&self, lo: DVec2, hi: DVec2, half: f64) -> (usize, usize, usize, usize) {
        let cell = |v: f64| cell_of(v, half, self.inv_cell, self.n);
        (cell(lo.x), cell(lo.y), cell(hi.x), cell(hi.y))
    }
}

/// The row or column, of `n`, of the coordinate `v` in cells of width
/// `1 / inv_cell` from `−half`, clamped. Truncation is the floor where it
/// is taken (`c ≥ 0`; a NaN gives 0): no call to `floor`, which the
/// baseline target lacks as an instruction.
fn cell_of(v: f64, half: f64, inv_cell: f64, n: usize) -> usize {
    let c = (v + half) * inv_cell;
    if c >= 0.0 {
        (c as usize).min(n - 1)
    } else {
        0
    }
}

/// The cover of an edge by the spans its search has found so far:
/// `[0, reach]` is covered, and the spans not within it are kept apart
/// (`pending`, which [`add_uncovered`] then takes with `(0, reach)`: the
/// same pieces as from every span, since `reach` is the largest end of the
/// spans it stands for). Each span that extends `reach` takes in the
/// pending spans it reaches, so the search ends at the span that completes
/// the cover. Past [`Cover::TRACKED`] spans, the pending ones are taken in
/// only when the number of spans is a power of two, which keeps an edge
/// with thousands of spans `O(m log m)`.
#[derive(Debug, Default)]
struct Cover {
    reach: f64,
    spans: usize,
}

impl Cover {
    /// The most spans of an edge followed span by span (ours: an edge of
    /// the pile of images in `benches/references.rs` collects about 20 at
    /// 4096 images; at 16384, where edges collect more, 64 cost 13 % more
    /// time than 128, measured on the first form of this bookkeeping).
    const TRACKED: usize = 128;

    /// Takes `span` (pending spans in `pending`); whether the edge is now
    /// covered whole. Kept out of the search's loop, which most candidates
    /// leave without a span.
    #[inline(never)]
    fn add(&mut self, span: (f64, f64), pending: &mut Vec<(f64, f64)>) -> bool {
        self.spans += 1;
        if span.0 <= self.reach {
            self.reach = self.reach.max(span.1);
            if self.spans <= Cover::TRACKED {
                self.take_in(pending);
            }
        } else {
            pending.push(span);
        }
        if self.spans > Cover::TRACKED && self.spans.is_power_of_two() {
            self.take_in_sorted(pending);
        }
        self.reach >= 1.0
    }

    /// Takes in every pending span that starts within `[0, reach]`, until
    /// none does: up to four passes in their order, then (a longer chain in
    /// reverse order) one after sorting them.
    fn take_in(&mut self, pending: &mut Vec<(f64, f64)>) {
        for _ in 0..4 {
            let before = pending.len();
            let mut k = 0;
            while k < pending.len() {
                let (s, e) = pending[k];
                if s <= self.reach {
                    self.reach = self.reach.max(e);
                    pending.swap_remove(k);
                } else {
                    k += 1;
                }
            }
            if pending.len() == before {
                return;
            }
        }
        self.take_in_sorted(pending);
    }

    /// [`Cover::take_in`] by sorting the pending spans: `O(m log m)`.
    fn take_in_sorted(&mut self, pending: &mut Vec<(f64, f64)>) {
        pending.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        let mut taken = 0;
        for &(s, e) in pending.iter() {
            if s > self.reach {
                break;
            }
            self.reach = self.reach.max(e);
            taken += 1;
        }
        pending.drain(..taken);
    }
}

/// Adds the pieces of `a → b` outside every interval of `intervals`.
#[inline(always)]
fn add_uncovered(
    a: DVec2,
    b: DVec2,
    intervals: &mut [(f64, f64)],
    measure: Measure,
    sum: &mut Sum,
) {
    if intervals.is_empty() {
        sum.add(measure.piece(a, b));
        return;
    }
    intervals.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let at = |t: f64| if t >= 1.0 { b } else { a + (b - a) * t };
    let mut t = 0.0;
    let mut from = a;
    for &(s, e) in intervals.iter() {
        if s > t {
            let to = at(s);
            sum.add(measure.piece(from, to));
        }
        if e > t {
            t = e;
            from = at(t);
        }
        if t >= 1.0 {
            return;
        }
    }
    sum.add(measure.piece(from, b));
}

/// The parameter interval of the edge `a → b` that the triangle covers,
/// `None` when it covers none of positive length. Closed triangle; where
/// the edge runs along an edge of `t` the rule of the
/// [module documentation](super) applies: covered when `t` lies on the
/// other side, or on the same side and `t_first` (it comes first in index
/// order).
#[inline(always)]
fn covered_span(a: DVec2, b: DVec2, t: &Tri, t_first: bool) -> Option<(f64, f64)> {
    let mut span = (0.0_f64, 1.0_f64);
    // Signed areas with exact signs and accurate values: the cut of this
    // edge by an edge `f` of `t` and the cut of `f` by this edge land on
    // the same point even for nearly parallel edges. The first edge of `t`
    // at both ends side by side (most triangles the search meets end
    // there), then the other two at both ends.
    let [v0, v1, v2] = t.v;
    let w = orient2d_values_finite(
        [[v0.x, v0.x], [v0.y, v0.y]],
        [[v1.x, v1.x], [v1.y, v1.y]],
        [[a.x, b.x], [a.y, b.y]],
    );
    cut_by_edge(&mut span, w[0], w[1], a, b, (v0, v1), t_first)?;
    let v = orient2d_values_finite(
        [[v1.x, v1.x, v2.x, v2.x], [v1.y, v1.y, v2.y, v2.y]],
        [[v2.x, v2.x, v0.x, v0.x], [v2.y, v2.y, v0.y, v0.y]],
        [[a.x, b.x, a.x, b.x], [a.y, b.y, a.y, b.y]],
    );
    cut_by_edge(&mut span, v[0], v[1], a, b, (v1, v2), t_first)?;
    cut_by_edge(&mut span, v[2], v[3], a, b, (v2, v0), t_first)?;
    (span.0 < span.1).then_some(span)
}

/// Narrows `span` (parameters of the edge `a → b`) to the inner side of
/// the triangle's edge `f`, given the signed areas `va`, `vb` of `a` and
/// `b` against it; `None` when nothing of positive length is left on that
/// side (see [`covered_span`]).
#[inline(always)]
fn cut_by_edge(
    span: &mut (f64, f64),
    va: f64,
    vb: f64,
    a: DVec2,
    b: DVec2,
    (f0, f1): (DVec2, DVec2),
    t_first: bool,
) -> Option<()> {
    // The signs' cases by comparisons (a NaN counts as zero, as `Sign`
    // has it; the values are finite).
    let (a_in, a_out, b_in, b_out) = (va > 0.0, va < 0.0, vb > 0.0, vb < 0.0);
    if !a_in && !b_in {
        if a_out || b_out {
            // Outside, touching the line at most at one end.
            return None;
        }
        // Along the line.
        let same_side = (b - a).dot(f1 - f0) > 0.0;
        if same_side && !t_first {
            return None;
        }
    } else if (a_out && b_in) || (a_in && b_out) {
        // A strict crossing: va and vb have opposite signs, so va − vb
        // does not cancel.
        let s = (va / (va - vb)).clamp(0.0, 1.0);
        if a_out {
            span.0 = span.0.max(s);
        } else {
            span.1 = span.1.min(s);
        }
    }
    Some(())
}

/// [`covered_span`] computed one signed area at a time (the same values,
/// so the same span) with bounds, and a bound on each end's error: `[s₀,
/// s₁, Δs₀, Δs₁]`.
fn covered_span_bounded(a: DVec2, b: DVec2, t: &Tri, t_first: bool) -> Option<[f64; 4]> {
    let mut span = [0.0, 1.0, 0.0, 0.0];
    let [v0, v1, v2] = t.v;
    for (f0, f1) in [(v0, v1), (v1, v2), (v2, v0)] {
        let (va, vb) = (
            orient2d_value_bounded(f0, f1, a),
            orient2d_value_bounded(f0, f1, b),
        );
        let mut narrowed = (span[0], span[1]);
        cut_by_edge(&mut narrowed, va.value, vb.value, a, b, (f0, f1), t_first)?;
        // The cut's error: the values' bounds over their difference (no
        // cancellation: opposite signs), and the quotient's rounding.
        let err = (va.bound + vb.bound) / (va.value - vb.value).abs() + f64::EPSILON;
        if narrowed.0 != span[0] {
            span[2] = err;
        }
        if narrowed.1 != span[1] {
            span[3] = err;
        }
        (span[0], span[1]) = narrowed;
    }
    (span[0] < span[1]).then_some(span)
}

/// Neumaier's compensated sum, with the count and the magnitudes of its
/// terms for its error bound.
#[derive(Default)]
struct Sum {
    sum: f64,
    c: f64,
    magnitude: f64,
    n: u32,
}

impl Sum {
    fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.c += (self.sum - t) + x;
        } else {
            self.c += (x - t) + self.sum;
        }
        self.sum = t;
        self.magnitude += x.abs();
        self.n += 1;
    }

    fn value(&self) -> f64 {
        self.sum + self.c
    }

    /// A bound on the sum's error, and the terms' own (each piece of the
    /// area kernel within `3 ε`, the unit disk's and the square's): the
    /// compensated sum is within `2 ε |s| + 4 n ε² Σ|tᵢ|` of the exact sum
    /// of its terms (Neumaier; Higham, *Accuracy and Stability*, §4.3).
    fn bound(&self) -> f64 {
        let eps = f64::EPSILON;
        let n = f64::from(self.n);
        (2.0 * eps * self.value().abs() + 4.0 * n * eps * eps * self.magnitude + 3.0 * n * eps)
            * (1.0 + 4.0 * eps)
    }
}

/// Under a deep pile of small images (at least [`Interior::FEWEST`]
/// triangles, their areas summing to at least [`Interior::DEPTH`] times
/// their common bounds, their mean width within [`Grid::LARGE`] cells of
/// the fine grid), a raster over the square `[−half, half]²` of the cells
/// that lie inside some triangle with a margin: an edge whose every point
/// is in such a cell is covered whole, and is dropped before any search
/// ([`Interior::covers`]).
///
/// That is the search's own answer, so the area is the same bit for bit. A
/// marked cell is closed and lies at least `μ = 2⁻²⁰ w / √2` (`w` the
/// cell's width) inside each edge line of some triangle `j`, and `j` is not
/// the searched edge's own (whose points are on its boundary). So every
/// point of the edge is at least `μ` inside a triangle whose bounds meet
/// the edge's, which the search tests: the span it finds contains that
/// point's parameter with `μ / |b − a|` to spare on either side (at least
/// `2⁻³¹` of the parameter range, the square's diagonal being `2.9 half`
/// and the cells at least `half / 512` wide), against a few units in the
/// last place of rounding in the span's ends. The spans then overlap and
/// cover `[0, 1]`, and the search ends with no piece on the boundary.
///
/// The arithmetic that marks a cell and walks an edge is rounded, and
/// its errors are absorbed by margins at least `2¹⁸` times wider. A cell
/// must be `2⁻²⁰ w` inside (in the edge function, `2⁻²⁰ w |d|∞`, `d` the
/// edge's direction): along a row, where the edge's line crosses it moved
/// by `2⁻²⁰ |d|∞ / |d.y| ≥ 2⁻²¹ (1 + |β|)` cells, `β = d.x / d.y`. That
/// crossing is computed as `α + β r` cells in row `r`, with an error of a
/// few units in the last place of `(1 + |β|) n`, at most `2⁻³⁹ (1 + |β|)`
/// cells (`n ≤ 1024` cells a side). A walk takes every cell within `10⁻⁶
/// (1 + |s|)` cells of the edge's computed course (`s` the slope against
/// `y`, which multiplies the error in a row's `y`), against errors of a few
/// units in the last place of `half` or of the cell index, about `2⁻⁴²` of
/// a cell.
///
/// The walk goes a row of blocks at a time ([`Interior::course_covered`];
/// blocks of [`Interior::BLOCK`] cells a side, those all marked listed in
/// [`Interior::full`]): where every block along the course in a row of
/// blocks is all marked, so is every cell the walk over the cells would
/// take in those rows, and that walk is left out of them. On the pile of
/// 4096 images below, the 25,277 questions (edges, and passages of
/// [`searched_cells`]) walk 54,030 rows of blocks and 60,948 rows of cells
/// (128,244 when the cells were walked whole wherever a block failed);
/// at 16384 images 53,238 questions, 166,938 and 18,121 rows.
///
/// Measured on the pile of 4096 images in `benches/references.rs`: of its
/// 12,138 edges, 9,143 of the 10,336 covered whole are dropped here,
/// leaving 31,438 span tests for the covered edges instead of 167,384;
/// the raster is 768 cells a side (72 KB). The 2,995 edges left are
/// searched only in the fine cells whose passage the raster does not cover
/// ([`searched_cells`]: 5,422 of the 21,452 in their ranges), which takes
/// their candidates from 451,561 to 133,994 and their span tests from
/// 99,215 to 58,849. A shallow pile gains nothing
/// (1024 images, depth 1: 2.8 → 3.6 ms), hence the thresholds, which no
/// built-in scene's receiver reaches (`large-light` has the most images
/// per receiver, up to 960, at most about two deep).
#[derive(Debug, Default)]
struct Interior {
    /// Cells a side, a multiple of 64 (0: not built).
    n: usize,
    half: f64,
    /// The cells' width, and its inverse.
    w: f64,
    inv_w: f64,
    /// Row-major, `n / 64` words a row: bit `k % 64` of word `k / 64` of
    /// row `r` for the cell `[−half + k w, −half + (k + 1) w] × [−half +
    /// r w, −half + (r + 1) w]`.
    bits: Vec<u64>,
    /// The blocks of [`Interior::BLOCK`] cells a side all marked, in the
    /// same layout: `n / BLOCK` blocks a side, a row's bits in whole words.
    full: Vec<u64>,
}

impl Interior {
    /// The fewest triangles the raster is built for.
    const FEWEST: usize = 256;

    /// The least depth (summed area over the area of the common bounds)
    /// it is built for (ours: the pile of `benches/references.rs`, about
    /// one deep per 1000 images, at 2048, 2400, 2800 and 4096 images: 7.9
    /// → 8.2, 9.97 → 10.1, 12.1 → 11.0 and 21.2 → 13.6 ms with it).
    const DEPTH: f64 = 2.5;

    /// Cells across the mean width of a triangle's bounds (ours: 16, 24,
    /// 32 and 48 put the pile of 4096 images at 15.1, 14.3, 14.0 and 17.5
    /// ms: finer cells drop more edges but cost more to mark and walk).
    const ACROSS: f64 = 32.0;

    /// The most cells a side.
    const MOST: usize = 1024;

    /// Cells a side of a block ([`Interior::full`]), a power of two below 64.
    const BLOCK: usize = 8;

    /// The triangles the depth is estimated from (ours: 64 put the pile of
    /// 2048 images, 2 deep, above 2.5).
    const SAMPLES: usize = 256;

    /// Marks the cells inside `tris`' triangles, if the pile is deep;
    /// whether it is (else [`Interior::covers`] is not to be called).
    fn build(&mut self, tris: &[Tri], half: f64) -> bool {
        self.n = 0;
        if tris.len() < Interior::FEWEST {
            return false;
        }
        // The depth and mean width from an even sample of the triangles
        // (a pass over all of them cost 1 % of the instructions of the
        // built-in scenes, whose piles are shallow).
        let step = tris.len() / Interior::SAMPLES;
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(-f64::INFINITY));
        let (mut area, mut width) = (0.0, 0.0);
        for t in tris.iter().step_by(step).take(Interior::SAMPLES) {
            (lo, hi) = (lo.min(t.lo), hi.max(t.hi));
            area += 0.5 * t.doubled_area();
            width += (t.hi - t.lo).max_element();
        }
        let bounds = (hi - lo).x * (hi - lo).y;
        let scale = tris.len() as f64 / Interior::SAMPLES as f64;
        if area * scale < Interior::DEPTH * bounds {
            return false;
        }
        let mean = width / Interior::SAMPLES as f64;
        // Large images go to the grid's coarse levels, where an edge meets
        // the largest first and its search ends soon: the raster saves
        // little there, and marking costs as much (ours: near-coincident
        // and nested images of `benches/references.rs`'s `degenerate`
        // group, 2.7 to 4.2 times the time with it).
        if mean * Grid::side(tris.len()) as f64 > Grid::LARGE * 2.0 * half {
            return false;
        }
        let want = (2.0 * half / mean * Interior::ACROSS).clamp(64.0, Interior::MOST as f64);
        // `want` is at least 64 (a NaN clamps to 64 too).
        let n = (want as usize).div_ceil(64) * 64;
        self.n = n;
        self.half = half;
        self.w = 2.0 * half / n as f64;
        self.inv_w = n as f64 / (2.0 * half);
        self.bits.clear();
        self.bits.resize(n * (n / 64), 0);
        let margin = self.w / f64::from(1_u32 << 20);
        let last = n as f64;
        'tris: for t in tris {
            // The edges' lines as bounds on the cells of a row inside them.
            let mut bounds = RowBounds::default();
            for e in 0..3 {
                let (p, q) = t.edge(e);
                let d = q - p;
                let m = margin * d.abs().max_element();
                if d.y == 0.0 {
                    bounds.flat[bounds.flats] = (p.y, d.x, m);
                    bounds.flats += 1;
                    continue;
                }
                // Inside (counter-clockwise): `f = d.x (y − p.y) − d.y (x −
                // p.x) ≥ m` at the cell's corner of least `f`, whose `y` is
                // the row's bottom where `d.x > 0`, its top else, and whose
                // `x` is the cell's left where `d.y < 0`, its right else.
                // `f = m` at `x = p.x + (d.x (y − p.y) − m) / d.y`: in cells,
                // at that corner's `y` in row `r`, `α + β r`.
                let beta = d.x / d.y;
                let s = if d.x > 0.0 { 0.0 } else { 1.0 };
                let alpha =
                    (p.x + half - m / d.y) * self.inv_w + beta * (s - (p.y + half) * self.inv_w);
                if !(alpha.abs() < 1e200 && beta.abs() < 1e200) {
                    // An edge within `10⁻²⁰⁰` of level: its triangle marks
                    // nothing (never met in practice; fewer marks are
                    // always safe).
                    continue 'tris;
                }
                // The first free slot (`α` finite where taken): a triangle
                // has at most two edges on a side, the differences `d.y`
                // of its corners having their exact signs.
                let side = if d.y < 0.0 {
                    &mut bounds.left
                } else {
                    &mut bounds.right
                };
                side[usize::from(side[0].0.is_finite())] = (alpha, beta);
            }
            for r in self.cell(t.lo.y)..=self.cell(t.hi.y) {
                let y0 = -half + r as f64 * self.w;
                let outside = bounds.flat[..bounds.flats].iter().any(|&(p, d, m)| {
                    let y = if d > 0.0 { y0 } else { y0 + self.w };
                    d * (y - p) < m
                });
                if outside {
                    continue;
                }
                // The cells `k0..=k1` of the row inside each edge's line:
                // the cell's left `k ≥ v` past the left edges (the first
                // such `k` is at most `floor(v) + 1`, by truncation of `v +
                // 1 ≥ 0`), its right `k + 1 ≤ v` short of the right ones.
                let at = |(alpha, beta): (f64, f64)| alpha + beta * r as f64;
                let v0 = at(bounds.left[0]).max(at(bounds.left[1]));
                let v1 = at(bounds.right[0]).min(at(bounds.right[1]));
                let k0 = (v0.max(-1.0).min(last) + 1.0) as i64;
                let k1 = v1.max(0.0).min(last) as i64 - 1;
                if k0 <= k1 {
                    self.mark(r, k0 as usize, k1 as usize);
                }
            }
        }
        self.find_full_blocks();
        true
    }

    /// How far inside some triangle every point of a marked cell lies:
    /// `2⁻²⁰ w / √2` (see [`Interior`]).
    fn margin(&self) -> f64 {
        self.w / f64::from(1_u32 << 20) * std::f64::consts::FRAC_1_SQRT_2
    }

    /// Fills [`Interior::full`] from the marks.
    fn find_full_blocks(&mut self) {
        const B: usize = Interior::BLOCK;
        let (words, blocks) = (self.n / 64, self.n / B);
        let block_words = self.block_words();
        self.full.clear();
        self.full.resize(blocks * block_words, 0);
        let group = u64::MAX >> (64 - B);
        for br in 0..blocks {
            for i in 0..words {
                let rows = (B * br..B * br + B).map(|r| self.bits[r * words + i]);
                let all = rows.fold(u64::MAX, |x, y| x & y);
                for g in 0..64 / B {
                    if (all >> (B * g)) & group == group {
                        let k = 64 / B * i + g;
                        self.full[br * block_words + k / 64] |= 1 << (k % 64);
                    }
                }
            }
        }
    }

    /// Words a row of [`Interior::full`].
    fn block_words(&self) -> usize {
        (self.n / Interior::BLOCK).div_ceil(64)
    }

    /// Row `r` of [`Interior::full`] (the blocks over the rows `BLOCK r..
    /// BLOCK (r + 1)` of cells).
    fn block_row(&self, r: usize) -> &[u64] {
        let words = self.block_words();
        &self.full[r * words..(r + 1) * words]
    }

    /// The row or column of the coordinate `v` (clamped).
    fn cell(&self, v: f64) -> usize {
        cell_of(v, self.half, self.inv_w, self.n)
    }

    /// Row `r` of the marks.
    fn row(&self, r: usize) -> &[u64] {
        let words = self.n / 64;
        &self.bits[r * words..(r + 1) * words]
    }

    fn mark(&mut self, r: usize, k0: usize, k1: usize) {
        let words = self.n / 64;
        let row = &mut self.bits[r * words..(r + 1) * words];
        let (i0, i1, first, last) = span_masks(k0, k1);
        if i0 == i1 {
            row[i0] |= first & last;
        } else {
            row[i0] |= first;
            row[i0 + 1..i1].fill(u64::MAX);
            row[i1] |= last;
        }
    }

    /// Whether every cell the edge `a → b` may pass through is marked
    /// ([`Interior::course_covered`]).
    fn covers(&self, a: DVec2, b: DVec2) -> bool {
        self.course(a, b).is_some_and(|c| self.course_covered(&c))
    }

    /// The edge `a → b` in cells, `None` where it leaves the square.
    #[inline(always)]
    fn course(&self, a: DVec2, b: DVec2) -> Option<Course> {
        if a.abs().max_element() > self.half || b.abs().max_element() > self.half {
            return None;
        }
        let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
        let to = |v: f64| (v + self.half) * self.inv_w;
        let (lx, ly, hx, hy) = (to(lo.x), to(lo.y), to(hi.x), to(hi.y));
        let top = self.n - 1;
        let cell = |v: f64| (v.max(0.0) as usize).min(top);
        Some(Course {
            lo: DVec2::new(lx, ly),
            hi: DVec2::new(hx, hy),
            rows: (cell(ly - Course::EPS), cell(hy + Course::EPS)),
        })
    }

    /// Whether every cell within `10⁻⁶ (1 + |s|)` of the course is marked
    /// (`s` its slope against `y`): the answer of [`Walk`] over the cells
    /// from the first row to the last, found row of blocks by row of
    /// blocks. In each row of blocks, [`Walk`] over the blocks (the course
    /// scaled to them) takes the blocks within `10⁻⁶ (1 + |s|)` blocks of
    /// the course — [`Interior::BLOCK`] times the margin the cells need —
    /// so each cell the walk over the cells takes in those rows lies in a
    /// block taken. Where those blocks are all marked, so are those cells,
    /// and the walk over the cells is left out of that row of blocks.
    #[inline(always)]
    fn course_covered(&self, c: &Course) -> bool {
        const B: usize = Interior::BLOCK;
        let in_blocks = c.in_blocks();
        let mut blocks = Walk::new(&in_blocks, self.n / B);
        // Set up where a row of blocks first fails (most questions the
        // blocks settle never need it).
        let mut cells = None;
        for block_row in in_blocks.rows.0..=in_blocks.rows.1 {
            let (k0, k1) = blocks.step(block_row);
            if all_set(self.block_row(block_row), k0, k1) {
                continue;
            }
            let cells = cells.get_or_insert_with(|| Walk::new(c, self.n));
            let rows = c.rows.0.max(B * block_row)..=c.rows.1.min(B * block_row + B - 1);
            cells.enter(*rows.start());
            for r in rows {
                let (k0, k1) = cells.step(r);
                if !all_set(self.row(r), k0, k1) {
                    return false;
                }
            }
        }
        true
    }

    /// Whether the blocks along the course are all marked: the walk of
    /// [`Walk`] over the blocks, the course scaled to them, whole.
    #[cfg(test)]
    fn blocks_cover(&self, c: &Course) -> bool {
        walk_covers(&c.in_blocks(), self.n / Interior::BLOCK, |r| {
            self.block_row(r)
        })
    }

    /// Whether every cell within `10⁻⁶ (1 + |s|)` of the course is marked,
    /// the walk over the cells whole.
    #[cfg(test)]
    fn cells_cover(&self, c: &Course) -> bool {
        walk_covers(c, self.n, |r| self.row(r))
    }
}

/// Whether every cell [`Walk`] takes along the course `c` (in a raster `n`
/// cells a side) is set in its row (`row(r)`, bit `k` for the column `k`),
/// from its first row to its last.
#[cfg(test)]
fn walk_covers<'a>(c: &Course, n: usize, row: impl Fn(usize) -> &'a [u64]) -> bool {
    let mut walk = Walk::new(c, n);
    (c.rows.0..=c.rows.1).all(|r| {
        let (k0, k1) = walk.step(r);
        all_set(row(r), k0, k1)
    })
}

/// A walk along a [`Course`] (in a raster `n` cells a side) row by row
/// from its first row: in each, the columns within `10⁻⁶ (1 + |s|)` of the
/// course (`s` its slope against `y`), clamped to the raster.
struct Walk {
    lo: DVec2,
    hi: DVec2,
    /// The first row.
    first: usize,
    level: bool,
    slope: f64,
    eps: f64,
    top: i64,
    /// The course's `x` where it enters the next row.
    x_in: f64,
}

impl Walk {
    #[inline(always)]
    fn new(c: &Course, n: usize) -> Walk {
        let (lo, hi, first) = (c.lo, c.hi, c.rows.0);
        let level = hi.y <= lo.y;
        let slope = if level {
            0.0
        } else {
            (hi.x - lo.x) / (hi.y - lo.y)
        };
        Walk {
            lo,
            hi,
            first,
            level,
            slope,
            eps: Course::EPS * (1.0 + slope.abs()),
            top: (n - 1) as i64,
            x_in: lo.x,
        }
    }

    /// Where the course leaves row `r` (at `y = r + 1`, at `y = hi.y` in
    /// the last row); a level course's whole `x` range is `lo.x..hi.x`.
    #[inline(always)]
    fn exit(&self, r: usize) -> f64 {
        if self.level {
            self.hi.x
        } else {
            self.lo.x + (((r + 1) as f64).min(self.hi.y) - self.lo.y) * self.slope
        }
    }

    /// Starts the next [`Walk::step`] at row `r` (the first row, or any
    /// later one): the course's `x` where it enters `r` is where it leaves
    /// `r − 1`, as a step through every row before would have carried it.
    #[inline(always)]
    fn enter(&mut self, r: usize) {
        self.x_in = if r == self.first || self.level {
            self.lo.x
        } else {
            self.exit(r - 1)
        };
    }

    /// The columns `k0..=k1` taken in row `r`, the row after the last step
    /// (or the one entered).
    #[inline(always)]
    fn step(&mut self, r: usize) -> (usize, usize) {
        let x_out = self.exit(r);
        let (x0, x1) = if self.x_in <= x_out {
            (self.x_in, x_out)
        } else {
            (x_out, self.x_in)
        };
        if !self.level {
            self.x_in = x_out;
        }
        let k0 = ((x0 - self.eps) as i64).clamp(0, self.top) as usize;
        let k1 = ((x1 + self.eps) as i64).clamp(0, self.top) as usize;
        (k0, k1)
    }
}

/// A triangle's edges as [`Interior::build`] bounds the cells of a row
/// inside them: where its left edges' lines cross row `r`, `α + β r` in
/// cells from the square's left side (a missing edge at `−∞`), where its
/// right edges' lines do (`+∞`), and its level edges, from height `p`
/// running `d` along `x` with the margin `m`, each of which takes a whole
/// row or none of it.
#[derive(Clone, Copy, Debug)]
struct RowBounds {
    left: [(f64, f64); 2],
    right: [(f64, f64); 2],
    flat: [(f64, f64, f64); 3],
    flats: usize,
}

impl Default for RowBounds {
    fn default() -> RowBounds {
        RowBounds {
            left: [(f64::NEG_INFINITY, 0.0); 2],
            right: [(f64::INFINITY, 0.0); 2],
            flat: [(0.0, 0.0, 0.0); 3],
            flats: 0,
        }
    }
}

/// An edge over the cells of an [`Interior`], in cells from the square's
/// corner `(−half, −half)`.
struct Course {
    /// The end of least `y`, and the other.
    lo: DVec2,
    hi: DVec2,
    /// The rows within [`Course::EPS`] of its ends (clamped).
    rows: (usize, usize),
}

impl Course {
    /// The margin, in cells, for the rounding of the course.
    const EPS: f64 = 1e-6;

    /// The course over the blocks of [`Interior::BLOCK`] cells a side: its
    /// ends scaled to them, its rows those of blocks holding its rows.
    #[inline(always)]
    fn in_blocks(&self) -> Course {
        const B: usize = Interior::BLOCK;
        let scale = 1.0 / B as f64;
        Course {
            lo: self.lo * scale,
            hi: self.hi * scale,
            rows: (self.rows.0 / B, self.rows.1 / B),
        }
    }
}

/// The words `i0..=i1` of a row holding its bits `k0..=k1` (`k0 ≤ k1`),
/// and the masks of those bits in the first word and in the last.
#[inline(always)]
fn span_masks(k0: usize, k1: usize) -> (usize, usize, u64, u64) {
    (
        k0 / 64,
        k1 / 64,
        u64::MAX << (k0 % 64),
        u64::MAX >> (63 - k1 % 64),
    )
}

/// Whether the bits `k0..=k1` (`k0 ≤ k1`) of the row `words` are all set.
#[inline(always)]
fn all_set(words: &[u64], k0: usize, k1: usize) -> bool {
    let (i0, i1, first, last) = span_masks(k0, k1);
    if i0 == i1 {
        words[i0] & first & last == first & last
    } else {
        words[i0] & first == first
            && words[i0 + 1..i1].iter().all(|&w| w == u64::MAX)
            && words[i1] & last == last
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arbitrary::Rng;

    /// Random triangles inside the square `[−h, h]²`, many with an edge on
    /// one of its sides (as clipped images have), some sharing corners.
    fn clipped_like(rng: &mut Rng, n: usize, h: f64) -> Vec<Tri> {
        let mut tris = Vec::new();
        while tris.len() < n {
            let coordinate = |rng: &mut Rng| {
                if rng.chance(0.3) {
                    h * rng.sign()
                } else {
                    // Now and then a value another triangle also uses.
                    (rng.below(9) as f64 / 4.0 - 1.0)
                        * h
                        * if rng.chance(0.5) { 1.0 } else { rng.unit() }
                }
            };
            let side = rng.below(4);
            let along = |u: f64| match side {
                0 => DVec2::new(u, -h),
                1 => DVec2::new(h, u),
                2 => DVec2::new(u, h),
                _ => DVec2::new(-h, u),
            };
            let (a, b) = (along(coordinate(rng)), along(coordinate(rng)));
            let c = DVec2::new(coordinate(rng), coordinate(rng));
            if let Some(t) = Tri::new(a, b, c) {
                tris.push(t);
            }
        }
        tris
    }

    /// The sweep of the square's sides and the search over the grid give
    /// the same area (the same set; their pieces' ends may differ in the
    /// last bits), on both measures.
    #[test]
    fn sweeping_the_sides_gives_the_searched_area() {
        let mut rng = Rng::new(17);
        let mut scratch = UnionScratch::default();
        for case in 0..300 {
            let n = 1 + rng.below(120) as usize;
            let (measure, h) = if case % 2 == 0 {
                (Measure::Disk(1.0), 1.5)
            } else {
                (Measure::Square, 1.0)
            };
            let tris = clipped_like(&mut rng, n, h);
            let searched =
                union_area_sweeping_from::<false>(&tris, &[], measure, h, &mut scratch, usize::MAX)
                    .0;
            let swept =
                union_area_sweeping_from::<false>(&tris, &[], measure, h, &mut scratch, 1).0;
            assert!(
                (searched - swept).abs() <= 1e-13,
                "case {case}: {n} triangles, searched {searched}, swept {swept}"
            );
        }
    }

    /// The grid's search lists every triangle whose bounds overlap the
    /// query box (brute force), with small and large triangles mixed so
    /// that the coarse levels are used, the fine level in either order.
    #[test]
    fn the_grid_finds_every_overlapping_triangle() {
        let mut rng = Rng::new(31);
        let mut grid = Grid::default();
        for case in 0..200 {
            let h = if case % 2 == 0 { 1.5 } else { 1.0 };
            let n = 1 + rng.below(600) as usize;
            let large_share = rng.unit();
            let tris: Vec<Tri> = (0..n)
                .filter_map(|_| {
                    let size = if rng.chance(large_share) {
                        rng.uniform(0.2, 2.0) * h
                    } else {
                        rng.uniform(0.001, 0.1) * h
                    };
                    let c = DVec2::new(rng.uniform(-h, h), rng.uniform(-h, h));
                    let mut corner = || {
                        (c + DVec2::new(rng.uniform(-size, size), rng.uniform(-size, size)))
                            .clamp(DVec2::splat(-h), DVec2::splat(h))
                    };
                    Tri::new(corner(), corner(), corner())
                })
                .collect();
            // In index order, and by area (as under a deep pile).
            if case % 4 < 2 {
                grid.build::<false>(&tris, h);
            } else {
                grid.build::<true>(&tris, h);
            }
            for _ in 0..20 {
                let a = DVec2::new(rng.uniform(-h, h), rng.uniform(-h, h));
                let b = a + DVec2::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)) * h;
                let (lo, hi) = (a.min(b), a.max(b));
                let mut found = vec![false; tris.len()];
                grid.for_each_near(
                    lo,
                    hi,
                    |_, _| true,
                    |j| {
                        found[j as usize] = true;
                        true
                    },
                );
                for (j, t) in tris.iter().enumerate() {
                    let overlaps =
                        t.hi.x >= lo.x && t.lo.x <= hi.x && t.hi.y >= lo.y && t.lo.y <= hi.y;
                    assert!(!overlaps || found[j], "case {case}: triangle {j} missed");
                }
            }
        }
    }

    /// [`Cover`] against a brute-force scan: span ends on a grid of
    /// sixteenths, the union tested at every grid point and between
    /// neighbours. Fed one span at a time (in random order, and in chains of
    /// decreasing start, which take the sorting path), its `reach` is the
    /// covered prefix of the spans so far and it says "whole" exactly when
    /// they cover `[0, 1]`; past [`Cover::TRACKED`] spans `reach` may lag
    /// but never exceeds the prefix. At the end, the pending spans with
    /// `(0, reach)` cover the same points as all the spans.
    #[test]
    fn the_cover_is_that_of_a_scan() {
        let mut rng = Rng::new(43);
        let grid_points = |spans: &[(f64, f64)]| -> Vec<bool> {
            (0..=32)
                .map(|k| {
                    let t = k as f64 / 32.0;
                    spans.iter().any(|&(s, e)| s <= t && t <= e)
                })
                .collect()
        };
        // The largest `g` on the grid with `[0, g]` in the union, 0 without
        // a span at 0.
        let prefix = |spans: &[(f64, f64)]| -> f64 {
            let inside = grid_points(spans);
            if !inside[0] {
                return 0.0;
            }
            let run = inside.iter().take_while(|&&x| x).count();
            ((run - 1) / 2 * 2) as f64 / 32.0
        };
        for case in 0..3000 {
            let n = if case % 10 == 9 {
                300
            } else {
                1 + rng.below(40) as usize
            };
            let mut spans: Vec<(f64, f64)> = (0..n)
                .map(|_| {
                    let s = rng.below(16) as f64 / 16.0;
                    let e = (s + (1 + rng.below(4)) as f64 / 16.0).min(1.0);
                    (s, e)
                })
                .collect();
            if case % 3 == 0 {
                spans.sort_by(|x, y| y.0.total_cmp(&x.0));
            }
            let mut cover = Cover::default();
            let mut pending = Vec::new();
            for m in 1..=n {
                let whole = cover.add(spans[m - 1], &mut pending);
                let scan = prefix(&spans[..m]);
                if m <= Cover::TRACKED {
                    assert_eq!(cover.reach, scan, "case {case}: {:?}", &spans[..m]);
                    assert_eq!(whole, scan >= 1.0, "case {case}");
                } else {
                    assert!(cover.reach <= scan, "case {case}");
                }
                if whole {
                    break;
                }
            }
            if cover.reach < 1.0 {
                let mut kept = pending.clone();
                if cover.reach > 0.0 {
                    kept.push((0.0, cover.reach));
                }
                assert_eq!(grid_points(&kept), grid_points(&spans), "case {case}");
            }
        }
    }

    /// [`Edges::has_reverse`] is the brute-force search for a triangle with
    /// the edge `b → a`, on triangles sharing corners (some given as
    /// `−0.0` where another has `0.0`, equal values of different bits),
    /// and the table holds each distinct directed edge once.
    #[test]
    fn reversed_edges_are_those_of_a_search() {
        let mut rng = Rng::new(5);
        let mut edges = Edges::default();
        let mut found = 0;
        for case in 0..200 {
            let corners: Vec<DVec2> = (0..3 + rng.below(12))
                .map(|_| {
                    let mut c = || match rng.below(4) {
                        0 => 0.0,
                        1 => -0.0,
                        _ => rng.uniform(-1.0, 1.0),
                    };
                    DVec2::new(c(), c())
                })
                .collect();
            let k = corners.len();
            // Around the table's threshold, on both sides.
            let n = Edges::FEWEST - 8 + rng.below(40) as usize;
            let mut tris: Vec<Tri> = Vec::new();
            // (Corners all on a line make no triangle: a bounded draw.)
            for _ in 0..20 * n {
                let pick = |rng: &mut Rng| corners[rng.below(k as u64) as usize];
                tris.extend(Tri::new(pick(&mut rng), pick(&mut rng), pick(&mut rng)));
                if tris.len() == n {
                    break;
                }
            }
            let n = tris.len();
            edges.build(&tris, 2.0);
            // One entry per distinct directed edge (copies are one).
            let mut distinct: Vec<(DVec2, DVec2)> = Vec::new();
            for t in &tris {
                for e in 0..3 {
                    if !distinct.contains(&t.edge(e)) {
                        distinct.push(t.edge(e));
                    }
                }
            }
            let entries = edges.slots.iter().filter(|&&e| e != Edges::EMPTY).count();
            let expected = if tris.len() < Edges::FEWEST {
                0
            } else {
                distinct.len()
            };
            assert_eq!(entries, expected, "case {case}");
            for t in &tris {
                for e in 0..3 {
                    let (a, b) = t.edge(e);
                    let searched = tris.iter().any(|u| (0..3).any(|f| u.edge(f) == (b, a)));
                    let expected = searched && n >= Edges::FEWEST;
                    assert_eq!(edges.has_reverse(&tris, a, b), expected, "case {case}");
                    found += usize::from(searched);
                }
            }
        }
        // The cases share corners enough for the search to find many.
        assert!(found > 1000, "{found} reversed edges");
    }

    /// A triangulated polygon — a jittered grid of squares, each split in
    /// two, sharing every inner edge bit for bit — covers the polygon: its
    /// union within the disk is [`polygon_disk_area`] of the outline, and
    /// within the square the outline's area. Only the outline's edges
    /// have no reverse, so nearly every edge is settled by the table.
    #[test]
    fn a_triangulated_polygon_is_its_outline() {
        use crate::kernel::disk::f64::polygon_disk_area;
        let mut rng = Rng::new(9);
        let mut scratch = UnionScratch::default();
        for case in 0..60 {
            let n = 1 + rng.below(12) as usize;
            let (x0, y0) = (rng.uniform(-1.4, 0.0), rng.uniform(-1.4, 0.0));
            let w = rng.uniform(0.1, 1.4 - x0.max(y0)) / n as f64;
            // Corner (i, j) of the grid; inner corners jittered.
            let corner: Vec<Vec<DVec2>> = (0..=n)
                .map(|i| {
                    (0..=n)
                        .map(|j| {
                            let inner = i > 0 && i < n && j > 0 && j < n;
                            let jitter = |rng: &mut Rng| {
                                if inner {
                                    rng.uniform(-0.3, 0.3) * w
                                } else {
                                    0.0
                                }
                            };
                            let x = x0 + i as f64 * w + jitter(&mut rng);
                            let y = y0 + j as f64 * w + jitter(&mut rng);
                            DVec2::new(x, y)
                        })
                        .collect()
                })
                .collect();
            let mut tris = Vec::new();
            for i in 0..n {
                for j in 0..n {
                    let [a, b, c, d] = [
                        corner[i][j],
                        corner[i + 1][j],
                        corner[i + 1][j + 1],
                        corner[i][j + 1],
                    ];
                    tris.extend(Tri::new(a, b, c));
                    tris.extend(Tri::new(a, c, d));
                }
            }
            assert_eq!(tris.len(), 2 * n * n);
            let outline = [corner[0][0], corner[n][0], corner[n][n], corner[0][n]];
            let (measure, half, expected) = if case % 2 == 0 {
                (Measure::Disk(1.0), 1.5, polygon_disk_area(1.0, &outline))
            } else {
                let d = corner[n][n] - corner[0][0];
                (Measure::Square, 1.5, d.x * d.y)
            };
            let area = union_area::<false>(&tris, &[], measure, half, &mut scratch).0;
            assert!(
                (area - expected).abs() <= 1e-14,
                "case {case}: {n}² squares, {area} against {expected}"
            );
        }
    }

    /// `n` translates of one triangle along its base, `δ` apart, large
    /// enough to sit on the grid's coarse levels, each edge covered by its
    /// neighbours together but by none alone: their union is the trapezoid
    /// swept by the triangle less a notch of area `δ²/2` between each two
    /// apexes (the tents' sides, of slopes ±2, meet `δ` below them):
    /// `½ + L − (n − 1)·δ²/2` with `L = (n − 1)·δ`.
    #[test]
    fn translates_along_the_base_are_the_swept_trapezoid_less_the_notches() {
        let mut scratch = UnionScratch::default();
        for (n, delta) in [(400, 1e-3), (1000, 3e-4), (50, 0.01)] {
            let tris: Vec<Tri> = (0..n)
                .map(|k| {
                    let x = k as f64 * delta;
                    Tri::new(
                        DVec2::new(-0.9 + x, -0.5),
                        DVec2::new(0.1 + x, -0.5),
                        DVec2::new(-0.4 + x, 0.5),
                    )
                    .expect("a triangle")
                })
                .collect();
            let l = (n - 1) as f64 * delta;
            let expected = 0.5 + l - (n - 1) as f64 * delta * delta / 2.0;
            let area = union_area::<false>(&tris, &[], Measure::Square, 1.0, &mut scratch).0;
            assert!(
                (area - expected).abs() <= 1e-12,
                "{n} translates {delta} apart: {area} against {expected}"
            );
        }
    }

    /// Nested images crossing one side of the square, more than enough to
    /// be swept: their union is the largest one, an answer that needs no
    /// union at all.
    #[test]
    fn nested_images_across_a_side_are_the_largest_one() {
        let h = 1.5;
        let n = 400;
        let tris: Vec<Tri> = (0..n)
            .map(|k| {
                let s = 0.3 + 0.6 * ((k * 7) % n) as f64 / n as f64;
                Tri::new(
                    DVec2::new(-s, -h),
                    DVec2::new(s, -h),
                    DVec2::new(0.1 * s, -h + 2.0 * s),
                )
                .expect("a triangle")
            })
            .collect();
        let largest = tris
            .iter()
            .copied()
            .max_by(|a, b| (a.hi.x - a.lo.x).total_cmp(&(b.hi.x - b.lo.x)))
            .expect("some");
        let mut scratch = UnionScratch::default();
        let all = union_area::<false>(&tris, &[], Measure::Disk(1.0), h, &mut scratch).0;
        let one = union_area::<false>(&[largest], &[], Measure::Disk(1.0), h, &mut scratch).0;
        assert!(one > 0.1);
        assert!((all - one).abs() <= 1e-14, "{all} against {one}");
    }

    /// A pile with holes: `n` random triangles about `[−0.3 h, 0.3 h]²`
    /// (small against the grid's cells, as images piled over a light are),
    /// sized for about `depth` layers (a random triangle in a square of
    /// side `2 s` has a mean area of about `0.3 s²`, and the pile's bounds
    /// are about `(0.9 h)²`), a fifth sharing an edge with the one before
    /// (reversed, as adjacent images have).
    fn deep_pile(rng: &mut Rng, n: usize, depth: f64, h: f64) -> Vec<Tri> {
        let size = (depth * 0.9 * 0.9 / (0.3 * n as f64)).sqrt();
        let mut tris: Vec<Tri> = Vec::new();
        while tris.len() < n {
            let c = DVec2::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)) * h;
            let shared = rng.chance(0.2);
            let mut corner = || {
                (c + DVec2::new(rng.uniform(-size, size), rng.uniform(-size, size)) * h)
                    .clamp(DVec2::splat(-h), DVec2::splat(h))
            };
            let (a, b) = match tris.last() {
                Some(t) if shared => (t.v[1], t.v[0]),
                _ => (corner(), corner()),
            };
            tris.extend(Tri::new(a, b, corner()));
        }
        tris
    }

    /// A pile like [`deep_pile`]'s on a lattice of step `h / 128`: corners
    /// on the raster's cell corners or halfway between them, edges along
    /// its cell lines (right triangles with axis-parallel legs), quads cut
    /// along a diagonal (two images sharing an edge), and edges lying on
    /// part of an earlier triangle's edge (T-junctions, overlapping
    /// collinear edges either way round) — the ties a raster's margins
    /// must hold against.
    fn lattice_pile(rng: &mut Rng, n: usize, depth: f64, h: f64) -> Vec<Tri> {
        let g = h / 128.0;
        // Corners `a` in the square `±38 g`, legs for about `depth` layers
        // over it grown by a leg (a triangle's mean area is about
        // `0.35 legs²`; the triangles along earlier edges spread the
        // pile, hence `0.25`).
        let root = depth.sqrt();
        let legs = 77.0 * root / ((0.25 * n as f64).sqrt() - root);
        let on = |v: DVec2| v.clamp(DVec2::splat(-h), DVec2::splat(h));
        let mut tris: Vec<Tri> = Vec::new();
        while tris.len() < n {
            let a = DVec2::new(rng.below(77) as f64 - 38.0, rng.below(77) as f64 - 38.0);
            let leg = |rng: &mut Rng| (rng.uniform(0.5, 1.5) * legs).round().max(1.0) * rng.sign();
            let (s, t) = (leg(rng), leg(rng));
            let corners: Vec<[DVec2; 3]> = match rng.below(4) {
                0 => vec![[a, a + DVec2::new(s, 0.0), a + DVec2::new(0.0, t)]],
                1 => {
                    let c = a + DVec2::new(s, t);
                    vec![
                        [a, a + DVec2::new(s, 0.0), c],
                        [c, a + DVec2::new(0.0, t), a],
                    ]
                }
                2 if !tris.is_empty() => {
                    // Along an earlier edge, shifted by half of it.
                    let k = rng.below(tris.len() as u64) as usize;
                    let (p, q) = tris[k].edge(rng.below(3) as usize);
                    let (p, q) = (p / g, q / g);
                    let half = (q - p) * 0.5;
                    let (p, q) = if rng.chance(0.5) {
                        (p + half, q + half)
                    } else {
                        (q - half, p - half)
                    };
                    vec![[p, q, p + DVec2::new(s, t)]]
                }
                _ => vec![[a, a + DVec2::new(s, leg(rng)), a + DVec2::new(leg(rng), t)]],
            };
            for [p, q, r] in corners {
                tris.extend(Tri::new(on(p * g), on(q * g), on(r * g)));
            }
        }
        tris.truncate(n);
        tris
    }

    /// Both kinds of pile, by case number.
    fn pile(case: usize, rng: &mut Rng, n: usize, depth: f64, h: f64) -> Vec<Tri> {
        if case % 4 < 2 {
            deep_pile(rng, n, depth, h)
        } else {
            lattice_pile(rng, n, depth, h)
        }
    }

    /// Case `case` of the deep piles the [`Interior`] tests run on: its
    /// square's half-width (`1.5` in even cases, `1` in odd ones) and a
    /// [`pile`] 3 to 6 deep of [`Interior::FEWEST`] triangles and up to
    /// `more` more.
    fn deep_case(case: usize, rng: &mut Rng, more: u64) -> (f64, Vec<Tri>) {
        let h = if case % 2 == 0 { 1.5 } else { 1.0 };
        let n = Interior::FEWEST + rng.below(more) as usize;
        let depth = rng.uniform(3.0, 6.0);
        (h, pile(case, rng, n, depth, h))
    }

    /// Whether some row of blocks along the course has every block within
    /// the walk's margin of the whole course's `x` range marked, so that
    /// [`Interior::course_covered`] leaves the cells of that row out (a
    /// wider walk than its own, from the course's start in each row).
    fn some_blocks_cover(interior: &Interior, c: &Course) -> bool {
        let (lo, hi) = (c.lo.min(c.hi), c.lo.max(c.hi));
        let level = Course {
            lo: DVec2::new(lo.x, c.lo.y),
            hi: DVec2::new(hi.x, c.lo.y),
            rows: c.rows,
        }
        .in_blocks();
        (level.rows.0..=level.rows.1).any(|r| {
            let row = Course {
                rows: (r, r),
                ..level
            };
            walk_covers(&row, interior.n / Interior::BLOCK, |k| {
                interior.block_row(k)
            })
        })
    }

    /// Whether `p` is strictly inside `t` (exactly).
    fn strictly_inside(t: &Tri, p: DVec2) -> bool {
        (0..3).all(|k| {
            let (a, b) = t.edge(k);
            orient2d(a, b, p) == Sign::Positive
        })
    }

    /// [`Interior`] against exact predicates: all four corners of a marked
    /// cell are strictly inside one triangle, and an edge it says is
    /// covered has each of 65 points along it strictly inside a triangle
    /// other than its own — on random piles and on lattice piles, whose
    /// corners and edges fall on the cells' corners and lines (there a
    /// margin of zero marks cells touching an edge: seen to fail). For
    /// every edge, the walk a row of blocks at a time answers as the walk
    /// over the cells from the first row to the last.
    #[test]
    fn marked_cells_lie_inside_a_triangle() {
        let mut rng = Rng::new(41);
        let mut interior = Interior::default();
        let (mut marked, mut covered, mut by_blocks, mut partly) = (0, 0, 0, 0);
        for case in 0..24 {
            let (h, tris) = deep_case(case, &mut rng, 400);
            assert!(interior.build(&tris, h), "case {case}: not deep");
            let at = |k: usize| -h + k as f64 * interior.w;
            for r in 0..interior.n {
                for k in 0..interior.n {
                    if !all_set(interior.row(r), k, k) {
                        continue;
                    }
                    marked += 1;
                    // One cell in seven, to keep the test quick.
                    if marked % 7 != 0 {
                        continue;
                    }
                    let corners = [(k, r), (k + 1, r), (k, r + 1), (k + 1, r + 1)]
                        .map(|(x, y)| DVec2::new(at(x), at(y)));
                    assert!(
                        tris.iter()
                            .any(|t| corners.iter().all(|&p| strictly_inside(t, p))),
                        "case {case}: cell ({k}, {r}) inside no triangle"
                    );
                }
            }
            for (i, t) in tris.iter().enumerate() {
                for e in 0..3 {
                    let (a, b) = t.edge(e);
                    let Some(course) = interior.course(a, b) else {
                        continue;
                    };
                    let cells = interior.cells_cover(&course);
                    assert_eq!(
                        interior.course_covered(&course),
                        cells,
                        "case {case}: an edge of {i}, row of blocks by row of blocks"
                    );
                    if !cells {
                        continue;
                    }
                    covered += 1;
                    if interior.blocks_cover(&course) {
                        by_blocks += 1;
                    } else if some_blocks_cover(&interior, &course) {
                        partly += 1;
                    }
                    for s in 0..=64 {
                        let p = a + (b - a) * (f64::from(s) / 64.0);
                        assert!(
                            tris.iter()
                                .enumerate()
                                .any(|(j, u)| j != i && strictly_inside(u, p)),
                            "case {case}: an edge of {i} uncovered at {s}/64"
                        );
                    }
                }
            }
        }
        // Enough cells and edges for the checks to mean something, both
        // ways of covering among them.
        assert!(
            marked > 100_000
                && covered > 2_000
                && by_blocks > 500
                && covered - by_blocks > 500
                && partly > 200,
            "{marked} cells, {covered} edges, {by_blocks} by blocks, {partly} partly"
        );
    }

    /// The blocks [`Interior`] lists as all marked are those whose cells
    /// are all marked, counted cell by cell.
    #[test]
    fn full_blocks_are_those_all_marked() {
        let mut rng = Rng::new(47);
        let mut interior = Interior::default();
        let (mut full, mut blocks) = (0, 0);
        for case in 0..12 {
            let (h, tris) = deep_case(case, &mut rng, 1200);
            assert!(interior.build(&tris, h), "case {case}: not deep");
            const B: usize = Interior::BLOCK;
            for br in 0..interior.n / B {
                for bk in 0..interior.n / B {
                    let cells = (B * br..B * br + B)
                        .flat_map(|r| (B * bk..B * bk + B).map(move |k| (r, k)))
                        .filter(|&(r, k)| all_set(interior.row(r), k, k))
                        .count();
                    let listed = all_set(interior.block_row(br), bk, bk);
                    assert_eq!(listed, cells == B * B, "case {case}: block ({bk}, {br})");
                    full += usize::from(listed);
                    blocks += 1;
                }
            }
        }
        assert!(
            full > blocks / 20 && full < blocks,
            "{full} of {blocks} blocks"
        );
    }

    /// Dropping the edges [`Interior`] covers, and leaving out of the other
    /// edges' searches the cells whose passage it covers
    /// ([`searched_cells`]), leaves the area as it is, bit for bit, on deep
    /// piles with holes, random and on a lattice (both measures); most
    /// edges are dropped, and the searched ones leave out more than one
    /// cell each on average.
    #[test]
    fn the_interior_drops_edges_and_keeps_the_area() {
        let mut rng = Rng::new(43);
        let mut scratch = UnionScratch::default();
        let (mut dropped, mut edges) = (0, 0);
        let (mut searched, mut left_out) = (0, 0);
        for case in 0..60 {
            let (h, tris) = deep_case(case, &mut rng, 1200);
            let n = tris.len();
            // The disk's measure on the wider square.
            let measure = if h > 1.0 {
                Measure::Disk(1.0)
            } else {
                Measure::Square
            };
            let with = union_area::<false>(&tris, &[], measure, h, &mut scratch).0;
            assert!(scratch.interior.n > 0, "case {case}: not deep");
            edges += 3 * n;
            dropped += tris
                .iter()
                .flat_map(|t| (0..3).map(|e| t.edge(e)))
                .filter(|&(a, b)| scratch.interior.covers(a, b))
                .count();
            let (grid, interior) = (&scratch.grid, &scratch.interior);
            for (a, b) in tris.iter().flat_map(|t| (0..3).map(|e| t.edge(e))) {
                if !interior.covers(a, b) {
                    searched += 1;
                    let cells = grid.fine.range(a.min(b), a.max(b), h);
                    let mut flags = Vec::new();
                    searched_cells(&grid.fine, interior, (a, b), cells, h, &mut flags, |_| {
                        left_out += 1;
                        false
                    });
                }
            }
            let without =
                union_area_in::<false, false>(&tris, &[], measure, h, &mut scratch, SWEEP_FROM).0;
            assert_eq!(
                with.to_bits(),
                without.to_bits(),
                "case {case}: {with} against {without}"
            );
            assert!(with > 0.0, "case {case}");
        }
        assert!(2 * dropped > edges, "{dropped} of {edges} edges dropped");
        // The searched edges took more than one covered passage each on
        // average, so the bits above were compared with that at work.
        assert!(
            left_out > searched,
            "{left_out} covered passages over {searched} searched edges"
        );
    }

    /// The union's area with the search `search`, and its bound with the
    /// weights `w` (one per edge).
    fn area_by(
        search: Search,
        tris: &[Tri],
        w: &[[f64; 3]],
        measure: Measure,
        h: f64,
        scratch: &mut UnionScratch,
    ) -> [(f64, f64); 2] {
        scratch.search = search;
        [
            union_area::<false>(tris, w, measure, h, scratch),
            union_area::<true>(tris, w, measure, h, scratch),
        ]
    }

    /// Homothets of one triangle: `n` copies scaled by `1 + k s` about
    /// `centre` (inside: nested; outside: stacked layers seen from a
    /// receiver), clamped to the square.
    fn homothets(t: [DVec2; 3], centre: DVec2, n: usize, s: f64, h: f64) -> Vec<Tri> {
        (0..n)
            .filter_map(|k| {
                let f = 1.0 + k as f64 * s;
                let m =
                    |v: DVec2| (centre + (v - centre) * f).clamp(DVec2::splat(-h), DVec2::splat(h));
                Tri::new(m(t[0]), m(t[1]), m(t[2]))
            })
            .collect()
    }

    /// A convex polygon (a circle's chords) as a fan of `n` slivers from
    /// `apex`, every sliver sharing its corners with its neighbours,
    /// clamped to the square.
    fn fan(apex: DVec2, centre: DVec2, r: f64, n: usize, h: f64) -> Vec<Tri> {
        let on = |v: DVec2| v.clamp(DVec2::splat(-h), DVec2::splat(h));
        let ring: Vec<DVec2> = (0..n)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / n as f64;
                on(centre + DVec2::new(a.cos(), a.sin()) * r)
            })
            .collect();
        (0..n)
            .filter_map(|k| Tri::new(on(apex), ring[k], ring[(k + 1) % n]))
            .collect()
    }

    /// Case `case` of the families the two searches are compared on, and
    /// its square's half-width: random piles deep and shallow, on a
    /// lattice, triangles along the square's sides, nested, stacked
    /// (homothets about a point outside), exact and near-coincident copies,
    /// and fans of slivers.
    fn family(case: usize, rng: &mut Rng) -> (f64, Vec<Tri>) {
        let h = if case % 2 == 0 { 1.5 } else { 1.0 };
        let corner = |rng: &mut Rng| DVec2::new(rng.uniform(-h, h), rng.uniform(-h, h));
        match case % 9 {
            0 => deep_case(case, rng, 600),
            1 => {
                let n = 1 + rng.below(200) as usize;
                let depth = rng.uniform(0.3, 2.0);
                (h, pile(case / 9, rng, n, depth, h))
            }
            2 => {
                let n = 1 + rng.below(150) as usize;
                (h, clipped_like(rng, n, h))
            }
            3 => {
                let t = [corner(rng), corner(rng), corner(rng)].map(|v| v * 0.3);
                let c = (t[0] + t[1] + t[2]) / 3.0;
                (
                    h,
                    homothets(
                        t,
                        c,
                        50 + rng.below(300) as usize,
                        rng.uniform(1e-4, 1e-2),
                        h,
                    ),
                )
            }
            4 => {
                let t = [corner(rng), corner(rng), corner(rng)];
                let outside = DVec2::new(rng.uniform(2.0, 4.0) * h, rng.uniform(-h, h));
                let n = 50 + rng.below(300) as usize;
                (h, homothets(t, outside, n, rng.uniform(1e-5, 1e-3), h))
            }
            5 => {
                let t = [corner(rng), corner(rng), corner(rng)];
                let mut tris: Vec<Tri> = (0..1 + rng.below(40))
                    .filter_map(|_| Tri::new(t[0], t[1], t[2]))
                    .collect();
                let more = rng.below(20) as usize;
                tris.extend(clipped_like(rng, more, h));
                (h, tris)
            }
            6 => {
                let t = [corner(rng), corner(rng), corner(rng)];
                let step = rng.uniform(1e-15, 1e-9);
                let tris = (0..2 + rng.below(100))
                    .filter_map(|k| {
                        let d = DVec2::new(step * k as f64, 0.0);
                        Tri::new(t[0] + d, t[1] + d, t[2] + d)
                    })
                    .collect();
                (h, tris)
            }
            7 => {
                let apex = corner(rng) * rng.uniform(0.0, 2.0);
                let c = corner(rng) * 0.5;
                (
                    h,
                    fan(
                        apex,
                        c,
                        rng.uniform(0.1, 3.0),
                        3 + rng.below(2000) as usize,
                        h,
                    ),
                )
            }
            _ => {
                // Two fans and a pile over them.
                let mut tris = fan(corner(rng), corner(rng) * 0.3, 0.7, 300, h);
                tris.extend(fan(corner(rng), corner(rng) * 0.3, 0.5, 200, h));
                tris.extend(pile(case / 9, rng, 200, 1.5, h));
                (h, tris)
            }
        }
    }

    /// The tree's search gives the grid's area and bound bit for bit, on both measures, over every family of
    /// [`family`] (the bound since [`cut_errors`] takes the largest error
    /// among spans starting at one point: before, the first found).
    #[test]
    fn the_tree_search_gives_the_grid_area_bit_for_bit() {
        let mut rng = Rng::new(61);
        let mut scratch = UnionScratch::default();
        let mut nonzero = 0;
        for case in 0..270 {
            let (h, tris) = family(case, &mut rng);
            let w: Vec<[f64; 3]> = tris
                .iter()
                .map(|t| {
                    let mut w = [0.0; 3];
                    for (k, wk) in w.iter_mut().enumerate() {
                        let (a, b) = t.edge(k);
                        *wk = 1e-16 * rng.unit() * (b - a).length();
                    }
                    w
                })
                .collect();
            for measure in [Measure::Disk(1.0), Measure::Square] {
                let grid = area_by(Search::Grid, &tris, &w, measure, h, &mut scratch);
                for search in [Search::Tree] {
                    let other = area_by(search, &tris, &w, measure, h, &mut scratch);
                    for (g, t) in grid.iter().zip(&other) {
                        assert_eq!(
                            g.0.to_bits(),
                            t.0.to_bits(),
                            "case {case}, {} triangles, {measure:?}: grid {g:?}, {search:?} {t:?}",
                            tris.len()
                        );
                        assert_eq!(
                            g.1.to_bits(),
                            t.1.to_bits(),
                            "case {case}: bounds {} and {}",
                            g.1,
                            t.1
                        );
                    }
                }
                nonzero += usize::from(grid[0].0 > 0.0);
            }
        }
        assert!(nonzero > 500, "{nonzero} unions of positive area");
    }

    /// The area of the union of `tris` by brute force: the plane cut into
    /// vertical slabs at every corner and every crossing of two edges, in
    /// each of which the union's section is a fixed set of trapezoids, so
    /// its length is linear in `x` and the midpoint rule is exact.
    fn slab_area(tris: &[Tri]) -> f64 {
        let edges: Vec<(DVec2, DVec2)> = tris
            .iter()
            .flat_map(|t| (0..3).map(|k| t.edge(k)))
            .collect();
        let mut xs: Vec<f64> = tris.iter().flat_map(|t| t.v.map(|v| v.x)).collect();
        for (i, &(a, b)) in edges.iter().enumerate() {
            for &(c, d) in &edges[i + 1..] {
                let (r, s) = (b - a, d - c);
                let den = r.perp_dot(s);
                if den == 0.0 {
                    continue;
                }
                let t = (c - a).perp_dot(s) / den;
                let u = (c - a).perp_dot(r) / den;
                if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u) {
                    xs.push(a.x + t * r.x);
                }
            }
        }
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        let mut area = 0.0;
        let mut sections = Vec::new();
        for w in xs.windows(2) {
            let x = 0.5 * (w[0] + w[1]);
            sections.clear();
            for t in tris {
                let ys: Vec<f64> = (0..3)
                    .filter_map(|k| {
                        let (a, b) = t.edge(k);
                        let (lo, hi) = (a.x.min(b.x), a.x.max(b.x));
                        (lo < x && x < hi).then(|| a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x))
                    })
                    .collect();
                if ys.len() == 2 {
                    sections.push((ys[0].min(ys[1]), ys[0].max(ys[1])));
                }
            }
            sections.sort_by(|p, q| p.0.total_cmp(&q.0));
            let (mut length, mut reach) = (0.0, f64::NEG_INFINITY);
            for &(lo, hi) in &sections {
                if hi > reach {
                    length += hi - lo.max(reach);
                    reach = hi;
                }
            }
            area += (w[1] - w[0]) * length;
        }
        area
    }

    /// The area of `∪ tris ∩ unit disk` by inclusion–exclusion: each
    /// subset's intersection a convex polygon (the triangles clipped by
    /// each other), its area within the disk by `polygon_disk_area`.
    fn inclusion_exclusion_disk_area(tris: &[Tri]) -> f64 {
        use crate::kernel::disk::f64::polygon_disk_area;
        let n = tris.len();
        let mut total = 0.0;
        for set in 1_u32..1 << n {
            let first = set.trailing_zeros() as usize;
            let mut poly: Vec<DVec2> = tris[first].v.to_vec();
            for (k, t) in tris.iter().enumerate().skip(first + 1) {
                if set >> k & 1 == 0 {
                    continue;
                }
                for e in 0..3 {
                    let (a, b) = t.edge(e);
                    let side = |p: DVec2| (b - a).perp_dot(p - a);
                    let mut out = Vec::new();
                    for i in 0..poly.len() {
                        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
                        let (sp, sq) = (side(p), side(q));
                        if sp >= 0.0 {
                            out.push(p);
                        }
                        if (sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0) {
                            out.push(p + (q - p) * (sp / (sp - sq)));
                        }
                    }
                    poly = out;
                }
            }
            let sign = if set.count_ones() % 2 == 1 { 1.0 } else { -1.0 };
            total += sign * polygon_disk_area(1.0, &poly);
        }
        total
    }

    /// The union's area (both searches) against brute force on small
    /// piles: random, nested, exact and near-coincident copies, stacked
    /// layers, slivers of a fan. Within the square, the slab
    /// decomposition (up to 60 triangles); within the unit disk,
    /// inclusion–exclusion (up to 7).
    #[test]
    fn the_union_is_the_brute_force_area_on_small_piles() {
        let mut rng = Rng::new(67);
        let mut scratch = UnionScratch::default();
        for case in 0..600 {
            let disk = case % 3 == 0;
            let (h, most) = if disk { (1.5, 7) } else { (1.0, 60) };
            let n = 1 + rng.below(most) as usize;
            let corner = |rng: &mut Rng| DVec2::new(rng.uniform(-h, h), rng.uniform(-h, h));
            let t = [corner(&mut rng), corner(&mut rng), corner(&mut rng)];
            let mut tris: Vec<Tri> = match case % 5 {
                0 => {
                    let depth = rng.uniform(0.5, 4.0);
                    pile(case, &mut rng, n, depth, h)
                }
                1 => {
                    let c = (t[0] + t[1] + t[2]) / 3.0;
                    homothets(t, c, n, rng.uniform(1e-3, 0.3), h)
                }
                2 => {
                    // Exact copies and copies 1e-12 apart, some reversed.
                    (0..n)
                        .filter_map(|k| {
                            let d = DVec2::new(1e-12 * (k % 3) as f64, 0.0);
                            if k % 2 == 0 {
                                Tri::new(t[0] + d, t[1] + d, t[2] + d)
                            } else {
                                Tri::new(t[2], t[1], t[0])
                            }
                        })
                        .collect()
                }
                3 => {
                    let outside = DVec2::new(rng.uniform(2.0, 4.0) * h, rng.uniform(-h, h));
                    homothets(t.map(|v| v * 0.5), outside, n, rng.uniform(1e-4, 1e-2), h)
                }
                _ => fan(
                    corner(&mut rng),
                    corner(&mut rng) * 0.3,
                    rng.uniform(0.2, 1.2),
                    n.max(3),
                    h,
                ),
            };
            tris.truncate(most as usize);
            let expected = if disk {
                inclusion_exclusion_disk_area(&tris)
            } else {
                slab_area(&tris)
            };
            let measure = if disk {
                Measure::Disk(1.0)
            } else {
                Measure::Square
            };
            for search in [Search::Grid, Search::Tree] {
                scratch.search = search;
                let area = union_area::<false>(&tris, &[], measure, h, &mut scratch).0;
                assert!(
                    (area - expected).abs() <= 1e-11,
                    "case {case} ({search:?}): {} triangles, {area} against {expected}",
                    tris.len()
                );
            }
        }
    }
}
