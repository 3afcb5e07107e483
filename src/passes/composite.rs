//! Composite: ambient x albedo x the product of the visibility terms, plus every radiance term
//! the effects contribute, Reinhard tonemap, sRGB encode into the RGBA8 output. The effects'
//! images come in as numbered terms; their count and kinds are specialization constants of the
//! pipeline, so a new effect needs no new shader variant and unused terms cost nothing.

use super::compute::{ComputePass, Dispatch, FrameSet};
use super::decl::{Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use crate::error::{Error, Result};
use crate::shaders;
use crate::vk::recorder::Recorder;
use crate::vk::{Buffer, Context, DescriptorPool, Image, Tracker};
use std::sync::Arc;

/// Effect terms the shader has bindings for.
pub const MAX_TERMS: usize = 4;

/// Into the final RGBA8 image, sRGB-encoded.
const BINDS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GAlbedo, Use::Sampled),
    Bind::new(2, Slot::Output, Use::StorageWrite),
    Bind::new(3, Slot::Term(0), Use::Sampled),
    Bind::new(4, Slot::Term(1), Use::Sampled),
    Bind::new(5, Slot::Term(2), Use::Sampled),
    Bind::new(6, Slot::Term(3), Use::Sampled),
];

/// With antialiasing: into the display-linear image the antialiasing pass filters.
const BINDS_LINEAR: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GAlbedo, Use::Sampled),
    Bind::new(2, Slot::Shaded, Use::StorageWrite),
    Bind::new(3, Slot::Term(0), Use::Sampled),
    Bind::new(4, Slot::Term(1), Use::Sampled),
    Bind::new(5, Slot::Term(2), Use::Sampled),
    Bind::new(6, Slot::Term(3), Use::Sampled),
];

fn module(linear: bool) -> (&'static crate::shaders::ShaderModuleInfo, &'static [Bind]) {
    if linear {
        (&shaders::COMPOSITE_COMP_LINEAR, BINDS_LINEAR)
    } else {
        (&shaders::COMPOSITE_COMP_SRGB, BINDS)
    }
}

pub fn layouts() -> Vec<PassLayout> {
    [false, true]
        .into_iter()
        .map(|linear| {
            let (module, binds) = module(linear);
            ComputePass::layout(PassId::COMPOSITE, module, binds)
        })
        .collect()
}

/// The composite's inputs: the shared targets, and each term's image per parity (in the order
/// of the kinds the pass was built with). Bindings past the last term repeat the first image
/// (never read).
pub struct CompositeInputs<'a> {
    pub shared: &'a dyn Resolve,
    /// The first `n` filled; a fixed array, so building it every frame allocates nothing.
    pub images: [Option<[&'a Image; 2]>; MAX_TERMS],
}

impl CompositeInputs<'_> {
    fn count(&self) -> usize {
        self.images.iter().take_while(|i| i.is_some()).count()
    }
}

impl Resolve for CompositeInputs<'_> {
    fn image(&self, slot: Slot, parity: usize) -> Option<&Image> {
        match slot {
            Slot::Term(i) => self
                .images
                .get(i as usize)
                .copied()
                .flatten()
                .or(self.images[0])
                .map(|pair| pair[parity]),
            other => self.shared.image(other, parity),
        }
    }

    fn buffer(&self, _slot: Slot) -> Option<&Buffer> {
        None
    }
}

pub struct CompositePass {
    pass: ComputePass,
    terms: usize,
}

impl CompositePass {
    /// For terms of the kinds `kinds` (the shader's codes), in order; `linear` writes the
    /// display-linear image an antialiasing pass filters instead of the output.
    pub fn new(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        kinds: &[u32],
        linear: bool,
    ) -> Result<Self> {
        if kinds.is_empty() || kinds.len() > MAX_TERMS {
            return Err(Error::Config(format!(
                "the composite takes 1 to {MAX_TERMS} effect terms, not {}",
                kinds.len()
            )));
        }
        let mut constants = vec![kinds.len() as u32];
        constants.extend(kinds);
        constants.resize(1 + MAX_TERMS, 0);
        Ok(Self {
            pass: ComputePass::specialized(
                ctx,
                pool,
                PassId::COMPOSITE,
                module(linear),
                &constants,
            )?,
            terms: kinds.len(),
        })
    }

    pub fn bind(&self, ctx: &Context, inputs: &CompositeInputs<'_>) -> Result<()> {
        if inputs.count() != self.terms {
            return Err(Error::Config(format!(
                "the composite was built for {} terms, not {}",
                self.terms,
                inputs.count()
            )));
        }
        self.pass.bind(ctx, inputs)
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        inputs: &CompositeInputs<'_>,
        width: u32,
        height: u32,
    ) {
        self.pass.record(
            rec,
            tracker,
            frame,
            inputs,
            &[],
            Dispatch::Pixels { width, height },
        );
    }

    /// Set 0 (frame constants) layout; identical in every pipeline.
    pub fn frame_layout(&self) -> ash::vk::DescriptorSetLayout {
        self.pass.frame_layout()
    }
}
