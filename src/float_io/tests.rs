//! Round trips and hostile input for the readers.

use super::*;

/// Non-dyadic values with NaN and infinities among them.
fn values(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| match k % 7 {
            3 => f64::NAN,
            5 => f64::NEG_INFINITY,
            _ => (k as f64 * 0.618_033_988_749_894_9).fract() * 1e6 - 3.3e5,
        })
        .collect()
}

fn same(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()))
}

#[test]
fn npy_float64_float32_and_int32_round_trip() {
    let v = values(5 * 3 * 2);
    let bytes = npy_bytes_f64(&[5, 3, 2], &v).unwrap();
    let a = read_npy_f64(&bytes).unwrap();
    assert_eq!(a.shape, vec![5, 3, 2]);
    assert!(same(&a.data, &v));
    let v32: Vec<f32> = v.iter().map(|&x| x as f32).collect();
    let a = read_npy_f64(&npy_bytes_f32(&[30], &v32).unwrap()).unwrap();
    assert!(same(
        &a.data,
        &v32.iter().map(|&x| f64::from(x)).collect::<Vec<_>>()
    ));
    let ids = [-1, 0, 7, i32::MAX, i32::MIN];
    let a = read_npy_i64(&npy_bytes_i32(&[5], &ids).unwrap()).unwrap();
    assert_eq!(a.data, ids.map(i64::from));
    // Integers are not floats, floats are not integers.
    let e = read_npy_f64(&npy_bytes_i32(&[5], &ids).unwrap())
        .unwrap_err()
        .to_string();
    assert!(e.contains("<i4") && e.contains("float"), "{e}");
    assert!(read_npy_i64(&bytes)
        .unwrap_err()
        .to_string()
        .contains("<f8"));
    assert!(npy_bytes_f64(&[2, 2], &[1.0]).is_err());
}

#[test]
fn npy_in_fortran_order_and_big_endian_reads_row_major() {
    use ndarray::{ArrayD, IxDyn, ShapeBuilder};
    use ndarray_npy::WriteNpyExt;
    // Column-major storage of [[1, 2, 3], [4, 5, 6]].
    let a = ArrayD::from_shape_vec(IxDyn(&[2, 3]).f(), vec![1.0, 4.0, 2.0, 5.0, 3.0, 6.0]).unwrap();
    let mut bytes = Vec::new();
    a.write_npy(&mut bytes).unwrap();
    assert!(String::from_utf8_lossy(&bytes[..80]).contains("'fortran_order': True"));
    let r = read_npy_f64(&bytes).unwrap();
    assert_eq!(r.data, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    // The same little-endian file rewritten as big-endian by hand.
    let mut be = npy_bytes_f64(&[3], &[0.1, -2.5, 1e300]).unwrap();
    let at = be.windows(3).position(|w| w == b"<f8").unwrap();
    be[at] = b'>';
    let data_at = be.len() - 24;
    be.truncate(data_at);
    for x in [0.1f64, -2.5, 1e300] {
        be.extend_from_slice(&x.to_be_bytes());
    }
    assert_eq!(read_npy_f64(&be).unwrap().data, vec![0.1, -2.5, 1e300]);
}

/// An `.npy` file with the given header dictionary and data bytes.
fn npy_with(dict: &str, major: u8, data: &[u8]) -> Vec<u8> {
    let mut text = dict.to_owned();
    let pre = if major == 1 { 10 } else { 12 };
    while (pre + text.len() + 1) % 64 != 0 {
        text.push(' ');
    }
    text.push('\n');
    let mut out = b"\x93NUMPY".to_vec();
    out.extend([major, 0]);
    if major == 1 {
        out.extend((text.len() as u16).to_le_bytes());
    } else {
        out.extend((text.len() as u32).to_le_bytes());
    }
    out.extend(text.as_bytes());
    out.extend(data);
    out
}

#[test]
fn hostile_and_truncated_npy_headers_are_refused_before_allocating() {
    // The header of a float64 array of `shape`, C order.
    let f8 =
        |shape: &str| format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    let ok = npy_with(&f8("(2, 2)"), 1, &[0; 32]);
    assert_eq!(read_npy_f64(&ok).unwrap().shape, vec![2, 2]);
    for (dict, major, data, needle) in [
        // A shape of 10¹⁸ elements in a file of a few bytes.
        (f8("(1000000000, 1000000000)"), 1, &[0u8; 8][..], "hostile"),
        // A shape whose size overflows 64 bits.
        (
            f8("(4294967296, 4294967296, 4294967296)"),
            2,
            &[0u8; 8][..],
            "overflow",
        ),
        // One value short.
        (f8("(2, 2)"), 1, &[0u8; 24][..], "truncated"),
        // One value too many.
        (f8("(2, 2)"), 1, &[0u8; 40][..], "after its header"),
        (
            "{'descr': '<c16', 'fortran_order': False, 'shape': (1,), }".to_owned(),
            1,
            &[0u8; 16][..],
            "dtype",
        ),
        (
            "{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (1,), }".to_owned(),
            1,
            &[0u8; 8][..],
            "dtype",
        ),
        (
            "{'descr': '<f8', 'shape': (1,), }".to_owned(),
            1,
            &[0u8; 8][..],
            "header",
        ),
        ("not a dict at all".to_owned(), 1, &[0u8; 8][..], "header"),
    ] {
        let bytes = npy_with(&dict, major, data);
        let e = read_npy_f64(&bytes).unwrap_err().to_string();
        assert!(e.contains(needle), "{dict}: {e}");
        assert!(!e.contains('\n'), "{e}");
    }
    // A format-2 header declaring 4 GiB of header text in a 20-byte file.
    let mut bytes = b"\x93NUMPY\x02\x00".to_vec();
    bytes.extend(u32::MAX.to_le_bytes());
    bytes.extend(b"{'descr'");
    let e = read_npy_f64(&bytes).unwrap_err().to_string();
    assert!(e.contains("header"), "{e}");
    // Every prefix of a good file is refused with one line, never a panic.
    for n in 0..ok.len() {
        let e = read_npy_f64(&ok[..n]).unwrap_err().to_string();
        assert!(!e.contains('\n'), "{e}");
    }
}

#[test]
fn exr_round_trips_float32_channels_and_picks_v() {
    let (w, h) = (7, 5);
    let v: Vec<f32> = values(w * h).iter().map(|&x| x as f32).collect();
    let other: Vec<f32> = (0..w * h).map(|k| k as f32 * 0.5).collect();
    let bytes = exr_bytes(w, h, &[("V", v.clone()), ("error", other.clone())]).unwrap();
    let img = read_exr(&bytes).unwrap();
    assert_eq!((img.width, img.height), (w, h));
    let names: Vec<&str> = img.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["V", "error"]);
    let want: Vec<f64> = v.iter().map(|&x| f64::from(x)).collect();
    assert!(same(&img.channels[0].data, &want));
    let image = image_from_bytes(&bytes).unwrap();
    assert!(same(&image.data, &want));
    // A single channel of another name is V; two without V are refused.
    let one = exr_bytes(w, h, &[("Y", v.clone())]).unwrap();
    assert!(same(&image_from_bytes(&one).unwrap().data, &want));
    let two = exr_bytes(w, h, &[("R", v.clone()), ("G", v)]).unwrap();
    let e = image_from_bytes(&two).unwrap_err().to_string();
    assert!(
        e.contains("no channel named V") && e.contains("G, R"),
        "{e}"
    );
}

