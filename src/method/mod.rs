//! The shadow methods (feature `render`), behind one trait: a method
//! declares what it needs ([`Method::needs`], [`Method::lights`],
//! [`Method::requires`]) and fills the visibility of a frame's receivers
//! ([`Method::visibility`]); [`run`] checks the light and every receiver
//! once, builds the shared stages, runs the method, applies the
//! [horizon](Horizon) where the method asks for it, checks the result and
//! times the whole.
//!
//! Every method of the crate is listed once, in the [`registry`]: its
//! name, options, summary, the light kinds it handles and whether the
//! default run compares it. [`parse`] turns a command-line name
//! (`pcss:map=512`) into a method and [`Method::name`] prints it back; the
//! names, their options and what they accept are listed by
//! `softshadow --help` and in the registry's docs.
//!
//! ```
//! use softshadow::method::{self, Method};
//! use softshadow::render::{Frame, Receiver, Stages};
//! use softshadow::scene::{primitive, Light, Scene};
//! use softshadow::glam::DVec3;
//!
//! // A unit square 1 above the floor, a sphere light of radius 0.5 above it.
//! let plate = primitive::quad(DVec3::Y, DVec3::X * 0.5, DVec3::Z * 0.5).unwrap();
//! let scene = Scene::new(Light::sphere(DVec3::Y * 3.0, 0.5).unwrap()).with_mesh("plate", plate);
//! let at = |x: f64| Receiver { position: DVec3::new(x, 0.0, 0.0), normal: Some(DVec3::Y), object: None };
//! let frame = Frame::from_receivers(vec![at(0.0), at(5.0)]);
//! let stages = Stages::new(&scene);
//! let run = method::run(&method::Exact, &stages, &frame).unwrap();
//! assert_eq!(run.output.visibility, vec![0.0, 1.0]); // under the plate; far away
//! let pcss = method::parse("pcss:map=256").unwrap();
//! assert_eq!(pcss.name(), "pcss:map=256");
//! ```

/// The paragraph of the map methods' docs on their fitted light-view maps
/// and back faces.
macro_rules! fitted_maps_doc {
    () => {
        "Its light-view maps are fitted as the frame's [`Fit`](crate::render::Fit) says: \
         to the scene for a frame of points (`Frame::from_receivers`; each receiver's `V` \
         independent of the other receivers of the call), to the scene and the receivers for a \
         camera image (the real-time practice, `render`). A receiver on a closed mesh that \
         faces away from the whole light reads `V = 0` \
         ([`Method::hides_back_faces`](crate::method::Method::hides_back_faces))."
    };
}
pub(crate) use fitted_maps_doc;

mod centre;
mod hard;
pub mod oess;
pub mod options;
mod pcss;
mod reference;
pub mod registry;
pub mod single_sample;
pub mod sism;
pub mod ssoc;

pub use hard::HardShadow;
pub use oess::Oess;
pub use options::{Configurable, OptionError, ParseError};
pub use pcss::{Pcss, PcssBias};
pub use reference::{Exact, MonteCarlo};
pub use registry::{default_set, parse, REGISTRY};
pub use single_sample::SingleSample;
pub use sism::Sism;
pub use ssoc::{BackprojectedSsoc, Ssoc};

use crate::render::raster::RasterError;
use crate::render::{Frame, Needs, Receiver, Stages, Stats};
use crate::scene::{Emitter, Light, LightKind, ReceiverError, Scene};
use rayon::prelude::*;
use std::fmt;
use std::time::Instant;

/// A shadow method: the visibility `V ∈ [0, 1]` (the fraction of the
/// light's emitting measure visible from a receiver) of each receiver of a
/// frame.
///
/// Contract for implementations: one finite value in `[0, 1]` per receiver,
/// in the frame's order; the same values whatever the number of threads;
/// no panic on any valid scene and frame; errors, not NaN, for what the
/// method cannot handle. [`run`] checks the light kind against
/// [`Method::lights`], every receiver against the light and against
/// [`Method::requires`] before calling [`Method::visibility`], so a method
/// does not check them again.
pub trait Method: Send + Sync + fmt::Debug {
    /// A name for the method and its settings, for tables and file names.
    /// For the methods of the [`registry`] it is the command-line name
    /// (`mc:64`, `pcss:map=512`), which [`parse`] maps back to an equal
    /// method; a method of one's own may return anything short and
    /// distinctive.
    fn name(&self) -> String;

