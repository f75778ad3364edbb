//! The closed-form case every exact-reference family is built on: a disk
//! light over a plate parallel to it, whose straight edge hides a circle
//! segment of the light; receivers across its penumbra, and the segment's
//! area without cancellation.

use crate::scene::Light;
use glam::DVec3;

/// A closed-form case: a disk light of radius `r` at height `big_h`
/// facing down, centred above the origin; a plate at height `h` covering
/// `x > s`; receivers at the points given.
pub(super) struct Plate {
    pub(super) r: f64,
    pub(super) big_h: f64,
    pub(super) h: f64,
    pub(super) s: f64,
}

impl Plate {
    /// The visible fraction from `p` (relative to the light's centre
    /// column): the plate's edge, seen from `p`, crosses the light's plane
    /// at `x = c`; the part beyond is hidden.
    pub(super) fn fraction(&self, p: DVec3) -> f64 {
        let k = (self.big_h - p.y) / (self.h - p.y);
        let c = p.x + (self.s - p.x) * k;
        let t = (c / self.r).clamp(-1.0, 1.0);
        // The hidden segment's area over πr².
        let hidden = (t.acos() - t * (1.0 - t * t).max(0.0).sqrt()) / std::f64::consts::PI;
        1.0 - hidden
    }

    /// How far the plate reaches past its edge and sideways for
    /// `points`: far enough that its other edges hide nothing of the
    /// light from any of them.
    pub(super) fn reach(&self, points: &[DVec3]) -> f64 {
        64.0 * (self.r + 1.0) * (1.0 + points.iter().map(|p| p.x.abs()).fold(0.0, f64::max))
    }

    /// The plate (two triangles) and the light, moved by `offset`; the
    /// plate reaches `reach` past the edge and sideways.
    pub(super) fn scene(
        &self,
        offset: DVec3,
        reach: f64,
        copies: usize,
        shift: f64,
    ) -> Option<(Light, Vec<[DVec3; 3]>)> {
        let light =
            Light::disk(DVec3::new(0.0, self.big_h, 0.0) + offset, -DVec3::Y, self.r).ok()?;
        let mut tris = Vec::with_capacity(2 * copies);
        for k in 0..copies {
            let s = self.s + shift * k as f64;
            let a = DVec3::new(s, self.h, -reach) + offset;
            let b = DVec3::new(s + reach, self.h, -reach) + offset;
            let c = DVec3::new(s + reach, self.h, reach) + offset;
            let d = DVec3::new(s, self.h, reach) + offset;
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
        Some((light, tris))
    }
}

/// Receivers across the penumbra of `plate` on the floor (`y = 0`),
/// `n` of them, placed so that the edge's image crosses the light at
/// `c = t·r` for `t` in `[−0.95, 0.95]`, on dyadic `x` (rounded to a
/// multiple of `2^-k` with `k` chosen for the size).
pub(super) fn receivers(plate: &Plate, y: f64, n: usize) -> Vec<DVec3> {
    let k = (plate.big_h - y) / (plate.h - y);
    (0..n)
        .map(|i| {
            let t = -0.95 + 1.9 * i as f64 / (n - 1) as f64;
            let c = t * plate.r;
            // c = x + (s − x)·k → x = (c − s·k) / (1 − k).
            let x = (c - plate.s * k) / (1.0 - k);
            DVec3::new(x, y, 0.0)
        })
        .collect()
}

/// `(x − sin x) / 2`, the area of a unit circle's segment of central angle
/// `x`, to a few ulps for every `x ∈ [0, 2π]` (a series below 1, where the
/// difference cancels).
pub(super) fn segment_area(x: f64) -> f64 {
    if x < 1.0 {
        // x³/6 − x⁵/120 + x⁷/5040 − …, halved: terms until they vanish.
        let x2 = x * x;
        let (mut term, mut sum, mut k) = (x * x2 / 6.0, 0.0_f64, 3.0_f64);
        while term != 0.0 && term.abs() > 1e-18 * sum.abs() {
            sum += term;
            term *= -x2 / ((k + 1.0) * (k + 2.0));
            k += 2.0;
        }
        0.5 * sum
    } else {
        0.5 * (x - x.sin())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_segment_area_closed_form_is_continuous_and_right_at_known_angles() {
        use std::f64::consts::PI;
        // A half disk, a full disk.
        assert!((segment_area(PI) - PI / 2.0).abs() < 1e-15);
        assert!((segment_area(2.0 * PI) - PI).abs() < 1e-15);
        // The series below 1 meets the direct form above it.
        let below = segment_area(1.0_f64.next_down());
        let above = segment_area(1.0);
        assert!(
            (below - above).abs() <= 4.0 * f64::EPSILON * above,
            "{below} {above}"
        );
        // A thin sliver: x³/12 to first order.
        let x = 1e-6;
        assert!((segment_area(x) / (x * x * x / 12.0) - 1.0).abs() < 1e-12);
    }
}
