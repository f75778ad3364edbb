//! Generators for the disk-occlusion kernels ([`crate::kernel::disk`]).

use super::Rng;
use glam::DVec2;
use std::fmt;

/// One input of [`segment_disk_area`](crate::kernel::disk::f64::segment_disk_area):
/// a disk radius and an edge. Its `Debug` prints valid Rust, so a failing
/// case pastes straight into a regression test.
#[derive(Clone, Copy, PartialEq)]
pub struct DiskEdge {
    /// Disk radius.
    pub r: f64,
    /// Edge start.
    pub a: DVec2,
    /// Edge end.
    pub b: DVec2,
}

impl fmt::Debug for DiskEdge {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "DiskEdge {{ r: {:?}, a: DVec2::new({:?}, {:?}), b: DVec2::new({:?}, {:?}) }}",
            self.r, self.a.x, self.a.y, self.b.x, self.b.y
        )
    }
}

/// A unit vector at a uniform random angle.
pub fn direction(rng: &mut Rng) -> DVec2 {
    let phi = rng.uniform(0.0, std::f64::consts::TAU);
    DVec2::new(phi.cos(), phi.sin())
}

/// A disk radius, log-uniform over `1e-6 ..= 1e6`, or one of the round
/// values `1`, `0.5`, `3`.
pub fn radius(rng: &mut Rng) -> f64 {
    match rng.below(4) {
        0 => [1.0, 0.5, 3.0][rng.below(3) as usize],
        _ => rng.log_uniform(-6.0, 6.0),
    }
}

/// A point a few ulps off the circle of radius `r` (or on it, to rounding).
pub fn near_circle(rng: &mut Rng, r: f64) -> DVec2 {
    let p = direction(rng) * r;
    DVec2::new(rng.nudge(p.x, 4), rng.nudge(p.y, 4))
}

/// A position along a line relative to a disk of radius `r`: inside, on the
/// chord's end, just beyond it, or far away (up to `1e6 · r`).
fn position(rng: &mut Rng, r: f64, half_chord: f64) -> f64 {
    let s = rng.sign();
    match rng.below(5) {
        0 => s * half_chord,
        1 => s * rng.nudge(half_chord, 8),
        2 => s * rng.unit() * half_chord,
        3 => s * r * rng.log_uniform(0.0, 6.0),
        _ => s * r * rng.log_uniform(-8.0, 1.0),
    }
}

/// An edge in a stiff configuration for a disk of radius `r` centred at the
/// origin: a chord at a distance from the centre that is `0`, tiny, a few
/// ulps from `r`, or beyond `r`; endpoints on the circle, just off it, inside,
/// or up to a million radii away; zero-length edges; edges through the centre;
/// random edges of every scale. Rotated to a random direction.
pub fn edge(rng: &mut Rng, r: f64) -> (DVec2, DVec2) {
    let kind = rng.below(10);
    match kind {
        0 => {
            // Zero-length edge, anywhere.
            let p = direction(rng) * r * rng.log_uniform(-3.0, 3.0);
            (p, p)
        }
        1 => (near_circle(rng, r), near_circle(rng, r)),
        2 => {
            // Random endpoints in a box of random scale.
            let scale = r * rng.log_uniform(-3.0, 6.0);
            let mut p = || DVec2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * scale;
            (p(), p())
        }
        3 => {
            // Through the centre (collinear with it).
            let u = direction(rng);
            (u * position(rng, r, r), u * position(rng, r, r))
        }
        _ => {
            // A line at distance h: the stiff family.
            let h = match rng.below(6) {
                0 => 0.0,
                1 => r * rng.log_uniform(-12.0, 0.0),
                2 => rng.nudge(r, 16),
                3 => r * (1.0 - rng.log_uniform(-15.0, -1.0)),
                4 => r * (1.0 + rng.log_uniform(-15.0, 1.0)),
                _ => r * rng.unit(),
            };
            let half_chord = if h < r {
                ((r - h) * (r + h)).sqrt()
            } else {
                0.0
            };
            let (t0, t1) = (position(rng, r, half_chord), position(rng, r, half_chord));
            let u = direction(rng);
            let n = u.perp() * rng.sign();
            (u * t0 + n * h, u * t1 + n * h)
        }
    }
}

