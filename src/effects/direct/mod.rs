//! Direct light from the spot light with PCF shadows from the light view's depth. Shadow
//! visibility every frame over all pixels for grid kernels (hard, 49 samples) and for disc
//! kernels without reuse; with reuse and a disc, the thesis's 9-sample PCF rotated and scaled
//! per frame and accumulated over the blocks that need work. Then the direct pass:
//! rgb = outgoing diffuse radiance albedo/pi * E * V, a = V.

pub mod sweep;

use super::effect::{
    every_pixel, refresh_dispatch, Effect, EffectId, FrameInfo, Recording, Registration, Setup,
    TermKind,
};
use super::resolve::EffectResources;
use crate::config::pcf::{Pcf, PcfKernel};
use crate::config::RenderConfig;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch, PassDecl};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::counters::{Counter, Role};
use crate::resources::targets::{Target, Targets, AO_FORMAT};
use crate::resources::temporal::Sampling;
use crate::resources::temporal_effect::{EffectKind, MovedReach, TemporalEffect};
use crate::shaders::{self, EffectPush};
use crate::vk::{Context, Image, ImageDesc};
use ash::vk;
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("direct");

pub const KIND: EffectKind = EffectKind {
    // The cache holds the shadow term alone, not the direct light: its images are named so.
    name: "shadow",
    history_format: crate::shaders::SHADOW_HISTORY_FORMAT,
    block_shift: 0,
    refresh_tile: 64,
    counters: &[
        ("shadow_computed_pixels", Counter::Computed),
        ("shadow_refresh_evaluations", Counter::Refresh),
        ("shadow_invalidated_pixels", Counter::Invalidated),
        ("shadow_invocations", Counter::Invocations(Role::Gather)),
        (
            "shadow_active_invocations",
            Counter::ActiveInvocations(Role::Gather),
        ),
        (
            "shadow_serial_evaluations",
            Counter::SerialEvaluations(Role::Gather),
        ),
        (
            "shadow_refresh_invocations",
            Counter::Invocations(Role::Refresh),
        ),
        (
            "shadow_refresh_active_invocations",
            Counter::ActiveInvocations(Role::Refresh),
        ),
        (
            "shadow_refresh_serial_evaluations",
            Counter::SerialEvaluations(Role::Refresh),
        ),
    ],
    fixups: false,
    moved: MovedReach::ShadowFootprint,
    lit: true,
    reaccumulates: true,
};

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// PCF shadow visibility (every frame, or accumulated with the cache).
    pub const SHADOW: PassId =
        PassId::new("shadow", &[Change::Camera, Change::Light, Change::Config]);
    /// The shadow's refresh tile, every pattern, spread over threads.
    pub const SHADOW_REFRESH: PassId = PassId::new(
        "shadow_refresh",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// Direct spot light times the shadow visibility.
    pub const DIRECT: PassId = PassId::new("direct", &[Change::Light, Change::Config]);

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[SHADOW, SHADOW_REFRESH, DIRECT];

    /// The timing groups `bench --compare-reuse`, tables and sweeps compare (summed per frame).
    pub const GROUPS: &[(&str, &[PassId])] =
        &[("shadow", &[SHADOW, SHADOW_REFRESH]), ("direct", &[DIRECT])];
}

/// Shadow visibility computed every frame.
const SHADOW: Slot = Slot::Own("shadow");
/// The visibility the direct pass reads: `SHADOW`, or the accumulated history.
const VISIBILITY: Slot = Slot::Own("visibility");
const DIRECT: Slot = Slot::DirectLight;

const SHADOW_FULL: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::RsmDepth, Use::Sampled),
    Bind::new(3, SHADOW, Use::StorageWrite),
];

const SHADOW_ACCUMULATE: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::RsmDepth, Use::Sampled),
    Bind::new(3, Slot::State, Use::StorageRead),
    Bind::new(4, Slot::History, Use::StorageReadWrite),
    Bind::new(5, Slot::Counters, Use::WorkList),
    Bind::new(6, Slot::Moments, Use::StorageReadWrite),
];

const DIRECT_LIGHT: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GAlbedo, Use::Sampled),
    Bind::new(3, VISIBILITY, Use::Sampled),
    Bind::new(4, DIRECT, Use::StorageWrite),
];

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "direct",
    enabled: |c| c.effects.direct,
    create: |s| Ok(Box::new(DirectEffect::new(s)?)),
    layouts,
    passes: pass::ALL,
    timing_groups: pass::GROUPS,
    sweep_keys: sweep::SWEEP_KEYS,
    ambient: false,
    views: &[],
    estimates: |_| Terms::DIRECT,
    toggles: &[],
    recompute_mask: Some(1),
};

