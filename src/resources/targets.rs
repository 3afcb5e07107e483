//! Render targets every effect shares (G-buffer, reflective shadow map, output) and the
//! ping-pong pair that holds a frame's image and the previous one.

use crate::config::antialias::AaMode;
use crate::config::GBufferMode;
use crate::error::Result;
use crate::vk::{Context, Image, ImageDesc};
use ash::vk;
use std::sync::Arc;

pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;
/// World position needs fp32 (large scenes); normals and flux/radiance are fine in fp16, and
/// so is motion (a displacement: its rounding is relative to the step, 0 stays exactly 0).
/// Albedo is linear, so fp16 too: 8-bit UNORM steps of 1/255 are 4-20% of albedos of
/// 0.01-0.05 (and 8-bit sRGB still 2% at 0.02); fp16 keeps 0.05% at any albedo.
pub const GBUFFER_COLOR_FORMATS: [vk::Format; 4] = [
    vk::Format::R32G32B32A32_SFLOAT,
    vk::Format::R16G16B16A16_SFLOAT,
    vk::Format::R16G16B16A16_SFLOAT,
    vk::Format::R16G16B16A16_SFLOAT,
];
pub const RSM_COLOR_FORMATS: [vk::Format; 3] = [
    vk::Format::R32G32B32A32_SFLOAT,
    vk::Format::R16G16B16A16_SFLOAT,
    vk::Format::R16G16B16A16_SFLOAT,
];
pub const DIRECT_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// AO / visibility images of the effects without history (value in r).
pub const AO_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
// A temporal effect's formats: its history's in its `EffectKind`, the moments', registration's
// and state's shared by all, each declared once for the shaders and this side.
pub use crate::shaders::{MOMENTS_FORMAT, REGISTRATION_FORMAT, STATE_FORMAT};
pub const OUTPUT_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

const ATTACHMENT_READ: vk::ImageUsageFlags = vk::ImageUsageFlags::from_raw(
    vk::ImageUsageFlags::COLOR_ATTACHMENT.as_raw()
        | vk::ImageUsageFlags::SAMPLED.as_raw()
        | vk::ImageUsageFlags::TRANSFER_SRC.as_raw(),
);
const DEPTH_READ: vk::ImageUsageFlags = vk::ImageUsageFlags::from_raw(
    vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT.as_raw()
        | vk::ImageUsageFlags::SAMPLED.as_raw()
        | vk::ImageUsageFlags::TRANSFER_SRC.as_raw(),
);
const STORAGE_READ: vk::ImageUsageFlags = vk::ImageUsageFlags::from_raw(
    vk::ImageUsageFlags::STORAGE.as_raw()
        | vk::ImageUsageFlags::SAMPLED.as_raw()
        | vk::ImageUsageFlags::TRANSFER_SRC.as_raw(),
);

fn image(
    ctx: &Arc<Context>,
    name: &str,
    size: (u32, u32),
    format: vk::Format,
    usage: vk::ImageUsageFlags,
) -> Result<Image> {
    Image::new(
        ctx,
        name,
        ImageDesc {
            width: size.0,
            height: size.1,
            format,
            usage,
        },
    )
}

/// Two images that swap roles every frame: one written this frame, the other holding last
/// frame's (a history, or the G-buffer position of eq 2). `parity` is the frame index mod 2.
/// Every history is one (the temporal effects', SVGF's, the G-buffer's).
pub struct PingPong {
    images: [Image; 2],
}

impl PingPong {
    pub fn new(images: [Image; 2]) -> Self {
        Self { images }
    }

    /// The pair `make(i)` makes, `i` = 0, 1.
    pub fn make(mut make: impl FnMut(usize) -> Result<Image>) -> Result<Self> {
        Ok(Self::new([make(0)?, make(1)?]))
    }

    /// The image written in each parity's frame, by parity (an effect's own slot for this
    /// frame's image: `EffectResources::own`).
    pub fn current_by_parity(&self) -> [&Image; 2] {
        [self.current(0), self.current(1)]
    }

    /// The image written the frame before, by parity (the slot for last frame's).
    pub fn previous_by_parity(&self) -> [&Image; 2] {
        [self.previous(0), self.previous(1)]
    }

    /// The image written in the frame of `parity`.
    pub fn current(&self, parity: usize) -> &Image {
        &self.images[parity & 1]
    }

