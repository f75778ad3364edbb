//! The light-view rasterizer (`softshadow::render::raster`) against
//! independent answers:
//!
//! - watertightness: triangulated grids and fans whose vertices sit on the
//!   pixel lattice (centres, corners, edge midpoints), so that many edges
//!   pass exactly through pixel centres, and jittered ones, in an axis frame
//!   where projection is exact; then tilted grids in random frames, some
//!   straddling the near plane. Each triangle is rasterised on its own and
//!   the coverage counted per pixel: exactly once inside the union (decided
//!   by `robust`'s predicates, not ours), never outside, at most once on
//!   its outer boundary;
//! - depth, triangle and object against a Möller–Trumbore ray cast through
//!   every pixel centre (relative depth error below `1e-12`), on random
//!   triangle soups and on the default scene (feature `scene-file`);
//! - the closed bunny: every pixel covered an even number of times, also
//!   with pixel centres placed exactly on hundreds of its vertices;
//! - the corner cases: empty scenes, 1 × 1 views, windows off the geometry,
//!   ties, both orientations, non-finite and huge input, the validation of
//!   `LightView::new` and `LightView::fit`.
#![cfg(feature = "render")]

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use robust::Coord;
use softshadow::arbitrary::Rng;
use softshadow::bvh::Occluders;
use softshadow::render::raster::{
    rasterize, rasterize_into, rasterize_occluders, rasterize_triangle, LightMaps, LightView,
    RasterError,
};
use softshadow::scene::LightFrame;

// ---------------------------------------------------------------------------
// Helpers.

/// The light at the origin looking down +z: its axes are exactly the world
/// axes, so light-frame coordinates are the world coordinates bit for bit.
fn axis_frame() -> LightFrame {
    let f = LightFrame::toward(DVec3::ZERO, DVec3::Z).unwrap();
    assert_eq!(f.axes(), [DVec3::X, DVec3::Y, DVec3::Z]);
    f
}

fn random_frame(rng: &mut Rng) -> LightFrame {
    let mut v = || {
        DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        )
    };
    loop {
        let origin = v() * 3.0;
        let target = v();
        if (target - origin).length() > 0.5 {
            return LightFrame::toward(origin, target).unwrap();
        }
    }
}

/// Per-pixel coverage counts, each triangle rasterised on its own.
fn coverage(view: &LightView, tris: &[[DVec3; 3]]) -> Vec<u32> {
    let mut counts = vec![0u32; view.len()];
    for t in tris {
        rasterize_triangle(view, t, |f| {
            assert!(f.depth.is_finite() && f.depth >= view.near());
            counts[view.index(f.col, f.row).unwrap()] += 1;
        });
    }
    counts
}

fn coord(p: DVec2) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// Where a point lies with respect to a simple polygon, exactly (`robust`).
#[derive(Debug, PartialEq)]
enum Where {
    Inside,
    Boundary,
    Outside,
}

fn locate(poly: &[DVec2], p: DVec2) -> Where {
    let n = poly.len();
    let mut winding = 0;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let o = robust::orient2d(coord(a), coord(b), coord(p));
        if o == 0.0 && p.cmpge(a.min(b)).all() && p.cmple(a.max(b)).all() {
            return Where::Boundary;
        }
        // Sunday's crossing rule.
        if a.y <= p.y {
            if b.y > p.y && o > 0.0 {
                winding += 1;
            }
        } else if b.y <= p.y && o < 0.0 {
            winding -= 1;
        }
    }
    if winding != 0 {
        Where::Inside
    } else {
        Where::Outside
    }
}

/// A triangulated grid of `(nx + 1) × (ny + 1)` image-plane points (row
/// major), split along alternating diagonals, and its outer boundary
/// (counter-clockwise, as indices).
fn grid_triangles(
    nx: usize,
    ny: usize,
    flip: &mut impl FnMut() -> bool,
) -> (Vec<[usize; 3]>, Vec<usize>) {
    let id = |i: usize, j: usize| j * (nx + 1) + i;
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if flip() {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            } else {
                tris.push([a, b, d]);
                // Reversed orientation: occluders are two-sided.
                tris.push([b, d, c]);
            }
        }
    }
    let mut ring = Vec::new();
    ring.extend((0..nx).map(|i| id(i, 0)));
    ring.extend((0..ny).map(|j| id(nx, j)));
    ring.extend((0..nx).map(|i| id(nx - i, ny)));
    ring.extend((0..ny).map(|j| id(0, ny - j)));
    (tris, ring)
}

fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Asserts exact watertightness of an image-plane mesh whose union is the
/// polygon `ring`: `uv` are the exact projections of the world vertices.
fn assert_watertight(view: &LightView, world: &[[DVec3; 3]], ring: &[DVec2]) {
    let counts = coverage(view, world);
    let mut inside = 0;
    for row in 0..view.height() {
        for col in 0..view.width() {
            let c = counts[view.index(col, row).unwrap()];
            let p = view.pixel_center(col, row);
            match locate(ring, p) {
                Where::Inside => {
                    inside += 1;
                    assert_eq!(c, 1, "pixel ({col}, {row}) at {p} inside the union");
                }
                Where::Boundary => {
                    assert!(c <= 1, "pixel ({col}, {row}) at {p} on the boundary: {c}");
                }
                Where::Outside => assert_eq!(c, 0, "pixel ({col}, {row}) at {p} outside"),
            }
        }
    }
    assert!(inside > 0, "a test that covers nothing tests nothing");
}

// ---------------------------------------------------------------------------
// Watertightness, exact (axis frame, lattice vertices).

/// A 32 × 32 view of `[-1, 1]²`: pixel size 1/16, every centre and corner
/// dyadic. Geometry at depth 4 (a power of two): projection is exact.
fn lattice_view(near: f64) -> LightView {
    LightView::new(
        axis_frame(),
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        32,
        32,
        near,
    )
    .unwrap()
}

