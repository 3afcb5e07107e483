//! What the command line accepts: the clap definitions of every subcommand and their value
//! parsers. Checks that need more than one flag, or the scene, happen in the jobs.

use crate::bench::warmup::Warmup;
pub use crate::config::parse::{
    parse_bias, parse_ema_alpha, parse_epsilon, parse_fraction, parse_gate, parse_on_off,
    parse_pattern_count, parse_render_scale, parse_vpls, AccumulateMode,
};
use crate::config::pcf::Pcf;
use crate::config::{
    Accumulate, Effects, Epsilon, GBufferMode, HistoryResample, Refresh, TemporalConfig,
};
use crate::effects::ao::config::{AoConfig, AoEstimator};
use crate::effects::EffectArgs;
use crate::post::PostArgs;
use crate::renderer::{RenderConfig, MAX_SIZE};
use crate::scene::HUGE_COORDINATE;
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "ssgi",
    version,
    about = "Screen-space global illumination renderer and benchmark (Vulkan)"
)]
pub struct Cli {
    /// Enable the Vulkan validation layers with synchronization validation; any validation
    /// message makes the command exit non-zero.
    #[arg(long, global = true)]
    pub validation: bool,
    /// Use the first Vulkan device whose name contains this text (case-insensitive). Default:
    /// a discrete GPU, else integrated, virtual, CPU; the choice is printed.
    #[arg(long, global = true, value_name = "NAME")]
    pub device: Option<String>,
    /// Directory holding the scene models (default: $SSGI_ASSETS).
    #[arg(long, global = true, value_name = "DIR")]
    pub assets: Option<PathBuf>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render frames offscreen and write the last one as PNG.
    Render(RenderArgs),
    /// Run a camera path and report per-pass GPU times (table + JSON).
    Bench(BenchArgs),
    /// Open a window with a fly camera (press F1 in the window for the keys).
    View(ViewArgs),
    /// Reproduce one of the papers' tables (or the dynamic scene's): report.md, report.json,
    /// CSV and PNG files in --out.
    Table(TableArgs),
    /// Ray-trace the ground truth of one frame on the CPU (no GPU): AO, direct light, shadow,
    /// one-bounce indirect light and the final image, as OpenEXR + PNG previews in --out.
    Reference(ReferenceArgs),
    /// Run every combination of --vary values in one process and put run time against error
    /// (ground truth and converged estimator): sweep.csv/json/md and scatter plots in --out.
    Sweep(SweepArgs),
    /// Numerical-stability matrix: extreme scales, depth ranges, cameras and lights in awkward
    /// places, degenerate geometry, tiny sizes, rotation-limit bounds and a long jittering run,
    /// under every effect set and both reuse modes, with validation on. Every target and
    /// history is checked for NaN/Inf/negative values on the GPU; exits non-zero on any
    /// failure. stress.json and stress.md in --out.
    Stress(StressArgs),
}

