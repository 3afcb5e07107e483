//! The fixed pass order of one frame, frames in flight, and the skip decisions.

pub mod frame;
pub mod scene_gpu;
pub mod targets;

use crate::error::{Error, Result};
use crate::passes::composite::CompositePass;
use crate::passes::direct::DirectPass;
use crate::passes::gbuffer::GBufferPass;
use crate::passes::light_view::LightViewPass;
use crate::passes::PassId;
use crate::scene::{Camera, Scene, SpotLight};
use crate::vk::cmd::Recorder;
use crate::vk::{
    read_image, Buffer, Context, DescriptorPool, FrameSlots, FrameTiming, GpuTimer, ImageData,
    SetWriter, SubmitSync, Tracker,
};
use ash::vk;
use frame::{FrameUniforms, Pcf};
use gpu_allocator::MemoryLocation;
use scene_gpu::SceneGpu;
use std::sync::Arc;
use targets::{Target, Targets};

/// Extra recording at the end of a frame plus the frame's submit semaphores.
pub struct FrameHook<'a> {
    pub record: &'a mut dyn FnMut(&Recorder<'_>, &mut Tracker, &crate::vk::Image),
    pub sync: SubmitSync,
}

/// Frames the CPU may record ahead of the GPU.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// Largest accepted image side: well above any real display, small enough that a typo like
/// `--size 100000x100000` fails with a clear message instead of an allocation error.
pub const MAX_SIZE: u32 = 16384;

#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct RenderConfig {
    pub width: u32,
    pub height: u32,
    /// Side of the (square) reflective shadow map / shadow map.
    pub rsm_size: u32,
    pub pcf: Pcf,
}

impl Default for RenderConfig {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            rsm_size: 512,
            pcf: Pcf::DEFAULT,
        }
    }
}

impl RenderConfig {
    pub fn validate(&self) -> Result<()> {
        for (what, v) in [
            ("width", self.width),
            ("height", self.height),
            ("shadow map size", self.rsm_size),
        ] {
            if v == 0 || v > MAX_SIZE {
                return Err(Error::Config(format!(
                    "{what} {v} is outside 1..={MAX_SIZE}"
                )));
            }
        }
        Ok(())
    }
}

struct FrameResources {
    uniforms: Buffer,
    set: vk::DescriptorSet,
}

pub struct Renderer {
    ctx: Arc<Context>,
    pub config: RenderConfig,
    pub scene: Scene,
    light_view: LightViewPass,
    gbuffer: GBufferPass,
    direct: DirectPass,
    composite: CompositePass,
    scene_gpu: SceneGpu,
    targets: Targets,
    frames: Vec<FrameResources>,
    slots: FrameSlots,
    timer: GpuTimer,
    tracker: Tracker,
    frame_index: u64,
    /// The light the RSM currently holds; `None` forces a re-render.
    rsm_light: Option<SpotLight>,
    _pool: DescriptorPool,
}

impl Renderer {
    pub fn new(ctx: &Arc<Context>, scene: Scene, config: RenderConfig) -> Result<Self> {
        config.validate()?;
        let textured = scene.mesh.has_textures();
        let pool = DescriptorPool::new(ctx, 16 + scene.mesh.materials.len() as u32)?;
        let light_view = LightViewPass::new(ctx, textured)?;
        let gbuffer = GBufferPass::new(ctx, textured)?;
        let direct = DirectPass::new(ctx, &pool)?;
        let composite = CompositePass::new(ctx, &pool)?;
        let mut tracker = Tracker::new();
        let scene_gpu = SceneGpu::new(
            ctx,
            &mut tracker,
            &pool,
            &scene.mesh,
            light_view.material_layout(),
        )?;
        let targets = Targets::new(ctx, config.width, config.height, config.rsm_size)?;
        direct.bind_targets(ctx, &targets);
        composite.bind_targets(ctx, &targets);
        let frame_layout = direct.frame_layout();
        let mut frames = Vec::new();
        for _ in 0..FRAMES_IN_FLIGHT {
            let uniforms = Buffer::new(
                ctx,
                "frame.uniforms",
                FrameUniforms::SIZE as u64,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            )?;
            let set = pool.allocate(frame_layout)?;
            SetWriter::new().uniform(0, &uniforms).write(ctx, set);
            frames.push(FrameResources { uniforms, set });
        }
        Ok(Self {
            ctx: ctx.clone(),
            config,
            scene,
            light_view,
            gbuffer,
            direct,
            composite,
            scene_gpu,
            targets,
            frames,
            slots: FrameSlots::new(ctx, FRAMES_IN_FLIGHT)?,
            timer: GpuTimer::new(ctx, FRAMES_IN_FLIGHT, PassId::ALL.len() as u32)?,
            tracker,
            frame_index: 0,
            rsm_light: None,
            _pool: pool,
        })
    }

