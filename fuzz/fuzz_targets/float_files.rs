//! The `.npy`, `.exr` and `.pfm` readers on fuzzed bytes: no panic; an
//! error is one line; what reads has as many values as its shape says, and
//! the memory it takes is bounded by the file's size (an `.npy`'s data is
//! exactly the file after its header; an `.exr`'s decoded channels at most
//! `EXR_MAX_RATIO` times the file; a `.pfm`'s 4 bytes a pixel); an array
//! written back and read again is the same bits.
//!
//! The first byte picks the reader (0: npy as floats, 1: npy as integers,
//! 2: exr, 3: pfm, 4–255: by magic number as an image of V); a seed corpus
//! of valid files of each kind helps (`softshadow gbuffer` writes some).
#![no_main]

use libfuzzer_sys::fuzz_target;
use softshadow::float_io::{
    image_from_bytes, npy_bytes_f64, read_exr, read_npy_f64, read_npy_i64, read_pfm,
    EXR_MAX_RATIO,
};

fn one_line(e: &str) {
    assert!(!e.contains('\n'), "{e}");
}

fn product(shape: &[usize]) -> usize {
    shape.iter().product()
}

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    match pick {
        0 => match read_npy_f64(bytes) {
            Ok(a) => {
                assert_eq!(a.data.len(), product(&a.shape));
                assert!(a.data.len() * 4 <= bytes.len());
                let again = read_npy_f64(&npy_bytes_f64(&a.shape, &a.data).unwrap()).unwrap();
                assert_eq!(again.shape, a.shape);
                assert!(again
                    .data
                    .iter()
                    .zip(&a.data)
                    .all(|(x, y)| x.to_bits() == y.to_bits()));
            }
            Err(e) => one_line(&e),
        },
        1 => match read_npy_i64(bytes) {
            Ok(a) => {
                assert_eq!(a.data.len(), product(&a.shape));
                assert!(a.data.len() * 4 <= bytes.len());
            }
            Err(e) => one_line(&e),
        },
        2 => match read_exr(bytes) {
            Ok(img) => {
                let decoded: usize = img.channels.len() * img.width * img.height * 2;
                assert!(decoded as u64 <= EXR_MAX_RATIO * bytes.len() as u64);
                for c in &img.channels {
                    assert_eq!(c.data.len(), img.width * img.height);
                }
            }
            Err(e) => one_line(&e),
        },
        3 => match read_pfm(bytes) {
            Ok(img) => {
                assert_eq!(img.data.len(), img.width * img.height);
                assert!(img.data.len() * 4 <= bytes.len());
            }
            Err(e) => one_line(&e),
        },
        _ => match image_from_bytes(bytes) {
            Ok(img) => assert_eq!(img.data.len(), img.width * img.height),
            Err(e) => one_line(&e),
        },
    }
});
