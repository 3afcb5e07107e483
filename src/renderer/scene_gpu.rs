//! The scene on the GPU: one vertex and one index buffer, per-material colour and (optional)
//! diffuse texture with its descriptor set.

use crate::error::{Error, Result};
use crate::scene::{DrawRange, Mesh, TextureImage};
use crate::shaders::MaterialPush;
use crate::vk::{
    upload_buffer, upload_image, Access, Buffer, Context, DescriptorPool, Image, ImageDesc,
    Sampler, SetWriter, Tracker,
};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::collections::HashMap;
use std::sync::Arc;

pub struct MaterialGpu {
    pub albedo: [f32; 3],
    /// Set 1 of the textured permutation; `None` draws with the flat permutation.
    pub texture_set: Option<vk::DescriptorSet>,
}

impl MaterialGpu {
    /// The `Material` push-constant block (vec4 albedo).
    pub fn push_bytes(&self) -> [u8; MaterialPush::SIZE] {
        MaterialPush {
            albedo: [self.albedo[0], self.albedo[1], self.albedo[2], 1.0],
        }
        .to_bytes()
    }
}

pub struct SceneGpu {
    pub vertices: Buffer,
    pub indices: Buffer,
    pub ranges: Vec<DrawRange>,
    pub materials: Vec<MaterialGpu>,
    _textures: Vec<Image>,
    _sampler: Option<Sampler>,
}

impl SceneGpu {
    /// Upload `mesh`. `material_layout` is the textured permutation's set-1 layout, present
    /// only when the mesh has textures.
    pub fn new(
        ctx: &Arc<Context>,
        tracker: &mut Tracker,
        pool: &DescriptorPool,
        mesh: &Mesh,
        material_layout: Option<vk::DescriptorSetLayout>,
    ) -> Result<Self> {
        if mesh.indices.is_empty() || mesh.vertices.is_empty() {
            return Err(Error::Config("the scene has no triangles to draw".into()));
        }
        let vdata = mesh.vertex_bytes();
        let idata = mesh.index_bytes();
        let vertices = Buffer::new(
            ctx,
            "vertices",
            vdata.len() as u64,
            vk::BufferUsageFlags::VERTEX_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuOnly,
        )?;
        let indices = Buffer::new(
            ctx,
            "indices",
            idata.len() as u64,
            vk::BufferUsageFlags::INDEX_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuOnly,
        )?;
        upload_buffer(ctx, tracker, &vertices, &vdata, Access::VertexBufferRead)?;
        upload_buffer(ctx, tracker, &indices, &idata, Access::IndexBufferRead)?;

        // Textures: decode once per path (shared Arc), upload each once.
        let mut unique: Vec<Arc<TextureImage>> = Vec::new();
        let mut index_of: HashMap<*const TextureImage, usize> = HashMap::new();
        if material_layout.is_some() {
            for m in &mesh.materials {
                if let Some(t) = &m.diffuse_texture {
                    index_of.entry(Arc::as_ptr(t)).or_insert_with(|| {
                        unique.push(t.clone());
                        unique.len() - 1
                    });
                }
            }
        }
        let mut textures = Vec::new();
        for t in &unique {
            if t.width == 0 || t.height == 0 || t.rgba8.len() != (t.width * t.height * 4) as usize {
                return Err(Error::Config(format!(
                    "texture {} has inconsistent size",
                    t.path.display()
                )));
            }
            let image = Image::new(
                ctx,
                &t.path.display().to_string(),
                ImageDesc {
                    width: t.width,
                    height: t.height,
                    format: vk::Format::R8G8B8A8_SRGB,
                    usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
                },
            )?;
            upload_image(ctx, tracker, &image, &t.rgba8, Access::FragmentSampledRead)?;
            textures.push(image);
        }

        let sampler = if textures.is_empty() {
            None
        } else {
            Some(Sampler::linear_repeat(ctx)?)
        };
        let mut materials = Vec::new();
        for m in &mesh.materials {
            let texture_set = match (&m.diffuse_texture, material_layout, &sampler) {
                (Some(t), Some(layout), Some(s)) => {
                    let set = pool.allocate(layout, &format!("material {} texture set", m.name))?;
                    SetWriter::new()
                        .sampled(0, &textures[index_of[&Arc::as_ptr(t)]])
                        .sampler(1, s.raw)
                        .write(ctx, set);
                    Some(set)
                }
                _ => None,
            };
            materials.push(MaterialGpu {
                albedo: m.diffuse,
                texture_set,
            });
        }
        Ok(Self {
            vertices,
            indices,
            ranges: mesh.ranges.clone(),
            materials,
            _textures: textures,
            _sampler: sampler,
        })
    }
}
