//! Properties of `kernel::silhouette`:
//! the exact silhouette set against a brute-force facing test written here
//! with Shewchuk's `robust::orient3d`, the orientation against an
//! independent central projection, the closed-cycle invariant and even
//! vertex degrees, single loops on convex meshes, the conservative set for
//! sphere lights against sampled light points, and typed errors.
//!
//! `SOFTSHADOW_PRINT_ACCURACY=1 cargo test --test silhouette -- --nocapture`
//! prints the accuracy rows; `SOFTSHADOW_EXHAUSTIVE=1` multiplies the sample
//! counts by 50.

mod support;
use support::{printing, samples};

use std::collections::{BTreeMap, HashMap};

use proptest::prelude::*;
use robust::Coord3D;
use softshadow::arbitrary::mesh::{
    any_mesh, closed_mesh, icosphere, light_point, octahedron, point_near_plane, sphere_light,
    tetrahedron, unit_vector, Mesh, SphereLight,
};
use softshadow::arbitrary::Rng;
use softshadow::glam::{DMat3, DVec3, Vec3};
use softshadow::kernel::silhouette::{
    EdgeKind, MeshTopology, SilhouetteEdge, SilhouetteError, TopologyError, MAX_VERTICES,
};

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Shewchuk's orient3d: positive when `d` is below the plane where `a, b, c`
/// look counter-clockwise from above (the crate's convention too).
fn shewchuk(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

fn finite(p: DVec3) -> bool {
    p.x.is_finite() && p.y.is_finite() && p.z.is_finite()
}

/// Where `predicate::orient3d` is exact: every coordinate zero or of
/// magnitude in `[1e-90, 1e90]` (the determinant is cubic in the
/// coordinates: beyond about `1e102` its products overflow, below `1e-90`
/// its error terms underflow; the predicate's module docs say `1e±140`,
/// which is too wide — reported to the lead). Outside it (e.g. a
/// subnormal coordinate from nudging a zero by a few ulps) intermediate
/// products underflow and the crate's sign may differ from Shewchuk's, so
/// the comparisons with `robust` skip such inputs; the invariants that do
/// not depend on exactness (the cycle, no panic) are still checked there.
fn in_domain(p: DVec3) -> bool {
    p.to_array()
        .iter()
        .all(|c| *c == 0.0 || (1e-90..=1e90).contains(&c.abs()))
}

fn mesh_in_domain(mesh: &Mesh) -> bool {
    mesh.positions.iter().all(|&p| in_domain(p))
}

/// The brute-force silhouette: every face's facing by `robust::orient3d`
/// (front when strictly negative; a non-finite vertex makes the face
/// edge-on), summed per undirected edge into a map from the directed edge
/// (with `m > 0`) to its multiplicity. No topology is shared with the crate.
fn brute_force(mesh: &Mesh, x: DVec3) -> BTreeMap<(u32, u32), u32> {
    let mut m: HashMap<(u32, u32), i64> = HashMap::new();
    for t in &mesh.triangles {
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            continue;
        }
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let front = finite(a) && finite(b) && finite(c) && shewchuk(a, b, c, x) < 0.0;
        let w = if front { 1 } else { -1 };
        for k in 0..3 {
            let (from, to) = (t[k], t[(k + 1) % 3]);
            let (key, sign) = if from < to {
                ((from, to), 1)
            } else {
                ((to, from), -1)
            };
            *m.entry(key).or_insert(0) += w * sign;
        }
    }
    m.into_iter()
        .filter(|&(_, v)| v != 0)
        .map(|((a, b), v)| {
            let key = if v > 0 { (a, b) } else { (b, a) };
            (key, v.unsigned_abs() as u32)
        })
        .collect()
}

fn as_map(edges: &[SilhouetteEdge]) -> BTreeMap<(u32, u32), u32> {
    edges
        .iter()
        .map(|e| ((e.from, e.to), e.multiplicity))
        .collect()
}

/// Viewpoints that stress the predicates: far and near random points, mesh
/// vertices, and points a few ulps off a face plane.
fn viewpoint(rng: &mut Rng, mesh: &Mesh) -> DVec3 {
    let pick = |rng: &mut Rng| mesh.positions[rng.below(mesh.positions.len() as u64) as usize];
    match rng.below(5) {
        0 => pick(rng),
        1 | 2 => {
            let t = mesh.triangles[rng.below(mesh.triangles.len() as u64) as usize];
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let ulps = [0, 1, 4][rng.below(3) as usize];
            point_near_plane(rng, a, b, c, ulps)
        }
        3 => pick(rng) + rng.log_uniform(-6.0, 3.0) * unit_vector(rng),
        _ => rng.log_uniform(-3.0, 6.0) * unit_vector(rng),
    }
}

