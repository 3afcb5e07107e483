//! Composite: direct + ambient x albedo, Reinhard tonemap, sRGB encode into the RGBA8 output.

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
    binding(1, 1, DescriptorKind::SampledImage), // g_albedo
    binding(1, 2, DescriptorKind::SampledImage), // direct_light
    binding(1, 3, DescriptorKind::StorageImage), // out_color
];

pub fn layout() -> PassLayout {
    PassLayout {
        pass: "composite",
        modules: vec![&shaders::COMPOSITE_COMP],
        declared: BINDINGS,
    }
}

pub struct CompositePass {
    pipeline: Pipeline,
    set: vk::DescriptorSet,
}

impl CompositePass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pipeline = Pipeline::compute(ctx, "composite", &shaders::COMPOSITE_COMP, BINDINGS)?;
        let set = pool.allocate(pipeline.set_layouts[1])?;
        Ok(Self { pipeline, set })
    }

    pub fn bind_targets(&self, ctx: &Context, t: &Targets) {
        SetWriter::new()
            .sampled(0, &t.gbuffer.position)
            .sampled(1, &t.gbuffer.albedo)
            .sampled(2, &t.direct)
            .storage(3, &t.output)
            .write(ctx, self.set);
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        t: &Targets,
    ) {
        for input in [&t.gbuffer.position, &t.gbuffer.albedo, &t.direct] {
            tracker.image(input, Access::ComputeSampledRead);
        }
        tracker.image(&t.output, Access::Undefined);
        tracker.image(&t.output, Access::ComputeStorageWrite);
        tracker.flush(rec.device, rec.cmd);
        rec.bind(&self.pipeline, &[frame_set, self.set]);
        rec.dispatch_2d(&self.pipeline, t.width, t.height);
    }
}