#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// Built-in scene (cornell-box, pyramids, tilted-quad), an OBJ path, an asset name (e.g. bunny),
    /// box:<path-or-asset> for a model in a box room, or a scene file (.toml; see scenes/).
    #[arg(long, default_value = "cornell-box")]
    pub scene: String,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "512x512", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Camera path: static, orbit[:SECONDS] (one turn per 12 s by default), dolly[:SECONDS]
    /// (6 s), or a keyframe file (.json / .toml, times in seconds). Default: the scene file's
    /// camera path, else static.
    #[arg(long)]
    pub path: Option<String>,
    /// Frame rate of path time: frame i shows the path at i / fps seconds, so the motion per
    /// frame does not depend on how many frames a run has.
    #[arg(long, default_value_t = crate::scene::path::DEFAULT_FPS, value_parser = parse_fps)]
    pub fps: f32,
    /// Shadow filtering: `hard`; 9 = the thesis's 9-sample disc, rotated and scaled every frame
    /// and accumulated with reuse (filling the disc uniformly over frames); another square (25, 49, ...) = a regular grid every frame;
    /// disc:N = an N-sample disc.
    #[arg(long, default_value = "49", value_parser = parse_pcf)]
    pub pcf: Pcf,
    /// Side of the reflective shadow map / shadow map in texels.
    #[arg(long, default_value_t = 512)]
    pub rsm_size: u32,
    /// Place the spot light: POSITION:TARGET, each x,y,z in world units (e.g.
    /// 0,1.9,0.5:0,0,0). Keeps the scene light's intensity, colour and cone; its shadow map
    /// reaches the whole scene from there
    #[arg(long, value_parser = parse_light)]
    pub light: Option<LightPlacement>,
    /// The spot's cone: INNER:OUTER half-angles in degrees (0 < inner <= outer <= 89), or
    /// OUTER alone (inner = 0.8 x outer).
    #[arg(long, value_parser = parse_light_cone, value_name = "INNER:OUTER")]
    pub light_cone: Option<(f32, f32)>,
    /// The spot's radiant intensity on its axis (W/sr): one value for white or R,G,B; at most
    /// 1e7 x the scene's bounding radius squared.
    #[arg(long, value_parser = parse_light_intensity, value_name = "I|R,G,B")]
    pub light_intensity: Option<[f32; 3]>,
    /// Move the light along a keyframe file (.json / .toml, as --path's: time, position,
    /// target), or `none` to hold the scene file's moving light still.
    #[arg(long, value_name = "FILE|none")]
    pub light_path: Option<String>,
    /// Write the scene as run (after --light and the other light flags) as a scene file with
    /// every value explicit, to edit or to load again with --scene.
    #[arg(long, value_name = "FILE")]
    pub save_scene: Option<PathBuf>,
    #[arg(long, default_value = "all", value_parser = parse_effects, help = effects_help())]
    pub effects: Effects,
    /// Temporal reuse (reverse reprojection cache): on, or off for the no-reuse baseline
    /// (fixed pattern every frame + 5x5 Gaussian blur).
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub reuse: bool,
    /// How fresh estimates merge into the history: gated (running mean of the patterns,
    /// restarted on a change beyond --gate standard deviations), confidence (eqs 4-5 as the
    /// thesis writes them), ema, mean.
    #[arg(long, value_enum, default_value = "gated")]
    pub accumulate: AccumulateMode,
    /// Restart threshold of the gated mean, in standard deviations of the patterns (> 0).
    #[arg(long, default_value_t = 4.0, value_parser = parse_gate)]
    pub gate: f32,
    /// Bias of eq 4 (confidence mode), finite and >= 0.
    #[arg(long, default_value_t = 0.1, value_parser = parse_bias)]
    pub bias: f32,
    /// Weight of the new estimate (ema mode), in (0, 1].
    #[arg(long, default_value_t = Accumulate::EMA_ALPHA, value_parser = parse_ema_alpha)]
    pub ema_alpha: f32,
    /// Most estimates averaged (mean mode; default: the rotation limit), 1..=2048.
    #[arg(long, value_parser = parse_pattern_count)]
    pub mean_cap: Option<u32>,
    /// Patterns per pixel before it counts as converged (thesis: 36 = 360 / 10 degrees),
    /// 1..=2048.
    #[arg(long, default_value_t = 36, value_parser = parse_pattern_count)]
    pub rotation_limit: u32,
    /// Disocclusion threshold of eq 3: a number = multiples of the pixel footprint
    /// (scale-free, default 2), or abs:<world units> for the thesis's absolute epsilon.
    #[arg(long, default_value = "2", value_parser = parse_epsilon)]
    pub epsilon: Epsilon,
    /// Tiled refresh: one tile per frame recomputed from scratch (at most 64x64 for AO and
    /// shadows, 16x16 for indirect light, smaller where --refresh-budget requires);
    /// `feathered` (or `on`) blends it in along a quarter-tile ramp on a grid shifted by half a
    /// tile each cycle, `hard` replaces it outright (the thesis).
    #[arg(long, value_enum, default_value_t = Refresh::Feathered)]
    pub refresh: Refresh,
    /// Most work the refresh may spend per frame, as a share of a full frame's pattern
    /// evaluations: `5%` or `0.05` (up to 100 frames' worth, e.g. 225% for the thesis's 64x64
    /// tiles at 256x256).
    #[arg(long, default_value = "5%", value_parser = parse_fraction)]
    pub refresh_budget: f32,
    /// Drop histories where a change reaches them: a moved light restarts the effects that
    /// read the light, a light view rendered again (something moved in the light's sight)
    /// those that read the RSM, a moving object each effect's pixels within its reach (its
    /// radius or the shadow map's footprint). `off`: only disocclusion and the gate react.
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub invalidate: bool,
    /// Re-accumulate when the camera stops: the histories the moving camera resampled take
    /// every pattern afresh over the next frames (their old value fading out a pattern's share
    /// per frame), so a still view ends where a render from scratch does. `off`: a still view
    /// keeps what the motion left (cheaper, not the estimator's own value).
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub reaccumulate: bool,
    /// How a moving camera reads a history between texels: `bilinear` blends the four around
    /// the previous position, `point` takes the one whose carried surface point lands nearest
    /// the pixel (the estimator's own value, no smear, more pixels accumulating).
    #[arg(long, value_enum, default_value_t = HistoryResample::Bilinear)]
    pub history_resample: HistoryResample,
    /// How the G-buffer is made: `raster` (one raster pass writes every target) or
    /// `visibility` (the raster pass writes each pixel's triangle, a compute pass rebuilds the
    /// targets: for GPUs whose raster output is narrow; the same image within float rounding).
    #[arg(long, value_enum, default_value_t = GBufferMode::Raster)]
    pub gbuffer: GBufferMode,
    /// Record nothing for a frame whose camera, light and configuration are those of the last
    /// two frames once every temporal effect has converged (its output is the last one).
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub skip_unchanged: bool,
    /// The post stages' options (the post registry's `PostArgs`: `--aa` and each stage's).
    #[command(flatten)]
    pub post_options: PostArgs,
    /// Each effect's own options (the registry's `EffectArgs`).
    #[command(flatten)]
    pub effect_options: EffectArgs,
}

