//! Screen-space directional occlusion (Szentandrasi sections 3.2 and 4.1, Ritschel et al.
//! 2009): Halton samples in the normal's hemisphere, back-projected; a modulation factor (eq 2
//! with visibility over eq 2 without) that darkens the ambient and direct light, and eq 4's
//! near-field bounce from the visible surfaces behind occluded samples. One step (section 4.1)
//! or the original two (directional occlusion, then the bounce from its result); then the
//! separable geometry-aware bilateral filter. With `--ssdo-samples adaptive`, a pre-pass first
//! picks each block's sample count. With `--ssdo-scale 0.5` SSDO and its filter run at half
//! resolution and a joint bilateral upsampling brings the result to the frame's. Every pixel
//! every frame, no temporal reuse.

pub mod args;
pub mod config;
mod params;
pub mod sweep;

use super::effect::TermKind;
use super::effect::{
    every_pixel, refresh_dispatch, Effect, EffectId, FrameInfo, Recording, Registration, Setup,
    Toggle,
};
use super::resolve::EffectResources;
use crate::config::RenderConfig;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch, PassDecl};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::counters::{Counter, OwnCounters, Role};
use crate::resources::targets::{EffectView, Look, Target, Targets, AO_FORMAT};
use crate::resources::temporal::Sampling;
use crate::resources::temporal_effect::{EffectKind, MovedReach, ScreenReach, TemporalEffect};
use crate::shaders::{self, EffectPush};
use crate::vk::recorder::Recorder;
use crate::vk::{Buffer, Context, Image, ImageDesc, Tracker};
use ash::vk;
use config::{SsdoConfig, SsdoForm};
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("ssdo");