// Every pass of the effect, declared once (`PassDecl`): `layouts` and `new` both read these.
const SHADOW_FULL_PASS: PassDecl =
    PassDecl::new(pass::SHADOW, &shaders::SHADOW_FULL_COMP, SHADOW_FULL);
const SHADOW_ACCUMULATE_BLOCKS: PassDecl = PassDecl::new(
    pass::SHADOW,
    &shaders::SHADOW_ACCUMULATE_COMP_BLOCKS,
    SHADOW_ACCUMULATE,
);
const SHADOW_ACCUMULATE_REFRESH: PassDecl = PassDecl::new(
    pass::SHADOW_REFRESH,
    &shaders::SHADOW_ACCUMULATE_COMP_REFRESH,
    SHADOW_ACCUMULATE,
);
const DIRECT_PASS: PassDecl = PassDecl::new(pass::DIRECT, &shaders::DIRECT_COMP, DIRECT_LIGHT);

fn layouts() -> Vec<PassLayout> {
    vec![
        SHADOW_FULL_PASS.layout(),
        SHADOW_ACCUMULATE_BLOCKS.layout(),
        SHADOW_ACCUMULATE_REFRESH.layout(),
        DIRECT_PASS.layout(),
    ]
}

/// What reuse adds: the accumulating shadow pass and a direct pass whose sets read the
/// history (the reprojection is the renderer's, one lane per temporal effect).
struct Reuse {
    accumulate: ComputePass,
    /// The refresh tile, one workgroup per pixel.
    refresh: ComputePass,
    direct_from_history: ComputePass,
}

struct Sized {
    shadow: Image,
    /// With reuse (used while the kernel is a disc).
    temporal: Option<TemporalEffect>,
}

pub struct DirectEffect {
    shadow_full: ComputePass,
    direct: ComputePass,
    reuse: Option<Reuse>,
    sized: Sized,
    push: EffectPush,
    /// The kernel the last frame recorded accumulated shadows with. A history left while a
    /// grid ran (the viewer's soft-shadow switch) belongs to an older view and light, and one
    /// of another kernel to another estimator: either restarts.
    accumulated: Option<Pcf>,
}

/// Whether shadows come from the accumulated history this frame: reuse on and a disc kernel
/// (the thesis's rotated and scaled 9-sample PCF). Grids run every frame. The viewer changes
/// the kernel in place, so this is decided per frame.
fn shadow_reuse(config: &RenderConfig) -> bool {
    config.temporal.reuse && matches!(config.pcf.kernel, PcfKernel::Disc { .. })
}

impl DirectEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let direct = ComputePass::declared(s.ctx, s.pool, &DIRECT_PASS)?;
        let reuse = if s.config.temporal.reuse {
            Some(Reuse {
                accumulate: ComputePass::declared(s.ctx, s.pool, &SHADOW_ACCUMULATE_BLOCKS)?,
                refresh: ComputePass::declared(s.ctx, s.pool, &SHADOW_ACCUMULATE_REFRESH)?,
                direct_from_history: direct.instance(s.pool, "direct from shadow history")?,
            })
        } else {
            None
        };
        Ok(Self {
            shadow_full: ComputePass::declared(s.ctx, s.pool, &SHADOW_FULL_PASS)?,
            direct,
            reuse,
            sized: Self::create_sized(s.ctx, s.config)?,
            push: EffectPush::default(),
            accumulated: None,
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let image = |name: &str, format| {
            Image::new(
                ctx,
                name,
                ImageDesc {
                    width: c.width,
                    height: c.height,
                    format,
                    usage: vk::ImageUsageFlags::STORAGE
                        | vk::ImageUsageFlags::SAMPLED
                        | vk::ImageUsageFlags::TRANSFER_SRC,
                },
            )
        };
        Ok(Sized {
            shadow: image("shadow", AO_FORMAT)?,
            temporal: if c.temporal.reuse {
                Some(TemporalEffect::new(ctx, KIND, c, Sampling::FullRes)?)
            } else {
                None
            },
        })
    }

    /// The effect's images; `VISIBILITY` is the history when `from_history`.
    fn own(&self, from_history: bool) -> [(Slot, [&Image; 2]); 2] {
        let s = &self.sized;
        let visibility = match (&s.temporal, from_history) {
            (Some(t), true) => [t.history.current(0), t.history.current(1)],
            _ => [&s.shadow, &s.shadow],
        };
        [(SHADOW, [&s.shadow, &s.shadow]), (VISIBILITY, visibility)]
    }

    fn resources<'a>(
        &'a self,
        targets: &'a Targets,
        own: &'a [(Slot, [&'a Image; 2]); 2],
    ) -> EffectResources<'a> {
        EffectResources {
            targets,
            temporal: self.sized.temporal.as_ref(),
            own,
            own_buffers: &[],
        }
    }

    /// The shadow visibility the direct pass reads this frame.
    fn visibility(&self, config: &RenderConfig, parity: usize) -> &Image {
        match (&self.sized.temporal, shadow_reuse(config)) {
            (Some(t), true) => t.history.current(parity),
            _ => &self.sized.shadow,
        }
    }
}

