//! Generators for meshes, sphere lights and edges (silhouette and wedge
//! kernels).
//!
//! Meshes: closed ones (icospheres, tori, jittered tetrahedra and octahedra,
//! flattened and grid-snapped variants full of coplanar and collinear
//! faces, randomly flipped windings), open ones (height-field grids, spheres
//! with holes), non-manifold ones (fins, solids sharing an edge), and index
//! soups with repeated indices. Lights: sphere lights with log-uniform radii
//! and distances. Edges: zero-length, huge, radial, and passing a few ulps
//! from the light. Points: a few ulps off a face plane, on a light's surface,
//! at its centre.

use std::collections::HashMap;

use glam::DVec3;

use super::Rng;

/// An indexed triangle mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// The positions rounded to `f32`.
    #[must_use]
    pub fn positions_f32(&self) -> Vec<glam::Vec3> {
        self.positions.iter().map(|p| p.as_vec3()).collect()
    }

    /// Applies `f` to every position.
    #[must_use]
    pub fn map_positions(mut self, f: impl Fn(DVec3) -> DVec3) -> Mesh {
        for p in &mut self.positions {
            *p = f(*p);
        }
        self
    }
}

/// A sphere light: centre and radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLight {
    /// The centre.
    pub center: DVec3,
    /// The radius (`> 0` from the generators).
    pub radius: f64,
}

/// A silhouette edge and a sphere light, for the wedge kernels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WedgeCase {
    /// First endpoint.
    pub e0: DVec3,
    /// Second endpoint.
    pub e1: DVec3,
    /// The light.
    pub light: SphereLight,
}

/// The icosphere of subdivision level `level` (`20 · 4^level` triangles),
/// unit radius, centred at the origin, faces counter-clockwise from outside.
#[must_use]
pub fn icosphere(level: u32) -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::with_capacity(triangles.len() * 4);
        let mut midpoint = |a: u32, b: u32, positions: &mut Vec<DVec3>| -> u32 {
            let key = (a.min(b), a.max(b));
            *midpoints.entry(key).or_insert_with(|| {
                let m = (positions[a as usize] + positions[b as usize]).normalize();
                positions.push(m);
                (positions.len() - 1) as u32
            })
        };
        for &[a, b, c] in &triangles {
            let ab = midpoint(a, b, &mut positions);
            let bc = midpoint(b, c, &mut positions);
            let ca = midpoint(c, a, &mut positions);
            next.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    Mesh {
        positions,
        triangles,
    }
}

/// A torus around the z axis: `major` × `minor` quads split in two triangles
/// (`major, minor ≥ 3`), tube radius `tube` around a circle of radius
/// `ring`, faces counter-clockwise from outside when `tube < ring`.
#[must_use]
pub fn torus(major: u32, minor: u32, ring: f64, tube: f64) -> Mesh {
    let (major, minor) = (major.max(3), minor.max(3));
    let mut positions = Vec::with_capacity((major * minor) as usize);
    for i in 0..major {
        let u = 2.0 * core::f64::consts::PI * f64::from(i) / f64::from(major);
        for j in 0..minor {
            let v = 2.0 * core::f64::consts::PI * f64::from(j) / f64::from(minor);
            let rr = ring + tube * v.cos();
            positions.push(DVec3::new(rr * u.cos(), rr * u.sin(), tube * v.sin()));
        }
    }
    Mesh {
        positions,
        triangles: quad_grid(major, minor, |i, j| (i % major) * minor + (j % minor)),
    }
}

/// The regular tetrahedron (4 faces), counter-clockwise from outside.
#[must_use]
pub fn tetrahedron() -> Mesh {
    Mesh {
        positions: vec![
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ],
        triangles: vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
    }
}

/// The regular octahedron (8 faces), counter-clockwise from outside.
#[must_use]
pub fn octahedron() -> Mesh {
    Mesh {
        positions: vec![
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ],
        triangles: vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    }
}

/// A height-field grid of `n × n` quads (`n ≥ 1`) over `[−1, 1]²`, heights
/// from `height`: an open surface whose boundary is the outer square.
#[must_use]
pub fn grid(n: u32, height: impl Fn(f64, f64) -> f64) -> Mesh {
    let n = n.max(1);
    let mut positions = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let x = -1.0 + 2.0 * f64::from(i) / f64::from(n);
            let y = -1.0 + 2.0 * f64::from(j) / f64::from(n);
            positions.push(DVec3::new(x, y, height(x, y)));
        }
    }
    Mesh {
        positions,
        triangles: quad_grid(n, n, |i, j| i * (n + 1) + j),
    }
}

