//! What the jobs share: loading the scene and camera path, the context options of
//! `--validation` / `--device`, the frame-count guard, and the final validation check.

use crate::cli::args::{Cli, SceneArgs};
use crate::error::{Error, Result};
use crate::scene::{
    asset_dir_from_env, load_scene_with_paths, CameraPath, LightPath, LoadedScene, Scene,
};
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

/// The scene and camera path of a run: everything before the GPU. The light flags apply to
/// the scene's light; `--save-scene` writes the result.
pub(super) fn load(cli: &Cli, args: &SceneArgs) -> Result<(Scene, CameraPath)> {
    let mut loaded = load_with_paths(cli, &args.scene)?;
    let scene = &mut loaded.scene;
    let bounds = scene.mesh.bounds;
    if let Some(l) = args.light {
        scene.light = scene.light.placed(l.position, l.target, &bounds);
    }
    if let Some((inner, outer)) = args.light_cone {
        scene.light.inner_deg = inner;
        scene.light.outer_deg = outer;
    }
    if let Some(i) = args.light_intensity {
        crate::scene::check_intensity(i, scene.bounds().radius())
            .map_err(|why| Error::Config(format!("--light-intensity {why}")))?;
        scene.light.intensity = i.into();
    }
    match args.light_path.as_deref() {
        Some("none") => scene.light_path = None,
        Some(file) => {
            let path = LightPath::from_file(std::path::Path::new(file))?;
            // The shadow map reaches the whole scene from every key.
            for k in path.keys() {
                let placed = scene
                    .light
                    .placed(k.position.into(), k.target.into(), &bounds);
                (scene.light.near, scene.light.far) = (placed.near, placed.far);
            }
            scene.light_path = Some(path);
        }
        None => {}
    }
    let path = match &args.path {
        Some(p) => CameraPath::parse(p)?,
        None => loaded.camera_path.clone().unwrap_or(CameraPath::Static),
    };
    loaded.camera_path = Some(path.clone());
    if let Some(out) = &args.save_scene {
        crate::files::write_atomic(out, loaded.describe().to_toml().as_bytes())?;
        eprintln!("wrote {}", out.display());
    }
    Ok((loaded.scene, path))
}

/// The scene `spec` and camera path `path` (warnings about the model printed).
pub(super) fn load_spec(cli: &Cli, spec: &str, path: &str) -> Result<(Scene, CameraPath)> {
    let scene = load_with_paths(cli, spec)?.scene;
    let path = CameraPath::parse(path)?;
    Ok((scene, path))
}

/// A scene spec or file with the paths it brings (warnings about the model printed).
fn load_with_paths(cli: &Cli, spec: &str) -> Result<LoadedScene> {
    let assets = cli.assets.clone().or_else(asset_dir_from_env);
    let loaded = load_scene_with_paths(spec, assets.as_deref())?;
    let scene = &loaded.scene;
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
    Ok(loaded)
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
