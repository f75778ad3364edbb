//! The emitting measure a light presents to one receiver ([`Emitter`],
//! from [`Light::emitter`](super::Light::emitter)): part of the light's
//! geometry, defined in [`kernel::light`](crate::kernel::light) and named
//! here too.

pub use crate::kernel::light::Emitter;
