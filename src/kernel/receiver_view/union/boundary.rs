//! The walk over every triangle's edges that keeps the pieces of the
//! union's boundary: what settles an edge before any search, the search
//! (over the grid or the tree) of the triangles that may cover it, and the
//! pieces it leaves uncovered.

use super::bound::{covered_span_bounded, cut_errors, outside_deep, Deep};
use super::cover::Cover;
use super::grid::{Grid, Level, Unbuilt};
use super::interior::Interior;
use super::shared_edges::Edges;
use super::sides::{Side, SideSet};
use super::span::covered_span;
use super::sum::{add_uncovered, Sum};
use super::tree::{Ray, Spans, Tree};
use super::tri::{Measure, Tri};
use glam::DVec2;

/// [`union_area`](super::union_area), with
/// `DEEP` whether [`Interior`] is built (and the grid lists the fine level
/// by area). The helpers it calls per edge, per candidate and per triangle
/// are `#[inline(always)]`, else the compiler keeps them out of line in its
/// two copies (chosen by measurement: see benches/README.md § The union's
/// constants and its two copies of the loop); so is it, in
/// [`union_area`](super::union_area) (measured: see benches/README.md §
/// The union's search).
///
/// The bound (`B`) sums: each edge's allowance unless it is shared (an
/// edge and its exact reverse move together, both sides covered) or
/// covered whole by the raster with a margin far above the images'
/// `reach` — the exact union's boundary lies within those bands of the
/// computed one — scaled by the measure of the parameters of `[−x, 1 +
/// x]` (`x = reach / |e|`, the band's run past the ends) that the
/// triangles its search found do not hold at least `2 reach` inside
/// ([`Deep`]; the raster's covered passages, where its margin is far above
/// the reach, whole): there the band lies inside both the computed union
/// and the exact one, so the two cannot differ in it (see the
/// [certified bound](crate::kernel::receiver_view#the-certified-bound));
/// for each piece kept on the boundary, the error of its ends where they
/// are cuts by other edges (`|e| Δt`: the pieces' areas move by at most
/// the distance their ends move, the disk's and the square's pieces being
/// 1-Lipschitz in their ends in the view's coordinates) and the area
/// kernel's (`3 ε` a piece for the unit disk; the square's `½ a × b`
/// likewise); and the compensated sum's (`2 ε` of the sum and `4 n ε²` of
/// the terms' magnitudes).
#[inline(always)]
pub(super) fn union_area_in<const DEEP: bool, const B: bool>(
    tris: &[Tri],
    (weights, reach): (&[[f64; 3]], f64),
    measure: Measure,
    half: f64,
    scratch: &mut UnionScratch,
    sweep_from: usize,
) -> (f64, f64) {
    scratch.edges.build(tris, half);
    let UnionScratch {
        grid,
        unbuilt,
        edges,
        stamp,
        intervals,
        sides,
        interior,
        searched,
        bounded,
        deep,
        ..
    } = scratch;
    let interior = &*interior;
    let settle = Settle {
        sides,
        edges,
        interior,
    };
    let mut edge_id = 0_u32;
    // The grid is built for the first edge searched but the first few
    // among many triangles ([`Unbuilt`]): where the side sweep and the
    // table of shared edges settle all but a few edges (a convex polygon
    // given as a fan of slivers), it is never built.
    let mut built = false;
    let mut unbuilt_left = if DEEP || tris.len() < Unbuilt::FROM {
        0
    } else {
        Unbuilt::SEARCHES
    };
    let search = |i: usize, a: DVec2, b: DVec2, sum: &mut Sum, bound: &mut f64| {
        let (lo, hi) = (a.min(b), a.max(b));
        intervals.clear();
        let band = Deep::of(reach, (b - a).length());
        if B {
            bounded.clear();
            deep.clear();
        }
        let mut cover = Cover::default();
        let mut whole = false;
        if !DEEP && unbuilt_left > 0 {
            unbuilt_left -= 1;
            if unbuilt.find(tris, half, (lo, hi), i) {
                for &(_, _, j) in &unbuilt.order {
                    let found = (band, (&mut *bounded, &mut *deep));
                    if let Some(span) = span_of::<B>(a, b, (i, j as usize), tris, (lo, hi), found) {
                        whole = cover.add(span, intervals);
                        if whole {
                            break;
                        }
                    }
                }
                add_pieces((a, b), (whole, cover.reach), intervals, measure, sum);
                return edge_bound::<B>((a, b), whole, bound, (bounded, deep), band);
            }
            // Too many to sort: the grid, from here on.
            unbuilt_left = 0;
        }
        if !built {
            if DEEP {
                // In the raster's order by area, without the triangles it
                // left out where there is no bound (see [`walk_edges`]).
                let left_out = |j: usize| !B && interior.left_out(j);
                grid.build_without::<true>(tris, half, left_out, interior.by_area());
            } else {
                grid.build::<false>(tris, half);
            }
            stamp.clear();
            stamp.resize(tris.len(), u32::MAX);
            built = true;
        }
        let grid = &*grid;
        // A covered passage lies deep enough where the raster's margin
        // holds the band (see [`walk_edges`]).
        let passage_deep = B && reach < 0.25 * interior.margin();
        let (fx0, fy0, fx1, fy1) = grid.fine.range(lo, hi, half);
        if DEEP {
            let cells = (fx0, fy0, fx1, fy1);
            whole = searched_cells(&grid.fine, interior, (a, b), cells, half, searched, |u| {
                if B {
                    // A covered passage: its ends are never a piece's.
                    bounded.push([u.0, u.1, 0.0, 0.0]);
                    if passage_deep {
                        deep.push(u);
                    }
                }
                cover.add(u, intervals)
            });
        }
        let searched = &*searched;
        let keep = |x: usize, y: usize| !DEEP || searched[(y - fy0) * (fx1 - fx0 + 1) + x - fx0];
        grid.for_each_near(lo, hi, keep, |j| {
            let j = j as usize;
            if j == i || stamp[j] == edge_id {
                return true;
            }
            stamp[j] = edge_id;
            // Spans that together cover the edge settle it: nothing of it
            // is on the boundary. Most edges are covered whole, and their
            // search ends at the span that completes the cover (see
            // [`Cover`]).
            if let Some(span) = span_of::<B>(a, b, (i, j), tris, (lo, hi), (band, (bounded, deep)))
            {
                whole = cover.add(span, intervals);
            }
            !whole
        });
        edge_id = edge_id.wrapping_add(1);
        add_pieces((a, b), (whole, cover.reach), intervals, measure, sum);
        edge_bound::<B>((a, b), whole, bound, (bounded, deep), band)
    };
    let bands = (weights, reach);
    walk_edges::<DEEP, B>(tris, bands, measure, half, settle, sweep_from, search)
}

