//! Fuzz `kernel::silhouette`: topology from fuzzed index lists (typed errors,
//! never a panic), the closed-cycle invariant of the silhouette edges and
//! even vertex degrees on closed meshes, and `potential_silhouettes ⊇`
//! the exact set from points of a fuzzed sphere.
#![no_main]

use std::collections::HashMap;

use glam::DVec3;
use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::mesh::{any_mesh, closed_mesh, light_point, Mesh, SphereLight};
use softshadow::arbitrary::Rng;
use softshadow::kernel::silhouette::{MeshTopology, SilhouetteEdge, TopologyError};

fn f64_at(data: &[u8], i: usize) -> f64 {
    let mut b = [0u8; 8];
    for (k, byte) in b.iter_mut().enumerate() {
        *byte = data.get(i + k).copied().unwrap_or(0);
    }
    f64::from_bits(u64::from_le_bytes(b))
}

/// Where `predicate::orient3d` is exact: coordinates zero or of magnitude in
/// `[1e-90, 1e90]` (its determinant is cubic in the coordinates: beyond
/// about `1e102` the products overflow, below `1e-90` its error terms
/// underflow). The exact set is only compared with the conservative one
/// inside it.
fn in_domain(p: DVec3) -> bool {
    p.to_array()
        .iter()
        .all(|c| *c == 0.0 || (1e-90..=1e90).contains(&c.abs()))
}

fn check_cycle(topo: &MeshTopology, edges: &[SilhouetteEdge]) {
    let mut balance: HashMap<u32, i64> = HashMap::new();
    let mut degree: HashMap<u32, usize> = HashMap::new();
    for e in edges {
        assert!(e.multiplicity >= 1);
        *balance.entry(e.from).or_default() += i64::from(e.multiplicity);
        *balance.entry(e.to).or_default() -= i64::from(e.multiplicity);
        *degree.entry(e.from).or_default() += 1;
        *degree.entry(e.to).or_default() += 1;
    }
    assert!(balance.values().all(|&b| b == 0), "not a cycle");
    if topo.is_closed_manifold() {
        assert!(
            degree.values().all(|&d| d % 2 == 0),
            "odd degree on a closed mesh"
        );
    }
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 9 {
        return;
    }
    let mut seed = [0u8; 8];
    seed.copy_from_slice(&data[1..9]);
    let mut rng = Rng::new(u64::from_le_bytes(seed));
    let rest = &data[9..];
    let mesh = match data[0] % 3 {
        0 => closed_mesh(&mut rng),
        1 => any_mesh(&mut rng),
        _ => {
            // Raw: a vertex count, indices (some out of range) and position
            // bits straight from the input.
            let vertex_count = usize::from(rest.first().copied().unwrap_or(0) % 12);
            let tri_bytes = rest.get(1..).unwrap_or(&[]);
            let triangles: Vec<[u32; 3]> = tri_bytes
                .chunks_exact(3)
                .take(24)
                .map(|c| [0, 1, 2].map(|k| u32::from(c[k] % 14)))
                .collect();
            let positions: Vec<DVec3> = (0..vertex_count)
                .map(|v| {
                    let base = 1 + 3 * triangles.len() + 24 * v;
                    DVec3::new(
                        f64_at(rest, base),
                        f64_at(rest, base + 8),
                        f64_at(rest, base + 16),
                    )
                })
                .collect();
            let expected = triangles.iter().enumerate().find_map(|(i, t)| {
                t.iter()
                    .position(|&v| v as usize >= vertex_count)
                    .map(|k| (i, k, t[k]))
            });
            match MeshTopology::new(&triangles, vertex_count) {
                Err(TopologyError::IndexOutOfRange {
                    triangle,
                    corner,
                    index,
                    ..
                }) => {
                    assert_eq!(Some((triangle, corner, index)), expected);
                    return;
                }
                Err(e) => panic!("unexpected error {e:?}"),
                Ok(_) => assert!(expected.is_none()),
            }
            Mesh {
                positions,
                triangles,
            }
        }
    };
    let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).expect("valid mesh");
    let x = DVec3::new(f64_at(rest, 0), f64_at(rest, 8), f64_at(rest, 16));
    let mut out = Vec::new();
    match topo.silhouettes_from_point_into(&mesh.positions, x, &mut out) {
        Ok(()) => check_cycle(&topo, &out),
        Err(_) => assert!(!x.is_finite() && out.is_empty()),
    }
    let p32 = mesh.positions_f32();
    if let Ok(s) = topo.silhouettes_from_point(&p32, x) {
        check_cycle(&topo, &s);
    }
    // A sphere: fuzzed bits, or a generated light at the mesh's scale.
    let light = if rest.len() > 40 && rest[24] & 1 == 0 {
        SphereLight {
            center: DVec3::new(f64_at(rest, 25), f64_at(rest, 33), f64_at(rest, 41)),
            radius: f64_at(rest, 49).abs(),
        }
    } else {
        let p = mesh.positions.first().copied().unwrap_or(DVec3::ZERO);
        let p = if p.is_finite() { p } else { DVec3::ZERO };
        SphereLight {
            center: p + DVec3::new(
                rng.uniform(-2.0, 2.0),
                rng.uniform(-2.0, 2.0),
                rng.uniform(-2.0, 2.0),
            ),
            radius: rng.log_uniform(-12.0, 0.0),
        }
    };
    let Ok(potential) = topo.potential_silhouettes(&mesh.positions, light.center, light.radius)
    else {
        assert!(!light.center.is_finite() || !light.radius.is_finite());
        return;
    };
    assert!(potential.windows(2).all(|w| w[0] < w[1]));
    if !(mesh.positions.iter().all(|&p| in_domain(p)) && light.radius <= 1e90) {
        return;
    }
    for k in 0..8 {
        let y = if k == 0 {
            light.center
        } else {
            light_point(&mut rng, &light)
        };
        // Only points provably in the ball (|y − c|² has ≤ 5 roundings).
        let d2 = (y - light.center).length_squared();
        if !in_domain(y)
            || !(k == 0 || d2 * (1.0 + 1e-15) <= light.radius * light.radius * (1.0 - 1e-15))
        {
            continue;
        }
        if let Ok(s) = topo.silhouettes_from_point(&mesh.positions, y) {
            for e in s {
                assert!(
                    potential.binary_search(&e.edge).is_ok(),
                    "edge {} missed from {y:?}",
                    e.edge
                );
            }
        }
    }
});
