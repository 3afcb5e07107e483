//! What the two raster passes (light view and G-buffer) share: the vertex layout, the two
//! material permutations (flat colour / textured) and the draw loop over material ranges.

use super::compute::FrameSet;
use super::decl::{self, Bind, Resolve};
use super::pass_id::PassId;
use crate::error::Result;
use crate::resources::scene_gpu::{Draw, SceneGpu};
use crate::shaders::{DescriptorKind, ReflectedBinding, ShaderModuleInfo};
use crate::vk::recorder::Recorder;
use crate::vk::Tracker;
use crate::vk::{Blend, Context, GraphicsDesc, Pipeline};
use ash::vk;
use std::sync::Arc;

use super::layout::{binding, FRAME_BINDING};

/// Bindings of the flat-colour permutation: only the frame constants.
pub const FLAT_BINDINGS: &[ReflectedBinding] = &[FRAME_BINDING];
/// Textured permutation: plus the material's diffuse texture and sampler (set 1).
pub const TEXTURED_BINDINGS: &[ReflectedBinding] = &[
    FRAME_BINDING,
    binding(1, 0, DescriptorKind::SampledImage),
    binding(1, 1, DescriptorKind::Sampler),
];

pub const VERTEX_BINDINGS: [vk::VertexInputBindingDescription; 1] =
    [vk::VertexInputBindingDescription {
        binding: 0,
        stride: 32,
        input_rate: vk::VertexInputRate::VERTEX,
    }];

pub const VERTEX_ATTRIBUTES: [vk::VertexInputAttributeDescription; 3] = [
    vk::VertexInputAttributeDescription {
        location: 0,
        binding: 0,
        format: vk::Format::R32G32B32_SFLOAT,
        offset: 0,
    },
    vk::VertexInputAttributeDescription {
        location: 1,
        binding: 0,
        format: vk::Format::R32G32B32_SFLOAT,
        offset: 12,
    },
    vk::VertexInputAttributeDescription {
        location: 2,
        binding: 0,
        format: vk::Format::R32G32_SFLOAT,
        offset: 24,
    },
];

/// Barriers for the attachments `targets` declares (colours cleared to 0, depth to 1), then
/// begin rendering into them; the caller draws and ends rendering.
pub fn begin_attachments(
    rec: &Recorder<'_>,
    tracker: &mut Tracker,
    name: &str,
    (binds, res): (&[Bind], &dyn Resolve),
    parity: usize,
) {
    // The slots are targets that exist whenever the pass does: a miss is a broken invariant.
    let (colors, depth) = match decl::attachments(name, binds, res, parity) {
        Ok((colors, Some(depth))) => (colors, depth),
        Ok((_, None)) => panic!("{name}: a raster pass needs a depth attachment"),
        Err(e) => panic!("{e}"),
    };
    decl::access(name, binds, res, parity, tracker);
    tracker.flush(rec.device, rec.cmd);
    let clear: Vec<_> = colors.iter().map(|c| (*c, [0.0; 4])).collect();
    rec.begin_rendering(&clear, depth);
}

/// A raster pass's pipelines: flat always, textured only when the scene has textures.
pub struct MaterialPipelines {
    pub flat: Pipeline,
    pub textured: Option<Pipeline>,
    /// Each draw's firstInstance is its first triangle in the index buffer (the visibility
    /// buffer numbers triangles from it: mesh.vert's VISIBILITY).
    pub first_triangle_instance: bool,
}

pub struct RasterModules {
    pub vertex: &'static ShaderModuleInfo,
    /// The textured materials' vertex stage (the flat one's, unless it must hand on more).
    pub textured_vertex: &'static ShaderModuleInfo,
    pub flat: &'static ShaderModuleInfo,
    pub textured: &'static ShaderModuleInfo,
}

impl MaterialPipelines {
    pub fn new(
        ctx: &Arc<Context>,
        pass: PassId,
        modules: &RasterModules,
        color_formats: &[vk::Format],
        depth_format: vk::Format,
        textured: bool,
    ) -> Result<Self> {
        let desc = |(vertex, fragment)| GraphicsDesc {
            vertex,
            fragment,
            vertex_bindings: &VERTEX_BINDINGS,
            vertex_attributes: &VERTEX_ATTRIBUTES,
            color_formats,
            depth_format,
            blend: Blend::Replace,
        };
        let name = pass.name();
        let flat = Pipeline::graphics(
            ctx,
            name,
            &desc((modules.vertex, modules.flat)),
            FLAT_BINDINGS,
        )?;
        let textured = if textured {
            Some(Pipeline::graphics(
                ctx,
                name,
                &desc((modules.textured_vertex, modules.textured)),
                TEXTURED_BINDINGS,
            )?)
        } else {
            None
        };
        Ok(Self {
            flat,
            textured,
            first_triangle_instance: false,
        })
    }

    /// Clear and render into the attachments `targets` declares: barriers from the
    /// declaration, then every material range.
    pub fn render(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        scene: &SceneGpu,
        targets: (&[Bind], &dyn Resolve),
    ) {
        begin_attachments(rec, tracker, self.flat.name, targets, frame.parity);
        self.draw(rec, frame.set, scene);
        rec.end_rendering();
    }

    /// Draw every material range: flat materials first, then textured ones (one pipeline bind
    /// each), with the material colour and the object's pose as push constants.
    pub fn draw(&self, rec: &Recorder<'_>, frame_set: vk::DescriptorSet, scene: &SceneGpu) {
        rec.bind(&self.flat, &[frame_set]);
        rec.bind_mesh(&scene.vertices, &scene.indices);
        for draw in scene.draws.iter() {
            let material = &scene.materials[draw.material];
            if material.texture_set.is_none() {
                rec.push(&self.flat, &material.push_bytes(&scene.pose(draw)));
                self.draw_range(rec, draw);
            }
        }
        if let Some(textured) = &self.textured {
            rec.bind(textured, &[frame_set]);
            for draw in scene.draws.iter() {
                let material = &scene.materials[draw.material];
                if let Some(set) = material.texture_set {
                    rec.bind_sets(textured, 1, &[set]);
                    rec.push(textured, &material.push_bytes(&scene.pose(draw)));
                    self.draw_range(rec, draw);
                }
            }
        }
    }

    fn draw_range(&self, rec: &Recorder<'_>, draw: &Draw) {
        match self.first_triangle_instance {
            true => {
                rec.draw_indexed_instance(draw.first_index, draw.index_count, draw.first_index / 3)
            }
            false => rec.draw_indexed(draw.first_index, draw.index_count),
        }
    }
}
