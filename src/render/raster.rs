//! The scalar light-view rasterizer: the scene's triangles as seen from the
//! light's centre, over the light frame and [image plane](crate::definitions#light-image-plane).
//! Every shadow-map method (PCSS, the single-sample method, SSOC, OESS)
//! draws on it.
//!
//! A [`LightView`] is a light frame, an axis-aligned window `[lo, hi]` on the
//! light image plane `z = 1`, a resolution and a near depth;
//! [`LightView::fit`] fits the window to a set of points. [`rasterize`] (or
//! [`rasterize_occluders`], or [`rasterize_into`] reusing storage) fills
//! [`LightMaps`]: per pixel, the depth of the nearest triangle on the ray
//! from the light's centre through the pixel centre, that triangle's object
//! id and its index. [`rasterize_triangle`] hands every covered pixel of one
//! triangle to a callback, for methods that rasterise something other than
//! a depth map. Single-threaded and scalar; the default scene (3676
//! triangles) takes about 2 ms at 512² into reused maps
//! (`benches/raster.rs`).
//!
//! ```
//! use softshadow::glam::{DVec2, DVec3};
//! use softshadow::render::raster::{rasterize, LightView};
//! use softshadow::scene::LightFrame;
//!
//! // Light at the origin looking down +z; one triangle at depth 2.
//! let frame = LightFrame::toward(DVec3::ZERO, DVec3::Z)?;
//! let view = LightView::new(frame, DVec2::splat(-1.0), DVec2::splat(1.0), 8, 8, 0.1)?;
//! let tri = [DVec3::new(-2.0, -2.0, 2.0), DVec3::new(2.0, -2.0, 2.0), DVec3::new(0.0, 2.0, 2.0)];
//! let maps = rasterize(&view, &[tri], &[7])?;
//! assert_eq!(maps.depth_at(4, 4), 2.0);
//! assert_eq!(maps.object_at(4, 4), 7);
//! assert_eq!(maps.triangle_at(0, 7), u32::MAX); // a top corner, outside
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Contract
//!
//! **Coverage by pixel centre, watertight.** Pixel `(col, row)` covers the
//! image-plane cell `x ∈ [lo.x + col·sx, lo.x + (col+1)·sx)`,
//! `y ∈ [lo.y + row·sy, lo.y + (row+1)·sy)`; a triangle covers it when the
//! cell's centre lies inside the triangle's projection. The inside test is
//! the crate's exact [`orient2d`] on the projected vertices and the centre
//! (a rounded evaluation with Shewchuk's static error bound answers almost
//! every pixel; only centres within that bound of an edge's line reach the
//! exact expansion). A centre exactly on an edge is decided by a top-left
//! rule: with the triangle counter-clockwise, the edge `a → b` owns its
//! points when `b.y < a.y`, or `b.y = a.y` and `b.x > a.x` (rows grow with
//! `y`, so these are the left edges and the top edges). An edge traversed in
//! the two directions gets opposite answers, so two triangles sharing an
//! edge (same world vertices, bit for bit) cover a centre on it exactly
//! once, and a fan around a vertex covers a centre at that vertex exactly
//! once. Equivalently, the rule moves every centre by `(δ, δ²)` with
//! `δ → 0⁺` (a symbolic perturbation: on an edge `a → b` the sign of
//! `(b − a) × (δ, δ²)` is that of `−(b.y − a.y)`, or of `b.x − a.x` when the
//! edge is horizontal), so coverage is that of a point on no edge, and every
//! counting argument for generic points holds exactly (a closed mesh covers
//! each centre an even number of times). Both orientations are rasterised
//! (occluders are two-sided); projections of zero area cover nothing.
//!
//! Why exact predicates rather than the GPU's fixed-point snapping: the
//! covered set is then exactly the set of centres inside the `f64`
//! projection of the triangle, the same triangle a ray cast through the
//! pixel centre sees, so the maps agree with ray casting everywhere except
//! within rounding of the projection of an edge; there is no sub-pixel
//! grid to choose, no guard band and no snapping error to document, and the
//! domain is the predicate's. Projected vertices are a deterministic
//! function of the world vertex alone (light-frame coordinates, then
//! `(x/z, y/z)`), so shared vertices project to the same bits.
//!
//! **Near plane.** Triangles are clipped against `z = near` in light-frame
//! coordinates before projection; parts nearer than `near` are dropped. A
//! crossing is computed from the edge's two endpoints taken in a canonical
//! order (lexicographic on their light-frame coordinates), with `z` set to
//! `near` exactly, so two triangles sharing an edge get the same clip point
//! bit for bit. The clipped polygon (up to four vertices) is rasterised as a
//! fan from its first vertex; its internal diagonal is shared bit for bit,
//! so the fan covers every centre of the polygon once. (The projection of
//! the clipped quadrilateral is convex; only when rounding of the clip
//! point bends it by a few ulps, with a centre in that sliver, could a
//! centre be counted twice or missed.)
//!
//! **Depth.** The stored depth is the light-frame `z` at which the ray from
//! the light's centre in direction `(u, v, 1)`, `(u, v)` the pixel centre,
//! meets the plane of the triangle: `z = (n·a) / (n·(u, v, 1))` with
//! `n = (b − a) × (c − a)` in light-frame coordinates, `a` the corner
//! nearest the light (so that a far corner does not swamp the differences;
//! found by the `raster` fuzz target), clamped to the range
//! of the (clipped) polygon's depths (the exact value lies in it). Relative
//! error a few ulps times the conditioning `|n|·|(u,v,1)| / |n·(u,v,1)|`
//! (grazing triangles lose digits) times `max(1, |n|·|a| / |n·a|)` (every
//! corner far from the light compared with the plane's distance to it),
//! for triangles whose corners' distances from the light are within a
//! factor `10¹⁵` of each other. Beyond that (corners 10²⁸ and 10⁷⁹ away,
//! found by the `raster` fuzz target) the depth still lies in the clipped
//! polygon's depth range and is never NaN, but may be wrong: the plane
//! would need exact arithmetic. Coverage is exact on the rounded projected
//! corners at any magnitude; the near-plane crossings are computed in
//! double length so that those corners are the true ones to a few ulps. Against an independent Möller–Trumbore
//! ray cast over random, non-grazing triangles (`tests/raster_depth.rs`) the
//! worst relative difference is `9.3e-15` over about 14 000 pixels. The
//! nearest triangle wins; at equal depth the lower triangle index.
//!
//! **Domain.** No input panics or produces NaN. Triangles with a non-finite
//! vertex are skipped. Light-frame coordinates and projected coordinates
//! are kept within [`MAX_COORD`] in magnitude: a triangle with a vertex (or
//! a projected, clipped vertex) beyond it is skipped, as is done for
//! non-finite ones, so nothing overflows. Projected coordinates and pixel
//! centres smaller than [`MIN_COORD`] in magnitude are flushed to zero (a
//! deterministic function of the value, so shared vertices stay shared);
//! this keeps every predicate inside [`orient2d`]'s exact range, so
//! coverage is exact for every triangle rasterised.

