//! What a run renders: size, effects and their parameters. Parsed from the command line,
//! validated here (absurd values get a clear error, never a silent clamp).

pub mod antialias;
pub mod parse;
pub mod pcf;
pub mod sweep_key;

use crate::effects::ao::config::AoConfig;
use crate::effects::ccipca::config::CcipcaConfig;
pub use crate::effects::indirect::config::{IndirectConfig, IndirectFilter, IndirectInput};
use crate::effects::ssdo::config::SsdoConfig;
use crate::effects::svgf::config::SvgfConfig;
use crate::error::{Error, Result};
pub use antialias::{AaConfig, AaMode};
use pcf::Pcf;
use serde::Serialize;

/// Most patterns per pixel (rotation limit) and most estimates in a capped mean. The fp32
/// history counts exactly far beyond it; the bound is the refresh, which evaluates every
/// pattern of a pixel in one invocation (llvmpipe caps loop iterations per invocation and GPU
/// drivers reset devices on long dispatches).
pub const MAX_PATTERNS: u32 = 2048;

/// Frames the CPU may record ahead of the GPU.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// Largest accepted image side: well above any real display, small enough that a typo like
/// `--size 100000x100000` fails with a clear message instead of an allocation error.
pub const MAX_SIZE: u32 = 16384;

/// Which effects are recorded. Disabled effects cost nothing: their passes are not recorded
/// and the composite permutation without them is used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Effects {
    pub direct: bool,
    pub ao: bool,
    /// One-bounce indirect light from the reflective shadow map.
    pub indirect: bool,
    /// Screen-space directional occlusion and its near-field bounce (Szentandrasi); it darkens
    /// the ambient light as AO does, so the two are exclusive.
    pub ssdo: bool,
    /// Debug: each pixel's shading normal as radiance (`effects/normals/`).
    pub normals: bool,
}

impl Effects {
    /// The thesis's effects (`all`).
    pub const ALL: Effects = Effects {
        direct: true,
        ao: true,
        indirect: true,
        ssdo: false,
        normals: false,
    };
    pub const NONE: Effects = Effects {
        direct: false,
        ao: false,
        indirect: false,
        ssdo: false,
        normals: false,
    };

    /// The `--effects` names, each a switch of its own (`all` is [`Effects::ALL`]). The
    /// registry's `Registration::switch` names which of them turns an effect on.
    pub const NAMES: [&'static str; 5] = ["direct", "ao", "indirect", "ssdo", "normals"];

    fn flag_mut(&mut self, name: &str) -> Option<&mut bool> {
        Some(match name {
            "direct" => &mut self.direct,
            "ao" => &mut self.ao,
            "indirect" => &mut self.indirect,
            "ssdo" => &mut self.ssdo,
            "normals" => &mut self.normals,
            _ => return None,
        })
    }

    /// Whether the switch `name` is on (false for a name that is not one).
    pub fn has(&self, name: &str) -> bool {
        let mut copy = *self;
        copy.flag_mut(name).is_some_and(|on| *on)
    }

    /// Turn the switch `name` on or off; an unknown name is an error naming the known ones.
    pub fn set(&mut self, name: &str, on: bool) -> std::result::Result<(), String> {
        let flag = self.flag_mut(name).ok_or_else(|| {
            format!(
                "unknown effect {name:?} in --effects (known: {}, all)",
                Effects::NAMES.join(", ")
            )
        })?;
        *flag = on;
        Ok(())
    }

    /// Comma-separated list of [`Effects::NAMES`], or `all` (the thesis's three).
    pub fn parse(s: &str) -> std::result::Result<Effects, String> {
        let mut e = Effects::NONE;
        for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            if part == "all" {
                e.direct = true;
                e.ao = true;
                e.indirect = true;
            } else {
                e.set(part, true)?;
            }
        }
        if e == Effects::NONE {
            return Err("--effects selects nothing (use e.g. direct,ao,indirect)".into());
        }
        Ok(e)
    }
}

/// The `--effects` list that selects exactly these: `direct,ao`.
impl std::fmt::Display for Effects {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let on: Vec<&str> = Effects::NAMES.into_iter().filter(|n| self.has(n)).collect();
        f.write_str(&on.join(","))
    }
}

