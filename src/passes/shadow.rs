//! Shadow visibility by percentage-closer filtering. Every frame over all pixels for the grid
//! kernels (hard, 49 samples) and for disc kernels without reuse; with reuse, the thesis's
//! 9-sample disc rotated and scaled per frame and accumulated over the blocks that need work.

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

const FULL: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // shadow_depth
    binding(1, 3, DescriptorKind::StorageImage), // visibility_out
];

const ACCUMULATE: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // shadow_depth
    binding(1, 3, DescriptorKind::StorageImage), // state_in
    binding(1, 4, DescriptorKind::StorageImage), // history
    binding(1, 5, DescriptorKind::StorageBuffer), // counters
];

pub fn layouts() -> Vec<PassLayout> {
    vec![
        PassLayout {
            pass: PassId::Shadow,
            modules: vec![&shaders::SHADOW_FULL_COMP],
            declared: FULL.to_vec(),
        },
        PassLayout {
            pass: PassId::Shadow,
            modules: vec![&shaders::SHADOW_ACCUMULATE_COMP],
            declared: ACCUMULATE.to_vec(),
        },
    ]
}

pub struct ShadowPass {
    pass: ComputePass,
    /// Accumulating over the shadow effect's work list (else every pixel every frame).
    pub reuse: bool,
}

impl ShadowPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool, reuse: bool) -> Result<Self> {
        let pass = if reuse {
            ComputePass::new(
                ctx,
                pool,
                PassId::Shadow,
                &shaders::SHADOW_ACCUMULATE_COMP,
                ACCUMULATE,
            )?
        } else {
            ComputePass::new(ctx, pool, PassId::Shadow, &shaders::SHADOW_FULL_COMP, FULL)?
        };
        Ok(Self { pass, reuse })
    }

    pub fn bind_targets(&self, ctx: &Context, t: &Targets, effect: Option<&TemporalEffect>) {
        for parity in 0..2 {
            let w = SetWriter::new()
                .sampled(0, &t.gbuffer.position[parity])
                .sampled(1, &t.gbuffer.normal)
                .sampled(2, &t.rsm.depth);
            let w = match (self.reuse, effect) {
                (true, Some(e)) => w
                    .storage(3, &e.state)
                    .storage(4, &e.history[parity])
                    .storage_buffer(5, &e.counters),
                _ => w.storage(3, &t.shadow),
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
        effect: Option<&TemporalEffect>,
        push: &[u8],
    ) {
        tracker.image(&t.gbuffer.position[parity], Access::ComputeSampledRead);
        tracker.image(&t.gbuffer.normal, Access::ComputeSampledRead);
        tracker.image(&t.rsm.depth, Access::ComputeSampledRead);
        match (self.reuse, effect) {
            (true, Some(e)) => {
                tracker.image(&e.state, Access::ComputeStorageRead);
                tracker.image(&e.history[parity], Access::ComputeStorageReadWrite);
                tracker.buffer(&e.counters, Access::IndirectCommandRead);
                tracker.buffer(&e.counters, Access::ComputeStorageReadWrite);
                tracker.flush(rec.device, rec.cmd);
                self.pass
                    .dispatch_indirect(rec, frame_set, parity, &e.counters, 0, push);
            }
            _ => {
                tracker.image(&t.shadow, Access::Undefined);
                tracker.image(&t.shadow, Access::ComputeStorageWrite);
                tracker.flush(rec.device, rec.cmd);
                self.pass
                    .dispatch(rec, frame_set, parity, t.width, t.height);
            }
        }
    }
}
