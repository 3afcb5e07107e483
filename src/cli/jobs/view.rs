//! `ssgi view`: the interactive window, and the hidden test flags (`--script`, `--capture`).

use super::common::{check_frames, context_options, finish, load};
use crate::cli::args::{Cli, ViewArgs};
use crate::error::{Error, Result};
use crate::frontend::png::write_rgba8;
use crate::frontend::window::{self, WindowOptions, WindowRun};
use crate::renderer::Renderer;

pub fn view(cli: &Cli, args: &ViewArgs) -> Result<()> {
    if let Some(frames) = args.frames {
        check_frames(frames.min(u32::MAX as u64 + 1) as u32, "--frames")?;
    }
    let script = match &args.script {
        Some(s) => window::parse_script(s).map_err(Error::Config)?,
        None => Vec::new(),
    };
    if let Some(path) = &args.capture {
        crate::files::prepare_png(path, "--capture")?;
    }
    let (scene, _path) = load(cli, &args.scene)?;
    let config = args.scene.render_config();
    let run = window::run(
        WindowOptions {
            title: format!("ssgi view: {}", scene.name),
            size: args.scene.size,
            frames: args.frames,
            script,
            capture: args.capture.clone(),
            overlay: args.overlay,
            render_scale: args.render_scale,
            screenshot_dir: args.screenshot_dir.clone(),
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
        write_rgba8(path, data.width, data.height, &rgba)?;
        eprintln!("wrote {}", path.display());
    }
    let WindowRun { ctx, renderer, .. } = run;
    drop(renderer);
    finish(&ctx)
}
