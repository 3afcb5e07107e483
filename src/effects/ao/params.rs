//! SSAO's parameter block (shaders/ao/ao_params.glsl): what its estimating passes read of the
//! configuration, in a buffer of its own rather than the shared frame block. Constant for a
//! configuration (a new configuration makes a new effect), so it is uploaded once.

use super::config::AoEstimator;
use crate::config::RenderConfig;
use crate::error::Result;
use crate::shaders::AoParams;
use crate::vk::{uploaded_buffer, Access, Buffer, Context, Tracker};
use ash::vk;
use std::sync::Arc;

/// First pattern of multi-pattern evaluations without reuse (references): an index range no
/// accumulation reaches (rotation limits stay at most `MAX_PATTERNS`), so a reference is drawn
/// from points independent of the ones it judges instead of repeating them (shaders/include/
/// patterns.glsl: the golden sequence is shifted by a generic fraction, and the index has
/// nonzero low digits in bases 2 and 3, so its radical inverses are not the accumulated
/// patterns' own strata). Below 2^20, so the index converts exactly to a float in the shaders,
/// and times 4096 AO samples it stays below 2^32.
pub const REFERENCE_PATTERN_BASE: u32 = 1_000_003;

/// The block for `c`.
pub fn params(c: &RenderConfig) -> AoParams {
    let ao = &c.ao;
    // GTAO's slices and steps per side travel in the thesis's directions and steps.
    let (directions, steps) = match ao.estimator {
        AoEstimator::Gtao => ao.slices_steps(),
        _ => ao.directions_steps(),
    };
    AoParams {
        // Relative to the scene's bounding radius (frame.scene_radius): scale-free AO.
        radius: ao.radius,
        atten_a: ao.attenuation[0],
        atten_b: ao.attenuation[1],
        near_px: ao.near_px,
        directions,
        steps,
        samples: ao.samples,
        patterns: ao.patterns,
        position_mips: ao.position_mips,
        pattern_base: if ao.patterns > 1 {
            REFERENCE_PATTERN_BASE
        } else {
            0
        },
    }
}

/// The block for `c` in a device-local buffer the passes read, uploaded once.
pub fn buffer(ctx: &Arc<Context>, tracker: &mut Tracker, c: &RenderConfig) -> Result<Buffer> {
    uploaded_buffer(
        ctx,
        tracker,
        "ao.params",
        &params(c).to_bytes(),
        vk::BufferUsageFlags::STORAGE_BUFFER,
        Access::ComputeStorageRead,
    )
}
