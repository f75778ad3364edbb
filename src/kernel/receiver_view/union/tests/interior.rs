//! Tests of the raster of a deep pile.

use super::*;
use crate::kernel::predicate::{orient2d, Sign};

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

/// Case `case`'s [`pile`] of `n.0` to `n.0 + n.1` triangles, `depth.0` to
/// `depth.1` deep, over the disk's square (even cases, `h = 1.5`) or the
/// square's (odd, `h = 1`): `h` and the triangles.
fn sized_pile(case: usize, rng: &mut Rng, n: (usize, u64), depth: (f64, f64)) -> (f64, Vec<Tri>) {
    let h = if case % 2 == 0 { 1.5 } else { 1.0 };
    let n = n.0 + rng.below(n.1) as usize;
    let depth = rng.uniform(depth.0, depth.1);
    (h, pile(case, rng, n, depth, h))
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
    let mut interior = Interior::default();
    let (mut marked, mut covered, mut by_blocks, mut partly) = (0, 0, 0, 0);
    for (case, h, tris) in deep_cases(41, 24, 400) {
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
    let mut interior = Interior::default();
    let (mut full, mut blocks) = (0, 0);
    for (case, h, tris) in deep_cases(47, 12, 1200) {
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
    let mut scratch = UnionScratch::default();
    let (mut dropped, mut edges) = (0, 0);
    let (mut searched, mut left_out) = (0, 0);
    for (case, h, tris) in deep_cases(43, 60, 1200) {
        let n = tris.len();
        // The disk's measure on the wider square.
        let measure = if h > 1.0 {
            Measure::Disk(1.0)
        } else {
            Measure::Square
        };
        let with = area_of(&tris, measure, h, &mut scratch);
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
        let without = union_area_in::<false, false>(
            &tris,
            (&[], f64::INFINITY),
            measure,
            h,
            &mut scratch,
            SWEEP_FROM,
        )
        .0;
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

/// Leaving out the triangles whose bounds lie in cells marked already
/// gives the raster of marking every triangle, bit for bit (every cell
/// and every full block), on random and lattice piles of 8000 to 12000
/// triangles 10 to 18 deep (small enough that the raster is built) — deep
/// enough that cases leave some out, which the test requires.
#[test]
fn leaving_out_triangles_inside_the_marks_keeps_the_raster() {
    let mut rng = Rng::new(53);
    let (mut every, mut skipping) = (Interior::default(), Interior::default());
    let (mut skipped, mut cases_skipping) = (0, 0);
    for case in 0..8 {
        let (h, tris) = sized_pile(case, &mut rng, (8000, 4000), (10.0, 18.0));
        let built = every.build_skipping::<false>(&tris, h);
        assert_eq!(every.skipped, 0);
        assert_eq!(
            skipping.build_skipping::<true>(&tris, h),
            built,
            "case {case}"
        );
        if !built {
            continue;
        }
        assert_eq!(skipping.n, every.n, "case {case}");
        for r in 0..every.n {
            assert_eq!(skipping.row(r), every.row(r), "case {case}: row {r}");
        }
        for r in 0..every.n / Interior::BLOCK {
            assert_eq!(
                skipping.block_row(r),
                every.block_row(r),
                "case {case}: blocks {r}"
            );
        }
        skipped += skipping.skipped;
        cases_skipping += usize::from(skipping.skipped > 0);
    }
    assert!(
        cases_skipping >= 5 && skipped > 10_000,
        "{cases_skipping} cases left triangles out, {skipped} in all"
    );
}

/// A triangle [`Interior::holds_edges_of`] answers for has each of its
/// three edges covered by the walk of [`Interior::covers`], on random and
/// lattice piles 4 to 18 deep (and the raster of the leaving-out test's
/// deep ones) — most of the deeper piles' triangles are held, which the
/// test requires, so that the answer is checked where it is given.
#[test]
fn a_triangle_held_has_every_edge_covered() {
    let mut rng = Rng::new(59);
    let mut interior = Interior::default();
    let (mut held, mut triangles) = (0, 0);
    for case in 0..8 {
        let (h, tris) = sized_pile(case, &mut rng, (6000, 6000), (4.0, 18.0));
        if !interior.build(&tris, h) {
            continue;
        }
        for (i, t) in tris.iter().enumerate() {
            triangles += 1;
            if !interior.holds_edges_of(t) {
                continue;
            }
            held += 1;
            for e in 0..3 {
                let (a, b) = t.edge(e);
                assert!(
                    interior.covers(a, b),
                    "case {case}: edge {e} of {i} held but not covered"
                );
                let course = interior.course(a, b).expect("inside the square");
                assert!(interior.cells_cover(&course), "case {case}: {i}, {e}");
            }
        }
    }
    assert!(
        held > 10_000 && held < triangles,
        "{held} of {triangles} triangles held"
    );
}

/// The triangles the raster leaves out lie inside the others: each corner
/// of the first 40 in every pile is strictly inside a triangle kept (exact
/// predicates), and the union's area with the raster is the area without
/// it, every edge searched, bit for bit (both measures), on random and
/// lattice piles of 8000 to 12000
/// triangles 10 to 18 deep — deep enough that thousands are left out,
/// which the test requires.
#[test]
fn triangles_left_out_lie_inside_the_kept_ones() {
    let (mut rng, mut scratch, mut left_out) = (Rng::new(61), UnionScratch::default(), 0);
    for case in 0..6 {
        let (h, tris) = sized_pile(case, &mut rng, (8000, 4000), (10.0, 18.0));
        let measure = if h > 1.0 {
            Measure::Disk(1.0)
        } else {
            Measure::Square
        };
        let with = area_of(&tris, measure, h, &mut scratch);
        let interior = &scratch.interior;
        if interior.n == 0 {
            continue;
        }
        let out: Vec<usize> = (0..tris.len()).filter(|&i| interior.left_out(i)).collect();
        assert_eq!(out.len(), interior.skipped, "case {case}");
        left_out += out.len();
        for &i in out.iter().take(40) {
            for k in 0..3 {
                let p = tris[i].edge(k).0;
                let inside = tris
                    .iter()
                    .enumerate()
                    .any(|(j, t)| !interior.left_out(j) && strictly_inside(t, p));
                assert!(inside, "case {case}: corner {k} of {i}");
            }
        }
        let no_raster = (&[][..], f64::INFINITY);
        let without =
            union_area_in::<false, false>(&tris, no_raster, measure, h, &mut scratch, SWEEP_FROM).0;
        assert_eq!(
            with.to_bits(),
            without.to_bits(),
            "case {case}: {with} against {without}"
        );
    }
    assert!(left_out > 5_000, "{left_out} triangles left out in all");
}