/// Two triangles for each of the `rows × cols` quads whose corners
/// `(i, j)…(i + 1, j + 1)` the index map `id` numbers (wrapping or not).
fn quad_grid(rows: u32, cols: u32, id: impl Fn(u32, u32) -> u32) -> Vec<[u32; 3]> {
    let mut triangles = Vec::with_capacity((2 * rows * cols) as usize);
    for i in 0..rows {
        for j in 0..cols {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    triangles
}

/// A random closed edge-manifold mesh (every edge has exactly two faces):
/// an icosphere, a torus, or a jittered tetrahedron / octahedron, then
/// possibly flattened to near-coplanarity, snapped to a coarse grid
/// (coplanar, collinear and coincident vertices), given randomly flipped
/// windings, and moved to a log-uniform scale and offset.
pub fn closed_mesh(rng: &mut Rng) -> Mesh {
    let mut mesh = match rng.below(5) {
        0 => icosphere(rng.below(3) as u32),
        1 => torus(
            3 + rng.below(10) as u32,
            3 + rng.below(8) as u32,
            1.0,
            rng.uniform(0.05, 0.9),
        ),
        2 => tetrahedron(),
        3 => octahedron(),
        _ => icosphere(0),
    };
    if rng.chance(0.5) {
        let amount = rng.log_uniform(-12.0, -0.5);
        for p in &mut mesh.positions {
            *p += amount
                * DVec3::new(
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(-1.0, 1.0),
                );
        }
    }
    finish(rng, mesh)
}

/// A random open mesh (with boundary edges): a height-field grid, or a
/// closed mesh with some faces removed.
pub fn open_mesh(rng: &mut Rng) -> Mesh {
    let mesh = if rng.chance(0.5) {
        let (a, b) = (rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0));
        let bumpy = rng.chance(0.5);
        grid(1 + rng.below(6) as u32, move |x, y| {
            if bumpy {
                0.3 * (a * x).sin() * (b * y).cos()
            } else {
                0.0
            }
        })
    } else {
        let mut mesh = closed_mesh(rng);
        let keep = rng.uniform(0.3, 0.95);
        let mut kept: Vec<[u32; 3]> = mesh
            .triangles
            .iter()
            .copied()
            .filter(|_| rng.chance(keep))
            .collect();
        if kept.len() == mesh.triangles.len() {
            kept.pop();
        }
        if kept.is_empty() {
            kept.push(mesh.triangles[0]);
        }
        mesh.triangles = kept;
        mesh
    };
    finish(rng, mesh)
}

/// A random non-manifold mesh: a fan of 3–6 triangles on one edge ("fins"),
/// two tetrahedra sharing an edge or a vertex, or a closed mesh with a fin
/// glued to one of its edges.
pub fn non_manifold_mesh(rng: &mut Rng) -> Mesh {
    let mesh = match rng.below(3) {
        0 => {
            let k = 3 + rng.below(4) as u32;
            let mut positions = vec![DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.0, 0.0, 1.0)];
            let mut triangles = Vec::new();
            for i in 0..k {
                let a = rng.uniform(0.0, 2.0 * core::f64::consts::PI);
                positions.push(DVec3::new(a.cos(), a.sin(), rng.uniform(-1.0, 1.0)));
                let apex = 2 + i;
                triangles.push(if rng.chance(0.5) {
                    [0, 1, apex]
                } else {
                    [1, 0, apex]
                });
            }
            Mesh {
                positions,
                triangles,
            }
        }
        1 => {
            // Two tetrahedra glued along the edge 0–1 (the copy rotated about
            // it) or at vertex 0 (the copy reflected through it).
            let a = tetrahedron();
            let share_edge = rng.chance(0.5);
            let (p0, p1) = (a.positions[0], a.positions[1]);
            let rotation =
                glam::DQuat::from_axis_angle((p1 - p0).normalize(), rng.uniform(0.5, 5.5));
            let mut positions = a.positions.clone();
            let base = positions.len() as u32;
            positions.extend(a.positions.iter().map(|&p| {
                if share_edge {
                    p0 + rotation * (p - p0)
                } else {
                    2.0 * p0 - p
                }
            }));
            let glue = |v: u32| match v {
                0 => 0,
                1 if share_edge => 1,
                _ => base + v,
            };
            let mut triangles = a.triangles.clone();
            triangles.extend(a.triangles.iter().map(|t| t.map(glue)));
            Mesh {
                positions,
                triangles,
            }
        }
        _ => {
            let mut mesh = closed_mesh(rng);
            let t = mesh.triangles[rng.below(mesh.triangles.len() as u64) as usize];
            let (a, b) = (t[0], t[1]);
            let apex = mesh.positions.len() as u32;
            let m = 0.5 * (mesh.positions[a as usize] + mesh.positions[b as usize]);
            mesh.positions.push(m * rng.uniform(1.2, 3.0));
            mesh.triangles.push([a, b, apex]);
            return mesh;
        }
    };
    finish(rng, mesh)
}