const DEPTH: f64 = 4.0;

fn lift(p: DVec2) -> DVec3 {
    DVec3::new(p.x * DEPTH, p.y * DEPTH, DEPTH)
}

/// A point on the half-pixel lattice (multiples of 1/32: pixel centres,
/// corners and edge midpoints), or a random float.
fn lattice_or_random(x: f64, lattice: bool) -> f64 {
    if lattice {
        (x * 32.0).round() / 32.0
    } else {
        x
    }
}

#[test]
fn lattice_grids_are_covered_exactly_once() {
    let mut rng = Rng::new(11);
    let mut skipped = 0;
    for case in 0..200 {
        let view = lattice_view(0.5);
        let nx = 1 + rng.below(6) as usize;
        let ny = 1 + rng.below(6) as usize;
        let lattice = case % 4 != 3;
        // Base grid on multiples of 1/32 (so corners and sides lie on pixel
        // centres, corners or midpoints), spacing 4..12 half-pixels,
        // extending partly outside the window.
        let h = (4 + rng.below(9)) as f64 / 32.0;
        let x0 = (rng.below(40) as f64 - 30.0) / 32.0;
        let y0 = (rng.below(40) as f64 - 30.0) / 32.0;
        let (mut uv, mut base) = (Vec::new(), Vec::new());
        for j in 0..=ny {
            for i in 0..=nx {
                let mut p = DVec2::new(x0 + i as f64 * h, y0 + j as f64 * h);
                base.push(p);
                // Interior vertices jittered by under h/4, on the lattice or
                // not; boundary ones slide along their side only.
                let jx = rng.uniform(-0.24, 0.24) * h;
                let jy = rng.uniform(-0.24, 0.24) * h;
                if i > 0 && i < nx {
                    p.x = lattice_or_random(p.x + jx, lattice);
                }
                if j > 0 && j < ny {
                    p.y = lattice_or_random(p.y + jy, lattice);
                }
                uv.push(p);
            }
        }
        let mut flip = || rng.chance(0.5);
        let (tris, ring) = grid_triangles(nx, ny, &mut flip);
        // Skip the rare jitter that folds a triangle over (or flattens it):
        // the union would no longer be the ring.
        let folded = tris.iter().any(|t| {
            let o = orient(uv[t[0]], uv[t[1]], uv[t[2]]);
            o == 0.0 || o.signum() != orient(base[t[0]], base[t[1]], base[t[2]]).signum()
        });
        if folded {
            skipped += 1;
            continue;
        }
        let world: Vec<[DVec3; 3]> = tris.iter().map(|t| t.map(|i| lift(uv[i]))).collect();
        let ring: Vec<DVec2> = ring.iter().map(|&i| uv[i]).collect();
        assert_watertight(&view, &world, &ring);
    }
    assert!(skipped < 40, "{skipped} of 200 grids folded");
}

#[test]
fn fans_around_pixel_centres_and_corners_cover_the_centre_once() {
    let mut rng = Rng::new(12);
    for case in 0..500 {
        let view = lattice_view(0.5);
        // The hub: a pixel centre, a corner, or an edge midpoint.
        let hub = DVec2::new(
            (rng.below(40) as f64 - 20.0) / 32.0,
            (rng.below(40) as f64 - 20.0) / 32.0,
        );
        // k spokes at increasing angles, consecutive gaps below π; on the
        // lattice when `case` is even (axis-parallel spokes included).
        let k = 3 + rng.below(6) as usize;
        let mut angles: Vec<f64> = loop {
            let mut a: Vec<f64> = (0..k)
                .map(|_| rng.uniform(0.0, std::f64::consts::TAU))
                .collect();
            if case % 3 == 0 {
                // Axis-parallel and diagonal spokes: through centres.
                for x in a.iter_mut() {
                    *x = (*x / std::f64::consts::FRAC_PI_4).round() * std::f64::consts::FRAC_PI_4;
                }
            }
            a.sort_by(f64::total_cmp);
            a.dedup();
            let ok = a.len() >= 3
                && a.windows(2).all(|w| w[1] - w[0] < 3.0)
                && a[0] + std::f64::consts::TAU - a[a.len() - 1] < 3.0;
            if ok {
                break a;
            }
        };
        angles.dedup();
        let ring: Vec<DVec2> = angles
            .iter()
            .map(|&a| {
                let r = rng.uniform(0.2, 0.6);
                let p = hub + DVec2::new(a.cos(), a.sin()) * r;
                if case % 2 == 0 {
                    (p * 32.0).round() / 32.0
                } else {
                    p
                }
            })
            .collect();
        let m = ring.len();
        let tris: Vec<[DVec2; 3]> = (0..m).map(|i| [hub, ring[i], ring[(i + 1) % m]]).collect();
        // Keep only proper fans: every triangle counter-clockwise around
        // the hub (rounding to the lattice may fold one).
        if tris.iter().any(|t| orient(t[0], t[1], t[2]) <= 0.0) {
            continue;
        }
        let world: Vec<[DVec3; 3]> = tris
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let w = t.map(lift);
                // Half of them reversed.
                if i % 2 == 1 {
                    [w[0], w[2], w[1]]
                } else {
                    w
                }
            })
            .collect();
        assert_watertight(&view, &world, &ring);
        // And the hub itself, when it is a pixel centre.
        let px = view.to_pixel(hub) - DVec2::splat(0.5);
        if px == px.round() && px.cmpge(DVec2::ZERO).all() && px.cmplt(DVec2::splat(32.0)).all() {
            let counts = coverage(&view, &world);
            assert_eq!(counts[view.index(px.x as u32, px.y as u32).unwrap()], 1);
        }
    }
}

