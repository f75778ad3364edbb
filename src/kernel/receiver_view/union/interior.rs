//! The raster of the cells inside some triangle, under a deep pile.

use super::grid::{cell_of, Grid};
use super::tri::Tri;
use glam::DVec2;

/// Under a deep pile of small images (at least [`Interior::FEWEST`]
/// triangles, their areas summing to at least [`Interior::DEPTH`] times
/// their common bounds, their mean width within [`Grid::LARGE`] cells of
/// the fine grid), a raster over the square `[−half, half]²` of the cells
/// that lie inside some triangle with a margin: an edge whose every point
/// is in such a cell is covered whole, and is dropped before any search
/// ([`Interior::covers`]).
///
/// That is the search's own answer, so the area is the same bit for bit. A
/// marked cell is closed and lies at least `μ = 2⁻²⁰ w / √2` (`w` the
/// cell's width) inside each edge line of some triangle `j`, and `j` is not
/// the searched edge's own (whose points are on its boundary). So every
/// point of the edge is at least `μ` inside a triangle whose bounds meet
/// the edge's, which the search tests: the span it finds contains that
/// point's parameter with `μ / |b − a|` to spare on either side (at least
/// `2⁻³¹` of the parameter range, the square's diagonal being `2.9 half`
/// and the cells at least `half / 512` wide), against a few units in the
/// last place of rounding in the span's ends. The spans then overlap and
/// cover `[0, 1]`, and the search ends with no piece on the boundary.
///
/// The arithmetic that marks a cell and walks an edge is rounded, and
/// its errors are absorbed by margins at least `2¹⁸` times wider. A cell
/// must be `2⁻²⁰ w` inside (in the edge function, `2⁻²⁰ w |d|∞`, `d` the
/// edge's direction): along a row, where the edge's line crosses it moved
/// by `2⁻²⁰ |d|∞ / |d.y| ≥ 2⁻²¹ (1 + |β|)` cells, `β = d.x / d.y`. That
/// crossing is computed as `α + β r` cells in row `r`, with an error of a
/// few units in the last place of `(1 + |β|) n`, at most `2⁻³⁹ (1 + |β|)`
/// cells (`n ≤ 1024` cells a side). A walk takes every cell within `10⁻⁶
/// (1 + |s|)` cells of the edge's computed course (`s` the slope against
/// `y`, which multiplies the error in a row's `y`), against errors of a few
/// units in the last place of `half` or of the cell index, about `2⁻⁴²` of
/// a cell.
///
/// The walk goes a row of blocks at a time ([`Interior::course_covered`];
/// blocks of [`Interior::BLOCK`] cells a side, those all marked listed in
/// [`Interior::full`]): where every block along the course in a row of
/// blocks is all marked, so is every cell the walk over the cells would
/// take in those rows, and that walk is left out of them.
///
/// Built only under deep piles, where it pays: the thresholds were chosen
/// by measurement (see benches/README.md § The union's constants and its
/// two copies of the loop, which has the counts and times).
#[derive(Debug, Default)]
pub(super) struct Interior {
    /// Cells a side, a multiple of 64 (0: not built).
    pub(super) n: usize,
    half: f64,
    /// The cells' width, and its inverse.
    pub(super) w: f64,
    inv_w: f64,
    /// Row-major, `n / 64` words a row: bit `k % 64` of word `k / 64` of
    /// row `r` for the cell `[−half + k w, −half + (k + 1) w] × [−half +
    /// r w, −half + (r + 1) w]`.
    bits: Vec<u64>,
    /// The blocks of [`Interior::BLOCK`] cells a side all marked, in the
    /// same layout: `n / BLOCK` blocks a side, a row's bits in whole words.
    full: Vec<u64>,
    /// Words a row of [`Interior::full`].
    block_words: usize,
    /// How many triangles the last build left out, their cells marked
    /// already.
    pub(super) skipped: usize,
    /// Which ones (bit `i % 64` of word `i / 64` for the triangle `i`),
    /// where any were.
    left_out: Vec<u64>,
    /// The triangles by decreasing area (a key and the index), the order
    /// they are marked in.
    order: Vec<(u64, u32)>,
}

