//! The exact reference's accuracy and its certified bound (issue 40), on
//! stiff few-triangle scenes with ordinary (non-round) coordinates, every
//! light kind, against the independent 256-bit evaluation of
//! `support::view`: far offsets (10⁶, 10⁹), tiny and huge lights, grazing
//! (the receiver near the light's plane, or far and at elevation 10⁻⁶),
//! contact (a triangle 10⁻⁹ … 10⁻¹² above the receiver), slivers close
//! above it, near-tangent chords, sliver images whose lines cross large
//! images' edges far from them. For each case: the error, and the bound
//! (`exact::visibility_bounded`), which must contain it.
#![cfg(all(feature = "reference", feature = "arbitrary"))]

mod support;

use softshadow::arbitrary::Rng;
use softshadow::glam::DVec3;
use softshadow::kernel::receiver_view::UnionSearch;
use softshadow::reference::exact;
use softshadow::scene::Light;
use softshadow::{Bvh, Occluders};
use support::view;

/// A few-triangle scene: a receiver, a light, occluders.
#[derive(Clone, Debug)]
pub struct Case {
    /// The receiver.
    pub p: DVec3,
    /// The light.
    pub light: Light,
    /// The occluders.
    pub tris: Vec<[DVec3; 3]>,
}

fn v3(rng: &mut Rng, s: f64) -> DVec3 {
    DVec3::new(rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-s, s))
}

/// A light of the given kind centred at `c`, of size `r`, facing `p`
/// roughly (ordinary parameters).
fn light_of(kind: usize, rng: &mut Rng, c: DVec3, r: f64, p: DVec3) -> Option<Light> {
    let toward = (p - c).normalize();
    let tilt = |rng: &mut Rng| (toward + v3(rng, 0.4)).normalize();
    let axis = |rng: &mut Rng| {
        let t = tilt(rng);
        let a = t.any_orthonormal_vector();
        (a + v3(rng, 0.3)).normalize() * r * rng.uniform(0.6, 1.2)
    };
    match kind {
        0 => Light::sphere(c, r).ok(),
        1 => Light::disk(c, tilt(rng), r).ok(),
        2 => {
            let u = axis(rng);
            let v = tilt(rng).cross(u).normalize() * r * rng.uniform(0.5, 1.1)
                + u * rng.uniform(-0.3, 0.3);
            Light::rect(c, u, v).ok()
        }
        3 => {
            let u = axis(rng);
            Light::segment(c - u, c + u * rng.uniform(0.5, 1.5)).ok()
        }
        _ => Light::point(c + v3(rng, r)).ok(),
    }
}

/// A triangle whose image crosses the light: one edge passes through a
/// point on the way from `p` to `aim` (a light point: near the centre of
/// an area light, on a segment light; at a random fraction of the way),
/// the triangle extending to one side.
fn crossing_triangle(rng: &mut Rng, p: DVec3, aim: DVec3) -> [DVec3; 3] {
    let t = rng.uniform(0.2, 0.8);
    let through = p + (aim - p) * t;
    let d = (aim - p).normalize();
    let along = (d.any_orthonormal_vector() + v3(rng, 0.2)).normalize();
    let side = d.cross(along).normalize();
    let size = (aim - p).length() * t * rng.uniform(0.5, 2.0);
    let a = through - along * size * rng.uniform(0.5, 1.5);
    let b = through + along * size * rng.uniform(0.5, 1.5);
    let e = through + side * size * rng.uniform(0.5, 1.5) + d * size * rng.uniform(-0.2, 0.2);
    [a, b, e]
}

/// `count` crossing triangles aimed at points of the light.
fn crossing_triangles(
    rng: &mut Rng,
    p: DVec3,
    light: &Light,
    r: f64,
    count: u64,
) -> Vec<[DVec3; 3]> {
    (0..count)
        .map(|_| {
            let at = aim(rng, light, r);
            crossing_triangle(rng, p, at)
        })
        .collect()
}

/// The triangles rotated by a random count, so that any of them may come
/// first in index order.
fn rotated(rng: &mut Rng, tris: &mut [[DVec3; 3]]) {
    let k = rng.below(tris.len() as u64) as usize;
    tris.rotate_left(k);
}

/// A light point to aim a crossing triangle at: within `0.6 r` of an area
/// light's centre, on a segment light, near a point light.
fn aim(rng: &mut Rng, light: &Light, r: f64) -> DVec3 {
    match *light {
        Light::Segment(s) => s.a() + (s.b() - s.a()) * rng.uniform(0.2, 0.8),
        Light::Point(x) => x.position() + v3(rng, 0.1 * r),
        _ => light.center() + v3(rng, 0.6 * r),
    }
}

/// A small triangle between `p` and the light point `at` whose image on
/// the light is a **sliver**, its three lines nearly coinciding: either a
/// face seen edge-on (its plane within `10⁻¹⁸ … 10⁻¹²` of `p` and holding
/// the direction to `at`), or a needle (a corner within `10⁻¹⁶ … 10⁻¹⁰`
/// of its size off the line through the other two). Its image is
/// `10⁻⁴ … 10⁻¹` of the light's angular size `rel` long, so that its
/// lines, run on across the light, cross other images' edges far from it.
fn sliver(rng: &mut Rng, p: DVec3, at: DVec3, rel: f64) -> [DVec3; 3] {
    let d = (at - p).normalize();
    let w = d.any_orthonormal_vector() + v3(rng, 0.5);
    let w = (w - d * w.dot(d)).normalize();
    let n = d.cross(w);
    let t = rng.uniform(0.2, 0.8) * (at - p).length();
    let s = t * rel * rng.log_uniform(-4.0, -1.0);
    if rng.chance(0.5) {
        let h = rng.log_uniform(-18.0, -12.0);
        let q = p + n * if rng.chance(0.5) { h } else { -h };
        let corner = |rng: &mut Rng| {
            q + d * (t + s * rng.uniform(-1.0, 1.0)) + w * s * rng.uniform(-1.0, 1.0)
        };
        [corner(rng), corner(rng), corner(rng)]
    } else {
        let a = p + d * t + (w * rng.uniform(-1.0, 1.0) + n * rng.uniform(-1.0, 1.0)) * s;
        let b = a + (w + v3(rng, 0.5)).normalize() * s * rng.uniform(0.5, 2.0);
        let off =
            (b - a).any_orthonormal_vector() * (b - a).length() * rng.log_uniform(-16.0, -10.0);
        // Along the side, or near a corner (a very sharp one).
        let f = if rng.chance(0.5) {
            rng.uniform(0.1, 0.9)
        } else {
            rng.log_uniform(-9.0, -3.0)
        };
        [a, b, a + (b - a) * f + off]
    }
}

