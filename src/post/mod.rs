//! Post stages: what turns the composite's display-linear image into the output, after the
//! effects (antialiasing: `--aa sraa|sraa-shadow` and `--aa ssaa16`). Each is a folder here
//! (its shaders in `shaders/<stage>/`) that owns its passes and is registered in [`REGISTRY`]
//! with one line; the renderer creates, binds and records those the configuration turns on.

pub mod sraa;
pub mod ssaa;

pub mod stage;

pub use stage::{PostFrame, PostRegistration, PostStage};

use crate::config::RenderConfig;
use crate::error::Result;
use crate::passes::PassLayout;
use crate::vk::{Context, DescriptorPool};
use std::sync::Arc;

/// The registry, in recording order.
pub const REGISTRY: &[PostRegistration] = &[sraa::REGISTRATION, ssaa::REGISTRATION];

/// Every post stage the configuration turns on, in registry order.
pub fn create(
    ctx: &Arc<Context>,
    pool: &DescriptorPool,
    config: &RenderConfig,
) -> Result<Vec<Box<dyn PostStage>>> {
    REGISTRY
        .iter()
        .filter(|r| (r.enabled)(config))
        .map(|r| (r.create)(ctx, pool))
        .collect()
}

/// Every pipeline of every post stage, for the reflection check and the dependency table.
pub fn all_layouts() -> Vec<PassLayout> {
    REGISTRY.iter().flat_map(|r| (r.layouts)()).collect()
}
