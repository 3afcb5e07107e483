//! Ground truth: a CPU ray tracer, independent of Vulkan and of the rasterizer, computing per
//! pixel what each screen-space effect approximates (docs/REFERENCE.md has the definitions):
//! world-space AO, direct light with exact visibility, one diffuse bounce with full
//! visibility, and the composited final image.

pub mod compose;
pub mod error_metrics;
pub mod estimate;
pub mod estimators;
pub mod output;
pub mod run;
pub mod sampling;
pub mod store;
pub mod surface;
pub mod trace;
pub mod visible_occluders;

pub use crate::scene::accel::Accel;
pub use estimators::AoDefinition;
pub use trace::{RefBuffer, Reference, Settings};

#[cfg(test)]
mod tests;
