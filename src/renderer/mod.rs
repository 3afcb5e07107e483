//! The fixed pass order of one frame, frames in flight, history ping-pong and the skip
//! decisions:
//!
//! light view (only when the light changed) → G-buffer → direct → [reproject → SSAO (indirect,
//! only blocks that need work)] or [SSAO every pixel → 5x5 blur] → composite.

pub mod config;
pub mod counters;
pub mod effect;
pub mod frame;
pub mod pcf;
pub mod scene_gpu;
pub mod targets;
pub mod temporal;

use crate::error::{Error, Result};
use crate::passes::blur::BlurPass;
use crate::passes::composite::CompositePass;
use crate::passes::direct::DirectPass;
use crate::passes::gbuffer::GBufferPass;
use crate::passes::indirect::{IndirectPass, IndirectTargets};
use crate::passes::light_view::LightViewPass;
use crate::passes::reproject::ReprojectPass;
use crate::passes::shadow::ShadowPass;
use crate::passes::ssao::SsaoPass;
use crate::passes::PassId;
use crate::scene::{Camera, Scene, SpotLight};
use crate::shaders::EffectPush;
use crate::vk::cmd::Recorder;
use crate::vk::{
    read_image, upload_image, Access, Buffer, Context, DescriptorPool, FrameSlots, FrameTiming,
    GpuTimer, Image, ImageData, ImageDesc, SetWriter, SubmitSync, Tracker,
};
use ash::vk;
pub use config::{RenderConfig, MAX_SIZE};
use effect::TemporalEffect;
use frame::{frame_block, FrameBlock, FrameInputs};
use glam::Mat4;
use gpu_allocator::MemoryLocation;
use pcf::PcfKernel;
use scene_gpu::SceneGpu;
use std::sync::Arc;
use targets::{Target, Targets};

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
    ssao: SsaoPass,
    blur: Option<BlurPass>,
    random: Image,
}

/// Size-dependent state: targets and the temporal effects' histories and work lists.
struct Sized {
    targets: Targets,
    ao: Option<TemporalEffect>,
    shadow: Option<TemporalEffect>,
    indirect: Option<(TemporalEffect, IndirectTargets)>,
}

/// Reprojection descriptor sets of each effect, allocated once and rewritten on resize.
struct EffectSets {
    ao: [vk::DescriptorSet; 2],
    shadow: [vk::DescriptorSet; 2],
    indirect: [vk::DescriptorSet; 2],
}

pub struct Renderer {
    ctx: Arc<Context>,
    pub config: RenderConfig,
    pub scene: Scene,
    light_view: LightViewPass,
    gbuffer: GBufferPass,
    reproject: ReprojectPass,
    shadow_full: Option<ShadowPass>,
    shadow_accumulate: Option<ShadowPass>,
    direct: Option<DirectPass>,
    ao: Option<AoPasses>,
    indirect: Option<IndirectPass>,
    composite: CompositePass,
    scene_gpu: SceneGpu,
    sized: Sized,
    effect_sets: EffectSets,
    frames: Vec<FrameResources>,
    slots: FrameSlots,
    timer: GpuTimer,
    tracker: Tracker,
    frame_index: u64,
    /// The light the RSM currently holds; `None` forces a re-render.
    rsm_light: Option<SpotLight>,
    /// Last frame's camera view-projection, when the histories hold last frame's data.
    history: Option<Mat4>,
    /// The last pass recorded into each slot's command buffer (device-loss reports).
    last_pass: [Option<PassId>; FRAMES_IN_FLIGHT],
    _pool: DescriptorPool,
}