#[test]
fn a_shared_edge_through_pixel_centres_is_owned_once_in_every_direction() {
    // Two triangles sharing an edge through many centres, in the 8 lattice
    // directions and both vertex orders.
    let view = lattice_view(0.5);
    let c = view.pixel_center(16, 16);
    let s = view.texel_size().x;
    for (dx, dy) in [
        (1.0, 0.0),
        (0.0, 1.0),
        (1.0, 1.0),
        (1.0, -1.0),
        (2.0, 1.0),
        (1.0, 2.0),
    ] {
        let d = DVec2::new(dx, dy) * s;
        let n = DVec2::new(-dy, dx) * s;
        let (a, b) = (c - d * 5.0, c + d * 5.0);
        for swap in [false, true] {
            let (a, b) = if swap { (b, a) } else { (a, b) };
            let t1 = [a, b, c + n * 3.0].map(lift);
            let t2 = [b, a, c - n * 3.0].map(lift);
            let counts = coverage(&view, &[t1, t2]);
            for k in -4..=4 {
                let p = c + d * k as f64;
                let q = view.to_pixel(p);
                let idx = view.index(q.x as u32, q.y as u32).unwrap();
                assert_eq!(view.pixel_center(q.x as u32, q.y as u32), p);
                assert_eq!(counts[idx], 1, "direction ({dx}, {dy}), k {k}, swap {swap}");
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Watertightness in random frames, with near-plane clipping.

/// A tilted planar grid in light-frame coordinates: `origin + s·e1 + t·e2`
/// for `(s, t)` in `[0, 1]²`, interior vertices jittered in `(s, t)`.
struct TiltedGrid {
    origin: DVec3,
    e1: DVec3,
    e2: DVec3,
    triangles: Vec<[DVec3; 3]>,
}

fn tilted_grid(
    rng: &mut Rng,
    frame: &LightFrame,
    nx: usize,
    ny: usize,
    near: f64,
    straddle: bool,
) -> TiltedGrid {
    // Light-frame geometry: centred on the axis at depth ~2, tilted so that
    // depths range over [near/3, 3] when straddling.
    let depth = 2.0;
    let origin = DVec3::new(rng.uniform(-0.8, -0.4), rng.uniform(-0.8, -0.4), depth);
    let tilt = if straddle {
        depth - near / 3.0
    } else {
        rng.uniform(0.0, 1.0)
    };
    let e1 = DVec3::new(
        rng.uniform(0.8, 1.6),
        rng.uniform(-0.2, 0.2),
        rng.uniform(-0.2, 0.2),
    );
    let e2 = DVec3::new(rng.uniform(-0.2, 0.2), rng.uniform(0.8, 1.6), -tilt);
    let mut st = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let mut s = i as f64 / nx as f64;
            let mut t = j as f64 / ny as f64;
            if i > 0 && i < nx {
                s += rng.uniform(-0.2, 0.2) / nx as f64;
            }
            if j > 0 && j < ny {
                t += rng.uniform(-0.2, 0.2) / ny as f64;
            }
            st.push(frame.to_world(origin + e1 * s + e2 * t));
        }
    }
    let mut flip = || rng.chance(0.5);
    let (tris, _) = grid_triangles(nx, ny, &mut flip);
    TiltedGrid {
        origin,
        e1,
        e2,
        triangles: tris.iter().map(|t| t.map(|i| st[i])).collect(),
    }
}

#[test]
fn tilted_grids_in_random_frames_are_covered_once_even_when_clipped() {
    let mut rng = Rng::new(13);
    let margin = 1e-9;
    let mut clipped_cases = 0;
    for case in 0..120 {
        let frame = random_frame(&mut rng);
        let near = 0.9;
        let straddle = case % 2 == 0;
        let (nx, ny) = (2 + rng.below(5) as usize, 2 + rng.below(5) as usize);
        let g = tilted_grid(&mut rng, &frame, nx, ny, near, straddle);
        let view =
            LightView::new(frame, DVec2::splat(-1.2), DVec2::splat(1.2), 48, 40, near).unwrap();
        let counts = coverage(&view, &g.triangles);
        // The plane's normal and the (s, t) of a ray's hit, independently.
        let n = g.e1.cross(g.e2);
        let mut interior = 0;
        for row in 0..view.height() {
            for col in 0..view.width() {
                let c = counts[view.index(col, row).unwrap()];
                let p = view.pixel_center(col, row);
                let d = DVec3::new(p.x, p.y, 1.0);
                let z = n.dot(g.origin) / n.dot(d);
                let hit = d * z - g.origin;
                // Solve hit = s·e1 + t·e2 (least squares via the normal).
                let s = hit.cross(g.e2).dot(n) / n.length_squared();
                let t = g.e1.cross(hit).dot(n) / n.length_squared();
                let strictly = z > 0.0
                    && z > near * (1.0 + margin)
                    && s > margin
                    && s < 1.0 - margin
                    && t > margin
                    && t < 1.0 - margin;
                let out = z <= 0.0
                    || z.is_nan()
                    || z < near * (1.0 - margin)
                    || s < -margin
                    || s > 1.0 + margin
                    || t < -margin
                    || t > 1.0 + margin;
                if strictly {
                    interior += 1;
                    assert_eq!(
                        c, 1,
                        "case {case}: pixel ({col}, {row}), (s, t, z) = ({s}, {t}, {z})"
                    );
                } else if out {
                    assert_eq!(c, 0, "case {case}: pixel ({col}, {row}) outside");
                } else {
                    assert!(
                        c <= 1,
                        "case {case}: pixel ({col}, {row}) on the boundary: {c}"
                    );
                }
            }
        }
        assert!(
            interior > 10,
            "case {case}: the grid should cover the view, {interior}"
        );
        if straddle {
            let behind = g
                .triangles
                .iter()
                .flatten()
                .filter(|&&p| frame.to_light(p).z < near)
                .count();
            assert!(
                behind > 0,
                "case {case}: the grid should cross the near plane"
            );
            clipped_cases += 1;
        }
    }
    assert!(clipped_cases >= 50);
}

// ---------------------------------------------------------------------------
// Depth, triangle and object against an independent ray cast.

/// Möller–Trumbore in the world: `t` along `origin + t·dir` and the
/// barycentrics `(u, v)`, without culling either orientation.
fn ray_triangle(origin: DVec3, dir: DVec3, tri: &[DVec3; 3]) -> Option<(f64, f64, f64)> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - tri[0];
    let u = s.dot(p) * inv;
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    let t = e2.dot(q) * inv;
    Some((t, u, v))
}

#[test]
fn depth_triangle_and_object_match_a_ray_cast() {
    let mut rng = Rng::new(14);
    let margin = 1e-9;
    let mut checked = 0usize;
    let mut worst = 0.0f64;
    for case in 0..60 {
        let frame = random_frame(&mut rng);
        let near = 0.5;
        let [ax, ay, az] = frame.axes();
        // A soup of overlapping triangles at light depths 0.2..4 (some cut
        // by the near plane), not grazing.
        let count = 1 + rng.below(30) as usize;
        let tris: Vec<[DVec3; 3]> = (0..count)
            .map(|_| {
                let c = DVec3::new(
                    rng.uniform(-1.5, 1.5),
                    rng.uniform(-1.5, 1.5),
                    rng.uniform(0.6, 4.0),
                );
                let r = rng.uniform(0.3, 1.5);
                [0; 3].map(|_| {
                    let l = c + DVec3::new(
                        rng.uniform(-r, r),
                        rng.uniform(-r, r),
                        rng.uniform(-0.5, 0.5) * r,
                    );
                    frame.to_world(l)
                })
            })
            .collect();
        let objects: Vec<u32> = (0..count).map(|_| rng.below(5) as u32).collect();
        let view =
            LightView::new(frame, DVec2::splat(-0.9), DVec2::splat(0.9), 37, 29, near).unwrap();
        let maps = rasterize(&view, &tris, &objects).unwrap();
        for row in 0..view.height() {
            for col in 0..view.width() {
                let p = view.pixel_center(col, row);
                // The ray in the world; its light-frame z-component is 1, so
                // the hit's light depth is t (to rounding).
                let dir = ax * p.x + ay * p.y + az;
                let origin = frame.origin();
                let hits: Vec<(usize, f64, bool)> = tris
                    .iter()
                    .enumerate()
                    .filter_map(|(i, tri)| {
                        let (t, u, v) = ray_triangle(origin, dir, tri)?;
                        let z = frame.to_light(origin + dir * t).z;
                        let inside = u >= -margin && v >= -margin && u + v <= 1.0 + margin;
                        let robust = u > margin && v > margin && u + v < 1.0 - margin;
                        (inside && z >= near * (1.0 - margin)).then_some((
                            i,
                            z,
                            robust && z > near * (1.0 + margin),
                        ))
                    })
                    .collect();
                let nearest_robust = hits
                    .iter()
                    .filter(|h| h.2)
                    .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                let tri = maps.triangle_at(col, row);
                if tri == u32::MAX {
                    assert_eq!(maps.depth_at(col, row), f64::INFINITY);
                    assert_eq!(maps.object_at(col, row), u32::MAX);
                    assert!(
                        nearest_robust.is_none(),
                        "case {case}: ({col}, {row}) missed {nearest_robust:?}"
                    );
                    continue;
                }
                checked += 1;
                let i = tri as usize;
                assert_eq!(maps.object_at(col, row), objects[i]);
                let depth = maps.depth_at(col, row);
                // The plane depth of the rasterised triangle on this ray.
                let (t, _, _) = ray_triangle(origin, dir, &tris[i]).unwrap();
                let z = frame.to_light(origin + dir * t).z;
                worst = worst.max(((depth - z) / z).abs());
                assert!(
                    ((depth - z) / z).abs() < 1e-12,
                    "case {case}: ({col}, {row}) depth {depth} against {z}"
                );
                // The rasterised triangle is a hit of the ray...
                assert!(
                    hits.iter().any(|h| h.0 == i),
                    "case {case}: ({col}, {row}) triangle {i} not hit"
                );
                // ...and the nearest robust hit, unless tied in depth.
                if let Some(&(j, zj, _)) = nearest_robust {
                    assert!(
                        depth <= zj * (1.0 + 1e-12),
                        "case {case}: ({col}, {row}) {depth} behind {zj}"
                    );
                    if j != i {
                        let tied = ((zj - depth) / depth).abs() < 1e-12;
                        let marginal = !hits.iter().any(|h| h.0 == i && h.2);
                        assert!(
                            tied || marginal,
                            "case {case}: ({col}, {row}) triangle {i}, ray says {j}"
                        );
                    }
                }
            }
        }
    }
    assert!(checked > 10_000, "checked {checked} pixels");
    eprintln!("worst relative depth error {worst:e} over {checked} pixels");
}

#[test]
fn depth_is_exact_for_a_plane_parallel_to_the_image_plane() {
    let view = lattice_view(0.5);
    let tri = [
        DVec3::new(-9.0, -9.0, 3.0),
        DVec3::new(9.0, -9.0, 3.0),
        DVec3::new(0.0, 9.0, 3.0),
    ];
    let maps = rasterize(&view, &[tri], &[0]).unwrap();
    assert!(maps.depth().iter().all(|&d| d == 3.0 || d == f64::INFINITY));
    assert!(maps.depth().iter().filter(|&&d| d == 3.0).count() > 500);
}

// ---------------------------------------------------------------------------
// Ids, ties, corner cases.

#[test]
fn ties_go_to_the_lower_index_and_both_orientations_render() {
    let view = lattice_view(0.5);
    let t = [
        DVec3::new(-4.0, -4.0, 4.0),
        DVec3::new(4.0, -4.0, 4.0),
        DVec3::new(0.0, 4.0, 4.0),
    ];
    let r = [t[0], t[2], t[1]];
    let a = rasterize(&view, &[t, r], &[5, 6]).unwrap();
    let b = rasterize(&view, &[r, t], &[6, 5]).unwrap();
    assert_eq!(a.depth(), b.depth());
    let covered: Vec<usize> = (0..view.len())
        .filter(|&k| a.triangles()[k] != u32::MAX)
        .collect();
    assert!(covered.len() > 100);
    for &k in &covered {
        assert_eq!((a.triangles()[k], a.objects()[k]), (0, 5));
        assert_eq!((b.triangles()[k], b.objects()[k]), (0, 6));
    }
    // A nearer triangle later in the list wins.
    let nearer = t.map(|p| p * 0.5);
    let c = rasterize(&view, &[t, nearer], &[1, 2]).unwrap();
    for &k in &covered {
        assert_eq!(c.triangles()[k], 1);
        assert_eq!(c.depth()[k], 2.0);
    }
}

#[test]
fn several_objects_keep_their_ids() {
    let view = lattice_view(0.5);
    // Three stacked squares (two triangles each) of decreasing size, the
    // smallest nearest; occluders in mesh order.
    let square = |h: f64, z: f64| {
        let c = [(-h, -h), (h, -h), (h, h), (-h, h)].map(|(x, y)| DVec3::new(x * z, y * z, z));
        vec![[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
    };
    let mut tris = Vec::new();
    let mut objects = Vec::new();
    for (o, (h, z)) in [(0.9, 8.0), (0.5, 4.0), (0.25, 2.0)]
        .into_iter()
        .enumerate()
    {
        for t in square(h, z) {
            tris.push(t);
            objects.push(o as u32 * 10);
        }
    }
    let maps = rasterize(&view, &tris, &objects).unwrap();
    for row in 0..32 {
        for col in 0..32 {
            let p = view.pixel_center(col, row).abs().max_element();
            let want = if p < 0.25 {
                (20, 2.0)
            } else if p < 0.5 {
                (10, 4.0)
            } else if p < 0.9 {
                (0, 8.0)
            } else {
                (u32::MAX, f64::INFINITY)
            };
            assert_eq!(
                (maps.object_at(col, row), maps.depth_at(col, row)),
                want,
                "({col}, {row})"
            );
            let t = maps.triangle_at(col, row);
            if t != u32::MAX {
                assert_eq!(objects[t as usize], want.0);
            }
        }
    }
    // The same through `Occluders`.
    let occ = Occluders::from_triangles(tris.clone());
    let m2 = rasterize_occluders(&view, &occ);
    assert_eq!(m2.depth(), maps.depth());
    assert!(m2.objects().iter().all(|&o| o == 0 || o == u32::MAX));
}

#[test]
fn empty_scenes_tiny_views_and_windows_off_the_geometry() {
    let frame = axis_frame();
    let view = lattice_view(0.5);
    let empty = rasterize(&view, &[], &[]).unwrap();
    assert_eq!(empty, LightMaps::empty(32, 32));
    assert!(empty.depth().iter().all(|&d| d == f64::INFINITY));
    assert_eq!(empty.depth_at(99, 0), f64::INFINITY);

    let big = [
        DVec3::new(-9.0, -9.0, 2.0),
        DVec3::new(9.0, -9.0, 2.0),
        DVec3::new(0.0, 9.0, 2.0),
    ];
    let one = LightView::new(frame, DVec2::splat(-0.1), DVec2::splat(0.1), 1, 1, 0.5).unwrap();
    assert_eq!(one.pixel_center(0, 0), DVec2::ZERO);
    let m = rasterize(&one, &[big], &[3]).unwrap();
    assert_eq!(
        (m.depth_at(0, 0), m.object_at(0, 0), m.triangle_at(0, 0)),
        (2.0, 3, 0)
    );

    let off = LightView::new(
        frame,
        DVec2::new(40.0, 40.0),
        DVec2::new(41.0, 42.0),
        16,
        16,
        0.5,
    )
    .unwrap();
    let m = rasterize(&off, &[big], &[3]).unwrap();
    assert!(m.triangles().iter().all(|&t| t == u32::MAX));
    // Entirely nearer than `near`: dropped.
    let close = big.map(|p| p * 0.1);
    assert!(rasterize(&view, &[close], &[0])
        .unwrap()
        .depth()
        .iter()
        .all(|d| d.is_infinite()));
}

#[test]
fn non_finite_and_huge_input_neither_panics_nor_lies() {
    let view = lattice_view(0.5);
    let good = [
        DVec3::new(-9.0, -9.0, 2.0),
        DVec3::new(9.0, -9.0, 2.0),
        DVec3::new(0.0, 9.0, 2.0),
    ];
    let bad = [
        [
            DVec3::new(f64::NAN, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ],
        [
            DVec3::new(f64::INFINITY, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ],
        [
            DVec3::new(1e300, -1e300, 1.0),
            DVec3::new(1.0, 0.0, 1e300),
            DVec3::new(-1e300, 1.0, 1.0),
        ],
        [
            DVec3::new(-1e200, -1e200, 1.0),
            DVec3::new(1e200, -1e200, 1.0),
            DVec3::new(0.0, 1e200, 1.0),
        ],
        [
            DVec3::new(0.0, 0.0, 1e-300),
            DVec3::new(1e-300, 0.0, 1.0),
            DVec3::new(0.0, 1e-300, 1.0),
        ],
        [DVec3::splat(1.0); 3],
    ];
    let mut tris = bad.to_vec();
    tris.push(good);
    let objects: Vec<u32> = (0..tris.len() as u32).collect();
    let maps = rasterize(&view, &tris, &objects).unwrap();
    let alone = rasterize(&view, &[good], &[6]).unwrap();
    // The out-of-domain triangles are skipped; the good one is unaffected.
    assert_eq!(maps.depth(), alone.depth());
    assert!(maps.depth().iter().all(|d| !d.is_nan()));
    // Large but in the domain: a triangle 1e40 across, seen at depth 1e30,
    // covers the whole view at that depth.
    let far = [
        DVec3::new(-1e40, -1e40, 1e30),
        DVec3::new(1e40, -1e40, 1e30),
        DVec3::new(0.0, 1e40, 1e30),
    ];
    let m = rasterize(&view, &[far], &[0]).unwrap();
    assert!(m.depth().iter().all(|&d| (d / 1e30 - 1.0).abs() < 1e-12));
}

#[test]
fn light_views_validate_their_input() {
    let f = axis_frame();
    let (lo, hi) = (DVec2::splat(-1.0), DVec2::splat(1.0));
    assert!(LightView::new(f, lo, hi, 1, 1, 1e-9).is_ok());
    assert!(LightView::new(f, lo, hi, 16384, 1, 1.0).is_ok());
    let e = |r: Result<LightView, RasterError>| r.unwrap_err();
    assert_eq!(
        e(LightView::new(f, hi, lo, 4, 4, 1.0)),
        RasterError::EmptyWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, DVec2::new(1.0, -1.0), 4, 4, 1.0)),
        RasterError::EmptyWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, DVec2::new(f64::NAN, 1.0), 4, 4, 1.0)),
        RasterError::NonFiniteWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, DVec2::new(1e200, 1.0), 4, 4, 1.0)),
        RasterError::NonFiniteWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, hi, 0, 4, 1.0)),
        RasterError::Resolution {
            width: 0,
            height: 4
        }
    );
    assert_eq!(
        e(LightView::new(f, lo, hi, 4, 16385, 1.0)),
        RasterError::Resolution {
            width: 4,
            height: 16385
        }
    );
    assert_eq!(
        e(LightView::new(
            f,
            DVec2::ZERO,
            DVec2::splat(2e-140),
            4,
            4,
            1.0
        )),
        RasterError::EmptyWindow
    );
    for near in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(e(LightView::new(f, lo, hi, 4, 4, near)), RasterError::Near);
    }
    let t = [DVec3::Z; 3];
    assert_eq!(
        rasterize(
            &LightView::new(f, lo, hi, 4, 4, 1.0).unwrap(),
            &[t, t],
            &[0]
        )
        .unwrap_err(),
        RasterError::LengthMismatch {
            triangles: 2,
            objects: 1
        }
    );
    // Pixel geometry.
    let v = LightView::new(f, DVec2::new(-1.0, 0.0), DVec2::new(1.0, 3.0), 4, 6, 0.1).unwrap();
    assert_eq!(v.texel_size(), DVec2::new(0.5, 0.5));
    assert_eq!(v.pixel_center(0, 0), DVec2::new(-0.75, 0.25));
    assert_eq!(v.pixel_center(3, 5), DVec2::new(0.75, 2.75));
    assert_eq!(v.to_pixel(v.pixel_center(2, 1)), DVec2::new(2.5, 1.5));
    assert_eq!(v.pixel_of(DVec2::new(0.0, 0.0)), Some((2, 0)));
    assert_eq!(v.pixel_of(DVec2::new(1.0, 0.0)), None);
    assert_eq!(v.index(3, 5), Some(23));
    assert_eq!(v.index(4, 0), None);
}

