//! Buffers and images: created through gpu-allocator, released through the context's deletion
//! queue once the GPU is done with them, and followed by the sync tracker.

use super::context::{Context, Garbage};
use super::sync::{ResourceState, Tracked, TrackedBuffer, TrackedImage};
use crate::error::{Error, Result, VkContext};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;
use std::cell::Cell;
use std::sync::Arc;

fn allocate(
    ctx: &Context,
    name: &str,
    requirements: vk::MemoryRequirements,
    location: MemoryLocation,
    linear: bool,
) -> Result<Allocation> {
    let mut allocator = ctx.allocator();
    // Refuse what would pass the device-memory budget: counted over the allocator's memory
    // blocks, so it errs on the safe side only when the request would fit a block's free room.
    let held = allocator.capacity();
    if held.saturating_add(requirements.size) > ctx.memory_limit {
        return Err(Error::OutOfMemory {
            name: name.to_string(),
            bytes: requirements.size,
            held,
            limit: ctx.memory_limit,
        });
    }
    allocator
        .allocate(&AllocationCreateDesc {
            name,
            requirements,
            location,
            linear,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        })
        .map_err(|e| match e {
            // The device's own heap is full (the allocator counts it too).
            gpu_allocator::AllocationError::OutOfMemory => Error::OutOfMemory {
                name: name.to_string(),
                bytes: requirements.size,
                held,
                limit: ctx.memory_limit,
            },
            e => Error::Allocation {
                name: name.to_string(),
                message: e.to_string(),
            },
        })
}

pub struct Buffer {
    ctx: Arc<Context>,
    /// Its debug name (validation messages, `--explain`).
    pub name: String,
    pub raw: vk::Buffer,
    pub size: u64,
    allocation: Option<Allocation>,
    state: Cell<ResourceState>,
}

impl Buffer {
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Self> {
        let info = vk::BufferCreateInfo::default()
            .size(size.max(4))
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: valid create info; the buffer is destroyed through the deletion queue.
        let raw = unsafe { ctx.device.create_buffer(&info, None) }.vk("vkCreateBuffer")?;
        ctx.names.set(raw, name);
        // SAFETY: `raw` was just created on this device.
        let req = unsafe { ctx.device.get_buffer_memory_requirements(raw) };
        let allocation = match allocate(ctx, name, req, location, true) {
            Ok(a) => a,
            Err(e) => {
                ctx.defer(Garbage::Buffer(raw));
                return Err(e);
            }
        };
        // SAFETY: the allocation satisfies `req` and is bound once.
        if let Err(e) = unsafe {
            ctx.device
                .bind_buffer_memory(raw, allocation.memory(), allocation.offset())
        }
        .vk("vkBindBufferMemory")
        {
            ctx.defer(Garbage::Buffer(raw));
            ctx.defer(Garbage::Allocation(allocation));
            return Err(e);
        }
        Ok(Self {
            ctx: ctx.clone(),
            name: name.to_string(),
            raw,
            size,
            allocation: Some(allocation),
            state: Cell::new(ResourceState::default()),
        })
    }

    /// Host-visible contents (CpuToGpu / GpuToCpu buffers only).
    pub fn mapped(&self) -> Option<&[u8]> {
        self.allocation.as_ref()?.mapped_slice()
    }

    pub fn mapped_mut(&mut self) -> Option<&mut [u8]> {
        self.allocation.as_mut()?.mapped_slice_mut()
    }

    /// Copy `data` into a host-visible buffer. Errors if the buffer is not mapped or too small.
    pub fn write(&mut self, data: &[u8]) -> Result<()> {
        let dst = self
            .mapped_mut()
            .ok_or_else(|| Error::Config("write to a buffer that is not host-visible".into()))?;
        if dst.len() < data.len() {
            return Err(Error::Config(format!(
                "write of {} bytes into a {}-byte buffer",
                data.len(),
                dst.len()
            )));
        }
        dst[..data.len()].copy_from_slice(data);
        Ok(())
    }
}

