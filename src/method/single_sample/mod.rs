//! Single-sample soft shadows (Brabec & Seidel, "Single Sample Soft
//! Shadows using Depth Maps", Graphics Interface 2002): [`SingleSample`].
//!
//! # The algorithm (the paper's §3–§4)
//!
//! From the light's centre, one depth map and one object-id map (the
//! shared light maps of [`Stages::light_maps`], 256² by default as in the
//! paper's §5). Each receiver `p` is warped into the light view: `P′` is
//! its continuous texel position and `P′_z` its light-frame depth.
//!
//! 1. **Hard test** (§3.2): the texel under `P′` blocks `p` or not, by the
//!    depth test with PCSS's receiver-plane bias (a texel blocks when its
//!    depth is below the receiver's tangent plane's along the texel's ray,
//!    less a margin; see `DepthTest` in `method::centre`).
//! 2. **Lit receivers** (§3.2, the *outer* penumbra): the nearest texel
//!    that blocks `p` and carries another object's id (§3.2's id test: a
//!    receiver is never its own blocker), at Euclidean distance `d` from
//!    `P′` to the texel centre, in texels, within `r_max = r_scale·|P′_z| +
//!    r_bias`; then `r_max ← r_max · r_shrink · (P′_z − z_blocker)` and
//!    `V = m + (1 − m)·clamp(d/r_max)` with `m` the meeting value (0.5).
//!    None found: `V = 1`.
//! 3. **Shadowed receivers** (§3.3, the *inner* penumbra): the nearest
//!    texel that is lit (does not block `p`) and carries `p`'s own id, as
//!    the paper's inner search requires; `r_max ← r_max · r_shrink ·
//!    max(z_texel − P′_z, margin)` (the depth difference is about 0 on a
//!    planar receiver; floored at the depth test's margin) and `V = m·(1 −
//!    clamp(d/r_max))`. None found: `V = 0`.
//!
//! The paper's printed pseudo-code returns `0.5·clamp(r/r_max)` (inner)
//! and `1 − 0.5·clamp(r/r_max)` (outer), which makes a receiver brightest
//! next to its blocker, against §3.2's own text ("`f` rises from 0 to 1 as
//! the distance to the blocker increases"): the two branches are used here
//! as the text describes them, meeting at `m` on the hard boundary.
//!
//! 4. **Adaptive interpolation** (§4.3): on camera frames, the searches of
//!    steps 2–3 run only where the paper's 5-pixel group test asks
//!    (columns, then rows; see `interpolate`), elsewhere values are
//!    interpolated linearly. Points files are never interpolated.
//!
//! # Parameters
//!
//! The paper's only figure is `r_max` = 20 texels at 256², "the average
//! search radius on the receiver plane about 16". Ours, fixed per frame
//! (documented as ours): `r_bias = 0`; `r_scale` such that `r_max` is 20
//! texels at the frame's farthest receiver (`r_scale = 20 / z_far`);
//! `r_shrink = 1 / z_far`, so the rescale is 1 when the blocker–receiver
//! depth gap equals the light-to-farthest-receiver depth. The options
//! `r-scale`, `r-bias`, `r-shrink` override them; the values used and the
//! texel size are in the run's stats (stage `single-sample setup`).
//!
//! # Light-aware, beyond the paper (its own future work, §6)
//!
//! With `light-aware` (sphere and disk lights) the constants are replaced
//! by the light's footprint on the light image plane
//! ([`footprint::radius`](crate::kernel::footprint::f64::radius)): the
//! search radius `r(1/z_min − 1/z_p)` (`z_min` the least depth of the map),
//! and `r_max = r(1/z_b − 1/z_p)` with `z_b` the depth of the blocker found
//! (outer) or of the blocker at `P′` (inner), distances on the image plane.
//! With `falloff=exact` the linear ramp `(1 ± d/r_max)/2` goes through the
//! straight-edge disk falloff (the paper's future work: "a sinusoid").
//!
//! # What the paper admits
//!
//! An object never shadows itself (the id test); shadows are rounded off at
//! corners (a circular search); the umbra is as large as the hard shadow.
//!
//! [`Stages::light_maps`]: crate::render::Stages::light_maps