/// [`union_area_in`] with the edges' searches in a [`Tree`] instead of the
/// grids: the same spans' union for every edge (the tree leaves out only
/// triangles whose spans lie inside the cover already found; see
/// [`tree`](super::tree)), so the same pieces, summed in the same order:
/// the same area, bit for bit, and the same bound where the images' reach
/// is unknown (infinite). With a known reach, the bands each search's
/// spans hold deep inside drop out, and the spans found before an edge is
/// covered whole differ between the searches: each bound holds, not
/// always the same bits. The side sweep, the table of
/// shared edges and the raster of a deep pile settle the same edges first
/// ([`walk_edges`]).
pub(super) fn union_area_tree<const DEEP: bool, const B: bool>(
    tris: &[Tri],
    (weights, reach): (&[[f64; 3]], f64),
    measure: Measure,
    half: f64,
    scratch: &mut UnionScratch,
    sweep_from: usize,
) -> (f64, f64) {
    scratch.edges.build(tris, half);
    let UnionScratch {
        tree,
        spans,
        edges,
        sides,
        interior,
        bounded,
        deep,
        ..
    } = scratch;
    let settle = Settle {
        sides,
        edges,
        interior,
    };
    // Built for the first edge searched (see [`union_area_in`]).
    let mut built = false;
    let search = |i: usize, a: DVec2, b: DVec2, sum: &mut Sum, bound: &mut f64| {
        if !built {
            tree.build(tris, half);
            built = true;
        }
        let band = Deep::of(reach, (b - a).length());
        if B {
            bounded.clear();
            deep.clear();
        }
        let (lo, hi) = (a.min(b), a.max(b));
        spans.clear();
        let whole = tree.search(&Ray::new(a, b), spans, |j| {
            span_of::<B>(
                a,
                b,
                (i, j as usize),
                tris,
                (lo, hi),
                (band, (&mut *bounded, &mut *deep)),
            )
        });
        if !whole {
            add_uncovered(a, b, &mut spans.list, measure, sum);
        }
        edge_bound::<B>((a, b), whole, bound, (bounded, deep), band)
    };
    let bands = (weights, reach);
    walk_edges::<DEEP, B>(tris, bands, measure, half, settle, sweep_from, search)
}

