//! The light-view rasterizer (placeholder; built on its own branch).
