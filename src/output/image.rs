//! Pictures and numbers from a visibility buffer: [shading](crate::definitions#shading), the
//! visibility itself, the signed error heat-map against a reference with
//! its legend, error summaries, and PNG files.
//!
//! Images are 8-bit sRGB, row-major from the top-left, three bytes per
//! pixel ([`Rgb`]).

use crate::definitions::in_penumbra;
use crate::render::frame::{Frame, BACKGROUND};
use crate::scene::{Light, Receiver, Scene};
use glam::DVec3;
use std::fmt;
use std::io;
use std::path::Path;

/// An 8-bit sRGB image, row-major from the top-left.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `3 · width · height` bytes: red, green, blue per pixel.
    pub data: Vec<u8>,
}

/// The colour of background pixels (no receiver).
pub const BACKGROUND_RGB: [u8; 3] = [28, 32, 44];

/// How many units of signed error the heat-map's colour scale spans on each
/// side of zero: errors beyond `±HEAT_RANGE` saturate.
pub const HEAT_RANGE: f64 = 0.25;

impl Rgb {
    fn new(width: u32, height: u32, fill: [u8; 3]) -> Rgb {
        Rgb {
            width,
            height,
            data: fill.repeat(width as usize * height as usize),
        }
    }

    fn set(&mut self, x: u32, y: u32, c: [u8; 3]) {
        if x < self.width && y < self.height {
            let i = 3 * (y as usize * self.width as usize + x as usize);
            self.data[i..i + 3].copy_from_slice(&c);
        }
    }

    /// The image shrunk by `factor` in each direction, each pixel the mean
    /// of its `factor × factor` block (of the sRGB codes; the edge blocks
    /// of a side not divisible by `factor` are dropped). `factor ≤ 1` is a
    /// copy.
    #[must_use]
    pub fn downsample(&self, factor: u32) -> Rgb {
        if factor <= 1 {
            return self.clone();
        }
        let (w, h) = (self.width / factor, self.height / factor);
        let mut out = Rgb::new(w, h, [0, 0, 0]);
        let n = u64::from(factor * factor);
        for y in 0..h {
            for x in 0..w {
                let mut sum = [0u64; 3];
                for dy in 0..factor {
                    for dx in 0..factor {
                        let i = 3 * (((y * factor + dy) * self.width + x * factor + dx) as usize);
                        for (c, total) in sum.iter_mut().enumerate() {
                            *total += u64::from(self.data[i + c]);
                        }
                    }
                }
                out.set(x, y, sum.map(|s| ((s + n / 2) / n) as u8));
            }
        }
        out
    }

    /// Writes the image as a PNG file, atomically: the bytes go to a
    /// temporary file in the same folder, which is renamed to `path` only
    /// once complete, so a reader never sees a partial picture, whatever
    /// stops the program; an existing file or symlink at `path` is
    /// replaced, never written through.
    ///
    /// # Errors
    /// The file's I/O errors, and the encoder's as [`io::ErrorKind::Other`];
    /// the temporary file is removed on error.
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        let mut bytes = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let mut writer = encoder.write_header().map_err(io::Error::other)?;
            writer
                .write_image_data(&self.data)
                .map_err(io::Error::other)?;
            writer.finish().map_err(io::Error::other)?;
        }
        write_atomically(path, &bytes)
    }
}

