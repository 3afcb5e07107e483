//! A window for scripted runs: `ssgi bench --window` and `ssgi table --window`. The run's own
//! loop drives the frames and pumps winit's event loop between them (non-blocking), so one
//! window, one swapchain and one context serve every renderer a table creates in turn, and
//! the table code is the same loop as offscreen (a [`FrameSink`]). [`open_sink`] picks this
//! window or offscreen for a run's `--window` flag.
//!
//! Pumping is what winit offers for an external loop on X11, Wayland and Windows (the
//! platforms ssgi presents on). Each frame: handle pending window events (close or Escape
//! ends the run with an error, since a partial table has no report; a resize marks the
//! swapchain stale); recreate a stale swapchain, waiting while the window has a zero extent;
//! render into the acquired image and present. The renderer keeps its own size: the blit
//! scales its output to the window.

use super::display::{new_event_loop, presenting_context};
use super::sink::{FrameSink, Offscreen};
use super::swapchain_frame::{recreate, render_and_present, Presented, Recreated};
use crate::error::{Error, Result};
use crate::renderer::{Renderer, FRAMES_IN_FLIGHT};
use crate::resources::targets::Target;
use crate::scene::Camera;
use crate::vk::swapchain::present_mode_name;
use crate::vk::{
    Context, ContextOptions, FrameTiming, PresentPolicy, Surface, Swapchain, SwapchainOptions,
};
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::platform::pump_events::{EventLoopExtPumpEvents, PumpStatus};
use winit::window::{Window, WindowAttributes, WindowId};

/// How long the window system gets to open the window.
const OPEN_TIMEOUT: Duration = Duration::from_secs(10);
/// Event wait while the window has a zero extent (minimised): low CPU, prompt resume.
const PAUSED_POLL: Duration = Duration::from_millis(50);
/// Out-of-date results in a row before giving up on a frame (each one recreates the
/// swapchain; a surface that never settles is an error, not a hang).
const MAX_OUT_OF_DATE: u32 = 16;
/// Title refresh interval.
const TITLE_EVERY: Duration = Duration::from_millis(250);

/// What the pumped event handler saw.
#[derive(Default)]
struct Events {
    /// Taken when the event loop is ready to create the window.
    attributes: Option<WindowAttributes>,
    /// The created window, until `open` takes it.
    window: Option<Arc<Window>>,
    create_error: Option<String>,
    /// Close button or Escape.
    closed: bool,
    resized: bool,
}

impl ApplicationHandler for Events {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(attributes) = self.attributes.take() {
            match event_loop.create_window(attributes) {
                Ok(w) => self.window = Some(Arc::new(w)),
                Err(e) => self.create_error = Some(e.to_string()),
            }
        }
    }

    fn window_event(&mut self, _: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => self.closed = true,
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        physical_key: PhysicalKey::Code(KeyCode::Escape),
                        state: ElementState::Pressed,
                        ..
                    },
                ..
            } => self.closed = true,
            WindowEvent::Resized(_) => self.resized = true,
            _ => {}
        }
    }
}

/// One window presenting the frames of any number of renderers on its context. Fields drop
/// in order: the swapchain (and its surface) before the window, the event loop last but the
/// context.
pub struct WindowPresenter {
    swapchain: Swapchain,
    window: Arc<Window>,
    events: Events,
    event_loop: EventLoop<()>,
    ctx: Arc<Context>,
    title: String,
    label: String,
    /// Frames presented since the window opened, and in the current run.
    presented: u64,
    run_frames: u64,
    paused: bool,
    title_at: Instant,
}

impl WindowPresenter {
    /// Open a `size` window titled `title` and a context (from `context`, plus what presenting
    /// needs) for the renderers that will present to it.
    pub fn open(title: &str, size: (u32, u32), context: ContextOptions) -> Result<Self> {
        let mut event_loop = new_event_loop()?;
        let ctx = presenting_context(context, &event_loop)?;
        let mut events = Events {
            attributes: Some(
                Window::default_attributes()
                    .with_title(title)
                    .with_inner_size(PhysicalSize::new(size.0.max(1), size.1.max(1)))
                    .with_resizable(false),
            ),
            ..Events::default()
        };
        let start = Instant::now();
        let window = loop {
            let status = event_loop.pump_app_events(Some(Duration::from_millis(10)), &mut events);
            if let Some(e) = events.create_error.take() {
                return Err(Error::Window(format!(
                    "cannot create the window: {}",
                    super::display::user_text(&e)
                )));
            }
            if let Some(w) = events.window.take() {
                break w;
            }
            if let PumpStatus::Exit(code) = status {
                return Err(Error::Window(format!(
                    "the event loop exited (code {code}) before the window opened"
                )));
            }
            if start.elapsed() > OPEN_TIMEOUT {
                return Err(Error::Window(format!(
                    "the window system did not open the window within {} s",
                    OPEN_TIMEOUT.as_secs()
                )));
            }
        };
        let surface = Surface::new(&ctx, window.clone())?;
        let inner = window.inner_size();
        let swapchain = Swapchain::new(
            &ctx,
            surface,
            (inner.width, inner.height),
            SwapchainOptions {
                policy: PresentPolicy::Benchmark,
                frames_in_flight: FRAMES_IN_FLIGHT,
                readable: false,
            },
        )?;
        eprintln!(
            "present mode for benchmarking: {} (preference: immediate, mailbox, fifo)",
            present_mode_name(swapchain.present_mode)
        );
        Ok(Self {
            swapchain,
            window,
            events,
            event_loop,
            ctx,
            title: title.to_string(),
            label: String::new(),
            presented: 0,
            run_frames: 0,
            paused: false,
            title_at: Instant::now(),
        })
    }

