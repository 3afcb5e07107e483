//! Frontends sharing one renderer: headless (offscreen + PNG).

pub mod headless;
pub mod png;
pub mod progress;