/// The accessors of a grid of `width × height` pixels stored row-major
/// (the fields `width` and `height`): `width()`, `height()` and
/// `index(col, row)`, the latter with visibility `$vis`.
macro_rules! pixel_grid {
    ($($vis:tt)*) => {
        /// The number of columns.
        #[must_use]
        pub fn width(&self) -> u32 {
            self.width
        }

        /// The number of rows.
        #[must_use]
        pub fn height(&self) -> u32 {
            self.height
        }

        /// The row-major index `row·width + col` of pixel `(col, row)`,
        /// `None` outside the grid.
        #[must_use]
        $($vis)* fn index(&self, col: u32, row: u32) -> Option<usize> {
            (col < self.width && row < self.height)
                .then(|| row as usize * self.width as usize + col as usize)
        }
    };
}

mod view;

pub use view::LightView;

use crate::bvh::Occluders;
use crate::kernel::predicate::{orient2d, Sign};
use glam::{DVec2, DVec3};

/// The largest width or height of a [`LightView`], in pixels.
pub const MAX_RESOLUTION: u32 = 16384;

/// The largest magnitude of a light-frame coordinate, a projected
/// coordinate or a window coordinate the rasterizer accepts; triangles
/// beyond it are skipped (see the module docs, "Domain").
pub const MAX_COORD: f64 = 1e100;