    /// The image written the frame before.
    pub fn previous(&self, parity: usize) -> &Image {
        &self.images[(parity + 1) & 1]
    }
}

pub struct GBuffer {
    /// This frame's world position, and last frame's (the world-position history of eq 2).
    pub position: PingPong,
    /// This frame's normal, and last frame's (the disocclusion test rejects a history texel
    /// facing away: the back of a thin wall sits at the same position as its front).
    pub normal: PingPong,
    pub albedo: Image,
    /// How far each pixel's surface point moved in the world since last frame (xyz; 0 for
    /// what stands still): a moving object's pixels reproject to where they were.
    pub motion: Image,
    pub depth: Image,
    /// `--gbuffer visibility`: each pixel's triangle, which the other targets are rebuilt from.
    pub visibility: Option<Image>,
}

/// The visibility buffer's format: 1 + a triangle's index in the scene's index buffer.
pub const VISIBILITY_FORMAT: vk::Format = vk::Format::R32_UINT;

pub struct Rsm {
    pub position: Image,
    pub normal: Image,
    pub flux: Image,
    pub depth: Image,
    pub size: u32,
}

/// The subpixel geometry an antialiasing mode asks for (`AaMode::subpixel`): position and normal at each subpixel of the rotated grid, one
/// render each, sharing a depth buffer.
pub struct Subpixels {
    pub position: [Image; 4],
    pub normal: [Image; 4],
    pub depth: Image,
}

/// What antialiasing adds: the composite's display-linear image it filters (at the render
/// size) and, for a mode that reconstructs from it, the subpixel geometry.
pub struct Antialias {
    pub shaded: Image,
    pub subpixels: Option<Subpixels>,
}

/// The composite's display-linear colour when an antialiasing pass follows it. fp32, so a
/// pixel the pass keeps as it is encodes to the same RGBA8 value as without antialiasing.
pub const SHADED_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

pub struct Targets {
    /// The render size (the output's times the supersampling factor).
    pub width: u32,
    pub height: u32,
    pub gbuffer: GBuffer,
    pub rsm: Rsm,
    /// The direct effect's outgoing radiance (rgb) and shadow visibility (a): shared, because
    /// other effects read it (a directional-occlusion bounce at its senders).
    pub direct: Image,
    /// The final image, at the output size.
    pub output: Image,
    pub antialias: Option<Antialias>,
}

/// Which target to read back or dump.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    Output,
    /// The composite's display-linear image before antialiasing (with `--aa` only).
    Shaded,
    Direct,
    GPosition,
    /// Last frame's G-buffer position: the world-position history of eq 2.
    GPositionHistory,
    GNormal,
    /// Last frame's G-buffer normal.
    GNormalHistory,
    GAlbedo,
    /// World-space motion of each pixel's surface point since last frame.
    GMotion,
    GDepth,
    RsmPosition,
    RsmNormal,
    RsmFlux,
    RsmDepth,
    /// AO visibility as composited (history with reuse, blurred or raw without).
    Ao,
    /// Shadow visibility as the direct pass reads it.
    Shadow,
    /// Indirect light (eq 9's I_p, rgb; a = estimates accumulated).
    Indirect,
    /// The per-frame filters' input: this frame's noisy gather (`--indirect-filter`).
    IndirectNoisy,
    /// Pixels the half-resolution upsampling discarded this frame (Figure 4.1).
    DiscardMask,
    /// Reprojection state per pixel (Figure 4.10's recompute mask).
    State,
    /// A view of an image one effect owns, declared in its registration (`Registration::views`).
    Effect(&'static EffectView),
}

/// A debug view an effect declares of one of its own images: its name (the PNG's and
/// `--target`'s) and how it is drawn.
#[derive(Debug, PartialEq, Eq)]
pub struct EffectView {
    pub name: &'static str,
    pub look: Look,
    /// The viewer's display cycle shows it (Tab), after the frame's own buffers.
    pub in_viewer: bool,
}

