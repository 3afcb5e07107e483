//! `ssgi render`: frames offscreen, the last one (and optionally every target) as PNG.

use super::common::{check_frames, context_options, finish, load};
use crate::cli::args::{Cli, RenderArgs, SceneArgs};
use crate::error::Result;
use crate::files::{prepare_dir, prepare_png};
use crate::frontend::headless;
use crate::frontend::sink::Offscreen;
use crate::renderer::Renderer;
use crate::scene::CameraPath;
use crate::vk::Context;
use std::sync::Arc;

pub fn render(cli: &Cli, args: &RenderArgs) -> Result<()> {
    check_frames(args.frames, "--frames")?;
    prepare_png(&args.out, "--out")?;
    if let Some(dir) = &args.dump_gbuffer {
        prepare_dir(dir, "--dump-gbuffer")?;
    }
    let frames = args.frames.max(1);
    let Setup {
        ctx,
        mut renderer,
        path,
    } = setup(cli, &args.scene)?;
    headless::run(
        &mut renderer,
        &mut Offscreen,
        &path,
        frames,
        args.scene.fps,
        true,
    )?;
    headless::write_output(&mut renderer, &args.out)?;
    eprintln!("wrote {}", args.out.display());
    if let Some(dir) = &args.dump_gbuffer {
        let files = headless::dump_targets(&mut renderer, dir)?;
        eprintln!("wrote {} targets to {}", files.len(), dir.display());
    }
    drop(renderer);
    finish(&ctx)
}

/// What the render job starts from.
struct Setup {
    ctx: Arc<Context>,
    renderer: Renderer,
    path: CameraPath,
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
