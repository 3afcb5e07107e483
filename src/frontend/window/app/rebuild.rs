//! Fitting the renderer to the window (its size times the render scale) and rebuilding it
//! for a new configuration.

use super::{displayable, App, Live};
use crate::error::Result;
use crate::frontend::overlay::History;
use crate::frontend::view_state::needs_rebuild;
use crate::renderer::{RenderConfig, Renderer};
use crate::vk::swapchain::present_mode_name;

impl App {
    /// After (re)creating the swapchain: match the renderer to it and report it.
    pub(super) fn on_swapchain(&mut self, live: &mut Live) -> Result<()> {
        if let Some(overlay) = live.overlay.as_mut() {
            overlay.set_format(live.swapchain.format)?;
        }
        let sc = &live.swapchain;
        let (w, h) = (sc.extent.width, sc.extent.height);
        self.fit_renderer((w, h))?;
        let sc = &live.swapchain;
        eprintln!(
            "swapchain: {w}x{h} {:?}, {} images, present mode {}",
            sc.format,
            sc.image_count(),
            present_mode_name(sc.present_mode)
        );
        Ok(())
    }

    /// Size the renderer to `window` times the render scale (at least a pixel each way).
    pub(super) fn fit_renderer(&mut self, (w, h): (u32, u32)) -> Result<()> {
        let s = self.options.render_scale;
        let scaled = |n: u32| ((n as f32 * s).round() as u32).max(1);
        let (w, h) = (scaled(w), scaled(h));
        let config = &self.renderer.config;
        if (config.width, config.height) != (w, h) {
            let pending = self.renderer.resize(w, h)?;
            self.frames.absorb(pending);
        }
        Ok(())
    }

    /// Make the renderer's configuration `wanted` (`what` names the change): in place when
    /// only the PCF kernel differs, else by rebuilding the renderer on the same context and
    /// size (histories and the last second's statistics start over). False when the renderer
    /// rejected it (reported; the old one stays).
    pub(super) fn apply_config(&mut self, wanted: RenderConfig, what: &str) -> Result<bool> {
        if !needs_rebuild(&self.renderer.config, &wanted) {
            self.renderer.config = wanted;
            return Ok(true);
        }
        let pending = self.renderer.finish()?;
        let rebuilt = Renderer::new(&self.ctx, self.renderer.scene.clone(), wanted);
        self.frames.absorb(pending);
        let applied = match rebuilt {
            Ok(rebuilt) => {
                self.renderer = rebuilt;
                self.frames.history = History::default();
                eprintln!("renderer rebuilt: {what}");
                if self.truth.error_map.is_some() {
                    self.drop_error_map("the configuration changed");
                }
                true
            }
            Err(e) => {
                self.report(format!("cannot switch to \"{what}\": {e}; switch undone"));
                false
            }
        };
        // Buffers of effects that are off are not written: step off them.
        if let Some(live) = self.live.as_mut() {
            let view = &mut self.viewer.view;
            live.displayable = displayable(&self.renderer, &live.swapchain);
            if !live.displayable[view.display] {
                view.display = 0;
                eprintln!("display: {}", view.display_name());
            }
        }
        Ok(applied)
    }
}
