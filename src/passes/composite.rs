//! Composite: direct + ambient x albedo x AO visibility, Reinhard tonemap, sRGB encode into the
//! RGBA8 output. One permutation per effect combination, so disabled effects are not read.

use super::compute::ComputePass;
use super::{binding, PassId, PassLayout, FRAME_BINDING};
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
const INDIRECT: ReflectedBinding = binding(1, 5, DescriptorKind::SampledImage);

/// The permutation for an effect combination and the bindings it declares.
fn variant(effects: Effects) -> (&'static ShaderModuleInfo, Vec<ReflectedBinding>) {
    let module: &'static ShaderModuleInfo = match (effects.direct, effects.ao, effects.indirect) {
        (true, false, false) => &shaders::COMPOSITE_COMP_D,
        (false, true, false) => &shaders::COMPOSITE_COMP_A,
        (false, false, true) => &shaders::COMPOSITE_COMP_I,
        (true, true, false) => &shaders::COMPOSITE_COMP_DA,
        (true, false, true) => &shaders::COMPOSITE_COMP_DI,
        (false, true, true) => &shaders::COMPOSITE_COMP_AI,
        _ => &shaders::COMPOSITE_COMP_DAI,
    };
    let mut b = vec![FRAME_BINDING, G_POSITION, G_ALBEDO, OUT];
    if effects.direct {
        b.push(DIRECT);
    }
    if effects.ao {
        b.push(AO);
    }
    if effects.indirect {
        b.push(INDIRECT);
    }
    (module, b)
}

pub fn layouts() -> Vec<PassLayout> {
    (1..8u32)
        .map(|m| {
            let effects = Effects {
                direct: m & 1 != 0,
                ao: m & 2 != 0,
                indirect: m & 4 != 0,
            };
            let (module, declared) = variant(effects);
            PassLayout {
                pass: PassId::Composite,
                modules: vec![module],
                declared,
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
        let pass = ComputePass::new(ctx, pool, PassId::Composite, module, &declared)?;
        Ok(Self { pass, effects })
    }

    /// `ao[parity]` / `indirect[parity]`: what the composite of that parity reads.
    pub fn bind_targets(
        &self,
        ctx: &Context,
        t: &Targets,
        ao: Option<[&Image; 2]>,
        indirect: Option<[&Image; 2]>,
    ) {
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
            if let Some(indirect) = indirect {
                w = w.sampled(5, indirect[parity]);
            }
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
        ao: Option<&Image>,
        indirect: Option<&Image>,
    ) {
        tracker.image(&t.gbuffer.position[parity], Access::ComputeSampledRead);
        tracker.image(&t.gbuffer.albedo, Access::ComputeSampledRead);
        if self.effects.direct {
            tracker.image(&t.direct, Access::ComputeSampledRead);
        }
        for input in [ao, indirect].into_iter().flatten() {
            tracker.image(input, Access::ComputeSampledRead);
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
