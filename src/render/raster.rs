//! TEMPORARY stub of the light-view rasterizer (replaced by the real one).
#![allow(missing_docs, dead_code, clippy::neg_cmp_op_on_partial_ord)]

use crate::reference::Occluders;
use crate::scene::LightFrame;
use glam::{DVec2, DVec3};
use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum RasterError {
    Empty,
}
impl fmt::Display for RasterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "nothing in front of the light")
    }
}
impl std::error::Error for RasterError {}

#[derive(Clone, Debug)]
pub struct LightView {
    frame: LightFrame,
    lo: DVec2,
    hi: DVec2,
    width: u32,
    height: u32,
    near: f64,
}

impl LightView {
    pub fn fit(
        frame: LightFrame,
        points: impl IntoIterator<Item = DVec3>,
        width: u32,
        height: u32,
        near: f64,
    ) -> Result<LightView, RasterError> {
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = -lo;
        for p in points {
            let q = frame.to_light(p);
            if q.z >= near {
                let s = DVec2::new(q.x / q.z, q.y / q.z);
                lo = lo.min(s);
                hi = hi.max(s);
            }
        }
        if !(lo.x <= hi.x) {
            return Err(RasterError::Empty);
        }
        let px =
            (hi - lo).max(DVec2::splat(1e-9)) / DVec2::new(f64::from(width), f64::from(height));
        Ok(LightView {
            frame,
            lo: lo - px,
            hi: hi + px,
            width,
            height,
            near,
        })
    }
    pub fn near(&self) -> f64 {
        self.near
    }
    pub fn frame(&self) -> LightFrame {
        self.frame
    }
    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    pub fn texel_size(&self) -> DVec2 {
        (self.hi - self.lo) / DVec2::new(f64::from(self.width), f64::from(self.height))
    }
    pub fn to_pixel(&self, s: DVec2) -> DVec2 {
        (s - self.lo) / self.texel_size()
    }
    pub fn pixel_center(&self, col: u32, row: u32) -> DVec2 {
        self.lo + (DVec2::new(f64::from(col), f64::from(row)) + 0.5) * self.texel_size()
    }
}

#[derive(Clone, Debug)]
pub struct LightMaps {
    view: LightView,
    depth: Vec<f64>,
    object: Vec<u32>,
}

impl LightMaps {
    pub fn view(&self) -> &LightView {
        &self.view
    }
    pub fn depth_at(&self, col: u32, row: u32) -> f64 {
        self.depth[(row * self.view.width + col) as usize]
    }
    pub fn depths(&self) -> &[f64] {
        &self.depth
    }
    pub fn object_at(&self, col: u32, row: u32) -> u32 {
        self.object[(row * self.view.width + col) as usize]
    }
}

pub fn rasterize_occluders(view: &LightView, occ: &Occluders) -> LightMaps {
    let n = (view.width * view.height) as usize;
    let mut depth = vec![f64::INFINITY; n];
    let mut object = vec![u32::MAX; n];
    for row in 0..view.height {
        for col in 0..view.width {
            let s = view.pixel_center(col, row);
            let d = DVec3::new(s.x, s.y, 1.0);
            for (i, t) in occ.triangles().iter().enumerate() {
                let [a, b, c] = t.map(|v| view.frame.to_light(v));
                let e1 = b - a;
                let e2 = c - a;
                let pv = d.cross(e2);
                let det = e1.dot(pv);
                if det.abs() < 1e-300 {
                    continue;
                }
                let inv = 1.0 / det;
                let tv = -a;
                let u = tv.dot(pv) * inv;
                if !(0.0..=1.0).contains(&u) {
                    continue;
                }
                let qv = tv.cross(e1);
                let v = d.dot(qv) * inv;
                if v < 0.0 || u + v > 1.0 {
                    continue;
                }
                let z = e2.dot(qv) * inv;
                let k = (row * view.width + col) as usize;
                if z >= view.near && z < depth[k] {
                    depth[k] = z;
                    object[k] = occ.objects()[i];
                }
            }
        }
    }
    LightMaps {
        view: view.clone(),
        depth,
        object,
    }
}