    /// The light kinds the method handles; [`run`] refuses the others with
    /// [`MethodError::UnsupportedLight`]. Default: every kind.
    fn lights(&self) -> &'static [LightKind] {
        LightKind::ALL
    }

    /// The shared stages the method needs built before it runs (it may
    /// build more of its own through [`Stages::cached`]).
    fn needs(&self) -> Needs {
        Needs::NONE
    }

    /// What every receiver must carry; [`run`] refuses a frame whose
    /// receivers lack it. Default: nothing.
    fn requires(&self) -> Requires {
        Requires::default()
    }

    /// How the light's share above each receiver's tangent plane bounds the
    /// answer ([`Horizon`]). Default: not at all.
    fn horizon(&self) -> Horizon {
        Horizon::Off
    }

    /// Whether [`run`] sets `V = 0` for a receiver that faces away from the
    /// whole light on a closed mesh: a receiver with a normal and an object
    /// whose mesh is closed (every edge of its topology has an even number
    /// of faces), whose tangent plane leaves all of the light on its back
    /// side ([`Emitter::share_above`] is 0). The segment from such a
    /// receiver to any light point enters its own solid, so the exact
    /// answer is 0; a method whose shadow map sees past the silhouette
    /// there (a map texel showing the floor behind a ball's terminator)
    /// would call it lit. Open surfaces are left to the method: a
    /// one-sided quad does not hide what is behind it. Default: `false`;
    /// the map methods of the crate say `true`, since none of their papers
    /// has an option that asks otherwise.
    fn hides_back_faces(&self) -> bool {
        false
    }

    /// An estimate of the peak bytes of the maps the method builds at its
    /// settings, whatever the frame — its light-view maps, whose side is
    /// an option — for a caller that bounds its memory before running it
    /// (the command line's `--max-memory`). The methods of the crate give
    /// their measured peak per texel, rounded up. Default: `0`, no such
    /// maps.
    fn map_bytes(&self) -> u64 {
        0
    }

    /// The visibility of every receiver of the checked frame `input`.
    ///
    /// # Errors
    /// [`MethodError`]: an invalid option, a light view that cannot be set
    /// up, …
    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError>;
}

/// What every receiver must carry for a method.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Requires {
    /// A normal.
    pub normals: bool,
    /// An object id.
    pub objects: bool,
    /// How to do without normals (an option of the method), if there is a
    /// way; shown in the error.
    pub normals_hint: &'static str,
}

/// The horizon bound, beyond the papers: the part of the light below a
/// receiver's tangent plane (the plane through it with its geometric
/// normal) is hidden by the receiver's own surface, so `V ≤ V_h`, the
/// light's share above that plane ([`Emitter::share_above`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Horizon {
    /// No bound (every paper's method).
    #[default]
    Off,
    /// [`run`] replaces each value by `min(V, V_h)`.
    Clamp,
    /// The method takes the plane into account itself (as one more edge of
    /// an exact union, say); [`run`] only checks that receivers have
    /// normals.
    Within,
}

impl Horizon {
    /// [`Horizon::Clamp`] when `on`, else [`Horizon::Off`]: the `horizon`
    /// option of a method that leaves the bound to [`run`].
    #[must_use]
    pub fn clamp_if(on: bool) -> Horizon {
        if on {
            Horizon::Clamp
        } else {
            Horizon::Off
        }
    }
}

/// A frame checked by [`run`] for a method: the stages, the receivers, and
/// each receiver's view of the light ([`Emitter`]) when the method asked
/// for them ([`Needs::EMITTERS`]). Only [`run`] builds one.
pub struct Input<'r, 'a> {
    stages: &'r Stages<'a>,
    frame: &'r Frame,
    emitters: Vec<Emitter>,
}

impl fmt::Debug for Input<'_, '_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Input")
            .field("receivers", &self.frame.receivers().len())
            .field("emitters", &self.emitters.len())
            .finish_non_exhaustive()
    }
}

impl<'r, 'a> Input<'r, 'a> {
    /// The stages of the scene.
    #[must_use]
    pub fn stages(&self) -> &'r Stages<'a> {
        self.stages
    }

