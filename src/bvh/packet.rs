//! Closest hits of [`PACKET`] rays through one walk of the tree
//! ([`Bvh::closest_packet`]), for the batch query: each node's boxes tested
//! against all the packet's rays side by side, each leaf's triangle
//! against the rays that reach it side by side
//! ([`crossings_filtered`]).

use super::hit::{facing, Hit, U_SLACK};
use super::node::{decode, Node, EMPTY, LEAF, WIDTH};
use super::ray::{Ray32, STACK, T_SLACK};
use super::{f32_up, Bvh};
use crate::kernel::segment::{crossing, crossings_filtered, Filtered};
use glam::DVec3;

/// Rays per packet.
pub(super) const PACKET: usize = 8;

/// One `f32` per ray of a packet.
type Lanes32 = [f32; PACKET];

impl Bvh {
    /// [`Bvh::closest_hit`] of each of the [`PACKET`] `rays` into `out`,
    /// the same answers bit for bit; `false` (and `out` untouched) where
    /// the packet is left to one query per ray: rays that do not share
    /// one origin and a narrow cone ([`Bvh::CONE`]), triangles kept out of
    /// the tree, no tree, a ray the query refuses or whose segment leaves
    /// the `f32` range, or a tree deeper than the packet's stack.
    ///
    /// The walk visits a node for the rays whose slab test kept it in its
    /// parent (each ray's own conservative test, limited by its own
    /// nearest hit so far, see [`Bvh::closest_hit`]), and a leaf's
    /// triangle is decided for those rays exactly as one query decides it:
    /// [`crossings_filtered`] gives each ray the verdict and `u` of the
    /// one-ray filter, and a ray it leaves unsure is decided by
    /// [`crossing`]. A ray's answer is the least `(u, triangle)` over the
    /// triangles it reached, which hold every triangle it crosses within
    /// its limit: the answer of testing every triangle, as for one query.
    #[inline(always)]
    pub(super) fn closest_packet(
        &self,
        rays: &[(DVec3, DVec3)],
        t_max: f64,
        out: &mut [Option<Hit>],
    ) -> bool {
        if rays.len() != PACKET
            || out.len() != PACKET
            || !self.outliers.is_empty()
            || self.nodes.is_empty()
            || self.stack_need() > STACK
            || t_max.is_nan()
            || t_max <= 0.0
        {
            return false;
        }
        let Some(ray) = self.setup(rays) else {
            return false;
        };
        // The entry side of each axis where every ray has the same.
        let sides: Option<[usize; 3]> = (0..3)
            .all(|k| ray.back[k].iter().all(|&m| m == ray.back[k][0]))
            .then(|| core::array::from_fn(|k| usize::from(ray.back[k][0] != 0)));
        let mut best = PacketBest {
            u: [f64::INFINITY; PACKET],
            id: [u32::MAX; PACKET],
            limit: core::array::from_fn(|l| {
                if t_max < f64::INFINITY {
                    1.0f32.min(f32_up(t_max / ray.scale[l] * (1.0 + U_SLACK)))
                } else {
                    1.0
                }
            }),
            t_max,
        };

        // Only the stack the tree needs is cleared (as `closest_in_tree`).
        let (mut small, mut large);
        let stack: &mut [(u32, u8)] = if self.stack_need() <= STACK / 2 {
            small = [(0u32, 0u8); STACK / 2];
            &mut small
        } else {
            large = [(0u32, 0u8); STACK];
            &mut large
        };
        let mut top = 0;
        let (mut node, mut rays_in) = (0u32, u8::MAX);
        loop {
            let n = &self.nodes[node as usize];
            let (kept, count) = packet_lanes(n, &ray, sides, &best.limit, rays_in);
            let mut inner = [(0u32, 0u8); WIDTH];
            let mut inner_count = 0;
            for &(_, hit, lane) in &kept[..count] {
                let child = n.child[lane];
                if child & LEAF == 0 {
                    inner[inner_count] = (child, hit);
                    inner_count += 1;
                } else {
                    self.packet_leaf((child & !LEAF) as usize, &ray, hit, &mut best);
                }
            }
            // Farthest first, so that the nearest is popped next.
            for &entry in inner[..inner_count].iter().rev() {
                stack[top] = entry;
                top += 1;
            }
            if top == 0 {
                break;
            }
            top -= 1;
            (node, rays_in) = stack[top];
        }
        let (normals, objects) = (self.normals(), self.occluders.objects());
        for (l, out) in out.iter_mut().enumerate() {
            let id = best.id[l];
            *out = if id == u32::MAX {
                None
            } else {
                Some(Hit {
                    t: (best.u[l] * ray.scale[l]).clamp(f64::from_bits(1), t_max.min(f64::MAX)),
                    triangle: id,
                    object: objects[id as usize],
                    normal: facing(normals[id as usize], rays[l].1),
                })
            };
        }
        true
    }

