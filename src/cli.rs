//! Command-line definitions and the `render` / `bench` jobs (the binary only dispatches).

use crate::bench::compare::Comparison;
use crate::bench::Report;
use crate::error::{Error, Result};
use crate::frontend::headless;
use crate::frontend::sink::{self, FrameSink, Offscreen};
use crate::frontend::window::{self, WindowOptions, WindowRun};
use crate::passes::PassId;
use crate::renderer::config::{
    Accumulate, AoConfig, AoEstimator, Effects, Epsilon, IndirectConfig, TemporalConfig,
};
use crate::renderer::frame::Pcf;
use crate::renderer::{RenderConfig, Renderer, MAX_SIZE};
use crate::scene::{asset_dir_from_env, load_scene, CameraPath, Scene};
use crate::vk::{Context, ContextOptions};
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use std::sync::Arc;

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
    /// Use the first Vulkan device whose name contains this text (case-insensitive).
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
    /// Open a window with a fly camera (press H in the window for the keys).
    View(ViewArgs),
    /// Reproduce a thesis table: report.md, report.json, CSV and PNG plots in --out.
    Table(crate::bench::cli::TableArgs),
}

#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// Built-in scene (cornell-box, pyramids), an OBJ path, an asset name (e.g. bunny), or
    /// box:<path-or-asset> for a model in a box room.
    #[arg(long, default_value = "cornell-box")]
    pub scene: String,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "512x512", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Camera path: static, orbit, dolly, or a keyframe file (.json / .toml).
    #[arg(long, default_value = "static")]
    pub path: String,
    /// Shadow filtering: `hard` or a square PCF sample count (9, 25, 49, ...).
    #[arg(long, default_value = "49", value_parser = parse_pcf)]
    pub pcf: Pcf,
    /// Side of the reflective shadow map / shadow map in texels.
    #[arg(long, default_value_t = 512)]
    pub rsm_size: u32,
    /// Effects to render, comma-separated: direct, ao (or all).
    #[arg(long, default_value = "all", value_parser = parse_effects)]
    pub effects: Effects,
    /// Temporal reuse (reverse reprojection cache): on, or off for the no-reuse baseline
    /// (fixed pattern every frame + 5x5 Gaussian blur).
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub reuse: bool,
    /// SSAO estimator.
    #[arg(long = "ao", value_enum, default_value = "thesis")]
    pub ao_estimator: AoEstimator,
    /// SSAO samples per pattern (thesis: 8 directions x 4 steps for 32).
    #[arg(long, default_value_t = 32)]
    pub ao_samples: u32,
    /// How fresh estimates merge into the history: confidence (eqs 4-5), ema, mean.
    #[arg(long, value_enum, default_value = "confidence")]
    pub accumulate: AccumulateMode,
    /// Bias of eq 4 (confidence mode).
    #[arg(long, default_value_t = 0.1)]
    pub bias: f32,
    /// Weight of the new estimate (ema mode).
    #[arg(long, default_value_t = 0.1)]
    pub ema_alpha: f32,
    /// Most estimates averaged (mean mode; default: the rotation limit).
    #[arg(long)]
    pub mean_cap: Option<u32>,
    /// Patterns per pixel before it counts as converged (thesis: 36 = 360 / 10 degrees).
    #[arg(long, default_value_t = 36)]
    pub rotation_limit: u32,
    /// Disocclusion threshold of eq 3: a number = multiples of the pixel footprint
    /// (scale-free, default 2), or abs:<world units> for the thesis's absolute epsilon.
    #[arg(long, default_value = "2", value_parser = parse_epsilon)]
    pub epsilon: Epsilon,
    /// VPLs gathered per pixel and frame for indirect light (`all`: every RSM texel).
    #[arg(long, default_value = "512", value_parser = parse_vpls)]
    pub vpls: u32,
    /// Screen-space visibility test of each VPL (Lin 2013 section 3.3.1; about halves speed).
    #[arg(long)]
    pub vpl_visibility: bool,
    /// Gather indirect light at half resolution with geometry-aware upsampling.
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub half_res: bool,
    /// Tiled refresh (one 64x64 tile recomputed from scratch per frame).
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub refresh: bool,
}

