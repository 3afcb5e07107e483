//! SSAO (Lin 2013 eqs 6-8, or Mittring's sphere). With reuse: an indirect dispatch over the
//! blocks the reprojection listed, one pattern per pixel merged into the AO history (the
//! gated running mean, or eqs 4-5), refresh tiles recomputed as the mean of every pattern. Without reuse: every pixel with a fixed
//! pattern (or many patterns, for references), then the thesis's 5x5 Gaussian blur.

use super::effect::{
    every_pixel, refresh_dispatch, Effect, EffectId, FrameInfo, Recording, Registration, Setup,
    TermKind,
};
use super::resolve::EffectResources;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::renderer::config::RenderConfig;
use crate::renderer::effect::{self, TemporalEffect};
use crate::renderer::targets::{Target, Targets, AO_FORMAT};
use crate::renderer::temporal::random_vectors;
use crate::renderer::temporal::Sampling;
use crate::shaders::{self, EffectPush};
use crate::vk::{upload_image, Access, Context, Image, ImageDesc};
use ash::vk;
use std::sync::Arc;

/// 4x4 random rotation vectors of the pattern.
const RANDOM: Slot = Slot::Own(0);
/// Without reuse: this frame's AO, and its blur.
const RAW: Slot = Slot::Own(1);
const BLURRED: Slot = Slot::Own(2);

const ACCUMULATE: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, RANDOM, Use::Sampled),
    Bind::new(3, Slot::State, Use::StorageRead),
    Bind::new(4, Slot::History, Use::StorageReadWrite),
    Bind::new(5, Slot::Counters, Use::WorkList),
    Bind::new(6, Slot::Moments, Use::StorageReadWrite),
];

const FULL: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, RANDOM, Use::Sampled),
    Bind::new(3, RAW, Use::StorageWrite),
    Bind::new(4, Slot::Counters, Use::BufferReadWrite),
];

const BLUR: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, RAW, Use::Sampled),
    Bind::new(2, BLURRED, Use::StorageWrite),
];

pub const REGISTRATION: Registration = Registration {
    id: EffectId::Ao,
    enabled: |c| c.effects.ao,
    create: |s| Ok(Box::new(AoEffect::new(s)?)),
    layouts,
};

fn layouts() -> Vec<PassLayout> {
    vec![
        ComputePass::layout(
            PassId::Ssao,
            &shaders::SSAO_ACCUMULATE_COMP_BLOCKS,
            ACCUMULATE,
        ),
        ComputePass::layout(
            PassId::SsaoRefresh,
            &shaders::SSAO_ACCUMULATE_COMP_REFRESH,
            ACCUMULATE,
        ),
        ComputePass::layout(PassId::Ssao, &shaders::SSAO_FULL_COMP, FULL),
        ComputePass::layout(PassId::Blur, &shaders::BLUR_COMP, BLUR),
    ]
}

/// Size-dependent images.
struct Sized {
    temporal: TemporalEffect,
    raw: Image,
    blurred: Image,
}

pub struct AoEffect {
    reuse: bool,
    ssao: ComputePass,
    /// With reuse: the refresh tile, one workgroup per pixel.
    refresh: Option<ComputePass>,
    /// The no-reuse baseline's blur (single-pattern runs only; references are not blurred).
    blur: Option<ComputePass>,
    random: Image,
    sized: Sized,
    push: EffectPush,
}

