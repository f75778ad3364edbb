//! Double-double arithmetic for the general-position closed form
//! ([`General`](super::general::General)).

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
    1.0 - super::plate::segment_area(2.0 * half) / std::f64::consts::PI
}
