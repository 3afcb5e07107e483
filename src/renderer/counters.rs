//! GPU counters (mirrors shaders/include/counters.glsl): written by atomics during the frame,
//! copied to a per-slot host buffer at its end and read when the slot comes round again, like
//! the timestamps, so reading never stalls.

use crate::error::Result;
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Buffer, Context, Tracker};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Header words: indirect dispatch (x, y, z), then the counters, then padding to 8 words.
const HEADER_WORDS: usize = 8;
const DISOCCLUDED: usize = 3;
const SSAO_COMPUTED: usize = 4;

/// Names of the counters as they appear in reports.
pub const DISOCCLUDED_PIXELS: &str = "disoccluded_pixels";
pub const SSAO_COMPUTED_PIXELS: &str = "ssao_computed_pixels";

/// The device-side buffer: header plus one work-list entry per 8x8 block.
pub fn create_gpu_buffer(ctx: &Arc<Context>, width: u32, height: u32) -> Result<Buffer> {
    let blocks = width.div_ceil(8) as u64 * height.div_ceil(8) as u64;
    Buffer::new(
        ctx,
        "counters",
        (HEADER_WORDS as u64 + blocks) * 4,
        vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::INDIRECT_BUFFER
            | vk::BufferUsageFlags::TRANSFER_DST
            | vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::GpuOnly,
    )
}

/// Zero the counters and set the indirect dispatch to (0, 1, 1).
pub fn record_reset(rec: &Recorder<'_>, tracker: &mut Tracker, gpu: &Buffer) {
    tracker.buffer(gpu, Access::TransferDst);
    tracker.flush(rec.device, rec.cmd);
    let mut header = [0u32; HEADER_WORDS];
    header[1] = 1;
    header[2] = 1;
    let bytes: Vec<u8> = header.iter().flat_map(|w| w.to_le_bytes()).collect();
    rec.update_buffer(gpu, &bytes);
}

/// Host copies of the header, one per frame slot, and which counters each frame filled.
pub struct CounterReadback {
    buffers: Vec<Buffer>,
    pending: Vec<Option<Vec<&'static str>>>,
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

    /// Copy the header at the end of the frame recorded in `slot`.
    pub fn record_copy(
        &mut self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        gpu: &Buffer,
        slot: usize,
        active: Vec<&'static str>,
    ) {
        let host = &self.buffers[slot];
        tracker.buffer(gpu, Access::TransferSrc);
        tracker.buffer(host, Access::TransferDst);
        tracker.flush(rec.device, rec.cmd);
        rec.copy_buffer(gpu, host, (HEADER_WORDS * 4) as u64);
        tracker.buffer(host, Access::HostRead);
        tracker.flush(rec.device, rec.cmd);
        self.pending[slot] = Some(active);
    }

    /// The counters of the frame last recorded in `slot` (its fence must have signalled).
    pub fn collect(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        let Some(active) = self.pending[slot].take() else {
            return Vec::new();
        };
        let Some(bytes) = self.buffers[slot].mapped() else {
            return Vec::new();
        };
        let word = |i: usize| {
            u32::from_le_bytes([
                bytes[4 * i],
                bytes[4 * i + 1],
                bytes[4 * i + 2],
                bytes[4 * i + 3],
            ]) as u64
        };
        active
            .into_iter()
            .map(|name| {
                let index = if name == DISOCCLUDED_PIXELS {
                    DISOCCLUDED
                } else {
                    SSAO_COMPUTED
                };
                (name, word(index))
            })
            .collect()
    }
}
