//! What the methods that project from the light's centre share (SISM, and
//! the single-sample and SSOC methods to come): the occluders' silhouette
//! edges from the centre, projected onto the light image plane, clipped in
//! front of the light and oriented, as a stage ([`projected_edges`]); the
//! layer weights that keep a closed solid from counting twice
//! ([`layer_weights`]); the tie rule every side decision on the image plane
//! uses ([`left`]); and the exact union of the occluders inside a
//! receiver's footprint ([`union`]).
//!
//! Everything here is in the light frame of
//! [`Stages::light_frame`](crate::render::Stages::light_frame): a point at
//! light-frame `(x, y, z)` projects to `(x/z, y/z)` on the image plane
//! `z = 1`.

pub(crate) mod depth;
pub(crate) mod union;

use crate::kernel::footprint::f64::{clip_near, project};
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use crate::kernel::silhouette::MeshTopology;
use crate::render::Stages;
use glam::{DVec2, DVec3};
use std::sync::Arc;
use union::MappedEdge;

/// Which edges a centre-projection method draws its penumbrae from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EdgeSource {
    /// The silhouette edges seen from the light's centre, each with its
    /// multiplicity (SISM §2.1: "silhouettes improve performance").
    Silhouettes,
    /// Every edge of every triangle, oriented by its triangle's facing
    /// (SISM §2.1's fallback "in the absence of adjacency information we
    /// assume all edges are silhouettes"): an interior edge appears twice,
    /// in opposite directions, and its two terms cancel.
    AllEdges,
}

/// Which edges [`projected_edges`] builds: those of an [`EdgeSource`], or
/// every edge that may be a silhouette from some point of the light's
/// bounding ball (`MeshTopology::potential_silhouettes`; backprojected
/// SSOC's `potential`). A potential edge is stored from its topology's
/// `v0` to `v1` (before the frame's handedness swap), with its layer weight
/// alone: which way round it runs, and its multiplicity, depend on the
/// point it is seen from, and are the caller's to recompute per receiver.
/// A mesh without a topology gives its triangles' sides, as
/// [`EdgeSource::AllEdges`] does (with [`NO_EDGE`]: nothing to recompute).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Selection {
    /// The edges of an [`EdgeSource`].
    Source(EdgeSource),
    /// The potential silhouettes of the light's ball.
    Potential,
}

impl From<EdgeSource> for Selection {
    fn from(source: EdgeSource) -> Selection {
        Selection::Source(source)
    }
}

/// A silhouette edge seen from the light's centre, clipped to the part in
/// front of the near depth and projected, oriented with the occluder on
/// its **left** on the image plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedEdge {
    /// The projected endpoints.
    pub a: DVec2,
    /// See [`ProjectedEdge::a`].
    pub b: DVec2,
    /// The light-frame endpoints the projections come from (after the near
    /// clip).
    pub la: DVec3,
    /// See [`ProjectedEdge::la`].
    pub lb: DVec3,
    /// The world endpoints of the whole edge, as oriented.
    pub wa: DVec3,
    /// See [`ProjectedEdge::wa`].
    pub wb: DVec3,
    /// The least light-frame depth of the clipped edge.
    pub z_min: f64,
    /// How many layers the count rises by from the edge's right to its
    /// left: the silhouette's multiplicity times its component's layer
    /// weight ([`layer_weights`]).
    pub weight: f64,
    /// The mesh the edge belongs to.
    pub mesh: u32,
    /// Its index in the mesh's topology, [`NO_EDGE`] for an edge of
    /// [`EdgeSource::AllEdges`] (a triangle's side).
    pub edge: u32,
}

/// [`ProjectedEdge::edge`] of an edge that is not one of the topology's.
pub const NO_EDGE: u32 = u32::MAX;

