//! The search grid: the triangles binned by their bounds.

use super::tri::Tri;
use glam::DVec2;

/// Uniform grids of triangle indices over the square `[−half, half]²`: a
/// fine grid of about one cell per triangle, in which a triangle is listed
/// in every cell its bounds overlap, in index order (by decreasing area
/// under a deep pile of images, where a larger triangle is likelier to
/// cover the searched edge and end its search: fewer tests per covered
/// edge, measured in benches/README.md); and above it coarse
/// levels, level `k` with `2^k` cells a side, for the triangles that would
/// span more than [`Grid::LARGE`] fine cells along an axis, each listed at
/// the finest level whose cells are at least as wide as its bounds (at most
/// four cells), larger bounds first. Without the coarse levels a large
/// image was listed in most fine cells, and building the grid dominated
/// under many large overlapping images (nested or near-coincident ones); a
/// search visits the coarse levels first, coarsest first, since an edge
/// is most often covered whole by a large triangle, which ends its search.
/// Where no triangle is large, the grid is the fine grid alone.
#[derive(Debug, Default)]
pub(super) struct Grid {
    half: f64,
    /// The fine grid.
    pub(super) fine: Level,
    /// Coarse level `k` (kept between builds, cleared when used).
    coarse: Vec<Level>,
    /// The coarse levels that hold a triangle, coarsest first.
    occupied: Vec<usize>,
    /// The coarse levels' triangles: the level, a key (decreasing area of
    /// the bounds) and the index; sorted, each level's a run, larger first.
    large: Vec<(u8, u64, u32)>,
    /// Where each cell's next item goes, while filling a level.
    fill: Vec<u32>,
    /// The fine level's triangles by decreasing area (a key and the
    /// index), when they are listed in that order.
    order: Vec<(u64, u32)>,
    /// Each triangle's cells in the fine level while building (found once
    /// for the count and the listing), [`Grid::COARSE`] for one on a
    /// coarse level or left out.
    ranges: Vec<[u16; 4]>,
}

/// One level of a [`Grid`], in compressed rows: cell `c` holds
/// `items[start[c]..start[c + 1]]`.
#[derive(Debug, Default)]
pub(super) struct Level {
    n: usize,
    inv_cell: f64,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    /// The most cells along a side of the fine grid: beyond it, building
    /// costs more than the tests it saves.
    const MAX_SIDE: usize = 64;

    /// A triangle whose bounds span more than this many fine cells along
    /// an axis goes to a coarse level (ours: an ordinary image stays in the
    /// fine grid; the nested and near-coincident images that would make
    /// building it quadratic, each many fine cells wide, go up).
    pub(super) const LARGE: f64 = 4.0;

    /// In [`Grid::ranges`], a triangle on a coarse level or left out (no
    /// fine cell is numbered so: the fine grid is at most
    /// [`Grid::MAX_SIDE`] a side).
    const COARSE: [u16; 4] = [u16::MAX; 4];

    /// The fine grid's cells a side for `n` triangles.
    pub(super) fn side(n: usize) -> usize {
        ((n as f64).sqrt().ceil() as usize).clamp(1, Grid::MAX_SIDE)
    }

    /// The number of coarse levels over a fine grid `side` cells a side:
    /// their sides are the powers of two below the fine grid's.
    fn levels(side: usize) -> usize {
        side.next_power_of_two().trailing_zeros() as usize
    }

    /// The coarse level of the triangle `t` in a grid `side` cells a side
    /// with `levels` coarse levels over `[−half, half]²`, or `None` for the
    /// fine level.
    #[inline(always)]
    fn level_of(t: &Tri, side: usize, levels: usize, half: f64) -> Option<u8> {
        let width = (t.hi - t.lo).max_element() / (2.0 * half);
        (levels > 0 && width * side as f64 > Grid::LARGE).then(|| {
            // The finest coarse level with cells at least `width` wide.
            let mut k = levels - 1;
            while k > 0 && width * (1_u64 << k) as f64 > 1.0 {
                k -= 1;
            }
            k as u8
        })
    }

    /// How many of `tris` a grid over `[−half, half]²` would put on its
    /// coarse levels ([`Grid::level_of`]).
    pub(super) fn large_count(tris: &[Tri], half: f64) -> usize {
        let side = Grid::side(tris.len());
        let levels = Grid::levels(side);
        tris.iter()
            .filter(|t| Grid::level_of(t, side, levels, half).is_some())
            .count()
    }

