//! Disk-occlusion kernels against independent answers: a 256-bit evaluation
//! of a different formulation (quadratic line–circle intersection), closed
//! forms, Monte Carlo with a tolerance derived from the sample count, and the
//! algebraic properties of the kernel's contract.
//!
//! `SOFTSHADOW_PRINT_ACCURACY=1 cargo test --release --test disk -- --nocapture`
//! prints the accuracy rows of `docs/accuracy/kernels.md`;
//! `SOFTSHADOW_EXHAUSTIVE=1` multiplies the sample counts by 50.

mod support;
use support::{normal_two_sided_quantile, printing, samples, sidak, Big, Ctx};

use proptest::prelude::*;
use softshadow::arbitrary::disk::{clipped_edge, disk_edge, edge, polygon, radius, DiskEdge};
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, Vec2};
use softshadow::kernel::catalogue;
use softshadow::kernel::disk::{f32 as k32, f64 as k64};
use softshadow::kernel::predicate::{orient2d, Sign};
use std::f64::consts::PI;

const EPS64: f64 = f64::EPSILON;
const EPS32: f64 = f32::EPSILON as f64;

/// Error budgets, from the kernel catalogue: in units of `ε · r²` (segment
/// and polygon areas) or `ε` (the normalised circle-segment occlusion;
/// relative for thin full-chord slivers).
const BUDGET_SEGMENT: f64 = catalogue::disk::SEGMENT_DISK_AREA.bound;
const BUDGET_POLYGON: f64 = catalogue::disk::POLYGON_DISK_AREA.bound;
const BUDGET_CIRCLE_SEGMENT: f64 = catalogue::disk::CIRCLE_SEGMENT_OCCLUSION.bound;
const BUDGET_SLIVER_RELATIVE: f64 = catalogue::disk::THIN_CHORD.bound;

// ---------------------------------------------------------------------------
// The 256-bit references.

/// Signed area of triangle (0, a, b) ∩ disk(0, r), from the parametric
/// intersection `|a + t(b − a)|² = r²` (a different formulation from the
/// kernel's foot-of-perpendicular frame), in 256-bit arithmetic.
fn reference_segment(ctx: &mut Ctx, r: f64, a: DVec2, b: DVec2) -> Big {
    let (r, ax, ay, bx, by) = (
        Big::new(r),
        Big::new(a.x),
        Big::new(a.y),
        Big::new(b.x),
        Big::new(b.y),
    );
    let (dx, dy) = (bx.sub(&ax), by.sub(&ay));
    let qa = dx.mul(&dx).add(&dy.mul(&dy));
    if qa.is_zero() {
        return Big::zero();
    }
    let r2 = r.mul(&r);
    let half = Big::new(0.5);
    let cross = |px: &Big, py: &Big, qx: &Big, qy: &Big| px.mul(qy).sub(&py.mul(qx));
    let dot = |px: &Big, py: &Big, qx: &Big, qy: &Big| px.mul(qx).add(&py.mul(qy));
    let mut sector = |px: &Big, py: &Big, qx: &Big, qy: &Big| {
        let angle = ctx.atan2(&cross(px, py, qx, qy), &dot(px, py, qx, qy));
        r2.mul(&angle).mul(&half)
    };
    let qb = ax.mul(&dx).add(&ay.mul(&dy));
    let qc = ax.mul(&ax).add(&ay.mul(&ay)).sub(&r2);
    let disc = qb.mul(&qb).sub(&qa.mul(&qc));
    if !disc.is_positive() {
        return sector(&ax, &ay, &bx, &by);
    }
    let sq = disc.sqrt();
    let clamp01 = |t: Big| {
        if t.is_negative() {
            Big::zero()
        } else if Big::new(1.0).lt(&t) {
            Big::new(1.0)
        } else {
            t
        }
    };
    let t1 = clamp01(qb.neg().sub(&sq).div(&qa));
    let t2 = clamp01(qb.neg().add(&sq).div(&qa));
    let (p1x, p1y) = (ax.add(&t1.mul(&dx)), ay.add(&t1.mul(&dy)));
    let (p2x, p2y) = (ax.add(&t2.mul(&dx)), ay.add(&t2.mul(&dy)));
    let inner = cross(&p1x, &p1y, &p2x, &p2y).mul(&half);
    sector(&ax, &ay, &p1x, &p1y)
        .add(&inner)
        .add(&sector(&p2x, &p2y, &bx, &by))
}

fn reference_polygon(ctx: &mut Ctx, r: f64, poly: &[DVec2]) -> Big {
    let mut sum = Big::zero();
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        sum = sum.add(&reference_segment(ctx, r, a, b));
    }
    sum
}

/// Johnson et al.'s eq. 3 from the endpoint angles `atan2(w1, d) +
/// atan2(w0, d)` (the kernel uses one `atan2` of a complex product), with the
/// same clipping and sign convention, in 256-bit arithmetic.
fn reference_circle_segment(ctx: &mut Ctx, d: f64, w0: f64, w1: f64) -> Big {
    let sign = if d.is_sign_negative() { -1.0 } else { 1.0 };
    let d = Big::new(d.abs());
    let one = Big::new(1.0);
    if !d.lt(&one) {
        return Big::zero();
    }
    let s = one.sub(&d.mul(&d)).sqrt();
    let clip = |w: f64| {
        let w = Big::new(w);
        if s.lt(&w) {
            s.clone()
        } else if w.lt(&s.neg()) {
            s.neg()
        } else {
            w
        }
    };
    let (w0, w1) = (clip(w0), clip(w1));
    let theta = ctx.atan2(&w1, &d).add(&ctx.atan2(&w0, &d));
    let value = theta.sub(&d.mul(&w0.add(&w1)));
    let two_pi = ctx.pi().mul(&Big::new(2.0));
    value.div(&two_pi).mul(&Big::new(sign))
}