/// SSDO with the cache (`--reuse on`): the factor's running mean rides in the moments' w.
pub const KIND: EffectKind = EffectKind {
    name: ID.name(),
    history_format: crate::shaders::SSDO_HISTORY_FORMAT,
    block_shift: 0,
    refresh_tile: 64,
    counters: &[
        ("disoccluded_pixels", Counter::Disoccluded),
        ("ssdo_computed_pixels", Counter::Computed),
        ("ssdo_samples", Counter::Samples),
        ("ssdo_refresh_evaluations", Counter::Refresh),
        ("ssdo_invalidated_pixels", Counter::Invalidated),
        ("ssdo_invocations", Counter::Invocations(Role::Gather)),
        (
            "ssdo_active_invocations",
            Counter::ActiveInvocations(Role::Gather),
        ),
        (
            "ssdo_serial_evaluations",
            Counter::SerialEvaluations(Role::Gather),
        ),
        (
            "ssdo_refresh_invocations",
            Counter::Invocations(Role::Refresh),
        ),
        (
            "ssdo_refresh_active_invocations",
            Counter::ActiveInvocations(Role::Refresh),
        ),
        (
            "ssdo_refresh_serial_evaluations",
            Counter::SerialEvaluations(Role::Refresh),
        ),
    ],
    fixups: false,
    // Its samples read the full-resolution G-buffer: no pixels beyond the radius.
    moved: MovedReach::ScreenRadius(|c| ScreenReach {
        radius: c.ssdo.radius,
        pad_px: 0,
    }),
    lit: true,
    reaccumulates: false,
};

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// SSDO's pre-pass: samples per block from the normal and depth changes.
    pub const SSDO_SAMPLES: PassId = PassId::new("ssdo_samples", &[Change::Camera, Change::Config]);
    /// SSDO: modulation factor and bounce in one pass, or the two-step form's directional
    /// occlusion pass.
    pub const SSDO: PassId = PassId::new("ssdo", &[Change::Camera, Change::Light, Change::Config]);
    /// The two-step SSDO's bounce pass.
    pub const SSDO_BOUNCE: PassId = PassId::new(
        "ssdo_bounce",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// With the cache: SSDO's refresh tile, every pattern, spread over threads.
    pub const SSDO_REFRESH: PassId = PassId::new(
        "ssdo_refresh",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// With the cache: the accumulated bounce and factor into the image the filter reads.
    pub const SSDO_RESOLVE: PassId = PassId::new(
        "ssdo_resolve",
        &[Change::Camera, Change::Light, Change::Config],
    );
    /// SSDO's separable bilateral filter (both directions).
    pub const SSDO_BILATERAL: PassId =
        PassId::new("ssdo_bilateral", &[Change::Camera, Change::Config]);
    /// Joint bilateral upsampling of half-resolution SSDO (--ssdo-scale 0.5).
    pub const SSDO_UPSAMPLE: PassId =
        PassId::new("ssdo_upsample", &[Change::Camera, Change::Config]);

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[
        SSDO_SAMPLES,
        SSDO,
        SSDO_BOUNCE,
        SSDO_REFRESH,
        SSDO_RESOLVE,
        SSDO_BILATERAL,
        SSDO_UPSAMPLE,
    ];

    /// The timing groups `bench --compare-reuse`, tables and sweeps compare (summed per frame).
    pub const GROUPS: &[(&str, &[PassId])] = &[("ssdo", ALL)];
}

/// The two-step form's directional-occlusion output: the senders' radiance, a = modulation.
const LIT: Slot = Slot::Own("lit");
/// SSDO's result (rgb bounce irradiance, a = modulation factor), before filtering.
const RAW: Slot = Slot::Own("raw");
/// The horizontal filter pass's output.
const HALF_FILTERED: Slot = Slot::Own("half_filtered");
/// The filtered result.
const FILTERED: Slot = Slot::Own("filtered");
/// The pre-pass's samples per block (r32ui, 1/scale resolution; 1x1 without the pre-pass).
const BLOCK_SAMPLES: Slot = Slot::Own("block_samples");
/// The half-resolution result upsampled to the frame (1x1 at full resolution).
const UPSAMPLED: Slot = Slot::Own("upsampled");
/// Pixels computed and samples taken this frame (the counters header, no work lists).
const COUNTERS: Slot = Slot::OwnBuffer("counters");
/// Its parameters (params.rs), bound at 15 in every pass.
const PARAMS: Slot = Slot::OwnBuffer("params");
const PARAMS_BIND: Bind = Bind::new(15, PARAMS, Use::BufferRead);

/// Report names of the counters the finishing pass (one step, or the bounce) fills; the mean
/// sample count per pixel is their ratio (`ssdo_samples_per_pixel` in the report).
pub const SSDO_COUNTERS: &[(&str, Counter)] = &[
    ("ssdo_computed_pixels", Counter::Computed),
    ("ssdo_samples", Counter::Samples),
];

const ONE_STEP: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GAlbedo, Use::Sampled),
    Bind::new(3, Slot::DirectLight, Use::Sampled),
    Bind::new(5, RAW, Use::StorageWrite),
    Bind::new(6, BLOCK_SAMPLES, Use::Sampled),
    Bind::new(7, COUNTERS, Use::BufferReadWrite),
    PARAMS_BIND,
];

const DIRECTIONAL: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GAlbedo, Use::Sampled),
    Bind::new(3, Slot::DirectLight, Use::Sampled),
    Bind::new(4, LIT, Use::StorageWrite),
    Bind::new(6, BLOCK_SAMPLES, Use::Sampled),
    PARAMS_BIND,
];

const BOUNCE: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GAlbedo, Use::Sampled),
    Bind::new(4, LIT, Use::Sampled),
    Bind::new(5, RAW, Use::StorageWrite),
    Bind::new(6, BLOCK_SAMPLES, Use::Sampled),
    Bind::new(7, COUNTERS, Use::BufferReadWrite),
    PARAMS_BIND,
];

const PREPASS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, BLOCK_SAMPLES, Use::StorageWrite),
    PARAMS_BIND,
];

const FILTER_H: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, RAW, Use::Sampled),
    Bind::new(3, HALF_FILTERED, Use::StorageWrite),
    PARAMS_BIND,
];

const FILTER_V: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, HALF_FILTERED, Use::Sampled),
    Bind::new(3, FILTERED, Use::StorageWrite),
    PARAMS_BIND,
];

/// With the cache: one pattern per listed pixel merged into the history (and the refresh tile).
const ACCUMULATE: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GAlbedo, Use::Sampled),
    Bind::new(3, Slot::DirectLight, Use::Sampled),
    Bind::new(4, Slot::State, Use::StorageRead),
    Bind::new(5, Slot::History, Use::StorageReadWrite),
    Bind::new(6, Slot::Counters, Use::WorkList),
    Bind::new(7, Slot::Moments, Use::StorageReadWrite),
    Bind::new(8, BLOCK_SAMPLES, Use::Sampled),
    PARAMS_BIND,
];

