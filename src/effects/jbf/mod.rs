//! Indirect light from the noisy per-frame gather, filtered within the frame by a joint
//! bilateral filter (`--indirect-filter jbf11|jbf17`): the geometry-aware baselines of Chen,
//! Lei & Chang's comparison, on the same input as the other per-frame filters
//! (`indirect_noisy`, --vpls per pixel, new VPLs every frame). No history: a pixel's light is as new each frame as its input.

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
use crate::resources::targets::{Target, Targets};
use crate::shaders;
use crate::vk::{Buffer, Context, Image};
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("jbf");

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// The joint bilateral filter of the noisy gather (--indirect-filter jbf11|jbf17).
    pub const INDIRECT_JBF: PassId = PassId::new("indirect_jbf", &[Change::Camera, Change::Config]);

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[crate::effects::indirect::pass::INDIRECT_NOISY, INDIRECT_JBF];

    /// The timing groups `bench --compare-reuse`, tables and sweeps compare (summed per frame):
    /// the indirect light's, which every way of making it shares.
    pub const GROUPS: &[(&str, &[PassId])] = &[("indirect", ALL)];
}

const FILTERED: Slot = Slot::Own("filtered");

const FILTER: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(5, NOISY, Use::Sampled),
    Bind::new(10, FILTERED, Use::StorageWrite),
];

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "indirect",
    enabled: |c| c.effects.indirect && radius(c.indirect.filter).is_some(),
    create: |s| Ok(Box::new(JbfEffect::new(s)?)),
    layouts,
    passes: pass::ALL,
    timing_groups: pass::GROUPS,
    sweep_keys: &[],
    ambient: false,
    views: &[],
    estimates: |_| Terms::INDIRECT,
    toggles: &[],
    recompute_mask: None,
};

// Every pass of the effect, declared once (`PassDecl`): `layouts` and `new` both read these.
const INDIRECT_JBF: PassDecl =
    PassDecl::new(pass::INDIRECT_JBF, &shaders::INDIRECT_JBF_COMP, FILTER);

fn layouts() -> Vec<PassLayout> {
    vec![NOISY_GATHER.layout(), INDIRECT_JBF.layout()]
}

/// Half the window's side of a joint bilateral filter.
fn radius(filter: IndirectFilter) -> Option<u32> {
    match filter {
        IndirectFilter::Jbf11 => Some(5),
        IndirectFilter::Jbf17 => Some(8),
        // Every other filter is another effect's.
        _ => None,
    }
}

struct Sized {
    noisy: Image,
    filtered: Image,
}

pub struct JbfEffect {
    noisy: ComputePass,
    filter: ComputePass,
    sized: Sized,
    /// The noisy gather's parameters.
    vpl_params: Buffer,
}

impl JbfEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let r = radius(s.config.indirect.filter).unwrap_or(5);
        Ok(Self {
            noisy: ComputePass::declared(s.ctx, s.pool, &NOISY_GATHER)?,
            filter: ComputePass::declared_with(s.ctx, s.pool, &INDIRECT_JBF, &[r])?,
            sized: Self::create_sized(s.ctx, s.config)?,
            vpl_params: params::buffer(s.ctx, s.tracker, "jbf.vpl_params", s.config)?,
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let image = |name: &str| float_image(ctx, name, c);
        Ok(Sized {
            noisy: image("jbf.noisy")?,
            filtered: image("jbf.filtered")?,
        })
    }

    fn own(&self) -> [(Slot, [&Image; 2]); 2] {
        let s = &self.sized;
        [
            (NOISY, [&s.noisy, &s.noisy]),
            (FILTERED, [&s.filtered, &s.filtered]),
        ]
    }
}

impl Effect for JbfEffect {
    fn id(&self) -> EffectId {
        ID
    }

    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let own = self.own();
        let res = EffectResources {
            targets,
            temporal: None,
            own: &own,
            own_buffers: &[(VPL_PARAMS, &self.vpl_params)],
        };
        self.noisy.bind(ctx, &res)?;
        self.filter.bind(ctx, &res)
    }

    /// A new sample every frame and nothing kept: the output never settles, but with
    /// unchanged inputs a frame is as good as the next, so skipping is left to the usual rule.
    fn prepare(&mut self, _info: &FrameInfo<'_>) {}

    fn reprojects(&self, _info: &FrameInfo<'_>) -> bool {
        false
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let own = self.own();
        let res = EffectResources {
            targets: info.targets,
            temporal: None,
            own: &own,
            own_buffers: &[(VPL_PARAMS, &self.vpl_params)],
        };
        let pixels = every_pixel(info);
        r.timed(crate::effects::indirect::pass::INDIRECT_NOISY, |rec, tr| {
            self.noisy.record(rec, tr, info.frame, &res, &[], pixels)
        });
        r.timed(pass::INDIRECT_JBF, |rec, tr| {
            self.filter.record(rec, tr, info.frame, &res, &[], pixels)
        });
    }

    fn term<'a>(&'a self, _targets: &'a Targets, _parity: usize) -> (TermKind, &'a Image) {
        (TermKind::VplIrradiance, &self.sized.filtered)
    }

    fn target(&self, target: Target, _parity: usize, _config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Indirect => Some(&self.sized.filtered),
            Target::IndirectNoisy => Some(&self.sized.noisy),
            _ => None,
        }
    }
}