/// Unit-disk circular segment `acos h − h√(1 − h²)`, `0 ≤ h ≤ 1`, with
/// `acos h = atan2(√(1 − h²), h)`, in 256-bit arithmetic.
fn reference_circular_segment(ctx: &mut Ctx, h: f64) -> Big {
    let h = Big::new(h);
    let root = Big::new(1.0).sub(&h.mul(&h)).sqrt();
    ctx.atan2(&root, &h).sub(&h.mul(&root))
}

// ---------------------------------------------------------------------------
// Accuracy against the references (the rows of docs/accuracy/kernels.md).

#[derive(Default)]
struct Worst {
    max: f64,
    case: String,
}

impl Worst {
    fn see(&mut self, err: f64, case: impl FnOnce() -> String) {
        if err > self.max || err.is_nan() {
            self.max = err;
            self.case = case();
        }
    }
}

#[test]
fn segment_disk_area_accuracy() {
    let mut ctx = Ctx::new();
    let n = samples(3000);
    let (mut w64, mut w32) = (Worst::default(), Worst::default());
    let mut rng = Rng::new(0x5e9_d15c);
    for _ in 0..n {
        let c = disk_edge(&mut rng);
        let exact = reference_segment(&mut ctx, c.r, c.a, c.b).to_f64();
        let got = k64::segment_disk_area(c.r, c.a, c.b);
        w64.see((got - exact).abs() / (EPS64 * c.r * c.r), || {
            format!("{c:?}")
        });
        // The f32 kernel against the reference on the same (rounded) input.
        let (r, a, b) = (c.r as f32, c.a.as_vec2(), c.b.as_vec2());
        let exact32 = reference_segment(&mut ctx, r as f64, a.as_dvec2(), b.as_dvec2()).to_f64();
        let got32 = k32::segment_disk_area(r, a, b) as f64;
        let scale = (r as f64) * (r as f64);
        w32.see((got32 - exact32).abs() / (EPS32 * scale), || {
            format!("r={r:?} a={a:?} b={b:?}")
        });
    }
    if printing() {
        println!(
            "| segment_disk_area | f64 | {:.2} ε·r² | disk_edge | {n} |",
            w64.max
        );
        println!(
            "| segment_disk_area | f32 | {:.2} ε·r² | disk_edge | {n} |",
            w32.max
        );
        println!("worst f64: {}\nworst f32: {}", w64.case, w32.case);
    }
    assert!(
        w64.max <= BUDGET_SEGMENT,
        "f64 error {} ε·r² at {}",
        w64.max,
        w64.case
    );
    assert!(
        w32.max <= BUDGET_SEGMENT,
        "f32 error {} ε·r² at {}",
        w32.max,
        w32.case
    );
}

/// Edges the batched form must hand back to the scalar kernel, or get right
/// without it: degenerate, non-finite, beyond the kernel's safe range,
/// exactly on the circle, tangent.
fn awkward_edges(r: f64) -> Vec<(DVec2, DVec2)> {
    let p = DVec2::new(0.3 * r, -1.7 * r);
    let on = DVec2::new(r, 0.0);
    vec![
        (p, p),
        (p, -p),
        (p, 2.0 * p),
        (DVec2::ZERO, DVec2::ZERO),
        (DVec2::ZERO, p),
        (DVec2::new(f64::NAN, 0.0), p),
        (p, DVec2::new(0.0, f64::INFINITY)),
        (
            DVec2::new(f64::NEG_INFINITY, 1.0),
            DVec2::new(f64::INFINITY, 1.0),
        ),
        (DVec2::new(-1e300, r), DVec2::new(1e300, r)),
        (DVec2::new(-1e61, 0.5 * r), DVec2::new(1e61, 0.5 * r)),
        (DVec2::new(-1e59, 0.5 * r), DVec2::new(1e59, 0.5 * r)),
        (on, DVec2::new(0.0, r)),
        (on, -on),
        (DVec2::new(r, -r), DVec2::new(r, r)),
        (DVec2::new(-r, r), DVec2::new(r, r)),
        (DVec2::new(1e-300, 0.0), DVec2::new(0.0, 1e-300)),
        (DVec2::new(-0.0, 0.0), DVec2::new(0.0, -0.0)),
        (DVec2::new(2.0 * r, -0.0), DVec2::new(-0.0, 2.0 * r)),
    ]
}

/// `segment_disk_areas` is `segment_disk_area` edge by edge, bit for bit
/// (both precisions): stiff edges for many radii, the awkward edges above
/// in every lane position, every remainder length, radii outside the safe
/// range. On a processor with AVX2 this runs the vector path.
#[test]
fn segment_disk_areas_is_segment_disk_area_bit_for_bit() {
    let mut rng = Rng::new(0xba7c4);
    let mut out64 = Vec::new();
    let mut out32 = Vec::new();
    let mut checked = 0usize;
    // One precision: the batch against one call per edge, by bits.
    macro_rules! same_bits {
        ($k:ident, $r:expr, $edges:expr, $out:expr) => {
            $k::segment_disk_areas($r, $edges, $out);
            assert_eq!($out.len(), $edges.len());
            for (&(a, b), &got) in $edges.iter().zip($out.iter()) {
                let want = $k::segment_disk_area($r, a, b);
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "{} r={:?} a={a:?} b={b:?}: {got} vs {want}",
                    stringify!($k),
                    $r
                );
            }
        };
    }
    let mut check = |r: f64, edges: &[(DVec2, DVec2)]| {
        same_bits!(k64, r, edges, &mut out64);
        let edges32: Vec<(Vec2, Vec2)> = edges
            .iter()
            .map(|(a, b)| (a.as_vec2(), b.as_vec2()))
            .collect();
        same_bits!(k32, r as f32, &edges32, &mut out32);
        checked += edges.len();
    };
    for _ in 0..samples(60) {
        let r = radius(&mut rng);
        let mut edges: Vec<(DVec2, DVec2)> = (0..200).map(|_| edge(&mut rng, r)).collect();
        check(r, &edges);
        // Every awkward edge in every lane position, amid stiff ones.
        for (i, &e) in awkward_edges(r).iter().enumerate() {
            edges[i % 16] = e;
            edges[100 + i] = e;
        }
        check(r, &edges);
        // Every remainder length.
        for n in 0..=17 {
            check(r, &edges[..n]);
        }
    }
    // Radii outside the safe range, and no radius at all.
    let edges: Vec<(DVec2, DVec2)> = (0..40).map(|_| edge(&mut rng, 1.0)).collect();
    for r in [
        0.0,
        -1.0,
        f64::NAN,
        f64::INFINITY,
        1e-70,
        1e70,
        1e-310,
        1e300,
    ] {
        check(r, &edges);
        check(r, &awkward_edges(1.0));
    }
    assert!(checked > 10_000, "{checked} edges checked");
}

