//! One-bounce indirect light from the reflective shadow map (Lin 2013 section 3.3, eqs 9-10):
//! the gather at half resolution over a compacted list of the low-resolution samples that
//! pixels needing work read (over the listed blocks with interleaving), geometry-aware
//! upsampling with a discard mask, and a full-resolution fix-up over the compacted list of
//! discarded pixels, all merged into the indirect history. Without half resolution, one
//! full-resolution gather per block. The fix-up and the refresh tile spread each estimate's
//! VPLs over a workgroup (indirect_spread.comp); at half resolution the refresh gathers the
//! tile's low-resolution samples and upsamples their pattern means, the estimator the
//! accumulation converges to. It always goes through the reprojection:
//! without reuse every pixel is new and every block listed, with the fixed pattern 0.

pub mod args;
pub mod config;
pub mod params;
pub mod sweep;

use super::effect::{
    refresh_pixels, Effect, EffectId, FrameInfo, Recording, Registration, Setup, TermKind,
};
use super::resolve::EffectResources;
use crate::config::{IndirectFilter, RenderConfig};
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch, PassDecl};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::counters::{Counter, Role, FIXUP_DISPATCH_OFFSET, LOWRES_DISPATCH_OFFSET};
use crate::resources::targets::{Target, Targets, STATE_FORMAT};
use crate::resources::temporal::{tile_evaluations, Sampling};
use crate::resources::temporal_effect::{EffectKind, MovedReach, TemporalEffect};
use crate::shaders::{self, EffectPush};
use crate::vk::recorder::Recorder;
use crate::vk::{Access, Buffer, Context, Image, ImageDesc, Tracker};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::cell::Cell;
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("indirect");

