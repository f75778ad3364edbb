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

/// The search of one receiver.
pub(super) type SearchFn<'a> = dyn Fn(usize) -> f64 + Sync + 'a;

/// The receiver of pixel entry `p` (`None` for background).
fn receiver(p: u32) -> Option<usize> {
    (p != crate::render::BACKGROUND).then_some(p as usize)
}

/// One line of pixels (a column or a row): per position the receiver index
/// or [`BACKGROUND`](crate::render::BACKGROUND), the values known so far
/// (`NaN`: not yet) and how each was found.
struct Line<'a> {
    pixels: &'a [u32],
    values: &'a mut [f64],
    sources: &'a mut [Option<Source>],
}

impl Line<'_> {
    fn value(&mut self, k: usize, search: &SearchFn<'_>) -> f64 {
        if self.values[k].is_nan() {
            if let Some(i) = receiver(self.pixels[k]) {
                self.values[k] = search(i);
                self.sources[k] = Some(Source::Searched);
            }
        }
        self.values[k]
    }

    /// Whether the pixels `from..=to` all have a receiver with one hard
    /// result and one id.
    fn alike(&self, from: usize, to: usize, hard: &[Hard]) -> bool {
        let first = receiver(self.pixels[from]).map(|i| hard[i]);
        first.is_some()
            && self.pixels[from + 1..=to]
                .iter()
                .all(|&p| receiver(p).map(|i| hard[i]) == first)
    }

    fn interpolate(&mut self, from: usize, to: usize) {
        let (a, b) = (self.values[from], self.values[to]);
        let (ia, ib) = (self.pixels[from], self.pixels[to]);
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
            let whole = self.pixels[start..=end]
                .iter()
                .all(|&p| receiver(p).is_some());
            if end - start < 4 || !whole {
                // A short tail or a background pixel: search every pixel.
                for k in start..=end {
                    self.value(k, search);
                }
            } else {
                self.value(start, search);
                self.value(end, search);
                if self.alike(start, end, hard) {
                    self.interpolate(start, end);
                } else {
                    let mid = start + 2;
                    self.value(mid, search);
                    for (a, b) in [(start, mid), (mid, end)] {
                        if self.alike(a, b, hard) {
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
/// map to receivers as `pixels` does (a receiver index, or
/// [`BACKGROUND`](crate::render::BACKGROUND)), searching (`search(i)`)
/// only where the group test asks; with how each was found. Columns and
/// rows in parallel; the result does not depend on the thread count.
pub(super) fn fill(
    width: usize,
    height: usize,
    pixels: &[u32],
    hard: &[Hard],
    search: &SearchFn<'_>,
) -> (Vec<f64>, Vec<Option<Source>>) {
    // In image order first.
    let mut values = vec![f64::NAN; width * height];
    let mut sources = vec![None; width * height];
    // Every 4th column, top to bottom.
    let columns: Vec<(usize, Vec<f64>, Vec<Option<Source>>)> = (0..width)
        .into_par_iter()
        .step_by(4)
        .map(|x| {
            let column: Vec<u32> = (0..height).map(|y| pixels[y * width + x]).collect();
            let (mut v, mut s) = (vec![f64::NAN; height], vec![None; height]);
            Line {
                pixels: &column,
                values: &mut v,
                sources: &mut s,
            }
            .fill(hard, search);
            (x, v, s)
        })
        .collect();
    for (x, v, s) in columns {
        for y in 0..height {
            values[y * width + x] = v[y];
            sources[y * width + x] = s[y];
        }
    }
    // Every row, between those columns, in place.
    values
        .par_chunks_mut(width.max(1))
        .zip(sources.par_chunks_mut(width.max(1)))
        .zip(pixels.par_chunks(width.max(1)))
        .for_each(|((values, sources), pixels)| {
            Line {
                pixels,
                values,
                sources,
            }
            .fill(hard, search);
        });
    // In receiver order.
    let mut by_receiver = vec![f64::NAN; hard.len()];
    let mut how = vec![None; hard.len()];
    for ((&p, v), s) in pixels.iter().zip(values).zip(sources) {
        if let Some(i) = receiver(p) {
            by_receiver[i] = v;
            how[i] = s;
        }
    }
    (by_receiver, how)
}
