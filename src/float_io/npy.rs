//! NumPy `.npy` through `ndarray-npy`, with the declared size checked
//! against the bytes before anything is allocated.

use super::{Array, FormatError};
use ndarray::{ArrayD, IxDyn};
use ndarray_npy::npy::header::Header;
use ndarray_npy::{ReadNpyExt, ReadableElement, WritableElement, WriteNpyExt};

/// The element types read here: `(descriptor, bytes)`.
const FLOATS: [(&str, usize); 4] = [("<f8", 8), (">f8", 8), ("<f4", 4), (">f4", 4)];
const INTS: [(&str, usize); 4] = [("<i4", 4), (">i4", 4), ("<i8", 8), (">i8", 8)];

/// What the header says, checked against the bytes: the descriptor, the
/// shape and whether the data is in Fortran order.
struct Checked {
    descr: &'static str,
    shape: Vec<usize>,
}

/// Parses and checks the header of `bytes` against the element types
/// `allowed` (`what` names them for the error): the header's own length
/// fits the file, the shape's element count times the item size is exactly
/// the data after the header.
fn check(
    bytes: &[u8],
    allowed: &[(&'static str, usize)],
    what: &str,
) -> Result<Checked, FormatError> {
    // The header's length field, before the crate allocates a buffer of
    // that length (up to 4 GiB for format 2 and 3).
    if bytes.len() >= 10 && bytes.starts_with(b"\x93NUMPY") {
        let (len, at) = match bytes[6] {
            1 => (usize::from(u16::from_le_bytes([bytes[8], bytes[9]])), 10),
            _ if bytes.len() >= 12 => (
                u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
                12,
            ),
            _ => (usize::MAX, 12),
        };
        if len > bytes.len().saturating_sub(at) {
            return Err(FormatError::Malformed(format!(
                "truncated or hostile .npy header: it declares {len} header bytes, the file has {}",
                bytes.len().saturating_sub(at)
            )));
        }
    }
    let mut rest = bytes;
    let header = Header::from_reader(&mut rest).map_err(|e| {
        FormatError::Malformed(format!(".npy header: {}", one_line(&e.to_string())))
    })?;
    let descr = descriptor(&header.type_descriptor);
    let Some(&(name, size)) = allowed.iter().find(|(d, _)| Some(*d) == descr.as_deref()) else {
        return Err(FormatError::Unsupported(format!(
            "dtype {}: expected {what}",
            descr.unwrap_or_else(|| header.type_descriptor.to_string())
        )));
    };
    let count = header
        .shape
        .iter()
        .try_fold(1usize, |n, &d| n.checked_mul(d))
        .and_then(|n| n.checked_mul(size));
    match count {
        Some(n) if n == rest.len() => Ok(Checked {
            descr: name,
            shape: header.shape,
        }),
        Some(n) => Err(FormatError::Malformed(format!(
            "shape {:?} of {name} is {n} bytes of data, the file has {} after its header{}",
            header.shape,
            rest.len(),
            if n > rest.len() {
                " (truncated, or a hostile header)"
            } else {
                ""
            }
        ))),
        None => Err(FormatError::Malformed(format!(
            "shape {:?}: the declared size overflows (a hostile header)",
            header.shape
        ))),
    }
}

/// The values of an array of `T` in the file, row-major.
fn values<T: ReadableElement + Copy>(bytes: &[u8]) -> Result<Vec<T>, FormatError> {
    let a = ArrayD::<T>::read_npy(bytes)
        .map_err(|e| FormatError::Malformed(format!(".npy data: {}", one_line(&e.to_string()))))?;
    Ok(a.iter().copied().collect())
}

/// An array of one of the `allowed` dtypes (named `what` in the error),
/// read as `Wide`: the 8-byte type (descr ending in `8`) as it is, the
/// 4-byte type `Narrow` widened.
fn read_either<Wide, Narrow>(
    bytes: &[u8],
    allowed: &[(&'static str, usize)],
    what: &str,
) -> Result<Array<Wide>, FormatError>
where
    Wide: ReadableElement + Copy + From<Narrow>,
    Narrow: ReadableElement + Copy,
{
    let c = check(bytes, allowed, what)?;
    let data = if c.descr.ends_with('8') {
        values::<Wide>(bytes)?
    } else {
        values::<Narrow>(bytes)?
            .into_iter()
            .map(Wide::from)
            .collect()
    };
    Ok(Array {
        shape: c.shape,
        data,
    })
}

/// A float array (`float32` or `float64`, either byte order, C or Fortran
/// order) from an `.npy` file's bytes, as `f64` in row-major order.
///
/// # Errors
/// [`FormatError::Malformed`]: not an `.npy`, a size that does not match
/// the file (truncated or hostile); [`FormatError::Unsupported`]: another
/// dtype.
pub fn read_npy_f64(bytes: &[u8]) -> Result<Array<f64>, FormatError> {
    read_either::<f64, f32>(bytes, &FLOATS, "float32 or float64")
}

/// An integer array (`int32` or `int64`) from an `.npy` file's bytes, as
/// `i64` in row-major order.
///
/// # Errors
/// As [`read_npy_f64`].
pub fn read_npy_i64(bytes: &[u8]) -> Result<Array<i64>, FormatError> {
    read_either::<i64, i32>(bytes, &INTS, "int32 or int64")
}

/// The `.npy` bytes of `data` with `shape` (row-major, little-endian).
fn bytes_of<T: WritableElement + Clone>(
    shape: &[usize],
    data: &[T],
) -> Result<Vec<u8>, FormatError> {
    let a = ArrayD::from_shape_vec(IxDyn(shape), data.to_vec()).map_err(|e| {
        FormatError::Unwritable(format!("shape {shape:?} for {} values: {e}", data.len()))
    })?;
    let mut out = Vec::new();
    a.write_npy(&mut out)
        .map_err(|e| FormatError::Unwritable(e.to_string()))?;
    Ok(out)
}

/// The `.npy` bytes (`<f8`) of `data` with `shape`, row-major.
///
/// # Errors
/// [`FormatError::Unwritable`]: `data.len()` is not the shape's element
/// count.
pub fn npy_bytes_f64(shape: &[usize], data: &[f64]) -> Result<Vec<u8>, FormatError> {
    bytes_of(shape, data)
}

/// The `.npy` bytes (`<f4`) of `data` with `shape`, row-major.
///
/// # Errors
/// As [`npy_bytes_f64`].
pub fn npy_bytes_f32(shape: &[usize], data: &[f32]) -> Result<Vec<u8>, FormatError> {
    bytes_of(shape, data)
}

/// The `.npy` bytes (`<i4`) of `data` with `shape`, row-major.
///
/// # Errors
/// As [`npy_bytes_f64`].
pub fn npy_bytes_i32(shape: &[usize], data: &[i32]) -> Result<Vec<u8>, FormatError> {
    bytes_of(shape, data)
}

/// The dtype string of a header's `descr` (`<f8` and the like), printed
/// by the header's own Python-literal writer as `'<f8'`; `None` for a
/// structured dtype.
fn descriptor(value: &impl std::fmt::Display) -> Option<String> {
    let text = value.to_string();
    let inner = text.strip_prefix('\'')?.strip_suffix('\'')?;
    (!inner.contains(['\'', '"'])).then(|| inner.to_owned())
}

/// A crate's message on one line.
pub(super) fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}
