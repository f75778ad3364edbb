//! A hierarchy of bounding boxes over the union's triangles, searched per
//! edge with the edge's cover so far: a subtree is left out where the part
//! of the edge inside its box is covered already, so that an edge meets the
//! triangles near its uncovered parts, not every triangle that overlaps it.
//!
//! Each node keeps the largest triangle of its subtree as its own (tested
//! when the node is visited, before its children): under a deep pile an
//! edge is most often covered whole by a large triangle, and under nested
//! or stacked images by the largest, which the root holds.
//!
//! Leaving a subtree out changes no span of the union: every span a
//! triangle gives an edge has its points within `2⁻³⁴` of the clip
//! square's half-width of the triangle's bounds (a span that is not is
//! none: see [`credible`](super::span::credible)); the edge's part
//! in a node's box is taken with the box grown by `10⁻⁹` of the half-width,
//! far above that and above the rounding of the clip (see [`Ray::range`]).
//! So the spans of a subtree left out lie inside the cover already found,
//! and the union of the spans — hence every piece and every bit of the
//! area — is that of testing every triangle.

use super::tri::Tri;
use glam::DVec2;

/// The most triangles a leaf holds.
const LEAF: usize = 4;

/// A node: the bounds of every triangle below it, its own triangles
/// (`items[first..first + own]`: the subtree's largest for an inner node,
/// all of a leaf's), and its children (`u32::MAX` for none).
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: DVec2,
    hi: DVec2,
    first: u32,
    own: u32,
    children: [u32; 2],
}

/// The hierarchy ([module documentation](self)).
#[derive(Debug, Default)]
pub(super) struct Tree {
    nodes: Vec<Node>,
    items: Vec<u32>,
    /// The search's stack: a node and the edge's parameter range in it.
    stack: Vec<(u32, f64, f64)>,
    /// Grows the boxes for the search (`10⁻⁹` of the half-width).
    grow: f64,
    /// The triangles while the tree is built.
    entries: Vec<Entry>,
}

/// A triangle while the tree is built: its bounds, doubled area and index.
#[derive(Clone, Copy, Debug)]
struct Entry {
    lo: DVec2,
    hi: DVec2,
    area: f64,
    index: u32,
}

impl Tree {
    /// Builds the hierarchy over `tris` (`half` the clip square's
    /// half-width): median splits of the bounds' centres along the longer
    /// axis of the node's bounds, each node promoting its subtree's largest
    /// triangle.
    pub(super) fn build(&mut self, tris: &[Tri], half: f64) {
        self.nodes.clear();
        self.items.clear();
        self.grow = 1e-9 * half;
        self.entries.clear();
        self.entries
            .extend(tris.iter().zip(0_u32..).map(|(t, index)| Entry {
                lo: t.lo,
                hi: t.hi,
                area: t.doubled_area(),
                index,
            }));
        if tris.is_empty() {
            return;
        }
        let n = self.entries.len();
        self.split(0, n);
        self.items.extend(self.entries.iter().map(|e| e.index));
    }

    /// Builds the node over `entries[start..end]` (not empty); its index.
    fn split(&mut self, start: usize, end: usize) -> u32 {
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(-f64::INFINITY));
        let mut largest = (f64::NEG_INFINITY, start);
        for (k, e) in self.entries[start..end].iter().enumerate() {
            (lo, hi) = (lo.min(e.lo), hi.max(e.hi));
            if e.area > largest.0 {
                largest = (e.area, start + k);
            }
        }
        let index = self.nodes.len() as u32;
        let own = if end - start <= LEAF { end - start } else { 1 };
        self.nodes.push(Node {
            lo,
            hi,
            first: start as u32,
            own: own as u32,
            children: [u32::MAX; 2],
        });
        if own == end - start {
            return index;
        }
        self.entries.swap(start, largest.1);
        let (from, mid) = (start + 1, start + 1 + (end - start - 1) / 2);
        let axis = usize::from(hi.y - lo.y > hi.x - lo.x);
        let centre = |e: &Entry| e.lo[axis] + e.hi[axis];
        self.entries[from..end]
            .select_nth_unstable_by(mid - from, |x, y| centre(x).total_cmp(&centre(y)));
        let left = self.split(from, mid);
        let right = self.split(mid, end);
        self.nodes[index as usize].children = [left, right];
        index
    }

    /// Calls `test` with every triangle whose box the edge `ray` meets,
    /// larger parts of the edge first, and takes the span it returns into
    /// `spans`, except in subtrees where the edge's part in the box (a
    /// parameter range) lies within `spans` already; ends when `spans`
    /// covers the edge whole, and says whether it does.
    #[inline(always)]
    pub(super) fn search(
        &mut self,
        ray: &Ray,
        spans: &mut Spans,
        mut test: impl FnMut(u32) -> Option<(f64, f64)>,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        self.stack.clear();
        let root = &self.nodes[0];
        if let Some((u0, u1)) = ray.range(root.lo, root.hi, self.grow) {
            self.stack.push((0, u0, u1));
        }
        while let Some((k, u0, u1)) = self.stack.pop() {
            if spans.contains(u0, u1) {
                continue;
            }
            let node = self.nodes[k as usize];
            let own = node.first as usize..(node.first + node.own) as usize;
            for &j in &self.items[own] {
                if let Some(span) = test(j) {
                    if spans.add(span) {
                        return true;
                    }
                }
            }
            if node.children[0] == u32::MAX {
                continue;
            }
            let mut next = [None; 2];
            for (slot, &c) in next.iter_mut().zip(&node.children) {
                let child = &self.nodes[c as usize];
                *slot = ray
                    .range(child.lo, child.hi, self.grow)
                    .filter(|&(v0, v1)| !spans.contains(v0, v1))
                    .map(|(v0, v1)| (c, v0, v1));
            }
            // The longer part last, to be searched first.
            if let (Some(x), Some(y)) = (next[0], next[1]) {
                if x.2 - x.1 > y.2 - y.1 {
                    next = [Some(y), Some(x)];
                }
            }
            self.stack.extend(next.into_iter().flatten());
        }
        false
    }
}

