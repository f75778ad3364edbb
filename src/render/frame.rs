//! Receivers: the points every method computes `V` at, one per pixel of a
//! camera image or one per point of a points file.

use crate::bvh::Bvh;
use crate::scene::{Camera, Receiver};
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// The pixel value of a background pixel in [`Frame::pixels`].
pub const BACKGROUND: u32 = u32::MAX;

/// A set of receivers laid out as an image: `width × height` pixels, each
/// either a receiver (an index into [`Frame::receivers`]) or
/// [`BACKGROUND`]. Methods compute one value per receiver; background pixels
/// are never shaded as receivers.
#[derive(Clone, Debug)]
pub struct Frame {
    id: u64,
    width: u32,
    height: u32,
    pixels: Vec<u32>,
    receivers: Vec<Receiver>,
    /// Whether the pixels are a camera image (neighbouring pixels are
    /// neighbours on screen), not a list of points.
    image: bool,
}

/// Frames are told apart by a process-wide counter, so that stages fitted to
/// one frame's receivers (light maps, receiver grids) are not reused for
/// another.
static NEXT_FRAME: AtomicU64 = AtomicU64::new(0);

/// How far a camera receiver is moved off its surface, relative to the
/// magnitude of its coordinates plus the scene's extent: `2⁻³²`.
///
/// The hit point `eye + t·d` is rounded, so it can land a few ulps behind
/// the surface it is on, where that surface's own triangle would occlude
/// part of the light. Moving it by `2⁻³²` of the scene's scale toward the
/// side the camera sees (far more than the rounding, far less than any
/// feature of a scene) puts it strictly in front, for every method alike.
pub const RECEIVER_OFFSET: f64 = 1.0 / 4_294_967_296.0;

impl Frame {
    /// The receivers seen by `camera`, one per pixel: the nearest point of
    /// any triangle of `bvh` on the pixel's [primary
    /// ray](Camera::primary_ray) (closest hit, watertight), moved off the
    /// surface by [`RECEIVER_OFFSET`] along the geometric normal facing the
    /// camera; pixels whose ray meets nothing are [`BACKGROUND`]. The image
    /// is the camera's resolution ([`Camera::with_resolution`] gives
    /// another). Parallel over rows; the result does not depend on the
    /// number of threads.
    #[must_use]
    pub fn from_camera(camera: &Camera, bvh: &Bvh) -> Frame {
        let (width, height) = camera.resolution();
        let extent = bvh_extent(bvh);
        // Per row, in parallel: the receivers found and which columns
        // they are at; then concatenated in row order.
        let rows: Vec<(Vec<u32>, Vec<Receiver>)> = (0..height)
            .into_par_iter()
            .map(|row| {
                let (mut cols, mut found) = (Vec::new(), Vec::new());
                let rays: Vec<(DVec3, DVec3)> =
                    (0..width).map(|col| camera.primary_ray(col, row)).collect();
                let mut hits = Vec::new();
                bvh.closest_hits(&rays, f64::INFINITY, &mut hits);
                for ((col, &(eye, d)), hit) in (0..width).zip(&rays).zip(hits) {
                    let Some(hit) = hit else {
                        continue;
                    };
                    let p = eye + d * hit.t;
                    let scale = p.abs().max_element() + extent;
                    let position = p + hit.normal * (scale * RECEIVER_OFFSET);
                    if position.is_finite() {
                        cols.push(col);
                        found.push(Receiver {
                            position,
                            normal: Some(hit.normal),
                            object: Some(hit.object),
                        });
                    }
                }
                (cols, found)
            })
            .collect();
        let mut pixels = vec![BACKGROUND; width as usize * height as usize];
        let mut receivers = Vec::with_capacity(rows.iter().map(|r| r.1.len()).sum());
        for (row, (cols, found)) in rows.into_iter().enumerate() {
            // The row's receivers follow the earlier rows' in column order:
            // the k-th found is at `cols[k]`.
            let first = receivers.len();
            for (k, col) in cols.into_iter().enumerate() {
                pixels[row * width as usize + col as usize] = (first + k) as u32;
            }
            receivers.extend(found);
        }
        Frame {
            id: NEXT_FRAME.fetch_add(1, Ordering::Relaxed),
            width,
            height,
            pixels,
            receivers,
            image: true,
        }
    }