impl SceneArgs {
    /// The renderer configuration these flags describe (validated by the renderer).
    pub fn render_config(&self) -> RenderConfig {
        let accumulate = match self.accumulate {
            AccumulateMode::Gated => Accumulate::Gated { sigmas: self.gate },
            AccumulateMode::Confidence => Accumulate::Confidence { bias: self.bias },
            AccumulateMode::Ema => Accumulate::Ema {
                alpha: self.ema_alpha,
            },
            AccumulateMode::Mean => Accumulate::Mean {
                cap: self.mean_cap.unwrap_or(self.rotation_limit),
            },
        };
        let mut config = RenderConfig {
            width: self.size.0,
            height: self.size.1,
            rsm_size: self.rsm_size,
            pcf: self.pcf,
            effects: self.effects,
            temporal: TemporalConfig {
                reuse: self.reuse,
                accumulate,
                rotation_limit: self.rotation_limit,
                epsilon: self.epsilon,
                refresh: self.refresh,
                refresh_budget: self.refresh_budget,
                resample: self.history_resample,
                invalidate: self.invalidate,
                reaccumulate: self.reaccumulate,
            },
            gbuffer: self.gbuffer,
            skip_unchanged: self.skip_unchanged,
            // The effects' and post stages' parts: set from their own options below.
            ..RenderConfig::default()
        };
        self.effect_options.apply(&mut config);
        self.post_options.apply(&mut config);
        config
    }
}

fn parse_frame_count_u64(s: &str) -> std::result::Result<u64, String> {
    parse_frame_count(s).map(u64::from)
}

/// `--long-frames`: 1 to 10 million.
fn parse_long_frames(s: &str) -> std::result::Result<u64, String> {
    match s.parse::<u64>() {
        Ok(n) if (1..=10_000_000).contains(&n) => Ok(n),
        _ => Err(format!(
            "--long-frames takes a frame count in 1..=10000000, not {s:?}"
        )),
    }
}

/// Frames per second of path time: finite, in (0, 10000].
pub fn parse_fps(s: &str) -> std::result::Result<f32, String> {
    match s.parse::<f32>() {
        Ok(f) if f.is_finite() && f > 0.0 && f <= 10000.0 => Ok(f),
        _ => Err(format!("--fps must be a number in (0, 10000], not {s:?}")),
    }
}

/// A frame count of a run: at least 1 (a run of no frames has nothing to write or report).
fn parse_frame_count(s: &str) -> std::result::Result<u32, String> {
    match s.parse::<u32>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!("--frames must be at least 1, not {s:?}")),
    }
}