/// The families of issue 40's table.
pub const FAMILIES: &[&str] = &[
    "ordinary",
    "huge light",
    "near-tangent chord",
    "offset 1e6",
    "offset 1e9",
    "contact 1e-9",
    "contact 1e-12",
    "sliver above the receiver",
    "light of radius 1e-6",
    "grazing near the light's plane",
    "grazing at elevation 1e-6",
    "long edge seen end-on",
    "tiny light at 1e9, rim",
    "just above a curved surface",
    "deep pile",
    "slivers over large images",
    "an edge's line through the receiver",
];

/// A case of `family` with light `kind`, or `None` where the generator
/// declines (a receiver the light refuses).
pub fn case(family: &str, kind: usize, rng: &mut Rng) -> Option<Case> {
    let p = v3(rng, 0.7);
    let dir = (DVec3::new(rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4), 1.0)).normalize();
    let dist = rng.uniform(3.0, 5.0);
    let c = p + dir * dist;
    let r = rng.uniform(0.3, 1.0);
    let ordinary = |rng: &mut Rng, r: f64| {
        let light = light_of(kind, rng, c, r, p)?;
        let at = aim(rng, &light, r);
        let tris = vec![crossing_triangle(rng, p, at)];
        Some(Case { p, light, tris })
    };
    let moved = |case: Case, o: DVec3| -> Option<Case> {
        Some(Case {
            p: case.p + o,
            light: match case.light {
                Light::Sphere(s) => Light::sphere(s.center() + o, s.radius()).ok()?,
                Light::Disk(d) => Light::disk(d.center() + o, d.normal(), d.radius()).ok()?,
                Light::Rect(q) => Light::rect(q.center() + o, q.u(), q.v()).ok()?,
                Light::Segment(s) => Light::segment(s.a() + o, s.b() + o).ok()?,
                Light::Point(x) => Light::point(x.position() + o).ok()?,
            },
            tris: case.tris.iter().map(|t| t.map(|v| v + o)).collect(),
        })
    };
    let case = match family {
        "ordinary" => ordinary(rng, r)?,
        "huge light" => {
            let big = dist * rng.uniform(20.0, 200.0);
            // A sphere that big is seen from outside it: farther away.
            let c = if kind == 0 {
                p + dir * big * rng.uniform(1.2, 3.0)
            } else {
                c
            };
            let light = light_of(kind, rng, c, big, p)?;
            let at = aim(rng, &light, big);
            let tris = vec![crossing_triangle(rng, p, at)];
            Case { p, light, tris }
        }
        "near-tangent chord" => {
            // An edge whose image passes within 1e-9 … 1e-3 of the light's
            // rim: through a point at the rim's distance from the centre.
            let light = light_of(kind, rng, c, r, p)?;
            let d = (c - p).normalize();
            let e1 = d.any_orthonormal_vector();
            let e2 = d.cross(e1);
            let gap = 10f64.powf(rng.uniform(-9.0, -3.0)) * r;
            let t = rng.uniform(0.3, 0.7);
            let rim = c + e1 * (r - gap);
            let through = p + (rim - p) * t;
            let size = dist * t;
            let a = through + e2 * size;
            let b = through - e2 * size;
            let out = through + e1 * size;
            Case {
                p,
                light,
                tris: vec![[a, b, out]],
            }
        }
        "offset 1e6" | "offset 1e9" => {
            let scale = if family == "offset 1e6" { 1e6 } else { 1e9 };
            let o = DVec3::new(
                rng.uniform(0.3, 1.0),
                rng.uniform(-1.0, -0.3),
                rng.uniform(0.3, 1.0),
            ) * scale;
            moved(ordinary(rng, r)?, o)?
        }
        "contact 1e-9" | "contact 1e-12" => {
            let h = if family == "contact 1e-9" {
                1e-9
            } else {
                1e-12
            } * rng.uniform(1.0, 9.0);
            let light = light_of(kind, rng, c, r, p)?;
            // A triangle whose plane passes h from p and holds nearly the
            // direction to the light, so that its trace (and, for a
            // receiver near an edge, the edge) crosses the light's view.
            let d = (aim(rng, &light, r) - p).normalize();
            let n = d.any_orthonormal_vector();
            let w = n.cross(d);
            let q = p + n * h;
            let tri = if rng.chance(0.5) {
                // Around p: the plane's trace bounds the image.
                [
                    q - d * rng.uniform(0.5, 2.0) - w * rng.uniform(0.5, 2.0),
                    q + d * rng.uniform(2.0, 6.0) + w * rng.uniform(-0.5, 0.5),
                    q - d * rng.uniform(0.5, 2.0) + w * rng.uniform(0.5, 2.0),
                ]
            } else {
                // An edge passing h from p along w's direction, the
                // triangle beyond it toward the light.
                let e = q + w * rng.uniform(-1e-3, 1e-3);
                [
                    e - w * rng.uniform(0.5, 2.0),
                    e + w * rng.uniform(0.5, 2.0),
                    e + d * rng.uniform(2.0, 6.0) + n * rng.uniform(-0.3, 0.3),
                ]
            };
            Case {
                p,
                light,
                tris: vec![tri],
            }
        }
        "sliver above the receiver" => {
            let h = rng.log_uniform(-8.0, -6.5);
            let light = light_of(kind, rng, c, r, p)?;
            // A sliver at distance h toward the light, long across the
            // line of sight and about as wide as h: its image is a band
            // across the light.
            let d = (aim(rng, &light, 0.5 * r) - p).normalize();
            let u = d.any_orthonormal_vector();
            let v = d.cross(u);
            let q = p + d * h;
            let width = h * rng.uniform(0.05, 0.5);
            let a = q - u * rng.uniform(0.5, 2.0);
            let b = q + u * rng.uniform(0.5, 2.0);
            let e = q + u * rng.uniform(-0.5, 0.5) + v * width + d * h * rng.uniform(-0.5, 0.5);
            Case {
                p,
                light,
                tris: vec![[a, b, e]],
            }
        }
        "light of radius 1e-6" => {
            let tiny = 1e-6 * rng.uniform(1.0, 3.0);
            let light = light_of(kind, rng, c, tiny, p)?;
            let at = aim(rng, &light, tiny);
            let tris = vec![crossing_triangle(rng, p, at)];
            Case { p, light, tris }
        }
        "grazing near the light's plane" | "grazing at elevation 1e-6" => {
            // The light's plane nearly holds p: a disk or rect facing
            // across, a sphere's facing disk can't be grazed (ordinary).
            let elevation = if family == "grazing at elevation 1e-6" {
                1e-6 * rng.uniform(1.0, 3.0)
            } else {
                rng.log_uniform(-6.0, -2.0)
            };
            let far = if family == "grazing at elevation 1e-6" {
                1.0
            } else {
                0.05
            };
            // The light's normal n; p at distance D from the centre in the
            // plane's direction u, lifted by D · elevation along n.
            let n = (DVec3::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), 1.0)).normalize();
            let u = n.any_orthonormal_vector();
            let big_d = (r * rng.uniform(1.5, 3.0) + far) * rng.uniform(1.0, 2.0);
            let c = p + u * big_d - n * (big_d * elevation);
            let light = match kind {
                1 => Light::disk(c, n, r).ok()?,
                2 => Light::rect(c, u * r, n.cross(u) * r * 0.7 + u * 0.1 * r).ok()?,
                _ => light_of(kind, rng, c, r, p)?,
            };
            let at = aim(rng, &light, r);
            let tris = vec![crossing_triangle(rng, p, at)];
            Case { p, light, tris }
        }
        "long edge seen end-on" => {
            // A plate-like triangle reaching 30–300 distances both ways
            // along its edge that crosses the light (a floor or a wall
            // seen from near it): the plane through p and that edge is a
            // cross product of two nearly parallel rows.
            let light = light_of(kind, rng, c, r, p)?;
            let at = aim(rng, &light, r);
            let d = (at - p).normalize();
            let along = (d.any_orthonormal_vector() + v3(rng, 0.2)).normalize();
            let side = d.cross(along).normalize();
            let through = p + (at - p) * rng.uniform(0.2, 0.8);
            let reach = dist * rng.uniform(30.0, 300.0);
            let a = through - along * reach * rng.uniform(0.5, 1.5);
            let b = through + along * reach * rng.uniform(0.5, 1.5);
            let e = through + side * reach + d * reach * rng.uniform(-0.01, 0.01);
            Case {
                p,
                light,
                tris: vec![[a, b, e]],
            }
        }
        "tiny light at 1e9, rim" => {
            // A light of radius 1e-6 about 1e9 from the origin, and an
            // edge whose image passes within 1e-9 … 1e-3 of its rim (a
            // rect's: of a corner), a small triangle beyond: only a sliver
            // at the rim is hidden, which culling must not lose to the
            // rounding of the pyramid's corners (ulp(1e9) ≈ 1e-7).
            let tiny = 1e-6 * rng.uniform(1.0, 3.0);
            let light = light_of(kind, rng, c, tiny, p)?;
            let (rim, outward) = match light {
                Light::Rect(q) => {
                    let (su, sv) = (
                        if rng.chance(0.5) { 1.0 } else { -1.0 },
                        if rng.chance(0.5) { 1.0 } else { -1.0 },
                    );
                    let corner = q.center() + q.u() * su + q.v() * sv;
                    (corner, (corner - q.center()).normalize())
                }
                _ => {
                    let normal = match light {
                        Light::Disk(k) => k.normal(),
                        _ => (p - c).normalize(),
                    };
                    let e1 = normal.any_orthonormal_vector();
                    (c + e1 * tiny, e1)
                }
            };
            let gap = 10f64.powf(rng.uniform(-9.0, -3.0)) * tiny;
            let mark = rim - outward * gap;
            let d = (mark - p).normalize();
            let across = d.cross(outward).normalize();
            let out =
                d.cross(across).normalize() * -outward.dot(d.cross(across).normalize()).signum();
            // Small (its image a few hundredths of the light wide), so
            // that its box is culled if the pyramid loses the rim.
            let t = rng.uniform(0.3, 0.7);
            let through = p + (mark - p) * t;
            let size = tiny * t * rng.uniform(0.01, 0.05) * (mark - p).length() / dist;
            let tri = [
                through + across * size,
                through - across * size,
                through + out * size,
            ];
            let o = DVec3::new(
                rng.uniform(0.3, 1.0),
                rng.uniform(-1.0, -0.3),
                rng.uniform(0.3, 1.0),
            ) * 1e9;
            moved(
                Case {
                    p,
                    light,
                    tris: vec![tri],
                },
                o,
            )?
        }
        "just above a curved surface" => {
            // A receiver a height 10⁻¹²…10⁻⁸ of the radius above a
            // triangle of a faceted ball (a fan of six around a vertex), as
            // a renderer's receivers lie on a tessellated surface: the
            // triangle under it and its neighbours, seen almost edge-on,
            // have images that are slivers along nearly the same line.
            let radius = rng.uniform(0.2, 0.5);
            let centre = p - dir * radius;
            let (t1, t2) = (
                dir.any_orthonormal_vector(),
                dir.cross(dir.any_orthonormal_vector()),
            );
            let alpha = rng.uniform(0.05, 0.2);
            let twist = rng.uniform(0.0, 1.0);
            let on_ball = |a: f64, t: f64| {
                let (s, c) = (t * std::f64::consts::TAU).sin_cos();
                centre + (dir * a.cos() + (t1 * c + t2 * s) * a.sin()) * radius
            };
            let ring: Vec<DVec3> = (0..6)
                .map(|k| on_ball(alpha, (k as f64 + twist) / 6.0))
                .collect();
            let apex = on_ball(0.0, 0.0);
            let tris: Vec<[DVec3; 3]> =
                (0..6).map(|k| [apex, ring[k], ring[(k + 1) % 6]]).collect();
            let under = tris[rng.below(6) as usize];
            let (b1, b2) = if rng.chance(0.5) {
                let (b1, b2) = (rng.uniform(0.05, 0.9), rng.uniform(0.05, 0.9));
                if b1 + b2 > 0.95 {
                    (1.0 - b1, 1.0 - b2)
                } else {
                    (b1, b2)
                }
            } else {
                // Beside the edge it shares with the next triangle of the
                // fan (apex to its second corner), where both planes pass
                // close to the receiver.
                (
                    10f64.powf(rng.uniform(-10.0, -5.0)),
                    rng.uniform(0.05, 0.95),
                )
            };
            let foot = under[0] + (under[1] - under[0]) * b1 + (under[2] - under[0]) * b2;
            let normal = (under[1] - under[0]).cross(under[2] - under[0]).normalize();
            let normal = if normal.dot(foot - centre) > 0.0 {
                normal
            } else {
                -normal
            };
            let h = radius * 10f64.powf(rng.uniform(-12.0, -8.0));
            let q = foot + normal * h;
            // The light across the tangent plane (its centre's elevation
            // within its angular radius), partly below the surface.
            let across = normal.cross(t1 + t2 * rng.uniform(-1.0, 1.0)).normalize();
            let elevation = rng.uniform(-0.5, 1.0) * r / dist;
            let up = normal * elevation.sin() + across * elevation.cos();
            let light = light_of(kind, rng, q + up * dist, r, q)?;
            Case { p: q, light, tris }
        }
        "deep pile" => {
            // Up to ten triangles across the light at different depths,
            // half of them copies of another moved by 10⁻¹⁵ … 10⁻⁹ of its
            // size: most edges are covered by other images, some with a
            // margin as small as the images' errors, which is where the
            // bound leaves out the bands that others hold deep inside.
            let light = light_of(kind, rng, c, r, p)?;
            let mut tris = Vec::new();
            for _ in 0..rng.below(3) + 3 {
                let at = aim(rng, &light, r);
                let tri = crossing_triangle(rng, p, at);
                let size = (tri[1] - tri[0]).length();
                let scale = size * 10f64.powf(rng.uniform(-15.0, -9.0));
                let nudge = v3(rng, scale);
                let copy = if rng.chance(0.5) {
                    tri.map(|v| v + nudge)
                } else {
                    // One corner moved: edges that cross at a tiny angle.
                    [tri[0], tri[1] + nudge, tri[2]]
                };
                tris.push(tri);
                tris.push(copy);
            }
            Case { p, light, tris }
        }
        "slivers over large images" => {
            let light = light_of(kind, rng, c, r, p)?;
            let count = rng.below(3) + 2;
            let mut tris = crossing_triangles(rng, p, &light, r, count);
            for _ in 0..rng.below(3) + 2 {
                let at = aim(rng, &light, r);
                tris.push(sliver(rng, p, at, r / dist));
            }
            // The slivers anywhere in index order (the order decides
            // which of two coinciding edges covers the other).
            rotated(rng, &mut tris);
            Case { p, light, tris }
        }
        "an edge's line through the receiver" => {
            // A face seen exactly edge-on but for rounding: one edge on a
            // line through p (its ends at p plus rounded multiples of one
            // direction, so p, the ends and the face's plane meet to an
            // ulp), its corners before p, between p and the light or
            // beyond the light's plane; over ordinary occluders. Where
            // two of its cone lines coincide to the last bit, a cut leaves
            // vertices exactly on a line.
            let light = light_of(kind, rng, c, r, p)?;
            let count = rng.below(3) + 1;
            let mut tris = crossing_triangles(rng, p, &light, r, count);
            for _ in 0..rng.below(2) + 1 {
                let d = aim(rng, &light, r) - p;
                let a = p + d * rng.uniform(0.2, 1.3);
                let f = [2.0, 0.5, 3.0, rng.uniform(-1.0, 3.0)][rng.below(4) as usize];
                let b = p + (a - p) * f;
                let e = p + (aim(rng, &light, 2.0 * r) - p) * rng.uniform(0.2, 1.3);
                let mut tri = [a, b, e];
                tri.rotate_left(rng.below(3) as usize);
                if rng.chance(0.5) {
                    tri.reverse();
                }
                tris.push(tri);
            }
            rotated(rng, &mut tris);
            Case { p, light, tris }
        }
        _ => panic!("unknown family {family}"),
    };
    case.light.emitter(case.p).ok()?;
    Some(case)
}

