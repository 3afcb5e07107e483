//! Direct light: spot light irradiance with PCF shadows from the light view's depth.
//! Output: rgb = outgoing diffuse radiance albedo/pi * E * V, a = PCF visibility V.

use super::compute::ComputePass;
use super::{binding, PassLayout, FRAME_BINDING};
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
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // g_albedo
    binding(1, 3, DescriptorKind::SampledImage), // shadow_depth
    binding(1, 4, DescriptorKind::StorageImage), // direct_out
];

pub fn layout() -> PassLayout {
    PassLayout {
        pass: "direct",
        modules: vec![&shaders::DIRECT_COMP],
        declared: BINDINGS,
    }
}

pub struct DirectPass {
    pass: ComputePass,
}

impl DirectPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pass = ComputePass::new(ctx, pool, "direct", &shaders::DIRECT_COMP, BINDINGS)?;
        Ok(Self { pass })
    }

    /// (Re)point the descriptors at the current targets.
    pub fn bind_targets(&self, ctx: &Context, t: &Targets) {
        for parity in 0..2 {
            let writer = SetWriter::new()
                .sampled(0, &t.gbuffer.position[parity])
                .sampled(1, &t.gbuffer.normal)
                .sampled(2, &t.gbuffer.albedo)
                .sampled(3, &t.rsm.depth)
                .storage(4, &t.direct);
            self.pass.write(ctx, parity, writer);
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
        let g = &t.gbuffer;
        for input in [&g.position[parity], &g.normal, &g.albedo, &t.rsm.depth] {
            tracker.image(input, Access::ComputeSampledRead);
        }
        tracker.image(&t.direct, Access::Undefined);
        tracker.image(&t.direct, Access::ComputeStorageWrite);
        tracker.flush(rec.device, rec.cmd);
        self.pass
            .dispatch(rec, frame_set, parity, t.width, t.height);
    }
}
