//! The node of the 4-wide tree: four child boxes quantised outward to 8
//! bits per plane, and the decoding the build and the traversals share.

/// Children per node of our tree.
pub(super) const WIDTH: usize = 4;
/// `child` of an empty lane.
pub(super) const EMPTY: u32 = u32::MAX;

/// A node of the 4-wide tree, one 64-byte cache line: the four child boxes
/// quantised to 8 bits per plane on a per-axis power-of-two grid (the
/// compressed wide nodes of Ylitie, Karras and Laine, "Efficient
/// Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", 2017),
/// in structure-of-arrays form (the slab test runs over the four lanes at
/// once).
///
/// A plane decodes to [`decode`]`(origin, q, scale)`, one `f32` product (exact:
/// `q < 2⁸`, `scale` a power of two) and one rounded sum; the build chooses
/// each `q` by evaluating that very expression, so the decoded box contains
/// the child's `f32` box — rounding included, the traversal computes the
/// same bits.
#[derive(Clone, Copy)]
#[repr(C, align(64))]
pub(super) struct Node {
    /// Per axis: the grid's origin (the least child minimum).
    pub(super) origin: [f32; 3],
    /// Per axis: the grid step, a power of two `2ᵉ`, `e ∈ [−126, 127]`.
    pub(super) scale: [f32; 3],
    /// `q[side][axis][lane]`: quantised box minima (`side` 0; each decodes
    /// to at most the `f32` minimum) and maxima (`side` 1; at least the
    /// maximum).
    pub(super) q: [[[u8; WIDTH]; 3]; 2],
    /// Inner child: its node index. Leaf: [`LEAF`] `|` its triangle's index
    /// in `Bvh::triangles`. Empty lane: [`EMPTY`].
    pub(super) child: [u32; WIDTH],
}

/// The flag of a leaf in [`Node::child`].
pub(super) const LEAF: u32 = 1 << 31;

/// A decoded plane: `origin + q · scale`. The one definition the build and
/// the traversal share, so both round alike (Rust never contracts to FMA).
#[inline(always)]
pub(super) fn decode(origin: f32, q: u8, scale: f32) -> f32 {
    origin + f32::from(q) * scale
}

impl Node {
    pub(super) const EMPTY_NODE: Node = Node {
        origin: [0.0; 3],
        scale: [1.0; 3],
        q: [[[0; WIDTH]; 3]; 2],
        child: [EMPTY; WIDTH],
    };

    /// Quantises `boxes` (at most [`WIDTH`]; `f32` boxes with `lo ≤ hi`,
    /// finite) into lanes `0..boxes.len()`, conservatively (see [`Node`]).
    pub(super) fn quantised(boxes: &[([f32; 3], [f32; 3])]) -> Node {
        let mut node = Node::EMPTY_NODE;
        for axis in 0..3 {
            let origin = boxes
                .iter()
                .map(|b| b.0[axis])
                .fold(f32::INFINITY, f32::min);
            let top = boxes
                .iter()
                .map(|b| b.1[axis])
                .fold(f32::NEG_INFINITY, f32::max);
            let extent = f64::from(top) - f64::from(origin);
            let guess = (extent / 255.0).log2().ceil();
            let mut e = if guess.is_finite() {
                guess as i32
            } else {
                -126
            }
            .clamp(-126, 127);
            // `decode(origin, 255, 2¹²⁷)` is `+∞`: the loop ends.
            while decode(origin, 255, pow2(e)) < top {
                e += 1;
            }
            let scale = pow2(e);
            node.origin[axis] = origin;
            node.scale[axis] = scale;
            for (lane, b) in boxes.iter().enumerate() {
                // `decode` is nondecreasing in `q`; `decode(·, 0, ·)` is
                // `origin ≤ lo` and `decode(·, 255, ·) ≥ top ≥ hi`.
                let (lo, hi) = (b.0[axis], b.1[axis]);
                let fit = |q: f64| q.clamp(0.0, 255.0) as u8;
                let mut q = fit(((f64::from(lo) - f64::from(origin)) / f64::from(scale)).floor());
                while q > 0 && decode(origin, q, scale) > lo {
                    q -= 1;
                }
                while q < 255 && decode(origin, q + 1, scale) <= lo {
                    q += 1;
                }
                node.q[0][axis][lane] = q;
                let mut q = fit(((f64::from(hi) - f64::from(origin)) / f64::from(scale)).ceil());
                while q < 255 && decode(origin, q, scale) < hi {
                    q += 1;
                }
                while q > 0 && decode(origin, q - 1, scale) >= hi {
                    q -= 1;
                }
                node.q[1][axis][lane] = q;
            }
        }
        node
    }

    /// The decoded planes of every lane on side `side` (0 the minima, 1
    /// the maxima): `[axis][lane]`.
    #[inline(always)]
    pub(super) fn planes(&self, side: usize) -> [[f64; WIDTH]; 3] {
        core::array::from_fn(|axis| {
            core::array::from_fn(|lane| {
                f64::from(decode(
                    self.origin[axis],
                    self.q[side][axis][lane],
                    self.scale[axis],
                ))
            })
        })
    }

    /// The decoded box of `lane`: `(lo, hi)`.
    #[cfg(test)]
    pub(super) fn lane_box(&self, lane: usize) -> (glam::DVec3, glam::DVec3) {
        let [lo, hi] = [0, 1].map(|side| {
            let p = self.planes(side);
            glam::DVec3::new(p[0][lane], p[1][lane], p[2][lane])
        });
        (lo, hi)
    }
}

/// `2ᵉ` for `e ∈ [−126, 127]` (normal `f32`).
fn pow2(e: i32) -> f32 {
    f32::from_bits(((e + 127) as u32) << 23)
}
