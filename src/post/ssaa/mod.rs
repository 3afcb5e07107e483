//! 16x supersampling (`--aa ssaa16`), the antialiasing reference: the frame renders at 4x the
//! output's width and height, and this pass box-filters each 4x4 block into the output.

use super::stage::{PostFrame, PostRegistration, PostStage};
use crate::config::RenderConfig;
use crate::effects::Recording;
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch, FrameSet};
use crate::passes::decl::{Bind, Resolve, Slot, Use};
use crate::passes::layout::PassLayout;
use crate::shaders;
use crate::vk::recorder::Recorder;
use crate::vk::{Context, DescriptorPool, Tracker};
use std::sync::Arc;

/// The stage's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// 16x supersampling: the 4x4 box filter into the output.
    pub const SSAA_DOWNSAMPLE: PassId = PassId::new("ssaa_downsample", &[Change::Config]);

    /// Every pass, in recording order.
    pub const ALL: &[PassId] = &[SSAA_DOWNSAMPLE];
}

pub const REGISTRATION: PostRegistration = PostRegistration {
    enabled: |c: &RenderConfig| c.aa.mode.supersampling() > 1,
    create: |ctx, pool, _| Ok(Box::new(SsaaPass::new(ctx, pool)?)),
    layouts: || vec![layout()],
    passes: pass::ALL,
    geometry_passes: &[],
};

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

    /// Over the output size.
    fn record_downsample(
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

impl PostStage for SsaaPass {
    fn bind(&self, ctx: &Context, targets: &dyn Resolve) -> Result<()> {
        self.pass.bind(ctx, targets)
    }

    fn record(&self, r: &mut Recording<'_>, f: &PostFrame<'_>) {
        r.timed(pass::SSAA_DOWNSAMPLE, |rec, tr| {
            self.record_downsample(rec, tr, f.frame, f.targets, f.output)
        });
    }
}
