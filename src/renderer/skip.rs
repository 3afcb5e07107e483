//! What a frame may leave out (`RenderConfig::skip_unchanged`): the G-buffer when the camera
//! has not moved, an effect when none of its inputs changed and it has converged, and the
//! whole frame when nothing changed at all. "For two frames" everywhere: both halves of every
//! ping-ponged target (G-buffer, histories) then hold the same inputs' results, so a frame of
//! either parity may read them.
//!
//! An effect that accumulates into a reused history has converged when a frame read back
//! since its inputs last changed, two or more frames ago, computed nothing (no pixel, fix-up
//! or refresh evaluation) and no refresh tile is pending: with unchanged inputs the work lists
//! follow from the inputs and the histories alone, so that frame's successors compute nothing
//! either and copy the history forward unchanged. Without reuse an effect recomputes the same
//! fixed-pattern estimate from the same inputs, so unchanged inputs suffice.

pub use super::dependencies::accumulates;
use super::dependencies::Changes;
pub use super::dependencies::{explain, triggers, Trigger};
use crate::config::{RenderConfig, FRAMES_IN_FLIGHT};
use crate::effects::Effect;
pub use crate::passes::Change;
use crate::passes::PassId;
use crate::scene::SpotLight;
use crate::vk::{GpuTimer, SkipReason};
use glam::{Mat4, Vec3};

/// Everything a frame's passes read besides each other's outputs and the histories.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inputs {
    pub view_proj: Mat4,
    pub eye: Vec3,
    pub light: SpotLight,
    pub ambient: Vec3,
    pub config: RenderConfig,
    /// Changes whenever a moving object's transform does (`Renderer::set_time`).
    pub poses: u64,
}

/// What one effect reads of them: those its passes depend on (`dependencies.rs`; AO, for
/// one, not the light).
#[derive(Clone, Copy, PartialEq)]
struct EffectInputs {
    camera: Option<(Mat4, Vec3)>,
    light: Option<(SpotLight, Vec3)>,
    config: Option<RenderConfig>,
    poses: Option<u64>,
}

impl EffectInputs {
    fn new(inputs: &Inputs, reads: Changes) -> Self {
        let has = |c| reads.contains(c);
        Self {
            camera: has(Change::Camera).then_some((inputs.view_proj, inputs.eye)),
            light: has(Change::Light).then_some((inputs.light, inputs.ambient)),
            config: has(Change::Config).then_some(inputs.config),
            poses: has(Change::Object).then_some(inputs.poses),
        }
    }
}

/// A value and the first frame that saw it.
#[derive(Clone, Copy)]
struct Since<K> {
    key: K,
    frame: u64,
}

/// Whether `key` has held since two frames before `n` at least; then records it (a new key
/// starts at `n`).
fn steady<K: PartialEq + Copy>(since: &mut Option<Since<K>>, key: K, n: u64) -> (bool, u64) {
    match since {
        Some(s) if s.key == key => (n >= s.frame + 2, s.frame),
        _ => {
            *since = Some(Since { key, frame: n });
            (false, n)
        }
    }
}

struct EffectTrack {
    /// The changes its passes depend on.
    reads: Changes,
    inputs: Option<Since<EffectInputs>>,
    /// The newest frame read back in which the effect computed nothing.
    idle: Option<u64>,
    /// The last frame whose histories restarted work with unchanged inputs (the camera came
    /// to rest: re-accumulation); an idle frame before it says nothing.
    restarted: u64,
}

/// This frame's decisions; `true` = skipped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Plan {
    pub frame: bool,
    pub gbuffer: bool,
    /// Bit i: effect i (registry order of the renderer's effects).
    pub effects: u64,
    /// Bit i: effect i has converged (skipped as soon as its inputs hold for two frames).
    pub converged: u64,
}

/// What the tracker asks of an effect before its frame, so that planning needs no device.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EffectState {
    /// Its output still changes with unchanged inputs (`Effect::settling`).
    pub settling: bool,
    /// It accumulates into a reused history (`accumulates`): converged only once its
    /// counters read back idle.
    pub accumulates: bool,
    /// Refresh tiles are still due (`TemporalEffect::refresh_left`).
    pub refresh_pending: bool,
}

