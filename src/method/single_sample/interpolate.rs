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

/// The search of one receiver, with a scratch buffer it may reuse.
pub(super) type SearchFn<'a> = dyn Fn(usize, &mut Vec<(f64, u32)>) -> f64 + Sync + 'a;

/// One line of pixels (a column or a row): per position the receiver index
/// or `None` for background, the values known so far (`NaN`: not yet).
struct Line {
    pixels: Vec<Option<usize>>,
    values: Vec<f64>,
    sources: Vec<Option<Source>>,
    scratch: Vec<(f64, u32)>,
}

impl Line {
    fn value(&mut self, k: usize, search: &SearchFn<'_>) -> f64 {
        if self.values[k].is_nan() {
            if let Some(i) = self.pixels[k] {
                self.values[k] = search(i, &mut self.scratch);
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
    fn fill(&mut self, hard: &[Hard], search: &SearchFn<'_>) {
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

/// The receiver of pixel entry `p` (`None` for background).
fn receiver(p: u32) -> Option<usize> {
    (p != crate::render::BACKGROUND).then_some(p as usize)
}

/// The values of every receiver of a `width × height` image whose pixels
/// map to receivers as `pixels` does (a receiver index, or
/// [`BACKGROUND`](crate::render::BACKGROUND)), searching (`search(i, _)`)
/// only where the group test asks; with how each was found. Columns and
/// rows in parallel; the result does not depend on the thread count.
pub(super) fn fill(
    width: usize,
    height: usize,
    pixels: &[u32],
    hard: &[Hard],
    search: &SearchFn<'_>,
) -> (Vec<f64>, Vec<Option<Source>>) {
    let receivers = hard.len();
    let mut values = vec![f64::NAN; receivers];
    let mut sources = vec![None; receivers];
    let line = |pixels: Vec<Option<usize>>, values: Vec<f64>, sources: Vec<Option<Source>>| Line {
        pixels,
        values,
        sources,
        scratch: Vec::new(),
    };
    // Every 4th column, top to bottom.
    let columns: Vec<(usize, Vec<f64>, Vec<Option<Source>>)> = (0..width)
        .into_par_iter()
        .step_by(4)
        .map(|x| {
            let column = (0..height)
                .map(|y| receiver(pixels[y * width + x]))
                .collect();
            let mut l = line(column, vec![f64::NAN; height], vec![None; height]);
            l.fill(hard, search);
            (x, l.values, l.sources)
        })
        .collect();
    for (x, v, s) in columns {
        for y in 0..height {
            if let Some(i) = receiver(pixels[y * width + x]) {
                values[i] = v[y];
                sources[i] = s[y];
            }
        }
    }
    // Every row, between those columns.
    let rows: Vec<(usize, Vec<f64>, Vec<Option<Source>>)> = (0..height)
        .into_par_iter()
        .map(|y| {
            let row: Vec<Option<usize>> = pixels[y * width..(y + 1) * width]
                .iter()
                .map(|&p| receiver(p))
                .collect();
            let v = row
                .iter()
                .map(|p| p.map_or(f64::NAN, |i| values[i]))
                .collect();
            let s = row.iter().map(|p| p.and_then(|i| sources[i])).collect();
            let mut l = line(row, v, s);
            l.fill(hard, search);
            (y, l.values, l.sources)
        })
        .collect();
    for (y, v, s) in rows {
        for x in 0..width {
            if let Some(i) = receiver(pixels[y * width + x]) {
                values[i] = v[x];
                sources[i] = s[x];
            }
        }
    }
    (values, sources)
}
