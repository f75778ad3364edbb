//! The closest hit of a ray ([`Bvh::closest_hit`]): the ordered, culling
//! traversal and the segment a ray is decided on; batches of rays, in
//! packets where they are coherent (`packet.rs`).

use super::hit::{facing, Hit, U_SLACK};
use super::node::{LEAF, WIDTH};
use super::packet::PACKET;
use super::ray::{Ray32, STACK, T_SLACK};
use super::{f32_up, Bvh};
use crate::kernel::lanes;
use crate::kernel::segment::crossing;
use glam::DVec3;
use rayon::prelude::*;

impl Bvh {
    /// The nearest crossing of the ray `origin + t · direction`,
    /// `t ∈ (0, t_max]`, with any triangle (both sides count); `None` when
    /// the ray meets none, or for a non-finite origin or direction, a zero
    /// direction, or `t_max` not positive (or NaN). `t_max` may be `+∞`.
    ///
    /// # How it decides
    ///
    /// The ray is represented by the segment from `origin` to a far point
    /// `x = fl(origin + T · direction)` beyond every triangle (see
    /// [`Bvh::ray_segment`]: `T |direction|∞` is twice the larger of the
    /// max-norm distance to the farthest corner of the box of all triangles
    /// and `|origin|∞`, so `x − o` follows `direction` to a relative
    /// `2⁻⁵¹`). Whether the ray meets a
    /// triangle is decided exactly on that segment by [`segment_crossing`]
    /// (the decision of [`segment_blocked`]): a ray through an edge or a
    /// vertex shared by two triangles meets at least one of them — closed
    /// meshes are watertight — and a hit exactly on an edge counts; a
    /// triangle whose plane contains the origin is not met (`t > 0`).
    /// The crossing's `t` comes from the plane (relative error below
    /// `2⁻²³`, in practice a few ulps), and the hit is the crossing of
    /// least segment parameter (so of least `t`), ties going to the lower
    /// triangle index: the answer is that of testing every triangle
    /// (`tests/closest_hit.rs` checks it bit for bit), independent of the
    /// traversal order and of threads. A crossing whose rounded `t`
    /// exceeds `t_max` is not counted.
    ///
    /// The traversal is the conservative `f32` one of
    /// [`Bvh::segment_unoccluded`], ordered: the lanes a node's slab test
    /// keeps are visited nearest entry first, and each hit shrinks the
    /// segment's far end to its `t`, rounded up and widened by the slab
    /// test's `2⁻²⁰`. The slab test's entry is at most `(1 + 2⁻²¹)` times
    /// the parameter of any point of the true segment in the box, and a
    /// crossing's computed parameter is within `2⁻²³` of the true one
    /// (`2⁻²¹ + 2⁻²³` stays below `2⁻²⁰` less the comparison's
    /// roundings), so no box holding a crossing at or before the current
    /// hit is culled.
    ///
    /// Triangles beyond `±2⁶⁰` (kept out of the tree) are tested by every
    /// query, and a far point beyond `f32::MAX` tests every triangle, as
    /// for [`Bvh::segment_unoccluded`]; far-away triangles also lengthen
    /// the segment, which makes the `f32` culling coarser.
    ///
    /// Returned: `t` rounded from the crossing's parameter and clamped to
    /// `[5e-324, min(t_max, f64::MAX)]`; the triangle, its object id and
    /// its unit geometric normal facing the ray (`normal · direction ≤ 0`,
    /// zero only for a hit so grazing that the rounded normal is
    /// perpendicular to the ray; `−direction` normalised for a triangle
    /// too thin for its normal to be computed). The first closest-hit query
    /// on a BVH computes every triangle's unit normal once (in parallel, 24
    /// bytes per triangle, kept with the BVH); later queries read it.
    ///
    /// Exact for coordinates in the domain of [`orient3d`] (including those
    /// of the far point).
    ///
    /// [`segment_crossing`]: crate::kernel::segment::segment_crossing
    /// [`segment_blocked`]: crate::kernel::segment::segment_blocked
    /// [`orient3d`]: crate::kernel::predicate::orient3d
    #[must_use]
    pub fn closest_hit(&self, origin: DVec3, direction: DVec3, t_max: f64) -> Option<Hit> {
        self.closest_hit_here(origin, direction, t_max)
    }

