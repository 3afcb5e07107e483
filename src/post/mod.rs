//! Post stages: what turns the composite's display-linear image into the output, after the
//! effects (antialiasing: `--aa sraa|sraa-shadow` and `--aa ssaa16`). Each is a folder here
//! (its shaders in `shaders/<stage>/`) that owns its passes and is registered in [`REGISTRY`]
//! with one line; the renderer creates, binds and records those the configuration turns on.

pub mod sraa;
pub mod ssaa;

pub mod stage;

pub use stage::{PostFrame, PostRegistration, PostStage};

use crate::config::{AaConfig, AaMode, RenderConfig};
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
        .map(|r| (r.create)(ctx, pool, config))
        .collect()
}

/// Every pipeline of every post stage, for the reflection check and the dependency table.
pub fn all_layouts() -> Vec<PassLayout> {
    REGISTRY.iter().flat_map(|r| (r.layouts)()).collect()
}

/// The post stages' command-line options, flattened into each subcommand that renders: which
/// antialiasing runs (`--aa`) and each stage's own.
#[derive(clap::Args, Debug, Clone)]
pub struct PostArgs {
    /// Antialiasing: `none`; `sraa` (shade once per pixel, geometry at 4 subpixels, each
    /// subpixel's shading rebuilt from the pixels around it with depth and normal weights);
    /// `sraa-shadow` (SRAA with a shadow test per subpixel in the weights); `ssaa16` (render
    /// at 4x width and height, box-filter 4x4: the reference).
    #[arg(long, value_enum, default_value_t = AaMode::None)]
    pub aa: AaMode,
    #[command(flatten)]
    pub sraa: sraa::args::SraaArgs,
}

impl PostArgs {
    /// Write the post stages' part of `config` from the options.
    pub fn apply(&self, config: &mut RenderConfig) {
        config.aa = AaConfig {
            mode: self.aa,
            sraa: self.sraa.config(),
        };
    }
}
