//! `PassId`: the typed name of every pass (timing rows, command labels, debug names).

/// The passes of one frame, in recording order (`ALL` lists them in the same order). Their
/// names are the timing report's rows, the command labels and the pipelines' debug names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PassId {
    /// Reflective shadow map + shadow depth from the spot light (only when light/geometry change).
    LightView,
    /// Camera G-buffer MRT (with `--gbuffer visibility`: each pixel's triangle).
    GBuffer,
    /// `--gbuffer visibility`: the G-buffer rebuilt from each pixel's triangle.
    GBufferResolve,
    /// Reverse reprojection: disocclusion test, history resampling, work list.
    Reproject,
    /// PCF shadow visibility (every frame, or accumulated with the cache).
    Shadow,
    /// The shadow's refresh tile, every pattern, spread over threads.
    ShadowRefresh,
    /// Direct spot light times the shadow visibility.
    Direct,
    /// Point-sampled levels of the G-buffer position for SSAO's far taps (--ao-position-mips).
    AoPositionChain,
    /// Screen-space ambient occlusion.
    Ssao,
    /// The AO's refresh tile, every pattern, spread over threads.
    SsaoRefresh,
    /// 5x5 Gaussian blur of the AO (no-reuse baseline only).
    Blur,
    /// The half-resolution gather's list: the low-resolution samples the upsampling reads.
    IndirectClassify,
    /// RSM gather (half resolution, or full resolution without half-res).
    IndirectGather,
    /// Geometry-aware upsampling of the half-resolution gather.
    IndirectUpsample,
    /// Full-resolution gather of the pixels the upsampling discarded.
    IndirectFixup,
    /// Indirect light's refresh tile, every pattern (at half resolution of the samples its
    /// pixels are upsampled from), spread over threads.
    IndirectRefresh,
    /// CCIPCA's input: a new noisy full-resolution gather each frame (--vpls per pixel).
    IndirectNoisy,
    /// CCIPCA: the bases warped along the reprojection and orthogonalized (a moving camera).
    CcipcaReproject,
    /// CCIPCA: every basis updated from the noisy image, in turn (image-wide sums on the GPU).
    CcipcaUpdate,
    /// CCIPCA: the noisy image projected on the updated bases.
    CcipcaReconstruct,
    /// CCIPCA: the bases smoothed for the next frame (--ccipca-basis-filter).
    CcipcaBasisFilter,
    /// The joint bilateral filter of the noisy gather (--indirect-filter jbf11|jbf17).
    IndirectJbf,
    /// SSDO's pre-pass: samples per block from the normal and depth changes.
    SsdoSamples,
    /// SSDO: modulation factor and bounce in one pass, or the two-step form's directional
    /// occlusion pass.
    Ssdo,
    /// The two-step SSDO's bounce pass.
    SsdoBounce,
    /// With the cache: SSDO's refresh tile, every pattern, spread over threads.
    SsdoRefresh,
    /// With the cache: the accumulated bounce and factor into the image the filter reads.
    SsdoResolve,
    /// SSDO's separable bilateral filter (both directions).
    SsdoBilateral,
    /// Joint bilateral upsampling of half-resolution SSDO (--ssdo-scale 0.5).
    SsdoUpsample,
    /// Composite + tonemap into the output image (display-linear for antialiasing).
    Composite,
    /// SRAA: position and normal at the 4 subpixels (4 renders with shifted projections).
    SraaGeometry,
    /// SRAA: each subpixel's shading from the shaded pixels around it, box-filtered.
    Sraa,
    /// 16x supersampling: the 4x4 box filter into the output.
    SsaaDownsample,
}

/// A scene input whose change makes passes run again (`renderer::dependencies`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Change {
    /// The camera's view-projection or eye.
    Camera,
    /// The lights: the spot light (position, axis, cone, intensity, depth range) and the
    /// ambient radiance.
    Light,
    /// A moving object's transform (for the light view: one the light's frustum meets).
    Object,
    /// The configuration (the viewer's in-place switches; other changes rebuild).
    Config,
}

impl Change {
    pub const ALL: [Change; 4] = [
        Change::Camera,
        Change::Light,
        Change::Object,
        Change::Config,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Change::Camera => "camera",
            Change::Light => "light",
            Change::Object => "moving objects",
            Change::Config => "configuration",
        }
    }
}