/// Projected coordinates and pixel centres smaller than this in magnitude
/// are flushed to zero, so that [`orient2d`] is exact on them.
pub const MIN_COORD: f64 = 1e-140;

/// The smallest extent of a window [`LightView::fit`] builds, relative to
/// `max(1, |coordinate|)`: points that project to one point or one line get
/// a window at least this wide around them.
pub const MIN_FIT_EXTENT: f64 = 1.0 / (1u64 << 40) as f64;

// Shewchuk's `ccwerrboundA = (3 + 16ε)ε`, ε = 2⁻⁵³, as in `orient2d`.
const EPS: f64 = f64::EPSILON / 2.0;
const CCW_ERR_BOUND_A: f64 = (3.0 + 16.0 * EPS) * EPS;

/// Why a light view could not be built or a rasterisation not run.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum RasterError {
    /// A window corner is not finite or exceeds [`MAX_COORD`] in magnitude.
    NonFiniteWindow,
    /// The window is empty: `lo ≥ hi` on some axis, or so narrow that a
    /// pixel is smaller than [`MIN_COORD`].
    EmptyWindow,
    /// A width or height is 0 or larger than [`MAX_RESOLUTION`].
    Resolution {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// The near depth is not finite and positive.
    Near,
    /// [`LightView::fit`]: no finite point lies at depth `≥ near`.
    NothingInFront,
    /// [`rasterize`]: `objects` does not have one id per triangle.
    LengthMismatch {
        /// The number of triangles.
        triangles: usize,
        /// The number of object ids.
        objects: usize,
    },
    /// [`rasterize`]: more triangles than a `u32` index can name (index
    /// `u32::MAX` means "no triangle").
    TooManyTriangles,
}

impl_error!(RasterError, |error, f| match error {
    RasterError::NonFiniteWindow => {
        write!(
            f,
            "light view window is not finite (or beyond {MAX_COORD:e})"
        )
    }
    RasterError::EmptyWindow => write!(f, "light view window is empty (lo ≥ hi)"),
    RasterError::Resolution { width, height } => write!(
        f,
        "light view resolution {width}×{height} is outside 1..={MAX_RESOLUTION}"
    ),
    RasterError::Near => write!(f, "light view near depth is not finite and positive"),
    RasterError::NothingInFront => {
        write!(f, "no point lies in front of the light view's near plane")
    }
    RasterError::LengthMismatch { triangles, objects } => write!(
        f,
        "{triangles} triangles but {objects} object ids: need one id per triangle"
    ),
    RasterError::TooManyTriangles => {
        write!(f, "more than {} triangles to rasterise", u32::MAX - 1)
    }
});

fn flush(x: f64) -> f64 {
    if x.abs() < MIN_COORD {
        0.0
    } else {
        x
    }
}

/// One pixel covered by a triangle: where, and the triangle's depth there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fragment {
    /// The pixel's column.
    pub col: u32,
    /// The pixel's row.
    pub row: u32,
    /// The light-frame depth `z` of the triangle's plane on the ray through
    /// the pixel centre, finite and `≥ near`.
    pub depth: f64,
}

/// The light maps: per pixel, the nearest triangle on the ray from the
/// light's centre through the pixel centre, row-major (`row·width + col`).
#[derive(Clone, Debug, PartialEq)]
pub struct LightMaps {
    width: u32,
    height: u32,
    depth: Vec<f64>,
    object: Vec<u32>,
    triangle: Vec<u32>,
}

