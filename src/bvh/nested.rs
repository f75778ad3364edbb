//! Runs of nested boxes, indexed by obvhs as one box each.
//!
//! PLOC merges the pairs of clusters that are each other's best neighbour
//! in Morton order, the best being the one whose merged box is smallest.
//! Among nested boxes every smaller neighbour ties (the merged box is the
//! larger one), so almost no pair agrees and each pass merges one pair:
//! `n` nested triangles took `n` passes (10⁴ about one centre: 3.1 s,
//! quadratic; obvhs's reinsertion passes after it were quadratic too, the
//! tree being a chain — ours, `reinsert.rs`, are bounded). Feeding PLOC points instead of boxes did not help
//! (near-coincident centres chain the same way, measured).
//!
//! So before PLOC, the boxes are put in Morton order of their centres and
//! every run of at least [`MIN_RUN`] consecutive boxes each of which
//! contains, or lies in, the one before it — or nearly: their union is
//! within [`NEARLY`] of the larger one's area, as for parallel layers
//! stacked closely, on which PLOC chains the same way (10⁴ layers 10⁻⁴
//! apart: 2.9 s) — becomes a *group*: PLOC sees the group as one box
//! (their union), and the collapse into our 4-wide tree splits the group's
//! members — sorted by area, smallest first, equal areas in Morton order —
//! in halves, a balanced subtree whose smaller half has the smaller box.
//! Every triangle is still in the tree exactly once; only the shape
//! changes.
//! Where no run is that long (every built-in scene, and ordinary meshes,
//! where two triangles of one quad share a box but a third does not), the
//! boxes PLOC sees are the input's, in the input's order: the same tree as
//! without this pass.

use obvhs::aabb::Aabb;

/// The shortest run of nested boxes taken as a group (ours). Shorter runs
/// cost PLOC little; a group gives up PLOC's choice of shape inside it.
pub(super) const MIN_RUN: usize = 16;

/// The boxes PLOC is given, each standing for a range of [`Groups::order`].
pub(super) struct Groups {
    /// The input boxes' indices, each group's members contiguous.
    pub order: Vec<u32>,
    /// Per box given to PLOC: its first slot in `order` and its count.
    pub ranges: Vec<(u32, u32)>,
    /// Per box given to PLOC: the union of its members' boxes.
    pub boxes: Vec<Aabb>,
}

impl Groups {
    /// The groups of `boxes` (see the module docs); `None` when there are
    /// none, and PLOC takes `boxes` as they are.
    pub(super) fn find(boxes: &[Aabb]) -> Option<Groups> {
        let n = boxes.len();
        if n < MIN_RUN {
            return None;
        }
        // Morton order of the centres, 21 bits per axis over their bounds;
        // ties by input index, so that the order is deterministic.
        let (lo, hi) = boxes.iter().fold(
            (
                glam::Vec3A::splat(f32::INFINITY),
                glam::Vec3A::splat(f32::NEG_INFINITY),
            ),
            |(lo, hi), b| (lo.min(b.center()), hi.max(b.center())),
        );
        let extent = (hi - lo).max(glam::Vec3A::splat(f32::MIN_POSITIVE));
        let cells = ((1u32 << 21) - 1) as f32;
        let mut sorted: Vec<(u64, u32)> = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let q = ((b.center() - lo) / extent * cells)
                    .clamp(glam::Vec3A::ZERO, glam::Vec3A::splat(cells));
                (morton(q.x as u32, q.y as u32, q.z as u32), i as u32)
            })
            .collect();
        sorted.sort_unstable();
        // Each input box's group (its run's index), or none.
        let mut group_of = vec![u32::MAX; n];
        let mut runs: Vec<Vec<u32>> = Vec::new();
        let mut start = 0;
        while start < n {
            let mut end = start + 1;
            while end < n
                && nested(
                    &boxes[sorted[end - 1].1 as usize],
                    &boxes[sorted[end].1 as usize],
                )
            {
                end += 1;
            }
            if end - start >= MIN_RUN {
                // By area, smallest first; equal areas (a stack of
                // parallel layers) in Morton order, so that the halves are
                // the stack's halves.
                let mut members: Vec<u32> = sorted[start..end].iter().map(|&(_, i)| i).collect();
                members.sort_by(|&a, &b| {
                    let area = |i: u32| boxes[i as usize].half_area();
                    area(a).total_cmp(&area(b))
                });
                for &m in &members {
                    group_of[m as usize] = runs.len() as u32;
                }
                runs.push(members);
            }
            start = end;
        }
        if runs.is_empty() {
            return None;
        }
        // In input order, each group where its first member (by index) is.
        let mut groups = Groups {
            order: Vec::with_capacity(n),
            ranges: Vec::new(),
            boxes: Vec::new(),
        };
        let mut placed = vec![false; runs.len()];
        for (i, &g) in group_of.iter().enumerate() {
            let members: &[u32] = if g == u32::MAX {
                &[i as u32]
            } else if !placed[g as usize] {
                placed[g as usize] = true;
                &runs[g as usize]
            } else {
                continue;
            };
            groups
                .ranges
                .push((groups.order.len() as u32, members.len() as u32));
            groups.boxes.push(
                members
                    .iter()
                    .fold(Aabb::empty(), |b, &m| b.union(&boxes[m as usize])),
            );
            groups.order.extend_from_slice(members);
        }
        Some(groups)
    }

    /// No groups: every box stands for itself.
    pub(super) fn identity(boxes: &[Aabb]) -> Groups {
        Groups {
            order: (0..boxes.len() as u32).collect(),
            ranges: (0..boxes.len() as u32).map(|i| (i, 1)).collect(),
            boxes: boxes.to_vec(),
        }
    }
}