/// Edges for `circle_segment_occlusion` the batch must leave to the scalar
/// path or get exactly right: `d` zero of either sign, at or past ±1, at
/// and around the safe range's floor of both precisions, non-finite input,
/// zero-length and reversed chords, endpoints far beyond the chord, a thin
/// full chord.
fn awkward_occlusions() -> Vec<(f64, f64, f64)> {
    let thin = 1.0 - 1e-15;
    let half = (1.0f64 - thin * thin).sqrt();
    vec![
        (0.0, 1.0, 1.0),
        (-0.0, 1.0, 1.0),
        (0.0, 0.0, 1.0),
        (1.0, 0.0, 0.0),
        (-1.0, 5.0, 5.0),
        (1.0 - f64::EPSILON, 1.0, 1.0),
        (-3.0, 5.0, 5.0),
        (1e-61, 0.5, 0.5),
        (1e-60, 0.5, 0.5),
        (1e-59, 0.5, -0.25),
        (1e-7, 0.5, 0.5),
        (1e-6, 0.5, 0.5),
        (1e-300, 1e-300, 1e-300),
        (f64::NAN, 0.5, 0.5),
        (0.5, f64::INFINITY, 0.5),
        (0.5, 0.5, f64::NEG_INFINITY),
        (0.5, 0.25, -0.25),
        (-0.5, -0.25, 0.25),
        (0.5, -0.6, 0.1),
        (0.5, 1e300, 1e300),
        (-0.5, -1e300, 0.0),
        (thin, half, half),
        (-thin, half, -0.5 * half),
        (0.5, -0.0, 0.0),
    ]
}

/// `circle_segment_occlusions` is `circle_segment_occlusion` edge by edge,
/// bit for bit (both precisions): random clipped edges, the awkward ones
/// above in every lane position, every remainder length. On a processor
/// with AVX2 this runs the vector path.
#[test]
fn circle_segment_occlusions_is_circle_segment_occlusion_bit_for_bit() {
    let mut rng = Rng::new(0x0cc1);
    let (mut out64, mut out32) = (Vec::new(), Vec::new());
    let mut checked = 0usize;
    macro_rules! same_bits {
        ($k:ident, $edges:expr, $out:expr) => {
            $k::circle_segment_occlusions($edges, $out);
            assert_eq!($out.len(), $edges.len());
            for (&(d, w0, w1), &got) in $edges.iter().zip($out.iter()) {
                let want = $k::circle_segment_occlusion(d, w0, w1);
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "{} d={d:?} w0={w0:?} w1={w1:?}: {got} vs {want}",
                    stringify!($k)
                );
            }
        };
    }
    let mut check = |edges: &[(f64, f64, f64)]| {
        same_bits!(k64, edges, &mut out64);
        let edges32: Vec<(f32, f32, f32)> = edges
            .iter()
            .map(|&(d, w0, w1)| (d as f32, w0 as f32, w1 as f32))
            .collect();
        same_bits!(k32, &edges32, &mut out32);
        checked += edges.len();
    };
    let awkward = awkward_occlusions();
    for _ in 0..samples(60) {
        let mut edges: Vec<(f64, f64, f64)> = (0..200).map(|_| clipped_edge(&mut rng)).collect();
        check(&edges);
        for (i, &e) in awkward.iter().enumerate() {
            edges[i % 16] = e;
            edges[100 + i] = e;
        }
        check(&edges);
        for n in 0..=17 {
            check(&edges[..n]);
        }
    }
    assert!(checked > 10_000, "{checked} edges checked");
}

#[test]
fn polygon_disk_area_accuracy() {
    let mut ctx = Ctx::new();
    let n = samples(400);
    let (mut w64, mut w32) = (Worst::default(), Worst::default());
    let mut rng = Rng::new(0x9017_90a1);
    for _ in 0..n {
        let r = softshadow::arbitrary::disk::radius(&mut rng);
        let poly = polygon(&mut rng, r);
        let exact = reference_polygon(&mut ctx, r, &poly).to_f64();
        let got = k64::polygon_disk_area(r, &poly);
        w64.see((got - exact).abs() / (EPS64 * r * r), || {
            format!("r={r:?} {poly:?}")
        });
        let r32 = r as f32;
        let poly32: Vec<Vec2> = poly.iter().map(|p| p.as_vec2()).collect();
        let poly32_64: Vec<DVec2> = poly32.iter().map(|p| p.as_dvec2()).collect();
        let exact32 = reference_polygon(&mut ctx, r32 as f64, &poly32_64).to_f64();
        let got32 = k32::polygon_disk_area(r32, &poly32) as f64;
        let scale = (r32 as f64) * (r32 as f64);
        w32.see((got32 - exact32).abs() / (EPS32 * scale), || {
            format!("r={r32:?} {poly32:?}")
        });
    }
    if printing() {
        println!(
            "| polygon_disk_area | f64 | {:.2} ε·r² | polygon (3–12 vertices) | {n} |",
            w64.max
        );
        println!(
            "| polygon_disk_area | f32 | {:.2} ε·r² | polygon (3–12 vertices) | {n} |",
            w32.max
        );
        println!("worst f64: {}\nworst f32: {}", w64.case, w32.case);
    }
    assert!(
        w64.max <= BUDGET_POLYGON,
        "f64 error {} ε·r² at {}",
        w64.max,
        w64.case
    );
    assert!(
        w32.max <= BUDGET_POLYGON,
        "f32 error {} ε·r² at {}",
        w32.max,
        w32.case
    );
}