    /// The key that orders a coarse level's triangles (decreasing area of
    /// the bounds).
    fn area_key(t: &Tri) -> u64 {
        let d = t.hi - t.lo;
        !(d.x * d.y).to_bits()
    }

    /// The key that orders the fine level's triangles under a deep pile
    /// ([`Grid::put_by_area`]; [`Interior`](super::interior::Interior)
    /// marks in the same order): decreasing area, by the bits of the
    /// doubled area.
    pub(super) fn fine_key(t: &Tri) -> u64 {
        !t.doubled_area().to_bits()
    }

    pub(super) fn build<const BY_AREA: bool>(&mut self, tris: &[Tri], half: f64) {
        self.build_without::<BY_AREA>(tris, half, |_| false, None);
    }

    /// [`Grid::build`] with the triangles `i` that `left_out(i)` says
    /// listed in no cell (the same cells, and the others in the same
    /// order); with `BY_AREA`, `by_area` may give every triangle's key of
    /// [`Grid::put_by_area`] and index, sorted (the same order, no sort).
    pub(super) fn build_without<const BY_AREA: bool>(
        &mut self,
        tris: &[Tri],
        half: f64,
        left_out: impl Fn(usize) -> bool,
        by_area: Option<&[(u64, u32)]>,
    ) {
        let side = Grid::side(tris.len());
        self.half = half;
        let levels = Grid::levels(side);
        self.fine.reset(side, half);
        self.large.clear();
        self.ranges.clear();
        for (t, i) in tris.iter().zip(0_u32..) {
            if left_out(i as usize) {
                self.ranges.push(Grid::COARSE);
                continue;
            }
            let range = match Grid::level_of(t, side, levels, half) {
                Some(k) => {
                    self.large.push((k, Grid::area_key(t), i));
                    Grid::COARSE
                }
                None => {
                    let range = self.fine.range(t.lo, t.hi, half);
                    self.fine.count_in(range);
                    // Cells below `MAX_SIDE`.
                    [range.0, range.1, range.2, range.3].map(|c| c as u16)
                }
            };
            self.ranges.push(range);
        }
        self.fine.prefix(&mut self.fill);
        if BY_AREA {
            self.put_by_area(tris, by_area);
        } else {
            for (range, i) in self.ranges.iter().zip(0_u32..) {
                if *range != Grid::COARSE {
                    self.fine.put_in(cells(*range), i, &mut self.fill);
                }
            }
        }
        self.occupied.clear();
        if self.large.is_empty() {
            return;
        }
        self.large.sort_unstable();
        if self.coarse.len() < levels {
            self.coarse.resize_with(levels, Level::default);
        }
        for run in self.large.chunk_by(|a, b| a.0 == b.0) {
            let k = usize::from(run[0].0);
            let level = &mut self.coarse[k];
            level.reset(1 << k, half);
            for &(_, _, i) in run {
                level.count(&tris[i as usize], half);
            }
            level.prefix(&mut self.fill);
            for &(_, _, i) in run {
                level.put(&tris[i as usize], i, half, &mut self.fill);
            }
            self.occupied.push(k);
        }
    }

    /// Lists the triangles of the fine level ([`Grid::ranges`]) in it, by
    /// decreasing area: the key [`Grid::fine_key`] and the index, sorted, or
    /// the sorted keys and indices of every triangle given (`sorted`:
    /// those of the fine level among them are in the order their own sort
    /// gives, the pairs being distinct).
    fn put_by_area(&mut self, tris: &[Tri], sorted: Option<&[(u64, u32)]>) {
        if let Some(sorted) = sorted {
            for &(_, i) in sorted {
                let range = self.ranges[i as usize];
                if range != Grid::COARSE {
                    self.fine.put_in(cells(range), i, &mut self.fill);
                }
            }
            return;
        }
        self.order.clear();
        self.order.extend(
            tris.iter()
                .zip(&self.ranges)
                .zip(0_u32..)
                .filter(|((_, range), _)| **range != Grid::COARSE)
                .map(|((t, _), i)| (Grid::fine_key(t), i)),
        );
        self.order.sort_unstable();
        for &(_, i) in &self.order {
            let range = cells(self.ranges[i as usize]);
            self.fine.put_in(range, i, &mut self.fill);
        }
    }

