//! Per-effect GPU counters (`Counters` in shaders/include/counters.glsl, whose header build.rs
//! generates as `CountersHeader`): written by atomics during the frame, the header copied to a
//! per-slot host buffer at the frame's end and read when the slot comes round again, like the
//! timestamps, so reading never stalls.

use crate::error::Result;
use crate::shaders::CountersHeader;
use crate::vk::recorder::Recorder;
use crate::vk::{Access, Buffer, Context, Tracker};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Bytes of the header before the work lists.
const HEADER_BYTES: u64 = CountersHeader::SIZE as u64;
/// Byte offset of the fix-up pass's indirect dispatch arguments.
pub const FIXUP_DISPATCH_OFFSET: u64 = CountersHeader::OFFSET_FIXUP_DISPATCH_X as u64;
/// Byte offset of the compacted low-resolution gather's indirect dispatch arguments.
pub const LOWRES_DISPATCH_OFFSET: u64 = CountersHeader::OFFSET_LOWRES_DISPATCH_X as u64;

/// An estimating pass whose work efficiency the header counts (`COUNT_WORK` in counters.glsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// The effect's main estimate over its list (the pixels whose value it computed).
    Gather,
    /// The full-resolution fix-up of discarded pixels.
    Fixup,
    /// The refresh tile.
    Refresh,
}

/// A header field an effect reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counter {
    /// Pixels that failed eq 3 or had no history.
    Disoccluded,
    /// Pixels the effect evaluated (low-resolution ones at half resolution).
    Computed,
    /// Full-resolution fix-ups.
    Fixup,
    /// Pattern evaluations spent on the refresh tile (each refreshed evaluation counts every
    /// pattern it averages).
    Refresh,
    /// Samples taken over the computed pixels (an effect with a per-pixel sample count).
    Samples,
    /// Pixels whose history held but lay within a moving object's reach (`--invalidate`).
    Invalidated,
    /// Low-resolution samples listed for the compacted half-resolution gather.
    LowresSamples,
    /// Lanes a pass launched (workgroups x local size; per round for a pass that strides).
    Invocations(Role),
    /// Launched lanes that evaluated an estimate or part of one.
    ActiveInvocations(Role),
    /// The most estimator evaluations (VPLs, taps, samples) one lane of the pass ran.
    SerialEvaluations(Role),
}

impl Counter {
    fn read(self, h: &CountersHeader) -> u32 {
        match self {
            Counter::Disoccluded => h.disoccluded_pixels,
            Counter::Computed => h.computed_pixels,
            Counter::Fixup => h.fixup_pixels,
            Counter::Refresh => h.refresh_evaluations,
            Counter::Samples => h.samples,
            Counter::Invalidated => h.invalidated_pixels,
            Counter::LowresSamples => h.lowres_samples,
            Counter::Invocations(r) => match r {
                Role::Gather => h.gather_invocations,
                Role::Fixup => h.fixup_invocations,
                Role::Refresh => h.refresh_invocations,
            },
            Counter::ActiveInvocations(r) => match r {
                Role::Gather => h.gather_active_invocations,
                Role::Fixup => h.fixup_active_invocations,
                Role::Refresh => h.refresh_active_invocations,
            },
            Counter::SerialEvaluations(r) => match r {
                Role::Gather => h.gather_serial_evaluations,
                Role::Fixup => h.fixup_serial_evaluations,
                Role::Refresh => h.refresh_serial_evaluations,
            },
        }
    }
}

/// A work list's indirect dispatch of `groups` workgroups as [x, y]: x at most `max_x` (the
/// device's maxComputeWorkGroupCount[0]), y growing beyond it; the reprojection's
/// LIST_DISPATCH (shaders/reproject.comp) computes the same from the list's running count,
/// and consumers skip the x * y - groups groups past the list (counters.glsl's
/// listed_group).
pub fn list_dispatch(groups: u32, max_x: u32) -> [u32; 2] {
    let most = max_x.max(1);
    [groups.min(most), groups.div_ceil(most)]
}