/// Any mesh: closed, open, non-manifold, or an index soup over a few
/// vertices (repeated indices, duplicate triangles, every edge kind).
pub fn any_mesh(rng: &mut Rng) -> Mesh {
    match rng.below(4) {
        0 => closed_mesh(rng),
        1 => open_mesh(rng),
        2 => non_manifold_mesh(rng),
        _ => {
            let n = 3 + rng.below(8) as u32;
            let positions: Vec<DVec3> = (0..n)
                .map(|_| {
                    DVec3::new(
                        rng.below(3) as f64,
                        rng.below(3) as f64,
                        rng.below(3) as f64,
                    ) + DVec3::splat(rng.uniform(0.0, 1.0) * f64::from(rng.chance(0.5)))
                })
                .collect();
            let triangles = (0..1 + rng.below(16))
                .map(|_| [0, 0, 0].map(|_: u32| rng.below(u64::from(n)) as u32))
                .collect();
            finish(
                rng,
                Mesh {
                    positions,
                    triangles,
                },
            )
        }
    }
}

/// Common finishing: maybe flip windings, flatten, snap to a coarse grid,
/// then scale and translate log-uniformly.
fn finish(rng: &mut Rng, mut mesh: Mesh) -> Mesh {
    if rng.chance(0.2) {
        for t in &mut mesh.triangles {
            if rng.chance(0.3) {
                t.swap(1, 2);
            }
        }
    }
    if rng.chance(0.2) {
        // Near-coplanar: squash one axis by up to 12 decades.
        let squash = rng.log_uniform(-12.0, -1.0);
        let axis = rng.below(3) as usize;
        for p in &mut mesh.positions {
            p[axis] *= squash;
        }
    }
    if rng.chance(0.15) {
        // Snap to a coarse grid: many exactly coplanar and collinear faces.
        let step = [0.5, 0.25, 1.0][rng.below(3) as usize];
        for p in &mut mesh.positions {
            *p = (*p / step).round() * step;
        }
    }
    let scale = rng.log_uniform(-3.0, 3.0);
    let offset = if rng.chance(0.3) {
        DVec3::ZERO
    } else {
        rng.log_uniform(-3.0, 3.0) * DVec3::new(rng.sign(), rng.sign(), rng.sign())
    };
    mesh.map_positions(|p| p * scale + offset)
}

/// A sphere light: radius log-uniform in `[1e-4, 1e2]`, centre at a
/// log-uniform distance in `[1e-2, 1e3]` from the origin in a random
/// direction.
pub fn sphere_light(rng: &mut Rng) -> SphereLight {
    SphereLight {
        center: rng.log_uniform(-2.0, 3.0) * unit_vector(rng),
        radius: rng.log_uniform(-4.0, 2.0),
    }
}

/// A point of the closed ball of `light`, biased to the boundary cases: the
/// centre, the surface (rounded), a few ulps inside or outside it, or
/// uniform in the volume.
pub fn light_point(rng: &mut Rng, light: &SphereLight) -> DVec3 {
    match rng.below(4) {
        0 => light.center,
        1 => light.center + light.radius * unit_vector(rng),
        2 => {
            let p = light.center + light.radius * unit_vector(rng);
            DVec3::new(rng.nudge(p.x, 4), rng.nudge(p.y, 4), rng.nudge(p.z, 4))
        }
        _ => light.center + light.radius * rng.unit().cbrt() * unit_vector(rng),
    }
}

/// A point a few ulps off the plane of triangle `(a, b, c)`: a rounded point
/// of the plane (inside or outside the triangle) with each coordinate moved
/// by up to `ulps` ulps.
pub fn point_near_plane(rng: &mut Rng, a: DVec3, b: DVec3, c: DVec3, ulps: u64) -> DVec3 {
    let (s, t) = (rng.uniform(-2.0, 3.0), rng.uniform(-2.0, 3.0));
    let p = a + s * (b - a) + t * (c - a);
    DVec3::new(
        rng.nudge(p.x, ulps),
        rng.nudge(p.y, ulps),
        rng.nudge(p.z, ulps),
    )
}

