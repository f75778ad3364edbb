//! The soft shadow occlusion camera (Mo, Popescu & Wyman, "The Soft
//! Shadow Occlusion Camera", Pacific Graphics 2007): [`Ssoc`], and its
//! backprojected variant (Mo & Wyman, "Interactive Backprojected Soft
//! Shadows with an Occlusion Camera Shadow Map", 2007 sketch):
//! [`BackprojectedSsoc`].
//!
//! # SSOC (the paper's §3.2, §4)
//!
//! A shadow map from the light's centre (1024² by default), the silhouette
//! edges from the centre, and two distortion maps built from them (see
//! `maps`): each texel near a silhouette names the nearest edge on the
//! image plane, in the map of its side of the hard shadow. For a receiver
//! `p` at depth `z_p` projecting to `π(p)`:
//!
//! 1. the shadow-map test (PCSS's receiver-plane bias) says which side of
//!    the hard shadow it is on; the map of that side at `π(p)` names an
//!    edge, or none — then `V` is the shadow map's 0 or 1;
//! 2. **the distortion** (the paper's formula for `dmax` is lost from the
//!    text; our reading of §3.2, documented as ours): `s` the edge's point
//!    nearest `π(p)`, `n̂` its outward unit normal (away from the occluder),
//!    `δ = (π(p) − s)·n̂` (negative inside the hard shadow), `z_near` the
//!    edge's depth at `s` (`1/z` interpolated), `R = r(1/z_near − 1/z_p)`,
//!    `dmax = 2R` ([`max_distortion`](crate::kernel::distortion::f64::max_distortion)),
//!    `d = clamp(R − δ, 0, dmax)`; the distorted point is
//!    `π(p) + d·n̂`. A receiver in front of the edge (`z_p ≤ z_near`) has
//!    no penumbra from it;
//! 3. Fig. 5: if the distorted point is still in the hard shadow, `V = 0`;
//!    the shadow-map test there compares the texel with `p`'s tangent
//!    plane along the texel's ray, as the first test does (ours). The
//!    paper compares with `p`'s own depth less "a rather large bias" (§4,
//!    Fig. 9, no value given; [`constant_bias`](Ssoc::constant_bias) with
//!    [`bias`](Ssoc::bias), ours 2 %): on a receiver that is steep as seen
//!    from the light (a wall lit at a grazing angle, a floor under a
//!    tilted disk) its own surface at the distorted point is more than 2 %
//!    nearer the light, so it shadowed itself and read `V = 0` across its
//!    penumbra (measured in `docs/accuracy/ssoc.md`); the tangent plane is
//!    the receiver's own surface there, whatever its slope. If the
//!    distorted point lies in no distortion region,
//!    `V = 1`; else eq. 1, `V = falloff(1 − d/dmax)`
//!    ([`intensity`](crate::kernel::distortion::f64::intensity)) — the Bernstein
//!    smoothstep as in the paper (§3.2.2), or the exact disk falloff;
//! 4. **overlapping penumbrae** (§3.2.3, §4): the map is read again at the
//!    distorted point; if it names another edge, the paper's three cases
//!    are told apart — outward normals within 45° of each other, or the
//!    two edges' points nearest the receiver within a texel (a shared
//!    corner; ours): the same region, one penumbra; disjoint `[z_near, z_far]` ranges: only the
//!    first penumbra counts; otherwise `d` is recomputed for the original
//!    receiver against the new edge and the intensities multiply — up to
//!    [`lookups`](Ssoc::lookups) edges in all.
//!
//! Three lookups or one: measured on the built-in scenes, three do not
//! beat one where penumbrae overlap (`overlapping-penumbrae`) or occluders
//! stack (`depth-complexity`) — penumbra RMSE 0.098 → 0.102 and 0.195 →
//! 0.202 — and the cause is not the multiplication: the exact union of
//! the edges' half-planes on the light does no better (the straight-edge
//! penumbra of the second edge found is itself wrong there). The default
//! stays the paper's three, the faithful reading; the figures are in
//! `docs/accuracy/ssoc.md`.
//!
//! `z_far`, "the shadow-map depth just outside the edge", is read from the
//! shadow map 1.5 texels outside `s`. With [`bilinear`](Ssoc::bilinear) the
//! four texels around `π(p)` each give a value and they are blended
//! bilinearly (§5's four lookups against nearest-texel aliasing).
//!
//! # Backprojected SSOC
//!
//! The same maps, read for their edge index only: the edges named in the
//! receiver's texel and its `(2·search + 1)²` neighbourhood, in both maps,
//! deduplicated, are mapped into the receiver's footprint and their
//! occlusion composed exactly — the union of `method::centre`, with SISM's
//! layer weights. The union needs the layer count at the footprint's
//! centre, which a shadow map does not give: it takes `1` where the map's
//! hard test says shadowed, `0` where lit (ours), so a receiver under two
//! stacked layers whose neighbourhood shows the edge of only one of them
//! reads that edge's far side as lit (measured on `depth-complexity` in
//! `docs/accuracy/ssoc.md`). With `horizon` the receiver's tangent plane
//! is one more edge of the union.
//!
//! With `potential` the maps are built from the potential silhouettes of
//! the light's bounding ball instead (every edge that is a silhouette from
//! some light point; stored in an arbitrary direction, so the two maps
//! hold the two sides of each edge), and each edge a receiver finds is
//! oriented and weighed by its multiplicity seen from the receiver
//! (`MeshTopology::silhouette_edge_from_point`): seen from the receiver
//! `p`, an edge with multiplicity `m` runs `from → to` with its faces on
//! the left; from a light point `x` whose segment to `p` crosses the edge,
//! `p` and `x` lie on opposite sides of each face's plane, so the faces
//! are on the right — the union takes the edge as `to → from`, with weight
//! `m` times the layer weight. An edge that is no silhouette from `p`
//! weighs nothing, as the sketch says; but it still takes a texel of the
//! map from an edge that would have counted, so without the walk more edges
//! find fewer of the ones that matter (measured in `docs/accuracy/ssoc.md`).
//! The walk crosses every edge whose image meets the footprint, whatever
//! its weight from the receiver, since the receiver's silhouette is a loop
//! inside the band of potential edges. Where the walk finds every edge and
//! the shadow map's centre test is right, the union is exact
//! (`tests/ssoc.rs`).

