//! Backprojected SSOC: the occlusion camera's maps as a search structure
//! for the silhouette edges a receiver backprojects (see the
//! [module docs](super)).

use super::maps::NONE;
use super::{margin, prepare, warp, Prepared};
use crate::kernel::footprint::f64 as footprint;
use crate::kernel::silhouette::MeshTopology;
use crate::method::centre::union::{self, MappedEdge};
use crate::method::centre::{horizon_edge, EdgeSource, ProjectedEdge, Selection, NO_EDGE};
use crate::method::options::{from_options, method_options};
use crate::method::{per_receiver, Horizon, Input, Method, MethodError, Output, Requires};
use crate::render::raster::MAX_RESOLUTION;
use crate::render::{FittedMaps, Receiver};
use crate::scene::{LightKind, Mesh};
use glam::DVec3;
use std::collections::HashMap;

method_options! {
    /// Backprojected soft shadows with an occlusion camera shadow map: see the
    /// [module docs](super). Sphere and disk lights; needs receiver normals.
    ///
    #[doc = crate::method::fitted_maps_doc!()]
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[non_exhaustive]
    pub struct BackprojectedSsoc {
        /// Side of the shadow and distortion maps, `1..=16384`; default 1024
        /// (ours, as [`Ssoc`](super::Ssoc)).
        pub resolution: u32 = super::Ssoc::DEFAULT_RESOLUTION, option(int "map", (1, MAX_RESOLUTION as u64), "side of the shadow and distortion maps (ours)"), builder(with_resolution);
        /// The neighbourhood searched for more edges, in texels around the
        /// receiver's: `(2·search + 1)²` texels, `0..=16`; default 1 (ours; the
        /// sketch gives no radius).
        pub search: u32 = 1, option(int "search", (0, 16), "texels around the receiver's searched for edges (ours: 1, 3×3)"), builder(with_search);
        /// Completes the edges found by walking the silhouette from them: each
        /// edge that meets the receiver's footprint adds the edges it shares an
        /// end with (ours: the sketch finds edges by the neighbourhood alone,
        /// which on a silhouette of many short edges misses most of those in a
        /// wide footprint); default off.
        pub walk: bool = false, option(flag "walk", "complete the edges found along the silhouette, within the footprint (ours)"), builder(with_walk);
        /// The [horizon bound](Horizon): the receiver's tangent plane as one
        /// more edge of the union; default off (ours).
        pub horizon: bool = false, option(flag "horizon", "the tangent plane as one more edge of the union (ours)"), builder(with_horizon);
        /// The maps hold the potential silhouettes of the light's bounding
        /// ball (every edge that is a silhouette from some light point) instead
        /// of the silhouettes from its centre, and each edge a receiver finds
        /// is oriented and weighted by its multiplicity seen from that receiver
        /// (the sketch: extra edges are harmless; an edge that is no silhouette
        /// from the receiver weighs 0); default off.
        pub potential: bool = false, option(flag "potential", "potential silhouettes of the light's ball, each weighed from the receiver"), builder(with_potential);
    }
    name: "backprojected-ssoc",
    summary: "backprojected soft shadows with an occlusion camera shadow map (Mo & Wyman 2007)",
    lights: &[LightKind::Sphere, LightKind::Disk],
    default_run: &["backprojected-ssoc"],
    compare: &["backprojected-ssoc", "backprojected-ssoc:search=0", "backprojected-ssoc:search=2",
        "backprojected-ssoc:walk", "backprojected-ssoc:walk,horizon",
        "backprojected-ssoc:potential", "backprojected-ssoc:walk,potential"],
}