/// An edge `a → b` as a parametric segment `a + u (b − a)`, `u ∈ [0, 1]`,
/// for clipping to boxes.
pub(super) struct Ray {
    a: DVec2,
    d: DVec2,
    inv: DVec2,
}

impl Ray {
    pub(super) fn new(a: DVec2, b: DVec2) -> Ray {
        let d = b - a;
        Ray {
            a,
            d,
            inv: DVec2::ONE / d,
        }
    }

    /// The parameters of the edge's points in the box `lo..hi` grown by
    /// `grow` on every side, as an interval within `[0, 1]`, or `None`.
    /// Where a coordinate of the direction is zero the edge is in the slab
    /// or not; else the slab's ends `(lo − grow − a) / d` and `(hi + grow −
    /// a) / d` are rounded by a few units in the last place of `(|lo| +
    /// |a| + grow) / |d|`, far below the `grow / |d|` the box was grown by
    /// (`grow` being `10⁻⁹` of the half-width that bounds every
    /// coordinate): a point of the edge within `grow / 2` of the box has
    /// its parameter inside the interval.
    #[inline(always)]
    pub(super) fn range(&self, lo: DVec2, hi: DVec2, grow: f64) -> Option<(f64, f64)> {
        let (mut u0, mut u1) = (0.0_f64, 1.0_f64);
        for axis in 0..2 {
            let (l, h) = (lo[axis] - grow, hi[axis] + grow);
            let (a, d) = (self.a[axis], self.d[axis]);
            if d == 0.0 {
                if a < l || a > h {
                    return None;
                }
            } else {
                let inv = self.inv[axis];
                let (t0, t1) = ((l - a) * inv, (h - a) * inv);
                let (t0, t1) = if d > 0.0 { (t0, t1) } else { (t1, t0) };
                u0 = u0.max(t0);
                u1 = u1.min(t1);
            }
        }
        (u0 <= u1).then_some((u0, u1))
    }
}

/// The union of closed parameter intervals of an edge found so far:
/// disjoint, in order, those that overlap or touch merged.
#[derive(Debug, Default)]
pub(super) struct Spans {
    pub(super) list: Vec<(f64, f64)>,
}

impl Spans {
    pub(super) fn clear(&mut self) {
        self.list.clear();
    }

    /// Whether `[u0, u1]` lies within one interval.
    #[inline(always)]
    pub(super) fn contains(&self, u0: f64, u1: f64) -> bool {
        // The last interval starting at or before `u0`.
        let k = self.list.partition_point(|&(s, _)| s <= u0);
        k > 0 && self.list[k - 1].1 >= u1
    }

    /// Takes in `[s, e]`; whether the intervals now cover `[0, 1]`.
    #[inline(never)]
    pub(super) fn add(&mut self, (s, e): (f64, f64)) -> bool {
        // The intervals from the first that ends at or after `s` to the
        // last that starts at or before `e` merge with it.
        let first = self.list.partition_point(|&(_, end)| end < s);
        let last = self.list.partition_point(|&(start, _)| start <= e);
        if first == last {
            self.list.insert(first, (s, e));
        } else {
            let merged = (s.min(self.list[first].0), e.max(self.list[last - 1].1));
            self.list[first] = merged;
            self.list.drain(first + 1..last);
        }
        self.list[0].0 <= 0.0 && self.list[0].1 >= 1.0
    }
}