/// The point of segment `[a, b]` nearest `p`, and its parameter.
pub(crate) fn nearest_on(a: DVec2, b: DVec2, p: DVec2) -> (DVec2, f64) {
    let d = b - a;
    let dd = d.length_squared();
    let t = if dd > 0.0 {
        ((p - a).dot(d) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * t, t)
}

/// `true` when `s` is on the left of `a → b`, ties (`s` on the line) broken
/// by the edge's direction so that the two directions of an edge disagree:
/// a point on an edge shared by two triangles is inside exactly one.
#[must_use]
#[inline]
pub(crate) fn left(a: DVec2, b: DVec2, s: DVec2) -> bool {
    match orient2d(a, b, s) {
        Sign::Positive => true,
        Sign::Negative => false,
        Sign::Zero => (b.y, b.x) < (a.y, a.x),
    }
}

/// Per mesh, the layer weight `ω` of each face and each edge of its
/// topology: `½` in a closed connected component (every edge with an even
/// number of faces), whose every ray from the light crosses twice per
/// layer, `1` in an open one. Components are found on the topology stage's
/// welded vertices, so a closed solid stored as a triangle soup is still
/// closed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LayerWeights {
    /// Per face of the mesh.
    pub faces: Vec<f64>,
    /// Per edge of the mesh's topology.
    pub edges: Vec<f64>,
}

/// The [`LayerWeights`] of every mesh of the scene (stage `layer weights`,
/// built once per scene).
pub(crate) fn layer_weights(stages: &Stages) -> Arc<Vec<LayerWeights>> {
    stages.cached("layer weights", String::new(), || {
        let weights: Vec<LayerWeights> = stages
            .scene()
            .meshes()
            .iter()
            .zip(stages.topology())
            .map(|(mesh, topo)| match topo {
                Some(t) => component_weights(t),
                None => LayerWeights {
                    faces: vec![1.0; mesh.triangles().len()],
                    edges: Vec::new(),
                },
            })
            .collect();
        let detail = format!("{} meshes", weights.len());
        (weights, detail)
    })
}

fn component_weights(topo: &MeshTopology) -> LayerWeights {
    let faces = topo.triangles().len();
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    let edges = topo.edges().len();
    for e in 0..edges {
        let mut it = topo.edge_faces(e);
        if let Some(f0) = it.next() {
            for f in it {
                let (a, b) = (find(&mut parent, f0.face), find(&mut parent, f.face));
                if a != b {
                    parent[a as usize] = b;
                }
            }
        }
    }
    let mut open = vec![false; faces];
    let mut edge_root = vec![u32::MAX; edges];
    for (e, root) in edge_root.iter_mut().enumerate() {
        let odd = topo.edge_faces(e).len() % 2 == 1;
        if let Some(f) = topo.edge_faces(e).next() {
            let r = find(&mut parent, f.face);
            *root = r;
            if odd {
                open[r as usize] = true;
            }
        }
    }
    let weight = |open: bool| if open { 1.0 } else { 0.5 };
    LayerWeights {
        faces: (0..faces as u32)
            .map(|f| weight(open[find(&mut parent, f) as usize]))
            .collect(),
        edges: edge_root
            .iter()
            .map(|&r| {
                if r == u32::MAX {
                    1.0
                } else {
                    weight(open[r as usize])
                }
            })
            .collect(),
    }
}

/// The edges `source` gives from the light's centre, clipped at light-frame
/// depth `near` and projected (stage `projected edges`, built once per
/// source and near depth). Edges wholly behind `near`, and edges whose
/// projection is a point or not finite, are left out.
pub(crate) fn projected_edges(
    stages: &Stages,
    source: Selection,
    near: f64,
) -> Arc<Vec<ProjectedEdge>> {
    let key = format!("{source:?} near {:x}", near.to_bits());
    stages.cached("projected edges", key, || {
        let edges = build_edges(stages, source, near);
        let detail = format!("{source:?}: {} edges", edges.len());
        (edges, detail)
    })
}

