//! Connecting to the window system: the winit event loop, and a Vulkan context that can
//! present to it (surface instance extensions + the swapchain device extension).

use crate::error::{Error, Result};
use crate::vk::{surface, Context, ContextOptions};
use std::sync::Arc;
use winit::event_loop::EventLoop;

/// The process's event loop (winit allows one per process).
pub fn new_event_loop() -> Result<EventLoop<()>> {
    let mut builder = EventLoop::builder();
    #[cfg(all(unix, not(target_os = "macos"), not(target_os = "android")))]
    {
        // Tests drive the window from a test thread; the CLI runs it on the main thread.
        use winit::platform::x11::EventLoopBuilderExtX11;
        builder.with_any_thread(true);
    }
    builder.build().map_err(|e| {
        Error::Window(format!(
            "cannot open a window: {} (set DISPLAY, or run under Xvfb: \
             `Xvfb :99 & DISPLAY=:99 ssgi ...`)",
            user_text(&e)
        ))
    })
}

/// A window-system error as a user should read it: winit's OS errors begin with the source
/// location inside winit (`os error at .../mod.rs:765: `), which means nothing to them.
pub fn user_text(e: &impl std::fmt::Display) -> String {
    let text = e.to_string();
    if let Some(rest) = text.strip_prefix("os error at ") {
        if let Some(i) = rest.find(".rs:") {
            if let Some(j) = rest[i..].find(": ") {
                return rest[i + j + 2..].to_string();
            }
        }
    }
    text
}

/// A context on `options` that can present to windows of `event_loop`'s display.
pub fn presenting_context(
    options: ContextOptions,
    event_loop: &EventLoop<()>,
) -> Result<Arc<Context>> {
    let mut options = options;
    for e in surface::instance_extensions(event_loop)? {
        if !options.instance_extensions.contains(&e) {
            options.instance_extensions.push(e);
        }
    }
    if !options
        .device_extensions
        .contains(&ash::khr::swapchain::NAME)
    {
        options.device_extensions.push(ash::khr::swapchain::NAME);
    }
    Context::new(&options)
}

#[cfg(test)]
mod tests {
    use super::user_text;

    #[test]
    fn winit_source_locations_are_dropped() {
        let raw = "os error at /root/.cargo/registry/src/x/winit-0.30.13/src/platform_impl/linux/\
                   mod.rs:765: neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set.";
        assert_eq!(
            user_text(&raw),
            "neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set."
        );
        assert_eq!(user_text(&"no adapter"), "no adapter");
    }
}