/// `--accumulate` choices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum AccumulateMode {
    Confidence,
    Ema,
    Mean,
}

impl SceneArgs {
    /// The renderer configuration these flags describe (validated by the renderer).
    pub fn render_config(&self) -> RenderConfig {
        let accumulate = match self.accumulate {
            AccumulateMode::Confidence => Accumulate::Confidence { bias: self.bias },
            AccumulateMode::Ema => Accumulate::Ema {
                alpha: self.ema_alpha,
            },
            AccumulateMode::Mean => Accumulate::Mean {
                cap: self.mean_cap.unwrap_or(self.rotation_limit),
            },
        };
        RenderConfig {
            width: self.size.0,
            height: self.size.1,
            rsm_size: self.rsm_size,
            pcf: self.pcf,
            effects: self.effects,
            ao: AoConfig {
                estimator: self.ao_estimator,
                samples: self.ao_samples,
                ..AoConfig::default()
            },
            indirect: IndirectConfig {
                vpls: self.vpls,
                visibility: self.vpl_visibility,
                half_res: self.half_res,
            },
            temporal: TemporalConfig {
                reuse: self.reuse,
                accumulate,
                rotation_limit: self.rotation_limit,
                epsilon: self.epsilon,
                refresh: self.refresh,
                ..TemporalConfig::default()
            },
        }
    }
}

fn parse_vpls(s: &str) -> std::result::Result<u32, String> {
    if s == "all" {
        return Ok(0);
    }
    match s.parse::<u32>() {
        Ok(n) if (1..=16384).contains(&n) => Ok(n),
        _ => Err(format!(
            "--vpls takes a count in 1..=16384 or `all`, not {s:?}"
        )),
    }
}

fn parse_effects(s: &str) -> std::result::Result<Effects, String> {
    Effects::parse(s)
}

fn parse_on_off(s: &str) -> std::result::Result<bool, String> {
    match s {
        "on" | "yes" | "true" => Ok(true),
        "off" | "no" | "false" => Ok(false),
        _ => Err(format!("expected on or off, got {s:?}")),
    }
}

fn parse_epsilon(s: &str) -> std::result::Result<Epsilon, String> {
    let (abs, number) = match s.strip_prefix("abs:") {
        Some(rest) => (true, rest),
        None => (false, s),
    };
    let v: f32 = number
        .parse()
        .map_err(|_| format!("--epsilon takes a number or abs:<number>, not {s:?}"))?;
    if !(v.is_finite() && v > 0.0) {
        return Err(format!("--epsilon {s}: must be a finite positive number"));
    }
    Ok(if abs {
        Epsilon::Absolute { epsilon: v }
    } else {
        Epsilon::Relative { scale: v }
    })
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames to render (the last one is written).
    #[arg(long, default_value_t = 1)]
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
    /// Frames measured after warmup.
    #[arg(long, default_value_t = 200)]
    pub frames: u32,
    /// Frames rendered first and left out of the statistics.
    #[arg(long, default_value_t = 10)]
    pub warmup: u32,
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
}

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Scene and renderer options; `--size` is the initial window size, `--path` is unused.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Exit by itself after this many presented frames.
    #[arg(long)]
    pub frames: Option<u64>,
    /// Test script: FRAME:resize=WxH, FRAME:zero=N, FRAME:key=NAME, comma-separated.
    #[arg(long, hide = true)]
    pub script: Option<String>,
    /// Write the last presented frame, read back from the swapchain, as PNG (needs --frames).
    #[arg(long, hide = true)]
    pub capture: Option<PathBuf>,
}

/// Frame counts above this are almost certainly a typo (a day at 1000 fps is 8.6e7).
const MAX_FRAMES: u32 = 10_000_000;

pub(crate) fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
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

fn check_frames(frames: u32, what: &str) -> Result<()> {
    if frames > MAX_FRAMES {
        return Err(Error::Config(format!(
            "{what} {frames} is more than {MAX_FRAMES}"
        )));
    }
    Ok(())
}