mod interpolate;
mod search;

use super::centre::depth::{self, DepthTest};
use super::options::{from_options, method_options};
use super::{per_receiver, Horizon, Input, Method, MethodError, Output, Requires};
use crate::kernel::falloff::{f64 as falloff, Falloff};
use crate::kernel::footprint::f64::{self as footprint, project};
use crate::render::raster::{LightMaps, LightView, MAX_RESOLUTION};
use crate::render::stages::fit_key;
use crate::render::{FittedMaps, Needs, Receiver};
use crate::scene::LightKind;
use glam::{DVec2, DVec3};
use interpolate::{Hard, Source};
use rayon::prelude::*;
use search::{Search, Tiles, Want};
use std::sync::Arc;

method_options! {
    /// Single-sample soft shadows: see the [module docs](self). Sphere, disk
    /// and rect lights (the paper's point sample is the light's centre); needs
    /// receiver normals (the depth test's receiver plane) and object ids (the
    /// id test; not with `no-id`).
    ///
    #[doc = crate::method::fitted_maps_doc!()]
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[non_exhaustive]
    pub struct SingleSample {
        /// Side of the light's depth and id maps, `1..=16384`; default
        /// [`SingleSample::DEFAULT_RESOLUTION`] (the paper's §5).
        pub resolution: u32 = SingleSample::DEFAULT_RESOLUTION, option(int "map", (1, MAX_RESOLUTION as u64), "side of the depth and id maps (§5: 256)"), builder(with_resolution);
        /// `r_scale`, texels per unit of light depth, `[0, 10⁶]`; `0` (the
        /// default): 20 texels at the frame's farthest receiver (ours).
        pub r_scale: f64 = 0.0, option(real "r-scale", (0.0, 1e6), "texels per unit depth; 0: 20 texels at the farthest receiver (ours)"), builder(with_r_scale);
        /// `r_bias`, texels, `[0, 10⁶]`; default 0 (ours).
        pub r_bias: f64 = 0.0, option(real "r-bias", (0.0, 1e6), "texels added to the search radius (§3.2)"), builder(with_r_bias);
        /// `r_shrink`, per unit of light depth, `[0, 10⁶]`; `0` (the default):
        /// the reciprocal of the frame's farthest receiver depth (ours).
        pub r_shrink: f64 = 0.0, option(real "r-shrink", (0.0, 1e6), "per unit depth gap; 0: 1/farthest depth (ours)"), builder(with_r_shrink);
        /// Where the inner and outer penumbrae meet, `[0, 1]`; default 0.5
        /// (§3.3: "0.5 (or some user defined constant)").
        pub meet: f64 = 0.5, option(real "meet", (0.0, 1.0), "where inner and outer penumbrae meet (§3.3)"), builder(with_meet);
        /// The adaptive interpolation of §4.3 on camera frames; default on
        /// (the paper's).
        pub interpolate: bool = true, option(flag ! "no-interpolate", "search every pixel (without §4.3's interpolation)"), builder(with_interpolation);
        /// The object-id test of §3.2; default on (the paper's).
        pub id_test: bool = true, option(flag ! "no-id", "without the object-id test (§3.2)"), builder(with_id_test);
        /// The light-aware radii (ours, the paper's future work); default off.
        pub light_aware: bool = false, option(flag "light-aware", "radii from the light's footprint (ours; §6's future work)"), builder(with_light_aware);
        /// The ramp's falloff; default [`Falloff::Linear`] (the paper's linear
        /// intensity).
        pub falloff: Falloff = Falloff::Linear, option(choice "falloff", ["linear" = Falloff::Linear, "exact" = Falloff::Exact, "bernstein" = Falloff::Bernstein], "the ramp's falloff (exact: ours)"), builder(with_falloff);
        /// The depth test's margin relative to the receiver's depth, `[0, 1]`;
        /// default `1e-3` (PCSS's).
        pub bias_relative: f64 = 1e-3, option(real "relative", (0.0, 1.0), "depth margin relative to the receiver's depth (PCSS's)");
        /// The depth test's margin in texels at the receiver, `[0, 1000]`;
        /// default 1 (PCSS's).
        pub bias_texels: f64 = 1.0, option(real "texels", (0.0, 1000.0), "depth margin in texels at the receiver (PCSS's)");
        /// The [horizon bound](Horizon); default off (ours).
        pub horizon: bool = false, option(flag "horizon", "V ≤ the light's share above the receiver's tangent plane (ours)"), builder(with_horizon);
    }
    name: "single-sample",
    summary: "single-sample soft shadows (Brabec & Seidel 2002)",
    lights: &[LightKind::Sphere, LightKind::Disk, LightKind::Rect],
    default_run: &["single-sample"],
    compare: &["single-sample", "single-sample:light-aware",
        "single-sample:light-aware,falloff=exact", "single-sample:no-interpolate",
        "single-sample:horizon"],
}

