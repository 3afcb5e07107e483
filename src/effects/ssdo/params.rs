//! SSDO's parameter block (shaders/ssdo/ssdo_params.glsl): what its passes read of the
//! configuration, in a buffer of its own rather than the shared frame block. Constant for a
//! configuration (a new configuration makes a new effect), so it is uploaded once.

use crate::config::RenderConfig;
use crate::error::Result;
use crate::shaders::SsdoParams;
use crate::vk::{uploaded_buffer, Access, Buffer, Context, Tracker};
use ash::vk;
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

/// The block for `c` in a device-local buffer the passes read, uploaded once.
pub fn buffer(ctx: &Arc<Context>, tracker: &mut Tracker, c: &RenderConfig) -> Result<Buffer> {
    uploaded_buffer(
        ctx,
        tracker,
        "ssdo.params",
        &params(c).to_bytes(),
        vk::BufferUsageFlags::STORAGE_BUFFER,
        Access::ComputeStorageRead,
    )
}
