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
/// intervals along it, none touching another, the one the last edge made
/// or grew held apart ([`SideSet::last`]) and the others keyed by their
/// start's order-preserving bits. Edges that follow one another along the
/// side (a fan of slivers, a mesh's border) each grow the last interval,
/// and the map is left as it is.
#[derive(Debug, Default)]
pub(super) struct SideSet {
    pub(super) active: bool,
    intervals: std::collections::BTreeMap<u64, (f64, f64)>,
    /// The interval the last edge made or grew, if any.
    last: Option<(f64, f64)>,
    /// Scratch for the uncovered pieces of one edge.
    pieces: Vec<(f64, f64)>,
    /// Scratch for the keys of the intervals one edge meets.
    met: Vec<u64>,
    /// Scratch for the intervals one edge meets, in order.
    meeting: Vec<(f64, f64)>,
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
        self.last = None;
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
        if self.last.is_some_and(|(s, e)| s <= lo && hi <= e) {
            // Covered whole by the last interval.
            return;
        }
        self.take_meeting(lo, hi);
        self.pieces.clear();
        let (mut t, mut new_lo, mut new_hi) = (lo, lo, hi);
        for &(s, e) in &self.meeting {
            if s > t {
                self.pieces.push((t, s));
            }
            t = t.max(e);
            (new_lo, new_hi) = (new_lo.min(s), new_hi.max(e));
        }
        if t < hi {
            self.pieces.push((t, hi));
        }
        self.last = Some((new_lo, new_hi));
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

    /// Takes the intervals meeting `[lo, hi]` (touching included) out of
    /// the set into [`SideSet::meeting`], in order: those of the map, from
    /// the last one starting at or before `lo` on, and the last interval;
    /// where that one does not meet `[lo, hi]`, it goes to the map.
    fn take_meeting(&mut self, lo: f64, hi: f64) {
        self.meeting.clear();
        if !self.intervals.is_empty() {
            self.take_from_map(lo, hi);
        }
        if let Some((s, e)) = self.last.take() {
            // Met as the map's would be: by its key (`−0.0` before `0.0`).
            if key(s) <= key(hi) && (e >= lo || key(s) >= key(lo)) {
                // Disjoint from the map's: its place among them by its start.
                let at = self.meeting.partition_point(|&(x, _)| x < s);
                self.meeting.insert(at, (s, e));
            } else {
                self.intervals.insert(key(s), (s, e));
            }
        }
    }

    /// Takes the map's intervals meeting `[lo, hi]` into
    /// [`SideSet::meeting`], in order: from the last one starting at or
    /// before `lo` on.
    fn take_from_map(&mut self, lo: f64, hi: f64) {
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
        for k in &self.met {
            self.meeting.push(self.intervals.remove(k).expect("listed"));
        }
    }
}