impl SingleSample {
    /// Default [`SingleSample::resolution`]: 256 (the paper's light map for
    /// a 512² image).
    pub const DEFAULT_RESOLUTION: u32 = 256;
    /// The paper's search radius, in texels at the farthest receiver.
    pub const PAPER_RADIUS: f64 = 20.0;
}

/// Everything [`SingleSample::passes`] computed, per receiver.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SingleSamplePasses {
    /// `V`.
    pub visibility: Vec<f64>,
    /// The hard test: shadowed by the light map at the receiver's texel.
    pub shadowed: Vec<bool>,
    /// The id the group test compares: the blocker's when shadowed, the
    /// receiver's own when lit (`u32::MAX` when it has none).
    pub id: Vec<u32>,
    /// For an interpolated receiver, the two receivers it was interpolated
    /// between; `None` for one that was searched (or needs no search).
    pub interpolated_from: Vec<Option<(u32, u32)>>,
}

impl Method for SingleSample {
    from_options! {
        /// The depth and id maps and their tile summaries (measured 16.6
        /// bytes a texel between `map=1024` and `map=4096`, `/usr/bin/time
        /// -f %M`).
        map_bytes_per_texel: 17,
        needs: Needs::BVH | Needs::LIGHT_FRAME | Needs::LIGHT_MAPS,
    }

    fn requires(&self) -> Requires {
        Requires {
            normals: true,
            objects: self.id_test,
            normals_hint: "the depth test compares texels with the receiver's tangent plane",
        }
    }

    fn horizon(&self) -> Horizon {
        Horizon::clamp_if(self.horizon)
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        Ok(Output::values(self.passes(input)?.visibility))
    }
}

/// What every receiver's shading reads, fixed per frame.
struct Context<'a> {
    method: &'a SingleSample,
    view: &'a LightView,
    maps: &'a LightMaps,
    tiles: &'a Tiles,
    axes: [DVec3; 3],
    /// The largest texel side on the image plane (the margin's unit).
    texel: f64,
    /// The paper's constants in texels (the defaults resolved).
    r_scale: f64,
    r_shrink: f64,
    /// The light's radius and the map's least depth (light-aware).
    radius: f64,
    z_min: f64,
}

/// One receiver in the light view.
struct Warped {
    /// Light-frame position.
    p: DVec3,
    /// Continuous texel position `P′`.
    q: DVec2,
    test: DepthTest,
    hard: Hard,
    /// In front of the map's near plane (else `V = 1`).
    in_view: bool,
    /// The depth of the texel under `P′` (the blocker, when shadowed).
    depth_here: f64,
}

