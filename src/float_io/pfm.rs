//! The portable float map (`.pfm`): a text header `Pf`, `W H`, a scale
//! whose sign is the byte order (negative: little-endian), each followed
//! by one whitespace character, then `W · H` float32 values, rows from the
//! **bottom** of the image up. Greyscale (`Pf`) only: a colour map (`PF`)
//! is refused, since `V` is one value per pixel.

use super::{Image, MAX_PIXELS};

/// The image of a greyscale `.pfm` file's bytes, row 0 the top.
///
/// # Errors
/// One line: not a PFM, a colour PFM, a malformed header, a size over
/// [`MAX_PIXELS`] or one that does not match the data exactly.
pub fn read_pfm(bytes: &[u8]) -> Result<Image, String> {
    if bytes.starts_with(b"PF") {
        return Err(
            "a colour PFM (PF, three channels); V is one value per pixel: write a greyscale PFM (Pf)"
                .to_owned(),
        );
    }
    if !bytes.starts_with(b"Pf") {
        return Err("not a PFM file (no Pf)".to_owned());
    }
    // Three whitespace-separated tokens after the magic, within the first
    // few hundred bytes, each ended by one whitespace byte.
    let mut at = 2;
    let mut tokens = Vec::new();
    while tokens.len() < 3 {
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let start = at;
        while at < bytes.len() && !bytes[at].is_ascii_whitespace() && at - start < 64 {
            at += 1;
        }
        if at >= bytes.len() || start == at || !bytes[at].is_ascii_whitespace() {
            return Err("malformed PFM header (Pf, width height, scale)".to_owned());
        }
        tokens.push(std::str::from_utf8(&bytes[start..at]).unwrap_or(""));
        at += 1;
    }
    let bad = |what: &str| format!("PFM header: {what}");
    let w: usize = tokens[0].parse().map_err(|_| bad("width is not a count"))?;
    let h: usize = tokens[1]
        .parse()
        .map_err(|_| bad("height is not a count"))?;
    let scale: f64 = tokens[2]
        .parse()
        .map_err(|_| bad("scale is not a number"))?;
    if !(scale.is_finite() && scale != 0.0) {
        return Err(bad("scale must be a non-zero number"));
    }
    let pixels = (w as u64).saturating_mul(h as u64);
    if pixels > MAX_PIXELS {
        return Err(format!(
            "PFM declares {w}×{h} pixels, over the limit of {MAX_PIXELS}"
        ));
    }
    let data = &bytes[at..];
    if data.len() as u64 != 4 * pixels {
        return Err(format!(
            "PFM declares {w}×{h} pixels ({} bytes), the file has {} after its header",
            4 * pixels,
            data.len()
        ));
    }
    let little = scale < 0.0;
    let value = |k: usize| {
        let b = [
            data[4 * k],
            data[4 * k + 1],
            data[4 * k + 2],
            data[4 * k + 3],
        ];
        f64::from(if little {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        })
    };
    let mut out = Vec::with_capacity(w * h);
    for row in (0..h).rev() {
        out.extend((0..w).map(|col| value(row * w + col)));
    }
    Ok(Image {
        width: w,
        height: h,
        data: out,
    })
}

/// The bytes of a little-endian greyscale PFM of `width × height` values
/// given row-major from the top (written bottom row first, as the format
/// wants).
#[must_use]
pub fn pfm_bytes(width: usize, height: usize, data: &[f32]) -> Vec<u8> {
    let mut out = format!("Pf\n{width} {height}\n-1.0\n").into_bytes();
    for row in (0..height).rev() {
        for col in 0..width {
            let v = data.get(row * width + col).copied().unwrap_or(f32::NAN);
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}
