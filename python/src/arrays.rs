//! Arrays from Python: float and integer arrays read in place or widened
//! exactly, their layout and shape checked, and the receivers of a points
//! array built from them under the points file's rules; the `ValueError`
//! every refused argument raises.

use numpy::{
    PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;
use softshadow::glam::DVec3;
use softshadow::render::Receiver;
use softshadow::scene::file::{receiver_from, ReceiverField};

/// A `ValueError` with the library's one-line message.
pub(crate) fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}

/// A float array read from Python: borrowed in place (C-contiguous
/// float64) or widened from float32.
pub(crate) enum Floats<'py> {
    Borrowed(numpy::PyReadonlyArrayDyn<'py, f64>),
    Owned(Vec<f64>),
}

impl Floats<'_> {
    pub(crate) fn as_slice(&self) -> &[f64] {
        match self {
            // Contiguous and aligned: checked by `floats` before it keeps
            // a borrowed array.
            Floats::Borrowed(a) => a.as_slice().unwrap_or_default(),
            Floats::Owned(v) => v,
        }
    }
}

/// `obj` as an array: a numpy array as it is, anything else through
/// `numpy.asarray` (a list of lists, say).
pub(crate) fn as_array<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<Bound<'py, PyUntypedArray>> {
    if let Ok(a) = obj.cast::<PyUntypedArray>() {
        if a.is_aligned() {
            return Ok(a.clone());
        }
        // An array over a byte buffer at an odd address (as
        // dask.distributed deserialises them) cannot be read in place:
        // an aligned copy, of the same layout.
        return a
            .call_method0("copy")?
            .cast_into::<PyUntypedArray>()
            .map_err(|_| value_error(format!("{what}: not an array")));
    }
    let np = obj.py().import("numpy")?;
    let a = np
        .call_method1("asarray", (obj,))
        .map_err(|e| value_error(format!("{what}: not an array ({e})")))?;
    a.cast_into::<PyUntypedArray>()
        .map_err(|_| value_error(format!("{what}: not an array")))
}

/// Checks `a`'s number of dimensions and C-contiguity.
fn check_layout(
    a: &Bound<'_, PyUntypedArray>,
    what: &str,
    shape: &str,
    ndim: usize,
) -> PyResult<()> {
    if a.ndim() != ndim || (ndim == 2 && a.shape()[1] != 3 && shape.ends_with("3)")) {
        return Err(value_error(format!(
            "{what}: shape {:?}, expected {shape}",
            a.shape()
        )));
    }
    if !a.is_c_contiguous() {
        return Err(value_error(format!(
            "{what}: the array is not C-contiguous (a strided view or a transpose); \
             numpy.ascontiguousarray({what}) makes a contiguous copy"
        )));
    }
    Ok(())
}

/// A float array of `ndim` dimensions (`shape` says which, for messages):
/// float64 read in place, float32 widened; every value finite unless
/// `nan_ok`.
pub(crate) fn floats<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    shape: &str,
    ndim: usize,
) -> PyResult<(Floats<'py>, Vec<usize>)> {
    let a = as_array(obj, what)?;
    check_layout(&a, what, shape, ndim)?;
    let dims = a.shape().to_vec();
    let dtype = a.dtype();
    let floats = if dtype.is_equiv_to(&numpy::dtype::<f64>(a.py())) {
        let a = a.cast::<PyArrayDyn<f64>>()?;
        let r = a
            .try_readonly()
            .map_err(|e| value_error(format!("{what}: {e}")))?;
        r.as_slice()
            .map_err(|e| value_error(format!("{what}: {e}")))?;
        Floats::Borrowed(r)
    } else if dtype.is_equiv_to(&numpy::dtype::<f32>(a.py())) {
        let a = a.cast::<PyArrayDyn<f32>>()?;
        let r = a
            .try_readonly()
            .map_err(|e| value_error(format!("{what}: {e}")))?;
        Floats::Owned(
            r.as_slice()
                .map_err(|e| value_error(format!("{what}: {e}")))?
                .iter()
                .map(|&x| f64::from(x))
                .collect(),
        )
    } else {
        return Err(value_error(format!(
            "{what}: dtype {}, expected float64 (or float32)",
            dtype.str()?
        )));
    };
    Ok((floats, dims))
}

