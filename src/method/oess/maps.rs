//! OESS's endpoint maps (Reimann & Dreier, steps 1–3): the shadow maps of
//! the segment light's two ends, their metadata, the occluding edges found
//! in them, and the outreach that hands each edge to the penumbra texels
//! beside it.
//!
//! Both maps look along the same axes — `x` along the segment, `z` toward
//! the receivers — over the same window and resolution, from `L` and from `R =
//! L + ℓx`. A point at `L`-frame `(x, y, z)` is at `(x − ℓ, y, z)` from `R`:
//! its depth is the same in both, `v = y/z` too, so a map row is a plane
//! through the light's line and the corresponding texel of `(col, row)` in
//! the other map is on the same row, `ℓ/(z·s_x)` columns over (`s_x` the
//! texel width). The metadata of a texel — its corresponding column and
//! its tilt (whether the other end sees the same side of its triangle,
//! from the signs of `orient3d` of the triangle with `L` and with `R`, so
//! two-sided occluders work) — is computed where it is read.
//!
//! In `L`'s map the penumbra of an occluder lies on its `L` side (toward
//! smaller columns): those texels are seen by `L` and hidden from `R`. An
//! *occluding edge* is a texel that the other end sees (its terminator
//! from there), found by either strategy of §3.2, combined by OR (ours):
//! - **tilt**: the texel's surface faces the other end, its neighbour on
//!   the penumbra side does not;
//! - **corresponding pixels**: the corresponding column runs backward
//!   between the neighbour on the penumbra side and the texel (a depth
//!   step: the texel is nearer), and forward again after it.
//!
//! **Outreach** (§3.3): from each edge, along the row toward the penumbra,
//! every texel hidden from the other end takes the edge, until one is seen
//! again; a texel reached by several edges keeps the nearest. `R`'s map is
//! the mirror image.

use crate::bvh::Occluders;
use crate::kernel::predicate::{orient3d, Sign};
use crate::render::raster::{rasterize_occluders, LightMaps, LightView, RasterError};
use crate::render::Frame;
use crate::scene::light::Segment;
use crate::scene::LightFrame;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// No occluding edge reaches the texel.
pub(crate) const NONE: u32 = u32::MAX;

/// One end's map and what was found in it.
#[derive(Clone, Debug)]
pub(crate) struct EndMap {
    pub view: LightView,
    pub maps: LightMaps,
    /// Every occluder triangle's plane in this end's frame.
    pub planes: Vec<Plane>,
    /// Per texel, the column of the occluding edge its outreach came from
    /// (same row), or [`NONE`].
    pub edge: Vec<u32>,
    /// Per texel, the nearest occluding edge on the occluder's side in its
    /// row (the texel's column or beyond, toward the other end), or
    /// [`NONE`]: where a receiver seen by this end only was reached by no
    /// outreach (ours).
    pub beyond: Vec<u32>,
    /// Texels found as occluding edges, by strategy (tilt, corresponding).
    pub found: (usize, usize),
}

/// Both ends' maps.
#[derive(Clone, Debug)]
pub(crate) struct EndpointMaps {
    pub l: EndMap,
    pub r: EndMap,
}

/// Which strategies find the edges.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Strategies {
    pub tilt: bool,
    pub corresponding: bool,
    /// Relative depth margin of the "hidden from the other end" test.
    pub bias: f64,
}

/// The light frames at both ends: `x` along the segment, `z` along the
/// mean of the directions from the light's line to `receivers` (each made
/// orthogonal to the segment and unit), so that as many receivers as can
/// be are in front of both ends. A segment of any length has them: its
/// direction is found from `b − a` scaled to a largest component of 1
/// (normalising `b − a` itself fails below a length of about 1e-154,
/// where its squared length underflows).
pub(crate) fn frames(light: &Segment, receivers: &[DVec3]) -> Option<(LightFrame, LightFrame)> {
    let (a, b) = (light.a(), light.b());
    let d = b - a;
    let x = (d / d.abs().max_element()).try_normalize()?;
    let mid = a.midpoint(b);
    let across = |p: DVec3| {
        let d = p - mid;
        (d - x * d.dot(x)).normalize_or_zero()
    };
    let mean: DVec3 = receivers.iter().map(|&p| across(p)).sum();
    let z = mean.try_normalize().or_else(|| {
        // No receiver off the light's line, or their directions cancel:
        // any direction across it.
        let (u, _) = x.any_orthonormal_pair();
        Some(u)
    })?;
    let l = LightFrame::with_x_axis(a, z, x).ok()?;
    let r = LightFrame::with_x_axis(b, z, x).ok()?;
    Some((l, r))
}

