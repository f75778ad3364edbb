//! An independent 256-bit evaluation of `V(p)` for a few triangles and
//! any light, straight from the definition (docs/definitions.md): a light
//! point `x` is hidden by a triangle `q₀q₁q₂` when the open segment `(p, x)`
//! meets it, i.e. (for `p` off the triangle's plane) when `x − p` lies in
//! the closed cone the triangle spans from `p` and `x` lies strictly beyond
//! its plane. Every sign of a determinant of the inputs is taken from the
//! `robust` crate (Shewchuk's predicates, not ours); the values at 256
//! bits (`support::Big`).
//!
//! - Area lights: on the light's plane, in an orthonormal frame built at
//!   256 bits (a rect in its affine coordinates), each condition is a
//!   half-plane; a triangle's image is a large square cut by its four
//!   half-planes (Sutherland–Hodgman), the union's area inside the light is
//!   summed by inclusion–exclusion over the images' intersections (convex),
//!   each intersection's area inside the unit disk by Green's theorem with
//!   exact circle crossings and `atan2` arcs, inside the square by one more
//!   clip and the shoelace formula.
//! - Segment lights: each condition is affine in the light's parameter; the
//!   blocked intervals' union length.
//! - Point lights: the open-segment test with `robust`'s signs.
//!
//! Nothing here calls the library's constructions.
#![allow(dead_code)]

use super::{Big, Ctx};
use softshadow::glam::DVec3;
use softshadow::scene::Light;

/// A 3-vector of [`Big`].
#[derive(Clone, Debug)]
pub struct B3(pub Big, pub Big, pub Big);

impl B3 {
    pub fn new(v: DVec3) -> B3 {
        B3(Big::new(v.x), Big::new(v.y), Big::new(v.z))
    }
    pub fn sub(&self, o: &B3) -> B3 {
        B3(self.0.sub(&o.0), self.1.sub(&o.1), self.2.sub(&o.2))
    }
    pub fn add(&self, o: &B3) -> B3 {
        B3(self.0.add(&o.0), self.1.add(&o.1), self.2.add(&o.2))
    }
    pub fn scale(&self, s: &Big) -> B3 {
        B3(self.0.mul(s), self.1.mul(s), self.2.mul(s))
    }
    pub fn dot(&self, o: &B3) -> Big {
        self.0
            .mul(&o.0)
            .add(&self.1.mul(&o.1))
            .add(&self.2.mul(&o.2))
    }
    pub fn cross(&self, o: &B3) -> B3 {
        B3(
            self.1.mul(&o.2).sub(&self.2.mul(&o.1)),
            self.2.mul(&o.0).sub(&self.0.mul(&o.2)),
            self.0.mul(&o.1).sub(&self.1.mul(&o.0)),
        )
    }
    pub fn det(a: &B3, b: &B3, c: &B3) -> Big {
        a.dot(&b.cross(c))
    }
    pub fn unit(&self) -> B3 {
        let l = self.dot(self).sqrt();
        B3(self.0.div(&l), self.1.div(&l), self.2.div(&l))
    }
}