#[test]
fn fit_contains_the_points_with_a_pixel_to_spare() {
    let mut rng = Rng::new(15);
    for _ in 0..200 {
        let frame = random_frame(&mut rng);
        let near = 0.3;
        let points: Vec<DVec3> = (0..1 + rng.below(50))
            .map(|_| {
                DVec3::new(
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(-2.0, 2.0),
                )
            })
            .collect();
        let (w, h) = (1 + rng.below(300) as u32, 1 + rng.below(300) as u32);
        let in_front: Vec<DVec2> = points
            .iter()
            .filter_map(|&p| {
                let q = frame.to_light(p);
                (q.z >= near).then(|| DVec2::new(q.x / q.z, q.y / q.z))
            })
            .collect();
        match LightView::fit(frame, points.iter().copied(), w, h, near) {
            Err(err) => {
                assert!(in_front.is_empty());
                assert_eq!(err, RasterError::NothingInFront);
            }
            Ok(view) => {
                assert!(!in_front.is_empty());
                let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
                for &u in &in_front {
                    let q = view.to_pixel(u);
                    lo = lo.min(q);
                    hi = hi.max(q);
                }
                // One pixel of margin each side for sizes ≥ 3, n/(n + 2) of
                // one below (the extent floor only widens).
                let size = DVec2::new(w as f64, h as f64);
                let margin = size.map(|n| if n >= 3.0 { 1.0 } else { n / (n + 2.0) });
                assert!(lo.cmpge(margin - 1e-9).all(), "{lo} {size}");
                assert!(hi.cmple(size - margin + 1e-9).all(), "{hi} {size}");
                if w >= 3 && in_front.len() > 1 && (hi.x - lo.x) > 1.0 {
                    assert!((lo.x - 1.0).abs() < 1e-9 && (hi.x - (size.x - 1.0)).abs() < 1e-9);
                }
            }
        }
    }
    let f = axis_frame();
    assert_eq!(
        LightView::fit(f, [DVec3::new(0.0, 0.0, -1.0)], 8, 8, 0.5).unwrap_err(),
        RasterError::NothingInFront
    );
    // One point: a tiny window around it.
    let v = LightView::fit(f, [DVec3::new(1.0, 2.0, 4.0)], 8, 8, 0.5).unwrap();
    let c = (v.lo() + v.hi()) * 0.5;
    assert!((c - DVec2::new(0.25, 0.5)).length() < 1e-15 && v.hi().x > v.lo().x);
}