#[test]
fn circle_segment_occlusion_accuracy() {
    let mut ctx = Ctx::new();
    let n = samples(3000);
    let (mut w64, mut w32) = (Worst::default(), Worst::default());
    let (mut rel64, mut rel32) = (Worst::default(), Worst::default());
    let mut rng = Rng::new(0xc1_5e9);
    for _ in 0..n {
        let (d, w0, w1) = clipped_edge(&mut rng);
        let exact = reference_circle_segment(&mut ctx, d, w0, w1).to_f64();
        let got = k64::circle_segment_occlusion(d, w0, w1);
        w64.see((got - exact).abs() / EPS64, || {
            format!("({d:?}, {w0:?}, {w1:?})")
        });
        let (d32, a32, b32) = (d as f32, w0 as f32, w1 as f32);
        let exact32 =
            reference_circle_segment(&mut ctx, d32 as f64, a32 as f64, b32 as f64).to_f64();
        let got32 = k32::circle_segment_occlusion(d32, a32, b32) as f64;
        w32.see((got32 - exact32).abs() / EPS32, || {
            format!("({d32:?}, {a32:?}, {b32:?})")
        });
    }
    // Relative accuracy of thin slivers: full chords near the circle.
    let mut rng = Rng::new(0x511_7e5);
    for _ in 0..samples(1000) {
        let h = 1.0 - rng.log_uniform(-15.0, -0.3);
        let s = ((1.0 - h) * (1.0 + h)).sqrt();
        let exact = reference_circle_segment(&mut ctx, h, s, s).to_f64();
        if exact > 0.0 {
            let got = k64::circle_segment_occlusion(h, s, s);
            rel64.see((got - exact).abs() / exact / EPS64, || format!("h={h:?}"));
        }
        let (h32, s32) = (h as f32, s as f32);
        let exact32 =
            reference_circle_segment(&mut ctx, h32 as f64, s32 as f64, s32 as f64).to_f64();
        if exact32 > 1e-30 {
            let got32 = k32::circle_segment_occlusion(h32, s32, s32) as f64;
            rel32.see((got32 - exact32).abs() / exact32 / EPS32, || {
                format!("h={h32:?}")
            });
        }
    }
    if printing() {
        println!(
            "| circle_segment_occlusion | f64 | {:.2} ε (abs) | clipped_edge | {n} |",
            w64.max
        );
        println!(
            "| circle_segment_occlusion | f32 | {:.2} ε (abs) | clipped_edge | {n} |",
            w32.max
        );
        println!("| circle_segment_occlusion, thin full chords | f64 | {:.2} ε (rel) | h = 1 − 10^[−15, −0.3] | {} |", rel64.max, samples(1000));
        println!("| circle_segment_occlusion, thin full chords | f32 | {:.2} ε (rel) | h = 1 − 10^[−15, −0.3] | {} |", rel32.max, samples(1000));
        println!(
            "worst: {} / {} / {} / {}",
            w64.case, w32.case, rel64.case, rel32.case
        );
    }
    assert!(
        w64.max <= BUDGET_CIRCLE_SEGMENT,
        "f64 {} ε at {}",
        w64.max,
        w64.case
    );
    assert!(
        w32.max <= BUDGET_CIRCLE_SEGMENT,
        "f32 {} ε at {}",
        w32.max,
        w32.case
    );
    assert!(
        rel64.max <= BUDGET_SLIVER_RELATIVE,
        "f64 sliver {} ε at {}",
        rel64.max,
        rel64.case
    );
    assert!(
        rel32.max <= BUDGET_SLIVER_RELATIVE,
        "f32 sliver {} ε at {}",
        rel32.max,
        rel32.case
    );
}

// ---------------------------------------------------------------------------
// Closed forms.

/// Asserts `got` within `budget · ε · scale` of `exact`.
fn assert_close(got: f64, exact: f64, scale: f64, budget: f64, what: &str) {
    let err = (got - exact).abs();
    assert!(
        err <= budget * EPS64 * scale,
        "{what}: got {got:e}, exact {exact:e}, error {:.2} ε·scale",
        err / (EPS64 * scale)
    );
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> [DVec2; 4] {
    [
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x1, y1),
        DVec2::new(x0, y1),
    ]
}

#[test]
fn circular_segment_closed_form() {
    // A half-plane y ≥ h (a rectangle reaching far beyond the disk) covers the
    // circular segment r²(acos(h/r) − (h/r)√(1 − (h/r)²)).
    let mut ctx = Ctx::new();
    for r in [1.0, 0.37, 1e-4, 2.5e5] {
        for h_over_r in [0.0, 1e-12, 0.1, 0.5, 0.9, 1.0 - 1e-6, 1.0 - 1e-12, 1.0, 1.5] {
            let h = h_over_r * r;
            let exact = if h_over_r >= 1.0 {
                0.0
            } else {
                reference_circular_segment(&mut ctx, h / r).to_f64() * r * r
            };
            let k = 1e6 * r;
            let got = k64::polygon_disk_area(r, &rect(-k, h, k, k));
            assert_close(
                got,
                exact,
                r * r,
                BUDGET_POLYGON,
                &format!("r={r} h/r={h_over_r}"),
            );
            let got32 =
                k32::polygon_disk_area(r as f32, &rect(-k, h, k, k).map(|p| p.as_vec2())) as f64;
            // The f32 input is the rounded h: compare with the segment at it.
            let h32 = (h as f32) as f64 / (r as f32) as f64;
            let exact32 = if h32 >= 1.0 {
                0.0
            } else {
                reference_circular_segment(&mut ctx, h32).to_f64() * (r as f32 as f64).powi(2)
            };
            let err = (got32 - exact32).abs() / (EPS32 * (r as f32 as f64).powi(2));
            assert!(
                err <= BUDGET_POLYGON,
                "f32 r={r} h/r={h_over_r}: {err} ε·r²"
            );
        }
    }
}

