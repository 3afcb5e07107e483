//! A frame is a plan: from this frame's inputs and what the renderer remembers of the frames
//! before, which steps of docs/ARCHITECTURE.md's "One frame" run, which are left out and why
//! (`skip.rs`), how the camera moved (moving, come to rest: re-accumulation starts), whether the light
//! moved and the light view is rendered again, and what the moving objects invalidate.
//! Planning needs no device; `Renderer::render_frame_with` records what the plan says.

use super::motion::{self, light_sees_motion, Moved};
use super::skip::{EffectState, Inputs, Plan, SkipTracker};
use crate::config::RenderConfig;
use crate::effects::FrameInfo;
use crate::passes::compute::FrameSet;
use crate::resources::scene_gpu::Pose;
use crate::resources::targets::Targets;
use crate::scene::{DynamicObject, SpotLight};
use crate::vk::SkipReason;
use glam::{Mat4, Vec3};

/// What planning remembers of the recorded frames (the skip tracker keeps its own keys).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Past {
    /// Last frame's camera view-projection (eq 1) and eye (the history's pixel footprints on
    /// each surface), when the histories hold last frame's data.
    pub history: Option<(Mat4, Vec3)>,
    /// Last frame reused the histories and its camera had moved: if this one's has not, the
    /// histories start re-accumulating (`TemporalConfig::reaccumulate`).
    pub camera_was_moving: bool,
    /// The light the RSM currently holds; `None` forces a re-render.
    pub rsm_light: Option<SpotLight>,
}

impl Past {
    /// `plan`'s frame was recorded and submitted.
    pub fn recorded(&mut self, plan: &FramePlan) {
        self.camera_was_moving = plan.camera_moved && plan.history_valid;
        if plan.light_changed {
            self.rsm_light = Some(plan.inputs.light);
        }
        self.history = Some((plan.inputs.view_proj, plan.inputs.eye));
    }
}

/// Everything one frame's plan reads.
pub struct FrameState<'a> {
    pub frame_index: u64,
    /// The skip key: camera, light, ambient, configuration, the poses' revision.
    pub inputs: Inputs,
    pub past: Past,
    /// Each effect's state, in registry order.
    pub effects: &'a [EffectState],
    /// The moving objects and this frame's poses of them (`Motion::write_poses`).
    pub objects: &'a [DynamicObject],
    pub poses: &'a [Pose],
}

/// A step of the frame that may be left out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameStep {
    LightView,
    GBuffer,
    /// Effect i, registry order (its passes and its reprojection lane).
    Effect(usize),
}

/// One frame's decisions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FramePlan {
    pub frame_index: u64,
    pub inputs: Inputs,
    /// What the skip tracker leaves out: the whole frame, the G-buffer, effects.
    pub skip: Plan,
    /// Bit i: effect i accumulates, so it is left out as converged, not as unchanged.
    pub accumulating: u64,
    /// Last frame's data is in the histories.
    pub history_valid: bool,
    /// The view-projection differs from last frame's (or there is no last frame).
    pub camera_moved: bool,
    /// The camera moved last frame and not this one: the histories start re-accumulating.
    pub camera_stopped: bool,
    /// The light differs from the one the light view was last rendered for.
    pub light_changed: bool,
    /// The light view is rendered: the light changed, or something moved where it sees it.
    pub light_view: bool,
    /// Objects whose pose changed since last frame.
    pub moved_objects: usize,
    /// Where they moved: what the reprojection invalidates (`--invalidate`).
    pub moved: Option<Moved>,
}

impl FramePlan {
    /// Why `step` is left out this frame; `None` when it runs.
    pub fn skipped(&self, step: FrameStep) -> Option<SkipReason> {
        let out = self.skip.frame
            || match step {
                FrameStep::LightView => !self.light_view,
                FrameStep::GBuffer => self.skip.gbuffer,
                FrameStep::Effect(i) => self.skip.effect(i),
            };
        let converged = matches!(step, FrameStep::Effect(i) if self.accumulating >> i & 1 == 1);
        out.then_some(if converged {
            SkipReason::Converged
        } else {
            SkipReason::Unchanged
        })
    }

    pub fn runs(&self, step: FrameStep) -> bool {
        self.skipped(step).is_none()
    }

    /// Effect i has converged: left out while its inputs hold.
    pub fn converged(&self, i: usize) -> bool {
        self.skip.converged >> i & 1 == 1
    }

