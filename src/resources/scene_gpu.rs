//! The scene on the GPU: one vertex and one index buffer (what stands still, then each moving
//! object in its own space), per-material colour and (optional) diffuse texture with its
//! descriptor set, and the draws: a material's range of one of them, with the object's pose.

use crate::config::FRAMES_IN_FLIGHT;
use crate::error::{Error, Result};
use crate::scene::{DynamicObject, Mesh, TextureImage};
use crate::shaders::MaterialPush;
use crate::vk::{
    upload_image, uploaded_buffer, Access, Buffer, Context, DescriptorPool, Image, ImageDesc,
    Sampler, SetWriter, Tracker,
};
use ash::vk;
use glam::Affine3A;
use gpu_allocator::MemoryLocation;
use std::collections::HashMap;
use std::sync::Arc;

pub struct MaterialGpu {
    pub albedo: [f32; 3],
    /// Set 1 of the textured permutation; `None` draws with the flat permutation.
    pub texture_set: Option<vk::DescriptorSet>,
}

/// Where a drawn object stands this frame and stood last frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub now: Affine3A,
    pub before: Affine3A,
}

impl Pose {
    /// What stands still.
    pub const STILL: Pose = Pose {
        now: Affine3A::IDENTITY,
        before: Affine3A::IDENTITY,
    };

    /// Whether the object moved since last frame.
    pub fn moved(&self) -> bool {
        self.now != self.before
    }
}

/// Row `i` of an affine transform (the `Material` block's `model_x/y/z`).
fn row(t: &Affine3A, i: usize) -> [f32; 4] {
    let m = t.matrix3;
    [m.x_axis[i], m.y_axis[i], m.z_axis[i], t.translation[i]]
}

impl MaterialGpu {
    /// The `Material` push-constant block: the colour and the draw's placement.
    pub fn push_bytes(&self, pose: &Pose) -> [u8; MaterialPush::SIZE] {
        MaterialPush {
            albedo: [self.albedo[0], self.albedo[1], self.albedo[2], 1.0],
            model_x: row(&pose.now, 0),
            model_y: row(&pose.now, 1),
            model_z: row(&pose.now, 2),
            prev_model_x: row(&pose.before, 0),
            prev_model_y: row(&pose.before, 1),
            prev_model_z: row(&pose.before, 2),
        }
        .to_bytes()
    }
}

/// One draw: a run of indices with one material, of what stands still (`object` None) or of a
/// moving object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Draw {
    pub material: usize,
    pub first_index: u32,
    pub index_count: u32,
    pub object: Option<usize>,
}

pub struct SceneGpu {
    pub vertices: Buffer,
    pub indices: Buffer,
    pub draws: Vec<Draw>,
    pub materials: Vec<MaterialGpu>,
    /// Each moving object's pose for the frame being recorded (`Renderer::set_time`).
    pub poses: Vec<Pose>,
    /// `--gbuffer visibility`: what the resolve reads besides the vertices and indices.
    pub visibility: Option<VisibilityTables>,
    _textures: Vec<Image>,
    _sampler: Option<Sampler>,
}

/// The visibility buffer's tables: the draw of each triangle, and per frame slot a copy of
/// every draw's material push (colour and poses), written before the slot's frame is
/// submitted (the slot's fence has signalled, so its last reader is done).
pub struct VisibilityTables {
    pub triangle_draws: Buffer,
    pub draws: Buffer,
}

impl VisibilityTables {
    fn new(
        ctx: &Arc<Context>,
        tracker: &mut Tracker,
        draws: &[Draw],
        triangles: usize,
    ) -> Result<Self> {
        let mut triangle_draws = vec![0u32; triangles];
        for (d, draw) in draws.iter().enumerate() {
            // Ranges are whole triangles inside the index list (checked when the mesh was
            // built).
            let first = draw.first_index as usize / 3;
            let end = (first + draw.index_count as usize / 3).min(triangles);
            triangle_draws[first.min(end)..end].fill(d as u32);
        }
        let bytes: Vec<u8> = triangle_draws
            .iter()
            .flat_map(|d| d.to_le_bytes())
            .collect();
        let buffer = uploaded_buffer(
            ctx,
            tracker,
            "scene.triangle_draws",
            &bytes,
            vk::BufferUsageFlags::STORAGE_BUFFER,
            Access::ComputeStorageRead,
        )?;
        let table = Buffer::new(
            ctx,
            "scene.draws",
            (FRAMES_IN_FLIGHT * draws.len() * MaterialPush::SIZE) as u64,
            vk::BufferUsageFlags::STORAGE_BUFFER,
            MemoryLocation::CpuToGpu,
        )?;
        Ok(Self {
            triangle_draws: buffer,
            draws: table,
        })
    }
}

