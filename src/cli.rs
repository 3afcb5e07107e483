//! Command-line definitions and the `render` / `bench` jobs (the binary only dispatches).

use crate::bench::Report;
use crate::error::{Error, Result};
use crate::frontend::headless;
use crate::passes::PassId;
use crate::renderer::frame::Pcf;
use crate::renderer::{RenderConfig, Renderer, MAX_SIZE};
use crate::scene::{asset_dir_from_env, load_scene, CameraPath};
use crate::vk::{Context, ContextOptions};
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
}

/// Frame counts above this are almost certainly a typo (a day at 1000 fps is 8.6e7).
const MAX_FRAMES: u32 = 10_000_000;

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

fn setup(cli: &Cli, args: &SceneArgs) -> Result<Setup> {
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
    let ctx = Context::new(&ContextOptions {
        validation: cli.validation,
        device: cli.device.clone(),
        verbose: true,
        ..Default::default()
    })?;
    let config = RenderConfig {
        width: args.size.0,
        height: args.size.1,
        rsm_size: args.rsm_size,
        pcf: args.pcf,
    };
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
    headless::run(&mut renderer, &path, frames, true)?;
    headless::write_output(&mut renderer, &args.out)?;
    eprintln!("wrote {}", args.out.display());
    if let Some(dir) = &args.dump_gbuffer {
        let files = headless::dump_targets(&mut renderer, dir)?;
        eprintln!("wrote {} targets to {}", files.len(), dir.display());
    }
    drop(renderer);
    finish(&ctx)
}

pub fn bench(cli: &Cli, args: &BenchArgs) -> Result<()> {
    check_frames(args.frames, "--frames")?;
    check_frames(args.warmup, "--warmup")?;
    if args.frames == 0 {
        return Err(Error::Config("--frames must be at least 1".into()));
    }
    let Setup {
        ctx,
        mut renderer,
        path,
    } = setup(cli, &args.scene)?;
    let total = args.frames + args.warmup;
    let timings = headless::run(&mut renderer, &path, total, true)?;
    let config = serde_json::json!({
        "scene": args.scene.scene,
        "path": path.name(),
        "frames": args.frames,
        "warmup": args.warmup,
        "rsm_size": args.scene.rsm_size,
        "pcf_samples": args.scene.pcf.samples(),
        "pcf_radius_texels": args.scene.pcf.radius_texels,
        "device_type": ctx.info.device_type,
        "api_version": ctx.info.api_version,
        "triangles": renderer.scene.mesh.indices.len() / 3,
    });
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
        if let Some(dir) = json.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|source| Error::Io {
                path: dir.to_path_buf(),
                source,
            })?;
        }
        let text = serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Config(format!("JSON encoding failed: {e}")))?;
        std::fs::write(json, text).map_err(|source| Error::Io {
            path: json.clone(),
            source,
        })?;
        eprintln!("wrote {}", json.display());
    }
    if let Some(out) = &args.out {
        headless::write_output(&mut renderer, out)?;
        eprintln!("wrote {}", out.display());
    }
    drop(renderer);
    finish(&ctx)
}
