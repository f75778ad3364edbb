//! The scalar renderer (feature `render`): receivers from the camera, the
//! light-view rasterizer, the lazily built stages every method draws on, and
//! image output. DESIGN.md §5.

pub mod raster;