/// After an edge's search in [`union_area_in`], unless it is covered
/// `whole`: its pieces outside the pending spans `intervals` and the
/// covered start `[0, reach]` ([`Cover`]; as one interval: the same
/// pieces), added to `sum`.
#[inline(always)]
fn add_pieces(
    (a, b): (DVec2, DVec2),
    (whole, reach): (bool, f64),
    intervals: &mut Vec<(f64, f64)>,
    measure: Measure,
    sum: &mut Sum,
) {
    if !whole {
        if reach > 0.0 {
            intervals.push((0.0, reach));
        }
        add_uncovered(a, b, intervals, measure, sum);
    }
}

/// With `B`, after an edge's search: the cut errors of its pieces on the
/// boundary (none when it is covered `whole`) added to `bound`, and the
/// measure of its band's parameters that the spans found do not hold deep
/// inside ([`outside_deep`]); 0 without `B`.
#[inline(always)]
fn edge_bound<const B: bool>(
    (a, b): (DVec2, DVec2),
    whole: bool,
    bound: &mut f64,
    (bounded, deep): Found<'_>,
    band: Deep,
) -> f64 {
    if !B {
        return 0.0;
    }
    if !whole {
        *bound += cut_errors(a, b, bounded);
    }
    outside_deep(deep, band.x)
}

/// What settles an edge before any search: the sweep of the square's
/// sides, the table of shared edges, and (`DEEP`) the raster of a deep
/// pile.
struct Settle<'s> {
    sides: &'s mut [SideSet; 4],
    edges: &'s Edges,
    interior: &'s Interior,
}

