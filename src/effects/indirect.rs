//! One-bounce indirect light from the reflective shadow map (Lin 2013 section 3.3, eqs 9-10):
//! the gather at half resolution over the blocks that need work, geometry-aware upsampling
//! with a discard mask, and a full-resolution fix-up over the compacted list of discarded
//! pixels, all merged into the indirect history. Without half resolution, one
//! full-resolution gather per block. It always goes through the reprojection: without reuse
//! every pixel is new and every block listed, with the fixed pattern 0.

use super::effect::{
    refresh_dispatch, Effect, EffectId, FrameInfo, Recording, Registration, Setup, TermKind,
};
use super::resolve::EffectResources;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::renderer::config::{IndirectFilter, RenderConfig};
use crate::renderer::counters::FIXUP_DISPATCH_OFFSET;
use crate::renderer::effect::{self, TemporalEffect};
use crate::renderer::targets::{Target, Targets, STATE_FORMAT};
use crate::renderer::temporal::Sampling;
use crate::shaders::{self, EffectPush};
use crate::vk::{Buffer, Context, Image, ImageDesc};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// 1 where the upsampling found no acceptable neighbour (Figure 4.1). Written only for the
/// pixels recomputed this frame, so it is not discarded between frames.
const DISCARD: Slot = Slot::Own(0);
/// One 9x9 low-resolution tile (block plus its right and bottom apron) per listed block.
const LOWRES: Slot = Slot::OwnBuffer(0);

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
            $($rest),*
        ]
    };
}

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
    id: EffectId::Indirect,
    enabled: |c| c.effects.indirect && c.indirect.filter == IndirectFilter::Accumulate,
    create: |s| Ok(Box::new(IndirectEffect::new(s)?)),
    layouts,
};

fn layouts() -> Vec<PassLayout> {
    vec![
        ComputePass::layout(
            PassId::IndirectGather,
            &shaders::INDIRECT_LOWRES_COMP,
            LOWRES_GATHER,
        ),
        ComputePass::layout(
            PassId::IndirectUpsample,
            &shaders::INDIRECT_UPSAMPLE_COMP,
            UPSAMPLE,
        ),
        ComputePass::layout(
            PassId::IndirectFixup,
            &shaders::INDIRECT_GATHER_COMP_FIXUP,
            GATHER,
        ),
        ComputePass::layout(
            PassId::IndirectGather,
            &shaders::INDIRECT_GATHER_COMP_BLOCKS,
            GATHER,
        ),
        ComputePass::layout(
            PassId::IndirectRefresh,
            &shaders::INDIRECT_GATHER_COMP_REFRESH,
            GATHER,
        ),
    ]
}

/// The half-resolution chain: gather, upsample, fix-up.
struct HalfRes {
    lowres: ComputePass,
    upsample: ComputePass,
    fixup: ComputePass,
}

/// The gather at half or at full resolution.
enum Gather {
    Half(HalfRes),
    Full(ComputePass),
}

struct Sized {
    temporal: TemporalEffect,
    lowres: Buffer,
    discard: Image,
}

pub struct IndirectEffect {
    gather: Gather,
    /// The refresh tile at full resolution, one workgroup per pixel.
    refresh: ComputePass,
    sized: Sized,
    push: EffectPush,
}

impl IndirectEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let pass = |id, module, binds| ComputePass::new(s.ctx, s.pool, id, module, binds);
        let gather = if s.config.indirect.half_res {
            Gather::Half(HalfRes {
                lowres: pass(
                    PassId::IndirectGather,
                    &shaders::INDIRECT_LOWRES_COMP,
                    LOWRES_GATHER,
                )?,
                upsample: pass(
                    PassId::IndirectUpsample,
                    &shaders::INDIRECT_UPSAMPLE_COMP,
                    UPSAMPLE,
                )?,
                fixup: pass(
                    PassId::IndirectFixup,
                    &shaders::INDIRECT_GATHER_COMP_FIXUP,
                    GATHER,
                )?,
            })
        } else {
            Gather::Full(pass(
                PassId::IndirectGather,
                &shaders::INDIRECT_GATHER_COMP_BLOCKS,
                GATHER,
            )?)
        };
        let refresh = pass(
            PassId::IndirectRefresh,
            &shaders::INDIRECT_GATHER_COMP_REFRESH,
            GATHER,
        )?;
        Ok(Self {
            gather,
            refresh,
            sized: Self::create_sized(s.ctx, s.config)?,
            push: EffectPush::default(),
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let sampling = if c.indirect.half_res {
            Sampling::HalfRes
        } else {
            Sampling::FullRes
        };
        let temporal = TemporalEffect::new(ctx, effect::INDIRECT, c, sampling)?;
        Ok(Sized {
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

    fn own(&self) -> [[&Image; 2]; 1] {
        [[&self.sized.discard, &self.sized.discard]]
    }

    fn resources<'a>(
        &'a self,
        targets: &'a Targets,
        own: &'a [[&'a Image; 2]; 1],
        buffers: &'a [&'a Buffer; 1],
    ) -> EffectResources<'a> {
        EffectResources {
            targets,
            temporal: Some(&self.sized.temporal),
            own,
            own_buffers: buffers,
        }
    }

    fn passes(&self) -> Vec<&ComputePass> {
        match &self.gather {
            Gather::Half(h) => vec![&h.lowres, &h.upsample, &h.fixup, &self.refresh],
            Gather::Full(p) => vec![p, &self.refresh],
        }
    }
}

impl Effect for IndirectEffect {
    fn passes(&self) -> &'static [PassId] {
        &[
            PassId::IndirectGather,
            PassId::IndirectUpsample,
            PassId::IndirectFixup,
            PassId::IndirectRefresh,
        ]
    }

    fn accumulating(&self) -> &'static [PassId] {
        &[
            PassId::IndirectGather,
            PassId::IndirectUpsample,
            PassId::IndirectFixup,
            PassId::IndirectRefresh,
        ]
    }

    fn id(&self) -> EffectId {
        EffectId::Indirect
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let (own, buffers) = (self.own(), [&self.sized.lowres]);
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
        let (own, buffers) = (self.own(), [&self.sized.lowres]);
        let res = self.resources(info.targets, &own, &buffers);
        let push = self.push.to_bytes();
        let blocks = Dispatch::Indirect { offset: 0 };
        let mut run = |pass: &ComputePass, dispatch| {
            r.timed(pass.id, |rec, tr| {
                pass.record(rec, tr, info.frame, &res, &push, dispatch)
            })
        };
        match &self.gather {
            Gather::Full(p) => run(p, blocks),
            Gather::Half(h) => {
                run(&h.lowres, blocks);
                run(&h.upsample, blocks);
                run(
                    &h.fixup,
                    Dispatch::Indirect {
                        offset: FIXUP_DISPATCH_OFFSET,
                    },
                );
            }
        }
        if let Some(tile) = refresh_dispatch(&self.push) {
            run(&self.refresh, tile);
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
