//! The culling query of the exact reference
//! ([`Bvh::triangles_meeting_hull`]): every triangle whose box may meet the
//! convex hull of a few points.

use super::node::{Node, EMPTY, LEAF, WIDTH};
use super::ray::{NodeStack, STACK};
use super::{in_f32_range, Bvh};
use crate::kernel::lanes;
use glam::DVec3;

impl Bvh {
    /// Writes to `out` (after clearing it), in increasing order and without
    /// repetition, the index (into [`Bvh::occluders`]) of every triangle
    /// whose box may meet the convex hull of `points`: a superset of the
    /// triangles that meet the hull. Any finite point set is accepted; the
    /// intended one is a pyramid, the receiver plus the corners of a box or
    /// polygon around the light's measure.
    ///
    /// A box is dropped only when it is separated from the hull, decided
    /// with rounding bounds (never wrongly): by the hull's bounding box
    /// (exact comparisons), or along a normal `n` of one of the hull's faces
    /// when the box's interval of `n · (q − points[0])` lies beyond the
    /// hull's. Any `n` is a valid separating axis, the face normals are
    /// merely the tight ones: five points are read as a pyramid (the apex,
    /// then the base's corners in order around it), whose four sides and
    /// base give the normals; otherwise they are found among the planes
    /// through three of the points (for at most [`Bvh::HULL_FACE_POINTS`]
    /// points). Each dot product with a point of the hull is bounded by
    /// `γ₆ Σ|nᵢ||qᵢ − aᵢ|` (one rounded difference, product and two sums
    /// need `γ₄`); a box's interval, from its rounded centre `c` and
    /// half-extent `e`, by `γ₁₀ Σ|nᵢ|(|cᵢ − aᵢ| + eᵢ + |cᵢ|)`.
    ///
    /// No points: `out` is empty. A non-finite point, or one beyond
    /// `f32::MAX`: every indexed triangle. Triangles beyond `±2⁶⁰`, kept out
    /// of the tree, are always reported; triangles with a non-finite corner
    /// never (they block nothing).
    pub fn triangles_meeting_hull(&self, points: &[DVec3], out: &mut Vec<u32>) {
        self.triangles_meeting_hull_at_most(points, out, usize::MAX);
    }

    /// [`Bvh::triangles_meeting_hull`] when it finds at most `cap`
    /// triangles (then `true`); else `false` as soon as it finds more,
    /// `out` holding an unspecified part of them.
    pub(crate) fn triangles_meeting_hull_at_most(
        &self,
        points: &[DVec3],
        out: &mut Vec<u32>,
        cap: usize,
    ) -> bool {
        lanes::vectorized(
            #[inline(always)]
            |_| self.meeting_hull_at_most(points, out, cap),
        )
    }

    /// [`Bvh::triangles_meeting_hull_at_most`], compiled where it is called.
    #[inline(always)]
    fn meeting_hull_at_most(&self, points: &[DVec3], out: &mut Vec<u32>, cap: usize) -> bool {
        out.clear();
        if points.is_empty() {
            return true;
        }
        out.extend_from_slice(&self.outlier_ids);
        if self.nodes.is_empty() || !points.iter().all(|&v| in_f32_range(v)) {
            out.extend_from_slice(&self.ids);
            out.sort_unstable();
            return out.len() <= cap;
        }
        let hull = Hull::new(points);
        // Depth-first, one node at a time: at most `stack_need` entries.
        let mut stack = NodeStack::<STACK>::new();
        let stack = stack.entries(self.stack_need());
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            let separated = hull.separated(n);
            for (&child, separated) in n.child.iter().zip(separated) {
                if child == EMPTY || separated {
                    continue;
                }
                if child & LEAF == 0 {
                    stack[top] = child;
                    top += 1;
                } else {
                    out.push(self.ids[(child & !LEAF) as usize]);
                }
            }
            if out.len() > cap {
                return false;
            }
        }
        out.sort_unstable();
        true
    }

    /// The most points whose face planes [`Bvh::triangles_meeting_hull`]
    /// looks for (`C(n, 3)` candidate planes); beyond it, only the hull's
    /// bounding box culls.
    pub const HULL_FACE_POINTS: usize = 16;
}

/// The separating tests of [`Bvh::triangles_meeting_hull`].
struct Hull {
    lo: DVec3,
    hi: DVec3,
    /// Reference point `a` of the axes (the first point).
    origin: DVec3,
    /// `(n, |n|, lo, hi)`: the hull lies in `lo ≤ n · (q − a) ≤ hi`.
    axes: Vec<(DVec3, DVec3, f64, f64)>,
}

/// `γ(6)`.
const GAMMA6: f64 = crate::kernel::footprint::f64::gamma(6);

/// `γ(10)`.
const GAMMA10: f64 = crate::kernel::footprint::f64::gamma(10);

