//! Penumbra wedges (`f64` and `f32`) must contain every receiver the edge
//! affects. An `f64` test written here ([`affected`]: some edge point
//! projects from `p` into the facing disk and lies between them, the
//! minimum of a quadratic along the edge) finds the receivers clearly
//! affected — through the disk shrunk by 0.1 % of its radius, so that
//! rounding cannot make a case — among 4000 drawn around the penumbra, and
//! the row counts those the wedge leaves out (0 is right), for an edge
//! under a sphere light, moved far, with tiny and huge lights.

use super::Row;
use crate::kernel::catalogue::Stiff;
use crate::kernel::wedge;
use glam::DVec3;

/// Whether the edge `e0 e1` clearly hides part of the disk of radius `r`
/// at `c` facing `p`. G(λ) = H⁴|rel|² − (H² + k) s², k = (0.999 r)², is
/// negative where the edge point projects inside the shrunk disk; a
/// quadratic in λ, tried at the ends and its vertex.
fn affected(p: DVec3, e0: DVec3, e1: DVec3, c: DVec3, r: f64) -> bool {
    let nu = c - p;
    let h2 = nu.length_squared();
    let k = (0.999 * r) * (0.999 * r);
    let (a, d) = (e0 - p, e1 - e0);
    let (sa, sd) = (a.dot(nu), d.dot(nu));
    let qa = h2 * h2 * d.length_squared() - (h2 + k) * sd * sd;
    let qb = 2.0 * (h2 * h2 * a.dot(d) - (h2 + k) * sa * sd);
    let vertex = if qa > 0.0 {
        (-qb / (2.0 * qa)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [0.0, 1.0, vertex].iter().any(|&l| {
        let rel = a + d * l;
        let s = rel.dot(nu);
        let g = h2 * h2 * rel.length_squared() - (h2 + k) * s * s;
        s > 0.01 * h2 && s < 0.99 * h2 && g < 0.0
    })
}

/// A fixed xorshift.
struct Xorshift(u64);

impl Xorshift {
    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let state = &mut self.0;
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        lo + (hi - lo) * ((*state >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// The rows of both precisions, one case after another.
pub(super) fn rows(rows: &mut Vec<Row>) {
    let (e0, e1) = (DVec3::new(-1.0, -0.2, 2.0), DVec3::new(1.0, 0.3, 2.0));
    let center = DVec3::new(0.0, 0.0, 4.0);
    let mut rng = Xorshift(0x5eed_u64);
    for (family, case, shift, r) in [
        (Stiff::FarOffset.name(), "moved 2^10, r = 0.5", 1024.0, 0.5),
        (
            Stiff::FarOffset.name(),
            "moved 2^30, r = 0.5",
            2f64.powi(30),
            0.5,
        ),
        (Stiff::LightSize.name(), "r = 1e-6", 0.0, 1e-6),
        (Stiff::LightSize.name(), "r = 1.5", 0.0, 1.5),
    ] {
        let off = DVec3::splat(shift);
        let (a, b, c) = (e0 + off, e1 + off, center + off);
        let w64 = wedge::f64::PenumbraWedge::new(a, b, c, r);
        let w32 = wedge::f32::PenumbraWedge::new(a.as_vec3(), b.as_vec3(), c.as_vec3(), r as f32);
        let (mut tested, mut missed64, mut missed32) = (0usize, 0usize, 0usize);
        for _ in 0..4000 {
            // Near the penumbra: on the plane through the light's centre
            // and the edge, beyond the edge, moved off it by up to three
            // penumbra half-widths.
            let q = a + (b - a) * rng.uniform(-0.2, 1.2);
            let t = rng.uniform(1.2, 2.5);
            let n = (b - a).cross(q - c).normalize();
            let p = c + (q - c) * t + n * (rng.uniform(-3.0, 3.0) * r * t);
            if !affected(p, a, b, c, r) {
                continue;
            }
            tested += 1;
            if let Ok(w) = &w64 {
                missed64 += usize::from(!w.contains(p));
            }
            // The f32 wedge on the f32-rounded receiver, tested in f32's
            // own terms only where rounding cannot matter: far from
            // 2^30 the inputs themselves round by more than the scene.
            if let Ok(w) = &w32 {
                missed32 += usize::from(!w.contains(p.as_vec3()));
            }
        }
        for (precision, missed, ok) in [
            ("f64", missed64, w64.is_ok()),
            ("f32", missed32, w32.is_ok()),
        ] {
            let note = if !ok {
                "refused by the constructor".to_owned()
            } else if precision == "f32" && shift > 1e6 {
                "beyond f32's resolution: the scene is 2^30 away, f32 rounds by 64".to_owned()
            } else {
                "inside (0 is right: the wedge is conservative)".to_owned()
            };
            rows.push(Row {
                subject: "wedge::PenumbraWedge::contains (affected receivers missed)".to_owned(),
                family,
                case: case.to_owned(),
                precision,
                count: tested,
                max: missed as f64,
                bound: None,
                note,
            });
        }
    }
}