pub(crate) mod maps;

mod backprojected;

pub use backprojected::BackprojectedSsoc;

use super::centre::depth::DepthTest;
use super::centre::nearest_on;
use super::centre::{left, projected_edges, EdgeSource, ProjectedEdge, Selection};
use super::options::{from_options, method_options};
use super::{per_receiver, Horizon, Input, MethodError, Output, Requires};
use crate::kernel::distortion::f64 as distortion;
use crate::kernel::falloff::Falloff;
use crate::kernel::footprint::f64::{self as footprint, project};
use crate::render::raster::{LightMaps, LightView, MAX_RESOLUTION};
use crate::render::stages::fit_key;
use crate::render::{FittedMaps, Needs, Receiver};
use crate::scene::LightKind;
use glam::{DVec2, DVec3};
use maps::{DistortionMaps, NONE};
use std::sync::Arc;

method_options! {
    /// The soft shadow occlusion camera: see the [module docs](self). Sphere
    /// and disk lights; needs receiver normals (the shadow-map test's receiver
    /// plane).
    ///
    #[doc = crate::method::fitted_maps_doc!()]
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[non_exhaustive]
    pub struct Ssoc {
        /// Side of the shadow and distortion maps, `1..=16384`; default
        /// [`Ssoc::DEFAULT_RESOLUTION`] (ours).
        pub resolution: u32 = Ssoc::DEFAULT_RESOLUTION, option(int "map", (1, MAX_RESOLUTION as u64), "side of the shadow and distortion maps (ours)"), builder(with_resolution);
        /// How many edges a receiver's distortion may visit (§3.2.3: "two or
        /// three such steps are generally sufficient"), `1..=8`; default 3.
        pub lookups: u32 = 3, option(int "lookups", (1, 8), "edges a distortion may visit (§3.2.3: 2 or 3)"), builder(with_lookups);
        /// The test at the distorted point compares the shadow map with the
        /// receiver's own depth less [`bias`](Ssoc::bias) (the paper's reading
        /// of §4, "a rather large bias") instead of with its tangent plane;
        /// default off (ours: steep receivers, see the [module docs](self)).
        pub constant_bias: bool = false, option(flag "constant", "the distorted point tested at the receiver's depth less bias (§4), not its tangent plane"), builder(with_constant_bias);
        /// The relative depth bias of the constant reading
        /// ([`constant_bias`](Ssoc::constant_bias)), `[0, 1]`; default
        /// [`Ssoc::DEFAULT_BIAS`] (ours).
        pub bias: f64 = Ssoc::DEFAULT_BIAS, option(real "bias", (0.0, 1.0), "relative depth bias of the constant test (§4; ours: 0.02)"), builder(with_bias);
        /// Four lookups blended bilinearly (§5); default off.
        pub bilinear: bool = false, option(flag "bilinear", "four lookups blended bilinearly (§5)"), builder(with_bilinear);
        /// The falloff of eq. 1; default [`Falloff::Bernstein`] (§3.2.2).
        pub falloff: Falloff = Falloff::Bernstein, option(choice "falloff", ["bernstein" = Falloff::Bernstein, "exact" = Falloff::Exact, "linear" = Falloff::Linear], "eq. 1's falloff (§3.2.2: bernstein)"), builder(with_falloff);
        /// The [horizon bound](Horizon); default off (ours).
        pub horizon: bool = false, option(flag "horizon", "V ≤ the light's share above the receiver's tangent plane (ours)"), builder(with_horizon);
    }
    name: "ssoc",
    summary: "the soft shadow occlusion camera (Mo, Popescu & Wyman 2007)",
    lights: &[LightKind::Sphere, LightKind::Disk],
    default_run: &["ssoc"],
    compare: &["ssoc", "ssoc:lookups=1", "ssoc:falloff=exact", "ssoc:bilinear", "ssoc:horizon"],
}

