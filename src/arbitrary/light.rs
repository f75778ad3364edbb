//! Generators for the falloff, SSOC distortion and linear-light kernels
//! (`kernel::falloff`, `kernel::distortion`, `kernel::linear_light`).
//!
//! Biased toward the inputs that break these kernels: penumbra positions a
//! few ulps from `0`, `1/2`, `1` and the branch points `1/4`, `3/4`, and
//! log-uniformly tiny; receivers a few ulps behind (or in front of) the
//! silhouette's depth; distortions at and just past `0` and `dmax`; light
//! configurations with the fragment near the light's line, the occluding
//! edge near the fragment or near the light, the shadow line through an
//! endpoint or parallel to the light, and scales over many decades.

use super::{step_ulps, Rng};
use crate::kernel::linear_light::OccluderSide;
use glam::{DVec2, DVec3};
use std::fmt;

/// A penumbra position `t` for the falloff kernels: mostly in `[0, 1]`,
/// concentrated near `0`, `1/2`, `1` and the exact falloff's branch points
/// `0.3`, `0.7` (and `1/4`, `3/4`) — within a few ulps, or log-uniformly
/// close — with exact boundary values and a few out-of-range values
/// (negative, above 1).
pub fn falloff_t(rng: &mut Rng) -> f64 {
    const CENTRES: [f64; 5] = [0.25, 0.3, 0.5, 0.7, 0.75];
    match rng.below(10) {
        0 | 1 => rng.unit(),
        // Thin slivers: t log-uniform down to deep underflow of t^(3/2).
        2 => 0.25 * rng.log_uniform(-320.0, 0.0),
        3 => 1.0 - 0.25 * rng.log_uniform(-17.0, 0.0),
        4 => {
            let centre = CENTRES[rng.below(CENTRES.len() as u64) as usize];
            rng.nudge(centre, 64)
        }
        5 => {
            let centre = CENTRES[rng.below(CENTRES.len() as u64) as usize];
            centre + rng.sign() * centre * rng.log_uniform(-16.0, -1.0)
        }
        6 => step_ulps(0.0, rng.below(64) as i64),
        7 => step_ulps(1.0, -(rng.below(64) as i64)),
        8 => {
            const EXACT: [f64; 9] = [
                0.0,
                -0.0,
                0.25,
                0.5,
                0.75,
                1.0,
                f64::MIN_POSITIVE,
                0.125,
                0.875,
            ];
            EXACT[rng.below(EXACT.len() as u64) as usize]
        }
        _ => {
            if rng.chance(0.5) {
                -rng.log_uniform(-300.0, 300.0)
            } else {
                1.0 + rng.log_uniform(-16.0, 300.0)
            }
        }
    }
}

/// `x` moved `k` `f32` representable values up (`k > 0`) or down.
fn step_ulps_f32(x: f32, k: i64) -> f32 {
    let mut y = x;
    for _ in 0..k.unsigned_abs() {
        y = if k > 0 { y.next_up() } else { y.next_down() };
    }
    y
}

/// [`falloff_t`] for `f32`: the same distribution rounded to `f32`, with the
/// near-boundary cases re-drawn in `f32` ulps (rounding an `f64` a few ulps
/// from `1/2` to `f32` would land exactly on `1/2`).
pub fn falloff_t_f32(rng: &mut Rng) -> f32 {
    match rng.below(4) {
        0 => {
            let centre = [0.0f32, 0.25, 0.3, 0.5, 0.7, 0.75, 1.0][rng.below(7) as usize];
            step_ulps_f32(centre, rng.below(129) as i64 - 64)
        }
        _ => falloff_t(rng) as f32,
    }
}

/// One SSOC distortion query: a light radius, the silhouette's depth, the
/// receiver's depth and the fragment's distortion `d`.
#[derive(Clone, Copy, PartialEq)]
pub struct DistortionCase {
    /// Sphere light radius `r`.
    pub light_radius: f64,
    /// Depth of the silhouette edge, `z_n`.
    pub z_near: f64,
    /// Depth of the receiver, `z_p`.
    pub z_receiver: f64,
    /// Distortion that brings the fragment to the outer edge of the
    /// distortion region.
    pub d: f64,
}

impl fmt::Debug for DistortionCase {
    /// Valid Rust, for pasting into a regression test.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "DistortionCase {{ light_radius: {:?}, z_near: {:?}, z_receiver: {:?}, d: {:?} }}",
            self.light_radius, self.z_near, self.z_receiver, self.d
        )
    }
}

