//! The neighbourhood search of the single-sample method: the nearest texel
//! of the light map that blocks a receiver (outer penumbra) or that is lit
//! and on the receiver's own object (inner penumbra), within a radius.
//!
//! The paper searches an axis-aligned box texel by texel (§4.2). Here the
//! map is summarised in tiles of [`TILE`]² texels — per tile the least depth
//! of its two nearest objects, the greatest depth, which object ids it
//! holds — so that a tile that cannot hold a qualifying texel is skipped
//! without reading it; tiles are visited nearest first and the search stops
//! once no tile can hold a nearer texel. The texels found are exactly the
//! texel-by-texel search's: a tile is skipped only when no texel in it can
//! qualify (the bounds below are conservative), and among texels at equal
//! distance the one visited first wins, tiles in order of their nearest
//! point then index, texels row by row.

use crate::method::centre::depth::DepthTest;
use crate::render::raster::{LightMaps, LightView};
use glam::DVec2;

/// Side of a summary tile, in texels.
pub(super) const TILE: u32 = 8;

/// What a tile holds, for skipping it.
#[derive(Clone, Copy, Debug)]
struct Tile {
    /// The least depth of any texel, and that texel's object id.
    d1: f64,
    id1: u32,
    /// The least depth of the texels whose id is not `id1`.
    d2: f64,
    /// The greatest depth of a covered texel (`−∞` when none is).
    dmax: f64,
    /// Whether a texel sees no triangle (infinite depth).
    uncovered: bool,
    /// Bit `id mod 64` set for every object id of a covered texel.
    ids: u64,
}

/// The light map's tile summaries.
#[derive(Clone, Debug)]
pub(super) struct Tiles {
    /// Tiles along x (rows of tiles follow each other).
    nx: u32,
    tiles: Vec<Tile>,
}

impl Tiles {
    /// The summaries of `maps`.
    pub(super) fn new(maps: &LightMaps) -> Tiles {
        let (w, h) = (maps.width(), maps.height());
        let (nx, ny) = (w.div_ceil(TILE), h.div_ceil(TILE));
        let mut tiles = Vec::with_capacity((nx * ny) as usize);
        for ty in 0..ny {
            for tx in 0..nx {
                let mut t = Tile {
                    d1: f64::INFINITY,
                    id1: u32::MAX,
                    d2: f64::INFINITY,
                    dmax: f64::NEG_INFINITY,
                    uncovered: false,
                    ids: 0,
                };
                for row in ty * TILE..((ty + 1) * TILE).min(h) {
                    for col in tx * TILE..((tx + 1) * TILE).min(w) {
                        let (d, id) = (maps.depth_at(col, row), maps.object_at(col, row));
                        if !maps.is_covered(col, row) {
                            t.uncovered = true;
                            continue;
                        }
                        t.ids |= 1 << (id % 64);
                        t.dmax = t.dmax.max(d);
                        if d < t.d1 {
                            if id != t.id1 {
                                t.d2 = t.d1;
                            }
                            t.d1 = d;
                            t.id1 = id;
                        } else if id != t.id1 {
                            t.d2 = t.d2.min(d);
                        }
                    }
                }
                tiles.push(t);
            }
        }
        Tiles { nx, tiles }
    }
}

/// What the search looks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Want {
    /// A texel that blocks the receiver, lies in front of it (the paper's
    /// layers in front of `P′_z`) and is on another object (`other`: `None`
    /// switches the id test off).
    Blocker { other: Option<u32> },
    /// A texel that does not block the receiver and is on its own object
    /// (`own`: `None` switches the id test off).
    LitOwn { own: Option<u32> },
}

/// The nearest qualifying texel: its distance and depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Found {
    pub distance: f64,
    pub depth: f64,
}

/// One search: the light view and maps, their tiles, the receiver's depth
/// test, and the metric (`scale`: the length of one texel step along x and
/// y — `(1, 1)` to measure in texels, the texel size to measure on the
/// image plane).
pub(super) struct Search<'a> {
    pub view: &'a LightView,
    pub maps: &'a LightMaps,
    pub tiles: &'a Tiles,
    pub test: &'a DepthTest,
    pub scale: DVec2,
}

