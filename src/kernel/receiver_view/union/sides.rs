//! The sweep of the edges lying on a side of the clip square.

use super::sum::Sum;
use super::tri::Measure;
use glam::DVec2;

/// A side of the clip square.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    /// `y = −half`.
    Bottom,
    /// `x = half`.
    Right,
    /// `y = half`.
    Top,
    /// `x = −half`.
    Left,
}

impl Side {
    /// The side both ends of `a → b` lie on (exactly: the clip leaves the
    /// square's coordinates as they are), if any.
    pub(super) fn of(a: DVec2, b: DVec2, half: f64) -> Option<Side> {
        if a.y == b.y && a.y == -half {
            Some(Side::Bottom)
        } else if a.x == b.x && a.x == half {
            Some(Side::Right)
        } else if a.y == b.y && a.y == half {
            Some(Side::Top)
        } else if a.x == b.x && a.x == -half {
            Some(Side::Left)
        } else {
            None
        }
    }

    /// The coordinate that varies along the side.
    fn along(self, v: DVec2) -> f64 {
        match self {
            Side::Bottom | Side::Top => v.x,
            Side::Right | Side::Left => v.y,
        }
    }

    /// The point of the side at `u` along it.
    fn at(self, u: f64, half: f64) -> DVec2 {
        match self {
            Side::Bottom => DVec2::new(u, -half),
            Side::Top => DVec2::new(u, half),
            Side::Right => DVec2::new(half, u),
            Side::Left => DVec2::new(-half, u),
        }
    }
}

/// The union of the edges swept so far on one side: disjoint closed
/// intervals along it, keyed by their start's order-preserving bits.
#[derive(Debug, Default)]
pub(super) struct SideSet {
    pub(super) active: bool,
    intervals: std::collections::BTreeMap<u64, (f64, f64)>,
    /// Scratch for the uncovered pieces of one edge.
    pieces: Vec<(f64, f64)>,
    /// Scratch for the keys of the intervals one edge meets.
    met: Vec<u64>,
}

/// An order-preserving key of a finite `f64`.
pub(super) fn key(u: f64) -> u64 {
    let bits = u.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    }
}

impl SideSet {
    pub(super) fn clear(&mut self) {
        self.intervals.clear();
    }

    /// Adds the pieces of the side edge `a → b` that no earlier edge on the
    /// side covers, in order from `a`, then takes the edge into the set.
    pub(super) fn add_uncovered(
        &mut self,
        side: Side,
        a: DVec2,
        b: DVec2,
        half: f64,
        measure: Measure,
        sum: &mut Sum,
    ) {
        let (ua, ub) = (side.along(a), side.along(b));
        let (lo, hi) = (ua.min(ub), ua.max(ub));
        // The intervals meeting [lo, hi]: from the last one starting at or
        // before `lo` on; merged into one afterwards.
        let first = self
            .intervals
            .range(..=key(lo))
            .next_back()
            .filter(|(_, &(_, e))| e >= lo)
            .map(|(&k, _)| k);
        let from = first.unwrap_or_else(|| key(lo));
        self.met.clear();
        self.met
            .extend(self.intervals.range(from..=key(hi)).map(|(&k, _)| k));
        self.pieces.clear();
        let (mut t, mut new_lo, mut new_hi) = (lo, lo, hi);
        for k in &self.met {
            let (s, e) = self.intervals.remove(k).expect("listed");
            if s > t {
                self.pieces.push((t, s));
            }
            t = t.max(e);
            (new_lo, new_hi) = (new_lo.min(s), new_hi.max(e));
        }
        if t < hi {
            self.pieces.push((t, hi));
        }
        self.intervals.insert(key(new_lo), (new_lo, new_hi));
        // In the edge's direction, from its exact ends and the earlier
        // edges' exact corners.
        let point = |u: f64| {
            if u == ua {
                a
            } else if u == ub {
                b
            } else {
                side.at(u, half)
            }
        };
        if ua <= ub {
            for &(s, e) in &self.pieces {
                sum.add(measure.piece(point(s), point(e)));
            }
        } else {
            for &(s, e) in self.pieces.iter().rev() {
                sum.add(measure.piece(point(e), point(s)));
            }
        }
    }
}
