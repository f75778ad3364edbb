//! Properties and measured accuracy of `kernel::linear_light` (OESS's
//! visible part of a segment light and its endpoint weights), both
//! precisions.
//!
//! Independent answers:
//! - an exact reference: the orientation determinants evaluated exactly as
//!   floating-point expansions (Shewchuk's Grow-Expansion, written here), so
//!   the classification is exact and the crossing parameter
//!   `s = |a|/(|a| + |b|)` is known to ~106 bits whatever the conditioning;
//! - dense midpoint quadrature over the light, each sample point tested for
//!   visibility against an explicit occluder (a half-line from `E` parallel
//!   to the light, on the occluder's side), with `robust`'s exact `orient2d`
//!   and the expansion signs;
//! - the paper's law-of-sines form.
//!
//! `SOFTSHADOW_PRINT_ACCURACY=1 cargo test --test linear_light -- --nocapture`
//! prints the accuracy table rows; `SOFTSHADOW_EXHAUSTIVE=1` runs more
//! samples.

mod support;
use support::{exhaustive, printing};

use proptest::prelude::*;
use softshadow::arbitrary::light::{
    embed_3d, linear_light_case, linear_light_well_conditioned, LinearLightCase,
};
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3, Vec2, Vec3};
use softshadow::kernel::linear_light::{self, OccluderSide};

const U64: f64 = f64::EPSILON / 2.0;
const U32: f64 = f32::EPSILON as f64 / 2.0;

/// Exact arithmetic on floating-point expansions, and a double-double
/// rounding of the result.
mod exact {
    use softshadow::glam::DVec2;

    pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
        let s = a + b;
        let bv = s - a;
        let av = s - bv;
        (s, (a - av) + (b - bv))
    }

    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        let p = a * b;
        (p, a.mul_add(b, -p))
    }

    /// The exact sum of `terms` as a nonoverlapping expansion, least
    /// significant component first (Shewchuk's Grow-Expansion, one term at
    /// a time).
    fn expansion(terms: &[f64]) -> Vec<f64> {
        let mut e: Vec<f64> = Vec::new();
        for &b in terms {
            let mut q = b;
            let mut h = Vec::with_capacity(e.len() + 1);
            for &x in &e {
                let (s, err) = two_sum(q, x);
                if err != 0.0 {
                    h.push(err);
                }
                q = s;
            }
            h.push(q);
            e = h;
        }
        e
    }

    /// `(a − b) × (c − d)`, exactly, as an expansion: each difference is an
    /// exact pair (TwoSum), each product of parts an exact pair (TwoProd).
    fn cross_terms(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Vec<f64> {
        let (px, pxl) = two_sum(a.x, -b.x);
        let (py, pyl) = two_sum(a.y, -b.y);
        let (qx, qxl) = two_sum(c.x, -d.x);
        let (qy, qyl) = two_sum(c.y, -d.y);
        let mut terms = Vec::with_capacity(16);
        for (x, y) in [(px, qy), (px, qyl), (pxl, qy), (pxl, qyl)] {
            let (h, l) = two_prod(x, y);
            terms.extend([h, l]);
        }
        for (x, y) in [(py, qx), (py, qxl), (pyl, qx), (pyl, qxl)] {
            let (h, l) = two_prod(x, y);
            terms.extend([-h, -l]);
        }
        expansion(&terms)
    }

    /// The exact sign of `(a − b) × (c − d)`: the sign of the most
    /// significant component of the nonoverlapping expansion.
    pub fn cross_sign(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> i32 {
        let e = cross_terms(a, b, c, d);
        match e.iter().rev().find(|x| **x != 0.0) {
            Some(x) if *x > 0.0 => 1,
            Some(_) => -1,
            None => 0,
        }
    }

    /// `(a − b) × (c − d)` rounded to a double-double `(hi, lo)`: the
    /// components below the top one sum to less than an ulp of it.
    pub fn cross_dd(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> (f64, f64) {
        let e = cross_terms(a, b, c, d);
        let n = e.len();
        let rest: f64 = e[..n - 1].iter().sum();
        two_sum(e[n - 1], rest)
    }

    /// `x/(x + y)` for double-doubles `x, y ≥ 0`, to about 100 bits.
    pub fn ratio(x: (f64, f64), y: (f64, f64)) -> f64 {
        let (s, e) = two_sum(x.0, y.0);
        let sum = (s, e + x.1 + y.1);
        let q = x.0 / sum.0;
        // One correction step: q + (x − q·sum)/sum.
        let (p, pl) = two_prod(q, sum.0);
        let r = ((x.0 - p) - pl + x.1) - q * sum.1;
        q + r / sum.0
    }
}

/// What the exact reference says about a configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Expected {
    /// No occlusion.
    Full,
    /// The crossing parameter is ≤ 0.
    BeforeL,
    /// ≥ 1.
    BeyondR,
    /// Inside, with `s`, `1 − s` (each to ~100 bits), `|a|`, `|b|` and the
    /// products `|E − F||L − F|`, `|E − F||R − F|` for the error bound.
    Inside {
        s: f64,
        q: f64,
        a: f64,
        b: f64,
        pl: f64,
        pr: f64,
    },
}

/// The exact classification (see the kernel's module docs for the
/// conventions), from exact signs of cross products of differences.
fn expected(l: DVec2, r: DVec2, f: DVec2, e: DVec2) -> Expected {
    // Signed distances from the light's line, and their difference.
    let c_f = exact::cross_sign(r, l, f, l);
    let c_e = exact::cross_sign(r, l, e, l);
    let c_fe = exact::cross_sign(r, l, f, e); // (R − L) × (F − E) = c_F − c_E
    if c_f == 0 || c_fe != c_f || c_e == -c_f {
        return Expected::Full;
    }
    // a = (E − F) × (L − F), b = (E − F) × (R − F); s = a/(a − b),
    // a − b = (E − F) × (L − R).
    let sa = exact::cross_sign(e, f, l, f);
    let sb = exact::cross_sign(e, f, r, f);
    let sd = exact::cross_sign(e, f, l, r);
    if sa * sd <= 0 {
        return Expected::BeforeL;
    }
    if sb * sd >= 0 {
        return Expected::BeyondR;
    }
    let a = exact::cross_dd(e, f, l, f);
    let b = exact::cross_dd(e, f, r, f);
    let abs = |x: (f64, f64)| if x.0 < 0.0 { (-x.0, -x.1) } else { x };
    let (a, b) = (abs(a), abs(b));
    Expected::Inside {
        s: exact::ratio(a, b),
        q: exact::ratio(b, a),
        a: a.0,
        b: b.0,
        pl: (e - f).length() * (l - f).length(),
        pr: (e - f).length() * (r - f).length(),
    }
}

/// The error bound of the stable construction (rigorous, from the kernel's
/// module docs): the cross products of rounded differences, each within
/// `dA = 2u|E − F||L − F| + 2u|a|` (the compensated difference of products
/// is within `2u` relative plus `O(u²)|p||q|`; the rounded differences move
/// the exact cross product by at most `2u|p||q|`), give
/// `|Â/(Â + B̂) − s| ≤ (B·dA + A·dB)/((A + B − dA − dB)(A + B))`; the sum and
/// the quotient round twice more (`2u·ŝ`). The factor `1 + 8u` covers
/// second-order terms (the `O(u²)|p||q|` included) and the rounding of this
/// very expression.
/// `None` when `dA + dB ≥ A + B` (the precision cannot resolve `s`).
fn stable_bound(u: f64, s_or_q: f64, a: f64, b: f64, pl: f64, pr: f64) -> Option<f64> {
    let da = (2.0 * u * pl + 2.0 * u * a) * (1.0 + 8.0 * u);
    let db = (2.0 * u * pr + 2.0 * u * b) * (1.0 + 8.0 * u);
    let margin = a + b - da - db;
    if margin <= 0.0 {
        return None;
    }
    Some(
        ((b * da + a * db) / (margin * (a + b)) + 2.0 * u * s_or_q) * (1.0 + 8.0 * u)
            + f64::MIN_POSITIVE,
    )
}

fn side_name(side: OccluderSide) -> &'static str {
    match side {
        OccluderSide::TowardL => "TowardL",
        OccluderSide::TowardR => "TowardR",
    }
}

