//! Indirect light filtered by SVGF (Schied et al. 2017, "Spatiotemporal Variance-Guided
//! Filtering", `--indirect-filter svgf`): the same noisy gather as the other per-frame filters
//! (`indirect_noisy`, --vpls per pixel, new VPLs every frame), accumulated over time with the
//! first and second moments of its luminance along the reprojection (a bilinear tap tested per
//! texel, as the article's), its variance estimated from the moments (spatially while a pixel
//! has few samples), then filtered by `--svgf-iterations` iterations of an edge-avoiding
//! a-trous wavelet whose luminance edge-stopping follows the variance. The first iteration's output is the next frame's
//! history. model.rs is the CPU evaluation the a-trous passes are checked against.

pub mod args;
pub mod config;
pub mod model;
pub mod sweep;

use super::effect::{
    every_pixel, float_image, Effect, EffectId, FrameInfo, Recording, Registration, Setup, TermKind,
};
use super::resolve::EffectResources;
use crate::config::{IndirectFilter, RenderConfig};
use crate::effects::indirect::{params, NOISY, NOISY_GATHER, VPL_PARAMS};
use crate::error::Result;
use crate::passes::compute::{ComputePass, PassDecl};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::counters::{Counter, OwnCounters};
use crate::resources::targets::{EffectView, Look, PingPong, Target, Targets};
use crate::shaders::{self, SvgfPush};
use crate::vk::recorder::Recorder;
use crate::vk::{Buffer, Context, Image, Tracker};
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("svgf");

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// SVGF's input, the indirect light's noisy gather.
    pub use crate::effects::indirect::pass::INDIRECT_NOISY;
    /// The temporal accumulation of colour and luminance moments along the reprojection.
    pub const SVGF_TEMPORAL: PassId =
        PassId::new("svgf_temporal", &[Change::Camera, Change::Config]);
    /// The variance from the moments (spatially for pixels with few samples).
    pub const SVGF_VARIANCE: PassId = PassId::new("svgf_variance", &[Change::Config]);
    /// Every a-trous iteration.
    pub const SVGF_ATROUS: PassId = PassId::new("svgf_atrous", &[Change::Config]);

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[INDIRECT_NOISY, SVGF_TEMPORAL, SVGF_VARIANCE, SVGF_ATROUS];

    /// The timing groups `bench --compare-reuse`, tables and sweeps compare (summed per frame):
    /// the indirect light's, which every way of making it shares.
    pub const GROUPS: &[(&str, &[PassId])] = &[("indirect", ALL)];
}

/// The a-trous input: the integrated colour (rgb) and its luminance variance (a).
pub const INTEGRATED_VIEW: EffectView = EffectView {
    name: "svgf_integrated",
    look: Look::Brightest,
    in_viewer: true,
};
/// r: the samples each pixel's history holds (white at 5, where the article's alpha of 0.2
/// takes over), g: the mean luminance, b: the mean squared luminance.
pub const HISTORY_VIEW: EffectView = EffectView {
    name: "svgf_history",
    look: Look::Count { full: 5 },
    in_viewer: true,
};
const VIEWS: &[EffectView] = &[INTEGRATED_VIEW, HISTORY_VIEW];

/// Report names of the temporal pass's counters.
pub const SVGF_COUNTERS: &[(&str, Counter)] = &[
    ("svgf_disoccluded_pixels", Counter::Disoccluded),
    ("svgf_computed_pixels", Counter::Computed),
];

/// This frame's colour (rgb), and last frame's.
const COLOR: Slot = Slot::Own("color");
const COLOR_PREV: Slot = Slot::Own("color_prev");
/// r: samples n, g: E[l], b: E[l^2]; this frame's and last frame's.
const MOMENTS: Slot = Slot::Own("moments");
const MOMENTS_PREV: Slot = Slot::Own("moments_prev");
/// Reciprocal view depth and its screen-space gradient.
const DEPTH: Slot = Slot::Own("depth");
/// The variance pass's output, the first iteration's input.
const INTEGRATED: Slot = Slot::Own("integrated");
const ATROUS_IN: Slot = Slot::Own("atrous_in");
const ATROUS_OUT: Slot = Slot::Own("atrous_out");
const COUNTERS: Slot = Slot::OwnBuffer("counters");

