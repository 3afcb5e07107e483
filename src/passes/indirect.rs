//! One-bounce indirect light from the reflective shadow map (Lin 2013 section 3.3): the gather
//! at half resolution over the blocks that need work, geometry-aware upsampling with a discard
//! mask, and a full-resolution fix-up over the compacted list of discarded pixels, all merged
//! into the indirect history. Without half resolution, one full-resolution gather per block.

use super::compute::ComputePass;
use super::{binding, PassId, PassLayout, FRAME_BINDING};
use crate::error::Result;
use crate::renderer::counters::FIXUP_DISPATCH_OFFSET;
use crate::renderer::effect::TemporalEffect;
use crate::renderer::targets::Targets;
use crate::shaders::{self, DescriptorKind, ReflectedBinding};
use crate::vk::cmd::Recorder;
use crate::vk::{Access, Buffer, Context, DescriptorPool, Image, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

use DescriptorKind::{SampledImage, StorageBuffer, StorageImage};

const COMMON: [ReflectedBinding; 7] = [
    FRAME_BINDING,
    binding(1, 0, SampledImage),  // g_position
    binding(1, 1, SampledImage),  // g_normal
    binding(1, 2, SampledImage),  // rsm_position
    binding(1, 3, SampledImage),  // rsm_normal
    binding(1, 4, SampledImage),  // rsm_flux
    binding(1, 5, StorageBuffer), // counters
];

fn with(extra: &[ReflectedBinding]) -> Vec<ReflectedBinding> {
    COMMON.iter().chain(extra).copied().collect()
}

fn lowres_bindings() -> Vec<ReflectedBinding> {
    with(&[binding(1, 6, StorageBuffer)]) // lowres
}

fn upsample_bindings() -> Vec<ReflectedBinding> {
    with(&[
        binding(1, 6, StorageBuffer), // lowres
        binding(1, 7, StorageImage),  // history
        binding(1, 8, StorageImage),  // state_in
        binding(1, 9, StorageImage),  // discard_mask
    ])
}

fn gather_bindings() -> Vec<ReflectedBinding> {
    with(&[
        binding(1, 6, StorageImage), // history
        binding(1, 7, StorageImage), // state_in
    ])
}

pub fn layouts() -> Vec<PassLayout> {
    let layout = |pass, module, declared| PassLayout {
        pass,
        modules: vec![module],
        declared,
    };
    vec![
        layout(
            PassId::IndirectGather,
            &shaders::INDIRECT_LOWRES_COMP,
            lowres_bindings(),
        ),
        layout(
            PassId::IndirectUpsample,
            &shaders::INDIRECT_UPSAMPLE_COMP,
            upsample_bindings(),
        ),
        layout(
            PassId::IndirectFixup,
            &shaders::INDIRECT_GATHER_COMP_FIXUP,
            gather_bindings(),
        ),
        layout(
            PassId::IndirectGather,
            &shaders::INDIRECT_GATHER_COMP_BLOCKS,
            gather_bindings(),
        ),
    ]
}

/// Records a sub-pass between the timestamps of the named timing row.
pub type TimedFn<'a> = dyn FnMut(PassId, &mut Tracker, &mut dyn FnMut(&mut Tracker)) + 'a;

/// The indirect effect's own size-dependent resources.
pub struct IndirectTargets {
    /// One 10x10 low-resolution tile (block plus apron) per listed block.
    pub lowres: Buffer,
    /// 1 where the upsampling found no acceptable neighbour (Figure 4.1).
    pub discard: Image,
}

pub struct IndirectPass {
    lowres: ComputePass,
    upsample: ComputePass,
    fixup: ComputePass,
    blocks: ComputePass,
    half_res: bool,
}

impl IndirectPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool, half_res: bool) -> Result<Self> {
        Ok(Self {
            lowres: ComputePass::new(
                ctx,
                pool,
                PassId::IndirectGather,
                &shaders::INDIRECT_LOWRES_COMP,
                &lowres_bindings(),
            )?,
            upsample: ComputePass::new(
                ctx,
                pool,
                PassId::IndirectUpsample,
                &shaders::INDIRECT_UPSAMPLE_COMP,
                &upsample_bindings(),
            )?,
            fixup: ComputePass::new(
                ctx,
                pool,
                PassId::IndirectFixup,
                &shaders::INDIRECT_GATHER_COMP_FIXUP,
                &gather_bindings(),
            )?,
            blocks: ComputePass::new(
                ctx,
                pool,
                PassId::IndirectGather,
                &shaders::INDIRECT_GATHER_COMP_BLOCKS,
                &gather_bindings(),
            )?,
            half_res,
        })
    }

    pub fn bind_targets(
        &self,
        ctx: &Context,
        t: &Targets,
        e: &TemporalEffect,
        own: &IndirectTargets,
    ) {
        for parity in 0..2 {
            let common = || {
                SetWriter::new()
                    .sampled(0, &t.gbuffer.position[parity])
                    .sampled(1, &t.gbuffer.normal)
                    .sampled(2, &t.rsm.position)
                    .sampled(3, &t.rsm.normal)
                    .sampled(4, &t.rsm.flux)
                    .storage_buffer(5, &e.counters)
            };
            self.lowres
                .write(ctx, parity, common().storage_buffer(6, &own.lowres));
            self.upsample.write(
                ctx,
                parity,
                common()
                    .storage_buffer(6, &own.lowres)
                    .storage(7, &e.history[parity])
                    .storage(8, &e.state)
                    .storage(9, &own.discard),
            );
            for pass in [&self.fixup, &self.blocks] {
                pass.write(
                    ctx,
                    parity,
                    common().storage(6, &e.history[parity]).storage(7, &e.state),
                );
            }
        }
    }

    fn read_inputs(tracker: &mut Tracker, t: &Targets, parity: usize) {
        for input in [
            &t.gbuffer.position[parity],
            &t.gbuffer.normal,
            &t.rsm.position,
            &t.rsm.normal,
            &t.rsm.flux,
        ] {
            tracker.image(input, Access::ComputeSampledRead);
        }
    }

    /// Record the gather (and upsampling and fix-up at half resolution); `timed` brackets each
    /// sub-pass with its timing row.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame_set: vk::DescriptorSet,
        parity: usize,
        t: &Targets,
        e: &TemporalEffect,
        own: &IndirectTargets,
        push: &[u8],
        timed: &mut TimedFn<'_>,
    ) {
        let history = &e.history[parity];
        let counters = &e.counters;
        if !self.half_res {
            timed(PassId::IndirectGather, tracker, &mut |tr| {
                Self::read_inputs(tr, t, parity);
                tr.image(&e.state, Access::ComputeStorageRead);
                tr.image(history, Access::ComputeStorageReadWrite);
                tr.buffer(counters, Access::IndirectCommandRead);
                tr.buffer(counters, Access::ComputeStorageReadWrite);
                tr.flush(rec.device, rec.cmd);
                self.blocks
                    .dispatch_indirect(rec, frame_set, parity, counters, 0, push);
            });
            return;
        }
        timed(PassId::IndirectGather, tracker, &mut |tr| {
            Self::read_inputs(tr, t, parity);
            tr.buffer(counters, Access::IndirectCommandRead);
            tr.buffer(counters, Access::ComputeStorageReadWrite);
            tr.buffer(&own.lowres, Access::ComputeStorageWrite);
            tr.flush(rec.device, rec.cmd);
            self.lowres
                .dispatch_indirect(rec, frame_set, parity, counters, 0, push);
        });
        timed(PassId::IndirectUpsample, tracker, &mut |tr| {
            Self::read_inputs(tr, t, parity);
            tr.buffer(&own.lowres, Access::ComputeStorageRead);
            tr.image(&e.state, Access::ComputeStorageRead);
            tr.image(history, Access::ComputeStorageReadWrite);
            tr.image(&own.discard, Access::ComputeStorageWrite);
            tr.buffer(counters, Access::IndirectCommandRead);
            tr.buffer(counters, Access::ComputeStorageReadWrite);
            tr.flush(rec.device, rec.cmd);
            self.upsample
                .dispatch_indirect(rec, frame_set, parity, counters, 0, push);
        });
        timed(PassId::IndirectFixup, tracker, &mut |tr| {
            Self::read_inputs(tr, t, parity);
            tr.image(&e.state, Access::ComputeStorageRead);
            tr.image(history, Access::ComputeStorageReadWrite);
            tr.buffer(counters, Access::IndirectCommandRead);
            tr.buffer(counters, Access::ComputeStorageReadWrite);
            tr.flush(rec.device, rec.cmd);
            self.fixup.dispatch_indirect(
                rec,
                frame_set,
                parity,
                counters,
                FIXUP_DISPATCH_OFFSET,
                push,
            );
        });
    }
}
