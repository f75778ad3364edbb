//! The uncovered pieces of an edge and their compensated sum.

use super::tri::Measure;
use glam::DVec2;

/// Adds the pieces of `a → b` outside every interval of `intervals`.
#[inline(always)]
pub(super) fn add_uncovered(
    a: DVec2,
    b: DVec2,
    intervals: &mut [(f64, f64)],
    measure: Measure,
    sum: &mut Sum,
) {
    if intervals.is_empty() {
        sum.add(measure.piece(a, b));
        return;
    }
    intervals.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let at = |t: f64| if t >= 1.0 { b } else { a + (b - a) * t };
    let mut t = 0.0;
    let mut from = a;
    for &(s, e) in intervals.iter() {
        if s > t {
            let to = at(s);
            sum.add(measure.piece(from, to));
        }
        if e > t {
            t = e;
            from = at(t);
        }
        if t >= 1.0 {
            return;
        }
    }
    sum.add(measure.piece(from, b));
}

/// Neumaier's compensated sum, with the count and the magnitudes of its
/// terms for its error bound.
#[derive(Default)]
pub(super) struct Sum {
    sum: f64,
    c: f64,
    magnitude: f64,
    n: u32,
}

impl Sum {
    pub(super) fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.c += (self.sum - t) + x;
        } else {
            self.c += (x - t) + self.sum;
        }
        self.sum = t;
        self.magnitude += x.abs();
        self.n += 1;
    }

    pub(super) fn value(&self) -> f64 {
        self.sum + self.c
    }

    /// A bound on the sum's error, and the terms' own (each piece of the
    /// area kernel within `3 ε`, the unit disk's and the square's): the
    /// compensated sum is within `2 ε |s| + 4 n ε² Σ|tᵢ|` of the exact sum
    /// of its terms (Neumaier; Higham, *Accuracy and Stability*, §4.3).
    pub(super) fn bound(&self) -> f64 {
        let eps = f64::EPSILON;
        let n = f64::from(self.n);
        (2.0 * eps * self.value().abs() + 4.0 * n * eps * eps * self.magnitude + 3.0 * n * eps)
            * (1.0 + 4.0 * eps)
    }
}