pub const KIND: EffectKind = EffectKind {
    name: ID.name(),
    history_format: crate::shaders::INDIRECT_HISTORY_FORMAT,
    block_shift: 4,
    refresh_tile: 16,
    counters: &[
        ("indirect_computed_pixels", Counter::Computed),
        ("indirect_fixup_pixels", Counter::Fixup),
        ("indirect_refresh_evaluations", Counter::Refresh),
        ("indirect_invalidated_pixels", Counter::Invalidated),
        ("indirect_lowres_samples", Counter::LowresSamples),
        (
            "indirect_gather_invocations",
            Counter::Invocations(Role::Gather),
        ),
        (
            "indirect_gather_active_invocations",
            Counter::ActiveInvocations(Role::Gather),
        ),
        (
            "indirect_gather_serial_evaluations",
            Counter::SerialEvaluations(Role::Gather),
        ),
        (
            "indirect_fixup_invocations",
            Counter::Invocations(Role::Fixup),
        ),
        (
            "indirect_fixup_active_invocations",
            Counter::ActiveInvocations(Role::Fixup),
        ),
        (
            "indirect_fixup_serial_evaluations",
            Counter::SerialEvaluations(Role::Fixup),
        ),
        (
            "indirect_refresh_invocations",
            Counter::Invocations(Role::Refresh),
        ),
        (
            "indirect_refresh_active_invocations",
            Counter::ActiveInvocations(Role::Refresh),
        ),
        (
            "indirect_refresh_serial_evaluations",
            Counter::SerialEvaluations(Role::Refresh),
        ),
    ],
    fixups: true,
    moved: MovedReach::Inside,
    lit: true,
    reaccumulates: true,
};

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// The per-frame filters' input: a new noisy full-resolution gather each frame (--vpls per
    /// pixel), recorded by whichever filter runs (`--indirect-filter`), not by this effect.
    pub const INDIRECT_NOISY: PassId = PassId::new(
        "indirect_noisy",
        &[Change::Camera, Change::Light, Change::Config],
    );

    /// The half-resolution gather's list: the low-resolution samples the upsampling reads.
    pub const INDIRECT_CLASSIFY: PassId = PassId::new(
        "indirect_classify",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// RSM gather (half resolution, or full resolution without half-res).
    pub const INDIRECT_GATHER: PassId = PassId::new(
        "indirect_gather",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// Geometry-aware upsampling of the half-resolution gather.
    pub const INDIRECT_UPSAMPLE: PassId = PassId::new(
        "indirect_upsample",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// Full-resolution gather of the pixels the upsampling discarded.
    pub const INDIRECT_FIXUP: PassId = PassId::new(
        "indirect_fixup",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// Indirect light's refresh tile, every pattern (at half resolution of the samples its
    /// pixels are upsampled from), spread over threads.
    pub const INDIRECT_REFRESH: PassId = PassId::new(
        "indirect_refresh",
        &[Change::Camera, Change::Light, Change::Config],
    );

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[
        INDIRECT_CLASSIFY,
        INDIRECT_GATHER,
        INDIRECT_UPSAMPLE,
        INDIRECT_FIXUP,
        INDIRECT_REFRESH,
    ];

    /// The timing groups `bench --compare-reuse`, tables and sweeps compare (summed per frame).
    pub const GROUPS: &[(&str, &[PassId])] = &[("indirect", ALL)];
}

/// 1 where the upsampling found no acceptable neighbour (Figure 4.1). Written only for the
/// pixels recomputed this frame, so it is not discarded between frames.
const DISCARD: Slot = Slot::Own("discard");
/// With interleaving: one 9x9 low-resolution tile (block plus its right and bottom apron) per
/// listed block.
const LOWRES: Slot = Slot::OwnBuffer("lowres");
/// Without: the low-resolution samples, each computed once, where the classification listed it.
const LOWRES_IMAGE: Slot = Slot::Own("lowres_image");
/// Per low-resolution sample, in rows: 1 where a workgroup of the classification listed a
/// block-border sample this frame; the gather sets it back to 0. (A buffer: naga reads no
/// image atomics.)
const CLAIMS: Slot = Slot::OwnBuffer("claims");
/// One estimate (rgb, squared luminance) per refresh-tile pixel and pattern.
const PARTIALS: Slot = Slot::OwnBuffer("partials");

/// Lanes of indirect_spread.comp's workgroups (shaders/include/shared_constants.glsl).
use crate::shaders::SPREAD_LANES;

/// Bindings 0-5 of every indirect pass.
macro_rules! gather_inputs {
    ($($rest:expr),* $(,)?) => {
        &[
            Bind::new(0, Slot::GPosition, Use::Sampled),
            Bind::new(1, Slot::GNormal, Use::Sampled),
            Bind::new(2, Slot::RsmPosition, Use::Sampled),
            Bind::new(3, Slot::RsmNormal, Use::Sampled),
            Bind::new(4, Slot::RsmFlux, Use::Sampled),
            Bind::new(5, Slot::Counters, Use::WorkList),
            Bind::new(params::BINDING, VPL_PARAMS, Use::BufferRead),
            $($rest),*
        ]
    };
}

/// The gather's parameters (params.rs), bound in every pass.
pub const VPL_PARAMS: Slot = Slot::OwnBuffer("vpl_params");

/// The per-frame filters' input image: a new noisy gather each frame (`indirect_noisy`).
pub const NOISY: Slot = Slot::Own("noisy");

/// The noisy gather the per-frame filters without state of their own in it share (the joint
/// bilateral filters, SVGF): the plain permutation of shaders/ccipca/indirect_noisy.comp into
/// `NOISY`. CCIPCA's permutation also updates its bases and declares its own.
pub const NOISY_GATHER: PassDecl = PassDecl::new(
    pass::INDIRECT_NOISY,
    &shaders::INDIRECT_NOISY_COMP_PLAIN,
    &[
        Bind::new(0, Slot::GPosition, Use::Sampled),
        Bind::new(1, Slot::GNormal, Use::Sampled),
        Bind::new(2, Slot::RsmPosition, Use::Sampled),
        Bind::new(3, Slot::RsmNormal, Use::Sampled),
        Bind::new(4, Slot::RsmFlux, Use::Sampled),
        Bind::new(5, NOISY, Use::StorageWrite),
        Bind::new(params::BINDING, VPL_PARAMS, Use::BufferRead),
    ],
);

const CLASSIFY: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(5, Slot::Counters, Use::WorkList),
    Bind::new(params::BINDING, VPL_PARAMS, Use::BufferRead),
    Bind::new(7, Slot::State, Use::StorageRead),
    Bind::new(11, CLAIMS, Use::BufferReadWrite),
];

const LOWRES_COMPACT: &[Bind] = gather_inputs![
    Bind::new(6, LOWRES_IMAGE, Use::StorageWrite),
    Bind::new(11, CLAIMS, Use::BufferReadWrite),
];

const UPSAMPLE_IMAGE: &[Bind] = gather_inputs![
    Bind::new(6, LOWRES_IMAGE, Use::StorageRead),
    Bind::new(7, Slot::History, Use::StorageReadWrite),
    Bind::new(8, Slot::State, Use::StorageRead),
    Bind::new(9, DISCARD, Use::StorageReadWrite),
    Bind::new(10, Slot::Moments, Use::StorageReadWrite),
];

/// The refresh tile's patterns into the partials, and their resolve into the history.
const REFRESH: &[Bind] = gather_inputs![
    Bind::new(6, Slot::History, Use::StorageReadWrite),
    Bind::new(7, Slot::State, Use::StorageRead),
    Bind::new(8, Slot::Moments, Use::StorageReadWrite),
    Bind::new(9, PARTIALS, Use::BufferReadWrite),
];

const LOWRES_GATHER: &[Bind] = gather_inputs![
    Bind::new(6, LOWRES, Use::BufferWrite),
    Bind::new(7, Slot::State, Use::StorageRead),
];

const UPSAMPLE: &[Bind] = gather_inputs![
    Bind::new(6, LOWRES, Use::BufferRead),
    Bind::new(7, Slot::History, Use::StorageReadWrite),
    Bind::new(8, Slot::State, Use::StorageRead),
    Bind::new(9, DISCARD, Use::StorageReadWrite),
    Bind::new(10, Slot::Moments, Use::StorageReadWrite),
];

/// The full-resolution gather over listed blocks, and the fix-up over discarded pixels.
const GATHER: &[Bind] = gather_inputs![
    Bind::new(6, Slot::History, Use::StorageReadWrite),
    Bind::new(7, Slot::State, Use::StorageRead),
    Bind::new(8, Slot::Moments, Use::StorageReadWrite),
];

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "indirect",
    enabled: |c| c.effects.indirect && c.indirect.filter == IndirectFilter::Accumulate,
    create: |s| Ok(Box::new(IndirectEffect::new(s)?)),
    layouts,
    passes: pass::ALL,
    timing_groups: pass::GROUPS,
    sweep_keys: sweep::SWEEP_KEYS,
    ambient: false,
    views: &[],
    estimates: |_| Terms::INDIRECT,
    toggles: &[],
    recompute_mask: None,
};

// Every pass of the effect, declared once (`PassDecl`): `layouts` and `new` both read these.
const INDIRECT_CLASSIFY: PassDecl = PassDecl::new(
    pass::INDIRECT_CLASSIFY,
    &shaders::INDIRECT_CLASSIFY_COMP,
    CLASSIFY,
);
const INDIRECT_SPREAD_GATHER: PassDecl = PassDecl::new(
    pass::INDIRECT_GATHER,
    &shaders::INDIRECT_SPREAD_COMP_GATHER,
    LOWRES_COMPACT,
);
const INDIRECT_LOWRES: PassDecl = PassDecl::new(
    pass::INDIRECT_GATHER,
    &shaders::INDIRECT_LOWRES_COMP,
    LOWRES_GATHER,
);
const INDIRECT_UPSAMPLE_IMAGE: PassDecl = PassDecl::new(
    pass::INDIRECT_UPSAMPLE,
    &shaders::INDIRECT_UPSAMPLE_COMP_IMAGE,
    UPSAMPLE_IMAGE,
);
const INDIRECT_UPSAMPLE_SLOTS: PassDecl = PassDecl::new(
    pass::INDIRECT_UPSAMPLE,
    &shaders::INDIRECT_UPSAMPLE_COMP_SLOTS,
    UPSAMPLE,
);
const INDIRECT_SPREAD_FIXUP: PassDecl = PassDecl::new(
    pass::INDIRECT_FIXUP,
    &shaders::INDIRECT_SPREAD_COMP_FIXUP,
    GATHER,
);
const INDIRECT_GATHER: PassDecl = PassDecl::new(
    pass::INDIRECT_GATHER,
    &shaders::INDIRECT_GATHER_COMP,
    GATHER,
);
const INDIRECT_SPREAD_REFRESH: PassDecl = PassDecl::new(
    pass::INDIRECT_REFRESH,
    &shaders::INDIRECT_SPREAD_COMP_REFRESH,
    REFRESH,
);
const INDIRECT_SPREAD_REFRESH_LOWRES: PassDecl = PassDecl::new(
    pass::INDIRECT_REFRESH,
    &shaders::INDIRECT_SPREAD_COMP_REFRESH_LOWRES,
    REFRESH,
);
const INDIRECT_SPREAD_RESOLVE: PassDecl = PassDecl::new(
    pass::INDIRECT_REFRESH,
    &shaders::INDIRECT_SPREAD_COMP_RESOLVE,
    REFRESH,
);
const INDIRECT_SPREAD_RESOLVE_LOWRES: PassDecl = PassDecl::new(
    pass::INDIRECT_REFRESH,
    &shaders::INDIRECT_SPREAD_COMP_RESOLVE_LOWRES,
    REFRESH,
);

fn layouts() -> Vec<PassLayout> {
    vec![
        INDIRECT_CLASSIFY.layout(),
        INDIRECT_SPREAD_GATHER.layout(),
        INDIRECT_LOWRES.layout(),
        INDIRECT_UPSAMPLE_IMAGE.layout(),
        INDIRECT_UPSAMPLE_SLOTS.layout(),
        INDIRECT_SPREAD_FIXUP.layout(),
        INDIRECT_GATHER.layout(),
        INDIRECT_SPREAD_REFRESH.layout(),
        INDIRECT_SPREAD_REFRESH_LOWRES.layout(),
        INDIRECT_SPREAD_RESOLVE.layout(),
        INDIRECT_SPREAD_RESOLVE_LOWRES.layout(),
    ]
}

/// How the half-resolution gather finds its samples.
enum LowRes {
    /// A list of the samples needed (classification), each sample's VPLs spread over
    /// `--vpl-lanes` lanes (no interleaving).
    Compact {
        classify: ComputePass,
        gather: ComputePass,
    },
    /// Every sample of each listed block's 9x9 tile (interleaving reconstructs across it).
    Blocks(ComputePass),
}

/// The half-resolution chain: gather, upsample, fix-up.
struct HalfRes {
    lowres: LowRes,
    upsample: ComputePass,
    fixup: ComputePass,
}

/// The gather at half or at full resolution.
enum Gather {
    /// Boxed: four passes beside the full gather's one.
    Half(Box<HalfRes>),
    Full(ComputePass),
}

struct Sized {
    temporal: TemporalEffect,
    lowres: Buffer,
    lowres_image: Image,
    claims: Buffer,
    /// Whether `claims` has been cleared (once, before its first use).
    claims_cleared: Cell<bool>,
    partials: Buffer,
    discard: Image,
}

pub struct IndirectEffect {
    gather: Gather,
    /// The refresh tile: every (pixel, pattern) spread over lanes (at half resolution every
    /// (low-resolution sample, pattern) its pixels are upsampled from), then each pixel's
    /// patterns resolved into the history.
    refresh: ComputePass,
    resolve: ComputePass,
    params: Buffer,
    sized: Sized,
    push: EffectPush,
    /// The device's maxComputeWorkGroupCount[0]: the refresh's estimates stride beyond it.
    max_groups_x: u32,
}

impl IndirectEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let pass = |decl: &PassDecl| ComputePass::declared(s.ctx, s.pool, decl);
        let gather = if s.config.indirect.half_res {
            let compact = s.config.indirect.interleave <= 1;
            let (lowres, upsample) = if compact {
                (
                    LowRes::Compact {
                        classify: pass(&INDIRECT_CLASSIFY)?,
                        gather: pass(&INDIRECT_SPREAD_GATHER)?,
                    },
                    pass(&INDIRECT_UPSAMPLE_IMAGE)?,
                )
            } else {
                (
                    LowRes::Blocks(pass(&INDIRECT_LOWRES)?),
                    pass(&INDIRECT_UPSAMPLE_SLOTS)?,
                )
            };
            Gather::Half(Box::new(HalfRes {
                lowres,
                upsample,
                fixup: pass(&INDIRECT_SPREAD_FIXUP)?,
            }))
        } else {
            Gather::Full(pass(&INDIRECT_GATHER)?)
        };
        // At half resolution the refresh computes the estimator the accumulation converges
        // to there: its low-resolution samples' patterns, upsampled by the resolve.
        let (refresh, resolve) = if s.config.indirect.half_res {
            (
                &INDIRECT_SPREAD_REFRESH_LOWRES,
                &INDIRECT_SPREAD_RESOLVE_LOWRES,
            )
        } else {
            (&INDIRECT_SPREAD_REFRESH, &INDIRECT_SPREAD_RESOLVE)
        };
        let (refresh, resolve) = (pass(refresh)?, pass(resolve)?);
        Ok(Self {
            gather,
            refresh,
            resolve,
            params: params::buffer(s.ctx, s.tracker, "indirect.vpl_params", s.config)?,
            sized: Self::create_sized(s.ctx, s.config)?,
            push: EffectPush::default(),
            max_groups_x: s.ctx.info.max_compute_work_group_count[0].max(1),
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let sampling = if c.indirect.half_res {
            Sampling::HalfRes
        } else {
            Sampling::FullRes
        };
        let temporal = TemporalEffect::new(ctx, KIND, c, sampling)?;
        let low = |name, format, usage| {
            Image::new(
                ctx,
                name,
                ImageDesc {
                    width: c.width.div_ceil(2),
                    height: c.height.div_ceil(2),
                    format,
                    usage,
                },
            )
        };
        let tile = temporal.schedule.tile();
        Ok(Sized {
            lowres_image: low(
                "indirect.lowres_image",
                vk::Format::R32G32B32A32_SFLOAT,
                vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC,
            )?,
            claims: Buffer::new(
                ctx,
                "indirect.claims",
                c.width.div_ceil(2) as u64 * c.height.div_ceil(2) as u64 * 4,
                vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuOnly,
            )?,
            claims_cleared: Cell::new(false),
            // One vec4 per tile evaluation (pixel or low-resolution sample) and pattern.
            partials: Buffer::new(
                ctx,
                "indirect.partials",
                (tile_evaluations(tile, sampling) * c.temporal.rotation_limit as u64 * 16).max(16),
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::GpuOnly,
            )?,
            // 9x9 texels of 16 bytes per block.
            lowres: Buffer::new(
                ctx,
                "indirect.lowres",
                temporal.max_blocks as u64 * 81 * 16,
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::GpuOnly,
            )?,
            discard: Image::new(
                ctx,
                "indirect.discard",
                ImageDesc {
                    width: c.width,
                    height: c.height,
                    format: STATE_FORMAT,
                    usage: vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC,
                },
            )?,
            temporal,
        })
    }

    fn own(&self) -> [(Slot, [&Image; 2]); 2] {
        let s = &self.sized;
        [
            (DISCARD, [&s.discard, &s.discard]),
            (LOWRES_IMAGE, [&s.lowres_image, &s.lowres_image]),
        ]
    }

    fn buffers(&self) -> [(Slot, &Buffer); 4] {
        let s = &self.sized;
        [
            (LOWRES, &s.lowres),
            (PARTIALS, &s.partials),
            (CLAIMS, &s.claims),
            (VPL_PARAMS, &self.params),
        ]
    }

    fn resources<'a>(
        &'a self,
        targets: &'a Targets,
        own: &'a [(Slot, [&'a Image; 2]); 2],
        buffers: &'a [(Slot, &'a Buffer); 4],
    ) -> EffectResources<'a> {
        EffectResources {
            targets,
            temporal: Some(&self.sized.temporal),
            own,
            own_buffers: buffers,
        }
    }

    fn passes(&self) -> Vec<&ComputePass> {
        let mut passes = match &self.gather {
            Gather::Half(h) => match &h.lowres {
                LowRes::Compact { classify, gather } => vec![classify, gather],
                LowRes::Blocks(p) => vec![p],
            }
            .into_iter()
            .chain([&h.upsample, &h.fixup])
            .collect(),
            Gather::Full(p) => vec![p],
        };
        passes.extend([&self.refresh, &self.resolve]);
        passes
    }

    /// The claims start at zero; afterwards the gather releases each one it was given.
    fn clear_claims(&self, rec: &Recorder<'_>, tracker: &mut Tracker) {
        if self.sized.claims_cleared.replace(true) {
            return;
        }
        tracker.buffer(&self.sized.claims, Access::TransferDst);
        tracker.flush(rec.device, rec.cmd);
        rec.fill_zero(&self.sized.claims);
    }

    /// The refresh tile's two dispatches: (pixel, pattern) estimates spread over lanes, at
    /// most the device's maxComputeWorkGroupCount[0] workgroups (they stride beyond), then
    /// one lane per pixel.
    fn refresh_dispatches(&self, config: &RenderConfig) -> Option<(Dispatch, Dispatch)> {
        let pixels = refresh_pixels(&self.push);
        if pixels == 0 {
            return None;
        }
        let per_group = SPREAD_LANES / params::lanes_per_estimate(config, SPREAD_LANES);
        let [x0, y0, x1, y1] = self.push.refresh_rect;
        let side = (x1 - x0).max(y1 - y0);
        let evaluations = if config.indirect.half_res {
            // The tile's low-resolution samples (a bound: refresh_samples clips at the edge).
            tile_evaluations(side, Sampling::HalfRes)
                .min((config.width.div_ceil(2) * config.height.div_ceil(2)) as u64)
        } else {
            pixels as u64
        };
        let estimates = evaluations * config.temporal.rotation_limit as u64;
        let groups = estimates
            .div_ceil(per_group as u64)
            .min(self.max_groups_x as u64) as u32;
        Some((
            Dispatch::Groups(groups),
            Dispatch::Groups(pixels.div_ceil(SPREAD_LANES)),
        ))
    }
}

