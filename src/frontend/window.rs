//! Window frontend: `ssgi view` (interactive fly camera). winit 0.30 `ApplicationHandler` + a
//! Vulkan swapchain; the same `Renderer` as the headless frontend, whose output (or another
//! target, for the buffer display) is blitted into the acquired swapchain image in the
//! renderer's frame hook. Scripted runs (`bench --window`, `table --window`) present through
//! `presenter.rs` instead, which shares the frame steps in `present.rs`.
//!
//! Frame loop (one `RedrawRequested`):
//! 1. if the swapchain is stale (resize, OUT_OF_DATE, SUBOPTIMAL): recreate it and resize the
//!    renderer's targets to the new extent; a zero extent (minimised) renders nothing and
//!    polls again later, keeping the event loop alive;
//! 2. wait for the renderer's next frame slot (so the slot's acquire semaphore is free);
//! 3. acquire an image; render the frame with a hook that blits into it and moves it to
//!    PRESENT_SRC; the submission waits on the acquire semaphore and signals the image's
//!    render-finished semaphore; present.
//!
//! Viewer keys: see [`HELP`] (`view_state.rs`).

use super::display::{new_event_loop, presenting_context};
use super::present::{recreate, render_and_present, Presented, Recreated};
use super::view_state::needs_rebuild;
pub use super::view_state::{Action, ViewState, DISPLAY_CYCLE, HELP};
use crate::error::{Error, Result};
use crate::renderer::targets::Target;
use crate::renderer::{Renderer, FRAMES_IN_FLIGHT};
use crate::scene::Camera;
use crate::vk::swapchain::present_mode_name;
use crate::vk::{
    Buffer, Context, ContextOptions, FrameTiming, ImageData, PresentPolicy, Surface, Swapchain,
    SwapchainOptions,
};
use glam::Vec3;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::{KeyCode, ModifiersState, PhysicalKey};
use winit::window::{Window, WindowId};

/// One step of a scripted run (hidden `--script` flag, for tests under Xvfb): before
/// presented frame `frame`, do `op`.
#[derive(Clone, Debug, PartialEq)]
pub struct ScriptStep {
    pub frame: u64,
    pub op: ScriptOp,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ScriptOp {
    /// Ask the window system for this inner size.
    Resize(u32, u32),
    /// Behave as if the window had a zero extent (minimised) for this many event-loop
    /// iterations: X11 windows never have one (a minimised X11 window keeps its size, and a
    /// zero-sized X window is invalid), so under Xvfb the path is exercised this way.
    ZeroExtent(u32),
    /// A viewer key action by name (cycle, pcf, ao, indirect, ssdo, filter, reuse, camera, help,
    /// quit).
    Key(String),
    /// Show this buffer of [`DISPLAY_CYCLE`] by name.
    Display(String),
}

/// Parse `FRAME:OP[,FRAME:OP...]` with OP one of `resize=WxH`, `zero=N`, `key=NAME`,
/// `display=NAME`.
pub fn parse_script(s: &str) -> std::result::Result<Vec<ScriptStep>, String> {
    let mut steps = Vec::new();
    for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let bad = || {
            format!("bad script step {part:?}: expected FRAME:resize=WxH, FRAME:zero=N, FRAME:key=NAME or FRAME:display=NAME")
        };
        let (frame, op) = part.split_once(':').ok_or_else(bad)?;
        let frame: u64 = frame.trim().parse().map_err(|_| bad())?;
        let (name, value) = op.split_once('=').ok_or_else(bad)?;
        let op = match name.trim() {
            "resize" => {
                let (w, h) = value.split_once(['x', 'X']).ok_or_else(bad)?;
                let w: u32 = w.trim().parse().map_err(|_| bad())?;
                let h: u32 = h.trim().parse().map_err(|_| bad())?;
                if w == 0 || h == 0 {
                    return Err(format!("{part:?}: use zero=N for a zero extent"));
                }
                ScriptOp::Resize(w, h)
            }
            "zero" => ScriptOp::ZeroExtent(value.trim().parse().map_err(|_| bad())?),
            "key" => {
                let key = value.trim();
                if Action::from_name(key).is_none() {
                    return Err(format!("{part:?}: unknown key action {key:?}"));
                }
                ScriptOp::Key(key.to_string())
            }
            "display" => {
                let name = value.trim();
                if !DISPLAY_CYCLE.iter().any(|(_, n)| *n == name) {
                    return Err(format!("{part:?}: unknown buffer {name:?}"));
                }
                ScriptOp::Display(name.to_string())
            }
            _ => return Err(bad()),
        };
        steps.push(ScriptStep { frame, op });
    }
    Ok(steps)
}

