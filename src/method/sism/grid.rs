//! The light-space perspective grid of receivers (Johnson et al. 2009,
//! Fig. 3): receivers sorted by light-image-plane cell and depth slice,
//! stored contiguously, built in `O(n)` by a counting sort.
//!
//! Storage order is bin-major: the cells of one bin (a `bin × bin` tile of
//! cells, the paper's rasteriser bin) are contiguous, and within a cell the
//! depth slices follow each other from the nearest to the deepest. So one
//! bin owns one contiguous range of the sorted receivers (the unit of
//! parallel work), one cell one contiguous range, and the receivers of a
//! column "at this depth and deeper" (§2.5's second optimisation) are a
//! suffix of the cell's range.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// The most cells along one side of the grid.
pub(super) const MAX_SIDE: u32 = 8192;

/// The most keys (cells, padded to whole bins, times depth slices) a grid
/// allocates: `2²⁶` (two `u32` arrays of that length, 512 MiB). The cell
/// count, the bin side and the slice count are lowered to fit; they change
/// only the work, never a value.
pub(super) const KEY_BUDGET: usize = 1 << 26;

/// The grid and its sorted receivers.
pub(super) struct Grid {
    /// Lower corner of the grid on the light image plane.
    pub lo: DVec2,
    /// Cell size.
    pub cell: DVec2,
    /// Cells along x and y.
    pub nx: u32,
    pub ny: u32,
    /// Cells per bin side.
    pub bin: u32,
    /// Bins along x and y.
    pub bx: u32,
    pub by: u32,
    /// Depth slices per cell.
    pub slices: u32,
    /// `offsets[key]..offsets[key + 1]`: the sorted receivers of one
    /// (bin, cell in bin, slice) key.
    offsets: Vec<u32>,
    /// Sorted receivers: image-plane position, light-frame depth, world
    /// position, index in the frame.
    pub s: Vec<DVec2>,
    pub z: Vec<f64>,
    pub world: Vec<DVec3>,
    pub index: Vec<u32>,
    /// Per bin, the greatest receiver depth (0 for an empty bin).
    pub bin_zmax: Vec<f64>,
    /// Per slice, the greatest receiver depth it holds over the whole grid
    /// (0 for an empty slice).
    pub slice_zmax: Vec<f64>,
    /// The greatest receiver depth.
    pub z_max: f64,
    /// Per row, the running count of receivers over its cells:
    /// `row_prefix[cy (nx + 1) + cx]` receivers in cells `0..cx` of row `cy`.
    row_prefix: Vec<u32>,
}

/// One receiver to store: image-plane position, depth, world position,
/// frame index.
pub(super) struct Entry {
    pub s: DVec2,
    pub z: f64,
    pub world: DVec3,
    pub index: u32,
}