#[test]
fn full_empty_half_disk() {
    for r in [1.0, 3.0e-7, 4.0e7] {
        let full = PI * r * r;
        let k = 10.0 * r;
        assert_close(
            k64::polygon_disk_area(r, &rect(-k, -k, k, k)),
            full,
            r * r,
            4.0,
            "full",
        );
        assert_close(
            k64::polygon_disk_area(r, &rect(-k, 0.0, k, k)),
            full / 2.0,
            r * r,
            4.0,
            "half",
        );
        assert_eq!(
            k64::polygon_disk_area(r, &rect(2.0 * r, 2.0 * r, 3.0 * r, 5.0 * r)),
            0.0
        );
        // Clockwise: the negated area.
        let mut cw = rect(-k, -k, k, k);
        cw.reverse();
        assert_close(
            k64::polygon_disk_area(r, &cw),
            -full,
            r * r,
            4.0,
            "clockwise",
        );
    }
}

#[test]
fn square_centred_on_the_disk() {
    // Half-side s: 4s² while the square is inside (s ≤ r/√2), πr² minus four
    // circular segments at distance s while its corners are outside.
    let mut ctx = Ctx::new();
    let r = 1.0;
    for s in [
        0.1,
        0.5,
        std::f64::consts::FRAC_1_SQRT_2,
        0.75,
        0.9,
        0.999_999,
        1.0,
        2.0,
    ] {
        let exact = if s * s * 2.0 <= r * r {
            4.0 * s * s
        } else if s >= r {
            PI * r * r
        } else {
            PI * r * r - 4.0 * reference_circular_segment(&mut ctx, s / r).to_f64() * r * r
        };
        let got = k64::polygon_disk_area(r, &rect(-s, -s, s, s));
        assert_close(got, exact, r * r, BUDGET_POLYGON, &format!("s={s}"));
    }
}

#[test]
fn circle_segment_closed_forms_and_limits() {
    let mut ctx = Ctx::new();
    // Full chord at distance h: (acos h − h√(1 − h²)) / π.
    for h in [0.0f64, 1e-9, 0.3, 0.8, 1.0 - 1e-9] {
        let s = ((1.0 - h) * (1.0 + h)).sqrt();
        let exact = reference_circular_segment(&mut ctx, h).to_f64() / PI;
        let got = k64::circle_segment_occlusion(h, s, s);
        let tol = BUDGET_SLIVER_RELATIVE * EPS64 * exact.max(EPS64);
        assert!((got - exact).abs() <= tol, "h={h}: {got} vs {exact}");
        // Inside the edge: the same magnitude, subtracted.
        assert_eq!(k64::circle_segment_occlusion(-h, s, s), -got);
    }
    // d = 0 with the full diameter: half the disk; d = ±0 select the sides.
    assert_eq!(k64::circle_segment_occlusion(0.0, 1.0, 1.0), 0.5);
    assert_eq!(k64::circle_segment_occlusion(-0.0, 1.0, 1.0), -0.5);
    // An endpoint at the centre, d = 0: the limit d → 0⁺ (a quarter disk).
    assert_eq!(k64::circle_segment_occlusion(0.0, 0.0, 1.0), 0.25);
    let near = k64::circle_segment_occlusion(1e-12, 0.0, (1.0f64 - 1e-24).sqrt());
    assert!((near - 0.25).abs() < 1e-11);
    // d = R = 1 and beyond: nothing.
    assert_eq!(k64::circle_segment_occlusion(1.0, 0.0, 0.0), 0.0);
    assert_eq!(k64::circle_segment_occlusion(1.0, 5.0, 5.0), 0.0);
    assert_eq!(k64::circle_segment_occlusion(-3.0, 5.0, 5.0), 0.0);
    // Unclipped endpoints are clipped to the chord.
    assert_eq!(
        k64::circle_segment_occlusion(0.6, 100.0, 1e300),
        k64::circle_segment_occlusion(0.6, 0.8, 0.8)
    );
}

#[test]
fn segment_limits() {
    let a = DVec2::new(-0.3, 0.7);
    let b = DVec2::new(2.0, 0.4);
    // R → 0: the area vanishes like R² (the sector R²θ/2), never NaN.
    let theta = a.perp_dot(b).atan2(a.dot(b));
    for r in [1e-10, 1e-100, 1e-300, 5e-324] {
        let got = k64::segment_disk_area(r, a, b);
        let exact = 0.5 * r * r * theta;
        assert!(
            (got - exact).abs() <= 4.0 * EPS64 * exact.abs() + f64::MIN_POSITIVE,
            "r={r}"
        );
    }
    assert_eq!(k64::segment_disk_area(0.0, a, b), 0.0);
    // Zero-length edges, and edges through the centre.
    assert_eq!(k64::segment_disk_area(1.0, a, a), 0.0);
    let c = DVec2::new(-0.25, 0.75); // −3c and 5c are exact
    assert_eq!(k64::segment_disk_area(1.0, -c * 3.0, c * 5.0), 0.0);
    // Both endpoints on the circle: exactly the triangle.
    let (p, q) = (DVec2::new(0.6, 0.8), DVec2::new(-0.8, 0.6));
    assert_close(
        k64::segment_disk_area(1.0, p, q),
        0.5,
        1.0,
        1.0,
        "inscribed",
    );
    // An edge 10⁶ times longer than R at distance h: the triangle (0, a, b)
    // covers the upper half disk less the cap above y = h and less the two
    // thin wedges below the endpoints' angles θa = atan(h / 10⁶).
    let mut ctx = Ctx::new();
    let h = 0.25;
    let got = k64::segment_disk_area(1.0, DVec2::new(1e6, h), DVec2::new(-1e6, h));
    let cap = reference_circular_segment(&mut ctx, h).to_f64();
    let exact = PI / 2.0 - cap - (h / 1e6).atan();
    assert_close(got, exact, 1.0, BUDGET_SEGMENT, "long edge");
}

