//! Float arrays and images in files (feature `float-io`): NumPy `.npy`
//! (through `ndarray-npy`), OpenEXR (through `exr`) and PFM, read and
//! written for the G-buffer and scoring workflow
//! (`output::gbuffer` and `output::score`, feature `render`).
//!
//! # Bad and hostile input
//!
//! Every reader works on the file's bytes (read whole, regular files only,
//! at most [`MAX_FILE_BYTES`]) and checks what a header declares against
//! what the file holds **before** anything of the declared size is
//! allocated:
//!
//! - `.npy`: the header's own length against the file; the shape's element
//!   count (overflow-checked) times the item size must equal the data that
//!   follows the header exactly.
//! - `.exr`: the first layer's pixels at most [`MAX_PIXELS`], and its
//!   decoded size (every channel) at most [`EXR_MAX_RATIO`] times the
//!   file's length — the most lossless compression gains on real images is
//!   far less; a small file declaring a huge image is refused.
//! - `.pfm`: the declared size times 4 bytes must equal the data exactly.
//!
//! So the memory a read takes is bounded by a fixed multiple of the file's
//! real size, whatever its header says. Errors are one line naming the
//! problem ([`FloatIoError`] adds the file).
//!
//! Arrays are row-major (C order; a Fortran-order `.npy` is reordered),
//! row 0 the top of an image; values are returned as `f64` (from `float32`
//! or `float64`) or `i64` (from `int32` or `int64`).

mod exr_file;
mod npy;
mod pfm;

pub use exr_file::{exr_bytes, read_exr, ExrChannel, ExrImage};
pub use npy::{npy_bytes_f32, npy_bytes_f64, npy_bytes_i32, read_npy_f64, read_npy_i64};
pub use pfm::{pfm_bytes, read_pfm};

use std::path::Path;

/// The largest file any reader here opens: 16 GiB.
pub const MAX_FILE_BYTES: u64 = 16 << 30;

/// The largest image, in pixels, an `.exr` or `.pfm` may declare:
/// `16384²`, the renderer's largest frame.
pub const MAX_PIXELS: u64 = 1 << 28;

/// An `.exr`'s decoded channels may take at most this many times the
/// file's length.
pub const EXR_MAX_RATIO: u64 = 4096;

/// An array read from a file: its shape and its values in row-major order.
#[derive(Clone, Debug, PartialEq)]
pub struct Array<T> {
    /// The extent of each axis, slowest first.
    pub shape: Vec<usize>,
    /// `shape.iter().product()` values, row-major.
    pub data: Vec<T>,
}

/// What is wrong with a float file's bytes, or with values to be written
/// as one: one line each.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum FormatError {
    /// Not a file of the kind read (told by its first bytes).
    NotThisKind(String),
    /// A header that is malformed, truncated, or declares what the file
    /// does not hold or more than the limits allow (a hostile header).
    Malformed(String),
    /// A well-formed file holding what is not read here: another dtype, a
    /// rank or shape that is not an image's, a colour or subsampled
    /// channel, no channel `V` among several, deep data only.
    Unsupported(String),
    /// Values that cannot be written as asked: their count against the
    /// shape, no channel, no pixels, or the encoder's error.
    Unwritable(String),
}

impl_error!(FormatError, |error, f| match error {
    FormatError::NotThisKind(what)
    | FormatError::Malformed(what)
    | FormatError::Unsupported(what)
    | FormatError::Unwritable(what) => f.write_str(what),
});

/// A file that could not be read or written: the file and the problem, one
/// line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FloatIoError {
    /// The file, as given.
    pub file: String,
    /// What is wrong, one line.
    pub message: String,
}

impl_error!(FloatIoError, |error, f| {
    write!(f, "{}: {}", error.file, error.message)
});

impl FloatIoError {
    /// An error about `path`.
    #[must_use]
    pub fn new(path: &Path, message: impl Into<String>) -> FloatIoError {
        FloatIoError {
            file: path.display().to_string(),
            message: message.into(),
        }
    }
}

/// The bytes of the regular file `path`, at most [`MAX_FILE_BYTES`].
///
/// # Errors
/// Not a regular file, too long, or unreadable.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, FloatIoError> {
    crate::scene::file::read_input(path, MAX_FILE_BYTES)
        .map_err(|e| FloatIoError::new(path, e.to_string()))
}

/// The kinds of file an image of `V` may be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageKind {
    /// NumPy `.npy`.
    Npy,
    /// OpenEXR.
    Exr,
    /// Portable float map.
    Pfm,
}

impl ImageKind {
    /// The kind from the file's first bytes (its magic number), whatever
    /// its name.
    #[must_use]
    pub fn sniff(bytes: &[u8]) -> Option<ImageKind> {
        if bytes.starts_with(b"\x93NUMPY") {
            Some(ImageKind::Npy)
        } else if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
            Some(ImageKind::Exr)
        } else if bytes.starts_with(b"Pf") || bytes.starts_with(b"PF") {
            Some(ImageKind::Pfm)
        } else {
            None
        }
    }
}

/// A single-channel image, `height × width` values, row 0 the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width · height` values, row-major from the top-left.
    pub data: Vec<f64>,
}

/// An image of one value per pixel from a file's bytes, the format told by
/// its magic number: an `.npy` of shape `H×W` (or `H×W×1`, float32 or
/// float64); an `.exr`'s channel named `V`, else its only channel; a
/// greyscale `.pfm` (`Pf`).
///
/// # Errors
/// [`FormatError::NotThisKind`]: none of the three formats;
/// [`FormatError::Unsupported`]: a wrong dtype or rank, a missing channel;
/// [`FormatError::Malformed`]: a truncated or hostile header.
pub fn image_from_bytes(bytes: &[u8]) -> Result<Image, FormatError> {
    match ImageKind::sniff(bytes) {
        Some(ImageKind::Npy) => {
            let a = read_npy_f64(bytes)?;
            match a.shape[..] {
                [h, w] | [h, w, 1] => Ok(Image {
                    width: w,
                    height: h,
                    data: a.data,
                }),
                _ => Err(FormatError::Unsupported(format!(
                    "shape {:?}: an image of V is H×W (or H×W×1)",
                    a.shape
                ))),
            }
        }
        Some(ImageKind::Exr) => {
            let image = read_exr(bytes)?;
            // Names as written, control characters escaped: one line.
            let names: Vec<String> = image
                .channels
                .iter()
                .map(|c| c.name.escape_debug().to_string())
                .collect();
            let pick = match image.channels.iter().position(|c| c.name == "V") {
                Some(k) => k,
                None if image.channels.len() == 1 => 0,
                None => {
                    return Err(FormatError::Unsupported(format!(
                        "no channel named V and {} channels ({}); write V as a channel named V",
                        names.len(),
                        names.join(", ")
                    )))
                }
            };
            let (width, height) = (image.width, image.height);
            let data = image.channels.into_iter().nth(pick).map(|c| c.data);
            Ok(Image {
                width,
                height,
                data: data.unwrap_or_default(),
            })
        }
        Some(ImageKind::Pfm) => read_pfm(bytes),
        None => Err(FormatError::NotThisKind(
            "not a .npy, .exr or .pfm file (by its first bytes)".to_owned(),
        )),
    }
}

/// [`image_from_bytes`] of the file at `path`.
///
/// # Errors
/// [`FloatIoError`]: the file and the problem.
pub fn read_image(path: &Path) -> Result<Image, FloatIoError> {
    let bytes = read_bytes(path)?;
    image_from_bytes(&bytes).map_err(|e| FloatIoError::new(path, e.to_string()))
}

#[cfg(test)]
mod tests;