#[test]
fn a_constant_exr_of_a_megapixel_is_within_the_ratio_bound() {
    let (w, h) = (1024, 1024);
    let bytes = exr_bytes(w, h, &[("V", vec![1.0; w * h])]).unwrap();
    let img = read_exr(&bytes).unwrap();
    assert!(img.channels[0].data.iter().all(|&x| x == 1.0));
    assert!(
        (w * h * 4) as u64 <= EXR_MAX_RATIO * bytes.len() as u64 / 2,
        "a constant megapixel compresses to {} bytes, too close to the bound",
        bytes.len()
    );
}

#[test]
fn hostile_and_truncated_exr_headers_are_refused() {
    let (w, h) = (8, 4);
    let bytes = exr_bytes(w, h, &[("V", vec![0.25; w * h])]).unwrap();
    // The data window (box2i: xmin, ymin, xmax, ymax) made 100000².
    let key = b"dataWindow\0box2i\0";
    let at = bytes
        .windows(key.len())
        .position(|x| x == key)
        .expect("a data window")
        + key.len()
        + 4;
    let mut hostile = bytes.clone();
    hostile[at + 8..at + 12].copy_from_slice(&99_999i32.to_le_bytes());
    hostile[at + 12..at + 16].copy_from_slice(&99_999i32.to_le_bytes());
    let e = read_exr(&hostile).unwrap_err().to_string();
    assert!(e.contains("100000×100000"), "{e}");
    // A million pixels declared in a file of a few hundred bytes.
    hostile[at + 8..at + 12].copy_from_slice(&999i32.to_le_bytes());
    hostile[at + 12..at + 16].copy_from_slice(&999i32.to_le_bytes());
    let e = read_exr(&hostile).unwrap_err().to_string();
    assert!(e.contains("hostile"), "{e}");
    // Every prefix: an error of one line, never a panic.
    for n in 0..bytes.len() {
        if let Err(e) = image_from_bytes(&bytes[..n]).map_err(|e| e.to_string()) {
            assert!(!e.contains('\n'), "{e}");
        }
    }
}

