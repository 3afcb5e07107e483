//! Samplers (for the textured G-buffer permutation; compute passes use texelFetch).

use super::context::{Context, Garbage};
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

pub struct Sampler {
    ctx: Arc<Context>,
    pub raw: vk::Sampler,
}

impl Sampler {
    /// Trilinear-free bilinear repeat sampler (textures carry a single mip level).
    pub fn linear_repeat(ctx: &Arc<Context>) -> Result<Self> {
        Self::linear(ctx, vk::SamplerAddressMode::REPEAT)
    }

    /// Bilinear, clamped to the edge (the overlay's font atlas: repeat would bleed the
    /// opposite edge's glyphs into border texels).
    pub fn linear_clamp(ctx: &Arc<Context>) -> Result<Self> {
        Self::linear(ctx, vk::SamplerAddressMode::CLAMP_TO_EDGE)
    }

    fn linear(ctx: &Arc<Context>, address: vk::SamplerAddressMode) -> Result<Self> {
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
            .address_mode_u(address)
            .address_mode_v(address)
            .address_mode_w(address)
            .max_lod(0.0);
        // SAFETY: valid create info; destroyed through the deletion queue.
        let raw = unsafe { ctx.device.create_sampler(&info, None) }.vk("vkCreateSampler")?;
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for Sampler {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::Sampler(self.raw));
    }
}