impl Ssoc {
    /// Default [`Ssoc::resolution`]: 1024 (ours; the paper's map size is
    /// not stated).
    pub const DEFAULT_RESOLUTION: u32 = 1024;
    /// Default [`Ssoc::bias`]: 2 % of the receiver's depth (ours).
    pub const DEFAULT_BIAS: f64 = 0.02;
}

/// What both variants build for a frame: the shadow map, the silhouette
/// edges, the distortion maps.
pub(crate) struct Prepared {
    pub maps: Arc<Result<FittedMaps, crate::render::raster::RasterError>>,
    pub edges: Arc<Vec<ProjectedEdge>>,
    pub distortion: Arc<DistortionMaps>,
    /// The light's radius.
    pub r: f64,
}

impl Prepared {
    /// The shadow map and its view.
    pub(crate) fn fitted(&self) -> Result<&FittedMaps, MethodError> {
        self.maps
            .as_ref()
            .as_ref()
            .map_err(|e| MethodError::LightView(*e))
    }
}

/// Builds (or fetches) the stages both variants read, at `resolution`.
pub(crate) fn prepare(
    input: &Input<'_, '_>,
    resolution: u32,
    selection: Selection,
) -> Result<Prepared, MethodError> {
    let (stages, frame) = (input.stages(), input.frame());
    let r = input.light().equivalent_radius();
    let maps = stages.light_maps(frame, resolution, resolution);
    let fitted = maps
        .as_ref()
        .as_ref()
        .map_err(|e| MethodError::LightView(*e))?;
    let view = &fitted.view;
    let edges = projected_edges(stages, selection, view.near());
    let lf = view.frame();
    let z_max = stages
        .fit_receivers(frame)
        .iter()
        .map(|&p| lf.to_light(p).z)
        .filter(|z| z.is_finite())
        .fold(0.0, f64::max);
    let key = format!("{} {resolution} {selection:?}", fit_key(frame));
    let distortion = stages.cached("ssoc distortion maps", key, || {
        let m = DistortionMaps::new(view, &edges, r, z_max);
        let (i, o) = m.coverage();
        (
            m,
            format!("{} edges, {i} inside and {o} outside texels", edges.len()),
        )
    });
    Ok(Prepared {
        maps,
        edges,
        distortion,
        r,
    })
}

