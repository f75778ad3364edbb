//! Occluding edges soft shadows (Reimann & Dreier, "Occluding Edges Soft
//! Shadows", GRAPP 2016): [`Oess`], for segment lights.
//!
//! # The algorithm (the paper's §3)
//!
//! 1. **Endpoint maps** (step 1): shadow maps from the light's two ends
//!    `L` and `R`, in frames with `x` along the segment, over one window:
//!    a map row is a plane through the light's line, and a texel's
//!    corresponding texel in the other map is on the same row (see
//!    `maps`).
//! 2. **Occluding edges** (step 2): in `L`'s map, the texels the other end
//!    sees at a terminator beside texels it does not — by the tilt of the
//!    texel's triangle toward `R`, by the corresponding columns running
//!    backward, or both (`no-tilt`, `no-corr` switch one off; combined by
//!    OR, ours: the paper does not say). Mirrored in `R`'s map.
//! 3. **Outreach** (step 3): each edge is handed along its row to the
//!    texels beside it that the other end cannot see.
//! 4. **Lighting** (step 4): a receiver `F` looks up, in each map, the edge
//!    that reached its texel in the two rows around it; the edge points
//!    are interpolated linearly to `F`'s row position, so that the edge
//!    lies (up to the kernel's projection) in the plane through the light
//!    and `F` — where only one row has an edge, that row's (ours). The
//!    visible part of the segment is the linear-light kernel's
//!    ([`visible_part_3d`]: the shadow line from `F` through the edge cuts
//!    the light at `P`), the occluder toward `R` for `L`'s map's edges and
//!    toward `L` for `R`'s; left and right penumbrae merge by intersecting
//!    their visible intervals (ours: the paper does not say how).
//!
//! **Umbra and penumbra** (substep 4.1, the paper's final choice): every
//! receiver reached by an outreach is penumbra, whatever its depth; one
//! reached by none is umbra (`0`) when neither end sees it and lit (`1`)
//! when both do. One seen by one end only and reached by no outreach —
//! the penumbra of an occluder that casts no umbra is not next to it in
//! the map, so no outreach gets there — takes the nearest edge on the
//! occluder's side of its texel in that end's row (interpolated between
//! the two rows as above), and half the light (the two ends' hard
//! shadows) where the row has none (ours: the paper leaves these
//! receivers to the two point lights, which is the half; the nearest edge
//! lowers the penumbra RMSE on `linear-light` from 0.343 to 0.317). With
//! `depth-check` (the paper's first approach) an outreach counts only
//! where the receiver is the surface the map sees at its texel. Depths
//! are compared on the plane of the triangle a texel sees, along the
//! receiver's own ray, with the relative margin `bias`. Receivers behind
//! the light frame's plane read 1, as in PCSS and SISM; the frames' `z`
//! axis is the mean of the directions from the light's line to the
//! receivers (ours), so that as many as can be are in front.
//!
//! `V` is the visible fraction of the segment. The weights of the two end
//! samples under linear emission ([`VisiblePart::weight_l`],
//! [`VisiblePart::weight_r`]) shade the picture ([`Output::end_weights`]);
//! error tables compare `V`. With `law-of-sines` the fraction comes from
//! the paper's eq. 1 as printed ([`law_of_sines_fraction`]) instead of the
//! stable construction.
//!
//! [`visible_part_3d`]: crate::kernel::linear_light::f64::visible_part_3d
//! [`law_of_sines_fraction`]: crate::kernel::linear_light::f64::law_of_sines_fraction
//! [`VisiblePart::weight_l`]: crate::kernel::linear_light::f64::VisiblePart::weight_l
//! [`VisiblePart::weight_r`]: crate::kernel::linear_light::f64::VisiblePart::weight_r

mod maps;

use super::options::{from_options, method_options};
use super::{per_receiver, Input, Method, MethodError, Output};
use crate::kernel::linear_light::f64::{law_of_sines_fraction, visible_part_3d, VisiblePart};
use crate::kernel::linear_light::OccluderSide;
use crate::render::raster::MAX_RESOLUTION;
use crate::render::stages::fit_key;
use crate::render::{Needs, Receiver};
use crate::scene::light::Segment;
use crate::scene::{Light, LightKind};
use glam::{DVec2, DVec3};
use maps::{EndMap, EndpointMaps, Strategies};

