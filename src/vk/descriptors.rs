//! Descriptor pool and set writes.

use super::context::{Context, Garbage};
use super::descriptor_counts::{DescriptorCounts, TYPES};
use super::memory::{Buffer, Image};
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::{Arc, Mutex};

/// One Vulkan pool and what is left of its declared sizes.
struct Chunk {
    raw: vk::DescriptorPool,
    /// The sizes it was created with: sets, descriptors per type.
    declared: (u32, DescriptorCounts),
    sets_left: u32,
    left: DescriptorCounts,
}

/// Sets per Vulkan pool, and descriptors per type per set it is sized for at least (the
/// largest layout, a reprojection of three lanes, holds 28 storage descriptors).
const CHUNK_SETS: u32 = 64;
const CHUNK_PER_SET: u32 = 8;

/// Descriptor sets for a renderer, allocated once and rewritten only when targets are
/// recreated. Every set is counted against its pool's declared sizes from the descriptors its
/// layout declares (`Context::layout_counts`), and a new Vulkan pool is opened before one
/// would run out, so no driver refuses an allocation (lavapipe never does; NVIDIA refuses
/// past `maxSets` or a type's size, as it did for the incremental-PCA filter's many sets).
pub struct DescriptorPool {
    ctx: Arc<Context>,
    chunks: Mutex<Vec<Chunk>>,
    allocated: Mutex<(u32, DescriptorCounts)>,
}

impl DescriptorPool {
    pub fn new(ctx: &Arc<Context>) -> Result<Self> {
        Ok(Self {
            ctx: ctx.clone(),
            chunks: Mutex::new(Vec::new()),
            allocated: Mutex::new((0, DescriptorCounts::default())),
        })
    }

    /// Sets allocated so far and their descriptors per type (the sum of their layouts').
    pub fn allocated(&self) -> (u32, DescriptorCounts) {
        *self.allocated.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Per Vulkan pool: its declared sizes (sets, descriptors per type) and what is left of
    /// them.
    pub fn capacities(&self) -> Vec<((u32, DescriptorCounts), (u32, DescriptorCounts))> {
        let chunks = self.chunks.lock().unwrap_or_else(|e| e.into_inner());
        chunks
            .iter()
            .map(|c| (c.declared, (c.sets_left, c.left)))
            .collect()
    }

    fn open_chunk(&self, need: DescriptorCounts) -> Result<Chunk> {
        let mut sizes = DescriptorCounts([CHUNK_SETS * CHUNK_PER_SET; 5]);
        for (s, n) in sizes.0.iter_mut().zip(need.0) {
            *s = (*s).max(n);
        }
        let pool_sizes: Vec<_> = TYPES
            .iter()
            .zip(sizes.0)
            .map(|(&ty, descriptor_count)| vk::DescriptorPoolSize {
                ty,
                descriptor_count,
            })
            .collect();
        let info = vk::DescriptorPoolCreateInfo::default()
            .max_sets(CHUNK_SETS)
            .pool_sizes(&pool_sizes);
        // SAFETY: valid create info; destroyed through the deletion queue.
        let raw = unsafe { self.ctx.device.create_descriptor_pool(&info, None) }
            .vk("vkCreateDescriptorPool")?;
        Ok(Chunk {
            raw,
            declared: (CHUNK_SETS, sizes),
            sets_left: CHUNK_SETS,
            left: sizes,
        })
    }

    /// One set of `layout` (created by `pipeline::create_set_layouts`), debug-named `name`.
    pub fn allocate(
        &self,
        layout: vk::DescriptorSetLayout,
        name: &str,
    ) -> Result<vk::DescriptorSet> {
        let need = self
            .ctx
            .layout_counts
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(&layout)
            .copied()
            .ok_or_else(|| {
                crate::error::Error::Reflection(format!(
                    "{name}: its set layout was not made by create_set_layouts, so its \
                     descriptors are unknown"
                ))
            })?;
        let mut chunks = self.chunks.lock().unwrap_or_else(|e| e.into_inner());
        let fits = |c: &Chunk| c.sets_left > 0 && need.fits_in(&c.left);
        if !chunks.last().is_some_and(fits) {
            chunks.push(self.open_chunk(need)?);
        }
        let chunk = chunks.last_mut().expect("a pool was just opened");
        let layouts = [layout];
        let info = vk::DescriptorSetAllocateInfo::default()
            .descriptor_pool(chunk.raw)
            .set_layouts(&layouts);
        // SAFETY: pool and layout are live; the pool has room for the set (counted above);
        // sets die with the pool.
        let set = unsafe { self.ctx.device.allocate_descriptor_sets(&info) }
            .vk("vkAllocateDescriptorSets")?[0];
        chunk.sets_left -= 1;
        for (l, n) in chunk.left.0.iter_mut().zip(need.0) {
            *l -= n;
        }
        let mut a = self.allocated.lock().unwrap_or_else(|e| e.into_inner());
        a.0 += 1;
        a.1.add(need);
        self.ctx.names.set(set, name);
        Ok(set)
    }
}

impl Drop for DescriptorPool {
    fn drop(&mut self) {
        for c in self
            .chunks
            .get_mut()
            .unwrap_or_else(|e| e.into_inner())
            .drain(..)
        {
            self.ctx.defer(Garbage::DescriptorPool(c.raw));
        }
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
