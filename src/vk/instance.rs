//! Vulkan instance, validation layers (with synchronization validation) and the debug messenger
//! that records every validation message.

use crate::error::{Error, Result, VkContext};
use ash::{ext, vk};
use std::ffi::{c_void, CStr};
use std::sync::{Arc, Mutex};

const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// Every warning or error the validation layers reported. Tests and `--validation` runs fail
/// when it is not empty.
#[derive(Default, Debug)]
pub struct ValidationLog {
    messages: Mutex<Vec<String>>,
}

impl ValidationLog {
    pub fn messages(&self) -> Vec<String> {
        self.messages.lock().map(|m| m.clone()).unwrap_or_default()
    }

    pub fn count(&self) -> usize {
        self.messages.lock().map(|m| m.len()).unwrap_or(0)
    }

    /// `Err` with the first message when any was recorded.
    pub fn check(&self) -> Result<()> {
        let messages = self.messages();
        match messages.first() {
            None => Ok(()),
            Some(first) => Err(Error::Validation {
                count: messages.len(),
                first: first.clone(),
            }),
        }
    }

    fn push(&self, message: String) {
        if let Ok(mut m) = self.messages.lock() {
            m.push(message);
        }
    }
}

unsafe extern "system" fn debug_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    kind: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    // SAFETY: the layer passes a valid callback-data pointer for the duration of the call, and
    // `user` is the `ValidationLog` kept alive by the `Instance` that owns the messenger.
    let (message, context, log) = unsafe {
        let text = if data.is_null() || (*data).p_message.is_null() {
            "<no message>".to_string()
        } else {
            CStr::from_ptr((*data).p_message)
                .to_string_lossy()
                .into_owned()
        };
        let context = if data.is_null() {
            String::new()
        } else {
            named_context(&*data)
        };
        (text, context, &*(user as *const ValidationLog))
    };
    let line = format!("[{severity:?} {kind:?}] {message}{context}");
    eprintln!("vulkan: {line}");
    log.push(line);
    vk::FALSE
}

