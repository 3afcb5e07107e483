//! SSDO's parameter block (shaders/ssdo/ssdo_params.glsl): what its passes read of the
//! configuration, in a buffer of its own rather than the shared frame block. Constant for a
//! configuration (a new configuration makes a new effect), so it is written once.

use crate::config::RenderConfig;
use crate::error::Result;
use crate::shaders::SsdoParams;
use crate::vk::{Buffer, Context};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// The block for `c`.
pub fn params(c: &RenderConfig) -> SsdoParams {
    let s = &c.ssdo;
    SsdoParams {
        thresholds: s.adaptive.map_or([0.0; 4], |a| a.thresholds),
        samples: s.samples,
        min_samples: s.adaptive.map_or(0, |a| a.min),
        prepass_scale: s.adaptive.map_or(1, |a| a.scale),
        threshold_count: s.adaptive.map_or(0, |a| a.threshold_count),
        // Relative to the scene's bounding radius (frame.scene_radius): scale-free.
        radius: s.radius,
        filter_radius: s.filter / 2,
        scale: s.scale,
        direct_enabled: c.effects.direct as u32,
    }
}

/// The block for `c` in a buffer the passes read (host-visible: written before any
/// submission that reads it, which makes the write visible to the device).
pub fn buffer(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Buffer> {
    let mut buffer = Buffer::new(
        ctx,
        "ssdo.params",
        SsdoParams::SIZE as u64,
        vk::BufferUsageFlags::STORAGE_BUFFER,
        MemoryLocation::CpuToGpu,
    )?;
    buffer.write(&params(c).to_bytes())?;
    Ok(buffer)
}
