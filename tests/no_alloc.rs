//! The kernels allocate nothing: every hot kernel runs over stiff input with
//! a counting global allocator (dhat in testing mode), which must see no
//! allocation. The silhouette queries append to the caller's `Vec`: given
//! room, they allocate nothing either.

use softshadow::arbitrary::disk::{clipped_edge, disk_edge, polygon, radius};
use softshadow::arbitrary::mesh::{icosphere, wedge_case};
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3, Vec2};
use softshadow::kernel::falloff::Falloff;
use softshadow::kernel::linear_light::OccluderSide;
use softshadow::kernel::silhouette::MeshTopology;
use softshadow::kernel::{angle, disk, distortion, falloff, linear_light, predicate, wedge};
use std::hint::black_box;

#[global_allocator]
static ALLOC: dhat::Alloc = dhat::Alloc;

/// The heap statistics are global, so this file runs without the test
/// harness (`harness = false`): on the main thread alone, with no other
/// thread allocating while it counts.
fn main() {
    the_counter_sees_allocations();
    hot_kernels_do_not_allocate();
    silhouette_queries_reuse_the_callers_buffer();
    println!("no_alloc: 3 passed, 0 failed");
}

/// Heap blocks allocated while running `f` (dhat in testing mode).
fn allocations(f: impl FnOnce()) -> u64 {
    let _profiler = dhat::Profiler::builder().testing().build();
    let before = dhat::HeapStats::get().total_blocks;
    f();
    dhat::HeapStats::get().total_blocks - before
}

fn the_counter_sees_allocations() {
    assert_eq!(allocations(|| drop(black_box(vec![1u8; 8]))), 1);
}

fn hot_kernels_do_not_allocate() {
    // Inputs are built first: only the kernel calls are counted.
    let mut rng = Rng::new(7);
    let edges: Vec<_> = (0..2000).map(|_| disk_edge(&mut rng)).collect();
    let clipped: Vec<_> = (0..2000).map(|_| clipped_edge(&mut rng)).collect();
    let polys: Vec<(f64, Vec<DVec2>)> = (0..200)
        .map(|_| {
            let r = radius(&mut rng);
            (r, polygon(&mut rng, r))
        })
        .collect();
    let wedges: Vec<_> = (0..200).map(|_| wedge_case(&mut rng)).collect();
    let ts: Vec<f64> = (0..2000).map(|_| rng.uniform(-0.5, 1.5)).collect();
    let n = allocations(|| {
        for c in &edges {
            black_box(disk::f64::segment_disk_area(c.r, c.a, c.b));
            black_box(disk::f32::segment_disk_area(
                c.r as f32,
                c.a.as_vec2(),
                c.b.as_vec2(),
            ));
            black_box(angle::f64::atan2(c.a.y, c.b.x));
            black_box(predicate::orient2d(c.a, c.b, DVec2::ZERO));
            black_box(predicate::orient3d(
                c.a.extend(1.0),
                c.b.extend(2.0),
                DVec3::X,
                DVec3::ZERO,
            ));
            black_box(linear_light::f64::visible_part(
                DVec2::new(-1.0, 0.0),
                DVec2::new(1.0, 0.0),
                c.a,
                c.b,
                OccluderSide::TowardR,
            ));
        }
        for &(d, w0, w1) in &clipped {
            black_box(disk::f64::circle_segment_occlusion(d, w0, w1));
            black_box(disk::f32::circle_segment_occlusion(
                d as f32, w0 as f32, w1 as f32,
            ));
        }
        for (r, poly) in &polys {
            black_box(disk::f64::polygon_disk_area(*r, poly));
        }
        for &t in &ts {
            black_box(falloff::f64::disk_edge_falloff(t));
            black_box(falloff::f32::bernstein(t as f32));
            black_box(distortion::f64::intensity(t, 1.0, Falloff::Exact));
            black_box(distortion::f64::max_distortion(0.5, 1.0, 1.0 + t.abs()));
        }
        for w in &wedges {
            let (c, r) = (w.light.center, w.light.radius);
            if let Ok(wedge) = wedge::f64::PenumbraWedge::new(w.e0, w.e1, c, r) {
                black_box(wedge.contains(w.e0 * 2.0 - c));
            }
        }
        let _ = black_box(wedge::f32::penumbra_quad(
            Vec2::ZERO.extend(2.0),
            Vec2::X.extend(3.0),
            0.5,
            10.0,
        ));
    });
    assert_eq!(n, 0, "the kernels allocated {n} times");
}

fn silhouette_queries_reuse_the_callers_buffer() {
    let mesh = icosphere(3);
    let topology = MeshTopology::new(&mesh.triangles, mesh.positions.len()).expect("a valid mesh");
    // Room for every edge: any allocation below is the kernel's own.
    let mut out = Vec::with_capacity(topology.edges().len());
    let mut potential = Vec::with_capacity(topology.edges().len());
    let eye = DVec3::new(3.0, 1.0, 0.5);
    topology
        .silhouettes_from_point_into(&mesh.positions, eye, &mut out)
        .expect("finite input");
    topology
        .potential_silhouettes_into(&mesh.positions, eye, 0.25, &mut potential)
        .expect("finite input");
    let first = out.len();
    assert!(first > 0);
    let n = allocations(|| {
        for k in 0..20 {
            out.clear();
            potential.clear();
            let x = eye + DVec3::splat(1e-3 * k as f64);
            topology
                .silhouettes_from_point_into(&mesh.positions, x, &mut out)
                .expect("finite input");
            topology
                .potential_silhouettes_into(&mesh.positions, x, 0.25, &mut potential)
                .expect("finite input");
            assert!(out.len() <= out.capacity());
        }
    });
    assert_eq!(n, 0, "the silhouette queries allocated {n} times");
}
