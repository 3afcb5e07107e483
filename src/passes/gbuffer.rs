//! G-buffer: world position (w = 1 on geometry, 0 on background), world normal (facing the
//! eye), albedo, world-space motion since last frame, and depth, from the camera. With
//! `--gbuffer visibility` the raster pass writes each pixel's triangle (and, in a scene with
//! textures, albedo) and a compute pass rebuilds the other targets from the triangles.

use super::compute::{ComputePass, Dispatch, FrameSet, PassDecl};
use super::decl::{Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use super::raster::{MaterialPipelines, RasterModules, FLAT_BINDINGS, TEXTURED_BINDINGS};
use crate::error::Result;
use crate::resources::scene_gpu::SceneGpu;
use crate::resources::targets::{DEPTH_FORMAT, GBUFFER_COLOR_FORMATS, VISIBILITY_FORMAT};
use crate::shaders::{self, GBufferResolvePush};
use crate::vk::recorder::Recorder;
use crate::vk::{Context, DescriptorPool, Tracker};
use ash::vk;
use std::sync::Arc;

/// Colour attachments in the order of gbuffer.frag's outputs, then depth.
const TARGETS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::ColorAttachment),
    Bind::new(1, Slot::GNormal, Use::ColorAttachment),
    Bind::new(2, Slot::GAlbedo, Use::ColorAttachment),
    Bind::new(3, Slot::GMotion, Use::ColorAttachment),
    Bind::new(0, Slot::GDepth, Use::DepthAttachment),
];

/// The visibility buffer of a scene without textures: the triangle, then depth.
const VISIBILITY_TARGETS: &[Bind] = &[
    Bind::new(0, Slot::GVisibility, Use::ColorAttachment),
    Bind::new(0, Slot::GDepth, Use::DepthAttachment),
];

/// With textures: albedo too (visibility.frag's ALBEDO permutations).
const VISIBILITY_ALBEDO_TARGETS: &[Bind] = &[
    Bind::new(0, Slot::GVisibility, Use::ColorAttachment),
    Bind::new(1, Slot::GAlbedo, Use::ColorAttachment),
    Bind::new(0, Slot::GDepth, Use::DepthAttachment),
];

/// gbuffer_resolve.comp's bindings; without textures the resolve writes albedo too (the last).
const RESOLVE_FLAT: &[Bind] = &[
    Bind::new(0, Slot::GVisibility, Use::StorageRead),
    Bind::new(1, Slot::SceneVertices, Use::BufferRead),
    Bind::new(2, Slot::SceneIndices, Use::BufferRead),
    Bind::new(3, Slot::SceneTriangleDraws, Use::BufferRead),
    Bind::new(4, Slot::SceneDraws, Use::BufferRead),
    Bind::new(5, Slot::GPosition, Use::StorageWrite),
    Bind::new(6, Slot::GNormal, Use::StorageWrite),
    Bind::new(7, Slot::GMotion, Use::StorageWrite),
    Bind::new(8, Slot::GAlbedo, Use::StorageWrite),
];

/// The textured-scene permutation: the same less albedo, which is the raster pass's.
const RESOLVE_TEXTURED: &[Bind] = RESOLVE_FLAT.split_at(RESOLVE_FLAT.len() - 1).0;

const RESOLVE_FLAT_PASS: PassDecl = PassDecl::new(
    PassId::GBUFFER_RESOLVE,
    &shaders::GBUFFER_RESOLVE_COMP_FLAT,
    RESOLVE_FLAT,
);
const RESOLVE_TEXTURED_PASS: PassDecl = PassDecl::new(
    PassId::GBUFFER_RESOLVE,
    &shaders::GBUFFER_RESOLVE_COMP_TEXTURED,
    RESOLVE_TEXTURED,
);

const MODULES: RasterModules = RasterModules {
    vertex: &shaders::MESH_VERT_CAMERA,
    textured_vertex: &shaders::MESH_VERT_CAMERA,
    flat: &shaders::GBUFFER_FRAG_FLAT,
    textured: &shaders::GBUFFER_FRAG_TEXTURED,
};

/// The visibility raster pass of a scene without textures (the textured module is never
/// built: no material has a texture).
const VISIBILITY_MODULES: RasterModules = RasterModules {
    vertex: &shaders::MESH_VERT_VISIBILITY,
    textured_vertex: &shaders::MESH_VERT_VISIBILITY_UV,
    flat: &shaders::VISIBILITY_FRAG_IDS,
    textured: &shaders::VISIBILITY_FRAG_TEXTURED,
};

/// With textures: every material writes albedo.
const VISIBILITY_ALBEDO_MODULES: RasterModules = RasterModules {
    vertex: &shaders::MESH_VERT_VISIBILITY,
    textured_vertex: &shaders::MESH_VERT_VISIBILITY_UV,
    flat: &shaders::VISIBILITY_FRAG_FLAT,
    textured: &shaders::VISIBILITY_FRAG_TEXTURED,
};