/// The visible part the reference implies, as `(start, end, fraction,
/// weight_r, weight_l)` in f64 (from the ~100-bit `s`, `q`).
fn expected_part(x: Expected, side: OccluderSide) -> [f64; 5] {
    let (s, q) = match x {
        Expected::Full => return [0.0, 1.0, 1.0, 0.5, 0.5],
        Expected::BeforeL => (0.0, 1.0),
        Expected::BeyondR => (1.0, 0.0),
        Expected::Inside { s, q, .. } => (s, q),
    };
    match side {
        OccluderSide::TowardR => [0.0, s, s, 0.5 * s * s, 0.5 * s * (1.0 + q)],
        OccluderSide::TowardL => [s, 1.0, q, 0.5 * q * (1.0 + s), 0.5 * q * q],
    }
}

fn parts_f64(p: linear_light::f64::VisiblePart) -> [f64; 5] {
    [p.start, p.end, p.fraction, p.weight_r, p.weight_l]
}

fn parts_f32(p: linear_light::f32::VisiblePart) -> [f64; 5] {
    [
        p.start as f64,
        p.end as f64,
        p.fraction as f64,
        p.weight_r as f64,
        p.weight_l as f64,
    ]
}

fn to_f32(c: &LinearLightCase) -> [Vec2; 4] {
    [c.l.as_vec2(), c.r.as_vec2(), c.f.as_vec2(), c.e.as_vec2()]
}

fn promote(p: [Vec2; 4]) -> [DVec2; 4] {
    p.map(|v| v.as_dvec2())
}

/// Checks one kernel result against the exact reference: the same
/// classification (exact decisions), and inside, `s` (or `1 − s`) within
/// the bound, the weights within the bound plus their own roundings
/// (`|∂w/∂s| ≤ 1`, three roundings). Returns `|ŝ − s|/bound` (0 if clamped).
fn check(got: [f64; 5], x: Expected, side: OccluderSide, u: f64, what: &str) -> f64 {
    let want = expected_part(x, side);
    match x {
        Expected::Inside { s, q, a, b, pl, pr } => {
            let (param, exact_param, frac) = match side {
                OccluderSide::TowardR => (got[1], s, s),
                OccluderSide::TowardL => (got[0], s, q),
            };
            let Some(bound) = stable_bound(u, frac.max(s), a, b, pl, pr) else {
                return 0.0;
            };
            let err = (param - exact_param).abs().max((got[2] - want[2]).abs());
            assert!(
                err <= bound,
                "{what}: error {err:e} > bound {bound:e}; got {got:?}, want {want:?}"
            );
            for k in 3..5 {
                let werr = (got[k] - want[k]).abs();
                assert!(
                    werr <= bound + 4.0 * u * want[k],
                    "{what}: weight {k}: {werr:e} > {bound:e}"
                );
            }
            err / bound
        }
        _ => {
            assert_eq!(got, want, "{what}: classification");
            0.0
        }
    }
}