impl Interior {
    /// The fewest triangles the raster is built for.
    pub(super) const FEWEST: usize = 256;

    /// The least depth (summed area over the area of the common bounds)
    /// it is built for (ours, chosen by measurement: see benches/README.md
    /// § The union's constants and its two copies of the loop).
    const DEPTH: f64 = 2.5;

    /// Cells across the mean width of a triangle's bounds: finer cells drop
    /// more edges but cost more to mark and walk (ours, chosen by
    /// measurement: see benches/README.md § The union's constants and its
    /// two copies of the loop).
    const ACROSS: f64 = 32.0;

    /// The most cells a side.
    const MOST: usize = 1024;

    /// The estimated depth of the triangles marked so far (larger ones
    /// first) from which a triangle whose bounds' cells are all marked
    /// already is left out: testing its bounds costs a few instructions a
    /// row against tens for marking it, and a triangle left out takes no
    /// part in the union's walk and grid either ([`Interior::left_out`]):
    /// it pays where the pile is deep enough that many bounds lie in
    /// marked cells (ours, chosen by measurement: see benches/README.md
    /// § The union's search).
    const SKIP_DEPTH: f64 = 1.0;

    /// Cells a side of a block ([`Interior::full`]), a power of two below 64.
    pub(super) const BLOCK: usize = 8;

    /// The triangles the depth is estimated from (ours, chosen by
    /// measurement: see benches/README.md § The union's constants and its
    /// two copies of the loop).
    const SAMPLES: usize = 256;

    /// Marks the cells inside `tris`' triangles, if the pile is deep;
    /// whether it is (else [`Interior::covers`] is not to be called).
    pub(super) fn build(&mut self, tris: &[Tri], half: f64) -> bool {
        self.build_skipping::<true>(tris, half)
    }

