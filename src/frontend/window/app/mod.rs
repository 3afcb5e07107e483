//! The viewer application: opening the window and swapchain, and the state the viewer keeps
//! between frames. Each job on that state has its file: `events.rs` winit's event loop
//! (`ApplicationHandler`), `frame.rs` the frame loop, `actions.rs` the viewer's actions and
//! live settings, `rebuild.rs` fitting and rebuilding the renderer, `script_run.rs` the test
//! script's steps, `truth_view.rs` the ground truth and its error map.
//!
//! Frame loop (one `RedrawRequested`):
//! 1. if the swapchain is stale (resize, OUT_OF_DATE, SUBOPTIMAL): recreate it and resize the
//!    renderer's targets to the new extent; a zero extent (minimised) renders nothing and
//!    polls again later, keeping the event loop alive;
//! 2. wait for the renderer's next frame slot (so the slot's acquire semaphore is free);
//! 3. acquire an image; render the frame with a hook that blits into it and moves it to
//!    PRESENT_SRC; the submission waits on the acquire semaphore and signals the image's
//!    render-finished semaphore; present.

mod actions;
mod events;
mod frame;
mod rebuild;
mod script_run;
mod truth_view;

use super::keys;
use super::script::ScriptStep;
use super::stats::Stats;
use super::truth::TruthJob;
use crate::error::{Error, Result};
use crate::frontend::display::{new_event_loop, presenting_context};
use crate::frontend::overlay::{History, Overlay, Request};
use crate::frontend::view_state::{display_cycle, ViewState};
use crate::renderer::{Renderer, FRAMES_IN_FLIGHT};
use crate::resources::targets::Target;
use crate::scene::Camera;
use crate::vk::{
    Buffer, Context, ContextOptions, FrameTiming, Image, ImageData, PresentPolicy, Surface,
    Swapchain, SwapchainOptions,
};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

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
        viewer: Viewer::new(&renderer),
        renderer,
        live: None,
        error: None,
        frames: FrameLog::default(),
        captured: None,
        panel: PanelState {
            command: std::env::args().collect(),
            ..PanelState::default()
        },
        truth: TruthView::default(),
        pause: Pause::default(),
    };
    let result = event_loop.run_app(&mut app);
    // `exiting` normally shut down already; make sure (an error before the loop started).
    app.shutdown();
    if let Some(e) = app.error.take() {
        return Err(e);
    }
    result.map_err(|e| Error::Window(format!("event loop: {e}")))?;
    let App {
        ctx,
        renderer,
        mut frames,
        captured,
        ..
    } = app;
    frames.timings.sort_by_key(|t| t.frame);
    Ok(WindowRun {
        ctx,
        renderer,
        timings: frames.timings,
        frames_presented: frames.presented,
        captured,
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

/// The viewer. The renderer lives from `run` to its end (the run returns it), so it is never
/// missing; the window and swapchain (`live`) exist once winit has resumed the application.
struct App {
    options: WindowOptions,
    ctx: Arc<Context>,
    renderer: Renderer,
    live: Option<Live>,
    error: Option<Error>,
    frames: FrameLog,
    captured: Option<ImageData>,
    viewer: Viewer,
    panel: PanelState,
    truth: TruthView,
    pause: Pause,
}

/// Frames presented and their timings: every GPU timing (the run's result), the title's
/// averages, and the last second of frames (the overlay's statistics, the screenshot's
/// report).
struct FrameLog {
    timings: Vec<FrameTiming>,
    presented: u64,
    stats: Stats,
    history: History,
}

impl Default for FrameLog {
    fn default() -> Self {
        Self {
            timings: Vec::new(),
            presented: 0,
            stats: Stats::new(),
            history: History::default(),
        }
    }
}

impl FrameLog {
    /// GPU timings the renderer handed back (they arrive a frame or more late).
    fn absorb(&mut self, timings: Vec<FrameTiming>) {
        for t in timings {
            self.stats.add_gpu(&t);
            self.history.add_gpu(Instant::now(), t.clone());
            self.timings.push(t);
        }
    }
}

/// What the user steers between frames: the switches, the camera and the clock.
struct Viewer {
    view: ViewState,
    input: keys::Input,
    /// The viewer's camera (None until it moves: the scene camera).
    camera: Option<Camera>,
    /// Seconds into the scene's light and object paths: they play at wall-clock speed while
    /// frames are drawn (a minimised window pauses them).
    scene_time: f32,
    last_frame: Option<Instant>,
    /// The screenshot key was pressed: the next presented frame is written.
    shot_pending: bool,
}

impl Viewer {
    fn new(renderer: &Renderer) -> Self {
        Self {
            view: ViewState::new(&renderer.config),
            input: keys::Input::default(),
            camera: None,
            scene_time: 0.0,
            last_frame: None,
            shot_pending: false,
        }
    }

    /// The held camera: the viewer's, or the scene's until it moved.
    fn camera_or(&self, renderer: &Renderer) -> Camera {
        self.camera.unwrap_or(renderer.scene.camera)
    }
}

/// The overlay's side of the viewer: what its widgets asked for, what it says, and the
/// live settings behind its printed command line.
#[derive(Default)]
struct PanelState {
    /// Live settings applied (sweep key, value), latest last: the command line's additions.
    settings: Vec<(String, String)>,
    /// The last message for the overlay's status line (a refused setting, say).
    message: Option<String>,
    /// What the overlay's widgets asked for last frame (applied after it).
    requests: Vec<Request>,
    /// The command line the viewer started with (the base of the printed one).
    command: Vec<String>,
}

/// The ground truth on demand (G) and its error map (M).
#[derive(Default)]
struct TruthView {
    /// The ground truth being traced, and what the overlay says of it.
    job: Option<TruthJob>,
    text: Vec<String>,
    /// The final image's FLIP map from the last ground truth, the camera it belongs to, and
    /// whether it is shown in place of the image.
    error_map: Option<(Image, Camera)>,
    show_error_map: bool,
}

/// Why nothing is rendered for now.
#[derive(Default)]
struct Pause {
    /// Event-loop iterations left of a scripted zero extent.
    zero_ticks: u32,
    /// The window has a zero extent: nothing is rendered until it has one again.
    minimised: bool,
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

    /// A message for the user: stderr, and the overlay's status line.
    fn report(&mut self, message: String) {
        eprintln!("{message}");
        self.panel.message = Some(message);
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
        let displayable = displayable(&self.renderer, &swapchain);
        let overlay = match self.options.overlay {
            true => Some(Overlay::new(&self.ctx, &window, swapchain.format)?),
            false => None,
        };
        let mut live = Live {
            overlay,
            swapchain,
            window,
            capture: None,
            displayable,
        };
        self.on_swapchain(&mut live)?;
        self.live = Some(live);
        eprintln!(
            "press F1 in the window for the viewer keys, H to hide the overlay, O for its full \
             panel"
        );
        Ok(())
    }

    /// Wait for the GPU, read back a capture, destroy the swapchain, surface and window.
    fn shutdown(&mut self) {
        match self.renderer.finish() {
            Ok(pending) => self.frames.absorb(pending),
            Err(e) => {
                if self.error.is_none() {
                    self.error = Some(e);
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
