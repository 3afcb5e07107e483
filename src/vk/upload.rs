//! One-off uploads of image data through a staging buffer.

use super::commands::one_shot;
use super::context::Context;
use super::sync::{Access, Tracker};
use super::{Buffer, Image};
use crate::error::Result;
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Fill `image` (whole, one mip) with `bytes` (tightly packed rows) and leave it in `then`.
pub fn upload_image(
    ctx: &Arc<Context>,
    tracker: &mut Tracker,
    image: &Image,
    bytes: &[u8],
    then: Access,
) -> Result<()> {
    let mut staging = Buffer::new(
        ctx,
        "upload.staging",
        bytes.len() as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    staging.write(bytes)?;
    one_shot(ctx, |cmd| {
        tracker.image(image, Access::Undefined);
        tracker.image(image, Access::TransferDst);
        tracker.flush(&ctx.device, cmd);
        let region = vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: image.aspect(),
                mip_level: 0,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(vk::Extent3D {
                width: image.desc.width,
                height: image.desc.height,
                depth: 1,
            });
        // SAFETY: recording; the image is in TRANSFER_DST layout (tracker) and the staging
        // buffer holds the whole image.
        unsafe {
            ctx.device.cmd_copy_buffer_to_image(
                cmd,
                staging.raw,
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
            )
        };
        tracker.image(image, then);
        tracker.flush(&ctx.device, cmd);
        Ok(())
    })
}