// ---------------------------------------------------------------------------
// Monte Carlo: polygons with corners inside the disk and several edges
// crossing it, against the fraction of uniform disk samples inside them.

fn inside_polygon(p: DVec2, poly: &[DVec2]) -> bool {
    // Winding number with exact side tests (independent of the disk kernel).
    let mut winding = 0;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if a.y <= p.y {
            if b.y > p.y && orient2d(a, b, p) == Sign::Positive {
                winding += 1;
            }
        } else if b.y <= p.y && orient2d(a, b, p) == Sign::Negative {
            winding -= 1;
        }
    }
    winding != 0
}

#[test]
fn polygon_area_agrees_with_monte_carlo() {
    // For each polygon, N independent uniform samples of the disk give a
    // binomial count with mean N·p, p = area/(πr²) as the kernel claims, and
    // standard deviation √(N p (1 − p)). The per-polygon threshold z is the
    // two-sided normal quantile at a Šidák-corrected significance that keeps
    // the family-wise false-failure probability at 1e-6 over all polygons
    // (z ≈ 6.1 for 40 polygons); seeds are fixed, so the test is
    // deterministic.
    const POLYGONS: usize = 40;
    const N: usize = 100_000;
    let z = normal_two_sided_quantile(sidak(1e-6, POLYGONS));
    let mut rng = Rng::new(0x3c_0dd);
    for case in 0..POLYGONS {
        let r = [1.0, 0.01, 250.0][case % 3];
        let poly = polygon(&mut rng, r);
        let p = k64::polygon_disk_area(r, &poly) / (PI * r * r);
        assert!((-1e-12..=1.0 + 1e-12).contains(&p), "fraction {p}");
        let mut hits = 0usize;
        for _ in 0..N {
            let rho = r * rng.unit().sqrt();
            let phi = rng.uniform(0.0, std::f64::consts::TAU);
            if inside_polygon(DVec2::new(rho * phi.cos(), rho * phi.sin()), &poly) {
                hits += 1;
            }
        }
        let p_hat = hits as f64 / N as f64;
        let sigma = (p.clamp(0.0, 1.0) * (1.0 - p.clamp(0.0, 1.0)) / N as f64).sqrt();
        assert!(
            (p_hat - p).abs() <= z * sigma + 0.5 / N as f64,
            "case {case}: kernel {p}, Monte Carlo {p_hat} ± {sigma} (z = {z:.2}), r={r:?} {poly:?}"
        );
    }
}

// ---------------------------------------------------------------------------
// Properties, for both precisions.