/// A uniformly distributed unit vector.
pub fn unit_vector(rng: &mut Rng) -> DVec3 {
    let z = rng.uniform(-1.0, 1.0);
    let phi = rng.uniform(0.0, 2.0 * core::f64::consts::PI);
    let s = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// An edge and a sphere light, biased toward the wedge construction's hard
/// cases: ordinary edges at log-uniform distances and lengths, zero-length
/// edges, huge edges, radial edges (pointing at the light), edges whose line
/// passes through the light, and edges passing a few ulps outside the
/// light's surface (or touching it).
pub fn wedge_case(rng: &mut Rng) -> WedgeCase {
    let light = sphere_light(rng);
    let (c, r) = (light.center, light.radius);
    let dist = r * (1.0 + rng.log_uniform(-3.0, 3.0));
    let dir = unit_vector(rng);
    let q = c + dist * dir; // a point outside the light
    let along = unit_vector(rng);
    let length = r * rng.log_uniform(-4.0, 4.0);
    let (e0, e1) = match rng.below(7) {
        0 => (q, q),
        1 => {
            let big = r * rng.log_uniform(6.0, 12.0);
            (q - big * along, q + big * along)
        }
        2 => {
            // Radial: along the line to the centre, outside the light.
            (q, q + length * dir)
        }
        3 => {
            // The line passes through the light; the segment does not.
            let t0 = dist * rng.uniform(1.01, 2.0);
            (
                c + t0 * dir,
                c + (t0 + length) * dir + 0.1 * r * along.cross(dir),
            )
        }
        4 => {
            // Tangent to the sphere, a few ulps away (or touching).
            let perp = along.cross(dir).normalize_or(dir.any_orthonormal_vector());
            let touch = c + r * dir;
            let e0 = touch - length * perp;
            let e1 = touch + length * perp;
            let ulps = rng.below(64) as i64;
            let push = |p: DVec3| {
                DVec3::new(
                    super::step_ulps(p.x, ulps * dir.x.signum() as i64),
                    super::step_ulps(p.y, ulps * dir.y.signum() as i64),
                    super::step_ulps(p.z, ulps * dir.z.signum() as i64),
                )
            };
            (push(e0), push(e1))
        }
        _ => {
            let mid = rng.uniform(-1.0, 1.0);
            (
                q + (mid - 0.5) * length * along,
                q + (mid + 0.5) * length * along,
            )
        }
    };
    WedgeCase { e0, e1, light }
}

/// An edge in light-frame coordinates (light at the origin, `+z` toward the
/// scene) with both endpoints at depth `z > 0`, and a receiver depth bound
/// `z_max`: log-uniform depths, off-axis angles up to about 80°, lengths
/// over many decades, sometimes radial or with an endpoint beyond `z_max`
/// or inside the light's depth slab.
pub fn light_frame_edge(rng: &mut Rng, radius: f64) -> (DVec3, DVec3, f64) {
    let point = |rng: &mut Rng| {
        let z = radius * (1.0 + rng.log_uniform(-3.0, 3.0));
        let spread = rng.log_uniform(-3.0, 0.7);
        DVec3::new(
            z * spread * rng.uniform(-1.0, 1.0),
            z * spread * rng.uniform(-1.0, 1.0),
            z,
        )
    };
    let e0 = point(rng);
    let e1 = match rng.below(4) {
        0 => e0 * rng.uniform(1.0, 3.0), // radial
        1 => e0 + e0.z * rng.log_uniform(-6.0, 0.0) * unit_vector(rng),
        _ => point(rng),
    };
    let e1 = if e1.z > 0.0 {
        e1
    } else {
        DVec3::new(e1.x, e1.y, e0.z)
    };
    let z_near = e0.z.min(e1.z);
    let z_max =
        z_near * (1.0 + rng.log_uniform(-4.0, 2.0)) * if rng.chance(0.1) { 0.5 } else { 1.0 };
    (e0, e1, z_max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge_counts(mesh: &Mesh) -> HashMap<(u32, u32), usize> {
        let mut counts = HashMap::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *counts.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        counts
    }

    #[test]
    fn closed_generators_are_closed() {
        assert_eq!(icosphere(3).triangles.len(), 1280);
        let mut rng = Rng::new(7);
        for _ in 0..200 {
            let mesh = closed_mesh(&mut rng);
            assert!(edge_counts(&mesh).values().all(|&c| c == 2));
        }
    }

    #[test]
    fn open_generators_have_boundaries() {
        let mut rng = Rng::new(8);
        for _ in 0..100 {
            let mesh = open_mesh(&mut rng);
            assert!(edge_counts(&mesh).values().any(|&c| c == 1));
        }
    }
}
