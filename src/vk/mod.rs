//! All raw Vulkan (ash) lives here. Passes talk to the GPU through these typed helpers.

pub mod context;
pub mod debug;
pub mod descriptor_counts;
pub mod descriptors;
pub mod instance;
pub mod memory;
pub mod pipeline;
pub mod readback;
pub mod recorder;
pub mod sampler;
pub mod submission;
pub mod surface;
pub mod swapchain;
pub mod sync;
pub mod timing;
pub mod upload;

pub use context::{Context, ContextOptions, DeviceInfo, SubmitSync};
pub use descriptor_counts::DescriptorCounts;
pub use descriptors::{DescriptorPool, SetWriter};
pub use memory::{Buffer, Image, ImageDesc};
pub use pipeline::{Blend, GraphicsDesc, Pipeline};
pub use readback::{read_buffer, read_image, ImageData};
pub use sampler::Sampler;
pub use submission::{one_shot, FrameSlots};
pub use surface::Surface;
pub use swapchain::{AcquiredImage, PresentPolicy, Swapchain, SwapchainOptions};
pub use sync::{Access, Tracked, TrackedImage, Tracker};
pub use timing::{FrameTiming, GpuTimer, SkipReason, Skipped};
pub use upload::{upload_buffer, upload_image, uploaded_buffer};
