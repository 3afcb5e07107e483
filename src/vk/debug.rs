//! `VK_EXT_debug_utils` names and command labels: every image, buffer, pipeline and descriptor
//! set gets its ssgi name, every pass runs inside a label with its `PassId` name, so validation
//! messages, RenderDoc captures and device-loss reports say which object and pass they mean.
//! Without the extension (some drivers omit it outside validation) naming does nothing.

use ash::{ext, vk};
use std::ffi::CString;

/// The device-level debug-utils functions, when the instance enabled the extension.
pub struct DebugNames {
    utils: Option<ext::debug_utils::Device>,
}

impl DebugNames {
    pub fn new(instance: &ash::Instance, device: &ash::Device, enabled: bool) -> Self {
        Self {
            utils: enabled.then(|| ext::debug_utils::Device::new(instance, device)),
        }
    }

    pub fn enabled(&self) -> bool {
        self.utils.is_some()
    }

    /// Give `handle` the name `name` (interior NULs are replaced: names are for people).
    pub fn set<H: vk::Handle>(&self, handle: H, name: &str) {
        let Some(utils) = &self.utils else { return };
        let name = c_name(name);
        let info = vk::DebugUtilsObjectNameInfoEXT::default()
            .object_handle(handle)
            .object_name(&name);
        // SAFETY: `handle` is a live object of this device; the name outlives the call. A
        // failure to name is not worth failing the caller for (names are diagnostics only).
        let _ = unsafe { utils.set_debug_utils_object_name(&info) };
    }

    /// Open a label region `name` in `cmd` (closed by [`Self::end_label`]).
    pub fn begin_label(&self, cmd: vk::CommandBuffer, name: &str) {
        let Some(utils) = &self.utils else { return };
        let name = c_name(name);
        let label = vk::DebugUtilsLabelEXT::default().label_name(&name);
        // SAFETY: `cmd` is recording; the label is copied by the call.
        unsafe { utils.cmd_begin_debug_utils_label(cmd, &label) };
    }

    pub fn end_label(&self, cmd: vk::CommandBuffer) {
        let Some(utils) = &self.utils else { return };
        // SAFETY: `cmd` is recording inside a region opened by `begin_label`.
        unsafe { utils.cmd_end_debug_utils_label(cmd) };
    }
}

fn c_name(name: &str) -> CString {
    CString::new(name.replace('\0', " ")).unwrap_or_default()
}