    /// [`Interior::build`]; with `SKIP`, a triangle whose bounds lie in
    /// cells marked already is left out (the same marks), once the
    /// triangles before it pile [`Interior::SKIP_DEPTH`] deep. The
    /// triangles are marked by decreasing area ([`Interior::by_area`]),
    /// so that the small ones, most often inside the marks of larger ones,
    /// come last: the raster is the same in any order.
    pub(super) fn build_skipping<const SKIP: bool>(&mut self, tris: &[Tri], half: f64) -> bool {
        self.n = 0;
        self.skipped = 0;
        self.left_out.clear();
        if tris.len() < Interior::FEWEST {
            return false;
        }
        // The depth and mean width, estimated.
        let (bounds, area, width) = sampled(tris);
        let scale = tris.len() as f64 / Interior::SAMPLES as f64;
        if area * scale < Interior::DEPTH * bounds {
            return false;
        }
        // Where the triangles before have piled [`Interior::SKIP_DEPTH`]
        // deep (estimated), those whose cells are marked already begin to
        // be left out.
        let skip_from = (tris.len() as f64 * Interior::SKIP_DEPTH * bounds / (area * scale))
            .min(tris.len() as f64) as usize;
        let mean = width / Interior::SAMPLES as f64;
        // Large images go to the grid's coarse levels, where an edge meets
        // the largest first and its search ends soon: the raster saves
        // little there, and marking costs as much (ours: near-coincident
        // and nested images of `benches/references.rs`'s `degenerate`
        // group, 2.7 to 4.2 times the time with it).
        if mean * Grid::side(tris.len()) as f64 > Grid::LARGE * 2.0 * half {
            return false;
        }
        let want = (2.0 * half / mean * Interior::ACROSS).clamp(64.0, Interior::MOST as f64);
        // `want` is at least 64 (a NaN clamps to 64 too).
        let n = (want as usize).div_ceil(64) * 64;
        self.n = n;
        self.half = half;
        self.w = 2.0 * half / n as f64;
        self.inv_w = n as f64 / (2.0 * half);
        self.bits.clear();
        self.bits.resize(n * (n / 64), 0);
        let margin = self.w / f64::from(1_u32 << 20);
        let last = n as f64;
        // Larger triangles first (the grid's fine level lists them in this
        // order too).
        let mut order = std::mem::take(&mut self.order);
        sort_by_area(tris, &mut order);
        'tris: for (index, &(_, i)) in order.iter().enumerate() {
            let (t, i) = (&tris[i as usize], i as usize);
            if SKIP && index >= skip_from && self.marked_already(t) {
                self.leave_out(i, tris.len());
                continue;
            }
            // The edges' lines as bounds on the cells of a row inside them.
            let mut bounds = RowBounds::default();
            for e in 0..3 {
                let (p, q) = t.edge(e);
                let d = q - p;
                let m = margin * d.abs().max_element();
                if d.y == 0.0 {
                    bounds.flat[bounds.flats] = (p.y, d.x, m);
                    bounds.flats += 1;
                    continue;
                }
                // Inside (counter-clockwise): `f = d.x (y − p.y) − d.y (x −
                // p.x) ≥ m` at the cell's corner of least `f`, whose `y` is
                // the row's bottom where `d.x > 0`, its top else, and whose
                // `x` is the cell's left where `d.y < 0`, its right else.
                // `f = m` at `x = p.x + (d.x (y − p.y) − m) / d.y`: in cells,
                // at that corner's `y` in row `r`, `α + β r`.
                let beta = d.x / d.y;
                let s = if d.x > 0.0 { 0.0 } else { 1.0 };
                let alpha =
                    (p.x + half - m / d.y) * self.inv_w + beta * (s - (p.y + half) * self.inv_w);
                if !(alpha.abs() < 1e200 && beta.abs() < 1e200) {
                    // An edge within `10⁻²⁰⁰` of level: its triangle marks
                    // nothing (never met in practice; fewer marks are
                    // always safe).
                    continue 'tris;
                }
                // The first free slot (`α` finite where taken): a triangle
                // has at most two edges on a side, the differences `d.y`
                // of its corners having their exact signs.
                let side = if d.y < 0.0 {
                    &mut bounds.left
                } else {
                    &mut bounds.right
                };
                side[usize::from(side[0].0.is_finite())] = (alpha, beta);
            }
            for r in self.cell(t.lo.y)..=self.cell(t.hi.y) {
                // The row as a number (exact: `r < 2¹⁰`), converted from 32
                // bits, which needs no fix-up for a sign.
                let rf = f64::from(r as u32);
                let y0 = -half + rf * self.w;
                let outside = bounds.flat[..bounds.flats].iter().any(|&(p, d, m)| {
                    let y = if d > 0.0 { y0 } else { y0 + self.w };
                    d * (y - p) < m
                });
                if outside {
                    continue;
                }
                // The cells `k0..=k1` of the row inside each edge's line:
                // the cell's left `k ≥ v` past the left edges (the first
                // such `k` is at most `floor(v) + 1`, by truncation of `v +
                // 1 ≥ 0`), its right `k + 1 ≤ v` short of the right ones.
                // No crossing is NaN (`α`, `β` finite, a missing edge's
                // `±∞ + 0 r`), so the larger and smaller need no test for
                // one (of `±0`, either gives the same cells).
                let at = |(alpha, beta): (f64, f64)| alpha + beta * rf;
                let v0 = larger(at(bounds.left[0]), at(bounds.left[1]));
                let v1 = smaller(at(bounds.right[0]), at(bounds.right[1]));
                let k0 = (v0.max(-1.0).min(last) + 1.0) as i64;
                let k1 = v1.max(0.0).min(last) as i64 - 1;
                if k0 <= k1 {
                    self.mark(r, k0 as usize, k1 as usize);
                }
            }
        }
        self.order = order;
        self.find_full_blocks();
        true
    }

    /// Records the triangle `i` of `count` as left out.
    fn leave_out(&mut self, i: usize, count: usize) {
        if self.left_out.is_empty() {
            self.left_out.resize(count.div_ceil(64), 0);
        }
        self.left_out[i / 64] |= 1 << (i % 64);
        self.skipped += 1;
    }

    /// Whether every cell of the rows and columns of `t`'s bounds (a
    /// column to spare either side) is marked: then `t` would mark none
    /// anew, its marks lying inside it (the same raster, bit for bit). The
    /// first and last rows first (where a triangle's bounds most often
    /// reach past the marks), then the others.
    #[inline(always)]
    fn marked_already(&self, t: &Tri) -> bool {
        let (r0, r1) = (self.cell(t.lo.y), self.cell(t.hi.y));
        let (k0, k1) = (
            self.cell(t.lo.x).saturating_sub(1),
            (self.cell(t.hi.x) + 1).min(self.n - 1),
        );
        let masks = span_masks(k0, k1);
        let held = |r: usize| all_masked(&self.bits, r * (self.n / 64), masks);
        held(r0) && held(r1) && (r0 + 1..r1).all(held)
    }

    /// Whether the last build left the triangle `i` out, its bounds' cells
    /// marked already: then every point of it lies within a few units in
    /// the last place of a marked cell ([`Interior::marked_already`]'s
    /// rows and columns hold its bounds, to the rounding of their cells),
    /// so at least half [`Interior::margin`] inside some triangle the
    /// build kept, not itself.
    #[inline(always)]
    pub(super) fn left_out(&self, i: usize) -> bool {
        self.left_out
            .get(i / 64)
            .is_some_and(|&w| (w >> (i % 64)) & 1 != 0)
    }

    /// Every triangle's key [`Grid::fine_key`] and index, sorted: by
    /// decreasing area, the order the last build marked them in
    /// (`None` where it was not built).
    pub(super) fn by_area(&self) -> Option<&[(u64, u32)]> {
        (self.n > 0).then_some(&self.order[..])
    }

    /// How far inside some triangle every point of a marked cell lies:
    /// `2⁻²⁰ w / √2` (see [`Interior`]).
    pub(super) fn margin(&self) -> f64 {
        self.w / f64::from(1_u32 << 20) * std::f64::consts::FRAC_1_SQRT_2
    }

    /// Fills [`Interior::full`] from the marks.
    fn find_full_blocks(&mut self) {
        const B: usize = Interior::BLOCK;
        let (words, blocks) = (self.n / 64, self.n / B);
        self.block_words = blocks.div_ceil(64);
        let block_words = self.block_words;
        self.full.clear();
        self.full.resize(blocks * block_words, 0);
        let group = u64::MAX >> (64 - B);
        for br in 0..blocks {
            for i in 0..words {
                let rows = (B * br..B * br + B).map(|r| self.bits[r * words + i]);
                let all = rows.fold(u64::MAX, |x, y| x & y);
                for g in 0..64 / B {
                    if (all >> (B * g)) & group == group {
                        let k = 64 / B * i + g;
                        self.full[br * block_words + k / 64] |= 1 << (k % 64);
                    }
                }
            }
        }
    }

    /// Row `r` of [`Interior::full`] (the blocks over the rows `BLOCK r..
    /// BLOCK (r + 1)` of cells).
    #[cfg(test)]
    pub(super) fn block_row(&self, r: usize) -> &[u64] {
        let words = self.block_words;
        &self.full[r * words..(r + 1) * words]
    }

    /// The row or column of the coordinate `v` (clamped).
    fn cell(&self, v: f64) -> usize {
        cell_of(v, self.half, self.inv_w, self.n)
    }

    /// Row `r` of the marks.
    #[cfg(test)]
    pub(super) fn row(&self, r: usize) -> &[u64] {
        let words = self.n / 64;
        &self.bits[r * words..(r + 1) * words]
    }

    fn mark(&mut self, r: usize, k0: usize, k1: usize) {
        let (i0, i1, first, last) = span_masks(k0, k1);
        // `k1 < n`: the words lie in row `r`.
        let at = r * (self.n / 64);
        if i0 == i1 {
            self.bits[at + i0] |= first & last;
        } else {
            self.bits[at + i0] |= first;
            self.bits[at + i0 + 1..at + i1].fill(u64::MAX);
            self.bits[at + i1] |= last;
        }
    }

    /// Whether every edge of `t` is covered ([`Interior::covers`]), shown
    /// once for the triangle: where every block its bounds overlap, grown
    /// by [`Interior::SPREAD`] cells across and [`Course::EPS`] along `y`,
    /// is all marked, and no edge is steeper than [`Interior::STEEPEST`].
    /// `false` where that does not show it (an edge may still be covered).
    ///
    /// A walk along an edge takes, in each row, the columns within `10⁻⁶
    /// (1 + |s|)` of the course's `x` there, and that `x` lies within
    /// `10⁻⁶ |s|` of the edge's `x` range (the first row's crossing is
    /// taken at most [`Course::EPS`] before the edge's end), to rounding
    /// far below `10⁻⁹` of a cell, `s` its slope against `y`: with `|s|`
    /// at most [`Interior::STEEPEST`], every cell it takes lies within
    /// [`Interior::SPREAD`] of the bounds' columns, in rows within
    /// [`Course::EPS`] of theirs, and the same rows of blocks. So in each
    /// row of blocks either the walk over the blocks finds its blocks all
    /// marked, or the walk over the cells takes only cells in blocks all
    /// marked: [`Interior::course_covered`] answers yes.
    #[inline(always)]
    pub(super) fn holds_edges_of(&self, t: &Tri) -> bool {
        const B: usize = Interior::BLOCK;
        let h = self.half;
        if t.lo.x < -h || t.lo.y < -h || t.hi.x > h || t.hi.y > h {
            // An edge leaving the square has no course.
            return false;
        }
        let to = |v: f64| (v + h) * self.inv_w;
        let steep = (0..3).any(|k| {
            let (a, b) = t.edge(k);
            let (dx, dy) = ((to(b.x) - to(a.x)).abs(), (to(b.y) - to(a.y)).abs());
            dy != 0.0 && dx > Interior::STEEPEST * dy
        });
        if steep {
            return false;
        }
        let top = (self.n - 1) as f64;
        let cell = |v: f64| v.max(0.0).min(top) as i64 as usize;
        let (r0, r1) = (
            cell(to(t.lo.y) - Course::EPS),
            cell(to(t.hi.y) + Course::EPS),
        );
        let (k0, k1) = (
            cell(to(t.lo.x) - Interior::SPREAD) / B,
            cell(to(t.hi.x) + Interior::SPREAD) / B,
        );
        // A loop written out, which the compiler keeps inline.
        for br in r0 / B..=r1 / B {
            if !all_set_at(&self.full, br * self.block_words, k0, k1) {
                return false;
            }
        }
        true
    }

    /// The steepest slope against `y`, in cells, of the edges
    /// [`Interior::holds_edges_of`] answers for.
    const STEEPEST: f64 = 1000.0;

    /// How far past a triangle's bounds, in cells, the walks along its
    /// edges may take columns: `10⁻⁶ (1 + 2 · STEEPEST)` and rounding
    /// ([`Interior::holds_edges_of`]).
    const SPREAD: f64 = 2.5e-3;

    /// Whether every cell the edge `a → b` may pass through is marked
    /// ([`Interior::course_covered`]).
    pub(super) fn covers(&self, a: DVec2, b: DVec2) -> bool {
        self.course(a, b).is_some_and(|c| self.course_covered(&c))
    }

    /// The edge `a → b` in cells, `None` where it leaves the square.
    #[inline(always)]
    pub(super) fn course(&self, a: DVec2, b: DVec2) -> Option<Course> {
        if a.abs().max_element() > self.half || b.abs().max_element() > self.half {
            return None;
        }
        let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
        let to = |v: f64| (v + self.half) * self.inv_w;
        let (lx, ly, hx, hy) = (to(lo.x), to(lo.y), to(hi.x), to(hi.y));
        // Clamped before the conversion (the same row as after it).
        let top = (self.n - 1) as f64;
        let cell = |v: f64| v.max(0.0).min(top) as i64 as usize;
        Some(Course {
            lo: DVec2::new(lx, ly),
            hi: DVec2::new(hx, hy),
            rows: (cell(ly - Course::EPS), cell(hy + Course::EPS)),
        })
    }

    /// Whether every cell within `10⁻⁶ (1 + |s|)` of the course is marked
    /// (`s` its slope against `y`): the answer of [`Walk`] over the cells
    /// from the first row to the last, found row of blocks by row of
    /// blocks. In each row of blocks, [`Walk`] over the blocks (the course
    /// scaled to them) takes the blocks within `10⁻⁶ (1 + |s|)` blocks of
    /// the course — [`Interior::BLOCK`] times the margin the cells need —
    /// so each cell the walk over the cells takes in those rows lies in a
    /// block taken. Where those blocks are all marked, so are those cells,
    /// and the walk over the cells is left out of that row of blocks.
    #[inline(always)]
    pub(super) fn course_covered(&self, c: &Course) -> bool {
        const B: usize = Interior::BLOCK;
        let in_blocks = c.in_blocks();
        let mut blocks = Walk::new(&in_blocks, self.n / B);
        // Set up where a row of blocks first fails (most questions the
        // blocks settle never need it).
        let mut cells = None;
        for block_row in in_blocks.rows.0..=in_blocks.rows.1 {
            let (k0, k1) = blocks.step(block_row);
            if all_set_at(&self.full, block_row * self.block_words, k0, k1) {
                continue;
            }
            let cells = cells.get_or_insert_with(|| blocks.over(c, self.n));
            let rows = c.rows.0.max(B * block_row)..=c.rows.1.min(B * block_row + B - 1);
            cells.enter(*rows.start());
            for r in rows {
                let (k0, k1) = cells.step(r);
                if !all_set_at(&self.bits, r * (self.n / 64), k0, k1) {
                    return false;
                }
            }
        }
        true
    }

    /// Whether the blocks along the course are all marked: the walk of
    /// [`Walk`] over the blocks, the course scaled to them, whole.
    #[cfg(test)]
    pub(super) fn blocks_cover(&self, c: &Course) -> bool {
        walk_covers(&c.in_blocks(), self.n / Interior::BLOCK, |r| {
            self.block_row(r)
        })
    }

    /// Whether every cell within `10⁻⁶ (1 + |s|)` of the course is marked,
    /// the walk over the cells whole.
    #[cfg(test)]
    pub(super) fn cells_cover(&self, c: &Course) -> bool {
        walk_covers(c, self.n, |r| self.row(r))
    }
}

