//! The frame as a list of steps over the registered effects (docs/ARCHITECTURE.md's "One
//! frame"), frames in flight and the shared targets; each frame records what its plan
//! (`frame_plan.rs`) runs:
//!
//! light view (only when the light changed) → G-buffer → reprojection of every temporal effect
//! → each effect's passes (shadow + direct, SSAO [+ blur], indirect light) → composite.

pub mod audit;
pub mod catalog;
pub mod dependencies;
pub mod explain;
pub mod frame;
pub mod frame_plan;
mod motion;
pub mod reprojection_lanes;
pub mod skip;

pub use crate::config::{RenderConfig, FRAMES_IN_FLIGHT, MAX_SIZE};
use crate::effects::resolve::shared_target;
use crate::effects::{self, Effect, EffectId, FrameInfo, Recording, Setup, TermKind};
use crate::error::{Error, Result};
use crate::passes::composite::{CompositeInputs, CompositePass};
use crate::passes::compute::FrameSet;
use crate::passes::decl::{Resolve, Slot};
use crate::passes::gbuffer::GBufferPass;
use crate::passes::light_view::LightViewPass;
use crate::passes::PassId;
use crate::post::{self, PostFrame, PostStage};
use crate::resources::scene_gpu::SceneGpu;
use crate::resources::targets::{Target, Targets};
use crate::scene::{Camera, Scene, SpotLight};
use crate::vk::recorder::Recorder;
use crate::vk::{
    read_buffer, read_image, Buffer, Context, DescriptorPool, FrameSlots, FrameTiming, GpuTimer,
    Image, ImageData, SetWriter, SkipReason, SubmitSync, Tracker,
};
use ash::vk;
pub use catalog::{all_layouts, all_passes};
use frame::{frame_block, FrameBlock, FrameInputs};
use frame_plan::{FramePlan, FrameState, FrameStep, Past};
use glam::Mat4;
use gpu_allocator::MemoryLocation;
use motion::Motion;
use reprojection_lanes::Reprojection;
use skip::{EffectState, Inputs, Plan, SkipTracker};
use std::sync::Arc;

/// Extra recording at the end of a frame plus the frame's submit semaphores.
pub struct FrameHook<'a> {
    /// Called with the frame's recording and the target named by `source` (the window
    /// frontend blits it into the swapchain image there, and times the viewer's overlay with
    /// `Recording::timed`), inside the command label `frame_hook`.
    pub record: &'a mut dyn FnMut(&mut Recording<'_>, &crate::vk::Image),
    pub sync: SubmitSync,
    /// Which target `record` receives: `Target::Output` (the final RGBA8 image), or another
    /// one for the viewer's buffer display.
    pub source: Target,
}

struct FrameResources {
    uniforms: Buffer,
    set: vk::DescriptorSet,
}

pub struct Renderer {
    ctx: Arc<Context>,
    /// Changed in place, it takes effect on the next frame and the histories stay: the
    /// effects run again (their inputs include it) and the shadows restart on a new PCF kernel
    /// (the viewer's soft-shadow switch); after a change of what an estimator computes, call
    /// `reset_history` (the viewer rebuilds the renderer for those).
    pub config: RenderConfig,
    pub scene: Scene,
    passes: FramePasses,
    effects: Vec<Box<dyn Effect>>,
    scene_gpu: SceneGpu,
    targets: Targets,
    frames: Vec<FrameResources>,
    slots: FrameSlots,
    timer: GpuTimer,
    tracker: Tracker,
    frame_index: u64,
    /// What planning remembers of the recorded frames: last frame's camera, whether it
    /// moved, the light the RSM holds.
    past: Past,
    /// The last frame read last frame's G-buffer (its history was valid): until then the
    /// G-buffer's other half holds nothing of this size and view (`audit` leaves it out).
    last_frame_reused: bool,
    /// The numerical audit's pipeline, built on the first `audit`.
    audit: Option<crate::vk::Pipeline>,
    /// The last pass recorded into each slot's command buffer (device-loss reports).
    last_pass: [Option<PassId>; FRAMES_IN_FLIGHT],
    reprojection: Reprojection,
    /// What frames leave out when nothing they read changed (`skip.rs`).
    skips: SkipTracker,
    /// The moving objects' transforms (`motion.rs`).
    motion: Motion,
    /// Objects each slot's last frame moved (its timing's `moved_objects`).
    moved: [usize; FRAMES_IN_FLIGHT],
    pool: DescriptorPool,
    /// Test hook: the pixel whose indirect estimates the next frame makes NaN (`plant_nan`).
    planted_nan: Option<[u32; 2]>,
    /// Work lists' dispatches in x (`limit_list_groups`; the device's limit by default).
    max_groups_x: u32,
}