impl Grid {
    /// Builds the grid over `entries` (finite, `z > 0`) with about
    /// `cells_per_receiver` cells per receiver, `bin × bin` cells per bin
    /// and `slices` depth slices uniform in `1/z` — all three lowered as
    /// needed to stay within [`KEY_BUDGET`] keys. `O(n + cells · slices)`.
    pub fn build(entries: &[Entry], cells_per_receiver: f64, bin: u32, slices: u32) -> Grid {
        let n = entries.len();
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        let (mut z_min, mut z_max) = (f64::INFINITY, 0.0f64);
        for e in entries {
            lo = lo.min(e.s);
            hi = hi.max(e.s);
            z_min = z_min.min(e.z);
            z_max = z_max.max(e.z);
        }
        if n == 0 {
            lo = DVec2::ZERO;
            hi = DVec2::ONE;
            z_min = 1.0;
            z_max = 1.0;
        }
        // A flat or point-like set still gets a box of positive size.
        let scale = lo.abs().max(hi.abs()).max_element().max(1.0);
        let floor = scale * 1e-9;
        let mut extent = (hi - lo).max(DVec2::splat(floor));
        let target = (n as f64 * cells_per_receiver).clamp(1.0, (KEY_BUDGET / 8) as f64);
        let aspect = extent.x / extent.y;
        let nx = ((target * aspect).sqrt().ceil()).clamp(1.0, f64::from(MAX_SIDE)) as u32;
        let ny = ((target / f64::from(nx)).ceil()).clamp(1.0, f64::from(MAX_SIDE)) as u32;
        // Enlarged by a hair so the greatest coordinate falls in the last
        // cell rather than on its far side.
        extent *= 1.0 + 1e-9;
        let cell = extent / DVec2::new(f64::from(nx), f64::from(ny));
        // A bin no wider than the grid keeps the padding below 4 nx ny
        // (bx bin < nx + bin ≤ 2 nx), hence below KEY_BUDGET / 2.
        let bin = bin.min(nx).min(ny).max(1);
        let bx = nx.div_ceil(bin);
        let by = ny.div_ceil(bin);
        let padded = bx as usize * by as usize * (bin as usize * bin as usize);
        let slices = slices.clamp(1, (KEY_BUDGET / padded).max(1) as u32);
        let keys = padded * slices as usize;

        let mut grid = Grid {
            lo,
            cell,
            nx,
            ny,
            bin,
            bx,
            by,
            slices,
            offsets: Vec::new(),
            s: Vec::new(),
            z: Vec::new(),
            world: Vec::new(),
            index: Vec::new(),
            bin_zmax: vec![0.0; bx as usize * by as usize],
            slice_zmax: vec![0.0; slices as usize],
            z_max,
            row_prefix: Vec::new(),
        };
        let (inv_near, inv_far) = (1.0 / z_min, 1.0 / z_max);
        let span = inv_near - inv_far;
        let slice_of = |z: f64| -> u32 {
            if span > 0.0 {
                let t = (inv_near - 1.0 / z) / span * f64::from(slices);
                (t.max(0.0) as u32).min(slices - 1)
            } else {
                0
            }
        };
        // Counting sort: count, prefix sums, place.
        // Keys in parallel (rayon), then a sequential counting sort.
        let key_of: Vec<u32> = entries
            .par_iter()
            .map(|e| {
                let (cx, cy) = grid.cell_of(e.s);
                grid.key(cx, cy, slice_of(e.z)) as u32
            })
            .collect();
        let mut offsets = vec![0u32; keys + 1];
        for &k in &key_of {
            offsets[k as usize + 1] += 1;
        }
        for k in 0..keys {
            offsets[k + 1] += offsets[k];
        }
        let mut next: Vec<u32> = offsets[..keys].to_vec();
        let mut order = vec![0u32; n];
        for (i, &k) in key_of.iter().enumerate() {
            order[next[k as usize] as usize] = i as u32;
            next[k as usize] += 1;
        }
        drop(next);
        grid.offsets = offsets;
        let mut row_prefix = vec![0u32; ny as usize * (nx as usize + 1)];
        for cy in 0..ny {
            let base = cy as usize * (nx as usize + 1);
            for cx in 0..nx {
                let k = grid.key(cx, cy, 0);
                let count = grid.offsets[k + slices as usize] - grid.offsets[k];
                row_prefix[base + cx as usize + 1] = row_prefix[base + cx as usize] + count;
            }
        }
        grid.row_prefix = row_prefix;
        grid.s = order.par_iter().map(|&i| entries[i as usize].s).collect();
        grid.z = order.par_iter().map(|&i| entries[i as usize].z).collect();
        grid.world = order
            .par_iter()
            .map(|&i| entries[i as usize].world)
            .collect();
        grid.index = order
            .par_iter()
            .map(|&i| entries[i as usize].index)
            .collect();
        // Per bin and per slice, the greatest depth, read off the keys.
        let per_bin = bin as usize * bin as usize * slices as usize;
        for (&o, &z) in order.iter().zip(&grid.z) {
            let k = key_of[o as usize] as usize;
            let (b, slice) = (k / per_bin, k % slices as usize);
            grid.bin_zmax[b] = grid.bin_zmax[b].max(z);
            grid.slice_zmax[slice] = grid.slice_zmax[slice].max(z);
        }
        grid
    }

    /// The number of bins.
    pub fn bins(&self) -> usize {
        self.bx as usize * self.by as usize
    }