/// The area of the common bounds, the summed area and the summed width
/// of the bounds of an even sample of [`Interior::SAMPLES`] triangles
/// (cheaper than a pass over all of them on shallow piles).
fn sampled(tris: &[Tri]) -> (f64, f64, f64) {
    let step = tris.len() / Interior::SAMPLES;
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(-f64::INFINITY));
    let (mut area, mut width) = (0.0, 0.0);
    for t in tris.iter().step_by(step).take(Interior::SAMPLES) {
        (lo, hi) = (lo.min(t.lo), hi.max(t.hi));
        area += 0.5 * t.doubled_area();
        width += (t.hi - t.lo).max_element();
    }
    ((hi - lo).x * (hi - lo).y, area, width)
}

/// Every triangle's key [`Grid::fine_key`] and index into `order`,
/// sorted: by decreasing area, the grid's order.
fn sort_by_area(tris: &[Tri], order: &mut Vec<(u64, u32)>) {
    order.clear();
    order.extend(
        tris.iter()
            .zip(0_u32..)
            .map(|(t, i)| (Grid::fine_key(t), i)),
    );
    order.sort_unstable();
}

/// A triangle's edges as [`Interior::build`] bounds the cells of a row
/// inside them: where its left edges' lines cross row `r`, `α + β r` in
/// cells from the square's left side (a missing edge at `−∞`), where its
/// right edges' lines do (`+∞`), and its level edges, from height `p`
/// running `d` along `x` with the margin `m`, each of which takes a whole
/// row or none of it.
#[derive(Clone, Copy, Debug)]
pub(super) struct RowBounds {
    left: [(f64, f64); 2],
    right: [(f64, f64); 2],
    flat: [(f64, f64, f64); 3],
    flats: usize,
}