impl LightMaps {
    /// Empty maps: every depth `f64::INFINITY`, every id `u32::MAX`.
    #[must_use]
    pub fn empty(width: u32, height: u32) -> LightMaps {
        let mut maps = LightMaps {
            width,
            height,
            depth: Vec::new(),
            object: Vec::new(),
            triangle: Vec::new(),
        };
        maps.reset(width, height);
        maps
    }

    /// Resizes to `width × height` and clears to the empty state, keeping
    /// the storage.
    pub fn reset(&mut self, width: u32, height: u32) {
        use rayon::prelude::*;
        let n = width as usize * height as usize;
        (self.width, self.height) = (width, height);
        // Filled in parallel: fresh storage is first touched, and its page
        // faults taken, by both threads (measured: a sixth of a 1024² SSOC
        // frame's time was the serial fill of new maps).
        fn fill<T: Copy + Send + Sync>(v: &mut Vec<T>, n: usize, x: T) {
            v.clear();
            v.par_extend(rayon::iter::repeat_n(x, n));
        }
        fill(&mut self.object, n, u32::MAX);
        fill(&mut self.triangle, n, u32::MAX);
        fill(&mut self.depth, n, f64::INFINITY);
    }

    pixel_grid!();

    /// The light-frame depth `z` of the nearest triangle at pixel
    /// `(col, row)`; `f64::INFINITY` where no triangle is seen, and outside
    /// the maps.
    #[must_use]
    pub fn depth_at(&self, col: u32, row: u32) -> f64 {
        self.index(col, row)
            .map_or(f64::INFINITY, |i| self.depth[i])
    }

    /// The object id of the nearest triangle at pixel `(col, row)`;
    /// `u32::MAX` where none, and outside the maps.
    #[must_use]
    pub fn object_at(&self, col: u32, row: u32) -> u32 {
        self.index(col, row).map_or(u32::MAX, |i| self.object[i])
    }

    /// The input index of the nearest triangle at pixel `(col, row)`;
    /// `u32::MAX` where none, and outside the maps.
    #[must_use]
    pub fn triangle_at(&self, col: u32, row: u32) -> u32 {
        self.index(col, row).map_or(u32::MAX, |i| self.triangle[i])
    }

    /// Whether some triangle covers pixel `(col, row)`.
    #[must_use]
    pub fn is_covered(&self, col: u32, row: u32) -> bool {
        self.triangle_at(col, row) != u32::MAX
    }

    /// The depth map, row-major.
    #[must_use]
    pub fn depth(&self) -> &[f64] {
        &self.depth
    }

    /// The object-id map, row-major.
    #[must_use]
    pub fn objects(&self) -> &[u32] {
        &self.object
    }

    /// The triangle-index map, row-major.
    #[must_use]
    pub fn triangles(&self) -> &[u32] {
        &self.triangle
    }
}

/// Rasterises world-space `triangles`, `objects[i]` the object id of
/// triangle `i`, into light maps over `view` (see the module docs for
/// coverage, clipping and depth). Triangles with a non-finite vertex, or
/// outside the domain, are skipped.
///
/// # Errors
/// [`RasterError::LengthMismatch`] when `objects.len() != triangles.len()`;
/// [`RasterError::TooManyTriangles`] beyond `u32::MAX − 1` triangles.
pub fn rasterize(
    view: &LightView,
    triangles: &[[DVec3; 3]],
    objects: &[u32],
) -> Result<LightMaps, RasterError> {
    check_lengths(triangles, objects)?;
    let mut maps = LightMaps::empty(view.width, view.height);
    fill_maps(view, triangles, objects, &mut maps);
    Ok(maps)
}

/// The errors of [`rasterize`] on its input's lengths.
fn check_lengths(triangles: &[[DVec3; 3]], objects: &[u32]) -> Result<(), RasterError> {
    if objects.len() != triangles.len() {
        return Err(RasterError::LengthMismatch {
            triangles: triangles.len(),
            objects: objects.len(),
        });
    }
    if triangles.len() >= u32::MAX as usize {
        return Err(RasterError::TooManyTriangles);
    }
    Ok(())
}