impl EndpointMaps {
    /// The maps of `occluders` from the ends of `light`, `side × side`,
    /// over the window that holds every receiver of `frame` and every
    /// occluder vertex seen from either end.
    pub(crate) fn new(
        light: &Segment,
        frames: (LightFrame, LightFrame),
        occluders: &Occluders,
        frame: &Frame,
        side: u32,
        strategies: Strategies,
    ) -> Result<EndpointMaps, RasterError> {
        let points: Vec<DVec3> = frame
            .receivers()
            .iter()
            .map(|r| r.position)
            .chain(occluders.triangles().iter().flatten().copied())
            .collect();
        // The near depth, as the shared light maps choose it.
        let depths = points
            .iter()
            .map(|&p| frames.0.to_light(p).z)
            .filter(|z| z.is_finite() && *z > 0.0);
        let (lo, hi) = depths.fold((f64::INFINITY, 0.0f64), |(lo, hi), z| {
            (lo.min(z), hi.max(z))
        });
        let near = if hi == 0.0 {
            1.0
        } else {
            (lo * 0.5).max(hi * (1.0 / 1_048_576.0))
        };
        let fit_l = LightView::fit(frames.0, points.iter().copied(), side, side, near)?;
        let fit_r = LightView::fit(frames.1, points.iter().copied(), side, side, near)?;
        let (lo, hi) = (fit_l.lo().min(fit_r.lo()), fit_l.hi().max(fit_r.hi()));
        let view_l = LightView::new(frames.0, lo, hi, side, side, near)?;
        let view_r = LightView::new(frames.1, lo, hi, side, side, near)?;
        let (maps_l, maps_r) = rayon::join(
            || rasterize_occluders(&view_l, occluders),
            || rasterize_occluders(&view_r, occluders),
        );
        let length = (light.b() - light.a()).length();
        let (a, b) = (light.a(), light.b());
        let triangles = occluders.triangles();
        // Whether both ends see the same side of each triangle (exact).
        let facing: Vec<bool> = triangles
            .par_iter()
            .map(|t| {
                let (sa, sb) = (orient3d(t[0], t[1], t[2], a), orient3d(t[0], t[1], t[2], b));
                sa == sb && sa != Sign::Zero
            })
            .collect();
        let (planes_l, planes_r) = rayon::join(
            || planes(&frames.0, triangles),
            || planes(&frames.1, triangles),
        );
        let find = |this: Sampled<'_>, other: Sampled<'_>, dir: i64| {
            Finder {
                this,
                other,
                facing: &facing,
                // From L the other end is at +ℓ along x; from R at −ℓ.
                shift: if dir < 0 { length } else { -length },
                dir,
                strategies,
            }
            .edges()
        };
        let l = Sampled {
            view: &view_l,
            maps: &maps_l,
            planes: &planes_l,
        };
        let r = Sampled {
            view: &view_r,
            maps: &maps_r,
            planes: &planes_r,
        };
        let (found_l, found_r) = rayon::join(|| find(l, r, -1), || find(r, l, 1));
        Ok(EndpointMaps {
            l: EndMap {
                view: view_l,
                maps: maps_l,
                planes: planes_l,
                edge: found_l.edge,
                beyond: found_l.beyond,
                found: found_l.counts,
            },
            r: EndMap {
                view: view_r,
                maps: maps_r,
                planes: planes_r,
                edge: found_r.edge,
                beyond: found_r.beyond,
                found: found_r.counts,
            },
        })
    }
}

/// A triangle's plane in a light frame: the points `p` with `n·p = d`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plane {
    n: DVec3,
    d: f64,
}

/// The planes of `triangles` in `frame`.
fn planes(frame: &LightFrame, triangles: &[[DVec3; 3]]) -> Vec<Plane> {
    triangles
        .par_iter()
        .map(|t| {
            let (n, a) = crate::render::raster::plane_of(&t.map(|p| frame.to_light(p)));
            Plane { n, d: n.dot(a) }
        })
        .collect()
}

/// One end's map as the edge search reads it.
#[derive(Clone, Copy)]
struct Sampled<'a> {
    view: &'a LightView,
    maps: &'a LightMaps,
    planes: &'a [Plane],
}

