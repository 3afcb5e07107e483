//! Reverse reprojection (Lin 2013 eqs 1-3), one dispatch per temporal effect: per-pixel state,
//! history resampling, the disocclusion count and the effect's list of blocks needing work.

use super::compute::ComputePass;
use super::{binding, PassId, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::effect::TemporalEffect;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, DescriptorPool, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

const BINDINGS: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // prev_position
    binding(1, 3, DescriptorKind::SampledImage), // history_prev
    binding(1, 4, DescriptorKind::StorageImage), // history_cur
    binding(1, 5, DescriptorKind::StorageImage), // state_out
    binding(1, 6, DescriptorKind::StorageBuffer), // counters
];

pub fn layout() -> PassLayout {
    PassLayout {
        pass: PassId::Reproject,
        modules: vec![&shaders::REPROJECT_COMP],
        declared: BINDINGS.to_vec(),
    }
}

pub struct ReprojectPass {
    pass: ComputePass,
}

impl ReprojectPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pass = ComputePass::new(
            ctx,
            pool,
            PassId::Reproject,
            &shaders::REPROJECT_COMP,
            BINDINGS,
        )?;
        Ok(Self { pass })
    }

    /// Descriptor sets for one more effect (one per parity).
    pub fn allocate_sets(
        &self,
        pool: &DescriptorPool,
        effect: &str,
    ) -> Result<[vk::DescriptorSet; 2]> {
        self.pass
            .allocate_sets(pool, &format!("reproject {effect} set 1"))
    }

    pub fn bind_targets(&self, ctx: &Context, t: &Targets, effect: &TemporalEffect) {
        for parity in 0..2 {
            let prev = 1 - parity;
            SetWriter::new()
                .sampled(0, &t.gbuffer.position[parity])
                .sampled(1, &t.gbuffer.normal)
                .sampled(2, &t.gbuffer.position[prev])
                .sampled(3, &effect.history[prev])
                .storage(4, &effect.history[parity])
                .storage(5, &effect.state)
                .storage_buffer(6, &effect.counters)
                .write(ctx, effect.reproject_sets[parity]);
        }
    }

    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        parity: usize,
        t: &Targets,
        effect: &TemporalEffect,
        push: &[u8],
    ) {
        let prev = 1 - parity;
        for input in [
            &t.gbuffer.position[parity],
            &t.gbuffer.normal,
            &t.gbuffer.position[prev],
            &effect.history[prev],
        ] {
            tracker.image(input, Access::ComputeSampledRead);
        }
        for output in [&effect.history[parity], &effect.state] {
            tracker.image(output, Access::Undefined);
            tracker.image(output, Access::ComputeStorageWrite);
        }
        tracker.buffer(&effect.counters, Access::ComputeStorageReadWrite);
        tracker.flush(rec.device, rec.cmd);
        rec.bind(
            &self.pass.pipeline,
            &[frame_set, effect.reproject_sets[parity]],
        );
        rec.push(&self.pass.pipeline, push);
        rec.dispatch_2d(&self.pass.pipeline, t.width, t.height);
    }
}