    /// Calls `f` with every triangle in a cell the box `lo..hi` overlaps,
    /// the coarse levels first, coarsest first (a triangle in several cells
    /// more than once), until it returns `false`; of the fine level, only
    /// in the cells `(x, y)` that `keep` keeps.
    pub(super) fn for_each_near(
        &self,
        lo: DVec2,
        hi: DVec2,
        keep: impl Fn(usize, usize) -> bool,
        mut f: impl FnMut(u32) -> bool,
    ) {
        let levels = self.occupied.iter().map(|&k| &self.coarse[k]);
        for level in levels.chain(std::iter::once(&self.fine)) {
            let fine = std::ptr::eq(level, &self.fine);
            let (x0, y0, x1, y1) = level.range(lo, hi, self.half);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if fine && !keep(x, y) {
                        continue;
                    }
                    let c = y * level.n + x;
                    for &j in &level.items[level.start[c] as usize..level.start[c + 1] as usize] {
                        if !f(j) {
                            return;
                        }
                    }
                }
            }
        }
    }
}

/// The order in which [`Grid::for_each_near`] over the grid
/// [`Grid::build`] would build without `BY_AREA` meets the triangles whose
/// bounds overlap a box, found without building it: for a few searches,
/// a pass over the triangles costs less than the build (a convex polygon
/// given as a fan of slivers, where all but a few edges are settled
/// before any search).
///
/// Each triangle is listed in one level, in every cell of its range; the
/// levels are visited coarsest first, then the fine one, each over the
/// box's range row by row, a cell's triangles in the level's order (a
/// coarse level's by decreasing area of the bounds, then index; the fine
/// level's by index). So a triangle is first met in its level, in the first
/// cell, row by row, of its range and the box's (their meet, not empty
/// where the bounds overlap: the cells are monotone in the coordinates),
/// and sorting by level, that cell's row and column, the level's key and
/// index gives the order of first meetings. Triangles whose bounds miss
/// the box give no span ([`span_of`](super::boundary::span_of)), so
/// leaving them out changes nothing.
#[derive(Debug, Default)]
pub(super) struct Unbuilt {
    /// The triangles met, each with its place: level and cell, key, index.
    pub(super) order: Vec<(u32, u64, u32)>,
}

impl Unbuilt {
    /// The fewest triangles for which the first searches go without the
    /// grid: below, building it costs little.
    pub(super) const FROM: usize = 1024;

    /// How many searches go without the grid before it is built: each
    /// passes over every triangle, about a tenth of the build's cost.
    pub(super) const SEARCHES: usize = 4;

    /// The largest share of the triangles a search goes on without the
    /// grid with ([`Unbuilt::find`]).
    const SHARE: f64 = 0.125;

    /// The triangles of `tris` but `i` whose bounds overlap `lo..hi`, in
    /// [`Unbuilt::order`] by their first meeting; `false` (and unsorted)
    /// where they are more than [`Unbuilt::SHARE`] of all: sorting them
    /// would cost about as much as the build (layers stacked over the
    /// light, each image's bounds the whole square).
    pub(super) fn find(
        &mut self,
        tris: &[Tri],
        half: f64,
        (lo, hi): (DVec2, DVec2),
        i: usize,
    ) -> bool {
        let side = Grid::side(tris.len());
        let levels = Grid::levels(side);
        self.order.clear();
        for (t, j) in tris.iter().zip(0_u32..) {
            if t.bounds_miss(lo, hi) || j as usize == i {
                continue;
            }
            let (rank, n, key) = match Grid::level_of(t, side, levels, half) {
                Some(k) => (usize::from(k), 1_usize << k, Grid::area_key(t)),
                None => (levels, side, 0),
            };
            let inv_cell = n as f64 / (2.0 * half);
            let cell = |v: f64| cell_of(v, half, inv_cell, n);
            let (x, y) = (cell(lo.x).max(cell(t.lo.x)), cell(lo.y).max(cell(t.lo.y)));
            let place = (rank * Grid::MAX_SIDE + y) * Grid::MAX_SIDE + x;
            self.order.push((place as u32, key, j));
        }
        if self.order.len() as f64 > Unbuilt::SHARE * tris.len() as f64 {
            return false;
        }
        self.order.sort_unstable();
        true
    }
}

impl Level {
    /// Empties the level and gives it `n` cells a side.
    fn reset(&mut self, n: usize, half: f64) {
        self.n = n;
        self.inv_cell = n as f64 / (2.0 * half);
        self.start.clear();
        self.start.resize(n * n + 1, 0);
    }

    /// Counts the triangle in the cells it overlaps.
    #[inline(always)]
    fn count(&mut self, t: &Tri, half: f64) {
        self.count_in(self.range(t.lo, t.hi, half));
    }