/// How a target's texels become a picture (`frontend::png::visualize`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Look {
    /// Tonemapped radiance (Reinhard), and the RGBA8 output as it is.
    Radiance,
    /// A world position (w = 0 off geometry) mapped from the scene bounds to 0..1.
    Position,
    /// A unit normal as n/2 + 1/2.
    Normal,
    /// A world-space motion (any sign), tonemapped per channel as radiance is (negative
    /// components black).
    Motion,
    /// Depth normalised by its range over the image, near bright, the far plane black.
    Depth,
    /// rgb scaled by the image's brightest channel (flux and bounce span any range).
    Brightest,
    /// The r channel as grey (visibilities).
    Red,
    /// The a channel as grey (a modulation factor kept in alpha).
    Alpha,
    /// The r channel as grey, `full` white (a count).
    Count { full: u32 },
    /// Linear albedo in 0..1, its alpha kept (0 over the background).
    Albedo,
    /// The r channel in red (a mask).
    Mask,
    /// Figure 4.10's reprojection states in colour.
    State,
}

impl Look {
    /// Channels that may be negative: positions, normals and motions (xyz).
    pub fn signed_channels(self) -> u32 {
        match self {
            Look::Position | Look::Normal | Look::Motion => 0b0111,
            _ => 0,
        }
    }
}

impl Target {
    /// The frame's own targets and the roles effects fill (an effect's own views are in the
    /// registry: `effects::all_targets`).
    pub const FRAME: [Target; 20] = [
        Target::Output,
        Target::Shaded,
        Target::Direct,
        Target::GPosition,
        Target::GPositionHistory,
        Target::GNormal,
        Target::GNormalHistory,
        Target::GAlbedo,
        Target::GMotion,
        Target::GDepth,
        Target::RsmPosition,
        Target::RsmNormal,
        Target::RsmFlux,
        Target::RsmDepth,
        Target::Ao,
        Target::Shadow,
        Target::Indirect,
        Target::IndirectNoisy,
        Target::DiscardMask,
        Target::State,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Target::Output => "output",
            Target::Shaded => "shaded",
            Target::Direct => "direct",
            Target::GPosition => "gbuffer_position",
            Target::GPositionHistory => "gbuffer_position_history",
            Target::GNormal => "gbuffer_normal",
            Target::GNormalHistory => "gbuffer_normal_history",
            Target::GAlbedo => "gbuffer_albedo",
            Target::GMotion => "gbuffer_motion",
            Target::GDepth => "gbuffer_depth",
            Target::RsmPosition => "rsm_position",
            Target::RsmNormal => "rsm_normal",
            Target::RsmFlux => "rsm_flux",
            Target::RsmDepth => "rsm_depth",
            Target::Ao => "ao",
            Target::Shadow => "shadow",
            Target::Indirect => "indirect",
            Target::IndirectNoisy => "indirect_noisy",
            Target::DiscardMask => "discard_mask",
            Target::State => "recompute_mask",
            Target::Effect(view) => view.name,
        }
    }

    /// How the target is drawn.
    pub fn look(self) -> Look {
        match self {
            Target::GPosition | Target::GPositionHistory | Target::RsmPosition => Look::Position,
            Target::GNormal | Target::GNormalHistory | Target::RsmNormal => Look::Normal,
            Target::GMotion => Look::Motion,
            Target::GDepth | Target::RsmDepth => Look::Depth,
            Target::RsmFlux => Look::Brightest,
            Target::Ao | Target::Shadow => Look::Red,
            Target::GAlbedo => Look::Albedo,
            Target::DiscardMask => Look::Mask,
            Target::State => Look::State,
            Target::Effect(view) => view.look,
            Target::Output
            | Target::Shaded
            | Target::Direct
            | Target::Indirect
            | Target::IndirectNoisy => Look::Radiance,
        }
    }
}

fn subpixels(ctx: &Arc<Context>, s: (u32, u32)) -> Result<Subpixels> {
    let [gp, gn, _, _] = GBUFFER_COLOR_FORMATS;
    let four = |what: &str, format| -> Result<[Image; 4]> {
        let layer = |i: usize| {
            image(
                ctx,
                &format!("subpixel.{what}.{i}"),
                s,
                format,
                ATTACHMENT_READ,
            )
        };
        Ok([layer(0)?, layer(1)?, layer(2)?, layer(3)?])
    };
    Ok(Subpixels {
        position: four("position", gp)?,
        normal: four("normal", gn)?,
        depth: image(ctx, "subpixel.depth", s, DEPTH_FORMAT, DEPTH_READ)?,
    })
}

