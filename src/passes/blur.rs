//! 5x5 Gaussian blur of the AO: the thesis's no-reuse baseline.

use super::compute::ComputePass;
use super::{binding, PassId, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, DescriptorPool, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

const BINDINGS: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // ao_in
    binding(1, 2, DescriptorKind::StorageImage), // ao_out
];

pub fn layout() -> PassLayout {
    PassLayout {
        pass: PassId::Blur,
        modules: vec![&shaders::BLUR_COMP],
        declared: BINDINGS.to_vec(),
    }
}

pub struct BlurPass {
    pass: ComputePass,
}

impl BlurPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pass = ComputePass::new(ctx, pool, PassId::Blur, &shaders::BLUR_COMP, BINDINGS)?;
        Ok(Self { pass })
    }

    pub fn bind_targets(&self, ctx: &Context, t: &Targets) {
        for parity in 0..2 {
            let w = SetWriter::new()
                .sampled(0, &t.gbuffer.position[parity])
                .sampled(1, &t.ao_raw)
                .storage(2, &t.ao_blurred);
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
    ) {
        tracker.image(&t.gbuffer.position[parity], Access::ComputeSampledRead);
        tracker.image(&t.ao_raw, Access::ComputeSampledRead);
        tracker.image(&t.ao_blurred, Access::Undefined);
        tracker.image(&t.ao_blurred, Access::ComputeStorageWrite);
        tracker.flush(rec.device, rec.cmd);
        self.pass
            .dispatch(rec, frame_set, parity, t.width, t.height);
    }
}
