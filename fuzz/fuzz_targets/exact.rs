//! The exact visibility reference: invariants and a cross-check with Monte
//! Carlo on fuzzed scenes.
//!
//! The first 8 bytes seed `arbitrary::scene::visibility_case` (every light
//! kind; occluders straddling the receiver's side or the light's plane,
//! shared edges, coincident copies, corners at the receiver, edge-on
//! triangles); the following words, read as raw `f64` bit patterns (NaN and
//! ±∞ included), replace coordinates of the occluders.
//!
//! Asserted: `V ∈ [0, 1]` and never NaN, on any input; within the exact
//! reference's documented domain (corners within 10⁶), the same `V` (to 1e-12) with the
//! triangles in reverse order and each one's corners reversed (the
//! coincident-edge tie-break and the orientation must not matter); never
//! more visible with more occluders; and agreement with Monte Carlo within
//! its standard error at a 10⁻¹² false-failure rate.
#![no_main]

use glam::DVec3;
use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::scene::visibility_case;
use softshadow::arbitrary::Rng;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::reference::exact;
use softshadow::reference::monte_carlo::{self, Options, REPLICATES};
use softshadow::reference::stats::{agreement_tolerance, student_t_two_sided_quantile};

fn word(data: &[u8], i: usize) -> Option<u64> {
    let bytes = data.get(8 * i..8 * i + 8)?;
    Some(u64::from_le_bytes(bytes.try_into().ok()?))
}

fn exact_v(
    triangles: &[[DVec3; 3]],
    case_light: &softshadow::scene::Light,
    p: DVec3,
) -> Option<f64> {
    let bvh = Bvh::new(Occluders::from_triangles(triangles.to_vec()));
    exact::visibility(&bvh, case_light, p).ok()
}

fuzz_target!(|data: &[u8]| {
    let seed = word(data, 0).unwrap_or(0);
    let mut case = visibility_case(&mut Rng::new(seed), 8);
    // Raw bit patterns over the occluders' coordinates, in order.
    let mut k = 1;
    'raw: for t in case.triangles.iter_mut() {
        for v in t.iter_mut() {
            for c in 0..3 {
                match word(data, k) {
                    Some(w) => v[c] = f64::from_bits(w),
                    None => break 'raw,
                }
                k += 1;
            }
        }
    }
    let (light, p) = (case.light, case.receiver);
    let Some(v) = exact_v(&case.triangles, &light, p) else {
        return;
    };
    assert!((0.0..=1.0).contains(&v), "{v} {case:?}");
    // Beyond the documented domain (corners within about 10⁶ times the
    // light's distance, here a few units) only the range is promised.
    let in_domain = case
        .triangles
        .iter()
        .flatten()
        .all(|v| v.is_finite() && v.abs().max_element() <= 1e6);
    if !in_domain {
        return;
    }

    let reversed: Vec<[DVec3; 3]> = case
        .triangles
        .iter()
        .rev()
        .map(|t| [t[2], t[1], t[0]])
        .collect();
    let w = exact_v(&reversed, &light, p).expect("same receiver");
    assert!(
        (v - w).abs() <= 1e-12,
        "order/orientation: {v} vs {w}\n{case:?}"
    );

    if case.triangles.len() > 1 {
        let fewer = exact_v(&case.triangles[1..], &light, p).expect("same receiver");
        assert!(
            v <= fewer + 1e-12,
            "more occluders, more light: {v} > {fewer}\n{case:?}"
        );
    }

    {
        let bvh = Bvh::new(Occluders::from_triangles(case.triangles.clone()));
        let samples = 1024;
        let m = monte_carlo::visibility(&bvh, &light, p, &Options::new(samples).with_seed(seed))
            .expect("the exact reference accepted this receiver");
        let q = student_t_two_sided_quantile(1e-12, REPLICATES - 1);
        let allowed = agreement_tolerance(&m, samples, q);
        assert!(
            (m.visibility - v).abs() <= allowed,
            "exact {v} vs {m:?}\n{case:?}"
        );
    }
});
