//! Direct light: spot light irradiance with PCF shadows from the light view's depth.
//! Output: rgb = outgoing diffuse radiance albedo/pi * E * V, a = PCF visibility V.

use super::{binding, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, DescriptorPool, Pipeline, SetWriter, Tracker};
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
    pipeline: Pipeline,
    set: vk::DescriptorSet,
}

impl DirectPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pipeline = Pipeline::compute(ctx, "direct", &shaders::DIRECT_COMP, BINDINGS)?;
        let set = pool.allocate(pipeline.set_layouts[1])?;
        Ok(Self { pipeline, set })
    }

    /// (Re)point the descriptors at the current targets.
    pub fn bind_targets(&self, ctx: &Context, t: &Targets) {
        SetWriter::new()
            .sampled(0, &t.gbuffer.position)
            .sampled(1, &t.gbuffer.normal)
            .sampled(2, &t.gbuffer.albedo)
            .sampled(3, &t.rsm.depth)
            .storage(4, &t.direct)
            .write(ctx, self.set);
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        t: &Targets,
    ) {
        let g = &t.gbuffer;
        for input in [&g.position, &g.normal, &g.albedo, &t.rsm.depth] {
            tracker.image(input, Access::ComputeSampledRead);
        }
        tracker.image(&t.direct, Access::Undefined);
        tracker.image(&t.direct, Access::ComputeStorageWrite);
        tracker.flush(rec.device, rec.cmd);
        rec.bind(&self.pipeline, &[frame_set, self.set]);
        rec.dispatch_2d(&self.pipeline, t.width, t.height);
    }
}

impl DirectPass {
    /// Set 0 (frame constants) layout, shared by every pipeline.
    pub fn frame_layout(&self) -> vk::DescriptorSetLayout {
        self.pipeline.set_layouts[0]
    }
}