/// One receiver in the light view.
pub(crate) struct Warped {
    /// Light-frame position.
    pub p: DVec3,
    /// Its projection on the image plane.
    pub u: DVec2,
    /// In front of the map's near plane.
    pub in_view: bool,
    /// The shadow map's hard test at `u`.
    pub shadowed: bool,
    /// The depth test the hard test used: the receiver's tangent plane
    /// (receiver-plane bias) with the margin of [`margin`].
    pub test: DepthTest,
}

/// The shadow-map test of `p` (light frame) at image point `u` with depth
/// test `test`; off the map: lit.
fn blocked_at(view: &LightView, maps: &LightMaps, test: &DepthTest, u: DVec2) -> bool {
    let Some((col, row)) = view.pixel_of(u) else {
        return false;
    };
    test.blocks(view, col, row, maps.depth_at(col, row))
}

/// Warps `r` into the light view of `fitted` and runs the hard test.
pub(crate) fn warp(fitted: &FittedMaps, r: &Receiver, margin: f64) -> Warped {
    let view = &fitted.view;
    let lf = view.frame();
    let p = lf.to_light(r.position);
    let [ax, ay, az] = lf.axes();
    let normal = r
        .normal
        .map(|n| DVec3::new(n.dot(ax), n.dot(ay), n.dot(az)));
    let in_view = p.z >= view.near() && p.z.is_finite();
    let u = project(p);
    let test = DepthTest::new(p, normal, p.z * margin);
    let shadowed = in_view && blocked_at(view, &fitted.maps, &test, u);
    Warped {
        p,
        u,
        in_view,
        shadowed,
        test,
    }
}

/// The depth-test margin of both variants, relative to the receiver's
/// depth: PCSS's `1e-3` plus one texel, capped as PCSS's is
/// ([`Pcss::MAX_BIAS_SHARE`](crate::method::Pcss::MAX_BIAS_SHARE)).
pub(crate) fn margin(view: &LightView) -> f64 {
    crate::method::centre::depth::margin(1.0, 1e-3, 1.0, view.texel_size().max_element())
}

/// An edge as a receiver reads it.
struct Reading {
    /// `d`, `dmax`.
    d: f64,
    dmax: f64,
    /// The outward normal.
    n: DVec2,
    /// The edge's point nearest the receiver's projection.
    s: DVec2,
    /// `[z_near, z_far]`.
    z: (f64, f64),
}