impl Default for RowBounds {
    fn default() -> RowBounds {
        RowBounds {
            left: [(f64::NEG_INFINITY, 0.0); 2],
            right: [(f64::INFINITY, 0.0); 2],
            flat: [(0.0, 0.0, 0.0); 3],
            flats: 0,
        }
    }
}

/// Whether every cell [`Walk`] takes along the course `c` (in a raster `n`
/// cells a side) is set in its row (`row(r)`, bit `k` for the column `k`),
/// from its first row to its last.
#[cfg(test)]
pub(super) fn walk_covers<'a>(c: &Course, n: usize, row: impl Fn(usize) -> &'a [u64]) -> bool {
    let mut walk = Walk::new(c, n);
    (c.rows.0..=c.rows.1).all(|r| {
        let (k0, k1) = walk.step(r);
        all_set(row(r), k0, k1)
    })
}

/// A walk along a [`Course`] (in a raster `n` cells a side) row by row
/// from its first row: in each, the columns within `10⁻⁶ (1 + |s|)` of the
/// course (`s` its slope against `y`), clamped to the raster.
pub(super) struct Walk {
    lo: DVec2,
    hi: DVec2,
    /// The first row.
    first: usize,
    level: bool,
    slope: f64,
    eps: f64,
    /// The last column, `n − 1`.
    top: f64,
    /// The course's `x` where it enters the next row.
    x_in: f64,
}