fn parse_effects(s: &str) -> std::result::Result<Effects, String> {
    Effects::parse(s)
}

/// `--effects`' help, from the switches and the registry's ambient effects.
fn effects_help() -> String {
    format!(
        "Effects to render, comma-separated: {} (all = direct, ao, indirect). At most one of \
         {} (each darkens the ambient light)",
        Effects::NAMES.join(", "),
        crate::effects::ambient_switches().join(", ")
    )
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames to render (the last one is written), at least 1.
    #[arg(long, default_value_t = 1, value_parser = parse_frame_count)]
    pub frames: u32,
    /// Output PNG.
    #[arg(long, default_value = "out/render.png")]
    pub out: PathBuf,
    /// Also write every G-buffer and RSM target as PNG into this directory.
    #[arg(long, value_name = "DIR")]
    pub dump_gbuffer: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames measured after warmup, at least 1.
    #[arg(long, default_value_t = 200, value_parser = parse_frame_count)]
    pub frames: u32,
    /// Frames rendered first along the path and left out of the statistics: a count, or
    /// `converged` (until the per-frame computed-pixel counters settle, at most 600 frames),
    /// so the measured frames are the cache's steady state at the path's speed.
    #[arg(long, default_value = "10", value_parser = crate::bench::warmup::parse_warmup)]
    pub warmup: Warmup,
    /// Write the report as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Write the last frame as PNG here.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Present every frame to a window (present mode immediate, else mailbox, else fifo).
    #[arg(long)]
    pub window: bool,
    /// Run the path twice in this process, with reuse on and off, and report both with the
    /// speed-up ratios (overrides --reuse).
    #[arg(long)]
    pub compare_reuse: bool,
    /// Print which change makes each pass run again (the dependency table `--skip-unchanged`
    /// follows) before running.
    #[arg(long)]
    pub explain_skips: bool,
    /// Print the frame as data and exit without measuring: every pass of the path's second
    /// frame (the first with a history), in recording order, with the images and buffers its
    /// declaration reads, writes and updates, and the passes it left out and why.
    #[arg(long)]
    pub explain: bool,
    /// Read the output (and indirect light) back after every measured frame and report the
    /// flicker measure: each frame's mean squared RGB difference from the one before, in
    /// `frames[]` and summarized (Chen et al.: barely notable below 2.5e-5). Waits for every
    /// frame, so frames no longer overlap.
    #[arg(long)]
    pub flicker: bool,
}

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Scene and renderer options; `--size` is the initial window size, `--path` is unused.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Exit by itself after this many presented frames (at least 1).
    #[arg(long, value_parser = parse_frame_count_u64)]
    pub frames: Option<u64>,
    /// The overlay over the frame: GPU time per pass and group (median and p95 over the last
    /// second), counters, device; `H` hides it. `off` draws none (no `overlay` timing row).
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub overlay: bool,
    /// Render at this fraction of the window's size (0.1 to 1); the presented image is
    /// scaled up to the window. The overlay's settings change it live.
    #[arg(long, default_value_t = 1.0, value_parser = parse_render_scale)]
    pub render_scale: f32,
    /// Where F12 writes the presented frame (`view-<frame>.png`) and the last second's GPU
    /// timings in the bench report format (`view-<frame>.json`).
    #[arg(long, value_name = "DIR", default_value = "out/view")]
    pub screenshot_dir: PathBuf,
    /// Test script: FRAME:resize=WxH, FRAME:zero=N, FRAME:key=NAME, comma-separated.
    #[arg(long, hide = true)]
    pub script: Option<String>,
    /// Write the last presented frame, read back from the swapchain, as PNG (needs --frames).
    #[arg(long, hide = true)]
    pub capture: Option<PathBuf>,
}

/// The tables' names for clap, each with its one-line summary, from the tables' registry.
fn table_names() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(
        crate::bench::tables::TABLES
            .map(|t| clap::builder::PossibleValue::new(t.name).help(t.summary)),
    )
}

