//! Silhouette kernels on an 81 920-triangle icosphere (subdivision level 6):
//! topology construction, exact silhouettes from a point (`f64` and `f32`
//! positions, reusing the output `Vec`), and the conservative set for a
//! sphere light.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use softshadow::arbitrary::mesh::icosphere;
use softshadow::glam::{DVec3, Vec3};
use softshadow::kernel::silhouette::MeshTopology;

fn silhouette(c: &mut Criterion) {
    let mesh = icosphere(6);
    let p32 = mesh.positions_f32();
    let topo = MeshTopology::new(&mesh.triangles, mesh.positions.len()).expect("valid mesh");
    let x = DVec3::new(0.3, 2.5, 1.7);
    let mut group = c.benchmark_group("silhouette");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));

    group.bench_function("MeshTopology::new/icosphere6", |b| {
        b.iter(|| MeshTopology::new(black_box(&mesh.triangles), mesh.positions.len()))
    });

    let mut out = Vec::new();
    group.bench_function("silhouettes_from_point_into/f64/icosphere6", |b| {
        b.iter(|| {
            out.clear();
            topo.silhouettes_from_point_into(black_box(&mesh.positions), black_box(x), &mut out)
                .expect("finite input");
            out.len()
        })
    });
    group.bench_function("silhouettes_from_point_into/f32/icosphere6", |b| {
        b.iter(|| {
            out.clear();
            topo.silhouettes_from_point_into(black_box(&p32), black_box(x.as_vec3()), &mut out)
                .expect("finite input");
            out.len()
        })
    });

    let mut edges = Vec::new();
    group.bench_function("potential_silhouettes_into/f64/icosphere6", |b| {
        b.iter(|| {
            edges.clear();
            topo.potential_silhouettes_into(
                black_box(&mesh.positions),
                black_box(x),
                0.3,
                &mut edges,
            )
            .expect("valid sphere");
            edges.len()
        })
    });
    group.bench_function("potential_silhouettes_into/f32/icosphere6", |b| {
        b.iter(|| {
            edges.clear();
            topo.potential_silhouettes_into(
                black_box(&p32),
                black_box(Vec3::new(0.3, 2.5, 1.7)),
                0.3,
                &mut edges,
            )
            .expect("valid sphere");
            edges.len()
        })
    });
    group.finish();
}

criterion_group!(benches, silhouette);
criterion_main!(benches);
