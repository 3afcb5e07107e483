//! Window frontend: `ssgi view` (interactive fly camera). winit 0.30 `ApplicationHandler` + a
//! Vulkan swapchain; the same `Renderer` as the headless frontend, whose output (or another
//! target, for the buffer display) is blitted into the acquired swapchain image in the
//! renderer's frame hook. Scripted runs (`bench --window`, `table --window`) present through
//! `window_sink.rs` instead, which shares the frame steps in `swapchain_frame.rs`.
//!
//! Files: `app/` the application (its `mod.rs` lists a file per job: events, frame loop,
//! actions, renderer rebuilds, script, ground truth), `keys.rs` window input to viewer input,
//! `fly_camera.rs` the camera step, `script.rs` the test script, `stats.rs` the title's
//! timings, `screenshot.rs` the screenshot key's PNG and report, `truth.rs` the ground
//! truth on demand. Viewer keys: see [`help`] (`view_state.rs`).

mod app;
pub mod fly_camera;
pub mod keys;
mod screenshot;
pub mod script;
mod stats;
mod truth;

pub use super::view_state::{display_cycle, help, Action, ViewState};
pub use app::{run, WindowOptions, WindowRun};
pub use script::{parse_script, ScriptOp, ScriptStep};
