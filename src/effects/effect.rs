//! What an effect is to the renderer: the [`Effect`] trait, its registration, and what it is
//! given to create itself and to record a frame.

use crate::config::sweep_key::SweepKey;
use crate::config::{Accumulate, RenderConfig};
use crate::error::Result;
use crate::passes::compute::{Dispatch, FrameSet};
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::targets::{EffectView, Target, Targets};
use crate::resources::temporal_effect::{EffectKind, TemporalEffect};
use crate::shaders::EffectPush;
use crate::vk::recorder::Recorder;
use crate::vk::{Buffer, Context, DescriptorPool, GpuTimer, Image, Tracker};
use std::sync::Arc;

/// Which effect: its name, declared in its folder (`ID`), for lookups (`Renderer::read_state`)
/// and reports. No two registered effects share one (`tests/reflection.rs`).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct EffectId(&'static str);

impl EffectId {
    pub const fn new(name: &'static str) -> EffectId {
        EffectId(name)
    }

    pub const fn name(self) -> &'static str {
        self.0
    }
}

impl std::fmt::Debug for EffectId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0)
    }
}

/// How the composite adds an effect's image (the `kind` codes of shaders/composite.comp).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TermKind {
    /// Outgoing radiance, added as is (direct light).
    Radiance = 0,
    /// Visibility of the ambient light, multiplied into it (AO, r channel).
    AmbientVisibility = 1,
    /// Eq 9's one-bounce irradiance from VPL flux: the receiver reflects albedo/pi of it, and a
    /// VPL of flux Phi has intensity Phi cos / pi (eq 9 leaves that 1/pi out).
    VplIrradiance = 2,
    /// rgb = bounce irradiance (the receiver reflects albedo/pi of it), a = a modulation
    /// factor that darkens the ambient light and the radiance terms (directional occlusion's:
    /// Szentandrasi section 4.1, "the diffuse and/or the ambient component").
    BounceAndModulation = 3,
}

/// What every effect sees of the frame being recorded.
pub struct FrameInfo<'a> {
    pub config: &'a RenderConfig,
    pub targets: &'a Targets,
    pub frame: FrameSet,
    pub frame_index: u64,
    /// Last frame's data is in the histories (false on the first frame, after a resize or a
    /// camera cut).
    pub history_valid: bool,
    /// The view-projection differs from last frame's (or there is no last frame).
    pub camera_moved: bool,
    /// The camera moved last frame and not this one: the histories start re-accumulating
    /// (`TemporalConfig::reaccumulate`).
    pub camera_stopped: bool,
    /// The light differs from the one the light view was last rendered for.
    pub light_changed: bool,
    /// The light view is rendered this frame: the light changed, or something moved where
    /// the light sees it (the RSM and the shadow map change).
    pub light_view: bool,
    /// A moving object's transform changed since last frame.
    pub objects_moved: bool,
}

impl FrameInfo<'_> {
    /// Reuse is on and the histories hold last frame's data.
    pub fn reusing(&self) -> bool {
        self.config.temporal.reuse && self.history_valid
    }

    /// Whether an effect whose value depends on the light (`light`) or on the whole RSM
    /// (`rsm`) keeps its history this frame: with `--invalidate`, a moved light restarts the
    /// first, a re-rendered light view the second (a change there reaches every pixel).
    pub fn keeps_history(&self, light: bool, rsm: bool) -> bool {
        let invalidate = self.config.temporal.invalidate;
        self.reusing() && !(invalidate && (light && self.light_changed || rsm && self.light_view))
    }

    /// Whether the histories of an effect of kind `kind` start re-accumulating this frame:
    /// the camera came to rest, the histories hold last frame's data, and the accumulation
    /// is the gated running mean of at least two patterns (`TemporalConfig::reaccumulate`).
    pub fn starts_reaccumulating(&self, kind: &EffectKind) -> bool {
        let t = &self.config.temporal;
        self.camera_stopped
            && self.reusing()
            && t.reaccumulate
            && kind.reaccumulates
            && matches!(t.accumulate, Accumulate::Gated { .. })
            && t.rotation_limit >= 2
    }

    /// Whether a change this frame reaches the values of an effect of kind `kind` (a moving
    /// object; the light, or a re-rendered light view, for an effect lit by it): its
    /// re-accumulation, if one is under way, ends.
    pub fn changes_reach(&self, kind: &EffectKind) -> bool {
        self.objects_moved || kind.lit && (self.light_changed || self.light_view)
    }

    /// Whether this frame's change makes the refresh pass over every pixel once
    /// (`TemporalEffect::frame_push`), for an effect whose value depends on the light (`light`)
    /// or on the whole RSM (`rsm`): with `--invalidate off` (where nothing restarts, so the
    /// refresh is what brings stale pixels up to date), a moved light, a light view rendered
    /// again or a moved object. With `--invalidate on` those restart the pixels they reach,
    /// which then recompute by themselves. (The viewer's in-place switch, the PCF kernel,
    /// restarts the shadows' history: `DirectEffect::prepare`.)
    pub fn refresh_cover(&self, light: bool, rsm: bool) -> bool {
        let stale = self.objects_moved || light && self.light_changed || rsm && self.light_view;
        !self.config.temporal.invalidate && stale
    }
}

