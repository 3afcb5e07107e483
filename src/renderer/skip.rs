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

use super::config::{RenderConfig, FRAMES_IN_FLIGHT};
use crate::effects::Effect;
use crate::passes::PassId;
use crate::scene::SpotLight;
use crate::vk::{GpuTimer, SkipReason};
use glam::{Mat4, Vec3};

/// Everything a frame's passes read besides each other's outputs and the histories.
#[derive(Clone, Copy, PartialEq)]
pub struct Inputs {
    pub view_proj: Mat4,
    pub eye: Vec3,
    pub light: SpotLight,
    pub ambient: Vec3,
    pub config: RenderConfig,
    /// Changes whenever a moving object's transform does (`Renderer::set_time`).
    pub poses: u64,
}

/// What one effect reads of them (the light only if its output depends on it).
#[derive(Clone, Copy, PartialEq)]
struct EffectInputs {
    view_proj: Mat4,
    eye: Vec3,
    light: Option<SpotLight>,
    config: RenderConfig,
    poses: u64,
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

#[derive(Default)]
struct EffectTrack {
    inputs: Option<Since<EffectInputs>>,
    /// The newest frame read back in which the effect computed nothing.
    idle: Option<u64>,
}

/// This frame's decisions; `true` = skipped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Plan {
    pub frame: bool,
    pub gbuffer: bool,
    /// Bit i: effect i (registry order of the renderer's effects).
    pub effects: u64,
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
    /// What each slot's frame skipped (its skipped effects copied no counters).
    slots: [Plan; FRAMES_IN_FLIGHT],
}

/// Whether `e` accumulates into a reused history under `config`.
pub fn accumulates(config: &RenderConfig, e: &dyn Effect) -> bool {
    config.temporal.reuse && e.counts(config) && e.temporal().is_some()
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
    pub fn new(effects: usize) -> Self {
        Self {
            frame: None,
            camera: None,
            tracks: (0..effects).map(|_| EffectTrack::default()).collect(),
            known: Vec::new(),
            slots: [Plan::default(); FRAMES_IN_FLIGHT],
        }
    }

    /// Everything runs again (histories dropped, targets recreated).
    pub fn forget(&mut self) {
        self.frame = None;
        self.camera = None;
        for t in &mut self.tracks {
            *t = EffectTrack::default();
        }
    }

    /// Decide frame `n` (its inputs `inputs`, the histories valid or not) and record its
    /// inputs.
    pub fn plan(
        &mut self,
        n: u64,
        inputs: Inputs,
        history_valid: bool,
        effects: &[Box<dyn Effect>],
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
        let config = &inputs.config;
        for (i, (e, track)) in effects.iter().zip(&mut self.tracks).enumerate() {
            let key = EffectInputs {
                view_proj: inputs.view_proj,
                eye: inputs.eye,
                light: e.reads_light().then_some(inputs.light),
                config: inputs.config,
                poses: inputs.poses,
            };
            let (unchanged, since) = steady(&mut track.inputs, key, n);
            let converged = !e.settling(config)
                && (!accumulates(config, e.as_ref())
                    || (track.idle.is_some_and(|f| f >= since && n >= f + 2)
                        && e.temporal().is_some_and(|t| t.refresh_left == 0)));
            if on && unchanged && converged {
                plan.effects |= 1 << i;
            }
        }
        let all = plan.effects.count_ones() as usize == effects.len();
        plan.frame = on && frame_steady && plan.gbuffer && all;
        plan
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
            let left_out = plan.frame
                || (pass == PassId::GBuffer && plan.gbuffer)
                // No lane ran: every temporal effect was left out.
                || pass == PassId::Reproject
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
            let Some(pass) = PassId::ALL.into_iter().find(|p| p.name() == name) else {
                continue;
            };
            if self.known.iter().any(|(p, _)| *p == pass) {
                continue;
            }
            let accumulated = effects
                .iter()
                .any(|e| accumulates(config, e.as_ref()) && e.accumulating().contains(&pass));
            self.known
                .push((pass, pass == PassId::Reproject || accumulated));
            added = true;
        }
        if added {
            self.known
                .sort_by_key(|(p, _)| PassId::ALL.iter().position(|q| q == p));
        }
    }
}

/// An input whose change makes passes run again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    /// The camera's view-projection or eye.
    Camera,
    /// The spot light.
    Light,
    /// A moving object's transform (for the light view: one the light's frustum meets).
    Object,
    /// The configuration (the viewer's switches).
    Config,
}

