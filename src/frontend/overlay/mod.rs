//! The viewer's overlay: GPU time per pass and per timing group (median and p95 over the last
//! second), the frame rate, the counters and lane efficiency, the device and driver, drawn in
//! the frame over the presented image. egui (a maintained immediate-mode UI) lays it out and
//! tessellates it; `painter.rs` draws the meshes with our own pipeline, so its barriers go
//! through the sync tracker and its cost is its own timing row (`overlay`, in the frame's
//! command buffer between timestamps). egui-ash-renderer was the ready-made alternative: it
//! needs another gpu-allocator major version than ours and records its own barriers.
//!
//! Per frame: `prepare` runs egui (input gathered from window events), applies texture
//! changes (the font atlas; they wait for the frames in flight, which happens when new glyphs
//! appear) and lays the meshes out for the coming frame's slot; `record`, called from the
//! frame hook after the blit, writes the slot's buffers and draws.

mod history;
mod painter;
mod panel;
mod settings;

pub use history::{History, Window as Stats};
pub use painter::layout;
pub use settings::{command_line, Request, RENDER_SCALE};

use crate::config::RenderConfig;
use crate::error::{Error, Result};
use crate::renderer::Renderer;
use crate::vk::recorder::Recorder;
use crate::vk::swapchain::SwapchainImage;
use crate::vk::{Context, FrameTiming, Tracker};
use ash::vk;
use painter::Painter;
use std::sync::Arc;
use winit::window::Window;

/// Where the panel sits: this many points from the top-left corner.
const MARGIN: f32 = 6.0;
/// The widest the panel grows, in points.
const PANEL_WIDTH: f32 = 460.0;
/// The full panel's size before it was first drawn, in points (every effect on: about
/// 470x400 pixels at one pixel per point).
const FULL_PANEL_GUESS: egui::Vec2 = egui::vec2(470.0, 400.0);
/// The most of the window the full panel may cover before the overlay shows its compact
/// summary instead (unless O asked for the full panel): in a 320x240 window the full panel
/// covered 87.5% of the frame.
const MOST_COVERED: f32 = 0.5;

/// Which panel the overlay draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Detail {
    /// The full panel where it covers at most `MOST_COVERED` of the window, else the
    /// compact summary.
    Auto,
    Full,
    Compact,
}

pub struct Overlay {
    egui: egui::Context,
    input: egui_winit::State,
    painter: Painter,
    visible: bool,
    device: String,
    format: vk::Format,
    /// Textures egui freed last frame (freed before the next frame's changes).
    to_free: Vec<egui::TextureId>,
    /// The slot `prepare` laid the meshes out for.
    slot: usize,
    /// The panel's rectangle in pixels last frame: x0, y0, x1, y1 (exclusive), widened by the
    /// anti-aliasing fringe.
    rect: Option<[u32; 4]>,
    /// An error while recording (reported after the frame).
    error: Option<Error>,
    /// The settings' edit fields (VPLs, refresh budget in percent), and the configuration
    /// they were last read from.
    edits: (u32, f32, f32),
    synced: Option<(RenderConfig, f32)>,
    detail: Detail,
    /// The full panel's size when it was last drawn, in points.
    full_size: egui::Vec2,
    /// The last frame drew the full panel.
    drew_full: bool,
}

/// What the panel shows besides the statistics.
pub struct PanelText<'a> {
    /// Render size, displayed buffer and switches.
    pub view: &'a str,
    /// The last message (a refused setting, say).
    pub message: Option<&'a str>,
    /// The ground truth's progress or result lines.
    pub truth: &'a [String],
    /// The render size as a fraction of the window's.
    pub render_scale: f32,
}