impl Ssoc {
    /// The distortion of the receiver at `u`, depth `z_p`, against edge
    /// `e`: `None` when the receiver is in front of the edge.
    fn read(
        &self,
        e: &ProjectedEdge,
        u: DVec2,
        z_p: f64,
        r: f64,
        fitted: &FittedMaps,
    ) -> Option<Reading> {
        let (s, t) = nearest_on(e.a, e.b, u);
        let z_near = 1.0 / ((1.0 - t) / e.la.z + t / e.lb.z);
        if z_p <= z_near {
            return None;
        }
        // The signed distance to the silhouette (negative on the
        // occluder's side, decided by the exact predicate): the distance
        // to the edge's segment, continuous along a chain of edges; and
        // the outward direction. Beside the edge (`s` inside it) that is
        // the edge's own right normal (away from the occluder, the paper's
        // stored "silhouette edge normal"), taken from `b − a` — not from
        // `u − s`, which for a receiver on the edge's line is rounding
        // noise. `b − a` is scaled to a largest component of 1 first, so
        // that its length never underflows. Beyond an end it is radial,
        // `±(u − s)/|u − s|`, so that the distorted point stays on the
        // region's outer boundary around a corner — unless `u` is within
        // rounding of the end itself, where the edge's normal serves.
        let inside = left(e.a, e.b, u);
        let sign = if inside { -1.0 } else { 1.0 };
        let v = u - s;
        let dist = v.length();
        let along = e.b - e.a;
        let beside = t > 0.0 && t < 1.0;
        let noise = 16.0 * f64::EPSILON * u.abs().max_element();
        let n = if !beside && dist > noise {
            v / dist * sign
        } else {
            let n = DVec2::new(along.y, -along.x) / along.abs().max_element();
            n.try_normalize()?
        };
        let delta = sign * dist;
        let radius = footprint::radius(r, z_near, z_p);
        // `2R` (§3.2.1), the doubling exact.
        let dmax = distortion::max_distortion(r, z_near, z_p);
        let d = (radius - delta).clamp(0.0, dmax);
        let view = &fitted.view;
        let outside = view.to_pixel(s + n * (1.5 * view.texel_size().max_element()));
        let z_far = if outside.x >= 0.0
            && outside.y >= 0.0
            && outside.x < f64::from(view.width())
            && outside.y < f64::from(view.height())
        {
            fitted.maps.depth_at(outside.x as u32, outside.y as u32)
        } else {
            f64::INFINITY
        };
        Some(Reading {
            d,
            dmax,
            n,
            s,
            z: (z_near, z_far),
        })
    }

    /// `V` of one receiver from the distortion-map texel `(col, row)`.
    fn shade_at(&self, prep: &Prepared, fitted: &FittedMaps, w: &Warped, texel: (i64, i64)) -> f64 {
        let hard = if w.shadowed { 0.0 } else { 1.0 };
        let edge = prep.distortion.at(w.shadowed, texel.0, texel.1);
        if edge == NONE {
            return hard;
        }
        // The distortion of the receiver by the map's edge `k`.
        let read = |k: u32| {
            prep.edges
                .get(k as usize)
                .and_then(|e| self.read(e, w.u, w.p.z, prep.r, fitted))
        };
        let Some(first) = read(edge) else {
            return hard;
        };
        let view = &fitted.view;
        // Fig. 5's test at the distorted point: the receiver's tangent
        // plane, as the first hard test (so that a steep receiver's own
        // surface, nearer the light at the distorted point, does not
        // shadow it), or the paper's constant bias.
        let test = if self.constant_bias {
            DepthTest::new(w.p, None, w.p.z * self.bias)
        } else {
            w.test
        };
        let mut v = 1.0;
        let mut seen = [edge; 8];
        let mut reading = first;
        let mut count = 1;
        loop {
            let moved = w.u + reading.n * reading.d;
            // Fig. 5, for the receiver's own edge: still in the hard
            // shadow after distortion, fully shadowed. (Against the later
            // edges the receiver is distorted only to find the next one:
            // another occluder's hard shadow there is that occluder's
            // part, already counted.)
            let blocked = blocked_at(view, &fitted.maps, &test, moved);
            if blocked && count == 1 {
                return 0.0;
            }
            // By construction the distorted point lies `R` outside the
            // edge, on its distortion region's outer boundary: Fig. 5's
            // "no longer near a discontinuity: lit", which the paper says
            // only its own rounding triggers, cannot arise here.
            let t = view.to_pixel(moved).floor();
            let (c, r) = (t.x as i64, t.y as i64);
            // The map of the distorted point's side names its edge.
            let next = [prep.distortion.at(blocked, c, r)];
            v *= distortion::intensity(reading.d, reading.dmax, self.falloff);
            if count >= self.lookups as usize {
                return v;
            }
            // The first edge the distorted point names that is not seen.
            let Some(other) = next
                .iter()
                .copied()
                .find(|&e| e != NONE && !seen[..count].contains(&e))
            else {
                return v;
            };
            let Some(second) = read(other) else {
                return v;
            };
            // The paper's three cases (§4): the same region, one relevant
            // penumbra (disjoint depth ranges), or several, whose
            // intensities multiply.
            let same_region = reading.n.dot(second.n) > SAME_REGION_COS
                || (reading.s - second.s).length() <= view.texel_size().max_element();
            let disjoint = second.z.0 > reading.z.1 || reading.z.0 > second.z.1;
            if same_region || disjoint {
                return v;
            }
            seen[count] = other;
            count += 1;
            reading = second;
        }
    }