struct Setup {
    ctx: std::sync::Arc<Context>,
    renderer: Renderer,
    path: CameraPath,
}

/// The scene and camera path of a run: everything before the GPU.
fn load(cli: &Cli, args: &SceneArgs) -> Result<(Scene, CameraPath)> {
    let assets = cli.assets.clone().or_else(asset_dir_from_env);
    let scene = load_scene(&args.scene, assets.as_deref())?;
    for w in &scene.mesh.stats.warnings {
        eprintln!("warning: {w}");
    }
    if scene.mesh.stats.dropped_degenerate > 0 {
        eprintln!(
            "note: dropped {} zero-area triangles",
            scene.mesh.stats.dropped_degenerate
        );
    }
    let path = CameraPath::parse(&args.path)?;
    Ok((scene, path))
}

/// The context every command starts from: `--validation`, `--device`, the device printed.
pub(crate) fn context_options(cli: &Cli) -> ContextOptions {
    ContextOptions {
        validation: cli.validation,
        device: cli.device.clone(),
        verbose: true,
        ..Default::default()
    }
}

fn setup(cli: &Cli, args: &SceneArgs) -> Result<Setup> {
    let (scene, path) = load(cli, args)?;
    let ctx = Context::new(&context_options(cli))?;
    let config = args.render_config();
    let renderer = Renderer::new(&ctx, scene, config)?;
    Ok(Setup {
        ctx,
        renderer,
        path,
    })
}

fn finish(ctx: &Context) -> Result<()> {
    ctx.wait_idle()?;
    match ctx.validation() {
        Some(log) => log.check(),
        None => Ok(()),
    }
}

pub fn render(cli: &Cli, args: &RenderArgs) -> Result<()> {
    check_frames(args.frames, "--frames")?;
    let frames = args.frames.max(1);
    let Setup {
        ctx,
        mut renderer,
        path,
    } = setup(cli, &args.scene)?;
    headless::run(&mut renderer, &mut Offscreen, &path, frames, true)?;
    headless::write_output(&mut renderer, &args.out)?;
    eprintln!("wrote {}", args.out.display());
    if let Some(dir) = &args.dump_gbuffer {
        let files = headless::dump_targets(&mut renderer, dir)?;
        eprintln!("wrote {} targets to {}", files.len(), dir.display());
    }
    drop(renderer);
    finish(&ctx)
}

fn write_json(path: &std::path::Path, value: &impl serde::Serialize) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| Error::Io {
            path: dir.to_path_buf(),
            source,
        })?;
    }
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::Config(format!("JSON encoding failed: {e}")))?;
    std::fs::write(path, text).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// The report's `config` object for a headless or windowed bench run.
fn bench_config(
    args: &BenchArgs,
    ctx: &Context,
    renderer: &Renderer,
    path: &CameraPath,
    sink: &dyn FrameSink,
) -> serde_json::Value {
    serde_json::json!({
        "scene": args.scene.scene,
        "path": path.name(),
        "frames": args.frames,
        "warmup": args.warmup,
        "rsm_size": args.scene.rsm_size,
        "pcf_samples": args.scene.pcf.samples(),
        "pcf_radius_texels": args.scene.pcf.radius_texels,
        "render": renderer.config,
        "device_type": ctx.info.device_type,
        "api_version": ctx.info.api_version,
        "triangles": renderer.scene.mesh.indices.len() / 3,
        "window": sink.present_mode().is_some(),
        "present_mode": sink.present_mode(),
    })
}

