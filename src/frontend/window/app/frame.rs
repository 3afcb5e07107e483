//! The frame loop: the script's and the overlay's requests, the swapchain's upkeep, the fly
//! camera, then render, blit, present, and what a frame leaves (timings, the title, the
//! screenshot).

use super::super::fly_camera;
use super::super::screenshot;
use super::{App, Live};
use crate::error::{Error, Result};
use crate::frontend::overlay::{command_line, PanelText, Request};
use crate::frontend::swapchain_frame::{
    recreate, render_and_present, OverlayDraw, Presented, Recreated,
};
use crate::scene::Camera;
use crate::vk::recorder::Recorder;
use crate::vk::swapchain::present_mode_name;
use crate::vk::Tracker;
use std::time::Instant;
use winit::event_loop::ActiveEventLoop;

impl App {
    /// Move the fly camera by the input since the last frame.
    fn update_camera(&mut self, dt: f32) -> Camera {
        let viewer = &mut self.viewer;
        let base = viewer.camera_or(&self.renderer);
        if viewer.input.fly.is_idle() {
            return base; // unchanged, bit for bit (the screenshot test relies on it)
        }
        let radius = self.renderer.scene.mesh.bounds.radius().max(1e-3);
        let cam = fly_camera::step(base, &viewer.input.fly, dt, fly_camera::base_speed(radius));
        viewer.input.fly.look = (0.0, 0.0);
        viewer.camera = Some(cam);
        cam
    }

    /// One frame: recreate the swapchain if needed, acquire, render + blit, present.
    pub(super) fn frame(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        if self.pause.zero_ticks > 0 {
            return Ok(());
        }
        if let Some(total) = self.total_frames() {
            if self.frames.presented >= total {
                event_loop.exit();
                return Ok(());
            }
        }
        self.run_script(event_loop);
        for request in std::mem::take(&mut self.panel.requests) {
            match request {
                Request::Action(a) => self.act(event_loop, a),
                Request::Set(key, value) => self.set_setting(key, &value)?,
                Request::CommandLine => {
                    let panel = &self.panel;
                    let line = command_line(&panel.command, &self.renderer.config, &panel.settings);
                    self.report(line);
                }
            }
        }
        if event_loop.exiting() {
            return Ok(());
        }
        if self.pause.zero_ticks > 0 {
            self.pause.minimised = true;
            eprintln!("window minimised (zero extent): rendering paused");
            return Ok(());
        }
        let Some(mut live) = self.live.take() else {
            return Ok(());
        };
        let result = self.frame_live(&mut live);
        self.live = Some(live);
        if self
            .total_frames()
            .is_some_and(|total| self.frames.presented >= total)
        {
            event_loop.exit();
        }
        result
    }

