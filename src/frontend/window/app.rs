//! The viewer application: opening the window and swapchain, winit's event loop
//! (`ApplicationHandler`), the frame loop, and the viewer's actions on the renderer.
//!
//! Frame loop (one `RedrawRequested`):
//! 1. if the swapchain is stale (resize, OUT_OF_DATE, SUBOPTIMAL): recreate it and resize the
//!    renderer's targets to the new extent; a zero extent (minimised) renders nothing and
//!    polls again later, keeping the event loop alive;
//! 2. wait for the renderer's next frame slot (so the slot's acquire semaphore is free);
//! 3. acquire an image; render the frame with a hook that blits into it and moves it to
//!    PRESENT_SRC; the submission waits on the acquire semaphore and signals the image's
//!    render-finished semaphore; present.

use super::fly_camera;
use super::keys;
use super::screenshot;
use super::script::{self, ScriptOp, ScriptStep};
use super::stats::Stats;
use super::truth::TruthJob;
use crate::bench::ground_truth;
use crate::bench::measure::read_frame;
use crate::config::parse::parse_render_scale;
use crate::error::{Error, Result};
use crate::frontend::display::{new_event_loop, presenting_context};
use crate::frontend::overlay::{command_line, History, Overlay, PanelText, Request, RENDER_SCALE};
use crate::frontend::swapchain_frame::{
    recreate, render_and_present, OverlayDraw, Presented, Recreated,
};
use crate::frontend::view_state::{display_cycle, help, needs_rebuild, Action, ViewState};
use crate::reference::store::default_dir;
use crate::reference::{Reference, Settings};
use crate::renderer::{RenderConfig, Renderer, FRAMES_IN_FLIGHT};
use crate::resources::targets::Target;
use crate::scene::Camera;
use crate::vk::recorder::Recorder;
use crate::vk::swapchain::present_mode_name;
use crate::vk::{
    upload_image, Access, Buffer, Context, ContextOptions, FrameTiming, Image, ImageData,
    ImageDesc, PresentPolicy, Surface, Swapchain, SwapchainOptions, Tracker,
};
use glam::Vec3;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::PhysicalKey;
use winit::window::{Window, WindowId};