pub struct WindowOptions {
    pub title: String,
    /// Initial inner size of the window.
    pub size: (u32, u32),
    /// End the run by itself after this many frames.
    pub frames: Option<u64>,
    /// Test script (hidden flag).
    pub script: Vec<ScriptStep>,
    /// Write the last presented image (read back from the swapchain) here as PNG; needs a
    /// frame count.
    pub capture: Option<PathBuf>,
}

/// What a windowed run leaves: the renderer (for PNG output; drop it before `ctx`), every
/// frame's GPU timing in frame order, and what was presented.
pub struct WindowRun {
    pub ctx: Arc<Context>,
    pub renderer: Renderer,
    pub timings: Vec<FrameTiming>,
    pub frames_presented: u64,
    /// The last presented image, read back from the swapchain (with `capture`).
    pub captured: Option<ImageData>,
}

/// Open the viewer. `context` is the base context configuration (surface and swapchain
/// extensions are added); `make_renderer` builds the renderer on the context.
pub fn run(
    options: WindowOptions,
    context: ContextOptions,
    make_renderer: impl FnOnce(&Arc<Context>) -> Result<Renderer>,
) -> Result<WindowRun> {
    if options.capture.is_some() && options.frames.is_none() {
        return Err(Error::Config("--capture needs --frames".into()));
    }
    let event_loop = new_event_loop()?;
    let ctx = presenting_context(context, &event_loop)?;
    let renderer = make_renderer(&ctx)?;
    let mut app = App {
        options,
        ctx,
        renderer: Some(renderer),
        live: None,
        error: None,
        timings: Vec::new(),
        presented: 0,
        captured: None,
        input: Input::default(),
        stats: Stats::new(),
        zero_ticks: 0,
        minimised: false,
        last_frame: None,
        view: None,
        camera: None,
    };
    let result = event_loop.run_app(&mut app);
    // `exiting` normally shut down already; make sure (an error before the loop started).
    app.shutdown();
    if let Some(e) = app.error.take() {
        return Err(e);
    }
    result.map_err(|e| Error::Window(format!("event loop: {e}")))?;
    let renderer = app
        .renderer
        .take()
        .ok_or_else(|| Error::Window("the renderer was lost".into()))?;
    app.timings.sort_by_key(|t| t.frame);
    Ok(WindowRun {
        ctx: app.ctx.clone(),
        renderer,
        timings: std::mem::take(&mut app.timings),
        frames_presented: app.presented,
        captured: app.captured.take(),
    })
}

/// Objects that live while the window is open. Field order is drop order: the swapchain
/// (and its surface) before the window.
struct Live {
    swapchain: Swapchain,
    window: Arc<Window>,
    capture: Option<Buffer>,
    /// Display targets whose format can be blitted.
    displayable: Vec<bool>,
}

#[derive(Default)]
struct Input {
    forward: f32,
    back: f32,
    left: f32,
    right: f32,
    up: f32,
    down: f32,
    mods: ModifiersState,
    dragging: bool,
    cursor: Option<(f64, f64)>,
    /// Mouse movement (pixels) since the last frame.
    look: (f64, f64),
}

/// Frame-time and per-pass GPU averages for the window title, refreshed ~4x per second.
struct Stats {
    since: Instant,
    frames: u32,
    wall_ms: f64,
    gpu: BTreeMap<&'static str, (f64, u32)>,
    order: Vec<&'static str>,
}

impl Stats {
    fn new() -> Self {
        Self {
            since: Instant::now(),
            frames: 0,
            wall_ms: 0.0,
            gpu: BTreeMap::new(),
            order: Vec::new(),
        }
    }