    /// [`Bvh::closest_hit`], compiled where it is called.
    #[inline(always)]
    fn closest_hit_here(&self, origin: DVec3, direction: DVec3, t_max: f64) -> Option<Hit> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let probe = self.probe(origin, direction)?;
        let mut best = Best {
            u: f64::INFINITY,
            id: u32::MAX,
            scale: probe.scale,
            t_max,
        };
        for (t, &id) in self.outliers.iter().zip(&self.outlier_ids) {
            best.offer(probe.crossing(t), id);
        }
        let ray = Ray32::new(probe.o, probe.x).filter(|_| !self.nodes.is_empty());
        match ray {
            Some(ray) => self.closest_in_tree(&probe, &ray, &mut best),
            None => {
                for (t, &id) in self.triangles.iter().zip(&self.ids) {
                    best.offer(probe.crossing(t), id);
                }
            }
        }
        if best.id == u32::MAX {
            return None;
        }
        let t = (best.u * probe.scale).clamp(f64::from_bits(1), t_max.min(f64::MAX));
        Some(Hit {
            t,
            triangle: best.id,
            object: self.occluders.objects()[best.id as usize],
            normal: facing(self.normals()[best.id as usize], direction),
        })
    }

    /// [`Bvh::closest_hit`] for every `(origin, direction)` of `rays`, on
    /// the current rayon pool (chunks of 256 rays, each as
    /// [`Bvh::closest_hits`]); the same answers as one call per ray, in
    /// order, whatever the number of threads.
    #[must_use]
    pub fn closest_hit_many(&self, rays: &[(DVec3, DVec3)], t_max: f64) -> Vec<Option<Hit>> {
        let mut out = vec![None; rays.len()];
        out.par_chunks_mut(256)
            .zip(rays.par_chunks(256))
            .for_each(|(out, rays)| self.closest_hits_into(rays, t_max, out));
        out
    }

    /// [`Bvh::closest_hit`] for every `(origin, direction)` of `rays`, in
    /// the calling thread: `out` is replaced by one answer per ray, in
    /// order (its allocation reused). For callers that spread their own
    /// work over threads (the renderer calls it per image row). The same
    /// answers as one call per ray, bit for bit; faster, since the whole
    /// batch is compiled for AVX2 where the processor has it (feature
    /// `simd`; one dispatch per batch: per ray it costs more than it
    /// saves), and since each run of eight consecutive rays that share
    /// their origin and point within a narrow cone — a camera's rays
    /// along an image row — goes through the tree in one walk, tested
    /// against each box and triangle side by side (`benches/README.md`
    /// has the figures). Give such rays in order to gain it; other rays
    /// are traced one at a time.
    pub fn closest_hits(&self, rays: &[(DVec3, DVec3)], t_max: f64, out: &mut Vec<Option<Hit>>) {
        out.clear();
        out.resize(rays.len(), None);
        self.closest_hits_into(rays, t_max, out);
    }

    /// [`Bvh::closest_hits`] into `out` (as many rays as both hold).
    fn closest_hits_into(&self, rays: &[(DVec3, DVec3)], t_max: f64, out: &mut [Option<Hit>]) {
        lanes::vectorized(
            #[inline(always)]
            |_| {
                for (out, rays) in out.chunks_mut(PACKET).zip(rays.chunks(PACKET)) {
                    if self.closest_packet(rays, t_max, out) {
                        continue;
                    }
                    for (o, &(origin, direction)) in out.iter_mut().zip(rays) {
                        *o = self.closest_hit_here(origin, direction, t_max);
                    }
                }
            },
        );
    }

    /// The segment [`Bvh::closest_hit`] decides on for the ray
    /// `origin + t · direction`: `Some((x, t_x))` with the far point `x`
    /// and the ray parameter `t_x` it stands for, so that a crossing at
    /// segment parameter `u` (as [`segment_crossing`]`(origin, x, ·)`
    /// returns it) is the hit `t = u · t_x` (rounded). `None` where
    /// [`Bvh::closest_hit`] returns `None` before testing any triangle: no
    /// triangle, non-finite or zero input, or a far point that overflows.
    ///
    /// With `m = |direction|∞` and `s = direction · fl(1/m)` (`direction /
    /// m` for `m` outside `[1e-300, 1e300]`; either way `|s|∞ = 1` to an
    /// ulp):
    /// `T = 2 max(E, |origin|∞)`, `E` the rounded max-norm distance from
    /// `origin` to the farthest corner of the exact box of all finite
    /// triangles (no point `origin + τ s` with `τ > E` is in the box; the
    /// factor 2 covers the rounding, and `|origin|∞` keeps `x − origin`
    /// within a relative `2⁻⁵¹` of `T s`), `x = fl(origin + T s)`,
    /// `t_x = T · fl(1/m)` (or `T / m`).
    ///
    /// [`segment_crossing`]: crate::kernel::segment::segment_crossing
    #[must_use]
    pub fn ray_segment(&self, origin: DVec3, direction: DVec3) -> Option<(DVec3, f64)> {
        self.probe(origin, direction).map(|p| (p.x, p.scale))
    }

    /// See [`Bvh::ray_segment`].
    #[inline(always)]
    fn probe(&self, origin: DVec3, direction: DVec3) -> Option<Probe> {
        if !(origin.is_finite() && direction.is_finite()) {
            return None;
        }
        let (lo, hi) = self.bounds?;
        let m = direction.abs().max_element();
        if m == 0.0 {
            return None;
        }
        // One division where the reciprocal stays in the normal range.
        let inv = 1.0 / m;
        let by_inverse = (1e-300..=1e300).contains(&m);
        let s = if by_inverse {
            direction * inv
        } else {
            direction / m
        };
        // Every point of the box is within `E = max |corner − origin|∞` of
        // the origin, and `|s|∞ = 1`: the ray leaves the box by `τ = E`.
        let far = (hi - origin).max(origin - lo).max_element();
        let reach = 2.0 * far.max(origin.abs().max_element());
        if reach.is_nan() || reach <= 0.0 {
            return None;
        }
        let x = origin + s * reach;
        if !x.is_finite() {
            return None;
        }
        let d = x - origin;
        Some(Probe {
            o: origin,
            x,
            d,
            d_norm: d.abs().max_element(),
            scale: if by_inverse { reach * inv } else { reach / m },
        })
    }

    /// The ordered, culling traversal of [`Bvh::closest_hit`].
    #[inline(always)]
    fn closest_in_tree(&self, probe: &Probe, ray: &Ray32, best: &mut Best) {
        let mut limit = 1.0f32;
        if best.t_max < f64::INFINITY {
            // Every counted crossing has `u · scale ≤ t_max`.
            limit = limit.min(f32_up(best.t_max / probe.scale * (1.0 + U_SLACK)));
        }
        if best.id != u32::MAX {
            limit = limit.min(f32_up(best.u));
        }
        // Only the stack the tree needs is cleared (most rays of small
        // scenes visit a node or two: clearing 512 bytes showed).
        let (mut small, mut medium, mut large);
        let stack: &mut [(u32, f32)] = if self.stack_need() <= STACK / 2 {
            small = [(0u32, 0.0f32); STACK / 2];
            &mut small
        } else if self.stack_need() <= STACK {
            medium = [(0u32, 0.0f32); STACK];
            &mut medium
        } else {
            large = vec![(0, 0.0); self.stack_need()];
            &mut large
        };
        let mut top = 0;
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            let (mask, near) = ray.slab(n, limit);
            // The kept lanes by entry (entries are `≥ 0`, so their bits
            // order as integers; the lane rides in the two low bits).
            let mut keys = [u32::MAX; WIDTH];
            let mut count = 0;
            let mut rest = mask;
            while rest != 0 {
                let lane = rest.trailing_zeros();
                rest &= rest - 1;
                let mut key = (near[lane as usize].to_bits() & !3) | lane;
                let mut k = count;
                while k > 0 && keys[k - 1] > key {
                    (keys[k], key) = (keys[k - 1], key);
                    k -= 1;
                }
                keys[k] = key;
                count += 1;
            }
            let mut inner = [(0u32, 0.0f32); WIDTH];
            let mut inner_count = 0;
            for &key in &keys[..count] {
                let lane = (key & 3) as usize;
                let child = n.child[lane];
                if child & LEAF == 0 {
                    inner[inner_count] = (child, near[lane]);
                    inner_count += 1;
                } else if near[lane] <= limit * T_SLACK {
                    let i = (child & !LEAF) as usize;
                    if best.offer(probe.crossing(&self.triangles[i]), self.ids[i]) {
                        limit = limit.min(f32_up(best.u));
                    }
                }
            }
            // Farthest first, so that the nearest is popped next.
            for &entry in inner[..inner_count].iter().rev() {
                stack[top] = entry;
                top += 1;
            }
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (child, entry) = stack[top];
                if entry <= limit * T_SLACK {
                    node = child;
                    break;
                }
            }
        }
    }
}

