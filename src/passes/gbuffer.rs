//! G-buffer: world position (w = 1 on geometry, 0 on background), world normal (facing the
//! eye), albedo, and depth, from the camera.

use super::layout::PassLayout;
use super::pass_id::PassId;
use super::raster::{MaterialPipelines, RasterModules, FLAT_BINDINGS, TEXTURED_BINDINGS};
use crate::error::Result;
use crate::renderer::scene_gpu::SceneGpu;
use crate::renderer::targets::{GBuffer, DEPTH_FORMAT, GBUFFER_COLOR_FORMATS};
use crate::shaders;
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Context, Tracker};
use ash::vk;
use std::sync::Arc;

const MODULES: RasterModules = RasterModules {
    vertex: &shaders::MESH_VERT_CAMERA,
    flat: &shaders::GBUFFER_FRAG_FLAT,
    textured: &shaders::GBUFFER_FRAG_TEXTURED,
};

pub fn layouts() -> Vec<PassLayout> {
    vec![
        PassLayout {
            pass: PassId::GBuffer,
            modules: vec![MODULES.vertex, MODULES.flat],
            declared: FLAT_BINDINGS.to_vec(),
        },
        PassLayout {
            pass: PassId::GBuffer,
            modules: vec![MODULES.vertex, MODULES.textured],
            declared: TEXTURED_BINDINGS.to_vec(),
        },
    ]
}

pub struct GBufferPass {
    pipelines: MaterialPipelines,
}

impl GBufferPass {
    pub fn new(ctx: &Arc<Context>, textured: bool) -> Result<Self> {
        let pipelines = MaterialPipelines::new(
            ctx,
            PassId::GBuffer,
            &MODULES,
            &GBUFFER_COLOR_FORMATS,
            DEPTH_FORMAT,
            textured,
        )?;
        Ok(Self { pipelines })
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        scene: &SceneGpu,
        g: &GBuffer,
        parity: usize,
    ) {
        let position = g.position.current(parity);
        for target in [position, &g.normal, &g.albedo] {
            tracker.image(target, Access::Undefined);
            tracker.image(target, Access::ColorAttachmentWrite);
        }
        tracker.image(&g.depth, Access::Undefined);
        tracker.image(&g.depth, Access::DepthAttachmentWrite);
        tracker.flush(rec.device, rec.cmd);
        let zero = [0.0; 4];
        rec.begin_rendering(
            &[(position, zero), (&g.normal, zero), (&g.albedo, zero)],
            &g.depth,
        );
        self.pipelines.draw(rec, frame_set, scene);
        rec.end_rendering();
    }
}
