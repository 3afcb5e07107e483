//! What a post stage is to the renderer: the [`PostStage`] trait, its registration, and what
//! it is given to record a frame.

use crate::config::RenderConfig;
use crate::effects::Recording;
use crate::error::Result;
use crate::passes::compute::FrameSet;
use crate::passes::decl::Resolve;
use crate::passes::{PassId, PassLayout};
use crate::resources::scene_gpu::SceneGpu;
use crate::vk::{Context, DescriptorPool};
use std::sync::Arc;

/// What a post stage is given to record a frame.
pub struct PostFrame<'a> {
    pub frame: FrameSet,
    pub scene: &'a SceneGpu,
    /// The shared targets (the composite's `shaded` image, the G-buffer, the output).
    pub targets: &'a dyn Resolve,
    /// The render size (the composite's) and the output's.
    pub render: (u32, u32),
    pub output: (u32, u32),
    /// The G-buffer was drawn this frame (the camera or an object moved): a stage that draws
    /// the scene's geometry too draws it now, and keeps last frame's otherwise.
    pub geometry: bool,
}

pub trait PostStage {
    /// Point its descriptor sets at this size's targets.
    fn bind(&self, ctx: &Context, targets: &dyn Resolve) -> Result<()>;

    /// Record its passes, each inside `Recording::timed`.
    fn record(&self, r: &mut Recording<'_>, f: &PostFrame<'_>);
}

/// Creates a post stage's pipelines and descriptor sets.
pub type CreateStage =
    fn(&Arc<Context>, &DescriptorPool, &RenderConfig) -> Result<Box<dyn PostStage>>;

/// How a post stage plugs in: when the configuration turns it on, how to create it, its
/// pipelines for the reflection check, and its passes.
pub struct PostRegistration {
    pub enabled: fn(&RenderConfig) -> bool,
    pub create: CreateStage,
    pub layouts: fn() -> Vec<PassLayout>,
    /// Every pass it may record, in recording order.
    pub passes: &'static [PassId],
    /// Those of `passes` that draw the scene's geometry: left out, as the G-buffer is, while
    /// nothing moves.
    pub geometry_passes: &'static [PassId],
}