impl Context<'_> {
    fn warp(&self, r: &Receiver) -> Warped {
        let lf = self.view.frame();
        let p = lf.to_light(r.position);
        let [ax, ay, az] = self.axes;
        let normal = r
            .normal
            .map(|n| DVec3::new(n.dot(ax), n.dot(ay), n.dot(az)));
        let margin = depth::margin(
            p.z,
            self.method.bias_relative,
            self.method.bias_texels,
            self.texel,
        );
        let test = DepthTest::new(p, normal, margin);
        let own = r.object.unwrap_or(u32::MAX);
        let in_view = p.z >= self.view.near() && p.z.is_finite();
        let q = self.view.to_pixel(project(p));
        // Truncation is the floor on the map (q ≥ 0).
        let on_map = in_view
            && q.x >= 0.0
            && q.y >= 0.0
            && q.x < f64::from(self.view.width())
            && q.y < f64::from(self.view.height());
        let (mut hard, mut depth_here) = (
            Hard {
                shadowed: false,
                id: own,
            },
            f64::INFINITY,
        );
        if on_map {
            let (col, row) = (q.x as u32, q.y as u32);
            let d = self.maps.depth_at(col, row);
            depth_here = d;
            if test.blocks(self.view, col, row, d) {
                hard = Hard {
                    shadowed: true,
                    id: self.maps.object_at(col, row),
                };
            }
        }
        Warped {
            p,
            q,
            test,
            hard,
            in_view,
            depth_here,
        }
    }

    /// The soft value of a warped receiver: the search of §3.2–3.3.
    fn soft(&self, r: &Receiver, w: &Warped) -> f64 {
        if !w.in_view {
            return 1.0;
        }
        let m = self.method;
        let own = if m.id_test { r.object } else { None };
        let scale = if m.light_aware {
            self.view.texel_size()
        } else {
            DVec2::ONE
        };
        let search = Search {
            view: self.view,
            maps: self.maps,
            tiles: self.tiles,
            test: &w.test,
            scale,
        };
        let z = w.p.z;
        let initial = if m.light_aware {
            footprint::radius(self.radius, self.z_min, z)
        } else {
            self.r_scale * z.abs() + m.r_bias
        };
        let lin = if w.hard.shadowed {
            let Some(found) = search.nearest(w.q, initial, Want::LitOwn { own }) else {
                return 0.0;
            };
            let r_max = if m.light_aware {
                footprint::radius(self.radius, w.depth_here, z)
            } else {
                initial * self.r_shrink * (found.depth - z).max(w.test.margin())
            };
            m.meet * (1.0 - ramp(found.distance, r_max))
        } else {
            let Some(found) = search.nearest(w.q, initial, Want::Blocker { other: own }) else {
                return 1.0;
            };
            let r_max = if m.light_aware {
                footprint::radius(self.radius, found.depth, z)
            } else {
                initial * self.r_shrink * (z - found.depth)
            };
            m.meet + (1.0 - m.meet) * ramp(found.distance, r_max)
        };
        falloff::eval(m.falloff, lin)
    }
}

/// `clamp(d / r_max, 0, 1)`; a zero or undefined `r_max` is a hard step
/// (`d > 0`: 1).
fn ramp(d: f64, r_max: f64) -> f64 {
    let t = d / r_max;
    if t.is_nan() {
        if d > 0.0 {
            1.0
        } else {
            0.0
        }
    } else {
        t.clamp(0.0, 1.0)
    }
}