    /// The scene.
    #[must_use]
    pub fn scene(&self) -> &'a Scene {
        self.stages.scene()
    }

    /// The light (of a kind the method handles).
    #[must_use]
    pub fn light(&self) -> &'a Light {
        self.stages.scene().light()
    }

    /// The frame.
    #[must_use]
    pub fn frame(&self) -> &'r Frame {
        self.frame
    }

    /// The receivers: each can see the light's measure, and carries what
    /// [`Method::requires`] asked for.
    #[must_use]
    pub fn receivers(&self) -> &'r [Receiver] {
        self.frame.receivers()
    }

    /// Each receiver's view of the light, in the frame's order, when the
    /// method's [`Method::needs`] contains [`Needs::EMITTERS`]; empty
    /// otherwise.
    #[must_use]
    pub fn emitters(&self) -> &[Emitter] {
        &self.emitters
    }

    /// Checks `frame` for `method` (see [`run`]).
    fn check(
        method: &dyn Method,
        stages: &'r Stages<'a>,
        frame: &'r Frame,
        keep_emitters: bool,
    ) -> Result<Input<'r, 'a>, MethodError> {
        let light = stages.scene().light();
        if !method.lights().contains(&light.kind()) {
            return Err(MethodError::UnsupportedLight {
                method: method.name(),
                light: light.kind().name(),
            });
        }
        let receivers = frame.receivers();
        if let Some(index) = receivers
            .par_iter()
            .position_first(|r| light.emitter(r.position).is_err())
        {
            if let Err(error) = light.emitter(receivers[index].position) {
                return Err(MethodError::Receiver { index, error });
            }
        }
        let requires = method.requires();
        let horizon = method.horizon() != Horizon::Off;
        if requires.normals || horizon {
            if let Some(index) = receivers.iter().position(|r| r.normal.is_none()) {
                return Err(MethodError::NeedsNormal {
                    method: method.name(),
                    index,
                    hint: if requires.normals {
                        requires.normals_hint
                    } else {
                        "or leave out the horizon option"
                    },
                });
            }
        }
        if requires.objects {
            if let Some(index) = receivers.iter().position(|r| r.object.is_none()) {
                return Err(MethodError::NeedsObject {
                    method: method.name(),
                    index,
                });
            }
        }
        let emitters = if keep_emitters {
            receivers
                .par_iter()
                .filter_map(|r| light.emitter(r.position).ok())
                .collect()
        } else {
            Vec::new()
        };
        Ok(Input {
            stages,
            frame,
            emitters,
        })
    }
}

/// What a method computed, per receiver.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Output {
    /// `V` per receiver, in `[0, 1]`.
    pub visibility: Vec<f64>,
    /// The standard error of each value, for the estimators that have one
    /// (Monte Carlo).
    pub stderr: Option<Vec<f64>>,
    /// A certified bound on each value's error, `|V − V_true| ≤ bound`, for
    /// the methods that have one (the exact reference).
    pub bound: Option<Vec<f64>>,
    /// For a segment light, the weights of its two end samples `[w_L, w_R]`
    /// (`w_L + w_R = V`) under linear emission, for the methods that shade
    /// with them (OESS); the shaded picture uses them.
    pub end_weights: Option<Vec<[f64; 2]>>,
}

impl Output {
    /// Values without standard errors.
    #[must_use]
    pub fn values(visibility: Vec<f64>) -> Output {
        Output {
            visibility,
            stderr: None,
            bound: None,
            end_weights: None,
        }
    }
}

/// Why a method could not compute a frame.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum MethodError {
    /// The method does not handle this kind of light.
    UnsupportedLight {
        /// The method.
        method: String,
        /// The light kind (`"segment"`, …).
        light: &'static str,
    },
    /// A receiver the light's measure cannot be seen from.
    Receiver {
        /// The receiver's index in the frame.
        index: usize,
        /// Why.
        error: ReceiverError,
    },
    /// The method needs receiver normals and receiver `index` has none.
    NeedsNormal {
        /// The method.
        method: String,
        /// The first receiver without one.
        index: usize,
        /// How to do without (an option of the method), if there is a way.
        hint: &'static str,
    },
    /// The method needs receiver object ids and receiver `index` has none.
    NeedsObject {
        /// The method.
        method: String,
        /// The first receiver without one.
        index: usize,
    },
    /// The light view could not be set up.
    LightView(RasterError),
    /// The method broke the trait's contract (a value outside `[0, 1]` or
    /// NaN, a missing value): a bug in the method, reported rather than
    /// passed on.
    Contract {
        /// The method.
        method: String,
        /// What was wrong.
        message: String,
    },
    /// The exact reference's certified bound at receiver `index` exceeds
    /// the tolerance asked for (`exact:tolerance=X`).
    Tolerance {
        /// The receiver's index in the frame.
        index: usize,
        /// Its bound.
        bound: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// An option of the method is out of its range.
    InvalidOption {
        /// The method.
        method: String,
        /// What is wrong.
        message: String,
    },
    /// The run was stopped by [`Stages::cancel`] before it finished.
    Cancelled,
}

