//! Light view: the reflective shadow map (world position, normal, reflected flux) and its
//! depth, which is also the shadow map. Rendered only when the light or geometry changed.

use super::compute::FrameSet;
use super::decl::{Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use super::raster::{MaterialPipelines, RasterModules, FLAT_BINDINGS, TEXTURED_BINDINGS};
use crate::error::Result;
use crate::resources::scene_gpu::SceneGpu;
use crate::resources::targets::{DEPTH_FORMAT, RSM_COLOR_FORMATS};
use crate::shaders;
use crate::vk::recorder::Recorder;
use crate::vk::{Context, Tracker};
use ash::vk;
use std::sync::Arc;

/// Colour attachments in the order of rsm.frag's outputs, then depth (the shadow map).
const TARGETS: &[Bind] = &[
    Bind::new(0, Slot::RsmPosition, Use::ColorAttachment),
    Bind::new(1, Slot::RsmNormal, Use::ColorAttachment),
    Bind::new(2, Slot::RsmFlux, Use::ColorAttachment),
    Bind::new(0, Slot::RsmDepth, Use::DepthAttachment),
];

const MODULES: RasterModules = RasterModules {
    vertex: &shaders::MESH_VERT_LIGHT,
    textured_vertex: &shaders::MESH_VERT_LIGHT,
    flat: &shaders::RSM_FRAG_FLAT,
    textured: &shaders::RSM_FRAG_TEXTURED,
};

pub fn layouts() -> Vec<PassLayout> {
    vec![
        PassLayout {
            pass: PassId::LIGHT_VIEW,
            modules: vec![MODULES.vertex, MODULES.flat],
            declared: FLAT_BINDINGS.to_vec(),
            binds: TARGETS.to_vec(),
        },
        PassLayout {
            pass: PassId::LIGHT_VIEW,
            modules: vec![MODULES.vertex, MODULES.textured],
            declared: TEXTURED_BINDINGS.to_vec(),
            binds: TARGETS.to_vec(),
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
            PassId::LIGHT_VIEW,
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
        frame: FrameSet,
        scene: &SceneGpu,
        res: &dyn Resolve,
    ) {
        self.pipelines
            .render(rec, tracker, frame, scene, (TARGETS, res));
    }
}