/// The loop of both searches over every triangle's edges: each edge on a
/// swept side of the square goes to its side's sweep, an edge whose
/// reverse is another triangle's or (`DEEP`) that the raster covers is
/// dropped, and every other edge goes to `search`, which adds its pieces
/// on the boundary to the sum (and with `B`, their cuts' errors to the
/// bound); with `B`, the bound's allowances of [`union_area_in`] too.
///
/// Without `B`, a triangle the raster left out ([`Interior::left_out`]:
/// its bounds' cells were marked by others) takes no part: its edges are
/// neither asked about nor searched, and the grid of [`union_area_in`]
/// lists it in no cell. That changes no bit of the area. Every point of
/// such a triangle `t` lies at least `μ / 2` inside a triangle `j` the
/// raster kept (`μ` its [`margin`](Interior::margin)), and `j` is not
/// the searched edge's own, whose points are on its boundary. So no
/// point of `t` is on the union's boundary, and none of its edges has a
/// piece there (an edge on a side of the square has none of its points
/// that deep, so `t` has no edge the sides' sweep takes). And on another
/// triangle's edge `e`, `t`'s span lies inside the union of the spans the
/// search finds without `t`: each point of it lies within `2⁻³³` of the
/// half-width of `t` (a span's points do, of their triangle:
/// [`credible`](super::span::credible)), against `μ / 2 ≥ 2⁻³⁰·⁵` of it,
/// so at least `0.4 μ` inside some such `j`, whose bounds meet `e`'s
/// there, and whose span then holds the point's parameter with at least
/// `2⁻³³` of the range to spare (the argument of [`Interior`]), far above
/// the spans' rounding; where the cell of that point is left out of the
/// search ([`searched_cells`]), its covered passage holds it instead. The
/// union of the spans is the same, so are the pieces outside it, in the
/// same order. The table of shared edges still holds `t`'s edges: an edge
/// whose reverse is one of them is dropped, as with `t` walked. With `B` the walk
/// and the grid keep `t`, the bound's allowances and the spans its
/// cut errors are found from being those of every edge searched.
#[inline(always)]
fn walk_edges<const DEEP: bool, const B: bool>(
    tris: &[Tri],
    (weights, reach): (&[[f64; 3]], f64),
    measure: Measure,
    half: f64,
    settle: Settle<'_>,
    sweep_from: usize,
    mut search: impl FnMut(usize, DVec2, DVec2, &mut Sum, &mut f64) -> f64,
) -> (f64, f64) {
    let Settle {
        sides,
        edges,
        interior,
    } = settle;
    prepare_sides(tris, half, sides, sweep_from);
    let mut sum = Sum::default();
    let mut bound = 0.0;
    for (i, ti) in tris.iter().enumerate() {
        if DEEP && !B && interior.left_out(i) {
            // Inside the others' union: no part of the boundary.
            continue;
        }
        // Every edge covered by the raster, shown once for the triangle.
        let held = DEEP && interior.holds_edges_of(ti);
        #[allow(clippy::needless_range_loop)] // `k` names the edge and its weight.
        for k in 0..3 {
            let (a, b) = ti.edge(k);
            if let Some(side) = Side::of(a, b, half) {
                let set = &mut sides[side as usize];
                if set.active {
                    // On a side of the square exactly: no allowance.
                    set.add_uncovered(side, a, b, half, measure, &mut sum);
                    continue;
                }
            }
            if !B && held {
                // Shared or covered: dropped either way.
                continue;
            }
            if edges.has_reverse(tris, a, b) {
                continue;
            }
            if DEEP && (held || interior.covers(a, b)) {
                // Covered whole, as the search would find (see
                // [`Interior`]), with a margin: if the images' reach is
                // far smaller, the band lies in marked cells.
                if B && (reach.is_nan() || reach >= 0.25 * interior.margin()) {
                    bound += weights[i][k];
                }
                continue;
            }
            let outside = search(i, a, b, &mut sum, &mut bound);
            if B {
                bound += weights[i][k] * outside.min(1.0);
            }
        }
    }
    if B {
        bound += sum.bound();
    }
    (sum.value(), bound)
}

