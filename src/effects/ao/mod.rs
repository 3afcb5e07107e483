//! SSAO (Lin 2013 eqs 6-8, or Mittring's sphere). With reuse: an indirect dispatch over the
//! blocks the reprojection listed, one pattern per pixel merged into the AO history (the
//! gated running mean, or eqs 4-5), refresh tiles recomputed as the mean of every pattern; GTAO
//! under camera motion denoises each pattern before the merge (`--gtao-moving-denoise`,
//! shaders/ao/gtao_moving.comp). Without reuse: every pixel with a fixed
//! pattern (or many patterns, for references), then the thesis's 5x5 Gaussian blur (GTAO: its
//! own edge-aware denoise, shaders/ao/gtao_denoise.comp). With
//! `--ao-position-mips`, a pass first writes point-sampled levels of the G-buffer position that
//! far taps read.

pub mod args;
pub mod config;
pub mod params;
pub mod sweep;

use self::config::AoEstimator;
use super::effect::{
    every_pixel, refresh_dispatch, Effect, EffectId, FrameInfo, Recording, Registration, Setup,
    TermKind,
};
use super::resolve::EffectResources;
use crate::config::RenderConfig;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch, PassDecl};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::counters::{Counter, Role};
use crate::resources::random::random_vectors;
use crate::resources::targets::{
    EffectView, Look, Target, Targets, AO_FORMAT, GBUFFER_COLOR_FORMATS,
};
use crate::resources::temporal::Sampling;
use crate::resources::temporal_effect::{EffectKind, MovedReach, ScreenReach, TemporalEffect};
use crate::shaders::{self, EffectPush};
use crate::vk::{upload_image, Access, Buffer, Context, Image, ImageDesc};
use ash::vk;
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("ao");

pub const KIND: EffectKind = EffectKind {
    name: ID.name(),
    history_format: crate::shaders::AO_HISTORY_FORMAT,
    block_shift: 0,
    refresh_tile: 64,
    counters: &[
        ("disoccluded_pixels", Counter::Disoccluded),
        ("ssao_computed_pixels", Counter::Computed),
        ("ssao_refresh_evaluations", Counter::Refresh),
        ("ssao_invalidated_pixels", Counter::Invalidated),
        ("ssao_invocations", Counter::Invocations(Role::Gather)),
        (
            "ssao_active_invocations",
            Counter::ActiveInvocations(Role::Gather),
        ),
        (
            "ssao_serial_evaluations",
            Counter::SerialEvaluations(Role::Gather),
        ),
        (
            "ssao_refresh_invocations",
            Counter::Invocations(Role::Refresh),
        ),
        (
            "ssao_refresh_active_invocations",
            Counter::ActiveInvocations(Role::Refresh),
        ),
        (
            "ssao_refresh_serial_evaluations",
            Counter::SerialEvaluations(Role::Refresh),
        ),
    ],
    fixups: false,
    // Far taps read position levels up to `position_mips`: a block of that level's side.
    moved: MovedReach::ScreenRadius(|c| ScreenReach {
        radius: c.ao.radius,
        // Clamped as validation clamps it: a shift past 31 would overflow.
        pad_px: 1 << c.ao.position_mips.min(config::AoConfig::MAX_POSITION_MIPS),
    }),
    lit: false,
    reaccumulates: true,
};

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// Point-sampled levels of the G-buffer position for SSAO's far taps (--ao-position-mips).
    pub const AO_POSITION_CHAIN: PassId = PassId::new("ao_position_chain", &[Change::Config]);
    /// Screen-space ambient occlusion.
    pub const SSAO: PassId = PassId::new("ssao", &[Change::Camera, Change::Config]);
    /// GTAO under camera motion: each fresh pattern denoised, then merged into the history.
    pub const GTAO_MOVING: PassId = PassId::new("gtao_moving", &[Change::Camera, Change::Config]);
    /// The AO's refresh tile, every pattern, spread over threads.
    pub const SSAO_REFRESH: PassId = PassId::new("ssao_refresh", &[Change::Camera, Change::Config]);
    /// 5x5 Gaussian blur of the AO (no-reuse baseline only).
    pub const BLUR: PassId = PassId::new("blur", &[Change::Config]);
    /// GTAO's edge-aware 5x5 denoise, in place of the blur (no-reuse only).
    pub const GTAO_DENOISE: PassId = PassId::new("gtao_denoise", &[Change::Camera, Change::Config]);

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[
        AO_POSITION_CHAIN,
        SSAO,
        GTAO_MOVING,
        SSAO_REFRESH,
        BLUR,
        GTAO_DENOISE,
    ];

    /// The timing groups `bench --compare-reuse`, tables and sweeps compare (summed per frame).
    pub const GROUPS: &[(&str, &[PassId])] = &[("ao", ALL)];
}

