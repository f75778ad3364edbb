//! The stability suite (`softshadow stability`): the kernels in `f32`
//! against `f64`, the exact reference against closed forms, and every
//! method of the default sets on stiff scenes, over families of extreme
//! input — far offsets, tiny and huge lights, grazing views, contact,
//! nearly coincident edges, deep overlap.
//!
//! # The answers measured against
//!
//! - **The exact reference** (`f64`): one straight edge of a plate parallel
//!   to a disk light hides, from a receiver, the part of the disk beyond a
//!   line — a circle segment, whose area has a closed form. Every family
//!   is built on that configuration; where it is moved far from the origin
//!   the coordinates are dyadic with few bits, so that the moved scene is
//!   the same scene exactly and the closed form does not change.
//! - **`f32` kernels**: the `f64` kernel on the same (`f32`-rounded)
//!   input, so that the error is the `f32` arithmetic's and not the
//!   input's rounding.
//! - **`f64` kernels**: answers known independently — a circle segment's
//!   area from its half-angle (a series for thin segments), the falloff's
//!   exact symmetry and thin-sliver closed form, the Bernstein polynomial
//!   where it is exact, silhouettes against a facing test per face. Their
//!   errors against 256-bit evaluations on random stiff input are measured
//!   by the tests (`docs/accuracy/kernels.md`).
//! - **Methods**: the exact reference on the same stiff scene, and the
//!   method's own answer on the scene before it was moved.

use crate::bvh::{Bvh, Occluders};
use crate::kernel::disk;
use crate::kernel::linear_light::{self, OccluderSide};
use crate::method::{self, Exact};
use crate::reference::exact;
use crate::render::image::ErrorSummary;
use crate::render::{Frame, Stages};
use crate::scene::primitive::Transform;
use crate::scene::{builtin, Camera, Light, Mesh, Scene};
use glam::{DVec2, DVec3, Vec2};
use std::fmt::Write as _;

/// One measured row.
#[derive(Clone, Debug)]
pub struct Row {
    /// What is measured (`exact reference`, `disk::segment_disk_area`, a
    /// method's name).
    pub subject: String,
    /// The family (`far offset`, …).
    pub family: &'static str,
    /// The family's parameter for this row.
    pub case: String,
    /// `f32` or `f64`.
    pub precision: &'static str,
    /// Inputs evaluated.
    pub count: usize,
    /// The largest error (in the unit the section states).
    pub max: f64,
    /// For the exact reference, the largest of its certified bounds over
    /// the row's receivers (and whether each contained its error: the
    /// note says otherwise).
    pub bound: Option<f64>,
    /// Whether the row is inside the subject's documented domain, and if
    /// not, why.
    pub note: String,
}

impl Row {
    /// A row of an `f64` subject.
    fn f64(
        subject: &str,
        family: &'static str,
        case: impl Into<String>,
        count: usize,
        max: f64,
        note: &str,
    ) -> Row {
        Row {
            subject: subject.to_owned(),
            family,
            case: case.into(),
            precision: "f64",
            count,
            max,
            bound: None,
            note: note.to_owned(),
        }
    }
}

/// A closed-form case: a disk light of radius `r` at height `big_h`
/// facing down, centred above the origin; a plate at height `h` covering
/// `x > s`; receivers at the points given.
struct Plate {
    r: f64,
    big_h: f64,
    h: f64,
    s: f64,
}

impl Plate {
    /// The visible fraction from `p` (relative to the light's centre
    /// column): the plate's edge, seen from `p`, crosses the light's plane
    /// at `x = c`; the part beyond is hidden.
    fn fraction(&self, p: DVec3) -> f64 {
        let k = (self.big_h - p.y) / (self.h - p.y);
        let c = p.x + (self.s - p.x) * k;
        let t = (c / self.r).clamp(-1.0, 1.0);
        // The hidden segment's area over πr².
        let hidden = (t.acos() - t * (1.0 - t * t).max(0.0).sqrt()) / std::f64::consts::PI;
        1.0 - hidden
    }

