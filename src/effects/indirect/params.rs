//! The VPL gather's parameter block (shaders/include/vpl_params.glsl): what the gathers that
//! read the RSM take of the configuration, in a buffer of their own rather than the shared
//! frame block. Every effect that gathers (the indirect light's cache, the noisy per-frame
//! gather its filters take) keeps a copy; constant for a configuration (a new configuration
//! makes new effects), so it is written once.

use crate::config::{IndirectConfig, RenderConfig};
use crate::error::Result;
use crate::shaders::VplParams;
use crate::vk::{uploaded_buffer, Access, Buffer, Context, Tracker};
use ash::vk;
use std::sync::Arc;

/// Where the effects bind it.
pub const BINDING: u32 = 15;

/// The block for `c`.
pub fn params(c: &RenderConfig) -> VplParams {
    let ind = &c.indirect;
    VplParams {
        count: ind.vpls,
        visibility: ind.visibility as u32,
        march_near_px: IndirectConfig::MARCH_NEAR_PX,
        interleave: ind.interleave,
        lanes: ind.vpl_lanes,
        noisy_half_res: ind.noisy_half_res as u32,
    }
}

/// The block for `c` in a device-local buffer the passes read, uploaded once.
pub fn buffer(
    ctx: &Arc<Context>,
    tracker: &mut Tracker,
    name: &str,
    c: &RenderConfig,
) -> Result<Buffer> {
    uploaded_buffer(
        ctx,
        tracker,
        name,
        &params(c).to_bytes(),
        vk::BufferUsageFlags::STORAGE_BUFFER,
        Access::ComputeStorageRead,
    )
}