method_options! {
    /// Occluding edges soft shadows: see the [module docs](self). Segment
    /// lights only; needs neither normals nor object ids.
    ///
    #[doc = crate::method::fitted_maps_doc!()]
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[non_exhaustive]
    pub struct Oess {
        /// Side of the two endpoint maps, `1..=16384`; default
        /// [`Oess::DEFAULT_RESOLUTION`] (the paper measured up to 800²).
        pub resolution: u32 = Oess::DEFAULT_RESOLUTION, option(int "map", (1, MAX_RESOLUTION as u64), "side of the endpoint maps (the paper: up to 800)"), builder(with_resolution);
        /// Occluding edges by the tilt of fragments (§3.2, strategy 1);
        /// default on.
        pub tilt: bool = true, option(flag ! "no-tilt", "without the tilt strategy (§3.2, strategy 1)"), builder(with_tilt);
        /// Occluding edges by the corresponding pixels (§3.2, strategy 2);
        /// default on.
        pub corresponding: bool = true, option(flag ! "no-corr", "without the corresponding-pixels strategy (§3.2, strategy 2)"), builder(with_corresponding);
        /// Penumbra only where the receiver is the surface the map sees
        /// (§3.4, substep 4.1's first approach); default off.
        pub depth_check: bool = false, option(flag "depth-check", "penumbra only where the map sees the receiver (§3.4, first approach)"), builder(with_depth_check);
        /// The paper's eq. 1 as printed instead of the stable construction;
        /// default off.
        pub law_of_sines: bool = false, option(flag "law-of-sines", "the paper's eq. 1 instead of the stable construction"), builder(with_law_of_sines);
        /// The relative depth margin of "hidden from the other end" and "seen
        /// by an end", `[0, 1]`; default [`Oess::DEFAULT_BIAS`] (ours).
        pub bias: f64 = Oess::DEFAULT_BIAS, option(real "bias", (0.0, 1.0), "relative depth margin of the visibility tests (ours: 0.001)"), builder(with_bias);
    }
    name: "oess",
    summary: "occluding edges soft shadows for segment lights (Reimann & Dreier 2016)",
    lights: &[LightKind::Segment],
    default_run: &["oess"],
    compare: &["oess", "oess:no-tilt", "oess:no-corr", "oess:depth-check", "oess:law-of-sines"],
}

impl Oess {
    /// Default [`Oess::resolution`]: 800 (the paper's largest measured map).
    pub const DEFAULT_RESOLUTION: u32 = 800;
    /// Default [`Oess::bias`]: 0.1 % of the depth (ours: the depths compared
    /// are the planes of the triangles the maps see, so the margin covers
    /// only the facets of tessellated curved surfaces; on `linear-light`
    /// 0.1 % gave the lowest error of 1 %, 0.3 %, 0.1 % and 0.03 %).
    pub const DEFAULT_BIAS: f64 = 0.001;
}

/// Everything [`Oess::passes`] computed, per receiver.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OessPasses {
    /// `V`, the visible fraction of the segment.
    pub visibility: Vec<f64>,
    /// `[w_L, w_R]`, the end samples' weights under linear emission.
    pub end_weights: Vec<[f64; 2]>,
    /// Whether an outreach reached the receiver (penumbra) in `L`'s map,
    /// in `R`'s map.
    pub reached: Vec<[bool; 2]>,
}

impl Method for Oess {
    from_options! {
        /// The two endpoint maps — each a depth, object and triangle map
        /// and the edge columns found in it — and the search's rows: measured
        /// 62.5 bytes a texel between `map=1024` and `map=4096` (`/usr/bin/time
        /// -f %M`); `map=16384` needs about 17 GB.
        map_bytes_per_texel: 64,
        needs: Needs::BVH,
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        let p = self.passes(input)?;
        Ok(Output {
            visibility: p.visibility,
            stderr: None,
            bound: None,
            end_weights: Some(p.end_weights),
        })
    }
}

/// One receiver's lookup in one end's map.
struct Lookup<'a> {
    map: &'a EndMap,
    side: OccluderSide,
}

