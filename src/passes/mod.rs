//! One file per pass. `PassId` names are the rows of the timing report.

pub mod blur;
pub mod composite;
pub mod compute;
pub mod direct;
pub mod gbuffer;
pub mod indirect;
pub mod light_view;
pub mod raster;
pub mod reproject;
pub mod shadow;
pub mod ssao;

use crate::shaders::{DescriptorKind, ReflectedBinding, ShaderModuleInfo};

/// The passes of one frame, in recording order (`ALL` lists them in the same order). Their
/// names are the timing report's rows, the command labels and the pipelines' debug names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PassId {
    /// Reflective shadow map + shadow depth from the spot light (only when light/geometry change).
    LightView,
    /// Camera G-buffer MRT.
    GBuffer,
    /// Reverse reprojection: disocclusion test, history resampling, work list.
    Reproject,
    /// PCF shadow visibility (every frame, or accumulated with the cache).
    Shadow,
    /// Direct spot light times the shadow visibility.
    Direct,
    /// Screen-space ambient occlusion.
    Ssao,
    /// 5x5 Gaussian blur of the AO (no-reuse baseline only).
    Blur,
    /// RSM gather (half resolution, or full resolution without half-res).
    IndirectGather,
    /// Geometry-aware upsampling of the half-resolution gather.
    IndirectUpsample,
    /// Full-resolution gather of the pixels the upsampling discarded.
    IndirectFixup,
    /// Composite + tonemap into the output image.
    Composite,
}

impl PassId {
    pub const ALL: [PassId; 11] = [
        PassId::LightView,
        PassId::GBuffer,
        PassId::Reproject,
        PassId::Shadow,
        PassId::Direct,
        PassId::Ssao,
        PassId::Blur,
        PassId::IndirectGather,
        PassId::IndirectUpsample,
        PassId::IndirectFixup,
        PassId::Composite,
    ];

    pub fn name(self) -> &'static str {
        match self {
            PassId::LightView => "light_view",
            PassId::GBuffer => "gbuffer",
            PassId::Shadow => "shadow",
            PassId::Direct => "direct",
            PassId::Reproject => "reproject",
            PassId::Ssao => "ssao",
            PassId::Blur => "blur",
            PassId::IndirectGather => "indirect_gather",
            PassId::IndirectUpsample => "indirect_upsample",
            PassId::IndirectFixup => "indirect_fixup",
            PassId::Composite => "composite",
        }
    }
}

/// The per-frame uniform buffer every pass reads (set 0, binding 0).
pub const FRAME_BINDING: ReflectedBinding = ReflectedBinding {
    set: 0,
    binding: 0,
    kind: DescriptorKind::UniformBuffer,
    count: 1,
};

pub(crate) const fn binding(set: u32, binding: u32, kind: DescriptorKind) -> ReflectedBinding {
    ReflectedBinding {
        set,
        binding,
        kind,
        count: 1,
    }
}

/// One pipeline of a pass: the modules it is built from and the layout the pass declares.
pub struct PassLayout {
    pub pass: PassId,
    pub modules: Vec<&'static ShaderModuleInfo>,
    pub declared: Vec<ReflectedBinding>,
}

/// Every pipeline of every pass, for the reflection check (also done at pipeline creation).
pub fn all_layouts() -> Vec<PassLayout> {
    let mut v = Vec::new();
    v.extend(light_view::layouts());
    v.extend(gbuffer::layouts());
    v.extend(shadow::layouts());
    v.push(direct::layout());
    v.push(reproject::layout());
    v.extend(ssao::layouts());
    v.push(blur::layout());
    v.extend(indirect::layouts());
    v.extend(composite::layouts());
    v
}