/// The common start of [`union_area_in`] and [`union_area_tree`]: each
/// side of the square swept if it holds `sweep_from` edges or more.
pub(super) fn prepare_sides(tris: &[Tri], half: f64, sides: &mut [SideSet; 4], sweep_from: usize) {
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
pub(super) fn searched_cells(
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

/// The span of the edge `a → b` (of triangle `i`, its bounds `lo..hi`)
/// that triangle `j` covers, as the grid's search finds it; with `B`, the
/// same span with its ends' errors pushed to `bounded`, and where `j`
/// holds the edge's band ([`Deep`]) to `deep`.
#[inline(always)]
pub(super) fn span_of<const B: bool>(
    a: DVec2,
    b: DVec2,
    (i, j): (usize, usize),
    tris: &[Tri],
    (lo, hi): (DVec2, DVec2),
    (band, (bounded, deep)): (Deep, Found<'_>),
) -> Option<(f64, f64)> {
    let tj = &tris[j];
    if j == i || tj.bounds_miss(lo, hi) {
        return None;
    }
    let span = covered_span(a, b, tj, j < i);
    if B && span.is_some() {
        if let Some((bounds, inside)) = covered_span_bounded(a, b, tj, j < i, band) {
            bounded.push(bounds);
            deep.push(inside);
        }
    }
    span
}

/// The spans with their ends' errors, and where their triangles hold an
/// edge's band ([`span_of`]).
type Found<'a> = (&'a mut Vec<[f64; 4]>, &'a mut Vec<(f64, f64)>);

/// How an edge finds the triangles that may cover it. Every choice gives
/// the same area, bit for bit, and its search's own certified bound (see
/// `union_area_tree`); they differ in cost only. Further choices may be
/// added: a `match` on it needs a wildcard arm.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Search {
    /// [`Search::Tree`] where many images are large, [`Search::Grid`]
    /// otherwise, decided per answer before either is built by one pass
    /// over the image triangles' bounds (no predicate, and none at all
    /// below [`Search::TREE_FROM`] triangles): the tree where at least
    /// [`Search::TREE_FROM`] of them are large — bounds wider than 4 of the
    /// grid's fine cells, about `4 / √n` of the clip square, which the grid
    /// lists on its coarse levels. There the grid tests an edge against
    /// every large triangle its coarse cells hold, while the tree leaves
    /// out the subtrees whose boxes miss the edge or whose part of it is
    /// covered already. Many large images come from layers stacked over
    /// one another (the layers of a mesh between the receiver and the
    /// light) and from a polygon given as a fan of slivers: on stacks the
    /// grid cost up to 10 times the tree from about 10⁴ triangles on,
    /// depending on how the layers lie, and 11 times on a fan of 10⁵
    /// slivers covering part of the light, while the tree cost at most
    /// 1.8 times the grid (5000 stacked layers) and 1.2 times (a fan
    /// covering the light whole). A pile of small images (few large) keeps
    /// the grid.
    #[default]
    Auto,
    /// Uniform grids of the triangles' bounds (fine, and coarse levels for
    /// large triangles), every triangle sharing a cell with the edge tested
    /// until the edge is covered whole.
    Grid,
    /// A hierarchy of bounding boxes, each node holding its subtree's
    /// largest triangle, searched with the edge's cover so far: subtrees
    /// whose part of the edge is covered already are left out.
    Tree,
}

impl Search {
    /// The fewest large triangles [`Search::Auto`] takes the tree for.
    pub const TREE_FROM: usize = 8192;

    /// The search used for the union of `tris` in the square
    /// `[−half, half]²`: [`Search::Auto`] decided (a pass over the
    /// triangles' bounds, [`Grid::large_count`], once there are
    /// [`Search::TREE_FROM`] of them), the others as they are.
    pub(super) fn resolve(self, tris: &[Tri], half: f64) -> Search {
        match self {
            Search::Auto => {
                let many_large = tris.len() >= Search::TREE_FROM
                    && Grid::large_count(tris, half) >= Search::TREE_FROM;
                if many_large {
                    Search::Tree
                } else {
                    Search::Grid
                }
            }
            chosen => chosen,
        }
    }
}

/// Buffers of [`union_area`](super::union_area).
#[derive(Debug, Default)]
pub(in crate::kernel::receiver_view) struct UnionScratch {
    /// The search the union uses.
    pub(in crate::kernel::receiver_view) search: Search,
    tree: Tree,
    spans: Spans,
    pub(super) grid: Grid,
    /// The grid's order for a few searches before it is built.
    unbuilt: Unbuilt,
    edges: Edges,
    /// The last edge each triangle was tested against.
    stamp: Vec<u32>,
    intervals: Vec<(f64, f64)>,
    /// Per side of the clip square, the swept edges so far.
    sides: [SideSet; 4],
    /// The cells inside some triangle, under a deep pile.
    pub(super) interior: Interior,
    /// Under [`Interior`], per fine cell of the searched edge's range,
    /// whether the search looks in it ([`searched_cells`]).
    searched: Vec<bool>,
    /// The spans with their ends' errors ([`cut_errors`]).
    bounded: Vec<[f64; 4]>,
    /// Where the spans' triangles hold the edge's band ([`outside_deep`]).
    deep: Vec<(f64, f64)>,
}
