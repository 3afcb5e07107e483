//! Per-effect GPU counters (mirrors shaders/include/counters.glsl): written by atomics during
//! the frame, the header copied to a per-slot host buffer at the frame's end and read when the
//! slot comes round again, like the timestamps, so reading never stalls.

use crate::error::Result;
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Buffer, Context, Tracker};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Header words before the work lists.
pub const HEADER_WORDS: usize = 16;
/// Word offsets of the header fields.
pub const DISOCCLUDED: usize = 3;
pub const COMPUTED: usize = 4;
pub const FIXUP: usize = 5;
/// Byte offset of the fix-up pass's indirect dispatch arguments.
pub const FIXUP_DISPATCH_OFFSET: u64 = 8 * 4;

/// The device-side buffer: header, one entry per work block, then (when `fixups`) one entry
/// per pixel for the fix-up list.
pub fn create_gpu_buffer(
    ctx: &Arc<Context>,
    name: &str,
    max_blocks: u32,
    fixups: u32,
) -> Result<Buffer> {
    Buffer::new(
        ctx,
        name,
        (HEADER_WORDS as u64 + max_blocks as u64 + fixups as u64) * 4,
        vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::INDIRECT_BUFFER
            | vk::BufferUsageFlags::TRANSFER_DST
            | vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::GpuOnly,
    )
}

/// Zero the counters, set both indirect dispatches to (0, 1, 1) and record the block-list size.
pub fn record_reset(rec: &Recorder<'_>, tracker: &mut Tracker, gpu: &Buffer, max_blocks: u32) {
    tracker.buffer(gpu, Access::TransferDst);
    tracker.flush(rec.device, rec.cmd);
    let mut header = [0u32; HEADER_WORDS];
    header[1] = 1;
    header[2] = 1;
    header[6] = max_blocks;
    header[9] = 1;
    header[10] = 1;
    let bytes: Vec<u8> = header.iter().flat_map(|w| w.to_le_bytes()).collect();
    rec.update_buffer(gpu, &bytes);
}

/// Host copies of a counters header, one per frame slot, and which fields each frame reports.
pub struct CounterReadback {
    buffers: Vec<Buffer>,
    pending: Vec<Option<&'static [(&'static str, usize)]>>,
}

impl CounterReadback {
    pub fn new(ctx: &Arc<Context>, slots: usize) -> Result<Self> {
        let mut buffers = Vec::new();
        for _ in 0..slots {
            buffers.push(Buffer::new(
                ctx,
                "counters.readback",
                (HEADER_WORDS * 4) as u64,
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
        fields: &'static [(&'static str, usize)],
    ) {
        let host = &self.buffers[slot];
        tracker.buffer(gpu, Access::TransferSrc);
        tracker.buffer(host, Access::TransferDst);
        tracker.flush(rec.device, rec.cmd);
        rec.copy_buffer(gpu, host, (HEADER_WORDS * 4) as u64);
        tracker.buffer(host, Access::HostRead);
        tracker.flush(rec.device, rec.cmd);
        self.pending[slot] = Some(fields);
    }

    /// The counters of the frame last recorded in `slot` (its fence must have signalled).
    pub fn collect(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        let Some(fields) = self.pending[slot].take() else {
            return Vec::new();
        };
        let Some(bytes) = self.buffers[slot].mapped() else {
            return Vec::new();
        };
        fields
            .iter()
            .map(|&(name, i)| {
                let w = [
                    bytes[4 * i],
                    bytes[4 * i + 1],
                    bytes[4 * i + 2],
                    bytes[4 * i + 3],
                ];
                (name, u32::from_le_bytes(w) as u64)
            })
            .collect()
    }
}