impl Oess {
    /// Runs the method and returns what it computed per receiver (the
    /// visibility, the end weights, which maps' outreach reached it), for
    /// tests and diagnostics; `input` comes from
    /// [`method::check`](super::check).
    ///
    /// # Errors
    /// An invalid option; a light that is not a segment; endpoint maps
    /// that cannot be set up.
    pub fn passes(&self, input: &Input<'_, '_>) -> Result<OessPasses, MethodError> {
        super::check_options(self)?;
        let Light::Segment(segment) = *input.light() else {
            return Err(MethodError::UnsupportedLight {
                method: self.name(),
                light: input.light().kind().name(),
            });
        };
        let (stages, frame) = (input.stages(), input.frame());
        if frame.receivers().is_empty() {
            return Ok(OessPasses::default());
        }
        // Every segment light (two distinct finite ends, any length) has
        // its frames; `None` would be a bug, reported rather than hidden.
        let frames =
            maps::frames(&segment, &stages.fit_receivers(frame)).ok_or_else(|| MethodError::Contract {
                method: self.name(),
                message: {
                    let (a, b) = (segment.a(), segment.b());
                    format!(
                        "no light frame along the segment from [{:e}, {:e}, {:e}] to [{:e}, {:e}, {:e}]",
                        a.x, a.y, a.z, b.x, b.y, b.z
                    )
                },
            })?;
        let strategies = Strategies {
            tilt: self.tilt,
            corresponding: self.corresponding,
            bias: self.bias,
        };
        let key = format!(
            "{} {} tilt {} corr {} bias {:x}",
            fit_key(frame),
            self.resolution,
            self.tilt,
            self.corresponding,
            self.bias.to_bits()
        );
        let maps = stages.cached("oess endpoint maps", key, || {
            let m = EndpointMaps::new(
                &segment,
                frames,
                stages.bvh().occluders(),
                &stages.fit_points(frame),
                self.resolution,
                strategies,
            );
            let detail = match &m {
                Ok(m) => format!(
                    "2 × {0}×{0}; edges by tilt {1} + {2}, by corresponding pixels {3} + {4}",
                    self.resolution, m.l.found.0, m.r.found.0, m.l.found.1, m.r.found.1
                ),
                Err(e) => format!("not built: {e}"),
            };
            (m, detail)
        });
        let maps = maps
            .as_ref()
            .as_ref()
            .map_err(|e| MethodError::LightView(*e))?;
        let results = per_receiver(input, || (), |(), _, r| Ok(self.shade(&segment, maps, r)))?;
        let mut out = OessPasses::default();
        for (v, w, reached) in results {
            out.visibility.push(v);
            out.end_weights.push(w);
            out.reached.push(reached);
        }
        Ok(out)
    }

    /// `V`, the end weights and which maps reached receiver `r`.
    fn shade(
        &self,
        light: &Segment,
        maps: &EndpointMaps,
        r: &Receiver,
    ) -> (f64, [f64; 2], [bool; 2]) {
        let f = r.position;
        let lf = maps.l.view.frame();
        let q = lf.to_light(f);
        if !(q.z >= maps.l.view.near() && q.z.is_finite()) {
            return (1.0, [0.5, 0.5], [false, false]);
        }
        let lookups = [
            Lookup {
                map: &maps.l,
                side: OccluderSide::TowardR,
            },
            Lookup {
                map: &maps.r,
                side: OccluderSide::TowardL,
            },
        ];
        let mut part = VisiblePart::FULL;
        let mut reached = [false, false];
        for (k, lookup) in lookups.iter().enumerate() {
            let Some(e) = self.edge_for(lookup.map, f) else {
                continue;
            };
            reached[k] = true;
            let p = self.visible(light, f, e, lookup.side);
            part = part.intersect(&p);
        }
        if reached.iter().any(|&x| x) {
            return (part.fraction, [part.weight_l, part.weight_r], reached);
        }
        // Reached by no outreach: umbra, lit, or seen by one end only.
        let seen = [self.seen(&maps.l, f), self.seen(&maps.r, f)];
        let part = match seen {
            [true, true] => VisiblePart::FULL,
            [false, false] => VisiblePart::EMPTY,
            // Seen by one end only, reached by no outreach (the penumbra
            // is not next to its occluder in the map, or an outreach
            // stopped a texel short): the nearest edge on the occluder's
            // side in the seeing end's map; with none, the two ends' hard
            // shadows, half the light (ours).
            [true, false] | [false, true] => {
                let lookup = if seen[0] { &lookups[0] } else { &lookups[1] };
                match self.edge_beyond(lookup.map, f) {
                    Some(e) => self.visible(light, f, e, lookup.side),
                    None if seen[0] => VisiblePart::interval(0.0, 0.5),
                    None => VisiblePart::interval(0.5, 1.0),
                }
            }
        };
        (part.fraction, [part.weight_l, part.weight_r], reached)
    }