impl SingleSample {
    /// Runs the method and returns what it computed per receiver (the
    /// visibility, the hard test, the ids the group test compares, the
    /// interpolants), for tests and diagnostics; `input` comes from
    /// [`method::check`](super::check).
    ///
    /// # Errors
    /// An invalid option; `light-aware` with a rect light; a light view
    /// that cannot be set up.
    pub fn passes(&self, input: &Input<'_, '_>) -> Result<SingleSamplePasses, MethodError> {
        super::check_options(self)?;
        let light = input.light();
        if self.light_aware && light.kind() == LightKind::Rect {
            return Err(MethodError::InvalidOption {
                method: self.name(),
                message: "light-aware needs a sphere or disk light".to_owned(),
            });
        }
        let (stages, frame) = (input.stages(), input.frame());
        let n = frame.receivers().len();
        if n == 0 {
            return Ok(SingleSamplePasses::default());
        }
        let maps = stages.light_maps(frame, self.resolution, self.resolution);
        let FittedMaps { view, maps } = match &*maps {
            Ok(m) => m,
            Err(e) => return Err(MethodError::LightView(*e)),
        };
        let key = format!("{} {}", fit_key(frame), self.resolution);
        let tiles: Arc<Tiles> = stages.cached("single-sample tiles", key, || {
            let tiles = Tiles::new(maps);
            (tiles, format!("{}-texel tiles", search::TILE))
        });
        let lf = view.frame();
        // The farthest receiver in the light view (a maximum: the same for
        // any thread count).
        let z_far = stages
            .fit_receivers(frame)
            .par_iter()
            .map(|&p| lf.to_light(p).z)
            .filter(|z| z.is_finite() && *z >= view.near())
            .reduce(|| 0.0, f64::max);
        let resolve = |given: f64, derived: f64| if given > 0.0 { given } else { derived };
        let ctx = Context {
            method: self,
            view,
            maps,
            tiles: &tiles,
            axes: lf.axes(),
            texel: view.texel_size().max_element(),
            r_scale: resolve(self.r_scale, SingleSample::PAPER_RADIUS / z_far),
            r_shrink: resolve(self.r_shrink, 1.0 / z_far),
            radius: light.equivalent_radius(),
            z_min: maps
                .depth()
                .iter()
                .copied()
                .filter(|d| d.is_finite())
                .fold(f64::INFINITY, f64::min),
        };
        stages.record(
            "single-sample setup",
            format!(
                "texel {:.3e} × {:.3e}, r_scale {:.4} texels/unit, r_bias {}, r_shrink {:.4}/unit, farthest receiver {z_far:.4}",
                view.texel_size().x,
                view.texel_size().y,
                ctx.r_scale,
                self.r_bias,
                ctx.r_shrink
            ),
            std::time::Duration::ZERO,
        );
        let receivers = input.receivers();
        // The hard test of every receiver; the rest of the warp is redone
        // where a search needs it (cheaper than keeping it).
        let hard: Vec<Hard> = stages.timed("single-sample hard test", || {
            let hard: Vec<Hard> = receivers.par_iter().map(|r| ctx.warp(r).hard).collect();
            let shadowed = hard.iter().filter(|h| h.shadowed).count();
            (
                hard,
                format!("{shadowed} of {n} receivers in the map's hard shadow"),
            )
        });
        let search = |i: usize| {
            let r = &receivers[i];
            ctx.soft(r, &ctx.warp(r))
        };
        let start = std::time::Instant::now();
        let (visibility, sources) = if self.interpolate && frame.is_image() {
            let (w, h) = frame.size();
            let (v, s) = interpolate::fill(w as usize, h as usize, frame.pixels(), &hard, &search);
            stages.advance(n);
            (v, s)
        } else {
            let v = per_receiver(input, || (), |(), i, _| Ok(search(i)))?;
            (v, vec![Some(Source::Searched); n])
        };
        let searched = sources
            .iter()
            .filter(|s| **s == Some(Source::Searched))
            .count() as u64;
        stages.record(
            "single-sample search",
            format!("{searched} searches, {} interpolated", n as u64 - searched),
            start.elapsed(),
        );
        stages.count("single-sample searches", searched);
        stages.count("single-sample searches saved", n as u64 - searched);
        Ok(SingleSamplePasses {
            visibility,
            shadowed: hard.iter().map(|h| h.shadowed).collect(),
            id: hard.iter().map(|h| h.id).collect(),
            interpolated_from: sources
                .iter()
                .map(|s| match s {
                    Some(Source::Between(a, b)) => Some((*a, *b)),
                    _ => None,
                })
                .collect(),
        })
    }
}