/// 4x4 random rotation vectors of the pattern.
const RANDOM: Slot = Slot::Own("random");
/// Without reuse: this frame's AO, and its blur.
const RAW: Slot = Slot::Own("raw");
const BLURRED: Slot = Slot::Own("blurred");
/// Point-sampled levels 1-3 of the G-buffer position (far taps).
const LEVEL1: Slot = Slot::Own("position_level1");
const LEVEL2: Slot = Slot::Own("position_level2");
const LEVEL3: Slot = Slot::Own("position_level3");
/// Its parameters (params.rs), bound at 15 in the estimating passes.
const PARAMS: Slot = Slot::OwnBuffer("params");

const ACCUMULATE: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, RANDOM, Use::Sampled),
    Bind::new(3, Slot::State, Use::StorageRead),
    Bind::new(4, Slot::History, Use::StorageReadWrite),
    Bind::new(5, Slot::Counters, Use::WorkList),
    Bind::new(6, Slot::Moments, Use::StorageReadWrite),
    Bind::new(7, LEVEL1, Use::Sampled),
    Bind::new(8, LEVEL2, Use::Sampled),
    Bind::new(9, LEVEL3, Use::Sampled),
    Bind::new(15, PARAMS, Use::BufferRead),
];

/// `ACCUMULATE`'s `split` permutation: the history read for its count, each fresh pattern
/// written to RAW for GTAO_MOVING_BINDS.
const ACCUMULATE_SPLIT: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, RANDOM, Use::Sampled),
    Bind::new(3, Slot::State, Use::StorageRead),
    Bind::new(4, Slot::History, Use::StorageRead),
    Bind::new(5, Slot::Counters, Use::WorkList),
    Bind::new(7, LEVEL1, Use::Sampled),
    Bind::new(8, LEVEL2, Use::Sampled),
    Bind::new(9, LEVEL3, Use::Sampled),
    Bind::new(10, RAW, Use::StorageWrite),
    Bind::new(15, PARAMS, Use::BufferRead),
];

const GTAO_MOVING_BINDS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, RAW, Use::Sampled),
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
    Bind::new(7, LEVEL1, Use::Sampled),
    Bind::new(8, LEVEL2, Use::Sampled),
    Bind::new(9, LEVEL3, Use::Sampled),
    Bind::new(15, PARAMS, Use::BufferRead),
];

const CHAIN: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, LEVEL1, Use::StorageWrite),
    Bind::new(2, LEVEL2, Use::StorageWrite),
    Bind::new(3, LEVEL3, Use::StorageWrite),
];

const BLUR: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, RAW, Use::Sampled),
    Bind::new(2, BLURRED, Use::StorageWrite),
];

const DENOISE: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, RAW, Use::Sampled),
    Bind::new(3, BLURRED, Use::StorageWrite),
];

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "ao",
    enabled: |c| c.effects.ao,
    create: |s| Ok(Box::new(AoEffect::new(s)?)),
    layouts,
    passes: pass::ALL,
    timing_groups: pass::GROUPS,
    sweep_keys: sweep::SWEEP_KEYS,
    ambient: true,
    views: &VIEWS,
    estimates: |_| Terms::AMBIENT_OCCLUSION,
    toggles: &[],
    recompute_mask: Some(0),
};

/// Without reuse: this frame's AO before the blur or GTAO's denoise (only when one runs). GTAO
/// with the cache and `moving_denoise`: the fresh patterns of the last frame the camera moved,
/// before their denoise (only at the pixels that estimated one then).
pub const RAW_VIEW: EffectView = EffectView {
    name: "ao_raw",
    look: Look::Red,
    in_viewer: false,
};