/// The stable construction against the exact reference, over the stiff
/// generator, both precisions: classification identical, the error within
/// the derived bound. Prints the largest error/bound ratio and the largest
/// absolute error on the well-conditioned generator.
#[test]
fn accuracy_budget() {
    let n = if exhaustive() { 2_000_000 } else { 100_000 };
    let mut rng = Rng::new(0x11_6E7);
    let (mut ratio64, mut ratio32) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let c = linear_light_case(&mut rng);
        let x = expected(c.l, c.r, c.f, c.e);
        let got = linear_light::f64::visible_part(c.l, c.r, c.f, c.e, c.side);
        let what = format!("f64 {c:?}");
        ratio64 = ratio64.max(check(parts_f64(got), x, c.side, U64, &what));
        let p = to_f32(&c);
        let [l, r, f, e] = promote(p);
        let x = expected(l, r, f, e);
        let got = linear_light::f32::visible_part(p[0], p[1], p[2], p[3], c.side);
        let what = format!("f32 {p:?} {}", side_name(c.side));
        ratio32 = ratio32.max(check(parts_f32(got), x, c.side, U32, &what));
    }
    let (mut abs64, mut abs32) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let c = linear_light_well_conditioned(&mut rng);
        if let Expected::Inside { s, .. } = expected(c.l, c.r, c.f, c.e) {
            let got = linear_light::f64::visible_part(c.l, c.r, c.f, c.e, OccluderSide::TowardR);
            abs64 = abs64.max((got.end - s).abs());
        }
        let p = to_f32(&c);
        let [l, r, f, e] = promote(p);
        if let Expected::Inside { s, .. } = expected(l, r, f, e) {
            let got =
                linear_light::f32::visible_part(p[0], p[1], p[2], p[3], OccluderSide::TowardR);
            abs32 = abs32.max((got.end as f64 - s).abs());
        }
    }
    if printing() {
        println!("| linear_light::visible_part (s, error / derived bound) | f64 | {ratio64:.3} | ratio | `linear_light_case` | {n} |");
        println!("| linear_light::visible_part (s, error / derived bound) | f32 | {ratio32:.3} | ratio | `linear_light_case` | {n} |");
        println!("| linear_light::visible_part (s) | f64 | {abs64:.2e} | abs | `linear_light_well_conditioned` | {n} |");
        println!("| linear_light::visible_part (s) | f32 | {abs32:.2e} | abs | `linear_light_well_conditioned` | {n} |");
    }
    let budget = softshadow::kernel::catalogue::linear_light::VISIBLE_PART.bound;
    assert!(ratio64 <= budget && ratio32 <= budget);
}

/// Dense midpoint quadrature with an explicit occluder: the half-line
/// `O = {E + λw, λ ≥ 0}`, `w = ±(R − L)` on the occluder's side. A sample
/// `X` of the light is hidden when the segment `(F, X]` meets `O` (open at
/// the fragment, closed at the light: an edge touching the light still
/// occludes, the limit of one approaching it). With `κ` the parameter of
/// the meeting point along `F → X` and `λ` along `O`:
/// `κ ∈ (0, 1]` iff `w × (E − F)` has the sign of `w × (X − F)` and
/// `w × (E − X)` is zero or of the other sign; `λ ≥ 0` iff
/// `(X − F) × (E − F)` is zero or of the sign opposite to `(X − F) × w`.
fn hidden(l: DVec2, r: DVec2, f: DVec2, e: DVec2, x: DVec2, side: OccluderSide) -> bool {
    // w × (A − B) = (W₁ − W₀) × (A − B) with w = R − L or L − R.
    let (w1, w0) = match side {
        OccluderSide::TowardR => (r, l),
        OccluderSide::TowardL => (l, r),
    };
    let c_xf = exact::cross_sign(w1, w0, x, f);
    if c_xf == 0 {
        return false;
    }
    let c_ef = exact::cross_sign(w1, w0, e, f);
    let c_ex = exact::cross_sign(w1, w0, e, x);
    let kappa_ok = c_ef == c_xf && (c_ex == 0 || c_ex == -c_xf);
    // (X − F) × (E − F) by robust's exact orient2d(F, X, E).
    let coord = |p: DVec2| robust::Coord { x: p.x, y: p.y };
    let o = robust::orient2d(coord(f), coord(x), coord(e));
    let s_xe = if o > 0.0 {
        1
    } else if o < 0.0 {
        -1
    } else {
        0
    };
    // (X − F) × w = −(w × (X − F)).
    let s_xw = -c_xf;
    let lambda_ok = s_xe == 0 || s_xe == -s_xw;
    kappa_ok && lambda_ok
}