/// Writes `bytes` to `path` through a temporary file in the same folder
/// (`.NAME.PID.tmp`), synced, then renamed over `path`.
///
/// # Errors
/// The I/O errors of writing or renaming; the temporary file is removed on
/// error.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    use std::io::Write as _;
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "no file name"))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".{}.tmp", std::process::id()));
    let tmp = path.with_file_name(tmp_name);
    // A leftover of an earlier run (or anything placed there) is removed
    // first and the file is created new, so nothing is written through a
    // link; the rename then replaces `path` itself, a symlink included.
    let _ = std::fs::remove_file(&tmp);
    let result = (|| {
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Linear `[0, 1]` to an 8-bit sRGB code (IEC 61966-2-1).
#[must_use]
pub fn srgb8(linear: f64) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

/// The unshadowed irradiance factor of [shading](crate::definitions#shading) at `p` with normal `n`:
/// `max(0, n·l̂) · cos θ_l / |l|²`, `l` from `p` to the light's centre,
/// with `cos θ_l` the cosine at the light (1 for a sphere, a segment and a
/// point; `|n_light · l̂|` for a disk or rect, which emit on both sides).
#[must_use]
pub fn irradiance_factor(light: &Light, p: DVec3, n: DVec3) -> f64 {
    let l = light.center() - p;
    let d2 = l.length_squared();
    let Some(dir) = l.try_normalize() else {
        return 0.0;
    };
    let cos_light = light.plane_normal().map_or(1.0, |n| n.dot(dir).abs());
    let e = n.dot(dir).max(0.0) * cos_light / d2;
    if e.is_finite() {
        e
    } else {
        0.0
    }
}

/// The frame shaded as in [shading](crate::definitions#shading) with `Φ = 1`: `E = irradiance_factor · V`,
/// exposed so that the brightest unshadowed receiver is white, sRGB-encoded;
/// background pixels [`BACKGROUND_RGB`]. Receivers without a normal are
/// shaded as if facing the light.
#[must_use]
pub fn shaded(scene: &Scene, frame: &Frame, visibility: &[f64]) -> Rgb {
    let light = scene.light();
    let unshadowed: Vec<f64> = frame
        .receivers()
        .iter()
        .map(|r| irradiance_factor(light, r.position, facing(light.center(), r)))
        .collect();
    let shadowed: Vec<f64> = unshadowed
        .iter()
        .enumerate()
        .map(|(i, e)| e * visibility.get(i).copied().unwrap_or(0.0))
        .collect();
    expose_values(frame, &unshadowed, &shadowed)
}

/// The frame shaded by a segment light's two end samples, as OESS does
/// (linear emission, its substep 4.3), on [`shaded`]'s scale: the
/// unshadowed term is [`shaded`]'s, and `V` is replaced by the end
/// samples' share `(w_L·g(L) + w_R·g(R)) / ((g(L) + g(R)) / 2)`, with the
/// weights `[w_L, w_R]` of each receiver ([`Output::end_weights`]) and
/// `g(X) = max(0, n·x̂) / |x|²`, `x` from the receiver to the end `X`. With
/// the light wholly visible (`w_L = w_R = ½`) the picture is [`shaded`]'s;
/// where one end's part of the light is hidden, the receiver gets that
/// end's share of the light's strength. So the pictures of every method
/// share one exposure. For a light that is not a segment, or a receiver
/// that neither end lights, the weights' sum is `V`.
///
/// [`Output::end_weights`]: crate::method::Output::end_weights
#[must_use]
pub fn shaded_by_ends(scene: &Scene, frame: &Frame, weights: &[[f64; 2]]) -> Rgb {
    let light = scene.light();
    let g = |end: DVec3, r: &Receiver| {
        let x = end - r.position;
        let e = facing(end, r).dot(x.normalize_or_zero()).max(0.0) / x.length_squared();
        if e.is_finite() {
            e
        } else {
            0.0
        }
    };
    let visible = |r: &Receiver, [wl, wr]: [f64; 2]| {
        let Light::Segment(segment) = light else {
            return wl + wr;
        };
        let (gl, gr) = (g(segment.a(), r), g(segment.b(), r));
        let share = (wl * gl + wr * gr) / (0.5 * (gl + gr));
        if share.is_finite() {
            share.clamp(0.0, 2.0)
        } else {
            wl + wr
        }
    };
    let v: Vec<f64> = frame
        .receivers()
        .iter()
        .zip(weights)
        .map(|(r, &w)| visible(r, w))
        .collect();
    shaded(scene, frame, &v)
}

/// The receiver's normal, or the direction to `toward` where it has none.
fn facing(toward: DVec3, r: &Receiver) -> DVec3 {
    r.normal
        .unwrap_or_else(|| (toward - r.position).normalize_or_zero())
}

/// Paints `shadowed` scaled so that the largest of `unshadowed` is white.
fn expose_values(frame: &Frame, unshadowed: &[f64], shadowed: &[f64]) -> Rgb {
    let top = unshadowed.iter().copied().fold(0.0, f64::max);
    let scale = if top > 0.0 { 1.0 / top } else { 0.0 };
    paint(frame, |i| {
        let v = srgb8(shadowed.get(i).copied().unwrap_or(0.0) * scale);
        [v, v, v]
    })
}

/// The visibility itself as grey levels (linear `V`, sRGB-encoded).
#[must_use]
pub fn visibility_image(frame: &Frame, visibility: &[f64]) -> Rgb {
    paint(frame, |i| {
        let v = srgb8(visibility.get(i).copied().unwrap_or(0.0));
        [v, v, v]
    })
}

/// The colour of a signed error `e = V − V_ref` on the heat-map scale:
/// white at 0, toward blue where the method is too dark (`e < 0`), toward
/// red where it is too bright, saturating at `±`[`HEAT_RANGE`].
#[must_use]
pub fn heat_colour(e: f64) -> [u8; 3] {
    let t = if e.is_finite() {
        (e.abs() / HEAT_RANGE).min(1.0)
    } else {
        1.0
    };
    let full: [f64; 3] = if e < 0.0 {
        [0.05, 0.25, 0.85]
    } else {
        [0.85, 0.08, 0.05]
    };
    let mix = |c: f64| srgb8(1.0 + (c - 1.0) * t);
    [mix(full[0]), mix(full[1]), mix(full[2])]
}

/// Rows of the legend under the heat-map.
const LEGEND_ROWS: u32 = 18;
/// The least image width that holds the legend.
const LEGEND_WIDTH: u32 = 64;

/// The size of [`error_heat_map`]'s image for a frame of `width × height`:
/// the legend's rows below, at least the legend's width.
#[must_use]
pub(crate) fn heat_map_size(width: u32, height: u32) -> (u32, u32) {
    (width.max(LEGEND_WIDTH), height + LEGEND_ROWS)
}

/// The signed error `V − V_ref` per pixel ([`heat_colour`]), with a legend
/// strip below the picture: the colour bar from `−HEAT_RANGE` to
/// `+HEAT_RANGE` and its labels (`-.25`, `0`, `+.25`). The image is at least
/// 64 pixels wide so the legend fits; the picture sits at the top-left.
#[must_use]
pub fn error_heat_map(frame: &Frame, visibility: &[f64], reference: &[f64]) -> Rgb {
    let picture = paint(frame, |i| {
        let e =
            visibility.get(i).copied().unwrap_or(0.0) - reference.get(i).copied().unwrap_or(0.0);
        heat_colour(e)
    });
    let (width, height) = heat_map_size(picture.width, picture.height);
    let mut out = Rgb::new(width, height, [0, 0, 0]);
    for y in 0..picture.height {
        let from = 3 * (y * picture.width) as usize;
        let to = 3 * (y * width) as usize;
        let n = 3 * picture.width as usize;
        out.data[to..to + n].copy_from_slice(&picture.data[from..from + n]);
    }
    // The bar: 6 rows, the full width less a 2-pixel margin.
    let top = picture.height + 2;
    let (left, right) = (2, width - 3);
    for x in left..=right {
        let e = HEAT_RANGE * (2.0 * f64::from(x - left) / f64::from(right - left) - 1.0);
        for y in top..top + 6 {
            out.set(x, y, heat_colour(e));
        }
    }
    let labels = top + 8;
    let white = [255, 255, 255];
    draw_text(&mut out, left, labels, "-.25", white);
    let mid = (left + right) / 2;
    draw_text(&mut out, mid - 1, labels, "0", white);
    draw_text(
        &mut out,
        right + 1 - text_width("+.25"),
        labels,
        "+.25",
        white,
    );
    out
}

/// An image of `frame`'s size, `colour(i)` at receiver `i`'s pixel,
/// [`BACKGROUND_RGB`] elsewhere.
fn paint(frame: &Frame, colour: impl Fn(usize) -> [u8; 3]) -> Rgb {
    let (width, height) = frame.size();
    let mut data = Vec::with_capacity(3 * frame.pixels().len());
    for &i in frame.pixels() {
        data.extend_from_slice(&if i == BACKGROUND {
            BACKGROUND_RGB
        } else {
            colour(i as usize)
        });
    }
    Rgb {
        width,
        height,
        data,
    }
}

/// A 3 × 5 pixel font for the legend: rows top to bottom, bit 2 the left.
fn glyph(c: char) -> [u8; 5] {
    match c {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '5' => [7, 4, 7, 1, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        '+' => [0, 2, 7, 2, 0],
        _ => [0; 5],
    }
}

fn text_width(s: &str) -> u32 {
    4 * s.chars().count() as u32 - 1
}

fn draw_text(img: &mut Rgb, x: u32, y: u32, s: &str, colour: [u8; 3]) {
    for (k, c) in s.chars().enumerate() {
        for (dy, bits) in glyph(c).iter().enumerate() {
            for dx in 0..3 {
                if bits >> (2 - dx) & 1 == 1 {
                    img.set(x + 4 * k as u32 + dx, y + dy as u32, colour);
                }
            }
        }
    }
}

/// Error statistics of values against a reference: over the compared
/// values, `e = value − reference`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "report", derive(serde::Serialize, serde::Deserialize))]
pub struct ErrorSummary {
    /// How many values were compared.
    pub count: usize,
    /// Mean of `|e|`.
    pub mean_abs: f64,
    /// `√(mean e²)`.
    pub rmse: f64,
    /// The 99th percentile of `|e|` (nearest rank).
    pub p99_abs: f64,
    /// The largest `|e|`.
    pub max_abs: f64,
    /// Mean of `e` (the bias: negative is too dark).
    pub mean_signed: f64,
    /// The share of values with `|e| > 0.05`.
    pub share_over_0_05: f64,
}

impl ErrorSummary {
    /// The statistics of `e = values[i] − reference[i]` over the indices
    /// `i` where `keep(i)`; all zero when none is kept. The slices must have
    /// the same length (the shorter one bounds the comparison).
    #[must_use]
    pub fn new(values: &[f64], reference: &[f64], keep: impl Fn(usize) -> bool) -> ErrorSummary {
        let errors: Vec<f64> = values
            .iter()
            .zip(reference)
            .enumerate()
            .filter(|&(i, _)| keep(i))
            .map(|(_, (v, r))| v - r)
            .collect();
        let count = errors.len();
        if count == 0 {
            return ErrorSummary::default();
        }
        let n = count as f64;
        let mut abs: Vec<f64> = errors.iter().map(|e| e.abs()).collect();
        abs.sort_unstable_by(f64::total_cmp);
        let rank = ((0.99 * n).ceil() as usize).clamp(1, count) - 1;
        ErrorSummary {
            count,
            mean_abs: abs.iter().sum::<f64>() / n,
            rmse: (errors.iter().map(|e| e * e).sum::<f64>() / n).sqrt(),
            p99_abs: abs[rank],
            max_abs: abs[count - 1],
            mean_signed: errors.iter().sum::<f64>() / n,
            share_over_0_05: abs.iter().filter(|&&a| a > 0.05).count() as f64 / n,
        }
    }
}

/// One row of the error table the `softshadow` program prints (and the
/// README shows): a method's errors against the exact values over every
/// receiver and over the exact penumbra, with its time.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorRow {
    /// The method's name.
    pub method: String,
    /// Its time, in seconds.
    pub seconds: f64,
    /// The errors over every receiver.
    pub all: ErrorSummary,
    /// The errors over the exact penumbra ([`in_penumbra`]).
    pub penumbra: ErrorSummary,
}

impl ErrorRow {
    /// The table's header, two Markdown lines.
    pub const HEADER: &'static str = "| method | time (ms) | mean abs | RMSE | max | mean signed | RMSE penumbra |\n|---|---:|---:|---:|---:|---:|---:|";

    /// The row of `values` against `exact` (same length and order; the
    /// shorter bounds the comparison).
    #[must_use]
    pub fn new(method: impl Into<String>, seconds: f64, values: &[f64], exact: &[f64]) -> ErrorRow {
        ErrorRow {
            method: method.into(),
            seconds,
            all: ErrorSummary::new(values, exact, |_| true),
            penumbra: ErrorSummary::new(values, exact, |i| in_penumbra(exact[i])),
        }
    }
}

impl fmt::Display for ErrorRow {
    /// The Markdown row under [`ErrorRow::HEADER`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "| {} | {:.1} | {:.5} | {:.5} | {:.4} | {:+.5} | {:.5} |",
            self.method,
            self.seconds * 1e3,
            self.all.mean_abs,
            self.all.rmse,
            self.all.max_abs,
            self.all.mean_signed,
            self.penumbra.rmse
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_encoding_matches_the_standard_at_known_points() {
        assert_eq!(srgb8(0.0), 0);
        assert_eq!(srgb8(1.0), 255);
        // 1.055 · 0.5^(1/2.4) − 0.055 = 0.73536 → 187.52.
        assert_eq!(srgb8(0.5), 188);
        // The linear toe: 12.92 · 0.002 · 255 = 6.59.
        assert_eq!(srgb8(0.002), 7);
        assert_eq!(srgb8(f64::NAN), 0);
        assert_eq!(srgb8(7.0), 255);
    }

    #[test]
    fn the_heat_scale_is_white_at_zero_blue_below_red_above_and_saturates() {
        assert_eq!(heat_colour(0.0), [255, 255, 255]);
        let [r, g, b] = heat_colour(-HEAT_RANGE);
        assert!(b > r && b > g, "too dark is blue: {r} {g} {b}");
        let [r, g, b] = heat_colour(HEAT_RANGE);
        assert!(r > g && r > b, "too bright is red: {r} {g} {b}");
        assert_eq!(heat_colour(HEAT_RANGE), heat_colour(1.0));
        assert_eq!(heat_colour(-HEAT_RANGE), heat_colour(-1.0));
        // Half the range is lighter than the full colour.
        assert!(heat_colour(0.5 * HEAT_RANGE)[1] > heat_colour(HEAT_RANGE)[1]);
    }

    #[test]
    fn error_summaries_match_hand_computed_values() {
        let reference = [0.0, 0.5, 1.0, 1.0];
        let values = [0.1, 0.5, 0.9, 0.7];
        // e = 0.1, 0, −0.1, −0.3.
        let s = ErrorSummary::new(&values, &reference, |_| true);
        assert_eq!(s.count, 4);
        assert!((s.mean_abs - 0.125).abs() < 1e-15);
        assert!((s.rmse - (0.11f64 / 4.0).sqrt()).abs() < 1e-15);
        assert!((s.max_abs - 0.3).abs() < 1e-15);
        assert!((s.p99_abs - 0.3).abs() < 1e-15);
        assert!((s.mean_signed + 0.075).abs() < 1e-15);
        assert_eq!(s.share_over_0_05, 0.75);
        let only = ErrorSummary::new(&values, &reference, |i| i == 1);
        assert_eq!((only.count, only.max_abs), (1, 0.0));
        assert_eq!(
            ErrorSummary::new(&values, &reference, |_| false),
            ErrorSummary::default()
        );
    }

    #[test]
    fn the_penumbra_group_ignores_the_exact_answers_last_bits() {
        use crate::definitions::PENUMBRA_MARGIN as M;
        // Rounding residues of a covered or an unobstructed light (as the
        // exact reference leaves them: 1e-16, 1 − 2⁻⁵³) are not penumbra;
        // the margin's own ends are not; a hair inside them is.
        let exact = [
            0.0,
            1e-16,
            M,
            M.next_up(),
            0.5,
            (1.0 - M).next_down(),
            1.0 - M,
            1.0 - f64::EPSILON / 2.0,
            1.0,
            f64::NAN,
        ];
        let inside: Vec<usize> = (0..exact.len())
            .filter(|&i| in_penumbra(exact[i]))
            .collect();
        assert_eq!(inside, [3, 4, 5]);
        let row = ErrorRow::new("m", 0.0, &[0.25; 10], &exact);
        assert_eq!(row.penumbra.count, 3);
    }

    #[cfg(unix)]
    #[test]
    fn pictures_replace_a_symlink_and_leave_no_temporary_file() {
        let dir = std::env::temp_dir().join(format!("softshadow-atomic-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("precious.txt");
        std::fs::write(&target, b"keep me").unwrap();
        let link = dir.join("picture.png");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let img = Rgb::new(3, 2, [10, 20, 30]);
        img.write_png(&link).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"keep me");
        assert!(!std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        let decoded =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&link).unwrap()))
                .read_info()
                .unwrap();
        assert_eq!((decoded.info().width, decoded.info().height), (3, 2));
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 2, "{names:?}");
        // A folder that does not exist: an error, and nothing left behind.
        assert!(img.write_png(&dir.join("missing").join("x.png")).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