/// `robust`'s exact orient3d: the sign of `det[a − d, b − d, c − d]`.
pub fn orient3d_sign(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i32 {
    let k = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    // robust::orient3d(a, b, c, d) is positive when d lies below the plane
    // of a, b, c (a, b, c counter-clockwise seen from above): the
    // determinant det[a − d, b − d, c − d].
    let v = robust::orient3d(k(a), k(b), k(c), k(d));
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// A 2D point of [`Big`].
#[derive(Clone, Debug)]
struct P2(Big, Big);

/// A half-plane `a X + b Y + c ≥ 0`.
#[derive(Clone, Debug)]
struct Half(Big, Big, Big);

impl Half {
    fn at(&self, q: &P2) -> Big {
        self.0.mul(&q.0).add(&self.1.mul(&q.1)).add(&self.2)
    }
}

/// Sutherland–Hodgman against a half-plane (closed; an area is all that
/// is measured, so a boundary's side does not matter).
fn clip(poly: &[P2], h: &Half) -> Vec<P2> {
    let n = poly.len();
    let mut out = Vec::new();
    if n == 0 {
        return out;
    }
    let f: Vec<Big> = poly.iter().map(|q| h.at(q)).collect();
    for k in 0..n {
        let j = (k + 1) % n;
        let (fa, fb) = (&f[k], &f[j]);
        if !fa.is_negative() {
            out.push(poly[k].clone());
        }
        if (fa.is_positive() && fb.is_negative()) || (fa.is_negative() && fb.is_positive()) {
            let t = fa.div(&fa.sub(fb));
            let (a, b) = (&poly[k], &poly[j]);
            out.push(P2(
                a.0.add(&b.0.sub(&a.0).mul(&t)),
                a.1.add(&b.1.sub(&a.1).mul(&t)),
            ));
        }
    }
    out
}

/// The half-planes of a convex counter-clockwise polygon, its vertices
/// first [`merged`]; a polygon left with fewer than three vertices has no
/// area, and its one half-plane holds nothing.
fn edges(poly: &[P2]) -> Vec<Half> {
    let poly = merged(poly);
    if poly.len() < 3 {
        return vec![Half(Big::zero(), Big::zero(), Big::new(-1.0))];
    }
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b) = (&poly[k], &poly[(k + 1) % n]);
            // Left of a → b: (b − a) × (q − a) ≥ 0.
            let (dx, dy) = (b.0.sub(&a.0), b.1.sub(&a.1));
            Half(dy.neg(), dx.clone(), dy.mul(&a.0).sub(&dx.mul(&a.1)))
        })
        .collect()
}

/// The polygon with each vertex within `2⁻¹⁶⁰` of the polygon's size
/// (at least 1) of the one kept before it dropped. Where three lines meet
/// at one point, Sutherland–Hodgman may compute that point twice, from
/// two pairs of lines, each rounded at 256 bits: the edge between the two
/// copies has a direction of rounding alone, and its half-plane would cut
/// a polygon clipped by it along a line through that point at an
/// arbitrary angle. Dropping the copy moves the polygon by less than
/// `2⁻¹⁶⁰` of its size.
fn merged(poly: &[P2]) -> Vec<P2> {
    let abs = |x: &Big| if x.is_negative() { x.neg() } else { x.clone() };
    let mut size = Big::new(1.0);
    for q in poly {
        for c in [&q.0, &q.1] {
            let a = abs(c);
            if size.lt(&a) {
                size = a;
            }
        }
    }
    let tol = size.mul(&Big::new(2f64.powi(-160)));
    let near = |a: &P2, b: &P2| abs(&a.0.sub(&b.0)).lt(&tol) && abs(&a.1.sub(&b.1)).lt(&tol);
    let mut out: Vec<P2> = Vec::new();
    for q in poly {
        if !out.last().is_some_and(|l| near(l, q)) {
            out.push(q.clone());
        }
    }
    while out.len() > 1 && near(&out[0], &out[out.len() - 1]) {
        out.pop();
    }
    out
}

fn shoelace(poly: &[P2]) -> Big {
    let n = poly.len();
    let mut s = Big::zero();
    for k in 0..n {
        let (a, b) = (&poly[k], &poly[(k + 1) % n]);
        s = s.add(&a.0.mul(&b.1).sub(&a.1.mul(&b.0)));
    }
    s.div(&Big::new(2.0))
}

/// The area of a convex counter-clockwise polygon inside the unit disk:
/// Green's theorem edge by edge, each edge split where it crosses the
/// circle; a piece inside contributes its triangle with the origin, a piece
/// outside the sector it subtends.
fn disk_area(poly: &[P2], ctx: &mut Ctx) -> Big {
    let n = poly.len();
    let two = Big::new(2.0);
    let one = Big::new(1.0);
    let mut total = Big::zero();
    for k in 0..n {
        let (a, b) = (&poly[k], &poly[(k + 1) % n]);
        let (dx, dy) = (b.0.sub(&a.0), b.1.sub(&a.1));
        // |a + t d|² = 1: A t² + 2 B t + C = 0.
        let qa = dx.mul(&dx).add(&dy.mul(&dy));
        if qa.is_zero() {
            continue;
        }
        let qb = a.0.mul(&dx).add(&a.1.mul(&dy));
        let qc = a.0.mul(&a.0).add(&a.1.mul(&a.1)).sub(&one);
        let disc = qb.mul(&qb).sub(&qa.mul(&qc));
        let mut ts = vec![Big::zero()];
        if disc.is_positive() {
            let s = disc.sqrt();
            for r in [qb.neg().sub(&s).div(&qa), qb.neg().add(&s).div(&qa)] {
                if r.is_positive() && r.lt(&one) {
                    ts.push(r);
                }
            }
        }
        ts.push(one.clone());
        for w in ts.windows(2) {
            let at = |t: &Big| P2(a.0.add(&dx.mul(t)), a.1.add(&dy.mul(t)));
            let (u, v) = (at(&w[0]), at(&w[1]));
            let mid = at(&w[0].add(&w[1]).div(&two));
            let inside = mid.0.mul(&mid.0).add(&mid.1.mul(&mid.1)).lt(&one);
            let cross = u.0.mul(&v.1).sub(&u.1.mul(&v.0));
            if inside {
                total = total.add(&cross.div(&two));
            } else {
                let dot = u.0.mul(&v.0).add(&u.1.mul(&v.1));
                total = total.add(&ctx.atan2(&cross, &dot).div(&two));
            }
        }
    }
    total
}