impl Effect for DirectEffect {
    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn accumulating(&self) -> &'static [PassId] {
        &[pass::SHADOW, pass::SHADOW_REFRESH]
    }

    fn id(&self) -> EffectId {
        ID
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let own = self.own(false);
        let res = self.resources(targets, &own);
        self.shadow_full.bind(ctx, &res)?;
        self.direct.bind(ctx, &res)?;
        if let Some(r) = &self.reuse {
            r.accumulate.bind(ctx, &res)?;
            r.refresh.bind(ctx, &res)?;
            let own = self.own(true);
            r.direct_from_history
                .bind(ctx, &self.resources(targets, &own))?;
        }
        Ok(())
    }

    fn temporal(&self) -> Option<&TemporalEffect> {
        self.sized.temporal.as_ref()
    }

    fn temporal_mut(&mut self) -> Option<&mut TemporalEffect> {
        self.sized.temporal.as_mut()
    }

    fn counts(&self, config: &RenderConfig) -> bool {
        shadow_reuse(config) && self.sized.temporal.is_some()
    }

    fn prepare(&mut self, info: &FrameInfo<'_>) {
        let now = self.counts(info.config).then_some(info.config.pcf);
        let before = std::mem::replace(&mut self.accumulated, now);
        if now.is_none() {
            return;
        }
        let refresh = info.config.temporal.refresh;
        if let Some(t) = &mut self.sized.temporal {
            // A moved light moves every shadow; a moving object only its own (the lane's
            // shadow-footprint reach).
            self.push = t.frame_push(
                before == now && info.keeps_history(true, false),
                refresh,
                0,
                info.camera_moved,
                info.refresh_cover(true, false),
            );
        }
    }

    fn reprojects(&self, info: &FrameInfo<'_>) -> bool {
        self.counts(info.config)
    }

    fn push(&self) -> &EffectPush {
        &self.push
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let accumulated = self.reuse.as_ref().filter(|_| self.counts(info.config));
        let own = self.own(accumulated.is_some());
        let res = self.resources(info.targets, &own);
        let push = self.push.to_bytes();
        let (shadow, direct, push, dispatch): (_, _, &[u8], _) = match accumulated {
            Some(reuse) => (
                &reuse.accumulate,
                &reuse.direct_from_history,
                &push,
                Dispatch::Indirect { offset: 0 },
            ),
            None => (&self.shadow_full, &self.direct, &[], every_pixel(info)),
        };
        r.timed(pass::SHADOW, |rec, tr| {
            shadow.record(rec, tr, info.frame, &res, push, dispatch)
        });
        if let (Some(reuse), Some(tile)) = (accumulated, refresh_dispatch(&self.push)) {
            r.timed(pass::SHADOW_REFRESH, |rec, tr| {
                reuse.refresh.record(rec, tr, info.frame, &res, push, tile)
            });
        }
        r.timed(pass::DIRECT, |rec, tr| {
            direct.record(rec, tr, info.frame, &res, &[], every_pixel(info))
        });
    }

    fn term<'a>(&'a self, targets: &'a Targets, _parity: usize) -> (TermKind, &'a Image) {
        (TermKind::Radiance, &targets.direct)
    }

    fn target(&self, target: Target, parity: usize, config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Shadow => Some(self.visibility(config, parity)),
            Target::State => self.sized.temporal.as_ref().map(|t| &t.state),
            _ => None,
        }
    }
}
