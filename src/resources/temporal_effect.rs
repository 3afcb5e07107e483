//! One temporal effect (each declares its `EffectKind` in its folder): its history pair, per-pixel state, work
//! lists and counters, refresh schedule and the push constants its passes share. The
//! reprojection pass and the accumulation rules are the same for every effect.

use super::counters::{self, Counter, CounterReadback};
use super::targets::{PingPong, MOMENTS_FORMAT, REGISTRATION_FORMAT, STATE_FORMAT};
use super::temporal::{budget_tile, RefreshSchedule, Sampling};
use crate::config::{Refresh, RenderConfig, FRAMES_IN_FLIGHT};
use crate::error::Result;
use crate::shaders::EffectPush;
use crate::vk::recorder::Recorder;
use crate::vk::{Buffer, Context, Image, ImageDesc, Tracker};
use ash::vk;
use std::sync::Arc;

/// What differs between effects.
#[derive(Clone, Copy, Debug)]
pub struct EffectKind {
    /// The cache's name (its images', counters' and audit's): the effect's id (`ID.name()`)
    /// unless the cache holds only part of the effect (direct light's shadow cache).
    pub name: &'static str,
    /// Its history's format: a `*_HISTORY_FORMAT` of shaders/include/shared_constants.glsl,
    /// which its passes' shaders and the reprojection's lane declare too.
    pub history_format: vk::Format,
    /// log2 of the work-block side: 4 (16x16), 3 (8x8), or 0: a compacted list of single
    /// pixels, 64 per workgroup (an effect whose pixels do not share a workgroup's data).
    pub block_shift: u32,
    /// Largest side of the refresh tile (the thesis: 64 for SSAO and shadows, 16 for indirect
    /// light); the refresh budget may make it smaller.
    pub refresh_tile: u32,
    /// Report names of the header words (see counters.rs) this effect fills.
    pub counters: &'static [(&'static str, Counter)],
    /// Whether the effect has the half-resolution lists: full-resolution fix-up pixels and
    /// low-resolution samples (`data` after the blocks, counters.glsl).
    pub fixups: bool,
    /// Which pixels a moving object takes the history from (`--invalidate`).
    pub moved: MovedReach,
    /// Whether its values depend on the spot light (a light change reaches them).
    pub lit: bool,
    /// Whether its histories re-accumulate when the camera stops (`--reaccumulate`): the
    /// value alone is merged with the running mean's weight (not for a cache that carries
    /// more in its moments than the re-accumulation can fade out).
    pub reaccumulates: bool,
}

/// Where a moving object changes an effect's value, so that its history there is dropped (the
/// lane's `w` in shaders/reproject.comp, which tests each pixel's surface point against the box
/// around what moved). Disocclusion is separate: the reprojection follows moving surfaces.
#[derive(Clone, Copy, Debug)]
pub enum MovedReach {
    /// Where a screen-space estimate's taps can read the box's screen footprint: within its
    /// sampling radius projected near the pixel's depth (taps read whatever the G-buffer shows
    /// there, attenuated, not cut, beyond the radius in world space), plus the pixels its
    /// taps reach beyond that (coarse position levels' blocks); both from the configuration.
    ScreenRadius(fn(&RenderConfig) -> ScreenReach),
    /// In the box, or where it falls on the shadow map (widened by the PCF kernel): the
    /// only pixels whose shadow test can meet it.
    ShadowFootprint,
    /// In the box: the gather sums every VPL, so a moved object that the light sees changes
    /// every pixel and the whole history restarts (`Effect::prepare`); this is for one the
    /// light does not see.
    Inside,
}

/// A screen-space estimate's reach (`MovedReach::ScreenRadius`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScreenReach {
    /// Sampling radius, relative to the scene's bounding radius.
    pub radius: f32,
    /// Pixels the taps reach beyond the projected radius.
    pub pad_px: u32,
}

impl MovedReach {
    /// The lane's reach in shaders/reproject.comp: `MOVED_*` (shared_constants.glsl) in bits
    /// 0-7 (0 there = none), the screen reach's extra pixels above.
    pub fn code(self, config: &RenderConfig) -> u32 {
        use crate::shaders::{MOVED_INSIDE, MOVED_SCREEN, MOVED_SHADOW};
        match self {
            MovedReach::ScreenRadius(reach) => {
                MOVED_SCREEN | reach(config).pad_px.min(1 << 16) << 8
            }
            MovedReach::ShadowFootprint => MOVED_SHADOW,
            MovedReach::Inside => MOVED_INSIDE,
        }
    }

    /// The sampling radius relative to the scene's bounding radius (0 for the other reaches).
    pub fn radius(self, config: &RenderConfig) -> f32 {
        match self {
            MovedReach::ScreenRadius(reach) => reach(config).radius,
            _ => 0.0,
        }
    }
}

const STORAGE_READ: vk::ImageUsageFlags = vk::ImageUsageFlags::from_raw(
    vk::ImageUsageFlags::STORAGE.as_raw()
        | vk::ImageUsageFlags::SAMPLED.as_raw()
        | vk::ImageUsageFlags::TRANSFER_SRC.as_raw(),
);