/// With the cache: history and moments into the image the filter and composite read.
const RESOLVE: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::History, Use::Sampled),
    Bind::new(2, Slot::Moments, Use::Sampled),
    Bind::new(3, RAW, Use::StorageWrite),
    PARAMS_BIND,
];

const fn upsample(src: Slot) -> [Bind; 5] {
    [
        Bind::new(0, Slot::GPosition, Use::Sampled),
        Bind::new(1, Slot::GNormal, Use::Sampled),
        Bind::new(2, src, Use::Sampled),
        Bind::new(3, UPSAMPLED, Use::StorageWrite),
        PARAMS_BIND,
    ]
}
const UPSAMPLE_FILTERED: &[Bind] = &upsample(FILTERED);
const UPSAMPLE_RAW: &[Bind] = &upsample(RAW);

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "ssdo",
    enabled: |c| c.effects.ssdo,
    create: |s| Ok(Box::new(SsdoEffect::new(s)?)),
    layouts,
    passes: pass::ALL,
    timing_groups: pass::GROUPS,
    sweep_keys: sweep::SWEEP_KEYS,
    ambient: true,
    views: VIEWS,
    estimates,
    toggles: &[FILTER_TOGGLE],
    recompute_mask: None,
};

/// SSDO estimates the occlusion of the ambient light (the `ao` buffer, as AO does) and, in its
/// forms with a bounce, the near-field part of the one-bounce indirect light (the `indirect`
/// buffer: the truth has the whole bounce, so what the radius leaves out counts as its error).
fn estimates(c: &RenderConfig) -> Terms {
    match c.ssdo.form {
        SsdoForm::Ssao => Terms::AMBIENT_OCCLUSION,
        SsdoForm::OneStep | SsdoForm::TwoStep => Terms::AMBIENT_OCCLUSION.union(Terms::INDIRECT),
    }
}

/// The bilateral filter on or off; on again, the run's side (or the default when it started
/// without one).
const FILTER_TOGGLE: Toggle = Toggle {
    name: "filter",
    what: "SSDO's bilateral filter",
    get: |c| c.ssdo.filter > 0,
    set: |c, on, start| {
        c.ssdo.filter = match (on, start.ssdo.filter) {
            (false, _) => 0,
            (true, 0) => SsdoConfig::default().filter,
            (true, side) => side,
        }
    },
};

/// The modulation factor (a of its term) and bounce irradiance (rgb), as composited, and the
/// adaptive pre-pass's samples per block.
pub const MODULATION_VIEW: EffectView = EffectView {
    name: "ssdo_modulation",
    look: Look::Alpha,
    in_viewer: false,
};
pub const BOUNCE_VIEW: EffectView = EffectView {
    name: "ssdo_bounce",
    look: Look::Brightest,
    in_viewer: true,
};
/// Samples per block: 50 (the paper's most) is white.
pub const SAMPLES_VIEW: EffectView = EffectView {
    name: "ssdo_samples",
    look: Look::Count { full: 50 },
    in_viewer: false,
};
const VIEWS: &[EffectView] = &[MODULATION_VIEW, BOUNCE_VIEW, SAMPLES_VIEW];

// Every pass of the effect, declared once (`PassDecl`): `layouts` and `new` both read these.
const SSDO_ONE_STEP: PassDecl = PassDecl::new(pass::SSDO, &shaders::SSDO_COMP_ONE_STEP, ONE_STEP);
const SSDO_SSAO: PassDecl = PassDecl::new(pass::SSDO, &shaders::SSDO_COMP_SSAO, ONE_STEP);
const SSDO_DIRECTIONAL: PassDecl =
    PassDecl::new(pass::SSDO, &shaders::SSDO_COMP_DIRECTIONAL, DIRECTIONAL);
const SSDO_BOUNCE: PassDecl = PassDecl::new(pass::SSDO_BOUNCE, &shaders::SSDO_COMP_BOUNCE, BOUNCE);
const SSDO_SAMPLES: PassDecl =
    PassDecl::new(pass::SSDO_SAMPLES, &shaders::SSDO_SAMPLES_COMP, PREPASS);