impl AoEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let reuse = s.config.temporal.reuse;
        let random = Image::new(
            s.ctx,
            "ao.random_vectors",
            ImageDesc {
                width: 4,
                height: 4,
                format: vk::Format::R32G32B32A32_SFLOAT,
                usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            },
        )?;
        upload_image(
            s.ctx,
            s.tracker,
            &random,
            &random_vectors(),
            Access::ComputeSampledRead,
        )?;
        let (module, binds) = if reuse {
            (&shaders::SSAO_ACCUMULATE_COMP_BLOCKS, ACCUMULATE)
        } else {
            (&shaders::SSAO_FULL_COMP, FULL)
        };
        let blur = if !reuse && s.config.ao.patterns == 1 {
            Some(ComputePass::new(
                s.ctx,
                s.pool,
                PassId::Blur,
                &shaders::BLUR_COMP,
                BLUR,
            )?)
        } else {
            None
        };
        let refresh = if reuse {
            Some(ComputePass::new(
                s.ctx,
                s.pool,
                PassId::SsaoRefresh,
                &shaders::SSAO_ACCUMULATE_COMP_REFRESH,
                ACCUMULATE,
            )?)
        } else {
            None
        };
        Ok(Self {
            reuse,
            ssao: ComputePass::new(s.ctx, s.pool, PassId::Ssao, module, binds)?,
            refresh,
            blur,
            random,
            sized: Self::create_sized(s.ctx, s.config)?,
            push: EffectPush::default(),
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let image = |name: &str| {
            Image::new(
                ctx,
                name,
                ImageDesc {
                    width: c.width,
                    height: c.height,
                    format: AO_FORMAT,
                    usage: vk::ImageUsageFlags::STORAGE
                        | vk::ImageUsageFlags::SAMPLED
                        | vk::ImageUsageFlags::TRANSFER_SRC,
                },
            )
        };
        Ok(Sized {
            temporal: TemporalEffect::new(ctx, effect::AO, c, Sampling::FullRes)?,
            raw: image("ao.raw")?,
            blurred: image("ao.blurred")?,
        })
    }

    fn resources<'a>(
        &'a self,
        targets: &'a Targets,
        own: &'a [[&'a Image; 2]; 3],
    ) -> EffectResources<'a> {
        EffectResources {
            targets,
            temporal: Some(&self.sized.temporal),
            own,
            own_buffers: &[],
        }
    }

    fn own(&self) -> [[&Image; 2]; 3] {
        let s = &self.sized;
        [
            [&self.random, &self.random],
            [&s.raw, &s.raw],
            [&s.blurred, &s.blurred],
        ]
    }
}

impl Effect for AoEffect {
    fn id(&self) -> EffectId {
        EffectId::Ao
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let own = self.own();
        let res = self.resources(targets, &own);
        self.ssao.bind(ctx, &res)?;
        if let Some(p) = &self.refresh {
            p.bind(ctx, &res)?;
        }
        if let Some(b) = &self.blur {
            b.bind(ctx, &res)?;
        }
        Ok(())
    }

    fn temporal(&self) -> Option<&TemporalEffect> {
        Some(&self.sized.temporal)
    }

    fn temporal_mut(&mut self) -> Option<&mut TemporalEffect> {
        Some(&mut self.sized.temporal)
    }

    fn prepare(&mut self, info: &FrameInfo<'_>) {
        let t = &info.config.temporal;
        self.push = self
            .sized
            .temporal
            .frame_push(info.reusing(), t.refresh, 0, info.camera_moved);
    }

    fn reprojects(&self, info: &FrameInfo<'_>) -> bool {
        info.config.temporal.reuse
    }

    fn push(&self) -> &EffectPush {
        &self.push
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let own = self.own();
        let res = self.resources(info.targets, &own);
        let push = self.push.to_bytes();
        // The every-pixel baseline has no work list and no push constants.
        let (push, dispatch): (&[u8], _) = if self.reuse {
            (&push, Dispatch::Indirect { offset: 0 })
        } else {
            (&[], every_pixel(info))
        };
        r.timed(PassId::Ssao, |rec, tr| {
            self.ssao.record(rec, tr, info.frame, &res, push, dispatch)
        });
        if let (Some(p), Some(tile)) = (&self.refresh, refresh_dispatch(&self.push)) {
            r.timed(PassId::SsaoRefresh, |rec, tr| {
                p.record(rec, tr, info.frame, &res, push, tile)
            });
        }
        if let Some(blur) = &self.blur {
            r.timed(PassId::Blur, |rec, tr| {
                blur.record(rec, tr, info.frame, &res, &[], every_pixel(info))
            });
        }
    }

    fn term(&self, parity: usize) -> (TermKind, &Image) {
        let s = &self.sized;
        let image = if self.reuse {
            s.temporal.history.current(parity)
        } else if self.blur.is_some() {
            &s.blurred
        } else {
            &s.raw
        };
        (TermKind::AmbientVisibility, image)
    }

    fn target(&self, target: Target, parity: usize, _config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Ao => Some(self.term(parity).1),
            Target::State => Some(&self.sized.temporal.state),
            _ => None,
        }
    }
}