/// How the G-buffer is made (`--gbuffer`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum GBufferMode {
    /// One raster pass writes every G-buffer target (40 bytes per pixel).
    #[default]
    Raster,
    /// The raster pass writes each pixel's triangle (4 bytes; albedo too in a scene with
    /// textures) and a compute pass rebuilds the targets from the triangles' vertices: for
    /// GPUs whose raster output is narrow (needs gl_PrimitiveID: the geometryShader feature).
    Visibility,
}

impl GBufferMode {
    /// Whether the G-buffer is a visibility buffer and its resolve.
    pub fn visibility(self) -> bool {
        self == GBufferMode::Visibility
    }
}

/// Nehab et al.'s tiled refresh: one tile per frame recomputed from scratch (the mean of every
/// pattern), and how the recomputed tile meets its neighbours.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Refresh {
    /// Converged pixels are reused until they are disoccluded.
    Off,
    /// The default: the recomputed tile is blended into the history along a ramp a quarter tile
    /// wide, on a grid shifted by half a tile from cycle to cycle, so a tile whose neighbours
    /// drifted under motion leaves no seam.
    #[value(alias = "on")]
    Feathered,
    /// The thesis's: the recomputed tile replaces the history (seams under motion, Figure 4.4).
    Hard,
}

/// How a fresh estimate is merged into the reprojected history.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "mode", rename_all = "lowercase")]
pub enum Accumulate {
    /// The default: the running mean of every pattern (what the refresh computes, so refreshed
    /// tiles and accumulated pixels hold the same estimator), restarted from the fresh estimate
    /// when it differs from the mean by more than `sigmas` standard deviations of the patterns
    /// seen so far and by more than `Accumulate::GATE_RELATIVE` of the larger value: a change
    /// of the lighting, not noise. Converges to the mean of the patterns in a static view.
    Gated { sigmas: f32 },
    /// Lin 2013 eqs 4-5 as written: confidence = 1 - saturate(|V_old - V_new|) / (1 + bias)
    /// (for RGB, the difference relative to the larger of the two values' norms). Its fixed
    /// point is where E[|X - V| (X - V)] = 0, not the mean: biased towards early patterns.
    Confidence { bias: f32 },
    /// Exponential moving average with a fixed weight on the new estimate.
    Ema { alpha: f32 },
    /// Cumulative mean over at most `cap` estimates.
    Mean { cap: u32 },
}

impl Accumulate {
    /// Default gate of the running mean: 4 standard deviations of the patterns.
    pub const GATED: Accumulate = Accumulate::Gated { sigmas: 4.0 };
    /// Relative floor of the gate (shaders/include/temporal.glsl `GATE_RELATIVE`): changes
    /// below a quarter of the value never restart the mean, so one PCF tap in nine (0.11) or
    /// an AO sample flipping cannot, even where every earlier pattern agreed (zero variance).
    pub const GATE_RELATIVE: f32 = 0.25;
    /// Default bias of eq 4. The thesis leaves it to the user; 0.1 keeps confidence <= 0.91 for
    /// a full-range difference and ~1 for small ones.
    pub const CONFIDENCE: Accumulate = Accumulate::Confidence { bias: 0.1 };
    /// Default weight of the new estimate in ema mode (`--ema-alpha`, `ema` in a sweep).
    pub const EMA_ALPHA: f32 = 0.1;

    /// The frame block's `accumulate_mode`: ACCUMULATE_* of shared_constants.glsl.
    pub fn code(&self) -> u32 {
        use crate::shaders::{
            ACCUMULATE_CONFIDENCE, ACCUMULATE_EMA, ACCUMULATE_GATED, ACCUMULATE_MEAN,
        };
        match self {
            Accumulate::Confidence { .. } => ACCUMULATE_CONFIDENCE,
            Accumulate::Ema { .. } => ACCUMULATE_EMA,
            Accumulate::Mean { .. } => ACCUMULATE_MEAN,
            Accumulate::Gated { .. } => ACCUMULATE_GATED,
        }
    }

    pub fn parameter(&self) -> f32 {
        match *self {
            Accumulate::Gated { sigmas } => sigmas,
            Accumulate::Confidence { bias } => bias,
            Accumulate::Ema { alpha } => alpha,
            Accumulate::Mean { cap } => cap as f32,
        }
    }
}

