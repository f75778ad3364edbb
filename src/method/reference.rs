//! The two references as methods: [`Exact`] and [`MonteCarlo`].

use super::{per_receiver, Method, MethodError, Output};
use crate::reference::{exact, monte_carlo};
use crate::render::{Frame, Needs, Stages};
use crate::scene::Light;

/// The exact reference ([`crate::reference::exact`]): the answer every
/// other method is measured against. Any light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Exact;

impl Method for Exact {
    fn name(&self) -> String {
        "exact".to_owned()
    }

    fn needs(&self, _: &Light) -> Result<Needs, MethodError> {
        Ok(Needs::BVH)
    }

    fn visibility(&self, stages: &Stages, frame: &Frame) -> Result<Output, MethodError> {
        let (bvh, light) = (stages.bvh(), stages.scene().light());
        let visibility = per_receiver(stages, frame, exact::Scratch::default, |s, index, r| {
            exact::visibility_with(bvh, light, r.position, s)
                .map_err(|error| MethodError::Receiver { index, error })
        })?;
        Ok(Output {
            visibility,
            stderr: None,
        })
    }
}

/// Monte Carlo light sampling ([`crate::reference::monte_carlo`]) with a
/// fixed sample count per receiver; reports each value's standard error.
/// Any light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MonteCarlo {
    /// Samples per receiver (at least
    /// [`MIN_SAMPLES`](monte_carlo::MIN_SAMPLES); fewer is an error per
    /// receiver).
    pub samples: u32,
    /// The seed of the sample sequences.
    pub seed: u64,
}

impl MonteCarlo {
    /// `samples` per receiver, the default seed.
    #[must_use]
    pub fn new(samples: u32) -> MonteCarlo {
        MonteCarlo {
            samples,
            seed: monte_carlo::DEFAULT_SEED,
        }
    }
}

impl Method for MonteCarlo {
    fn name(&self) -> String {
        format!("mc:{}", self.samples)
    }

    fn needs(&self, _: &Light) -> Result<Needs, MethodError> {
        Ok(Needs::BVH)
    }

    fn visibility(&self, stages: &Stages, frame: &Frame) -> Result<Output, MethodError> {
        let (bvh, light) = (stages.bvh(), stages.scene().light());
        let options = monte_carlo::Options::new(self.samples).with_seed(self.seed);
        let invalid = |e: monte_carlo::Error| MethodError::InvalidOption {
            method: self.name(),
            message: e.to_string(),
        };
        if self.samples < monte_carlo::MIN_SAMPLES {
            return Err(invalid(monte_carlo::Error::TooFewSamples {
                samples: self.samples,
            }));
        }
        let estimates = per_receiver(
            stages,
            frame,
            || (),
            |(), index, r| {
                monte_carlo::visibility(bvh, light, r.position, &options).map_err(|e| match e {
                    monte_carlo::Error::Receiver(error) => MethodError::Receiver { index, error },
                    e => invalid(e),
                })
            },
        )?;
        Ok(Output {
            visibility: estimates.iter().map(|e| e.visibility).collect(),
            stderr: Some(estimates.iter().map(|e| e.stderr).collect()),
        })
    }
}