/// What the viewer opens and how a scripted run ends.
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
    /// Draw the overlay (timings, counters, device; `H` hides it).
    pub overlay: bool,
    /// Where the screenshot key writes.
    pub screenshot_dir: PathBuf,
    /// The render size as a fraction of the window's (`--render-scale`).
    pub render_scale: f32,
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
        input: keys::Input::default(),
        stats: Stats::new(),
        history: History::default(),
        shot_pending: false,
        settings: Vec::new(),
        message: None,
        requests: Vec::new(),
        command: std::env::args().collect(),
        truth: None,
        truth_text: Vec::new(),
        error_map: None,
        show_error_map: false,
        zero_ticks: 0,
        minimised: false,
        last_frame: None,
        view: None,
        camera: None,
        scene_time: 0.0,
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
    /// Before the swapchain: its input state holds the window's display connection.
    overlay: Option<Overlay>,
    swapchain: Swapchain,
    window: Arc<Window>,
    capture: Option<Buffer>,
    /// Display targets whose format can be blitted.
    displayable: Vec<bool>,
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
    input: keys::Input,
    stats: Stats,
    /// The last second of frames (the overlay's statistics, the screenshot's report).
    history: History,
    /// The screenshot key was pressed: the next presented frame is written.
    shot_pending: bool,
    /// Live settings applied (sweep key, value), latest last: the command line's additions.
    settings: Vec<(String, String)>,
    /// The last message for the overlay's status line (a refused setting, say).
    message: Option<String>,
    /// What the overlay's widgets asked for last frame (applied after it).
    requests: Vec<Request>,
    /// The command line the viewer started with (the base of the printed one).
    command: Vec<String>,
    /// The ground truth being traced (G), and what the overlay says of it.
    truth: Option<TruthJob>,
    truth_text: Vec<String>,
    /// The final image's FLIP map from the last ground truth, the camera it belongs to, and
    /// whether it is shown in place of the image (M).
    error_map: Option<(Image, Camera)>,
    show_error_map: bool,
    /// Event-loop iterations left of a scripted zero extent.
    zero_ticks: u32,
    /// The window has a zero extent: nothing is rendered until it has one again.
    minimised: bool,
    last_frame: Option<Instant>,
    view: Option<ViewState>,
    /// The viewer's camera (None until the first frame: the scene camera).
    camera: Option<Camera>,
    /// Seconds into the scene's light and object paths: they play at wall-clock speed while
    /// frames are drawn (a minimised window pauses them).
    scene_time: f32,
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
        let window = Arc::new(event_loop.create_window(attributes).map_err(|e| {
            Error::Window(format!(
                "cannot create the window: {}",
                crate::frontend::display::user_text(&e)
            ))
        })?);
        let surface = Surface::new(&self.ctx, window.clone())?;
        let size = window.inner_size();
        let swapchain = Swapchain::new(
            &self.ctx,
            surface,
            (size.width, size.height),
            SwapchainOptions {
                policy: PresentPolicy::Vsync,
                frames_in_flight: FRAMES_IN_FLIGHT,
                readable: true, // --capture and the screenshot key
            },
        )?;
        let renderer = self
            .renderer
            .as_mut()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        let displayable = displayable(renderer, &swapchain);
        self.view = Some(ViewState::new(&renderer.config));
        let overlay = match self.options.overlay {
            true => Some(Overlay::new(&self.ctx, &window, swapchain.format)?),
            false => None,
        };
        let live = Live {
            overlay,
            swapchain,
            window,
            capture: None,
            displayable,
        };
        let mut live = live;
        self.on_swapchain(&mut live)?;
        self.live = Some(live);
        eprintln!(
            "press F1 in the window for the viewer keys, H to hide the overlay, O for its full \
             panel"
        );
        Ok(())
    }

    /// After (re)creating the swapchain: match the renderer to it and report it.
    fn on_swapchain(&mut self, live: &mut Live) -> Result<()> {
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
    fn fit_renderer(&mut self, (w, h): (u32, u32)) -> Result<()> {
        let s = self.options.render_scale;
        let scaled = |n: u32| ((n as f32 * s).round() as u32).max(1);
        let (w, h) = (scaled(w), scaled(h));
        let renderer = self
            .renderer
            .as_mut()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        if (renderer.config.width, renderer.config.height) != (w, h) {
            let pending = renderer.resize(w, h)?;
            self.absorb(pending);
        }
        Ok(())
    }

    fn act(&mut self, event_loop: &ActiveEventLoop, action: Action) {
        match action {
            Action::GroundTruth => return self.toggle_truth(),
            Action::ErrorMap => {
                self.show_error_map = self.error_map.is_some() && !self.show_error_map;
                return match (&self.error_map, self.show_error_map) {
                    (None, _) => self.report("no error map: press G for the ground truth".into()),
                    (Some(_), on) => {
                        eprintln!("error map: {}", if on { "shown" } else { "hidden" })
                    }
                };
            }
            _ => {}
        }
        let Some(view) = self.view.as_mut() else {
            return;
        };
        match action {
            Action::CycleDisplay(step) => {
                let n = display_cycle().len() as i32;
                let displayable = self.live.as_ref().map(|l| l.displayable.clone());
                for _ in 0..n {
                    view.display = (view.display as i32 + step).rem_euclid(n) as usize;
                    if displayable.as_ref().is_none_or(|d| d[view.display]) {
                        break;
                    }
                }
                eprintln!("display: {}", view.display_name());
            }
            Action::ToggleShadows => view.soft_shadows = !view.soft_shadows,
            Action::ToggleEffect(name) => view.toggle_effect(name),
            Action::ToggleSetting(i) => {
                if let Some(on) = view.toggles.get_mut(i) {
                    *on = !*on;
                }
            }
            Action::ToggleReuse => view.temporal_reuse = !view.temporal_reuse,
            Action::Screenshot => self.shot_pending = true,
            Action::GroundTruth | Action::ErrorMap => {} // above: they need the whole viewer
            Action::ToggleOverlay => match self.live.as_mut().and_then(|l| l.overlay.as_mut()) {
                Some(overlay) => {
                    overlay.toggle();
                    eprintln!(
                        "overlay: {}",
                        if overlay.visible() { "shown" } else { "hidden" }
                    );
                }
                None => eprintln!("overlay: off for this run (--overlay off)"),
            },
            Action::ToggleOverlayDetail => {
                match self.live.as_mut().and_then(|l| l.overlay.as_mut()) {
                    Some(overlay) => {
                        overlay.toggle_detail();
                        eprintln!(
                            "overlay: {}",
                            if overlay.full() {
                                "full panel"
                            } else {
                                "compact"
                            }
                        );
                    }
                    None => eprintln!("overlay: off for this run (--overlay off)"),
                }
            }
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
            Action::Help => eprintln!("{}", help()),
            Action::Quit => event_loop.exit(),
        }
        if !matches!(
            action,
            Action::CycleDisplay(_)
                | Action::PrintCamera
                | Action::ToggleOverlay
                | Action::ToggleOverlayDetail
                | Action::Screenshot
                | Action::GroundTruth
                | Action::ErrorMap
                | Action::Help
                | Action::Quit
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
        let (Some(view), Some(renderer)) = (self.view.as_ref(), self.renderer.as_ref()) else {
            return Ok(());
        };
        let wanted = view.config(&renderer.config);
        let what = view.summary();
        if !self.apply_config(wanted, &what)? {
            self.reset_view();
        }
        Ok(())
    }

    /// A live setting (the overlay's controls, a script's `set=KEY:VALUE`): `name` is a sweep
    /// key and `value` goes through the same parser as the command line's option, then the
    /// configuration through `RenderConfig::validate`. A refused value is reported (stderr and
    /// the overlay) and changes nothing.
    fn set_setting(&mut self, name: &str, value: &str) -> Result<()> {
        if name == RENDER_SCALE {
            return self.set_render_scale(value);
        }
        let Some(renderer) = self.renderer.as_ref() else {
            return Ok(());
        };
        let mut wanted = renderer.config;
        let checked = crate::sweep::keys::parse_key(name).and_then(|key| {
            (key.set)(&mut wanted, value.trim()).map_err(|why| {
                Error::Config(format!(
                    "invalid value {value:?} for {name} ({why}); expected {}",
                    key.syntax
                ))
            })?;
            wanted.validate()
        });
        if let Err(e) = checked {
            self.report(format!("cannot set {name}={value}: {e}"));
            return Ok(());
        }
        if self.apply_config(wanted, &format!("{name}={value}"))? {
            self.settings.retain(|(n, _)| n != name);
            self.settings
                .push((name.to_string(), value.trim().to_string()));
            self.report(format!("set {name}={value}"));
        }
        self.reset_view();
        Ok(())
    }

    /// The viewer's own setting: the render scale (`--render-scale`'s parser).
    fn set_render_scale(&mut self, value: &str) -> Result<()> {
        match parse_render_scale(value) {
            Ok(scale) => {
                self.options.render_scale = scale;
                if let Some(extent) = self.live.as_ref().map(|l| l.swapchain.extent) {
                    self.fit_renderer((extent.width, extent.height))?;
                }
                self.history = History::default();
                self.settings.retain(|(n, _)| n != RENDER_SCALE);
                self.settings
                    .push((RENDER_SCALE.to_string(), value.trim().to_string()));
                self.report(format!("set {RENDER_SCALE}={value}"));
            }
            Err(why) => self.report(format!("cannot set {RENDER_SCALE}={value}: {why}")),
        }
        Ok(())
    }

    /// Make the renderer's configuration `wanted` (`what` names the change): in place when
    /// only the PCF kernel differs, else by rebuilding the renderer on the same context and
    /// size (histories and the last second's statistics start over). False when the renderer
    /// rejected it (reported; the old one stays).
    fn apply_config(&mut self, wanted: RenderConfig, what: &str) -> Result<bool> {
        let Some(renderer) = self.renderer.as_mut() else {
            return Ok(false);
        };
        if !needs_rebuild(&renderer.config, &wanted) {
            renderer.config = wanted;
            return Ok(true);
        }
        let pending = renderer.finish()?;
        let rebuilt = Renderer::new(&self.ctx, renderer.scene.clone(), wanted);
        self.absorb(pending);
        let applied = match rebuilt {
            Ok(rebuilt) => {
                if let Some(r) = self.renderer.as_mut() {
                    *r = rebuilt;
                }
                self.history = History::default();
                eprintln!("renderer rebuilt: {what}");
                if self.error_map.is_some() {
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
        Ok(applied)
    }

    /// The viewer's switches from the renderer's configuration, keeping the displayed buffer.
    fn reset_view(&mut self) {
        if let (Some(view), Some(renderer)) = (self.view.as_mut(), self.renderer.as_ref()) {
            let display = view.display;
            *view = ViewState::new(&renderer.config);
            view.display = display;
        }
    }

    /// G: trace the ground truth of the held view in the background, or cancel the tracing.
    fn toggle_truth(&mut self) {
        if let Some(job) = self.truth.take() {
            job.cancel();
            self.truth_text.clear();
            self.report("ground truth cancelled (G)".into());
            return;
        }
        let Some(r) = self.renderer.as_ref() else {
            return;
        };
        let camera = self.camera.unwrap_or(r.scene.camera);
        let scene = r.scene.posed(self.scene_time);
        let settings = Settings::for_render(&r.config, &scene);
        let (w, h) = (r.config.width, r.config.height);
        eprintln!(
            "ground truth: tracing {w}x{h} from the held camera on {} threads (G or moving \
             cancels)",
            rayon::current_num_threads()
        );
        self.truth = Some(TruthJob::start(
            scene,
            camera,
            (w, h),
            settings,
            Some(default_dir()),
        ));
    }

    /// Each frame: a camera other than the traced one cancels the job; a finished one scores
    /// the frame.
    fn check_truth(&mut self, camera: &Camera) -> Result<()> {
        let Some(job) = self.truth.as_mut() else {
            return Ok(());
        };
        if job.camera() != *camera {
            if let Some(job) = self.truth.take() {
                job.cancel();
            }
            self.truth_text.clear();
            self.report("ground truth cancelled: the camera moved".into());
            return Ok(());
        }
        let progress = job.progress();
        match job.poll() {
            None => {
                self.truth_text = vec![format!(
                    "ground truth: {:.0}% traced (G cancels)",
                    100.0 * progress
                )];
                Ok(())
            }
            Some(result) => match self.truth.take() {
                Some(job) => self.score_truth(&job, result),
                None => Ok(()),
            },
        }
    }

    /// The frame now on screen against the traced reference, as the sweep scores it.
    fn score_truth(&mut self, job: &TruthJob, result: Result<Reference>) -> Result<()> {
        let reference = match result {
            Ok(r) => r,
            Err(e) => {
                self.truth_text.clear();
                self.report(format!("ground truth failed: {e}"));
                return Ok(());
            }
        };
        let renderer = self
            .renderer
            .as_mut()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        let pending = renderer.finish()?;
        let last = read_frame(renderer, job.camera())?;
        let terms = crate::effects::estimated_terms(&renderer.config);
        let errors = ground_truth::errors(&last, &reference, job.scene(), terms)?;
        let map = ground_truth::final_flip_map(&last, &reference, job.scene(), terms)?;
        self.absorb(pending);
        self.error_map = match map {
            Some((rgba, w, h)) => {
                let image = Image::new(
                    &self.ctx,
                    "ground truth FLIP map",
                    ImageDesc {
                        width: w,
                        height: h,
                        format: ash::vk::Format::R8G8B8A8_UNORM,
                        // SAMPLED: every image gets a view (memory.rs), which needs a
                        // view-compatible usage; the map is only blitted.
                        usage: ash::vk::ImageUsageFlags::TRANSFER_SRC
                            | ash::vk::ImageUsageFlags::TRANSFER_DST
                            | ash::vk::ImageUsageFlags::SAMPLED,
                    },
                )?;
                upload_image(
                    &self.ctx,
                    &mut Tracker::default(),
                    &image,
                    &rgba,
                    Access::TransferSrc,
                )?;
                Some((image, job.camera()))
            }
            None => None,
        };
        self.truth_text = errors
            .iter()
            .map(|(b, e)| {
                let flip = e.flip.map_or(String::new(), |f| format!(" flip {f:.9e}"));
                format!("ground truth: {} rmse {:.9e}{flip}", b.name(), e.error.rmse)
            })
            .collect();
        for line in &self.truth_text {
            eprintln!("{line}");
        }
        self.message = None;
        Ok(())
    }

    /// The error map no longer matches the view (`why`): drop it, and the scores with it.
    fn drop_error_map(&mut self, why: &str) {
        self.error_map = None;
        self.show_error_map = false;
        self.truth_text.clear();
        self.report(format!("ground truth dropped: {why}"));
    }

    /// A message for the user: stderr, and the overlay's status line.
    fn report(&mut self, message: String) {
        eprintln!("{message}");
        self.message = Some(message);
    }

    fn run_script(&mut self, event_loop: &ActiveEventLoop) {
        for op in script::take_due(&mut self.options.script, self.presented) {
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
                    let index = display_cycle().iter().position(|(_, n)| *n == name);
                    let shown = self.live.as_ref().map(|l| l.displayable.clone());
                    match (index, self.view.as_mut(), shown) {
                        (Some(i), Some(view), Some(shown)) if shown[i] => {
                            view.display = i;
                            eprintln!("display: {name}");
                        }
                        _ => eprintln!("display: {name} is not available in this run"),
                    }
                }
                ScriptOp::WaitTruth => {
                    let result = self.truth.take().and_then(|mut job| {
                        let result = job.wait()?;
                        Some((job, result))
                    });
                    match result {
                        Some((job, result)) => {
                            if let Err(e) = self.score_truth(&job, result) {
                                self.fail(event_loop, e);
                            }
                        }
                        None => eprintln!("script: no ground truth is being traced"),
                    }
                }
                ScriptOp::Move(fraction) => {
                    if let Some(r) = self.renderer.as_ref() {
                        let c = self.camera.unwrap_or(r.scene.camera);
                        let step = c.frame().0 * fraction * r.scene.mesh.bounds.radius();
                        let mut moved = c;
                        moved.position += step;
                        moved.target += step;
                        self.camera = Some(moved);
                        eprintln!("script: camera moved forward by {fraction} scene radii");
                    }
                }
                ScriptOp::Set(key, value) => {
                    if let Err(e) = self.set_setting(&key, &value) {
                        self.fail(event_loop, e);
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
        if self.input.fly.is_idle() {
            return base; // unchanged, bit for bit (the screenshot test relies on it)
        }
        let radius = renderer.map_or(1.0, |r| r.scene.mesh.bounds.radius().max(1e-3));
        let cam = fly_camera::step(base, &self.input.fly, dt, fly_camera::base_speed(radius));
        self.input.fly.look = (0.0, 0.0);
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
        for request in std::mem::take(&mut self.requests) {
            match request {
                Request::Action(a) => self.act(event_loop, a),
                Request::Set(key, value) => self.set_setting(key, &value)?,
                Request::CommandLine => {
                    if let Some(r) = self.renderer.as_ref() {
                        let line = command_line(&self.command, &r.config, &self.settings);
                        self.report(line);
                    }
                }
            }
        }
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
        self.check_truth(&camera)?;
        if self.error_map.as_ref().is_some_and(|(_, c)| *c != camera) {
            self.drop_error_map("the camera moved");
        }
        self.scene_time += dt;
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
        let shoot = std::mem::take(&mut self.shot_pending);
        let bytes = live.swapchain.extent.width as u64 * live.swapchain.extent.height as u64 * 4;
        if (capture_now || shoot) && live.capture.as_ref().is_none_or(|b| b.size != bytes) {
            live.capture = Some(live.swapchain.readback_buffer()?);
        }
        let capture = live.capture.as_ref().filter(|_| capture_now || shoot);
        renderer.set_time(self.scene_time);
        let (w, h) = (renderer.config.width, renderer.config.height);
        let shown = format!(
            "{w}x{h} | {} | {}",
            self.view.as_ref().map_or("final", |v| v.display_name()),
            self.view.as_ref().map_or(String::new(), |v| v.summary()),
        );
        let draws = live.overlay.as_ref().is_some_and(|o| o.visible());
        let mut overlay = live.overlay.as_mut().filter(|o| o.visible());
        let (mut pending, mut requests) = (Vec::new(), Vec::new());
        if let Some(o) = overlay.as_mut() {
            let stats = self.history.window(Instant::now());
            let text = PanelText {
                view: &shown,
                message: self.message.as_deref(),
                truth: &self.truth_text,
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
        let replace = self
            .error_map
            .as_ref()
            .filter(|_| self.show_error_map)
            .map(|(image, _)| image);
        let presented = render_and_present(
            &mut live.swapchain,
            renderer,
            &camera,
            (source, replace),
            capture,
            draws.then_some(&mut draw as OverlayDraw<'_>),
        )?;
        self.absorb(pending);
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
        self.presented += 1;
        self.absorb(timing.into_iter().collect());
        if let Some(last) = self.last_frame {
            let ms = (now - last).as_secs_f64() * 1e3;
            self.stats.add_wall(ms);
            self.history.add_wall(Instant::now(), ms);
        }
        if shoot {
            self.screenshot(live)?;
        }
        self.requests.extend(requests);
        self.last_frame = Some(now);
        let prefix = format!("{} | {shown}", self.options.title);
        if let Some(title) = self.stats.title(&prefix) {
            live.window.set_title(&title);
        }
        Ok(())
    }

    fn absorb(&mut self, timings: Vec<FrameTiming>) {
        for t in timings {
            self.stats.add_gpu(&t);
            self.history.add_gpu(Instant::now(), t.clone());
            self.timings.push(t);
        }
    }

    /// The screenshot key: wait for the frame just presented (its copy into the readback
    /// buffer), then write it and the last second's report.
    fn screenshot(&mut self, live: &mut Live) -> Result<()> {
        let renderer = self
            .renderer
            .as_mut()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        let pending = renderer.finish()?;
        self.absorb(pending);
        let buffer = live
            .capture
            .as_ref()
            .ok_or_else(|| Error::Window("no readback buffer".into()))?;
        let image = live.swapchain.read_buffer(buffer)?;
        let (timings, seconds) = self.history.frames(Instant::now());
        let renderer = self
            .renderer
            .as_ref()
            .ok_or_else(|| Error::Window("no renderer".into()))?;
        let mode = present_mode_name(live.swapchain.present_mode);
        let report = screenshot::report(&self.ctx, renderer, &timings, seconds, mode);
        let (png, json) = screenshot::write(
            &self.options.screenshot_dir,
            self.presented,
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

/// Mouse buttons and wheel, which the overlay may take; keys always reach the viewer (the
/// overlay has no text fields), and so do cursor moves (a drag begun outside the panel keeps
/// turning the camera across it).
fn is_pointer(event: &WindowEvent) -> bool {
    matches!(
        event,
        WindowEvent::MouseInput { .. } | WindowEvent::MouseWheel { .. }
    )
}

/// Per display-cycle entry, whether it can be shown: the target exists in this run (the
/// buffers of effects that are off do not) and is written (the direct and shadow
/// targets exist without direct light, unwritten), and its format can be blitted into the
/// swapchain (depth and integer formats cannot).
fn displayable(renderer: &Renderer, swapchain: &Swapchain) -> Vec<bool> {
    display_cycle()
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
        if let Some(live) = self.live.as_mut() {
            let window = live.window.clone();
            if let Some(o) = live.overlay.as_mut() {
                if o.on_window_event(&window, &event) && is_pointer(&event) {
                    return; // a drag or click on the panel does not turn the camera
                }
            }
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(_) => {
                if let Some(live) = self.live.as_mut() {
                    live.swapchain.invalidate();
                }
            }
            WindowEvent::ModifiersChanged(m) => self.input.set_modifiers(m.state()),
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
                if let Some(a) = self.input.key(key, state == ElementState::Pressed, repeat) {
                    self.act(event_loop, a);
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => self.input.left_button(state == ElementState::Pressed),
            WindowEvent::CursorMoved { position, .. } => {
                self.input.cursor_moved((position.x, position.y));
            }
            WindowEvent::Focused(false) => self.input.focus_lost(),
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