/// One row of the dependency table: a pass and the changes that make it run again.
pub struct Trigger {
    pub pass: PassId,
    pub changes: &'static [Change],
    /// The effect the pass belongs to, and whether it accumulates (it then also runs on
    /// until its history converges).
    pub effect: Option<(crate::effects::EffectId, bool)>,
}

const EVERYTHING: &[Change] = &[
    Change::Camera,
    Change::Light,
    Change::Object,
    Change::Config,
];
const LIT_EFFECT: &[Change] = EVERYTHING;
const UNLIT_EFFECT: &[Change] = &[Change::Camera, Change::Object, Change::Config];

/// The dependency table of `effects` under `config`, from each effect's declarations
/// (`passes`, `reads_light`, whether it accumulates): for each pass, the changes that make it
/// run again. The frame planner follows it (`SkipTracker::plan`), `explain` prints it, and the
/// tests compare each change's recorded passes with it.
pub fn triggers(config: &RenderConfig, effects: &[Box<dyn Effect>]) -> Vec<Trigger> {
    let mut rows = vec![
        Trigger {
            pass: PassId::LightView,
            changes: &[Change::Light, Change::Object],
            effect: None,
        },
        Trigger {
            pass: PassId::GBuffer,
            changes: &[Change::Camera, Change::Object],
            effect: None,
        },
    ];
    for e in effects {
        let changes = if e.reads_light() {
            LIT_EFFECT
        } else {
            UNLIT_EFFECT
        };
        for &pass in e.passes() {
            rows.push(Trigger {
                pass,
                changes,
                effect: Some((e.id(), accumulates(config, e.as_ref()))),
            });
        }
    }
    // Any effect with a reused history running runs its lane; the composite and what follows
    // it run on every frame that runs anything.
    rows.push(Trigger {
        pass: PassId::Reproject,
        changes: EVERYTHING,
        effect: None,
    });
    let mut last = vec![PassId::Composite];
    if config.aa.mode.subpixel() {
        last.extend([PassId::SraaGeometry, PassId::Sraa]);
    }
    if config.aa.mode.supersampling() > 1 {
        last.push(PassId::SsaaDownsample);
    }
    rows.extend(last.into_iter().map(|pass| Trigger {
        pass,
        changes: EVERYTHING,
        effect: None,
    }));
    rows.sort_by_key(|t| PassId::ALL.iter().position(|q| *q == t.pass));
    rows.dedup_by_key(|t| t.pass);
    rows
}

/// Why a row of the dependency table runs again, in words.
fn why(t: &Trigger) -> String {
    match (t.pass, t.effect) {
        (PassId::LightView, _) => "the light, or a moving object whose bounds (this frame's or \
                                   the last one's) meet the light's frustum"
            .to_string(),
        (PassId::GBuffer, _) => "the camera (view-projection or eye), a moving object".to_string(),
        (PassId::Reproject, _) => {
            "any effect with a reused history running (one lane each)".to_string()
        }
        (_, Some((id, converges))) => {
            let light = if t.changes.contains(&Change::Light) {
                ", light"
            } else {
                ""
            };
            let converge = if converges {
                "; every frame until its history converges"
            } else {
                ""
            };
            format!("{id:?} effect: camera, configuration, moving objects{light}{converge}")
        }
        (_, None) => "anything (only a frame that changes nothing leaves it out)".to_string(),
    }
}

/// The dependency table of `effects` under `config`: for each pass, what makes it run again
/// (`ssgi bench --explain-skips`, docs/ARCHITECTURE.md).
pub fn explain(config: &RenderConfig, effects: &[Box<dyn Effect>]) -> String {
    let mut out = String::from(
        "pass (those an effect may record)  runs again when this changed in the last two \
         frames\n",
    );
    for t in triggers(config, effects) {
        out += &format!("{:<18} {}\n", t.pass.name(), why(&t));
    }
    if !config.skip_unchanged {
        out += "(--skip-unchanged off: every pass runs every frame)\n";
    }
    out
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
        let c = [
            ("disoccluded_pixels", 5),
            ("ssao_computed_pixels", 0),
            ("indirect_fixup_pixels", 2),
            ("ssao_refresh_evaluations", 3),
        ];
        assert_eq!(work(&c), 5);
        assert_eq!(work(&c[..2]), 0);
    }
}