/// The kernel against the quadrature, on the stiff generator restricted to
/// configurations the samples resolve. The sample points `L + σ(R − L)` are
/// rounded, each moved by up to `δ = 4u·M` (M the largest coordinate: the
/// difference, the product and the sum). A moved sample can change status
/// only if it crosses the shadow line (it is then within
/// `δ/(|R − L| sin ψ)` of the crossing in σ, ψ the angle between the shadow
/// line and the light), or crosses the occluder's level or the light's
/// line (impossible when `F` and `E` are farther than `2δ` from the light's
/// line). Configurations where `F` or `E` is within `2δ` of the light's
/// line, or the crossing zone is wider than a quarter sample spacing, are
/// skipped (those conventions are tested exactly in
/// `conventions_at_the_edge_of_the_domain` and `accuracy_budget`). Then at
/// most the boundary cell and one rounded neighbour differ: the visible
/// fraction and both weights (midpoint rule, exact for linear integrands on
/// whole cells) are within `2/N`, plus the summation's rounding `N·u`.
#[test]
fn matches_quadrature_with_explicit_occluder() {
    const N: usize = 2048;
    let cases = if exhaustive() { 20_000 } else { 1_000 };
    let mut rng = Rng::new(0x0CC1);
    let mut checked = 0;
    while checked < cases {
        let c = linear_light_case(&mut rng);
        let (l, r, f, e) = (c.l, c.r, c.f, c.e);
        let len = (r - l).length();
        let m = [l, r, f, e]
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        let delta = 4.0 * U64 * m;
        let dir = e - f;
        let sin_psi = if dir.length() > 0.0 {
            ((r - l).perp_dot(dir) / (len * dir.length())).abs()
        } else {
            0.0
        };
        let (h_f, h_e) = ((r - l).perp_dot(f - l) / len, (r - l).perp_dot(e - l) / len);
        let unresolved = len == 0.0
            || h_f.abs() <= 2.0 * delta
            || h_e.abs() <= 2.0 * delta
            || delta > 0.25 / N as f64 * len * sin_psi;
        if unresolved {
            continue;
        }
        checked += 1;
        let (mut count, mut wr, mut wl) = (0usize, 0.0f64, 0.0f64);
        for j in 0..N {
            let sigma = (j as f64 + 0.5) / N as f64;
            let x = l + (r - l) * sigma;
            if !hidden(l, r, f, e, x, c.side) {
                count += 1;
                wr += sigma;
                wl += 1.0 - sigma;
            }
        }
        let nf = N as f64;
        let got = linear_light::f64::visible_part(l, r, f, e, c.side);
        let tol = 2.0 / nf + nf * U64;
        let estimates = [
            (count as f64 / nf, got.fraction),
            (wr / nf, got.weight_r),
            (wl / nf, got.weight_l),
        ];
        for (k, (q, g)) in estimates.into_iter().enumerate() {
            assert!(
                (q - g).abs() <= tol,
                "{c:?}: quantity {k}: quadrature {q} vs kernel {g}"
            );
        }
    }
}

/// The tolerance between the paper's law-of-sines form and the exact
/// crossing parameter. Each angle `atan2(|p × q|, p · q)` of rounded,
/// exactly rescaled differences is within `e_θ = 16u`: the directions of
/// the rounded differences within `1.5u` each, the cross product within
/// `2u` relative and the dot product within `2u|p||q|` move the angle by at
/// most `3.5u`, and the crate's `atan2` (within 1.5 ulp) adds at most
/// `1.5·2πu` (`1.5 + 1.5 + 3.5 + 3π < 16`). `π − δ − γ` adds its own two
/// roundings (`2πu`) to `2e_θ`. Then `|Δi|/i ≤ Σ |cot x|·e_x` over
/// `α, β, δ` and `δ + γ`, plus four sines (`2u` each) and three
/// products/quotients (`u` each).
fn law_of_sines_tolerance(u: f64, l: DVec2, r: DVec2, f: DVec2, e: DVec2, i: f64) -> f64 {
    let angle = |p: DVec2, q: DVec2| p.perp_dot(q).abs().atan2(p.dot(q));
    let alpha = angle(l - f, r - f);
    let beta = angle(l - r, f - r);
    let gamma = angle(r - l, f - l);
    let delta = angle(l - f, e - f);
    let e_t = 16.0 * u;
    let cot = |x: f64| (x.cos() / x.sin()).abs();
    let rel = e_t * (cot(alpha) + cot(beta) + cot(delta))
        + (2.0 * e_t + 2.0 * core::f64::consts::PI * u) * cot(delta + gamma)
        + 8.0 * u
        + 3.0 * u;
    i * rel * 1.01
}

/// The paper's eq. 1 agrees with the stable construction on well-conditioned
/// configurations, within the law-of-sines form's derived error plus the
/// stable form's bound; `None` exactly outside its domain.
#[test]
fn law_of_sines_agrees_with_stable_construction() {
    let n = if exhaustive() { 1_000_000 } else { 50_000 };
    let mut rng = Rng::new(0x1A3);
    let (mut worst64, mut worst32, mut ratio) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 0..n {
        let c = linear_light_well_conditioned(&mut rng);
        let Expected::Inside {
            s, a, b, pl, pr, ..
        } = expected(c.l, c.r, c.f, c.e)
        else {
            panic!("well-conditioned case not inside: {c:?}");
        };
        let i = linear_light::f64::law_of_sines_fraction(c.l, c.r, c.f, c.e).expect("in domain");
        let stable =
            linear_light::f64::visible_part(c.l, c.r, c.f, c.e, OccluderSide::TowardR).fraction;
        let tol = law_of_sines_tolerance(U64, c.l, c.r, c.f, c.e, s)
            + stable_bound(U64, s, a, b, pl, pr).unwrap();
        assert!(
            (i - stable).abs() <= tol,
            "{c:?}: law of sines {i} vs stable {stable} (tol {tol:e})"
        );
        worst64 = worst64.max((i - s).abs());
        ratio = ratio.max((i - stable).abs() / tol);
        let p = to_f32(&c);
        let [l, r, f, e] = promote(p);
        if let Expected::Inside {
            s, a, b, pl, pr, ..
        } = expected(l, r, f, e)
        {
            let i = linear_light::f32::law_of_sines_fraction(p[0], p[1], p[2], p[3])
                .expect("in domain") as f64;
            let tol = law_of_sines_tolerance(U32, l, r, f, e, s)
                + stable_bound(U32, s, a, b, pl, pr).unwrap();
            assert!((i - s).abs() <= tol, "{p:?}: f32 law of sines {i} vs {s}");
            worst32 = worst32.max((i - s).abs());
        }
    }
    if printing() {
        println!("| linear_light::law_of_sines_fraction | f64 | {worst64:.2e} | abs | `linear_light_well_conditioned` | {n} |");
        println!("| linear_light::law_of_sines_fraction | f32 | {worst32:.2e} | abs | `linear_light_well_conditioned` | {n} |");
        println!("| linear_light::law_of_sines_fraction − visible_part (diff / derived tolerance) | f64 | {ratio:.3} | ratio | `linear_light_well_conditioned` | {n} |");
    }
}