#[derive(Args, Debug)]
pub struct TableArgs {
    /// Which table.
    #[arg(value_parser = table_names())]
    pub table: String,
    /// Output directory for report.md, report.json, CSV and PNG files (default out/<table>).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Image size, WIDTHxHEIGHT (default 512x512; szentandrasi-1: the paper's 1024x768).
    #[arg(long, value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Frames measured per row along the camera path, at least 1 (default 120;
    /// szentandrasi-1: 20).
    #[arg(long, value_parser = parse_frame_count)]
    pub frames: Option<u32>,
    /// Frames rendered first and left out of the statistics: N held at the path's first
    /// camera, or `converged`: three rotation limits of frames along the path before its
    /// time 0, so the measured frames see the cache's moving steady state (default 10;
    /// szentandrasi-1, which has no cache: 2).
    #[arg(long, value_parser = crate::bench::warmup::parse_warmup)]
    pub warmup: Option<Warmup>,
    /// Frame rate of path time (frame i at i / fps seconds along the path).
    #[arg(long, default_value_t = crate::scene::path::DEFAULT_FPS, value_parser = parse_fps)]
    pub fps: f32,
    /// thesis-4.1: static, orbit, dolly, or a keyframe file, for all four scenes (default:
    /// paths/box.json, compiled in). thesis-walkthroughs: a directory holding sponza.json,
    /// sibenik.json and conference.json (default: those of paths/, compiled in).
    /// szentandrasi-1: a path for all three scenes (default static, as the paper measured).
    #[arg(long, value_name = "P")]
    pub path: Option<String>,
    /// Effects to render, comma-separated: direct, ao, indirect (or all; the default). Leaving
    /// one out drops its columns (e.g. `direct,ao` on a slow device). Not for the tables whose
    /// rows choose theirs (szentandrasi-1).
    #[arg(long, value_parser = Effects::parse)]
    pub effects: Option<Effects>,
    /// Present every frame to a window (present mode immediate, else mailbox, else fifo) and
    /// time that; Escape or closing the window aborts the table.
    #[arg(long)]
    pub window: bool,
    /// KEY=VALUE: a parameter every row uses in place of its default, with `ssgi sweep`'s keys
    /// and values (repeatable). Each table accepts the keys of the techniques it compares that
    /// its rows do not set themselves (chang-flicker: svgf.* and ccipca.*; ao: ao.samples,
    /// ao.steps, ao.position_mips, ao.moving_denoise); the report lists them.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

/// `--light POSITION:TARGET`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPlacement {
    pub position: glam::Vec3,
    pub target: glam::Vec3,
}

pub fn parse_light(s: &str) -> std::result::Result<LightPlacement, String> {
    let point = |part: &str, what: &str| -> std::result::Result<glam::Vec3, String> {
        let v: Vec<f32> = part
            .split(',')
            .map(|c| c.trim().parse::<f32>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| format!("--light: the {what} {part:?} is not x,y,z"))?;
        match v.as_slice() {
            [x, y, z] if v.iter().all(|c| c.is_finite() && c.abs() <= HUGE_COORDINATE) => {
                Ok(glam::Vec3::new(*x, *y, *z))
            }
            [_, _, _] => Err(format!(
                "--light: the {what} {part:?} must be finite, at most {HUGE_COORDINATE:e} from the origin on each axis"
            )),
            _ => Err(format!("--light: the {what} {part:?} is not x,y,z")),
        }
    };
    let (position, target) = s
        .split_once(':')
        .ok_or_else(|| format!("--light takes POSITION:TARGET like 0,1.9,0:0,0,0, not {s:?}"))?;
    let (position, target) = (point(position, "position")?, point(target, "target")?);
    if position == target {
        return Err(format!(
            "--light: the position and the target are the same point ({position}): no direction"
        ));
    }
    Ok(LightPlacement { position, target })
}

/// `--light-cone INNER:OUTER` or `OUTER`.
pub fn parse_light_cone(s: &str) -> std::result::Result<(f32, f32), String> {
    let angle = |t: &str| -> std::result::Result<f32, String> {
        match t.trim().parse::<f32>() {
            Ok(a) if a.is_finite() && a > 0.0 && a <= 89.0 => Ok(a),
            _ => Err(format!(
                "--light-cone: {t:?} is not an angle in (0, 89] degrees"
            )),
        }
    };
    let (inner, outer) = match s.split_once(':') {
        Some((i, o)) => (angle(i)?, angle(o)?),
        None => {
            let o = angle(s)?;
            (0.8 * o, o)
        }
    };
    if inner > outer {
        return Err(format!(
            "--light-cone: the inner angle {inner} is wider than the outer {outer}"
        ));
    }
    Ok((inner, outer))
}