/// The debug names of the objects and the open command labels of a message, e.g.
/// ` [objects: VkImage "ao.history.0"] [labels: ssao]`, so a message always names what it is
/// about even when the layer's text does not.
///
/// # Safety
/// `data` must be the callback data the layer passed, valid for the duration of the call.
unsafe fn named_context(data: &vk::DebugUtilsMessengerCallbackDataEXT<'_>) -> String {
    let text = |p: *const std::ffi::c_char| {
        // SAFETY: the layer's strings are NUL-terminated and live for the call (caller).
        (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
    };
    // SAFETY: the layer passes `object_count` valid elements at `p_objects` (caller).
    let objects: Vec<String> = unsafe { raw_slice(data.p_objects, data.object_count) }
        .iter()
        .filter_map(|o| {
            Some(format!(
                "{:?} \"{}\"",
                o.object_type,
                text(o.p_object_name)?
            ))
        })
        .collect();
    // SAFETY: as above, `cmd_buf_label_count` labels at `p_cmd_buf_labels`.
    let mut labels: Vec<String> =
        unsafe { raw_slice(data.p_cmd_buf_labels, data.cmd_buf_label_count) }
            .iter()
            .filter_map(|l| text(l.p_label_name))
            .collect();
    // Some layer versions list the innermost region twice.
    labels.dedup();
    let mut out = String::new();
    if !objects.is_empty() {
        out += &format!(" [objects: {}]", objects.join(", "));
    }
    if !labels.is_empty() {
        out += &format!(" [labels: {}]", labels.join(" > "));
    }
    out
}

/// `n` elements at `ptr`, or none when it is null.
///
/// # Safety
/// A non-null `ptr` must point to `n` initialised elements that outlive `'a`.
unsafe fn raw_slice<'a, T>(ptr: *const T, n: u32) -> &'a [T] {
    if ptr.is_null() || n == 0 {
        &[]
    } else {
        // SAFETY: guaranteed by the caller.
        unsafe { std::slice::from_raw_parts(ptr, n as usize) }
    }
}

pub struct Instance {
    pub entry: ash::Entry,
    pub raw: ash::Instance,
    /// `VK_EXT_debug_utils` is enabled: objects can be named and passes labelled.
    pub debug_utils: bool,
    debug: Option<(ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    /// Present when validation is on.
    pub validation: Option<Arc<ValidationLog>>,
}

impl Instance {
    /// `extensions`: extra instance extensions (surface extensions for the window frontend).
    pub fn new(validation: bool, extensions: &[*const std::ffi::c_char]) -> Result<Self> {
        // SAFETY: loading the system Vulkan loader; the library stays loaded inside `Entry`.
        let entry = unsafe { ash::Entry::load() }.map_err(|e| Error::Loader(e.to_string()))?;
        let app = vk::ApplicationInfo::default()
            .application_name(c"ssgi")
            .engine_name(c"ssgi")
            .api_version(vk::API_VERSION_1_3);
        let mut ext_names: Vec<*const std::ffi::c_char> = extensions.to_vec();
        let mut layers = Vec::new();
        let log = validation.then(|| Arc::new(ValidationLog::default()));
        // Debug names and labels whenever the loader offers them (validation needs them too).
        // SAFETY: plain enumeration call on a loaded entry.
        let debug_utils = unsafe { entry.enumerate_instance_extension_properties(None) }
            .vk("vkEnumerateInstanceExtensionProperties")?
            .iter()
            .any(|e| e.extension_name_as_c_str() == Ok(ext::debug_utils::NAME));
        if debug_utils {
            ext_names.push(ext::debug_utils::NAME.as_ptr());
        }
        if validation {
            // SAFETY: plain enumeration call on a loaded entry.
            let available = unsafe { entry.enumerate_instance_layer_properties() }
                .vk("vkEnumerateInstanceLayerProperties")?;
            let has_layer = available
                .iter()
                .any(|l| l.layer_name_as_c_str() == Ok(VALIDATION_LAYER));
            if !has_layer {
                return Err(Error::MissingFeature(
                    "the validation layer VK_LAYER_KHRONOS_validation (install vulkan-validationlayers)"
                        .into(),
                ));
            }
            layers.push(VALIDATION_LAYER.as_ptr());
            if !debug_utils {
                // The layer provides the extension itself when the loader does not list it.
                ext_names.push(ext::debug_utils::NAME.as_ptr());
            }
            ext_names.push(ext::validation_features::NAME.as_ptr());
        }
        let enabled_features = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        let mut features =
            vk::ValidationFeaturesEXT::default().enabled_validation_features(&enabled_features);
        let mut info = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_layer_names(&layers)
            .enabled_extension_names(&ext_names);
        if validation {
            info = info.push_next(&mut features);
        }
        // SAFETY: every pointer in `info` refers to locals that outlive the call.
        let raw = unsafe { entry.create_instance(&info, None) }.vk("vkCreateInstance")?;
        let mut instance = Instance {
            entry,
            raw,
            debug_utils: debug_utils || validation,
            debug: None,
            validation: log,
        };
        if let Some(log) = &instance.validation {
            let loader = ext::debug_utils::Instance::new(&instance.entry, &instance.raw);
            let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
                .message_severity(
                    vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                        | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
                )
                .message_type(
                    vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                        | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE
                        | vk::DebugUtilsMessageTypeFlagsEXT::GENERAL,
                )
                .pfn_user_callback(Some(debug_callback))
                .user_data(Arc::as_ptr(log) as *mut c_void);
            // SAFETY: the log outlives the messenger, which is destroyed in `Drop` before it.
            let messenger = unsafe { loader.create_debug_utils_messenger(&info, None) }
                .vk("vkCreateDebugUtilsMessengerEXT")?;
            instance.debug = Some((loader, messenger));
        }
        Ok(instance)
    }
}

impl Drop for Instance {
    fn drop(&mut self) {
        // SAFETY: all child objects (device, surfaces) are destroyed before the instance: the
        // `Context` drops its device first and holds the instance last.
        unsafe {
            if let Some((loader, messenger)) = self.debug.take() {
                loader.destroy_debug_utils_messenger(messenger, None);
            }
            self.raw.destroy_instance(None);
        }
    }
}