/// With reuse: the history's moments (r: the mean squared visibility of the estimates in the
/// gated mean, g: a pending gate crossing, b: the estimates in that mean since it last
/// restarted).
pub const MOMENTS_VIEW: EffectView = EffectView {
    name: "ao_moments",
    look: Look::Red,
    in_viewer: false,
};

/// The effect's views: the point-sampled G-buffer position levels the far taps read
/// (`--ao-position-mips`), then the raw AO and the history's moments.
const VIEWS: [EffectView; 5] = [
    level_view("ao_position_level1"),
    level_view("ao_position_level2"),
    level_view("ao_position_level3"),
    RAW_VIEW,
    MOMENTS_VIEW,
];

/// The position levels (the first three views).
pub const POSITION_LEVELS: &[EffectView] = VIEWS.split_at(3).0;

const fn level_view(name: &'static str) -> EffectView {
    EffectView {
        name,
        look: Look::Position,
        in_viewer: false,
    }
}

// Every pass of the effect, declared once (`PassDecl`): `layouts` and `new` both read these.
const SSAO_ACCUMULATE_BLOCKS: PassDecl = PassDecl::new(
    pass::SSAO,
    &shaders::SSAO_ACCUMULATE_COMP_BLOCKS,
    ACCUMULATE,
);
const SSAO_ACCUMULATE_REFRESH: PassDecl = PassDecl::new(
    pass::SSAO_REFRESH,
    &shaders::SSAO_ACCUMULATE_COMP_REFRESH,
    ACCUMULATE,
);
const SSAO_ACCUMULATE_SPLIT: PassDecl = PassDecl::new(
    pass::SSAO,
    &shaders::SSAO_ACCUMULATE_COMP_SPLIT,
    ACCUMULATE_SPLIT,
);
const GTAO_MOVING_PASS: PassDecl = PassDecl::new(
    pass::GTAO_MOVING,
    &shaders::GTAO_MOVING_COMP,
    GTAO_MOVING_BINDS,
);
const SSAO_FULL: PassDecl = PassDecl::new(pass::SSAO, &shaders::SSAO_FULL_COMP, FULL);
const BLUR_PASS: PassDecl = PassDecl::new(pass::BLUR, &shaders::BLUR_COMP, BLUR);
const GTAO_DENOISE_PASS: PassDecl =
    PassDecl::new(pass::GTAO_DENOISE, &shaders::GTAO_DENOISE_COMP, DENOISE);
const AO_POSITION_CHAIN: PassDecl = PassDecl::new(
    pass::AO_POSITION_CHAIN,
    &shaders::AO_POSITION_CHAIN_COMP,
    CHAIN,
);

fn layouts() -> Vec<PassLayout> {
    vec![
        SSAO_ACCUMULATE_BLOCKS.layout(),
        SSAO_ACCUMULATE_REFRESH.layout(),
        SSAO_ACCUMULATE_SPLIT.layout(),
        GTAO_MOVING_PASS.layout(),
        SSAO_FULL.layout(),
        BLUR_PASS.layout(),
        GTAO_DENOISE_PASS.layout(),
        AO_POSITION_CHAIN.layout(),
    ]
}

/// Size-dependent images.
struct Sized {
    temporal: TemporalEffect,
    raw: Image,
    blurred: Image,
    /// Levels 1-3 of the position chain (created whatever `position_mips` is: the SSAO passes
    /// bind them either way, and they are small).
    levels: [Image; 3],
}

