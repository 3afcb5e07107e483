//! Descriptor pool and set writes.

use super::context::{Context, Garbage};
use super::memory::{Buffer, Image};
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

/// A pool sized for a renderer's fixed set of descriptor sets (they are allocated once and
/// rewritten only when targets are recreated).
pub struct DescriptorPool {
    ctx: Arc<Context>,
    raw: vk::DescriptorPool,
}

impl DescriptorPool {
    pub fn new(ctx: &Arc<Context>, max_sets: u32) -> Result<Self> {
        let per = max_sets * 8;
        let sizes = [
            vk::DescriptorPoolSize {
                ty: vk::DescriptorType::UNIFORM_BUFFER,
                descriptor_count: per,
            },
            vk::DescriptorPoolSize {
                ty: vk::DescriptorType::STORAGE_BUFFER,
                descriptor_count: per,
            },
            vk::DescriptorPoolSize {
                ty: vk::DescriptorType::SAMPLED_IMAGE,
                descriptor_count: per,
            },
            vk::DescriptorPoolSize {
                ty: vk::DescriptorType::STORAGE_IMAGE,
                descriptor_count: per,
            },
            vk::DescriptorPoolSize {
                ty: vk::DescriptorType::SAMPLER,
                descriptor_count: per,
            },
        ];
        let info = vk::DescriptorPoolCreateInfo::default()
            .max_sets(max_sets)
            .pool_sizes(&sizes);
        // SAFETY: valid create info; destroyed through the deletion queue.
        let raw = unsafe { ctx.device.create_descriptor_pool(&info, None) }
            .vk("vkCreateDescriptorPool")?;
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }

    /// One set of `layout`, debug-named `name`.
    pub fn allocate(
        &self,
        layout: vk::DescriptorSetLayout,
        name: &str,
    ) -> Result<vk::DescriptorSet> {
        let layouts = [layout];
        let info = vk::DescriptorSetAllocateInfo::default()
            .descriptor_pool(self.raw)
            .set_layouts(&layouts);
        // SAFETY: pool and layout are live; sets die with the pool.
        let set = unsafe { self.ctx.device.allocate_descriptor_sets(&info) }
            .vk("vkAllocateDescriptorSets")?[0];
        self.ctx.names.set(set, name);
        Ok(set)
    }
}

impl Drop for DescriptorPool {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::DescriptorPool(self.raw));
    }
}

enum Item {
    Image(u32, vk::DescriptorType, vk::DescriptorImageInfo),
    Buffer(u32, vk::DescriptorType, vk::DescriptorBufferInfo),
}

/// Collects the writes of one set, then applies them in one `vkUpdateDescriptorSets`.
#[derive(Default)]
pub struct SetWriter {
    items: Vec<Item>,
}

impl SetWriter {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn sampled(mut self, binding: u32, image: &Image) -> Self {
        self.items.push(Item::Image(
            binding,
            vk::DescriptorType::SAMPLED_IMAGE,
            vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: image.view,
                image_layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            },
        ));
        self
    }

    pub fn storage(mut self, binding: u32, image: &Image) -> Self {
        self.items.push(Item::Image(
            binding,
            vk::DescriptorType::STORAGE_IMAGE,
            vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: image.view,
                image_layout: vk::ImageLayout::GENERAL,
            },
        ));
        self
    }

    pub fn sampler(mut self, binding: u32, sampler: vk::Sampler) -> Self {
        self.items.push(Item::Image(
            binding,
            vk::DescriptorType::SAMPLER,
            vk::DescriptorImageInfo {
                sampler,
                image_view: vk::ImageView::null(),
                image_layout: vk::ImageLayout::UNDEFINED,
            },
        ));
        self
    }

    pub fn uniform(mut self, binding: u32, buffer: &Buffer) -> Self {
        self.items.push(Item::Buffer(
            binding,
            vk::DescriptorType::UNIFORM_BUFFER,
            vk::DescriptorBufferInfo {
                buffer: buffer.raw,
                offset: 0,
                range: vk::WHOLE_SIZE,
            },
        ));
        self
    }

    pub fn storage_buffer(mut self, binding: u32, buffer: &Buffer) -> Self {
        self.items.push(Item::Buffer(
            binding,
            vk::DescriptorType::STORAGE_BUFFER,
            vk::DescriptorBufferInfo {
                buffer: buffer.raw,
                offset: 0,
                range: vk::WHOLE_SIZE,
            },
        ));
        self
    }

    pub fn write(self, ctx: &Context, set: vk::DescriptorSet) {
        let writes: Vec<vk::WriteDescriptorSet> = self
            .items
            .iter()
            .map(|item| match item {
                Item::Image(b, ty, info) => vk::WriteDescriptorSet::default()
                    .dst_set(set)
                    .dst_binding(*b)
                    .descriptor_type(*ty)
                    .image_info(std::slice::from_ref(info)),
                Item::Buffer(b, ty, info) => vk::WriteDescriptorSet::default()
                    .dst_set(set)
                    .dst_binding(*b)
                    .descriptor_type(*ty)
                    .buffer_info(std::slice::from_ref(info)),
            })
            .collect();
        // SAFETY: the set is not in use by a pending command buffer (sets are written at
        // creation/resize, after the device went idle) and every referenced object is live.
        unsafe { ctx.device.update_descriptor_sets(&writes, &[]) };
    }
}