/// A [`DistortionCase`] biased toward the stiff cases: magnitudes over many
/// decades, the receiver a few ulps behind (or at, or in front of) the
/// silhouette, or far behind it; `d` at `0`, at `dmax`, a few ulps past
/// either, or inside. `dmax` for placing `d` is computed here from the
/// formula `2r(z_p − z_n)/(z_n z_p)` (not from the kernel).
pub fn distortion_case(rng: &mut Rng) -> DistortionCase {
    let light_radius = match rng.below(8) {
        0 => 0.0,
        _ => rng.log_uniform(-6.0, 3.0),
    };
    let z_near = rng.log_uniform(-4.0, 5.0);
    let z_receiver = match rng.below(6) {
        0 => rng.nudge(z_near, 8),
        1 => step_ulps(z_near, 1 + rng.below(8) as i64),
        2 => z_near * (1.0 + rng.log_uniform(-15.0, 0.0)),
        3 => z_near * (1.0 + rng.log_uniform(0.0, 6.0)),
        4 => {
            if rng.chance(0.5) {
                f64::INFINITY
            } else {
                z_near * rng.uniform(0.0, 1.0)
            }
        }
        _ => z_near * rng.uniform(1.0, 4.0),
    };
    let dmax = if z_receiver > z_near && z_receiver.is_finite() {
        2.0 * light_radius * (z_receiver - z_near) / (z_near * z_receiver)
    } else if z_receiver > z_near {
        2.0 * light_radius / z_near
    } else {
        0.0
    };
    let d = match rng.below(8) {
        0 => 0.0,
        1 => dmax,
        2 => rng.nudge(dmax, 4),
        3 => step_ulps(0.0, rng.below(9) as i64 - 4),
        4 => dmax * (1.0 + rng.log_uniform(-16.0, 2.0)),
        5 => -dmax * rng.log_uniform(-16.0, 2.0),
        _ => dmax * falloff_t(rng).clamp(0.0, 1.0),
    };
    DistortionCase {
        light_radius,
        z_near,
        z_receiver,
        d,
    }
}

/// One linear-light query: the light `[l, r]`, the fragment `f`, the
/// occluding edge point `e` and the occluder's side, in 2D (the plane through
/// the light and the fragment).
#[derive(Clone, Copy, PartialEq)]
pub struct LinearLightCase {
    /// Light endpoint `L` (`s = 0`).
    pub l: DVec2,
    /// Light endpoint `R` (`s = 1`).
    pub r: DVec2,
    /// The fragment `F`.
    pub f: DVec2,
    /// The occluding edge point `E`.
    pub e: DVec2,
    /// The side of the shadow line the occluder lies on.
    pub side: OccluderSide,
}

impl fmt::Debug for LinearLightCase {
    /// Valid Rust, for pasting into a regression test.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "LinearLightCase {{ l: DVec2::new({:?}, {:?}), r: DVec2::new({:?}, {:?}), \
             f: DVec2::new({:?}, {:?}), e: DVec2::new({:?}, {:?}), side: OccluderSide::{:?} }}",
            self.l.x,
            self.l.y,
            self.r.x,
            self.r.y,
            self.f.x,
            self.f.y,
            self.e.x,
            self.e.y,
            self.side
        )
    }
}

/// A rigid motion plus uniform scale of the plane: `x ↦ scale·rot(x) + shift`.
fn similarity(rng: &mut Rng) -> (f64, DVec2, DVec2) {
    let scale = rng.log_uniform(-6.0, 6.0);
    let rot = DVec2::from_angle(rng.uniform(0.0, core::f64::consts::TAU));
    let shift = match rng.below(3) {
        0 => DVec2::ZERO,
        1 => DVec2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * scale * 4.0,
        _ => DVec2::new(rng.sign(), rng.sign()) * rng.log_uniform(-6.0, 8.0),
    };
    (scale, rot, shift)
}