/// Net multiplicity out minus in at every vertex: zero everywhere for a
/// closed 1-cycle.
fn vertex_balance(edges: &[SilhouetteEdge]) -> HashMap<u32, i64> {
    let mut balance = HashMap::new();
    for e in edges {
        *balance.entry(e.from).or_insert(0) += i64::from(e.multiplicity);
        *balance.entry(e.to).or_insert(0) -= i64::from(e.multiplicity);
    }
    balance
}

fn degree(edges: &[SilhouetteEdge]) -> HashMap<u32, usize> {
    let mut d = HashMap::new();
    for e in edges {
        *d.entry(e.from).or_insert(0) += 1;
        *d.entry(e.to).or_insert(0) += 1;
    }
    d
}

/// Is `p` provably inside the closed ball? `|p − c|²` carries at most 5
/// roundings per term, so a relative `1e-15` margin settles it.
fn provably_in_ball(p: DVec3, light: &SphereLight) -> bool {
    let d2 = (p - light.center).length_squared();
    d2 * (1.0 + 1e-15) <= light.radius * light.radius * (1.0 - 1e-15)
}

// ---------------------------------------------------------------------------
// Exact silhouettes.

proptest! {
    #![proptest_config(ProptestConfig { cases: 384, ..ProptestConfig::default() })]

    /// The crate's set, orientation and multiplicities equal the brute-force
    /// facing test, for every mesh kind and stiff viewpoints, in `f64` and
    /// with `f32` positions (promotion is exact: same answer as the
    /// promoted positions).
    #[test]
    fn matches_brute_force(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let mesh = any_mesh(&mut rng);
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        let mut out = Vec::new();
        for _ in 0..8 {
            let x = viewpoint(&mut rng, &mesh);
            if !in_domain(x) || !mesh_in_domain(&mesh) {
                continue;
            }
            out.clear();
            topo.silhouettes_from_point_into(&mesh.positions, x, &mut out).unwrap();
            prop_assert_eq!(as_map(&out), brute_force(&mesh, x), "x = {:?}", x);
            // One edge at a time: the same edges, orientations and
            // multiplicities, `None` for the others.
            let one: Vec<_> = (0..topo.edges().len() as u32)
                .filter_map(|e| topo.silhouette_edge_from_point(e, &mesh.positions, x).unwrap())
                .collect();
            prop_assert_eq!(&one, &out);
            let p32 = mesh.positions_f32();
            let promoted = Mesh {
                positions: p32.iter().map(|&p| DVec3::from(p)).collect(),
                triangles: mesh.triangles.clone(),
            };
            let x32 = x.as_vec3();
            let s32 = topo.silhouettes_from_point(&p32, x32).unwrap();
            prop_assert_eq!(as_map(&s32), brute_force(&promoted, DVec3::from(x32)));
            // Edge order is edge-index order, and the edge index names the pair.
            prop_assert!(out.windows(2).all(|w| w[0].edge < w[1].edge));
            for e in &out {
                let [v0, v1] = topo.edges()[e.edge as usize];
                prop_assert!((e.from, e.to) == (v0, v1) || (e.from, e.to) == (v1, v0));
            }
        }
    }

    /// The returned edges form a closed 1-cycle (outgoing = incoming
    /// multiplicity at every vertex) for every mesh and viewpoint; on closed
    /// edge-manifold meshes every vertex has even silhouette degree and
    /// every multiplicity is 2.
    #[test]
    fn cycle_and_even_degree(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let closed = rng.chance(0.5);
        let mesh = if closed { closed_mesh(&mut rng) } else { any_mesh(&mut rng) };
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        prop_assert_eq!(topo.is_closed_manifold(), {
            let mut counts: HashMap<(u32, u32), usize> = HashMap::new();
            for t in &mesh.triangles {
                if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] { continue; }
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    *counts.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
            counts.values().all(|&c| c == 2)
        });
        if closed {
            prop_assert!(topo.is_closed_manifold());
        }
        for _ in 0..8 {
            let x = viewpoint(&mut rng, &mesh);
            let s = topo.silhouettes_from_point(&mesh.positions, x).unwrap();
            prop_assert!(vertex_balance(&s).values().all(|&b| b == 0), "x = {:?}", x);
            if topo.is_closed_manifold() {
                prop_assert!(degree(&s).values().all(|&d| d % 2 == 0), "x = {:?}", x);
                prop_assert!(s.iter().all(|e| e.multiplicity == 2));
            }
        }
    }

    /// Orientation: for every returned edge, the incident faces on its left
    /// minus those on its right equal its multiplicity, with "left" decided
    /// independently twice — by `robust::orient3d(from, to, apex, x) < 0`
    /// and, where all three points lie clearly in front of `x`, by the sign
    /// of the 2D cross product of the central projection onto a camera
    /// plane looking from `x` at the edge.
    #[test]
    fn front_faces_on_the_left(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let mesh = any_mesh(&mut rng);
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        for _ in 0..8 {
            let x = viewpoint(&mut rng, &mesh);
            if !in_domain(x) || !mesh_in_domain(&mesh) {
                continue;
            }
            for e in topo.silhouettes_from_point(&mesh.positions, x).unwrap() {
                let (from, to) = (mesh.positions[e.from as usize], mesh.positions[e.to as usize]);
                let mut net = 0i64;
                for face in topo.edge_faces(e.edge as usize) {
                    let t = mesh.triangles[face.face as usize];
                    let apex = t.iter().copied().find(|&v| v != e.from && v != e.to).unwrap();
                    let w = mesh.positions[apex as usize];
                    let o = shewchuk(from, to, w, x);
                    // Edge-on faces count as back-facing: the face's own
                    // traversal reversed, i.e. on the right of its traversal.
                    let traverses = (0..3).any(|k| t[k] == e.from && t[(k + 1) % 3] == e.to);
                    let left = if o == 0.0 { !traverses } else { o < 0.0 };
                    net += if left { 1 } else { -1 };
                    if let Some(left) = projected_left(x, from, to, w) {
                        prop_assert_eq!(left, o < 0.0);
                    }
                }
                prop_assert_eq!(net, i64::from(e.multiplicity));
            }
        }
    }

    /// A convex closed mesh (an affine image of an icosphere, octahedron or
    /// tetrahedron, windings possibly all reversed by the map) seen from a
    /// point outside it: the silhouette is one simple closed loop.
    #[test]
    fn convex_mesh_gives_one_loop(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let base = match rng.below(3) {
            0 => icosphere(rng.below(3) as u32),
            1 => octahedron(),
            _ => tetrahedron().map_positions(|p| p / 3f64.sqrt()),
        };
        // Inside the unit ball; x = M y + t with |y| > 1 is outside M·base + t.
        let m = DMat3::from_cols(unit_vector(&mut rng), unit_vector(&mut rng), unit_vector(&mut rng));
        prop_assume!(m.determinant().abs() > 1e-3);
        let squash = if rng.chance(0.2) { rng.log_uniform(-9.0, -1.0) } else { 1.0 };
        let m = m * DMat3::from_diagonal(DVec3::new(1.0, 1.0, squash));
        let t = rng.log_uniform(-3.0, 3.0) * unit_vector(&mut rng);
        let mesh = base.map_positions(|p| m * p + t);
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        for _ in 0..8 {
            let y = (1.0 + rng.log_uniform(-6.0, 3.0)) * unit_vector(&mut rng);
            let x = m * y + t;
            let s = topo.silhouettes_from_point(&mesh.positions, x).unwrap();
            prop_assert!(!s.is_empty());
            let mut next: HashMap<u32, u32> = HashMap::new();
            for e in &s {
                prop_assert!(next.insert(e.from, e.to).is_none(), "vertex left twice");
            }
            let mut v = s[0].from;
            for _ in 0..s.len() {
                v = next[&v];
            }
            prop_assert_eq!(v, s[0].from);
            let mut count = 0;
            let mut w = s[0].from;
            loop {
                w = next[&w];
                count += 1;
                if w == s[0].from { break; }
            }
            prop_assert_eq!(count, s.len(), "more than one loop");
        }
    }

    /// Non-finite positions: faces with a non-finite vertex are edge-on
    /// (back-facing); no panic, the cycle invariant holds, and the answer
    /// equals the brute force with that rule.
    #[test]
    fn non_finite_positions(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let mut mesh = any_mesh(&mut rng);
        for p in &mut mesh.positions {
            if rng.chance(0.2) {
                p[rng.below(3) as usize] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][rng.below(3) as usize];
            }
        }
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        let x = rng.log_uniform(-3.0, 3.0) * unit_vector(&mut rng);
        let s = topo.silhouettes_from_point(&mesh.positions, x).unwrap();
        let finite_positions: Vec<DVec3> = mesh.positions.iter().copied().filter(|&p| finite(p)).collect();
        if in_domain(x) && finite_positions.iter().all(|&p| in_domain(p)) {
            prop_assert_eq!(as_map(&s), brute_force(&mesh, x));
        }
        prop_assert!(vertex_balance(&s).values().all(|&b| b == 0));
        let bad = DVec3::new(f64::NAN, 0.0, 1.0);
        prop_assert_eq!(topo.silhouettes_from_point(&mesh.positions, bad), Err(SilhouetteError::NonFinitePoint));
        let light = sphere_light(&mut rng);
        let potential = topo.potential_silhouettes(&mesh.positions, light.center, light.radius).unwrap();
        prop_assert!(potential.windows(2).all(|w| w[0] < w[1]));
    }

    /// Bad index lists give the typed error the independent check predicts;
    /// valid ones build, deterministically.
    #[test]
    fn bad_meshes_are_typed_errors(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let vertex_count = rng.below(12) as usize;
        let triangles: Vec<[u32; 3]> = (0..rng.below(10))
            .map(|_| [0; 3].map(|_: u32| rng.below(14) as u32))
            .collect();
        let expected = triangles.iter().enumerate().find_map(|(i, t)| {
            t.iter().position(|&v| v as usize >= vertex_count).map(|k| (i, k, t[k]))
        });
        match (MeshTopology::new(&triangles, vertex_count), expected) {
            (Ok(topo), None) => {
                prop_assert_eq!(topo.vertex_count(), vertex_count);
                prop_assert_eq!(MeshTopology::new(&triangles, vertex_count).unwrap(), topo.clone());
                prop_assert!(topo.edges().windows(2).all(|w| w[0] < w[1]));
                prop_assert!(topo.edges().iter().all(|e| e[0] < e[1]));
            }
            (Err(TopologyError::IndexOutOfRange { triangle, corner, index, vertex_count: n }), Some((i, k, v))) => {
                prop_assert_eq!((triangle, corner, index, n), (i, k, v, vertex_count));
            }
            (got, want) => prop_assert!(false, "got {:?}, expected {:?}", got, want),
        }
    }
}

