//! The two searches against each other and against independent areas.

use super::*;

/// The union's area with the search `search`, and its bound with the
/// weights `w` (one per edge) and the images' reach `reach`.
fn area_by(
    search: Search,
    tris: &[Tri],
    (w, reach): (&[[f64; 3]], f64),
    measure: Measure,
    h: f64,
    scratch: &mut UnionScratch,
) -> [(f64, f64); 2] {
    scratch.search = search;
    [
        union_area::<false>(tris, w, reach, measure, h, scratch, SWEEP_FROM),
        union_area::<true>(tris, w, reach, measure, h, scratch, SWEEP_FROM),
    ]
}

/// Random allowances for the edges of `tris`, each up to `10⁻¹⁶` of its
/// edge's length.
fn weights(tris: &[Tri], rng: &mut Rng) -> Vec<[f64; 3]> {
    tris.iter()
        .map(|t| {
            let mut w = [0.0; 3];
            for (k, wk) in w.iter_mut().enumerate() {
                let (a, b) = t.edge(k);
                *wk = 1e-16 * rng.unit() * (b - a).length();
            }
            w
        })
        .collect()
}

/// Homothets of one triangle: `n` copies scaled by `1 + k s` about
/// `centre` (inside: nested; outside: stacked layers seen from a
/// receiver), clamped to the square.
fn homothets(t: [DVec2; 3], centre: DVec2, n: usize, s: f64, h: f64) -> Vec<Tri> {
    (0..n)
        .filter_map(|k| {
            let f = 1.0 + k as f64 * s;
            let m = |v: DVec2| (centre + (v - centre) * f).clamp(DVec2::splat(-h), DVec2::splat(h));
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
/// among spans starting at one point: before, the first found), where the
/// images' reach is unknown (infinite: every band counted whole). With a
/// finite reach each search leaves out the parts of bands its own spans
/// hold deep inside — the spans found before an edge is covered differ
/// between the searches — so the areas are the same and each bound is at
/// most the one without.
#[test]
fn the_tree_search_gives_the_grid_area_bit_for_bit() {
    let (mut rng, mut scratch) = seeded(61);
    let mut nonzero = 0;
    for case in 0..270 {
        let (h, tris) = family(case, &mut rng);
        let w = weights(&tris, &mut rng);
        for measure in [Measure::Disk(1.0), Measure::Square] {
            let unknown = (&w[..], f64::INFINITY);
            let grid = area_by(Search::Grid, &tris, unknown, measure, h, &mut scratch);
            for search in [Search::Grid, Search::Tree] {
                let reach = (&w[..], 1e-16);
                let within = area_by(search, &tris, reach, measure, h, &mut scratch);
                for (g, r) in grid.iter().zip(&within) {
                    assert_eq!(g.0.to_bits(), r.0.to_bits(), "case {case}, {search:?}");
                    assert!(r.1 <= g.1, "case {case}, {search:?}: {} > {}", r.1, g.1);
                }
            }
            for search in [Search::Tree] {
                let other = area_by(search, &tris, unknown, measure, h, &mut scratch);
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
    let (mut rng, mut scratch) = seeded(67);
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
            let area = area_of(&tris, measure, h, &mut scratch);
            assert!(
                (area - expected).abs() <= 1e-11,
                "case {case} ({search:?}): {} triangles, {area} against {expected}",
                tris.len()
            );
        }
    }
}

/// Large unions for [`Search::Auto`]'s choice, in the square of
/// half-width `h`, with what it must choose: layers stacked many deep
/// (homothets about a point outside, in steps of `10⁻⁶`–`2·10⁻⁵`), nested
/// ones (about their centroid), coincident and near-coincident copies of
/// one large triangle, and twice as many slivers of a fan (one layer
/// deep), all at random non-dyadic corners and more than
/// [`Search::TREE_FROM`] of them (the tree); a random pile of as many small triangles a few deep,
/// and a stack of fewer than [`Search::TREE_FROM`] layers (the grid).
fn auto_cases(rng: &mut Rng, h: f64) -> Vec<(&'static str, Vec<Tri>, Search)> {
    let many = Search::TREE_FROM + 1 + rng.below(2000) as usize;
    let corner = |rng: &mut Rng| DVec2::new(rng.uniform(-h, h), rng.uniform(-h, h));
    // A large triangle, its corners jittered: about a quarter of the square.
    let t = [(-0.8, -0.7), (0.75, -0.6), (0.1, 0.8)]
        .map(|(x, y)| DVec2::new(x, y) * h + corner(rng) * 0.1);
    let outside = DVec2::new(rng.uniform(2.0, 4.0) * h, rng.uniform(-h, h));
    let centroid = (t[0] + t[1] + t[2]) / 3.0;
    let step = rng.uniform(1e-12, 1e-9);
    let copies = (0..many)
        .filter_map(|k| {
            let d = DVec2::new(step * (k % 7) as f64, -step * (k % 3) as f64);
            Tri::new(t[0] + d, t[1] + d, t[2] + d)
        })
        .collect();
    let stacked = homothets(t, outside, many, rng.uniform(1e-6, 2e-5), h);
    let nested = homothets(t, centroid, many, rng.uniform(1e-6, 2e-5), h);
    let few = homothets(t, outside, Search::TREE_FROM / 2, 1e-5, h);
    let fan = fan(
        corner(rng) * 0.5,
        corner(rng) * 0.2,
        rng.uniform(0.3, 0.7) * h,
        2 * many,
        h,
    );
    let depth = rng.uniform(2.0, 5.0);
    let pile = pile(0, rng, many, depth, h);
    vec![
        ("stacked", stacked, Search::Tree),
        ("nested", nested, Search::Tree),
        ("copies", copies, Search::Tree),
        ("fan", fan, Search::Tree),
        ("pile", pile, Search::Grid),
        ("fewer stacked", few, Search::Grid),
    ]
}

/// [`Search::Auto`] takes the tree on many large images (stacked, nested
/// or copied many deep, or a fan of slivers), and the grid on a pile of
/// small images and a smaller stack (that the searches it chooses between give the
/// same value bits, and that its bound is the chosen one's, is checked
/// through the whole exact reference by `tests/union_search.rs`).
#[test]
fn the_automatic_search_is_the_tree_on_many_large_images_only() {
    let mut rng = Rng::new(71);
    for h in [1.5, 1.0, 0.73] {
        for (what, tris, expected) in auto_cases(&mut rng, h) {
            let count = Grid::large_count(&tris, h);
            let shown = format!("{what}: {} triangles, {count} large", tris.len());
            // The tree's cases as many as it asks for, the grid's many.
            let fewest = if expected == Search::Tree {
                Search::TREE_FROM
            } else {
                Search::TREE_FROM / 4
            };
            assert!(tris.len() >= fewest, "{shown}");
            assert_eq!(Search::Auto.resolve(&tris, h), expected, "{shown}");
            for explicit in [Search::Grid, Search::Tree] {
                assert_eq!(explicit.resolve(&tris, h), explicit, "{shown}");
            }
        }
    }
}
