//! The `f64` kernels against answers known independently: closed forms
//! evaluated without cancellation (a circle segment's area from the
//! half-angle `asin(√δ)`, with a series for thin segments) and exact
//! identities.

use super::plate::segment_area;
use super::Row;
use crate::kernel::catalogue::disk::SEGMENT_DISK_AREA;
use crate::kernel::catalogue::Stiff;
use crate::kernel::disk;
use crate::kernel::falloff::f64 as falloff;
use glam::DVec2;

/// `polygon_disk_area` of a big triangle beyond the chord at distance
/// `(1 − δ)·r`, its corners `far` away: the segment r² (x − sin x)/2 with
/// x = 4 asin(√(δ/2)). The error over r², the measure of the kernel's
/// documented bound (absolute, that of one edge: the catalogue's
/// `SEGMENT_DISK_AREA`); δ is taken from the rounded chord, so that the
/// input's rounding is not counted.
fn cap(r: f64, delta: f64, far: f64) -> f64 {
    let y = (1.0 - delta) * r;
    let tri = [
        DVec2::new(-far, y),
        DVec2::new(far, y),
        DVec2::new(0.0, y + far),
    ];
    let got = disk::f64::polygon_disk_area(r, &tri);
    let delta = (r - y) / r;
    let want = r * r * segment_area(4.0 * (0.5 * delta).sqrt().asin());
    (got - want).abs() / (r * r)
}

/// `polygon_disk_area` far away, for tiny and huge disks, and for thin
/// slivers.
pub(super) fn polygon_disk_area_rows(rows: &mut Vec<Row>) {
    let subject = "disk::polygon_disk_area (error / r²)";
    // A cap is cut by one edge: the bound is that of one edge.
    let documented = format!("inside (documented: {})", SEGMENT_DISK_AREA.stated());
    let mut push = |family, case: String, count, max, note: &str| {
        rows.push(Row::new("f64", subject, family, case, count, max, note));
    };
    let deltas = [0.5, 0.25, 1.0, 1.5, 1.9];
    let worst = |r: f64, far: f64| deltas.iter().map(|&d| cap(r, d, far)).fold(0.0, f64::max);
    for e in [3, 5, 8] {
        let far = 10f64.powi(e);
        push(
            Stiff::FarOffset.name(),
            format!("triangle corners 10^{e} away, r = 1"),
            deltas.len(),
            worst(1.0, far),
            &documented,
        );
    }
    for r in [1e-6, 1e-3, 1e3] {
        push(
            Stiff::LightSize.name(),
            format!("r = {r:e}, corners 10r away"),
            deltas.len(),
            worst(r, 10.0 * r),
            &documented,
        );
    }
    for e in [3, 6, 9, 12] {
        let delta = 10f64.powi(-e);
        push(
            Stiff::Grazing.name(),
            format!("chord at (1 − 1e-{e})·r"),
            1,
            cap(1.0, delta, 4.0),
            &format!(
                "inside (documented: {}, absolute: a sliver's relative error grows as it thins)",
                SEGMENT_DISK_AREA.stated()
            ),
        );
    }
}

/// The straight-edge falloff: F(t) + F(1 − t) = 1 on dyadic t (both
/// exact), F(½) = ½, and thin slivers against the closed form
/// F(t) = (x − sin x)/(2π), x = 4 asin(√t); the Bernstein smoothstep where
/// it is exact.
pub(super) fn falloff_rows(rows: &mut Vec<Row>) {
    let f = falloff::disk_edge_falloff;
    let symmetric = (1..1024)
        .map(|k| {
            let t = f64::from(k) / 1024.0;
            (f(t) + f(1.0 - t) - 1.0).abs()
        })
        .fold((f(0.5) - 0.5).abs(), f64::max);
    let mut cases = vec![(
        Stiff::Symmetry,
        "|F(t) + F(1 − t) − 1| at t = k/1024, and F(½) − ½".to_owned(),
        (1024, symmetric),
        "inside (absolute)",
    )];
    for e in [3, 6, 9, 12] {
        let t = 10f64.powi(-e);
        let want = segment_area(4.0 * t.sqrt().asin()) / std::f64::consts::PI;
        let case = format!("t = 1e-{e} (relative error)");
        cases.push((
            Stiff::Grazing,
            case,
            (1, ((f(t) - want) / want).abs()),
            "inside",
        ));
    }
    Row::push_cases(rows, "f64", "falloff::disk_edge_falloff", cases);
    // The Bernstein smoothstep 3t² − 2t³ is exact in f64 at t = k/1024
    // (30 bits): any difference is the kernel's.
    let b = (0..=1024)
        .map(|k| {
            let t = f64::from(k) / 1024.0;
            (falloff::bernstein(t) - (3.0 * t * t - 2.0 * t * t * t)).abs()
        })
        .fold(0.0, f64::max);
    let case = "t = k/1024 (3t² − 2t³ exact)".to_owned();
    let cases = [(Stiff::ExactPoints, case, (1025, b), "inside (absolute)")];
    Row::push_cases(rows, "f64", "falloff::bernstein", cases);
}