impl Tracked for Buffer {
    fn state(&self) -> &Cell<ResourceState> {
        &self.state
    }
}

impl TrackedBuffer for Buffer {
    fn handle(&self) -> vk::Buffer {
        self.raw
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::Buffer(self.raw));
        if let Some(a) = self.allocation.take() {
            self.ctx.defer(Garbage::Allocation(a));
        }
    }
}

/// What an image is for; decides usage flags and aspect.
#[derive(Clone, Copy, Debug)]
pub struct ImageDesc {
    pub width: u32,
    pub height: u32,
    pub format: vk::Format,
    pub usage: vk::ImageUsageFlags,
}

pub struct Image {
    ctx: Arc<Context>,
    pub name: String,
    pub raw: vk::Image,
    pub view: vk::ImageView,
    pub desc: ImageDesc,
    allocation: Option<Allocation>,
    state: Cell<ResourceState>,
}

pub fn is_depth(format: vk::Format) -> bool {
    matches!(
        format,
        vk::Format::D32_SFLOAT | vk::Format::D16_UNORM | vk::Format::X8_D24_UNORM_PACK32
    )
}

/// Bytes of one texel of the formats ssgi makes (None for others).
pub fn bytes_per_pixel(format: vk::Format) -> Option<usize> {
    Some(match format {
        vk::Format::R32G32B32A32_SFLOAT => 16,
        vk::Format::R16G16B16A16_SFLOAT => 8,
        vk::Format::R8G8B8A8_UNORM | vk::Format::R8G8B8A8_SRGB | vk::Format::B8G8R8A8_UNORM => 4,
        vk::Format::B8G8R8A8_SRGB | vk::Format::D32_SFLOAT | vk::Format::R32_SFLOAT => 4,
        vk::Format::R32_UINT => 4,
        _ => return None,
    })
}

/// Refuses an image past what the device takes for its format and use
/// (vkGetPhysicalDeviceImageFormatProperties: maxExtent, maxResourceSize) before it is
/// created, naming the image: creating it anyway breaks a valid-usage rule and then fails as
/// if memory had run out (`--size 16384x16384` on lavapipe: 'rsm.position' of 4 GiB against
/// a 2 GiB largest resource), though no allocation was ever the problem.
fn check_image_limits(ctx: &Context, name: &str, desc: &ImageDesc) -> Result<()> {
    // SAFETY: the physical device belongs to this instance; the query has no side effects.
    let props = unsafe {
        ctx.instance
            .raw
            .get_physical_device_image_format_properties(
                ctx.physical,
                desc.format,
                vk::ImageType::TYPE_2D,
                vk::ImageTiling::OPTIMAL,
                desc.usage,
                vk::ImageCreateFlags::empty(),
            )
    };
    let props = match props {
        Ok(p) => p,
        Err(vk::Result::ERROR_FORMAT_NOT_SUPPORTED) => {
            return Err(Error::Config(format!(
                "image '{name}': this device does not support {:?} with usage {:?}",
                desc.format, desc.usage
            )))
        }
        Err(result) => {
            return Err(Error::Vulkan {
                call: "vkGetPhysicalDeviceImageFormatProperties",
                result,
            })
        }
    };
    let max = props.max_extent;
    // The texel size where readback knows it (every format ssgi makes), else 1 byte: the
    // driver's own check then still catches what this one lets through.
    let texel = bytes_per_pixel(desc.format).unwrap_or(1) as u64;
    let bytes = desc.width as u64 * desc.height as u64 * texel;
    if desc.width > max.width || desc.height > max.height || bytes > props.max_resource_size {
        return Err(Error::Config(format!(
            "image '{name}' ({}x{} {:?}, {} MiB) is past this device's largest image of that \
             format and use ({}x{}, {} MiB); try a smaller --size or --rsm-size",
            desc.width,
            desc.height,
            desc.format,
            bytes.div_ceil(1 << 20),
            max.width,
            max.height,
            props.max_resource_size >> 20
        )));
    }
    Ok(())
}