    pub fn ctx(&self) -> &Arc<Context> {
        &self.ctx
    }

    /// Dispatch pending window events, waiting up to `wait` for one.
    fn pump(&mut self, wait: Duration) -> Result<()> {
        let status = self
            .event_loop
            .pump_app_events(Some(wait), &mut self.events);
        if self.events.closed || matches!(status, PumpStatus::Exit(_)) {
            return Err(Error::Window(format!(
                "the window was closed after {} frames of \"{}\"; no report",
                self.run_frames, self.label
            )));
        }
        if std::mem::take(&mut self.events.resized) {
            self.swapchain.invalidate();
        }
        Ok(())
    }

    /// Recreate the swapchain while it is stale, waiting (pumping events) while the window has
    /// a zero extent. Returns the timings of the frames the renderer finished meanwhile.
    fn ready_swapchain(&mut self, renderer: &mut Renderer) -> Result<Vec<FrameTiming>> {
        let mut timings = Vec::new();
        while self.swapchain.is_stale() || self.paused {
            let inner = self.window.inner_size();
            match recreate(&mut self.swapchain, (inner.width, inner.height), renderer)? {
                Recreated::Ready(pending) => {
                    timings.extend(pending);
                    if self.paused {
                        eprintln!("window restored: run resumed");
                    }
                    self.paused = false;
                }
                Recreated::ZeroExtent => {
                    if !self.paused {
                        eprintln!("window minimised (zero extent): run paused until restored");
                    }
                    self.paused = true;
                    self.pump(PAUSED_POLL)?;
                }
            }
        }
        Ok(timings)
    }

    fn update_title(&mut self) {
        if self.title_at.elapsed() < TITLE_EVERY {
            return;
        }
        self.title_at = Instant::now();
        self.window.set_title(&format!(
            "{} | {} | frame {}",
            self.title, self.label, self.run_frames
        ));
    }
}

impl FrameSink for WindowPresenter {
    fn begin(&mut self, label: &str) {
        self.label = label.to_string();
        self.run_frames = 0;
        self.title_at = Instant::now() - TITLE_EVERY;
        self.update_title();
    }

    fn frame(&mut self, renderer: &mut Renderer, camera: &Camera) -> Result<Vec<FrameTiming>> {
        let mut timings = Vec::new();
        for _ in 0..MAX_OUT_OF_DATE {
            self.pump(Duration::ZERO)?;
            timings.extend(self.ready_swapchain(renderer)?);
            match render_and_present(
                &mut self.swapchain,
                renderer,
                camera,
                (Target::Output, None),
                None,
                None,
            )? {
                Presented::Frame(t) => {
                    timings.extend(t);
                    self.presented += 1;
                    self.run_frames += 1;
                    self.update_title();
                    return Ok(timings);
                }
                Presented::OutOfDate => continue,
            }
        }
        Err(Error::Window(format!(
            "the swapchain stayed out of date through {MAX_OUT_OF_DATE} recreations"
        )))
    }

    fn present_mode(&self) -> Option<&'static str> {
        Some(present_mode_name(self.swapchain.present_mode))
    }

    fn frames_presented(&self) -> u64 {
        self.presented
    }
}

/// A context and the sink its renderers draw into: a presenting window titled `window` (of
/// `size`), or offscreen.
pub fn open_sink(
    window: Option<String>,
    size: (u32, u32),
    context: ContextOptions,
) -> Result<(Arc<Context>, Box<dyn FrameSink>)> {
    Ok(match window {
        Some(title) => {
            let presenter = WindowPresenter::open(&title, size, context)?;
            (presenter.ctx().clone(), Box::new(presenter))
        }
        None => (Context::new(&context)?, Box::new(Offscreen)),
    })
}