impl Renderer {
    pub fn new(ctx: &Arc<Context>, scene: Scene, config: RenderConfig) -> Result<Self> {
        config.validate()?;
        let ranges = [
            ("camera", scene.camera.near, scene.camera.far),
            ("light", scene.light.near, scene.light.far),
        ];
        for (what, near, far) in ranges {
            if let Some(problem) = crate::scene::depth_range_problem(near, far) {
                return Err(Error::Config(format!(
                    "scene {}: {what}: {problem}",
                    scene.name
                )));
            }
        }
        if config.gbuffer.visibility() && !ctx.info.geometry_shader {
            return Err(Error::Config(format!(
                "--gbuffer visibility reads gl_PrimitiveID, which needs the geometryShader \
                 feature; {} does not have it (use --gbuffer raster)",
                ctx.info.name
            )));
        }
        let rendered = config.rendered();
        let textured =
            scene.mesh.has_textures() || scene.objects.iter().any(|o| o.mesh.has_textures());
        let pool = DescriptorPool::new(ctx)?;
        let light_view = LightViewPass::new(ctx, textured)?;
        let mut tracker = Tracker::new();
        let scene_gpu = SceneGpu::new(
            ctx,
            &mut tracker,
            &pool,
            &scene.mesh,
            &scene.objects,
            light_view.material_layout(),
            config.gbuffer.visibility(),
        )?;
        let effects = effects::create(&mut Setup {
            ctx,
            pool: &pool,
            config: &rendered,
            tracker: &mut tracker,
        })?;
        let reprojection = Reprojection::new(ctx, &pool, &effects)?;
        let reads = dependencies::of(&effects).effects;
        let aa = config.aa.mode;
        let targets = Targets::new(
            ctx,
            rendered.width,
            rendered.height,
            config.rsm_size,
            aa,
            config.gbuffer,
        )?;
        let kinds: Vec<u32> = effects
            .iter()
            .map(|e| e.term(&targets, 0).0 as u32)
            .collect();
        let composite = CompositePass::new(ctx, &pool, &kinds, aa.resolves())?;
        let post = post::create(ctx, &pool, &config)?;
        // Set 0 layout: every pipeline declares the same frame binding, so any of them works.
        let frame_layout = composite.frame_layout();
        let mut frames = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            let uniforms = Buffer::new(
                ctx,
                &format!("frame.uniforms.{slot}"),
                FrameBlock::SIZE as u64,
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::CpuToGpu,
            )?;
            let set = pool.allocate(frame_layout, &format!("frame set 0 slot {slot}"))?;
            SetWriter::new()
                .storage_buffer(0, &uniforms)
                .write(ctx, set);
            frames.push(FrameResources { uniforms, set });
        }
        let scene_objects = scene.objects.clone();
        let renderer = Self {
            ctx: ctx.clone(),
            targets,
            config,
            scene,
            passes: FramePasses {
                light_view,
                gbuffer: GBufferPass::new(ctx, &pool, textured, config.gbuffer.visibility())?,
                composite,
                post,
            },
            effects,
            scene_gpu,
            frames,
            slots: FrameSlots::new(ctx, FRAMES_IN_FLIGHT)?,
            timer: GpuTimer::new(
                ctx,
                FRAMES_IN_FLIGHT,
                // + the frontend's overlay (`PassId::OVERLAY`, in the frame hook).
                catalog::all_passes().len() as u32 + 3,
            )?,
            tracker,
            frame_index: 0,
            past: Past::default(),
            planted_nan: None,
            max_groups_x: ctx.info.max_compute_work_group_count[0],
            last_frame_reused: false,
            audit: None,
            last_pass: [None; FRAMES_IN_FLIGHT],
            reprojection,
            skips: SkipTracker::new(&reads),
            motion: Motion::new(&scene_objects),
            moved: [0; FRAMES_IN_FLIGHT],
            pool,
        };
        renderer.bind()?;
        Ok(renderer)
    }

    /// Point every descriptor set at the current targets (creation and resize).
    fn bind(&self) -> Result<()> {
        for e in &self.effects {
            e.bind(&self.ctx, &self.targets)?;
        }
        self.reprojection
            .bind(&self.ctx, &self.targets, &self.effects)?;
        let shared = SharedTargets(&self.targets);
        self.passes.gbuffer.bind(
            &self.ctx,
            &GBufferResources {
                targets: &self.targets,
                scene: &self.scene_gpu,
            },
        )?;
        for stage in &self.passes.post {
            stage.bind(&self.ctx, &shared)?;
        }
        self.passes
            .composite
            .bind(&self.ctx, &composite_inputs(&shared, &self.effects))
    }

    /// The image behind `target` for parity `parity` (see [`resolve_target`]).
    fn image(&self, target: Target, parity: usize) -> Option<&Image> {
        resolve_target(&self.targets, &self.effects, &self.config, target, parity)
    }

    /// Parity of the last rendered frame.
    fn last_parity(&self) -> usize {
        (self.frame_index.wrapping_sub(1) % 2) as usize
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
        self.image(target, self.last_parity())
            .map_or(vk::Format::UNDEFINED, |i| i.desc.format)
    }

    /// Whether `target` exists in this run (the buffers of effects that are off do not).
    pub fn has_target(&self, target: Target) -> bool {
        self.target_format(target) != vk::Format::UNDEFINED
    }

    pub fn context(&self) -> &Arc<Context> {
        &self.ctx
    }

    pub fn frame_index(&self) -> u64 {
        self.frame_index
    }

    /// Change the light; the light view is re-rendered on the next frame.
    /// The descriptor sets this renderer allocated (`DescriptorPool::allocated`, `pools`).
    pub fn descriptor_pool(&self) -> &DescriptorPool {
        &self.pool
    }

    pub fn set_light(&mut self, light: SpotLight) {
        self.scene.light = light;
    }

    /// Pose what the scene animates at `time` seconds into its paths: the light along the
    /// scene's light path (the light view re-renders on a frame whose light moved). Nothing
    /// for a scene without one. Runs call it before each frame with the frame's path time.
    pub fn set_time(&mut self, time: f32) {
        if let Some(path) = &self.scene.light_path {
            self.scene.light = path.light_at(&self.scene.light, time);
        }
        self.motion.set_time(&self.scene.objects, time);
    }

    /// Forget every history (camera cut): the next frame recomputes all pixels.
    pub fn reset_history(&mut self) {
        self.past.history = None;
        self.skips.forget();
        self.motion.forget();
    }

    /// What makes each pass run again (`skip::explain`).
    pub fn explain_skips(&self) -> String {
        dependencies::explain(&self.config, &self.effects)
    }

    /// Render a frame from `first` at `times.0`, then one from `second` at `times.1`, and
    /// describe the second (`explain::describe`): its passes in order with what each declares
    /// it reads and writes, and the passes it left out.
    pub fn explain_frame(
        &mut self,
        (first, second): (&Camera, &Camera),
        times: (f32, f32),
    ) -> Result<String> {
        self.set_time(times.0);
        self.render_frame(first)?;
        self.tracker.start_declaring();
        self.set_time(times.1);
        let frame = self.frame_index;
        let rendered = self.render_frame(second);
        let declared = self.tracker.take_declared();
        rendered?;
        let timings = self.finish()?;
        let skipped = timings
            .into_iter()
            .find(|t| t.frame == frame)
            .map(|t| t.skipped)
            .unwrap_or_default();
        Ok(explain::describe(&declared, &skipped))
    }

    /// The dependency table itself: each pass and the changes that make it run again.
    pub fn dependency_table(&self) -> Vec<dependencies::Trigger> {
        dependencies::triggers(&self.config, &self.effects)
    }

    fn frame_inputs(&self, camera: &Camera) -> Inputs {
        let aspect = self.config.width as f32 / self.config.height as f32;
        Inputs {
            view_proj: camera.view_proj(aspect),
            eye: camera.position,
            light: self.scene.light,
            ambient: self.scene.ambient,
            config: self.config,
            poses: self.motion.revision(self.past.history.is_some()),
        }
    }

    /// This frame's plan (`frame_plan.rs`), from its poses and each effect's state.
    fn plan(&mut self, camera: &Camera) -> FramePlan {
        let inputs = self.frame_inputs(camera);
        // Also on a frame the plan skips whole: it does so only when nothing moved, so the
        // poses are those of the last frame drawn.
        let poses = &mut self.scene_gpu.poses;
        self.motion.write_poses(self.past.history.is_some(), poses);
        // Fixed-size: nothing is allocated per frame.
        let mut states = [EffectState::default(); effects::REGISTRY.len()];
        for (s, e) in states.iter_mut().zip(&self.effects) {
            *s = EffectState::of(&self.config, e.as_ref());
        }
        let state = FrameState {
            frame_index: self.frame_index,
            inputs,
            past: self.past,
            effects: &states[..self.effects.len()],
            objects: &self.scene.objects,
            poses: &self.scene_gpu.poses,
        };
        frame_plan::plan(&mut self.skips, &state)
    }

    /// Record and submit one frame seen from `camera`. Returns the GPU timing of the frame that
    /// last used this slot (`FRAMES_IN_FLIGHT` frames ago), if any.
    pub fn render_frame(&mut self, camera: &Camera) -> Result<Option<FrameTiming>> {
        self.render_frame_with(camera, None)
    }

    /// As `render_frame`, with a hook that records after the composite (the window frontend
    /// copies the output into the swapchain image there) and the submission's semaphores.
    /// The steps of docs/ARCHITECTURE.md's "One frame", as the frame's plan has them.
    pub fn render_frame_with(
        &mut self,
        camera: &Camera,
        mut hook: Option<FrameHook<'_>>,
    ) -> Result<Option<FrameTiming>> {
        // Ctrl-C: stop between frames, never inside a recording.
        crate::interrupt::check()?;
        // Planned before this slot's last counters are read back: they count from the next
        // frame's plan on.
        let plan = self.plan(camera);
        let slot = self.next_slot();
        let cmd = self.begin_slot(slot)?;
        let previous = self.collect(slot);
        self.moved[slot] = plan.moved_objects;
        let (last_pass, hook_sync) = if plan.skip.frame {
            self.record_skipped(cmd, slot, &plan, &mut hook)
        } else {
            // 1. Scene update: the constants (`record` prepares each effect's refresh tile and
            // pattern).
            self.write_uniforms(slot, camera, plan.inputs.view_proj, plan.moved)?;
            self.record(cmd, slot, &plan, &mut hook)
        };
        self.last_pass[slot] = last_pass;
        self.slots
            .submit_with(slot, &hook_sync)
            .map_err(|e| e.lost_after(last_pass.map(PassId::name)))?;
        if !plan.skip.frame {
            self.motion.drawn(plan.moved_objects);
            self.last_frame_reused = self.past.history.is_some();
            self.past.recorded(&plan);
        }
        self.frame_index += 1;
        Ok(previous)
    }

    /// A frame with nothing to record (`skip.rs`): every pass is reported skipped with its
    /// reason, the frontend's hook still runs (a window presents the unchanged output), and
    /// the submission keeps the slot's fence in step.
    fn record_skipped(
        &mut self,
        cmd: vk::CommandBuffer,
        slot: usize,
        plan: &FramePlan,
        hook: &mut Option<FrameHook<'_>>,
    ) -> (Option<PassId>, SubmitSync) {
        self.timer
            .skip(slot, PassId::LIGHT_VIEW.name(), SkipReason::Unchanged);
        self.skips.report(
            &mut self.timer,
            slot,
            plan.skip,
            &self.config,
            &self.effects,
        );
        self.skips.recorded(slot, plan.skip);
        let mut r = Recording {
            rec: Recorder::new(&self.ctx, cmd),
            tracker: &mut self.tracker,
            timer: &mut self.timer,
            slot,
            last_pass: None,
        };
        let parity = (self.frame_index % 2) as usize;
        let (t, effects, config) = (&self.targets, &self.effects, &self.config);
        let source = |target| resolve_target(t, effects, config, target, parity);
        (None, record_hook(&mut r, hook, source, &t.output))
    }

    /// Record the steps `plan` runs, the frontend's hook and the counters' copies into `cmd`,
    /// and report the steps it leaves out. Returns the last pass and the hook's semaphores.
    fn record(
        &mut self,
        cmd: vk::CommandBuffer,
        slot: usize,
        plan: &FramePlan,
        hook: &mut Option<FrameHook<'_>>,
    ) -> (Option<PassId>, SubmitSync) {
        let rendered = self.config.rendered();
        let frame = FrameSet {
            set: self.frames[slot].set,
            parity: (self.frame_index % 2) as usize,
        };
        let info = plan.info(&rendered, &self.targets, frame);
        for (i, e) in self.effects.iter_mut().enumerate() {
            if plan.runs(FrameStep::Effect(i)) {
                e.prepare(&info);
            }
        }
        let mut r = Recording {
            rec: Recorder::new(&self.ctx, cmd),
            tracker: &mut self.tracker,
            timer: &mut self.timer,
            slot,
            last_pass: None,
        };
        // 2-3. Light view and G-buffer.
        let scene = &self.scene_gpu;
        self.passes.record_views(&mut r, &info, scene, plan);
        // 4. One reprojection, a lane per temporal effect that reuses its history this frame.
        self.reprojection
            .record(&self.effects, &info, &mut r, plan.skip.effects);
        // 5. Effects, in registry order, but those whose inputs did not change and which have
        // converged.
        for (i, e) in self.effects.iter().enumerate() {
            if plan.runs(FrameStep::Effect(i)) {
                e.record(&info, &mut r);
            }
        }
        // 6-7. Composite + tonemap, and the antialiasing into the output.
        let (t, config) = (&self.targets, &self.config);
        let shared = SharedTargets(t);
        let inputs = composite_inputs(&shared, &self.effects);
        self.passes
            .record_output(&mut r, &info, scene, &inputs, plan);
        let source = |target| resolve_target(t, &self.effects, config, target, frame.parity);
        let hook_sync = record_hook(&mut r, hook, source, &t.output);
        let last_pass = r.last_pass;
        self.skips
            .report(r.timer, slot, plan.skip, &self.config, &self.effects);
        self.skips.recorded(slot, plan.skip);
        self.copy_counters(cmd, slot, plan.skip);
        (last_pass, hook_sync)
    }

    /// Wait for `slot`'s previous frame and begin recording its command buffer. A device loss
    /// shows here: it is named after that frame's last pass.
    fn begin_slot(&mut self, slot: usize) -> Result<vk::CommandBuffer> {
        let lost_in = self.last_pass[slot].map(PassId::name);
        self.slots.begin(slot).map_err(|e| e.lost_after(lost_in))
    }

    /// Timings and counters of the frame that last used `slot` (its fence has signalled).
    fn collect(&mut self, slot: usize) -> Option<FrameTiming> {
        let counters = self.collect_counters(slot);
        let mut previous = self.timer.begin_frame(slot, self.frame_index)?;
        previous.counters = counters;
        Some(previous)
    }

    /// The counters `slot`'s last frame copied (those of the effects it ran); an effect that
    /// accumulates reports its work to the skip tracker.
    fn collect_counters(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        let mut counters = Vec::new();
        let frame = self.timer.frame_of(slot);
        let config = self.config;
        for (i, e) in self.effects.iter_mut().enumerate() {
            if !self.skips.counted(slot, i) {
                continue;
            }
            let c = e.collect_counters(slot);
            if let (Some(frame), true) = (frame, skip::accumulates(&config, e.as_ref())) {
                self.skips.read_back(i, frame, &c);
            }
            counters.extend(c);
        }
        if !self.scene.objects.is_empty() {
            counters.push(("moved_objects", self.moved[slot] as u64));
        }
        counters
    }

    /// The frame's constants into this slot's uniform buffer (host write before submission: the
    /// submit makes it visible, no barrier needed). `view_proj` is the camera's, as the skip
    /// plan computed it.
    fn write_uniforms(
        &mut self,
        slot: usize,
        camera: &Camera,
        view_proj: Mat4,
        moved: Option<motion::Moved>,
    ) -> Result<()> {
        let block = frame_block(
            &self.config.rendered(),
            &FrameInputs {
                camera,
                prev_view_proj: self.past.history.map_or(view_proj, |(m, _)| m),
                prev_camera_pos: self.past.history.map_or(camera.position, |(_, eye)| eye),
                light: &self.scene.light,
                ambient: self.scene.ambient,
                frame: self.frame_index,
                // Everywhere a moving object goes counts: the radius stays put.
                scene_radius: self.scene.bounds().radius(),
                moved,
                planted_nan: self.planted_nan.take(),
                max_groups_x: self.max_groups_x,
            },
        );
        self.frames[slot].uniforms.write(&block.to_bytes())?;
        self.scene_gpu.write_draw_table(slot)
    }

    /// Copy this frame's counters (of the effects it ran) for reading when `slot` comes round
    /// again.
    fn copy_counters(&mut self, cmd: vk::CommandBuffer, slot: usize, plan: Plan) {
        let rec = Recorder::new(&self.ctx, cmd);
        let config = self.config;
        for (i, e) in self.effects.iter_mut().enumerate() {
            if !plan.effect(i) {
                e.copy_counters(&rec, &mut self.tracker, slot, &config);
            }
        }
    }

    /// Wait for the GPU and return the timings not yet returned, oldest first.
    pub fn finish(&mut self) -> Result<Vec<FrameTiming>> {
        let newest = (self.frame_index.wrapping_sub(1) % FRAMES_IN_FLIGHT as u64) as usize;
        self.slots
            .wait_all()
            .map_err(|e| e.lost_after(self.last_pass[newest].map(PassId::name)))?;
        let mut out = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            let counters = self.collect_counters(slot);
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
        let rendered = config.rendered();
        self.targets = Targets::new(
            &self.ctx,
            rendered.width,
            rendered.height,
            config.rsm_size,
            config.aa.mode,
            config.gbuffer,
        )?;
        for e in &mut self.effects {
            e.resize(&self.ctx, &rendered)?;
        }
        self.config = config;
        self.bind()?;
        // The RSM targets were recreated with the rest: render the light view again.
        self.past.rsm_light = None;
        self.past.history = None;
        self.skips.forget();
        Ok(pending)
    }

    /// Copy the per-pixel reprojection state of effect `id` in the last rendered frame to the
    /// host (waits for the GPU): `Target::State` shows one effect's, this any effect's.
    pub fn read_state(&mut self, id: EffectId) -> Result<ImageData> {
        let effect = self.effects.iter().find(|e| e.id() == id);
        let state = effect.and_then(|e| e.temporal()).map(|t| &t.state);
        let state = state.ok_or_else(|| {
            Error::Config(format!(
                "{id:?} keeps no history in this run (off, or no reuse)"
            ))
        })?;
        read_image(&self.ctx, &mut self.tracker, state)
    }

    /// Copy buffer `name` of effect `id` (see [`Effect::buffer`]) after the last rendered
    /// frame to the host (waits for the GPU).
    pub fn read_buffer(&mut self, id: EffectId, name: &str) -> Result<Vec<u8>> {
        let effect = self.effects.iter().find(|e| e.id() == id);
        let buffer = effect
            .and_then(|e| e.buffer(name))
            .ok_or_else(|| Error::Config(format!("{id:?} has no buffer {name:?} in this run")))?;
        read_buffer(&self.ctx, &mut self.tracker, buffer)
    }

    /// The running effects and the kind of the term each hands the composite.
    pub fn term_kinds(&self) -> Vec<(EffectId, TermKind)> {
        self.effects
            .iter()
            .map(|e| (e.id(), e.term(&self.targets, 0).0))
            .collect()
    }

    /// Copy effect `id`'s composite term (the image `Effect::term` hands the composite) of the
    /// last rendered frame to the host, with its kind (waits for the GPU): any effect's
    /// contribution, without a debug target of its own.
    pub fn read_term(&mut self, id: EffectId) -> Result<(TermKind, ImageData)> {
        let parity = self.last_parity();
        let effect = self.effects.iter().find(|e| e.id() == id);
        let (kind, image) = effect
            .map(|e| e.term(&self.targets, parity))
            .ok_or_else(|| Error::Config(format!("{id:?} does not run in this configuration")))?;
        Ok((kind, read_image(&self.ctx, &mut self.tracker, image)?))
    }

    /// Test hook: the next recorded frame computes NaN for every indirect estimate of `pixel`
    /// (the noisy gather's sample and the cached gather's pattern) before the guards that keep
    /// NaN out of histories, bases and image-wide sums. No effect outside the image.
    pub fn plant_nan(&mut self, pixel: [u32; 2]) {
        self.planted_nan = Some(pixel);
    }

    /// Test hook: work lists' indirect dispatches take at most `groups` workgroups in x (at
    /// least 1, at most the device's maxComputeWorkGroupCount[0]) and continue in y, as lists
    /// past the device's limit do (16.8 Mpx of 16x16 blocks on a device at Vulkan's least
    /// 65,535), so a small render takes the same path.
    pub fn limit_list_groups(&mut self, groups: u32) {
        self.max_groups_x = groups.clamp(1, self.ctx.info.max_compute_work_group_count[0]);
    }

    /// Copy a target of the last rendered frame to the host (waits for the GPU).
    pub fn read(&mut self, target: Target) -> Result<ImageData> {
        let parity = self.last_parity();
        let image = resolve_target(&self.targets, &self.effects, &self.config, target, parity);
        let image = image.ok_or_else(|| {
            Error::Config(format!(
                "the {} buffer does not exist in this run (its effect is off)",
                target.name()
            ))
        })?;
        read_image(&self.ctx, &mut self.tracker, image)
    }
}