impl_error!(MethodError, |error, f| match error {
    MethodError::UnsupportedLight { method, light } => {
        write!(f, "method {method} does not handle a {light} light")
    }
    MethodError::Receiver { index, error } => write!(f, "receiver {index}: {error}"),
    MethodError::NeedsNormal {
        method,
        index,
        hint,
    } => {
        write!(
            f,
            "method {method} needs receiver normals; receiver {index} has none"
        )?;
        if !hint.is_empty() {
            write!(f, " ({hint})")?;
        }
        Ok(())
    }
    MethodError::NeedsObject { method, index } => write!(
        f,
        "method {method} needs receiver object ids; receiver {index} has none"
    ),
    MethodError::LightView(e) => write!(f, "light view: {e}"),
    MethodError::Tolerance {
        index,
        bound,
        tolerance,
    } => write!(
        f,
        "receiver {index}: the exact answer's certified bound {bound:.3e} exceeds \
         the tolerance {tolerance:e}"
    ),
    MethodError::InvalidOption { method, message } => write!(f, "{method}: {message}"),
    MethodError::Contract { method, message } => {
        write!(f, "{method} broke the method contract: {message}")
    }
    MethodError::Cancelled => write!(f, "cancelled"),
});

/// A timed run of one method on one frame.
#[derive(Clone, Debug)]
pub struct Run {
    /// The method's name.
    pub method: String,
    /// Its values.
    pub output: Output,
    /// Wall time of the run: the checks, the stages it needed that were not
    /// built yet, and its visibility pass. Stages built by earlier runs on
    /// the same [`Stages`] (the BVH the camera's receivers were found with,
    /// say) are not counted again.
    pub seconds: f64,
    /// The stages built and counters kept during the run.
    pub stats: Stats,
}

/// Runs `method` on `frame`:
///
/// 1. checks once what no method checks again: the light is of a kind the
///    method handles ([`Method::lights`], else
///    [`MethodError::UnsupportedLight`]); every receiver can see the
///    light's measure (the first that cannot, by index, is
///    [`MethodError::Receiver`]); receivers carry the normals and object
///    ids the method [requires](Method::requires) (and normals for the
///    [horizon](Method::horizon));
/// 2. builds the shared stages it [needs](Method::needs);
/// 3. computes the visibility, and with [`Horizon::Clamp`] replaces each
///    value by `min(V, V_h)`;
/// 4. checks the contract — one value in `[0, 1]` per receiver, a finite
///    standard error for each if any ([`MethodError::Contract`] otherwise)
///    — and times the whole.
///
/// A run on [`Stages`] that are [cancelled](Stages::cancel), before or
/// while it runs, returns [`MethodError::Cancelled`] and no values.
///
/// [`Run::stats`] is what the stage log gained during the run: runs on one
/// [`Stages`] from several threads at once still compute the right values,
/// but their stats then mix.
///
/// # Errors
/// As above, and the method's own [`MethodError`].
pub fn run(method: &dyn Method, stages: &Stages, frame: &Frame) -> Result<Run, MethodError> {
    let before = stages.stats();
    let start = Instant::now();
    let horizon = method.horizon() == Horizon::Clamp;
    if stages.is_cancelled() {
        return Err(MethodError::Cancelled);
    }
    let input = check(method, stages, frame)?;
    let mut output = method.visibility(&input)?;
    if stages.is_cancelled() {
        return Err(MethodError::Cancelled);
    }
    if horizon && output.visibility.len() == input.emitters.len() {
        output
            .visibility
            .par_iter_mut()
            .zip(input.emitters.par_iter().zip(frame.receivers()))
            .for_each(|(v, (e, r))| {
                if let Some(n) = r.normal {
                    *v = v.min(e.share_above(r.position, n));
                }
            });
    }
    if method.hides_back_faces() {
        hide_back_faces(stages, frame, &mut output);
    }
    let seconds = start.elapsed().as_secs_f64();
    let n = frame.receivers().len();
    let bad = if output.visibility.len() != n {
        Some(format!(
            "{} values for {n} receivers",
            output.visibility.len()
        ))
    } else if let Some(i) = output
        .visibility
        .iter()
        .position(|v| !(0.0..=1.0).contains(v))
    {
        Some(format!("receiver {i} got {}", output.visibility[i]))
    } else if output
        .bound
        .as_ref()
        .is_some_and(|b| b.len() != n || b.iter().any(|x| x.is_nan() || *x < 0.0))
    {
        Some("a bound is missing, negative or NaN".to_owned())
    } else {
        output
            .stderr
            .as_ref()
            .filter(|e| e.len() != n || e.iter().any(|x| !x.is_finite()))
            .map(|_| "a standard error is missing or not finite".to_owned())
    };
    if let Some(message) = bad {
        return Err(MethodError::Contract {
            method: method.name(),
            message,
        });
    }
    Ok(Run {
        method: method.name(),
        output,
        seconds,
        stats: stages.stats_since(&before),
    })
}

