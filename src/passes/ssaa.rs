//! 16x supersampling (`--aa ssaa16`), the antialiasing reference: the frame renders at 4x the
//! output's width and height, and this pass box-filters each 4x4 block into the output.

use super::compute::{ComputePass, Dispatch, FrameSet};
use super::decl::{Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use crate::error::Result;
use crate::shaders;
use crate::vk::recorder::Recorder;
use crate::vk::{Context, DescriptorPool, Tracker};
use std::sync::Arc;

const DOWNSAMPLE: &[Bind] = &[
    Bind::new(0, Slot::Shaded, Use::Sampled),
    Bind::new(1, Slot::Output, Use::StorageWrite),
];

pub fn layout() -> PassLayout {
    ComputePass::layout(
        PassId::SsaaDownsample,
        &shaders::SSAA_DOWNSAMPLE_COMP,
        DOWNSAMPLE,
    )
}

pub struct SsaaPass {
    pass: ComputePass,
}

impl SsaaPass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        let pass = ComputePass::new(
            ctx,
            pool,
            PassId::SsaaDownsample,
            &shaders::SSAA_DOWNSAMPLE_COMP,
            DOWNSAMPLE,
        )?;
        Ok(Self { pass })
    }

    pub fn bind(&self, ctx: &Context, res: &dyn Resolve) -> Result<()> {
        self.pass.bind(ctx, res)
    }

    /// Over the output size.
    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        res: &dyn Resolve,
        (width, height): (u32, u32),
    ) {
        self.pass.record(
            rec,
            tracker,
            frame,
            res,
            &[],
            Dispatch::Pixels { width, height },
        );
    }
}