    /// What every effect sees of the frame: the plan's change flags.
    pub fn info<'a>(
        &self,
        config: &'a RenderConfig,
        targets: &'a Targets,
        frame: FrameSet,
    ) -> FrameInfo<'a> {
        FrameInfo {
            config,
            targets,
            frame,
            frame_index: self.frame_index,
            history_valid: self.history_valid,
            camera_moved: self.camera_moved,
            camera_stopped: self.camera_stopped,
            light_changed: self.light_changed,
            light_view: self.light_view,
            objects_moved: self.moved_objects > 0,
        }
    }
}

/// Plan frame `f.frame_index`; the skip tracker records its inputs and, when the camera came
/// to rest, that the histories restart work.
pub fn plan(skips: &mut SkipTracker, f: &FrameState<'_>) -> FramePlan {
    let (inputs, past) = (f.inputs, f.past);
    let history_valid = past.history.is_some();
    let skip = skips.plan(f.frame_index, inputs, history_valid, f.effects);
    let camera_moved = past.history.map(|(m, _)| m) != Some(inputs.view_proj);
    // Never on a frame skipped whole, which needs the camera still for two frames: the
    // restart follows a recorded frame.
    let camera_stopped = past.camera_was_moving && !camera_moved && history_valid;
    if camera_stopped {
        skips.restart(f.frame_index);
    }
    let light_changed = past.rsm_light != Some(inputs.light);
    // The light view also shows what moved where the light sees it.
    let light_view = light_changed || light_sees_motion(&inputs.light, f.objects, f.poses);
    let rendered = inputs.config.rendered();
    let views = motion::Views {
        light: inputs.light,
        map_size: inputs.config.rsm_size,
        camera: inputs.view_proj,
        size: (rendered.width, rendered.height),
    };
    let accumulating =
        (f.effects.iter().enumerate()).fold(0, |m, (i, e)| m | u64::from(e.accumulates) << i);
    FramePlan {
        frame_index: f.frame_index,
        inputs,
        skip,
        accumulating,
        history_valid,
        camera_moved,
        camera_stopped,
        light_changed,
        light_view,
        moved_objects: f.poses.iter().filter(|p| p.moved()).count(),
        moved: motion::moved(f.objects, f.poses, &views),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::passes::Change;
    use crate::renderer::dependencies::Changes;
    use crate::renderer::RenderConfig;
    use crate::scene::{cornell_box, sphere, ObjectKey};
    use glam::Affine3A;

    /// Effect 0 reads everything and accumulates (shadows, indirect light); effect 1 reads the
    /// camera, the objects and the configuration only and recomputes its estimate (AO
    /// without reuse).
    fn reads() -> [Changes; 2] {
        [
            Changes::of(&Change::ALL),
            Changes::of(&[Change::Camera, Change::Object, Change::Config]),
        ]
    }

    const ACCUMULATING: EffectState = EffectState {
        settling: false,
        accumulates: true,
        refresh_pending: false,
    };
    /// The same estimate from the same inputs: converged once it ran.
    const FIXED_PATTERN: EffectState = EffectState {
        settling: false,
        accumulates: false,
        refresh_pending: false,
    };

    fn ball() -> DynamicObject {
        let key = |time, position| ObjectKey {
            time,
            position,
            rotation_deg: [0.0; 3],
        };
        DynamicObject {
            name: "ball".into(),
            mesh: sphere(),
            keys: vec![key(0.0, [0.0, 0.5, 0.0]), key(1.0, [0.5, 0.5, 0.0])],
        }
    }

    /// The renderer's side of planning, without the device: frames are planned, and a frame
    /// that is not skipped is recorded; `idle` marks effects whose counters read back no
    /// work two frames later (the counters' lag).
    struct Frames {
        skips: SkipTracker,
        past: Past,
        n: u64,
        inputs: Inputs,
        effects: [EffectState; 2],
        objects: Vec<DynamicObject>,
        poses: Vec<Pose>,
        idle: u64,
    }

    impl Frames {
        fn new() -> Self {
            let scene = cornell_box();
            let config = RenderConfig {
                width: 32,
                height: 32,
                skip_unchanged: true,
                ..Default::default()
            };
            let camera = scene.camera;
            Self {
                skips: SkipTracker::new(&reads()),
                past: Past::default(),
                n: 0,
                inputs: Inputs {
                    view_proj: camera.view_proj(1.0),
                    eye: camera.position,
                    light: scene.light,
                    ambient: scene.ambient,
                    config,
                    poses: 0,
                },
                effects: [ACCUMULATING, FIXED_PATTERN],
                objects: vec![ball()],
                poses: vec![Pose::STILL],
                idle: 0,
            }
        }

        fn frame(&mut self) -> FramePlan {
            let plan = plan(
                &mut self.skips,
                &FrameState {
                    frame_index: self.n,
                    inputs: self.inputs,
                    past: self.past,
                    effects: &self.effects,
                    objects: &self.objects,
                    poses: &self.poses,
                },
            );
            if !plan.skip.frame {
                self.past.recorded(&plan);
            }
            if self.n >= 2 {
                for i in 0..2 {
                    let work = if self.idle >> i & 1 == 1 { 0 } else { 1 };
                    let counters = [("ssao_computed_pixels", work)];
                    self.skips.read_back(i, self.n - 2, &counters);
                }
            }
            self.n += 1;
            plan
        }

        /// Frames until one is skipped whole (at most 20).
        fn until_skipped(&mut self) -> (u64, FramePlan) {
            for _ in 0..20 {
                let p = self.frame();
                if p.skip.frame {
                    return (self.n - 1, p);
                }
            }
            panic!("no skipped frame");
        }

        fn walk(&mut self, dx: f32) {
            self.inputs.view_proj *= Mat4::from_translation(Vec3::new(dx, 0.0, 0.0));
            self.inputs.eye.x -= dx;
        }
    }

    #[test]
    fn the_first_frame_runs_everything() {
        let mut f = Frames::new();
        let p = f.frame();
        assert!(!p.history_valid && p.camera_moved && !p.camera_stopped);
        assert!(p.light_changed && p.light_view);
        for step in [
            FrameStep::LightView,
            FrameStep::GBuffer,
            FrameStep::Effect(0),
            FrameStep::Effect(1),
        ] {
            assert!(p.runs(step), "{step:?}");
        }
        assert_eq!((p.moved_objects, p.moved), (0, None));
    }

    #[test]
    fn a_still_camera_is_not_moving_and_a_moving_one_is() {
        let mut f = Frames::new();
        f.frame();
        let still = f.frame();
        assert!(still.history_valid && !still.camera_moved && !still.camera_stopped);
        assert!(!still.light_changed && !still.light_view);
        assert_eq!(
            still.skipped(FrameStep::LightView),
            Some(SkipReason::Unchanged)
        );
        f.walk(0.01);
        let moving = f.frame();
        assert!(moving.camera_moved && !moving.camera_stopped);
        assert!(moving.runs(FrameStep::GBuffer));
        assert!(f.past.camera_was_moving);
    }

    #[test]
    fn a_camera_coming_to_rest_starts_re_accumulation_and_waits_for_new_idle_frames() {
        let mut f = Frames::new();
        f.idle = 0b11;
        f.until_skipped();
        f.walk(0.01);
        assert!(f.frame().camera_moved);
        let rest = f.frame();
        assert!(rest.camera_stopped && !rest.camera_moved);
        assert!(!f.past.camera_was_moving);
        let rest_at = f.n - 1;
        // Only the next frame keeps the camera still: no restart again.
        assert!(!f.frame().camera_stopped);
        // The accumulating effect waits for an idle frame from the restart on, read back
        // (two frames later) and two frames old: one frame later than the idle frame before
        // the restart would have allowed.
        let (skipped_at, _) = f.until_skipped();
        assert_eq!(skipped_at, rest_at + 3);
    }

    #[test]
    fn a_moved_light_renders_the_light_view_and_reruns_what_reads_it() {
        let mut f = Frames::new();
        f.idle = 0b11;
        f.until_skipped();
        f.inputs.light.position.x += 0.1;
        let p = f.frame();
        assert!(p.light_changed && p.light_view && !p.camera_moved);
        assert!(!p.skip.frame && p.runs(FrameStep::LightView));
        // The G-buffer and the effect that does not read the light stay left out.
        assert_eq!(p.skipped(FrameStep::GBuffer), Some(SkipReason::Unchanged));
        assert_eq!(p.skipped(FrameStep::Effect(1)), Some(SkipReason::Unchanged));
        assert!(p.runs(FrameStep::Effect(0)));
        assert_eq!(f.past.rsm_light, Some(f.inputs.light));
        assert!(!f.frame().light_changed);
    }

    #[test]
    fn a_moved_object_invalidates_where_it_went_and_reruns_the_g_buffer() {
        let mut f = Frames::new();
        f.idle = 0b11;
        f.until_skipped();
        // The ball rolls under the light, then stands still at its new place.
        let to = f.objects[0].transform_at(0.5);
        f.poses[0] = Pose {
            now: to,
            before: Affine3A::from_translation(Vec3::new(0.0, 0.5, 0.0)),
        };
        f.inputs.poses += 1;
        let p = f.frame();
        assert_eq!(p.moved_objects, 1);
        let moved = p.moved.expect("what moved");
        assert_eq!(moved.count, 1);
        // Around the unit ball at both of its poses.
        assert!(
            moved.bounds.min.x < -0.9 && moved.bounds.max.x > 1.2,
            "{moved:?}"
        );
        assert!(moved.screen_rect[0] < moved.screen_rect[2]);
        // The light sees it: its view is rendered though the light did not move.
        assert!(p.light_view && !p.light_changed);
        for step in [
            FrameStep::GBuffer,
            FrameStep::Effect(0),
            FrameStep::Effect(1),
        ] {
            assert!(p.runs(step), "{step:?}");
        }
        f.poses[0] = Pose {
            now: to,
            before: to,
        };
        let p = f.frame();
        assert_eq!((p.moved_objects, p.moved, p.light_view), (0, None, false));
    }

    #[test]
    fn an_accumulating_effect_is_converged_only_when_idle_and_no_refresh_is_due() {
        let mut f = Frames::new();
        // Work read back every frame: never converged, never skipped.
        for _ in 0..8 {
            let p = f.frame();
            assert!(!p.converged(0) && p.runs(FrameStep::Effect(0)));
        }
        // The fixed-pattern effect converged as soon as it ran; left out with steady inputs.
        assert!(f.frame().converged(1));
        assert_eq!(
            f.frame().skipped(FrameStep::Effect(1)),
            Some(SkipReason::Unchanged)
        );
        f.idle = 0b11;
        let (_, p) = f.until_skipped();
        assert!(p.converged(0));
        assert_eq!(p.skipped(FrameStep::Effect(0)), Some(SkipReason::Converged));
        // A refresh tile still due, or a settling estimate, holds convergence back.
        for state in [
            EffectState {
                refresh_pending: true,
                ..ACCUMULATING
            },
            EffectState {
                settling: true,
                ..FIXED_PATTERN
            },
        ] {
            f.effects[0] = state;
            let p = f.frame();
            assert!(!p.converged(0) && p.runs(FrameStep::Effect(0)) && !p.skip.frame);
            f.effects[0] = ACCUMULATING;
        }
    }

    #[test]
    fn every_skip_reason() {
        let mut f = Frames::new();
        f.idle = 0b11;
        let (_, p) = f.until_skipped();
        // Everything left out: unchanged, but accumulating passes converged.
        assert_eq!(p.skipped(FrameStep::LightView), Some(SkipReason::Unchanged));
        assert_eq!(p.skipped(FrameStep::GBuffer), Some(SkipReason::Unchanged));
        assert_eq!(p.skipped(FrameStep::Effect(0)), Some(SkipReason::Converged));
        assert_eq!(p.skipped(FrameStep::Effect(1)), Some(SkipReason::Unchanged));
        // The G-buffer alone: the camera held for two frames, an effect still working.
        f.idle = 0b10;
        f.walk(0.01);
        for _ in 0..6 {
            f.frame();
        }
        let p = f.frame();
        assert!(!p.skip.frame && p.runs(FrameStep::Effect(0)));
        assert_eq!(p.skipped(FrameStep::GBuffer), Some(SkipReason::Unchanged));
        // Skipping off, or no valid history: nothing is left out but an unchanged light view.
        f.inputs.config.skip_unchanged = false;
        let p = f.frame();
        assert_eq!(
            p.skip,
            Plan {
                converged: p.skip.converged,
                ..Plan::default()
            }
        );
        assert_eq!(p.skipped(FrameStep::LightView), Some(SkipReason::Unchanged));
        f.inputs.config.skip_unchanged = true;
        f.past.history = None;
        let p = f.frame();
        assert!(!p.history_valid && p.camera_moved);
        assert_eq!(
            p.skip,
            Plan {
                converged: p.skip.converged,
                ..Plan::default()
            }
        );
        assert!(p.runs(FrameStep::GBuffer) && p.runs(FrameStep::Effect(1)));
    }
}