    fn frame_live(&mut self, live: &mut Live) -> Result<()> {
        let size = live.window.inner_size();
        let window = (size.width, size.height);
        if live.swapchain.is_stale() || self.pause.minimised {
            if live.swapchain.surface_extent(window)?.is_none() {
                if !self.pause.minimised {
                    eprintln!("window minimised (zero extent): rendering paused");
                }
                self.pause.minimised = true;
                return Ok(());
            }
            match recreate(&mut live.swapchain, window, &mut self.renderer)? {
                Recreated::Ready(pending) => self.frames.absorb(pending),
                Recreated::ZeroExtent => {
                    self.pause.minimised = true;
                    return Ok(());
                }
            }
            if self.pause.minimised {
                eprintln!("window restored: rendering resumed");
            }
            self.pause.minimised = false;
            self.on_swapchain(live)?;
        }
        let now = Instant::now();
        let dt = self
            .viewer
            .last_frame
            .map_or(0.0, |t| (now - t).as_secs_f32().min(0.1));
        let camera = self.update_camera(dt);
        self.check_truth(&camera)?;
        if self
            .truth
            .error_map
            .as_ref()
            .is_some_and(|(_, c)| *c != camera)
        {
            self.drop_error_map("the camera moved");
        }
        self.viewer.scene_time += dt;
        let capture_now = self.options.capture.is_some()
            && self.total_frames() == Some(self.frames.presented + 1);
        let view = &self.viewer.view;
        let source = view.display_target();
        let renderer = &mut self.renderer;
        let shoot = std::mem::take(&mut self.viewer.shot_pending);
        let bytes = live.swapchain.extent.width as u64 * live.swapchain.extent.height as u64 * 4;
        if (capture_now || shoot) && live.capture.as_ref().is_none_or(|b| b.size != bytes) {
            live.capture = Some(live.swapchain.readback_buffer()?);
        }
        let capture = live.capture.as_ref().filter(|_| capture_now || shoot);
        renderer.set_time(self.viewer.scene_time);
        let (w, h) = (renderer.config.width, renderer.config.height);
        let shown = format!("{w}x{h} | {} | {}", view.display_name(), view.summary());
        let draws = live.overlay.as_ref().is_some_and(|o| o.visible());
        let mut overlay = live.overlay.as_mut().filter(|o| o.visible());
        let (mut pending, mut requests) = (Vec::new(), Vec::new());
        if let Some(o) = overlay.as_mut() {
            let stats = self.frames.history.window(Instant::now());
            let text = PanelText {
                view: &shown,
                message: self.panel.message.as_deref(),
                truth: &self.truth.text,
                render_scale: self.options.render_scale,
            };
            (pending, requests) = o.prepare(
                &live.window,
                renderer,
                (&text, &stats),
                live.swapchain.extent,
            )?;
        }
        let mut draw = |rec: &Recorder<'_>, tracker: &mut Tracker, target: &_, extent| {
            if let Some(o) = overlay.as_mut() {
                o.record(rec, tracker, target, extent);
            }
        };
        let truth = &self.truth;
        let replace = truth
            .error_map
            .as_ref()
            .filter(|_| truth.show_error_map)
            .map(|(image, _)| image);
        let presented = render_and_present(
            &mut live.swapchain,
            renderer,
            &camera,
            (source, replace),
            capture,
            draws.then_some(&mut draw as OverlayDraw<'_>),
        )?;
        self.frames.absorb(pending);
        let timing = match presented {
            Presented::Frame(timing) => timing,
            Presented::OutOfDate => return Ok(()), // recreated on the next redraw
        };
        if let Some(o) = live.overlay.as_mut() {
            o.take_error()?;
            if let (true, Some([x0, y0, x1, y1])) = (capture_now, o.rect().filter(|_| o.visible()))
            {
                // For the window test: the capture differs from one without the overlay only
                // inside this rectangle.
                eprintln!("overlay rectangle: {x0} {y0} {x1} {y1} (pixels, x1 and y1 exclusive)");
            }
        }
        let frames = &mut self.frames;
        frames.presented += 1;
        frames.absorb(timing.into_iter().collect());
        if let Some(last) = self.viewer.last_frame {
            let ms = (now - last).as_secs_f64() * 1e3;
            frames.stats.add_wall(ms);
            frames.history.add_wall(Instant::now(), ms);
        }
        if shoot {
            self.screenshot(live)?;
        }
        self.panel.requests.extend(requests);
        self.viewer.last_frame = Some(now);
        let prefix = format!("{} | {shown}", self.options.title);
        if let Some(title) = self.frames.stats.title(&prefix) {
            live.window.set_title(&title);
        }
        Ok(())
    }

    /// The screenshot key: wait for the frame just presented (its copy into the readback
    /// buffer), then write it and the last second's report.
    fn screenshot(&mut self, live: &mut Live) -> Result<()> {
        let pending = self.renderer.finish()?;
        self.frames.absorb(pending);
        let buffer = live
            .capture
            .as_ref()
            .ok_or_else(|| Error::Window("no readback buffer".into()))?;
        let image = live.swapchain.read_buffer(buffer)?;
        let (timings, seconds) = self.frames.history.frames(Instant::now());
        let mode = present_mode_name(live.swapchain.present_mode);
        let report = screenshot::report(&self.ctx, &self.renderer, &timings, seconds, mode);
        let (png, json) = screenshot::write(
            &self.options.screenshot_dir,
            self.frames.presented,
            &image,
            &report,
        )?;
        eprintln!(
            "screenshot: wrote {} and {} ({} frames timed over {seconds:.2} s)",
            png.display(),
            json.display(),
            timings.len()
        );
        Ok(())
    }
}
