//! The shadow methods (feature `render`), behind one trait: a method
//! declares what it needs ([`Method::needs`]) and fills the visibility of a
//! frame's receivers ([`Method::visibility`]). DESIGN.md §6.
//!
//! | name | type | what |
//! |---|---|---|
//! | `exact` | [`Exact`] | the exact reference |
//! | `mc:N` | [`MonteCarlo`] | Monte Carlo light sampling, `N` samples |
//! | `hard` | [`HardShadow`] | the point light at the light's centre |
//! | `pcss` | [`Pcss`] | percentage-closer soft shadows (Fernando 2005) |
//! | `sism`, `sism:OPT,…` | [`Sism`] | soft irregular shadow mapping (Johnson et al. 2009); options in [`Sism::from_name`] |
//!
//! [`parse`] turns a command-line name into a method; [`run`] runs one on a
//! frame, timed, with the stages it built.
//!
//! ```
//! use softshadow::method::{self, Method};
//! use softshadow::render::{Frame, Receiver, Stages};
//! use softshadow::scene::{primitive, Light, Scene};
//! use glam::DVec3;
//!
//! // A unit square 1 above the floor, a sphere light of radius 0.5 above it.
//! let plate = primitive::quad(DVec3::Y, DVec3::X * 0.5, DVec3::Z * 0.5).unwrap();
//! let scene = Scene::new(Light::sphere(DVec3::Y * 3.0, 0.5).unwrap()).with_mesh("plate", plate);
//! let at = |x: f64| Receiver { position: DVec3::new(x, 0.0, 0.0), normal: Some(DVec3::Y), object: None };
//! let frame = Frame::from_receivers(vec![at(0.0), at(5.0)]);
//! let stages = Stages::new(&scene);
//! let run = method::run(&method::Exact, &stages, &frame).unwrap();
//! assert_eq!(run.output.visibility, vec![0.0, 1.0]); // under the plate; far away
//! ```

mod hard;
mod pcss;
mod reference;
pub mod sism;

pub use hard::HardShadow;
pub use pcss::{Pcss, PcssBias};
pub use reference::{Exact, MonteCarlo};
pub use sism::Sism;

use crate::render::raster::RasterError;
use crate::render::{Frame, Stages, Stats};
use crate::scene::{Light, ReceiverError};
use std::fmt;
use std::time::Instant;

/// A shadow method: the visibility `V ∈ [0, 1]` (DESIGN §1) of each
/// receiver of a frame.
///
/// Contract for implementations: one finite value in `[0, 1]` per receiver,
/// in the frame's order; the same values whatever the number of threads;
/// no panic on any valid scene and frame; errors, not NaN, for receivers
/// the method cannot handle.
pub trait Method: Send + Sync + fmt::Debug {
    /// The command-line name (`exact`, `mc:64`, `pcss`, …), which
    /// [`parse`] maps back to an equal method.
    fn name(&self) -> String;

    /// The shared stages this method needs for `light`, or why it cannot
    /// handle that light.
    ///
    /// # Errors
    /// [`MethodError::UnsupportedLight`].
    fn needs(&self, light: &Light) -> Result<crate::render::Needs, MethodError>;

    /// The visibility of every receiver of `frame`, building what it needs
    /// through `stages`.
    ///
    /// # Errors
    /// [`MethodError`]: a receiver the light cannot be seen from (inside a
    /// sphere light, …), a receiver lacking a normal or object id the method
    /// needs, an unsupported light.
    fn visibility(&self, stages: &Stages, frame: &Frame) -> Result<Output, MethodError>;
}

/// What a method computed, per receiver.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Output {
    /// `V` per receiver, in `[0, 1]`.
    pub visibility: Vec<f64>,
    /// The standard error of each value, for the estimators that have one
    /// (Monte Carlo).
    pub stderr: Option<Vec<f64>>,
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
    /// An option of the method is out of its range.
    InvalidOption {
        /// The method.
        method: String,
        /// What is wrong.
        message: String,
    },
}

impl fmt::Display for MethodError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
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
            MethodError::InvalidOption { method, message } => write!(f, "{method}: {message}"),
            MethodError::Contract { method, message } => {
                write!(f, "{method} broke the method contract: {message}")
            }
        }
    }
}

impl std::error::Error for MethodError {}

/// The kind name of a light, as in the scene file.
#[must_use]
pub fn light_kind(light: &Light) -> &'static str {
    match light {
        Light::Sphere { .. } => "sphere",
        Light::Disk { .. } => "disk",
        Light::Rect { .. } => "rect",
        Light::Segment { .. } => "segment",
        Light::Point { .. } => "point",
    }
}