/// The light's plane for an area light: the point `center + X e₀ + Y e₁`,
/// the light the unit disk or the square `[−1, 1]²` in `(X, Y)`.
struct Plane {
    center: B3,
    e0: B3,
    e1: B3,
    disk: bool,
}

/// The images' half-planes of one triangle, `None` when its plane holds
/// `p` (then the open segments meet it at most at `p`, or lie in its plane:
/// nothing is hidden).
fn image_halves(plane: &Plane, p: DVec3, tri: &[DVec3; 3]) -> Option<Vec<Half>> {
    let sigma = orient3d_sign(tri[0], tri[1], tri[2], p);
    if sigma == 0 {
        return None;
    }
    let s = Big::new(f64::from(sigma));
    let pb = B3::new(p);
    let q: Vec<B3> = tri.iter().map(|&v| B3::new(v)).collect();
    let rel: Vec<B3> = q.iter().map(|v| v.sub(&pb)).collect();
    let mut out = Vec::new();
    // f(x) = s · det[u, v, x − o] at x = center + X e₀ + Y e₁.
    let mut half = |u: &B3, v: &B3, o: &B3| {
        let n = u.cross(v);
        out.push(Half(
            s.mul(&n.dot(&plane.e0)),
            s.mul(&n.dot(&plane.e1)),
            s.mul(&n.dot(&plane.center.sub(o))),
        ));
    };
    for (j, k) in [(1, 2), (2, 0), (0, 1)] {
        half(&rel[j], &rel[k], &pb);
    }
    half(&q[1].sub(&q[0]), &q[2].sub(&q[0]), &q[0]);
    Some(out)
}

/// The 256-bit `V(p)` of an area `light` behind one convex planar polygon
/// (corners in order): the cone over each edge and the polygon's plane, as
/// for a triangle.
pub fn visibility_polygon(light: &Light, p: DVec3, poly: &[DVec3]) -> f64 {
    let mut ctx = Ctx::new();
    let plane = match *light {
        Light::Sphere(s) => {
            let c = B3::new(s.center());
            let n = c.sub(&B3::new(p)).unit();
            disk_plane(c, n, s.radius())
        }
        Light::Disk(d) => disk_plane(B3::new(d.center()), B3::new(d.normal()).unit(), d.radius()),
        Light::Rect(r) => Plane {
            center: B3::new(r.center()),
            e0: B3::new(r.u()),
            e1: B3::new(r.v()),
            disk: false,
        },
        _ => panic!("an area light"),
    };
    let sigma = orient3d_sign(poly[0], poly[1], poly[2], p);
    let one = Big::new(1.0);
    if sigma == 0 {
        return 1.0;
    }
    let s = Big::new(f64::from(sigma));
    let pb = B3::new(p);
    let q: Vec<B3> = poly.iter().map(|&v| B3::new(v)).collect();
    let mut halves = Vec::new();
    let mut half = |u: &B3, v: &B3, o: &B3| {
        let n = u.cross(v);
        halves.push(Half(
            s.mul(&n.dot(&plane.e0)),
            s.mul(&n.dot(&plane.e1)),
            s.mul(&n.dot(&plane.center.sub(o))),
        ));
    };
    let k = q.len();
    for i in 0..k {
        half(&q[i].sub(&pb), &q[(i + 1) % k].sub(&pb), &pb);
    }
    half(&q[1].sub(&q[0]), &q[2].sub(&q[0]), &q[0]);
    let big = 64.0;
    let square = |h: f64| {
        vec![
            P2(Big::new(-h), Big::new(-h)),
            P2(Big::new(h), Big::new(-h)),
            P2(Big::new(h), Big::new(h)),
            P2(Big::new(-h), Big::new(h)),
        ]
    };
    let image = halves.iter().fold(square(big), |poly, h| clip(&poly, h));
    if image.len() < 3 {
        return 1.0;
    }
    let area = if plane.disk {
        disk_area(&image, &mut ctx).div(&ctx.pi())
    } else {
        shoelace(&edges(&square(1.0)).iter().fold(image, |q, h| clip(&q, h))).div(&Big::new(4.0))
    };
    one.sub(&area).to_f64()
}

