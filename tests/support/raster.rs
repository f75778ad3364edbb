//! What the light-view rasterizer's tests (`tests/raster_*.rs`) share,
//! included with `#[path]`: light frames, per-pixel coverage counts, exact
//! point-in-polygon location (`robust`), triangulated grids, the
//! watertightness assertion, the 32 × 32 lattice view and an independent
//! Möller–Trumbore ray cast.
#![allow(dead_code)]

use robust::Coord;
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3};
use softshadow::render::raster::{rasterize_triangle, LightView};
use softshadow::scene::LightFrame;

/// The light at the origin looking down +z: its axes are exactly the world
/// axes, so light-frame coordinates are the world coordinates bit for bit.
pub fn axis_frame() -> LightFrame {
    let f = LightFrame::toward(DVec3::ZERO, DVec3::Z).unwrap();
    assert_eq!(f.axes(), [DVec3::X, DVec3::Y, DVec3::Z]);
    f
}

pub fn random_frame(rng: &mut Rng) -> LightFrame {
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
pub fn coverage(view: &LightView, tris: &[[DVec3; 3]]) -> Vec<u32> {
    let mut counts = vec![0u32; view.len()];
    for t in tris {
        rasterize_triangle(view, t, |f| {
            assert!(f.depth.is_finite() && f.depth >= view.near());
            counts[view.index(f.col, f.row).unwrap()] += 1;
        });
    }
    counts
}

pub fn coord(p: DVec2) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// Where a point lies with respect to a simple polygon, exactly (`robust`).
#[derive(Debug, PartialEq)]
pub enum Where {
    Inside,
    Boundary,
    Outside,
}

pub fn locate(poly: &[DVec2], p: DVec2) -> Where {
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
pub fn grid_triangles(
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

pub fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Asserts exact watertightness of an image-plane mesh whose union is the
/// polygon `ring`: `uv` are the exact projections of the world vertices.
pub fn assert_watertight(view: &LightView, world: &[[DVec3; 3]], ring: &[DVec2]) {
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

/// A 32 × 32 view of `[-1, 1]²`: pixel size 1/16, every centre and corner
/// dyadic. Geometry at depth 4 (a power of two): projection is exact.
pub fn lattice_view(near: f64) -> LightView {
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

/// Möller–Trumbore in the world: `t` along `origin + t·dir` and the
/// barycentrics `(u, v)`, without culling either orientation.
pub fn ray_triangle(origin: DVec3, dir: DVec3, tri: &[DVec3; 3]) -> Option<(f64, f64, f64)> {
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
