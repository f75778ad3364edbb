//! Percentage-closer soft shadows (Fernando, "Percentage-Closer Soft
//! Shadows", SIGGRAPH 2005 sketch): the baseline engines ship today.

use super::{per_receiver, Method, MethodError, Output};
use crate::render::FittedMaps;
use crate::render::{Frame, Needs, Stages};
use crate::scene::Light;
use glam::{DVec2, DVec3};

/// Percentage-closer soft shadows over one light-view depth map from the
/// light's centre, in three steps per receiver `p` (light-frame depth
/// `z_p`, projection `s` on the light image plane):
///
/// 1. **Blocker search**: the depth map is read at
///    [`blocker_samples`](Pcss::blocker_samples) points of the disk of
///    radius `r (1/z_min − 1/z_p)` around `s` — the light as seen from `p`,
///    drawn on the image plane at the least occluder depth `z_min` of the
///    map (DESIGN §2's footprint radius; Fernando's "search width"
///    `w_light (d_r − d_near)/d_r` in the same units). Texels nearer than the
///    receiver (see [`PcssBias`]) are blockers; `z_b` is their mean depth.
///    No blocker: `V = 1`.
/// 2. **Penumbra estimate**: `w = r (1/z_b − 1/z_p)`, Fernando's
///    `w_penumbra = (d_r − d_b) w_light / d_b` on the light image plane.
/// 3. **Percentage-closer filtering**: `V` is the fraction of
///    [`filter_samples`](Pcss::filter_samples) points of the disk of radius
///    `w` around `s` whose texel is not a blocker.
///
/// For a single planar blocker parallel to the light this is the exact
/// answer up to sampling; where blockers lie at several depths the mean
/// `z_b` is the method's known approximation.
///
/// `r` is the light's radius: a sphere's or disk's; for a rect the radius
/// of the disk of equal area; for a segment half its length; `0` for a
/// point light (PCSS is then a plain shadow-map test). Samples are placed
/// on a Vogel (golden-angle) spiral, deterministic and the same for every
/// receiver; the map is point-sampled (nearest texel). Receivers not in
/// front of the light (light-frame depth at or below the map's near plane)
/// are outside every shadow map and read `V = 1`.
///
/// The paper fixes neither sample counts, resolution nor bias; the defaults
/// here ([`Pcss::default`]) are ours and documented per field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pcss {
    /// Side of the square light-view depth map, in texels; default 1024.
    pub resolution: u32,
    /// Points read in the blocker search; default 32.
    pub blocker_samples: u32,
    /// Points read by the filter; default 64.
    pub filter_samples: u32,
    /// Which depth a texel is compared with; default
    /// [`PcssBias::ReceiverPlane`].
    pub bias: PcssBias,
    /// The margin below that depth, relative to the receiver's depth `z_p`,
    /// for rounding and curvature; default `1e-3`.
    pub bias_relative: f64,
    /// The margin below that depth in texels: `bias_texels · t · z_p`, `t`
    /// the texel's side on the light image plane (so `t · z_p` is its width
    /// at the receiver); covers a faceted or curved receiver leaving its
    /// tangent plane within the texel the sample falls in; default `1`.
    pub bias_texels: f64,
}

/// Which depth PCSS compares a depth-map texel with to decide that it blocks
/// the receiver: the texel at depth `d` blocks when `d < z − m`, with the
/// margin `m = z_p (bias_relative + bias_texels · t)` of [`Pcss`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PcssBias {
    /// `z` is the depth, at the texel's centre, of the receiver's tangent
    /// plane (the plane through the receiver with its normal): the
    /// receiver's own surface is never its blocker however wide the filter,
    /// on any slope ("receiver plane depth bias", a known improvement on a
    /// constant bias). Needs receiver normals. A receiver whose normal faces
    /// away from the light's centre (its own surface lies between it and the
    /// centre) is shadowed by that surface: for it a texel blocks when
    /// `d < z_p + m`, so its own surface, at its own depth, counts.
    ReceiverPlane,
    /// `z = z_p`, the receiver's own depth: the classic constant bias, which
    /// needs no normal but lets a sloped receiver shadow itself under a wide
    /// filter.
    Constant,
}

impl Default for Pcss {
    fn default() -> Pcss {
        Pcss {
            resolution: 1024,
            blocker_samples: 32,
            filter_samples: 64,
            bias: PcssBias::ReceiverPlane,
            bias_relative: 1e-3,
            bias_texels: 1.0,
        }
    }
}

