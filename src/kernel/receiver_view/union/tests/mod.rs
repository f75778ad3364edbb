//! Tests of the union's parts and of its area on shapes with known answers.

mod interior;
mod needles;
mod searches;
mod spans;

use super::boundary::*;
use super::cover::*;
use super::grid::*;
use super::interior::*;
use super::shared_edges::*;
use super::sides::*;
use super::sum::*;
use super::tri::*;
use super::*;
use crate::arbitrary::Rng;
use glam::DVec2;

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

/// The count the environment variable `name` gives (a campaign's), if
/// it is set to a number.
fn count_from_env(name: &str) -> Option<usize> {
    std::env::var(name).ok().and_then(|s| s.parse().ok())
}

/// A generator seeded `seed` and an empty scratch: what a randomised
/// test of the union starts from.
fn seeded(seed: u64) -> (Rng, UnionScratch) {
    (Rng::new(seed), UnionScratch::default())
}

/// The area of the union of `tris` on `measure` where no image has an
/// allowance (no weights, an unknown reach), the sides holding
/// `sweep_from` edges or more swept.
fn area_of_sweeping_from(
    tris: &[Tri],
    measure: Measure,
    h: f64,
    scratch: &mut UnionScratch,
    sweep_from: usize,
) -> f64 {
    union_area::<false>(tris, &[], f64::INFINITY, measure, h, scratch, sweep_from).0
}

/// [`area_of_sweeping_from`] with the exact reference's sides swept.
fn area_of(tris: &[Tri], measure: Measure, h: f64, scratch: &mut UnionScratch) -> f64 {
    area_of_sweeping_from(tris, measure, h, scratch, SWEEP_FROM)
}

/// The sweep of the square's sides and the search over the grid give
/// the same area (the same set; their pieces' ends may differ in the
/// last bits), on both measures.
#[test]
fn sweeping_the_sides_gives_the_searched_area() {
    let (mut rng, mut scratch) = seeded(17);
    for case in 0..300 {
        let n = 1 + rng.below(120) as usize;
        let (measure, h) = if case % 2 == 0 {
            (Measure::Disk(1.0), 1.5)
        } else {
            (Measure::Square, 1.0)
        };
        let tris = clipped_like(&mut rng, n, h);
        let searched = area_of_sweeping_from(&tris, measure, h, &mut scratch, usize::MAX);
        let swept = area_of_sweeping_from(&tris, measure, h, &mut scratch, 1);
        assert!(
            (searched - swept).abs() <= 1e-13,
            "case {case}: {n} triangles, searched {searched}, swept {swept}"
        );
    }
}

/// A side's sweep keeps of each edge what no earlier edge on the side
/// covers, against a brute force over the earlier edges: ends from a few
/// shared values (edges touching, nested, repeated), runs of edges
/// following one another either way (a fan's), the pieces summed in the
/// same order to the same bits.
#[test]
fn a_side_keeps_what_no_earlier_edge_covers() {
    let mut rng = Rng::new(29);
    let h = 1.37;
    let mut set = SideSet::default();
    for case in 0..400 {
        let (side, at) = if case % 2 == 0 {
            (
                Side::Bottom,
                (|u: f64, h: f64| DVec2::new(u, -h)) as fn(f64, f64) -> DVec2,
            )
        } else {
            (
                Side::Left,
                (|u: f64, h: f64| DVec2::new(-h, u)) as fn(f64, f64) -> DVec2,
            )
        };
        let values: Vec<f64> = (0..2 + rng.below(30)).map(|_| rng.uniform(-h, h)).collect();
        let pick = |rng: &mut Rng| values[rng.below(values.len() as u64) as usize];
        let mut edges: Vec<(f64, f64)> = Vec::new();
        while edges.len() < 1 + rng.below(150) as usize {
            let run = if rng.chance(0.3) {
                1 + rng.below(20)
            } else {
                1
            };
            let step = rng.uniform(-0.1, 0.1);
            let mut u = pick(&mut rng);
            for _ in 0..run {
                let v = if run > 1 {
                    (u + step).clamp(-h, h)
                } else {
                    pick(&mut rng)
                };
                if v != u {
                    edges.push((u, v));
                }
                u = v;
            }
        }
        set.clear();
        let (mut swept, mut brute) = (Sum::default(), Sum::default());
        for (k, &(ua, ub)) in edges.iter().enumerate() {
            let (a, b) = (at(ua, h), at(ub, h));
            set.add_uncovered(side, a, b, h, Measure::Disk(1.0), &mut swept);
            // The earlier edges merged, then the gaps of `[lo, hi]`.
            let mut earlier: Vec<(f64, f64)> = edges[..k]
                .iter()
                .map(|&(s, e)| (s.min(e), s.max(e)))
                .collect();
            earlier.sort_by(|x, y| x.0.total_cmp(&y.0));
            let (lo, hi) = (ua.min(ub), ua.max(ub));
            let mut pieces = Vec::new();
            let mut t = lo;
            for &(s, e) in &earlier {
                if s > hi {
                    break;
                }
                if s > t {
                    pieces.push((t, s));
                }
                t = t.max(e);
            }
            if t < hi {
                pieces.push((t, hi));
            }
            let point = |u: f64| {
                if u == ua {
                    a
                } else if u == ub {
                    b
                } else {
                    at(u, h)
                }
            };
            if ua > ub {
                pieces.reverse();
            }
            for (s, e) in pieces {
                let (p, q) = if ua <= ub { (s, e) } else { (e, s) };
                brute.add(Measure::Disk(1.0).piece(point(p), point(q)));
            }
        }
        assert_eq!(
            swept.value().to_bits(),
            brute.value().to_bits(),
            "case {case}"
        );
        assert_eq!(
            swept.bound().to_bits(),
            brute.bound().to_bits(),
            "case {case}"
        );
    }
}