    /// `V` of one receiver.
    fn shade(&self, prep: &Prepared, fitted: &FittedMaps, w: &Warped) -> f64 {
        if !w.in_view {
            return 1.0;
        }
        let t = fitted.view.to_pixel(w.u);
        if !self.bilinear {
            return self.shade_at(prep, fitted, w, (t.x.floor() as i64, t.y.floor() as i64));
        }
        // The four texels whose centres surround the point, bilinearly.
        let b = t - 0.5;
        let (c, r) = (b.x.floor(), b.y.floor());
        let (fx, fy) = (b.x - c, b.y - r);
        let (c, r) = (c as i64, r as i64);
        let at = |dc: i64, dr: i64| self.shade_at(prep, fitted, w, (c + dc, r + dr));
        let top = at(0, 0) * (1.0 - fx) + at(1, 0) * fx;
        let bottom = at(0, 1) * (1.0 - fx) + at(1, 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

/// Two edges whose outward normals are closer than this (the cosine of
/// 45°, ours) bound the same distortion region (§4's "dot product near
/// unity"); so do two edges whose points nearest the receiver are within a
/// texel (a shared corner of the silhouette, where the outward directions
/// are radial and may differ by up to 180°).
const SAME_REGION_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// What SSOC and its backprojected variant need: the shadow map and the
/// distortion maps built from the silhouettes.
const NEEDS: Needs = Needs::BVH
    .union(Needs::LIGHT_FRAME)
    .union(Needs::LIGHT_MAPS)
    .union(Needs::TOPOLOGY);

/// What both variants require of the receivers.
const REQUIRES: Requires = Requires {
    normals: true,
    objects: false,
    normals_hint: "the shadow-map test compares texels with the receiver's tangent plane",
};

/// The peak bytes a texel of SSOC's maps, rounded up
/// ([`Method::map_bytes`](super::Method::map_bytes)).
pub(super) const MAP_BYTES_PER_TEXEL: u64 = 21;

impl super::Method for Ssoc {
    from_options! {
        /// The shadow and distortion maps (measured 20.9 bytes a texel
        /// between `map=1024` and `map=4096`, `/usr/bin/time -f %M`).
        map_bytes_per_texel: MAP_BYTES_PER_TEXEL,
        needs: NEEDS,
    }

    fn requires(&self) -> Requires {
        REQUIRES
    }

    fn horizon(&self) -> Horizon {
        Horizon::clamp_if(self.horizon)
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        super::check_options(self)?;
        if input.receivers().is_empty() {
            return Ok(Output::default());
        }
        let prep = prepare(input, self.resolution, EdgeSource::Silhouettes.into())?;
        let fitted = prep.fitted()?;
        let m = margin(&fitted.view);
        let v = per_receiver(
            input,
            || (),
            |(), _, r| Ok(self.shade(&prep, fitted, &warp(fitted, r, m))),
        )?;
        Ok(Output::values(v))
    }
}
