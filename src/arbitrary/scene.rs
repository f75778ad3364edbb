//! Random visibility cases for the references: a light of any kind, a
//! receiver below it, and occluding triangles between them — biased toward
//! what breaks a visibility reference: triangles straddling the receiver's
//! side or the light's plane (they must be clipped), strips and fans whose
//! shared edges cross the light (they must not leak or double count),
//! coincident copies, triangles with a corner exactly at the receiver,
//! triangles seen edge-on, and occluders behind the receiver or beyond the
//! light.

use super::Rng;
use crate::scene::Light;
use glam::DVec3;

/// One case: the light, the receiver and the occluding triangles.
#[derive(Clone, Debug, PartialEq)]
pub struct VisibilityCase {
    /// The light (every kind, point lights rarely).
    pub light: Light,
    /// The receiver, below the light.
    pub receiver: DVec3,
    /// The occluders.
    pub triangles: Vec<[DVec3; 3]>,
}

/// A random unit vector.
fn direction(rng: &mut Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        );
        if let Some(u) = v.try_normalize() {
            if v.length_squared() <= 1.0 {
                return u;
            }
        }
    }
}

/// A light centred at `c` of size about `s`, of a random kind.
fn light(rng: &mut Rng, c: DVec3, s: f64) -> Light {
    let built = match rng.below(9) {
        0 | 1 => Light::sphere(c, s),
        2 | 3 => {
            // Facing down-ish, tilted up to about 60°.
            let n = (-DVec3::Z + direction(rng) * 0.9).normalize_or(-DVec3::Z);
            Light::disk(c, n, s)
        }
        4 | 5 => {
            let u = DVec3::new(
                rng.uniform(0.3, 1.0),
                rng.uniform(-0.5, 0.5),
                rng.uniform(-0.2, 0.2),
            ) * s;
            let v = DVec3::new(
                rng.uniform(-0.5, 0.5),
                rng.uniform(0.3, 1.0),
                rng.uniform(-0.2, 0.2),
            ) * s;
            Light::rect(c, u, v)
        }
        6 | 7 => {
            let d = DVec3::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-0.3, 0.3),
            );
            Light::segment(c - d * s, c + d * s)
        }
        _ => Light::point(c),
    };
    // The generators give finite `c` and `s > 0`, so `built` is a light; a
    // point at the origin keeps the function total regardless.
    built
        .or_else(|_| Light::point(c))
        .or_else(|_| Light::point(DVec3::ZERO))
        .unwrap_or_else(|_| unreachable!("the origin is finite"))
}

/// A random case; `triangles` occluders at most (at least one).
pub fn visibility_case(rng: &mut Rng, triangles: usize) -> VisibilityCase {
    let height = rng.uniform(2.0, 6.0);
    let size = rng.log_uniform(-1.0, 0.2);
    let c = DVec3::new(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), height);
    let light = light(rng, c, size);
    let receiver = DVec3::new(
        rng.uniform(-0.5, 0.5),
        rng.uniform(-0.5, 0.5),
        rng.uniform(-0.2, 0.2),
    );
    let count = 1 + rng.below(triangles.max(1) as u64) as usize;
    let mut out: Vec<[DVec3; 3]> = Vec::with_capacity(count + 4);
    while out.len() < count {
        // A point between the receiver and a point of the light's extent.
        let target = c + direction(rng) * size * rng.uniform(0.0, 1.2);
        let lambda = match rng.below(10) {
            0 => rng.uniform(-0.3, 0.0),  // behind the receiver
            1 => rng.uniform(1.0, 1.3),   // beyond the light's centre
            _ => rng.uniform(0.05, 0.95), // between
        };
        let q = receiver + (target - receiver) * lambda;
        // Occluder size comparable to the light's image at that depth.
        let s = size * lambda.abs().max(0.05) * rng.log_uniform(-0.7, 0.5);
        let (e0, e1) = (direction(rng) * s, direction(rng) * s);
        match rng.below(8) {
            0 => {
                // A quad strip of two triangles sharing a diagonal.
                let (a, b, c2, d) = (q - e0 - e1, q + e0 - e1, q + e0 + e1, q - e0 + e1);
                out.push([a, b, c2]);
                out.push([a, c2, d]);
            }
            1 => {
                // A fan of three around q: three shared edges through q.
                let ring = [q + e0, q + e1, q - e0 - e1];
                for k in 0..3 {
                    out.push([q, ring[k], ring[(k + 1) % 3]]);
                }
            }
            2 => {
                // A coincident copy of an earlier triangle, reversed.
                if let Some(&t) = out.last() {
                    out.push([t[2], t[1], t[0]]);
                } else {
                    out.push([q, q + e0, q + e1]);
                }
            }
            3 => {
                // A long triangle reaching behind the receiver and past
                // the light's plane: clipped on both sides.
                let d = (target - receiver) * rng.uniform(0.8, 1.5);
                out.push([q - d, q + d + e0, q + e1]);
            }
            4 => {
                // A corner exactly at the receiver.
                out.push([receiver, q + e0, q + e1]);
            }
            5 => {
                // Edge-on: the receiver in the triangle's plane.
                let a = q + e0;
                out.push([
                    receiver + (a - receiver) * 0.5,
                    a,
                    q + (q - receiver) * 0.25,
                ]);
            }
            _ => out.push([q - e0, q + e0, q + e1]),
        }
    }
    VisibilityCase {
        light,
        receiver,
        triangles: out,
    }
}