/// The segment a closest-hit query decides on (see [`Bvh::ray_segment`]).
struct Probe {
    o: DVec3,
    /// The far point.
    x: DVec3,
    /// `x − o`, rounded, and its max-norm.
    d: DVec3,
    d_norm: f64,
    /// The ray parameter of `x`: a crossing at `u` is the hit `u · scale`.
    scale: f64,
}

impl Probe {
    #[inline(always)]
    fn crossing(&self, t: &[DVec3; 3]) -> Option<f64> {
        crossing(self.o, self.x, self.d, self.d_norm, t)
    }
}

/// The best crossing so far of a closest-hit query.
struct Best {
    /// Segment parameter (`∞`: none yet) and occluder index (`u32::MAX`).
    u: f64,
    id: u32,
    scale: f64,
    t_max: f64,
}

impl Best {
    /// Takes the crossing `u` of occluder `id` if it is the least `(u, id)`
    /// so far and its `t` is within `t_max`; whether it did.
    #[inline(always)]
    fn offer(&mut self, u: Option<f64>, id: u32) -> bool {
        match u {
            Some(u)
                if (u < self.u || (u == self.u && id < self.id))
                    && u * self.scale <= self.t_max =>
            {
                self.u = u;
                self.id = id;
                true
            }
            _ => false,
        }
    }
}