/// Where the paper's form loses accuracy and the stable one does not:
/// the fragment a tiny height above the middle of the light (α → π), and
/// the shadow line grazing the light (δ + γ → π).
#[test]
fn law_of_sines_weak_spots() {
    let (l, r) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
    let mut rows = Vec::new();
    for h in [1e-2, 1e-5, 1e-8, 1e-11] {
        // α → π: F just above the light, E halfway to P = (0.3, 0).
        let f = DVec2::new(0.55, h);
        let e = f + (DVec2::new(0.3, 0.0) - f) * 0.5;
        // Grazing: F far to the side at height h, E toward P = (0.3, 0).
        let g = DVec2::new(-3.0, h);
        let eg = g + (DVec2::new(0.3, 0.0) - g) * 0.5;
        for (f, e, name) in [(f, e, "alpha→π"), (g, eg, "grazing")] {
            let Expected::Inside {
                s, a, b, pl, pr, ..
            } = expected(l, r, f, e)
            else {
                panic!("inside expected");
            };
            let stable = linear_light::f64::visible_part(l, r, f, e, OccluderSide::TowardR).end;
            let bound = stable_bound(U64, s, a, b, pl, pr).unwrap();
            assert!((stable - s).abs() <= bound);
            let paper = linear_light::f64::law_of_sines_fraction(l, r, f, e).unwrap();
            rows.push(format!(
                "{name} h={h:e}: stable {:.1e}, law of sines {:.1e}",
                (stable - s).abs(),
                (paper - s).abs()
            ));
        }
    }
    if printing() {
        for row in rows {
            println!("weak spot: {row}");
        }
    }
}

/// `f32` and `f64` kernels on the same (f32) input: the decisions are the
/// same exact predicates on the same values, so they agree on the
/// classification, and inside within the sum of the two bounds.
#[test]
fn f32_agrees_with_f64() {
    let n = if exhaustive() { 1_000_000 } else { 100_000 };
    let mut rng = Rng::new(0x3232);
    for _ in 0..n {
        let c = linear_light_case(&mut rng);
        let p = to_f32(&c);
        let [l, r, f, e] = promote(p);
        let g32 = parts_f32(linear_light::f32::visible_part(
            p[0], p[1], p[2], p[3], c.side,
        ));
        let g64 = parts_f64(linear_light::f64::visible_part(l, r, f, e, c.side));
        match expected(l, r, f, e) {
            Expected::Inside { s, q, a, b, pl, pr } => {
                let frac = if c.side == OccluderSide::TowardR {
                    s
                } else {
                    q
                };
                if let (Some(b32), Some(b64)) = (
                    stable_bound(U32, frac.max(s), a, b, pl, pr),
                    stable_bound(U64, frac.max(s), a, b, pl, pr),
                ) {
                    assert!((g32[2] - g64[2]).abs() <= b32 + b64, "{p:?}");
                }
            }
            _ => assert_eq!(g32, g64, "{p:?}"),
        }
    }
}

#[test]
fn weights_sum_to_fraction_and_swap_with_the_endpoints() {
    let mut rng = Rng::new(0x5A5A);
    for _ in 0..100_000 {
        let c = linear_light_case(&mut rng);
        let v = linear_light::f64::visible_part(c.l, c.r, c.f, c.e, c.side);
        assert!((0.0..=1.0).contains(&v.fraction) && v.start <= v.end);
        assert!(v.weight_l >= 0.0 && v.weight_r >= 0.0);
        // A = s²/2 (1 rounding), B = s(1 + q)/2 (2), s + q = 1 within 4u
        // (both from one sum, one division each), so |A + B − i| ≤ 6u·i.
        assert!(
            (v.weight_l + v.weight_r - v.fraction).abs() <= 6.0 * U64 * v.fraction,
            "{c:?}"
        );
        // Swapping L and R together with the side mirrors everything, bit for
        // bit: the kernel evaluates the same two cross products.
        let w = linear_light::f64::visible_part(c.r, c.l, c.f, c.e, c.side.flip());
        assert_eq!(w.fraction, v.fraction, "{c:?}");
        assert_eq!(w.weight_l, v.weight_r, "{c:?}");
        assert_eq!(w.weight_r, v.weight_l, "{c:?}");
        // The mirrored interval: q̂ against 1 − ŝ, where ŝ + q̂ = 1 within 2u
        // and the subtraction rounds once more.
        assert!(
            (w.start - (1.0 - v.end)).abs() <= 4.0 * U64
                && (w.end - (1.0 - v.start)).abs() <= 4.0 * U64,
            "{c:?}"
        );
    }
}