/// [`Method::hides_back_faces`]: `V = 0` (and both end weights 0) for each
/// receiver on a closed mesh whose tangent plane leaves the whole light on
/// its back side.
fn hide_back_faces(stages: &Stages, frame: &Frame, output: &mut Output) {
    let receivers = frame.receivers();
    if output.visibility.len() != receivers.len() {
        return;
    }
    let light = stages.scene().light();
    // The receivers facing away from the whole light, first: the meshes'
    // closedness (the topology stage) is built only when there are some.
    let away: Vec<usize> = receivers
        .par_iter()
        .enumerate()
        .filter_map(|(k, r)| {
            let n = r.normal.filter(|_| r.object.is_some())?;
            let e = light.emitter(r.position).ok()?;
            (e.share_above(r.position, n) == 0.0).then_some(k)
        })
        .collect();
    if away.is_empty() {
        return;
    }
    let weights = centre::layer_weights(stages);
    let closed = |o: u32| {
        weights
            .get(o as usize)
            .is_some_and(|w| !w.faces.is_empty() && w.faces.iter().all(|&f| f < 1.0))
    };
    for k in away {
        if receivers[k].object.is_some_and(closed) {
            output.visibility[k] = 0.0;
            if let Some(w) = output.end_weights.as_mut().and_then(|w| w.get_mut(k)) {
                *w = [0.0, 0.0];
            }
        }
    }
}

/// Steps 1 and 2 of [`run`] without running the method: checks `frame` for
/// `method` and builds the shared stages it needs. The [`Input`] it returns
/// is what [`Method::visibility`] and a method's own diagnostics (such as
/// [`Sism::passes`]) take.
///
/// # Errors
/// As [`run`]'s checks.
pub fn check<'r, 'a>(
    method: &dyn Method,
    stages: &'r Stages<'a>,
    frame: &'r Frame,
) -> Result<Input<'r, 'a>, MethodError> {
    let needs = method.needs();
    let keep = needs.contains(Needs::EMITTERS) || method.horizon() == Horizon::Clamp;
    let input = Input::check(method, stages, frame, keep)?;
    stages.prepare(needs);
    Ok(input)
}

/// An [`MethodError::InvalidOption`] for `method` from an options check.
pub(crate) fn check_options<T: Configurable>(m: &T) -> Result<(), MethodError> {
    options::check(m).map_err(|e| MethodError::InvalidOption {
        method: m.name(),
        message: e.to_string(),
    })
}

/// The receivers' visibility computed one receiver at a time, in parallel
/// in chunks (rayon), with per-worker state from `init`, progress reported
/// per chunk; the first error (by receiver index) wins. The result does not
/// depend on the number of threads. Once the stages are
/// [cancelled](Stages::cancel), each chunk not yet started returns
/// [`MethodError::Cancelled`] at once.
pub(crate) fn per_receiver<S, T: Send>(
    input: &Input<'_, '_>,
    init: impl Fn() -> S + Send + Sync,
    f: impl Fn(&mut S, usize, &Receiver) -> Result<T, MethodError> + Send + Sync,
) -> Result<Vec<T>, MethodError> {
    const CHUNK: usize = 256;
    let receivers = input.receivers();
    let stages = input.stages();
    let chunks: Vec<Result<Vec<T>, MethodError>> = receivers
        .par_chunks(CHUNK)
        .enumerate()
        .map_init(&init, |state, (c, chunk)| {
            if stages.is_cancelled() {
                return Err(MethodError::Cancelled);
            }
            let out = chunk
                .iter()
                .enumerate()
                .map(|(k, r)| f(state, c * CHUNK + k, r))
                .collect();
            stages.advance(chunk.len());
            out
        })
        .collect();
    let mut all = Vec::with_capacity(receivers.len());
    for c in chunks {
        all.extend(c?);
    }
    Ok(all)
}
