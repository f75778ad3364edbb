//! OpenEXR through the `exr` crate: the first flat layer's channels as
//! `f64`, its declared size checked against the file before the pixels are
//! read; and single-part float32 files written with lossless ZIP
//! compression.

use super::npy::one_line;
use super::{EXR_MAX_RATIO, MAX_PIXELS};
use exr::prelude::{
    read, AnyChannel, AnyChannels, Encoding, FlatSamples, Image, ReadChannels as _,
    ReadLayers as _, SmallVec, Vec2, WritableImage as _,
};
use std::io::Cursor;

/// One channel of an [`ExrImage`].
#[derive(Clone, Debug, PartialEq)]
pub struct ExrChannel {
    /// The channel's full name (`V`, `P.X`, …).
    pub name: String,
    /// `width · height` values, row-major from the top-left.
    pub data: Vec<f64>,
}

/// The first flat layer of an OpenEXR file: its size (the data window's)
/// and channels, in the file's (alphabetical) order.
#[derive(Clone, Debug, PartialEq)]
pub struct ExrImage {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The channels, each `width · height` values.
    pub channels: Vec<ExrChannel>,
}

/// The first flat (not deep) layer of an OpenEXR file's bytes, every
/// channel as `f64` (from `half`, `float` or `uint`), its largest
/// resolution level.
///
/// # Errors
/// One line: not an OpenEXR file, a malformed or truncated one, deep data
/// only, a subsampled channel, or a layer declaring more than
/// [`MAX_PIXELS`] pixels or more decoded bytes than [`EXR_MAX_RATIO`] times
/// the file's length (a hostile header).
pub fn read_exr(bytes: &[u8]) -> Result<ExrImage, String> {
    let meta = exr::meta::MetaData::read_from_buffered(bytes, false)
        .map_err(|e| format!(".exr header: {}", one_line(&e.to_string())))?;
    let header = meta
        .headers
        .iter()
        .find(|h| !h.deep)
        .ok_or(".exr: no flat (non-deep) layer")?;
    let (w, h) = (header.layer_size.0, header.layer_size.1);
    let pixels = (w as u64).saturating_mul(h as u64);
    if pixels > MAX_PIXELS {
        return Err(format!(
            ".exr declares {w}×{h} pixels, over the limit of {MAX_PIXELS}"
        ));
    }
    let mut decoded: u64 = 0;
    for c in &header.channels.list {
        if c.sampling != Vec2(1, 1) {
            return Err(format!(
                ".exr channel {} is subsampled ({}×{}); write full-resolution channels",
                c.name.to_string().escape_debug(),
                c.sampling.0,
                c.sampling.1
            ));
        }
        decoded = decoded.saturating_add(pixels * c.sample_type.bytes_per_sample() as u64);
    }
    let limit = EXR_MAX_RATIO.saturating_mul(bytes.len() as u64);
    if decoded > limit {
        return Err(format!(
            ".exr declares {w}×{h} pixels in {} channels ({decoded} bytes decoded) in a file of {} bytes: \
             truncated, or a hostile header",
            header.channels.list.len(),
            bytes.len()
        ));
    }
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| format!(".exr: {}", one_line(&e.to_string())))?;
    let layer = image.layer_data;
    let (width, height) = (layer.size.0, layer.size.1);
    let channels = layer
        .channel_data
        .list
        .into_iter()
        .map(|c| ExrChannel {
            name: c.name.to_string(),
            data: match c.sample_data {
                FlatSamples::F16(v) => v.into_iter().map(|x| f64::from(x.to_f32())).collect(),
                FlatSamples::F32(v) => v.into_iter().map(f64::from).collect(),
                FlatSamples::U32(v) => v.into_iter().map(f64::from).collect(),
            },
        })
        .collect::<Vec<_>>();
    if channels.iter().any(|c| c.data.len() != width * height) {
        return Err(".exr: a channel's size differs from the layer's".to_owned());
    }
    Ok(ExrImage {
        width,
        height,
        channels,
    })
}

/// The bytes of a single-layer OpenEXR file of `width × height` pixels
/// holding `channels` (name, `width · height` float32 values row-major
/// from the top-left), ZIP-compressed (lossless, 16 scan lines a block).
///
/// # Errors
/// A channel of the wrong length, no channel, an empty image, or the
/// encoder's error.
pub fn exr_bytes(
    width: usize,
    height: usize,
    channels: &[(&str, Vec<f32>)],
) -> Result<Vec<u8>, String> {
    if width == 0 || height == 0 || channels.is_empty() {
        return Err("an .exr needs pixels and at least one channel".to_owned());
    }
    if let Some((name, d)) = channels.iter().find(|(_, d)| d.len() != width * height) {
        return Err(format!(
            "channel {name}: {} values for {width}×{height} pixels",
            d.len()
        ));
    }
    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> = channels
        .iter()
        .map(|(name, d)| AnyChannel::new(*name, FlatSamples::F32(d.clone())))
        .collect();
    let image = Image::from_encoded_channels(
        (width, height),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(list),
    );
    let mut out = Cursor::new(Vec::new());
    image
        .write()
        .non_parallel()
        .to_buffered(&mut out)
        .map_err(|e| format!(".exr: {e}"))?;
    Ok(out.into_inner())
}