    /// The visible part of the segment from `f` past the edge point `e`.
    fn visible(&self, light: &Segment, f: DVec3, e: DVec3, side: OccluderSide) -> VisiblePart {
        let (l, r) = (light.a(), light.b());
        if !self.law_of_sines {
            return visible_part_3d(l, r, f, e, side);
        }
        // The paper's eq. 1 in the plane through the light and `f`: `i` is
        // the fraction from `L` to `P`.
        let Some([l2, r2, f2, e2]) = in_plane(l, r, f, e) else {
            return VisiblePart::FULL;
        };
        match law_of_sines_fraction(l2, r2, f2, e2) {
            Some(i) => match side {
                OccluderSide::TowardR => VisiblePart::interval(0.0, i),
                OccluderSide::TowardL => VisiblePart::interval(i, 1.0),
            },
            // The shadow line misses the segment: the stable construction
            // says wholly visible or wholly hidden.
            None => visible_part_3d(l, r, f, e, side),
        }
    }

    /// The occluding edge for the receiver at `f` in `map`: the edges that
    /// reached its texel in the two rows around its position, interpolated
    /// to it (one row's alone where the other has none).
    fn edge_for(&self, map: &EndMap, f: DVec3) -> Option<DVec3> {
        self.row_edges(map, f, EndMap::edge_at)
    }

    /// The edges nearest the receiver's texel on the occluder's side in
    /// the two rows around it, interpolated as [`Oess::edge_for`] does.
    fn edge_beyond(&self, map: &EndMap, f: DVec3) -> Option<DVec3> {
        self.row_edges(map, f, EndMap::beyond_at)
    }

    /// The edge columns `column` gives for the receiver's texel in the two
    /// rows around it, as edge points interpolated to its row position.
    fn row_edges(
        &self,
        map: &EndMap,
        f: DVec3,
        column: impl Fn(&EndMap, i64, i64) -> Option<u32>,
    ) -> Option<DVec3> {
        let view = &map.view;
        let q = view.frame().to_light(f);
        let u = DVec2::new(q.x / q.z, q.y / q.z);
        let t = view.to_pixel(u);
        if !t.is_finite() {
            return None;
        }
        let col = t.x.floor() as i64;
        let below = (t.y - 0.5).floor();
        let w = (t.y - 0.5) - below;
        let r0 = below as i64;
        let point = |row: i64| {
            let c = column(map, col, row)?;
            if self.depth_check {
                // Penumbra only where the map sees the receiver's surface.
                let d = map.surface_depth(col as u32, row as u32, u);
                if (d - q.z).abs() > self.bias * q.z {
                    return None;
                }
            }
            map.edge_point(c, row as u32)
        };
        match (point(r0), point(r0 + 1)) {
            (Some(a), Some(b)) => Some(a + (b - a) * w),
            (Some(a), None) | (None, Some(a)) => Some(a),
            (None, None) => None,
        }
    }

    /// Whether the end of `map` sees the receiver at `f`.
    fn seen(&self, map: &EndMap, f: DVec3) -> bool {
        let view = &map.view;
        let q = view.frame().to_light(f);
        let u = DVec2::new(q.x / q.z, q.y / q.z);
        let Some((col, row)) = view.pixel_of(u) else {
            return true;
        };
        map.surface_depth(col, row, u) >= q.z * (1.0 - self.bias)
    }
}

/// `l`, `r`, `f` and the projection of `e` in orthonormal coordinates of
/// the plane through `l`, `r`, `f` (origin `l`, first axis along `r − l`);
/// `None` when the plane is undefined.
fn in_plane(l: DVec3, r: DVec3, f: DVec3, e: DVec3) -> Option<[DVec2; 4]> {
    let x = (r - l).try_normalize()?;
    let y = ((f - l) - x * (f - l).dot(x)).try_normalize()?;
    let to = |p: DVec3| DVec2::new((p - l).dot(x), (p - l).dot(y));
    Some([to(l), to(r), to(f), to(e)])
}