    /// Tests the leaf triangle `i` against the packet's rays in `hit` (a
    /// bit a ray), offering each crossing to `best`.
    #[inline(always)]
    fn packet_leaf(&self, i: usize, ray: &Setup, hit: u8, best: &mut PacketBest) {
        let t = &self.triangles[i];
        let id = self.ids[i];
        let (verdict, u) = crossings_filtered(ray.origin, &ray.d, &ray.d_norm, t);
        let mut rest = hit;
        while rest != 0 {
            let l = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let u = match verdict[l] {
                Filtered::Miss => continue,
                Filtered::Hit => u[l],
                Filtered::Unsure => {
                    let at = |v: &[[f64; PACKET]; 3]| DVec3::new(v[0][l], v[1][l], v[2][l]);
                    match crossing(ray.origin, at(&ray.x), at(&ray.d), ray.d_norm[l], t) {
                        Some(u) => u,
                        None => continue,
                    }
                }
            };
            if (u < best.u[l] || (u == best.u[l] && id < best.id[l]))
                && u * ray.scale[l] <= best.t_max
            {
                best.u[l] = u;
                best.id[l] = id;
                best.limit[l] = best.limit[l].min(f32_up(u));
            }
        }
    }
}

/// Each ray's nearest crossing so far in a packet's walk.
struct PacketBest {
    /// Segment parameter (`∞`: none yet) and occluder index (`u32::MAX`).
    u: [f64; PACKET],
    id: [u32; PACKET],
    /// The segment parameter past which a box cannot hold a better
    /// crossing (rounded up).
    limit: Lanes32,
    t_max: f64,
}

/// The lanes of node `n` that some ray of `rays_in` (a bit a ray) may
/// meet within its `limit`, each with those rays and the entry of the
/// first of them, sorted by that entry (the order of the visit); and how
/// many. `sides`: the entry side of each axis where every ray has the same.
#[inline(always)]
fn packet_lanes(
    n: &Node,
    ray: &Setup,
    sides: Option<[usize; 3]>,
    limit: &Lanes32,
    rays_in: u8,
) -> ([(f32, u8, usize); WIDTH], usize) {
    let mut kept = [(f32::INFINITY, 0u8, 0usize); WIDTH];
    let mut count = 0;
    for lane in 0..WIDTH {
        if n.child[lane] == EMPTY {
            continue;
        }
        let mut t_near = [0.0f32; PACKET];
        let mut t_far = *limit;
        for k in 0..3 {
            let plane = |side: usize| decode(n.origin[k], n.q[side][k][lane], n.scale[k]);
            let mut axis = |entry: &dyn Fn(usize) -> f32, exit: &dyn Fn(usize) -> f32| {
                for l in 0..PACKET {
                    let a = (entry(l) - ray.near[k][l]) * ray.inv[k][l];
                    let b = (exit(l) - ray.far[k][l]) * ray.inv[k][l];
                    t_near[l] = if a > t_near[l] { a } else { t_near[l] };
                    t_far[l] = if b < t_far[l] { b } else { t_far[l] };
                }
            };
            if let Some(side) = sides {
                // Every ray enters by the same plane (most packets).
                let (entry, exit) = (plane(side[k]), plane(1 - side[k]));
                axis(&|_| entry, &|_| exit);
            } else {
                let (lo, hi) = (plane(0).to_bits(), plane(1).to_bits());
                let m = &ray.back[k];
                axis(&|l| f32::from_bits((hi & m[l]) | (lo & !m[l])), &|l| {
                    f32::from_bits((lo & m[l]) | (hi & !m[l]))
                });
            }
        }
        // Each ray's bit in place, then one reduction (a form the
        // compiler keeps in vector registers).
        let bits: [u32; PACKET] =
            core::array::from_fn(|l| u32::from(t_near[l] <= t_far[l] * T_SLACK) << l);
        let hit = bits.iter().fold(0, |a, b| a | b) as u8 & rays_in;
        if hit == 0 {
            continue;
        }
        // The order of the visit: the entry of the first ray kept.
        let first = t_near[hit.trailing_zeros() as usize];
        // By that entry (insertion: at most four).
        let mut k = count;
        let mut item = (first, hit, lane);
        while k > 0 && kept[k - 1].0 > item.0 {
            (kept[k], item) = (kept[k - 1], item);
            k -= 1;
        }
        kept[k] = item;
        count += 1;
    }
    (kept, count)
}

/// The packet's rays as [`Bvh::probe`] and [`Ray32::new`] make them, in
/// structure-of-arrays form (`[axis][ray]`).
struct Setup {
    /// The rays' one origin (a packet's rays share it).
    origin: DVec3,
    x: [F64s; 3],
    d: [F64s; 3],
    d_norm: F64s,
    scale: F64s,
    near: [Lanes32; 3],
    far: [Lanes32; 3],
    inv: [Lanes32; 3],
    /// All ones where the ray enters a box by its upper plane.
    back: [[u32; PACKET]; 3],
}

/// One `f64` per ray of a packet.
type F64s = [f64; PACKET];