/// `--light-intensity I` or `R,G,B`: finite, >= 0 (the bound for the scene's size is
/// checked with the scene, `scene::max_intensity`).
pub fn parse_light_intensity(s: &str) -> std::result::Result<[f32; 3], String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|c| c.trim().parse::<f32>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| format!("--light-intensity takes I or R,G,B, not {s:?}"))?;
    let rgb = match v.as_slice() {
        [i] => [*i; 3],
        [r, g, b] => [*r, *g, *b],
        _ => return Err(format!("--light-intensity takes I or R,G,B, not {s:?}")),
    };
    if !rgb.iter().all(|c| c.is_finite() && *c >= 0.0) {
        return Err(format!("--light-intensity: {s:?} must be finite and >= 0"));
    }
    Ok(rgb)
}

fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT like 512x512, got {s:?}"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in {s:?}"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in {s:?}"))?;
    if w == 0 || h == 0 || w > MAX_SIZE || h > MAX_SIZE {
        return Err(format!(
            "size {w}x{h} is outside 1..={MAX_SIZE} on each side"
        ));
    }
    Ok((w, h))
}

fn parse_pcf(s: &str) -> std::result::Result<Pcf, String> {
    Pcf::parse(s)
}

#[derive(Args, Debug)]
pub struct ReferenceArgs {
    /// Built-in scene, OBJ path, asset name or box:<model>, as for render.
    #[arg(long, default_value = "cornell-box")]
    pub scene: String,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "256x256", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Camera path: static, orbit[:SECONDS] (one turn per 12 s by default), dolly[:SECONDS]
    /// (6 s), or a keyframe file (.json / .toml, times in seconds).
    #[arg(long, default_value = "static")]
    pub path: String,
    /// Frame rate of path time: frame i shows the path at i / fps seconds, so the motion per
    /// frame does not depend on how many frames a run has.
    #[arg(long, default_value_t = crate::scene::path::DEFAULT_FPS, value_parser = parse_fps)]
    pub fps: f32,
    /// Frames of the run the reference belongs to (the path's timing), at least 1.
    #[arg(long, default_value_t = 1, value_parser = parse_frame_count)]
    pub frames: u32,
    /// Frame of the path to trace, 0-based (default: the last of --frames).
    #[arg(long)]
    pub frame: Option<u32>,
    /// AO radius as a fraction of the scene's bounding radius (the renderer's --ao radius).
    #[arg(long, default_value_t = AoConfig::default().radius, value_parser = parse_ao_radius)]
    pub ao_radius: f32,
    /// AO attenuation D(x) = 1 + a x + b x^2 as A:B (eq 7; the renderer's --ao-attenuation and
    /// its default 0:1).
    #[arg(long, default_value = "0:1", value_parser = parse_attenuation, value_name = "A:B")]
    pub ao_attenuation: [f32; 2],
    /// Radius of a spherical light for soft shadows, world units (0: the point light).
    #[arg(long, default_value_t = 0.0, value_parser = parse_light_radius)]
    pub light_radius: f32,
    /// AO rays per pixel (split into two halves for the standard error), 2..=131072.
    #[arg(long, default_value_t = 2 * crate::reference::trace::DEFAULT_AO_SAMPLES, value_parser = parse_reference_samples)]
    pub ao_samples: u32,
    /// Indirect-light paths per pixel (two rays each), 2..=131072.
    #[arg(long, default_value_t = 2 * crate::reference::trace::DEFAULT_INDIRECT_SAMPLES, value_parser = parse_reference_samples)]
    pub indirect_samples: u32,
    /// Shadow rays per pixel towards the spherical light (ignored for the point light).
    #[arg(long, default_value_t = 2 * crate::reference::trace::DEFAULT_SOFT_SHADOW_SAMPLES, value_parser = parse_reference_samples)]
    pub shadow_samples: u32,
    /// Output directory.
    #[arg(long, default_value = "out/reference")]
    pub out: PathBuf,
    /// Reference cache directory (default: $SSGI_CACHE/reference, else
    /// $XDG_CACHE_HOME/ssgi/reference, else ~/.cache/ssgi/reference).
    #[arg(long, value_name = "DIR")]
    pub cache_dir: Option<PathBuf>,
    /// Trace from scratch and do not read or write the cache.
    #[arg(long)]
    pub no_cache: bool,
}