/// The case moved by `−o` (for `o = p`, the receiver at the origin: the
/// same scene exactly, every coordinate's difference from `p` unchanged,
/// where the scene lies within a factor 2 of `p`'s coordinates).
pub fn moved_back(case: &Case, o: DVec3) -> Case {
    let light = match case.light {
        Light::Sphere(s) => Light::sphere(s.center() - o, s.radius()),
        Light::Disk(d) => Light::disk(d.center() - o, d.normal(), d.radius()),
        Light::Rect(q) => Light::rect(q.center() - o, q.u(), q.v()),
        Light::Segment(s) => Light::segment(s.a() - o, s.b() - o),
        Light::Point(x) => Light::point(x.position() - o),
    }
    .expect("the same light");
    Case {
        p: case.p - o,
        light,
        tris: case.tris.iter().map(|t| t.map(|v| v - o)).collect(),
    }
}

/// The exact answer, its bound and the 256-bit answer.
pub fn measure(case: &Case) -> (f64, f64, f64) {
    let bvh = Bvh::new(Occluders::from_triangles(case.tris.clone()));
    let b = exact::visibility_bounded(&bvh, &case.light, case.p).expect("receiver accepted");
    let truth = view::visibility(&case.light, case.p, &case.tris);
    (b.visibility, b.bound, truth)
}

