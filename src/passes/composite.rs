//! Composite: direct + ambient x albedo x AO visibility, Reinhard tonemap, sRGB encode into the
//! RGBA8 output. One permutation per effect combination, so disabled effects are not read.

use super::compute::ComputePass;
use super::{binding, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::config::Effects;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding, ShaderModuleInfo};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, DescriptorPool, Image, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

const G_POSITION: ReflectedBinding = binding(1, 0, DescriptorKind::SampledImage);
const G_ALBEDO: ReflectedBinding = binding(1, 1, DescriptorKind::SampledImage);
const OUT: ReflectedBinding = binding(1, 2, DescriptorKind::StorageImage);
const DIRECT: ReflectedBinding = binding(1, 3, DescriptorKind::SampledImage);
const AO: ReflectedBinding = binding(1, 4, DescriptorKind::SampledImage);

const DIRECT_ONLY: &[ReflectedBinding] = &[FRAME_BINDING, G_POSITION, G_ALBEDO, OUT, DIRECT];
const AO_ONLY: &[ReflectedBinding] = &[FRAME_BINDING, G_POSITION, G_ALBEDO, OUT, AO];
const DIRECT_AO: &[ReflectedBinding] = &[FRAME_BINDING, G_POSITION, G_ALBEDO, OUT, DIRECT, AO];

fn variant(effects: Effects) -> (&'static ShaderModuleInfo, &'static [ReflectedBinding]) {
    match (effects.direct, effects.ao) {
        (true, false) => (&shaders::COMPOSITE_COMP_DIRECT, DIRECT_ONLY),
        (false, true) => (&shaders::COMPOSITE_COMP_AO, AO_ONLY),
        _ => (&shaders::COMPOSITE_COMP_DIRECT_AO, DIRECT_AO),
    }
}

pub fn layouts() -> Vec<PassLayout> {
    [(true, false), (false, true), (true, true)]
        .into_iter()
        .map(|(direct, ao)| {
            let (module, declared) = variant(Effects { direct, ao });
            PassLayout {
                pass: "composite",
                modules: vec![module],
                declared: declared.to_vec(),
            }
        })
        .collect()
}

pub struct CompositePass {
    pass: ComputePass,
    effects: Effects,
}

impl CompositePass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool, effects: Effects) -> Result<Self> {
        let (module, declared) = variant(effects);
        let pass = ComputePass::new(ctx, pool, "composite", module, declared)?;
        Ok(Self { pass, effects })
    }

    /// `ao[parity]`: the AO visibility the composite of that parity reads.
    pub fn bind_targets(&self, ctx: &Context, t: &Targets, ao: Option<[&Image; 2]>) {
        for parity in 0..2 {
            let mut w = SetWriter::new()
                .sampled(0, &t.gbuffer.position[parity])
                .sampled(1, &t.gbuffer.albedo)
                .storage(2, &t.output);
            if self.effects.direct {
                w = w.sampled(3, &t.direct);
            }
            if let Some(ao) = ao {
                w = w.sampled(4, ao[parity]);
            }
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
        ao: Option<&Image>,
    ) {
        tracker.image(&t.gbuffer.position[parity], Access::ComputeSampledRead);
        tracker.image(&t.gbuffer.albedo, Access::ComputeSampledRead);
        if self.effects.direct {
            tracker.image(&t.direct, Access::ComputeSampledRead);
        }
        if let Some(ao) = ao {
            tracker.image(ao, Access::ComputeSampledRead);
        }
        tracker.image(&t.output, Access::Undefined);
        tracker.image(&t.output, Access::ComputeStorageWrite);
        tracker.flush(rec.device, rec.cmd);
        self.pass
            .dispatch(rec, frame_set, parity, t.width, t.height);
    }
}

impl CompositePass {
    /// Set 0 (frame constants) layout; identical in every pipeline.
    pub fn frame_layout(&self) -> vk::DescriptorSetLayout {
        self.pass.pipeline.set_layouts[0]
    }
}