impl Image {
    pub fn new(ctx: &Arc<Context>, name: &str, desc: ImageDesc) -> Result<Self> {
        if desc.width == 0 || desc.height == 0 {
            return Err(Error::Config(format!(
                "image '{name}' has a zero extent {}x{}",
                desc.width, desc.height
            )));
        }
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(desc.format)
            .extent(vk::Extent3D {
                width: desc.width,
                height: desc.height,
                depth: 1,
            })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(desc.usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        check_image_limits(ctx, name, &desc)?;
        // SAFETY: valid create info; destroyed through the deletion queue.
        let raw = unsafe { ctx.device.create_image(&info, None) }.vk("vkCreateImage")?;
        ctx.names.set(raw, name);
        // SAFETY: `raw` was just created on this device.
        let req = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let allocation = match allocate(ctx, name, req, MemoryLocation::GpuOnly, false) {
            Ok(a) => a,
            Err(e) => {
                ctx.defer(Garbage::Image(raw));
                return Err(e);
            }
        };
        // SAFETY: the allocation satisfies `req` and is bound once.
        let bound = unsafe {
            ctx.device
                .bind_image_memory(raw, allocation.memory(), allocation.offset())
        }
        .vk("vkBindImageMemory");
        let mut image = Self {
            ctx: ctx.clone(),
            name: name.to_string(),
            raw,
            view: vk::ImageView::null(),
            desc,
            allocation: Some(allocation),
            state: Cell::new(ResourceState::default()),
        };
        bound?;
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(vk::ImageViewType::TYPE_2D)
            .format(desc.format)
            .subresource_range(image.full_range());
        // SAFETY: the image is bound to memory; the view is destroyed before the image.
        image.view =
            unsafe { ctx.device.create_image_view(&view_info, None) }.vk("vkCreateImageView")?;
        ctx.names.set(image.view, name);
        Ok(image)
    }

    /// Whether anything was written since the image was created or last discarded (its
    /// tracked layout is no longer `UNDEFINED`).
    pub fn holds_contents(&self) -> bool {
        self.state.get().layout != vk::ImageLayout::UNDEFINED
    }

    pub fn aspect(&self) -> vk::ImageAspectFlags {
        if is_depth(self.desc.format) {
            vk::ImageAspectFlags::DEPTH
        } else {
            vk::ImageAspectFlags::COLOR
        }
    }

    pub fn full_range(&self) -> vk::ImageSubresourceRange {
        vk::ImageSubresourceRange {
            aspect_mask: self.aspect(),
            base_mip_level: 0,
            level_count: 1,
            base_array_layer: 0,
            layer_count: 1,
        }
    }

    /// Buffer <-> image copy region covering the whole image (tightly packed rows).
    pub fn copy_region(&self) -> vk::BufferImageCopy {
        vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: self.aspect(),
                mip_level: 0,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(vk::Extent3D {
                width: self.desc.width,
                height: self.desc.height,
                depth: 1,
            })
    }

    pub fn extent(&self) -> vk::Extent2D {
        vk::Extent2D {
            width: self.desc.width,
            height: self.desc.height,
        }
    }
}

impl Tracked for Image {
    fn state(&self) -> &Cell<ResourceState> {
        &self.state
    }
}

impl TrackedImage for Image {
    fn handle(&self) -> vk::Image {
        self.raw
    }

    fn range(&self) -> vk::ImageSubresourceRange {
        self.full_range()
    }
}

impl Drop for Image {
    fn drop(&mut self) {
        if self.view != vk::ImageView::null() {
            self.ctx.defer(Garbage::ImageView(self.view));
        }
        self.ctx.defer(Garbage::Image(self.raw));
        if let Some(a) = self.allocation.take() {
            self.ctx.defer(Garbage::Allocation(a));
        }
    }
}