    pub fn context(&self) -> &Arc<Context> {
        &self.ctx
    }

    pub fn frame_index(&self) -> u64 {
        self.frame_index
    }

    /// Change the light; the light view is re-rendered on the next frame.
    pub fn set_light(&mut self, light: SpotLight) {
        self.scene.light = light;
    }

    /// Record and submit one frame seen from `camera`. Returns the GPU timing of the frame that
    /// last used this slot (`FRAMES_IN_FLIGHT` frames ago), if any.
    pub fn render_frame(&mut self, camera: &Camera) -> Result<Option<FrameTiming>> {
        self.render_frame_with(camera, None)
    }

    /// As `render_frame`, with a hook that records after the composite (the window frontend
    /// copies the output into the swapchain image there) and the submission's semaphores.
    pub fn render_frame_with(
        &mut self,
        camera: &Camera,
        mut hook: Option<FrameHook<'_>>,
    ) -> Result<Option<FrameTiming>> {
        let slot = (self.frame_index % FRAMES_IN_FLIGHT as u64) as usize;
        let cmd = self.slots.begin(slot)?;
        let previous = self.timer.begin_frame(slot, self.frame_index);
        let c = &self.config;
        let uniforms = FrameUniforms::new(
            camera,
            c.width as f32 / c.height as f32,
            &self.scene.light,
            self.scene.ambient,
            c.width,
            c.height,
            self.frame_index,
            c.pcf,
            c.rsm_size,
        );
        // Host write before submission: the submit makes it visible, no barrier needed.
        self.frames[slot].uniforms.write(&uniforms.bytes())?;
        let frame_set = self.frames[slot].set;
        let rec = Recorder {
            device: &self.ctx.device,
            cmd,
        };

        // Light view only when the light changed since the RSM was rendered (geometry is
        // static for the renderer's lifetime).
        if self.rsm_light != Some(self.scene.light) {
            let began = self.timer.begin_pass(cmd, slot, PassId::LightView.name());
            self.light_view.record(
                &rec,
                &mut self.tracker,
                frame_set,
                &self.scene_gpu,
                &self.targets.rsm,
            );
            if began {
                self.timer.end_pass(cmd, slot);
            }
            self.rsm_light = Some(self.scene.light);
        } else {
            self.timer.skip(slot, PassId::LightView.name());
        }

        let began = self.timer.begin_pass(cmd, slot, PassId::GBuffer.name());
        self.gbuffer.record(
            &rec,
            &mut self.tracker,
            frame_set,
            &self.scene_gpu,
            &self.targets.gbuffer,
        );
        if began {
            self.timer.end_pass(cmd, slot);
        }

        let began = self.timer.begin_pass(cmd, slot, PassId::Direct.name());
        self.direct
            .record(&rec, &mut self.tracker, frame_set, &self.targets);
        if began {
            self.timer.end_pass(cmd, slot);
        }

        let began = self.timer.begin_pass(cmd, slot, PassId::Composite.name());
        self.composite
            .record(&rec, &mut self.tracker, frame_set, &self.targets);
        if began {
            self.timer.end_pass(cmd, slot);
        }

        let sync = match &mut hook {
            Some(h) => {
                (h.record)(&rec, &mut self.tracker, &self.targets.output);
                h.sync.clone()
            }
            None => SubmitSync::default(),
        };
        self.slots.submit_with(slot, &sync)?;
        self.frame_index += 1;
        Ok(previous)
    }

    /// Wait for the GPU and return the timings not yet returned, oldest first.
    pub fn finish(&mut self) -> Result<Vec<FrameTiming>> {
        self.slots.wait_all()?;
        let mut out: Vec<FrameTiming> = (0..FRAMES_IN_FLIGHT)
            .filter_map(|slot| self.timer.collect(slot))
            .collect();
        out.sort_by_key(|t| t.frame);
        Ok(out)
    }

    /// Recreate every size-dependent target for a new output size (window resize). Waits for
    /// the GPU; timings of frames in flight are returned. Histories start over.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<Vec<FrameTiming>> {
        let config = RenderConfig {
            width,
            height,
            ..self.config
        };
        config.validate()?;
        let pending = self.finish()?;
        self.ctx.wait_idle()?;
        self.targets = Targets::new(&self.ctx, width, height, config.rsm_size)?;
        self.direct.bind_targets(&self.ctx, &self.targets);
        self.composite.bind_targets(&self.ctx, &self.targets);
        self.config = config;
        // The RSM targets were recreated with the rest: render the light view again.
        self.rsm_light = None;
        Ok(pending)
    }

    /// Copy a target to the host (waits for the GPU).
    pub fn read(&mut self, target: Target) -> Result<ImageData> {
        read_image(&self.ctx, &mut self.tracker, self.targets.get(target))
    }
}