    /// Counts a triangle in the cells `x0..=x1`, `y0..=y1`.
    #[inline(always)]
    fn count_in(&mut self, (x0, y0, x1, y1): (usize, usize, usize, usize)) {
        for y in y0..=y1 {
            let at = y * self.n + 1;
            for count in &mut self.start[at + x0..=at + x1] {
                *count += 1;
            }
        }
    }

    /// Turns the counts into starts, and the cells' fill positions into
    /// `fill`.
    fn prefix(&mut self, fill: &mut Vec<u32>) {
        let cells = self.n * self.n;
        for c in 0..cells {
            self.start[c + 1] += self.start[c];
        }
        self.items.clear();
        self.items.resize(self.start[cells] as usize, 0);
        fill.clear();
        fill.extend_from_slice(&self.start[..cells]);
    }

    /// Lists the triangle in the cells it overlaps (after [`Level::prefix`]
    /// of this level: `fill` is this level's).
    #[inline(always)]
    fn put(&mut self, t: &Tri, i: u32, half: f64, fill: &mut [u32]) {
        self.put_in(self.range(t.lo, t.hi, half), i, fill);
    }

    /// Lists the triangle `i` in the cells `x0..=x1`, `y0..=y1`, row by
    /// row.
    #[inline(always)]
    fn put_in(&mut self, (x0, y0, x1, y1): (usize, usize, usize, usize), i: u32, fill: &mut [u32]) {
        for y in y0..=y1 {
            let at = y * self.n;
            for next in &mut fill[at + x0..=at + x1] {
                self.items[*next as usize] = i;
                *next += 1;
            }
        }
    }

    /// The parameters `u ∈ [0, 1]` at which the point `a + u (b − a)` may
    /// lie in the cell `(x, y)`, as an interval: `None` where it never does.
    /// The cell is taken grown by `10⁻⁹` of the square on every side, and
    /// unbounded beyond the outer cells (as [`cell_of`] clamps): a point
    /// [`Level::put`] would list in the cell, or within rounding of one,
    /// lies in the interval by a margin far above the rounding of `u`.
    pub(super) fn passage(
        &self,
        x: usize,
        y: usize,
        a: DVec2,
        b: DVec2,
        half: f64,
    ) -> Option<(f64, f64)> {
        let grow = 2e-9 * half;
        let w = 2.0 * half / self.n as f64;
        let mut u = (0.0_f64, 1.0_f64);
        for (c, pa, pb) in [(x, a.x, b.x), (y, a.y, b.y)] {
            let lo = if c == 0 {
                f64::NEG_INFINITY
            } else {
                -half + c as f64 * w - grow
            };
            let hi = if c + 1 >= self.n {
                f64::INFINITY
            } else {
                -half + (c + 1) as f64 * w + grow
            };
            let d = pb - pa;
            if d == 0.0 {
                if pa < lo || pa > hi {
                    return None;
                }
            } else {
                let (t0, t1) = ((lo - pa) / d, (hi - pa) / d);
                u = (u.0.max(t0.min(t1)), u.1.min(t0.max(t1)));
            }
        }
        (u.0 <= u.1).then_some(u)
    }

    /// The cells `x0..=x1`, `y0..=y1` the box `lo..hi` overlaps (clamped:
    /// rounding may put a clipped vertex a hair outside the square).
    pub(super) fn range(&self, lo: DVec2, hi: DVec2, half: f64) -> (usize, usize, usize, usize) {
        let cell = |v: f64| cell_of(v, half, self.inv_cell, self.n);
        (cell(lo.x), cell(lo.y), cell(hi.x), cell(hi.y))
    }
}

/// The cells of a range kept in [`Grid::ranges`].
fn cells([x0, y0, x1, y1]: [u16; 4]) -> (usize, usize, usize, usize) {
    (x0.into(), y0.into(), x1.into(), y1.into())
}

/// The row or column, of `n`, of the coordinate `v` in cells of width
/// `1 / inv_cell` from `−half`, clamped. Truncation is the floor where it
/// is taken (`c ≥ 0`; a NaN gives 0): no call to `floor`, which the
/// baseline target lacks as an instruction.
pub(super) fn cell_of(v: f64, half: f64, inv_cell: f64, n: usize) -> usize {
    let c = (v + half) * inv_cell;
    if c >= 0.0 {
        // Clamped before the conversion (the same cell as after it).
        c.min((n - 1) as f64) as i64 as usize
    } else {
        0
    }
}
