//! The stages methods draw on — BVH, mesh topology, light frame, light maps,
//! and whatever a method builds for itself — built lazily, once, and timed
//! into [`Stats`].

use super::frame::{Fit, Frame};
use super::raster::{rasterize_occluders, LightMaps, LightView, RasterError};
use crate::bvh::{Bvh, Occluders};
use crate::kernel::silhouette::MeshTopology;
use crate::scene::{LightFrame, Scene};
use glam::DVec3;
use std::any::{Any, TypeId};
use std::collections::HashMap;
use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

/// What a method needs built before it runs (a method may also build more
/// for itself, lazily; these are the shared stages). Combine with `|`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Needs(u32);

impl Needs {
    /// Nothing shared.
    pub const NONE: Needs = Needs(0);
    /// The BVH over every triangle ([`Stages::bvh`]).
    pub const BVH: Needs = Needs(1);
    /// Per-mesh edge topology ([`Stages::topology`]), for silhouettes.
    pub const TOPOLOGY: Needs = Needs(2);
    /// The [light frame](crate::definitions#light-frame) ([`Stages::light_frame`]).
    pub const LIGHT_FRAME: Needs = Needs(4);
    /// A light-view depth/object map fitted to the frame's receivers and the
    /// occluders ([`Stages::light_maps`]); the resolution is the method's.
    pub const LIGHT_MAPS: Needs = Needs(8);
    /// Each receiver's view of the light ([`Emitter`](crate::scene::Emitter)),
    /// computed once by [`method::run`](crate::method::run) and handed to
    /// the method ([`Input::emitters`](crate::method::Input::emitters)).
    pub const EMITTERS: Needs = Needs(16);

    /// The stages of `self` and of `other` (`self | other`, usable in
    /// constants).
    #[must_use]
    pub const fn union(self, other: Needs) -> Needs {
        Needs(self.0 | other.0)
    }

    /// Whether every stage of `other` is in `self`.
    #[must_use]
    pub fn contains(self, other: Needs) -> bool {
        self.0 & other.0 == other.0
    }

    /// The names of the stages, for printing.
    #[must_use]
    pub fn names(self) -> Vec<&'static str> {
        [
            (Needs::BVH, "bvh"),
            (Needs::TOPOLOGY, "topology"),
            (Needs::LIGHT_FRAME, "light frame"),
            (Needs::LIGHT_MAPS, "light maps"),
            (Needs::EMITTERS, "emitters"),
        ]
        .into_iter()
        .filter(|&(n, _)| self.contains(n))
        .map(|(_, s)| s)
        .collect()
    }
}

impl std::ops::BitOr for Needs {
    type Output = Needs;
    fn bitor(self, rhs: Needs) -> Needs {
        self.union(rhs)
    }
}

/// Light maps as [`Stages::light_maps`] hands them out.
pub type SharedMaps = Arc<Result<FittedMaps, RasterError>>;

/// Light maps with the view they were rendered over.
#[derive(Clone, Debug)]
pub struct FittedMaps {
    /// The view: the light frame, the window on the light image plane, the
    /// resolution, the near depth.
    pub view: LightView,
    /// Depth, object and triangle per texel.
    pub maps: LightMaps,
}

/// One timed stage: what was built, for how long.
#[derive(Clone, Debug, PartialEq)]
pub struct StageTime {
    /// The stage's name (`"bvh"`, `"light maps"`, `"receivers"`, a method's
    /// own stage such as `"pcss filter"`).
    pub name: String,
    /// What was built (sizes, counts), for people.
    pub detail: String,
    /// Wall time.
    pub seconds: f64,
}

/// What was built and how long it took, plus the counters methods keep
/// (e.g. how often a clamp fired). Printed by `softshadow render --stats`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// The stages, in the order they were built or run.
    pub stages: Vec<StageTime>,
    /// Named counters, in the order first counted.
    pub counters: Vec<(String, u64)>,
}

impl Stats {
    /// Adds `n` to the counter `name` (created at 0).
    pub fn count(&mut self, name: &str, n: u64) {
        match self.counters.iter_mut().find(|(k, _)| k == name) {
            Some((_, v)) => *v += n,
            None => self.counters.push((name.to_owned(), n)),
        }
    }

    /// The counter `name`, 0 when never counted.
    #[must_use]
    pub fn counter(&self, name: &str) -> u64 {
        self.counters
            .iter()
            .find(|(k, _)| k == name)
            .map_or(0, |&(_, v)| v)
    }

    /// The total time of the stages called `name`.
    #[must_use]
    pub fn seconds(&self, name: &str) -> f64 {
        self.stages
            .iter()
            .filter(|s| s.name == name)
            .map(|s| s.seconds)
            .sum()
    }