/// An integer array of `ndim` dimensions as `i64` (any signed or unsigned
/// integer dtype whose values fit).
pub(crate) fn integers(
    obj: &Bound<'_, PyAny>,
    what: &str,
    shape: &str,
    ndim: usize,
) -> PyResult<(Vec<i64>, Vec<usize>)> {
    let a = as_array(obj, what)?;
    check_layout(&a, what, shape, ndim)?;
    let dims = a.shape().to_vec();
    let dtype = a.dtype();
    let py = a.py();
    macro_rules! read {
        ($($t:ty),*) => {
            $(
                if dtype.is_equiv_to(&numpy::dtype::<$t>(py)) {
                    let a = a.cast::<PyArrayDyn<$t>>()?;
                    let r = a.try_readonly().map_err(|e| value_error(format!("{what}: {e}")))?;
                    let s = r.as_slice().map_err(|e| value_error(format!("{what}: {e}")))?;
                    return s
                        .iter()
                        .map(|&x| {
                            i64::try_from(x).map_err(|_| value_error(format!("{what}: {x} is out of range")))
                        })
                        .collect::<PyResult<Vec<i64>>>()
                        .map(|v| (v, dims));
                }
            )*
        };
    }
    read!(i64, i32, i16, i8, u64, u32, u16, u8);
    Err(value_error(format!(
        "{what}: dtype {}, expected integers (int64, int32, …)",
        dtype.str()?
    )))
}

/// The receivers of `points` (N×3), with `normals` (N×3) and `objects`
/// (N) when given, under the points file's rules ([`receiver_from`]).
pub(crate) fn receivers(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    normals: Option<&Bound<'_, PyAny>>,
    objects: Option<&Bound<'_, PyAny>>,
    meshes: usize,
) -> PyResult<Vec<Receiver>> {
    let (p, shape) = floats(points, "points", "(n, 3)", 2)?;
    let n = shape[0];
    // An array beside `points` has its n rows.
    let rows = |what: &str, s: &[usize], want: &str| {
        if s[0] == n {
            Ok(())
        } else {
            Err(value_error(format!(
                "{what}: shape {s:?}, points has {n} rows (expected {want})"
            )))
        }
    };
    let normals = normals
        .map(|obj| {
            let (a, s) = floats(obj, "normals", "(n, 3)", 2)?;
            rows("normals", &s, &format!("[{n}, 3]")).map(|()| a)
        })
        .transpose()?;
    let objects = objects
        .map(|obj| {
            let (a, s) = integers(obj, "objects", "(n,)", 1)?;
            rows("objects", &s, &format!("[{n}]")).map(|()| a)
        })
        .transpose()?;
    let p = p.as_slice();
    let nrm = normals.as_ref().map(Floats::as_slice);
    let objects = objects.as_deref();
    let build = |i: usize| {
        let row = |a: &[f64]| [a[3 * i], a[3 * i + 1], a[3 * i + 2]];
        receiver_from(row(p), nrm.map(row), objects.map(|o| o[i]), meshes)
    };
    // In parallel and without the GIL: the first row at fault, then the
    // receivers, written in place.
    let built = py.detach(|| {
        if let Some(i) = (0..n).into_par_iter().position_first(|i| build(i).is_err()) {
            return Err((i, build(i).err()));
        }
        let mut out = Vec::with_capacity(n);
        (0..n)
            .into_par_iter()
            .map(|i| build(i).unwrap_or(UNREACHED))
            .collect_into_vec(&mut out);
        Ok(out)
    });
    built.map_err(|(i, e)| {
        let (field, message) = e.unwrap_or((ReceiverField::Position, String::new()));
        let array = match field {
            ReceiverField::Position => "points",
            ReceiverField::Normal => "normals",
            ReceiverField::Object => "objects",
        };
        value_error(format!("{array}: row {i}: {message}"))
    })
}

/// A receiver standing for one [`receiver_from`] refused, where every row
/// was checked before (never in a result).
const UNREACHED: Receiver = Receiver {
    position: DVec3::ZERO,
    normal: None,
    object: None,
};
