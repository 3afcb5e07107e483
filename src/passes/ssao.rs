//! SSAO. With reuse: an indirect dispatch over the blocks the reprojection listed, one rotated
//! pattern per pixel merged into the AO history (eqs 4-5), refresh tiles recomputed in full.
//! Without reuse: every pixel with a fixed pattern (or many patterns, for references).

use super::compute::ComputePass;
use super::{binding, PassId, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::effect::TemporalEffect;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, DescriptorPool, Image, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

const ACCUMULATE: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // random_vectors
    binding(1, 3, DescriptorKind::StorageImage), // state_in
    binding(1, 4, DescriptorKind::StorageImage), // history
    binding(1, 5, DescriptorKind::StorageBuffer), // counters
];

const FULL: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // random_vectors
    binding(1, 3, DescriptorKind::StorageImage), // ao_out
    binding(1, 4, DescriptorKind::StorageBuffer), // counters
];

pub fn layouts() -> Vec<PassLayout> {
    vec![
        PassLayout {
            pass: PassId::Ssao,
            modules: vec![&shaders::SSAO_ACCUMULATE_COMP],
            declared: ACCUMULATE.to_vec(),
        },
        PassLayout {
            pass: PassId::Ssao,
            modules: vec![&shaders::SSAO_FULL_COMP],
            declared: FULL.to_vec(),
        },
    ]
}

pub struct SsaoPass {
    pass: ComputePass,
    reuse: bool,
}

impl SsaoPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool, reuse: bool) -> Result<Self> {
        let pass = if reuse {
            ComputePass::new(
                ctx,
                pool,
                PassId::Ssao,
                &shaders::SSAO_ACCUMULATE_COMP,
                ACCUMULATE,
            )?
        } else {
            ComputePass::new(ctx, pool, PassId::Ssao, &shaders::SSAO_FULL_COMP, FULL)?
        };
        Ok(Self { pass, reuse })
    }

    pub fn bind_targets(
        &self,
        ctx: &Context,
        t: &Targets,
        random: &Image,
        effect: &TemporalEffect,
    ) {
        for parity in 0..2 {
            let w = SetWriter::new()
                .sampled(0, &t.gbuffer.position[parity])
                .sampled(1, &t.gbuffer.normal)
                .sampled(2, random);
            let w = if self.reuse {
                w.storage(3, &effect.state)
                    .storage(4, &effect.history[parity])
                    .storage_buffer(5, &effect.counters)
            } else {
                w.storage(3, &t.ao_raw).storage_buffer(4, &effect.counters)
            };
            self.pass.write(ctx, parity, w);
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
        random: &Image,
        effect: &TemporalEffect,
        push: &[u8],
    ) {
        tracker.image(&t.gbuffer.position[parity], Access::ComputeSampledRead);
        tracker.image(&t.gbuffer.normal, Access::ComputeSampledRead);
        tracker.image(random, Access::ComputeSampledRead);
        if self.reuse {
            tracker.image(&effect.state, Access::ComputeStorageRead);
            tracker.image(&effect.history[parity], Access::ComputeStorageReadWrite);
            tracker.buffer(&effect.counters, Access::IndirectCommandRead);
            tracker.buffer(&effect.counters, Access::ComputeStorageReadWrite);
            tracker.flush(rec.device, rec.cmd);
            self.pass
                .dispatch_indirect(rec, frame_set, parity, &effect.counters, 0, push);
        } else {
            tracker.image(&t.ao_raw, Access::Undefined);
            tracker.image(&t.ao_raw, Access::ComputeStorageWrite);
            tracker.buffer(&effect.counters, Access::ComputeStorageReadWrite);
            tracker.flush(rec.device, rec.cmd);
            self.pass
                .dispatch(rec, frame_set, parity, t.width, t.height);
        }
    }
}