/// The radius PCSS uses for `light` (see [`Pcss`]).
fn light_radius(light: &Light) -> f64 {
    match *light {
        Light::Sphere { radius, .. } | Light::Disk { radius, .. } => radius,
        Light::Rect { u, v, .. } => (4.0 * u.cross(v).length() / std::f64::consts::PI).sqrt(),
        Light::Segment { a, b } => 0.5 * (b - a).length(),
        Light::Point { .. } => 0.0,
    }
}

/// `n` points of the unit disk on a Vogel spiral: radius `√((i + ½)/n)`,
/// angle `i` golden angles.
fn vogel(n: u32) -> Vec<DVec2> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let i = f64::from(i);
            let (sin, cos) = (i * golden).sin_cos();
            DVec2::new(cos, sin) * ((i + 0.5) / f64::from(n)).sqrt()
        })
        .collect()
}

/// One receiver's view of the depth map.
struct Lookup<'a> {
    maps: &'a FittedMaps,
    /// The receiver in light-frame coordinates.
    p: DVec3,
    /// Its light-frame normal, when the receiver-plane bias is used.
    normal: Option<DVec3>,
    /// The margin `m` of [`PcssBias`].
    margin: f64,
    /// The receiver faces away from the light's centre: its own surface
    /// blocks it ([`PcssBias::ReceiverPlane`]).
    own_surface_blocks: bool,
}

impl Lookup<'_> {
    /// The depth of the texel under image-plane point `u` when it blocks
    /// the receiver, `None` when it does not (or `u` is off the map).
    fn blocker(&self, u: DVec2) -> Option<f64> {
        let view = &self.maps.view;
        let t = view.to_pixel(u).floor();
        if !(t.x >= 0.0
            && t.y >= 0.0
            && t.x < f64::from(view.width())
            && t.y < f64::from(view.height()))
        {
            return None;
        }
        let (col, row) = (t.x as u32, t.y as u32);
        let d = self.maps.maps.depth_at(col, row);
        let z = match self.normal {
            Some(n) => {
                // The tangent plane n·X = n·p along the ray (c, 1).
                let c = view.pixel_center(col, row);
                let z = n.dot(self.p) / n.dot(DVec3::new(c.x, c.y, 1.0));
                if z.is_finite() && z > 0.0 {
                    z
                } else {
                    self.p.z
                }
            }
            None => self.p.z,
        };
        let blocks = if self.own_surface_blocks {
            d < z + self.margin
        } else {
            d < z - self.margin
        };
        blocks.then_some(d)
    }
}

impl Pcss {
    /// The method called `name`: `pcss` (the defaults) or `pcss:OPT,…` with
    /// options `map=N` ([`resolution`](Pcss::resolution)), `search=N`
    /// ([`blocker_samples`](Pcss::blocker_samples)), `filter=N`
    /// ([`filter_samples`](Pcss::filter_samples)), `constant`
    /// ([`PcssBias::Constant`]), `relative=X`
    /// ([`bias_relative`](Pcss::bias_relative)), `texels=X`
    /// ([`bias_texels`](Pcss::bias_texels)). [`Method::name`] writes the
    /// options that differ from the defaults, in that order, so names
    /// round-trip. Values are checked when the method runs.
    ///
    /// # Errors
    /// A message naming the unknown option or the malformed value.
    pub fn from_name(name: &str) -> Result<Pcss, String> {
        let mut p = Pcss::default();
        let options =
            super::option_list(name, "pcss").ok_or_else(|| format!("unknown method '{name}'"))?;
        for opt in options {
            let bad = || {
                format!(
                    "'{name}': option '{opt}' is not one of map=N, search=N, filter=N, \
                     constant, relative=X, texels=X"
                )
            };
            if opt == "constant" {
                p.bias = PcssBias::Constant;
                continue;
            }
            let (k, v) = opt.split_once('=').ok_or_else(bad)?;
            match k {
                "map" => p.resolution = v.parse().map_err(|_| bad())?,
                "search" => p.blocker_samples = v.parse().map_err(|_| bad())?,
                "filter" => p.filter_samples = v.parse().map_err(|_| bad())?,
                "relative" => p.bias_relative = v.parse().map_err(|_| bad())?,
                "texels" => p.bias_texels = v.parse().map_err(|_| bad())?,
                _ => return Err(bad()),
            }
        }
        Ok(p)
    }
}