impl Walk {
    #[inline(always)]
    pub(super) fn new(c: &Course, n: usize) -> Walk {
        let (lo, hi, first) = (c.lo, c.hi, c.rows.0);
        let level = hi.y <= lo.y;
        let slope = if level {
            0.0
        } else {
            (hi.x - lo.x) / (hi.y - lo.y)
        };
        Walk {
            lo,
            hi,
            first,
            level,
            slope,
            eps: Course::EPS * (1.0 + slope.abs()),
            top: (n - 1) as f64,
            x_in: lo.x,
        }
    }

    /// The walk along `c` (in a raster `n` cells a side) of which this one
    /// is the walk over the blocks ([`Course::in_blocks`]), from its first
    /// row. Its slope is the one [`Walk::new`] would compute, bit for bit:
    /// the block course's ends are the cells' times `2⁻³`, exactly (in
    /// cells from the square's corner, each `0` or at least `2⁻⁶⁰`, far
    /// from underflow), so are their differences, and the quotient of two
    /// numbers scaled alike by a power of two is the same.
    #[inline(always)]
    pub(super) fn over(&self, c: &Course, n: usize) -> Walk {
        Walk {
            lo: c.lo,
            hi: c.hi,
            first: c.rows.0,
            top: (n - 1) as f64,
            x_in: c.lo.x,
            ..*self
        }
    }