impl EffectState {
    pub fn of(config: &RenderConfig, e: &dyn Effect) -> Self {
        Self {
            settling: e.settling(config),
            accumulates: accumulates(config, e),
            refresh_pending: e.temporal().is_some_and(|t| t.refresh_left > 0),
        }
    }
}

impl Plan {
    pub fn effect(&self, i: usize) -> bool {
        self.effects >> i & 1 == 1
    }
}

pub struct SkipTracker {
    frame: Option<Since<Inputs>>,
    camera: Option<Since<(Mat4, Vec3, u64)>>,
    tracks: Vec<EffectTrack>,
    /// The passes recorded since the configuration last changed, and whether each
    /// accumulates into a reused history (a skipped one is then `converged`).
    known: Vec<(PassId, bool)>,
    /// Every pass in recording order (`renderer::all_passes`), to name a recorded pass and
    /// keep `known` in that order.
    order: Vec<PassId>,
    /// What each slot's frame skipped (its skipped effects copied no counters).
    slots: [Plan; FRAMES_IN_FLIGHT],
}

/// Pixels and pattern evaluations an effect's counters say it spent this frame.
fn work(counters: &[(&'static str, u64)]) -> u64 {
    counters
        .iter()
        .filter(|(name, _)| {
            name.ends_with("_computed_pixels")
                || name.ends_with("_fixup_pixels")
                || name.ends_with("_refresh_evaluations")
        })
        .map(|(_, n)| n)
        .sum()
}

impl SkipTracker {
    /// A tracker for effects whose passes depend on `reads` (one entry per effect).
    pub fn new(reads: &[Changes]) -> Self {
        Self {
            frame: None,
            camera: None,
            tracks: reads
                .iter()
                .map(|&reads| EffectTrack {
                    reads,
                    inputs: None,
                    idle: None,
                    restarted: 0,
                })
                .collect(),
            known: Vec::new(),
            order: super::catalog::all_passes(),
            slots: [Plan::default(); FRAMES_IN_FLIGHT],
        }
    }

    /// Everything runs again (histories dropped, targets recreated).
    pub fn forget(&mut self) {
        self.frame = None;
        self.camera = None;
        for t in &mut self.tracks {
            t.inputs = None;
            t.idle = None;
        }
    }

    /// Decide frame `n` (its inputs `inputs`, the histories valid or not, each effect's
    /// state) and record its inputs.
    pub fn plan(
        &mut self,
        n: u64,
        inputs: Inputs,
        history_valid: bool,
        effects: &[EffectState],
    ) -> Plan {
        let on = inputs.config.skip_unchanged && history_valid;
        if self.frame.is_some_and(|f| f.key.config != inputs.config) {
            self.known.clear();
        }
        let (frame_steady, _) = steady(&mut self.frame, inputs, n);
        // The G-buffer sees the camera and the moving objects.
        let (camera_steady, _) = steady(
            &mut self.camera,
            (inputs.view_proj, inputs.eye, inputs.poses),
            n,
        );
        let mut plan = Plan {
            gbuffer: on && camera_steady,
            ..Plan::default()
        };
        for (i, (e, track)) in effects.iter().zip(&mut self.tracks).enumerate() {
            let key = EffectInputs::new(&inputs, track.reads);
            let (unchanged, since) = steady(&mut track.inputs, key, n);
            let converged = !e.settling
                && (!e.accumulates
                    || (track
                        .idle
                        .is_some_and(|f| f >= since.max(track.restarted) && n >= f + 2)
                        && !e.refresh_pending));
            plan.converged |= u64::from(converged) << i;
            if on && unchanged && converged {
                plan.effects |= 1 << i;
            }
        }
        let all = plan.effects.count_ones() as usize == effects.len();
        plan.frame = on && frame_steady && plan.gbuffer && all;
        plan
    }

    /// The histories restart work on frame `n` with unchanged inputs (the camera came to
    /// rest): no effect counts as converged on an idle frame from before it.
    pub fn restart(&mut self, n: u64) {
        for t in &mut self.tracks {
            t.restarted = n;
        }
    }

    /// Note what `slot`'s frame skipped (before its counters are next read).
    pub fn recorded(&mut self, slot: usize, plan: Plan) {
        self.slots[slot] = plan;
    }

    /// Whether effect `i` copied counters in `slot`'s last frame.
    pub fn counted(&self, slot: usize, i: usize) -> bool {
        !self.slots[slot].frame && !self.slots[slot].effect(i)
    }

    /// Effect `i`'s counters of `frame`, read back: zero work makes it idle, any work not.
    pub fn read_back(&mut self, i: usize, frame: u64, counters: &[(&'static str, u64)]) {
        let Some(track) = self.tracks.get_mut(i) else {
            return;
        };
        if work(counters) == 0 {
            track.idle = track.idle.max(Some(frame));
        } else {
            track.idle = None;
        }
    }

    /// Report every known pass that `plan` left out of the frame in `slot` as skipped, with
    /// its reason (a pass an effect that ran did not need, such as a refresh with no tile
    /// drawn, is not a skip); then add the passes it recorded to the known ones.
    pub fn report(
        &mut self,
        timer: &mut GpuTimer,
        slot: usize,
        plan: Plan,
        config: &RenderConfig,
        effects: &[Box<dyn Effect>],
    ) {
        for &(pass, temporal) in &self.known {
            let name = pass.name();
            if timer.recorded(slot).contains(&name) || timer.is_skipped(slot, name) {
                continue;
            }
            // A pass that draws the scene's geometry (a post stage's too) is left out with
            // the G-buffer.
            let geometry = matches!(pass, PassId::GBUFFER | PassId::GBUFFER_RESOLVE)
                || crate::post::REGISTRY
                    .iter()
                    .any(|r| r.geometry_passes.contains(&pass));
            let left_out = plan.frame
                || geometry && plan.gbuffer
                // No lane ran: every temporal effect was left out.
                || pass == PassId::REPROJECT
                || effects
                    .iter()
                    .enumerate()
                    .any(|(i, e)| plan.effect(i) && e.passes().contains(&pass));
            if !left_out {
                continue;
            }
            let reason = if temporal {
                SkipReason::Converged
            } else {
                SkipReason::Unchanged
            };
            timer.skip(slot, name, reason);
        }
        // New passes are rare (the first frames, a configuration change): nothing is
        // allocated or sorted on the frames in between.
        let mut added = false;
        for &name in timer.recorded(slot) {
            let Some(&pass) = self.order.iter().find(|p| p.name() == name) else {
                continue;
            };
            if self.known.iter().any(|(p, _)| *p == pass) {
                continue;
            }
            let accumulated = effects
                .iter()
                .any(|e| accumulates(config, e.as_ref()) && e.accumulating().contains(&pass));
            self.known
                .push((pass, pass == PassId::REPROJECT || accumulated));
            added = true;
        }
        if added {
            let order = &self.order;
            self.known
                .sort_by_key(|(p, _)| order.iter().position(|o| o == p));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_is_steady_from_its_third_frame() {
        let mut s: Option<Since<u32>> = None;
        assert_eq!(steady(&mut s, 7, 10), (false, 10));
        assert_eq!(steady(&mut s, 7, 11), (false, 10));
        assert_eq!(steady(&mut s, 7, 12), (true, 10));
        assert_eq!(steady(&mut s, 8, 13), (false, 13));
    }

    #[test]
    fn work_counts_pixels_fixups_and_refresh_but_not_disocclusions() {
        // Distinct powers of two: the sum says which counters were counted.
        let c = [
            ("disoccluded_pixels", 1),
            ("ssao_computed_pixels", 2),
            ("indirect_fixup_pixels", 4),
            ("ssao_refresh_evaluations", 8),
            ("indirect_gather_invocations", 16),
        ];
        assert_eq!(work(&c), 2 + 4 + 8);
        assert_eq!(work(&c[..1]), 0);
    }
}
