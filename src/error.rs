//! The crate's error type. Vulkan failures keep the `vk::Result` and the name of the call.

use ash::vk;
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("{call} failed: {result:?}{}", vk_hint(*result))]
    Vulkan {
        call: &'static str,
        result: vk::Result,
    },
    #[error("could not load the Vulkan loader (libvulkan.so.1): {0}; install it with tools/setup-vulkan or `apt-get install libvulkan1 mesa-vulkan-drivers`")]
    Loader(String),
    #[error("no suitable Vulkan device: {0}")]
    NoDevice(String),
    #[error("the Vulkan device lacks {0}")]
    MissingFeature(String),
    #[error("GPU memory allocation for '{name}' failed: {message}")]
    Allocation { name: String, message: String },
    #[error(
        "out of device memory: '{name}' needs {} MiB while {} MiB are held (ssgi allows itself \
         {} MiB on this device, the device may allow less); try a smaller --size or --rsm-size",
        bytes.div_ceil(1 << 20),
        held.div_ceil(1 << 20),
        limit / (1 << 20)
    )]
    OutOfMemory {
        name: String,
        bytes: u64,
        held: u64,
        limit: u64,
    },
    #[error("shader and pass disagree: {0}")]
    Reflection(String),
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
    #[error("invalid configuration: {0}")]
    Config(String),
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// An output path (named by its option) that a run could not write, found before it.
    #[error("{option} {}: {message}", .path.display())]
    Output {
        option: String,
        path: PathBuf,
        message: String,
    },
    #[error("{path}: could not write image: {message}")]
    ImageWrite { path: PathBuf, message: String },
    #[error("window: {0}")]
    Window(String),
    #[error(
        "{call} failed: ERROR_DEVICE_LOST in a frame whose last recorded pass was '{pass}'{}",
        vk_hint(vk::Result::ERROR_DEVICE_LOST)
    )]
    DeviceLost {
        call: &'static str,
        /// The last pass recorded into the lost frame's command buffer: the first suspect.
        pass: &'static str,
    },
    #[error("{count} Vulkan validation message(s); first: {first}")]
    Validation { count: usize, first: String },
    #[error("interrupted: stopped cleanly; no report was written for the unfinished run")]
    Interrupted,
}

/// What a user can do about the Vulkan results that are not bugs.
fn vk_hint(result: vk::Result) -> &'static str {
    match result {
        vk::Result::ERROR_DEVICE_LOST => {
            " (the device was lost: the driver crashed or reset the GPU, often because one \
             dispatch ran past the OS's GPU timeout; nothing more can run on this device in \
             this process. Try a smaller --size, --vpls or --rsm-size, and check the driver log)"
        }
        vk::Result::ERROR_OUT_OF_DEVICE_MEMORY | vk::Result::ERROR_OUT_OF_HOST_MEMORY => {
            " (out of memory: try a smaller --size or --rsm-size)"
        }
        _ => "",
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Attach the failing call's name to a raw `vk::Result`.
pub trait VkContext<T> {
    fn vk(self, call: &'static str) -> Result<T>;
}

impl<T> VkContext<T> for std::result::Result<T, vk::Result> {
    fn vk(self, call: &'static str) -> Result<T> {
        self.map_err(|result| Error::Vulkan { call, result })
    }
}

impl Error {
    /// True when the device was lost: the caller cannot continue on this device.
    pub fn is_device_lost(&self) -> bool {
        matches!(
            self,
            Error::Vulkan {
                result: vk::Result::ERROR_DEVICE_LOST,
                ..
            } | Error::DeviceLost { .. }
        )
    }

    /// A device loss named after `pass`, the last pass recorded in the lost frame; any other
    /// error unchanged.
    pub fn lost_after(self, pass: Option<&'static str>) -> Error {
        match (self, pass) {
            (
                Error::Vulkan {
                    call,
                    result: vk::Result::ERROR_DEVICE_LOST,
                },
                Some(pass),
            ) => Error::DeviceLost { call, pass },
            (e, _) => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn device_loss_says_what_to_do() {
        let lost = Error::Vulkan {
            call: "vkQueueSubmit2",
            result: vk::Result::ERROR_DEVICE_LOST,
        };
        assert!(lost.is_device_lost());
        let text = lost.to_string();
        assert!(text.starts_with("vkQueueSubmit2 failed: ERROR_DEVICE_LOST (the device was lost"));
        let other = Error::Vulkan {
            call: "vkCreateImage",
            result: vk::Result::ERROR_FORMAT_NOT_SUPPORTED,
        };
        assert_eq!(
            other.to_string(),
            "vkCreateImage failed: ERROR_FORMAT_NOT_SUPPORTED"
        );
        let named = lost.lost_after(Some("indirect_gather"));
        assert!(named.is_device_lost());
        assert!(
            named.to_string().starts_with(
                "vkQueueSubmit2 failed: ERROR_DEVICE_LOST in a frame whose last recorded pass \
                 was 'indirect_gather' (the device was lost"
            ),
            "{named}"
        );
        assert_eq!(
            other.lost_after(Some("ssao")).to_string(),
            "vkCreateImage failed: ERROR_FORMAT_NOT_SUPPORTED"
        );
    }
}
