//! Window surfaces (VK_KHR_surface + the platform extension ash-window picks for the window's
//! display: Xlib/Xcb on X11, Wayland, Win32, Metal).

use super::context::Context;
use crate::error::{Error, Result, VkContext};
use ash::{khr, vk};
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use std::any::Any;
use std::ffi::CStr;
use std::sync::Arc;

/// The instance extensions a surface for `display` needs (pass them in
/// `ContextOptions::instance_extensions`).
pub fn instance_extensions(display: &impl HasDisplayHandle) -> Result<Vec<&'static CStr>> {
    let handle = display
        .display_handle()
        .map_err(|e| Error::Window(format!("no display handle: {e}")))?;
    let names = ash_window::enumerate_required_extensions(handle.as_raw())
        .vk("ash_window::enumerate_required_extensions")?;
    Ok(names
        .iter()
        // SAFETY: ash-window returns pointers to `'static` NUL-terminated extension-name
        // constants of ash (`surface::NAME`, `xlib_surface::NAME`, ...).
        .map(|&p| unsafe { CStr::from_ptr(p) })
        .collect())
}

/// A presentable surface of a window. Holds the window (so the native window outlives the
/// surface) and the context (so the instance outlives it); destroyed in `Drop`, after every
/// swapchain made from it (a `Swapchain` owns its surface and destroys the swapchain first).
pub struct Surface {
    ctx: Arc<Context>,
    pub(crate) loader: khr::surface::Instance,
    pub raw: vk::SurfaceKHR,
    _window: Arc<dyn Any + Send + Sync>,
}

impl Surface {
    /// Create a surface for `window` and check that the context's queue can present to it.
    pub fn new<W>(ctx: &Arc<Context>, window: Arc<W>) -> Result<Self>
    where
        W: HasWindowHandle + HasDisplayHandle + Send + Sync + 'static,
    {
        let display = window
            .display_handle()
            .map_err(|e| Error::Window(format!("no display handle: {e}")))?
            .as_raw();
        let handle = window
            .window_handle()
            .map_err(|e| Error::Window(format!("no window handle: {e}")))?
            .as_raw();
        let entry = &ctx.instance.entry;
        let instance = &ctx.instance.raw;
        // SAFETY: the handles come from a live window that this `Surface` keeps alive (the Arc
        // below) until after the surface is destroyed; the instance was created with the
        // extensions `instance_extensions` names for this display (else the call fails with
        // ERROR_EXTENSION_NOT_PRESENT, reported below).
        let raw = unsafe { ash_window::create_surface(entry, instance, display, handle, None) }
            .vk("vkCreate*SurfaceKHR")?;
        let loader = khr::surface::Instance::new(entry, instance);
        let surface = Surface {
            ctx: ctx.clone(),
            loader,
            raw,
            _window: window,
        };
        // SAFETY: the physical device and queue family belong to this instance; the surface
        // is live.
        let supported = unsafe {
            surface
                .loader
                .get_physical_device_surface_support(ctx.physical, ctx.queue_family, raw)
        }
        .vk("vkGetPhysicalDeviceSurfaceSupportKHR")?;
        if !supported {
            return Err(Error::MissingFeature(format!(
                "presentation to this window from {} (queue family {}); pick another device \
                 with --device",
                ctx.info.name, ctx.queue_family
            )));
        }
        Ok(surface)
    }

    pub fn capabilities(&self) -> Result<vk::SurfaceCapabilitiesKHR> {
        // SAFETY: live surface of this instance's physical device.
        unsafe {
            self.loader
                .get_physical_device_surface_capabilities(self.ctx.physical, self.raw)
        }
        .vk("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")
    }

    pub fn formats(&self) -> Result<Vec<vk::SurfaceFormatKHR>> {
        // SAFETY: live surface of this instance's physical device.
        unsafe {
            self.loader
                .get_physical_device_surface_formats(self.ctx.physical, self.raw)
        }
        .vk("vkGetPhysicalDeviceSurfaceFormatsKHR")
    }

    pub fn present_modes(&self) -> Result<Vec<vk::PresentModeKHR>> {
        // SAFETY: live surface of this instance's physical device.
        unsafe {
            self.loader
                .get_physical_device_surface_present_modes(self.ctx.physical, self.raw)
        }
        .vk("vkGetPhysicalDeviceSurfacePresentModesKHR")
    }
}

impl Drop for Surface {
    fn drop(&mut self) {
        // SAFETY: every swapchain of this surface was destroyed first (the owning `Swapchain`
        // destroys its swapchain before its fields drop); the instance is still alive through
        // `ctx`, and the window through `_window`.
        unsafe { self.loader.destroy_surface(self.raw, None) };
    }
}