const SSDO_ACCUMULATE_BLOCKS: PassDecl = PassDecl::new(
    pass::SSDO,
    &shaders::SSDO_ACCUMULATE_COMP_BLOCKS,
    ACCUMULATE,
);
const SSDO_ACCUMULATE_BLOCKS_SSAO: PassDecl = PassDecl::new(
    pass::SSDO,
    &shaders::SSDO_ACCUMULATE_COMP_BLOCKS_SSAO,
    ACCUMULATE,
);
const SSDO_ACCUMULATE_REFRESH: PassDecl = PassDecl::new(
    pass::SSDO_REFRESH,
    &shaders::SSDO_ACCUMULATE_COMP_REFRESH,
    ACCUMULATE,
);
const SSDO_ACCUMULATE_REFRESH_SSAO: PassDecl = PassDecl::new(
    pass::SSDO_REFRESH,
    &shaders::SSDO_ACCUMULATE_COMP_REFRESH_SSAO,
    ACCUMULATE,
);
const SSDO_ACCUMULATE_RESOLVE: PassDecl = PassDecl::new(
    pass::SSDO_RESOLVE,
    &shaders::SSDO_ACCUMULATE_COMP_RESOLVE,
    RESOLVE,
);
const SSDO_ACCUMULATE_RESOLVE_SSAO: PassDecl = PassDecl::new(
    pass::SSDO_RESOLVE,
    &shaders::SSDO_ACCUMULATE_COMP_RESOLVE_SSAO,
    RESOLVE,
);
const SSDO_BILATERAL_HORIZONTAL: PassDecl = PassDecl::new(
    pass::SSDO_BILATERAL,
    &shaders::SSDO_BILATERAL_COMP_HORIZONTAL,
    FILTER_H,
);
const SSDO_BILATERAL_VERTICAL: PassDecl = PassDecl::new(
    pass::SSDO_BILATERAL,
    &shaders::SSDO_BILATERAL_COMP_VERTICAL,
    FILTER_V,
);
/// The upsampling of the raw result (no filter) and of the filtered one.
const SSDO_UPSAMPLE_RAW: PassDecl = PassDecl::new(
    pass::SSDO_UPSAMPLE,
    &shaders::SSDO_UPSAMPLE_COMP,
    UPSAMPLE_RAW,
);
const SSDO_UPSAMPLE_FILTERED: PassDecl = PassDecl::new(
    pass::SSDO_UPSAMPLE,
    &shaders::SSDO_UPSAMPLE_COMP,
    UPSAMPLE_FILTERED,
);

fn layouts() -> Vec<PassLayout> {
    vec![
        SSDO_ONE_STEP.layout(),
        SSDO_SSAO.layout(),
        SSDO_DIRECTIONAL.layout(),
        SSDO_BOUNCE.layout(),
        SSDO_SAMPLES.layout(),
        SSDO_ACCUMULATE_BLOCKS.layout(),
        SSDO_ACCUMULATE_BLOCKS_SSAO.layout(),
        SSDO_ACCUMULATE_REFRESH.layout(),
        SSDO_ACCUMULATE_REFRESH_SSAO.layout(),
        SSDO_ACCUMULATE_RESOLVE.layout(),
        SSDO_ACCUMULATE_RESOLVE_SSAO.layout(),
        SSDO_BILATERAL_HORIZONTAL.layout(),
        SSDO_BILATERAL_VERTICAL.layout(),
        SSDO_UPSAMPLE_RAW.layout(),
        SSDO_UPSAMPLE_FILTERED.layout(),
    ]
}

/// The passes of the configured form.
enum Form {
    /// One pass: one-step SSDO, or SSAO.
    Single(ComputePass),
    TwoStep {
        directional: ComputePass,
        bounce: ComputePass,
    },
    /// With the cache (one step or SSAO): accumulate the listed pixels, refresh a tile,
    /// resolve every pixel.
    Cached {
        blocks: ComputePass,
        refresh: ComputePass,
        resolve: ComputePass,
    },
}

/// Size-dependent images: [lit, raw, half filtered, filtered, samples per block, upsampled],
/// and with the cache the history machinery.
struct Sized {
    images: [Image; 6],
    temporal: Option<TemporalEffect>,
}