impl Effect for IndirectEffect {
    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn accumulating(&self) -> &'static [PassId] {
        &[
            pass::INDIRECT_CLASSIFY,
            pass::INDIRECT_GATHER,
            pass::INDIRECT_UPSAMPLE,
            pass::INDIRECT_FIXUP,
            pass::INDIRECT_REFRESH,
        ]
    }

    fn id(&self) -> EffectId {
        ID
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let (own, buffers) = (self.own(), self.buffers());
        let res = self.resources(targets, &own, &buffers);
        for p in self.passes() {
            p.bind(ctx, &res)?;
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
        // A new rotated pattern every frame with reuse; the fixed pattern 0 without.
        let pattern = if t.reuse {
            (info.frame_index % t.rotation_limit as u64) as u32
        } else {
            0
        };
        // Every pixel gathers from the whole RSM: when it is rendered again, every value may
        // change.
        self.push = self.sized.temporal.frame_push(
            info.keeps_history(true, true),
            t.refresh,
            pattern,
            info.camera_moved,
            info.refresh_cover(true, true),
        );
    }

    fn reprojects(&self, _info: &FrameInfo<'_>) -> bool {
        true
    }

    fn push(&self) -> &EffectPush {
        &self.push
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let (own, buffers) = (self.own(), self.buffers());
        let res = self.resources(info.targets, &own, &buffers);
        let push = self.push.to_bytes();
        let blocks = Dispatch::Indirect { offset: 0 };
        let record = |pass: &ComputePass, rec: &Recorder<'_>, tr: &mut Tracker, dispatch| {
            pass.record(rec, tr, info.frame, &res, &push, dispatch)
        };
        match &self.gather {
            Gather::Full(p) => r.timed(p.id, |rec, tr| record(p, rec, tr, blocks)),
            Gather::Half(h) => {
                match &h.lowres {
                    LowRes::Compact { classify, gather } => {
                        r.timed(classify.id, |rec, tr| {
                            self.clear_claims(rec, tr);
                            record(classify, rec, tr, blocks)
                        });
                        let listed = Dispatch::Indirect {
                            offset: LOWRES_DISPATCH_OFFSET,
                        };
                        r.timed(gather.id, |rec, tr| record(gather, rec, tr, listed));
                    }
                    LowRes::Blocks(p) => r.timed(p.id, |rec, tr| record(p, rec, tr, blocks)),
                }
                r.timed(h.upsample.id, |rec, tr| {
                    record(&h.upsample, rec, tr, blocks)
                });
                let fixups = Dispatch::Indirect {
                    offset: FIXUP_DISPATCH_OFFSET,
                };
                r.timed(h.fixup.id, |rec, tr| record(&h.fixup, rec, tr, fixups));
            }
        }
        if let Some((estimates, pixels)) = self.refresh_dispatches(info.config) {
            r.timed(self.refresh.id, |rec, tr| {
                record(&self.refresh, rec, tr, estimates);
                record(&self.resolve, rec, tr, pixels);
            });
        }
    }

    fn term<'a>(&'a self, _targets: &'a Targets, parity: usize) -> (TermKind, &'a Image) {
        (
            TermKind::VplIrradiance,
            self.sized.temporal.history.current(parity),
        )
    }

    fn target(&self, target: Target, parity: usize, _config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Indirect => Some(self.sized.temporal.history.current(parity)),
            Target::DiscardMask => Some(&self.sized.discard),
            _ => None,
        }
    }
}