const KINDS: [&str; 5] = ["sphere", "disk", "rect", "segment", "point"];

/// The accuracy every family is held to: a few units in the last place of
/// `V` (`ε = 2.2·10⁻¹⁶`), the "about 10⁻¹⁵".
const ACCURATE: f64 = 4e-15;

/// Families whose answers are well conditioned: there the bound must stay
/// within 10³ of the error it certifies.
const ORDINARY: &[&str] = &[
    "ordinary",
    "huge light",
    "offset 1e6",
    "offset 1e9",
    "light of radius 1e-6",
    "sliver above the receiver",
];

/// For every family and light kind: every bound contains its error; every
/// error is within [`ACCURATE`] (`V` is a fraction: a few ulps of 1), and
/// far from the origin within that of the same scene moved to the origin;
/// on the ordinary families the largest bound is within 10³ of the
/// largest error (or of `ε` where every answer came out exact), and every
/// bound is below `10⁻¹²`. `SOFTSHADOW_PRINT_ACCURACY=1` prints the
/// table of `docs/accuracy/references.md` (cases, of which partly lit;
/// worst error; worst bound; median bound ÷ error).
#[test]
fn every_family_every_light_kind() {
    let per = support::samples(24);
    let mut failures = Vec::new();
    for family in FAMILIES {
        for (kind, name) in KINDS.iter().enumerate() {
            let mut rng = Rng::new(0x40 + kind as u64 * 1000 + family.len() as u64);
            let (mut worst, mut worst_bound, mut n, mut partial) = (0.0_f64, 0.0_f64, 0, 0);
            let mut ratios = Vec::new();
            for _ in 0..per {
                let Some(case) = case(family, kind, &mut rng) else {
                    continue;
                };
                let (v, bound, truth) = measure(&case);
                let err = (v - truth).abs();
                if truth > 1e-12 && truth < 1.0 - 1e-12 {
                    partial += 1;
                }
                // A few units in the last place of V (measured over 1,200
                // cases a family and kind: 1.2e-15 on the ordinary
                // family, 3.7e-15 for rect lights at contact); far from
                // the origin, also no worse than the same scene at the
                // origin.
                let goal = if family.starts_with("offset") {
                    let (v0, _, truth0) = measure(&moved_back(&case, case.p));
                    ACCURATE.max((v0 - truth0).abs())
                } else {
                    ACCURATE
                };
                if err > goal {
                    failures.push(format!(
                        "{family}, {name}: error {err:e} above {goal:e}\n{case:?}"
                    ));
                }
                worst = worst.max(err);
                worst_bound = worst_bound.max(bound);
                n += 1;
                if err > bound {
                    failures.push(format!(
                        "{family}, {name}: error {err:e} > bound {bound:e}\n{case:?}"
                    ));
                }
                if bound > 1e-12 {
                    failures.push(format!(
                        "{family}, {name}: bound {bound:e} > 1e-12\n{case:?}"
                    ));
                }
                if err > 0.0 {
                    ratios.push(bound / err);
                }
            }
            if ORDINARY.contains(family) && worst_bound > 1e3 * worst.max(f64::EPSILON) {
                failures.push(format!(
                    "{family}, {name}: worst bound {worst_bound:e} against worst error {worst:e}"
                ));
            }
            ratios.sort_by(f64::total_cmp);
            let median = ratios.get(ratios.len() / 2).copied().unwrap_or(f64::NAN);
            if support::printing() {
                println!(
                    "| {family} | {name} | {n} ({partial}) | {worst:.1e} | {worst_bound:.1e} | {median:.0} |"
                );
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(support::samples(256) as u32))]

    /// Any family, any light kind, any seed: the bound contains the error
    /// (a violation shrinks to its family, kind and seed).
    #[test]
    fn the_bound_contains_the_error(
        family in 0..FAMILIES.len(),
        kind in 0usize..5,
        seed in proptest::prelude::any::<u64>(),
    ) {
        let mut rng = Rng::new(seed);
        if let Some(case) = case(FAMILIES[family], kind, &mut rng) {
            let (v, bound, truth) = measure(&case);
            proptest::prop_assert!(
                (v - truth).abs() <= bound,
                "{}: |{v} − {truth}| > {bound}\n{case:?}", FAMILIES[family]
            );
        }
    }
}

/// The fuzz targets' scene `arbitrary::scene::visibility_case(seed, 8)`
/// (every light kind; quad strips, fans, reversed copies, triangles
/// reaching behind the receiver and past the light's plane, corners at the
/// receiver, faces seen edge-on) as a [`Case`], or `None` where the light
/// refuses the receiver.
fn fuzzers_case(seed: u64) -> Option<Case> {
    let c = softshadow::arbitrary::scene::visibility_case(&mut Rng::new(seed), 8);
    c.light.emitter(c.receiver).ok()?;
    Some(Case {
        p: c.receiver,
        light: c.light,
        tris: c.triangles,
    })
}

/// On a fuzz targets' scene: the bound contains the error against the
/// 256-bit answer, and every way of asking for `V` ([`every_way`]: with
/// and without the bound, under every search) gives the same bits.
fn check_fuzzers_case(seed: u64) -> Result<(), String> {
    let Some(case) = fuzzers_case(seed) else {
        return Ok(());
    };
    let (v, bound, truth) = measure(&case);
    let ways = every_way(&case);
    if (v - truth).abs() > bound || ways.iter().any(|w| w.0.to_bits() != v.to_bits()) {
        return Err(format!(
            "seed {seed}: bounded {v} ± {bound:e}, truth {truth}, every way {ways:?}\n{case:?}"
        ));
    }
    Ok(())
}

/// Seeds of [`fuzzers_case`] where [`check_fuzzers_case`] catches a
/// defect: 746 and 1988 a segment light's interval shorter than its ends'
/// rounding, left out of the bound (a bound of 0); 3300 and 25760 choices
/// (a vertex from its two lines or the crossing on the edge, the fast
/// path) taken on the closer error bounds when the bound is asked for,
/// which move the value with the bound by `2.2·10⁻¹³` and `1.2·10⁻¹³`
/// from the one without.
const FUZZERS_SEEDS: &[u64] = &[746, 1988, 3300, 25760];

#[test]
fn the_fuzzers_scenes_pinned() {
    let failures: Vec<String> = FUZZERS_SEEDS
        .iter()
        .filter_map(|&seed| check_fuzzers_case(seed).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(support::samples(64) as u32))]

    /// Any fuzz targets' scene: within the bound of the 256-bit answer,
    /// the same bits with and without the bound.
    #[test]
    fn the_fuzzers_scenes_are_within_their_bounds(seed in proptest::prelude::any::<u64>()) {
        if let Err(e) = check_fuzzers_case(seed) {
            proptest::prop_assert!(false, "{}", e);
        }
    }
}