fn build_edges(stages: &Stages, source: Selection, near: f64) -> Vec<ProjectedEdge> {
    let scene = stages.scene();
    let light_frame = stages.light_frame();
    let center = scene.light().center();
    let ball = scene.light().bounding_radius();
    let topology = stages.topology();
    let weights = layer_weights(stages);
    // Which way round the light frame's image plane is seen: an edge with
    // the occluder on its left as seen from the centre keeps it on the left
    // once projected exactly when the frame is right-handed as seen from
    // the light.
    let cover_left = orient3d(
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
        DVec3::ZERO,
    ) == Sign::Negative;
    let mut edges = Vec::new();
    let mut sil = Vec::new();
    let mut potential = Vec::new();
    for (mesh_index, mesh) in scene.meshes().iter().enumerate() {
        let pos = mesh.positions();
        let lf: Vec<DVec3> = pos.iter().map(|&p| light_frame.to_light(p)).collect();
        let topo = topology.get(mesh_index).and_then(Option::as_ref);
        let w = &weights[mesh_index];
        let mut push = |from: u32, to: u32, edge: u32, weight: f64| {
            let (from, to) = if cover_left { (from, to) } else { (to, from) };
            let Some((la, lb)) = clip_near(lf[from as usize], lf[to as usize], near) else {
                return;
            };
            let (a, b) = (project(la), project(lb));
            if a == b || !a.is_finite() || !b.is_finite() {
                return;
            }
            edges.push(ProjectedEdge {
                a,
                b,
                la,
                lb,
                wa: pos[from as usize],
                wb: pos[to as usize],
                z_min: la.z.min(lb.z),
                weight,
                mesh: mesh_index as u32,
                edge,
            });
        };
        match (source, topo) {
            (Selection::Potential, Some(topo)) => {
                potential.clear();
                if topo
                    .potential_silhouettes_into(pos, center, ball, &mut potential)
                    .is_ok()
                {
                    for &e in &potential {
                        let [v0, v1] = topo.edges()[e as usize];
                        let weight = w.edges.get(e as usize).copied().unwrap_or(1.0);
                        push(v0, v1, e, weight);
                    }
                }
            }
            (Selection::Source(EdgeSource::Silhouettes), Some(topo)) => {
                sil.clear();
                if topo
                    .silhouettes_from_point_into(pos, center, &mut sil)
                    .is_ok()
                {
                    for e in &sil {
                        let weight = w.edges.get(e.edge as usize).copied().unwrap_or(1.0);
                        push(e.from, e.to, e.edge, weight * f64::from(e.multiplicity));
                    }
                }
            }
            _ => {
                for (f, t) in mesh.triangles().iter().enumerate() {
                    if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                        continue;
                    }
                    let [a, b, c] = t.map(|i| pos[i as usize]);
                    let front = orient3d(a, b, c, center) == Sign::Negative;
                    let weight = w.faces[f];
                    for k in 0..3 {
                        let (u, v) = (t[k], t[(k + 1) % 3]);
                        if front {
                            push(u, v, NO_EDGE, weight);
                        } else {
                            push(v, u, NO_EDGE, weight);
                        }
                    }
                }
            }
        }
    }
    edges
}

/// A receiver's tangent plane as the exact union sees it: the light points
/// below the plane are hidden by the receiver's own surface (the `horizon`
/// option), a half-plane of the unit footprint.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct HorizonEdge {
    /// Layers the plane adds at the footprint's centre (1 when the light's
    /// centre is below the plane, else 0).
    pub centre: f64,
    /// The plane's trace across the unit footprint, covered side on the
    /// left, weight 1; `None` when the plane misses the footprint (it then
    /// covers all of it or none, as `centre` says).
    pub edge: Option<MappedEdge>,
}

/// The tangent plane of a receiver at light-frame `p` with light-frame
/// normal `n` (pointing to the side it sees), in the unit footprint of a
/// light of radius `r` in the light frame's `z = 0` plane: the light point
/// `r u` is hidden when `n·(r u − p) < 0`, i.e. `g·u < c` with `g = r n_xy`
/// and `c = n·p`.
#[must_use]
pub(crate) fn horizon_edge(n: DVec3, p: DVec3, r: f64) -> HorizonEdge {
    let g = DVec2::new(n.x, n.y) * r;
    let c = n.dot(p);
    let len = g.length();
    let covered_centre = if c > 0.0 { 1.0 } else { 0.0 };
    // The signed distance of the trace from the centre, in footprint radii.
    let d = c / len;
    if !(d.is_finite() && d.abs() < 1.0) {
        // Parallel to the light, or the trace outside the footprint: all
        // of it or none is below the plane, as its centre is.
        return HorizonEdge {
            centre: covered_centre,
            edge: None,
        };
    }
    // Direction along the trace with the covered side (`g·u < c`) on its
    // left; the ends 2 radii from the trace's nearest point, outside the
    // unit disk.
    let t = g.perp() / len;
    let foot = g * (d / len);
    HorizonEdge {
        centre: covered_centre,
        edge: Some(MappedEdge {
            a: foot - t * 2.0,
            b: foot + t * 2.0,
            weight: 1.0,
        }),
    }
}