    /// Receivers given directly (a points file), laid out as one row.
    ///
    /// Frames index receivers with `u32`: beyond `2³² − 2` receivers (some
    /// 200 GB of them) the extra ones are dropped.
    #[must_use]
    pub fn from_receivers(mut receivers: Vec<Receiver>) -> Frame {
        receivers.truncate(BACKGROUND as usize);
        let n = receivers.len() as u32;
        Frame {
            id: NEXT_FRAME.fetch_add(1, Ordering::Relaxed),
            width: n,
            height: u32::from(n > 0),
            pixels: (0..n).collect(),
            receivers,
            image: false,
        }
    }

    /// A camera image given pixel by pixel: `width × height` entries,
    /// row-major from the top-left, each a receiver or `None` (background).
    /// Receivers are numbered in pixel order. For receivers found by a
    /// rasteriser of one's own (a G-buffer read back).
    ///
    /// # Panics
    /// Never; missing entries are background, extra ones are dropped.
    #[must_use]
    pub fn from_pixels(
        width: u32,
        height: u32,
        pixels: impl IntoIterator<Item = Option<Receiver>>,
    ) -> Frame {
        let n = width as usize * height as usize;
        let mut index = Vec::with_capacity(n);
        let mut receivers = Vec::new();
        for p in pixels.into_iter().take(n) {
            match p {
                Some(r) if receivers.len() < BACKGROUND as usize => {
                    index.push(receivers.len() as u32);
                    receivers.push(r);
                }
                _ => index.push(BACKGROUND),
            }
        }
        index.resize(n, BACKGROUND);
        Frame {
            id: NEXT_FRAME.fetch_add(1, Ordering::Relaxed),
            width,
            height,
            pixels: index,
            receivers,
            image: true,
        }
    }

    /// Whether the frame is a camera image ([`Frame::from_camera`]), whose
    /// neighbouring pixels are neighbours on screen — methods may then
    /// interpolate between them — rather than a list of points
    /// ([`Frame::from_receivers`]).
    #[must_use]
    pub fn is_image(&self) -> bool {
        self.image
    }

    /// A number unique to this frame within the process.
    #[must_use]
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Width and height in pixels.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Per pixel, row-major from the top-left: the receiver's index, or
    /// [`BACKGROUND`].
    #[must_use]
    pub fn pixels(&self) -> &[u32] {
        &self.pixels
    }

    /// The receivers.
    #[must_use]
    pub fn receivers(&self) -> &[Receiver] {
        &self.receivers
    }

    /// The receivers' positions, in order.
    #[must_use]
    pub fn positions(&self) -> Vec<DVec3> {
        self.receivers.iter().map(|r| r.position).collect()
    }

    /// Per-receiver `values` spread over the pixels, `background` where
    /// there is none. `values.len()` must be the receiver count; missing
    /// values read as `background`.
    #[must_use]
    pub fn to_image<T: Copy>(&self, values: &[T], background: T) -> Vec<T> {
        self.pixels
            .iter()
            .map(|&i| values.get(i as usize).copied().unwrap_or(background))
            .collect()
    }
}

/// The largest coordinate magnitude of the BVH's triangles (0 when empty):
/// the scene's scale for [`RECEIVER_OFFSET`].
fn bvh_extent(bvh: &Bvh) -> f64 {
    bvh.occluders()
        .triangles()
        .iter()
        .flatten()
        .map(|v| v.abs().max_element())
        .filter(|m| m.is_finite())
        .fold(0.0, f64::max)
}
