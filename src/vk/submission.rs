//! Command submission: frames in flight (one command buffer + fence per slot) and one-shot
//! submissions for uploads and readbacks.

use super::context::{Context, SubmitSync};
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

/// How long a fence wait may take before ssgi reports the device as hung. Generous because a
/// CPU device (lavapipe) legitimately needs over a minute for one reference frame at 512x512
/// (16384 VPLs per pixel); a real GPU that takes 10 minutes has hung.
const FENCE_TIMEOUT_NS: u64 = 600_000_000_000;

struct Slot {
    cmd: vk::CommandBuffer,
    fence: vk::Fence,
    serial: u64,
}

/// `count` frames in flight. `begin(i)` waits for slot `i`'s previous submission, which is
/// the only wait on the frame path.
pub struct FrameSlots {
    ctx: Arc<Context>,
    pool: vk::CommandPool,
    slots: Vec<Slot>,
}

impl FrameSlots {
    pub fn new(ctx: &Arc<Context>, count: usize) -> Result<Self> {
        let info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        // SAFETY: valid create info; destroyed in Drop after the fences signalled.
        let pool =
            unsafe { ctx.device.create_command_pool(&info, None) }.vk("vkCreateCommandPool")?;
        let mut this = Self {
            ctx: ctx.clone(),
            pool,
            slots: Vec::new(),
        };
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(count as u32);
        // SAFETY: the pool is live.
        let cmds = unsafe { ctx.device.allocate_command_buffers(&alloc) }
            .vk("vkAllocateCommandBuffers")?;
        for (i, cmd) in cmds.into_iter().enumerate() {
            ctx.names.set(cmd, &format!("frame slot {i}"));
            let info = vk::FenceCreateInfo::default().flags(vk::FenceCreateFlags::SIGNALED);
            // SAFETY: valid create info; destroyed in Drop.
            let fence = unsafe { ctx.device.create_fence(&info, None) }.vk("vkCreateFence")?;
            this.slots.push(Slot {
                cmd,
                fence,
                serial: 0,
            });
        }
        Ok(this)
    }

    pub fn len(&self) -> usize {
        self.slots.len()
    }

    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    /// Wait until slot `i` is free, then start recording its command buffer.
    pub fn begin(&mut self, i: usize) -> Result<vk::CommandBuffer> {
        let slot = &mut self.slots[i];
        let d = &self.ctx.device;
        // SAFETY: the fence and command buffer belong to this slot; after the wait the GPU no
        // longer uses the command buffer, so it may be reset.
        unsafe {
            d.wait_for_fences(&[slot.fence], true, FENCE_TIMEOUT_NS)
                .vk("vkWaitForFences")?;
            self.ctx.mark_complete(slot.serial);
            d.reset_fences(&[slot.fence]).vk("vkResetFences")?;
            d.reset_command_buffer(slot.cmd, vk::CommandBufferResetFlags::empty())
                .vk("vkResetCommandBuffer")?;
            let begin = vk::CommandBufferBeginInfo::default()
                .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
            d.begin_command_buffer(slot.cmd, &begin)
                .vk("vkBeginCommandBuffer")?;
        }
        Ok(slot.cmd)
    }

    /// End and submit slot `i`.
    pub fn submit(&mut self, i: usize) -> Result<()> {
        self.submit_with(i, &SubmitSync::default())
    }

    /// End and submit slot `i` with semaphores.
    pub fn submit_with(&mut self, i: usize, sync: &SubmitSync) -> Result<()> {
        let slot = &mut self.slots[i];
        // SAFETY: the command buffer is recording (begun by `begin`).
        unsafe { self.ctx.device.end_command_buffer(slot.cmd) }.vk("vkEndCommandBuffer")?;
        slot.serial = self.ctx.submit_with(slot.cmd, slot.fence, sync)?;
        Ok(())
    }

    /// Wait until slot `i`'s last submission completed, without starting a new one (the
    /// window frontend waits before reusing the slot's swapchain acquire semaphore).
    pub fn wait(&mut self, i: usize) -> Result<()> {
        let slot = &self.slots[i];
        // SAFETY: the fence belongs to this slot; waiting does not change its state.
        unsafe {
            self.ctx
                .device
                .wait_for_fences(&[slot.fence], true, FENCE_TIMEOUT_NS)
        }
        .vk("vkWaitForFences")?;
        self.ctx.mark_complete(slot.serial);
        Ok(())
    }

    /// Wait for every slot (end of a run, before readback or resize).
    pub fn wait_all(&mut self) -> Result<()> {
        for slot in &self.slots {
            // SAFETY: fences owned by this object.
            unsafe {
                self.ctx
                    .device
                    .wait_for_fences(&[slot.fence], true, FENCE_TIMEOUT_NS)
            }
            .vk("vkWaitForFences")?;
            self.ctx.mark_complete(slot.serial);
        }
        Ok(())
    }
}

impl Drop for FrameSlots {
    fn drop(&mut self) {
        // SAFETY: wait (bounded) for the last submissions, then nothing uses the pool/fences.
        unsafe {
            for slot in &self.slots {
                let _ = self
                    .ctx
                    .device
                    .wait_for_fences(&[slot.fence], true, FENCE_TIMEOUT_NS);
                self.ctx.device.destroy_fence(slot.fence, None);
            }
            self.ctx.device.destroy_command_pool(self.pool, None);
        }
    }
}

/// Record with `record`, submit, and wait: for uploads and readbacks outside the frame loop.
pub fn one_shot(
    ctx: &Arc<Context>,
    record: impl FnOnce(vk::CommandBuffer) -> Result<()>,
) -> Result<()> {
    let mut slots = FrameSlots::new(ctx, 1)?;
    let cmd = slots.begin(0)?;
    record(cmd)?;
    slots.submit(0)?;
    slots.wait_all()
}