/// One of `a`, `b` contains the other (closed boxes), or nearly: their
/// union's area exceeds the larger one's by at most [`NEARLY`] of it
/// (near-coincident boxes, and the flat boxes of parallel layers stacked
/// closely, on which PLOC chains as on nested ones).
fn nested(a: &Aabb, b: &Aabb) -> bool {
    let within = |x: &Aabb, y: &Aabb| x.min.cmpge(y.min).all() && x.max.cmple(y.max).all();
    if within(a, b) || within(b, a) {
        return true;
    }
    let larger = a.half_area().max(b.half_area());
    a.union(b).half_area() - larger <= NEARLY * larger
}

/// How much a run's next box may grow the larger one's area and still be
/// taken as nested with it (ours: ordinary meshes' neighbours in Morton
/// order grow it by about their own size).
const NEARLY: f32 = 1e-3;

/// The Morton code of a cell with 21-bit coordinates.
fn morton(x: u32, y: u32, z: u32) -> u64 {
    fn spread(v: u32) -> u64 {
        let mut v = u64::from(v) & 0x1f_ffff;
        v = (v | v << 32) & 0x1f_0000_0000_ffff;
        v = (v | v << 16) & 0x1f_0000_ff00_00ff;
        v = (v | v << 8) & 0x100f_00f0_0f00_f00f;
        v = (v | v << 4) & 0x10c3_0c30_c30c_30c3;
        v = (v | v << 2) & 0x1249_2492_4924_9249;
        v
    }
    spread(x) | spread(y) << 1 | spread(z) << 2
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    #[test]
    fn morton_interleaves_bits() {
        assert_eq!(morton(1, 0, 0), 1);
        assert_eq!(morton(0, 1, 0), 2);
        assert_eq!(morton(0, 0, 1), 4);
        assert_eq!(morton(2, 0, 0), 8);
        let top = (1 << 21) - 1;
        assert_eq!(morton(top, top, top), (1u64 << 63) - 1);
    }

    #[test]
    fn a_nested_run_is_one_group_and_every_box_stays() {
        // 40 nested boxes about one centre, shuffled, and 10 apart.
        let mut boxes: Vec<Aabb> = (0..40)
            .map(|k| {
                let h = 1.0 + (k * 17 % 40) as f32;
                Aabb::new(Vec3A::splat(-h), Vec3A::splat(h))
            })
            .collect();
        boxes.extend((0..10).map(|k| {
            let c = Vec3A::new(100.0 + 3.0 * k as f32, 0.0, 0.0);
            Aabb::new(c - 0.5, c + 0.5)
        }));
        let g = Groups::find(&boxes).expect("a group");
        let mut all = g.order.clone();
        all.sort_unstable();
        assert_eq!(all, (0..50).collect::<Vec<u32>>());
        assert_eq!(g.ranges.len(), 11);
        let (first, count) = g.ranges[0];
        assert_eq!(count, 40);
        let members = &g.order[first as usize..(first + count) as usize];
        assert!(members
            .windows(2)
            .all(|w| boxes[w[0] as usize].half_area() <= boxes[w[1] as usize].half_area()));
        assert_eq!(
            g.boxes[0],
            Aabb::new(Vec3A::splat(-40.0), Vec3A::splat(40.0))
        );
        // The disjoint boxes stand for themselves, in input order.
        assert!(g.ranges[1..].iter().all(|&(_, c)| c == 1));
        assert_eq!(g.order[40..], (40..50).collect::<Vec<u32>>()[..]);
    }

    #[test]
    fn stacked_flat_layers_are_one_group_in_stack_order() {
        // 64 flat boxes 1e-4 apart in y, shuffled, and 10 apart.
        let n = 64;
        let layer = |k: usize| {
            let y = 1.0 + 1e-4 * k as f32;
            Aabb::new(Vec3A::new(-1.0, y, -1.0), Vec3A::new(1.0, y, 1.0))
        };
        let mut boxes: Vec<Aabb> = (0..n).map(|k| layer(k * 37 % n)).collect();
        boxes.extend((0..10).map(|k| {
            let c = Vec3A::new(100.0 + 3.0 * k as f32, 0.0, 0.0);
            Aabb::new(c - 0.5, c + 0.5)
        }));
        let g = Groups::find(&boxes).expect("a group");
        assert_eq!(g.ranges.len(), 11);
        let (first, count) = g.ranges[0];
        assert_eq!(count as usize, n);
        // Equal areas: bottom to top, so that halves are the stack's.
        let members = &g.order[first as usize..(first + count) as usize];
        assert!(members
            .windows(2)
            .all(|w| boxes[w[0] as usize].min.y < boxes[w[1] as usize].min.y));
        // Boxes merely near each other are not nested.
        assert!(!nested(
            &layer(0),
            &Aabb::new(Vec3A::new(-1.0, 1.0, -0.9), Vec3A::new(1.0, 1.0, 1.1))
        ));
    }

    #[test]
    fn short_runs_leave_the_input_as_it_is() {
        // Pairs of equal boxes (two triangles of one quad), in a row.
        let boxes: Vec<Aabb> = (0..64)
            .map(|k| {
                let c = Vec3A::new((k / 2) as f32, 0.0, 0.0);
                Aabb::new(c, c + Vec3A::new(1.0, 0.0, 1.0))
            })
            .collect();
        assert!(Groups::find(&boxes).is_none());
    }
}