impl Hull {
    fn new(points: &[DVec3]) -> Hull {
        let (mut lo, mut hi) = (points[0], points[0]);
        for &v in points {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        let origin = points[0];
        let mut hull = Hull {
            lo,
            hi,
            origin,
            axes: Vec::new(),
        };
        let n = points.len();
        if let &[apex, a, b, c, d] = points {
            // A pyramid, as the references pass it: its four sides and its
            // base, with no search.
            let faces = [
                (apex, a, b),
                (apex, b, c),
                (apex, c, d),
                (apex, d, a),
                (a, b, c),
            ];
            for (p, q, r) in faces {
                if let Some(normal) = (q - p).cross(r - p).try_normalize() {
                    hull.add_axis(normal, points);
                }
            }
            return hull;
        }
        if !(3..=Bvh::HULL_FACE_POINTS).contains(&n) {
            return hull;
        }
        let mut normals: Vec<DVec3> = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let (a, b, c) = (points[i], points[j], points[k]);
                    let normal = (b - a).cross(c - a);
                    let Some(unit) = normal.try_normalize() else {
                        continue;
                    };
                    // A face: no point strictly on both sides (rounded test;
                    // only tightness, not soundness, depends on it).
                    let tol = 1e-9 * (b - a).length().max((c - a).length());
                    let (mut below, mut above) = (false, false);
                    for &v in points {
                        let s = unit.dot(v - a);
                        below |= s < -tol;
                        above |= s > tol;
                    }
                    let duplicate = normals.iter().any(|m| m.dot(unit).abs() > 1.0 - 1e-12);
                    let face = !(below && above);
                    if face && !duplicate {
                        normals.push(unit);
                    }
                }
            }
        }
        for normal in normals {
            hull.add_axis(normal, points);
        }
        hull
    }

    /// Adds `normal` as a separating axis, with the interval the points
    /// span along it (rounding bounds included).
    fn add_axis(&mut self, normal: DVec3, points: &[DVec3]) {
        let (mut l, mut h) = (f64::INFINITY, f64::NEG_INFINITY);
        for &v in points {
            let (s, bound) = dot_bounded(normal, v, self.origin);
            l = l.min(s - bound);
            h = h.max(s + bound);
        }
        if l.is_finite() && h.is_finite() {
            self.axes.push((normal, normal.abs(), l, h));
        }
    }

    /// Whether each lane of `n` is certainly disjoint from the hull: the
    /// four lanes side by side, in straight loops the compiler vectorises.
    #[inline(always)]
    fn separated(&self, n: &Node) -> [bool; WIDTH] {
        let (lo, hi) = (n.planes(0), n.planes(1));
        let (hull_lo, hull_hi) = (self.lo.to_array(), self.hi.to_array());
        let origin = self.origin.to_array();
        // The box as its centre `c` and half-extent `e`, each rounded once
        // (the box lies within `(e + u |c|)/(1 − u)` of `c` on each axis),
        // and along each axis the interval `n · (c − a) ± |n| · e`, widened
        // by `γ₁₀ |n| · (|c − a| + e + |c|)`: more than the rounding of
        // `c`, `e`, `c − a`, the two dot products and the sum
        // (`γ₃ + γ₅`); the final comparisons need none (a rounded
        // `s − r > h` implies the exact one).
        let mut out = [false; WIDTH];
        let (mut d, mut e, mut slack) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
        for axis in 0..3 {
            for lane in 0..WIDTH {
                let (l, h) = (lo[axis][lane], hi[axis][lane]);
                // Beyond the hull's bounding box (exact comparisons).
                out[lane] |= (l > hull_hi[axis]) | (h < hull_lo[axis]);
                let c = (l + h) * 0.5;
                e[axis][lane] = (h - l) * 0.5;
                d[axis][lane] = c - origin[axis];
                slack[axis][lane] = d[axis][lane].abs() + e[axis][lane] + c.abs();
            }
        }
        // The dot products summed in `DVec3::dot`'s order.
        let dot = |n: DVec3, v: &[[f64; WIDTH]; 3], lane: usize| {
            n.x * v[0][lane] + n.y * v[1][lane] + n.z * v[2][lane]
        };
        for &(normal, abs_normal, l, h) in &self.axes {
            for (lane, out) in out.iter_mut().enumerate() {
                let s = dot(normal, &d, lane);
                let r = dot(abs_normal, &e, lane) + GAMMA10 * dot(abs_normal, &slack, lane);
                // NaN (never expected with finite inputs) compares false: kept.
                *out |= (s - r > h) | (s + r < l);
            }
        }
        out
    }
}

/// `n · (q − a)` rounded, and a bound on its rounding error.
fn dot_bounded(n: DVec3, q: DVec3, a: DVec3) -> (f64, f64) {
    let d = q - a;
    (n.dot(d), GAMMA6 * n.abs().dot(d.abs()))
}
