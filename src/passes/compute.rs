//! What every full-screen compute pass shares: one pipeline and a descriptor set per frame
//! parity (the G-buffer position and the histories are ping-ponged).

use super::PassId;
use crate::error::Result;
use crate::shaders::{ReflectedBinding, ShaderModuleInfo};
use crate::vk::cmd::Recorder;
use crate::vk::{Buffer, Context, DescriptorPool, Pipeline, SetWriter};
use ash::vk;
use std::sync::Arc;

pub struct ComputePass {
    pub pipeline: Pipeline,
    pub sets: [vk::DescriptorSet; 2],
}

impl ComputePass {
    pub fn new(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        pass: PassId,
        module: &ShaderModuleInfo,
        bindings: &[ReflectedBinding],
    ) -> Result<Self> {
        let name = pass.name();
        let pipeline = Pipeline::compute(ctx, name, module, bindings)?;
        let sets = [
            pool.allocate(pipeline.set_layouts[1], &format!("{name} set 1 parity 0"))?,
            pool.allocate(pipeline.set_layouts[1], &format!("{name} set 1 parity 1"))?,
        ];
        Ok(Self { pipeline, sets })
    }

    /// Two more sets with this pipeline's set-1 layout (for per-effect bindings).
    pub fn allocate_sets(
        &self,
        pool: &DescriptorPool,
        name: &str,
    ) -> Result<[vk::DescriptorSet; 2]> {
        let layout = self.pipeline.set_layouts[1];
        Ok([
            pool.allocate(layout, &format!("{name} parity 0"))?,
            pool.allocate(layout, &format!("{name} parity 1"))?,
        ])
    }

    /// Write the set of `parity`.
    pub fn write(&self, ctx: &Context, parity: usize, writer: SetWriter) {
        writer.write(ctx, self.sets[parity]);
    }

    /// Bind for `parity` and dispatch over `width x height` pixels.
    pub fn dispatch(
        &self,
        rec: &Recorder<'_>,
        frame_set: vk::DescriptorSet,
        parity: usize,
        width: u32,
        height: u32,
    ) {
        rec.bind(&self.pipeline, &[frame_set, self.sets[parity]]);
        rec.dispatch_2d(&self.pipeline, width, height);
    }

    /// Bind for `parity`, push `push` (if any) and dispatch with the workgroup counts stored in
    /// `args` at byte `offset`.
    pub fn dispatch_indirect(
        &self,
        rec: &Recorder<'_>,
        frame_set: vk::DescriptorSet,
        parity: usize,
        args: &Buffer,
        offset: u64,
        push: &[u8],
    ) {
        rec.bind(&self.pipeline, &[frame_set, self.sets[parity]]);
        if !push.is_empty() {
            rec.push(&self.pipeline, push);
        }
        rec.dispatch_indirect(args, offset);
    }
}
