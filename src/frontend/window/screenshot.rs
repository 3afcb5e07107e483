//! The viewer's screenshot key: the presented frame as PNG (overlay included, as shown) and
//! the last second's GPU timings as JSON in the bench report format (docs/formats.md), side
//! by side in `--screenshot-dir`, named by the frame number.

use crate::bench::measure::{report_config, RunLength};
use crate::bench::report::Report;
use crate::bench::warmup::Outcome;
use crate::error::{Error, Result};
use crate::frontend::png::write_rgba8;
use crate::passes::PassId;
use crate::renderer::Renderer;
use crate::scene::CameraPath;
use crate::vk::{Context, FrameTiming, ImageData};
use std::path::{Path, PathBuf};

/// Write `image` and the report of `timings` (spanning `seconds`) as `view-<frame>.png` and
/// `view-<frame>.json` in `dir`; returns both paths.
pub fn write(
    dir: &Path,
    frame: u64,
    image: &ImageData,
    report: &Report,
) -> Result<(PathBuf, PathBuf)> {
    let png = dir.join(format!("view-{frame:06}.png"));
    let json = dir.join(format!("view-{frame:06}.json"));
    let rgba = image.rgba8().ok_or_else(|| {
        Error::Window(format!(
            "cannot write a {:?} swapchain image as PNG",
            image.format
        ))
    })?;
    write_rgba8(&png, image.width, image.height, &rgba)?;
    let text = serde_json::to_string_pretty(report)
        .map_err(|e| Error::Config(format!("JSON encoding failed: {e}")))?;
    crate::files::write_atomic(&json, text.as_bytes())?;
    Ok((png, json))
}

/// The bench report of the viewer's last second: every timed frame is measured (no warmup),
/// the path is the fly camera, `fps` the rate the frames came at.
pub fn report(
    ctx: &Context,
    renderer: &Renderer,
    timings: &[FrameTiming],
    seconds: f64,
    present_mode: &'static str,
) -> Report {
    let frames = timings.len() as u32;
    let fps = if seconds > 0.0 {
        (frames as f64 / seconds) as f32
    } else {
        0.0
    };
    let mut config = report_config(
        ctx,
        renderer,
        &CameraPath::Static,
        RunLength {
            fps,
            frames,
            warmup: Outcome {
                mode: "frames",
                frames: 0,
                settled: true,
            },
        },
        Some(present_mode),
    );
    config["path"] = "view (fly camera)".into();
    config["seconds"] = seconds.into();
    let mut names: Vec<&str> = crate::renderer::all_passes()
        .iter()
        .map(|p| p.name())
        .collect();
    names.push(PassId::OVERLAY.name());
    let first = timings.first().map_or(0, |t| t.frame);
    Report::new(
        &ctx.info,
        renderer.config.width,
        renderer.config.height,
        config,
        &names,
        timings,
        first,
    )
}
