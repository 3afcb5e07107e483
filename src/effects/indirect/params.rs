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

/// Lanes that share one every-VPL estimate in indirect_spread.comp, at most `most`: all of
/// them, or for fewer evaluations of eq 9 the next power of two, so that no lane idles for
/// lack of VPLs. The shaders read it from the block (`gather_lanes`, `spread_lanes`), so
/// their dispatch sizes and this side's agree.
pub fn lanes_per_estimate(c: &RenderConfig, most: u32) -> u32 {
    let evaluations = match c.indirect.vpls {
        0 => c.rsm_size * c.rsm_size,
        v => v,
    };
    evaluations.clamp(1, most.max(1)).next_power_of_two()
}

/// The block for `c`.
pub fn params(c: &RenderConfig) -> VplParams {
    let ind = &c.indirect;
    VplParams {
        count: ind.vpls,
        visibility: ind.visibility as u32,
        march_near_px: IndirectConfig::MARCH_NEAR_PX,
        interleave: ind.interleave,
        gather_lanes: lanes_per_estimate(c, ind.vpl_lanes),
        spread_lanes: lanes_per_estimate(c, crate::shaders::SPREAD_LANES),
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