/// A receiver of the built-in `contact` scene's camera (40 × 40), 2·10⁻¹⁰
/// off the ball it lies on, with the light straddling its tangent plane:
/// a neighbouring face, seen almost edge-on, has an image whose lines
/// nearly coincide, and whose corners (where those lines meet) are known
/// only to 10⁻⁶. The bound, taken from those corners, was 4.1·10⁻⁶ for
/// an answer exact to the last place; from the lines alone it is within
/// the goal. Moved along its normal and by ulps, every answer is within
/// its bound of the 256-bit one.
#[test]
fn a_receiver_beside_a_ball_s_face_has_a_tight_bound() {
    let p = DVec3::new(0.7599248919945946, 0.4964504121327844, 0.47110638069313315);
    let normal = DVec3::new(0.2889002104397811, -0.09754966309535132, 0.9523763602892681);
    let face = [
        DVec3::new(0.7913417161825449, 0.5, 0.46193976625564337),
        DVec3::new(0.6956708580912725, 0.4024548389919359, 0.4809698831278217),
        DVec3::new(0.7876651387589326, 0.4024548389919359, 0.4530637231764439),
    ];
    let light = Light::sphere(DVec3::new(0.5, 3.0, 1.0), 0.4).expect("the scene's light");
    let mut failures = Vec::new();
    for step in [0.0, 1e-10, -1e-10, 1e-12, 1e-15] {
        for ulps in [-2_i64, 0, 3] {
            let q = p + normal * step;
            let q = DVec3::new(
                f64::from_bits((q.x.to_bits() as i64 + ulps) as u64),
                q.y,
                q.z,
            );
            let case = Case {
                p: q,
                light,
                tris: vec![face],
            };
            let (v, bound, truth) = measure(&case);
            if (v - truth).abs() > bound || bound > 1e-12 {
                failures.push(format!(
                    "{step:e}, {ulps} ulps: V {v} truth {truth} bound {bound:e}"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The face in every corner order, alone and put at index `at` among
/// `others` (if any): the answers not within their bounds of the 256-bit
/// one, or not within [`ACCURATE`].
fn every_corner_order(
    p: DVec3,
    light: Light,
    face: [DVec3; 3],
    others: &[[DVec3; 3]],
    at: usize,
) -> Vec<String> {
    let orders = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
        [1, 0, 2],
        [0, 2, 1],
    ];
    let mut failures = Vec::new();
    for order in orders {
        let tri = order.map(|k| face[k]);
        let mut sets = vec![vec![tri]];
        if !others.is_empty() {
            let mut all = others.to_vec();
            all.insert(at, tri);
            sets.push(all);
        }
        for tris in sets {
            let case = Case { p, light, tris };
            let (v, bound, truth) = measure(&case);
            if (v - truth).abs() > bound.min(ACCURATE) {
                failures.push(format!("{order:?}: V {v} truth {truth} bound {bound:e}"));
            }
        }
    }
    failures
}

/// Found by the `exact` fuzz target: a face whose edge lies on a line
/// through the receiver to an ulp (its far corner at `p + 2 (a − p)`),
/// straddling the light's plane, over four ordinary occluders. Its cone
/// planes over the other two edges meet the light's plane in one line, so
/// the first cut leaves a corner of the square exactly on the second's,
/// and the edge leaving that corner runs along the new line (taken up the
/// square's side instead, the image is a strip across the light: `V`
/// 0.4407 for 0.4423, with a bound of `3·10⁻¹³`). Every corner order,
/// alone and among the others, within the bound of the 256-bit answer.
#[test]
fn a_face_on_a_line_through_the_receiver_hides_nothing() {
    let d = DVec3::new;
    let light = Light::disk(
        d(0.12715341871740782, 0.3304246549937394, 2.514845990609777),
        d(-0.550590722312633, 0.3038233305410433, -0.7775225014893146),
        0.7275763966373854,
    )
    .expect("a disk");
    let p = d(0.473069902343512, -0.1113461885075614, -0.12945373866195825);
    let face = [
        d(0.1888824522504039, -0.14099094392910785, 1.234191164209791),
        d(
            -0.09530499784270424,
            -0.1706356993506543,
            2.5978360670815404,
        ),
        d(0.04225121511494234, 0.38583149485045415, 3.0268244383637035),
    ];
    let others = [
        [
            d(0.7337155556854111, -0.6234514501485804, -2.0676428020018225),
            d(0.08082181943839219, 0.5679373147952476, 3.3394871299898083),
            d(0.2876519200628429, 0.2778412228659102, 0.7120768099171533),
        ],
        [
            d(
                -0.04228115878971417,
                0.015383154947321565,
                0.8926219381196654,
            ),
            d(-0.5576322199229403, 0.14211249840220455, 1.914697614901289),
            d(-0.5952249722464329, 0.3073275806295715, 2.5148481805437206),
        ],
        [
            d(0.5783701337774204, -0.06522276310381406, -1.105106039076159),
            d(
                -0.17204354704011787,
                0.21536775340665493,
                4.4728324425046155,
            ),
            d(0.09246686330312859, 0.428560402169337, 1.4175593845648018),
        ],
        [
            d(-0.4738356665497512, -0.7829482602297124, 3.7970710671399286),
            d(0.23750239571426657, 1.029018138373279, 2.7005211890193013),
            d(0.736241836887888, 0.6411731710069872, 3.7482261642047625),
        ],
    ];
    let failures = every_corner_order(p, light, face, &others, 3);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A face whose edge lies on a line through the receiver to an ulp (its
/// far corner at `p + 2 (a − p)`), its third corner on the ray from `p`
/// through a corner of the square around a sphere light's facing disk:
/// its plane holds `p` to `4·10⁻¹⁷` and its cone lines meet at that
/// corner of the square, so the clipping leaves an image whose vertices
/// all coincide there. Such an image has no edge of positive length and
/// covers nothing (every edge's covering test holds for an edge of length
/// 0: taken as covering, `V = 0` with a bound of `8·10⁻¹⁴` for a face
/// that hides nothing). Found by a campaign of faces aimed at the square's
/// corners. Every corner order, alone and among three ordinary
/// occluders, within the bound of the 256-bit answer and within
/// [`ACCURATE`].
#[test]
fn an_image_collapsed_to_a_corner_of_the_square_covers_nothing() {
    let d = DVec3::new;
    let light = Light::sphere(
        d(-0.11010637251695593, 0.7243761743123254, 2.7458141081899825),
        0.5952661694379173,
    )
    .expect("a sphere");
    let p = d(
        -0.3356614384785803,
        -0.3426237614822594,
        -0.06897200919580837,
    );
    let face = [
        d(-0.13925904218685645, 0.5872576273313435, 2.393781291773079),
        d(-0.2374602403327184, 0.12231693292454199, 1.1624046412886353),
        d(-1.9196592021277286, 4.245046929122981, 6.031829402195066),
    ];
    let others = [
        [
            d(-0.9330184958784239, 1.3874780902691322, 2.2317615287692627),
            d(
                -0.14530174667457713,
                -0.6548988253428611,
                -0.8927654182422758,
            ),
            d(
                -0.5260211302825835,
                -0.030348697621657705,
                0.7548213998506591,
            ),
        ],
        [
            d(-0.3326059402597054, -2.1724850449354136, 1.3361730461388848),
            d(-0.38083236808902365, 2.732036172333483, 0.4223840546719342),
            d(
                -1.8638762541475262,
                -0.02249074548472009,
                0.8754640852650744,
            ),
        ],
        [
            d(-0.9842727526778591, 0.7213889906019983, 2.737933804774924),
            d(0.31294987572069843, -1.406636513566517, -2.8758778231665403),
            d(
                -0.30422975340441855,
                -0.2715005459238837,
                0.35267867231475203,
            ),
        ],
    ];
    let failures = every_corner_order(p, light, face, &others, others.len());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Two images meeting where three lines cross: a face with a corner at a
/// sphere light's centre (so on its facing disk's plane, where its image
/// is the disk's centre, its plane's line and two cone lines meeting
/// there) under a large face, `10⁴` from the origin. The 256-bit answer
/// computed that corner twice, from two pairs of its lines, `10⁻⁷⁷` apart,
/// and the edge between the copies — its direction of rounding alone —
/// cut the two images' intersection along an arbitrary line through the
/// centre: `V` 0.4537 for the 0.47397 of the exact reference (and of
/// `2²²` Monte Carlo samples, `0.473978 ± 9·10⁻⁶`). Found by a campaign of
/// faces aimed at the square's corners and the light's centre.
#[test]
fn images_meeting_where_three_lines_cross_are_intersected_whole() {
    let d = DVec3::new;
    let light = Light::sphere(
        d(-5909.481230043663, -1195.6297042473939, -49441.97975697864),
        0.5509940963709583,
    )
    .expect("a sphere");
    let p = d(-5910.311654548627, -1196.8839528014478, -49445.19361044486);
    let large = [
        d(-5909.955168856098, -1197.416483310664, -49443.2175516488),
        d(-5909.771800728946, -1194.2747481042088, -49444.233890247495),
        d(-5911.382468326656, -1196.115779121045, -49443.38186427811),
    ];
    let at_centre = [
        d(-5909.172270602635, -1195.5712843038825, -49441.540849824145),
        d(-5909.481230043663, -1195.6297042473939, -49441.97975697864),
        d(-5910.1881157719545, -1196.3385750633445, -49443.79614889042),
    ];
    let case = Case {
        p,
        light,
        tris: vec![large, at_centre],
    };
    let (v, bound, truth) = measure(&case);
    assert!(
        (v - truth).abs() <= bound.min(ACCURATE),
        "V {v} truth {truth} bound {bound:e}"
    );
}

/// A face through the receiver to an ulp (two corners at `p ± (a − p)`:
/// the receiver on its edge but for rounding), before a rect light, from
/// a campaign of faces with an edge on a line through the receiver: two
/// of its lines meet `9·10⁻¹¹` outside the square's left side, within
/// the slack a vertex from its lines is taken at. The union takes every
/// image to lie in the square (it sweeps the edges on its sides as the
/// images'), so the vertex is the crossing on the edge being cut (kept
/// outside the square, the sliver between it and the side, `6·10⁻¹¹` of
/// area, counts: `V` off by `1.6·10⁻¹¹` with a bound of `1.4·10⁻¹⁴`). Every
/// corner order, alone, within the bound of the 256-bit answer and
/// within [`ACCURATE`].
#[test]
fn a_meeting_point_past_a_side_of_the_square_is_taken_on_the_edge() {
    let d = DVec3::new;
    let light = Light::rect(
        d(0.4924273536307737, 0.4347042618319392, 3.7215703408583067),
        d(
            0.043252148767866226,
            -0.4573807285026901,
            -0.041374416641909,
        ),
        d(
            -0.4634044886318086,
            -0.08399431851971281,
            0.09656680946840912,
        ),
    )
    .expect("a rect");
    let face = [
        d(-0.4373727837810293, -0.6858754656277597, -5.801950824010419),
        d(0.9125796934822574, 0.9760793088935316, 3.666377948029549),
        d(0.4373727837810293, 0.6858754658605903, 5.801950824010419),
    ];
    let failures = every_corner_order(DVec3::ZERO, light, face, &[], 0);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Found by comparing `arbitrary::scene::visibility_case` (seed 746) with
/// the 256-bit answer: a face seen edge-on from the receiver (its plane
/// `10⁻¹⁸` from it) hides `9.9·10⁻¹⁷` of a segment light, an interval
/// whose rounded ends cross. The crossed interval's ends count for the
/// bound (dropped with nothing added, `V = 1` comes with a bound of 0,
/// the truth a unit in the last place below).
#[test]
fn a_segment_s_interval_lost_to_rounding_counts_for_the_bound() {
    let d = DVec3::new;
    let light = Light::segment(
        d(
            -0.023960415809670732,
            0.23077192327554494,
            4.226318928755276,
        ),
        d(0.41166900153215585, 0.47189829923601856, 4.120008129849893),
    )
    .expect("a segment");
    let p = d(
        -0.27215046544600663,
        -0.3724811788852893,
        -0.026759721229377836,
    );
    let face = [
        d(
            -0.30733975687753556,
            -0.3484687903136826,
            0.15431751550725972,
        ),
        d(
            -0.3425290483090645,
            -0.32445640174207585,
            0.33539475224389725,
        ),
        d(
            -0.20762298780124472,
            -0.2742285696110518,
            0.5592632370702157,
        ),
    ];
    for order in [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
        [1, 0, 2],
        [0, 2, 1],
    ] {
        let case = Case {
            p,
            light,
            tris: vec![order.map(|k| face[k])],
        };
        let (v, bound, truth) = measure(&case);
        assert!(truth < 1.0, "the face hides some of the light: {truth}");
        assert!(
            (v - truth).abs() <= bound,
            "{order:?}: V {v} truth {truth} bound {bound:e}"
        );
    }
}

/// A triangle crossing a sphere light's facing disk's plane at a small
/// angle (its corners `h` off the plane, across the light): the facing
/// disk's normal is the rounded unit of `c − p`, whose plane is turned by
/// a few `ε` from the exact one, and the triangle's trace on it moves by
/// about that over the angle. The answer is the exact one for the rounded
/// disk (the same triangle before a disk light of that normal is exact to
/// `2·10⁻¹⁶`); the bound does not count the turn. Measured: `h = 10⁻⁶`
/// error `4.5·10⁻¹³` with a bound of `3.9·10⁻¹⁴`, growing as `1 / h`
/// (`4.5·10⁻⁷` at `h = 10⁻¹²`). The receiver view's domain leaves such
/// occluders out until the bound counts the turn.
#[test]
#[ignore = "fails: a sphere light's facing plane crossed at a small angle; the bound does not count the rounded normal's turn"]
fn a_triangle_crossing_a_sphere_light_s_facing_plane_at_a_small_angle() {
    let p = DVec3::ZERO;
    let c = DVec3::new(-0.5109877809882164, -1.07033172249794, 4.416556052863598);
    let light = Light::sphere(c, 0.4754440439459453).expect("a sphere");
    let n = (c - p).normalize();
    let e0 = n.any_orthonormal_vector() * 0.47;
    let e1 = n.cross(e0);
    let mut failures = Vec::new();
    for h in [1e-6, 1e-9, 1e-12] {
        let tri = [
            c + e0 * 1.3 + e1 * 0.2 + n * h,
            c - e0 * 1.1 + e1 * 0.4 - n * h,
            c + e0 * 0.1 - e1 * 1.4 + n * (0.5 * h),
        ];
        let (v, bound, truth) = measure(&Case {
            p,
            light,
            tris: vec![tri],
        });
        if (v - truth).abs() > bound {
            failures.push(format!("h {h:e}: V {v} truth {truth} bound {bound:e}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Seeds of [`case`]`("slivers over large images", kind, Rng::new(seed))`
/// (`kind` first) at which a span test keeping the spans far from their
/// triangle gives the grid's and the tree's searches different bits, or
/// an error above [`ACCURATE`].
const SLIVER_SEEDS: &[(usize, u64)] = &[
    (0, 124_349_059),
    (0, 114_933_368),
    (1, 89_624_245),
    (1, 121_300_245),
    (2, 103_522_091),
    (2, 55_382_490),
];

/// Every way of asking for `V` on the case: `visibility` and
/// `visibility_bounded` under the grid, the tree and the automatic
/// search, each its `V` and bound (none for `visibility`).
fn every_way(case: &Case) -> Vec<(f64, Option<f64>)> {
    let bvh = Bvh::new(Occluders::from_triangles(case.tris.clone()));
    let mut out = Vec::new();
    for search in [UnionSearch::Grid, UnionSearch::Tree, UnionSearch::Auto] {
        let mut scratch = exact::Scratch::default();
        scratch.set_union_search(search);
        let v = exact::visibility_with(&bvh, &case.light, case.p, &mut scratch)
            .expect("receiver accepted");
        let b = exact::visibility_bounded_with(&bvh, &case.light, case.p, &mut scratch)
            .expect("receiver accepted");
        out.push((v, None));
        out.push((b.visibility, Some(b.bound)));
    }
    out
}

/// Sliver images crossed by large ones' edges far from them (the family
/// "slivers over large images", every area light kind, and the seeds of
/// [`SLIVER_SEEDS`]): `visibility` and `visibility_bounded` under the grid,
/// the tree and the automatic search give the same bits; every bound
/// contains the error against the 256-bit evaluation, and the error is
/// within [`ACCURATE`]. 16 cases a kind, or 800 in exhaustive runs.
#[test]
fn sliver_images_give_the_same_bits_every_way_within_the_bound() {
    let per = support::samples(16) as u64;
    let family = "slivers over large images";
    let seeds =
        (0..3).flat_map(|kind| (0..per).map(move |i| (kind, 0x5117 + 7919 * i + kind as u64)));
    let mut failures = Vec::new();
    for (kind, seed) in seeds.chain(SLIVER_SEEDS.iter().copied()) {
        let Some(case) = case(family, kind, &mut Rng::new(seed)) else {
            continue;
        };
        let answers = every_way(&case);
        let truth = view::visibility(&case.light, case.p, &case.tris);
        let v = answers[0].0;
        let err = (v - truth).abs();
        for &(w, bound) in &answers {
            if w.to_bits() != v.to_bits() {
                failures.push(format!("{} {seed}: {answers:?}", KINDS[kind]));
                break;
            }
            let Some(bound) = bound else { continue };
            if err.is_nan() || err > bound {
                failures.push(format!(
                    "{} {seed}: error {err:e} > bound {bound:e}",
                    KINDS[kind]
                ));
            }
        }
        if err > ACCURATE {
            failures.push(format!(
                "{} {seed}: error {err:e} above {ACCURATE:e}",
                KINDS[kind]
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// One needle (sides `6.5·10⁻³`, `6.5·10⁻³` and `1.1·10⁻⁸`: a corner of
/// about `1.7·10⁻⁶` radians, the receiver `1.2·10⁻³` off its plane) before
/// a rect light, from the family "slivers over large images" (rect, the
/// 897th case of [`every_family_every_light_kind`]'s exhaustive run): the
/// answer is within `1.1·10⁻¹⁶` of the 256-bit value and its bound
/// `6.2·10⁻¹⁴`. Clipped by a side of the square, the image has a vertex
/// exactly on its next line, and the edge leaving it runs along that line
/// (taken on the square's side instead, the bound from that edge's run
/// past its end is `4.7·10⁻¹²`).
#[test]
fn a_needle_with_a_sharp_corner_has_a_tight_bound() {
    let light = Light::rect(
        DVec3::new(0.7901238294905627, 1.1692513310525783, 2.634207329174778),
        DVec3::new(
            -0.02647442289233379,
            -0.3639909866085162,
            0.07670008500339835,
        ),
        DVec3::new(
            -0.26514937719970033,
            -0.050388952112145606,
            0.1593837202906631,
        ),
    )
    .expect("a rect");
    let case = Case {
        p: DVec3::new(0.5054298927970633, 0.09324257801914226, -0.3946406617210759),
        light,
        tris: vec![[
            DVec3::new(0.6450008495458672, 0.34755131419519497, 0.5089775481677694),
            DVec3::new(0.6445154835185046, 0.35399702992457666, 0.5084852325300062),
            DVec3::new(0.6450008487375024, 0.34755132493037116, 0.5089775473478302),
        ]],
    };
    let (v, bound, truth) = measure(&case);
    assert!((v - truth).abs() <= bound, "{v} {truth} {bound:e}");
    assert!(bound <= 1e-12, "bound {bound:e}");
}