impl Renderer {
    pub fn new(ctx: &Arc<Context>, scene: Scene, config: RenderConfig) -> Result<Self> {
        config.validate()?;
        let textured = scene.mesh.has_textures();
        let pool = DescriptorPool::new(ctx, 48 + scene.mesh.materials.len() as u32)?;
        let light_view = LightViewPass::new(ctx, textured)?;
        let gbuffer = GBufferPass::new(ctx, textured)?;
        let reproject = ReprojectPass::new(ctx, &pool)?;
        let direct_on = config.effects.direct;
        let (direct, shadow_full, shadow_accumulate) = if direct_on {
            (
                Some(DirectPass::new(ctx, &pool)?),
                Some(ShadowPass::new(ctx, &pool, false)?),
                if config.temporal.reuse {
                    Some(ShadowPass::new(ctx, &pool, true)?)
                } else {
                    None
                },
            )
        } else {
            (None, None, None)
        };
        let composite = CompositePass::new(ctx, &pool, config.effects)?;
        let indirect = if config.effects.indirect {
            Some(IndirectPass::new(ctx, &pool, config.indirect.half_res)?)
        } else {
            None
        };
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
                FrameBlock::SIZE as u64,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            )?;
            let set = pool.allocate(frame_layout, "frame.uniforms set 0")?;
            SetWriter::new().uniform(0, &uniforms).write(ctx, set);
            frames.push(FrameResources { uniforms, set });
        }
        let effect_sets = EffectSets {
            ao: reproject.allocate_sets(&pool, "ao")?,
            shadow: reproject.allocate_sets(&pool, "shadow")?,
            indirect: reproject.allocate_sets(&pool, "indirect")?,
        };
        let sized = Self::create_sized(ctx, &config, &effect_sets)?;
        let renderer = Self {
            ctx: ctx.clone(),
            config,
            scene,
            light_view,
            gbuffer,
            reproject,
            shadow_full,
            shadow_accumulate,
            direct,
            ao,
            indirect,
            composite,
            scene_gpu,
            sized,
            effect_sets,
            frames,
            slots: FrameSlots::new(ctx, FRAMES_IN_FLIGHT)?,
            timer: GpuTimer::new(ctx, FRAMES_IN_FLIGHT, PassId::ALL.len() as u32 + 2)?,
            tracker,
            frame_index: 0,
            rsm_light: None,
            history: None,
            last_pass: [None; FRAMES_IN_FLIGHT],
            _pool: pool,
        };
        renderer.bind_targets();
        Ok(renderer)
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig, sets: &EffectSets) -> Result<Sized> {
        let (w, h) = (c.width, c.height);
        let effect = |on: bool, kind, sets| -> Result<Option<TemporalEffect>> {
            if !on {
                return Ok(None);
            }
            Ok(Some(TemporalEffect::new(
                ctx,
                kind,
                w,
                h,
                FRAMES_IN_FLIGHT,
                sets,
            )?))
        };
        Ok(Sized {
            targets: Targets::new(ctx, w, h, c.rsm_size)?,
            ao: effect(c.effects.ao, effect::AO, sets.ao)?,
            shadow: effect(
                c.effects.direct && c.temporal.reuse,
                effect::SHADOW,
                sets.shadow,
            )?,
            indirect: match effect(c.effects.indirect, effect::INDIRECT, sets.indirect)? {
                Some(e) => {
                    let own = IndirectTargets {
                        lowres: Buffer::new(
                            ctx,
                            "indirect.lowres",
                            e.max_blocks as u64 * 100 * 16,
                            vk::BufferUsageFlags::STORAGE_BUFFER,
                            MemoryLocation::GpuOnly,
                        )?,
                        discard: Image::new(
                            ctx,
                            "indirect.discard",
                            ImageDesc {
                                width: w,
                                height: h,
                                format: targets::STATE_FORMAT,
                                usage: vk::ImageUsageFlags::STORAGE
                                    | vk::ImageUsageFlags::TRANSFER_SRC,
                            },
                        )?,
                    };
                    Some((e, own))
                }
                None => None,
            },
        })
    }

    /// Every temporal effect of this configuration.
    fn effects_mut(&mut self) -> impl Iterator<Item = &mut TemporalEffect> {
        let s = &mut self.sized;
        [
            s.ao.as_mut(),
            s.shadow.as_mut(),
            s.indirect.as_mut().map(|(e, _)| e),
        ]
        .into_iter()
        .flatten()
    }

    /// Whether this frame's shadows come from the accumulated history: reuse on and a disc
    /// kernel (the thesis's rotated and scaled 9-sample PCF). Grids run every frame.
    fn shadow_reuse(&self) -> bool {
        self.config.temporal.reuse
            && matches!(self.config.pcf.kernel, PcfKernel::Disc { .. })
            && self.sized.shadow.is_some()
    }

    /// Which images hold the effect targets in this configuration.
    fn sources(&self) -> TargetSources {
        TargetSources {
            ao: self.ao.is_some(),
            ao_blur: self.ao.as_ref().is_some_and(|a| a.blur.is_some()),
            reuse: self.config.temporal.reuse,
            shadow_reuse: self.shadow_reuse(),
        }
    }

    /// Slot the next frame will record into.
    pub fn next_slot(&self) -> usize {
        (self.frame_index % FRAMES_IN_FLIGHT as u64) as usize
    }

    /// Wait until the next frame's slot is free (its previous submission finished), so that
    /// per-slot objects of a frontend (swapchain semaphores) can be reused.
    pub fn wait_for_next_slot(&mut self) -> Result<()> {
        let slot = self.next_slot();
        self.slots.wait(slot)
    }

    /// Format of a target's image (the window frontend checks blit support with it).
    pub fn target_format(&self, target: Target) -> vk::Format {
        let parity = (self.frame_index.wrapping_sub(1) % 2) as usize;
        self.sources()
            .image(&self.sized, target, parity)
            .map_or(vk::Format::UNDEFINED, |i| i.desc.format)
    }

    /// Whether `target` exists in this run (the buffers of effects that are off do not).
    pub fn has_target(&self, target: Target) -> bool {
        self.target_format(target) != vk::Format::UNDEFINED
    }

    fn bind_targets(&self) {
        let t = &self.sized.targets;
        let ctx = &self.ctx;
        if let Some(e) = &self.sized.ao {
            self.reproject.bind_targets(ctx, t, e);
        }
        if let Some(e) = &self.sized.shadow {
            self.reproject.bind_targets(ctx, t, e);
        }
        if let Some(s) = &self.shadow_full {
            s.bind_targets(ctx, t, None);
        }
        if let Some(s) = &self.shadow_accumulate {
            s.bind_targets(ctx, t, self.sized.shadow.as_ref());
        }
        if let Some(direct) = &self.direct {
            let history = self
                .sized
                .shadow
                .as_ref()
                .map(|e| [&e.history[0], &e.history[1]]);
            direct.bind_targets(ctx, t, history);
        }
        if let (Some(ao), Some(e)) = (&self.ao, &self.sized.ao) {
            ao.ssao.bind_targets(ctx, t, &ao.random, e);
            if let Some(b) = &ao.blur {
                b.bind_targets(ctx, t);
            }
        }
        if let (Some(pass), Some((e, own))) = (&self.indirect, &self.sized.indirect) {
            self.reproject.bind_targets(ctx, t, e);
            pass.bind_targets(ctx, t, e, own);
        }
        let sources = self.sources();
        let ao_images = match (sources.ao(&self.sized, 0), sources.ao(&self.sized, 1)) {
            (Some(a), Some(b)) => Some([a, b]),
            _ => None,
        };
        let indirect_images = self
            .sized
            .indirect
            .as_ref()
            .map(|(e, _)| [&e.history[0], &e.history[1]]);
        self.composite
            .bind_targets(ctx, t, ao_images, indirect_images);
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
        // A device loss shows when waiting for the slot's previous frame: name its last pass.
        let cmd = self
            .slots
            .begin(slot)
            .map_err(|e| e.lost_after(self.last_pass[slot].map(PassId::name)))?;
        self.last_pass[slot] = None;
        let mut previous = self.timer.begin_frame(slot, self.frame_index);
        let mut counters = Vec::new();
        for e in self.effects_mut() {
            counters.extend(e.readback.collect(slot));
        }
        if let Some(p) = &mut previous {
            p.counters = counters;
        }
        let c = self.config;
        let aspect = c.width as f32 / c.height as f32;
        let view_proj = camera.view_proj(aspect);
        let uniforms = frame_block(
            &c,
            &FrameInputs {
                camera,
                prev_view_proj: self.history.unwrap_or(view_proj),
                light: &self.scene.light,
                ambient: self.scene.ambient,
                frame: self.frame_index,
                scene_radius: self.scene.mesh.bounds.radius(),
            },
        );
        // Host write before submission: the submit makes it visible, no barrier needed.
        self.frames[slot].uniforms.write(&uniforms.to_bytes())?;
        let frame_set = self.frames[slot].set;
        let rec = Recorder::new(&self.ctx, cmd);
        let reuse = c.temporal.reuse;
        let history_valid = reuse && self.history.is_some();
        let sources = self.sources();
        let shadow_reuse = sources.shadow_reuse;
        // Per-effect push constants: refresh tile (drawn only with a valid history) and flags.
        let effect_push = |e: &mut Option<TemporalEffect>| {
            e.as_mut().map(|e| {
                let tile = (history_valid && c.temporal.refresh).then(|| e.schedule.next_tile());
                e.push_constants(tile, history_valid, 0).to_bytes()
            })
        };
        let ao_push = effect_push(&mut self.sized.ao);
        // Indirect light always goes through the reprojection: without reuse every pixel is
        // new and every block listed, with the fixed pattern 0.
        let indirect_push = self.sized.indirect.as_mut().map(|(e, _)| {
            let tile = (history_valid && c.temporal.refresh).then(|| e.schedule.next_tile());
            let pattern = if reuse {
                (self.frame_index % c.temporal.rotation_limit as u64) as u32
            } else {
                0
            };
            e.push_constants(tile, history_valid, pattern).to_bytes()
        });
        let shadow_push = if shadow_reuse {
            effect_push(&mut self.sized.shadow)
        } else {
            None
        };
        let ao_image = sources.ao(&self.sized, parity);
        let shadow_image = sources.shadow(&self.sized, parity);
        let t = &self.sized.targets;
        let tracker = &mut self.tracker;
        let timer = &mut self.timer;
        let last_pass = &mut self.last_pass[slot];
        // Every pass inside its command label and its timestamps; the last one recorded is
        // remembered for device-loss reports.
        let mut timed = |pass: PassId, tracker: &mut Tracker, f: &mut dyn FnMut(&mut Tracker)| {
            rec.begin_label(pass.name());
            let began = timer.begin_pass(cmd, slot, pass.name());
            f(tracker);
            if began {
                timer.end_pass(cmd, slot);
            }
            rec.end_label();
            *last_pass = Some(pass);
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
        // Reprojection of every temporal effect that reuses its history this frame.
        let reprojected: Vec<(&TemporalEffect, &[u8; EffectPush::SIZE])> = [
            (self.sized.ao.as_ref(), ao_push.as_ref().filter(|_| reuse)),
            (self.sized.shadow.as_ref(), shadow_push.as_ref()),
            (
                self.sized.indirect.as_ref().map(|(e, _)| e),
                indirect_push.as_ref(),
            ),
        ]
        .into_iter()
        .filter_map(|(e, p)| Some((e?, p?)))
        .collect();
        let indirect_effect = self.sized.indirect.as_ref().map(|(e, _)| e);
        for e in [
            self.sized.ao.as_ref(),
            self.sized.shadow.as_ref(),
            indirect_effect,
        ]
        .into_iter()
        .flatten()
        {
            e.reset_counters(&rec, tracker);
        }
        if !reprojected.is_empty() {
            timed(PassId::Reproject, tracker, &mut |tr| {
                for (e, push) in &reprojected {
                    self.reproject
                        .record(&rec, tr, frame_set, parity, t, e, &push[..]);
                }
            });
        }
        if let Some(direct) = &self.direct {
            let shadow_pass = if shadow_reuse {
                self.shadow_accumulate.as_ref()
            } else {
                self.shadow_full.as_ref()
            };
            if let Some(pass) = shadow_pass {
                let push = shadow_push.unwrap_or([0; EffectPush::SIZE]);
                timed(PassId::Shadow, tracker, &mut |tr| {
                    pass.record(
                        &rec,
                        tr,
                        frame_set,
                        parity,
                        t,
                        self.sized.shadow.as_ref(),
                        &push,
                    )
                });
            }
            timed(PassId::Direct, tracker, &mut |tr| {
                direct.record(&rec, tr, frame_set, parity, t, shadow_image)
            });
        }
        if let (Some(ao), Some(effect)) = (&self.ao, &self.sized.ao) {
            let push = ao_push.unwrap_or([0; EffectPush::SIZE]);
            timed(PassId::Ssao, tracker, &mut |tr| {
                ao.ssao
                    .record(&rec, tr, frame_set, parity, t, &ao.random, effect, &push)
            });
            if let Some(blur) = &ao.blur {
                timed(PassId::Blur, tracker, &mut |tr| {
                    blur.record(&rec, tr, frame_set, parity, t)
                });
            }
        }
        let indirect_image = self
            .sized
            .indirect
            .as_ref()
            .map(|(e, _)| &e.history[parity]);
        if let (Some(pass), Some((e, own)), Some(push)) =
            (&self.indirect, &self.sized.indirect, &indirect_push)
        {
            pass.record(
                &rec,
                tracker,
                frame_set,
                parity,
                t,
                e,
                own,
                push,
                &mut |pass, tr, f| timed(pass, tr, f),
            );
        }
        timed(PassId::Composite, tracker, &mut |tr| {
            self.composite
                .record(&rec, tr, frame_set, parity, t, ao_image, indirect_image)
        });
        if let Some(e) = &mut self.sized.ao {
            e.copy_counters(&rec, &mut self.tracker, slot);
        }
        if let Some((e, _)) = &mut self.sized.indirect {
            e.copy_counters(&rec, &mut self.tracker, slot);
        }
        if let (Some(e), true) = (&mut self.sized.shadow, shadow_reuse) {
            e.copy_counters(&rec, &mut self.tracker, slot);
        }
        if !light_changed {
            self.timer.skip(slot, PassId::LightView.name());
        }

        let sync = match &mut hook {
            Some(h) => {
                // The hook gets the target it asked for (the viewer's buffer display), this
                // frame's image of it; the output when the target does not exist in this run.
                let source = sources.image(&self.sized, h.source, parity);
                let output = &self.sized.targets.output;
                rec.begin_label("frame_hook");
                (h.record)(&rec, &mut self.tracker, source.unwrap_or(output));
                rec.end_label();
                h.sync.clone()
            }
            None => SubmitSync::default(),
        };
        self.slots
            .submit_with(slot, &sync)
            .map_err(|e| e.lost_after(self.last_pass[slot].map(PassId::name)))?;
        self.history = Some(view_proj);
        self.frame_index += 1;
        Ok(previous)
    }

    /// Wait for the GPU and return the timings not yet returned, oldest first.
    pub fn finish(&mut self) -> Result<Vec<FrameTiming>> {
        let newest = (self.frame_index.wrapping_sub(1) % FRAMES_IN_FLIGHT as u64) as usize;
        self.slots
            .wait_all()
            .map_err(|e| e.lost_after(self.last_pass[newest].map(PassId::name)))?;
        let mut out = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            let mut counters = Vec::new();
            for e in self.effects_mut() {
                counters.extend(e.readback.collect(slot));
            }
            if let Some(mut t) = self.timer.collect(slot) {
                t.counters = counters;
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
        self.sized = Self::create_sized(&self.ctx, &config, &self.effect_sets)?;
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
        let image = self
            .sources()
            .image(&self.sized, target, parity)
            .ok_or_else(|| {
                Error::Config(format!(
                    "the {} buffer does not exist in this run (its effect is off)",
                    target.name()
                ))
            })?;
        read_image(&self.ctx, &mut self.tracker, image)
    }
}

/// Which image of [`Sized`] holds each target in a configuration: the one place targets are
/// resolved, so the passes, reads, formats and the window's frame hook agree. A copy of the
/// choices, so resolving borrows only `Sized` (the tracker stays free for recording).
#[derive(Clone, Copy)]
struct TargetSources {
    /// AO passes exist, and whether they blur (no reuse).
    ao: bool,
    ao_blur: bool,
    reuse: bool,
    /// Shadows come from the accumulated history (see `Renderer::shadow_reuse`).
    shadow_reuse: bool,
}

impl TargetSources {
    /// The AO visibility the composite reads for `parity`; `None` with AO off.
    fn ao(self, sized: &Sized, parity: usize) -> Option<&Image> {
        if !self.ao {
            return None;
        }
        Some(if self.reuse {
            &sized.ao.as_ref()?.history[parity]
        } else if self.ao_blur {
            &sized.targets.ao_blurred
        } else {
            &sized.targets.ao_raw
        })
    }

    /// The shadow visibility the direct pass reads for `parity`.
    fn shadow(self, sized: &Sized, parity: usize) -> &Image {
        match (&sized.shadow, self.shadow_reuse) {
            (Some(e), true) => &e.history[parity],
            _ => &sized.targets.shadow,
        }
    }

    /// The image holding `target` for history parity `parity`; `None` when the target does not
    /// exist in this configuration (its effect is off).
    fn image(self, sized: &Sized, target: Target, parity: usize) -> Option<&Image> {
        match target {
            Target::Ao => self.ao(sized, parity),
            Target::Shadow => Some(self.shadow(sized, parity)),
            Target::Indirect => sized.indirect.as_ref().map(|(e, _)| &e.history[parity]),
            Target::DiscardMask => sized.indirect.as_ref().map(|(_, own)| &own.discard),
            Target::State => sized
                .ao
                .as_ref()
                .or(sized.shadow.as_ref())
                .map(|e| &e.state),
            other => sized.targets.get(other, parity),
        }
    }
}
