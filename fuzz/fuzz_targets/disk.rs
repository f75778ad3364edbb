//! Disk-occlusion kernels: invariants and cross-checks on fuzzed input.
//!
//! The first 8 bytes seed the stiff generators of `softshadow::arbitrary`
//! (edges and polygons near the degenerate configurations); the rest are read
//! as raw `f64` bit patterns (anything, NaN and ±∞ included).
#![no_main]

use glam::DVec2;
use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::disk::{clipped_edge, disk_edge, polygon, radius};
use softshadow::arbitrary::Rng;
use softshadow::kernel::catalogue;
use softshadow::kernel::disk::f64 as k;

const EPS: f64 = f64::EPSILON;
/// The error budget of `segment_disk_area` (the kernel catalogue), in
/// `ε·r²`, with a margin of one for the few operations the checks add.
const SLACK: f64 = catalogue::disk::SEGMENT_DISK_AREA.bound + 1.0;

fn word(data: &[u8], i: usize) -> u64 {
    let mut w = [0u8; 8];
    for (j, b) in w.iter_mut().enumerate() {
        *b = data.get(8 * i + j).copied().unwrap_or(0);
    }
    u64::from_le_bytes(w)
}

fuzz_target!(|data: &[u8]| {
    let mut rng = Rng::new(word(data, 0));

    // Segment: exact antisymmetry, bounds, additivity.
    let c = disk_edge(&mut rng);
    let v = k::segment_disk_area(c.r, c.a, c.b);
    assert!(v.is_finite(), "{c:?}");
    assert_eq!(k::segment_disk_area(c.r, c.b, c.a), -v, "{c:?}");
    let r2 = c.r * c.r;
    let tri = c.a.perp_dot(c.b).abs() / 2.0;
    let tri_err = EPS * (c.a.x * c.b.y).abs().max((c.a.y * c.b.x).abs());
    assert!(
        v.abs() <= (tri + tri_err).min(std::f64::consts::PI * r2 / 2.0) + SLACK * EPS * r2,
        "{c:?}: {v}"
    );
    let t = (word(data, 1) >> 11) as f64 / (1u64 << 53) as f64;
    let m = c.a + (c.b - c.a) * t;
    let parts = k::segment_disk_area(c.r, c.a, m) + k::segment_disk_area(c.r, m, c.b);
    // m is rounded off the segment by at most a thin triangle (a, m, b).
    let off = (m - c.a).perp_dot(c.b - c.a).abs() / 2.0
        + EPS * ((m - c.a).length() * (c.b - c.a).length());
    assert!(
        (parts - v).abs() <= 3.0 * SLACK * EPS * r2 + off,
        "{c:?} t={t}: {parts} vs {v}"
    );

    // Polygon: within [0, min(polygon area, πr²)] for a counter-clockwise one.
    let r = radius(&mut rng);
    let poly = polygon(&mut rng, r);
    let area = k::polygon_disk_area(r, &poly);
    let shoelace: f64 = (0..poly.len())
        .map(|i| poly[i].perp_dot(poly[(i + 1) % poly.len()]))
        .sum::<f64>()
        / 2.0;
    let tol = 2.0 * SLACK * EPS * r * r;
    assert!(area >= -tol, "r={r:?} {poly:?}: {area}");
    assert!(
        area <= shoelace.min(std::f64::consts::PI * r * r) * (1.0 + 1e-12) + tol,
        "r={r:?} {poly:?}: {area} > {shoelace}"
    );

    // Circle segment: range, sign flip, additivity.
    let (d, w0, w1) = clipped_edge(&mut rng);
    let s = k::circle_segment_occlusion(d, w0, w1);
    assert!(s.abs() <= 0.5 + EPS);
    assert_eq!(k::circle_segment_occlusion(-d, w0, w1), -s);
    let split = -w0 + (w0 + w1) * t;
    let halves =
        k::circle_segment_occlusion(d, w0, split) + k::circle_segment_occlusion(d, -split, w1);
    assert!(
        (halves - s).abs() <= 8.0 * EPS * (1.0 + w0.abs() + w1.abs()),
        "({d:?}, {w0:?}, {w1:?}) t={t}: {halves} vs {s}"
    );

    // Raw bits: total, never NaN.
    let f = |i: usize| f64::from_bits(word(data, i));
    let (a, b) = (DVec2::new(f(2), f(3)), DVec2::new(f(4), f(5)));
    assert!(!k::segment_disk_area(f(6), a, b).is_nan());
    assert!(!k::polygon_disk_area(f(6), &[a, b, DVec2::new(f(7), f(8))]).is_nan());
    assert!(!k::circle_segment_occlusion(f(2), f(3), f(4)).is_nan());
});