/// Refuses a work list of `groups` workgroups (at most) whose dispatch would pass the device's
/// maxComputeWorkGroupCount in y (`list_dispatch`): at MAX_SIZE the longest list, one 8x8
/// block or 64 pixels per group, needs 64 rows of 65,535, so only a device below Vulkan's
/// minimum limits could refuse.
pub fn check_list_dispatch(ctx: &Context, name: &str, groups: u32) -> Result<()> {
    let [x, y, _] = ctx.info.max_compute_work_group_count;
    let [_, rows] = list_dispatch(groups, x);
    if rows > y {
        return Err(crate::error::Error::Config(format!(
            "{name}'s work list needs up to {groups} workgroups, {rows} rows of {x}: past \
             this device's maxComputeWorkGroupCount ({x}, {y}); render smaller"
        )));
    }
    Ok(())
}

/// The device-side buffer: header, one entry per work block, then `lists` more entries (the
/// half-resolution indirect light's fix-up pixels and low-resolution samples).
pub fn create_gpu_buffer(
    ctx: &Arc<Context>,
    name: &str,
    max_blocks: u32,
    lists: u64,
) -> Result<Buffer> {
    Buffer::new(
        ctx,
        name,
        HEADER_BYTES + (max_blocks as u64 + lists) * 4,
        vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::INDIRECT_BUFFER
            | vk::BufferUsageFlags::TRANSFER_DST
            | vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::GpuOnly,
    )
}

/// Zero the counters, set the indirect dispatches to (0, 1, 1) and record the block-list size
/// and where the low-resolution sample list starts in `data`.
pub fn record_reset(
    rec: &Recorder<'_>,
    tracker: &mut Tracker,
    gpu: &Buffer,
    max_blocks: u32,
    lowres_list: u32,
) {
    tracker.buffer(gpu, Access::TransferDst);
    tracker.flush(rec.device, rec.cmd);
    let header = CountersHeader {
        dispatch_x: 0,
        dispatch_y: 1,
        dispatch_z: 1,
        listed_pixels: 0,
        listed_blocks: 0,
        disoccluded_pixels: 0,
        computed_pixels: 0,
        fixup_pixels: 0,
        max_blocks,
        fixup_dispatch_x: 0,
        fixup_dispatch_y: 1,
        fixup_dispatch_z: 1,
        refresh_evaluations: 0,
        samples: 0,
        invalidated_pixels: 0,
        lowres_samples: 0,
        lowres_dispatch_x: 0,
        lowres_dispatch_y: 1,
        lowres_dispatch_z: 1,
        lowres_list,
        gather_invocations: 0,
        gather_active_invocations: 0,
        gather_serial_evaluations: 0,
        fixup_invocations: 0,
        fixup_active_invocations: 0,
        fixup_serial_evaluations: 0,
        refresh_invocations: 0,
        refresh_active_invocations: 0,
        refresh_serial_evaluations: 0,
    };
    rec.update_buffer(gpu, &header.to_bytes());
}

/// Host copies of a counters header, one per frame slot, and which fields each frame reports.
pub struct CounterReadback {
    buffers: Vec<Buffer>,
    pending: Vec<Option<&'static [(&'static str, Counter)]>>,
}

impl CounterReadback {
    pub fn new(ctx: &Arc<Context>, slots: usize) -> Result<Self> {
        let mut buffers = Vec::new();
        for _ in 0..slots {
            buffers.push(Buffer::new(
                ctx,
                "counters.readback",
                HEADER_BYTES,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )?);
        }
        Ok(Self {
            buffers,
            pending: vec![None; slots],
        })
    }