/// Regression (fuzz `linear_light`): extreme magnitudes put the crossing
/// within `4e-311` of `R`, so `1 − s` and both weights are subnormal and
/// `A + B = i` holds only to the subnormal spacing: the documented slack is
/// `6u·i` plus half the smallest subnormal per rounding (three).
#[test]
fn regression_subnormal_weights() {
    let l = DVec2::new(-7.29112022742516e-304, -4.775122389511747e307);
    let r = DVec2::new(4.345859439646e-311, 0.0020134504941893283);
    let f = DVec2::new(-3.4277787587268165e-294, 2.2762829333864096e-301);
    let e = DVec2::new(0.0, 0.0);
    for side in [OccluderSide::TowardL, OccluderSide::TowardR] {
        let v = linear_light::f64::visible_part(l, r, f, e, side);
        assert_sane(parts_f64(v)).unwrap();
        let slack = 6.0 * U64 * v.fraction + 3.0 * f64::from_bits(1);
        assert!(
            (v.weight_l + v.weight_r - v.fraction).abs() <= slack,
            "{v:?}"
        );
    }
}

/// Scaling every point by a power of two changes nothing (bit for bit, as
/// long as nothing under- or overflows): every step of the kernel is exact
/// under such scaling.
#[test]
fn invariant_under_power_of_two_scaling() {
    let mut rng = Rng::new(0x2222);
    for _ in 0..50_000 {
        let c = linear_light_case(&mut rng);
        let v = linear_light::f64::visible_part(c.l, c.r, c.f, c.e, c.side);
        let k = 2f64.powi(rng.below(81) as i32 - 40);
        let w = linear_light::f64::visible_part(c.l * k, c.r * k, c.f * k, c.e * k, c.side);
        assert_eq!(v, w, "{c:?} × {k}");
        let p = to_f32(&c);
        let k = 2f32.powi(rng.below(21) as i32 - 10);
        let v = linear_light::f32::visible_part(p[0], p[1], p[2], p[3], c.side);
        let w = linear_light::f32::visible_part(p[0] * k, p[1] * k, p[2] * k, p[3] * k, c.side);
        assert_eq!(v, w, "{p:?} × {k}");
    }
}

/// A rigid motion (rotation and translation) of a well-conditioned
/// configuration: the rounded motion moves each point by at most
/// `δ = 4u(M + M')` (M, M' the largest coordinates before and after: three
/// roundings of terms bounded by them), which moves `a` by at most
/// `2δ(|E − F| + |L − F|)` and `b` likewise, hence `s` by at most
/// `s(1 − s)(Δa/|a| + Δb/|b|)` to first order; plus both kernels' bounds.
#[test]
fn invariant_under_rigid_motion() {
    let mut rng = Rng::new(0x7070);
    let mut checked = 0;
    while checked < 20_000 {
        let c = linear_light_well_conditioned(&mut rng);
        let rot = DVec2::from_angle(rng.uniform(0.0, core::f64::consts::TAU));
        let shift = DVec2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0))
            * rng.log_uniform(-3.0, 3.0)
            * c.l.length().max(1.0);
        let mv = |p: DVec2| rot.rotate(p) + shift;
        let (l, r, f, e) = (mv(c.l), mv(c.r), mv(c.f), mv(c.e));
        let Expected::Inside {
            s, a, b, pl, pr, ..
        } = expected(c.l, c.r, c.f, c.e)
        else {
            panic!("inside expected");
        };
        let m = [c.l, c.r, c.f, c.e]
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        let m2 = [l, r, f, e]
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        let delta = 4.0 * U64 * (m + m2);
        let (pe, ql, qr) = (
            (c.e - c.f).length(),
            (c.l - c.f).length(),
            (c.r - c.f).length(),
        );
        let moved =
            s * (1.0 - s) * (2.0 * delta * (pe + ql) / a + 2.0 * delta * (pe + qr) / b) * 1.01;
        if moved > 1e-3 {
            // The translation dwarfs the configuration: the motion itself
            // destroys the digits (a first-order bound says nothing).
            continue;
        }
        checked += 1;
        let Expected::Inside {
            a: a2,
            b: b2,
            pl: pl2,
            pr: pr2,
            s: s2,
            ..
        } = expected(l, r, f, e)
        else {
            panic!("inside expected after the motion: {c:?}");
        };
        let tol = moved
            + stable_bound(U64, s, a, b, pl, pr).unwrap()
            + stable_bound(U64, s2, a2, b2, pl2, pr2).unwrap();
        let v = linear_light::f64::visible_part(c.l, c.r, c.f, c.e, c.side);
        let w = linear_light::f64::visible_part(l, r, f, e, c.side);
        assert!(
            (v.fraction - w.fraction).abs() <= tol,
            "{c:?}: {} vs {}",
            v.fraction,
            w.fraction
        );
    }
}