/// The 256-bit `V(p)` of `light` among `tris` (see the module docs).
pub fn visibility(light: &Light, p: DVec3, tris: &[[DVec3; 3]]) -> f64 {
    let mut ctx = Ctx::new();
    visibility_big(light, p, tris, &mut ctx).to_f64()
}

/// [`visibility`] as a [`Big`].
pub fn visibility_big(light: &Light, p: DVec3, tris: &[[DVec3; 3]], ctx: &mut Ctx) -> Big {
    let one = Big::new(1.0);
    match *light {
        Light::Point(x) => {
            let x = x.position();
            let blocked = tris.iter().any(|t| open_segment_meets(p, x, t));
            Big::new(if blocked { 0.0 } else { 1.0 })
        }
        Light::Segment(s) => one.sub(&segment_blocked_length(p, s.a(), s.b(), tris)),
        Light::Sphere(s) => {
            let c = B3::new(s.center());
            let n = c.sub(&B3::new(p)).unit();
            let plane = disk_plane(c, n, s.radius());
            one.sub(&area_fraction(&plane, p, tris, ctx))
        }
        Light::Disk(d) => {
            let n = B3::new(d.normal()).unit();
            let plane = disk_plane(B3::new(d.center()), n, d.radius());
            one.sub(&area_fraction(&plane, p, tris, ctx))
        }
        Light::Rect(r) => {
            let plane = Plane {
                center: B3::new(r.center()),
                e0: B3::new(r.u()),
                e1: B3::new(r.v()),
                disk: false,
            };
            one.sub(&area_fraction(&plane, p, tris, ctx))
        }
    }
}

/// An orthonormal frame of the plane normal to `n` (unit), times `r`.
fn disk_plane(center: B3, n: B3, r: f64) -> Plane {
    // The coordinate axis least aligned with n, made orthogonal to it.
    let ax = [n.0.to_f64().abs(), n.1.to_f64().abs(), n.2.to_f64().abs()];
    let k = (0..3).fold(0, |m, k| if ax[k] < ax[m] { k } else { m });
    let mut axis = [0.0; 3];
    axis[k] = 1.0;
    let a = B3::new(DVec3::from_array(axis));
    let e0 = a.sub(&n.scale(&n.dot(&a))).unit();
    let e1 = n.cross(&e0);
    let rb = Big::new(r);
    Plane {
        center,
        e0: e0.scale(&rb),
        e1: e1.scale(&rb),
        disk: true,
    }
}

