//! Percentage-closer soft shadows (Fernando, "Percentage-Closer Soft
//! Shadows", SIGGRAPH 2005 sketch): the baseline engines ship today.

use super::centre::depth::{margin as depth_margin, DepthTest};
use super::options::{from_options, method_options};
use super::{per_receiver, Horizon, Input, Method, MethodError, Output, Requires};
use crate::kernel::footprint::f64::{self as footprint, project};
use crate::render::raster::MAX_RESOLUTION;
use crate::render::{FittedMaps, Needs};
use crate::scene::LightKind;
use glam::{DVec2, DVec3};

method_options! {
    /// Percentage-closer soft shadows over one light-view depth map from the
    /// light's centre, in three steps per receiver `p` (light-frame depth
    /// `z_p`, projection `s` on the light image plane):
    ///
    /// 1. **Blocker search**: the depth map is read at
    ///    [`blocker_samples`](Pcss::blocker_samples) points of the disk of
    ///    radius `r (1/z_min − 1/z_p)` around `s` — the light as seen from `p`,
    ///    drawn on the image plane at the least occluder depth `z_min` of the
    ///    map (the [footprint radius](crate::definitions#footprint-radius); Fernando's "search width"
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
    ///
    #[doc = crate::method::fitted_maps_doc!()]
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[non_exhaustive]
    pub struct Pcss {
        /// Side of the square light-view depth map, in texels, `1..=16384`;
        /// default [`Pcss::DEFAULT_RESOLUTION`].
        pub resolution: u32 = Pcss::DEFAULT_RESOLUTION, option(int "map", (1, MAX_RESOLUTION as u64), "side of the depth map in texels (ours)"), builder(with_resolution);
        /// Points read in the blocker search, `1..=4096`; default
        /// [`Pcss::DEFAULT_BLOCKER_SAMPLES`].
        pub blocker_samples: u32 = Pcss::DEFAULT_BLOCKER_SAMPLES, option(int "search", (1, 4096), "points read in the blocker search (ours)"), builder(with_blocker_samples);
        /// Points read by the filter, `1..=4096`; default
        /// [`Pcss::DEFAULT_FILTER_SAMPLES`].
        pub filter_samples: u32 = Pcss::DEFAULT_FILTER_SAMPLES, option(int "filter", (1, 4096), "points read by the filter (ours)"), builder(with_filter_samples);
        /// Which depth a texel is compared with; default
        /// [`PcssBias::ReceiverPlane`] (ours: the known improvement on the
        /// constant bias).
        pub bias: PcssBias = PcssBias::ReceiverPlane, option(flag "constant" == PcssBias::Constant, else PcssBias::ReceiverPlane, "compare texels with the receiver's own depth, not its tangent plane's"), builder(with_bias);
        /// The margin below that depth, relative to the receiver's depth `z_p`,
        /// for rounding and curvature, in `[0, 1]`; default
        /// [`Pcss::DEFAULT_BIAS_RELATIVE`].
        pub bias_relative: f64 = Pcss::DEFAULT_BIAS_RELATIVE, option(real "relative", (0.0, 1.0), "depth margin relative to the receiver's depth (ours)");
        /// The margin below that depth in texels, in `[0, 1000]`:
        /// `bias_texels · t · z_p`, `t` the texel's side on the light image
        /// plane (so `t · z_p` is its width at the receiver); covers a faceted
        /// or curved receiver leaving its tangent plane within the texel the
        /// sample falls in; default [`Pcss::DEFAULT_BIAS_TEXELS`].
        pub bias_texels: f64 = Pcss::DEFAULT_BIAS_TEXELS, option(real "texels", (0.0, 1000.0), "depth margin in texels at the receiver (ours)");
        /// The [horizon bound](super::Horizon), `min(V, V_h)`; default off
        /// (ours).
        pub horizon: bool = false, option(flag "horizon", "V ≤ the light's share above the receiver's tangent plane (ours)"), builder(with_horizon);
    }
    name: "pcss",
    summary: "percentage-closer soft shadows (Fernando 2005)",
    lights: LightKind::ALL,
    default_run: &["pcss"],
    compare: &["pcss", "pcss:map=256", "pcss:map=4096", "pcss:horizon"],
}