/// `Some(true)` when `w` lies left of `from → to` in the central projection
/// from `x` onto a camera plane looking at the edge's midpoint, `None` when
/// a point is not clearly in front of `x` or the turn is too close to call
/// in floating point.
fn projected_left(x: DVec3, from: DVec3, to: DVec3, w: DVec3) -> Option<bool> {
    let forward = (0.5 * (from + to) - x).try_normalize()?;
    let right = forward.any_orthonormal_vector();
    let up = right.cross(forward); // right × up = −forward: a right-handed camera looking along +forward
    let project = |p: DVec3| {
        let v = p - x;
        let depth = v.dot(forward);
        (depth > 1e-6 * v.length())
            .then(|| softshadow::glam::DVec2::new(v.dot(right), v.dot(up)) / depth)
    };
    let (a, b, c) = (project(from)?, project(to)?, project(w)?);
    let cross = (b - a).perp_dot(c - a);
    // Image coordinates carry errors of order ε (1 + |coordinate|); a
    // relative 1e-6 of the squared magnitudes is far above that.
    let m = 1.0 + a.length() + b.length() + c.length();
    let scale = m * m;
    (cross.abs() > 1e-6 * scale).then_some(cross > 0.0)
}

// ---------------------------------------------------------------------------
// Conservative silhouettes for a sphere light.

