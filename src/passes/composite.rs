//! Composite: ambient x albedo x the product of the visibility terms, plus every radiance term
//! the effects contribute, Reinhard tonemap, sRGB encode into the RGBA8 output. The effects'
//! images come in as numbered terms with a kind each (push constants), so a new effect needs no
//! new shader variant.

use super::compute::{ComputePass, Dispatch, FrameSet};
use super::decl::{Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use crate::error::{Error, Result};
use crate::shaders::{self, CompositePush};
use crate::vk::cmd::Recorder;
use crate::vk::{Buffer, Context, DescriptorPool, Image, Tracker};
use std::sync::Arc;

/// Terms the shader has bindings for.
pub const MAX_TERMS: usize = 4;

const BINDS: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GAlbedo, Use::Sampled),
    Bind::new(2, Slot::Output, Use::StorageWrite),
    Bind::new(3, Slot::Term(0), Use::Sampled),
    Bind::new(4, Slot::Term(1), Use::Sampled),
    Bind::new(5, Slot::Term(2), Use::Sampled),
    Bind::new(6, Slot::Term(3), Use::Sampled),
];

pub fn layout() -> PassLayout {
    ComputePass::layout(PassId::Composite, &shaders::COMPOSITE_COMP, BINDS)
}

/// The composite's inputs: the shared targets, and each term's image per parity with the
/// code of its kind. Bindings past the last term repeat the first image (never read).
pub struct Terms<'a> {
    pub shared: &'a dyn Resolve,
    pub images: Vec<([&'a Image; 2], u32)>,
}

impl Terms<'_> {
    fn push(&self) -> CompositePush {
        let mut kinds = [0; 4];
        for (k, (_, kind)) in kinds.iter_mut().zip(&self.images) {
            *k = *kind;
        }
        CompositePush {
            term_kinds: kinds,
            term_count: self.images.len() as u32,
        }
    }
}

impl Resolve for Terms<'_> {
    fn image(&self, slot: Slot, parity: usize) -> Option<&Image> {
        match slot {
            Slot::Term(i) => self
                .images
                .get(i as usize)
                .or(self.images.first())
                .map(|(pair, _)| pair[parity]),
            other => self.shared.image(other, parity),
        }
    }

    fn buffer(&self, _slot: Slot) -> Option<&Buffer> {
        None
    }
}

pub struct CompositePass {
    pass: ComputePass,
}

impl CompositePass {
    pub fn new(ctx: &Arc<Context>, pool: &DescriptorPool) -> Result<Self> {
        Ok(Self {
            pass: ComputePass::new(
                ctx,
                pool,
                PassId::Composite,
                &shaders::COMPOSITE_COMP,
                BINDS,
            )?,
        })
    }

    pub fn bind(&self, ctx: &Context, terms: &Terms<'_>) -> Result<()> {
        if terms.images.is_empty() || terms.images.len() > MAX_TERMS {
            return Err(Error::Config(format!(
                "the composite takes 1 to {MAX_TERMS} effect terms, not {}",
                terms.images.len()
            )));
        }
        self.pass.bind(ctx, terms)
    }

    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        terms: &Terms<'_>,
        width: u32,
        height: u32,
    ) {
        let push = terms.push().to_bytes();
        self.pass.record(
            rec,
            tracker,
            frame,
            terms,
            &push,
            Dispatch::Pixels { width, height },
        );
    }

    /// Set 0 (frame constants) layout; identical in every pipeline.
    pub fn frame_layout(&self) -> ash::vk::DescriptorSetLayout {
        self.pass.frame_layout()
    }
}
