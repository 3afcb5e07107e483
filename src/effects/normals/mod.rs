//! A debug effect (`--effects normals`): each pixel's shading normal as radiance (n * 0.5 +
//! 0.5), so the image shows the normals every other effect reads. One pass, no history; it is
//! the smallest effect and the worked example of docs/ARCHITECTURE.md's "adding an effect".

use super::effect::{
    every_pixel, float_image, Effect, EffectId, FrameInfo, Recording, Registration, Setup, TermKind,
};
use super::resolve::EffectResources;
use crate::config::RenderConfig;
use crate::error::Result;
use crate::passes::compute::{ComputePass, PassDecl};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::PassId;
use crate::reference::compose::Terms;
use crate::resources::targets::{Target, Targets};
use crate::shaders;
use crate::vk::{Context, Image};
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("normals");

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// The normals debug effect: the G-buffer normal as radiance. Its shader reads no camera
    /// or light member of the frame block; the G-buffer it reads brings the camera's changes.
    pub const NORMALS: PassId = PassId::new("normals", &[Change::Config]);

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[NORMALS];
}

const OUT: Slot = Slot::Own("normals");

const NORMALS_BINDS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, OUT, Use::StorageWrite),
];

const NORMALS: PassDecl = PassDecl::new(pass::NORMALS, &shaders::NORMALS_COMP, NORMALS_BINDS);

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "normals",
    enabled: |c| c.effects.normals,
    create: |s| Ok(Box::new(NormalsEffect::new(s)?)),
    layouts: || vec![NORMALS.layout()],
    passes: pass::ALL,
    timing_groups: &[],
    sweep_keys: &[],
    ambient: false,
    views: &[],
    estimates: |_| Terms::NONE,
    toggles: &[],
    recompute_mask: None,
};

pub struct NormalsEffect {
    pass: ComputePass,
    out: Image,
}

impl NormalsEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        Ok(Self {
            pass: ComputePass::declared(s.ctx, s.pool, &NORMALS)?,
            out: float_image(s.ctx, "normals.out", s.config)?,
        })
    }

    fn resources<'a>(
        &'a self,
        targets: &'a Targets,
        own: &'a [(Slot, [&'a Image; 2])],
    ) -> EffectResources<'a> {
        EffectResources {
            targets,
            temporal: None,
            own,
            own_buffers: &[],
        }
    }
}

impl Effect for NormalsEffect {
    fn id(&self) -> EffectId {
        ID
    }

    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.out = float_image(ctx, "normals.out", config)?;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let own = [(OUT, [&self.out, &self.out])];
        self.pass.bind(ctx, &self.resources(targets, &own))
    }

    fn prepare(&mut self, _info: &FrameInfo<'_>) {}

    fn reprojects(&self, _info: &FrameInfo<'_>) -> bool {
        false
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let own = [(OUT, [&self.out, &self.out])];
        let res = self.resources(info.targets, &own);
        let pixels = every_pixel(info);
        r.timed(pass::NORMALS, |rec, tr| {
            self.pass.record(rec, tr, info.frame, &res, &[], pixels)
        });
    }

    fn term<'a>(&'a self, _targets: &'a Targets, _parity: usize) -> (TermKind, &'a Image) {
        (TermKind::Radiance, &self.out)
    }

    fn target(&self, _target: Target, _parity: usize, _config: &RenderConfig) -> Option<&Image> {
        None
    }
}
