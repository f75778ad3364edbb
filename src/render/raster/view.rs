//! [`LightView`]: what the light sees — a light frame, a window on its
//! image plane, a resolution and a near depth — and its fitting to a set of
//! points ([`LightView::fit`]).

use super::{flush, RasterError, MAX_COORD, MAX_RESOLUTION, MIN_COORD, MIN_FIT_EXTENT};
use crate::scene::{LightFrame, Projected};
use glam::{DVec2, DVec3};

/// What the light sees: a light frame, a window `[lo, hi]` on its image
/// plane `z = 1`, a resolution and a near depth.
///
/// Pixel `(col, row)` covers `x ∈ [lo.x + col·sx, lo.x + (col+1)·sx)`,
/// `y ∈ [lo.y + row·sy, lo.y + (row+1)·sy)`, with `(sx, sy)` the
/// [texel size](LightView::texel_size); maps are row-major, index
/// `row·width + col`.
#[derive(Clone, Debug, PartialEq)]
pub struct LightView {
    pub(super) frame: LightFrame,
    pub(super) lo: DVec2,
    hi: DVec2,
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) near: f64,
    pub(super) texel: DVec2,
    // Pixel-centre coordinates, computed once so that every triangle (and
    // `pixel_center`) sees the same bits.
    pub(super) xs: Vec<f64>,
    pub(super) ys: Vec<f64>,
}

impl LightView {
    /// The view of `frame` over the window `[lo, hi]` at `width × height`
    /// pixels, rasterising only what lies at light-frame depth `≥ near`.
    ///
    /// # Errors
    /// [`RasterError::NonFiniteWindow`] (a corner not finite or beyond
    /// [`MAX_COORD`]), [`RasterError::EmptyWindow`] (`lo ≥ hi` on an axis,
    /// or pixels smaller than [`MIN_COORD`]),
    /// [`RasterError::Resolution`] (a size 0 or above [`MAX_RESOLUTION`]),
    /// [`RasterError::Near`] (`near` not finite and positive).
    pub fn new(
        frame: LightFrame,
        lo: DVec2,
        hi: DVec2,
        width: u32,
        height: u32,
        near: f64,
    ) -> Result<LightView, RasterError> {
        let ok = |p: DVec2| p.is_finite() && p.abs().max_element() <= MAX_COORD;
        if !(ok(lo) && ok(hi)) {
            return Err(RasterError::NonFiniteWindow);
        }
        if !(lo.x < hi.x && lo.y < hi.y) {
            return Err(RasterError::EmptyWindow);
        }
        if !(1..=MAX_RESOLUTION).contains(&width) || !(1..=MAX_RESOLUTION).contains(&height) {
            return Err(RasterError::Resolution { width, height });
        }
        if !(near.is_finite() && near > 0.0) {
            return Err(RasterError::Near);
        }
        // |lo|, |hi| ≤ MAX_COORD: `hi − lo` cannot overflow.
        let texel = DVec2::new(
            (hi.x - lo.x) / f64::from(width),
            (hi.y - lo.y) / f64::from(height),
        );
        // Pixels narrower than MIN_COORD would have centres flushed
        // together (and underflowing pixel coordinates).
        if !(texel.x >= MIN_COORD && texel.y >= MIN_COORD) {
            return Err(RasterError::EmptyWindow);
        }
        let centers = |lo: f64, s: f64, n: u32| -> Vec<f64> {
            (0..n)
                .map(|k| flush(lo + (f64::from(k) + 0.5) * s))
                .collect()
        };
        Ok(LightView {
            frame,
            lo,
            hi,
            width,
            height,
            near,
            texel,
            xs: centers(lo.x, texel.x, width),
            ys: centers(lo.y, texel.y, height),
        })
    }