/// A timed run of one method on one frame.
#[derive(Clone, Debug)]
pub struct Run {
    /// The method's name.
    pub method: String,
    /// Its values.
    pub output: Output,
    /// Wall time of the run: the stages it needed that were not built yet,
    /// and its visibility pass. Stages built by earlier runs on the same
    /// [`Stages`] (the BVH the camera's receivers were found with, say) are
    /// not counted again.
    pub seconds: f64,
    /// The stages built and counters kept during the run.
    pub stats: Stats,
}

/// Runs `method` on `frame`: builds the stages it needs, computes the
/// visibility, checks the contract (one value in `[0, 1]` per receiver, a
/// finite standard error for each if any; [`MethodError::Contract`]
/// otherwise) and times the whole.
///
/// [`Run::stats`] is what the stage log gained during the run: runs on one
/// [`Stages`] from several threads at once still compute the right values,
/// but their stats then mix.
///
/// # Errors
/// The method's [`MethodError`].
pub fn run(method: &dyn Method, stages: &Stages, frame: &Frame) -> Result<Run, MethodError> {
    let before = stages.stats();
    let start = Instant::now();
    let needs = method.needs(stages.scene().light())?;
    stages.prepare(needs);
    let output = method.visibility(stages, frame)?;
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

/// The method names of DESIGN §8, in the order the default run and the
/// report list them; `mc:N` stands for any sample count.
pub const NAMES: &[&str] = &[
    "exact",
    "mc:N",
    "hard",
    "pcss",
    "sism",
    "single-sample",
    "ssoc",
    "backprojected-ssoc",
    "oess",
];

/// The methods of [`NAMES`] not built yet; [`parse`] says so for them.
pub const LATER: &[&str] = &["single-sample", "ssoc", "backprojected-ssoc", "oess"];

/// The method called `name` on the command line (DESIGN §8), with its
/// default options.
///
/// # Errors
/// A message naming the method and what is accepted.
pub fn parse(name: &str) -> Result<Box<dyn Method>, String> {
    match name {
        "exact" => return Ok(Box::new(Exact)),
        "hard" => return Ok(Box::new(HardShadow)),
        _ => {}
    }
    if option_list(name, "pcss").is_some() {
        return Ok(Box::new(Pcss::from_name(name)?));
    }
    if name == "sism" || name.starts_with("sism:") {
        return Sism::from_name(name).map(|s| Box::new(s) as Box<dyn Method>);
    }
    if let Some(n) = name.strip_prefix("mc:") {
        use crate::reference::monte_carlo::MIN_SAMPLES;
        return match n.parse::<u32>() {
            Ok(n) if n >= MIN_SAMPLES => Ok(Box::new(MonteCarlo::new(n))),
            _ => Err(format!(
                "'{name}': the sample count must be an integer from {MIN_SAMPLES} to {}",
                u32::MAX
            )),
        };
    }
    let available = "exact, mc:N, hard, pcss, sism";
    if LATER.contains(&name) {
        return Err(format!(
            "method '{name}' is not built yet; available: {available}"
        ));
    }
    Err(format!("unknown method '{name}'; available: {available}"))
}

/// The options of a method name `base` or `base:opt,opt,…`: `Some` list
/// (empty for `base` alone) when `name` is of that form, `None` otherwise.
pub(crate) fn option_list<'a>(name: &'a str, base: &str) -> Option<Vec<&'a str>> {
    match name.strip_prefix(base)? {
        "" => Some(Vec::new()),
        rest => Some(rest.strip_prefix(':')?.split(',').collect()),
    }
}

/// The methods the default run (`softshadow` with no arguments) compares,
/// in order: every available method, Monte Carlo at 16 and 256 samples.
#[must_use]
pub fn default_set() -> Vec<Box<dyn Method>> {
    vec![
        Box::new(HardShadow),
        Box::new(Pcss::default()),
        Box::new(Sism::default()),
        Box::new(MonteCarlo::new(16)),
        Box::new(MonteCarlo::new(256)),
        Box::new(Exact),
    ]
}

/// The receivers' visibility computed one receiver at a time, in parallel
/// in chunks (rayon), with per-worker state from `init`, progress reported
/// per chunk; the first error (by receiver index) wins. The result does not
/// depend on the number of threads.
pub(crate) fn per_receiver<S, T: Send>(
    stages: &Stages,
    frame: &Frame,
    init: impl Fn() -> S + Send + Sync,
    f: impl Fn(&mut S, usize, &crate::render::Receiver) -> Result<T, MethodError> + Send + Sync,
) -> Result<Vec<T>, MethodError> {
    use rayon::prelude::*;
    const CHUNK: usize = 256;
    let receivers = frame.receivers();
    let chunks: Vec<Result<Vec<T>, MethodError>> = receivers
        .par_chunks(CHUNK)
        .enumerate()
        .map_init(&init, |state, (c, chunk)| {
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