    fn add_wall(&mut self, ms: f64) {
        self.frames += 1;
        self.wall_ms += ms;
    }

    fn add_gpu(&mut self, t: &FrameTiming) {
        for (name, ms) in &t.passes {
            if let Some(ms) = ms {
                if !self.order.contains(name) {
                    self.order.push(name);
                }
                let e = self.gpu.entry(name).or_insert((0.0, 0));
                e.0 += ms;
                e.1 += 1;
            }
        }
    }

    /// The title text when a refresh is due (then the averages start over).
    fn title(&mut self, prefix: &str) -> Option<String> {
        if self.since.elapsed() < Duration::from_millis(250) || self.frames == 0 {
            return None;
        }
        let frame_ms = self.wall_ms / self.frames as f64;
        let mut total = 0.0;
        let mut passes = Vec::new();
        for name in &self.order {
            if let Some((sum, n)) = self.gpu.get(name) {
                let ms = sum / *n as f64;
                total += ms;
                passes.push(format!("{name} {ms:.2}"));
            }
        }
        let title = format!(
            "{prefix} | {frame_ms:.1} ms ({:.0} fps) | GPU {total:.2} ms: {}",
            1000.0 / frame_ms.max(1e-3),
            passes.join(", ")
        );
        *self = Stats {
            order: std::mem::take(&mut self.order),
            ..Stats::new()
        };
        Some(title)
    }
}

