//! Reverse reprojection (Lin 2013 eqs 1-3): per-pixel state, AO history resampling, the
//! disocclusion count and the list of 8x8 blocks that need SSAO work.

use super::compute::ComputePass;
use super::{binding, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Buffer, Context, DescriptorPool, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

const BINDINGS: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // prev_position
    binding(1, 3, DescriptorKind::SampledImage), // ao_prev
    binding(1, 4, DescriptorKind::StorageImage), // ao_cur
    binding(1, 5, DescriptorKind::StorageImage), // state_out
    binding(1, 6, DescriptorKind::StorageBuffer), // counters
];

pub fn layout() -> PassLayout {
    PassLayout {
        pass: "reproject",
        modules: vec![&shaders::REPROJECT_COMP],
        declared: BINDINGS,
    }
}

pub struct ReprojectPass {
    pass: ComputePass,
}

impl ReprojectPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pass = ComputePass::new(ctx, pool, "reproject", &shaders::REPROJECT_COMP, BINDINGS)?;
        Ok(Self { pass })
    }

    pub fn bind_targets(&self, ctx: &Context, t: &Targets, counters: &Buffer) {
        for parity in 0..2 {
            let prev = 1 - parity;
            let w = SetWriter::new()
                .sampled(0, &t.gbuffer.position[parity])
                .sampled(1, &t.gbuffer.normal)
                .sampled(2, &t.gbuffer.position[prev])
                .sampled(3, &t.ao_history[prev])
                .storage(4, &t.ao_history[parity])
                .storage(5, &t.state)
                .storage_buffer(6, counters);
            self.pass.write(ctx, parity, w);
        }
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        parity: usize,
        t: &Targets,
        counters: &Buffer,
    ) {
        let prev = 1 - parity;
        for input in [
            &t.gbuffer.position[parity],
            &t.gbuffer.normal,
            &t.gbuffer.position[prev],
            &t.ao_history[prev],
        ] {
            tracker.image(input, Access::ComputeSampledRead);
        }
        tracker.image(&t.ao_history[parity], Access::Undefined);
        tracker.image(&t.ao_history[parity], Access::ComputeStorageWrite);
        tracker.image(&t.state, Access::Undefined);
        tracker.image(&t.state, Access::ComputeStorageWrite);
        tracker.buffer(counters, Access::ComputeStorageReadWrite);
        tracker.flush(rec.device, rec.cmd);
        self.pass
            .dispatch(rec, frame_set, parity, t.width, t.height);
    }
}