/// About `n` random triangles in the square `[−h, h]²`, small ones and a
/// random share of large ones (for the grid's coarse levels).
fn small_and_large(rng: &mut Rng, n: usize, h: f64) -> Vec<Tri> {
    let large_share = rng.unit();
    (0..n)
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
        .collect()
}

/// [`Unbuilt`] finds the triangles whose bounds overlap a box in the
/// order the built grid's search first meets them (index order on the
/// fine level), leaving out the searched edge's own: the same triangles
/// tested in the same order, so the same spans, cover and bound.
#[test]
fn the_unbuilt_order_is_the_grids() {
    let mut rng = Rng::new(43);
    let (mut grid, mut unbuilt) = (Grid::default(), Unbuilt::default());
    for case in 0..60 {
        let h = [1.37, 0.83, 1.0][case % 3];
        let n = 1 + rng.below(if case % 2 == 0 { 300 } else { 5000 }) as usize;
        let tris = small_and_large(&mut rng, n, h);
        grid.build::<false>(&tris, h);
        for _ in 0..20 {
            let a = DVec2::new(rng.uniform(-h, h), rng.uniform(-h, h));
            let b = a + DVec2::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)) * h;
            let (lo, hi) = (a.min(b), a.max(b));
            let own = rng.below(tris.len() as u64) as usize;
            let mut seen = vec![false; tris.len()];
            let mut met = Vec::new();
            grid.for_each_near(
                lo,
                hi,
                |_, _| true,
                |j| {
                    let (j, t) = (j as usize, &tris[j as usize]);
                    let overlaps =
                        t.hi.x >= lo.x && t.lo.x <= hi.x && t.hi.y >= lo.y && t.lo.y <= hi.y;
                    if !seen[j] && overlaps && j != own {
                        met.push(j);
                    }
                    seen[j] = true;
                    true
                },
            );
            if unbuilt.find(&tris, h, (lo, hi), own) {
                let order: Vec<usize> = unbuilt.order.iter().map(|e| e.2 as usize).collect();
                assert_eq!(order, met, "case {case}: n {n}");
            } else {
                // Refused only where more than an eighth of them overlap.
                assert!(8 * met.len() > tris.len(), "case {case}: n {n}");
            }
        }
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
        let tris = small_and_large(&mut rng, n, h);
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
                let overlaps = t.hi.x >= lo.x && t.lo.x <= hi.x && t.hi.y >= lo.y && t.lo.y <= hi.y;
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
    let (mut rng, mut scratch) = seeded(9);
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
        let area = area_of(&tris, measure, half, &mut scratch);
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
        let area = area_of(&tris, Measure::Square, 1.0, &mut scratch);
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
    let all = area_of(&tris, Measure::Disk(1.0), h, &mut scratch);
    let one = area_of(&[largest], Measure::Disk(1.0), h, &mut scratch);
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

/// The first `count` of [`deep_case`]'s cases, drawn from the seed
/// `seed`: `(case, h, tris)`.
fn deep_cases(seed: u64, count: usize, more: u64) -> impl Iterator<Item = (usize, f64, Vec<Tri>)> {
    let mut rng = Rng::new(seed);
    (0..count).map(move |case| {
        let (h, tris) = deep_case(case, &mut rng, more);
        (case, h, tris)
    })
}