struct App {
    options: WindowOptions,
    ctx: Arc<Context>,
    renderer: Option<Renderer>,
    live: Option<Live>,
    error: Option<Error>,
    timings: Vec<FrameTiming>,
    presented: u64,
    captured: Option<ImageData>,
    input: Input,
    stats: Stats,
    /// Event-loop iterations left of a scripted zero extent.
    zero_ticks: u32,
    /// The window has a zero extent: nothing is rendered until it has one again.
    minimised: bool,
    last_frame: Option<Instant>,
    view: Option<ViewState>,
    /// The viewer's camera (None until the first frame: the scene camera).
    camera: Option<Camera>,
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, e: Error) {
        if self.error.is_none() {
            self.error = Some(e);
        }
        event_loop.exit();
    }

    fn total_frames(&self) -> Option<u64> {
        self.options.frames
    }

    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let (w, h) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title(self.options.title.clone())
            .with_inner_size(PhysicalSize::new(w, h))
            .with_resizable(true);
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| Error::Window(format!("cannot create the window: {e}")))?,
        );
        let surface = Surface::new(&self.ctx, window.clone())?;
        let size = window.inner_size();
        let swapchain = Swapchain::new(
            &self.ctx,
            surface,
            (size.width, size.height),
            SwapchainOptions {
                policy: PresentPolicy::Vsync,
                frames_in_flight: FRAMES_IN_FLIGHT,
                readable: self.options.capture.is_some(),
            },
        )?;
        let renderer = self
            .renderer
            .as_mut()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        let displayable = displayable(renderer, &swapchain);
        self.view = Some(ViewState::new(&renderer.config));
        let live = Live {
            swapchain,
            window,
            capture: None,
            displayable,
        };
        self.on_swapchain(&live)?;
        self.live = Some(live);
        eprintln!("press H in the window for the viewer keys");
        Ok(())
    }

    /// After (re)creating the swapchain: match the renderer to it and report it.
    fn on_swapchain(&mut self, live: &Live) -> Result<()> {
        let sc = &live.swapchain;
        let (w, h) = (sc.extent.width, sc.extent.height);
        let renderer = self
            .renderer
            .as_mut()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        if (renderer.config.width, renderer.config.height) != (w, h) {
            let pending = renderer.resize(w, h)?;
            self.timings.extend(pending);
        }
        eprintln!(
            "swapchain: {w}x{h} {:?}, {} images, present mode {}",
            sc.format,
            sc.image_count(),
            present_mode_name(sc.present_mode)
        );
        Ok(())
    }

    fn act(&mut self, event_loop: &ActiveEventLoop, action: Action) {
        let Some(view) = self.view.as_mut() else {
            return;
        };
        let e = &mut view.effects;
        match action {
            Action::CycleDisplay(step) => {
                let n = DISPLAY_CYCLE.len() as i32;
                let displayable = self.live.as_ref().map(|l| l.displayable.clone());
                for _ in 0..n {
                    view.display = (view.display as i32 + step).rem_euclid(n) as usize;
                    if displayable.as_ref().is_none_or(|d| d[view.display]) {
                        break;
                    }
                }
                eprintln!("display: {}", view.display_name());
            }
            Action::ToggleShadows => e.soft_shadows = !e.soft_shadows,
            Action::ToggleAo => e.ao = !e.ao,
            Action::ToggleIndirect => e.indirect = !e.indirect,
            Action::ToggleSsdo => {
                e.ssdo = !e.ssdo;
                eprintln!("SSDO is not in the renderer yet: the switch is only recorded");
            }
            Action::ToggleFilter => {
                e.filter = !e.filter;
                eprintln!(
                    "the spatial filter is not in the renderer yet: the switch is only recorded"
                );
            }
            Action::ToggleReuse => view.temporal_reuse = !view.temporal_reuse,
            Action::PrintCamera => {
                if let Some(c) = self
                    .camera
                    .or(self.renderer.as_ref().map(|r| r.scene.camera))
                {
                    eprintln!(
                        "{{ \"time\": 0.0, \"position\": [{}, {}, {}], \"target\": [{}, {}, {}] }}",
                        c.position.x,
                        c.position.y,
                        c.position.z,
                        c.target.x,
                        c.target.y,
                        c.target.z
                    );
                }
            }
            Action::Help => eprintln!("{HELP}"),
            Action::Quit => event_loop.exit(),
        }
        if !matches!(
            action,
            Action::CycleDisplay(_) | Action::PrintCamera | Action::Help | Action::Quit
        ) {
            eprintln!("effects: {}", view.summary());
        }
        if let Err(e) = self.apply_view() {
            self.fail(event_loop, e);
        }
    }

    /// Make the renderer match the viewer's switches. The PCF kernel changes in place; effects
    /// and reuse rebuild the renderer on the same context and size (histories start over). A
    /// configuration the renderer rejects is reported and the switch undone.
    fn apply_view(&mut self) -> Result<()> {
        let (Some(view), Some(renderer)) = (self.view.as_mut(), self.renderer.as_mut()) else {
            return Ok(());
        };
        let wanted = view.config(&renderer.config);
        if !needs_rebuild(&renderer.config, &wanted) {
            renderer.config = wanted;
            return Ok(());
        }
        let pending = renderer.finish()?;
        match Renderer::new(&self.ctx, renderer.scene.clone(), wanted) {
            Ok(rebuilt) => {
                *renderer = rebuilt;
                eprintln!("renderer rebuilt: {}", view.summary());
            }
            Err(e) => {
                eprintln!(
                    "cannot switch to \"{}\": {e}; switch undone",
                    view.summary()
                );
                let display = view.display;
                *view = ViewState::new(&renderer.config);
                view.display = display;
            }
        }
        self.absorb(pending);
        // Buffers of effects that are off are not written: step off them.
        if let (Some(live), Some(view), Some(renderer)) = (
            self.live.as_mut(),
            self.view.as_mut(),
            self.renderer.as_ref(),
        ) {
            live.displayable = displayable(renderer, &live.swapchain);
            if !live.displayable[view.display] {
                view.display = 0;
                eprintln!("display: {}", view.display_name());
            }
        }
        Ok(())
    }

    fn run_script(&mut self, event_loop: &ActiveEventLoop) {
        let due: Vec<ScriptOp> = self
            .options
            .script
            .iter()
            .filter(|s| s.frame == self.presented)
            .map(|s| s.op.clone())
            .collect();
        self.options.script.retain(|s| s.frame != self.presented);
        for op in due {
            match op {
                ScriptOp::Resize(w, h) => {
                    if let Some(live) = &self.live {
                        eprintln!("script: resize to {w}x{h}");
                        let _ = live.window.request_inner_size(PhysicalSize::new(w, h));
                    }
                }
                ScriptOp::ZeroExtent(n) => {
                    eprintln!("script: zero extent for {n} event-loop iterations");
                    self.zero_ticks = n.max(1);
                }
                ScriptOp::Key(name) => {
                    if let Some(a) = Action::from_name(&name) {
                        self.act(event_loop, a);
                    }
                }
                ScriptOp::Display(name) => {
                    let index = DISPLAY_CYCLE.iter().position(|(_, n)| *n == name);
                    let shown = self.live.as_ref().map(|l| l.displayable.clone());
                    match (index, self.view.as_mut(), shown) {
                        (Some(i), Some(view), Some(shown)) if shown[i] => {
                            view.display = i;
                            eprintln!("display: {name}");
                        }
                        _ => eprintln!("display: {name} is not available in this run"),
                    }
                }
            }
        }
    }

    /// Move the fly camera by the input since the last frame.
    fn update_camera(&mut self, dt: f32) -> Camera {
        let renderer = self.renderer.as_ref();
        let base = match (self.camera, renderer) {
            (Some(c), _) => c,
            (None, Some(r)) => r.scene.camera,
            (None, None) => return Camera::new(Vec3::Z, Vec3::ZERO, 60.0, 0.1, 100.0),
        };
        let i = &mut self.input;
        let moving = i.forward + i.back + i.left + i.right + i.up + i.down;
        if moving == 0.0 && i.look == (0.0, 0.0) {
            return base; // unchanged, bit for bit (the screenshot test relies on it)
        }
        let mut cam = base;
        let dist = (cam.target - cam.position).length().max(1e-6);
        let (f, _, _) = cam.frame();
        let mut yaw = f.x.atan2(-f.z);
        let mut pitch = f.y.clamp(-1.0, 1.0).asin();
        const SENSITIVITY: f64 = 0.003;
        yaw += (i.look.0 * SENSITIVITY) as f32;
        pitch -= (i.look.1 * SENSITIVITY) as f32;
        let limit = 89f32.to_radians();
        pitch = pitch.clamp(-limit, limit);
        i.look = (0.0, 0.0);
        let forward = Vec3::new(
            yaw.sin() * pitch.cos(),
            pitch.sin(),
            -yaw.cos() * pitch.cos(),
        );
        let right = forward.cross(Vec3::Y).normalize_or(Vec3::X);
        let radius = renderer.map_or(1.0, |r| r.scene.mesh.bounds.radius().max(1e-3));
        let mut speed = 0.6 * radius;
        if i.mods.shift_key() {
            speed *= 4.0;
        }
        if i.mods.control_key() {
            speed *= 0.25;
        }
        let dir =
            forward * (i.forward - i.back) + right * (i.right - i.left) + Vec3::Y * (i.up - i.down);
        cam.position += dir * speed * dt;
        cam.target = cam.position + forward * dist;
        cam.up = Vec3::Y;
        self.camera = Some(cam);
        cam
    }

    /// One frame: recreate the swapchain if needed, acquire, render + blit, present.
    fn frame(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        if self.zero_ticks > 0 {
            return Ok(());
        }
        if let Some(total) = self.total_frames() {
            if self.presented >= total {
                event_loop.exit();
                return Ok(());
            }
        }
        self.run_script(event_loop);
        if event_loop.exiting() {
            return Ok(());
        }
        if self.zero_ticks > 0 {
            self.minimised = true;
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
            .is_some_and(|total| self.presented >= total)
        {
            event_loop.exit();
        }
        result
    }

    fn frame_live(&mut self, live: &mut Live) -> Result<()> {
        let size = live.window.inner_size();
        let window = (size.width, size.height);
        if live.swapchain.is_stale() || self.minimised {
            if live.swapchain.surface_extent(window)?.is_none() {
                if !self.minimised {
                    eprintln!("window minimised (zero extent): rendering paused");
                }
                self.minimised = true;
                return Ok(());
            }
            let renderer = self
                .renderer
                .as_mut()
                .ok_or_else(|| Error::Window("no renderer".into()))?;
            match recreate(&mut live.swapchain, window, renderer)? {
                Recreated::Ready(pending) => self.absorb(pending),
                Recreated::ZeroExtent => {
                    self.minimised = true;
                    return Ok(());
                }
            }
            if self.minimised {
                eprintln!("window restored: rendering resumed");
            }
            self.minimised = false;
            self.on_swapchain(live)?;
        }
        let now = Instant::now();
        let dt = self
            .last_frame
            .map_or(0.0, |t| (now - t).as_secs_f32().min(0.1));
        let camera = self.update_camera(dt);
        let capture_now =
            self.options.capture.is_some() && self.total_frames() == Some(self.presented + 1);
        let source = self
            .view
            .as_ref()
            .map_or(Target::Output, |v| v.display_target());
        let renderer = self
            .renderer
            .as_mut()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        if capture_now && live.capture.is_none() {
            live.capture = Some(live.swapchain.readback_buffer()?);
        }
        let capture = live.capture.as_ref().filter(|_| capture_now);
        let timing =
            match render_and_present(&mut live.swapchain, renderer, &camera, source, capture)? {
                Presented::Frame(timing) => timing,
                Presented::OutOfDate => return Ok(()), // recreated on the next redraw
            };
        self.presented += 1;
        if let Some(t) = timing {
            self.absorb(vec![t]);
        }
        if let Some(last) = self.last_frame {
            self.stats.add_wall((now - last).as_secs_f64() * 1e3);
        }
        self.last_frame = Some(now);
        let prefix = format!(
            "{} | {}x{} | {} | {}",
            self.options.title,
            renderer_size(self.renderer.as_ref()).0,
            renderer_size(self.renderer.as_ref()).1,
            self.view.as_ref().map_or("final", |v| v.display_name()),
            self.view.as_ref().map_or(String::new(), |v| v.summary()),
        );
        if let Some(title) = self.stats.title(&prefix) {
            live.window.set_title(&title);
        }
        Ok(())
    }

    fn absorb(&mut self, timings: Vec<FrameTiming>) {
        for t in timings {
            self.stats.add_gpu(&t);
            self.timings.push(t);
        }
    }

    /// Wait for the GPU, read back a capture, destroy the swapchain, surface and window.
    fn shutdown(&mut self) {
        if let Some(r) = self.renderer.as_mut() {
            match r.finish() {
                Ok(pending) => self.absorb(pending),
                Err(e) => {
                    if self.error.is_none() {
                        self.error = Some(e);
                    }
                }
            }
        }
        if let Err(e) = self.ctx.wait_idle() {
            if self.error.is_none() {
                self.error = Some(e);
            }
        }
        if let Some(live) = self.live.take() {
            if let Some(buffer) = &live.capture {
                match live.swapchain.read_buffer(buffer) {
                    Ok(data) => self.captured = Some(data),
                    Err(e) => {
                        if self.error.is_none() {
                            self.error = Some(e);
                        }
                    }
                }
            }
            drop(live);
        }
    }
}

