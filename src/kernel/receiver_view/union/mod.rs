//! The area of the union of the projected triangles within the light's
//! measure ([`union_area`]), by Green's theorem over the union's boundary
//! with exact predicates (the construction and its degenerate cases are in
//! the [parent module's documentation](super)).

mod bound;
mod boundary;
mod cover;
mod grid;
mod interior;
mod shared_edges;
mod sides;
mod span;
mod sum;
#[cfg(test)]
mod tests;
mod tree;
mod tri;

pub use boundary::Search;
pub(super) use boundary::UnionScratch;
use boundary::{union_area_in, union_area_tree};
pub(super) use tri::{Measure, Tri};

/// The area of `∪ triangles ∩ measure`, by Green's theorem over the
/// union's boundary (see the [module documentation](super)). `half` bounds
/// every coordinate (the clip square's half-width): the triangles are
/// binned in grids over it (a fine grid, and coarse levels for the large
/// triangles) so that an edge is tested only against triangles sharing a
/// cell with its bounds. An edge's search ends as soon as the spans it has
/// found cover it whole ([`Cover`](cover::Cover)), so the order of the search decides
/// only how soon; an edge that is not covered collects the span of every
/// triangle it meets (its covered start as one interval), the same union
/// in any order, so the area does not depend on it. A span test computes
/// its signed areas two and four at a time
/// ([`orient2d_values_finite`](crate::kernel::predicate::orient2d_values_finite), each lane the one-at-a-time value). An
/// edge whose reverse is an edge of another triangle
/// (two images sharing a mesh edge, their corners the same bits) lies
/// between the two and is dropped before any search ([`Edges`](shared_edges::Edges)), as the
/// search would find: on a mesh's images most edges are shared. Under a
/// deep pile of images, so is an edge whose every point lies in a cell of
/// a raster marked as inside some image ([`Interior`](interior::Interior)), and the fine grid
/// lists its images by decreasing area.
///
/// An edge lying on a side of the clip square can be covered only by the
/// edges of other triangles on that side (every triangle lies in the closed
/// square), and by the rule of coinciding edges only by those of lower
/// index. Where at least `sweep_from` edges lie on one side (the exact
/// reference's: [`SWEEP_FROM`]) — images
/// crossing the same side of the square, each edge overlapping all the
/// others, which made the search quadratic — that side is swept instead:
/// its edges, in index order, take what the earlier ones leave uncovered
/// from a set of merged intervals, cut at the earlier edges' own corners
/// (exact) rather than at parameters computed along the edge (rounded):
/// the same set, its pieces' ends differing in the last bits.
///
/// With `B`, also a bound on the area's error (else 0): `weights` holds
/// each triangle's edges' area allowances (how far the exact images may
/// differ from these along each edge; see [`union_area_in`]).
pub(super) fn union_area<const B: bool>(
    tris: &[Tri],
    weights: &[[f64; 3]],
    reach: f64,
    measure: Measure,
    half: f64,
    scratch: &mut UnionScratch,
    sweep_from: usize,
) -> (f64, f64) {
    // Two copies of the loop: the test of [`Interior`] left out of the
    // one most receivers run (chosen by measurement: see
    // benches/README.md § The union's constants and its two copies of
    // the loop).
    let deep = scratch.interior.build(tris, half);
    let search = scratch.search.resolve(tris, half);
    match (search, deep) {
        (Search::Tree, true) => {
            union_area_tree::<true, B>(tris, (weights, reach), measure, half, scratch, sweep_from)
        }
        (Search::Tree, false) => {
            union_area_tree::<false, B>(tris, (weights, reach), measure, half, scratch, sweep_from)
        }
        (_, true) => {
            union_area_in::<true, B>(tris, (weights, reach), measure, half, scratch, sweep_from)
        }
        (_, false) => {
            union_area_in::<false, B>(tris, (weights, reach), measure, half, scratch, sweep_from)
        }
    }
}

/// Sides holding at least this many edges are swept ([`union_area`]; ours:
/// no built-in scene's receiver has a side that full).
pub(super) const SWEEP_FROM: usize = 64;
