//! Penumbra wedges and quads over 1024 fixed-seed cases from the shared
//! generators: `PenumbraWedge::new`, `contains` (16 receivers per wedge),
//! `penumbra_quad`, in `f64` and `f32`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use softshadow::arbitrary::mesh::{light_frame_edge, unit_vector, wedge_case, WedgeCase};
use softshadow::arbitrary::Rng;
use softshadow::glam::DVec3;
use softshadow::kernel::wedge::{f32 as w32, f64 as w64};

const CASES: usize = 1024;

/// A light-frame edge `(e0, e1)` with the light radius and `z_max`.
type QuadCase = (DVec3, DVec3, f64, f64);

fn inputs() -> (Vec<WedgeCase>, Vec<DVec3>, Vec<QuadCase>) {
    let mut rng = Rng::new(0x3ed9e);
    let mut cases = Vec::with_capacity(CASES);
    while cases.len() < CASES {
        let case = wedge_case(&mut rng);
        if w64::PenumbraWedge::new(case.e0, case.e1, case.light.center, case.light.radius).is_ok() {
            cases.push(case);
        }
    }
    // Receivers around each light, at a few times its distance to the edge.
    let receivers = cases
        .iter()
        .map(|c| {
            let mid = 0.5 * (c.e0 + c.e1);
            mid + (mid - c.light.center).length() * rng.uniform(0.0, 2.0) * unit_vector(&mut rng)
        })
        .collect();
    let quads = (0..CASES)
        .map(|_| {
            let radius = rng.log_uniform(-3.0, 1.0);
            let (e0, e1, z_max) = light_frame_edge(&mut rng, radius);
            (e0, e1, radius, z_max)
        })
        .collect();
    (cases, receivers, quads)
}

fn wedge(c: &mut Criterion) {
    let (cases, receivers, quads) = inputs();
    let wedges64: Vec<w64::PenumbraWedge> = cases
        .iter()
        .map(|c| {
            w64::PenumbraWedge::new(c.e0, c.e1, c.light.center, c.light.radius).expect("valid")
        })
        .collect();
    let cases32: Vec<_> = cases
        .iter()
        .map(|c| {
            (
                c.e0.as_vec3(),
                c.e1.as_vec3(),
                c.light.center.as_vec3(),
                c.light.radius as f32,
            )
        })
        .collect();
    let wedges32: Vec<w32::PenumbraWedge> = cases32
        .iter()
        .filter_map(|&(a, b, c, r)| w32::PenumbraWedge::new(a, b, c, r).ok())
        .collect();
    let receivers32: Vec<_> = receivers.iter().map(|p| p.as_vec3()).collect();
    let quads32: Vec<_> = quads
        .iter()
        .map(|&(a, b, r, z)| (a.as_vec3(), b.as_vec3(), r as f32, z as f32))
        .collect();

    let mut group = c.benchmark_group("wedge");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));

    group.bench_function("PenumbraWedge::new/f64/1024", |b| {
        b.iter(|| {
            black_box(&cases)
                .iter()
                .filter(|c| {
                    w64::PenumbraWedge::new(c.e0, c.e1, c.light.center, c.light.radius).is_ok()
                })
                .count()
        })
    });
    group.bench_function("PenumbraWedge::new/f32/1024", |b| {
        b.iter(|| {
            black_box(&cases32)
                .iter()
                .filter(|&&(a, b, c, r)| w32::PenumbraWedge::new(a, b, c, r).is_ok())
                .count()
        })
    });
    group.bench_function("PenumbraWedge::contains/f64/1024x16", |b| {
        b.iter(|| {
            let mut n = 0usize;
            for w in black_box(&wedges64) {
                for p in &receivers[..16] {
                    n += usize::from(w.contains(*p));
                }
            }
            n
        })
    });
    group.bench_function("PenumbraWedge::contains/f32/1024x16", |b| {
        b.iter(|| {
            let mut n = 0usize;
            for w in black_box(&wedges32) {
                for p in &receivers32[..16] {
                    n += usize::from(w.contains(*p));
                }
            }
            n
        })
    });
    group.bench_function("penumbra_quad/f64/1024", |b| {
        b.iter(|| {
            black_box(&quads)
                .iter()
                .filter(|&&(a, b, r, z)| {
                    matches!(w64::penumbra_quad(a, b, r, z), Ok(w64::QuadBound::Quad(_)))
                })
                .count()
        })
    });
    group.bench_function("penumbra_quad/f32/1024", |b| {
        b.iter(|| {
            black_box(&quads32)
                .iter()
                .filter(|&&(a, b, r, z)| {
                    matches!(w32::penumbra_quad(a, b, r, z), Ok(w32::QuadBound::Quad(_)))
                })
                .count()
        })
    });
    group.finish();
}

criterion_group!(benches, wedge);
criterion_main!(benches);