/// The image behind `target` for parity `parity` under `config`: the one place targets are
/// resolved, so reads, formats and the window's frame hook agree. `None` when the target's
/// effect is off in this run.
fn resolve_target<'a>(
    targets: &'a Targets,
    effects: &'a [Box<dyn Effect>],
    config: &RenderConfig,
    target: Target,
    parity: usize,
) -> Option<&'a Image> {
    let of = |id| {
        effects
            .iter()
            .find(|e| e.id() == id)
            .and_then(|e| e.target(target, parity, config))
    };
    match target {
        // The recompute mask: the state of the lowest-ranked effect that has one
        // (`Registration::recompute_mask`).
        Target::State => crate::effects::REGISTRY
            .iter()
            .filter_map(|r| Some((r.recompute_mask?, of(r.id)?)))
            .min_by_key(|(rank, _)| *rank)
            .map(|(_, image)| image),
        _ => targets.get(target, parity).or_else(|| {
            effects
                .iter()
                .find_map(|e| e.target(target, parity, config))
        }),
    }
}

/// The composite's inputs: every effect's contribution, in registry order.
fn composite_inputs<'a>(
    shared: &'a SharedTargets<'a>,
    effects: &'a [Box<dyn Effect>],
) -> CompositeInputs<'a> {
    CompositeInputs {
        shared,
        images: std::array::from_fn(|i| {
            effects
                .get(i)
                .map(|e| [e.term(shared.0, 0).1, e.term(shared.0, 1).1])
        }),
    }
}