pub struct TemporalEffect {
    pub kind: EffectKind,
    /// rgb = value, a = estimates accumulated.
    pub history: PingPong,
    /// r = mean squared luminance of the estimates, g = pending gate crossing, b = estimates in
    /// the gated mean since its last restart.
    pub moments: PingPong,
    /// rgb = the surface point each history value belongs to, a = the history's area
    /// magnification since its counts were last scaled (>= 1); the reprojection's alone
    /// (shaders/reproject.comp).
    pub registration: PingPong,
    pub state: Image,
    pub counters: Buffer,
    pub max_blocks: u32,
    /// Index in the counters' `data` of the low-resolution sample list.
    pub lowres_list: u32,
    pub schedule: RefreshSchedule,
    /// Refresh tiles still to draw after the last change of camera or light.
    pub refresh_left: u32,
    pub readback: CounterReadback,
}

impl TemporalEffect {
    /// The effect's images at `config`'s size; its refresh tile is the largest within the
    /// refresh budget (`temporal::budget_tile`) for an effect sampled as `sampling`.
    pub fn new(
        ctx: &Arc<Context>,
        kind: EffectKind,
        config: &RenderConfig,
        sampling: Sampling,
    ) -> Result<Self> {
        let (width, height) = (config.width, config.height);
        let t = &config.temporal;
        let tile = budget_tile(
            kind.refresh_tile,
            sampling,
            (width, height),
            t.rotation_limit,
            t.refresh_budget,
        );
        let image = |suffix: &str, format| {
            Image::new(
                ctx,
                &format!("{}.{suffix}", kind.name),
                ImageDesc {
                    width,
                    height,
                    format,
                    usage: STORAGE_READ,
                },
            )
        };
        let side = 1u32 << kind.block_shift;
        // Blocks are listed by 16x16 reprojection groups, so count whole groups (single
        // pixels: every pixel).
        let max_blocks = width.div_ceil(16) * height.div_ceil(16) * (16 / side) * (16 / side);
        let longest = if side == 1 {
            (width * height).div_ceil(64)
        } else {
            max_blocks
        };
        counters::check_list_dispatch(ctx, kind.name, longest)?;
        // Fix-ups: every pixel at most; then every low-resolution sample at most.
        let (fixups, lowres) = if kind.fixups {
            (width * height, width.div_ceil(2) * height.div_ceil(2))
        } else {
            (0, 0)
        };
        Ok(Self {
            kind,
            history: PingPong::new([
                image("history.0", kind.history_format)?,
                image("history.1", kind.history_format)?,
            ]),
            moments: PingPong::new([
                image("moments.0", MOMENTS_FORMAT)?,
                image("moments.1", MOMENTS_FORMAT)?,
            ]),
            registration: PingPong::new([
                image("registration.0", REGISTRATION_FORMAT)?,
                image("registration.1", REGISTRATION_FORMAT)?,
            ]),
            state: image("state", STATE_FORMAT)?,
            counters: counters::create_gpu_buffer(
                ctx,
                &format!("{}.counters", kind.name),
                max_blocks,
                fixups as u64 + lowres as u64,
            )?,
            max_blocks,
            lowres_list: max_blocks + fixups,
            schedule: RefreshSchedule::with_tile(width, height, tile),
            refresh_left: 0,
            readback: CounterReadback::new(ctx, FRAMES_IN_FLIGHT)?,
        })
    }

    /// This frame's push constants; `pattern` is the frame's pattern index. A refresh tile is
    /// drawn only while the history is reused (`reusing`) and tiled refresh is on, and only
    /// where it serves (the refresh rule, docs/techniques.md, "Refresh only where it serves"):
    /// - on every frame the camera moved (`camera_moved`): each reprojection resamples the
    ///   history, and the tiles bound how long a value drifts (Nehab et al. 2007). With the
    ///   camera still the reprojection is the identity, nothing drifts, and the tiles stop;
    /// - after a change whose stale values nothing else restarts (`cover`,
    ///   `FrameInfo::refresh_cover`): tiles run until every pixel has been in a tile's core
    ///   once (`RefreshSchedule::frames_to_cover`), then stop.
    ///
    /// Pixels not yet converged need no tile: they keep accumulating by themselves.
    pub fn frame_push(
        &mut self,
        reusing: bool,
        refresh: Refresh,
        pattern: u32,
        camera_moved: bool,
        cover: bool,
    ) -> EffectPush {
        // Below 4 pixels a tile has no core inside its feather: tiles that small replace.
        let feathered = refresh == Refresh::Feathered && self.schedule.tile() >= 4;
        let on = reusing && refresh != Refresh::Off && self.schedule.tile() > 0;
        if !on {
            self.refresh_left = 0;
        } else if cover {
            self.refresh_left = self.schedule.frames_to_cover(feathered);
        }
        let draw = on && (camera_moved || self.refresh_left > 0);
        let tile = draw.then(|| {
            self.refresh_left = self.refresh_left.saturating_sub(1);
            self.schedule.next_tile(feathered)
        });
        // An empty rectangle: no refresh this frame. A feather of 0: hard tiles.
        let r = tile.unwrap_or_default();
        EffectPush {
            refresh_rect: [r.x0, r.y0, r.x1, r.y1],
            refresh_feather: if feathered {
                self.schedule.feather()
            } else {
                0
            },
            history_valid: reusing as u32,
            block_shift: self.kind.block_shift,
            pattern,
        }
    }

    pub fn reset_counters(&self, rec: &Recorder<'_>, tracker: &mut Tracker) {
        counters::record_reset(
            rec,
            tracker,
            &self.counters,
            self.max_blocks,
            self.lowres_list,
        );
    }

    /// Copy this frame's counters for reading when `slot` comes round again.
    pub fn copy_counters(&mut self, rec: &Recorder<'_>, tracker: &mut Tracker, slot: usize) {
        self.readback
            .record_copy(rec, tracker, &self.counters, slot, self.kind.counters);
    }
}