/// Lights that stress the face classification: random ones, and tiny ones
/// (or radius 0) centred a few ulps off a face plane.
fn stiff_light(rng: &mut Rng, mesh: &Mesh) -> SphereLight {
    if rng.chance(0.5) {
        let t = mesh.triangles[rng.below(mesh.triangles.len() as u64) as usize];
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let scale = (b - a).length().max((c - a).length());
        let radius = if rng.chance(0.2) {
            0.0
        } else {
            scale * rng.log_uniform(-16.0, 0.0)
        };
        SphereLight {
            center: point_near_plane(rng, a, b, c, 4),
            radius,
        }
    } else {
        let light = sphere_light(rng);
        let scale = mesh
            .positions
            .iter()
            .map(|p| p.length())
            .fold(0.0, f64::max);
        SphereLight {
            center: light.center * scale,
            radius: light.radius * scale,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// `potential_silhouettes ⊇ silhouettes_from_point(y)` for light points
    /// `y` provably in the ball: the centre, rounded surface points, points
    /// a few ulps off the surface, and interior points.
    #[test]
    fn potential_contains_exact(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let mesh = any_mesh(&mut rng);
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        let light = stiff_light(&mut rng, &mesh);
        let potential = topo.potential_silhouettes(&mesh.positions, light.center, light.radius).unwrap();
        prop_assert!(potential.windows(2).all(|w| w[0] < w[1]));
        let p32 = mesh.positions_f32();
        let potential32 = topo.potential_silhouettes(&p32, light.center, light.radius).unwrap();
        for _ in 0..16 {
            let y = light_point(&mut rng, &light);
            if !(y == light.center || provably_in_ball(y, &light)) {
                continue;
            }
            for e in topo.silhouettes_from_point(&mesh.positions, y).unwrap() {
                prop_assert!(potential.binary_search(&e.edge).is_ok(), "edge {} missed, y = {:?}", e.edge, y);
            }
            for e in topo.silhouettes_from_point(&p32, y).unwrap() {
                prop_assert!(potential32.binary_search(&e.edge).is_ok());
            }
        }
    }
}

#[test]
fn potential_silhouette_tightness() {
    // Over closed meshes and random lights: reported edges against the union
    // of the exact sets from many sampled light points (a lower bound of the
    // true union, so the ratio overestimates the looseness).
    let mut rng = Rng::new(0x5111_0e77);
    let (mut reported, mut seen, mut misses) = (0usize, 0usize, 0usize);
    let cases = samples(60);
    for _ in 0..cases {
        let mesh = closed_mesh(&mut rng);
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        let scale = mesh
            .positions
            .iter()
            .map(|p| p.length())
            .fold(0.0, f64::max);
        let center = scale * rng.uniform(1.5, 4.0) * unit_vector(&mut rng);
        let light = SphereLight {
            center,
            radius: scale * rng.log_uniform(-3.0, -0.5),
        };
        let potential = topo
            .potential_silhouettes(&mesh.positions, light.center, light.radius)
            .unwrap();
        let mut union = std::collections::BTreeSet::new();
        for _ in 0..200 {
            let y = light_point(&mut rng, &light);
            if y != light.center && !provably_in_ball(y, &light) {
                continue;
            }
            for e in topo.silhouettes_from_point(&mesh.positions, y).unwrap() {
                union.insert(e.edge);
                misses += usize::from(potential.binary_search(&e.edge).is_err());
            }
        }
        reported += potential.len();
        seen += union.len();
    }
    if printing() {
        println!(
            "| potential_silhouettes | f64/f32 positions | 0 misses; reported/seen = {:.3} | closed_mesh, light 1.5–4 radii away | {cases} meshes × 200 light points |",
            reported as f64 / seen as f64
        );
    }
    assert_eq!(misses, 0);
    assert!(reported >= seen);
}

// ---------------------------------------------------------------------------
// Topology details and the accuracy rows.

#[test]
fn edge_kinds_and_degenerate_faces() {
    // Square split in two (boundary), a fin on its diagonal (non-manifold),
    // a repeated-index face and a collinear face.
    let positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.5, 0.5, 1.0),
        DVec3::new(2.0, 2.0, 0.0),
    ];
    let triangles = [[0, 1, 2], [0, 2, 3], [0, 2, 4], [1, 1, 3], [0, 2, 5]];
    let topo = MeshTopology::new(&triangles, positions.len()).unwrap();
    assert_eq!(topo.repeated_index_faces(), &[3]);
    let diagonal = topo.edges().iter().position(|&e| e == [0, 2]).unwrap();
    assert_eq!(topo.edge_kind(diagonal), Some(EdgeKind::NonManifold));
    assert_eq!(topo.edge_faces(diagonal).count(), 4);
    assert_eq!(
        topo.non_manifold_edges().collect::<Vec<_>>(),
        vec![diagonal as u32]
    );
    let boundary: Vec<[u32; 2]> = topo
        .boundary_edges()
        .map(|e| topo.edges()[e as usize])
        .collect();
    assert_eq!(
        boundary,
        vec![
            [0, 1],
            [0, 3],
            [0, 4],
            [0, 5],
            [1, 2],
            [2, 3],
            [2, 4],
            [2, 5]
        ]
    );
    assert!(!topo.is_closed_manifold());
    let mut degenerate = Vec::new();
    topo.degenerate_faces_into(&positions, &mut degenerate)
        .unwrap();
    assert_eq!(degenerate, vec![3, 4]);
    // The collinear face is edge-on from everywhere: never front-facing.
    let s = topo
        .silhouettes_from_point(&positions, DVec3::new(0.3, 0.1, 5.0))
        .unwrap();
    assert!(vertex_balance(&s).values().all(|&b| b == 0));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Degenerate faces: exact collinearity against an independent test —
    /// three points are collinear exactly when they are coplanar with each
    /// of the four non-coplanar points 0, X, Y, Z (`robust::orient3d`).
    #[test]
    fn degenerate_faces_match_coplanarity(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let mesh = any_mesh(&mut rng);
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        let mut got = Vec::new();
        topo.degenerate_faces_into(&mesh.positions, &mut got).unwrap();
        let want: Vec<u32> = mesh.triangles.iter().enumerate().filter(|(_, t)| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z].iter().all(|&d| shewchuk(a, b, c, d) == 0.0)
        }).map(|(i, _)| i as u32).collect();
        prop_assert_eq!(got, want);
    }
}

