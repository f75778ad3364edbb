//! What is done with a method's answers (feature `render`): pictures,
//! error summaries, scores and arrays for other renderers. The data flows
//! scene → [stages](crate::render) → [method](crate::method) → here.
//!
//! - [`image`]: [shading](crate::definitions#shading), the error heat-map,
//!   error summaries ([`ErrorSummary`](image::ErrorSummary)) and PNG files.
//! - [`score`]: an image of `V` made elsewhere scored against the exact
//!   answer on the same receivers, with the report's statistics.
//! - [`gbuffer`]: the receivers of a camera as arrays (position, normal,
//!   object id, exact `V`) and the camera as a rasteriser's matrices.
//! - `yardstick` (feature `report`): Monte Carlo's RMSE against its
//!   sample count as a fitted power law, and the count at which it meets a
//!   given RMSE — the yardstick of a score and of the report.

pub mod gbuffer;
pub mod image;
pub mod score;
#[cfg(feature = "report")]
pub mod yardstick;
