//! The exact reference measured against a closed form: its worst error
//! over a set of receivers, its certified bounds, its refusals; and the
//! dyadic scenes, moved so far that only their offset changes.

use super::plate::Plate;
use crate::bvh::{Bvh, Occluders};
use crate::reference::exact;
use crate::scene::Light;
use glam::DVec3;

/// The exact reference's worst error over a set of receivers (each with
/// its certified bound): the largest `|V − V_true|`, how many receivers
/// were refused, the largest bound, and how many bounds did not contain
/// their error (none, if the bound is right).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Measured {
    pub(super) max: f64,
    pub(super) refused: usize,
    pub(super) bound: f64,
    pub(super) violations: usize,
}

impl Measured {
    /// All `n` receivers refused (the scene could not be built).
    pub(super) fn refused(n: usize) -> Measured {
        Measured {
            max: f64::NAN,
            refused: n,
            ..Measured::default()
        }
    }
}

/// The exact reference's [`Measured`] error against `truth` over `points`,
/// with `light` and the triangles `tris`.
pub(super) fn measure(
    light: &Light,
    tris: Vec<[DVec3; 3]>,
    points: &[DVec3],
    truth: impl Fn(DVec3) -> f64,
) -> Measured {
    let bvh = Bvh::new(Occluders::from_triangles(tris));
    let values = exact::visibility_many_bounded(&bvh, light, points);
    let mut m = Measured::default();
    for (&p, v) in points.iter().zip(values) {
        match v {
            Ok(b) => {
                let err = (b.visibility - truth(p)).abs();
                m.max = m.max.max(err);
                m.bound = m.bound.max(b.bound);
                if err > b.bound {
                    m.violations += 1;
                }
            }
            Err(_) => m.refused += 1,
        }
    }
    m
}

/// The largest `|V − V_closed|` of the exact reference over `points`
/// (moved by `offset`, dyadic: the same scene).
pub(super) fn exact_error(
    plate: &Plate,
    offset: DVec3,
    points: &[DVec3],
    copies: usize,
    shift: f64,
) -> Measured {
    let reach = plate.reach(points);
    let Some((light, tris)) = plate.scene(offset, reach, copies, shift) else {
        return Measured::refused(points.len());
    };
    let moved: Vec<DVec3> = points.iter().map(|&p| p + offset).collect();
    measure(&light, tris, &moved, |q| plate.fraction(q - offset))
}