impl Sampled<'_> {
    /// The depth, along the ray through image point `u`, of the plane of
    /// the triangle the map sees at texel `(col, row)`: the surface's
    /// depth there, free of the texel's sampling (the texel's own depth
    /// where the plane is edge-on); infinite where the texel sees nothing.
    fn surface_depth(&self, col: u32, row: u32, u: DVec2) -> f64 {
        if !self.maps.is_covered(col, row) {
            return f64::INFINITY;
        }
        let texel = self.maps.depth_at(col, row);
        let Some(p) = self.planes.get(self.maps.triangle_at(col, row) as usize) else {
            return texel;
        };
        // The ray is `z·(u, 1)`; it meets the plane at `z = d / n·(u, 1)`.
        let z = p.d / p.n.dot(u.extend(1.0));
        if z.is_finite() && z > 0.0 {
            z
        } else {
            texel
        }
    }
}

/// The search of one end's map.
struct Finder<'a> {
    this: Sampled<'a>,
    other: Sampled<'a>,
    /// Per triangle, whether both ends see the same side of it.
    facing: &'a [bool],
    /// The other end's offset along x from this one's (±ℓ).
    shift: f64,
    /// The penumbra's direction along a row: −1 for `L`'s map, +1 for `R`'s.
    dir: i64,
    strategies: Strategies,
}

/// One row's texels as the search reads them.
#[derive(Clone, Copy, Default)]
struct Texel {
    /// The texel's surface point in the other map: its image point and
    /// its continuous column; `None` where the texel sees nothing.
    other: Option<(DVec2, f64)>,
    /// Whether the other end sees the side of the texel's triangle this
    /// end sees; `None` where the texel sees nothing.
    faces_other: Option<bool>,
    /// The texel's depth.
    depth: f64,
}

impl Finder<'_> {
    /// Texel `(col, row)` as the search reads it.
    fn texel(&self, col: u32, row: u32) -> Texel {
        let maps = self.this.maps;
        if !maps.is_covered(col, row) {
            return Texel::default();
        }
        let z = maps.depth_at(col, row);
        let u = self.this.view.pixel_center(col, row);
        // From the other end the point is `shift` further along −x.
        let other = DVec2::new(u.x - self.shift / z, u.y);
        let column = self.other.view.to_pixel(other).x;
        Texel {
            other: Some((other, column)),
            faces_other: self
                .facing
                .get(maps.triangle_at(col, row) as usize)
                .copied(),
            depth: z,
        }
    }

    /// Whether a texel's surface point is hidden from the other end: its
    /// triangle faces away from the other end, or the other map, at its
    /// corresponding texel, sees something nearer by more than the margin.
    /// Off the other map: not hidden.
    ///
    /// The facing test comes first: near an occluder's rim the surface
    /// turned away from the other end is within the depth margin of the
    /// rim the other map sees, and only the facing test tells it hidden.
    fn hidden(&self, t: &Texel, row: u32) -> bool {
        if t.faces_other == Some(false) {
            return true;
        }
        let Some((u, c)) = t.other else {
            return false;
        };
        if !(c >= 0.0 && c < f64::from(self.other.view.width())) {
            return false;
        }
        self.other.surface_depth(c as u32, row, u) < t.depth * (1.0 - self.strategies.bias)
    }

    /// Whether the texel at `c` of a row (`texels`) is an occluding edge,
    /// by tilt and by corresponding pixels.
    fn is_edge(&self, texels: &[Texel], c: usize) -> (bool, bool) {
        let w = texels.len() as i64;
        let (ahead, behind) = (c as i64 + self.dir, c as i64 - self.dir);
        if ahead < 0 || ahead >= w {
            return (false, false);
        }
        let (this, ahead) = (&texels[c], &texels[ahead as usize]);
        let tilt = self.strategies.tilt
            && this.faces_other == Some(true)
            && ahead.faces_other == Some(false);
        let corresponding = self.strategies.corresponding
            && behind >= 0
            && behind < w
            && match (ahead.other, this.other, texels[behind as usize].other) {
                (Some((_, qa)), Some((_, q)), Some((_, qb))) => {
                    // Backward from the penumbra side into the texel (a
                    // depth step toward the light), forward after it.
                    let s = -(self.dir as f64);
                    s * (qa - q) > 0.0 && s * (qb - q) >= 0.0
                }
                _ => false,
            };
        (tilt, corresponding)
    }

    /// The outreach of every row: per texel the edge column, the nearest
    /// edge beyond, and how many edges each strategy found.
    fn edges(&self) -> Found {
        let (w, h) = (self.this.view.width(), self.this.view.height());
        let rows: Vec<Found> = (0..h)
            .into_par_iter()
            .map(|row| {
                let texels: Vec<Texel> = (0..w).map(|c| self.texel(c, row)).collect();
                let mut edge = vec![NONE; w as usize];
                let mut beyond = vec![NONE; w as usize];
                let (mut by_tilt, mut by_corr) = (0, 0);
                // Edges nearest the penumbra first, so that a texel keeps the
                // nearest edge: for L (penumbra toward smaller columns) in
                // increasing order, for R in decreasing order.
                let order: Box<dyn Iterator<Item = u32>> = if self.dir < 0 {
                    Box::new(0..w)
                } else {
                    Box::new((0..w).rev())
                };
                let mut found = Vec::new();
                for c in order {
                    let (t, k) = self.is_edge(&texels, c as usize);
                    by_tilt += usize::from(t);
                    by_corr += usize::from(k);
                    if !(t || k) {
                        continue;
                    }
                    found.push(c);
                    let mut k = i64::from(c) + self.dir;
                    while k >= 0 && k < i64::from(w) {
                        let kk = k as usize;
                        let t = &texels[kk];
                        if t.other.is_none() || !self.hidden(t, row) {
                            break;
                        }
                        if edge[kk] == NONE {
                            edge[kk] = c;
                        }
                        k += self.dir;
                    }
                }
                // The nearest edge on the occluder's side: walking from
                // the penumbra's side, each texel takes the next edge.
                let mut next = found.iter().copied().peekable();
                let toward: Box<dyn Iterator<Item = u32>> = if self.dir < 0 {
                    Box::new(0..w)
                } else {
                    Box::new((0..w).rev())
                };
                for c in toward {
                    while next
                        .peek()
                        .is_some_and(|&e| (i64::from(e) - i64::from(c)) * self.dir > 0)
                    {
                        next.next();
                    }
                    beyond[c as usize] = next.peek().copied().unwrap_or(NONE);
                }
                Found {
                    edge,
                    beyond,
                    counts: (by_tilt, by_corr),
                }
            })
            .collect();
        let mut all = Found {
            edge: Vec::with_capacity((w * h) as usize),
            beyond: Vec::with_capacity((w * h) as usize),
            counts: (0, 0),
        };
        for r in rows {
            all.edge.extend(r.edge);
            all.beyond.extend(r.beyond);
            all.counts.0 += r.counts.0;
            all.counts.1 += r.counts.1;
        }
        all
    }
}