/// The 3D kernel on a 2D configuration placed in a random plane of space
/// agrees with the 2D kernel: the embedding and the kernel's projection back
/// move each point by at most `32u·M` (a unit-quaternion rotation is within
/// about `12u|v|` per coordinate, the translation `u`, the difference,
/// normalisation and dot products of the projection about `10u`), which
/// moves `s` as in `invariant_under_rigid_motion`.
#[test]
fn three_d_agrees_with_two_d() {
    let mut rng = Rng::new(0x3D3D);
    let mut worst = (0.0f64, 0.0f64);
    for _ in 0..20_000 {
        let c = linear_light_well_conditioned(&mut rng);
        let c3 = embed_3d(&c, &mut rng);
        let tolerance_ratio = |err: f64, tol: f64| err / tol;
        let Expected::Inside {
            s, a, b, pl, pr, ..
        } = expected(c.l, c.r, c.f, c.e)
        else {
            panic!("inside expected");
        };
        let m = [c3.l, c3.r, c3.f, c3.e]
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        let delta = 32.0 * U64 * m;
        let (pe, ql, qr) = (
            (c.e - c.f).length(),
            (c.l - c.f).length(),
            (c.r - c.f).length(),
        );
        let moved =
            s * (1.0 - s) * (2.0 * delta * (pe + ql) / a + 2.0 * delta * (pe + qr) / b) * 1.01;
        let tol = moved + stable_bound(U64, s, a, b, pl, pr).unwrap();
        let v = linear_light::f64::visible_part_3d(c3.l, c3.r, c3.f, c3.e, c.side);
        let want = if c.side == OccluderSide::TowardR {
            s
        } else {
            1.0 - s
        };
        assert!(
            (v.fraction - want).abs() <= tol + U64,
            "{c3:?}: {} vs {want}",
            v.fraction
        );
        worst.0 = worst
            .0
            .max(tolerance_ratio((v.fraction - want).abs(), tol + U64));
        // f32: the same with u = 2⁻²⁴, on the rounded 3D points.
        let p = [c3.l, c3.r, c3.f, c3.e].map(|v| v.as_vec3());
        let v32 = linear_light::f32::visible_part_3d(p[0], p[1], p[2], p[3], c.side);
        let m32 = p
            .iter()
            .map(|v| v.abs().max_element() as f64)
            .fold(0.0, f64::max);
        let delta32 = (32.0 + 2.0) * U32 * m32; // plus the rounding to f32
        let moved32 =
            s * (1.0 - s) * (2.0 * delta32 * (pe + ql) / a + 2.0 * delta32 * (pe + qr) / b) * 1.01;
        let tol32 = moved32 + stable_bound(U32, s, a, b, pl, pr).unwrap();
        assert!(
            (v32.fraction as f64 - want).abs() <= tol32 + U32,
            "{c3:?} (f32): {} vs {want}",
            v32.fraction
        );
        worst.1 = worst.1.max(tolerance_ratio(
            (v32.fraction as f64 - want).abs(),
            tol32 + U32,
        ));
    }
    if printing() {
        println!("| linear_light::visible_part_3d (vs exact 2D s, error / derived tolerance) | f64 | {:.3} | ratio | `linear_light_well_conditioned` + `embed_3d` | 20000 |", worst.0);
        println!("| linear_light::visible_part_3d (vs exact 2D s, error / derived tolerance) | f32 | {:.3} | ratio | `linear_light_well_conditioned` + `embed_3d` | 20000 |", worst.1);
    }
}

#[test]
fn conventions_at_the_edge_of_the_domain() {
    use linear_light::f64::{visible_part as vp, VisiblePart};
    let full = VisiblePart::FULL;
    let (l, r) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
    let f = DVec2::new(0.25, 1.0);
    for side in [OccluderSide::TowardL, OccluderSide::TowardR] {
        // F on the light's line, inside and outside the segment.
        assert_eq!(
            vp(l, r, DVec2::new(0.5, 0.0), DVec2::new(0.5, 0.5), side),
            full
        );
        assert_eq!(
            vp(l, r, DVec2::new(3.0, 0.0), DVec2::new(2.0, 0.5), side),
            full
        );
        // E = F; L = R; the shadow line parallel to the light.
        assert_eq!(vp(l, r, f, f, side), full);
        assert_eq!(vp(l, l, f, DVec2::new(0.25, 0.5), side), full);
        assert_eq!(vp(l, r, f, DVec2::new(0.75, 1.0), side), full);
        // E behind F, E beyond the light.
        assert_eq!(vp(l, r, f, DVec2::new(0.25, 2.0), side), full);
        assert_eq!(vp(l, r, f, DVec2::new(0.5, -1.0), side), full);
        // Non-finite.
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(vp(l, r, f, DVec2::new(bad, 0.5), side), full);
            assert_eq!(
                vp(DVec2::new(0.0, bad), r, f, DVec2::new(0.25, 0.5), side),
                full
            );
        }
    }
    // E on the light's line occludes, with P = E (here s = 1/2 exactly).
    let v = vp(l, r, f, DVec2::new(0.5, 0.0), OccluderSide::TowardR);
    assert_eq!((v.start, v.end, v.fraction), (0.0, 0.5, 0.5));
    assert_eq!((v.weight_r, v.weight_l), (0.125, 0.375));
    // P exactly at L: TowardR hides everything, TowardL nothing.
    let e = DVec2::new(0.125, 0.5); // on the line from F = (0.25, 1) to L
    let v = vp(l, r, f, e, OccluderSide::TowardR);
    assert_eq!(
        (v.fraction, v.weight_r, v.weight_l, v.start, v.end),
        (0.0, 0.0, 0.0, 0.0, 0.0)
    );
    assert_eq!(vp(l, r, f, e, OccluderSide::TowardL), full);
    // P beyond R.
    let v = vp(l, r, f, DVec2::new(1.0, 0.5), OccluderSide::TowardL);
    assert_eq!((v.fraction, v.start, v.end), (0.0, 1.0, 1.0));
    // A symmetric case: F above the middle, E straight below: s = 1/2.
    let v = vp(
        l,
        r,
        DVec2::new(0.5, 2.0),
        DVec2::new(0.5, 1.0),
        OccluderSide::TowardL,
    );
    assert_eq!((v.fraction, v.weight_r, v.weight_l), (0.5, 0.375, 0.125));
    // The law-of-sines form is None outside its domain.
    use linear_light::f64::law_of_sines_fraction as ls;
    assert_eq!(ls(l, r, DVec2::new(0.5, 0.0), DVec2::new(0.5, 0.5)), None);
    assert_eq!(ls(l, r, f, f), None);
    assert_eq!(ls(l, r, f, DVec2::new(0.25, 2.0)), None);
    assert_eq!(ls(l, r, f, DVec2::new(-1.0, 0.5)), None);
    assert_eq!(ls(l, r, f, DVec2::new(f64::NAN, 0.5)), None);
    assert_eq!(
        ls(l, r, DVec2::new(0.5, 2.0), DVec2::new(0.5, 1.0)),
        Some(0.5)
    );
    // 3D: collinear fragment, non-finite, huge magnitudes.
    use linear_light::f64::visible_part_3d as vp3;
    let (l3, r3) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(2.0, 3.0, 4.0));
    assert_eq!(
        vp3(
            l3,
            r3,
            DVec3::new(3.0, 4.0, 5.0),
            DVec3::ZERO,
            OccluderSide::TowardR
        ),
        full
    );
    assert_eq!(
        vp3(
            l3,
            r3,
            DVec3::new(3.0, 4.0, f64::NAN),
            DVec3::ZERO,
            OccluderSide::TowardR
        ),
        full
    );
    let big = 1e300;
    let v = vp3(
        DVec3::new(-big, 0.0, 0.0),
        DVec3::new(big, 0.0, 0.0),
        DVec3::new(0.0, big, 0.0),
        DVec3::new(0.0, 0.5 * big, 0.0),
        OccluderSide::TowardR,
    );
    assert!((v.fraction - 0.5).abs() <= 1e-15, "{v:?}");
    let v32 = linear_light::f32::visible_part_3d(
        Vec3::new(-1e38, 0.0, 0.0),
        Vec3::new(1e38, 0.0, 0.0),
        Vec3::new(0.0, 3e38, 0.0),
        Vec3::new(0.0, 1e38, 0.0),
        OccluderSide::TowardL,
    );
    assert!((v32.fraction - 0.5).abs() <= 1e-6, "{v32:?}");
}

