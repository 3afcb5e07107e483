//! The crate's error type. Vulkan failures keep the `vk::Result` and the name of the call.

use ash::vk;
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("{call} failed: {result:?}")]
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
    #[error("{path}: could not write image: {message}")]
    ImageWrite { path: PathBuf, message: String },
    #[error("window: {0}")]
    Window(String),
    #[error("{count} Vulkan validation message(s); first: {first}")]
    Validation { count: usize, first: String },
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
            }
        )
    }
}
