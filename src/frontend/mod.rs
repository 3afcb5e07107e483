//! Frontends sharing one renderer: headless (offscreen + PNG), the interactive window
//! (`view`) and the presenting window of scripted runs (`bench --window`, `table --window`).

pub mod display;
pub mod headless;
pub mod overlay;
pub mod png;
pub mod progress;
pub mod sink;
pub mod swapchain_frame;
pub mod view_state;
pub mod window;
pub mod window_sink;