#[test]
fn errors() {
    assert!(matches!(
        MeshTopology::new(&[], MAX_VERTICES + 1),
        Err(TopologyError::TooManyVertices { .. })
    ));
    let mesh = icosphere(1);
    let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
    assert_eq!(
        topo.potential_silhouettes(&mesh.positions, DVec3::ZERO, f64::NAN),
        Err(SilhouetteError::InvalidSphere)
    );
    assert_eq!(
        topo.potential_silhouettes(&mesh.positions, DVec3::splat(f64::INFINITY), 1.0),
        Err(SilhouetteError::InvalidSphere)
    );
    let mut reused = vec![];
    assert!(topo
        .silhouettes_from_point_into(&mesh.positions[1..], DVec3::ZERO, &mut reused)
        .is_err());
    assert!(reused.is_empty());
    let edges = topo.edges().len();
    assert_eq!(
        topo.silhouette_edge_from_point(edges as u32, &mesh.positions, DVec3::ZERO),
        Err(SilhouetteError::EdgeIndex {
            edge: edges as u32,
            edges
        })
    );
    assert_eq!(
        topo.silhouette_edge_from_point(0, &mesh.positions, DVec3::NAN),
        Err(SilhouetteError::NonFinitePoint)
    );
    assert!(matches!(
        topo.silhouette_edge_from_point(0, &mesh.positions[1..], DVec3::ZERO),
        Err(SilhouetteError::PositionCount { .. })
    ));
    let mut degenerate = vec![];
    assert!(topo
        .degenerate_faces_into(&mesh.positions[1..], &mut degenerate)
        .is_err());
    // An f32 mesh and an f64 viewpoint mix freely.
    let p32: Vec<Vec3> = mesh.positions_f32();
    assert!(!topo
        .silhouettes_from_point(&p32, DVec3::new(0.0, 0.0, 3.0))
        .unwrap()
        .is_empty());
}