impl Overlay {
    /// An overlay for `window`, drawn into swapchain images of `format`.
    pub fn new(ctx: &Arc<Context>, window: &Window, format: vk::Format) -> Result<Self> {
        let egui = egui::Context::default();
        egui.set_visuals(egui::Visuals::dark());
        egui.all_styles_mut(|s| {
            // Small, fixed-width numbers: the panel keeps its size as the values change.
            for (style, size) in [
                (egui::TextStyle::Body, 11.0),
                (egui::TextStyle::Monospace, 11.0),
                (egui::TextStyle::Button, 11.0),
                (egui::TextStyle::Small, 9.0),
            ] {
                s.text_styles.insert(style, egui::FontId::monospace(size));
            }
            s.spacing.item_spacing = egui::vec2(4.0, 1.0);
            // Rows as tall as the text (the default fits a button).
            s.spacing.interact_size.y = 12.0;
        });
        // Every Vulkan device takes 4096-texel images (maxImageDimension2D's minimum).
        let max_side = 4096;
        let input = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            Some(max_side),
        );
        Ok(Self {
            egui,
            input,
            painter: Painter::new(ctx, format)?,
            visible: true,
            device: format!("{} ({})", ctx.info.name, ctx.info.driver),
            format,
            to_free: Vec::new(),
            slot: 0,
            rect: None,
            error: None,
            edits: (0, 0.0, 1.0),
            synced: None,
            detail: Detail::Auto,
            full_size: FULL_PANEL_GUESS,
            drew_full: true,
        })
    }

    /// Whether the overlay draws its full panel (else the compact summary).
    pub fn full(&self) -> bool {
        self.drew_full
    }

    /// Switch between the full panel and the compact summary (from whichever is shown).
    pub fn toggle_detail(&mut self) {
        self.detail = if self.drew_full {
            Detail::Compact
        } else {
            Detail::Full
        };
        self.drew_full = self.detail == Detail::Full;
    }

    /// Whether the full panel fits a window of `size` pixels at `ppp` pixels per point.
    fn full_fits(&self, size: [u32; 2], ppp: f32) -> bool {
        let panel = self.full_size * ppp;
        let (w, h) = (size[0] as f32, size[1] as f32);
        panel.x * panel.y <= MOST_COVERED * w * h && panel.y <= h && panel.x <= w
    }

    pub fn visible(&self) -> bool {
        self.visible
    }

    pub fn toggle(&mut self) {
        self.visible = !self.visible;
        self.rect = None;
    }

    /// A window event; true when egui takes it (a drag over the panel does not turn the
    /// camera).
    pub fn on_window_event(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        self.visible && self.input.on_window_event(window, event).consumed
    }

    /// The swapchain was recreated, possibly with another format.
    pub fn set_format(&mut self, format: vk::Format) -> Result<()> {
        if format != self.format {
            self.painter.set_format(format)?;
            self.format = format;
        }
        Ok(())
    }

    /// The panel's rectangle in the last prepared frame, in pixels (x0, y0, x1, y1 exclusive).
    pub fn rect(&self) -> Option<[u32; 4]> {
        self.rect
    }

    /// Lay out the panel of `stats` for the renderer's next frame on an `extent` swapchain
    /// image. Returns the timings of frames waited for (texture changes wait for the frames
    /// in flight) and what the settings' widgets ask for (the caller applies it).
    pub fn prepare(
        &mut self,
        window: &Window,
        renderer: &mut Renderer,
        (text, stats): (&PanelText<'_>, &Stats),
        extent: vk::Extent2D,
    ) -> Result<(Vec<FrameTiming>, Vec<Request>)> {
        if !self.visible {
            return Ok((Vec::new(), Vec::new()));
        }
        let config = renderer.config;
        if self.synced != Some((config, text.render_scale)) {
            self.edits = (
                config.indirect.vpls,
                100.0 * config.temporal.refresh_budget,
                text.render_scale,
            );
            self.synced = Some((config, text.render_scale));
        }
        let full = match self.detail {
            Detail::Full => true,
            Detail::Compact => false,
            Detail::Auto => {
                self.full_fits([extent.width, extent.height], self.egui.pixels_per_point())
            }
        };
        let mut requests = Vec::new();
        let edits = &mut self.edits;
        let raw = self.input.take_egui_input(window);
        let header = panel::Header {
            device: &self.device,
            view: text.view,
        };
        let mut rect = None;
        let mut out = self.egui.run_pass(raw, |ctx| {
            let shown = egui::Area::new(egui::Id::unique("ssgi overlay"))
                .fixed_pos(egui::pos2(MARGIN, MARGIN))
                .show(ctx, |ui| {
                    egui::Frame::new()
                        .fill(egui::Color32::from_black_alpha(200))
                        .inner_margin(6.0)
                        .corner_radius(3.0)
                        .show(ui, |ui| {
                            // Long lines (a printed command line) wrap.
                            ui.set_max_width(PANEL_WIDTH);
                            if !full {
                                panel::show_compact(ui, stats);
                                return;
                            }
                            panel::show(ui, &header, stats);
                            if let Some(m) = text.message {
                                ui.label(egui::RichText::new(m).weak());
                            }
                            for line in text.truth {
                                ui.label(line.as_str());
                            }
                            ui.collapsing("settings", |ui| {
                                let fields = settings::Fields {
                                    vpls: &mut edits.0,
                                    budget: &mut edits.1,
                                    scale: (&mut edits.2, text.render_scale),
                                };
                                settings::show(ui, &config, fields, &mut requests);
                            });
                        });
                });
            rect = Some(shown.response.rect);
        });
        if let (true, Some(r)) = (full, rect) {
            self.full_size = r.size() + egui::vec2(MARGIN, MARGIN);
        }
        self.drew_full = full;
        self.input
            .handle_platform_output(window, out.platform_output);
        let ppp = out.pixels_per_point;
        let mut pending = Vec::new();
        let free = std::mem::take(&mut self.to_free);
        let set: Vec<_> = std::mem::take(&mut out.textures_delta.set)
            .into_iter()
            .flat_map(|(id, deltas)| deltas.into_iter().map(move |d| (id, d)))
            .collect();
        if !set.is_empty() || !free.is_empty() {
            // The textures and their descriptor sets are rewritten in place.
            pending = renderer.finish()?;
            self.painter.free_textures(&free);
            self.painter.update_textures(&set)?;
        }
        self.to_free = std::mem::take(&mut out.textures_delta.free)
            .into_iter()
            .collect();
        let primitives = self.egui.tessellate(out.shapes, ppp);
        self.slot = renderer.next_slot();
        self.painter
            .prepare(self.slot, &primitives, ppp, [extent.width, extent.height])?;
        self.rect = rect.map(|r| pixel_rect(r, ppp, [extent.width, extent.height]));
        Ok((pending, requests))
    }

    /// Record the prepared panel over `target` (the frame hook calls this after the blit).
    pub fn record(
        &mut self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        target: &SwapchainImage,
        extent: vk::Extent2D,
    ) {
        if let Err(e) = self.painter.record(rec, tracker, self.slot, target, extent) {
            self.error.get_or_insert(e);
        }
    }

    /// An error from the last `record`.
    pub fn take_error(&mut self) -> Result<()> {
        match self.error.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

/// egui's rectangle (points) in pixels, widened by one pixel for the anti-aliasing fringe
/// egui feathers shapes with, clamped to the image.
fn pixel_rect(r: egui::Rect, ppp: f32, size: [u32; 2]) -> [u32; 4] {
    let px = |v: f32, max: u32| (v * ppp).clamp(0.0, max as f32);
    [
        (px(r.min.x, size[0]).floor() as u32).saturating_sub(1),
        (px(r.min.y, size[1]).floor() as u32).saturating_sub(1),
        (px(r.max.x, size[0]).ceil() as u32 + 1).min(size[0]),
        (px(r.max.y, size[1]).ceil() as u32 + 1).min(size[1]),
    ]
}
