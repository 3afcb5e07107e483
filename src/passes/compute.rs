//! What every compute pass shares: its declaration, one pipeline, a descriptor set per frame
//! parity (the G-buffer position and the histories are ping-ponged), and recording as
//! "declared accesses → barriers → bind → dispatch".

use super::decl::{self, Bind, Resolve, Slot};
use super::layout::PassLayout;
use super::pass_id::PassId;
use crate::error::{Error, Result};
use crate::shaders::ShaderModuleInfo;
use crate::vk::recorder::Recorder;
use crate::vk::{Context, DescriptorPool, Pipeline, Tracker};
use ash::vk;
use std::sync::Arc;

/// The frame's set 0 (per-frame constants) and its history parity.
#[derive(Clone, Copy, Debug)]
pub struct FrameSet {
    pub set: vk::DescriptorSet,
    pub parity: usize,
}

/// How many workgroups a dispatch launches.
#[derive(Clone, Copy, Debug)]
pub enum Dispatch {
    /// Enough to cover `width x height` pixels.
    Pixels { width: u32, height: u32 },
    /// The (x, y, z) counts stored at byte `offset` of the pass's `Slot::Counters` buffer.
    Indirect { offset: u64 },
    /// `groups` workgroups in x (one per refresh-tile pixel).
    Groups(u32),
}

/// Set 1 of `pipeline` once per frame parity, labelled `name`.
pub fn parity_sets(
    pool: &DescriptorPool,
    pipeline: &Pipeline,
    name: &str,
) -> Result<[vk::DescriptorSet; 2]> {
    let layout = pipeline.set_layouts[1];
    Ok([
        pool.allocate(layout, &format!("{name} set 1 parity 0"))?,
        pool.allocate(layout, &format!("{name} set 1 parity 1"))?,
    ])
}

/// A compute pass declared once: its timing row, shader module and resources. Both its
/// reflection-check layout ([`PassDecl::layout`]) and its pipeline ([`ComputePass::declared`])
/// come from it, so the two cannot name different modules or tables.
#[derive(Clone, Copy)]
pub struct PassDecl {
    pub id: PassId,
    pub module: &'static ShaderModuleInfo,
    pub binds: &'static [Bind],
}

impl PassDecl {
    pub const fn new(
        id: PassId,
        module: &'static ShaderModuleInfo,
        binds: &'static [Bind],
    ) -> Self {
        Self { id, module, binds }
    }

    /// The layout entry for the up-front reflection check.
    pub fn layout(&self) -> PassLayout {
        ComputePass::layout(self.id, self.module, self.binds)
    }
}

pub struct ComputePass {
    pub id: PassId,
    /// Its shader: the storage formats its bound images must have.
    module: &'static ShaderModuleInfo,
    pipeline: Arc<Pipeline>,
    sets: [vk::DescriptorSet; 2],
    binds: &'static [Bind],
}

impl ComputePass {
    /// The layout entry of a pass for the up-front reflection check.
    pub fn layout(
        id: PassId,
        module: &'static ShaderModuleInfo,
        binds: &'static [Bind],
    ) -> PassLayout {
        PassLayout {
            pass: id,
            modules: vec![module],
            declared: decl::layout(binds),
            binds: binds.to_vec(),
        }
    }

    pub fn new(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        id: PassId,
        module: &'static ShaderModuleInfo,
        binds: &'static [Bind],
    ) -> Result<Self> {
        Self::specialized(ctx, pool, id, (module, binds), &[])
    }

    /// The pass `decl` declares.
    pub fn declared(ctx: &Arc<Context>, pool: &DescriptorPool, decl: &PassDecl) -> Result<Self> {
        Self::new(ctx, pool, decl.id, decl.module, decl.binds)
    }

    /// The pass `decl` declares, with specialization constants.
    pub fn declared_with(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        decl: &PassDecl,
        constants: &[u32],
    ) -> Result<Self> {
        Self::specialized(ctx, pool, decl.id, (decl.module, decl.binds), constants)
    }

    /// With specialization constants (`constant_id = i` takes `constants[i]`).
    pub fn specialized(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        id: PassId,
        (module, binds): (&'static ShaderModuleInfo, &'static [Bind]),
        constants: &[u32],
    ) -> Result<Self> {
        let layout = decl::layout(binds);
        let pipeline = Pipeline::compute_specialized(ctx, id.name(), module, &layout, constants)?;
        Self::with_pipeline(pool, (id, module), Arc::new(pipeline), binds, id.name())
    }

    /// Another instance of the same pipeline with its own descriptor sets (the direct pass
    /// reading the shadow history); `name` labels the sets.
    pub fn instance(&self, pool: &DescriptorPool, name: &str) -> Result<Self> {
        Self::with_pipeline(
            pool,
            (self.id, self.module),
            self.pipeline.clone(),
            self.binds,
            name,
        )
    }

    fn with_pipeline(
        pool: &DescriptorPool,
        (id, module): (PassId, &'static ShaderModuleInfo),
        pipeline: Arc<Pipeline>,
        binds: &'static [Bind],
        name: &str,
    ) -> Result<Self> {
        let sets = parity_sets(pool, &pipeline, name)?;
        Ok(Self {
            id,
            module,
            pipeline,
            sets,
            binds,
        })
    }

    /// Point both parities' descriptor sets at the resources `res` resolves (at creation and
    /// after a resize, with the device idle).
    pub fn bind(&self, ctx: &Context, res: &dyn Resolve) -> Result<()> {
        for (parity, set) in self.sets.iter().enumerate() {
            decl::writes(self.id.name(), self.module, self.binds, res, parity)?.write(ctx, *set);
        }
        Ok(())
    }

    /// Barriers for the declared accesses, then bind, push `push` (if any) and dispatch.
    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        res: &dyn Resolve,
        push: &[u8],
        dispatch: Dispatch,
    ) {
        decl::access(self.id.name(), self.binds, res, frame.parity, tracker);
        tracker.flush(rec.device, rec.cmd);
        rec.bind(&self.pipeline, &[frame.set, self.sets[frame.parity]]);
        // A shader without a push block (the classification) takes none.
        if !push.is_empty() && !self.pipeline.push_stages.is_empty() {
            rec.push(&self.pipeline, push);
        }
        match dispatch {
            Dispatch::Pixels { width, height } => rec.dispatch_2d(&self.pipeline, width, height),
            Dispatch::Groups(groups) => rec.dispatch_groups(groups),
            Dispatch::Indirect { offset } => match res.buffer(Slot::Counters) {
                Some(args) => rec.dispatch_indirect(args, offset),
                None => panic!(
                    "{}",
                    Error::Reflection(format!(
                        "{}: an indirect dispatch needs the effect's counters",
                        self.id.name()
                    ))
                ),
            },
        }
    }

    /// Set 0 (frame constants) layout; identical in every pipeline.
    pub fn frame_layout(&self) -> vk::DescriptorSetLayout {
        self.pipeline.set_layouts[0]
    }
}