/// `statics` and every object's mesh in one vertex and index list (indices offset to their
/// vertices), their materials in one list, and the draws.
fn combine(statics: &Mesh, objects: &[DynamicObject]) -> (Vec<u8>, Vec<u8>, Vec<Draw>) {
    let mut vertices = statics.vertex_bytes();
    let mut indices = statics.index_bytes();
    let mut draws: Vec<Draw> = statics
        .ranges
        .iter()
        .map(|r| Draw {
            material: r.material,
            first_index: r.first_index,
            index_count: r.index_count,
            object: None,
        })
        .collect();
    let (mut vertex_base, mut index_base) = (statics.vertices.len(), statics.indices.len());
    let mut material_base = statics.materials.len();
    for (o, object) in objects.iter().enumerate() {
        let m = &object.mesh;
        vertices.extend(m.vertex_bytes());
        // Vertex counts come from meshes held in memory: far below u32::MAX.
        indices.extend(
            m.indices
                .iter()
                .flat_map(|i| (i + vertex_base as u32).to_le_bytes()),
        );
        draws.extend(m.ranges.iter().map(|r| Draw {
            material: material_base + r.material,
            first_index: index_base as u32 + r.first_index,
            index_count: r.index_count,
            object: Some(o),
        }));
        vertex_base += m.vertices.len();
        index_base += m.indices.len();
        material_base += m.materials.len();
    }
    (vertices, indices, draws)
}

impl SceneGpu {
    /// The pose of `draw`'s object (still for what stands still).
    pub fn pose(&self, draw: &Draw) -> Pose {
        pose_of(&self.poses, draw)
    }

    /// First entry of `slot`'s draw table (the resolve's push constant).
    pub fn draw_table_base(&self, slot: usize) -> u32 {
        (slot * self.draws.len()) as u32
    }

    /// Copy every draw's colour and pose for this frame into `slot`'s draw table (visibility
    /// buffer only; the slot's last frame has finished). A scene without moving objects has
    /// its tables written once, at creation: nothing in them changes.
    pub fn write_draw_table(&mut self, slot: usize) -> Result<()> {
        if self.poses.is_empty() {
            return Ok(());
        }
        self.fill_draw_table(slot)
    }

    fn fill_draw_table(&mut self, slot: usize) -> Result<()> {
        let Some(tables) = &mut self.visibility else {
            return Ok(());
        };
        let size = self.draws.len() * MaterialPush::SIZE;
        let table = tables
            .draws
            .mapped_mut()
            .and_then(|m| m.get_mut(slot * size..(slot + 1) * size))
            .ok_or_else(|| Error::Config("the draw table is not host-visible".into()))?;
        for (entry, d) in table.chunks_exact_mut(MaterialPush::SIZE).zip(&self.draws) {
            entry.copy_from_slice(&self.materials[d.material].push_bytes(&pose_of(&self.poses, d)));
        }
        Ok(())
    }

    /// Upload `mesh` (what stands still) and `objects`. `material_layout` is the textured
    /// permutation's set-1 layout, present only when a material has a texture; `visibility`
    /// adds the visibility buffer's tables (and lets compute passes read the mesh).
    pub fn new(
        ctx: &Arc<Context>,
        tracker: &mut Tracker,
        pool: &DescriptorPool,
        mesh: &Mesh,
        objects: &[DynamicObject],
        material_layout: Option<vk::DescriptorSetLayout>,
        visibility: bool,
    ) -> Result<Self> {
        if mesh.indices.is_empty() || mesh.vertices.is_empty() {
            return Err(Error::Config("the scene has no triangles to draw".into()));
        }
        let (vdata, idata, draws) = combine(mesh, objects);
        let all_materials: Vec<&crate::scene::Material> = mesh
            .materials
            .iter()
            .chain(objects.iter().flat_map(|o| &o.mesh.materials))
            .collect();
        // Storage too: the visibility buffer's resolve reads the triangles.
        let storage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let vertices = uploaded_buffer(
            ctx,
            tracker,
            "scene.vertices",
            &vdata,
            vk::BufferUsageFlags::VERTEX_BUFFER | storage,
            Access::VertexBufferRead,
        )?;
        let indices = uploaded_buffer(
            ctx,
            tracker,
            "scene.indices",
            &idata,
            vk::BufferUsageFlags::INDEX_BUFFER | storage,
            Access::IndexBufferRead,
        )?;
        let visibility = visibility
            .then(|| VisibilityTables::new(ctx, tracker, &draws, idata.len() / 12))
            .transpose()?;

        // Textures: decode once per path (shared Arc), upload each once.
        let mut unique: Vec<Arc<TextureImage>> = Vec::new();
        let mut index_of: HashMap<*const TextureImage, usize> = HashMap::new();
        if material_layout.is_some() {
            for m in &all_materials {
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
        for m in &all_materials {
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
        let mut scene = Self {
            vertices,
            indices,
            draws,
            materials,
            poses: vec![Pose::STILL; objects.len()],
            visibility,
            _textures: textures,
            _sampler: sampler,
        };
        for slot in 0..FRAMES_IN_FLIGHT {
            scene.fill_draw_table(slot)?;
        }
        Ok(scene)
    }
}

/// The pose of `draw`'s object among `poses` (still for what stands still).
fn pose_of(poses: &[Pose], draw: &Draw) -> Pose {
    draw.object
        .and_then(|o| poses.get(o).copied())
        .unwrap_or(Pose::STILL)
}