pub struct AoEffect {
    reuse: bool,
    ssao: ComputePass,
    /// With reuse: the refresh tile, one workgroup per pixel.
    refresh: Option<ComputePass>,
    /// GTAO with reuse and `moving_denoise`: `split` and the merge (GTAO_MOVING), recorded in
    /// place of `ssao` while the camera moves.
    moving: Option<(ComputePass, ComputePass)>,
    /// `moving` has written the raw image since it was created (its view is readable).
    moving_wrote: bool,
    /// The no-reuse baseline's blur, GTAO's denoise (single-pattern runs only; references are
    /// not blurred).
    blur: Option<ComputePass>,
    /// Writes the position levels (`--ao-position-mips` above 0).
    chain: Option<ComputePass>,
    random: Image,
    params: Buffer,
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
        let ssao = if reuse {
            &SSAO_ACCUMULATE_BLOCKS
        } else {
            &SSAO_FULL
        };
        let blur = if !reuse && s.config.ao.patterns == 1 {
            let decl = match s.config.ao.estimator {
                AoEstimator::Gtao => &GTAO_DENOISE_PASS,
                _ => &BLUR_PASS,
            };
            Some(ComputePass::declared(s.ctx, s.pool, decl)?)
        } else {
            None
        };
        let chain = if s.config.ao.position_mips > 0 {
            Some(ComputePass::declared(s.ctx, s.pool, &AO_POSITION_CHAIN)?)
        } else {
            None
        };
        // The estimating passes are specialized for the estimator (ao.glsl's AO_ESTIMATOR).
        let estimating = |decl: &PassDecl| {
            ComputePass::declared_with(s.ctx, s.pool, decl, &[s.config.ao.estimator.code()])
        };
        let refresh = if reuse {
            Some(estimating(&SSAO_ACCUMULATE_REFRESH)?)
        } else {
            None
        };
        let moving =
            if reuse && s.config.ao.estimator == AoEstimator::Gtao && s.config.ao.moving_denoise {
                Some((
                    estimating(&SSAO_ACCUMULATE_SPLIT)?,
                    ComputePass::declared(s.ctx, s.pool, &GTAO_MOVING_PASS)?,
                ))
            } else {
                None
            };
        Ok(Self {
            reuse,
            ssao: estimating(ssao)?,
            refresh,
            moving,
            moving_wrote: false,
            blur,
            chain,
            random,
            params: params::buffer(s.ctx, s.tracker, s.config)?,
            sized: Self::create_sized(s.ctx, s.config)?,
            push: EffectPush::default(),
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let level = |l: u32| {
            let side = |n: u32| n.div_ceil(1 << l);
            Image::new(
                ctx,
                &format!("ao.position_level{l}"),
                ImageDesc {
                    width: side(c.width),
                    height: side(c.height),
                    format: GBUFFER_COLOR_FORMATS[0],
                    usage: vk::ImageUsageFlags::STORAGE
                        | vk::ImageUsageFlags::SAMPLED
                        | vk::ImageUsageFlags::TRANSFER_SRC,
                },
            )
        };
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
            temporal: TemporalEffect::new(ctx, KIND, c, Sampling::FullRes)?,
            raw: image("ao.raw")?,
            blurred: image("ao.blurred")?,
            levels: [level(1)?, level(2)?, level(3)?],
        })
    }

    fn resources<'a>(
        &'a self,
        targets: &'a Targets,
        own: &'a [(Slot, [&'a Image; 2]); 6],
        buffers: &'a [(Slot, &'a Buffer); 1],
    ) -> EffectResources<'a> {
        EffectResources {
            targets,
            temporal: Some(&self.sized.temporal),
            own,
            own_buffers: buffers,
        }
    }

    /// The AO visibility the composite reads for parity `parity`.
    fn visibility(&self, parity: usize) -> &Image {
        let s = &self.sized;
        if self.reuse {
            s.temporal.history.current(parity)
        } else if self.blur.is_some() {
            &s.blurred
        } else {
            &s.raw
        }
    }

    /// Whether `moving` records this frame: the camera moved since a frame whose histories it
    /// holds (not a first frame, where every pixel is new, nor a still one).
    fn moving_records(&self, info: &FrameInfo<'_>) -> bool {
        self.moving.is_some() && info.camera_moved && info.reusing()
    }

    fn own(&self) -> [(Slot, [&Image; 2]); 6] {
        let s = &self.sized;
        let [l1, l2, l3] = &s.levels;
        [
            (RANDOM, [&self.random, &self.random]),
            (RAW, [&s.raw, &s.raw]),
            (BLURRED, [&s.blurred, &s.blurred]),
            (LEVEL1, [l1, l1]),
            (LEVEL2, [l2, l2]),
            (LEVEL3, [l3, l3]),
        ]
    }
}

