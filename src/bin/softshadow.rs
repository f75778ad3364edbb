//! The `softshadow` command-line program.
//!
//! Until the renderer lands, running it with no arguments is the kernel
//! self-check: each kernel family evaluated on a case with a closed-form
//! answer, printed side by side with that answer and the error in units of
//! the precision's machine epsilon.

use glam::{DVec2, Vec2};
use softshadow::kernel::{angle, disk, predicate};
use std::f64::consts::PI;
use std::process::ExitCode;

/// One row of the self-check: what was computed, the kernel's value, the
/// closed form, and the error in units of `eps · scale`.
struct Row {
    kernel: &'static str,
    case: String,
    value: f64,
    exact: f64,
    /// Error unit: the precision's epsilon times the quantity's scale.
    unit: f64,
    /// Largest acceptable error, in `unit`s: the kernel's documented budget,
    /// plus the rounding of the closed form evaluated here in `f64`.
    budget: f64,
}

impl Row {
    fn error(&self) -> f64 {
        (self.value - self.exact).abs() / self.unit
    }
}

/// `acos h − h√(1 − h²)`: the unit disk's circular segment beyond a chord at
/// distance `h` (here for moderate `h`, where the direct form is accurate).
fn circular_segment(h: f64) -> f64 {
    let root = ((1.0 - h) * (1.0 + h)).sqrt();
    root.atan2(h) - h * root
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> [DVec2; 4] {
    [
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x1, y1),
        DVec2::new(x0, y1),
    ]
}

fn disk_rows(rows: &mut Vec<Row>) {
    let eps64 = f64::EPSILON;
    let eps32 = f32::EPSILON as f64;
    let half_plane = rect(-1e6, 0.5, 1e6, 1e6);
    rows.push(Row {
        kernel: "disk::f64::polygon_disk_area",
        case: "half-plane y ≥ ½ over the unit disk".into(),
        value: disk::f64::polygon_disk_area(1.0, &half_plane),
        exact: circular_segment(0.5),
        unit: eps64,
        budget: 4.0,
    });
    rows.push(Row {
        kernel: "disk::f32::polygon_disk_area",
        case: "the same, in f32".into(),
        value: disk::f32::polygon_disk_area(1.0, &half_plane.map(|p| p.as_vec2())) as f64,
        exact: circular_segment(0.5),
        unit: eps32,
        budget: 4.0,
    });
    rows.push(Row {
        kernel: "disk::f64::polygon_disk_area",
        case: "square of half-side 0.9 centred on the unit disk".into(),
        value: disk::f64::polygon_disk_area(1.0, &rect(-0.9, -0.9, 0.9, 0.9)),
        exact: PI - 4.0 * circular_segment(0.9),
        unit: eps64,
        // The kernel's budget (4 ε·r²) plus the f64 closed form's own rounding.
        budget: 8.0,
    });
    let h: f64 = 0.3;
    let w = ((1.0 - h) * (1.0 + h)).sqrt();
    rows.push(Row {
        kernel: "disk::f64::circle_segment_occlusion",
        case: "full chord at d = 0.3 (SISM eq. 3)".into(),
        value: disk::f64::circle_segment_occlusion(h, w, w),
        exact: circular_segment(h) / PI,
        unit: eps64,
        budget: 2.0,
    });
    let a = Vec2::new(1e3, 0.25);
    rows.push(Row {
        kernel: "disk::f32::segment_disk_area",
        case: "edge 2000 R long at distance ¼ R".into(),
        value: disk::f32::segment_disk_area(1.0, a, Vec2::new(-1e3, 0.25)) as f64,
        exact: PI / 2.0 - circular_segment(0.25) - (0.25f64 / 1e3).atan(),
        unit: eps32,
        budget: 4.0,
    });
}

fn angle_rows(rows: &mut Vec<Row>) {
    let (y, x) = (1.0, 3f64.sqrt());
    rows.push(Row {
        kernel: "angle::f64::atan2",
        case: "atan2(1, √3) = π/6".into(),
        value: angle::f64::atan2(y, x),
        exact: PI / 6.0,
        unit: f64::EPSILON,
        budget: 2.0,
    });
}

fn predicate_rows(rows: &mut Vec<Row>) {
    // Points a few ulps around (½, ½) against the line y = x through
    // (12, 12) and (24, 24): the exact predicate must call the diagonal ones
    // collinear and the others by the sign of y − x.
    let (b, c) = (DVec2::new(12.0, 12.0), DVec2::new(24.0, 24.0));
    let (mut wrong_exact, mut wrong_naive) = (0, 0);
    for i in 0..64 {
        for j in 0..64 {
            let p = DVec2::new(
                0.5 + i as f64 * f64::EPSILON / 2.0,
                0.5 + j as f64 * f64::EPSILON / 2.0,
            );
            // p − c is exact here, and the line is y = x, so the true side is
            // the sign of p.y − p.x (exact: the two are within a factor 2).
            let truth = (p.y - p.x).partial_cmp(&0.0).map(|o| o as i32).unwrap_or(0);
            let exact = predicate::orient2d(p, b, c).to_i32();
            let naive = (p.x - c.x) * (b.y - c.y) - (p.y - c.y) * (b.x - c.x);
            let naive = naive.partial_cmp(&0.0).map(|o| o as i32).unwrap_or(0);
            wrong_exact += (exact != truth) as usize;
            wrong_naive += (naive != truth) as usize;
        }
    }
    rows.push(Row {
        kernel: "predicate::orient2d",
        case: format!("64×64 near-collinear grid (rounded evaluation: {wrong_naive} wrong)"),
        value: wrong_exact as f64,
        exact: 0.0,
        unit: 1.0,
        budget: 0.0,
    });
}

fn main() -> ExitCode {
    let mut rows = Vec::new();
    disk_rows(&mut rows);
    angle_rows(&mut rows);
    predicate_rows(&mut rows);

    println!(
        "softshadow {} — kernel self-check (closed forms; error in ε·scale)\n",
        env!("CARGO_PKG_VERSION")
    );
    println!(
        "{:<38} {:<58} {:>24} {:>24} {:>8}",
        "kernel", "case", "value", "closed form", "error"
    );
    let mut failed = 0;
    for row in &rows {
        let ok = row.error() <= row.budget;
        failed += (!ok) as usize;
        println!(
            "{:<38} {:<58} {:>24.17e} {:>24.17e} {:>8.2}{}",
            row.kernel,
            row.case,
            row.value,
            row.exact,
            row.error(),
            if ok { "" } else { "  OVER BUDGET" }
        );
    }
    println!(
        "\n{} checks, {} over budget. Measured accuracy: docs/accuracy/kernels.md",
        rows.len(),
        failed
    );
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
