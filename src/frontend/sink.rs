//! Where the frames of a scripted run go: offscreen, or presented to a window. Benchmarks and
//! tables render through a [`FrameSink`], so the same loop measures both. The window sink is
//! `window_sink.rs`, which depends on this file, not the other way round.

use crate::error::Result;
use crate::renderer::Renderer;
use crate::scene::Camera;
use crate::vk::FrameTiming;

pub trait FrameSink {
    /// A new run starts (a table row, a bench): `label` names it (window title).
    fn begin(&mut self, label: &str);

    /// Render one frame of `renderer` at `camera`; returns the GPU timings that became
    /// available (of older frames, whose slots came round).
    fn frame(&mut self, renderer: &mut Renderer, camera: &Camera) -> Result<Vec<FrameTiming>>;

    /// The window's present mode (as written in reports); `None` offscreen.
    fn present_mode(&self) -> Option<&'static str>;

    /// Frames presented to a window so far (0 offscreen).
    fn frames_presented(&self) -> u64;
}

/// Frames stay in the renderer's targets.
pub struct Offscreen;

impl FrameSink for Offscreen {
    fn begin(&mut self, _label: &str) {}

    fn frame(&mut self, renderer: &mut Renderer, camera: &Camera) -> Result<Vec<FrameTiming>> {
        Ok(renderer.render_frame(camera)?.into_iter().collect())
    }

    fn present_mode(&self) -> Option<&'static str> {
        None
    }

    fn frames_presented(&self) -> u64 {
        0
    }
}