#[test]
fn pfm_round_trips_top_row_first_and_refuses_colour_and_bad_sizes() {
    let (w, h) = (3, 2);
    let v = [0.1f32, 0.2, 0.3, 0.4, 0.5, 0.6];
    let bytes = pfm_bytes(w, h, &v);
    let img = read_pfm(&bytes).unwrap();
    assert_eq!((img.width, img.height), (3, 2));
    assert_eq!(img.data, v.map(f64::from).to_vec());
    // The file stores the bottom row first.
    assert_eq!(
        &bytes[bytes.len() - 12..bytes.len() - 8],
        &0.1f32.to_le_bytes()
    );
    // Big-endian (positive scale).
    let mut be = b"Pf\n1 2\n1.0\n".to_vec();
    be.extend(2.5f32.to_be_bytes());
    be.extend((-1.0f32).to_be_bytes());
    assert_eq!(read_pfm(&be).unwrap().data, vec![-1.0, 2.5]);
    for (bad, needle) in [
        (&b"PF\n1 1\n-1\n\0\0\0\0"[..], "colour"),
        (&b"Pf\n100000 100000\n-1\n\0\0\0\0"[..], "limit"),
        (&b"Pf\n2 2\n-1\n\0\0\0\0"[..], "the file has 4"),
        (&b"Pf\n2 x\n-1\n\0\0\0\0"[..], "height"),
        (&b"Pf\n1 1\n0\n\0\0\0\0"[..], "scale"),
        (&b"Pf\n1 1"[..], "malformed"),
    ] {
        let e = image_from_bytes(bad).unwrap_err().to_string();
        assert!(e.contains(needle), "{e}");
    }
}

#[test]
fn an_unknown_format_is_named() {
    let e = image_from_bytes(b"\x89PNG\r\n").unwrap_err().to_string();
    assert!(e.contains(".npy, .exr or .pfm"), "{e}");
}

/// Found by the `float_files` fuzz target: a subsampled channel whose name
/// holds a line break made a two-line error.
#[test]
fn channel_names_with_control_characters_stay_on_one_line() {
    let bytes = include_bytes!("testdata/subsampled-channel-with-newline.exr");
    let e = image_from_bytes(bytes).unwrap_err().to_string();
    assert!(e.contains("subsampled") && e.contains("\\r\\n"), "{e}");
    assert!(!e.contains('\n') && !e.contains('\r'), "{e}");
    let named = exr_bytes(2, 1, &[("a\nb", vec![0.0; 2]), ("c", vec![0.0; 2])]).unwrap();
    let e = image_from_bytes(&named).unwrap_err().to_string();
    assert!(e.contains("a\\nb") && !e.contains('\n'), "{e}");
}

/// Each fault is of its kind, so that a caller can tell a file of another
/// kind from a damaged one and from one holding what is not an image.
#[test]
fn faults_are_typed_by_what_is_wrong() {
    let kind = |r: Result<Image, FormatError>| match r {
        Err(FormatError::NotThisKind(_)) => "not this kind",
        Err(FormatError::Malformed(_)) => "malformed",
        Err(FormatError::Unsupported(_)) => "unsupported",
        Err(FormatError::Unwritable(_)) => "unwritable",
        Ok(_) => "read",
    };
    let npy = npy_bytes_f64(&[2, 3], &values(6)).unwrap();
    assert_eq!(kind(image_from_bytes(&npy)), "read");
    assert_eq!(kind(image_from_bytes(b"\x89PNG\r\n")), "not this kind");
    assert_eq!(kind(read_pfm(b"P6\n1 1\n255\n\0\0\0")), "not this kind");
    assert_eq!(kind(image_from_bytes(&npy[..npy.len() - 1])), "malformed");
    assert_eq!(
        kind(image_from_bytes(b"Pf\n2 2\n-1\n\0\0\0\0")),
        "malformed"
    );
    assert_eq!(
        kind(image_from_bytes(b"PF\n1 1\n-1\n\0\0\0\0")),
        "unsupported"
    );
    let cube = npy_bytes_f64(&[2, 2, 2], &values(8)).unwrap();
    assert_eq!(kind(image_from_bytes(&cube)), "unsupported");
    let ids = npy_bytes_i32(&[2, 2], &[1, 2, 3, 4]).unwrap();
    assert!(matches!(
        read_npy_f64(&ids),
        Err(FormatError::Unsupported(_))
    ));
    assert!(matches!(
        npy_bytes_f64(&[2, 2], &values(3)),
        Err(FormatError::Unwritable(_))
    ));
    assert!(matches!(
        exr_bytes(0, 1, &[("V", vec![])]),
        Err(FormatError::Unwritable(_))
    ));
}