impl BackprojectedSsoc {
    /// `V` of one receiver: the union of the edges found around it.
    fn shade(
        &self,
        pass: &Pass<'_>,
        r: &Receiver,
        found: &mut Vec<u32>,
        mapped: &mut Vec<MappedEdge>,
        scratch: &mut union::Scratch,
    ) -> f64 {
        let Pass {
            prep,
            fitted,
            chains,
            topology,
            meshes,
        } = *pass;
        let w = warp(fitted, r, margin(&fitted.view));
        if !w.in_view {
            return 1.0;
        }
        let t = fitted.view.to_pixel(w.u).floor();
        let (c, row) = (t.x as i64, t.y as i64);
        let k = i64::from(self.search);
        found.clear();
        for dr in -k..=k {
            for dc in -k..=k {
                for inside in [true, false] {
                    let e = prep.distortion.at(inside, c + dc, row + dr);
                    if e != NONE && !found.contains(&e) {
                        found.push(e);
                    }
                }
            }
        }
        let map = |e: u32| -> Option<MappedEdge> {
            let e: &ProjectedEdge = prep.edges.get(e as usize)?;
            let (flip, weight) = match (self.potential, e.edge) {
                (true, edge) if edge != NO_EDGE => {
                    let topo = topology.get(e.mesh as usize)?.as_ref()?;
                    let positions = meshes.get(e.mesh as usize)?.positions();
                    let seen = topo
                        .silhouette_edge_from_point(edge, positions, r.position)
                        .ok()??;
                    // Seen from a light point beyond the edge (the receiver
                    // on one side of each face's plane, the light point on
                    // the other), its faces lie on the other side: that
                    // orientation runs `to → from`, stored is `v0 → v1`.
                    let v1 = topo.edges()[edge as usize][1];
                    (seen.from != v1, e.weight * f64::from(seen.multiplicity))
                }
                _ => (false, e.weight),
            };
            let (a, b, la, lb) = if flip {
                (e.b, e.a, e.lb, e.la)
            } else {
                (e.a, e.b, e.la, e.lb)
            };
            let (a, b) = footprint::map_edge(a, b, la, lb, w.u, w.p.z, prep.r)?;
            Some(MappedEdge { a, b, weight })
        };
        if let (true, Some(chains)) = (self.walk, chains) {
            // Breadth first from the edges found, through every edge that
            // meets the footprint — whatever its multiplicity from the
            // receiver: with `potential`, the receiver's silhouette is a
            // loop inside a band of potential edges, and the edges a texel
            // names may all be of the band.
            let meets = |e: u32| {
                prep.edges.get(e as usize).is_some_and(|e| {
                    footprint::map_edge(e.a, e.b, e.la, e.lb, w.u, w.p.z, prep.r)
                        .is_some_and(|(a, b)| union::meets_disk(a, b))
                })
            };
            let mut k = 0;
            while k < found.len() {
                let e = found[k];
                k += 1;
                if meets(e) {
                    for &n in chains.neighbours(e) {
                        if !found.contains(&n) {
                            found.push(n);
                        }
                    }
                }
            }
        }
        // In index order, so that the union sees the same list whatever
        // the order the texels were read in.
        found.sort_unstable();
        mapped.clear();
        mapped.extend(found.iter().filter_map(|&e| map(e)));
        let mut centre = if w.shadowed { 1.0 } else { 0.0 };
        if self.horizon {
            if let Some(n) = r.normal {
                let [ax, ay, az] = fitted.view.frame().axes();
                let n = DVec3::new(n.dot(ax), n.dot(ay), n.dot(az));
                let h = horizon_edge(n, w.p, prep.r);
                centre += h.centre;
                mapped.extend(h.edge);
            }
        }
        if mapped.is_empty() {
            return if centre > 0.5 { 0.0 } else { 1.0 };
        }
        (1.0 - union::union_occlusion(centre, mapped, scratch)).clamp(0.0, 1.0)
    }
}

impl Method for BackprojectedSsoc {
    from_options! {
        /// The shadow and distortion maps, as [`Ssoc`](super::Ssoc)'s.
        map_bytes_per_texel: super::MAP_BYTES_PER_TEXEL,
        needs: super::NEEDS,
    }

    fn requires(&self) -> Requires {
        super::REQUIRES
    }

    fn horizon(&self) -> Horizon {
        if self.horizon {
            Horizon::Within
        } else {
            Horizon::Off
        }
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        crate::method::check_options(self)?;
        if input.receivers().is_empty() {
            return Ok(Output::default());
        }
        let selection = if self.potential {
            Selection::Potential
        } else {
            EdgeSource::Silhouettes.into()
        };
        let prep = prepare(input, self.resolution, selection)?;
        let fitted = prep.fitted()?;
        let chains = self.walk.then(|| {
            // The edges are those of `selection`, clipped at the view's
            // near depth.
            let key = format!("{selection:?} near {:x}", fitted.view.near().to_bits());
            input.stages().cached("ssoc silhouette chains", key, || {
                let c = Chains::new(&prep.edges);
                (c, format!("{} edges", prep.edges.len()))
            })
        });
        let pass = Pass {
            prep: &prep,
            fitted,
            chains: chains.as_deref(),
            topology: input.stages().topology(),
            meshes: input.stages().scene().meshes(),
        };
        let v = per_receiver(
            input,
            || (Vec::new(), Vec::new(), union::Scratch::default()),
            |(found, mapped, scratch), _, r| Ok(self.shade(&pass, r, found, mapped, scratch)),
        )?;
        Ok(Output::values(v))
    }
}

/// What every receiver of a frame reads.
#[derive(Clone, Copy)]
struct Pass<'a> {
    prep: &'a Prepared,
    fitted: &'a FittedMaps,
    /// The silhouette chains, with `walk`.
    chains: Option<&'a Chains>,
    /// Each mesh's topology and mesh, for `potential`'s multiplicities.
    topology: &'a [Option<MeshTopology>],
    meshes: &'a [Mesh],
}

/// Which silhouette edges share an end: the edges of `edges` whose world
/// ends coincide bit for bit.
pub(crate) struct Chains {
    /// Per edge, the range of its neighbours in `list`.
    start: Vec<u32>,
    list: Vec<u32>,
}

impl Chains {
    fn new(edges: &[ProjectedEdge]) -> Chains {
        let key = |v: DVec3| (v + DVec3::ZERO).to_array().map(f64::to_bits);
        let mut at: HashMap<[u64; 3], Vec<u32>> = HashMap::new();
        for (i, e) in edges.iter().enumerate() {
            at.entry(key(e.wa)).or_default().push(i as u32);
            at.entry(key(e.wb)).or_default().push(i as u32);
        }
        let mut start = Vec::with_capacity(edges.len() + 1);
        let mut list = Vec::new();
        for (i, e) in edges.iter().enumerate() {
            start.push(list.len() as u32);
            for end in [e.wa, e.wb] {
                for &n in &at[&key(end)] {
                    if n != i as u32 && !list[start[i] as usize..].contains(&n) {
                        list.push(n);
                    }
                }
            }
        }
        start.push(list.len() as u32);
        Chains { start, list }
    }

    fn neighbours(&self, e: u32) -> &[u32] {
        let e = e as usize;
        match (self.start.get(e), self.start.get(e + 1)) {
            (Some(&a), Some(&b)) => &self.list[a as usize..b as usize],
            _ => &[],
        }
    }
}