/// The frontend's hook (inside the `frame_hook` label) with this frame's image of the target
/// it asked for (`output` when that target does not exist in this run).
fn record_hook<'a>(
    r: &mut Recording<'_>,
    hook: &mut Option<FrameHook<'_>>,
    source: impl Fn(Target) -> Option<&'a Image>,
    output: &'a Image,
) -> SubmitSync {
    let Some(h) = hook else {
        return SubmitSync::default();
    };
    r.rec.begin_label("frame_hook");
    (h.record)(r, source(h.source).unwrap_or(output));
    r.rec.end_label();
    h.sync.clone()
}

/// The frame's passes besides the effects': before them the light view and the G-buffer,
/// after them the composite and the antialiasing.
struct FramePasses {
    light_view: LightViewPass,
    gbuffer: GBufferPass,
    composite: CompositePass,
    /// The post stages the configuration turns on (antialiasing), in registry order.
    post: Vec<Box<dyn PostStage>>,
}

impl FramePasses {
    /// The light view, only when the light changed or moved geometry in its frustum; the
    /// G-buffer, unless the camera and objects stood still for two frames (both halves hold it).
    fn record_views(
        &self,
        r: &mut Recording<'_>,
        info: &FrameInfo<'_>,
        scene: &SceneGpu,
        plan: &FramePlan,
    ) {
        let (frame, shared) = (info.frame, SharedTargets(info.targets));
        match plan.skipped(FrameStep::LightView) {
            None => r.timed(PassId::LIGHT_VIEW, |rec, tr| {
                self.light_view.record(rec, tr, frame, scene, &shared)
            }),
            Some(reason) => r.timer.skip(r.slot, PassId::LIGHT_VIEW.name(), reason),
        }
        if plan.runs(FrameStep::GBuffer) {
            r.timed(PassId::GBUFFER, |rec, tr| {
                self.gbuffer.record(rec, tr, frame, scene, &shared)
            });
            if self.gbuffer.resolves() {
                let res = GBufferResources {
                    targets: info.targets,
                    scene,
                };
                let (base, size) = (
                    scene.draw_table_base(r.slot),
                    (info.targets.width, info.targets.height),
                );
                r.timed(PassId::GBUFFER_RESOLVE, |rec, tr| {
                    self.gbuffer
                        .record_resolve(rec, tr, frame, &res, base, size)
                });
            }
        }
    }