impl Method for Pcss {
    fn name(&self) -> String {
        let d = Pcss::default();
        let mut options = Vec::new();
        if self.resolution != d.resolution {
            options.push(format!("map={}", self.resolution));
        }
        if self.blocker_samples != d.blocker_samples {
            options.push(format!("search={}", self.blocker_samples));
        }
        if self.filter_samples != d.filter_samples {
            options.push(format!("filter={}", self.filter_samples));
        }
        if self.bias == PcssBias::Constant {
            options.push("constant".to_owned());
        }
        // `{:?}` prints the shortest string that parses back to the same f64.
        if self.bias_relative.to_bits() != d.bias_relative.to_bits() {
            options.push(format!("relative={:?}", self.bias_relative));
        }
        if self.bias_texels.to_bits() != d.bias_texels.to_bits() {
            options.push(format!("texels={:?}", self.bias_texels));
        }
        if options.is_empty() {
            "pcss".to_owned()
        } else {
            format!("pcss:{}", options.join(","))
        }
    }

    fn needs(&self, _: &Light) -> Result<Needs, MethodError> {
        Ok(Needs::BVH | Needs::LIGHT_FRAME | Needs::LIGHT_MAPS)
    }

    fn visibility(&self, stages: &Stages, frame: &Frame) -> Result<Output, MethodError> {
        let invalid = |message: &str| MethodError::InvalidOption {
            method: self.name(),
            message: message.to_owned(),
        };
        if self.resolution == 0 || self.resolution > 16384 {
            return Err(invalid("resolution must be from 1 to 16384"));
        }
        if self.blocker_samples == 0 || self.filter_samples == 0 {
            return Err(invalid("sample counts must be at least 1"));
        }
        let plane = self.bias == PcssBias::ReceiverPlane;
        if !(self.bias_relative >= 0.0
            && self.bias_texels >= 0.0
            && self.bias_relative + self.bias_texels < 1e6)
        {
            return Err(invalid("the bias margins must be finite and at least 0"));
        }
        if plane {
            if let Some(index) = frame.receivers().iter().position(|r| r.normal.is_none()) {
                return Err(MethodError::NeedsNormal {
                    method: self.name(),
                    index,
                    hint: "or use PcssBias::Constant, which needs none",
                });
            }
        }
        if frame.receivers().is_empty() {
            return Ok(Output::default());
        }
        let light = stages.scene().light();
        let maps = stages.light_maps(frame, self.resolution, self.resolution);
        let maps = match &*maps {
            Ok(maps) => maps,
            Err(e) => return Err(MethodError::LightView(*e)),
        };
        let r = light_radius(light);
        let view = &maps.view;
        let lf = view.frame();
        let [ax, ay, az] = lf.axes();
        // The least occluder depth seen by the map bounds the search.
        let z_min = maps
            .maps
            .depth()
            .iter()
            .copied()
            .filter(|d| d.is_finite())
            .fold(f64::INFINITY, f64::min);
        let texel = view.texel_size().max_element();
        let search = vogel(self.blocker_samples);
        let filter = vogel(self.filter_samples);
        let visibility = per_receiver(
            stages,
            frame,
            || (),
            |(), index, rec| {
                light
                    .emitter(rec.position)
                    .map_err(|error| MethodError::Receiver { index, error })?;
                let p = lf.to_light(rec.position);
                if !(p.z >= view.near() && z_min < p.z) {
                    return Ok(1.0);
                }
                // The tangent plane stands for the receiver's own surface
                // where that surface faces the light's centre; a receiver
                // facing away is behind its own surface, which blocks it.
                let n = rec
                    .normal
                    .filter(|_| plane)
                    .map(|n| DVec3::new(n.dot(ax), n.dot(ay), n.dot(az)));
                let facing = n.filter(|n| n.dot(p) < 0.0);
                let lookup = Lookup {
                    maps,
                    p,
                    normal: facing,
                    margin: p.z * (self.bias_relative + self.bias_texels * texel),
                    own_surface_blocks: n.is_some() && facing.is_none(),
                };
                let s = DVec2::new(p.x / p.z, p.y / p.z);
                // 1. Blocker search.
                let radius = r * (1.0 / z_min - 1.0 / p.z);
                let (mut sum, mut count) = (0.0, 0u32);
                for o in &search {
                    if let Some(d) = lookup.blocker(s + *o * radius) {
                        sum += d;
                        count += 1;
                    }
                }
                if count == 0 {
                    return Ok(1.0);
                }
                // 2. Penumbra estimate.
                let z_b = sum / f64::from(count);
                let w = r * (1.0 / z_b - 1.0 / p.z).max(0.0);
                // 3. Filtering.
                let lit = filter
                    .iter()
                    .filter(|o| lookup.blocker(s + **o * w).is_none())
                    .count();
                Ok(lit as f64 / filter.len() as f64)
            },
        )?;
        Ok(Output {
            visibility,
            stderr: None,
        })
    }
}