/// `f(l)` for every ray `l`.
#[inline(always)]
fn each<T>(f: impl FnMut(usize) -> T) -> [T; PACKET] {
    core::array::from_fn(f)
}

impl Bvh {
    /// The widest spread of a packet's directions, each divided by its
    /// max-norm: `|s − s₀|∞`, `s₀` the first ray's (ours: 8 adjacent
    /// pixels of a 32-pixel-wide image of 40° spread about 0.17).
    const CONE: f64 = 0.25;

    /// [`Bvh::probe`] and [`Ray32::new`] of every ray of the packet, the
    /// same operations lane by lane (so the same bits, in vector
    /// registers); `None` where either refuses a ray.
    #[inline(always)]
    fn setup(&self, rays: &[(DVec3, DVec3)]) -> Option<Setup> {
        let (lo, hi) = self.bounds?;
        let axes = |f: &dyn Fn(usize, usize) -> f64| -> [F64s; 3] {
            core::array::from_fn(|k| each(|l| f(k, l)))
        };
        let origin = axes(&|k, l| rays[l].0[k]);
        let direction = axes(&|k, l| rays[l].1[k]);
        // glam's `max_element` (the values are finite where it matters).
        let norm = |v: &[F64s; 3]| -> F64s {
            each(|l| {
                let max = |a: f64, b: f64| if a > b { a } else { b };
                max(max(v[0][l].abs(), v[1][l].abs()), v[2][l].abs())
            })
        };
        let mut refused = false;
        for k in 0..3 {
            for l in 0..PACKET {
                refused |= !(origin[k][l].is_finite() && direction[k][l].is_finite());
            }
        }
        let m = norm(&direction);
        let inv_m = each(|l| 1.0 / m[l]);
        let by_inverse = each(|l| (1e-300..=1e300).contains(&m[l]));
        // (The divisions only where some ray needs them.)
        let s = if by_inverse.iter().all(|&b| b) {
            axes(&|k, l| direction[k][l] * inv_m[l])
        } else {
            axes(&|k, l| {
                if by_inverse[l] {
                    direction[k][l] * inv_m[l]
                } else {
                    direction[k][l] / m[l]
                }
            })
        };
        // Coherent packets only: one origin, directions within a narrow
        // cone (`|s − s₀|∞ ≤ 1/4`, `|s|∞ = 1`). Elsewhere a shared walk
        // visits more than its rays would apart (slower on random rays,
        // and on random directions from one origin). A NaN (zero or
        // non-finite input) is refused below.
        for k in 0..3 {
            for l in 0..PACKET {
                refused |= origin[k][l].to_bits() != origin[k][0].to_bits();
                refused |= (s[k][l] - s[k][0]).abs() > Bvh::CONE;
            }
        }
        if refused {
            return None;
        }
        let far = each(|l| {
            let gap = |k: usize| (hi[k] - origin[k][l]).max(origin[k][l] - lo[k]);
            let max = |a: f64, b: f64| if a > b { a } else { b };
            max(max(gap(0), gap(1)), gap(2))
        });
        let o_norm = norm(&origin);
        let reach = each(|l| 2.0 * far[l].max(o_norm[l]));
        let x = axes(&|k, l| origin[k][l] + s[k][l] * reach[l]);
        let d = axes(&|k, l| x[k][l] - origin[k][l]);
        let d_norm = norm(&d);
        let scale = if by_inverse.iter().all(|&b| b) {
            each(|l| reach[l] * inv_m[l])
        } else {
            each(|l| {
                if by_inverse[l] {
                    reach[l] * inv_m[l]
                } else {
                    reach[l] / m[l]
                }
            })
        };
        let x_norm = norm(&x);
        for l in 0..PACKET {
            refused |= m[l] == 0.0 || reach[l].is_nan() || reach[l] <= 0.0;
            refused |= !(x[0][l].is_finite() && x[1][l].is_finite() && x[2][l].is_finite());
            // `Ray32::new`'s range.
            refused |= !(o_norm[l] <= f64::from(f32::MAX) && x_norm[l] <= f64::from(f32::MAX));
        }
        if refused {
            return None;
        }
        // `Ray32::new`, each axis for the eight rays at once.
        let (mut near, mut far, mut inv) = (
            [[0.0f32; PACKET]; 3],
            [[0.0f32; PACKET]; 3],
            [[0.0f32; PACKET]; 3],
        );
        let mut back = [[0u32; PACKET]; 3];
        for k in 0..3 {
            let axes = Ray32::axes(origin[k], d[k]);
            (near[k], far[k], inv[k]) = (axes.near, axes.far, axes.inv);
            for (b, &backward) in back[k].iter_mut().zip(&axes.backward) {
                *b = 0u32.wrapping_sub(u32::from(backward));
            }
        }
        Some(Setup {
            origin: rays[0].0,
            x,
            d,
            d_norm,
            scale,
            near,
            far,
            inv,
            back,
        })
    }
}
