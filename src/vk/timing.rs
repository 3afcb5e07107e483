//! GPU timer: a timestamp before and after each pass, one query pool per frame slot, results
//! read when the slot comes round again (its fence has signalled), so reading never stalls.

use super::context::{Context, Garbage};
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

/// Why a pass was not recorded in a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkipReason {
    /// None of its inputs changed since it last ran: its output is still valid.
    Unchanged,
    /// A temporal effect's pass whose pixels have all converged and whose inputs are unchanged.
    Converged,
}

impl SkipReason {
    pub fn name(self) -> &'static str {
        match self {
            SkipReason::Unchanged => "unchanged",
            SkipReason::Converged => "converged",
        }
    }
}

/// A pass a frame did not record, and why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Skipped {
    pub pass: &'static str,
    pub reason: SkipReason,
}

/// What one frame measured: every pass in recording order, with its GPU time in milliseconds
/// (`None` only if the driver had not written the query), and the passes it skipped.
#[derive(Clone, Debug, Default)]
pub struct FrameTiming {
    pub frame: u64,
    pub passes: Vec<(&'static str, Option<f64>)>,
    pub skipped: Vec<Skipped>,
    /// GPU counters of the frame (filled by the renderer, not the timer).
    pub counters: Vec<(&'static str, u64)>,
}

#[derive(Default)]
struct SlotState {
    frame: Option<u64>,
    passes: Vec<&'static str>,
    skipped: Vec<Skipped>,
}

pub struct GpuTimer {
    ctx: Arc<Context>,
    pools: Vec<vk::QueryPool>,
    slots: Vec<SlotState>,
    capacity: u32,
    /// Valid-bits mask and nanoseconds per tick, from the queue family and device limits.
    mask: u64,
    period_ns: f64,
}

impl GpuTimer {
    pub fn new(ctx: &Arc<Context>, slots: usize, max_passes: u32) -> Result<Self> {
        let capacity = max_passes * 2;
        let mut pools = Vec::new();
        for _ in 0..slots {
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::TIMESTAMP)
                .query_count(capacity);
            // SAFETY: valid create info; destroyed through the deletion queue.
            let pool =
                unsafe { ctx.device.create_query_pool(&info, None) }.vk("vkCreateQueryPool")?;
            // SAFETY: host query reset is enabled on the device; the pool is unused.
            unsafe { ctx.device.reset_query_pool(pool, 0, capacity) };
            pools.push(pool);
        }
        let bits = ctx.info.timestamp_valid_bits.min(64);
        Ok(Self {
            ctx: ctx.clone(),
            pools,
            slots: (0..slots).map(|_| SlotState::default()).collect(),
            capacity,
            mask: if bits >= 64 {
                u64::MAX
            } else {
                (1u64 << bits) - 1
            },
            period_ns: ctx.info.timestamp_period as f64,
        })
    }

    /// Call after slot `slot`'s fence signalled: returns what its previous frame measured and
    /// resets the slot for `frame`.
    pub fn begin_frame(&mut self, slot: usize, frame: u64) -> Option<FrameTiming> {
        let previous = self.collect(slot);
        // SAFETY: the slot's last submission completed (caller waited on its fence).
        unsafe {
            self.ctx
                .device
                .reset_query_pool(self.pools[slot], 0, self.capacity)
        };
        self.slots[slot] = SlotState {
            frame: Some(frame),
            ..Default::default()
        };
        previous
    }

    /// Results of the slot's recorded frame (its submission must have completed).
    pub fn collect(&mut self, slot: usize) -> Option<FrameTiming> {
        let state = &mut self.slots[slot];
        let frame = state.frame.take()?;
        let n = state.passes.len() * 2;
        let mut raw = vec![0u64; n];
        let ok = n == 0 || {
            // SAFETY: queries 0..n were written by the completed submission; no WAIT flag,
            // so this never blocks.
            unsafe {
                self.ctx.device.get_query_pool_results(
                    self.pools[slot],
                    0,
                    &mut raw,
                    vk::QueryResultFlags::TYPE_64,
                )
            }
        }
        .is_ok();
        let passes = state
            .passes
            .iter()
            .enumerate()
            .map(|(i, name)| {
                let begin = raw[2 * i] & self.mask;
                let end = raw[2 * i + 1] & self.mask;
                let ticks = end.wrapping_sub(begin) & self.mask;
                (*name, ok.then(|| ticks as f64 * self.period_ns / 1e6))
            })
            .collect();
        Some(FrameTiming {
            frame,
            passes,
            skipped: std::mem::take(&mut state.skipped),
            counters: Vec::new(),
        })
    }

    /// Timestamp before `pass`. Returns false when the pool is full (the pass then runs
    /// untimed; `max_passes` is sized for every pass, so this only guards programming errors).
    pub fn begin_pass(&mut self, cmd: vk::CommandBuffer, slot: usize, pass: &'static str) -> bool {
        let state = &mut self.slots[slot];
        let q = state.passes.len() as u32 * 2;
        if q + 2 > self.capacity {
            return false;
        }
        state.passes.push(pass);
        // SAFETY: recording `cmd`; query `q` was reset in `begin_frame`.
        unsafe {
            self.ctx.device.cmd_write_timestamp2(
                cmd,
                vk::PipelineStageFlags2::TOP_OF_PIPE,
                self.pools[slot],
                q,
            )
        };
        true
    }

    pub fn end_pass(&mut self, cmd: vk::CommandBuffer, slot: usize) {
        let q = self.slots[slot].passes.len() as u32 * 2 - 1;
        // SAFETY: recording `cmd`; query `q` was reset in `begin_frame`.
        unsafe {
            self.ctx.device.cmd_write_timestamp2(
                cmd,
                vk::PipelineStageFlags2::BOTTOM_OF_PIPE,
                self.pools[slot],
                q,
            )
        };
    }

    /// The passes recorded into `slot`'s frame so far, in order.
    pub fn recorded(&self, slot: usize) -> &[&'static str] {
        &self.slots[slot].passes
    }

    /// The frame `slot` holds (recorded and not yet collected).
    pub fn frame_of(&self, slot: usize) -> Option<u64> {
        self.slots[slot].frame
    }

    /// Whether `pass` is already noted as skipped in `slot`'s frame.
    pub fn is_skipped(&self, slot: usize, pass: &str) -> bool {
        self.slots[slot].skipped.iter().any(|s| s.pass == pass)
    }

    /// Note that `pass` was not recorded this frame, and why.
    pub fn skip(&mut self, slot: usize, pass: &'static str, reason: SkipReason) {
        self.slots[slot].skipped.push(Skipped { pass, reason });
    }
}

impl Drop for GpuTimer {
    fn drop(&mut self) {
        for pool in self.pools.drain(..) {
            self.ctx.defer(Garbage::QueryPool(pool));
        }
    }
}

impl FrameTiming {
    /// Whether the frame skipped `pass`.
    pub fn skipped(&self, pass: &str) -> bool {
        self.skipped.iter().any(|s| s.pass == pass)
    }
}