const TEMPORAL: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GPositionPrev, Use::Sampled),
    Bind::new(3, Slot::GNormalPrev, Use::Sampled),
    Bind::new(4, Slot::GMotion, Use::Sampled),
    Bind::new(5, NOISY, Use::Sampled),
    Bind::new(6, COLOR_PREV, Use::Sampled),
    Bind::new(7, MOMENTS_PREV, Use::Sampled),
    Bind::new(8, COLOR, Use::StorageWrite),
    Bind::new(9, MOMENTS, Use::StorageWrite),
    Bind::new(10, DEPTH, Use::StorageWrite),
    Bind::new(11, COUNTERS, Use::BufferReadWrite),
];

const VARIANCE: &[Bind] = &[
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(8, COLOR, Use::Sampled),
    Bind::new(9, MOMENTS, Use::Sampled),
    Bind::new(10, DEPTH, Use::Sampled),
    Bind::new(12, INTEGRATED, Use::StorageWrite),
];

const ATROUS: &[Bind] = &[
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(10, DEPTH, Use::Sampled),
    Bind::new(12, ATROUS_IN, Use::Sampled),
    Bind::new(13, ATROUS_OUT, Use::StorageWrite),
];

/// The first iteration also writes the colour history.
const ATROUS_FEEDBACK: &[Bind] = &[
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(8, COLOR, Use::StorageWrite),
    Bind::new(10, DEPTH, Use::Sampled),
    Bind::new(12, ATROUS_IN, Use::Sampled),
    Bind::new(13, ATROUS_OUT, Use::StorageWrite),
];

// Every pass, declared once (`PassDecl`): `layouts` and `new` both read these.
const TEMPORAL_PASS: PassDecl =
    PassDecl::new(pass::SVGF_TEMPORAL, &shaders::SVGF_TEMPORAL_COMP, TEMPORAL);
const VARIANCE_PASS: PassDecl =
    PassDecl::new(pass::SVGF_VARIANCE, &shaders::SVGF_VARIANCE_COMP, VARIANCE);
const FEEDBACK_PASS: PassDecl = PassDecl::new(
    pass::SVGF_ATROUS,
    &shaders::SVGF_ATROUS_COMP_FEEDBACK,
    ATROUS_FEEDBACK,
);
const ATROUS_PASS: PassDecl =
    PassDecl::new(pass::SVGF_ATROUS, &shaders::SVGF_ATROUS_COMP_PLAIN, ATROUS);
const PASSES: [&PassDecl; 5] = [
    &NOISY_GATHER,
    &TEMPORAL_PASS,
    &VARIANCE_PASS,
    &FEEDBACK_PASS,
    &ATROUS_PASS,
];

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "indirect",
    enabled: |c| c.effects.indirect && c.indirect.filter == IndirectFilter::Svgf,
    create: |s| Ok(Box::new(SvgfEffect::new(s)?)),
    layouts,
    passes: pass::ALL,
    timing_groups: pass::GROUPS,
    sweep_keys: sweep::SWEEP_KEYS,
    ambient: false,
    views: VIEWS,
    estimates: |_| Terms::INDIRECT,
    toggles: &[],
    recompute_mask: None,
};

fn layouts() -> Vec<PassLayout> {
    PASSES.iter().map(|d| d.layout()).collect()
}

/// The passes in `SvgfEffect::passes` order.
#[derive(Clone, Copy)]
enum Step {
    Noisy,
    Temporal,
    Variance,
    /// The first a-trous iteration, into `atrous[0]` and the colour history.
    Feedback,
    /// An iteration from `atrous[0]` into `atrous[1]`.
    Forth,
    /// An iteration from `atrous[1]` into `atrous[0]`.
    Back,
}

struct Sized {
    noisy: Image,
    /// This frame's colour and moments histories, and last frame's.
    color: PingPong,
    moments: PingPong,
    depth: Image,
    integrated: Image,
    /// The a-trous iterations' outputs, in turn.
    atrous: [Image; 2],
}

