//! Indirect light filtered by CCIPCA (Chen, Lei & Chang 2012, `--indirect-filter ccipca`): a
//! new noisy RSM gather of `--vpls` VPLs per pixel every frame, the k bases updated from it
//! one after another (each update's image-wide sums reduced on the GPU, so no frame waits for
//! the CPU), and the noisy image projected on them. The equations and the CPU model the
//! passes are checked against are in src/reference/ccipca.rs.
//!
//! The bases live in screen space: a camera that moves restarts them (every pixel a new
//! dimension, the first frame's basis the frame itself) until the bases are warped along the
//! reprojection (Chen et al. section 3.4).

use super::effect::{
    every_pixel, Effect, EffectId, FrameInfo, Recording, Registration, Setup, TermKind,
};
use super::resolve::EffectResources;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::reference::ccipca::AMNESIC;
use crate::renderer::config::{IndirectConfig, IndirectFilter, RenderConfig};
use crate::renderer::effect::TemporalEffect;
use crate::renderer::targets::{Target, Targets};
use crate::shaders::{self, CcipcaPush, EffectPush};
use crate::vk::{Buffer, Context, Image, ImageDesc};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// This frame's noisy gather (rgb).
const NOISY: Slot = Slot::Own(0);
/// The projection on the bases: the indirect light the composite adds.
const FILTERED: Slot = Slot::Own(1);
/// k basis images, vec4 per pixel, basis-major.
const BASES: Slot = Slot::OwnBuffer(0);
/// Per pixel: the residual (rgb) and the samples seen (a).
const RESIDUAL: Slot = Slot::OwnBuffer(1);
/// Two vec4 of partial sums per 16x16 group.
const PARTIALS: Slot = Slot::OwnBuffer(2);
/// Two vec4 of image-wide sums per basis.
const TOTALS: Slot = Slot::OwnBuffer(3);

/// Pixels per side of the groups whose partial sums are stored.
const GROUP_SIDE: u32 = 16;

const NOISY_GATHER: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::RsmPosition, Use::Sampled),
    Bind::new(3, Slot::RsmNormal, Use::Sampled),
    Bind::new(4, Slot::RsmFlux, Use::Sampled),
    Bind::new(5, NOISY, Use::StorageWrite),
    Bind::new(6, BASES, Use::BufferReadWrite),
    Bind::new(7, RESIDUAL, Use::BufferReadWrite),
    Bind::new(8, PARTIALS, Use::BufferWrite),
];

const SUMS: &[Bind] = &[
    Bind::new(8, PARTIALS, Use::BufferRead),
    Bind::new(9, TOTALS, Use::BufferWrite),
];

const UPDATE: &[Bind] = &[
    Bind::new(6, BASES, Use::BufferReadWrite),
    Bind::new(7, RESIDUAL, Use::BufferReadWrite),
    Bind::new(8, PARTIALS, Use::BufferWrite),
    Bind::new(9, TOTALS, Use::BufferRead),
];

const RECONSTRUCT: &[Bind] = &[
    Bind::new(5, NOISY, Use::Sampled),
    Bind::new(7, RESIDUAL, Use::BufferRead),
    Bind::new(10, FILTERED, Use::StorageWrite),
];

pub const REGISTRATION: Registration = Registration {
    id: EffectId::Ccipca,
    enabled: |c| c.effects.indirect && c.indirect.filter == IndirectFilter::Ccipca,
    create: |s| Ok(Box::new(CcipcaEffect::new(s)?)),
    layouts,
};

fn layouts() -> Vec<PassLayout> {
    vec![
        ComputePass::layout(
            PassId::IndirectNoisy,
            &shaders::INDIRECT_NOISY_COMP,
            NOISY_GATHER,
        ),
        ComputePass::layout(PassId::CcipcaUpdate, &shaders::CCIPCA_SUMS_COMP, SUMS),
        ComputePass::layout(PassId::CcipcaUpdate, &shaders::CCIPCA_UPDATE_COMP, UPDATE),
        ComputePass::layout(
            PassId::CcipcaReconstruct,
            &shaders::CCIPCA_RECONSTRUCT_COMP,
            RECONSTRUCT,
        ),
    ]
}

struct Sized {
    noisy: Image,
    filtered: Image,
    bases: Buffer,
    residual: Buffer,
    partials: Buffer,
    totals: Buffer,
    groups: u32,
}

pub struct CcipcaEffect {
    noisy: ComputePass,
    sums: ComputePass,
    update: ComputePass,
    reconstruct: ComputePass,
    sized: Sized,
    push: CcipcaPush,
    /// Frames since the bases last restarted, up to the memory (`max_age`).
    age: u32,
    /// Only the reprojection reads the temporal effects' shared push constants; this effect
    /// has its own (`push`).
    no_effect_push: EffectPush,
}