/// What [`Finder::edges`] found in one map (or one row of it).
struct Found {
    edge: Vec<u32>,
    beyond: Vec<u32>,
    counts: (usize, usize),
}

impl EndMap {
    /// [`Sampled::surface_depth`] in this map.
    pub(crate) fn surface_depth(&self, col: u32, row: u32, u: DVec2) -> f64 {
        Sampled {
            view: &self.view,
            maps: &self.maps,
            planes: &self.planes,
        }
        .surface_depth(col, row, u)
    }

    /// The world point of the occluding edge texel `(col, row)`: its
    /// centre's ray at the map's depth there.
    pub(crate) fn edge_point(&self, col: u32, row: u32) -> Option<DVec3> {
        if !self.maps.is_covered(col, row) {
            return None;
        }
        let z = self.maps.depth_at(col, row);
        let u = self.view.pixel_center(col, row);
        let p = self.view.frame().to_world(DVec3::new(u.x * z, u.y * z, z));
        p.is_finite().then_some(p)
    }

    /// The edge column reaching texel `(col, row)`, if any.
    pub(crate) fn edge_at(&self, col: i64, row: i64) -> Option<u32> {
        self.read(&self.edge, col, row)
    }

    /// The nearest edge column on the occluder's side of texel `(col,
    /// row)`, if any.
    pub(crate) fn beyond_at(&self, col: i64, row: i64) -> Option<u32> {
        self.read(&self.beyond, col, row)
    }

    fn read(&self, columns: &[u32], col: i64, row: i64) -> Option<u32> {
        let (w, h) = (i64::from(self.view.width()), i64::from(self.view.height()));
        if col < 0 || row < 0 || col >= w || row >= h {
            return None;
        }
        let e = columns[(row * w + col) as usize];
        (e != NONE).then_some(e)
    }
}