/// Which depth PCSS compares a depth-map texel with to decide that it blocks
/// the receiver: the texel at depth `d` blocks when `d < z − m`, with the
/// margin `m = z_p · min(bias_relative + bias_texels · t, MAX_BIAS_SHARE)`
/// of [`Pcss`].
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

impl Pcss {
    /// Default [`Pcss::resolution`]: 1024 (ours; the paper fixes none).
    pub const DEFAULT_RESOLUTION: u32 = 1024;
    /// Default [`Pcss::blocker_samples`]: 32 (ours; the paper fixes none).
    pub const DEFAULT_BLOCKER_SAMPLES: u32 = 32;
    /// Default [`Pcss::filter_samples`]: 64 (ours; the paper fixes none).
    pub const DEFAULT_FILTER_SAMPLES: u32 = 64;
    /// The largest depth margin, as a share of the receiver's depth: `0.05`
    /// (ours). However coarse the map, a blocker nearer the light than the
    /// receiver by more than 5 % of the receiver's depth is always found (a
    /// 1000 × 1000 ceiling one unit above a floor point five units from the
    /// light made texels of 1.2 units at the receiver, and the uncapped
    /// margin lit the point). The single-sample method and SSOC cap theirs
    /// the same way.
    pub const MAX_BIAS_SHARE: f64 = super::centre::depth::MAX_MARGIN_SHARE;
    /// Default [`Pcss::bias_relative`]: `1e-3` (ours).
    pub const DEFAULT_BIAS_RELATIVE: f64 = 1e-3;
    /// Default [`Pcss::bias_texels`]: one texel (ours).
    pub const DEFAULT_BIAS_TEXELS: f64 = 1.0;

    /// With the bias margins, relative and in texels.
    #[must_use]
    pub fn with_bias_margins(self, relative: f64, texels: f64) -> Pcss {
        Pcss {
            bias_relative: relative,
            bias_texels: texels,
            ..self
        }
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
    test: DepthTest,
}

impl Lookup<'_> {
    /// The depth of the texel under image-plane point `u` when it blocks
    /// the receiver ([`DepthTest`]), `None` when it does not (or `u` is off
    /// the map).
    fn blocker(&self, u: DVec2) -> Option<f64> {
        let view = &self.maps.view;
        let (col, row) = view.pixel_of(u)?;
        let d = self.maps.maps.depth_at(col, row);
        self.test.blocks(view, col, row, d).then_some(d)
    }
}

impl Method for Pcss {
    from_options! {
        /// The depth, object and triangle maps (16 bytes a texel: measured
        /// 16.0 between `map=1024` and `map=4096`, `/usr/bin/time -f %M`).
        map_bytes_per_texel: 16,
        needs: Needs::BVH | Needs::LIGHT_FRAME | Needs::LIGHT_MAPS,
    }

    fn requires(&self) -> Requires {
        Requires {
            normals: self.bias == PcssBias::ReceiverPlane,
            normals_hint:
                "or pcss:constant, which compares with the receiver's own depth and needs none",
            ..Requires::default()
        }
    }

    fn horizon(&self) -> Horizon {
        Horizon::clamp_if(self.horizon)
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        super::check_options(self)?;
        let plane = self.bias == PcssBias::ReceiverPlane;
        let (stages, frame) = (input.stages(), input.frame());
        if frame.receivers().is_empty() {
            return Ok(Output::default());
        }
        let light = input.light();
        let maps = stages.light_maps(frame, self.resolution, self.resolution);
        let maps = match &*maps {
            Ok(maps) => maps,
            Err(e) => return Err(MethodError::LightView(*e)),
        };
        let r = light.equivalent_radius();
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
            input,
            || (),
            |(), _, rec| {
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
                let margin = depth_margin(p.z, self.bias_relative, self.bias_texels, texel);
                let lookup = Lookup {
                    maps,
                    test: DepthTest::new(p, n, margin),
                };
                let s = project(p);
                // 1. Blocker search.
                let radius = footprint::radius(r, z_min, p.z);
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
                let w = footprint::radius(r, z_b, p.z);
                // 3. Filtering.
                let lit = filter
                    .iter()
                    .filter(|o| lookup.blocker(s + **o * w).is_none())
                    .count();
                Ok(lit as f64 / filter.len() as f64)
            },
        )?;
        Ok(Output::values(visibility))
    }
}
