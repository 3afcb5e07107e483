//! One-off uploads of image data through a staging buffer.

use super::context::Context;
use super::memory::{Buffer, Image};
use super::submission::one_shot;
use super::sync::{Access, Tracker};
use crate::error::Result;
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// A host-visible buffer holding `bytes`, the source of one upload.
fn staging(ctx: &Arc<Context>, bytes: &[u8]) -> Result<Buffer> {
    let mut buffer = Buffer::new(
        ctx,
        "upload.staging",
        bytes.len() as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    buffer.write(bytes)?;
    Ok(buffer)
}

/// Fill `image` (whole, one mip) with `bytes` (tightly packed rows) and leave it in `then`.
pub fn upload_image(
    ctx: &Arc<Context>,
    tracker: &mut Tracker,
    image: &Image,
    bytes: &[u8],
    then: Access,
) -> Result<()> {
    let staging = staging(ctx, bytes)?;
    one_shot(ctx, |cmd| {
        tracker.image(image, Access::Undefined);
        tracker.image(image, Access::TransferDst);
        tracker.flush(&ctx.device, cmd);
        let region = image.copy_region();
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

/// Fill the start of `buffer` with `bytes` through a staging buffer and leave it in `then`.
pub fn upload_buffer(
    ctx: &Arc<Context>,
    tracker: &mut Tracker,
    buffer: &Buffer,
    bytes: &[u8],
    then: Access,
) -> Result<()> {
    let staging = staging(ctx, bytes)?;
    one_shot(ctx, |cmd| {
        tracker.buffer(buffer, Access::TransferDst);
        tracker.flush(&ctx.device, cmd);
        let region = [vk::BufferCopy {
            src_offset: 0,
            dst_offset: 0,
            size: bytes.len() as u64,
        }];
        // SAFETY: recording; both buffers are live, `buffer` is at least `bytes.len()` long
        // (callers size it from the same data) and in the transfer-write state.
        unsafe {
            ctx.device
                .cmd_copy_buffer(cmd, staging.raw, buffer.raw, &region)
        };
        tracker.buffer(buffer, then);
        tracker.flush(&ctx.device, cmd);
        Ok(())
    })
}

/// A device-local buffer of `usage` holding `bytes`, left in `then`.
pub fn uploaded_buffer(
    ctx: &Arc<Context>,
    tracker: &mut Tracker,
    name: &str,
    bytes: &[u8],
    usage: vk::BufferUsageFlags,
    then: Access,
) -> Result<Buffer> {
    let buffer = Buffer::new(
        ctx,
        name,
        bytes.len().max(4) as u64,
        usage | vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuOnly,
    )?;
    upload_buffer(ctx, tracker, &buffer, bytes, then)?;
    Ok(buffer)
}