impl Search<'_> {
    /// Whether texel `(col, row)` qualifies.
    fn qualifies(&self, want: Want, col: u32, row: u32) -> bool {
        let d = self.maps.depth_at(col, row);
        let id = self.maps.object_at(col, row);
        match want {
            Want::Blocker { other } => {
                other.is_none_or(|own| id != own)
                    && d < self.test.in_front()
                    && self.test.blocks(self.view, col, row, d)
            }
            Want::LitOwn { own } => {
                own.is_none_or(|own| id == own) && !self.test.blocks(self.view, col, row, d)
            }
        }
    }

    /// Whether the tile's part `c0..=c1` × `r0..=r1` may hold a qualifying
    /// texel: `false` only when none can. A texel blocks when its depth is
    /// below the test's threshold at that texel ([`DepthTest::threshold`]),
    /// which over the part lies between the thresholds of the bounds of
    /// the reference depth.
    fn may_hold(&self, want: Want, tile: &Tile, (c0, r0, c1, r1): (u32, u32, u32, u32)) -> bool {
        // The cheap tests first; the reference depth's bounds (four
        // divisions) only when they pass.
        let range = || self.test.reference_range(self.view, (c0, r0), (c1, r1));
        match want {
            Want::Blocker { other } => {
                // The least depth among the texels of other objects.
                let least = match other {
                    Some(own) if tile.id1 == own => tile.d2,
                    _ => tile.d1,
                };
                least < self.test.in_front() && least < self.test.threshold(range().1)
            }
            Want::LitOwn { own: Some(own) } => {
                tile.ids & (1 << (own % 64)) != 0 && tile.dmax >= self.test.threshold(range().0)
            }
            Want::LitOwn { own: None } => {
                tile.uncovered || tile.dmax >= self.test.threshold(range().0)
            }
        }
    }

    /// The nearest texel within `radius` of `q` (continuous texel
    /// coordinates; distances in the search's metric) that qualifies for
    /// `want`, and its depth; `None` when none does.
    pub(super) fn nearest(&self, q: DVec2, radius: f64, want: Want) -> Option<Found> {
        let (w, h) = (self.maps.width(), self.maps.height());
        if !(radius >= 0.0 && q.is_finite()) || w == 0 || h == 0 {
            return None;
        }
        // The texel box the disk of `radius` around `q` can reach.
        let reach = DVec2::new(radius / self.scale.x, radius / self.scale.y);
        let lo = (q - reach - 0.5).ceil().max(DVec2::ZERO);
        let hi = (q + reach - 0.5)
            .floor()
            .min(DVec2::new(f64::from(w - 1), f64::from(h - 1)));
        if !(lo.x <= hi.x && lo.y <= hi.y) {
            return None;
        }
        let (c_lo, r_lo, c_hi, r_hi) = (lo.x as u32, lo.y as u32, hi.x as u32, hi.y as u32);
        // Tiles ring by ring (Chebyshev distance in tiles) around the one
        // nearest `q`: a texel of ring k is at least (k − 1)·TILE + ½
        // texels away along one axis, which ends the search once the best
        // found is nearer.
        let (tx_lo, ty_lo, tx_hi, ty_hi) = (c_lo / TILE, r_lo / TILE, c_hi / TILE, r_hi / TILE);
        let centre = (
            ((q.x.max(0.0) as u32) / TILE).clamp(tx_lo, tx_hi),
            ((q.y.max(0.0) as u32) / TILE).clamp(ty_lo, ty_hi),
        );
        let rings = (centre.0 - tx_lo)
            .max(tx_hi - centre.0)
            .max(centre.1 - ty_lo)
            .max(ty_hi - centre.1);
        let step = self.scale.min_element();
        let mut best: Option<Found> = None;
        let mut limit2 = radius * radius;
        for k in 0..=rings {
            if k >= 1 && best.is_some() {
                let ring = (f64::from((k - 1) * TILE) + 0.5) * step;
                if ring * ring > limit2 {
                    break;
                }
            }
            let (kx0, kx1) = (
                centre.0.saturating_sub(k).max(tx_lo),
                (centre.0 + k).min(tx_hi),
            );
            let (ky0, ky1) = (
                centre.1.saturating_sub(k).max(ty_lo),
                (centre.1 + k).min(ty_hi),
            );
            for ty in ky0..=ky1 {
                for tx in kx0..=kx1 {
                    let on_ring = tx.abs_diff(centre.0).max(ty.abs_diff(centre.1)) == k;
                    if on_ring {
                        self.scan_tile(
                            q,
                            (tx, ty),
                            (c_lo, r_lo, c_hi, r_hi),
                            want,
                            &mut best,
                            &mut limit2,
                        );
                    }
                }
            }
        }
        best
    }

    /// The texels of tile `(tx, ty)` within the box, nearer than the best
    /// so far (squared limit `limit2`), that qualify.
    fn scan_tile(
        &self,
        q: DVec2,
        (tx, ty): (u32, u32),
        (c_lo, r_lo, c_hi, r_hi): (u32, u32, u32, u32),
        want: Want,
        best: &mut Option<Found>,
        limit2: &mut f64,
    ) {
        let (c0, r0) = ((tx * TILE).max(c_lo), (ty * TILE).max(r_lo));
        let (c1, r1) = (
            ((tx + 1) * TILE - 1).min(c_hi),
            ((ty + 1) * TILE - 1).min(r_hi),
        );
        // The tile's nearest texel centre to `q`.
        let nearest = DVec2::new(
            (q.x - 0.5).clamp(f64::from(c0), f64::from(c1)),
            (q.y - 0.5).clamp(f64::from(r0), f64::from(r1)),
        );
        let lb = ((nearest + 0.5 - q) * self.scale).length_squared();
        if lb > *limit2 || (best.is_some() && lb >= *limit2) {
            return;
        }
        let tile = &self.tiles.tiles[(ty * self.tiles.nx + tx) as usize];
        if !self.may_hold(want, tile, (c0, r0, c1, r1)) {
            return;
        }
        for row in r0..=r1 {
            let dy = (f64::from(row) + 0.5 - q.y) * self.scale.y;
            let dy2 = dy * dy;
            if dy2 > *limit2 {
                continue;
            }
            for col in c0..=c1 {
                let dx = (f64::from(col) + 0.5 - q.x) * self.scale.x;
                let d2 = dx * dx + dy2;
                // Strictly nearer than the best so far (ties: first
                // found), within the radius.
                let nearer = if best.is_some() {
                    d2 < *limit2
                } else {
                    d2 <= *limit2
                };
                if nearer && self.qualifies(want, col, row) {
                    *limit2 = d2;
                    *best = Some(Found {
                        distance: d2.sqrt(),
                        depth: self.maps.depth_at(col, row),
                    });
                }
            }
        }
    }
}