impl Effect for AoEffect {
    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn accumulating(&self) -> &'static [PassId] {
        &[pass::SSAO, pass::GTAO_MOVING, pass::SSAO_REFRESH]
    }

    fn id(&self) -> EffectId {
        ID
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        self.moving_wrote = false;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let own = self.own();
        let buffers = [(PARAMS, &self.params)];
        let res = self.resources(targets, &own, &buffers);
        self.ssao.bind(ctx, &res)?;
        if let Some(p) = &self.refresh {
            p.bind(ctx, &res)?;
        }
        if let Some((split, merge)) = &self.moving {
            split.bind(ctx, &res)?;
            merge.bind(ctx, &res)?;
        }
        if let Some(b) = &self.blur {
            b.bind(ctx, &res)?;
        }
        if let Some(c) = &self.chain {
            c.bind(ctx, &res)?;
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
        self.push = self.sized.temporal.frame_push(
            info.reusing(),
            t.refresh,
            0,
            info.camera_moved,
            info.refresh_cover(false, false),
        );
        self.moving_wrote |= self.moving_records(info);
    }

    fn reprojects(&self, info: &FrameInfo<'_>) -> bool {
        info.config.temporal.reuse
    }

    fn push(&self) -> &EffectPush {
        &self.push
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let own = self.own();
        let buffers = [(PARAMS, &self.params)];
        let res = self.resources(info.targets, &own, &buffers);
        let push = self.push.to_bytes();
        // The every-pixel baseline has no work list and no push constants.
        let (push, dispatch): (&[u8], _) = if self.reuse {
            (&push, Dispatch::Indirect { offset: 0 })
        } else {
            (&[], every_pixel(info))
        };
        if let Some(chain) = &self.chain {
            let d = &self.sized.levels[0].desc;
            let level1 = Dispatch::Pixels {
                width: d.width,
                height: d.height,
            };
            r.timed(pass::AO_POSITION_CHAIN, |rec, tr| {
                chain.record(rec, tr, info.frame, &res, &[], level1)
            });
        }
        match &self.moving {
            Some((split, merge)) if self.moving_records(info) => {
                r.timed(pass::SSAO, |rec, tr| {
                    split.record(rec, tr, info.frame, &res, push, dispatch)
                });
                r.timed(pass::GTAO_MOVING, |rec, tr| {
                    merge.record(rec, tr, info.frame, &res, push, dispatch)
                });
            }
            _ => r.timed(pass::SSAO, |rec, tr| {
                self.ssao.record(rec, tr, info.frame, &res, push, dispatch)
            }),
        }
        if let (Some(p), Some(tile)) = (&self.refresh, refresh_dispatch(&self.push)) {
            r.timed(pass::SSAO_REFRESH, |rec, tr| {
                p.record(rec, tr, info.frame, &res, push, tile)
            });
        }
        if let Some(blur) = &self.blur {
            r.timed(blur.id, |rec, tr| {
                blur.record(rec, tr, info.frame, &res, &[], every_pixel(info))
            });
        }
    }

    fn term<'a>(&'a self, _targets: &'a Targets, parity: usize) -> (TermKind, &'a Image) {
        (TermKind::AmbientVisibility, self.visibility(parity))
    }

    fn target(&self, target: Target, parity: usize, _config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Ao => Some(self.visibility(parity)),
            Target::State => Some(&self.sized.temporal.state),
            // Written by the blur's or denoise's input, or by GTAO's `split` under motion.
            Target::Effect(v) if *v == RAW_VIEW => {
                (self.blur.is_some() || self.moving_wrote).then_some(&self.sized.raw)
            }
            Target::Effect(v) if *v == MOMENTS_VIEW => self
                .reuse
                .then(|| self.sized.temporal.moments.current(parity)),
            // Only when the chain writes them (otherwise they hold nothing).
            Target::Effect(v) if self.chain.is_some() => POSITION_LEVELS
                .iter()
                .position(|l| l == v)
                .map(|i| &self.sized.levels[i]),
            _ => None,
        }
    }
}