    /// The cell holding image-plane point `s` (clamped to the grid).
    pub fn cell_of(&self, s: DVec2) -> (u32, u32) {
        let t = (s - self.lo) / self.cell;
        let cx = (t.x.max(0.0) as u32).min(self.nx - 1);
        let cy = (t.y.max(0.0) as u32).min(self.ny - 1);
        (cx, cy)
    }

    /// The range of cells (inclusive) whose rectangles can meet the box
    /// `[lo, hi]`; `None` when the box misses the grid.
    pub fn cell_range(&self, lo: DVec2, hi: DVec2) -> Option<(u32, u32, u32, u32)> {
        if !(lo.x <= hi.x && lo.y <= hi.y) {
            return None;
        }
        let a = (lo - self.lo) / self.cell;
        let b = (hi - self.lo) / self.cell;
        if b.x < -1e-9 || b.y < -1e-9 {
            return None;
        }
        let (nx, ny) = (f64::from(self.nx), f64::from(self.ny));
        if a.x > nx + 1e-9 || a.y > ny + 1e-9 {
            return None;
        }
        // One cell of margin on each side for the rounding of the cell
        // assignment.
        let x0 = (a.x.floor() - 1.0).clamp(0.0, nx - 1.0) as u32;
        let y0 = (a.y.floor() - 1.0).clamp(0.0, ny - 1.0) as u32;
        let x1 = (b.x.floor() + 1.0).clamp(0.0, nx - 1.0) as u32;
        let y1 = (b.y.floor() + 1.0).clamp(0.0, ny - 1.0) as u32;
        Some((x0, y0, x1, y1))
    }

    /// The bin of cell `(cx, cy)`.
    pub fn bin_id(&self, cx: u32, cy: u32) -> usize {
        (cy / self.bin) as usize * self.bx as usize + (cx / self.bin) as usize
    }

    /// The cells of bin `b` as an inclusive range `(x0, y0, x1, y1)`.
    pub fn bin_cells(&self, b: usize) -> (u32, u32, u32, u32) {
        let (bx, by) = ((b % self.bx as usize) as u32, (b / self.bx as usize) as u32);
        let x0 = bx * self.bin;
        let y0 = by * self.bin;
        (
            x0,
            y0,
            (x0 + self.bin - 1).min(self.nx - 1),
            (y0 + self.bin - 1).min(self.ny - 1),
        )
    }

    fn key(&self, cx: u32, cy: u32, slice: u32) -> usize {
        let b = self.bin_id(cx, cy);
        let local = (cy % self.bin) as usize * self.bin as usize + (cx % self.bin) as usize;
        (b * (self.bin as usize * self.bin as usize) + local) * self.slices as usize
            + slice as usize
    }

    /// The sorted receivers of bin `b`.
    pub fn bin_range(&self, b: usize) -> std::ops::Range<usize> {
        let per = self.bin as usize * self.bin as usize * self.slices as usize;
        self.offsets[b * per] as usize..self.offsets[(b + 1) * per] as usize
    }

    /// The sorted receivers of cell `(cx, cy)`, slices `first..` (the
    /// column at that depth and deeper).
    pub fn column(&self, cx: u32, cy: u32, first: u32) -> std::ops::Range<usize> {
        let k = self.key(cx, cy, 0);
        self.offsets[k + first.min(self.slices) as usize] as usize
            ..self.offsets[k + self.slices as usize] as usize
    }

    /// The receivers in cells `x0..=x1` of row `cy`.
    pub fn row_count(&self, cy: u32, x0: u32, x1: u32) -> u64 {
        let base = cy as usize * (self.nx as usize + 1);
        u64::from(self.row_prefix[base + x1 as usize + 1] - self.row_prefix[base + x0 as usize])
    }

    /// Row `cy`'s band `[ylo, yhi]`, enlarged by a hair like
    /// [`cell_box`](Self::cell_box).
    pub fn row_band(&self, cy: u32) -> (f64, f64) {
        let (lo, hi) = self.cell_box(0, cy);
        (lo.y, hi.y)
    }

