//! The `f32` kernels against their `f64` twins on the same (`f32`-rounded)
//! input, so that the error is the `f32` arithmetic's and not the input's
//! rounding.

use super::Row;
use crate::kernel::catalogue::disk::SEGMENT_DISK_AREA;
use crate::kernel::catalogue::Stiff;
use crate::kernel::linear_light::{self, OccluderSide};
use crate::kernel::{angle, disk, distortion, falloff, footprint};
use glam::{DVec2, Vec2};

/// Every `f32` kernel's rows.
pub(super) fn rows(rows: &mut Vec<Row>) {
    segment_disk_area_rows(rows);
    visible_part_rows(rows);
    falloff_rows(rows);
    atan2_rows(rows);
    footprint_and_distortion_rows(rows);
}

/// "inside", or why not: inputs of magnitude `scale` round in `f32` by
/// more than the `feature` measured.
fn f32_note(scale: f64, feature: f64) -> String {
    if scale * f64::from(f32::EPSILON) > feature {
        format!("beyond f32's resolution: inputs of magnitude {scale:.0e} round by more than the feature size {feature:.0e}")
    } else {
        "inside".to_owned()
    }
}

/// `segment_disk_area`: a chord at distance `d·r` from the centre, its
/// ends `far` away along the chord, error over r².
fn segment(r: f64, d: f64, far: f64) -> f64 {
    let a = Vec2::new(-far as f32, (d * r) as f32);
    let b = Vec2::new(far as f32, (d * r) as f32);
    let rf = r as f32;
    let got = f64::from(disk::f32::segment_disk_area(rf, a, b));
    let want = disk::f64::segment_disk_area(f64::from(rf), a.as_dvec2(), b.as_dvec2());
    (got - want).abs() / (f64::from(rf) * f64::from(rf))
}

/// The worst of [`segment`] over 41 chords across the disk.
fn chords(r: f64, far: f64) -> f64 {
    (0..=40)
        .map(|i| segment(r, -0.99 + 1.98 * f64::from(i) / 40.0, far))
        .fold(0.0, f64::max)
}

fn segment_disk_area_rows(rows: &mut Vec<Row>) {
    let documented = format!(
        "inside (documented: {} for any edge length)",
        SEGMENT_DISK_AREA.stated()
    );
    let far = [3, 5, 8].map(|e| {
        let case = format!("chord ends 10^{e} away, r = 1");
        (
            Stiff::FarOffset,
            case,
            (41, chords(1.0, 10f64.powi(e))),
            documented.clone(),
        )
    });
    let size = [1e-6, 1e-3, 1e3].map(|r| {
        let case = format!("r = {r:e}, chord ends 2r away");
        (
            Stiff::LightSize,
            case,
            (41, chords(r, 2.0 * r)),
            "inside".to_owned(),
        )
    });
    let grazing = [3, 6].map(|e| {
        let worst = segment(1.0, 1.0 - 10f64.powi(-e), 2.0);
        let case = format!("chord at (1 − 1e-{e})·r");
        (
            Stiff::Grazing,
            case,
            (1, worst),
            f32_note(1.0, 10f64.powi(-e)),
        )
    });
    let cases = far.into_iter().chain(size).chain(grazing);
    Row::push_cases(rows, "f32", "disk::segment_disk_area (error / r²)", cases);
}

/// `linear_light::visible_part`: a light `[x0, x0 + len]` on the x axis,
/// the fragment at height `y` under its middle, the edge on the segment to
/// points across the light; the worst error of the fraction.
fn part(x0: f64, y: f64, len: f64) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..=20 {
        let t = 0.05 + 0.9 * f64::from(i) / 20.0;
        let l = DVec2::new(x0, 0.0);
        let r = DVec2::new(x0 + len, 0.0);
        let f = DVec2::new(x0 + 0.5 * len, -y);
        let e = f + (l + (r - l) * t - f) * 0.5;
        let conv = |p: DVec2| p.as_vec2();
        let got = linear_light::f32::visible_part(
            conv(l),
            conv(r),
            conv(f),
            conv(e),
            OccluderSide::TowardR,
        );
        let want = linear_light::f64::visible_part(
            conv(l).as_dvec2(),
            conv(r).as_dvec2(),
            conv(f).as_dvec2(),
            conv(e).as_dvec2(),
            OccluderSide::TowardR,
        );
        worst = worst.max((f64::from(got.fraction) - want.fraction).abs());
    }
    worst
}

fn visible_part_rows(rows: &mut Vec<Row>) {
    let far = [3, 5, 8].map(|e| {
        let x0 = 10f64.powi(e);
        let case = format!("light 10^{e} from the origin, length 1");
        (
            Stiff::FarOffset,
            case,
            (21, part(x0, 1.0, 1.0)),
            f32_note(x0, 1.0),
        )
    });
    let grazing = [3, 6].map(|e| {
        let case = format!("fragment 1e-{e} from the light's line");
        let worst = part(0.0, 10f64.powi(-e), 1.0);
        (Stiff::Grazing, case, (21, worst), "inside".to_owned())
    });
    let size = [1e-6, 1e3].map(|len| {
        let case = format!("length {len:e}, fragment at 1");
        (
            Stiff::LightSize,
            case,
            (21, part(0.0, 1.0, len)),
            "inside".to_owned(),
        )
    });
    let cases = far.into_iter().chain(grazing).chain(size);
    Row::push_cases(rows, "f32", "linear_light::visible_part (fraction)", cases);
}

