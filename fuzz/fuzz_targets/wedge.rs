//! Fuzz `kernel::wedge`: the wedge (`f64`, `f32`) and the penumbra quad
//! must contain every receiver that an independent partial-occlusion test
//! finds affected. Edges and lights come from the shared generators, moved
//! by fuzzed ulps; receivers from the definition of the affected region.
#![no_main]

use glam::{DVec2, DVec3};
use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::mesh::{light_frame_edge, unit_vector, wedge_case};
use softshadow::arbitrary::{step_ulps, Rng};
use softshadow::kernel::wedge::{f32 as w32, f64 as w64};

/// `γ(n) = nu/(1 − nu)`.
fn gamma(n: f64) -> f64 {
    let nu = n * f64::EPSILON / 2.0;
    nu / (1.0 - nu)
}

fn dot_abs(a: DVec3, b: DVec3) -> f64 {
    a.abs().dot(b.abs())
}

/// The independent test of visibility (docs/definitions.md) in `f64`, sound in the direction it
/// is used: `true` only when the edge provably meets the open segment from
/// `p` to an interior point of the facing disk. With `ν = c − p`,
/// `rel(λ) = e0 + λ(e1 − e0) − p`, `s = rel·ν`, the point at `λ` qualifies
/// when `0 < s < |ν|²` and `G(λ) = (|rel|²|ν|² − s²)|ν|² − r²s² < 0`. Each
/// test is accepted only beyond its forward error bound: `γ(40)` times the
/// same polynomial with every monomial's absolute value (6 rounded
/// differences, at most ~20 operations per monomial).
fn surely_affected(p: DVec3, e0: DVec3, e1: DVec3, c: DVec3, r: f64) -> bool {
    let nu = c - p;
    let rel0 = e0 - p;
    let delta = e1 - e0;
    let h2 = nu.dot(nu);
    let (s0, s1) = (rel0.dot(nu), delta.dot(nu));
    let (ps0, ps1) = (dot_abs(rel0, nu), dot_abs(delta, nu));
    let (a2, a1, a0) = (delta.dot(delta), 2.0 * rel0.dot(delta), rel0.dot(rel0));
    let pa1 = 2.0 * dot_abs(rel0, delta);
    let r2 = r * r;
    let ga = (a2 * h2 - s1 * s1) * h2 - r2 * s1 * s1;
    let gb = (a1 * h2 - 2.0 * s0 * s1) * h2 - 2.0 * r2 * s0 * s1;
    let gc = (a0 * h2 - s0 * s0) * h2 - r2 * s0 * s0;
    let pa = (a2 * h2 + ps1 * ps1) * h2 + r2 * ps1 * ps1;
    let pb = (pa1 * h2 + 2.0 * ps0 * ps1) * h2 + 2.0 * r2 * ps0 * ps1;
    let pc = (a0 * h2 + ps0 * ps0) * h2 + r2 * ps0 * ps0;
    if !(pa.is_finite() && pb.is_finite() && pc.is_finite()) || !(h2 > r2 * (1.0 + 1e-12)) {
        return false;
    }
    let mut candidates = [0.0, 1.0, 0.5, 0.5];
    if ga > 0.0 {
        candidates[2] = (-gb / (2.0 * ga)).clamp(0.0, 1.0);
    }
    if s1 != 0.0 {
        // Just inside the end of the interval where s < |ν|².
        let at_h2 = (h2 - s0) / s1;
        candidates[3] = (at_h2 - 1e-9 * s1.signum()).clamp(0.0, 1.0);
    }
    candidates.iter().any(|&l| {
        let s = s0 + l * s1;
        let s_err = gamma(8.0) * (ps0 + l * ps1) + gamma(4.0) * h2;
        let g = (ga * l + gb) * l + gc;
        let g_err = gamma(40.0) * ((pa * l + pb) * l + pc);
        s > s_err && s < h2 - s_err && g < -g_err
    })
}

fn constructive(rng: &mut Rng, e0: DVec3, e1: DVec3, c: DVec3, r: f64) -> DVec3 {
    let q = e0 + rng.unit() * (e1 - e0);
    let y = c + r * rng.unit().cbrt() * unit_vector(rng);
    q + rng.log_uniform(-4.0, 2.0) * (q - y)
}

fn nudge(v: DVec3, data: &[u8]) -> DVec3 {
    let k = |i: usize| i64::from(data.get(i).copied().unwrap_or(0) as i8) / 8;
    DVec3::new(
        step_ulps(v.x, k(0)),
        step_ulps(v.y, k(1)),
        step_ulps(v.z, k(2)),
    )
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 8 {
        return;
    }
    let mut seed = [0u8; 8];
    seed.copy_from_slice(&data[..8]);
    let mut rng = Rng::new(u64::from_le_bytes(seed));
    let rest = &data[8..];

    // The wedge, f64 and f32.
    let case = wedge_case(&mut rng);
    let e0 = nudge(case.e0, rest);
    let e1 = nudge(case.e1, rest.get(3..).unwrap_or(&[]));
    let (c, r) = (case.light.center, case.light.radius);
    if let Ok(wedge) = w64::PenumbraWedge::new(e0, e1, c, r) {
        for _ in 0..16 {
            let p = constructive(&mut rng, e0, e1, c, r);
            if surely_affected(p, e0, e1, c, r) {
                assert!(wedge.contains(p), "f64 wedge misses {p:?}");
            }
        }
    }
    let (f0, f1, fc, fr) = (e0.as_vec3(), e1.as_vec3(), c.as_vec3(), r as f32);
    if let Ok(wedge) = w32::PenumbraWedge::new(f0, f1, fc, fr) {
        let (d0, d1, dc, dr) = (
            DVec3::from(f0),
            DVec3::from(f1),
            DVec3::from(fc),
            f64::from(fr),
        );
        for _ in 0..16 {
            let p = constructive(&mut rng, d0, d1, dc, dr).as_vec3();
            if p.is_finite() && surely_affected(DVec3::from(p), d0, d1, dc, dr) {
                assert!(wedge.contains(p), "f32 wedge misses {p:?}");
            }
        }
    }

    // The quad, light frame.
    let radius = rng.log_uniform(-3.0, 1.0);
    let (q0, q1, z_max) = light_frame_edge(&mut rng, radius);
    let (q0, q1) = (
        nudge(q0, rest.get(6..).unwrap_or(&[])),
        nudge(q1, rest.get(9..).unwrap_or(&[])),
    );
    if let Ok(w64::QuadBound::Quad(quad)) = w64::penumbra_quad(q0, q1, radius, z_max) {
        for _ in 0..16 {
            let p = constructive(&mut rng, q0, q1, DVec3::ZERO, radius);
            if p.z <= z_max && surely_affected(p, q0, q1, DVec3::ZERO, radius) {
                let w = DVec2::new(p.x / p.z, p.y / p.z);
                assert!(quad.contains(w), "quad misses {p:?}");
            }
        }
    } else if let Ok(w64::QuadBound::Empty) = w64::penumbra_quad(q0, q1, radius, z_max) {
        for _ in 0..16 {
            let p = constructive(&mut rng, q0, q1, DVec3::ZERO, radius);
            assert!(
                !(p.z <= z_max && surely_affected(p, q0, q1, DVec3::ZERO, radius)),
                "empty, yet {p:?} is affected"
            );
        }
    }
});