    /// Copy the header at the end of the frame recorded in `slot`; `fields` names the words to
    /// report.
    pub fn record_copy(
        &mut self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        gpu: &Buffer,
        slot: usize,
        fields: &'static [(&'static str, Counter)],
    ) {
        let host = &self.buffers[slot];
        tracker.buffer(gpu, Access::TransferSrc);
        tracker.buffer(host, Access::TransferDst);
        tracker.flush(rec.device, rec.cmd);
        rec.copy_buffer(gpu, host, HEADER_BYTES);
        tracker.buffer(host, Access::HostRead);
        tracker.flush(rec.device, rec.cmd);
        self.pending[slot] = Some(fields);
    }

    /// The counters of the frame last recorded in `slot` (its fence must have signalled).
    pub fn collect(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        let Some(fields) = self.pending[slot].take() else {
            return Vec::new();
        };
        let Some(header) = self.buffers[slot]
            .mapped()
            .and_then(|b| b.get(..CountersHeader::SIZE))
            .and_then(|b| b.try_into().ok())
            .map(CountersHeader::from_bytes)
        else {
            return Vec::new();
        };
        fields
            .iter()
            .map(|&(name, c)| (name, c.read(&header) as u64))
            .collect()
    }
}

/// The counters of an effect without the temporal machinery (a header, no work lists): its
/// device buffer, bound as the effect's own, with the readback and the fields it reports.
pub struct OwnCounters {
    pub gpu: Buffer,
    readback: CounterReadback,
    fields: &'static [(&'static str, Counter)],
}

impl OwnCounters {
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        fields: &'static [(&'static str, Counter)],
    ) -> Result<Self> {
        Ok(Self {
            gpu: create_gpu_buffer(ctx, name, 0, 0)?,
            readback: CounterReadback::new(ctx, crate::config::FRAMES_IN_FLIGHT)?,
            fields,
        })
    }

    /// Zero them before the frame's passes count.
    pub fn reset(&self, rec: &Recorder<'_>, tracker: &mut Tracker) {
        record_reset(rec, tracker, &self.gpu, 0, 0);
    }

    /// Copy them at the end of the frame recorded in `slot`.
    pub fn copy(&mut self, rec: &Recorder<'_>, tracker: &mut Tracker, slot: usize) {
        self.readback
            .record_copy(rec, tracker, &self.gpu, slot, self.fields);
    }

    /// Those of the frame last recorded in `slot` (its fence has signalled).
    pub fn collect(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        self.readback.collect(slot)
    }
}

#[cfg(test)]
mod tests {
    use super::list_dispatch;
    use crate::config::MAX_SIZE;

    /// Vulkan's least maxComputeWorkGroupCount, per dimension.
    const SPEC_MIN: u32 = 65_535;

    /// Every render size up to MAX_SIZE (in steps, and the sizes at the limits' edges), every
    /// list shape (16x16 and 8x8 blocks, 64-pixel groups): the dispatch stays within the
    /// spec's least limits in x and y and covers the list with less than one row to spare.
    #[test]
    fn list_dispatches_fit_the_least_limits_up_to_max_size() {
        let mut sides: Vec<u32> = (1..=MAX_SIZE).step_by(97).collect();
        sides.extend([4095, 4096, 4097, 8191, 8192, 16383, MAX_SIZE]);
        let mut past_x = 0;
        for &w in &sides {
            for &h in &[1, 7, 1080, 4320, 8191, MAX_SIZE] {
                let lists = [
                    w.div_ceil(16) * h.div_ceil(16),
                    w.div_ceil(16) * h.div_ceil(16) * 4,
                    (w * h).div_ceil(64),
                ];
                for groups in lists {
                    let [x, y] = list_dispatch(groups, SPEC_MIN);
                    assert!(
                        x <= SPEC_MIN && y <= SPEC_MIN,
                        "{w}x{h}: {groups} -> {x}x{y}"
                    );
                    let launched = x as u64 * y as u64;
                    assert!(launched >= groups as u64, "{w}x{h}: {x}x{y} < {groups}");
                    assert!(
                        launched - (groups as u64) < x as u64,
                        "{w}x{h}: a spare row"
                    );
                    past_x += (groups > SPEC_MIN) as u32;
                }
            }
        }
        assert!(past_x > 0, "some lists pass the limit in x");
        // --aa ssaa16 at 1920x1080 renders 7680x4320: 129,600 16x16 blocks.
        assert_eq!(list_dispatch(480 * 270, SPEC_MIN), [SPEC_MIN, 2]);
        assert_eq!(list_dispatch(0, SPEC_MIN), [0, 0]);
        assert_eq!(list_dispatch(10, 3), [3, 4]);
    }
}