/// [`rasterize`] into existing maps, reusing their storage (resized to the
/// view and cleared first): for a method that rasterises every frame.
///
/// # Errors
/// As [`rasterize`]; `maps` is left cleared then.
pub fn rasterize_into(
    view: &LightView,
    triangles: &[[DVec3; 3]],
    objects: &[u32],
    maps: &mut LightMaps,
) -> Result<(), RasterError> {
    maps.reset(view.width, view.height);
    check_lengths(triangles, objects)?;
    fill_maps(view, triangles, objects, maps);
    Ok(())
}

/// Rows per band of the parallel rasterisation.
const BAND_ROWS: usize = 32;

/// The triangles' nearest fragments into `maps`, in bands of rows in
/// parallel: each band takes every triangle in index order and keeps only
/// its own rows, so every texel sees the same fragments in the same order
/// as a single pass would — the same bits for any thread count.
fn fill_maps(view: &LightView, triangles: &[[DVec3; 3]], objects: &[u32], maps: &mut LightMaps) {
    use rayon::prelude::*;
    let w = view.width as usize;
    if w == 0 {
        return;
    }
    let projected: Vec<Option<Projected>> = triangles
        .par_iter()
        .map(|t| project_triangle(view, t))
        .collect();
    let band = BAND_ROWS * w;
    maps.depth
        .par_chunks_mut(band)
        .zip(maps.object.par_chunks_mut(band))
        .zip(maps.triangle.par_chunks_mut(band))
        .enumerate()
        .for_each(|(b, ((depth, object_map), triangle_map))| {
            let first = (b * BAND_ROWS) as u32;
            let rows = (first, first + (depth.len() / w) as u32 - 1);
            // The band's image-plane rows, widened by a pixel each way as
            // `fill`'s own candidate rows are (the exact test decides).
            let y0 = view.lo.y + (f64::from(rows.0) - 1.0) * view.texel.y;
            let y1 = view.lo.y + (f64::from(rows.1) + 2.0) * view.texel.y;
            for (i, (t, &object)) in projected.iter().zip(objects).enumerate() {
                let Some(t) = t else { continue };
                if t.ymax < y0 || t.ymin > y1 {
                    continue;
                }
                t.fill_rows(view, rows, &mut |f: Fragment| {
                    let k = (f.row - first) as usize * w + f.col as usize;
                    // Strict: at equal depth the earlier (lower) index stays.
                    if f.depth < depth[k] {
                        depth[k] = f.depth;
                        object_map[k] = object;
                        triangle_map[k] = i as u32;
                    }
                });
            }
        });
}

/// [`rasterize`] for a scene's [`Occluders`] (which always have one object
/// id per triangle; past `u32::MAX − 1` triangles, which no `Occluders` of
/// this crate can hold in memory, the maps would be empty).
#[must_use]
pub fn rasterize_occluders(view: &LightView, occluders: &Occluders) -> LightMaps {
    rasterize(view, occluders.triangles(), occluders.objects())
        .unwrap_or_else(|_| LightMaps::empty(view.width, view.height))
}

/// Calls `emit` once for every pixel of `view` whose centre the world-space
/// triangle `tri` covers (clipped at `near`), with the triangle's depth
/// there; in no particular order. The coverage and depth of [`rasterize`],
/// for methods that accumulate something other than the nearest triangle.
/// Nothing is emitted for a triangle with a non-finite vertex, one outside
/// the domain (module docs), one entirely nearer than `near`, or one whose
/// projection has zero area.
pub fn rasterize_triangle(view: &LightView, tri: &[DVec3; 3], mut emit: impl FnMut(Fragment)) {
    if let Some(t) = project_triangle(view, tri) {
        t.fill_rows(view, (0, u32::MAX), &mut emit);
    }
}

/// A triangle clipped at the near plane and projected: up to four
/// image-plane corners (a fan) and its depth plane.
struct Projected {
    uv: [DVec2; 4],
    count: usize,
    plane: Plane,
    /// The rows its corners span (for skipping bands it cannot touch).
    ymin: f64,
    ymax: f64,
}

