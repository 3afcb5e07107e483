//! Frontends sharing one renderer: headless (offscreen + PNG) and window (swapchain).

pub mod headless;
pub mod png;
pub mod progress;
pub mod window;