/// The command buffer being recorded: passes run inside [`Recording::timed`], which puts each
/// in its command label and between its timestamps.
pub struct Recording<'a> {
    pub rec: Recorder<'a>,
    pub tracker: &'a mut Tracker,
    pub timer: &'a mut GpuTimer,
    pub slot: usize,
    /// The last pass recorded (device-loss reports name it).
    pub last_pass: Option<PassId>,
}

impl Recording<'_> {
    pub fn timed(&mut self, pass: PassId, f: impl FnOnce(&Recorder<'_>, &mut Tracker)) {
        self.rec.begin_label(pass.name());
        let began = self.timer.begin_pass(self.rec.cmd, self.slot, pass.name());
        f(&self.rec, self.tracker);
        if began {
            self.timer.end_pass(self.rec.cmd, self.slot);
        }
        self.rec.end_label();
        self.last_pass = Some(pass);
    }
}

/// Everything an effect needs to create itself.
pub struct Setup<'a> {
    pub ctx: &'a Arc<Context>,
    pub pool: &'a DescriptorPool,
    pub config: &'a RenderConfig,
    pub tracker: &'a mut Tracker,
}

pub trait Effect {
    fn id(&self) -> EffectId;

    /// (Re)create the size-dependent images and history for `config`'s size (the device is
    /// idle; histories start over).
    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()>;

    /// Point every descriptor set at this size's images.
    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()>;

    /// The effect's temporal machinery (history, state, work lists, counters), if it has one
    /// (by default none: the per-frame filters keep their own histories).
    fn temporal(&self) -> Option<&TemporalEffect> {
        None
    }
    fn temporal_mut(&mut self) -> Option<&mut TemporalEffect> {
        None
    }

    /// Whether this frame uses the temporal machinery (its counters are reset, filled and read
    /// back). The viewer changes the PCF kernel in place, so it is asked per frame.
    fn counts(&self, _config: &RenderConfig) -> bool {
        self.temporal().is_some()
    }

    /// Whether the effect's output still changes with unchanged inputs (an estimate that
    /// takes a new sample every frame until its memory is full); the frame skipping waits for
    /// it. Accumulating effects say so through their counters instead.
    fn settling(&self, _config: &RenderConfig) -> bool {
        false
    }

    /// Every pass the effect may record (the skip report names those of a skipped effect).
    fn passes(&self) -> &'static [PassId];

    /// The passes that accumulate into the effect's history (a frame skipped because
    /// nothing changed reports them `converged` while the effect counts, the others
    /// `unchanged`).
    fn accumulating(&self) -> &'static [PassId] {
        &[]
    }

    /// Copy this frame's counters for reading when `slot` comes round again (by default the
    /// temporal machinery's, on frames that use it).
    fn copy_counters(
        &mut self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        slot: usize,
        config: &RenderConfig,
    ) {
        if self.counts(config) {
            if let Some(t) = self.temporal_mut() {
                t.copy_counters(rec, tracker, slot);
            }
        }
    }

    /// The counters of the frame that last used `slot` (its fence has signalled).
    fn collect_counters(&mut self, slot: usize) -> Vec<(&'static str, u64)> {
        self.temporal_mut()
            .map(|t| t.readback.collect(slot))
            .unwrap_or_default()
    }

    /// Before recording: draw the frame's refresh tile and push constants.
    fn prepare(&mut self, info: &FrameInfo<'_>);

    /// Whether this frame reprojects the effect's history (its lane of the shared
    /// reprojection pass runs).
    fn reprojects(&self, info: &FrameInfo<'_>) -> bool;

    /// This frame's push constants (from `prepare`): the reprojection takes the refresh tile,
    /// history validity and block size of its lane from them. Only effects with a temporal
    /// history are asked; the others have none.
    fn push(&self) -> &EffectPush {
        const NONE: EffectPush = EffectPush {
            refresh_rect: [0; 4],
            refresh_feather: 0,
            history_valid: 0,
            block_shift: 0,
            pattern: 0,
        };
        &NONE
    }

    /// Record the effect's passes.
    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>);

    /// The image the composite adds for frame parity `parity`, and how.
    fn term<'a>(&'a self, targets: &'a Targets, parity: usize) -> (TermKind, &'a Image);

    /// A buffer the effect exposes for readback by name (tests and debugging).
    fn buffer(&self, _name: &str) -> Option<&Buffer> {
        None
    }

    /// The image behind a debug/readback target this effect owns, for frame parity `parity`
    /// under `config` (the configuration the frame was rendered with).
    fn target(&self, target: Target, parity: usize, config: &RenderConfig) -> Option<&Image>;
}