/// [`rasterize_triangle`]'s projection of `tri`: `None` when nothing is
/// emitted (a non-finite vertex, outside the domain, wholly nearer than
/// `near`).
fn project_triangle(view: &LightView, tri: &[DVec3; 3]) -> Option<Projected> {
    let q = tri.map(|p| view.frame.to_light(p));
    if !q
        .iter()
        .all(|p| p.is_finite() && p.abs().max_element() <= MAX_COORD)
    {
        return None;
    }
    let near = view.near;
    // Clip against z ≥ near (Sutherland–Hodgman on one plane): at most 4.
    let mut poly = [DVec3::ZERO; 4];
    let mut count = 0;
    for i in 0..3 {
        let (p, r) = (q[i], q[(i + 1) % 3]);
        let (pin, rin) = (p.z >= near, r.z >= near);
        if pin {
            poly[count] = p;
            count += 1;
        }
        if pin != rin {
            poly[count] = crossing(p, r, near);
            count += 1;
        }
    }
    if count < 3 {
        return None;
    }
    let mut uv = [DVec2::ZERO; 4];
    let (mut zmin, mut zmax) = (f64::INFINITY, 0.0f64);
    let (mut ymin, mut ymax) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..count {
        let p = poly[k];
        let u = DVec2::new(flush(p.x / p.z), flush(p.y / p.z));
        if !(u.is_finite() && u.abs().max_element() <= MAX_COORD) {
            return None;
        }
        uv[k] = u;
        zmin = zmin.min(p.z);
        zmax = zmax.max(p.z);
        ymin = ymin.min(u.y);
        ymax = ymax.max(u.y);
    }
    Some(Projected {
        uv,
        count,
        plane: Plane::new(&q, zmin, zmax),
        ymin,
        ymax,
    })
}

impl Projected {
    /// Its fragments in the pixel rows `rows.0..=rows.1`.
    fn fill_rows(&self, view: &LightView, rows: (u32, u32), emit: &mut impl FnMut(Fragment)) {
        let uv = &self.uv;
        for k in 1..self.count - 1 {
            fill(view, [uv[0], uv[k], uv[k + 1]], &self.plane, rows, emit);
        }
    }
}

/// The crossing of the edge `p r` with `z = near`:
/// `x = (x_p·(z_r − near) − x_r·(z_p − near)) / (z_r − z_p)` (and `y`
/// alike), the numerator carried in double length (error-free products and
/// sums), so that the two terms may cancel — an edge between corners 10⁷⁸
/// and 10²⁸ away crossing the plane near the light, found by the `raster`
/// fuzz target — without losing the crossing; the relative error is then a
/// few ulps. Antisymmetric in `p, r` term by term, so both triangles sharing
/// the edge get the same bits. The caller guarantees the ends are on
/// opposite sides.
fn crossing(p: DVec3, r: DVec3, near: f64) -> DVec3 {
    use crate::kernel::eft::f64::two_prod;
    // `a + b = s + e` exactly (Knuth).
    let two_sum = |a: f64, b: f64| {
        let s = a + b;
        let bv = s - a;
        (s, (a - (s - bv)) + (b - bv))
    };
    let (dp, ep) = two_sum(p.z, -near);
    let (dr, er) = two_sum(r.z, -near);
    let along = |xp: f64, xr: f64| {
        let (a, ea) = two_prod(xp, dr);
        let (b, eb) = two_prod(xr, dp);
        let (s, es) = two_sum(a, -b);
        let lo = es + ((ea + xp * er) - (eb + xr * ep));
        (s + lo) / (r.z - p.z)
    };
    DVec3::new(along(p.x, r.x), along(p.y, r.y), near)
}