/// The counters header the uncached passes fill, and its per-slot host copies.
pub struct SsdoEffect {
    form: Form,
    /// Horizontal and vertical bilateral passes (`--bilateral` not off).
    filter: Option<[ComputePass; 2]>,
    /// The adaptive sample count's pre-pass.
    prepass: Option<ComputePass>,
    /// Joint bilateral upsampling (`--ssdo-scale 0.5`).
    upsample: Option<ComputePass>,
    /// `--ssdo ssao`: the result is ambient visibility, no bounce.
    ssao: bool,
    /// Without the cache, SSDO's own counters (with it, its `TemporalEffect`'s).
    own_counters: Option<OwnCounters>,
    params: Buffer,
    sized: Sized,
    push: EffectPush,
}

impl SsdoEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let pass = |decl: &PassDecl| ComputePass::declared(s.ctx, s.pool, decl);
        let ssao = s.config.ssdo.form == SsdoForm::Ssao;
        let form = match s.config.ssdo.form {
            // RenderConfig::validate keeps the cache to full-resolution one step and SSAO.
            _ if s.config.temporal.reuse => {
                let (blocks, refresh, resolve) = if ssao {
                    (
                        &SSDO_ACCUMULATE_BLOCKS_SSAO,
                        &SSDO_ACCUMULATE_REFRESH_SSAO,
                        &SSDO_ACCUMULATE_RESOLVE_SSAO,
                    )
                } else {
                    (
                        &SSDO_ACCUMULATE_BLOCKS,
                        &SSDO_ACCUMULATE_REFRESH,
                        &SSDO_ACCUMULATE_RESOLVE,
                    )
                };
                Form::Cached {
                    blocks: pass(blocks)?,
                    refresh: pass(refresh)?,
                    resolve: pass(resolve)?,
                }
            }
            SsdoForm::OneStep => Form::Single(pass(&SSDO_ONE_STEP)?),
            SsdoForm::Ssao => Form::Single(pass(&SSDO_SSAO)?),
            SsdoForm::TwoStep => Form::TwoStep {
                directional: pass(&SSDO_DIRECTIONAL)?,
                bounce: pass(&SSDO_BOUNCE)?,
            },
        };
        let filter = if s.config.ssdo.filter > 0 {
            Some([
                pass(&SSDO_BILATERAL_HORIZONTAL)?,
                pass(&SSDO_BILATERAL_VERTICAL)?,
            ])
        } else {
            None
        };
        let prepass = match s.config.ssdo.adaptive {
            Some(_) => Some(pass(&SSDO_SAMPLES)?),
            None => None,
        };
        let upsample = if s.config.ssdo.scale > 1 {
            let decl = if filter.is_some() {
                &SSDO_UPSAMPLE_FILTERED
            } else {
                &SSDO_UPSAMPLE_RAW
            };
            Some(pass(decl)?)
        } else {
            None
        };
        Ok(Self {
            form,
            filter,
            prepass,
            upsample,
            ssao,
            own_counters: if s.config.temporal.reuse {
                None
            } else {
                Some(OwnCounters::new(s.ctx, "ssdo.counters", SSDO_COUNTERS)?)
            },
            params: params::buffer(s.ctx, s.tracker, s.config)?,
            sized: Self::create_sized(s.ctx, s.config)?,
            push: EffectPush::default(),
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let image = |name: &str, divisor: u32| {
            Image::new(
                ctx,
                name,
                ImageDesc {
                    width: c.width.div_ceil(divisor),
                    height: c.height.div_ceil(divisor),
                    format: AO_FORMAT,
                    usage: vk::ImageUsageFlags::STORAGE
                        | vk::ImageUsageFlags::SAMPLED
                        | vk::ImageUsageFlags::TRANSFER_SRC,
                },
            )
        };
        // One texel per pre-pass block (a 1x1 placeholder when the count is fixed: the SSDO
        // passes bind it either way and do not read it).
        let scale = c.ssdo.adaptive.map(|a| a.scale);
        let side = |n: u32| scale.map_or(1, |s| n.div_ceil(s));
        let samples = Image::new(
            ctx,
            "ssdo.block_samples",
            ImageDesc {
                width: side(c.width),
                height: side(c.height),
                format: vk::Format::R32_UINT,
                usage: vk::ImageUsageFlags::STORAGE
                    | vk::ImageUsageFlags::SAMPLED
                    | vk::ImageUsageFlags::TRANSFER_SRC,
            },
        )?;
        // SSDO's grid: 1/scale of the frame.
        let grid = c.ssdo.scale;
        // A 1x1 placeholder at full resolution, where nothing is upsampled.
        let upsampled = if grid > 1 { 1 } else { c.width.max(c.height) };
        Ok(Sized {
            images: [
                image("ssdo.lit", grid)?,
                image("ssdo.raw", grid)?,
                image("ssdo.half_filtered", grid)?,
                image("ssdo.filtered", grid)?,
                samples,
                image("ssdo.upsampled", upsampled)?,
            ],
            temporal: if c.temporal.reuse {
                Some(TemporalEffect::new(ctx, KIND, c, Sampling::FullRes)?)
            } else {
                None
            },
        })
    }

    fn own(&self) -> [(Slot, [&Image; 2]); 6] {
        let slots = [LIT, RAW, HALF_FILTERED, FILTERED, BLOCK_SAMPLES, UPSAMPLED];
        let mut images = self.sized.images.iter();
        slots.map(|slot| {
            let image = images.next().expect("one image per slot");
            (slot, [image, image])
        })
    }

    fn resources<'a>(
        &'a self,
        targets: &'a Targets,
        own: &'a [(Slot, [&'a Image; 2]); 6],
        buffers: &'a [(Slot, &'a Buffer)],
    ) -> EffectResources<'a> {
        EffectResources {
            targets,
            temporal: self.sized.temporal.as_ref(),
            own,
            own_buffers: buffers,
        }
    }

    /// `Slot::OwnBuffer` bindings: the parameters, and the counters when SSDO keeps its own.
    fn own_buffers(&self) -> Vec<(Slot, &Buffer)> {
        let counters = self.own_counters.as_ref().map(|c| (COUNTERS, &c.gpu));
        [(PARAMS, &self.params)]
            .into_iter()
            .chain(counters)
            .collect()
    }

    /// The image the composite reads: upsampled, filtered, or the raw result.
    fn result(&self) -> &Image {
        let [_, raw, _, filtered, _, upsampled] = &self.sized.images;
        if self.upsample.is_some() {
            upsampled
        } else if self.filter.is_some() {
            filtered
        } else {
            raw
        }
    }
}