fn renderer_size(r: Option<&Renderer>) -> (u32, u32) {
    r.map_or((0, 0), |r| (r.config.width, r.config.height))
}

/// Per [`DISPLAY_CYCLE`] entry, whether it can be shown: the target exists in this run (the
/// buffers of effects that are off do not) and is written (the direct and shadow
/// targets exist without direct light, unwritten), and its format can be blitted into the
/// swapchain (depth and integer formats cannot).
fn displayable(renderer: &Renderer, swapchain: &Swapchain) -> Vec<bool> {
    DISPLAY_CYCLE
        .iter()
        .map(|(target, _)| {
            let written = renderer.config.effects.direct
                || !matches!(target, Target::Direct | Target::Shadow);
            written
                && renderer.has_target(*target)
                && swapchain.can_blit_from(renderer.target_format(*target))
        })
        .collect()
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.live.is_some() || self.error.is_some() {
            return;
        }
        event_loop.set_control_flow(ControlFlow::Poll);
        if let Err(e) = self.start(event_loop) {
            self.fail(event_loop, e);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(_) => {
                if let Some(live) = self.live.as_mut() {
                    live.swapchain.invalidate();
                }
            }
            WindowEvent::ModifiersChanged(m) => self.input.mods = m.state(),
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        physical_key: PhysicalKey::Code(key),
                        state,
                        repeat,
                        ..
                    },
                ..
            } => {
                let pressed = state == ElementState::Pressed;
                let v = if pressed { 1.0 } else { 0.0 };
                let i = &mut self.input;
                match key {
                    KeyCode::KeyW => i.forward = v,
                    KeyCode::KeyS => i.back = v,
                    KeyCode::KeyA => i.left = v,
                    KeyCode::KeyD => i.right = v,
                    KeyCode::KeyQ => i.down = v,
                    KeyCode::KeyE => i.up = v,
                    _ => {
                        if pressed && !repeat {
                            if let Some(a) = Action::from_key(key, i.mods) {
                                self.act(event_loop, a);
                            }
                        }
                    }
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                self.input.dragging = state == ElementState::Pressed;
            }
            WindowEvent::CursorMoved { position, .. } => {
                let p = (position.x, position.y);
                if let (true, Some(last)) = (self.input.dragging, self.input.cursor) {
                    self.input.look.0 += p.0 - last.0;
                    self.input.look.1 += p.1 - last.1;
                }
                self.input.cursor = Some(p);
            }
            WindowEvent::Focused(false) => {
                // Keys released while unfocused never arrive: stop moving.
                let mods = self.input.mods;
                self.input = Input {
                    mods,
                    ..Input::default()
                };
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame(event_loop) {
                    self.fail(event_loop, e);
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.error.is_some() || event_loop.exiting() {
            return;
        }
        if self.zero_ticks > 0 {
            self.zero_ticks -= 1;
            if self.zero_ticks == 0 {
                // Back from the (scripted) zero extent: the swapchain is recreated.
                if let Some(live) = self.live.as_mut() {
                    live.swapchain.invalidate();
                }
            }
            event_loop.set_control_flow(ControlFlow::WaitUntil(
                Instant::now() + Duration::from_millis(5),
            ));
            if self.zero_ticks > 0 {
                return;
            }
        }
        if self.minimised {
            // Keep polling the surface at a low rate; a resize event also wakes the loop.
            event_loop.set_control_flow(ControlFlow::WaitUntil(
                Instant::now() + Duration::from_millis(50),
            ));
        } else {
            event_loop.set_control_flow(ControlFlow::Poll);
        }
        if let Some(live) = &self.live {
            live.window.request_redraw();
        }
    }

    fn exiting(&mut self, _event_loop: &ActiveEventLoop) {
        self.shutdown();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn script_parses_and_rejects_nonsense() {
        let s = parse_script("10:resize=96x72, 20:zero=5,30:key=cycle").unwrap();
        assert_eq!(
            s,
            vec![
                ScriptStep {
                    frame: 10,
                    op: ScriptOp::Resize(96, 72)
                },
                ScriptStep {
                    frame: 20,
                    op: ScriptOp::ZeroExtent(5)
                },
                ScriptStep {
                    frame: 30,
                    op: ScriptOp::Key("cycle".into())
                },
            ]
        );
        assert!(parse_script("10:resize=0x5").is_err());
        assert!(parse_script("x:zero=1").is_err());
        assert!(parse_script("1:key=explode").is_err());
        assert!(parse_script("1:fly=1").is_err());
    }

    #[test]
    fn title_averages_frame_time_and_passes() {
        let mut stats = Stats::new();
        assert_eq!(stats.title("x"), None, "nothing measured yet");
        for ms in [10.0, 30.0] {
            stats.add_wall(ms);
            stats.add_gpu(&FrameTiming {
                frame: 0,
                passes: vec![("gbuffer", Some(ms / 10.0)), ("direct", None)],
                ..Default::default()
            });
        }
        stats.since -= Duration::from_secs(1);
        let title = stats.title("ssgi").unwrap();
        assert_eq!(title, "ssgi | 20.0 ms (50 fps) | GPU 2.00 ms: gbuffer 2.00");
        assert_eq!(stats.frames, 0, "averages start over");
    }
}