/// The raster pass's attachments, modules and the resolve's module and bindings, by mode and
/// whether the scene has textures.
struct Variant {
    targets: &'static [Bind],
    modules: &'static RasterModules,
    resolve: Option<&'static PassDecl>,
}

/// `visibility`: `--gbuffer visibility`.
fn variant(visibility: bool, textured: bool) -> Variant {
    match (visibility, textured) {
        (false, _) => Variant {
            targets: TARGETS,
            modules: &MODULES,
            resolve: None,
        },
        (true, false) => Variant {
            targets: VISIBILITY_TARGETS,
            modules: &VISIBILITY_MODULES,
            resolve: Some(&RESOLVE_FLAT_PASS),
        },
        (true, true) => Variant {
            targets: VISIBILITY_ALBEDO_TARGETS,
            modules: &VISIBILITY_ALBEDO_MODULES,
            resolve: Some(&RESOLVE_TEXTURED_PASS),
        },
    }
}

/// The colour formats of `targets`, in attachment order.
fn color_formats(targets: &[Bind]) -> Vec<vk::Format> {
    let [gp, gn, ga, gm] = GBUFFER_COLOR_FORMATS;
    targets
        .iter()
        .filter(|b| b.usage == Use::ColorAttachment)
        .map(|b| match b.slot {
            Slot::GPosition => gp,
            Slot::GNormal => gn,
            Slot::GAlbedo => ga,
            Slot::GMotion => gm,
            _ => VISIBILITY_FORMAT,
        })
        .collect()
}

pub fn layouts() -> Vec<PassLayout> {
    let mut v = Vec::new();
    for textured in [false, true] {
        for visibility in [false, true] {
            let m = variant(visibility, textured);
            let (vertex, fragment, declared) = match textured {
                false => (m.modules.vertex, m.modules.flat, FLAT_BINDINGS),
                true => (
                    m.modules.textured_vertex,
                    m.modules.textured,
                    TEXTURED_BINDINGS,
                ),
            };
            v.push(PassLayout {
                pass: PassId::GBUFFER,
                modules: vec![vertex, fragment],
                declared: declared.to_vec(),
                binds: m.targets.to_vec(),
            });
            if let Some(decl) = m.resolve {
                v.push(decl.layout());
            }
        }
    }
    // The flat materials of a textured scene's visibility pass.
    v.push(PassLayout {
        pass: PassId::GBUFFER,
        modules: vec![
            VISIBILITY_ALBEDO_MODULES.vertex,
            VISIBILITY_ALBEDO_MODULES.flat,
        ],
        declared: FLAT_BINDINGS.to_vec(),
        binds: VISIBILITY_ALBEDO_TARGETS.to_vec(),
    });
    v
}

pub struct GBufferPass {
    pipelines: MaterialPipelines,
    targets: &'static [Bind],
    /// `--gbuffer visibility`: the compute pass that rebuilds the targets from the triangles.
    resolve: Option<ComputePass>,
}

impl GBufferPass {
    pub fn new(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        textured: bool,
        visibility: bool,
    ) -> Result<Self> {
        let v = variant(visibility, textured);
        let mut pipelines = MaterialPipelines::new(
            ctx,
            PassId::GBUFFER,
            v.modules,
            &color_formats(v.targets),
            DEPTH_FORMAT,
            textured,
        )?;
        pipelines.first_triangle_instance = v.resolve.is_some();
        let resolve = v
            .resolve
            .map(|decl| ComputePass::declared(ctx, pool, decl))
            .transpose()?;
        Ok(Self {
            pipelines,
            targets: v.targets,
            resolve,
        })
    }

    /// Whether the G-buffer is a visibility buffer and a resolve (`record_resolve`) follows.
    pub fn resolves(&self) -> bool {
        self.resolve.is_some()
    }

    /// Point the resolve at the targets and the scene's buffers (creation and resize).
    pub fn bind(&self, ctx: &Context, res: &dyn Resolve) -> Result<()> {
        match &self.resolve {
            Some(pass) => pass.bind(ctx, res),
            None => Ok(()),
        }
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
            .render(rec, tracker, frame, scene, (self.targets, res));
    }

    /// The visibility buffer's resolve over `size` pixels, reading the draw table from entry
    /// `table_base` (this frame slot's).
    pub fn record_resolve(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        res: &dyn Resolve,
        table_base: u32,
        (width, height): (u32, u32),
    ) {
        let Some(pass) = &self.resolve else {
            return;
        };
        let push = GBufferResolvePush { table_base }.to_bytes();
        pass.record(
            rec,
            tracker,
            frame,
            res,
            &push,
            Dispatch::Pixels { width, height },
        );
    }
}