/// A triangle's plane as a normal `n = (b − a) × (c − a)` and a corner
/// `a`, with `a` the corner nearest the light (the light frame's origin):
/// the differences from it keep the triangle's shape near the light when
/// another corner is far away (found by the `raster` fuzz target: a corner
/// 10¹³ behind the light swamped both edges from it, a corner 10³⁰ away
/// the offset `n·a`), and the offset is taken where the pixels that see the
/// triangle look; each component of `n` is a difference of exact products,
/// rounded once (corners 10⁷⁸ and 10²⁸ away made the products cancel).
/// Cyclic, so `n` keeps the winding of `q`.
pub(crate) fn plane_of(q: &[DVec3; 3]) -> (DVec3, DVec3) {
    use crate::kernel::eft::f64::two_prod;
    let i = (0..3)
        .min_by(|&x, &y| q[x].length_squared().total_cmp(&q[y].length_squared()))
        .unwrap_or(0);
    let (a, b, c) = (q[i], q[(i + 1) % 3], q[(i + 2) % 3]);
    let (e1, e2) = (b - a, c - a);
    // `x·y − z·w` to about one ulp of the result: the products are exact
    // pairs, so two edges to far corners in nearly the same plane (their
    // products cancel to a small normal component) keep it.
    let det2 = |x: f64, y: f64, z: f64, w: f64| {
        let (p, ep) = two_prod(x, y);
        let (r, er) = two_prod(z, w);
        let s = p - r;
        let bv = s - p;
        let es = (p - (s - bv)) + (-r - bv);
        s + (es + (ep - er))
    };
    let n = DVec3::new(
        det2(e1.y, e2.z, e1.z, e2.y),
        det2(e1.z, e2.x, e1.x, e2.z),
        det2(e1.x, e2.y, e1.y, e2.x),
    );
    (n, a)
}

/// The triangle's plane for the depth along a pixel ray.
struct Plane {
    n: DVec3,
    na: f64,
    zmin: f64,
    zmax: f64,
}

impl Plane {
    fn new(q: &[DVec3; 3], zmin: f64, zmax: f64) -> Plane {
        let (n, a) = plane_of(q);
        Plane {
            n,
            na: n.dot(a),
            zmin,
            zmax,
        }
    }

    /// `z = (n·a) / (n·(u, v, 1))`, clamped to the polygon's depth range
    /// (where the exact value lies); never NaN.
    #[inline]
    fn depth(&self, p: DVec2) -> f64 {
        let z = self.na / (self.n.x * p.x + self.n.y * p.y + self.n.z);
        if z >= self.zmin {
            z.min(self.zmax)
        } else {
            self.zmin
        }
    }
}

/// Whether an edge `a → b` of a counter-clockwise triangle owns the points
/// on it: the top-left rule. Antisymmetric in `a, b` for `a ≠ b` (the sign
/// of a rounded difference is exact).
#[inline]
fn owns_edge(a: DVec2, b: DVec2) -> bool {
    b.y < a.y || (b.y == a.y && b.x > a.x)
}

/// The sign of `orient2d(a, b, p)` (left of `a → b` is positive): the
/// rounded determinant when Shewchuk's bound certifies its sign, else the
/// exact predicate. The same evaluation order as `orient2d`'s filter.
#[inline]
fn side(a: DVec2, b: DVec2, p: DVec2) -> i32 {
    let l = (a.x - p.x) * (b.y - p.y);
    let r = (a.y - p.y) * (b.x - p.x);
    let det = l - r;
    let bound = CCW_ERR_BOUND_A * (l.abs() + r.abs());
    if det > bound {
        1
    } else if -det > bound {
        -1
    } else {
        orient2d(a, b, p).to_i32()
    }
}

/// An edge of a counter-clockwise triangle and whether it owns its points.
#[derive(Clone, Copy)]
struct Edge {
    a: DVec2,
    b: DVec2,
    owns: bool,
}

impl Edge {
    fn new(a: DVec2, b: DVec2) -> Edge {
        Edge {
            a,
            b,
            owns: owns_edge(a, b),
        }
    }

    #[inline]
    fn admits(&self, p: DVec2) -> bool {
        match side(self.a, self.b, p) {
            1 => true,
            0 => self.owns,
            _ => false,
        }
    }
}