/// The bound leaves out only the parts of a band that another triangle
/// holds at least twice the reach inside. Two strips across the square,
/// each two triangles with every edge on a side of the square but one:
/// the upper strip's lower edge `f` and the lower strip's upper edge `g`,
/// a height `m` apart, overlapping (each covered whole by the other
/// strip). The exact triangles are these with the ends of `f` moved up and
/// those of `g` down by the reach `e` (every corner within `e`): where `m
/// < 2e` a gap of height `2e − m` opens across the square, which only the
/// two edges' bands hold, and the bound must count them; where `g` lies
/// deep inside the upper strip (and `f` inside the lower: `3e` across,
/// above the `2√2 e` the search may ask where it bounds a line's length
/// by its larger coordinate difference), the bound
/// counts of their bands only the stretches within `2e` of where they
/// cross a strip's diagonal (the edges of the triangles holding them):
/// `O(e²)`, not the bands' `4e` each. Ordinary (non-dyadic) heights and
/// slopes.
#[test]
fn bands_held_deep_inside_other_triangles_are_left_out() {
    let (mut rng, mut scratch) = seeded(40);
    for case in 0..400 {
        let e = 10f64.powf(rng.uniform(-12.0, -6.0));
        let (y0, y1) = (rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6));
        // The vertical distance between the lines; across, `m cos θ`.
        let m = e * rng.uniform(0.0, 6.0);
        let cos = 2.0 / (2.0_f64).hypot(y1 - y0);
        let (l, r) = (DVec2::new(-1.0, y0), DVec2::new(1.0, y1));
        let (gl, gr) = (l + DVec2::Y * m, r + DVec2::Y * m);
        let tris: Vec<Tri> = [
            (l, r, DVec2::new(1.0, 1.0)),
            (l, DVec2::new(1.0, 1.0), DVec2::new(-1.0, 1.0)),
            (DVec2::new(-1.0, -1.0), DVec2::new(1.0, -1.0), gr),
            (DVec2::new(-1.0, -1.0), gr, gl),
        ]
        .iter()
        .map(|&(a, b, c)| Tri::new(a, b, c).expect("a triangle"))
        .collect();
        // Each edge's allowance: `2 e` along `f` and `g`, none on the
        // sides or the shared diagonals.
        let band = 2.0 * e * (r - l).length() * (1.0 + 4.0 * f64::EPSILON);
        let weights: Vec<[f64; 3]> = tris
            .iter()
            .map(|t| {
                [0, 1, 2].map(|k| {
                    let (a, b) = t.edge(k);
                    let on = |p: DVec2, q: DVec2| (a == p && b == q) || (a == q && b == p);
                    if on(l, r) || on(gl, gr) {
                        band
                    } else {
                        0.0
                    }
                })
            })
            .collect();
        let (area, bound) = union_area::<true>(
            &tris,
            &weights,
            e,
            Measure::Square,
            1.0,
            &mut scratch,
            SWEEP_FROM,
        );
        let exact = 4.0 - 2.0 * (2.0 * e - m).max(0.0);
        assert!(
            (area - exact).abs() <= bound,
            "case {case}: e {e:e}, m {m:e}: |{area} − {exact}| > {bound:e}"
        );
        if m * cos > 3.0 * e {
            assert!(
                bound < 0.01 * band,
                "case {case}: e {e:e}, m {m:e}: bound {bound:e} with the bands held"
            );
        }
    }
}

/// The area of the union of `tris` every way: the grid and the tree, with
/// the raster (triangles left out, then none) and without, the value
/// with a bound (reach `reach`, the allowances `w`) and without, and
/// through [`union_area`]'s own choice; with how many the raster left
/// out (0 where it is not built).
fn every_area(
    tris: &[Tri],
    (w, reach): (&[[f64; 3]], f64),
    measure: Measure,
    h: f64,
    scratch: &mut UnionScratch,
) -> (Vec<(&'static str, f64)>, usize) {
    let none = (&[][..], f64::INFINITY);
    let bands = (w, reach);
    let mut out = Vec::new();
    let s = SWEEP_FROM;
    let deep = scratch.interior.build(tris, h);
    let skipped = if deep { scratch.interior.skipped } else { 0 };
    if deep {
        out.push((
            "grid, raster",
            union_area_in::<true, false>(tris, none, measure, h, scratch, s).0,
        ));
        out.push((
            "tree, raster",
            union_area_tree::<true, false>(tris, none, measure, h, scratch, s).0,
        ));
        out.push((
            "grid, raster, bound",
            union_area_in::<true, true>(tris, bands, measure, h, scratch, s).0,
        ));
        out.push((
            "tree, raster, bound",
            union_area_tree::<true, true>(tris, bands, measure, h, scratch, s).0,
        ));
        scratch.interior.build_skipping::<false>(tris, h);
        out.push((
            "grid, raster, none left out",
            union_area_in::<true, false>(tris, none, measure, h, scratch, s).0,
        ));
        out.push((
            "tree, raster, none left out",
            union_area_tree::<true, false>(tris, none, measure, h, scratch, s).0,
        ));
    }
    out.push((
        "grid",
        union_area_in::<false, false>(tris, none, measure, h, scratch, s).0,
    ));
    out.push((
        "tree",
        union_area_tree::<false, false>(tris, none, measure, h, scratch, s).0,
    ));
    out.push((
        "grid, bound",
        union_area_in::<false, true>(tris, bands, measure, h, scratch, s).0,
    ));
    out.push((
        "tree, bound",
        union_area_tree::<false, true>(tris, bands, measure, h, scratch, s).0,
    ));
    scratch.search = Search::Auto;
    out.push((
        "auto",
        union_area::<false>(tris, none.0, none.1, measure, h, scratch, s).0,
    ));
    out.push((
        "auto, bound",
        union_area::<true>(tris, w, reach, measure, h, scratch, s).0,
    ));
    (out, skipped)
}

/// Every area of [`every_area`] is the same, bit for bit.
fn assert_same_bits(areas: &[(&str, f64)], what: &str) {
    let (name0, a0) = areas[0];
    for &(name, a) in areas {
        assert_eq!(
            a.to_bits(),
            a0.to_bits(),
            "{what}: {name} {a:e} against {name0} {a0:e}: {areas:?}"
        );
    }
}