fn case_from_seed(seed: u64) -> DiskEdge {
    disk_edge(&mut Rng::new(seed))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn reversal_negates_exactly(seed in any::<u64>()) {
        let c = case_from_seed(seed);
        prop_assert_eq!(k64::segment_disk_area(c.r, c.b, c.a), -k64::segment_disk_area(c.r, c.a, c.b));
        let (r, a, b) = (c.r as f32, c.a.as_vec2(), c.b.as_vec2());
        prop_assert_eq!(k32::segment_disk_area(r, b, a), -k32::segment_disk_area(r, a, b));
    }

    #[test]
    fn bounded_by_triangle_and_half_disk(seed in any::<u64>()) {
        let c = case_from_seed(seed);
        let got = k64::segment_disk_area(c.r, c.a, c.b);
        let r2 = c.r * c.r;
        let triangle = (Big::new(c.a.x).mul(&Big::new(c.b.y)).sub(&Big::new(c.a.y).mul(&Big::new(c.b.x)))).to_f64().abs() / 2.0;
        let slack = BUDGET_SEGMENT * EPS64 * r2;
        prop_assert!(got.abs() <= triangle.min(PI * r2 / 2.0) + slack, "{:?}: {}", c, got);
        // Sign: that of the orientation of (0, a, b).
        let o = orient2d(DVec2::ZERO, c.a, c.b);
        prop_assert!(got * o.to_i32() as f64 >= 0.0, "{:?}: sign of {} vs {:?}", c, got, o);
    }

    #[test]
    fn additive_when_split(seed in any::<u64>(), t in 0.0f64..1.0) {
        let c = case_from_seed(seed);
        let m = c.a + (c.b - c.a) * t;
        let whole = k64::segment_disk_area(c.r, c.a, c.b);
        let parts = k64::segment_disk_area(c.r, c.a, m) + k64::segment_disk_area(c.r, m, c.b);
        // m is rounded, so it may sit off the segment: the two pieces then
        // differ from the whole by the part of the thin triangle (a, m, b)
        // inside the disk — at most its area, and at most the disk's chord
        // (2r) times its height over ab. Both from the coordinates' exact
        // differences: far from the disk, rounding m − a and b − a moves
        // that area by far more than it is.
        let d1 = (Big::new(m.x).sub(&Big::new(c.a.x)), Big::new(m.y).sub(&Big::new(c.a.y)));
        let d2 = (Big::new(c.b.x).sub(&Big::new(c.a.x)), Big::new(c.b.y).sub(&Big::new(c.a.y)));
        let off = d1.0.mul(&d2.1).sub(&d1.1.mul(&d2.0)).to_f64().abs() / 2.0;
        let height = 2.0 * off / (c.b - c.a).length();
        let inside = off.min(2.0 * c.r * height);
        let tol = 3.0 * BUDGET_SEGMENT * EPS64 * c.r * c.r + inside * (1.0 + 1e-9);
        prop_assert!((whole - parts).abs() <= tol, "{:?} t={}: {} vs {}", c, t, whole, parts);
    }

    #[test]
    fn invariant_under_exact_symmetries(seed in any::<u64>(), k in -300i32..300) {
        let c = case_from_seed(seed);
        let base = k64::segment_disk_area(c.r, c.a, c.b);
        let tol = 2.0 * BUDGET_SEGMENT * EPS64 * c.r * c.r;
        // Quarter turns are exact: the area is unchanged.
        let rot = |p: DVec2| DVec2::new(-p.y, p.x);
        prop_assert!((k64::segment_disk_area(c.r, rot(c.a), rot(c.b)) - base).abs() <= tol);
        // A mirror reverses the orientation.
        let mirror = |p: DVec2| DVec2::new(p.y, p.x);
        prop_assert!((k64::segment_disk_area(c.r, mirror(c.a), mirror(c.b)) + base).abs() <= tol);
        // Power-of-two scaling is exact; the area scales by its square
        // (crossing into and out of the rescaled path).
        let s = 2f64.powi(k);
        let scaled = k64::segment_disk_area(c.r * s, c.a * s, c.b * s);
        let expected = base * s * s;
        if expected.is_normal() || expected == 0.0 {
            prop_assert!((scaled - expected).abs() <= tol * s * s, "{:?} k={}: {} vs {}", c, k, scaled, expected);
        }
    }

    #[test]
    fn monotone_in_radius(seed in any::<u64>(), grow in 1.0f64..4.0) {
        let c = case_from_seed(seed);
        let (small, large) = (k64::segment_disk_area(c.r, c.a, c.b), k64::segment_disk_area(c.r * grow, c.a, c.b));
        let tol = BUDGET_SEGMENT * EPS64 * (c.r * grow).powi(2);
        prop_assert!(large.abs() + tol >= small.abs(), "{:?}: {} then {}", c, small, large);
    }

    #[test]
    fn polygon_area_within_bounds(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let r = softshadow::arbitrary::disk::radius(&mut rng);
        let poly = polygon(&mut rng, r);
        let got = k64::polygon_disk_area(r, &poly);
        let shoelace: f64 = (0..poly.len()).map(|i| poly[i].perp_dot(poly[(i + 1) % poly.len()])).sum::<f64>() / 2.0;
        let tol = BUDGET_POLYGON * EPS64 * r * r;
        prop_assert!(got >= -tol && got <= shoelace.min(PI * r * r) * (1.0 + 1e-12) + tol,
            "r={:?} {:?}: {} (polygon {})", r, poly, got, shoelace);
        // Any starting vertex gives the same sum.
        let mut rotated = poly.clone();
        rotated.rotate_left(1);
        prop_assert!((k64::polygon_disk_area(r, &rotated) - got).abs() <= 2.0 * tol);
        // Cutting a convex polygon along a diagonal: the two parts add up.
        // (A star polygon is star-shaped around its centre, so fan pieces of
        // three consecutive vertices and the rest need convexity; use the
        // triangle fan from vertex 0, valid for convex polygons only.)
        let convex = (0..poly.len()).all(|i| {
            orient2d(poly[i], poly[(i + 1) % poly.len()], poly[(i + 2) % poly.len()]) != Sign::Negative
        });
        if convex {
            let fan: f64 = (1..poly.len() - 1)
                .map(|i| k64::polygon_disk_area(r, &[poly[0], poly[i], poly[i + 1]]))
                .sum();
            prop_assert!((fan - got).abs() <= poly.len() as f64 * tol, "fan {} vs {}", fan, got);
        }
    }

    #[test]
    fn circle_segment_properties(seed in any::<u64>(), t in 0.0f64..1.0) {
        let (d, w0, w1) = clipped_edge(&mut Rng::new(seed));
        let v = k64::circle_segment_occlusion(d, w0, w1);
        prop_assert!(v.abs() <= 0.5 + EPS64);
        // Sign flip with the side, exactly.
        prop_assert_eq!(k64::circle_segment_occlusion(-d, w0, w1), -v);
        // Reversing the edge negates it (positions −w0 → w1 become w1 → −w0).
        let rev = k64::circle_segment_occlusion(d, -w1, -w0);
        prop_assert!((rev + v).abs() <= 2.0 * BUDGET_CIRCLE_SEGMENT * EPS64);
        // Additivity when the edge is split at position m.
        let m = -w0 + (w0 + w1) * t;
        let parts = k64::circle_segment_occlusion(d, w0, m) + k64::circle_segment_occlusion(d, -m, w1);
        prop_assert!((parts - v).abs() <= 4.0 * BUDGET_CIRCLE_SEGMENT * EPS64 + 4.0 * EPS64 * (w0.abs() + w1.abs()),
            "({}, {}, {}) m={}: {} vs {}", d, w0, w1, m, parts, v);
    }

    #[test]
    fn circle_segment_is_sector_minus_triangle(seed in any::<u64>()) {
        // An independent composition through the other kernel: for |d| > 0,
        // the segment's area is the sector the edge subtends minus the
        // triangle (centre, endpoints). The sector is segment_disk_area of
        // the edge pushed radially out of the disk.
        let (d, w0, w1) = clipped_edge(&mut Rng::new(seed));
        let ad = d.abs();
        prop_assume!(ad > 1e-3 && ad < 1.0);
        let s = ((1.0 - ad) * (1.0 + ad)).sqrt();
        let (w0, w1) = (w0.clamp(-s, s), w1.clamp(-s, s));
        // Counter-clockwise about the centre: from +w1 back to −w0.
        let (p0, p1) = (DVec2::new(w1, ad), DVec2::new(-w0, ad));
        let push = 2.0 / ad;
        let sector = k64::segment_disk_area(1.0, p0 * push, p1 * push);
        let triangle = k64::segment_disk_area(1.0, p0, p1);
        let expected = (sector - triangle) / PI;
        let got = k64::circle_segment_occlusion(ad, w0, w1);
        prop_assert!((got - expected).abs() <= 8.0 * EPS64 * push, "({}, {}, {}): {} vs {}", ad, w0, w1, got, expected);
    }

    #[test]
    fn total_on_any_bits(r in any::<u64>(), ax in any::<u64>(), ay in any::<u64>(), bx in any::<u64>(), by in any::<u64>()) {
        let f = f64::from_bits;
        let (a, b) = (DVec2::new(f(ax), f(ay)), DVec2::new(f(bx), f(by)));
        let v = k64::segment_disk_area(f(r), a, b);
        prop_assert!(!v.is_nan());
        prop_assert!(!k64::polygon_disk_area(f(r), &[a, b, DVec2::new(f(ay), f(bx))]).is_nan());
        prop_assert!(!k64::circle_segment_occlusion(f(r), f(ax), f(ay)).is_nan());
        let g = |x: u64| f32::from_bits(x as u32);
        let (a, b) = (Vec2::new(g(ax), g(ay)), Vec2::new(g(bx), g(by)));
        prop_assert!(!k32::segment_disk_area(g(r), a, b).is_nan());
        prop_assert!(!k32::polygon_disk_area(g(r), &[a, b, Vec2::new(g(ay), g(bx))]).is_nan());
        prop_assert!(!k32::circle_segment_occlusion(g(r), g(ax), g(ay)).is_nan());
    }
}