/// A [`LinearLightCase`] biased toward near-degenerate configurations.
///
/// Built in a canonical frame (`L = (0, 0)`, `R = (1, 0)`, `F` above the
/// light), then moved by a random rotation, uniform scale over twelve decades
/// and translation (rounded, so the final configuration is generic). The
/// canonical choices: `F` at heights from `1e-12` to `1e3`, sometimes exactly
/// on the light's line; the crossing `P` at a parameter near `0`, near `1`,
/// inside, or outside the segment; `E` on the segment `F–P` near `F`, near
/// `P` (within ulps of the light's line), in the middle, or off it: beyond
/// the light, behind `F`, on a line parallel to the light through `F`, or
/// `E = F`; `R` occasionally equal to `L`.
pub fn linear_light_case(rng: &mut Rng) -> LinearLightCase {
    let height = match rng.below(6) {
        0 => rng.log_uniform(-12.0, -3.0),
        1 => 0.0,
        2 => rng.log_uniform(1.0, 3.0),
        _ => rng.log_uniform(-1.0, 1.0),
    };
    let f_c = DVec2::new(rng.uniform(-1.0, 2.0) * rng.log_uniform(0.0, 2.0), height);
    let s_p = match rng.below(6) {
        0 => rng.log_uniform(-15.0, -1.0),
        1 => 1.0 - rng.log_uniform(-15.0, -1.0),
        2 => [0.0, 1.0][rng.below(2) as usize],
        3 => rng.uniform(-2.0, 3.0),
        _ => rng.unit(),
    };
    let p_c = DVec2::new(s_p, 0.0);
    let e_c = match rng.below(10) {
        0 => f_c + (p_c - f_c) * rng.log_uniform(-12.0, -1.0),
        1 => p_c + (f_c - p_c) * rng.log_uniform(-16.0, -1.0),
        2 => p_c,
        3 => f_c + (p_c - f_c) * rng.uniform(1.0, 3.0),
        4 => f_c - (p_c - f_c) * rng.uniform(0.0, 2.0),
        5 => f_c + DVec2::new(rng.uniform(-2.0, 2.0), 0.0),
        6 => f_c,
        _ => f_c + (p_c - f_c) * rng.uniform(0.0, 1.0),
    };
    let r_c = if rng.below(32) == 0 {
        DVec2::ZERO
    } else {
        DVec2::X
    };
    let (scale, rot, shift) = similarity(rng);
    let place = |p: DVec2| rot.rotate(p) * scale + shift;
    let side = if rng.chance(0.5) {
        OccluderSide::TowardL
    } else {
        OccluderSide::TowardR
    };
    LinearLightCase {
        l: place(DVec2::ZERO),
        r: place(r_c),
        f: place(f_c),
        e: place(e_c),
        side,
    }
}

/// A well-conditioned [`LinearLightCase`]: every angle of the triangles
/// `L R F` and `L P F` at least about 0.1 rad away from `0` and `π`, `E`
/// strictly between `F` and `P`, and `P` inside the segment
/// (`s_P ∈ [0.05, 0.95]`). For comparing the stable construction with the
/// paper's law-of-sines form.
pub fn linear_light_well_conditioned(rng: &mut Rng) -> LinearLightCase {
    let f_c = DVec2::new(rng.uniform(-0.5, 1.5), rng.uniform(0.4, 2.0));
    let s_p = rng.uniform(0.05, 0.95);
    let p_c = DVec2::new(s_p, 0.0);
    let e_c = f_c + (p_c - f_c) * rng.uniform(0.1, 0.9);
    let (scale, rot, shift) = similarity(rng);
    let place = |p: DVec2| rot.rotate(p) * scale + shift;
    LinearLightCase {
        l: place(DVec2::ZERO),
        r: place(DVec2::X),
        f: place(f_c),
        e: place(e_c),
        side: if rng.chance(0.5) {
            OccluderSide::TowardL
        } else {
            OccluderSide::TowardR
        },
    }
}

/// A linear-light query in 3D: the points of a [`LinearLightCase`] placed
/// in a random plane of space.
#[derive(Clone, Copy, PartialEq)]
pub struct LinearLightCase3 {
    /// Light endpoint `L`.
    pub l: DVec3,
    /// Light endpoint `R`.
    pub r: DVec3,
    /// The fragment `F`.
    pub f: DVec3,
    /// The occluding edge point `E`.
    pub e: DVec3,
    /// The side of the shadow line the occluder lies on.
    pub side: OccluderSide,
}

impl fmt::Debug for LinearLightCase3 {
    /// Valid Rust, for pasting into a regression test.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = |p: DVec3| format!("DVec3::new({:?}, {:?}, {:?})", p.x, p.y, p.z);
        write!(
            f,
            "LinearLightCase3 {{ l: {}, r: {}, f: {}, e: {}, side: OccluderSide::{:?} }}",
            v(self.l),
            v(self.r),
            v(self.f),
            v(self.e),
            self.side
        )
    }
}

/// Places a 2D case in 3D: the plane `z = 0` rotated by a random rotation
/// (a random unit quaternion) and translated. The 3D coordinates are rounded,
/// so the four points are coplanar only to within rounding.
pub fn embed_3d(case: &LinearLightCase, rng: &mut Rng) -> LinearLightCase3 {
    let q = glam::DQuat::from_xyzw(
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
    )
    .normalize();
    let q = if q.is_finite() {
        q
    } else {
        glam::DQuat::IDENTITY
    };
    let shift = DVec3::new(
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
    ) * case.l.abs().max_element().max(1.0);
    let place = |p: DVec2| q * p.extend(0.0) + shift;
    LinearLightCase3 {
        l: place(case.l),
        r: place(case.r),
        f: place(case.f),
        e: place(case.e),
        side: case.side,
    }
}