/// Emits the pixels whose centres the projected triangle covers.
///
/// Per row the covered centres form one run of columns: each edge's test is
/// the exact sign of a function linear in `x`, and pixel centres increase
/// with the column. So a row is found from a guess of its first column
/// (where the left edges cross the row, in floating point): when the exact
/// test accepts the guess, the run starts at the first column to its left
/// that the test rejects; when it rejects the guess, the row is scanned
/// from the left of the bounding box as if there were no guess. Either way
/// every decision is the exact test's, and the run ends at the first
/// rejected column.
fn fill(
    view: &LightView,
    t: [DVec2; 3],
    plane: &Plane,
    rows: (u32, u32),
    emit: &mut impl FnMut(Fragment),
) {
    let [a, mut b, mut c] = t;
    match orient2d(a, b, c) {
        Sign::Zero => return,
        Sign::Negative => std::mem::swap(&mut b, &mut c),
        Sign::Positive => {}
    }
    let edges = [Edge::new(a, b), Edge::new(b, c), Edge::new(c, a)];
    let min = a.min(b).min(c);
    let max = a.max(b).max(c);
    // Candidate pixels: centres in [min, max], widened by a pixel for the
    // rounding of the division; the exact test decides.
    let Some((c0, c1)) = span(min.x, max.x, view.lo.x, view.texel.x, view.width) else {
        return;
    };
    let Some((r0, r1)) = span(min.y, max.y, view.lo.y, view.texel.y, view.height) else {
        return;
    };
    let (r0, r1) = (r0.max(rows.0), r1.min(rows.1));
    if r0 > r1 {
        return;
    }
    let inside = |x: f64, y: f64| {
        let p = DVec2::new(x, y);
        x >= min.x && x <= max.x && edges.iter().all(|e| e.admits(p))
    };
    // The left edges (interior on their +x side: going down, counter-
    // clockwise) as x = x0 + (y − y0)·slope, for the guess only.
    let mut left = [(0.0, 0.0, 0.0); 3];
    let mut lefts = 0;
    for e in edges.iter().filter(|e| e.b.y < e.a.y) {
        left[lefts] = (e.a.x, e.a.y, (e.b.x - e.a.x) / (e.b.y - e.a.y));
        lefts += 1;
    }
    let left = &left[..lefts];
    let xs = &view.xs[..];
    for row in r0..=r1 {
        let y = view.ys[row as usize];
        if y < min.y || y > max.y {
            continue;
        }
        let xl = left
            .iter()
            .map(|&(x0, y0, k)| x0 + (y - y0) * k)
            .fold(min.x, f64::max);
        let g = ((xl - view.lo.x) / view.texel.x - 0.5).ceil();
        // NaN saturates to 0 in the cast; clamp to the box.
        let mut col = (g.max(0.0) as u32).clamp(c0, c1);
        if inside(xs[col as usize], y) {
            while col > c0 && inside(xs[col as usize - 1], y) {
                col -= 1;
            }
        } else {
            match (c0..=c1).find(|&k| inside(xs[k as usize], y)) {
                Some(k) => col = k,
                None => continue,
            }
        }
        // `col` is covered and starts the run.
        loop {
            let x = xs[col as usize];
            emit(Fragment {
                col,
                row,
                depth: plane.depth(DVec2::new(x, y)),
            });
            if col == c1 || !inside(xs[col as usize + 1], y) {
                break;
            }
            col += 1;
        }
    }
}

/// The range of pixel indices whose centres may lie in `[min, max]`, with a
/// one-pixel margin; `None` when it misses the view.
fn span(min: f64, max: f64, lo: f64, s: f64, n: u32) -> Option<(u32, u32)> {
    let first = ((min - lo) / s - 0.5).floor() - 1.0;
    let last = ((max - lo) / s - 0.5).ceil() + 1.0;
    let top = f64::from(n - 1);
    if !(first <= top && last >= 0.0) {
        return None;
    }
    // Both in [0, n − 1] now; the casts are exact.
    Some((first.max(0.0) as u32, last.min(top) as u32))
}