impl Effect for SsdoEffect {
    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn accumulating(&self) -> &'static [PassId] {
        &[
            pass::SSDO_SAMPLES,
            pass::SSDO,
            pass::SSDO_BOUNCE,
            pass::SSDO_REFRESH,
            pass::SSDO_RESOLVE,
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
        let own = self.own();
        let buffers = self.own_buffers();
        let res = self.resources(targets, &own, &buffers);
        match &self.form {
            Form::Single(p) => p.bind(ctx, &res)?,
            Form::TwoStep {
                directional,
                bounce,
            } => {
                directional.bind(ctx, &res)?;
                bounce.bind(ctx, &res)?;
            }
            Form::Cached {
                blocks,
                refresh,
                resolve,
            } => {
                blocks.bind(ctx, &res)?;
                refresh.bind(ctx, &res)?;
                resolve.bind(ctx, &res)?;
            }
        }
        let others = self.filter.iter().flatten();
        for p in others.chain(&self.prepass).chain(&self.upsample) {
            p.bind(ctx, &res)?;
        }
        Ok(())
    }

    fn temporal(&self) -> Option<&TemporalEffect> {
        self.sized.temporal.as_ref()
    }

    fn temporal_mut(&mut self) -> Option<&mut TemporalEffect> {
        self.sized.temporal.as_mut()
    }

    /// With the cache, the temporal machinery's counters; without, SSDO's own.
    fn copy_counters(
        &mut self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        slot: usize,
        _config: &RenderConfig,
    ) {
        if let Some(t) = &mut self.sized.temporal {
            t.copy_counters(rec, tracker, slot);
        }
        if let Some(c) = &mut self.own_counters {
            c.copy(rec, tracker, slot);
        }
    }