    /// The columns (inclusive) whose cells meet `[x0, x1]`, clamped to the
    /// grid, enlarged by a hair; `None` when the range misses the grid.
    pub fn col_range(&self, x0: f64, x1: f64) -> Option<(u32, u32)> {
        let pad = self.cell.x * 1e-6 + x0.abs().max(x1.abs()).min(f64::MAX) * 1e-12;
        let a = ((x0 - pad) - self.lo.x) / self.cell.x;
        let b = ((x1 + pad) - self.lo.x) / self.cell.x;
        let n = f64::from(self.nx);
        if !(b >= 0.0 && a < n) {
            return None;
        }
        Some((
            a.max(0.0).min(n - 1.0) as u32,
            b.max(0.0).min(n - 1.0) as u32,
        ))
    }

    /// The cell's rectangle, enlarged by a hair for the rounding of the
    /// cell assignment.
    pub fn cell_box(&self, cx: u32, cy: u32) -> (DVec2, DVec2) {
        let lo = self.lo + self.cell * DVec2::new(f64::from(cx), f64::from(cy));
        let hi = lo + self.cell;
        let pad = self.cell * 1e-6 + DVec2::splat(lo.abs().max(hi.abs()).max_element() * 1e-12);
        (lo - pad, hi + pad)
    }

    /// Splits `data` (one value per stored receiver) into the consecutive
    /// ranges of the bins.
    pub fn split_bins<'a, T>(&self, mut data: &'a mut [T]) -> Vec<&'a mut [T]> {
        let mut out = Vec::with_capacity(self.bins());
        for b in 0..self.bins() {
            let len = self.bin_range(b).len();
            let (head, tail) = std::mem::take(&mut data).split_at_mut(len);
            out.push(head);
            data = tail;
        }
        out
    }

    /// The first depth slice whose receivers can be deeper than `z` (the
    /// per-slice maxima grow with the slice; empty slices read 0).
    pub fn first_slice_deeper(&self, z: f64) -> u32 {
        self.slice_zmax
            .iter()
            .position(|&m| m > z)
            .map_or(self.slices, |k| k as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arbitrary::Rng;

    #[test]
    fn every_receiver_is_stored_once_in_its_cell_and_slice_order() {
        let mut rng = Rng::new(0x6e1d);
        for case in 0..20 {
            let n = [0, 1, 2, 17, 500, 3000][case % 6];
            let entries: Vec<Entry> = (0..n)
                .map(|i| {
                    let z = rng.uniform(1.0, 5.0);
                    // Clusters and a few coincident points.
                    let s = if i % 7 == 0 {
                        DVec2::splat(0.25)
                    } else {
                        DVec2::new(rng.uniform(-1.0, 1.0), rng.uniform(-0.3, 0.2))
                    };
                    Entry {
                        s,
                        z,
                        world: DVec3::new(s.x * z, s.y * z, z),
                        index: i as u32,
                    }
                })
                .collect();
            let grid = Grid::build(&entries, 1.0 + (case % 3) as f64, 1 + case as u32 % 5, 4);
            // A permutation of the input.
            let mut seen = vec![false; n];
            for &i in &grid.index {
                assert!(!seen[i as usize]);
                seen[i as usize] = true;
            }
            assert!(seen.iter().all(|&b| b));
            // Bins tile the array in order; each cell's column holds
            // exactly its receivers, depths non-decreasing by slice.
            let mut next = 0;
            for b in 0..grid.bins() {
                let r = grid.bin_range(b);
                assert_eq!(r.start, next);
                next = r.end;
                let (x0, y0, x1, y1) = grid.bin_cells(b);
                for cy in y0..=y1 {
                    for cx in x0..=x1 {
                        let col = grid.column(cx, cy, 0);
                        assert!(r.start <= col.start && col.end <= r.end);
                        assert_eq!(grid.row_count(cy, cx, cx), col.len() as u64);
                        for i in col.clone() {
                            assert_eq!(grid.cell_of(grid.s[i]), (cx, cy));
                            assert!(grid.z[i] <= grid.z_max);
                            assert!(grid.bin_zmax[b] >= grid.z[i]);
                        }
                        for k in 0..grid.slices {
                            for i in grid.column(cx, cy, k).start..grid.column(cx, cy, k + 1).start
                            {
                                assert!(grid.z[i] <= grid.slice_zmax[k as usize]);
                            }
                        }
                    }
                }
            }
            assert_eq!(next, n);
        }
    }
}
