//! Linear-light kernel (OESS): invariants and cross-checks on fuzzed input.
//!
//! The first 8 bytes seed the stiff generators of `softshadow::arbitrary`
//! (fragments near the light's line, occluding edges near the fragment or
//! the light, shadow lines through an endpoint or parallel to the light);
//! the following words are read as raw `f64` bit patterns (anything, NaN and
//! ±∞ included).
#![no_main]

use glam::DVec2;
use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::light::{embed_3d, linear_light_case, linear_light_well_conditioned};
use softshadow::arbitrary::Rng;
use softshadow::kernel::linear_light::f64::{self as k, VisiblePart};
use softshadow::kernel::linear_light::OccluderSide;

const U: f64 = f64::EPSILON / 2.0;

fn word(data: &[u8], i: usize) -> u64 {
    let mut w = [0u8; 8];
    for (j, b) in w.iter_mut().enumerate() {
        *b = data.get(8 * i + j).copied().unwrap_or(0);
    }
    u64::from_le_bytes(w)
}

fn point(data: &[u8], i: usize) -> DVec2 {
    DVec2::new(
        f64::from_bits(word(data, i)),
        f64::from_bits(word(data, i + 1)),
    )
}

/// Range, ordering, non-negative weights, and `A + B = i` (A = s²/2 and
/// B = s(1 + q)/2 round once and twice, `s + q = 1` within 4u: 6u·i; each
/// of the three roundings of a subnormal weight adds up to half the smallest
/// subnormal).
fn sane(v: &VisiblePart, what: &dyn std::fmt::Debug) {
    let all = [v.start, v.end, v.fraction, v.weight_r, v.weight_l];
    assert!(all.iter().all(|x| x.is_finite()), "{what:?}: {v:?}");
    assert!(
        0.0 <= v.start && v.start <= v.end && v.end <= 1.0,
        "{what:?}: {v:?}"
    );
    assert!(
        (0.0..=1.0).contains(&v.fraction) && v.weight_r >= 0.0 && v.weight_l >= 0.0,
        "{what:?}: {v:?}"
    );
    let slack = 6.0 * U * v.fraction + 3.0 * f64::from_bits(1);
    assert!(
        (v.weight_r + v.weight_l - v.fraction).abs() <= slack,
        "{what:?}: {v:?}"
    );
}

/// Angle between `p` and `q`, as the kernel's law-of-sines form takes it.
fn angle(p: DVec2, q: DVec2) -> f64 {
    p.perp_dot(q).abs().atan2(p.dot(q))
}

fuzz_target!(|data: &[u8]| {
    let mut rng = Rng::new(word(data, 0));

    // Stiff generated case: sanity, the mirror symmetry (bit for bit), and
    // power-of-two scale invariance (bit for bit).
    let c = linear_light_case(&mut rng);
    let v = k::visible_part(c.l, c.r, c.f, c.e, c.side);
    sane(&v, &c);
    let w = k::visible_part(c.r, c.l, c.f, c.e, c.side.flip());
    assert_eq!(
        (w.fraction, w.weight_l, w.weight_r),
        (v.fraction, v.weight_r, v.weight_l),
        "{c:?}"
    );
    let scale = 2f64.powi((word(data, 1) % 61) as i32 - 30);
    let s = k::visible_part(c.l * scale, c.r * scale, c.f * scale, c.e * scale, c.side);
    assert_eq!(s, v, "{c:?} × {scale}");
    // The 3D kernel on the case placed in space: sane.
    let c3 = embed_3d(&c, &mut rng);
    sane(&k::visible_part_3d(c3.l, c3.r, c3.f, c3.e, c3.side), &c3);

    // Raw bit patterns: never NaN, always a valid part.
    let (l, r, f, e) = (
        point(data, 2),
        point(data, 4),
        point(data, 6),
        point(data, 8),
    );
    let side = if word(data, 10) & 1 == 0 {
        OccluderSide::TowardL
    } else {
        OccluderSide::TowardR
    };
    sane(&k::visible_part(l, r, f, e, side), &(l, r, f, e));
    sane(
        &k::visible_part_3d(
            l.extend(f.x),
            r.extend(e.y),
            f.extend(l.y),
            e.extend(r.x),
            side,
        ),
        &(l, r, f, e),
    );
    if let Some(i) = k::law_of_sines_fraction(l, r, f, e) {
        assert!((0.0..=1.0).contains(&i));
    }
    let p32 = [l, r, f, e].map(|p| p.as_vec2());
    let v32 =
        softshadow::kernel::linear_light::f32::visible_part(p32[0], p32[1], p32[2], p32[3], side);
    assert!(v32.fraction.is_finite() && (0.0..=1.0).contains(&v32.fraction));

    // The paper's law-of-sines form against the stable construction where
    // both are well-conditioned: every angle (α, β, γ, δ, δ + γ and the
    // angles θ_L = δ, θ_R = α − δ of the stable bound) at least 0.1 from 0
    // and π. There |cot| ≤ 10: the law-of-sines form is within
    // (16u·30 + (32u + 2πu)·10 + 11u)·i < 880u·i (tests/linear_light.rs
    // derives the terms) and the stable form within
    // (2u/0.0998·2 + 4u)/4 + 2u < 13u.
    let c = linear_light_well_conditioned(&mut rng);
    let (l, r, f, e) = (c.l, c.r, c.f, c.e);
    let alpha = angle(l - f, r - f);
    let beta = angle(l - r, f - r);
    let gamma = angle(r - l, f - l);
    let delta = angle(l - f, e - f);
    let far = |x: f64| (0.1..=core::f64::consts::PI - 0.1).contains(&x);
    if [alpha, beta, gamma, delta, delta + gamma, alpha - delta]
        .into_iter()
        .all(far)
    {
        let stable = k::visible_part(l, r, f, e, OccluderSide::TowardR).fraction;
        let paper = k::law_of_sines_fraction(l, r, f, e).expect("in the domain");
        assert!(
            (paper - stable).abs() <= 880.0 * U * stable + 13.0 * U,
            "{c:?}: {paper} vs {stable}"
        );
    }
});
