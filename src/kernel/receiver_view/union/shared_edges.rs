//! The table of the triangles' directed edges that finds an edge's reverse.

use super::sides::Side;
use super::tri::Tri;
use glam::DVec2;

/// The triangles' distinct directed edges, hashed by their ends, to find
/// an edge's reverse: two counter-clockwise triangles with an edge `a → b`
/// and `b → a` lie on its two sides, so the edge is covered whole and
/// neither keeps any of it. The search would find that too (the other
/// triangle's span is the whole edge); on a mesh's images, where most
/// edges are shared, finding it here is what saves the search.
#[derive(Debug, Default)]
pub(super) struct Edges {
    /// Open addressing, linear probing: `3 i + k` for edge `k` of triangle
    /// `i`, the first with its ends (copies of an edge — images cut by the
    /// same corner of the clip square, copies of a triangle — are one
    /// entry, so that a probe never walks past them), [`Edges::EMPTY`] for
    /// a free slot. Empty when there are fewer than [`Edges::FEWEST`]
    /// triangles or more than [`Edges::MOST`].
    pub(super) slots: Vec<u32>,
    /// `64 −` the number of index bits.
    shift: u32,
}

impl Edges {
    pub(super) const EMPTY: u32 = u32::MAX;

    /// The most triangles the table is built for (a bound on its memory:
    /// 32 MiB of slots at most): a convex polygon given as a fan of 10⁵
    /// slivers, every inner edge shared, needs it, or each of its edges
    /// goes to the search (`examples/union_depth.rs`, `one fan0 100000`).
    const MOST: usize = 1 << 20;

    /// The fewest triangles the table is built for: below, the search is
    /// short, and the table costs more than it saves where no edge is
    /// shared (16 random images).
    pub(super) const FEWEST: usize = 32;

    /// The table of `tris`' edges, but for those on a side of the clip
    /// square (`half` its half-width), whose reverse no triangle in the
    /// square can have (a side edge's reverse would lie on the side too:
    /// left out, so never found).
    #[inline(always)]
    pub(super) fn build(&mut self, tris: &[Tri], half: f64) {
        self.slots.clear();
        if !(Edges::FEWEST..=Edges::MOST).contains(&tris.len()) {
            return;
        }
        let bits = (6 * tris.len()).next_power_of_two().trailing_zeros();
        self.shift = 64 - bits;
        self.slots.resize(1 << bits, Edges::EMPTY);
        for (t, i) in tris.iter().zip(0_u32..) {
            for k in 0..3 {
                let (a, b) = t.edge(k);
                if Side::of(a, b, half).is_some() {
                    continue;
                }
                if let Err(s) = self.probe(tris, a, b) {
                    self.slots[s] = 3 * i + k as u32;
                }
            }
        }
    }

    /// The slot holding the edge `a → b` (`Ok`), or else the free slot the
    /// probe ends at, where it would go (`Err`). The table is not empty.
    fn probe(&self, tris: &[Tri], a: DVec2, b: DVec2) -> Result<usize, usize> {
        let mask = self.slots.len() - 1;
        let mut s = self.slot(a, b);
        loop {
            let e = self.slots[s];
            if e == Edges::EMPTY {
                return Err(s);
            }
            if tris[(e / 3) as usize].edge((e % 3) as usize) == (a, b) {
                return Ok(s);
            }
            s = (s + 1) & mask;
        }
    }

    /// The first slot to probe for the edge `a → b`: each end's bits
    /// (`0.0` and `−0.0` alike) multiplied up, which carries a difference
    /// in the last bits (images of shifted copies) into the high ones, the
    /// two ends combined in order and multiplied again; the slot is the
    /// top bits. Three independent products, then one.
    fn slot(&self, a: DVec2, b: DVec2) -> usize {
        const K: [u64; 3] = [
            0x9e37_79b9_7f4a_7c15,
            0xbf58_476d_1ce4_e5b9,
            0x94d0_49bb_1331_11eb,
        ];
        let end = |v: DVec2| {
            (v.x + 0.0).to_bits().wrapping_mul(K[0]) ^ (v.y + 0.0).to_bits().wrapping_mul(K[1])
        };
        let h = end(a).rotate_left(29) ^ end(b);
        ((h ^ h >> 31).wrapping_mul(K[2]) >> self.shift) as usize
    }

    /// Whether some triangle of `tris` (those of the last
    /// [`Edges::build`]) has the edge `b → a`.
    pub(super) fn has_reverse(&self, tris: &[Tri], a: DVec2, b: DVec2) -> bool {
        !self.slots.is_empty() && self.probe(tris, b, a).is_ok()
    }
}
