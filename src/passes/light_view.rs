//! Light view: the reflective shadow map (world position, normal, reflected flux) and its
//! depth, which is also the shadow map. Rendered only when the light or geometry changed.

use super::layout::PassLayout;
use super::pass_id::PassId;
use super::raster::{MaterialPipelines, RasterModules, FLAT_BINDINGS, TEXTURED_BINDINGS};
use crate::error::Result;
use crate::renderer::scene_gpu::SceneGpu;
use crate::renderer::targets::{Rsm, DEPTH_FORMAT, RSM_COLOR_FORMATS};
use crate::shaders;
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, Tracker};
use ash::vk;
use std::sync::Arc;

const MODULES: RasterModules = RasterModules {
    vertex: &shaders::MESH_VERT_LIGHT,
    flat: &shaders::RSM_FRAG_FLAT,
    textured: &shaders::RSM_FRAG_TEXTURED,
};

pub fn layouts() -> Vec<PassLayout> {
    vec![
        PassLayout {
            pass: PassId::LightView,
            modules: vec![MODULES.vertex, MODULES.flat],
            declared: FLAT_BINDINGS.to_vec(),
        },
        PassLayout {
            pass: PassId::LightView,
            modules: vec![MODULES.vertex, MODULES.textured],
            declared: TEXTURED_BINDINGS.to_vec(),
        },
    ]
}

pub struct LightViewPass {
    pipelines: MaterialPipelines,
}

impl LightViewPass {
    pub fn new(ctx: &Arc<Context>, textured: bool) -> Result<Self> {
        let pipelines = MaterialPipelines::new(
            ctx,
            PassId::LightView,
            &MODULES,
            &RSM_COLOR_FORMATS,
            DEPTH_FORMAT,
            textured,
        )?;
        Ok(Self { pipelines })
    }

    /// The set-1 layout of the textured permutation (material sets are allocated with it).
    pub fn material_layout(&self) -> Option<vk::DescriptorSetLayout> {
        self.pipelines.textured.as_ref().map(|p| p.set_layouts[1])
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        scene: &SceneGpu,
        rsm: &Rsm,
    ) {
        for target in [&rsm.position, &rsm.normal, &rsm.flux] {
            tracker.image(target, Access::Undefined);
            tracker.image(target, Access::ColorAttachmentWrite);
        }
        tracker.image(&rsm.depth, Access::Undefined);
        tracker.image(&rsm.depth, Access::DepthAttachmentWrite);
        tracker.flush(rec.device, rec.cmd);
        let zero = [0.0; 4];
        rec.begin_rendering(
            &[
                (&rsm.position, zero),
                (&rsm.normal, zero),
                (&rsm.flux, zero),
            ],
            &rsm.depth,
        );
        self.pipelines.draw(rec, frame_set, scene);
        rec.end_rendering();
    }
}
