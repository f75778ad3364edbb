//! The closed-form configurations in general position: turned by an
//! ordinary rotation, moved by an ordinary offset, every coordinate
//! rounded, and the closed form evaluated for the scene as rounded.

use super::dd;
use super::measured::{measure, Measured};
use super::plate::Plate;
use crate::scene::Light;
use glam::DVec3;

/// The same configurations in general position: the plate, the light and
/// the receivers turned by an ordinary rotation and moved by an ordinary
/// (non-dyadic) offset, every coordinate rounded. The closed form is then
/// evaluated for the scene as rounded: the edge's trace on the light's
/// plane from the rounded corners, the receiver and the light (its stored
/// centre, normal and radius), in double-double ([`dd`]); the segment's
/// area from that distance in `f64` ([`segment_area`](super::plate::segment_area)).
pub(super) struct General {
    /// The frame: `x` across the edge, `y` toward the light, `z` along the
    /// edge.
    frame: [DVec3; 3],
    offset: DVec3,
}

impl General {
    /// A frame turned by the angles (radians) about two axes, and the
    /// offset.
    pub(super) fn new(a: f64, b: f64, offset: DVec3) -> General {
        let (sa, ca) = a.sin_cos();
        let (sb, cb) = b.sin_cos();
        let x = DVec3::new(ca, sa * cb, sa * sb);
        let y = DVec3::new(-sa, ca * cb, ca * sb);
        let z = x.cross(y);
        General {
            frame: [x, y, z],
            offset,
        }
    }

    fn at(&self, v: DVec3) -> DVec3 {
        self.offset + self.frame[0] * v.x + self.frame[1] * v.y + self.frame[2] * v.z
    }

    /// The scene of `plate` in general position (its light facing `−y`),
    /// with `copies` plates each `shift` further across, and the points.
    pub(super) fn measure(
        &self,
        plate: &Plate,
        points: &[DVec3],
        copies: usize,
        shift: f64,
    ) -> Measured {
        let reach = plate.reach(points);
        let Ok(light) = Light::disk(
            self.at(DVec3::new(0.0, plate.big_h, 0.0)),
            -self.frame[1],
            plate.r,
        ) else {
            return Measured::refused(points.len());
        };
        let mut tris = Vec::with_capacity(2 * copies);
        let mut first = None;
        for k in 0..copies {
            let s = plate.s + shift * k as f64;
            let a = self.at(DVec3::new(s, plate.h, -reach));
            let b = self.at(DVec3::new(s + reach, plate.h, -reach));
            let c = self.at(DVec3::new(s + reach, plate.h, reach));
            let d = self.at(DVec3::new(s, plate.h, reach));
            first.get_or_insert((a, d, c));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
        let (a, d, inside) = first.expect("a plate");
        let moved: Vec<DVec3> = points.iter().map(|&p| self.at(p)).collect();
        measure(&light, tris, &moved, |p| {
            dd::visible(&light, p, a, d, inside)
        })
    }
}