    /// The view whose window just contains the projections of the finite
    /// `points` at light-frame depth `≥ near` (typically the receivers and
    /// the occluders' vertices a method is given), grown by one pixel on
    /// each side: per axis, with `n` pixels, the pixel size is
    /// `extent / (n − 2)` for `n ≥ 3` and the window extends one pixel
    /// beyond the extreme projections (for `n ≤ 2`, by `extent / n`, which
    /// is `n / (n + 2)` of a pixel). Pixels need not be square.
    /// Points behind `near` are ignored. An extent below
    /// [`MIN_FIT_EXTENT`]` · max(1, |coordinate|)` (all points projecting
    /// to one point or onto one line) is widened to that, centred.
    ///
    /// # Errors
    /// [`RasterError::NothingInFront`] when no finite point is at depth
    /// `≥ near`; the errors of [`LightView::new`] otherwise (a bad `near`
    /// or resolution, or projections beyond [`MAX_COORD`]).
    pub fn fit(
        frame: LightFrame,
        points: impl IntoIterator<Item = DVec3>,
        width: u32,
        height: u32,
        near: f64,
    ) -> Result<LightView, RasterError> {
        if !(near.is_finite() && near > 0.0) {
            return Err(RasterError::Near);
        }
        if !(1..=MAX_RESOLUTION).contains(&width) || !(1..=MAX_RESOLUTION).contains(&height) {
            return Err(RasterError::Resolution { width, height });
        }
        let mut bounds: Option<(DVec2, DVec2)> = None;
        for p in points {
            let q = frame.to_light(p);
            if !(q.is_finite() && q.z >= near) {
                continue;
            }
            let u = crate::kernel::footprint::f64::project(q);
            if !u.is_finite() {
                return Err(RasterError::NonFiniteWindow);
            }
            bounds = Some(match bounds {
                None => (u, u),
                Some((a, b)) => (a.min(u), b.max(u)),
            });
        }
        let (min, max) = bounds.ok_or(RasterError::NothingInFront)?;
        let axis = |min: f64, max: f64, n: u32| -> (f64, f64) {
            let floor = MIN_FIT_EXTENT * min.abs().max(max.abs()).max(1.0);
            let (min, max) = if max - min < floor {
                let mid = 0.5 * min + 0.5 * max;
                (mid - 0.5 * floor, mid + 0.5 * floor)
            } else {
                (min, max)
            };
            let inner = if n >= 3 { n - 2 } else { n };
            let s = (max - min) / f64::from(inner);
            (min - s, max + s)
        };
        let (lx, hx) = axis(min.x, max.x, width);
        let (ly, hy) = axis(min.y, max.y, height);
        LightView::new(
            frame,
            DVec2::new(lx, ly),
            DVec2::new(hx, hy),
            width,
            height,
            near,
        )
    }

    /// The light frame.
    #[must_use]
    pub fn frame(&self) -> &LightFrame {
        &self.frame
    }

    /// The window's lower corner on the image plane.
    #[must_use]
    pub fn lo(&self) -> DVec2 {
        self.lo
    }

    /// The window's upper corner on the image plane.
    #[must_use]
    pub fn hi(&self) -> DVec2 {
        self.hi
    }

    pixel_grid!(pub);

    /// The number of pixels, `width · height`.
    #[must_use]
    pub fn len(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Always `false` (a view has at least one pixel); for clippy's sake.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The near depth.
    #[must_use]
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The size of one pixel on the image plane, `(sx, sy)`.
    #[must_use]
    pub fn texel_size(&self) -> DVec2 {
        self.texel
    }

    /// The image-plane centre of pixel `(col, row)`, `lo + (k + ½)·s` per
    /// axis (coordinates below [`MIN_COORD`] flushed to zero): exactly the
    /// point the rasterizer tests. Indices past the last pixel are clamped
    /// to it.
    #[must_use]
    pub fn pixel_center(&self, col: u32, row: u32) -> DVec2 {
        let c = (col.min(self.width - 1)) as usize;
        let r = (row.min(self.height - 1)) as usize;
        DVec2::new(self.xs[c], self.ys[r])
    }

    /// Continuous pixel coordinates of an image-plane point:
    /// `(point − lo) / s`, so that pixel `(col, row)` spans `[col, col + 1)
    /// × [row, row + 1)` and its centre is near `(col + ½, row + ½)` (up to
    /// rounding).
    #[must_use]
    pub fn to_pixel(&self, point: DVec2) -> DVec2 {
        (point - self.lo) / self.texel
    }

    /// The pixel `(col, row)` whose cell contains the image-plane point,
    /// `None` outside the window or for a non-finite point.
    #[must_use]
    pub fn pixel_of(&self, point: DVec2) -> Option<(u32, u32)> {
        let p = self.to_pixel(point).floor();
        let inside =
            p.x >= 0.0 && p.y >= 0.0 && p.x < f64::from(self.width) && p.y < f64::from(self.height);
        inside.then_some((p.x as u32, p.y as u32))
    }

    /// The image-plane projection and light-frame depth of a world point
    /// ([`LightFrame::project`]); `None` at or behind the light's plane.
    #[must_use]
    pub fn project(&self, p: DVec3) -> Option<Projected> {
        self.frame.project(p)
    }
}