    /// The plate (two triangles) and the light, moved by `offset`; the
    /// plate reaches `reach` past the edge and sideways.
    fn scene(
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

/// The exact reference's worst error against `truth` over `points` (each
/// with its certified bound): the largest `|V − V_true|`, how many
/// receivers were refused, the largest bound, and how many bounds did not
/// contain their error (none, if the bound is right).
#[derive(Clone, Copy, Debug, Default)]
struct Measured {
    max: f64,
    refused: usize,
    bound: f64,
    violations: usize,
}

fn measure(
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
fn exact_error(
    plate: &Plate,
    offset: DVec3,
    points: &[DVec3],
    copies: usize,
    shift: f64,
) -> Measured {
    let reach =
        64.0 * (plate.r + 1.0) * (1.0 + points.iter().map(|p| p.x.abs()).fold(0.0, f64::max));
    let Some((light, tris)) = plate.scene(offset, reach, copies, shift) else {
        return Measured {
            max: f64::NAN,
            refused: points.len(),
            ..Measured::default()
        };
    };
    let moved: Vec<DVec3> = points.iter().map(|&p| p + offset).collect();
    measure(&light, tris, &moved, |q| plate.fraction(q - offset))
}

/// The same configurations in general position: the plate, the light and
/// the receivers turned by an ordinary rotation and moved by an ordinary
/// (non-dyadic) offset, every coordinate rounded. The closed form is then
/// evaluated for the scene as rounded: the edge's trace on the light's
/// plane from the rounded corners, the receiver and the light (its stored
/// centre, normal and radius), in double-double ([`dd`]); the segment's
/// area from that distance in `f64` ([`segment_area`]).
struct General {
    /// The frame: `x` across the edge, `y` toward the light, `z` along the
    /// edge.
    frame: [DVec3; 3],
    offset: DVec3,
}

impl General {
    /// A frame turned by the angles (radians) about two axes, and the
    /// offset.
    fn new(a: f64, b: f64, offset: DVec3) -> General {
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
    fn measure(&self, plate: &Plate, points: &[DVec3], copies: usize, shift: f64) -> Measured {
        let reach =
            64.0 * (plate.r + 1.0) * (1.0 + points.iter().map(|p| p.x.abs()).fold(0.0, f64::max));
        let Ok(light) = Light::disk(
            self.at(DVec3::new(0.0, plate.big_h, 0.0)),
            -self.frame[1],
            plate.r,
        ) else {
            return Measured {
                max: f64::NAN,
                refused: points.len(),
                ..Measured::default()
            };
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

/// Double-double arithmetic for the general-position closed form.
mod dd {
    use crate::kernel::eft::f64::two_prod;
    use crate::scene::Light;
    use glam::DVec3;

    /// `hi + lo`, about 106 bits.
    #[derive(Clone, Copy, Debug)]
    struct Dd(f64, f64);

    fn two_sum(a: f64, b: f64) -> Dd {
        let s = a + b;
        let bv = s - a;
        Dd(s, (a - (s - bv)) + (b - bv))
    }

    impl Dd {
        fn add(self, o: Dd) -> Dd {
            let s = two_sum(self.0, o.0);
            let t = s.1 + self.1 + o.1;
            two_sum(s.0, t)
        }
        fn neg(self) -> Dd {
            Dd(-self.0, -self.1)
        }
        fn sub(self, o: Dd) -> Dd {
            self.add(o.neg())
        }
        fn mul(self, o: Dd) -> Dd {
            let (p, e) = two_prod(self.0, o.0);
            two_sum(p, e + (self.0 * o.1 + self.1 * o.0))
        }
        fn div(self, o: Dd) -> Dd {
            let q = self.0 / o.0;
            let r = self.sub(o.mul(Dd(q, 0.0)));
            two_sum(q, r.0 / o.0)
        }
        fn sqrt(self) -> Dd {
            if self.0 <= 0.0 {
                return Dd(0.0, 0.0);
            }
            let x = self.0.sqrt();
            let (p, e) = two_prod(x, x);
            let r = self.sub(Dd(p, e));
            two_sum(x, r.0 / (2.0 * x))
        }
        fn value(self) -> f64 {
            self.0 + self.1
        }
    }

    type V = [Dd; 3];

    /// `a − b` exactly.
    fn diff(a: DVec3, b: DVec3) -> V {
        [two_sum(a.x, -b.x), two_sum(a.y, -b.y), two_sum(a.z, -b.z)]
    }
    fn of(a: DVec3) -> V {
        [Dd(a.x, 0.0), Dd(a.y, 0.0), Dd(a.z, 0.0)]
    }
    fn dot(a: &V, b: &V) -> Dd {
        a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
    }
    fn cross(a: &V, b: &V) -> V {
        [
            a[1].mul(b[2]).sub(a[2].mul(b[1])),
            a[2].mul(b[0]).sub(a[0].mul(b[2])),
            a[0].mul(b[1]).sub(a[1].mul(b[0])),
        ]
    }

    /// The visible fraction of the disk light from `p` with one straight
    /// occluding edge `a d` of a plate on the side of `inside`, as the
    /// inputs are given: the plane through `p` and the edge meets the
    /// light's plane (its stored centre and normal) in a line at signed
    /// distance `h r` from the centre; the part beyond it is hidden.
    pub(super) fn visible(light: &Light, p: DVec3, a: DVec3, d: DVec3, inside: DVec3) -> f64 {
        let Light::Disk(disk) = light else {
            return f64::NAN;
        };
        let m = cross(&diff(a, p), &diff(d, a));
        let n = of(disk.normal());
        let n = {
            let l = dot(&n, &n).sqrt();
            [n[0].div(l), n[1].div(l), n[2].div(l)]
        };
        // m's part in the light's plane: n × (m × n).
        let m_par = cross(&n, &cross(&m, &n));
        let len = dot(&m_par, &m_par).sqrt();
        let side = dot(&m, &diff(inside, p)).value().signum();
        // The centre's signed distance from the line, positive on the
        // visible side, in radii.
        let dist = dot(&m, &diff(disk.center(), p)).div(len).value() * -side;
        let h = (dist / disk.radius()).clamp(-1.0, 1.0);
        // The hidden segment's half-angle acos(h) = atan2(√(1 − h²), h),
        // 1 − h² as (1 − h)(1 + h).
        let half = ((1.0 - h) * (1.0 + h)).max(0.0).sqrt().atan2(h);
        1.0 - super::segment_area(2.0 * half) / std::f64::consts::PI
    }
}

/// Receivers across the penumbra of `plate` on the floor (`y = 0`),
/// `n` of them, placed so that the edge's image crosses the light at
/// `c = t·r` for `t` in `[−0.95, 0.95]`, on dyadic `x` (rounded to a
/// multiple of `2^-k` with `k` chosen for the size).
fn receivers(plate: &Plate, y: f64, n: usize) -> Vec<DVec3> {
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

/// The exact reference's section: every family twice, dyadic (the
/// closed form exact, the moved scene the same scene) and in general
/// position with ordinary coordinates (every input rounded; the closed
/// form of the scene as rounded, [`General`]).
fn exact_rows(rows: &mut Vec<Row>) {
    let row = |family: &'static str, case: String, m: Measured, n: usize| Row {
        subject: "exact reference".to_owned(),
        family,
        case,
        precision: "f64",
        count: n - m.refused,
        max: m.max,
        bound: Some(m.bound),
        note: if m.violations > 0 {
            format!("{} bounds below their error", m.violations)
        } else if m.refused > 0 {
            format!(
                "{} receivers refused (a typed error, documented)",
                m.refused
            )
        } else if m.max <= 4e-15 {
            "inside; within a few ulps, every bound containing its error".to_owned()
        } else {
            "inside the documented domain, above a few ulps; every bound containing its error"
                .to_owned()
        },
    };
    // General position: turned by these angles, moved by ordinary offsets.
    let general = |scale: f64| {
        General::new(
            0.7319,
            -0.4127,
            DVec3::new(0.61237, -0.44371, 0.77113) * scale,
        )
    };
    let unit = Plate {
        r: 0.5,
        big_h: 2.0,
        h: 1.0,
        s: 0.0,
    };
    // Far offsets: dyadic, so the moved scene is the same scene; and
    // ordinary offsets of the same size in general position.
    let base = receivers(&unit, 0.0, 33);
    let base: Vec<DVec3> = base
        .iter()
        .map(|p| DVec3::new((p.x * 1024.0).round() / 1024.0, p.y, p.z))
        .collect();
    for e in [3, 4, 5, 6, 7, 8, 9] {
        let d = 2f64.powi((f64::from(e) * std::f64::consts::LOG2_10).round() as i32);
        let offset = DVec3::new(d, d * 0.5, -d);
        rows.push(row(
            "far offset",
            format!("10^{e} (2^{}), dyadic", d.log2() as i32),
            exact_error(&unit, offset, &base, 1, 0.0),
            base.len(),
        ));
        rows.push(row(
            "far offset",
            format!("10^{e}, ordinary"),
            general(10f64.powi(e)).measure(&unit, &base, 1, 0.0),
            base.len(),
        ));
    }
    // Light size relative to its height.
    for r in [1e-6, 1e-5, 1e-4, 1e-3, 10.0, 100.0, 1000.0] {
        let plate = Plate { r, ..unit };
        let pts = receivers(&plate, 0.0, 33);
        rows.push(row(
            "light size",
            format!("r = {r:e}, dyadic"),
            exact_error(&plate, DVec3::ZERO, &pts, 1, 0.0),
            pts.len(),
        ));
        rows.push(row(
            "light size",
            format!("r = {r:e}, ordinary"),
            general(1.0).measure(&plate, &pts, 1, 0.0),
            pts.len(),
        ));
    }
    // Grazing: the receivers far to the side, seeing the light at
    // elevation θ.
    for e in [1, 2, 3, 4, 5, 6] {
        let theta = 10f64.powi(-e);
        let x = -unit.big_h / theta;
        // The edge where the penumbra's middle falls at x: c = 0.
        let k = unit.big_h / unit.h;
        // Dyadic (multiples of 2^-28), so that the closed form's
        // `c = x + (s − x)·2` is exact and its error is not the answer's.
        let dyadic = |v: f64| (v * 268_435_456.0).round() / 268_435_456.0;
        let plate = Plate {
            s: dyadic(x * (k - 1.0) / k),
            ..unit
        };
        let pts: Vec<DVec3> = (0..33)
            .map(|i| {
                let t = -0.95 + 1.9 * f64::from(i) / 32.0;
                DVec3::new(dyadic((t * plate.r - plate.s * k) / (1.0 - k)), 0.0, 0.0)
            })
            .collect();
        rows.push(row(
            "grazing",
            format!("elevation 1e-{e}, dyadic"),
            exact_error(&plate, DVec3::ZERO, &pts, 1, 0.0),
            pts.len(),
        ));
        rows.push(row(
            "grazing",
            format!("elevation 1e-{e}, ordinary"),
            general(1.0).measure(&plate, &pts, 1, 0.0),
            pts.len(),
        ));
    }
    // Contact: the receivers just under the plate.
    for e in [10, 20, 30] {
        let y = unit.h - 2f64.powi(-e);
        let pts = receivers(&unit, y, 33);
        rows.push(row(
            "contact",
            format!("2^-{e} under the plate, dyadic"),
            exact_error(&unit, DVec3::ZERO, &pts, 1, 0.0),
            pts.len(),
        ));
    }
    for e in [3, 6, 9, 12] {
        let y = unit.h - 1.37 * 10f64.powi(-e);
        let pts = receivers(&unit, y, 33);
        rows.push(row(
            "contact",
            format!("1.37e-{e} under the plate, ordinary"),
            general(1.0).measure(&unit, &pts, 1, 0.0),
            pts.len(),
        ));
    }
    // Nearly coincident edges: a second plate's edge 2^-k past the first.
    for e in [20, 40, 52] {
        let pts = receivers(&unit, 0.0, 33);
        rows.push(row(
            "coincident edges",
            format!("second edge 2^-{e} away, dyadic"),
            exact_error(&unit, DVec3::ZERO, &pts, 2, 2f64.powi(-e)),
            pts.len(),
        ));
        rows.push(row(
            "coincident edges",
            format!("second edge 2^-{e} away, ordinary"),
            general(1.0).measure(&unit, &pts, 2, 2f64.powi(-e)),
            pts.len(),
        ));
    }
    // Deep overlap: 10⁴ plates on one another (the same, then each 2^-30
    // further; the union is the first).
    let pts = receivers(&unit, 0.0, 9);
    for (case, shift) in [
        ("10^4 coincident plates", 0.0),
        ("10^4 plates, each 2^-30 further", 2f64.powi(-30)),
    ] {
        rows.push(row(
            "deep overlap",
            format!("{case}, dyadic"),
            exact_error(&unit, DVec3::ZERO, &pts, 10_000, shift),
            pts.len(),
        ));
        rows.push(row(
            "deep overlap",
            format!("{case}, ordinary"),
            general(1.0).measure(&unit, &pts, 10_000, shift),
            pts.len(),
        ));
    }
}

/// `f32` kernels against `f64` on the same `f32` input.
fn kernel_rows(rows: &mut Vec<Row>) {
    let f32_note = |scale: f64, feature: f64| {
        if scale * f64::from(f32::EPSILON) > feature {
            format!("beyond f32's resolution: inputs of magnitude {scale:.0e} round by more than the feature size {feature:.0e}")
        } else {
            "inside".to_owned()
        }
    };
    // segment_disk_area: a chord at distance d·r from the centre, its ends
    // `far` away along the chord, error over r².
    let segment = |r: f64, d: f64, far: f64| -> f64 {
        let a = Vec2::new(-far as f32, (d * r) as f32);
        let b = Vec2::new(far as f32, (d * r) as f32);
        let rf = r as f32;
        let got = f64::from(disk::f32::segment_disk_area(rf, a, b));
        let want = disk::f64::segment_disk_area(f64::from(rf), a.as_dvec2(), b.as_dvec2());
        (got - want).abs() / (f64::from(rf) * f64::from(rf))
    };
    let chords = |r: f64, far: f64| -> f64 {
        (0..=40)
            .map(|i| segment(r, -0.99 + 1.98 * f64::from(i) / 40.0, far))
            .fold(0.0, f64::max)
    };
    let subject = "disk::segment_disk_area (error / r²)";
    for e in [3, 5, 8] {
        let far = 10f64.powi(e);
        rows.push(Row {
            subject: subject.to_owned(),
            family: "far offset",
            case: format!("chord ends 10^{e} away, r = 1"),
            precision: "f32",
            count: 41,
            max: chords(1.0, far),
            bound: None,
            note: "inside (documented: 3ε·r² for any edge length)".to_owned(),
        });
    }
    for r in [1e-6, 1e-3, 1e3] {
        rows.push(Row {
            subject: subject.to_owned(),
            family: "light size",
            case: format!("r = {r:e}, chord ends 2r away"),
            precision: "f32",
            count: 41,
            max: chords(r, 2.0 * r),
            bound: None,
            note: "inside".to_owned(),
        });
    }
    for e in [3, 6] {
        let d = 1.0 - 10f64.powi(-e);
        rows.push(Row {
            subject: subject.to_owned(),
            family: "grazing",
            case: format!("chord at (1 − 1e-{e})·r"),
            precision: "f32",
            count: 1,
            max: segment(1.0, d, 2.0),
            bound: None,
            note: f32_note(1.0, 10f64.powi(-e)),
        });
    }
    // linear_light::visible_part: a light [0, 1] on the x axis, the
    // fragment at height `y` and offset `x0`, the edge on the segment to
    // the light's middle; error of the fraction.
    let subject = "linear_light::visible_part (fraction)";
    let part = |x0: f64, y: f64, len: f64| -> f64 {
        let mut worst = 0.0f64;
        for i in 0..=20 {
            let t = 0.05 + 0.9 * f64::from(i) / 20.0;
            let l = DVec2::new(x0, 0.0);
            let r = DVec2::new(x0 + len, 0.0);
            let f = DVec2::new(x0 + 0.5 * len, -y);
            let e = f + (l + (r - l) * t - f) * 0.5;
            let conv = |p: DVec2| p.as_vec2();
            let got = linear_light::f32::visible_part(
                conv(l),
                conv(r),
                conv(f),
                conv(e),
                OccluderSide::TowardR,
            );
            let want = linear_light::f64::visible_part(
                conv(l).as_dvec2(),
                conv(r).as_dvec2(),
                conv(f).as_dvec2(),
                conv(e).as_dvec2(),
                OccluderSide::TowardR,
            );
            worst = worst.max((f64::from(got.fraction) - want.fraction).abs());
        }
        worst
    };
    for e in [3, 5, 8] {
        let x0 = 10f64.powi(e);
        rows.push(Row {
            subject: subject.to_owned(),
            family: "far offset",
            case: format!("light 10^{e} from the origin, length 1"),
            precision: "f32",
            count: 21,
            max: part(x0, 1.0, 1.0),
            bound: None,
            note: f32_note(x0, 1.0),
        });
    }
    for e in [3, 6] {
        let y = 10f64.powi(-e);
        rows.push(Row {
            subject: subject.to_owned(),
            family: "grazing",
            case: format!("fragment 1e-{e} from the light's line"),
            precision: "f32",
            count: 21,
            max: part(0.0, y, 1.0),
            bound: None,
            note: "inside".to_owned(),
        });
    }
    for len in [1e-6, 1e3] {
        rows.push(Row {
            subject: subject.to_owned(),
            family: "light size",
            case: format!("length {len:e}, fragment at 1"),
            precision: "f32",
            count: 21,
            max: part(0.0, 1.0, len),
            bound: None,
            note: "inside".to_owned(),
        });
    }
    scalar_kernel_rows(rows);
}

/// One `f32` kernel of scalars against its `f64` twin on the same
/// (`f32`-rounded) inputs: the largest error, absolute or relative to the
/// `f64` value.
fn scalar_row(
    rows: &mut Vec<Row>,
    (subject, family, case): (&str, &'static str, String),
    inputs: &[[f64; 3]],
    f32_fn: impl Fn([f32; 3]) -> f32,
    f64_fn: impl Fn([f64; 3]) -> f64,
    relative: bool,
) {
    let mut worst = 0.0f64;
    for x in inputs {
        let xf = x.map(|v| v as f32);
        let got = f64::from(f32_fn(xf));
        let want = f64_fn(xf.map(f64::from));
        let e = if relative {
            (got - want).abs() / want.abs().max(f64::MIN_POSITIVE)
        } else {
            (got - want).abs()
        };
        worst = worst.max(if e.is_nan() { f64::INFINITY } else { e });
    }
    rows.push(Row {
        subject: subject.to_owned(),
        family,
        case,
        precision: "f32",
        count: inputs.len(),
        max: worst,
        bound: None,
        note: "inside".to_owned(),
    });
}

/// The scalar kernels in `f32` against `f64`: the falloffs near their
/// ends, `atan2` at extreme magnitudes and near the axes, the footprint
/// radius and SSOC's distortion at contact and far away.
fn scalar_kernel_rows(rows: &mut Vec<Row>) {
    use crate::kernel::{angle, distortion, falloff, footprint};
    let ramp = |lo: f64, hi: f64, n: usize| -> Vec<[f64; 3]> {
        (0..=n)
            .map(|i| [lo + (hi - lo) * i as f64 / n as f64, 0.0, 0.0])
            .collect()
    };
    let ends = |eps: f64| -> Vec<[f64; 3]> {
        (0..=20)
            .flat_map(|i| {
                let t = eps * (1.0 + i as f64 / 20.0);
                [[t, 0.0, 0.0], [1.0 - t, 0.0, 0.0]]
            })
            .collect()
    };
    for (name, f32_fn, f64_fn) in [
        (
            "falloff::bernstein (absolute)",
            falloff::f32::bernstein as fn(f32) -> f32,
            falloff::f64::bernstein as fn(f64) -> f64,
        ),
        (
            "falloff::disk_edge_falloff (absolute)",
            falloff::f32::disk_edge_falloff,
            falloff::f64::disk_edge_falloff,
        ),
    ] {
        scalar_row(
            rows,
            (name, "uniform", "t in [0, 1]".to_owned()),
            &ramp(0.0, 1.0, 200),
            |x| f32_fn(x[0]),
            |x| f64_fn(x[0]),
            false,
        );
        for e in [3, 6] {
            scalar_row(
                rows,
                (name, "contact", format!("t within 1e-{e} of 0 and 1")),
                &ends(10f64.powi(-e)),
                |x| f32_fn(x[0]),
                |x| f64_fn(x[0]),
                false,
            );
        }
    }
    let name = "angle::atan2 (relative)";
    for (family, case, scale) in [
        ("far offset", "x and y of magnitude 1e30", 1e30),
        ("light size", "x and y of magnitude 1e-30", 1e-30),
        ("uniform", "x and y of magnitude 1", 1.0),
    ] {
        let inputs: Vec<[f64; 3]> = (0..64)
            .map(|i| {
                let a = -3.1 + 6.2 * f64::from(i) / 63.0;
                [a.sin() * scale, a.cos() * scale, 0.0]
            })
            .collect();
        scalar_row(
            rows,
            (name, family, case.to_owned()),
            &inputs,
            |x| angle::f32::atan2(x[0], x[1]),
            |x| angle::f64::atan2(x[0], x[1]),
            true,
        );
    }
    let near_axis: Vec<[f64; 3]> = (1..=30)
        .map(|k| [10f64.powi(-k / 2 - 1), 1.0, 0.0])
        .collect();
    scalar_row(
        rows,
        (name, "grazing", "y/x from 1e-1 to 1e-16".to_owned()),
        &near_axis,
        |x| angle::f32::atan2(x[0], x[1]),
        |x| angle::f64::atan2(x[0], x[1]),
        true,
    );
    let name = "footprint::radius (relative)";
    for (family, case, inputs) in [
        (
            "contact",
            "receiver 1e-3 … 1e-6 past the occluder (relative)",
            (3..=6)
                .map(|e| [0.5, 2.0, 2.0 * (1.0 + 10f64.powi(-e))])
                .collect::<Vec<_>>(),
        ),
        (
            "light size",
            "light radius 1e-6 … 1e3",
            [1e-6, 1e-3, 1.0, 1e3].map(|r| [r, 2.0, 3.0]).to_vec(),
        ),
        (
            "far offset",
            "depths 1e3 … 1e8",
            (3..=8)
                .map(|e| [0.5, 10f64.powi(e), 1.5 * 10f64.powi(e)])
                .collect(),
        ),
    ] {
        scalar_row(
            rows,
            (name, family, case.to_owned()),
            &inputs,
            |x| footprint::f32::radius(x[0], x[1], x[2]),
            |x| footprint::f64::radius(x[0], x[1], x[2]),
            true,
        );
    }
    let name = "distortion::max_distortion (relative)";
    scalar_row(
        rows,
        (
            name,
            "contact",
            "receiver 1e-3 … 1e-6 past the near depth".to_owned(),
        ),
        &(3..=6)
            .map(|e| [0.5, 2.0, 2.0 * (1.0 + 10f64.powi(-e))])
            .collect::<Vec<_>>(),
        |x| distortion::f32::max_distortion(x[0], x[1], x[2]),
        |x| distortion::f64::max_distortion(x[0], x[1], x[2]),
        true,
    );
}

/// A built-in scene moved by `offset`, its light scaled by `light_scale`.
fn moved(name: &str, offset: DVec3, light_scale: f64) -> Option<Scene> {
    let scene = builtin(name)?;
    let t = Transform::new(1.0, 0.0, offset).ok()?;
    let light = match scene.light() {
        Light::Sphere(s) => Light::sphere(s.center() + offset, s.radius() * light_scale).ok()?,
        other => *other,
    };
    let camera = scene.camera()?;
    let (w, h) = camera.resolution();
    let camera = Camera::new(
        camera.eye() + offset,
        camera.target() + offset,
        camera.up(),
        camera.fov_y_deg(),
        w,
        h,
    )
    .ok()?;
    let mut out = Scene::new(light).with_camera(camera);
    for (mesh, name) in scene.meshes().iter().zip(scene.names()) {
        let m: Mesh = t.apply(mesh).ok()?;
        out = out.with_mesh(name.clone(), m);
    }
    Some(out)
}

/// The default scene with its light at elevation `deg` over the floor.
fn grazing(deg: f64) -> Option<Scene> {
    let scene = builtin("default")?;
    let a = deg.to_radians();
    let light = Light::sphere(DVec3::new(6.0 * a.cos(), 6.0 * a.sin() + 0.3, 0.0), 0.5).ok()?;
    Some(scene.with_light(light))
}

/// Every method of the sphere light's default set on stiff versions of
/// the default scene, at `side²`: RMSE against the exact reference there,
/// values out of `[0, 1]` or not finite, and the method's RMSE on the
/// scene as built in.
fn method_rows(rows: &mut Vec<Row>, side: u32) {
    let cases: Vec<(&'static str, String, Option<Scene>)> = vec![
        (
            "far offset",
            "moved by 2^10".to_owned(),
            moved("default", DVec3::splat(1024.0), 1.0),
        ),
        (
            "far offset",
            "moved by 2^20".to_owned(),
            moved("default", DVec3::splat(1_048_576.0), 1.0),
        ),
        (
            "light size",
            "light radius × 2^-10".to_owned(),
            moved("default", DVec3::ZERO, 1.0 / 1024.0),
        ),
        (
            "light size",
            "light radius × 4".to_owned(),
            moved("default", DVec3::ZERO, 4.0),
        ),
        (
            "grazing",
            "light 2° over the floor".to_owned(),
            grazing(2.0),
        ),
        (
            "contact",
            "the contact scene".to_owned(),
            builtin("contact"),
        ),
    ];
    // Each method's RMSE on the default scene as built in.
    let mut unmoved: Vec<(String, f64)> = Vec::new();
    if let Some(scene) = builtin("default") {
        if let Some((frame, exact)) = frame_and_exact(&scene, side) {
            let stages = Stages::new(&scene);
            for m in method::default_set(scene.light().kind()) {
                if let Ok(run) = method::run(m.as_ref(), &stages, &frame) {
                    let rmse = ErrorSummary::new(&run.output.visibility, &exact, |_| true).rmse;
                    unmoved.push((m.name(), rmse));
                }
            }
        }
    }
    for (family, case, scene) in cases {
        let Some(scene) = scene else {
            rows.push(Row {
                subject: "(scene)".to_owned(),
                family,
                case,
                precision: "f64",
                count: 0,
                max: f64::NAN,
                bound: None,
                note: "the scene could not be built".to_owned(),
            });
            continue;
        };
        let Some((frame, exact)) = frame_and_exact(&scene, side) else {
            rows.push(Row {
                subject: "exact reference".to_owned(),
                family,
                case,
                precision: "f64",
                count: 0,
                max: f64::NAN,
                bound: None,
                note: "refused (a receiver inside the light, or no camera)".to_owned(),
            });
            continue;
        };
        let stages = Stages::new(&scene);
        for m in method::default_set(scene.light().kind()) {
            if m.name() == "exact" || m.name().starts_with("mc") {
                continue;
            }
            let mut note = String::new();
            let (max, count) = match method::run(m.as_ref(), &stages, &frame) {
                Ok(run) => {
                    let v = run.output.visibility;
                    let bad = v.iter().filter(|x| !(0.0..=1.0).contains(*x)).count();
                    let rmse = ErrorSummary::new(&v, &exact, |_| true).rmse;
                    let before = unmoved.iter().find(|(n, _)| *n == m.name()).map(|x| x.1);
                    match before {
                        Some(b) => {
                            let _ = write!(note, "RMSE {b:.4} on the scene as built in");
                        }
                        None => note.push_str("inside"),
                    }
                    if bad > 0 {
                        let _ = write!(note, "; {bad} values outside [0, 1] or not finite");
                    }
                    (rmse, v.len())
                }
                Err(e) => {
                    let _ = write!(note, "refused: {e}");
                    (f64::NAN, 0)
                }
            };
            rows.push(Row {
                subject: m.name(),
                family,
                case: case.clone(),
                precision: "f64",
                count,
                max,
                bound: None,
                note,
            });
        }
    }
}

/// `(x − sin x) / 2`, the area of a unit circle's segment of central angle
/// `x`, to a few ulps for every `x ∈ [0, 2π]` (a series below 1, where the
/// difference cancels).
fn segment_area(x: f64) -> f64 {
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

/// The `f64` kernels against answers known independently: closed forms
/// evaluated without cancellation (a circle segment's area from the
/// half-angle `asin(√δ)`, with a series for thin segments), exact
/// identities, and, for silhouettes, a facing test per face.
fn f64_kernel_rows(rows: &mut Vec<Row>) {
    use crate::kernel::falloff::f64 as falloff;
    use crate::kernel::silhouette::MeshTopology;
    // polygon_disk_area of a big triangle beyond the chord at distance
    // (1 − δ)·r, its corners `far` away: the segment r² (x − sin x)/2 with
    // x = 4 asin(√(δ/2)). The error over r², the measure of the kernel's
    // documented bound (an absolute 3ε·r²); δ is taken from the rounded
    // chord, so that the input's rounding is not counted.
    let cap = |r: f64, delta: f64, far: f64| -> f64 {
        let y = (1.0 - delta) * r;
        let tri = [
            DVec2::new(-far, y),
            DVec2::new(far, y),
            DVec2::new(0.0, y + far),
        ];
        let got = disk::f64::polygon_disk_area(r, &tri);
        let delta = (r - y) / r;
        let want = r * r * segment_area(4.0 * (0.5 * delta).sqrt().asin());
        (got - want).abs() / (r * r)
    };
    let subject = "disk::polygon_disk_area (error / r²)";
    let mut push = |family, case: String, count, max, note| {
        rows.push(Row::f64(subject, family, case, count, max, note));
    };
    let deltas = [0.5, 0.25, 1.0, 1.5, 1.9];
    let worst = |r: f64, far: f64| deltas.iter().map(|&d| cap(r, d, far)).fold(0.0, f64::max);
    for e in [3, 5, 8] {
        let far = 10f64.powi(e);
        push(
            "far offset",
            format!("triangle corners 10^{e} away, r = 1"),
            deltas.len(),
            worst(1.0, far),
            "inside (documented: 3ε·r²)",
        );
    }
    for r in [1e-6, 1e-3, 1e3] {
        push(
            "light size",
            format!("r = {r:e}, corners 10r away"),
            deltas.len(),
            worst(r, 10.0 * r),
            "inside (documented: 3ε·r²)",
        );
    }
    for e in [3, 6, 9, 12] {
        let delta = 10f64.powi(-e);
        push(
            "grazing",
            format!("chord at (1 − 1e-{e})·r"),
            1,
            cap(1.0, delta, 4.0),
            "inside (documented: 3ε·r², absolute: a sliver's relative error grows as it thins)",
        );
    }

    // The straight-edge falloff: F(t) + F(1 − t) = 1 on dyadic t (both
    // exact), F(½) = ½, and thin slivers against the closed form
    // F(t) = (x − sin x)/(2π), x = 4 asin(√t).
    let f = falloff::disk_edge_falloff;
    let symmetric = (1..1024)
        .map(|k| {
            let t = f64::from(k) / 1024.0;
            (f(t) + f(1.0 - t) - 1.0).abs()
        })
        .fold((f(0.5) - 0.5).abs(), f64::max);
    rows.push(Row::f64(
        "falloff::disk_edge_falloff",
        "symmetry",
        "|F(t) + F(1 − t) − 1| at t = k/1024, and F(½) − ½",
        1024,
        symmetric,
        "inside (absolute)",
    ));
    for e in [3, 6, 9, 12] {
        let t = 10f64.powi(-e);
        let want = segment_area(4.0 * t.sqrt().asin()) / std::f64::consts::PI;
        rows.push(Row::f64(
            "falloff::disk_edge_falloff",
            "grazing",
            format!("t = 1e-{e} (relative error)"),
            1,
            ((f(t) - want) / want).abs(),
            "inside",
        ));
    }
    // The Bernstein smoothstep 3t² − 2t³ is exact in f64 at t = k/1024
    // (30 bits): any difference is the kernel's.
    let b = (0..=1024)
        .map(|k| {
            let t = f64::from(k) / 1024.0;
            (falloff::bernstein(t) - (3.0 * t * t - 2.0 * t * t * t)).abs()
        })
        .fold(0.0, f64::max);
    rows.push(Row::f64(
        "falloff::bernstein",
        "exact points",
        "t = k/1024 (3t² − 2t³ exact)",
        1025,
        b,
        "inside (absolute)",
    ));

    wedge_rows(rows);

    // Silhouettes of a sphere mesh moved far away, seen from near and far:
    // the kernel's edges against a facing test per face (the same exact
    // predicate, but no shared topology): mismatched edges counted.
    let sphere = crate::scene::primitive::sphere(DVec3::ZERO, 1.0, 24).ok();
    if let Some(mesh) = sphere {
        let tris = mesh.triangles();
        if let Ok(topo) = MeshTopology::new(tris, mesh.positions().len()) {
            for e in [0, 4, 8] {
                let shift = DVec3::splat(2f64.powi(e * 10 / 3));
                let positions: Vec<DVec3> = mesh.positions().iter().map(|&q| q + shift).collect();
                let mut mismatched = 0usize;
                let mut views = 0usize;
                for (k, d) in [1.5, 3.0, 1e3, 1e6].iter().enumerate() {
                    let x = shift
                        + DVec3::new(0.3, 0.8, -0.5).normalize() * *d
                        + DVec3::X * (k as f64 * 1e-3);
                    let Ok(edges) = topo.silhouettes_from_point(&positions, x) else {
                        continue;
                    };
                    views += 1;
                    mismatched += silhouette_mismatch(&positions, tris, x, &edges);
                }
                rows.push(Row::f64(
                    "silhouette::silhouettes_from_point (edges wrong)",
                    "far offset",
                    format!(
                        "sphere of 24 bands moved 2^{}, seen from 1.5 to 1e6 radii",
                        e * 10 / 3
                    ),
                    views,
                    mismatched as f64,
                    "inside",
                ));
            }
        }
    }
}

/// Penumbra wedges (`f64` and `f32`) must contain every receiver the edge
/// affects. An `f64` test written here (some edge point projects from `p`
/// into the facing disk and lies between them: the minimum of a quadratic
/// along the edge)
/// finds the receivers clearly affected — through the disk shrunk by 0.1 %
/// of its radius, so that rounding cannot make a case — among 4000 drawn around
/// the penumbra, and the row counts those the wedge leaves out (0 is
/// right), for an edge under a sphere light, moved far, with tiny and huge
/// lights.
fn wedge_rows(rows: &mut Vec<Row>) {
    use crate::kernel::wedge;
    let (e0, e1) = (DVec3::new(-1.0, -0.2, 2.0), DVec3::new(1.0, 0.3, 2.0));
    let center = DVec3::new(0.0, 0.0, 4.0);
    // G(λ) = H⁴|rel|² − (H² + k) s², k = (0.999 r)², is negative where
    // the edge point projects inside the shrunk disk; a quadratic in λ,
    // tried at the ends and its vertex.
    let affected = |p: DVec3, e0: DVec3, e1: DVec3, c: DVec3, r: f64| -> bool {
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
    };
    // A fixed xorshift, uniform in [lo, hi).
    let mut state = 0x5eed_u64;
    let mut rng = move |lo: f64, hi: f64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        lo + (hi - lo) * ((state >> 11) as f64 / (1u64 << 53) as f64)
    };
    for (family, case, shift, r) in [
        ("far offset", "moved 2^10, r = 0.5", 1024.0, 0.5),
        ("far offset", "moved 2^30, r = 0.5", 2f64.powi(30), 0.5),
        ("light size", "r = 1e-6", 0.0, 1e-6),
        ("light size", "r = 1.5", 0.0, 1.5),
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
            let q = a + (b - a) * rng(-0.2, 1.2);
            let t = rng(1.2, 2.5);
            let n = (b - a).cross(q - c).normalize();
            let p = c + (q - c) * t + n * (rng(-3.0, 3.0) * r * t);
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

/// How many silhouette edges differ from a per-face facing test: an edge
/// is a silhouette when its two faces face `x` differently (the exact
/// `orient3d`), each face visited once, no topology shared with the kernel.
fn silhouette_mismatch(
    positions: &[DVec3],
    tris: &[[u32; 3]],
    x: DVec3,
    edges: &[crate::kernel::silhouette::SilhouetteEdge],
) -> usize {
    use crate::kernel::predicate::{orient3d, Sign};
    use std::collections::BTreeMap;
    let mut sum: BTreeMap<(u32, u32), i64> = BTreeMap::new();
    for t in tris {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let w = if orient3d(a, b, c, x) == Sign::Negative {
            1
        } else {
            -1
        };
        for k in 0..3 {
            let (from, to) = (t[k], t[(k + 1) % 3]);
            let (key, sign) = if from < to {
                ((from, to), 1)
            } else {
                ((to, from), -1)
            };
            *sum.entry(key).or_insert(0) += w * sign;
        }
    }
    let brute: BTreeMap<(u32, u32), u32> = sum
        .into_iter()
        .filter(|&(_, v)| v != 0)
        .map(|((a, b), v)| (if v > 0 { (a, b) } else { (b, a) }, v.unsigned_abs() as u32))
        .collect();
    let kernel: BTreeMap<(u32, u32), u32> = edges
        .iter()
        .map(|e| ((e.from, e.to), e.multiplicity))
        .collect();
    brute
        .iter()
        .filter(|(k, v)| kernel.get(k) != Some(v))
        .count()
        + kernel
            .iter()
            .filter(|(k, v)| brute.get(k) != Some(v))
            .count()
}

/// The scene's camera frame at `side²` and the exact answer there.
fn frame_and_exact(scene: &Scene, side: u32) -> Option<(Frame, Vec<f64>)> {
    let stages = Stages::new(scene);
    let camera = scene.camera()?.with_resolution(side, side).ok()?;
    let frame = Frame::from_camera(&camera, stages.bvh());
    let exact = method::run(&Exact, &stages, &frame).ok()?.output.visibility;
    Some((frame, exact))
}

/// Runs the suite: the exact reference, the kernels, the methods at
/// `side²`.
#[must_use]
pub fn run(side: u32, progress: &dyn Fn(&str)) -> Vec<Row> {
    let mut rows = Vec::new();
    progress("the exact reference");
    exact_rows(&mut rows);
    progress("the kernels in f32");
    kernel_rows(&mut rows);
    progress("the kernels in f64");
    f64_kernel_rows(&mut rows);
    progress("the methods on stiff scenes");
    method_rows(&mut rows, side);
    rows
}

/// `docs/stability.md` from the rows.
#[must_use]
pub fn markdown(rows: &[Row], machine: &str, command: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Stability on stiff and extreme input\n");
    let _ = writeln!(
        s,
        "Written by `{command}` ({machine}). Three parts: the exact reference against closed \
         forms, the kernels (`f32` against `f64`, `f64` against closed forms), and every method of the default set on \
         stiff versions of the default scene. Rows outside a subject's documented domain say so \
         in the last column rather than being left out.\n"
    );
    type Keep<'a> = &'a dyn Fn(&Row) -> bool;
    let sections: [(&str, Keep<'_>, &str); 3] = [
        (
            "The exact reference against closed forms",
            &|r: &Row| r.subject == "exact reference",
            "A disk light over a plate parallel to it: the plate's straight edge hides a circle \
             segment of the light, whose area is a closed form (the error of the closed form \
             itself is a few `ε`). Every family twice: *dyadic* — axis-aligned, far offsets by a \
             power of two with dyadic coordinates, so the moved scene is exactly the same scene; \
             and *ordinary* — the same configuration turned by an ordinary rotation and moved by \
             an ordinary offset, every input coordinate rounded, the closed form evaluated for the \
             scene as rounded (the edge's trace on the light's plane in double-double). \"max\" \
             is the largest `|V − V_closed|`; \"bound\" the largest certified bound the exact \
             reference gave with its answers (`exact::visibility_bounded`), each of which must \
             contain its error (the note says if one did not).",
        ),
        (
            "The kernels",
            &|r: &Row| r.subject.contains("::"),
            "`f32` rows: each `f32` kernel against the `f64` kernel on the same `f32` input, so \
             that the error is the `f32` arithmetic's. `f64` rows: the `f64` kernels against \
             answers known independently — a circle segment's area from its half-angle (a series \
             for thin segments, so the closed form itself does not cancel), the falloff's exact \
             symmetry and its thin-sliver closed form, the Bernstein polynomial at points where \
             it is exact in `f64`, and silhouettes against a facing test per face. The `f64` \
             kernels against 256-bit evaluations on random stiff input: \
             `docs/accuracy/kernels.md` (the tests).",
        ),
        (
            "The methods on stiff scenes",
            &|r: &Row| r.subject != "exact reference" && !r.subject.contains("::"),
            "Each method of the sphere light's default set on the default scene moved far from \
             the origin (its coordinates round there, so the moved scene differs from the built-in \
             one by that rounding), with a tiny and a huge light, with the light near the horizon, \
             and on `contact`. \"max\" is the RMSE against the exact reference on the same \
             scene; the note gives the method's RMSE on the default scene as built in.",
        ),
    ];
    for (title, keep, text) in sections {
        let _ = writeln!(s, "## {title}\n\n{text}\n");
        let bounded = rows.iter().filter(|r| keep(r)).any(|r| r.bound.is_some());
        if bounded {
            let _ = writeln!(
                s,
                "| subject | family | case | precision | inputs | max | bound | domain / note |"
            );
            let _ = writeln!(s, "|---|---|---|---|---:|---:|---:|---|");
        } else {
            let _ = writeln!(
                s,
                "| subject | family | case | precision | inputs | max | domain / note |"
            );
            let _ = writeln!(s, "|---|---|---|---|---:|---:|---|");
        }
        for r in rows.iter().filter(|r| keep(r)) {
            let bound = match (bounded, r.bound) {
                (false, _) => String::new(),
                (true, Some(b)) => format!(" {b:.2e} |"),
                (true, None) => " — |".to_owned(),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {:.2e} |{bound} {} |",
                r.subject, r.family, r.case, r.precision, r.count, r.max, r.note
            );
        }
        let _ = writeln!(s);
    }
    s
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
