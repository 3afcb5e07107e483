//! The validation harness itself: synchronization validation is on and a real hazard is
//! reported (so a silent log in the other tests means something).

mod common;

use ash::vk;
use gpu_allocator::MemoryLocation;
use ssgi::vk::{one_shot, Buffer};

#[test]
fn sync_validation_reports_a_write_after_write_hazard() {
    let ctx = common::context();
    let src = Buffer::new(
        &ctx,
        "src",
        256,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::GpuOnly,
    )
    .unwrap();
    let dst = Buffer::new(
        &ctx,
        "dst",
        256,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuOnly,
    )
    .unwrap();
    one_shot(&ctx, |cmd| {
        let region = [vk::BufferCopy {
            src_offset: 0,
            dst_offset: 0,
            size: 256,
        }];
        // SAFETY: valid API use (live buffers, recording command buffer); the two copies
        // deliberately write `dst` without a barrier between them, a hazard that only
        // synchronization validation reports.
        unsafe {
            ctx.device.cmd_copy_buffer(cmd, src.raw, dst.raw, &region);
            ctx.device.cmd_copy_buffer(cmd, src.raw, dst.raw, &region);
        }
        Ok(())
    })
    .unwrap();
    ctx.wait_idle().unwrap();
    let messages = ctx.validation().unwrap().messages();
    assert!(
        messages
            .iter()
            .any(|m| m.contains("SYNC-HAZARD-WRITE-AFTER-WRITE")),
        "expected a WAW hazard report, got {messages:?}"
    );
}
