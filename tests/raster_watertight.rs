//! The light-view rasterizer (`softshadow::render::raster`): watertightness
//! against independent answers. Triangulated grids and fans whose vertices
//! sit on the pixel lattice (centres, corners, edge midpoints), so that
//! many edges pass exactly through pixel centres, and jittered ones, in an
//! axis frame where projection is exact; then tilted grids in random
//! frames, some straddling the near plane. Each triangle is rasterised on
//! its own and the coverage counted per pixel: exactly once inside the
//! union (decided by `robust`'s predicates, not ours), never outside, at
//! most once on its outer boundary.
#![cfg(feature = "render")]

use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3};
use softshadow::render::raster::LightView;
use softshadow::scene::LightFrame;

#[path = "support/raster.rs"]
mod raster_support;
use raster_support::{
    assert_watertight, coverage, grid_triangles, lattice_view, orient, random_frame,
};

// ---------------------------------------------------------------------------
// Watertightness, exact (axis frame, lattice vertices).

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