    /// Where the course leaves row `r` (at `y = r + 1`, at `y = hi.y` in
    /// the last row); a level course's whole `x` range is `lo.x..hi.x`.
    #[inline(always)]
    fn exit(&self, r: usize) -> f64 {
        if self.level {
            self.hi.x
        } else {
            // `r < 2¹⁰`: exact, converted from 32 bits (no fix-up for a
            // sign).
            let next = f64::from((r + 1) as u32);
            self.lo.x + (next.min(self.hi.y) - self.lo.y) * self.slope
        }
    }

    /// Starts the next [`Walk::step`] at row `r` (the first row, or any
    /// later one): the course's `x` where it enters `r` is where it leaves
    /// `r − 1`, as a step through every row before would have carried it.
    #[inline(always)]
    pub(super) fn enter(&mut self, r: usize) {
        self.x_in = if r == self.first || self.level {
            self.lo.x
        } else {
            self.exit(r - 1)
        };
    }

    /// The columns `k0..=k1` taken in row `r`, the row after the last step
    /// (or the one entered).
    #[inline(always)]
    pub(super) fn step(&mut self, r: usize) -> (usize, usize) {
        let x_out = self.exit(r);
        let (x0, x1) = if self.x_in <= x_out {
            (self.x_in, x_out)
        } else {
            (x_out, self.x_in)
        };
        if !self.level {
            self.x_in = x_out;
        }
        // Clamped before the conversion (the same column as after it, a
        // NaN to 0 either way), which then needs no clamp of its own.
        let column = |x: f64| x.max(0.0).min(self.top) as i64 as usize;
        (column(x0 - self.eps), column(x1 + self.eps))
    }
}

