//! Benchmarks of the falloff, SSOC distortion and linear-light kernels
//! (`kernel::falloff`, `kernel::distortion`, `kernel::linear_light`), both
//! precisions, over deterministic black-boxed input arrays from the shared
//! generators (fixed seeds). Each iteration evaluates the whole array; the
//! reported throughput is per element.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use softshadow::arbitrary::light::{
    distortion_case, embed_3d, falloff_t, linear_light_case, linear_light_well_conditioned,
    LinearLightCase,
};
use softshadow::arbitrary::Rng;
use softshadow::glam::Vec2;
use softshadow::kernel::distortion;
use softshadow::kernel::falloff::{self, Falloff};
use softshadow::kernel::linear_light::{self, OccluderSide};
use std::hint::black_box;
use std::time::Duration;

const N: usize = 1024;

/// Penumbra positions: uniform in `[0, 1]` (the common case in a renderer)
/// and from the stiff generator (branch points, tiny values).
fn positions(seed: u64, stiff: bool) -> Vec<f64> {
    let mut rng = Rng::new(seed);
    (0..N)
        .map(|_| {
            if stiff {
                falloff_t(&mut rng)
            } else {
                rng.unit()
            }
        })
        .collect()
}

fn bench_falloff(c: &mut Criterion) {
    let mut g = c.benchmark_group("falloff");
    g.throughput(Throughput::Elements(N as u64));
    for (label, stiff) in [("uniform", false), ("stiff", true)] {
        let t64 = positions(0xFA11, stiff);
        let t32: Vec<f32> = t64.iter().map(|&t| t as f32).collect();
        g.bench_function(format!("bernstein/f64/{label}"), |b| {
            b.iter(|| {
                black_box(&t64)
                    .iter()
                    .map(|&t| falloff::f64::bernstein(t))
                    .sum::<f64>()
            })
        });
        g.bench_function(format!("bernstein/f32/{label}"), |b| {
            b.iter(|| {
                black_box(&t32)
                    .iter()
                    .map(|&t| falloff::f32::bernstein(t))
                    .sum::<f32>()
            })
        });
        g.bench_function(format!("disk_edge_falloff/f64/{label}"), |b| {
            b.iter(|| {
                black_box(&t64)
                    .iter()
                    .map(|&t| falloff::f64::disk_edge_falloff(t))
                    .sum::<f64>()
            })
        });
        g.bench_function(format!("disk_edge_falloff/f32/{label}"), |b| {
            b.iter(|| {
                black_box(&t32)
                    .iter()
                    .map(|&t| falloff::f32::disk_edge_falloff(t))
                    .sum::<f32>()
            })
        });
    }
    g.finish();
}

fn bench_distortion(c: &mut Criterion) {
    let mut g = c.benchmark_group("distortion");
    g.throughput(Throughput::Elements(N as u64));
    let mut rng = Rng::new(0xD157);
    let cases: Vec<_> = (0..N).map(|_| distortion_case(&mut rng)).collect();
    let depths: Vec<[f64; 3]> = cases
        .iter()
        .map(|c| [c.light_radius, c.z_near, c.z_receiver])
        .collect();
    let depths32: Vec<[f32; 3]> = depths.iter().map(|d| d.map(|x| x as f32)).collect();
    // (d, dmax) pairs: the stiff generator's d against the true dmax.
    let pairs: Vec<[f64; 2]> = cases
        .iter()
        .map(|c| {
            [
                c.d,
                distortion::f64::max_distortion(c.light_radius, c.z_near, c.z_receiver),
            ]
        })
        .collect();
    let pairs32: Vec<[f32; 2]> = pairs.iter().map(|p| p.map(|x| x as f32)).collect();
    g.bench_function("max_distortion/f64", |b| {
        b.iter(|| {
            black_box(&depths)
                .iter()
                .map(|&[r, zn, zp]| distortion::f64::max_distortion(r, zn, zp))
                .sum::<f64>()
        })
    });
    g.bench_function("max_distortion/f32", |b| {
        b.iter(|| {
            black_box(&depths32)
                .iter()
                .map(|&[r, zn, zp]| distortion::f32::max_distortion(r, zn, zp))
                .sum::<f32>()
        })
    });
    for f in [Falloff::Bernstein, Falloff::Exact] {
        g.bench_function(format!("intensity/f64/{f:?}"), |b| {
            b.iter(|| {
                black_box(&pairs)
                    .iter()
                    .map(|&[d, m]| distortion::f64::intensity(d, m, f))
                    .sum::<f64>()
            })
        });
        g.bench_function(format!("intensity/f32/{f:?}"), |b| {
            b.iter(|| {
                black_box(&pairs32)
                    .iter()
                    .map(|&[d, m]| distortion::f32::intensity(d, m, f))
                    .sum::<f32>()
            })
        });
    }
    g.finish();
}

fn bench_linear_light(c: &mut Criterion) {
    let mut g = c.benchmark_group("linear_light");
    g.throughput(Throughput::Elements(N as u64));
    let mut rng = Rng::new(0x11_6E7);
    // Realistic fragments (every angle away from 0 and π, so the exact
    // predicates' filters decide at once) and the stiff generator (near
    // degenerate: many decisions fall through to the exact expansions).
    let well: Vec<LinearLightCase> = (0..N)
        .map(|_| linear_light_well_conditioned(&mut rng))
        .collect();
    let stiff: Vec<LinearLightCase> = (0..N).map(|_| linear_light_case(&mut rng)).collect();
    for (label, cases) in [("well_conditioned", &well), ("stiff", &stiff)] {
        let cases32: Vec<([Vec2; 4], OccluderSide)> = cases
            .iter()
            .map(|c| ([c.l, c.r, c.f, c.e].map(|p| p.as_vec2()), c.side))
            .collect();
        let cases3: Vec<_> = cases.iter().map(|c| embed_3d(c, &mut rng)).collect();
        g.bench_function(format!("visible_part/f64/{label}"), |b| {
            b.iter(|| {
                black_box(cases)
                    .iter()
                    .map(|c| linear_light::f64::visible_part(c.l, c.r, c.f, c.e, c.side).weight_r)
                    .sum::<f64>()
            })
        });
        g.bench_function(format!("visible_part/f32/{label}"), |b| {
            b.iter(|| {
                black_box(&cases32)
                    .iter()
                    .map(|([l, r, f, e], side)| {
                        linear_light::f32::visible_part(*l, *r, *f, *e, *side).weight_r
                    })
                    .sum::<f32>()
            })
        });
        g.bench_function(format!("visible_part_3d/f64/{label}"), |b| {
            b.iter(|| {
                black_box(&cases3)
                    .iter()
                    .map(|c| {
                        linear_light::f64::visible_part_3d(c.l, c.r, c.f, c.e, c.side).weight_r
                    })
                    .sum::<f64>()
            })
        });
        g.bench_function(format!("law_of_sines_fraction/f64/{label}"), |b| {
            b.iter(|| {
                black_box(cases)
                    .iter()
                    .map(|c| {
                        linear_light::f64::law_of_sines_fraction(c.l, c.r, c.f, c.e).unwrap_or(0.0)
                    })
                    .sum::<f64>()
            })
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = bench_falloff, bench_distortion, bench_linear_light
}
criterion_main!(benches);