fn parse_ao_radius(s: &str) -> std::result::Result<f32, String> {
    match s.parse::<f32>() {
        Ok(r) if r.is_finite() && r > 0.0 && r <= 10.0 => Ok(r),
        _ => Err(format!(
            "--ao-radius takes a fraction of the scene radius in (0, 10], not {s:?}"
        )),
    }
}

/// `reference --ao-attenuation`: the renderer's syntax, A:B.
fn parse_attenuation(s: &str) -> std::result::Result<[f32; 2], String> {
    crate::config::parse::parse_attenuation(s)
        .map_err(|why| format!("--ao-attenuation takes A:B for D(x) = 1 + A x + B x^2 ({why})"))
}

fn parse_light_radius(s: &str) -> std::result::Result<f32, String> {
    match s.parse::<f32>() {
        Ok(r) if r.is_finite() && r >= 0.0 => Ok(r),
        _ => Err(format!(
            "--light-radius takes a finite radius >= 0, not {s:?}"
        )),
    }
}

fn parse_reference_samples(s: &str) -> std::result::Result<u32, String> {
    let max = 2 * crate::reference::run::MAX_SAMPLES_PER_HALF;
    match s.parse::<u32>() {
        Ok(n) if (2..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "a reference sample count is in 2..={max} (two halves), not {s:?}"
        )),
    }
}

#[derive(Args, Debug)]
pub struct SweepArgs {
    /// The base configuration; --vary overrides its keys.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames measured per combination along the path, at least 1.
    #[arg(long, default_value_t = 60, value_parser = parse_frame_count)]
    pub frames: u32,
    /// Frames before measuring: N frames held at the path's first camera (default: the
    /// rotation limit + 4, every pattern accumulated once), or `converged`: three rotation
    /// limits of frames along the path before its time 0, so the cache enters the measured
    /// frames in its moving steady state (reported per combination: settled or not).
    #[arg(long, value_parser = crate::bench::warmup::parse_warmup)]
    pub warmup: Option<Warmup>,
    /// KEY=V1,V2,...: a configuration key and its values (repeatable; every combination runs,
    /// the first --vary outermost). `ssgi sweep --list-keys` lists the keys.
    #[arg(long = "vary", value_name = "KEY=VALUES")]
    pub vary: Vec<String>,
    /// Print the keys --vary accepts and exit.
    #[arg(long)]
    pub list_keys: bool,
    /// Output directory.
    #[arg(long, default_value = "out/sweep")]
    pub out: PathBuf,
    /// Reference cache directory (as for `ssgi reference`).
    #[arg(long, value_name = "DIR")]
    pub cache_dir: Option<PathBuf>,
    /// Trace the ground truth from scratch and do not read or write the cache.
    #[arg(long)]
    pub no_cache: bool,
}

#[derive(Args, Debug)]
pub struct StressArgs {
    /// The quick subset: every kind of case at its small end, the variants taken in turn
    /// (what the tests run).
    #[arg(long)]
    pub quick: bool,
    /// Frames of the long jittering run, 1..=10000000 (default 100000; 2000 with --quick).
    #[arg(long, value_parser = parse_long_frames)]
    pub long_frames: Option<u64>,
    /// Only the cases whose name contains this text (e.g. scale, size, long).
    #[arg(long, value_name = "TEXT")]
    pub only: Option<String>,
    /// Side of the shadow map / RSM in texels.
    #[arg(long, default_value_t = 256)]
    pub rsm_size: u32,
    /// The AO estimator of every variant with AO (e.g. `gtao` to stress ground-truth AO).
    #[arg(long = "ao", value_enum, default_value = "thesis")]
    pub ao_estimator: AoEstimator,
    /// Output directory.
    #[arg(long, default_value = "out/stress")]
    pub out: PathBuf,
}
