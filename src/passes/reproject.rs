//! Reverse reprojection (Lin 2013 eqs 1-3), one dispatch per temporal effect: per-pixel state,
//! history resampling, the disocclusion count and the effect's list of blocks needing work.

use super::compute::ComputePass;
use super::decl::{Bind, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use crate::error::Result;
use crate::shaders;
use crate::vk::{Context, DescriptorPool};
use std::sync::Arc;

const BINDS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GPositionPrev, Use::Sampled),
    Bind::new(3, Slot::HistoryPrev, Use::Sampled),
    // Every pixel is written: resampled history, or cleared where it is disoccluded.
    Bind::new(4, Slot::History, Use::StorageWrite),
    Bind::new(5, Slot::State, Use::StorageWrite),
    Bind::new(6, Slot::Counters, Use::BufferReadWrite),
    Bind::new(7, Slot::MomentsPrev, Use::Sampled),
    Bind::new(8, Slot::Moments, Use::StorageWrite),
    Bind::new(9, Slot::GNormalPrev, Use::Sampled),
];

pub fn layout() -> PassLayout {
    ComputePass::layout(PassId::Reproject, &shaders::REPROJECT_COMP, BINDS)
}

/// The pipeline; each temporal effect records through its own [`ComputePass::instance`].
pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<ComputePass> {
    ComputePass::new(
        ctx,
        pool,
        PassId::Reproject,
        &shaders::REPROJECT_COMP,
        BINDS,
    )
}