    /// The entries recorded after `earlier` (a snapshot of the same log).
    fn since(&self, earlier: &Stats) -> Stats {
        let stages = self.stages[earlier.stages.len().min(self.stages.len())..].to_vec();
        let counters = self
            .counters
            .iter()
            .filter_map(|(k, v)| {
                let before = earlier.counter(k);
                (*v > before).then(|| (k.clone(), v - before))
            })
            .collect();
        Stats { stages, counters }
    }
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for s in &self.stages {
            writeln!(
                f,
                "  {:<22} {:>10.3} ms  {}",
                s.name,
                s.seconds * 1e3,
                s.detail
            )?;
        }
        for (k, v) in &self.counters {
            writeln!(f, "  {k:<22} {v:>10}")?;
        }
        Ok(())
    }
}

/// The lazily built stages of one scene, shared by every method run on it.
///
/// Each accessor builds its stage on first use (thread-safe, once) and
/// records the time in the stage log; [`Stages::stats`] returns the log.
/// Nothing is built that no method asked for: a method on a point light
/// never touches a penumbra stage.
pub struct Stages<'a> {
    scene: &'a Scene,
    bvh: OnceLock<Bvh>,
    topology: OnceLock<Vec<Option<MeshTopology>>>,
    light_frame: OnceLock<LightFrame>,
    /// Method-owned stages and the light maps, by (type, name, key).
    cache: Mutex<HashMap<CacheKey, Slot>>,
    log: Mutex<Stats>,
    progress: Mutex<Option<Progress<'a>>>,
    cancelled: AtomicBool,
}

/// The key of a cached stage: the type of what it holds, its name, and the
/// key its owner chose (frame, parameters).
type CacheKey = (TypeId, &'static str, String);

/// A cached stage, built once by whoever asks first.
type Slot = Arc<OnceLock<Arc<dyn Any + Send + Sync>>>;

/// A progress callback: called with the number of receivers just finished.
pub type Progress<'a> = Arc<dyn Fn(usize) + Send + Sync + 'a>;

impl fmt::Debug for Stages<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Stages")
            .field("stats", &*self.lock_log())
            .finish_non_exhaustive()
    }
}

impl<'a> Stages<'a> {
    /// No stage built yet.
    #[must_use]
    pub fn new(scene: &'a Scene) -> Stages<'a> {
        Stages {
            scene,
            bvh: OnceLock::new(),
            topology: OnceLock::new(),
            light_frame: OnceLock::new(),
            cache: Mutex::new(HashMap::new()),
            log: Mutex::new(Stats::default()),
            progress: Mutex::new(None),
            cancelled: AtomicBool::new(false),
        }
    }

    /// Asks every method running on these stages to stop: from any
    /// thread, at any time. [`crate::method::run`] then returns
    /// [`MethodError::Cancelled`](crate::method::MethodError::Cancelled):
    /// methods that work per receiver stop within a chunk of 256
    /// receivers, the others when their pass ends; a run started later on
    /// the same stages is refused the same way (cancelling is for good:
    /// make new stages to compute again). A run is never cut short into a
    /// partial answer, so an answer that is returned is the whole
    /// computation's, bit for bit.
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }

    /// Whether [`Stages::cancel`] was called.
    #[must_use]
    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    /// From now on, calls `f(n)` as receivers are finished, `n` at a time
    /// (for progress bars on long runs; methods that work per receiver
    /// report it); `None` stops reporting.
    pub fn set_progress(&self, f: Option<Progress<'a>>) {
        *self
            .progress
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner) = f;
    }

    /// Reports `n` more receivers finished to the progress callback.
    pub fn advance(&self, n: usize) {
        let f = self
            .progress
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .clone();
        if let Some(f) = f {
            f(n);
        }
    }

    /// The scene.
    #[must_use]
    pub fn scene(&self) -> &'a Scene {
        self.scene
    }

    /// Builds every stage in `needs` that is not built yet, except
    /// [`Needs::LIGHT_MAPS`]: those are fitted to a frame and a resolution,
    /// and built when the method asks [`Stages::light_maps`] for them.
    pub fn prepare(&self, needs: Needs) {
        if needs.contains(Needs::BVH) {
            self.bvh();
        }
        if needs.contains(Needs::TOPOLOGY) {
            self.topology();
        }
        if needs.contains(Needs::LIGHT_FRAME) {
            self.light_frame();
        }
    }

    /// The BVH over every mesh's triangles (object id = mesh index).
    pub fn bvh(&self) -> &Bvh {
        self.bvh.get_or_init(|| {
            self.timed("bvh", || {
                let bvh = Bvh::new(Occluders::from_scene(self.scene));
                let detail = format!("{} triangles", bvh.occluders().len());
                (bvh, detail)
            })
        })
    }

    /// Per mesh, its edge topology over *welded* vertices: corners at
    /// bit-identical positions (`−0` and `+0` alike) are one vertex, the one
    /// with the lowest index, so a mesh stored as a triangle soup or with
    /// duplicated seam vertices still has its shared edges (a closed solid
    /// stays closed). The topology's triangles index the mesh's own
    /// positions. `None` for a mesh the topology rejects (never a validated
    /// [`Mesh`](crate::scene::Mesh)).
    pub fn topology(&self) -> &[Option<MeshTopology>] {
        self.topology.get_or_init(|| {
            self.timed("topology", || {
                let mut welded_vertices = 0usize;
                let t: Vec<_> = self
                    .scene
                    .meshes()
                    .iter()
                    .map(|m| {
                        let (triangles, merged) = welded(m.positions(), m.triangles());
                        welded_vertices += merged;
                        MeshTopology::new(&triangles, m.positions().len()).ok()
                    })
                    .collect();
                let edges: usize = t.iter().flatten().map(|t| t.edges().len()).sum();
                (
                    t,
                    format!("{edges} edges, {welded_vertices} vertices welded"),
                )
            })
        })
    }

    /// The [light frame](crate::definitions#light-frame), at the light's centre. `+z` points
    /// toward the centre of the scene's bounding box, except for a disk or
    /// rect light, where it is the light's normal (`u × v` for a rect) on
    /// the side of that centre — the light image plane is then parallel to
    /// the light, where single-projection footprints (SISM's `R`, PCSS's
    /// filter) are exact for occluders parallel to it. When the scene has no
    /// triangle or the direction is undefined, `+z` is world `−y` (down).
    pub fn light_frame(&self) -> LightFrame {
        *self.light_frame.get_or_init(|| {
            let light = self.scene.light();
            let c = light.center();
            let center = self.scene.bounds().map(|(lo, hi)| (lo + hi) * 0.5);
            let normal = light.plane_normal();
            let toward = match (normal, center) {
                (Some(n), Some(m)) => {
                    let side = if (m - c).dot(n) < 0.0 { -1.0 } else { 1.0 };
                    LightFrame::along(c, n * side).ok()
                }
                (Some(n), None) => LightFrame::along(c, n).ok(),
                (None, Some(m)) => LightFrame::toward(c, m).ok(),
                (None, None) => None,
            };
            // A validated light has a finite centre, so `along` succeeds; a
            // light built around its constructors with a non-finite centre
            // gets the frame at the origin (its receivers are errors).
            toward
                .or_else(|| LightFrame::along(c, -DVec3::Y).ok())
                .unwrap_or_else(LightFrame::down_at_origin)
        })
    }

    /// The light-view depth and object maps of `width × height` texels, over
    /// the window that holds every point of [`Stages::fit_points`] in front
    /// of the light (depth at least `near`, see [`LightView::fit`]): the
    /// occluders' vertices, and with [`Fit::Frame`] the frame's receivers.
    /// Built once per size for every frame fitted to the scene, once per
    /// frame and size for a frame fitted to itself.
    ///
    /// # Errors
    /// [`RasterError`] from fitting the view, e.g. when nothing is in front
    /// of the light.
    pub fn light_maps(&self, frame: &Frame, width: u32, height: u32) -> SharedMaps {
        let key = format!("{} {width}×{height}", fit_key(frame));
        self.cached("light maps", key, || {
            let light_frame = self.light_frame();
            let occluders = self.bvh().occluders();
            let points = self.fit_points(frame);
            let near = near_depth(light_frame, &points);
            let maps = LightView::fit(light_frame, points, width, height, near).map(|view| {
                let maps = rasterize_occluders(&view, occluders);
                FittedMaps { view, maps }
            });
            let detail = match &maps {
                Ok(_) => format!("{width}×{height}, near {near:.3e}"),
                Err(e) => format!("not built: {e}"),
            };
            (maps, detail)
        })
    }

    /// What stands for `frame`'s receivers where a map method sizes
    /// something by them (the farthest receiver's depth, a window): the
    /// receivers with [`Fit::Frame`], every occluder vertex with
    /// [`Fit::Scene`] — then nothing depends on the frame.
    pub fn fit_receivers(&self, frame: &Frame) -> Vec<DVec3> {
        match frame.fit() {
            Fit::Frame => frame.positions(),
            Fit::Scene => self.occluder_vertices(),
        }
    }

    /// The points the map methods' light views of `frame` are fitted to:
    /// [`Stages::fit_receivers`] and every occluder vertex.
    pub fn fit_points(&self, frame: &Frame) -> Vec<DVec3> {
        match frame.fit() {
            Fit::Frame => {
                let mut points = frame.positions();
                points.extend(self.occluder_vertices());
                points
            }
            Fit::Scene => self.occluder_vertices(),
        }
    }

    fn occluder_vertices(&self) -> Vec<DVec3> {
        let occluders = self.bvh().occluders();
        occluders.triangles().iter().flatten().copied().collect()
    }

    /// A stage a method builds for itself — distortion maps, endpoint maps,
    /// projected edges — kept here so that it is built once per scene and
    /// `key` and shared by every later run: the first call runs `build`
    /// (which returns the value and a description of what it built), logs
    /// it as the stage `name` and keeps it; later calls with the same type,
    /// `name` and `key` return the same value. The key is the owner's to
    /// choose: it must name everything the value depends on besides the
    /// scene (the frame's [`id`](Frame::id), resolutions, options).
    ///
    /// Thread-safe: concurrent callers with one key wait for one build;
    /// `build` may itself ask for other cached stages (not for its own key).
    pub fn cached<T: Send + Sync + 'static>(
        &self,
        name: &'static str,
        key: String,
        build: impl FnOnce() -> (T, String),
    ) -> Arc<T> {
        let slot = Arc::clone(
            self.cache
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .entry((TypeId::of::<T>(), name, key))
                .or_default(),
        );
        let value = slot.get_or_init(|| {
            let value: Arc<dyn Any + Send + Sync> = Arc::new(self.timed(name, build));
            value
        });
        // The slot's type is `T` by its key.
        match Arc::clone(value).downcast::<T>() {
            Ok(v) => v,
            Err(_) => unreachable!("a cache slot holds the type of its key"),
        }
    }

    /// Runs `build`, which returns a value and a description of what it
    /// built, and logs it as the stage `name`.
    pub fn timed<T>(&self, name: &str, build: impl FnOnce() -> (T, String)) -> T {
        let start = Instant::now();
        let (value, detail) = build();
        self.record(name, detail, start.elapsed());
        value
    }

    /// Logs a stage that took `elapsed`.
    pub fn record(&self, name: &str, detail: String, elapsed: Duration) {
        self.lock_log().stages.push(StageTime {
            name: name.to_owned(),
            detail,
            seconds: elapsed.as_secs_f64(),
        });
    }

    /// Adds `n` to the counter `name` in the log.
    pub fn count(&self, name: &str, n: u64) {
        self.lock_log().count(name, n);
    }

    /// Everything logged so far.
    #[must_use]
    pub fn stats(&self) -> Stats {
        self.lock_log().clone()
    }

    /// What was logged since `earlier` (an earlier [`Stages::stats`]).
    #[must_use]
    pub fn stats_since(&self, earlier: &Stats) -> Stats {
        self.lock_log().since(earlier)
    }

    fn lock_log(&self) -> std::sync::MutexGuard<'_, Stats> {
        self.log
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

