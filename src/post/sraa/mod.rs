//! Subpixel reconstruction antialiasing (`--aa sraa|sraa-shadow`): the subpixel geometry (four
//! renders of position and normal, the projection shifted to each subpixel of the rotated
//! grid, as Chiu et al. render theirs) and the reconstruction (shaders/sraa/sraa.comp: eq 1's
//! weights over the shaded pixels around each subpixel, then the box filter into the output).
//!
//! Four renders rather than one 4x multisampled G-buffer: the subpixels land exactly where
//! shaders/include/subpixel.glsl says on every device (no dependence on standard sample
//! locations or sample-rate shading), and the reconstruction reads plain images. The cost is
//! four vertex passes; `sraa_geometry` times all four.

pub mod args;
pub mod config;

use super::stage::{PostFrame, PostRegistration, PostStage};
use crate::config::RenderConfig;
use crate::effects::Recording;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch, FrameSet};
use crate::passes::decl::{Bind, Resolve, Slot, Use};
use crate::passes::layout::PassLayout;
use crate::passes::raster::{begin_attachments, FLAT_BINDINGS, VERTEX_ATTRIBUTES, VERTEX_BINDINGS};
use crate::resources::scene_gpu::SceneGpu;
use crate::resources::targets::{DEPTH_FORMAT, GBUFFER_COLOR_FORMATS};
use crate::shaders::{self, SraaPush};
use crate::vk::recorder::Recorder;
use crate::vk::{Blend, Context, DescriptorPool, GraphicsDesc, Pipeline, Tracker};
use std::sync::Arc;

/// The stage's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// SRAA: position and normal at the 4 subpixels (4 renders with shifted projections).
    pub const SRAA_GEOMETRY: PassId =
        PassId::new("sraa_geometry", &[Change::Camera, Change::Object]);
    /// SRAA: each subpixel's shading from the shaded pixels around it, box-filtered.
    pub const SRAA: PassId = PassId::new("sraa", &[Change::Camera, Change::Light, Change::Config]);

    /// Every pass, in recording order.
    pub const ALL: &[PassId] = &[SRAA_GEOMETRY, SRAA];
}

pub const REGISTRATION: PostRegistration = PostRegistration {
    enabled: |c: &RenderConfig| c.aa.mode.subpixel(),
    create: |ctx, pool, config| Ok(Box::new(SraaPass::new(ctx, pool, config)?)),
    layouts,
    passes: pass::ALL,
    geometry_passes: &[pass::SRAA_GEOMETRY],
};

/// Attachments of subpixel `n`'s render: position, normal (the G-buffer's formats), depth.
const fn subpixel_targets(n: u8) -> [Bind; 3] {
    [
        Bind::new(0, Slot::SubPosition(n), Use::ColorAttachment),
        Bind::new(1, Slot::SubNormal(n), Use::ColorAttachment),
        Bind::new(0, Slot::SubDepth, Use::DepthAttachment),
    ]
}

const SUBPIXEL_TARGETS: [[Bind; 3]; 4] = [
    subpixel_targets(0),
    subpixel_targets(1),
    subpixel_targets(2),
    subpixel_targets(3),
];

const COLOR_FORMATS: [ash::vk::Format; 2] = [GBUFFER_COLOR_FORMATS[0], GBUFFER_COLOR_FORMATS[1]];

const RECONSTRUCT: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::Shaded, Use::Sampled),
    Bind::new(3, Slot::RsmDepth, Use::Sampled),
    Bind::new(4, Slot::SubPosition(0), Use::Sampled),
    Bind::new(5, Slot::SubPosition(1), Use::Sampled),
    Bind::new(6, Slot::SubPosition(2), Use::Sampled),
    Bind::new(7, Slot::SubPosition(3), Use::Sampled),
    Bind::new(8, Slot::SubNormal(0), Use::Sampled),
    Bind::new(9, Slot::SubNormal(1), Use::Sampled),
    Bind::new(10, Slot::SubNormal(2), Use::Sampled),
    Bind::new(11, Slot::SubNormal(3), Use::Sampled),
    Bind::new(12, Slot::Output, Use::StorageWrite),
];

