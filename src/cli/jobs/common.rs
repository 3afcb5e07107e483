//! What the jobs share: loading the scene and camera path, the context options of
//! `--validation` / `--device`, the frame-count guard, and the final validation check.

use crate::cli::args::{Cli, SceneArgs};
use crate::error::{Error, Result};
use crate::scene::{asset_dir_from_env, load_scene, CameraPath, Scene};
use crate::vk::{Context, ContextOptions};

/// Frame counts above this are almost certainly a typo (a day at 1000 fps is 8.6e7).
const MAX_FRAMES: u32 = 10_000_000;

pub(super) fn check_frames(frames: u32, what: &str) -> Result<()> {
    if frames > MAX_FRAMES {
        return Err(Error::Config(format!(
            "{what} {frames} is more than {MAX_FRAMES}"
        )));
    }
    Ok(())
}

/// The scene and camera path of a run: everything before the GPU.
pub(super) fn load(cli: &Cli, args: &SceneArgs) -> Result<(Scene, CameraPath)> {
    let (mut scene, path) = load_spec(cli, &args.scene, &args.path)?;
    if let Some(l) = args.light {
        scene.light = scene.light.placed(l.position, l.target, &scene.mesh.bounds);
    }
    Ok((scene, path))
}

/// The scene `spec` and camera path `path` (warnings about the model printed).
pub(super) fn load_spec(cli: &Cli, spec: &str, path: &str) -> Result<(Scene, CameraPath)> {
    let assets = cli.assets.clone().or_else(asset_dir_from_env);
    let scene = load_scene(spec, assets.as_deref())?;
    for w in &scene.mesh.stats.warnings {
        eprintln!("warning: {w}");
    }
    let stats = &scene.mesh.stats;
    if stats.dropped_zero_area > 0 {
        eprintln!(
            "note: dropped {} zero-area triangles (repeated or collinear corners)",
            stats.dropped_zero_area
        );
    }
    if stats.dropped_slivers > 0 {
        eprintln!(
            "note: dropped {} slivers thinner than float precision of their longest edge",
            stats.dropped_slivers
        );
    }
    let path = CameraPath::parse(path)?;
    Ok((scene, path))
}

/// The context every command starts from: `--validation`, `--device`, the device printed.
pub(super) fn context_options(cli: &Cli) -> ContextOptions {
    ContextOptions {
        validation: cli.validation,
        device: cli.device.clone(),
        verbose: true,
        ..Default::default()
    }
}

/// Wait for the GPU, then fail the command if the validation layers said anything.
pub(super) fn finish(ctx: &Context) -> Result<()> {
    ctx.wait_idle()?;
    match ctx.validation() {
        Some(log) => log.check(),
        None => Ok(()),
    }
}