#[test]
fn accuracy_rows() {
    // The silhouette kernels are exact: the "error" is the number of
    // disagreements with the brute-force robust::orient3d test, asserted 0.
    let mut rng = Rng::new(0xacc_0a11);
    let cases = samples(300);
    let (mut mismatches64, mut mismatches32, mut points) = (0usize, 0usize, 0usize);
    for _ in 0..cases {
        let mesh = any_mesh(&mut rng);
        let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).unwrap();
        let p32 = mesh.positions_f32();
        let promoted = Mesh {
            positions: p32.iter().map(|&p| DVec3::from(p)).collect(),
            triangles: mesh.triangles.clone(),
        };
        for _ in 0..10 {
            let x = viewpoint(&mut rng, &mesh);
            if !in_domain(x) || !mesh_in_domain(&mesh) {
                continue;
            }
            points += 1;
            let s = topo.silhouettes_from_point(&mesh.positions, x).unwrap();
            mismatches64 += usize::from(as_map(&s) != brute_force(&mesh, x));
            let s32 = topo.silhouettes_from_point(&p32, x).unwrap();
            mismatches32 += usize::from(as_map(&s32) != brute_force(&promoted, x));
        }
    }
    if printing() {
        println!("| silhouettes_from_point | f64 | {mismatches64} mismatching sets (exact) | any_mesh + stiff viewpoints | {points} |");
        println!("| silhouettes_from_point | f32 | {mismatches32} mismatching sets (exact) | any_mesh + stiff viewpoints | {points} |");
    }
    assert_eq!((mismatches64, mismatches32), (0, 0));
}