/// Disocclusion threshold of eq 3.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "mode", rename_all = "lowercase")]
pub enum Epsilon {
    /// `scale` pixel footprints at the pixel's distance, divided by |cos| of the view angle:
    /// the distance between neighbouring texels on that surface, so it is independent of the
    /// scene's units and of depth.
    Relative { scale: f32 },
    /// The thesis's absolute world-space threshold (0.1 and 0.01 in Figure 3.1).
    Absolute { epsilon: f32 },
}

impl Epsilon {
    /// Two texel spacings: the nearest previous texel is at most ~0.71 spacings away for a
    /// surface that was visible, so 2 leaves margin for interpolation and fp16 noise.
    pub const DEFAULT: Epsilon = Epsilon::Relative { scale: 2.0 };

    /// The `Frame` block's `epsilon` and `epsilon_absolute` (1: world-space).
    pub fn shader_params(self) -> (f32, u32) {
        match self {
            Epsilon::Relative { scale } => (scale, 0),
            Epsilon::Absolute { epsilon } => (epsilon, 1),
        }
    }
}

/// How a moving camera reads a history between texels (reproject.comp).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum HistoryResample {
    /// The default: the bilinear blend of the four texels around the previous position. Each
    /// frame mixes neighbouring values again, so an ageing history drifts from the estimator's
    /// own converged value towards a smoother one, which on the box:bunny orbit is nearer the
    /// ground truth (docs/results/DECISIONS.md (lavapipe-orbit-resample-2026-12-03)).
    Bilinear,
    /// Of the four texels, the one whose carried surface point lands nearest the pixel, as it
    /// is (value, counts and point): no smear along the flow, the estimator's own value, but
    /// counts no longer borrow from neighbours, so more pixels accumulate (slower).
    Point,
}