/// The fraction of an area light the triangles hide.
fn area_fraction(plane: &Plane, p: DVec3, tris: &[[DVec3; 3]], ctx: &mut Ctx) -> Big {
    let big = 64.0;
    let square = |h: f64| {
        vec![
            P2(Big::new(-h), Big::new(-h)),
            P2(Big::new(h), Big::new(-h)),
            P2(Big::new(h), Big::new(h)),
            P2(Big::new(-h), Big::new(h)),
        ]
    };
    let images: Vec<Vec<P2>> = tris
        .iter()
        .filter_map(|t| image_halves(plane, p, t))
        .map(|hs| hs.iter().fold(square(big), |poly, h| clip(&poly, h)))
        .filter(|poly| poly.len() >= 3)
        .collect();
    assert!(
        images.len() <= 12,
        "inclusion–exclusion over at most 12 images"
    );
    let light_square = edges(&square(1.0));
    let mut total = Big::zero();
    // Inclusion–exclusion over the nonempty subsets.
    for subset in 1u32..(1 << images.len()) {
        let mut poly: Option<Vec<P2>> = None;
        for (i, image) in images.iter().enumerate() {
            if subset >> i & 1 == 1 {
                poly = Some(match poly {
                    None => image.clone(),
                    Some(acc) => edges(image).iter().fold(acc, |q, h| clip(&q, h)),
                });
            }
        }
        let poly = poly.expect("a nonempty subset");
        if poly.len() < 3 {
            continue;
        }
        let area = if plane.disk {
            disk_area(&poly, ctx)
        } else {
            shoelace(&light_square.iter().fold(poly, |q, h| clip(&q, h)))
        };
        total = if subset.count_ones() % 2 == 1 {
            total.add(&area)
        } else {
            total.sub(&area)
        };
    }
    let light_area = if plane.disk { ctx.pi() } else { Big::new(4.0) };
    total.div(&light_area)
}

/// The length, as a fraction, of the segment light `a b` the triangles
/// hide from `p`.
fn segment_blocked_length(p: DVec3, a: DVec3, b: DVec3, tris: &[[DVec3; 3]]) -> Big {
    let (zero, one) = (Big::zero(), Big::new(1.0));
    let pb = B3::new(p);
    let (ab, bb) = (B3::new(a), B3::new(b));
    let mut spans: Vec<(Big, Big)> = Vec::new();
    'tris: for tri in tris {
        let sigma = orient3d_sign(tri[0], tri[1], tri[2], p);
        if sigma == 0 {
            continue;
        }
        let s = Big::new(f64::from(sigma));
        let q: Vec<B3> = tri.iter().map(|&v| B3::new(v)).collect();
        let rel: Vec<B3> = q.iter().map(|v| v.sub(&pb)).collect();
        let (mut lo, mut hi) = (zero.clone(), one.clone());
        // (1 − t) fa + t fb, closed or open.
        let conds: Vec<(Big, Big, bool)> = [(1, 2), (2, 0), (0, 1)]
            .iter()
            .map(|&(j, k)| {
                let n = rel[j].cross(&rel[k]);
                (
                    s.mul(&n.dot(&ab.sub(&pb))),
                    s.mul(&n.dot(&bb.sub(&pb))),
                    true,
                )
            })
            .chain(std::iter::once({
                let n = q[1].sub(&q[0]).cross(&q[2].sub(&q[0]));
                (
                    s.mul(&n.dot(&ab.sub(&q[0]))),
                    s.mul(&n.dot(&bb.sub(&q[0]))),
                    false,
                )
            }))
            .collect();
        for (fa, fb, closed) in conds {
            let inside = |f: &Big| f.is_positive() || (closed && f.is_zero());
            match (inside(&fa), inside(&fb)) {
                (true, true) => {}
                (false, false) => continue 'tris,
                (a_in, _) => {
                    let t = fa.div(&fa.sub(&fb));
                    if a_in {
                        if t.lt(&hi) {
                            hi = t;
                        }
                    } else if lo.lt(&t) {
                        lo = t;
                    }
                }
            }
        }
        if lo.lt(&hi) {
            spans.push((lo, hi));
        }
    }
    spans.sort_by(|x, y| x.0 .0.partial_cmp(&y.0 .0).expect("finite"));
    let mut total = zero.clone();
    let mut reach = zero;
    for (s, e) in spans {
        let s = if s.lt(&reach) { reach.clone() } else { s };
        if s.lt(&e) {
            total = total.add(&e.sub(&s));
            reach = e;
        }
    }
    total
}

/// Whether the open segment `(p, x)` meets the closed triangle: the ends
/// strictly on both sides of its plane and the line through them on no
/// strict outer side of an edge (`robust`'s signs).
pub fn open_segment_meets(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> bool {
    let sp = orient3d_sign(t[0], t[1], t[2], p);
    let sx = orient3d_sign(t[0], t[1], t[2], x);
    if sp == 0 || sx != -sp {
        return false;
    }
    let e = [
        orient3d_sign(p, x, t[0], t[1]),
        orient3d_sign(p, x, t[1], t[2]),
        orient3d_sign(p, x, t[2], t[0]),
    ];
    !(e.contains(&1) && e.contains(&-1))
}