/// An edge over the cells of an [`Interior`], in cells from the square's
/// corner `(−half, −half)`.
pub(super) struct Course {
    /// The end of least `y`, and the other.
    pub(super) lo: DVec2,
    pub(super) hi: DVec2,
    /// The rows within [`Course::EPS`] of its ends (clamped).
    pub(super) rows: (usize, usize),
}

impl Course {
    /// The margin, in cells, for the rounding of the course.
    pub(super) const EPS: f64 = 1e-6;

    /// The course over the blocks of [`Interior::BLOCK`] cells a side: its
    /// ends scaled to them, its rows those of blocks holding its rows.
    #[inline(always)]
    pub(super) fn in_blocks(&self) -> Course {
        const B: usize = Interior::BLOCK;
        let scale = 1.0 / B as f64;
        Course {
            lo: self.lo * scale,
            hi: self.hi * scale,
            rows: (self.rows.0 / B, self.rows.1 / B),
        }
    }
}

/// The words `i0..=i1` of a row holding its bits `k0..=k1` (`k0 ≤ k1`),
/// and the masks of those bits in the first word and in the last.
#[inline(always)]
pub(super) fn span_masks(k0: usize, k1: usize) -> (usize, usize, u64, u64) {
    (
        k0 / 64,
        k1 / 64,
        u64::MAX << (k0 % 64),
        u64::MAX >> (63 - k1 % 64),
    )
}

/// Whether the bits `k0..=k1` (`k0 ≤ k1`) of the row `words` are all set.
#[inline(always)]
#[cfg(test)]
pub(super) fn all_set(words: &[u64], k0: usize, k1: usize) -> bool {
    all_set_at(words, 0, k0, k1)
}

/// Whether the bits `k0..=k1` (`k0 ≤ k1`) of the row that begins at word
/// `at` of `bits` are all set: the test of that row alone, its words indexed
/// in `bits` (one bounds check a word read, none for the row's slice).
#[inline(always)]
fn all_set_at(bits: &[u64], at: usize, k0: usize, k1: usize) -> bool {
    all_masked(bits, at, span_masks(k0, k1))
}

/// Whether the bits that [`span_masks`] gave of the row that begins at
/// word `at` of `bits` are all set.
#[inline(always)]
fn all_masked(bits: &[u64], at: usize, (i0, i1, first, last): (usize, usize, u64, u64)) -> bool {
    if i0 == i1 {
        bits[at + i0] & first & last == first & last
    } else {
        bits[at + i0] & first == first
            && bits[at + i0 + 1..at + i1].iter().all(|&w| w == u64::MAX)
            && bits[at + i1] & last == last
    }
}

/// The larger of `a` and `b`, neither NaN (`f64::max` without its test for
/// NaN; either zero where they are `±0`).
#[inline(always)]
fn larger(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// The smaller of `a` and `b`, neither NaN (`f64::min` without its test
/// for NaN; either zero where they are `±0`).
#[inline(always)]
fn smaller(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}