/// A [`DiskEdge`] from [`radius`] and [`edge`].
pub fn disk_edge(rng: &mut Rng) -> DiskEdge {
    let r = radius(rng);
    let (a, b) = edge(rng, r);
    DiskEdge { r, a, b }
}

/// A simple polygon (counter-clockwise) relative to a disk of radius `r`:
/// convex or star-shaped, 3 to 12 vertices, centred anywhere from the disk
/// centre to a few radii away, of any size from a hundredth of the disk to a
/// hundred times it; sometimes with vertices on the circle (to rounding);
/// sometimes a [`grazing_triangle`].
pub fn polygon(rng: &mut Rng, r: f64) -> Vec<DVec2> {
    if rng.chance(0.15) {
        return grazing_triangle(rng, r);
    }
    let n = 3 + rng.below(10) as usize;
    // Vertices snapped onto the circle: then the polygon is star-shaped
    // around the disk centre itself, so snapping keeps it simple.
    let snap = rng.chance(0.2);
    let centre = if snap {
        DVec2::ZERO
    } else {
        direction(rng) * r * rng.uniform(0.0, 3.0)
    };
    let size = r * rng.log_uniform(-2.0, 2.0);
    let star = rng.chance(0.5);
    // Increasing angles with every gap below π make the polygon star-shaped
    // around `centre`, hence simple and counter-clockwise.
    let start = rng.uniform(0.0, std::f64::consts::TAU);
    let step = std::f64::consts::TAU / n as f64;
    let angles: Vec<f64> = (0..n)
        .map(|i| start + (i as f64 + 0.5 * rng.unit()) * step)
        .collect();
    angles
        .into_iter()
        .map(|phi| {
            let radial = if snap && rng.chance(0.5) {
                r
            } else if star {
                size * rng.uniform(0.2, 1.0)
            } else {
                size
            };
            centre + DVec2::new(phi.cos(), phi.sin()) * radial
        })
        .collect()
}

/// A counter-clockwise triangle with one edge `10²` to `10⁹` radii long
/// whose line passes at a distance from the centre a few ulps from `r`,
/// inside or outside it, or anywhere up to `r`: the endpoints are far from
/// the disk while the edge grazes it.
pub fn grazing_triangle(rng: &mut Rng, r: f64) -> Vec<DVec2> {
    let h = match rng.below(3) {
        0 => rng.nudge(r, 16),
        1 => r * (1.0 - rng.log_uniform(-12.0, -1.0)),
        _ => r * rng.unit(),
    };
    let u = direction(rng);
    let n = u.perp();
    let half = r * rng.log_uniform(2.0, 9.0);
    let (t0, t1) = (-half * rng.uniform(0.5, 1.0), half * rng.uniform(0.5, 1.0));
    // The third vertex on the far side of the centre, so the triangle holds
    // it (or, half the time, on the near side, so it does not).
    let away = if rng.chance(0.5) { -1.0 } else { 1.0 } * half;
    let a = u * t0 + n * h;
    let b = u * t1 + n * h;
    let c = u * rng.uniform(-half, half) + n * (h + away);
    if (b - a).perp_dot(c - a) > 0.0 {
        vec![a, b, c]
    } else {
        vec![a, c, b]
    }
}

/// A clipped edge for
/// [`circle_segment_occlusion`](crate::kernel::disk::f64::circle_segment_occlusion):
/// `(d, w0, w1)` with `|d| < 1` near 0, near 1 (thin slivers) or anywhere,
/// and endpoints on the chord's ends, just inside, or anywhere on the chord.
pub fn clipped_edge(rng: &mut Rng) -> (f64, f64, f64) {
    let d = match rng.below(5) {
        0 => 0.0,
        1 => rng.log_uniform(-12.0, 0.0).min(1.0),
        2 => 1.0 - rng.log_uniform(-15.0, -0.5),
        3 => rng.nudge(1.0, 8),
        _ => rng.unit(),
    } * rng.sign();
    let s = ((1.0 - d.abs()) * (1.0 + d.abs())).max(0.0).sqrt();
    let end = |rng: &mut Rng| match rng.below(4) {
        0 => s,
        1 => rng.nudge(s, 8).min(s),
        2 => s * rng.uniform(-1.0, 1.0),
        _ => s * (1.0 - rng.log_uniform(-15.0, 0.0)),
    };
    let (w0, w1) = (end(rng), end(rng));
    (d, w0, w1)
}
