//! SISM's umbra pass (§2.4): every triangle clipped in front of the light,
//! projected and rasterised over the receiver grid; per stored receiver an
//! exact point-in-triangle test with the shared tie rule, and a depth test,
//! adding the triangle's layer weight when it lies between the receiver and
//! the light's centre.

use super::grid::Grid;
use crate::kernel::footprint::f64::{clip_near, project};
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use crate::method::centre::{layer_weights, left};
use crate::render::Stages;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// One triangle of the umbra pass, projected.
struct UmbraTri {
    /// Projected corners, counter-clockwise.
    p: [DVec2; 3],
    lo: DVec2,
    hi: DVec2,
    /// The world triangle (for the exact depth test).
    world: [DVec3; 3],
    /// `orient3d(world, light centre)`, never zero.
    light_side: Sign,
    /// Least and greatest light-frame depth of the corners.
    z_min: f64,
    z_max: f64,
    weight: f64,
}

/// Relative margin on light-frame depths (each rounded a few times) when
/// they decide a depth order without the exact test.
const DEPTH_MARGIN: f64 = 1e-12;

/// The layer count `U(p)` of every stored receiver of `grid`, in grid
/// order, in whole layers (stages `sism triangles`, `sism umbra`).
pub(super) fn pass(stages: &Stages, grid: &Grid, z_near: f64) -> Vec<f64> {
    let tris = stages.timed("sism triangles", || {
        let scene = stages.scene();
        let light_frame = stages.light_frame();
        let center = scene.light().center();
        let weights = layer_weights(stages);
        let mut tris = Vec::new();
        for (mesh, w) in scene.meshes().iter().zip(weights.iter()) {
            let pos = mesh.positions();
            let lf: Vec<DVec3> = pos.iter().map(|&p| light_frame.to_light(p)).collect();
            for (f, t) in mesh.triangles().iter().enumerate() {
                push_umbra_tri(&mut tris, t, pos, &lf, center, w.faces[f], z_near);
            }
        }
        let detail = format!("{} projected triangles", tris.len());
        (tris, detail)
    });
    let m = grid.s.len();
    let mut umbra = vec![0.0f64; m];
    stages.timed("sism umbra", || {
        let mut bin_tris: Vec<Vec<u32>> = vec![Vec::new(); grid.bins()];
        for (i, t) in tris.iter().enumerate() {
            if t.z_min >= grid.z_max {
                continue;
            }
            if let Some((x0, y0, x1, y1)) = grid.cell_range(t.lo, t.hi) {
                for by in y0 / grid.bin..=y1 / grid.bin {
                    for bx in x0 / grid.bin..=x1 / grid.bin {
                        bin_tris[by as usize * grid.bx as usize + bx as usize].push(i as u32);
                    }
                }
            }
        }
        let tests: u64 = grid
            .split_bins(&mut umbra)
            .into_par_iter()
            .enumerate()
            .map(|(b, acc)| {
                let start = grid.bin_range(b).start;
                let (bx0, by0, bx1, by1) = grid.bin_cells(b);
                let mut tests = 0u64;
                for &ti in &bin_tris[b] {
                    let t = &tris[ti as usize];
                    let Some((x0, y0, x1, y1)) = grid.cell_range(t.lo, t.hi) else {
                        continue;
                    };
                    let first = grid.first_slice_deeper(t.z_min);
                    for cy in y0.max(by0)..=y1.min(by1) {
                        for cx in x0.max(bx0)..=x1.min(bx1) {
                            for i in grid.column(cx, cy, first) {
                                let s = grid.s[i];
                                if s.x < t.lo.x || s.x > t.hi.x || s.y < t.lo.y || s.y > t.hi.y {
                                    continue;
                                }
                                let zp = grid.z[i];
                                if zp < t.z_min * (1.0 - DEPTH_MARGIN) {
                                    // The whole triangle is beyond the
                                    // receiver.
                                    continue;
                                }
                                tests += 1;
                                let [p0, p1, p2] = t.p;
                                if !(left(p0, p1, s) && left(p1, p2, s) && left(p2, p0, s)) {
                                    continue;
                                }
                                // The ray meets the triangle: it is in
                                // front of the receiver when wholly
                                // nearer, else the exact plane test.
                                let between = zp * (1.0 - DEPTH_MARGIN) > t.z_max
                                    || orient3d(t.world[0], t.world[1], t.world[2], grid.world[i])
                                        == t.light_side.flip();
                                if between {
                                    acc[i - start] += t.weight;
                                }
                            }
                        }
                    }
                }
                tests
            })
            .sum();
        (
            (),
            format!("{} triangles, {tests} point-in-triangle tests", tris.len()),
        )
    });

    // A half layer comes only from a receiver on or inside a closed
    // surface (an odd number of its faces in front of it): the centre is
    // blocked, so it counts as a whole layer.
    for u in &mut umbra {
        *u = u.ceil();
    }
    umbra
}

/// The triangle `t` of a mesh, clipped in front of the light and projected,
/// as umbra triangles (one, or two for a clipped quadrilateral).
fn push_umbra_tri(
    out: &mut Vec<UmbraTri>,
    t: &[u32; 3],
    pos: &[DVec3],
    lf: &[DVec3],
    center: DVec3,
    weight: f64,
    z_near: f64,
) {
    let world = t.map(|i| pos[i as usize]);
    let light_side = orient3d(world[0], world[1], world[2], center);
    if light_side == Sign::Zero {
        return;
    }
    let q = t.map(|i| lf[i as usize]);
    let z_min = q[0].z.min(q[1].z).min(q[2].z);
    // Sutherland–Hodgman against z ≥ z_near, keeping unclipped vertices'
    // projections bit for bit.
    let mut poly: Vec<DVec2> = Vec::with_capacity(4);
    for k in 0..3 {
        let (a, b) = (q[k], q[(k + 1) % 3]);
        if a.z >= z_near {
            poly.push(project(a));
        }
        if (a.z >= z_near) != (b.z >= z_near) {
            if let Some((c, d)) = clip_near(a, b, z_near) {
                poly.push(project(if a.z >= z_near { d } else { c }));
            }
        }
    }
    if poly.len() < 3 || poly.iter().any(|p| !p.is_finite()) {
        return;
    }
    for k in 1..poly.len() - 1 {
        let (p0, mut p1, mut p2) = (poly[0], poly[k], poly[k + 1]);
        match orient2d(p0, p1, p2) {
            Sign::Zero => continue,
            Sign::Negative => std::mem::swap(&mut p1, &mut p2),
            Sign::Positive => {}
        }
        out.push(UmbraTri {
            p: [p0, p1, p2],
            lo: p0.min(p1).min(p2),
            hi: p0.max(p1).max(p2),
            world,
            light_side,
            z_min: z_min.max(z_near),
            z_max: q[0].z.max(q[1].z).max(q[2].z),
            weight,
        });
    }
}