impl Targets {
    /// Targets rendered at `width` x `height`; `aa` adds its images, and with supersampling
    /// the output is that size divided by the factor.
    pub fn new(
        ctx: &Arc<Context>,
        width: u32,
        height: u32,
        rsm_size: u32,
        aa: AaMode,
        gbuffer: GBufferMode,
    ) -> Result<Self> {
        let s = (width, height);
        // The visibility buffer's resolve writes the G-buffer from a compute pass.
        let (g, visibility) = match gbuffer {
            GBufferMode::Raster => (ATTACHMENT_READ, None),
            GBufferMode::Visibility => (
                ATTACHMENT_READ | vk::ImageUsageFlags::STORAGE,
                Some(image(
                    ctx,
                    "gbuffer.visibility",
                    s,
                    VISIBILITY_FORMAT,
                    ATTACHMENT_READ | vk::ImageUsageFlags::STORAGE,
                )?),
            ),
        };
        let scale = aa.supersampling();
        let out = (width / scale, height / scale);
        let antialias = if aa.resolves() {
            Some(Antialias {
                shaded: image(ctx, "shaded", s, SHADED_FORMAT, STORAGE_READ)?,
                subpixels: aa.subpixel().then(|| subpixels(ctx, s)).transpose()?,
            })
        } else {
            None
        };
        let r = (rsm_size, rsm_size);
        let [gp, gn, ga, gm] = GBUFFER_COLOR_FORMATS;
        let [rp, rn, rf] = RSM_COLOR_FORMATS;
        Ok(Self {
            width,
            height,
            gbuffer: GBuffer {
                position: PingPong::new([
                    image(ctx, "gbuffer.position.0", s, gp, g)?,
                    image(ctx, "gbuffer.position.1", s, gp, g)?,
                ]),
                normal: PingPong::new([
                    image(ctx, "gbuffer.normal.0", s, gn, g)?,
                    image(ctx, "gbuffer.normal.1", s, gn, g)?,
                ]),
                albedo: image(ctx, "gbuffer.albedo", s, ga, g)?,
                motion: image(ctx, "gbuffer.motion", s, gm, g)?,
                depth: image(ctx, "gbuffer.depth", s, DEPTH_FORMAT, DEPTH_READ)?,
                visibility,
            },
            rsm: Rsm {
                position: image(ctx, "rsm.position", r, rp, ATTACHMENT_READ)?,
                normal: image(ctx, "rsm.normal", r, rn, ATTACHMENT_READ)?,
                flux: image(ctx, "rsm.flux", r, rf, ATTACHMENT_READ)?,
                depth: image(ctx, "rsm.depth", r, DEPTH_FORMAT, DEPTH_READ)?,
                size: rsm_size,
            },
            direct: image(ctx, "direct", s, DIRECT_FORMAT, STORAGE_READ)?,
            output: image(ctx, "output", out, OUTPUT_FORMAT, STORAGE_READ)?,
            antialias,
        })
    }

    /// The image behind a shared target for frame parity `parity` (`None` for the targets the
    /// effects own: direct light, AO, shadow, indirect light, masks and state).
    pub fn get(&self, target: Target, parity: usize) -> Option<&Image> {
        Some(match target {
            Target::Output => &self.output,
            Target::Shaded => &self.antialias.as_ref()?.shaded,
            Target::GPosition => self.gbuffer.position.current(parity),
            Target::GPositionHistory => self.gbuffer.position.previous(parity),
            Target::GNormal => self.gbuffer.normal.current(parity),
            Target::GNormalHistory => self.gbuffer.normal.previous(parity),
            Target::GAlbedo => &self.gbuffer.albedo,
            Target::GMotion => &self.gbuffer.motion,
            Target::GDepth => &self.gbuffer.depth,
            Target::RsmPosition => &self.rsm.position,
            Target::RsmNormal => &self.rsm.normal,
            Target::RsmFlux => &self.rsm.flux,
            Target::RsmDepth => &self.rsm.depth,
            Target::Direct => &self.direct,
            Target::Ao
            | Target::Shadow
            | Target::Indirect
            | Target::IndirectNoisy
            | Target::DiscardMask
            | Target::State
            | Target::Effect(_) => return None,
        })
    }
}