/// How an effect plugs in: when the configuration turns it on, how to create it, and its
/// pipelines for the up-front reflection check.
pub struct Registration {
    pub id: EffectId,
    /// The `--effects` switch (`Effects::NAMES`) that turns it on; `enabled` may ask more.
    pub switch: &'static str,
    pub enabled: fn(&RenderConfig) -> bool,
    pub create: fn(&mut Setup<'_>) -> Result<Box<dyn Effect>>,
    pub layouts: fn() -> Vec<PassLayout>,
    /// Every pass the effect may record, in recording order (`Effect::passes`).
    pub passes: &'static [PassId],
    /// Named groups of its passes whose summed time reports compare (`bench::compare::groups`).
    pub timing_groups: &'static [(&'static str, &'static [PassId])],
    /// The parameters `ssgi sweep --vary` may vary (`effects/<effect>/sweep.rs`).
    pub sweep_keys: &'static [SweepKey],
    /// Its term darkens the ambient light (a visibility, or a bounce-and-modulation factor):
    /// the reports' ambient-visibility buffer and its time are this effect's.
    pub ambient: bool,
    /// Debug views of its own images (`Effect::target` answers `Target::Effect` for them).
    pub views: &'static [EffectView],
    /// The ground truth's buffers its term estimates under a configuration that enables it
    /// (what the final image's error is measured against).
    pub estimates: fn(&RenderConfig) -> Terms,
    /// On/off settings of its own the viewer offers beside the effect switches.
    pub toggles: &'static [Toggle],
    /// Its rank for the recompute mask (`Target::State`, one effect's per-pixel reprojection
    /// state): of the effects that run and have one, the lowest-ranked shows its own (AO
    /// first: a screen-space estimate's mask has the most structure); `None`: it has none.
    pub recompute_mask: Option<u8>,
}

/// An on/off setting of an effect's configuration (the viewer's keys).
pub struct Toggle {
    /// Its name (the viewer's summary and test scripts' `key=NAME`).
    pub name: &'static str,
    /// What it switches, for the viewer's help.
    pub what: &'static str,
    pub get: fn(&RenderConfig) -> bool,
    /// Turn it on or off in a configuration; `start` is the one the viewer began with (its
    /// value comes back when the setting is turned on again).
    pub set: fn(config: &mut RenderConfig, on: bool, start: &RenderConfig),
}

/// The refresh pass's dispatch this frame, one workgroup per pixel of the refresh tile in
/// `push`; `None` when no tile is drawn.
pub fn refresh_dispatch(push: &EffectPush) -> Option<Dispatch> {
    let pixels = refresh_pixels(push);
    (pixels > 0).then_some(Dispatch::Groups(pixels))
}

/// Pixels of the refresh tile `push` draws (0: none).
pub fn refresh_pixels(push: &EffectPush) -> u32 {
    let [x0, y0, x1, y1] = push.refresh_rect;
    x1.saturating_sub(x0) * y1.saturating_sub(y0)
}

/// A render-sized RGBA32F image a pass writes and later passes sample or read back (the noisy
/// gather and filtered light of the per-frame indirect filters).
pub fn float_image(ctx: &Arc<Context>, name: &str, c: &RenderConfig) -> Result<Image> {
    Image::new(
        ctx,
        name,
        crate::vk::ImageDesc {
            width: c.width,
            height: c.height,
            format: ash::vk::Format::R32G32B32A32_SFLOAT,
            usage: ash::vk::ImageUsageFlags::STORAGE
                | ash::vk::ImageUsageFlags::SAMPLED
                | ash::vk::ImageUsageFlags::TRANSFER_SRC,
        },
    )
}

/// A dispatch over every pixel of the frame.
pub fn every_pixel(info: &FrameInfo<'_>) -> Dispatch {
    Dispatch::Pixels {
        width: info.targets.width,
        height: info.targets.height,
    }
}