impl CcipcaEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let pass = |id, module, binds| ComputePass::new(s.ctx, s.pool, id, module, binds);
        Ok(Self {
            noisy: pass(
                PassId::IndirectNoisy,
                &shaders::INDIRECT_NOISY_COMP,
                NOISY_GATHER,
            )?,
            sums: pass(PassId::CcipcaUpdate, &shaders::CCIPCA_SUMS_COMP, SUMS)?,
            update: pass(PassId::CcipcaUpdate, &shaders::CCIPCA_UPDATE_COMP, UPDATE)?,
            reconstruct: pass(
                PassId::CcipcaReconstruct,
                &shaders::CCIPCA_RECONSTRUCT_COMP,
                RECONSTRUCT,
            )?,
            sized: Self::create_sized(s.ctx, s.config)?,
            push: CcipcaPush::default(),
            age: 0,
            no_effect_push: EffectPush::default(),
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
                    format: vk::Format::R32G32B32A32_SFLOAT,
                    usage: vk::ImageUsageFlags::STORAGE
                        | vk::ImageUsageFlags::SAMPLED
                        | vk::ImageUsageFlags::TRANSFER_SRC,
                },
            )
        };
        let buffer = |name: &str, bytes: u64| {
            Buffer::new(
                ctx,
                name,
                bytes,
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::GpuOnly,
            )
        };
        let pixels = c.width as u64 * c.height as u64;
        let groups = c.width.div_ceil(GROUP_SIDE) * c.height.div_ceil(GROUP_SIDE);
        let vec4 = 16;
        Ok(Sized {
            noisy: image("ccipca.noisy")?,
            filtered: image("ccipca.filtered")?,
            bases: buffer("ccipca.bases", c.indirect.bases as u64 * pixels * vec4)?,
            residual: buffer("ccipca.residual", pixels * vec4)?,
            partials: buffer("ccipca.partials", groups as u64 * 2 * vec4)?,
            totals: buffer("ccipca.totals", IndirectConfig::MAX_BASES as u64 * 2 * vec4)?,
            groups,
        })
    }

    fn own(&self) -> [[&Image; 2]; 2] {
        let s = &self.sized;
        [[&s.noisy, &s.noisy], [&s.filtered, &s.filtered]]
    }

    fn buffers(&self) -> [&Buffer; 4] {
        let s = &self.sized;
        [&s.bases, &s.residual, &s.partials, &s.totals]
    }

    fn passes(&self) -> [&ComputePass; 4] {
        [&self.noisy, &self.sums, &self.update, &self.reconstruct]
    }
}

impl Effect for CcipcaEffect {
    fn id(&self) -> EffectId {
        EffectId::Ccipca
    }

    fn passes(&self) -> &'static [PassId] {
        &[
            PassId::IndirectNoisy,
            PassId::CcipcaUpdate,
            PassId::CcipcaReconstruct,
        ]
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        self.age = 0;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let (own, buffers) = (self.own(), self.buffers());
        let res = EffectResources {
            targets,
            temporal: None,
            own: &own,
            own_buffers: &buffers,
        };
        for p in self.passes() {
            p.bind(ctx, &res)?;
        }
        Ok(())
    }

    fn temporal(&self) -> Option<&TemporalEffect> {
        None
    }

    fn temporal_mut(&mut self) -> Option<&mut TemporalEffect> {
        None
    }

    /// Every frame adds a sample until the memory is full; with unchanged inputs the bases
    /// then only wander with the noise, so the filter has settled.
    fn settling(&self, config: &RenderConfig) -> bool {
        self.age < config.indirect.max_age
    }

    fn prepare(&mut self, info: &FrameInfo<'_>) {
        let restart = !info.reusing() || info.camera_moved;
        self.age = if restart {
            1
        } else {
            (self.age + 1).min(info.config.indirect.max_age)
        };
        self.push = CcipcaPush {
            basis: 0,
            bases: info.config.indirect.bases,
            groups: self.sized.groups,
            max_age: info.config.indirect.max_age,
            restart: restart as u32,
            amnesic: AMNESIC as f32,
        };
    }

    fn reprojects(&self, _info: &FrameInfo<'_>) -> bool {
        false
    }

    fn push(&self) -> &EffectPush {
        &self.no_effect_push
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let (own, buffers) = (self.own(), self.buffers());
        let res = EffectResources {
            targets: info.targets,
            temporal: None,
            own: &own,
            own_buffers: &buffers,
        };
        let pixels = every_pixel(info);
        let push = |basis| CcipcaPush { basis, ..self.push }.to_bytes();
        r.timed(PassId::IndirectNoisy, |rec, tr| {
            self.noisy
                .record(rec, tr, info.frame, &res, &push(0), pixels)
        });
        r.timed(PassId::CcipcaUpdate, |rec, tr| {
            for basis in 0..self.push.bases {
                let bytes = push(basis);
                self.sums
                    .record(rec, tr, info.frame, &res, &bytes, Dispatch::Groups(1));
                self.update
                    .record(rec, tr, info.frame, &res, &bytes, pixels);
            }
        });
        r.timed(PassId::CcipcaReconstruct, |rec, tr| {
            self.reconstruct
                .record(rec, tr, info.frame, &res, &push(0), pixels)
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