/// One `f32` kernel of scalars against its `f64` twin on the same
/// (`f32`-rounded) inputs: the largest error, absolute or relative to the
/// `f64` value.
fn scalar_row(
    rows: &mut Vec<Row>,
    (subject, family, case): (&str, &'static str, String),
    inputs: &[[f64; 3]],
    f32_fn: impl Fn([f32; 3]) -> f32,
    f64_fn: impl Fn([f64; 3]) -> f64,
    relative: bool,
) {
    let mut worst = 0.0f64;
    for x in inputs {
        let xf = x.map(|v| v as f32);
        let got = f64::from(f32_fn(xf));
        let want = f64_fn(xf.map(f64::from));
        let e = if relative {
            (got - want).abs() / want.abs().max(f64::MIN_POSITIVE)
        } else {
            (got - want).abs()
        };
        worst = worst.max(if e.is_nan() { f64::INFINITY } else { e });
    }
    rows.push(Row::new(
        "f32",
        subject,
        family,
        case,
        inputs.len(),
        worst,
        "inside".to_owned(),
    ));
}

/// The falloffs over `[0, 1]` and near their ends.
fn falloff_rows(rows: &mut Vec<Row>) {
    let ramp = |lo: f64, hi: f64, n: usize| -> Vec<[f64; 3]> {
        (0..=n)
            .map(|i| [lo + (hi - lo) * i as f64 / n as f64, 0.0, 0.0])
            .collect()
    };
    let ends = |eps: f64| -> Vec<[f64; 3]> {
        (0..=20)
            .flat_map(|i| {
                let t = eps * (1.0 + i as f64 / 20.0);
                [[t, 0.0, 0.0], [1.0 - t, 0.0, 0.0]]
            })
            .collect()
    };
    for (name, f32_fn, f64_fn) in [
        (
            "falloff::bernstein (absolute)",
            falloff::f32::bernstein as fn(f32) -> f32,
            falloff::f64::bernstein as fn(f64) -> f64,
        ),
        (
            "falloff::disk_edge_falloff (absolute)",
            falloff::f32::disk_edge_falloff,
            falloff::f64::disk_edge_falloff,
        ),
    ] {
        scalar_row(
            rows,
            (name, Stiff::Uniform.name(), "t in [0, 1]".to_owned()),
            &ramp(0.0, 1.0, 200),
            |x| f32_fn(x[0]),
            |x| f64_fn(x[0]),
            false,
        );
        for e in [3, 6] {
            scalar_row(
                rows,
                (
                    name,
                    Stiff::Contact.name(),
                    format!("t within 1e-{e} of 0 and 1"),
                ),
                &ends(10f64.powi(-e)),
                |x| f32_fn(x[0]),
                |x| f64_fn(x[0]),
                false,
            );
        }
    }
}

/// `atan2` at extreme magnitudes and near the axes.
fn atan2_rows(rows: &mut Vec<Row>) {
    let name = "angle::atan2 (relative)";
    for (family, case, scale) in [
        (Stiff::FarOffset.name(), "x and y of magnitude 1e30", 1e30),
        (Stiff::LightSize.name(), "x and y of magnitude 1e-30", 1e-30),
        (Stiff::Uniform.name(), "x and y of magnitude 1", 1.0),
    ] {
        let inputs: Vec<[f64; 3]> = (0..64)
            .map(|i| {
                let a = -3.1 + 6.2 * f64::from(i) / 63.0;
                [a.sin() * scale, a.cos() * scale, 0.0]
            })
            .collect();
        scalar_row(
            rows,
            (name, family, case.to_owned()),
            &inputs,
            |x| angle::f32::atan2(x[0], x[1]),
            |x| angle::f64::atan2(x[0], x[1]),
            true,
        );
    }
    let near_axis: Vec<[f64; 3]> = (1..=30)
        .map(|k| [10f64.powi(-k / 2 - 1), 1.0, 0.0])
        .collect();
    scalar_row(
        rows,
        (
            name,
            Stiff::Grazing.name(),
            "y/x from 1e-1 to 1e-16".to_owned(),
        ),
        &near_axis,
        |x| angle::f32::atan2(x[0], x[1]),
        |x| angle::f64::atan2(x[0], x[1]),
        true,
    );
}

/// The footprint radius and SSOC's distortion at contact and far away.
fn footprint_and_distortion_rows(rows: &mut Vec<Row>) {
    let name = "footprint::radius (relative)";
    for (family, case, inputs) in [
        (
            Stiff::Contact.name(),
            "receiver 1e-3 … 1e-6 past the occluder (relative)",
            (3..=6)
                .map(|e| [0.5, 2.0, 2.0 * (1.0 + 10f64.powi(-e))])
                .collect::<Vec<_>>(),
        ),
        (
            Stiff::LightSize.name(),
            "light radius 1e-6 … 1e3",
            [1e-6, 1e-3, 1.0, 1e3].map(|r| [r, 2.0, 3.0]).to_vec(),
        ),
        (
            Stiff::FarOffset.name(),
            "depths 1e3 … 1e8",
            (3..=8)
                .map(|e| [0.5, 10f64.powi(e), 1.5 * 10f64.powi(e)])
                .collect(),
        ),
    ] {
        scalar_row(
            rows,
            (name, family, case.to_owned()),
            &inputs,
            |x| footprint::f32::radius(x[0], x[1], x[2]),
            |x| footprint::f64::radius(x[0], x[1], x[2]),
            true,
        );
    }
    let name = "distortion::max_distortion (relative)";
    scalar_row(
        rows,
        (
            name,
            Stiff::Contact.name(),
            "receiver 1e-3 … 1e-6 past the near depth".to_owned(),
        ),
        &(3..=6)
            .map(|e| [0.5, 2.0, 2.0 * (1.0 + 10f64.powi(-e))])
            .collect::<Vec<_>>(),
        |x| distortion::f32::max_distortion(x[0], x[1], x[2]),
        |x| distortion::f64::max_distortion(x[0], x[1], x[2]),
        true,
    );
}
