//! The fixed pass order of one frame, frames in flight, history ping-pong and the skip
//! decisions:
//!
//! light view (only when the light changed) → G-buffer → direct → [reproject → SSAO (indirect,
//! only blocks that need work)] or [SSAO every pixel → 5x5 blur] → composite.

pub mod config;
pub mod counters;
pub mod frame;
pub mod scene_gpu;
pub mod targets;
pub mod temporal;

use crate::error::Result;
use crate::passes::blur::BlurPass;
use crate::passes::composite::CompositePass;
use crate::passes::direct::DirectPass;
use crate::passes::gbuffer::GBufferPass;
use crate::passes::light_view::LightViewPass;
use crate::passes::reproject::ReprojectPass;
use crate::passes::ssao::SsaoPass;
use crate::passes::PassId;
use crate::scene::{Camera, Scene, SpotLight};
use crate::vk::cmd::Recorder;
use crate::vk::{
    read_image, upload_image, Access, Buffer, Context, DescriptorPool, FrameSlots, FrameTiming,
    GpuTimer, Image, ImageData, ImageDesc, SetWriter, SubmitSync, Tracker,
};
use ash::vk;
pub use config::{RenderConfig, MAX_SIZE};
use counters::{CounterReadback, DISOCCLUDED_PIXELS, SSAO_COMPUTED_PIXELS};
use frame::{FrameInputs, FrameUniforms};
use glam::Mat4;
use gpu_allocator::MemoryLocation;
use scene_gpu::SceneGpu;
use std::sync::Arc;
use targets::{AoSource, Target, Targets};
use temporal::RefreshSchedule;

/// Extra recording at the end of a frame plus the frame's submit semaphores.
pub struct FrameHook<'a> {
    /// Called with the target named by `source` (the window frontend blits it into the
    /// swapchain image there).
    pub record: &'a mut dyn FnMut(&Recorder<'_>, &mut Tracker, &crate::vk::Image),
    pub sync: SubmitSync,
    /// Which target `record` receives: `Target::Output` (the final RGBA8 image), or another
    /// one for the viewer's buffer display.
    pub source: Target,
}

/// Frames the CPU may record ahead of the GPU.
pub const FRAMES_IN_FLIGHT: usize = 2;

struct FrameResources {
    uniforms: Buffer,
    set: vk::DescriptorSet,
}

/// AO passes, present only when the AO effect is on.
struct AoPasses {
    reproject: Option<ReprojectPass>,
    ssao: SsaoPass,
    blur: Option<BlurPass>,
    random: Image,
}

/// Size-dependent state: targets, the counters buffer, the refresh schedule.
struct Sized {
    targets: Targets,
    counters: Buffer,
    refresh: RefreshSchedule,
}

pub struct Renderer {
    ctx: Arc<Context>,
    pub config: RenderConfig,
    pub scene: Scene,
    light_view: LightViewPass,
    gbuffer: GBufferPass,
    direct: Option<DirectPass>,
    ao: Option<AoPasses>,
    composite: CompositePass,
    scene_gpu: SceneGpu,
    sized: Sized,
    frames: Vec<FrameResources>,
    slots: FrameSlots,
    timer: GpuTimer,
    counter_readback: CounterReadback,
    tracker: Tracker,
    frame_index: u64,
    /// The light the RSM currently holds; `None` forces a re-render.
    rsm_light: Option<SpotLight>,
    /// Last frame's camera view-projection, when the histories hold last frame's data.
    history: Option<Mat4>,
    _pool: DescriptorPool,
}