impl HistoryResample {
    /// The frame block's `history_resample`: HISTORY_RESAMPLE_* of shared_constants.glsl.
    pub fn code(self) -> u32 {
        match self {
            HistoryResample::Point => crate::shaders::HISTORY_RESAMPLE_POINT,
            HistoryResample::Bilinear => crate::shaders::HISTORY_RESAMPLE_BILINEAR,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TemporalConfig {
    /// Reverse-reprojection reuse; off = recompute every frame with a fixed pattern and blur.
    pub reuse: bool,
    pub accumulate: Accumulate,
    /// Patterns per pixel before it counts as converged: 360 / 10 degrees in the thesis.
    pub rotation_limit: u32,
    pub epsilon: Epsilon,
    pub refresh: Refresh,
    /// Most pattern evaluations the refresh may spend per frame, as a fraction of a full
    /// frame's (every pixel, one pattern): the refresh tile's side follows from it
    /// (`temporal::budget_tile`).
    pub refresh_budget: f32,
    pub resample: HistoryResample,
    /// Drop histories where a change reaches them (`--invalidate`): a moved light or a
    /// re-rendered RSM restarts what depends on them, a moving object what lies within the
    /// effect's reach of it (shaders/reproject.comp). Off: only disocclusion and the gate.
    pub invalidate: bool,
    /// Re-accumulate when the camera stops (`--reaccumulate`): every reused history, which the
    /// reprojection resampled while the camera moved, takes the rotation limit's patterns
    /// afresh on the frames after the camera comes to rest, its resampled value fading out
    /// one pattern's share per frame (shaders/reproject.comp), so the still view converges to
    /// what a render from scratch shows. Gated accumulation only (the others are no running
    /// mean of the patterns to begin with).
    pub reaccumulate: bool,
}

/// Threads sharing out one refresh-tile pixel's patterns (shaders/include/refresh.glsl),
/// defined in shaders/include/shared_constants.glsl.
pub use crate::shaders::REFRESH_THREADS;

/// The default refresh budget: 5% of a full frame's evaluations.
pub const REFRESH_BUDGET: f32 = 0.05;
/// The largest: 100 frames' work, enough for the thesis's tiles (a 64x64 tile with 36
/// patterns is 2.25 frames of a 256x256 image, 36 of a 64x64 one).
pub const MAX_REFRESH_BUDGET: f32 = 100.0;

impl Default for TemporalConfig {
    fn default() -> Self {
        Self {
            reuse: true,
            accumulate: Accumulate::GATED,
            rotation_limit: 36,
            epsilon: Epsilon::DEFAULT,
            refresh: Refresh::Feathered,
            refresh_budget: REFRESH_BUDGET,
            resample: HistoryResample::Bilinear,
            invalidate: true,
            reaccumulate: true,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RenderConfig {
    pub width: u32,
    pub height: u32,
    /// Side of the (square) reflective shadow map / shadow map.
    pub rsm_size: u32,
    pub pcf: Pcf,
    pub effects: Effects,
    pub ao: AoConfig,
    pub indirect: IndirectConfig,
    pub ccipca: CcipcaConfig,
    pub svgf: SvgfConfig,
    pub ssdo: SsdoConfig,
    pub temporal: TemporalConfig,
    pub aa: AaConfig,
    pub gbuffer: GBufferMode,
    /// Record nothing for a frame whose inputs (camera, light, configuration) are those of
    /// the last two and whose temporal effects have converged: its output is the last one.
    pub skip_unchanged: bool,
}

impl Default for RenderConfig {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            rsm_size: 512,
            pcf: Pcf::DEFAULT,
            effects: Effects::ALL,
            ao: AoConfig::default(),
            indirect: IndirectConfig::default(),
            ccipca: CcipcaConfig::default(),
            svgf: SvgfConfig::default(),
            ssdo: SsdoConfig::default(),
            temporal: TemporalConfig::default(),
            aa: AaConfig::default(),
            gbuffer: GBufferMode::Raster,
            skip_unchanged: true,
        }
    }
}

impl RenderConfig {
    /// The configuration the frame renders at: `width` x `height` are the output's, times
    /// the supersampling factor of `--aa ssaa16` (every target, effect and constant uses it;
    /// only the final image has the output size).
    pub fn rendered(&self) -> RenderConfig {
        let scale = self.aa.mode.supersampling();
        RenderConfig {
            width: self.width * scale,
            height: self.height * scale,
            ..*self
        }
    }

    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Config(m));
        for (what, v) in [
            ("width", self.width),
            ("height", self.height),
            ("shadow map size", self.rsm_size),
        ] {
            if v == 0 || v > MAX_SIZE {
                return bad(format!("{what} {v} is outside 1..={MAX_SIZE}"));
            }
        }
        self.aa.validate()?;
        let scale = self.aa.mode.supersampling();
        if scale > 1 && self.width.max(self.height) * scale > MAX_SIZE {
            return bad(format!(
                "--aa ssaa16 renders {}x{}, past the largest size {MAX_SIZE}",
                self.width * scale,
                self.height * scale
            ));
        }
        self.ao.validate()?;
        self.ssdo
            .validate(self.effects.ssdo, self.effects.ao, self.temporal.reuse)?;
        self.indirect.validate()?;
        self.ccipca.validate()?;
        self.svgf.validate()?;
        if self.indirect.vpls == 0 && self.rsm_size > 128 {
            return bad(format!(
                "--vpls all gathers every RSM texel: use --rsm-size 128 or less (got {})",
                self.rsm_size
            ));
        }
        if self.effects.indirect
            && self.indirect.filter == IndirectFilter::Accumulate
            && self.temporal.reuse
            && self.temporal.refresh != Refresh::Off
            && self.indirect.vpls as u64
                * self.temporal.rotation_limit.div_ceil(REFRESH_THREADS) as u64
                > 32768
        {
            return bad(format!(
                "each refresh thread gathers {} VPLs x {} of the {} patterns; keep the product at \
                 most 32768",
                self.indirect.vpls,
                self.temporal.rotation_limit.div_ceil(REFRESH_THREADS),
                self.temporal.rotation_limit
            ));
        }
        let t = &self.temporal;
        if !(1..=MAX_PATTERNS).contains(&t.rotation_limit) {
            return bad(format!(
                "rotation limit {} outside 1..={MAX_PATTERNS} (the refresh evaluates every \
                 pattern of a pixel at once)",
                t.rotation_limit
            ));
        }
        if !(t.refresh_budget.is_finite()
            && t.refresh_budget > 0.0
            && t.refresh_budget <= MAX_REFRESH_BUDGET)
        {
            return bad(format!(
                "refresh budget {} must be a share of a frame's work in (0, {MAX_REFRESH_BUDGET}]                  (5% = 0.05)",
                t.refresh_budget
            ));
        }
        match t.accumulate {
            Accumulate::Gated { sigmas } if !(sigmas.is_finite() && sigmas > 0.0) => {
                return bad(format!(
                    "gate {sigmas} must be finite and > 0 standard deviations"
                ))
            }
            Accumulate::Confidence { bias } if !(bias.is_finite() && bias >= 0.0) => {
                return bad(format!("confidence bias {bias} must be finite and >= 0"))
            }
            Accumulate::Ema { alpha } if !(alpha > 0.0 && alpha <= 1.0) => {
                return bad(format!("EMA alpha {alpha} must be in (0, 1]"))
            }
            Accumulate::Mean { cap } if !(1..=MAX_PATTERNS).contains(&cap) => {
                return bad(format!(
                    "mean cap {cap} outside 1..={MAX_PATTERNS} (the rotation limit's bound)"
                ))
            }
            _ => {}
        }
        match t.epsilon {
            Epsilon::Relative { scale } if !(scale.is_finite() && scale > 0.0) => {
                bad(format!("relative epsilon {scale} must be finite and > 0"))
            }
            Epsilon::Absolute { epsilon } if !(epsilon.is_finite() && epsilon > 0.0) => {
                bad(format!("absolute epsilon {epsilon} must be finite and > 0"))
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refresh_loops_stay_short_per_thread() {
        let mut c = RenderConfig::default();
        c.indirect.vpls = 16384;
        // 64 patterns: one per refresh thread; 128: two.
        c.temporal.rotation_limit = 64;
        assert!(c.validate().is_ok());
        c.temporal.rotation_limit = 128;
        assert!(c.validate().is_ok());
        c.temporal.rotation_limit = 129;
        let e = c.validate().unwrap_err().to_string();
        assert!(
            e.contains("each refresh thread gathers 16384 VPLs x 3"),
            "{e}"
        );
        // Without refresh no loop gathers more than one pattern.
        c.temporal.refresh = Refresh::Off;
        assert!(c.validate().is_ok());
    }

    #[test]
    fn absurd_counts_gates_and_step_sizes_are_rejected() {
        let ok = RenderConfig::default();
        assert!(ok.validate().is_ok());
        let mut c = ok;
        // (Indirect light also bounds VPLs x rotation limit; leave it out here.)
        c.effects.indirect = false;
        c.temporal.rotation_limit = MAX_PATTERNS;
        assert!(c.validate().is_ok());
        c.temporal.rotation_limit = MAX_PATTERNS + 1;
        assert!(c.validate().unwrap_err().to_string().contains("refresh"));
        let mut c = ok;
        c.temporal.accumulate = Accumulate::Mean { cap: 100_000 };
        assert!(c.validate().is_err());
        c.temporal.accumulate = Accumulate::Mean { cap: 0 };
        assert!(c.validate().is_err());
        for sigmas in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            c.temporal.accumulate = Accumulate::Gated { sigmas };
            assert!(c.validate().is_err(), "gate {sigmas}");
        }
        for near in [0.0, -1.0, f32::NAN, f32::INFINITY, 1000.0] {
            let mut c = ok;
            c.ao.near_px = near;
            assert!(c.validate().is_err(), "near_px {near}");
        }
        for (interleave, vpls, valid) in [(0, 512, false), (9, 512, false), (8, 64, true)] {
            let mut c = ok;
            (c.indirect.interleave, c.indirect.vpls) = (interleave, vpls);
            assert_eq!(c.validate().is_ok(), valid, "interleave {interleave}");
        }
        // Every pixel of a block needs at least one VPL of its own.
        let mut c = ok;
        (c.indirect.interleave, c.indirect.vpls) = (4, 15);
        assert!(c.validate().unwrap_err().to_string().contains("4x4"));
        c.indirect.vpls = 0; // every RSM texel (with a small enough map)
        c.rsm_size = 64;
        assert!(c.validate().is_ok());
    }

    #[test]
    fn the_list_parses_back() {
        for s in [
            "direct",
            "direct,ao",
            "ao,indirect",
            "direct,ao,indirect",
            "direct,ssdo",
        ] {
            let e = Effects::parse(s).unwrap();
            assert_eq!(e.to_string(), s);
            assert_eq!(Effects::parse(&e.to_string()).unwrap(), e);
        }
    }
}
