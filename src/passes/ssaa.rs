//! 16x supersampling (`--aa ssaa16`), the antialiasing reference: the frame renders at 4x the
//! output's width and height, and this pass box-filters each 4x4 block into the output.

use super::compute::{ComputePass, Dispatch, FrameSet};
use super::decl::{Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use crate::error::Result;
use crate::shaders;
use crate::vk::recorder::Recorder;
use crate::vk::{Context, DescriptorPool, Tracker};
use std::sync::Arc;

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// 16x supersampling: the 4x4 box filter into the output.
    pub const SSAA_DOWNSAMPLE: PassId = PassId::new("ssaa_downsample", &[Change::Config]);
}

const DOWNSAMPLE: &[Bind] = &[
    Bind::new(0, Slot::Shaded, Use::Sampled),
    Bind::new(1, Slot::Output, Use::StorageWrite),
];

pub fn layout() -> PassLayout {
    ComputePass::layout(
        pass::SSAA_DOWNSAMPLE,
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
            pass::SSAA_DOWNSAMPLE,
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