pub fn layouts() -> Vec<PassLayout> {
    vec![
        PassLayout {
            pass: pass::SRAA_GEOMETRY,
            modules: vec![&shaders::MESH_VERT_SUBPIXEL, &shaders::SUBPIXEL_FRAG],
            declared: FLAT_BINDINGS.to_vec(),
            binds: SUBPIXEL_TARGETS.concat(),
        },
        ComputePass::layout(pass::SRAA, &shaders::SRAA_COMP, RECONSTRUCT),
    ]
}

pub struct SraaPass {
    geometry: Pipeline,
    reconstruct: ComputePass,
    /// Eq 1's weights, constant for the configuration.
    push: SraaPush,
}

impl SraaPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool, config: &RenderConfig) -> Result<Self> {
        let desc = GraphicsDesc {
            vertex: &shaders::MESH_VERT_SUBPIXEL,
            fragment: &shaders::SUBPIXEL_FRAG,
            vertex_bindings: &VERTEX_BINDINGS,
            vertex_attributes: &VERTEX_ATTRIBUTES,
            color_formats: &COLOR_FORMATS,
            depth_format: DEPTH_FORMAT,
            blend: Blend::Replace,
        };
        let name = pass::SRAA_GEOMETRY.name();
        Ok(Self {
            geometry: Pipeline::graphics(ctx, name, &desc, FLAT_BINDINGS)?,
            reconstruct: ComputePass::new(ctx, pool, pass::SRAA, &shaders::SRAA_COMP, RECONSTRUCT)?,
            push: SraaPush {
                sigma_z: config.aa.sraa.sigma_z,
                sigma_n: config.aa.sraa.sigma_n,
                sigma_shadow: config.aa.shadow_scale(),
            },
        })
    }

    /// The four subpixel renders; the draw's first instance tells mesh.vert which subpixel.
    fn record_geometry(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        scene: &SceneGpu,
        res: &dyn Resolve,
    ) {
        for (n, binds) in SUBPIXEL_TARGETS.iter().enumerate() {
            let targets = (binds.as_slice(), res);
            begin_attachments(rec, tracker, self.geometry.name, targets, frame.parity);
            rec.bind(&self.geometry, &[frame.set]);
            rec.bind_mesh(&scene.vertices, &scene.indices);
            for draw in &scene.draws {
                let material = &scene.materials[draw.material];
                rec.push(&self.geometry, &material.push_bytes(&scene.pose(draw)));
                rec.draw_indexed_instance(draw.first_index, draw.index_count, n as u32);
            }
            rec.end_rendering();
        }
    }

    /// The reconstruction over the render size.
    fn record_reconstruct(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        res: &dyn Resolve,
        (width, height): (u32, u32),
    ) {
        self.reconstruct.record(
            rec,
            tracker,
            frame,
            res,
            &self.push.to_bytes(),
            Dispatch::Pixels { width, height },
        );
    }
}

impl PostStage for SraaPass {
    fn bind(&self, ctx: &Context, targets: &dyn Resolve) -> Result<()> {
        self.reconstruct.bind(ctx, targets)
    }

    fn record(&self, r: &mut Recording<'_>, f: &PostFrame<'_>) {
        // The subpixel geometry, as the G-buffer, only while the camera or objects move.
        if f.geometry {
            r.timed(pass::SRAA_GEOMETRY, |rec, tr| {
                self.record_geometry(rec, tr, f.frame, f.scene, f.targets)
            });
        }
        r.timed(pass::SRAA, |rec, tr| {
            self.record_reconstruct(rec, tr, f.frame, f.targets, f.render)
        });
    }
}