// ---------------------------------------------------------------------------
// Properties.

fn arb_frame() -> impl Strategy<Value = LightFrame> {
    (
        prop::array::uniform3(-3.0..3.0f64),
        prop::array::uniform3(-1.0..1.0f64),
    )
        .prop_filter_map("a direction", |(o, t)| {
            let (o, t) = (DVec3::from(o), DVec3::from(t));
            ((t - o).length() > 0.3).then(|| LightFrame::toward(o, t).unwrap())
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// A quad split along a diagonal, in any frame, any order of its four
    /// triangles' vertices, partly behind `near` or not: no pixel is
    /// covered twice, and the split does not change what the two halves
    /// cover, compared with the other diagonal.
    #[test]
    fn both_diagonals_of_a_quad_cover_the_same_pixels_once(
        frame in arb_frame(),
        corners in prop::array::uniform3(prop::array::uniform3(-1.0..1.0f64)),
        near in 0.05..2.0f64,
        rot in 0usize..3,
    ) {
        // A parallelogram a, b, c, d around light depth 2 (convex, so both
        // diagonals split it).
        let [a, b, c] = corners.map(DVec3::from);
        let (a, b, c) = (a + DVec3::Z * 2.0, b + DVec3::Z * 2.0, c + DVec3::Z * 2.0);
        let d = a + c - b; // parallelogram a, b, c, d
        let w = |p: DVec3| frame.to_world(p);
        let (a, b, c, d) = (w(a), w(b), w(c), w(d));
        let view = LightView::new(frame, DVec2::splat(-1.5), DVec2::splat(1.5), 24, 24, near).unwrap();
        let rotate = |t: [DVec3; 3]| [t[rot % 3], t[(rot + 1) % 3], t[(rot + 2) % 3]];
        let one = coverage(&view, &[rotate([a, b, c]), rotate([a, c, d])]);
        let other = coverage(&view, &[rotate([b, c, d]), rotate([d, a, b])]);
        prop_assert!(one.iter().all(|&n| n <= 1));
        prop_assert!(other.iter().all(|&n| n <= 1));
        // Same outline, so the same pixels (up to a centre within rounding
        // of a clipped outline, which random input does not hit).
        let diff = one.iter().zip(&other).filter(|(x, y)| x != y).count();
        prop_assert!(diff == 0, "{} pixels differ", diff);
    }

    /// Depth is never NaN, always within the near plane and the farthest
    /// vertex, for arbitrary triangles.
    #[test]
    fn fragments_are_finite_and_in_range(
        frame in arb_frame(),
        tri in prop::array::uniform3(prop::array::uniform3(-1e3..1e3f64)),
        near in 1e-6..10.0f64,
    ) {
        let tri = tri.map(DVec3::from);
        let view = LightView::new(frame, DVec2::splat(-3.0), DVec2::splat(3.0), 16, 16, near).unwrap();
        let zmax = tri.iter().map(|&p| frame.to_light(p).z).fold(f64::NEG_INFINITY, f64::max);
        rasterize_triangle(&view, &tri, |f| {
            assert!(f.depth >= near && f.depth <= zmax, "{} outside [{near}, {zmax}]", f.depth);
        });
    }
}

#[test]
fn an_edge_cut_by_the_near_plane_is_cut_at_the_same_point_from_both_sides() {
    // Two triangles sharing the edge P Q, P at depth 4 and Q at depth 1/4
    // (powers of two, so both project exactly onto the pixel-centre column
    // x = c), cut by a near plane in between. The clip point on P Q is
    // rounded; unless both triangles compute it from the same ordered
    // endpoints, their projected edges differ by an ulp and the centres on
    // the column x = c are covered twice or not at all.
    let mut rng = Rng::new(16);
    let mut checked = 0;
    for _ in 0..2000 {
        let near = rng.uniform(0.3, 3.5);
        let view = LightView::new(
            axis_frame(),
            DVec2::splat(-1.0),
            DVec2::splat(1.0),
            32,
            32,
            near,
        )
        .unwrap();
        let col = 8 + rng.below(16) as u32;
        let c = view.pixel_center(col, 0).x;
        let (yp, yq) = (rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9));
        let p = DVec3::new(c * 4.0, yp * 4.0, 4.0);
        let q = DVec3::new(c * 0.25, yq * 0.25, 0.25);
        let left = DVec3::new((c - 0.5) * 4.0, rng.uniform(-0.9, 0.9) * 4.0, 4.0);
        let right = DVec3::new((c + 0.5) * 4.0, rng.uniform(-0.9, 0.9) * 4.0, 4.0);
        let tris = if rng.chance(0.5) {
            [[p, q, left], [q, p, right]]
        } else {
            [[q, left, p], [right, p, q]]
        };
        let counts = coverage(&view, &tris);
        // The clip point's projection, to rounding.
        let s = (near - 0.25) / (4.0 - 0.25);
        let clip_y = (q.y + s * (p.y - q.y)) / near;
        for row in 0..32 {
            let y = view.pixel_center(col, row).y;
            let (lo, hi) = (clip_y.min(yp), clip_y.max(yp));
            if y > lo + 1e-9 && y < hi - 1e-9 {
                checked += 1;
                // Strictly between the left and right triangles' far sides
                // as well: the union's interior (the sides are 0.5 away).
                assert_eq!(
                    counts[view.index(col, row).unwrap()],
                    1,
                    "near {near}, column {col}, row {row}"
                );
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}

#[test]
fn rasterize_into_reuses_maps_and_matches_rasterize() {
    let mut rng = Rng::new(17);
    let frame = random_frame(&mut rng);
    let tris: Vec<[DVec3; 3]> = (0..40)
        .map(|_| {
            [0; 3].map(|_| {
                frame.to_world(DVec3::new(
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(0.2, 3.0),
                ))
            })
        })
        .collect();
    let objects: Vec<u32> = (0..40).collect();
    let mut maps = LightMaps::empty(3, 5);
    for (w, h) in [(17, 9), (40, 33), (1, 1), (17, 9)] {
        let view = LightView::new(frame, DVec2::splat(-1.0), DVec2::splat(1.0), w, h, 0.5).unwrap();
        rasterize_into(&view, &tris, &objects, &mut maps).unwrap();
        assert_eq!(maps, rasterize(&view, &tris, &objects).unwrap());
        assert_eq!(
            rasterize_into(&view, &tris, &objects[1..], &mut maps),
            Err(RasterError::LengthMismatch {
                triangles: 40,
                objects: 39
            })
        );
        assert_eq!(maps, LightMaps::empty(w, h));
    }
}

// ---------------------------------------------------------------------------
// The default scene: a real closed mesh at arbitrary positions.

/// The default scene's occluders and its light view (the frame toward the
/// centre of the bounding box, fitted to every vertex).
#[cfg(feature = "scene-file")]
fn default_scene_view(size: u32) -> (Occluders, LightView) {
    let scene = softshadow::scene::builtin("default").unwrap();
    let occ = Occluders::from_scene(&scene);
    let (lo, hi) = scene.bounds().unwrap();
    let frame = LightFrame::toward(scene.light().center(), 0.5 * (lo + hi)).unwrap();
    let view = LightView::fit(
        frame,
        occ.triangles().iter().flatten().copied(),
        size,
        size,
        1e-3,
    )
    .unwrap();
    (occ, view)
}

/// The top-left rule is the symbolic perturbation of every centre by
/// `(δ, δ²)`, `δ → 0⁺`, so over a closed mesh every pixel's coverage count
/// is even, edges and vertices through centres included: any inconsistency
/// between two triangles sharing an edge shows as an odd count.
#[cfg(feature = "scene-file")]
#[test]
fn the_closed_bunny_covers_every_pixel_an_even_number_of_times() {
    let (occ, _) = default_scene_view(8);
    let bunny: Vec<[DVec3; 3]> = occ
        .triangles()
        .iter()
        .zip(occ.objects())
        .filter(|(_, &o)| o == 1)
        .map(|(t, _)| *t)
        .collect();
    assert_eq!(bunny.len(), 3674);
    let (_, view) = default_scene_view(8);
    let frame = *view.frame();
    // Fitted to the bunny alone, at several resolutions (so that many
    // pixel centres fall near vertices and edges).
    for size in [97, 256, 509] {
        let view =
            LightView::fit(frame, bunny.iter().flatten().copied(), size, size, 1e-3).unwrap();
        let counts = coverage(&view, &bunny);
        let odd = counts.iter().filter(|&&n| n % 2 == 1).count();
        assert_eq!(
            odd, 0,
            "{size}²: {odd} pixels covered an odd number of times"
        );
        let covered = counts.iter().filter(|&&n| n >= 2).count();
        assert!(
            covered > view.len() / 4,
            "{size}²: the bunny should fill its window"
        );
    }
    // Random positions rarely put a centre on an edge, so also centre a
    // small view's pixel exactly on the projection of each of many
    // vertices: the fans around them (front, back, silhouette).
    let mut exact = 0;
    let mut vertices: Vec<DVec3> = bunny.iter().flatten().copied().collect();
    vertices.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
    vertices.dedup();
    for &w in vertices.iter().step_by(4) {
        let u = frame.project(w).unwrap().point;
        let s = DVec2::splat(1e-3);
        let mut lo = u - s * 2.5;
        for _ in 0..8 {
            let view = LightView::new(frame, lo, lo + s * 5.0, 5, 5, 1e-3).unwrap();
            let c = view.pixel_center(2, 2);
            if c == u {
                let n = coverage(&view, &bunny)[view.index(2, 2).unwrap()];
                assert_eq!(n % 2, 0, "vertex {w}: covered {n} times");
                exact += 1;
                break;
            }
            lo += u - c;
        }
    }
    assert!(
        exact > 200,
        "only {exact} vertices landed on a pixel centre"
    );
}

#[cfg(feature = "scene-file")]
#[test]
fn the_default_scene_matches_a_ray_cast() {
    let (occ, view) = default_scene_view(64);
    let maps = rasterize_occluders(&view, &occ);
    let frame = view.frame();
    let [ax, ay, az] = frame.axes();
    let mut seen = [0usize; 2];
    for row in 0..view.height() {
        for col in 0..view.width() {
            let p = view.pixel_center(col, row);
            let dir = ax * p.x + ay * p.y + az;
            let mut best: Option<(f64, usize)> = None;
            for (i, tri) in occ.triangles().iter().enumerate() {
                if let Some((t, u, v)) = ray_triangle(frame.origin(), dir, tri) {
                    if u >= 0.0
                        && v >= 0.0
                        && u + v <= 1.0
                        && t > 0.0
                        && best.is_none_or(|b| t < b.0)
                    {
                        best = Some((t, i));
                    }
                }
            }
            let tri = maps.triangle_at(col, row);
            match best {
                None => assert_eq!(tri, u32::MAX, "({col}, {row})"),
                Some((t, i)) => {
                    assert_ne!(tri, u32::MAX, "({col}, {row}) missed triangle {i}");
                    let z = frame.to_light(frame.origin() + dir * t).z;
                    let depth = maps.depth_at(col, row);
                    assert!(
                        ((depth - z) / z).abs() < 1e-12,
                        "({col}, {row}): {depth} against {z}"
                    );
                    // Different triangles only where they meet (same depth).
                    let object = maps.object_at(col, row);
                    assert_eq!(object, occ.objects()[tri as usize]);
                    if tri as usize != i {
                        assert_eq!(object, occ.objects()[i]);
                    }
                    seen[object as usize] += 1;
                }
            }
        }
    }
    // Floor and bunny both in view.
    assert!(seen[0] > 500 && seen[1] > 20, "{seen:?}");
}
