//! Direct light: spot light irradiance with PCF shadows from the light view's depth.
//! Output: rgb = outgoing diffuse radiance albedo/pi * E * V, a = PCF visibility V.

use super::compute::ComputePass;
use super::{binding, PassId, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, DescriptorPool, Image, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

const BINDINGS: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage), // g_position
    binding(1, 1, DescriptorKind::SampledImage), // g_normal
    binding(1, 2, DescriptorKind::SampledImage), // g_albedo
    binding(1, 3, DescriptorKind::SampledImage), // shadow_visibility
    binding(1, 4, DescriptorKind::StorageImage), // direct_out
];

pub fn layout() -> PassLayout {
    PassLayout {
        pass: PassId::Direct,
        modules: vec![&shaders::DIRECT_COMP],
        declared: BINDINGS.to_vec(),
    }
}

pub struct DirectPass {
    pass: ComputePass,
    /// Sets reading the accumulated shadow history instead of the every-frame visibility.
    history_sets: [vk::DescriptorSet; 2],
}

impl DirectPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pass = ComputePass::new(ctx, pool, PassId::Direct, &shaders::DIRECT_COMP, BINDINGS)?;
        let history_sets = pass.allocate_sets(pool, "direct shadow-history set 1")?;
        Ok(Self { pass, history_sets })
    }

    /// (Re)point the descriptors at the current targets: the every-frame shadow visibility,
    /// and (with shadow reuse) the shadow history of each parity.
    pub fn bind_targets(&self, ctx: &Context, t: &Targets, history: Option<[&Image; 2]>) {
        for parity in 0..2 {
            let writer = |shadow: &Image| {
                SetWriter::new()
                    .sampled(0, &t.gbuffer.position[parity])
                    .sampled(1, &t.gbuffer.normal)
                    .sampled(2, &t.gbuffer.albedo)
                    .sampled(3, shadow)
                    .storage(4, &t.direct)
            };
            self.pass.write(ctx, parity, writer(&t.shadow));
            if let Some(h) = history {
                writer(h[parity]).write(ctx, self.history_sets[parity]);
            }
        }
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        parity: usize,
        t: &Targets,
        shadow: &Image,
    ) {
        let g = &t.gbuffer;
        for input in [&g.position[parity], &g.normal, &g.albedo, shadow] {
            tracker.image(input, Access::ComputeSampledRead);
        }
        tracker.image(&t.direct, Access::Undefined);
        tracker.image(&t.direct, Access::ComputeStorageWrite);
        tracker.flush(rec.device, rec.cmd);
        if std::ptr::eq(shadow, &t.shadow) {
            self.pass
                .dispatch(rec, frame_set, parity, t.width, t.height);
        } else {
            rec.bind(&self.pass.pipeline, &[frame_set, self.history_sets[parity]]);
            rec.dispatch_2d(&self.pass.pipeline, t.width, t.height);
        }
    }
}
