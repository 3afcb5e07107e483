//! Scripted runs: render a camera path (offscreen or into a presenting window), collect GPU
//! timings, write PNGs.

use super::png::{visualize, write_rgba8};
use super::progress::Progress;
use super::sink::FrameSink;
use crate::error::Result;
use crate::renderer::Renderer;
use crate::resources::targets::Target;
use crate::scene::path::frame_time;
use crate::scene::CameraPath;
use crate::vk::FrameTiming;
use std::path::Path;

/// Render `frames` frames along `path` into `sink`, frame i at i / `fps` seconds; returns every
/// frame's GPU timing in frame order.
pub fn run(
    renderer: &mut Renderer,
    sink: &mut dyn FrameSink,
    path: &CameraPath,
    frames: u32,
    fps: f32,
    progress: bool,
) -> Result<Vec<FrameTiming>> {
    run_from(renderer, sink, path, 0..frames, fps, progress, &mut |_| {
        Ok(())
    })
}

/// As [`run`], starting at frame `first` of the path (after a warmup of `first` frames).
pub fn run_from(
    renderer: &mut Renderer,
    sink: &mut dyn FrameSink,
    path: &CameraPath,
    frames: std::ops::Range<u32>,
    fps: f32,
    progress: bool,
    after_frame: &mut dyn FnMut(&mut Renderer) -> Result<()>,
) -> Result<Vec<FrameTiming>> {
    let base = renderer.scene.camera;
    let orbit = renderer.scene.orbit();
    let mut timings = Vec::with_capacity(frames.len());
    let mut bar = Progress::new(frames.len() as u64, "rendering", progress);
    sink.begin(&renderer.scene.name);
    // Each frame polls for Ctrl-C: a signal stops the run between frames.
    let _scope = crate::interrupt::graceful();
    for i in frames {
        let camera = path.camera_at(&base, &orbit, frame_time(i, fps));
        renderer.set_time(frame_time(i, fps));
        timings.extend(sink.frame(renderer, &camera)?);
        after_frame(renderer)?;
        bar.inc();
    }
    timings.extend(renderer.finish()?);
    bar.finish();
    Ok(timings)
}

/// Write the tonemapped output image.
pub fn write_output(renderer: &mut Renderer, path: &Path) -> Result<()> {
    let data = renderer.read(Target::Output)?;
    let rgba = visualize(Target::Output, &data, &renderer.scene.mesh.bounds);
    write_rgba8(path, data.width, data.height, &rgba)
}

/// Write every target of the run (G-buffer, RSM, effect buffers) as `<dir>/<name>.png`; the
/// buffers of effects that are off do not exist and are left out.
pub fn dump_targets(renderer: &mut Renderer, dir: &Path) -> Result<Vec<std::path::PathBuf>> {
    let mut written = Vec::new();
    let present: Vec<Target> = crate::effects::all_targets()
        .into_iter()
        .filter(|t| renderer.has_target(*t))
        .collect();
    for target in present {
        let data = renderer.read(target)?;
        let rgba = visualize(target, &data, &renderer.scene.mesh.bounds);
        let path = dir.join(format!("{}.png", target.name()));
        write_rgba8(&path, data.width, data.height, &rgba)?;
        written.push(path);
    }
    Ok(written)
}