    /// The composite and tonemap, then the antialiasing of its display-linear image into the
    /// output.
    fn record_output(
        &self,
        r: &mut Recording<'_>,
        info: &FrameInfo<'_>,
        scene: &SceneGpu,
        inputs: &CompositeInputs<'_>,
        plan: &FramePlan,
    ) {
        let (frame, t) = (info.frame, info.targets);
        let shared = SharedTargets(t);
        r.timed(PassId::COMPOSITE, |rec, tr| {
            self.composite
                .record(rec, tr, frame, inputs, t.width, t.height)
        });
        let f = PostFrame {
            frame,
            scene,
            targets: &shared,
            render: (t.width, t.height),
            output: (t.output.desc.width, t.output.desc.height),
            geometry: plan.runs(FrameStep::GBuffer),
        };
        for stage in &self.post {
            stage.record(r, &f);
        }
    }
}

/// The visibility buffer's resolve reads the shared targets and the scene's buffers.
struct GBufferResources<'a> {
    targets: &'a Targets,
    scene: &'a SceneGpu,
}

impl Resolve for GBufferResources<'_> {
    fn image(&self, slot: Slot, parity: usize) -> Option<&Image> {
        shared_target(self.targets, slot, parity)
    }

    fn buffer(&self, slot: Slot) -> Option<&Buffer> {
        let tables = self.scene.visibility.as_ref();
        match slot {
            Slot::SceneVertices => Some(&self.scene.vertices),
            Slot::SceneIndices => Some(&self.scene.indices),
            Slot::SceneTriangleDraws => tables.map(|t| &t.triangle_draws),
            Slot::SceneDraws => tables.map(|t| &t.draws),
            _ => None,
        }
    }
}

/// The shared targets as a resolver (the composite's G-buffer and output).
struct SharedTargets<'a>(&'a Targets);

impl Resolve for SharedTargets<'_> {
    fn image(&self, slot: Slot, parity: usize) -> Option<&Image> {
        shared_target(self.0, slot, parity)
    }

    fn buffer(&self, _slot: Slot) -> Option<&Buffer> {
        None
    }
}