    fn collect_counters(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        match (&mut self.sized.temporal, &mut self.own_counters) {
            (Some(t), _) => t.readback.collect(slot),
            (None, Some(c)) => c.collect(slot),
            (None, None) => Vec::new(),
        }
    }

    fn prepare(&mut self, info: &FrameInfo<'_>) {
        let refresh = info.config.temporal.refresh;
        if let Some(t) = &mut self.sized.temporal {
            // The senders' radiance and L_in follow the light and the shadows: a light view
            // rendered again (a moved light, or something moving in its sight) restarts the
            // history, and refreshes after it.
            self.push = t.frame_push(
                info.keeps_history(true, true),
                refresh,
                0,
                info.camera_moved,
                info.refresh_cover(true, true),
            );
        }
    }

    fn reprojects(&self, _info: &FrameInfo<'_>) -> bool {
        self.sized.temporal.is_some()
    }

    fn push(&self) -> &EffectPush {
        &self.push
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let own = self.own();
        let buffers = self.own_buffers();
        let res = self.resources(info.targets, &own, &buffers);
        let grid = &self.sized.images[1].desc;
        // With the cache the reprojection resets the temporal counters.
        if let Some(c) = &self.own_counters {
            c.reset(&r.rec, r.tracker);
        }
        let all = Dispatch::Pixels {
            width: grid.width,
            height: grid.height,
        };
        if let Some(p) = &self.prepass {
            let d = &self.sized.images[4].desc;
            let blocks = Dispatch::Pixels {
                width: d.width,
                height: d.height,
            };
            r.timed(pass::SSDO_SAMPLES, |rec, tr| {
                p.record(rec, tr, info.frame, &res, &[], blocks)
            });
        }
        match &self.form {
            Form::Single(p) => {
                r.timed(pass::SSDO, |rec, tr| {
                    p.record(rec, tr, info.frame, &res, &[], all)
                });
            }
            Form::TwoStep {
                directional,
                bounce,
            } => {
                r.timed(pass::SSDO, |rec, tr| {
                    directional.record(rec, tr, info.frame, &res, &[], all)
                });
                r.timed(pass::SSDO_BOUNCE, |rec, tr| {
                    bounce.record(rec, tr, info.frame, &res, &[], all)
                });
            }
            Form::Cached {
                blocks,
                refresh,
                resolve,
            } => {
                let push = self.push.to_bytes();
                r.timed(pass::SSDO, |rec, tr| {
                    let listed = Dispatch::Indirect { offset: 0 };
                    blocks.record(rec, tr, info.frame, &res, &push, listed)
                });
                if let Some(tile) = refresh_dispatch(&self.push) {
                    r.timed(pass::SSDO_REFRESH, |rec, tr| {
                        refresh.record(rec, tr, info.frame, &res, &push, tile)
                    });
                }
                r.timed(pass::SSDO_RESOLVE, |rec, tr| {
                    resolve.record(rec, tr, info.frame, &res, &[], all)
                });
            }
        }
        if let Some([h, v]) = &self.filter {
            r.timed(pass::SSDO_BILATERAL, |rec, tr| {
                h.record(rec, tr, info.frame, &res, &[], all);
                v.record(rec, tr, info.frame, &res, &[], all);
            });
        }
        if let Some(p) = &self.upsample {
            r.timed(pass::SSDO_UPSAMPLE, |rec, tr| {
                p.record(rec, tr, info.frame, &res, &[], every_pixel(info))
            });
        }
    }

    fn term<'a>(&'a self, _targets: &'a Targets, _parity: usize) -> (TermKind, &'a Image) {
        if self.ssao {
            // rgba = the unoccluded fraction: the composite reads red, as for AO.
            (TermKind::AmbientVisibility, self.result())
        } else {
            (TermKind::BounceAndModulation, self.result())
        }
    }

    fn target(&self, target: Target, _parity: usize, _config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Effect(v) if *v == MODULATION_VIEW => Some(self.result()),
            Target::Effect(v) if *v == BOUNCE_VIEW && !self.ssao => Some(self.result()),
            Target::Ao if self.ssao => Some(self.result()),
            Target::Effect(v) if *v == SAMPLES_VIEW && self.prepass.is_some() => {
                Some(&self.sized.images[4])
            }
            _ => None,
        }
    }
}