pub struct SvgfEffect {
    noisy: ComputePass,
    temporal: ComputePass,
    variance: ComputePass,
    /// The first iteration: the integrated colour into `atrous[0]` and the colour history.
    feedback: ComputePass,
    /// `atrous[0]` into `atrous[1]`, and back.
    atrous: [ComputePass; 2],
    sized: Sized,
    counters: OwnCounters,
    vpl_params: Buffer,
    push: SvgfPush,
    /// Frames since the histories last restarted or the lighting last changed (the light, a
    /// re-rendered light view or a moving object): `SvgfConfig::alpha_still` applies past
    /// `lit_settle_frames`, and the output settles within `settle_frames`.
    age: u32,
    /// A-trous iterations (the configuration's; another count builds another renderer).
    iterations: u32,
}

impl SvgfEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let atrous = ComputePass::declared(s.ctx, s.pool, &ATROUS_PASS)?;
        let back = atrous.instance(s.pool, "svgf_atrous (back)")?;
        Ok(Self {
            noisy: ComputePass::declared(s.ctx, s.pool, &NOISY_GATHER)?,
            temporal: ComputePass::declared(s.ctx, s.pool, &TEMPORAL_PASS)?,
            variance: ComputePass::declared(s.ctx, s.pool, &VARIANCE_PASS)?,
            feedback: ComputePass::declared(s.ctx, s.pool, &FEEDBACK_PASS)?,
            atrous: [atrous, back],
            sized: Self::create_sized(s.ctx, s.config)?,
            counters: OwnCounters::new(s.ctx, "svgf.counters", SVGF_COUNTERS)?,
            vpl_params: params::buffer(s.ctx, s.tracker, "svgf.vpl_params", s.config)?,
            push: SvgfPush::default(),
            age: 0,
            iterations: s.config.svgf.iterations,
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let image = |name: &str| float_image(ctx, name, c);
        Ok(Sized {
            noisy: image("svgf.noisy")?,
            color: PingPong::make(|i| image(&format!("svgf.color.{i}")))?,
            moments: PingPong::make(|i| image(&format!("svgf.moments.{i}")))?,
            depth: image("svgf.depth")?,
            integrated: image("svgf.integrated")?,
            atrous: [image("svgf.atrous.0")?, image("svgf.atrous.1")?],
        })
    }

    /// The images every pass may bind, per parity, with `input` and `output` as the a-trous
    /// iteration's.
    fn own<'a>(&'a self, input: &'a Image, output: &'a Image) -> [(Slot, [&'a Image; 2]); 9] {
        let s = &self.sized;
        [
            (NOISY, [&s.noisy, &s.noisy]),
            (COLOR, s.color.current_by_parity()),
            (COLOR_PREV, s.color.previous_by_parity()),
            (MOMENTS, s.moments.current_by_parity()),
            (MOMENTS_PREV, s.moments.previous_by_parity()),
            (DEPTH, [&s.depth, &s.depth]),
            (INTEGRATED, [&s.integrated, &s.integrated]),
            (ATROUS_IN, [input, input]),
            (ATROUS_OUT, [output, output]),
        ]
    }

    fn buffers(&self) -> [(Slot, &Buffer); 2] {
        [
            (COUNTERS, &self.counters.gpu),
            (VPL_PARAMS, &self.vpl_params),
        ]
    }

    /// Each pass with the a-trous images it reads and writes, indexed by `Step`.
    fn passes(&self) -> [(&ComputePass, &Image, &Image); 6] {
        let s = &self.sized;
        let [a0, a1] = &s.atrous;
        let i = &s.integrated;
        [
            (&self.noisy, i, a0),
            (&self.temporal, i, a0),
            (&self.variance, i, a0),
            (&self.feedback, i, a0),
            (&self.atrous[0], a0, a1),
            (&self.atrous[1], a1, a0),
        ]
    }

    /// The last a-trous iteration's output (the integrated colour for none): the indirect
    /// light the composite adds.
    fn output_image(&self) -> &Image {
        match self.iterations {
            0 => &self.sized.integrated,
            n => &self.sized.atrous[((n - 1) % 2) as usize],
        }
    }

    fn push_bytes(&self, step: u32) -> [u8; SvgfPush::SIZE] {
        SvgfPush { step, ..self.push }.to_bytes()
    }
}

impl Effect for SvgfEffect {
    fn id(&self) -> EffectId {
        ID
    }

    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        self.age = 0;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let buffers = self.buffers();
        for (p, input, output) in self.passes() {
            let own = self.own(input, output);
            let res = EffectResources {
                targets,
                temporal: None,
                own: &own,
                own_buffers: &buffers,
            };
            p.bind(ctx, &res)?;
        }
        Ok(())
    }

    /// A new sample every frame: with unchanged inputs the running means still move until
    /// their first samples are forgotten (`SvgfConfig::settle_frames`), then only wander with
    /// the noise. Without reuse nothing is kept: a frame is as good as the next.
    fn settling(&self, config: &RenderConfig) -> bool {
        config.temporal.reuse && self.age < config.svgf.settle_frames()
    }

    fn copy_counters(
        &mut self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        slot: usize,
        _config: &RenderConfig,
    ) {
        self.counters.copy(rec, tracker, slot);
    }

    fn collect_counters(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        self.counters.collect(slot)
    }

    fn prepare(&mut self, info: &FrameInfo<'_>) {
        let c = &info.config.svgf;
        let reusing = info.reusing();
        let lighting_changed = info.light_changed || info.light_view || info.objects_moved;
        self.age = if reusing && !lighting_changed {
            self.age.saturating_add(1)
        } else {
            1
        };
        // The first frames after a change take the article's weights, so the new light comes
        // through within `lit_settle_frames`; then the still lighting's longer mean.
        let (alpha, alpha_moments) = if self.age > c.lit_settle_frames() {
            c.still_alphas()
        } else {
            (c.alpha, c.alpha_moments)
        };
        self.push = SvgfPush {
            history_valid: reusing as u32,
            alpha,
            alpha_moments,
            bilinear: c.history.code(),
            step: 1,
            sigma_luminance: c.sigma_luminance,
            sigma_normal: c.sigma_normal,
            sigma_depth: c.sigma_depth,
        };
    }

    fn reprojects(&self, _info: &FrameInfo<'_>) -> bool {
        false
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let buffers = self.buffers();
        let pixels = every_pixel(info);
        let passes = self.passes();
        let run = |step: Step, push: &[u8], rec: &Recorder<'_>, tr: &mut Tracker| {
            let (p, input, output) = passes[step as usize];
            let own = self.own(input, output);
            let res = EffectResources {
                targets: info.targets,
                temporal: None,
                own: &own,
                own_buffers: &buffers,
            };
            p.record(rec, tr, info.frame, &res, push, pixels);
        };
        self.counters.reset(&r.rec, r.tracker);
        let push = self.push_bytes(1);
        r.timed(pass::INDIRECT_NOISY, |rec, tr| {
            run(Step::Noisy, &[], rec, tr)
        });
        r.timed(pass::SVGF_TEMPORAL, |rec, tr| {
            run(Step::Temporal, &push, rec, tr)
        });
        r.timed(pass::SVGF_VARIANCE, |rec, tr| {
            run(Step::Variance, &push, rec, tr)
        });
        let iterations = self.iterations;
        if iterations > 0 {
            r.timed(pass::SVGF_ATROUS, |rec, tr| {
                for i in 0..iterations {
                    // The first with feedback, then back and forth between the two images.
                    let step = match i {
                        0 => Step::Feedback,
                        i if i % 2 == 1 => Step::Forth,
                        _ => Step::Back,
                    };
                    run(step, &self.push_bytes(1 << i), rec, tr);
                }
            });
        }
    }

    fn term<'a>(&'a self, _targets: &'a Targets, _parity: usize) -> (TermKind, &'a Image) {
        (TermKind::VplIrradiance, self.output_image())
    }

    fn target(&self, target: Target, parity: usize, _config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Indirect => Some(self.output_image()),
            Target::IndirectNoisy => Some(&self.sized.noisy),
            Target::Effect(v) if *v == INTEGRATED_VIEW => Some(&self.sized.integrated),
            Target::Effect(v) if *v == HISTORY_VIEW => Some(self.sized.moments.current(parity)),
            _ => None,
        }
    }
}