impl Renderer {
    pub fn new(ctx: &Arc<Context>, scene: Scene, config: RenderConfig) -> Result<Self> {
        config.validate()?;
        let textured = scene.mesh.has_textures();
        let pool = DescriptorPool::new(ctx, 32 + scene.mesh.materials.len() as u32)?;
        let light_view = LightViewPass::new(ctx, textured)?;
        let gbuffer = GBufferPass::new(ctx, textured)?;
        let direct = if config.effects.direct {
            Some(DirectPass::new(ctx, &pool)?)
        } else {
            None
        };
        let composite = CompositePass::new(ctx, &pool, config.effects)?;
        let mut tracker = Tracker::new();
        let scene_gpu = SceneGpu::new(
            ctx,
            &mut tracker,
            &pool,
            &scene.mesh,
            light_view.material_layout(),
        )?;
        let ao = if config.effects.ao {
            let reuse = config.temporal.reuse;
            let random = Image::new(
                ctx,
                "ao.random_vectors",
                ImageDesc {
                    width: 4,
                    height: 4,
                    format: vk::Format::R32G32B32A32_SFLOAT,
                    usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
                },
            )?;
            upload_image(
                ctx,
                &mut tracker,
                &random,
                &temporal::random_vectors(),
                Access::ComputeSampledRead,
            )?;
            Some(AoPasses {
                reproject: if reuse {
                    Some(ReprojectPass::new(ctx, &pool)?)
                } else {
                    None
                },
                ssao: SsaoPass::new(ctx, &pool, reuse)?,
                blur: if !reuse && config.ao.patterns == 1 {
                    Some(BlurPass::new(ctx, &pool)?)
                } else {
                    None
                },
                random,
            })
        } else {
            None
        };
        // Set 0 layout: every pipeline declares the same frame binding, so any of them works.
        let frame_layout = composite.frame_layout();
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
        let sized = Self::create_sized(ctx, &config)?;
        let renderer = Self {
            ctx: ctx.clone(),
            config,
            scene,
            light_view,
            gbuffer,
            direct,
            ao,
            composite,
            scene_gpu,
            sized,
            frames,
            slots: FrameSlots::new(ctx, FRAMES_IN_FLIGHT)?,
            timer: GpuTimer::new(ctx, FRAMES_IN_FLIGHT, PassId::ALL.len() as u32)?,
            counter_readback: CounterReadback::new(ctx, FRAMES_IN_FLIGHT)?,
            tracker,
            frame_index: 0,
            rsm_light: None,
            history: None,
            _pool: pool,
        };
        renderer.bind_targets();
        Ok(renderer)
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        Ok(Sized {
            targets: Targets::new(ctx, c.width, c.height, c.rsm_size)?,
            counters: counters::create_gpu_buffer(ctx, c.width, c.height)?,
            refresh: RefreshSchedule::new(c.width, c.height),
        })
    }

    /// Where the composite's AO comes from in this configuration.
    pub fn ao_source(&self) -> AoSource {
        match (&self.ao, self.config.temporal.reuse) {
            (Some(ao), false) if ao.blur.is_none() => AoSource::Raw,
            (_, false) => AoSource::Blurred,
            _ => AoSource::History,
        }
    }