/// The near depth of a light view: the least light-frame depth of any of
/// `points` (the view's [fit points](Stages::fit_points)) in front of the
/// light, halved (so nothing of
/// interest is clipped), and at least `2⁻²⁰` of the greatest such depth
/// (so the perspective stays well conditioned); `1` when nothing is in
/// front.
pub(crate) fn near_depth(frame: LightFrame, points: &[DVec3]) -> f64 {
    let depths = points
        .iter()
        .map(|&p| frame.to_light(p).z)
        .filter(|z| z.is_finite() && *z > 0.0);
    let (lo, hi) = depths.fold((f64::INFINITY, 0.0f64), |(lo, hi), z| {
        (lo.min(z), hi.max(z))
    });
    if hi == 0.0 {
        return 1.0;
    }
    (lo * 0.5).max(hi * (1.0 / 1_048_576.0))
}

/// The cache key of what is fitted to `frame` ([`Fit`]): one for every
/// frame fitted to the scene, one per frame fitted to itself.
pub(crate) fn fit_key(frame: &Frame) -> String {
    match frame.fit() {
        Fit::Scene => "scene".to_owned(),
        Fit::Frame => format!("frame {}", frame.id()),
    }
}

/// `triangles` with every index replaced by the lowest index of a vertex at
/// the bit-identical position (`−0` read as `+0`), and how many vertices
/// were merged into another.
fn welded(positions: &[DVec3], triangles: &[[u32; 3]]) -> (Vec<[u32; 3]>, usize) {
    let mut first = std::collections::HashMap::with_capacity(positions.len());
    let key = |v: DVec3| (v + DVec3::ZERO).to_array().map(f64::to_bits);
    let canonical: Vec<u32> = positions
        .iter()
        .enumerate()
        .map(|(i, &v)| *first.entry(key(v)).or_insert(i as u32))
        .collect();
    let merged = positions.len() - first.len();
    let triangles = triangles
        .iter()
        .map(|t| t.map(|i| canonical.get(i as usize).copied().unwrap_or(i)))
        .collect();
    (triangles, merged)
}