fn any_dvec2() -> impl Strategy<Value = DVec2> {
    (any::<u64>(), any::<u64>()).prop_map(|(x, y)| DVec2::new(f64::from_bits(x), f64::from_bits(y)))
}

fn any_vec3() -> impl Strategy<Value = Vec3> {
    (any::<u32>(), any::<u32>(), any::<u32>())
        .prop_map(|(x, y, z)| Vec3::new(f32::from_bits(x), f32::from_bits(y), f32::from_bits(z)))
}

fn assert_sane(v: [f64; 5]) -> Result<(), TestCaseError> {
    let [start, end, fraction, wr, wl] = v;
    prop_assert!(v.iter().all(|x| x.is_finite()), "{v:?}");
    prop_assert!((0.0..=1.0).contains(&start) && (0.0..=1.0).contains(&end) && start <= end);
    prop_assert!((0.0..=1.0).contains(&fraction) && wr >= 0.0 && wl >= 0.0);
    // |A + B − i| ≤ 6u·i plus three half-subnormals (f32: u = 2⁻²⁴).
    prop_assert!(
        (wr + wl - fraction).abs() <= 6.0 * U32 * fraction + 3.0 * f32::from_bits(1) as f64
    );
    Ok(())
}

proptest! {
    /// Any bit patterns: never NaN, always a valid visible part.
    #[test]
    fn total_on_any_bits(l in any_dvec2(), r in any_dvec2(), f in any_dvec2(), e in any_dvec2(), toward_r in any::<bool>()) {
        let side = if toward_r { OccluderSide::TowardR } else { OccluderSide::TowardL };
        assert_sane(parts_f64(linear_light::f64::visible_part(l, r, f, e, side)))?;
        let p = [l, r, f, e].map(|v| v.as_vec2());
        assert_sane(parts_f32(linear_light::f32::visible_part(p[0], p[1], p[2], p[3], side)))?;
        if let Some(i) = linear_light::f64::law_of_sines_fraction(l, r, f, e) {
            prop_assert!((0.0..=1.0).contains(&i));
        }
        let l3 = l.extend(f.x);
        let r3 = r.extend(e.y);
        assert_sane(parts_f64(linear_light::f64::visible_part_3d(l3, r3, f.extend(l.x), e.extend(r.y), side)))?;
    }

    #[test]
    fn total_on_any_bits_3d_f32(l in any_vec3(), r in any_vec3(), f in any_vec3(), e in any_vec3()) {
        assert_sane(parts_f32(linear_light::f32::visible_part_3d(l, r, f, e, OccluderSide::TowardR)))?;
    }

    /// Seeds into the stiff generator: the exact classification and the
    /// bound hold (the same check as `accuracy_budget`, on proptest's seeds).
    #[test]
    fn stiff_cases_within_bound(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let c = linear_light_case(&mut rng);
        let x = expected(c.l, c.r, c.f, c.e);
        let got = linear_light::f64::visible_part(c.l, c.r, c.f, c.e, c.side);
        check(parts_f64(got), x, c.side, U64, &format!("{c:?}"));
    }
}
