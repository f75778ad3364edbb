//! The two references as methods: [`Exact`](struct@Exact) and [`MonteCarlo`].

use super::options::{from_options, method_options, Configurable};
use super::{per_receiver, Input, Method, MethodError, Output};
use crate::bvh::Bvh;
use crate::reference::{exact, monte_carlo};
use crate::render::Needs;
use crate::scene::{Emitter, LightKind, ReceiverError};
use glam::DVec3;

/// Each receiver's answer by `f(state, index, bvh, emitter, p)`, the
/// receiver's emitter and position, after `method`'s options are checked;
/// a receiver whose coordinates `out_of_range` refuses is refused with
/// [`ReceiverError::OutOfRange`]. `init` makes a worker's state.
fn per_emitter<S, T: Send>(
    method: &impl Configurable,
    input: &Input<'_, '_>,
    init: impl Fn() -> S + Send + Sync,
    out_of_range: impl Fn(&Bvh, &Emitter, DVec3) -> bool + Send + Sync,
    f: impl Fn(&mut S, usize, &Bvh, &Emitter, DVec3) -> Result<T, MethodError> + Send + Sync,
) -> Result<Vec<T>, MethodError> {
    super::check_options(method)?;
    let bvh = input.stages().bvh();
    let emitters = input.emitters();
    per_receiver(input, init, |s, index, r| {
        if out_of_range(bvh, &emitters[index], r.position) {
            return Err(MethodError::Receiver {
                index,
                error: ReceiverError::OutOfRange,
            });
        }
        f(s, index, bvh, &emitters[index], r.position)
    })
}

method_options! {
    /// The exact reference ([`crate::reference::exact`]): the answer every
    /// other method is measured against, each value with its certified bound
    /// ([`Output::bound`]: `|V − V_true| ≤ bound`). Any light.
    ///
    /// `exact:tolerance=X` refuses any receiver whose bound exceeds `X`
    /// ([`MethodError::Tolerance`]), so that a validation run cannot rest on a
    /// weak answer unawares; the default, 1, refuses nothing (`V` is a
    /// fraction).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Exact {
        /// The largest certified bound accepted, in `(0, 1]`; 1 accepts every
        /// answer. Default 1.
        pub tolerance: f64 = Exact.tolerance, option(real "tolerance", (f64::MIN_POSITIVE, 1.0), "refuse any receiver whose certified bound on |V - V_true| exceeds X; 1 refuses nothing (ours)");
    }
    name: "exact",
    summary: "the exact reference: the union of the occluders' images on the light, with a certified bound",
    lights: LightKind::ALL,
    default_run: &["exact"],
    compare: &[],
}

/// The exact reference with its default options (the value of the type
/// [`Exact`](struct@Exact), so that `&Exact` reads as the method).
#[allow(non_upper_case_globals)]
pub const Exact: Exact = Exact { tolerance: 1.0 };

impl Method for Exact {
    from_options!();

    fn needs(&self) -> Needs {
        Needs::BVH | Needs::EMITTERS
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        let answers = per_emitter(
            self,
            input,
            exact::Scratch::default,
            |bvh, emitter, p| exact::domain(bvh, emitter, p).refused(),
            |s, index, bvh, emitter, p| {
                let b = exact::emitter_visibility_bounded(bvh, emitter, p, s);
                if self.tolerance < 1.0 && (b.bound > self.tolerance || b.bound.is_nan()) {
                    return Err(MethodError::Tolerance {
                        index,
                        bound: b.bound,
                        tolerance: self.tolerance,
                    });
                }
                Ok(b)
            },
        )?;
        Ok(Output {
            visibility: answers.iter().map(|b| b.visibility).collect(),
            stderr: None,
            bound: Some(answers.iter().map(|b| b.bound).collect()),
            end_weights: None,
        })
    }
}

method_options! {
    /// Monte Carlo light sampling ([`crate::reference::monte_carlo`]) with a
    /// fixed sample count per receiver; reports each value's standard error.
    /// Any light.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    #[non_exhaustive]
    pub struct MonteCarlo {
        /// Samples per receiver, from [`MIN_SAMPLES`](monte_carlo::MIN_SAMPLES)
        /// to `u32::MAX`; default [`MonteCarlo::DEFAULT_SAMPLES`].
        pub samples: u32 = MonteCarlo::DEFAULT_SAMPLES, option(positional int "N", (monte_carlo::MIN_SAMPLES as u64, u32::MAX as u64), "samples per receiver");
        /// The seed of the sample sequences; default
        /// [`monte_carlo::DEFAULT_SEED`].
        pub seed: u64 = monte_carlo::DEFAULT_SEED, option(int "seed", (0, u64::MAX), "the seed of the sample sequences"), builder(with_seed);
    }
    name: "mc",
    summary: "Monte Carlo light sampling: N stratified samples per receiver, with a standard error",
    lights: LightKind::ALL,
    default_run: &["mc:16", "mc:256"],
    compare: &[],
}

impl MonteCarlo {
    /// Default [`MonteCarlo::samples`] (ours).
    pub const DEFAULT_SAMPLES: u32 = 64;

    /// `samples` per receiver, the default seed.
    #[must_use]
    pub fn new(samples: u32) -> MonteCarlo {
        MonteCarlo {
            samples,
            ..MonteCarlo::default()
        }
    }
}

impl Method for MonteCarlo {
    from_options!();

    fn needs(&self) -> Needs {
        Needs::BVH | Needs::EMITTERS
    }

    fn visibility(&self, input: &Input<'_, '_>) -> Result<Output, MethodError> {
        let options = monte_carlo::Options::new(self.samples).with_seed(self.seed);
        let estimates = per_emitter(
            self,
            input,
            || (),
            monte_carlo::out_of_range,
            |(), _, bvh, emitter, p| Ok(monte_carlo::emitter_visibility(bvh, emitter, p, &options)),
        )?;
        Ok(Output {
            visibility: estimates.iter().map(|e| e.visibility).collect(),
            stderr: Some(estimates.iter().map(|e| e.stderr).collect()),
            bound: None,
            end_weights: None,
        })
    }
}
