//! The paper's adaptive interpolation (§4.3, Fig. 5): along every 4th
//! column of the image, groups of 5 pixels; the hard test for all 5 (its
//! result and an object id: the blocker's for a shadowed pixel, the
//! receiver's own for a lit one); the soft search for the two border
//! pixels; when all 5 ids and all 5 hard results are equal, the inner 3
//! are interpolated linearly between the borders, else the middle pixel is
//! searched and the two 3-pixel halves are treated the same way. Then every
//! row fills the gaps between those columns the same way. A background
//! pixel breaks a group: its other pixels are searched.

use rayon::prelude::*;

/// The hard test of one receiver, as the group test reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Hard {
    /// Shadowed by the light map at the receiver's own texel.
    pub shadowed: bool,
    /// The blocker's object id when shadowed, the receiver's own when lit.
    pub id: u32,
}

/// How a receiver's value was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Source {
    /// By the search.
    Searched,
    /// Linearly between the values of two receivers (their indices).
    Between(u32, u32),
}

/// One line of pixels (a column or a row): per position the receiver index
/// or `None` for background, the values known so far (`NaN`: not yet).
struct Line<'a> {
    pixels: &'a [Option<usize>],
    values: Vec<f64>,
    sources: Vec<Option<Source>>,
}

impl Line<'_> {
    fn value(&mut self, k: usize, search: &(dyn Fn(usize) -> f64 + Sync)) -> f64 {
        if self.values[k].is_nan() {
            if let Some(i) = self.pixels[k] {
                self.values[k] = search(i);
                self.sources[k] = Some(Source::Searched);
            }
        }
        self.values[k]
    }

    /// Whether the pixels `ks` all have a receiver with one hard result and
    /// one id.
    fn alike(&self, ks: &[usize], hard: &[Hard]) -> bool {
        let first = self.pixels[ks[0]].map(|i| hard[i]);
        first.is_some() && ks.iter().all(|&k| self.pixels[k].map(|i| hard[i]) == first)
    }

    fn interpolate(&mut self, from: usize, to: usize) {
        let (a, b) = (self.values[from], self.values[to]);
        let (ia, ib) = match (self.pixels[from], self.pixels[to]) {
            (Some(ia), Some(ib)) => (ia as u32, ib as u32),
            _ => return,
        };
        let n = (to - from) as f64;
        for k in from + 1..to {
            if self.values[k].is_nan() {
                let t = (k - from) as f64 / n;
                self.values[k] = a + (b - a) * t;
                self.sources[k] = Some(Source::Between(ia, ib));
            }
        }
    }

    /// Every pixel of the line valued, group by group.
    fn fill(&mut self, hard: &[Hard], search: &(dyn Fn(usize) -> f64 + Sync)) {
        let n = self.pixels.len();
        let mut start = 0;
        while start < n {
            let end = (start + 4).min(n - 1);
            if end - start < 4 || !(start..=end).all(|k| self.pixels[k].is_some()) {
                // A short tail or a background pixel: search every pixel.
                for k in start..=end {
                    self.value(k, search);
                }
            } else {
                self.value(start, search);
                self.value(end, search);
                let all: Vec<usize> = (start..=end).collect();
                if self.alike(&all, hard) {
                    self.interpolate(start, end);
                } else {
                    let mid = start + 2;
                    self.value(mid, search);
                    for (a, b) in [(start, mid), (mid, end)] {
                        if self.alike(&[a, a + 1, b], hard) {
                            self.interpolate(a, b);
                        } else {
                            self.value(a + 1, search);
                        }
                    }
                }
            }
            if end + 1 >= n {
                break;
            }
            start = end;
        }
    }
}

/// The values of every receiver of a `width × height` image whose pixels
/// map to receivers as `pixels` does (`u32::MAX`-like `None` for
/// background), searching (`search(i)`) only where the group test asks;
/// with how each was found. Columns and rows in parallel; the result does
/// not depend on the thread count.
pub(super) fn fill(
    width: usize,
    height: usize,
    pixels: &[Option<usize>],
    receivers: usize,
    hard: &[Hard],
    search: &(dyn Fn(usize) -> f64 + Sync),
) -> (Vec<f64>, Vec<Option<Source>>) {
    let mut values = vec![f64::NAN; receivers];
    let mut sources = vec![None; receivers];
    // Every 4th column, top to bottom.
    let columns: Vec<(usize, Vec<f64>, Vec<Option<Source>>)> = (0..width)
        .into_par_iter()
        .step_by(4)
        .map(|x| {
            let column: Vec<Option<usize>> = (0..height).map(|y| pixels[y * width + x]).collect();
            let mut line = Line {
                pixels: &column,
                values: vec![f64::NAN; height],
                sources: vec![None; height],
            };
            line.fill(hard, search);
            (x, line.values, line.sources)
        })
        .collect();
    for (x, v, s) in columns {
        for y in 0..height {
            if let Some(i) = pixels[y * width + x] {
                values[i] = v[y];
                sources[i] = s[y];
            }
        }
    }
    // Every row, between those columns.
    let rows: Vec<(usize, Vec<f64>, Vec<Option<Source>>)> = (0..height)
        .into_par_iter()
        .map(|y| {
            let row = &pixels[y * width..(y + 1) * width];
            let mut line = Line {
                pixels: row,
                values: row.iter().map(|p| p.map_or(f64::NAN, |i| values[i])).collect(),
                sources: row.iter().map(|p| p.and_then(|i| sources[i])).collect(),
            };
            line.fill(hard, search);
            (y, line.values, line.sources)
        })
        .collect();
    for (y, v, s) in rows {
        for x in 0..width {
            if let Some(i) = pixels[y * width + x] {
                values[i] = v[x];
                sources[i] = s[x];
            }
        }
    }
    (values, sources)
}
