//! What a descriptor set holds, per descriptor type: from a layout's declared bindings, and
//! summed over what a pool has handed out.

use crate::shaders::DescriptorKind;
use ash::vk;

/// The Vulkan descriptor type of a reflected binding kind.
pub fn descriptor_type(kind: DescriptorKind) -> vk::DescriptorType {
    match kind {
        DescriptorKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
        DescriptorKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
        DescriptorKind::SampledImage => vk::DescriptorType::SAMPLED_IMAGE,
        DescriptorKind::StorageImage => vk::DescriptorType::STORAGE_IMAGE,
        DescriptorKind::Sampler => vk::DescriptorType::SAMPLER,
    }
}

/// The descriptor types ssgi's layouts use, in `DescriptorCounts` order.
pub const TYPES: [vk::DescriptorType; 5] = [
    vk::DescriptorType::UNIFORM_BUFFER,
    vk::DescriptorType::STORAGE_BUFFER,
    vk::DescriptorType::SAMPLED_IMAGE,
    vk::DescriptorType::STORAGE_IMAGE,
    vk::DescriptorType::SAMPLER,
];

/// Descriptors per type (in `TYPES` order) of one set layout, or a pool's sum of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DescriptorCounts(pub [u32; 5]);

impl DescriptorCounts {
    /// What a set with these declared bindings holds.
    pub fn of<'a>(bindings: impl Iterator<Item = &'a crate::shaders::ReflectedBinding>) -> Self {
        let mut c = [0; 5];
        for b in bindings {
            let ty = descriptor_type(b.kind);
            if let Some(i) = TYPES.iter().position(|t| *t == ty) {
                c[i] += b.count;
            }
        }
        Self(c)
    }

    pub fn add(&mut self, other: Self) {
        for (a, b) in self.0.iter_mut().zip(other.0) {
            *a += b;
        }
    }

    pub fn fits_in(&self, left: &Self) -> bool {
        self.0.iter().zip(left.0).all(|(need, left)| *need <= left)
    }
}