// ---------------------------------------------------------------------------
// Regressions: inputs a numerics review found wrong (exact inputs kept).

/// Long slanted edges pass inside the disk while their endpoints are far:
/// the "no edge touches" fast path once measured the distance from a foot
/// point off by `ε |b − a|` and answered an exact 0.
#[test]
fn regression_long_edges_grazing_the_disk() {
    // The line y = x + 1 is at distance 1/√2: the cap beyond it is π/4 − ½.
    let p = [
        DVec2::new(-3e15, -3e15 + 1.0),
        DVec2::new(5e15, 5e15 + 1.0),
        DVec2::new(-4e15, 4e15),
    ];
    assert_close(
        k64::polygon_disk_area(1.0, &p),
        PI / 4.0 - 0.5,
        1.0,
        BUDGET_POLYGON,
        "y = x + 1",
    );
    let mut ctx = Ctx::new();
    let s = [
        DVec2::new(-1297605.1561524784, 568770.9522962695),
        DVec2::new(1292155.8800703941, -566384.5851406781),
        DVec2::new(-396644.3796997313, -904910.4954396713),
    ];
    let exact = reference_polygon(&mut ctx, 1.0, &s).to_f64();
    assert_close(
        k64::polygon_disk_area(1.0, &s),
        exact,
        1.0,
        BUDGET_POLYGON,
        "1.3e6-long edges",
    );
    let q = [
        Vec2::new(463845.88, 555936.2),
        Vec2::new(-685459.8, -821544.9),
        Vec2::new(-563174.75, 469886.66),
    ];
    let q64: Vec<DVec2> = q.iter().map(|v| v.as_dvec2()).collect();
    let exact = reference_polygon(&mut ctx, 1.0, &q64).to_f64();
    let got = k32::polygon_disk_area(1.0, &q) as f64;
    assert!(
        (got - exact).abs() <= BUDGET_POLYGON * EPS32,
        "f32: {got} vs {exact}"
    );
}

/// Coordinates near 1e165 with a disk of radius 1e50 (no rescaling by the
/// radius alone): `|b − a|²` overflowed in the edge test.
#[test]
fn regression_huge_polygon_small_disk() {
    let p = [
        DVec2::new(-1e165, 0.5e50),
        DVec2::new(1e165, 0.5e50),
        DVec2::new(0.0, 1e166),
    ];
    let r: f64 = 1e50;
    // The cap beyond the chord at distance r/2: r²(π/3 − √3/4).
    let exact = r * r * (PI / 3.0 - 3f64.sqrt() / 4.0);
    let got = k64::polygon_disk_area(r, &p);
    assert!(
        (got - exact).abs() <= 2.0 * BUDGET_POLYGON * EPS64 * r * r,
        "{got:e} vs {exact:e}"
    );
}

/// A non-finite vertex removes its two edges, fast path or not.
#[test]
fn regression_non_finite_vertex_drops_its_edges() {
    let p = [
        DVec2::new(-10.0, -10.0),
        DVec2::new(10.0, -10.0),
        DVec2::new(10.0, 10.0),
        DVec2::new(f64::NAN, f64::NAN),
    ];
    let finite_edges =
        k64::segment_disk_area(1.0, p[0], p[1]) + k64::segment_disk_area(1.0, p[1], p[2]);
    assert_eq!(k64::polygon_disk_area(1.0, &p), finite_edges);
}

/// The documented ratio limit of `segment_disk_area`: at r = 1e-100 ·
/// max|coordinate| the accuracy still holds.
#[test]
fn regression_tiny_disk_long_edge_at_the_domain_limit() {
    let mut ctx = Ctx::new();
    let r = 1e-100;
    let (a, b) = (DVec2::new(-2.0 * r, 0.5 * r), DVec2::new(1.0, 0.5 * r));
    let exact = reference_segment(&mut ctx, r, a, b).to_f64();
    let got = k64::segment_disk_area(r, a, b);
    assert!(
        (got - exact).abs() <= BUDGET_SEGMENT * EPS64 * r * r,
        "{got:e} vs {exact:e}"
    );
}

/// Tiny d and w: c and q underflowed together and θ came out 0.
#[test]
fn regression_circle_segment_at_tiny_scale() {
    // The centre on the edge's line, endpoints a right angle apart: ¼.
    assert_eq!(k64::circle_segment_occlusion(1e-200, 1e-200, 1e-200), 0.25);
    assert_eq!(k32::circle_segment_occlusion(1e-30, 1e-30, 1e-30), 0.25);
    // The limit d → 0⁺ of an edge from the centre: ¼, continuous at d = 0.
    assert_eq!(k64::circle_segment_occlusion(5e-324, 0.0, 0.5), 0.25);
    let mut ctx = Ctx::new();
    let exact = reference_circle_segment(&mut ctx, 1e-160, 2e-160, 1e-161).to_f64();
    let got = k64::circle_segment_occlusion(1e-160, 2e-160, 1e-161);
    assert!(
        (got - exact).abs() <= BUDGET_CIRCLE_SEGMENT * EPS64,
        "{got} vs {exact}"
    );
}