/// `bench --compare-reuse`: both configurations on one context, one after the other.
fn bench_compare_reuse(
    args: &BenchArgs,
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    scene: Scene,
    path: CameraPath,
) -> Result<()> {
    let names: Vec<&str> = PassId::ALL.iter().map(|p| p.name()).collect();
    let mut reports = Vec::new();
    for reuse in [true, false] {
        let mut config = args.scene.render_config();
        config.temporal.reuse = reuse;
        let mut renderer = Renderer::new(ctx, scene.clone(), config)?;
        let timings = headless::run(&mut renderer, sink, &path, args.frames + args.warmup, true)?;
        let report = Report::new(
            &ctx.info,
            args.scene.size.0,
            args.scene.size.1,
            bench_config(args, ctx, &renderer, &path, sink),
            &names,
            &timings,
            args.warmup as u64,
        );
        println!("reuse {}:", if reuse { "on" } else { "off" });
        print!("{}", report.table());
        if let (Some(out), true) = (&args.out, reuse) {
            headless::write_output(&mut renderer, out)?;
            eprintln!("wrote {}", out.display());
        }
        reports.push(report);
    }
    let [on, off]: [Report; 2] = reports
        .try_into()
        .map_err(|_| Error::Config("comparison needs two runs".into()))?;
    let comparison = Comparison::new("reuse", ["reuse on", "reuse off"], [on, off]);
    print!("{}", comparison.table());
    if let Some(json) = &args.json {
        write_json(json, &comparison)?;
    }
    Ok(())
}

pub fn bench(cli: &Cli, args: &BenchArgs) -> Result<()> {
    check_frames(args.frames, "--frames")?;
    check_frames(args.warmup, "--warmup")?;
    if args.frames == 0 {
        return Err(Error::Config("--frames must be at least 1".into()));
    }
    let (scene, path) = load(cli, &args.scene)?;
    let window = args.window.then(|| format!("ssgi bench: {}", scene.name));
    let (ctx, mut sink) = sink::open(window, args.scene.size, context_options(cli))?;
    if args.compare_reuse {
        bench_compare_reuse(args, &ctx, sink.as_mut(), scene, path)?;
        drop(sink);
        return finish(&ctx);
    }
    let total = args.frames + args.warmup;
    let mut renderer = Renderer::new(&ctx, scene, args.scene.render_config())?;
    let timings = headless::run(&mut renderer, sink.as_mut(), &path, total, true)?;
    let config = bench_config(args, &ctx, &renderer, &path, sink.as_ref());
    let names: Vec<&str> = PassId::ALL.iter().map(|p| p.name()).collect();
    let report = Report::new(
        &ctx.info,
        args.scene.size.0,
        args.scene.size.1,
        config,
        &names,
        &timings,
        args.warmup as u64,
    );
    print!("{}", report.table());
    if let Some(json) = &args.json {
        write_json(json, &report)?;
    }
    if let Some(out) = &args.out {
        headless::write_output(&mut renderer, out)?;
        eprintln!("wrote {}", out.display());
    }
    drop(renderer);
    drop(sink);
    finish(&ctx)
}

pub fn view(cli: &Cli, args: &ViewArgs) -> Result<()> {
    if let Some(frames) = args.frames {
        check_frames(frames.min(u32::MAX as u64 + 1) as u32, "--frames")?;
    }
    let script = match &args.script {
        Some(s) => window::parse_script(s).map_err(Error::Config)?,
        None => Vec::new(),
    };
    let (scene, _path) = load(cli, &args.scene)?;
    let config = args.scene.render_config();
    let run = window::run(
        WindowOptions {
            title: format!("ssgi view: {}", scene.name),
            size: args.scene.size,
            frames: args.frames,
            script,
            capture: args.capture.clone(),
        },
        context_options(cli),
        move |ctx| Renderer::new(ctx, scene, config),
    )?;
    eprintln!("presented {} frames", run.frames_presented);
    if let Some(path) = &args.capture {
        let data = run
            .captured
            .as_ref()
            .ok_or_else(|| Error::Window("no frame was captured".into()))?;
        let rgba = data.rgba8().ok_or_else(|| {
            Error::Window(format!(
                "cannot write a {:?} swapchain image as PNG",
                data.format
            ))
        })?;
        crate::frontend::png::write_rgba8(path, data.width, data.height, &rgba)?;
        eprintln!("wrote {}", path.display());
    }
    let WindowRun { ctx, renderer, .. } = run;
    drop(renderer);
    finish(&ctx)
}