impl PassId {
    pub const ALL: [PassId; 33] = [
        PassId::LightView,
        PassId::GBuffer,
        PassId::GBufferResolve,
        PassId::Reproject,
        PassId::Shadow,
        PassId::ShadowRefresh,
        PassId::Direct,
        PassId::AoPositionChain,
        PassId::Ssao,
        PassId::SsaoRefresh,
        PassId::Blur,
        PassId::IndirectClassify,
        PassId::IndirectGather,
        PassId::IndirectUpsample,
        PassId::IndirectFixup,
        PassId::IndirectRefresh,
        PassId::IndirectNoisy,
        PassId::CcipcaReproject,
        PassId::CcipcaUpdate,
        PassId::CcipcaReconstruct,
        PassId::CcipcaBasisFilter,
        PassId::IndirectJbf,
        PassId::SsdoSamples,
        PassId::Ssdo,
        PassId::SsdoBounce,
        PassId::SsdoRefresh,
        PassId::SsdoResolve,
        PassId::SsdoBilateral,
        PassId::SsdoUpsample,
        PassId::Composite,
        PassId::SraaGeometry,
        PassId::Sraa,
        PassId::SsaaDownsample,
    ];

    /// Position in the recording order (`ALL`, declared in the enum's own order).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The scene inputs the pass reads itself: the frame block's camera and light members its
    /// shaders use, the objects it draws (or whose motion it follows), the configuration. What
    /// it reads of other passes' outputs comes from its resource declaration (`PassLayout::
    /// binds`); `renderer::dependencies` puts the two together, and `tests/dependencies.rs`
    /// checks this list against the frame members each compute shader names.
    pub fn inputs(self) -> &'static [Change] {
        use Change::*;
        match self {
            PassId::LightView => &[Light, Object],
            PassId::GBuffer | PassId::GBufferResolve | PassId::SraaGeometry => &[Camera, Object],
            // Moving objects' reach; the shadow lane's footprint on the shadow map.
            PassId::Reproject => &[Camera, Light, Object, Config],
            PassId::Shadow
            | PassId::ShadowRefresh
            | PassId::IndirectClassify
            | PassId::IndirectGather
            | PassId::IndirectUpsample
            | PassId::IndirectFixup
            | PassId::IndirectRefresh
            | PassId::IndirectNoisy
            | PassId::Ssdo
            | PassId::SsdoBounce
            | PassId::SsdoRefresh
            | PassId::SsdoResolve
            | PassId::Sraa => &[Camera, Light, Config],
            PassId::Direct | PassId::Composite => &[Light, Config],
            PassId::Ssao
            | PassId::SsaoRefresh
            | PassId::CcipcaReproject
            | PassId::CcipcaBasisFilter
            | PassId::IndirectJbf
            | PassId::SsdoSamples
            | PassId::SsdoBilateral
            | PassId::SsdoUpsample => &[Camera, Config],
            PassId::AoPositionChain
            | PassId::Blur
            | PassId::CcipcaUpdate
            | PassId::CcipcaReconstruct
            | PassId::SsaaDownsample => &[Config],
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            PassId::LightView => "light_view",
            PassId::GBuffer => "gbuffer",
            PassId::GBufferResolve => "gbuffer_resolve",
            PassId::Shadow => "shadow",
            PassId::ShadowRefresh => "shadow_refresh",
            PassId::Direct => "direct",
            PassId::Reproject => "reproject",
            PassId::AoPositionChain => "ao_position_chain",
            PassId::Ssao => "ssao",
            PassId::SsaoRefresh => "ssao_refresh",
            PassId::Blur => "blur",
            PassId::IndirectClassify => "indirect_classify",
            PassId::IndirectGather => "indirect_gather",
            PassId::IndirectUpsample => "indirect_upsample",
            PassId::IndirectFixup => "indirect_fixup",
            PassId::IndirectRefresh => "indirect_refresh",
            PassId::IndirectNoisy => "indirect_noisy",
            PassId::CcipcaReproject => "ccipca_reproject",
            PassId::CcipcaUpdate => "ccipca_update",
            PassId::CcipcaReconstruct => "ccipca_reconstruct",
            PassId::CcipcaBasisFilter => "ccipca_basis_filter",
            PassId::IndirectJbf => "indirect_jbf",
            PassId::SsdoSamples => "ssdo_samples",
            PassId::Ssdo => "ssdo",
            PassId::SsdoBounce => "ssdo_bounce",
            PassId::SsdoRefresh => "ssdo_refresh",
            PassId::SsdoResolve => "ssdo_resolve",
            PassId::SsdoBilateral => "ssdo_bilateral",
            PassId::SsdoUpsample => "ssdo_upsample",
            PassId::Composite => "composite",
            PassId::SraaGeometry => "sraa_geometry",
            PassId::Sraa => "sraa",
            PassId::SsaaDownsample => "ssaa_downsample",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_is_the_position_in_all() {
        for (i, p) in PassId::ALL.into_iter().enumerate() {
            assert_eq!(p.index(), i, "{p:?}");
        }
    }
}
