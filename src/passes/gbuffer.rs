//! G-buffer: world position (w = 1 on geometry, 0 on background), world normal (facing the
//! eye), albedo, world-space motion since last frame, and depth, from the camera.

use super::compute::FrameSet;
use super::decl::{Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use super::raster::{MaterialPipelines, RasterModules, FLAT_BINDINGS, TEXTURED_BINDINGS};
use crate::error::Result;
use crate::renderer::scene_gpu::SceneGpu;
use crate::renderer::targets::{DEPTH_FORMAT, GBUFFER_COLOR_FORMATS};
use crate::shaders;
use crate::vk::cmd::Recorder;
use crate::vk::{Context, Tracker};
use std::sync::Arc;

/// Colour attachments in the order of gbuffer.frag's outputs, then depth.
const TARGETS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::ColorAttachment),
    Bind::new(1, Slot::GNormal, Use::ColorAttachment),
    Bind::new(2, Slot::GAlbedo, Use::ColorAttachment),
    Bind::new(3, Slot::GMotion, Use::ColorAttachment),
    Bind::new(0, Slot::GDepth, Use::DepthAttachment),
];

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
            binds: TARGETS.to_vec(),
        },
        PassLayout {
            pass: PassId::GBuffer,
            modules: vec![MODULES.vertex, MODULES.textured],
            declared: TEXTURED_BINDINGS.to_vec(),
            binds: TARGETS.to_vec(),
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
        frame: FrameSet,
        scene: &SceneGpu,
        res: &dyn Resolve,
    ) {
        self.pipelines
            .render(rec, tracker, frame, scene, (TARGETS, res));
    }
}