    fn bind_targets(&self) {
        let t = &self.sized.targets;
        if let Some(direct) = &self.direct {
            direct.bind_targets(&self.ctx, t);
        }
        if let Some(ao) = &self.ao {
            if let Some(r) = &ao.reproject {
                r.bind_targets(&self.ctx, t, &self.sized.counters);
            }
            ao.ssao
                .bind_targets(&self.ctx, t, &ao.random, &self.sized.counters);
            if let Some(b) = &ao.blur {
                b.bind_targets(&self.ctx, t);
            }
        }
        self.composite.bind_targets(&self.ctx, t, self.ao_source());
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

    /// Forget every history (camera cut): the next frame recomputes all pixels.
    pub fn reset_history(&mut self) {
        self.history = None;
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
        let parity = (self.frame_index % 2) as usize;
        let cmd = self.slots.begin(slot)?;
        let mut previous = self.timer.begin_frame(slot, self.frame_index);
        let counters = self.counter_readback.collect(slot);
        if let Some(p) = &mut previous {
            p.counters = counters;
        }
        let c = self.config;
        let aspect = c.width as f32 / c.height as f32;
        let view_proj = camera.view_proj(aspect);
        let reuse = c.temporal.reuse && self.ao.is_some();
        let refresh_tile = (reuse && c.temporal.refresh && self.history.is_some())
            .then(|| self.sized.refresh.next_tile());
        let uniforms = FrameUniforms::new(
            &c,
            &FrameInputs {
                camera,
                prev_view_proj: self.history.unwrap_or(view_proj),
                light: &self.scene.light,
                ambient: self.scene.ambient,
                frame: self.frame_index,
                history_valid: self.history.is_some(),
                refresh_tile,
                scene_radius: self.scene.mesh.bounds.radius(),
            },
        );
        // Host write before submission: the submit makes it visible, no barrier needed.
        self.frames[slot].uniforms.write(&uniforms.bytes())?;
        let frame_set = self.frames[slot].set;
        let rec = Recorder {
            device: &self.ctx.device,
            cmd,
        };
        let ao_source = self.ao_source();
        let t = &self.sized.targets;
        let tracker = &mut self.tracker;
        let timer = &mut self.timer;
        let mut timed = |pass: PassId, tracker: &mut Tracker, f: &mut dyn FnMut(&mut Tracker)| {
            let began = timer.begin_pass(cmd, slot, pass.name());
            f(tracker);
            if began {
                timer.end_pass(cmd, slot);
            }
        };

        // Light view only when the light changed since the RSM was rendered (geometry is
        // static for the renderer's lifetime).
        let light_changed = self.rsm_light != Some(self.scene.light);
        if light_changed {
            timed(PassId::LightView, tracker, &mut |tr| {
                self.light_view
                    .record(&rec, tr, frame_set, &self.scene_gpu, &t.rsm)
            });
            self.rsm_light = Some(self.scene.light);
        }
        timed(PassId::GBuffer, tracker, &mut |tr| {
            self.gbuffer
                .record(&rec, tr, frame_set, &self.scene_gpu, &t.gbuffer, parity)
        });
        if let Some(direct) = &self.direct {
            timed(PassId::Direct, tracker, &mut |tr| {
                direct.record(&rec, tr, frame_set, parity, t)
            });
        }
        let mut active_counters = Vec::new();
        if let Some(ao) = &self.ao {
            counters::record_reset(&rec, tracker, &self.sized.counters);
            if let Some(reproject) = &ao.reproject {
                timed(PassId::Reproject, tracker, &mut |tr| {
                    reproject.record(&rec, tr, frame_set, parity, t, &self.sized.counters)
                });
                active_counters.push(DISOCCLUDED_PIXELS);
            }
            timed(PassId::Ssao, tracker, &mut |tr| {
                ao.ssao.record(
                    &rec,
                    tr,
                    frame_set,
                    parity,
                    t,
                    &ao.random,
                    &self.sized.counters,
                )
            });
            active_counters.push(SSAO_COMPUTED_PIXELS);
            if let Some(blur) = &ao.blur {
                timed(PassId::Blur, tracker, &mut |tr| {
                    blur.record(&rec, tr, frame_set, parity, t)
                });
            }
        }
        timed(PassId::Composite, tracker, &mut |tr| {
            self.composite
                .record(&rec, tr, frame_set, parity, t, ao_source)
        });
        if !active_counters.is_empty() {
            self.counter_readback.record_copy(
                &rec,
                tracker,
                &self.sized.counters,
                slot,
                active_counters,
            );
        }
        if !light_changed {
            self.timer.skip(slot, PassId::LightView.name());
        }

        let sync = match &mut hook {
            Some(h) => {
                let source = t.get(h.source, parity, ao_source);
                (h.record)(&rec, &mut self.tracker, source);
                h.sync.clone()
            }
            None => SubmitSync::default(),
        };
        self.slots.submit_with(slot, &sync)?;
        self.history = Some(view_proj);
        self.frame_index += 1;
        Ok(previous)
    }

    /// The frame slot the next `render_frame` uses.
    pub fn next_slot(&self) -> usize {
        (self.frame_index % FRAMES_IN_FLIGHT as u64) as usize
    }

    /// Wait until the next frame's slot is free (its previous submission completed), without
    /// starting the frame: the window frontend calls this before reusing the slot's swapchain
    /// acquire semaphore.
    pub fn wait_for_next_slot(&mut self) -> Result<()> {
        let slot = self.next_slot();
        self.slots.wait(slot)
    }

    /// The format of `target` (the window frontend checks it can be blitted).
    pub fn target_format(&self, target: Target) -> vk::Format {
        self.sized
            .targets
            .get(target, 0, self.ao_source())
            .desc
            .format
    }

    /// Wait for the GPU and return the timings not yet returned, oldest first.
    pub fn finish(&mut self) -> Result<Vec<FrameTiming>> {
        self.slots.wait_all()?;
        let mut out = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            if let Some(mut t) = self.timer.collect(slot) {
                t.counters = self.counter_readback.collect(slot);
                out.push(t);
            }
        }
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
        self.sized = Self::create_sized(&self.ctx, &config)?;
        self.config = config;
        self.bind_targets();
        // The RSM targets were recreated with the rest: render the light view again.
        self.rsm_light = None;
        self.history = None;
        Ok(pending)
    }

    /// Copy a target of the last rendered frame to the host (waits for the GPU).
    pub fn read(&mut self, target: Target) -> Result<ImageData> {
        let parity = (self.frame_index.wrapping_sub(1) % 2) as usize;
        let image = self.sized.targets.get(target, parity, self.ao_source());
        read_image(&self.ctx, &mut self.tracker, image)
    }
}
