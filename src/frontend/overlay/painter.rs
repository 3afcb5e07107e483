//! Draws egui's tessellated meshes over the presented frame: one graphics pipeline
//! (shaders/overlay/), the textures egui asks for (its font atlas), and per frame slot a
//! host-visible vertex and index buffer. egui's colours are sRGB-encoded and premultiplied
//! and it blends in gamma space; the swapchain is UNORM and holds the renderer's sRGB-encoded
//! output, so the shader multiplies and the blend stage composites "over" with no conversion.
//!
//! Barriers go through the sync tracker: the swapchain image moves from the blit's transfer
//! write to colour-attachment write; the buffers are host writes made visible by the
//! submission, then vertex and index reads.

use crate::error::{Error, Result};
use crate::passes::layout::{binding, PassLayout};
use crate::passes::PassId;
use crate::renderer::FRAMES_IN_FLIGHT;
use crate::shaders::{self, DescriptorKind, OverlayPush, ReflectedBinding};
use crate::vk::recorder::Recorder;
use crate::vk::swapchain::SwapchainImage;
use crate::vk::{
    upload_image, Access, Blend, Buffer, Context, DescriptorPool, GraphicsDesc, Image, ImageDesc,
    Pipeline, Sampler, SetWriter, Tracker,
};
use ash::vk;
use egui::epaint::{ClippedPrimitive, ImageDelta, Primitive, TextureId};
use gpu_allocator::MemoryLocation;
use std::collections::HashMap;
use std::sync::Arc;

/// The atlas texture and its sampler (set 0).
const BINDINGS: &[ReflectedBinding] = &[
    binding(0, 0, DescriptorKind::SampledImage),
    binding(0, 1, DescriptorKind::Sampler),
];

/// egui's vertex as the shader reads it: position and texture coordinate in f32, colour in
/// four bytes (sRGB, premultiplied).
const VERTEX_BYTES: usize = 20;
const VERTEX_BINDINGS: [vk::VertexInputBindingDescription; 1] =
    [vk::VertexInputBindingDescription {
        binding: 0,
        stride: VERTEX_BYTES as u32,
        input_rate: vk::VertexInputRate::VERTEX,
    }];
const VERTEX_ATTRIBUTES: [vk::VertexInputAttributeDescription; 3] = [
    vk::VertexInputAttributeDescription {
        location: 0,
        binding: 0,
        format: vk::Format::R32G32_SFLOAT,
        offset: 0,
    },
    vk::VertexInputAttributeDescription {
        location: 1,
        binding: 0,
        format: vk::Format::R32G32_SFLOAT,
        offset: 8,
    },
    vk::VertexInputAttributeDescription {
        location: 2,
        binding: 0,
        format: vk::Format::R8G8B8A8_UNORM,
        offset: 16,
    },
];

/// A texture egui manages, with its pixels kept for partial updates.
struct Texture {
    /// Alive while the set refers to it (dropped through the deletion queue).
    _image: Image,
    set: vk::DescriptorSet,
    pixels: Vec<egui::Color32>,
    size: [usize; 2],
}

/// One slot's vertex and index buffers.
struct SlotBuffers {
    vertices: Buffer,
    indices: Buffer,
}

/// One draw: a range of the slot's buffers, its texture and scissor rectangle.
struct Draw {
    texture: TextureId,
    scissor: vk::Rect2D,
    first_index: u32,
    index_count: u32,
    vertex_offset: i32,
}

/// What `prepare` laid out for the next recording.
#[derive(Default)]
struct Prepared {
    vertex_bytes: Vec<u8>,
    index_bytes: Vec<u8>,
    draws: Vec<Draw>,
    screen_points: [f32; 2],
}

pub struct Painter {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    pool: DescriptorPool,
    sampler: Sampler,
    textures: HashMap<TextureId, Texture>,
    slots: Vec<Option<SlotBuffers>>,
    prepared: Prepared,
}

impl Painter {
    /// The pipeline for swapchain images of `format`.
    pub fn new(ctx: &Arc<Context>, format: vk::Format) -> Result<Self> {
        Ok(Self {
            ctx: ctx.clone(),
            pipeline: pipeline(ctx, format)?,
            pool: DescriptorPool::new(ctx)?,
            sampler: Sampler::linear_clamp(ctx)?,
            textures: HashMap::new(),
            slots: (0..FRAMES_IN_FLIGHT).map(|_| None).collect(),
            prepared: Prepared::default(),
        })
    }

    /// A swapchain recreated with another format needs another pipeline.
    pub fn set_format(&mut self, format: vk::Format) -> Result<()> {
        self.pipeline = pipeline(&self.ctx, format)?;
        Ok(())
    }

    /// Apply egui's texture changes. The caller has waited for every frame in flight (the
    /// textures and their sets are rewritten in place).
    pub fn update_textures(&mut self, set: &[(TextureId, ImageDelta)]) -> Result<()> {
        for (id, delta) in set {
            self.update_texture(*id, delta)?;
        }
        Ok(())
    }

    fn update_texture(&mut self, id: TextureId, delta: &ImageDelta) -> Result<()> {
        let egui::ImageData::Color(image) = &delta.image;
        let [w, h] = image.size;
        if image.pixels.len() != w * h {
            return Err(Error::Window(format!(
                "overlay texture {id:?}: {} pixels for {w}x{h}",
                image.pixels.len()
            )));
        }
        let (mut pixels, size) = match (delta.pos, self.textures.remove(&id)) {
            (None, old) => {
                drop(old);
                (image.pixels.clone(), image.size)
            }
            (Some([x0, y0]), Some(old)) => {
                let [tw, th] = old.size;
                if x0 + w > tw || y0 + h > th {
                    return Err(Error::Window(format!(
                        "overlay texture {id:?}: a {w}x{h} update at ({x0}, {y0}) outside {tw}x{th}"
                    )));
                }
                let mut pixels = old.pixels;
                for row in 0..h {
                    let dst = (y0 + row) * tw + x0;
                    pixels[dst..dst + w].copy_from_slice(&image.pixels[row * w..(row + 1) * w]);
                }
                (pixels, old.size)
            }
            (Some(_), None) => {
                return Err(Error::Window(format!(
                    "overlay texture {id:?}: a partial update before the texture"
                )))
            }
        };
        let image = Image::new(
            &self.ctx,
            &format!("overlay texture {id:?}"),
            ImageDesc {
                width: size[0] as u32,
                height: size[1] as u32,
                format: vk::Format::R8G8B8A8_UNORM,
                usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            },
        )?;
        let bytes: Vec<u8> = pixels.iter().flat_map(|c| c.to_array()).collect();
        let mut tracker = Tracker::default();
        upload_image(
            &self.ctx,
            &mut tracker,
            &image,
            &bytes,
            Access::FragmentSampledRead,
        )?;
        let set = self
            .pool
            .allocate(self.pipeline.set_layouts[0], "overlay texture")?;
        SetWriter::new()
            .sampled(0, &image)
            .sampler(1, self.sampler.raw)
            .write(&self.ctx, set);
        pixels.shrink_to_fit();
        self.textures.insert(
            id,
            Texture {
                _image: image,
                set,
                pixels,
                size,
            },
        );
        Ok(())
    }

    /// Textures egui no longer uses (after the frames that drew with them: their images are
    /// destroyed through the deletion queue).
    pub fn free_textures(&mut self, ids: &[TextureId]) {
        for id in ids {
            self.textures.remove(id);
        }
    }

    /// Lay out `primitives` for the next frame of slot `slot` on a `pixels` swapchain image
    /// at `pixels_per_point`, growing the slot's buffers when they are too small (the old ones
    /// go through the deletion queue: a frame in flight may still read them).
    pub fn prepare(
        &mut self,
        slot: usize,
        primitives: &[ClippedPrimitive],
        pixels_per_point: f32,
        pixels: [u32; 2],
    ) -> Result<()> {
        let ppp = pixels_per_point.max(1e-3);
        // Last frame's vectors, cleared: their capacity carries over (no per-frame
        // allocation once the panel's size is reached).
        let mut p = std::mem::take(&mut self.prepared);
        p.vertex_bytes.clear();
        p.index_bytes.clear();
        p.draws.clear();
        p.screen_points = [pixels[0] as f32 / ppp, pixels[1] as f32 / ppp];
        for prim in primitives {
            let Primitive::Mesh(mesh) = &prim.primitive else {
                continue; // paint callbacks: the overlay adds none
            };
            if mesh.indices.is_empty() || !self.textures.contains_key(&mesh.texture_id) {
                continue;
            }
            let Some(scissor) = scissor(prim.clip_rect, ppp, pixels) else {
                continue;
            };
            let vertex_offset = (p.vertex_bytes.len() / VERTEX_BYTES) as i32;
            let first_index = (p.index_bytes.len() / 4) as u32;
            for v in &mesh.vertices {
                for f in [v.pos.x, v.pos.y, v.uv.x, v.uv.y] {
                    p.vertex_bytes.extend_from_slice(&f.to_le_bytes());
                }
                p.vertex_bytes.extend_from_slice(&v.color.to_array());
            }
            for i in &mesh.indices {
                p.index_bytes.extend_from_slice(&i.to_le_bytes());
            }
            p.draws.push(Draw {
                texture: mesh.texture_id,
                scissor,
                first_index,
                index_count: mesh.indices.len() as u32,
                vertex_offset,
            });
        }
        let fits = self.slots[slot].as_ref().is_some_and(|b| {
            b.vertices.size >= p.vertex_bytes.len() as u64
                && b.indices.size >= p.index_bytes.len() as u64
        });
        if !fits && !p.draws.is_empty() {
            // Doubling: a growing overlay reallocates a few times, then never.
            let grow = |n: usize| (n.max(4096) as u64).next_power_of_two();
            self.slots[slot] = Some(SlotBuffers {
                vertices: Buffer::new(
                    &self.ctx,
                    "overlay vertices",
                    grow(p.vertex_bytes.len()),
                    vk::BufferUsageFlags::VERTEX_BUFFER,
                    MemoryLocation::CpuToGpu,
                )?,
                indices: Buffer::new(
                    &self.ctx,
                    "overlay indices",
                    grow(p.index_bytes.len()),
                    vk::BufferUsageFlags::INDEX_BUFFER,
                    MemoryLocation::CpuToGpu,
                )?,
            });
        }
        self.prepared = p;
        Ok(())
    }

    /// Record what `prepare` laid out over `target` (of `extent`). Runs inside the frame's
    /// recording, after slot `slot`'s previous frame completed: its buffers are free to write.
    pub fn record(
        &mut self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        slot: usize,
        target: &SwapchainImage,
        extent: vk::Extent2D,
    ) -> Result<()> {
        let p = &mut self.prepared;
        if p.draws.is_empty() {
            return Ok(());
        }
        let buffers = self.slots[slot]
            .as_mut()
            .ok_or_else(|| Error::Window("overlay buffers missing".into()))?;
        buffers.vertices.write(&p.vertex_bytes)?;
        buffers.indices.write(&p.index_bytes)?;
        tracker.buffer(&buffers.vertices, Access::HostWrite);
        tracker.buffer(&buffers.vertices, Access::VertexBufferRead);
        tracker.buffer(&buffers.indices, Access::HostWrite);
        tracker.buffer(&buffers.indices, Access::IndexBufferRead);
        tracker.image(target, Access::ColorAttachmentWrite);
        tracker.flush(rec.device, rec.cmd);
        rec.begin_rendering_over(target.view, extent);
        rec.bind(&self.pipeline, &[]);
        rec.push(
            &self.pipeline,
            &OverlayPush {
                screen_points: p.screen_points,
            }
            .to_bytes(),
        );
        rec.bind_mesh_at(&buffers.vertices, 0, &buffers.indices, 0);
        for d in &p.draws {
            let Some(texture) = self.textures.get(&d.texture) else {
                continue;
            };
            rec.bind_sets(&self.pipeline, 0, &[texture.set]);
            rec.set_scissor(d.scissor);
            rec.draw_indexed_offset(d.first_index, d.index_count, d.vertex_offset);
        }
        rec.end_rendering();
        // Drawn once: a frame that `prepare` skipped draws nothing.
        p.draws.clear();
        Ok(())
    }
}

/// The overlay's pipeline as a pass layout, for the reflection checks beside the renderer's
/// (`tests/reflection.rs`; it is no renderer pass, so not in `renderer::all_layouts`).
pub fn layout() -> PassLayout {
    PassLayout {
        pass: PassId::OVERLAY,
        modules: vec![&shaders::OVERLAY_VERT, &shaders::OVERLAY_FRAG],
        declared: BINDINGS.to_vec(),
        binds: Vec::new(),
    }
}

fn pipeline(ctx: &Arc<Context>, format: vk::Format) -> Result<Pipeline> {
    let formats = [format];
    Pipeline::graphics(
        ctx,
        PassId::OVERLAY.name(),
        &GraphicsDesc {
            vertex: &shaders::OVERLAY_VERT,
            fragment: &shaders::OVERLAY_FRAG,
            vertex_bindings: &VERTEX_BINDINGS,
            vertex_attributes: &VERTEX_ATTRIBUTES,
            color_formats: &formats,
            depth_format: vk::Format::UNDEFINED,
            blend: Blend::Premultiplied,
        },
        BINDINGS,
    )
}

/// egui's clip rectangle (points) as a scissor in pixels, clamped to the image; `None` when
/// nothing of it is on screen.
fn scissor(clip: egui::Rect, ppp: f32, pixels: [u32; 2]) -> Option<vk::Rect2D> {
    let clamp = |v: f32, max: u32| (v * ppp).round().clamp(0.0, max as f32) as u32;
    let (x0, y0) = (clamp(clip.min.x, pixels[0]), clamp(clip.min.y, pixels[1]));
    let (x1, y1) = (clamp(clip.max.x, pixels[0]), clamp(clip.max.y, pixels[1]));
    (x1 > x0 && y1 > y0).then_some(vk::Rect2D {
        offset: vk::Offset2D {
            x: x0 as i32,
            y: y0 as i32,
        },
        extent: vk::Extent2D {
            width: x1 - x0,
            height: y1 - y0,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scissors_clamp_to_the_image_and_drop_empty_rectangles() {
        let r = |x0, y0, x1, y1| egui::Rect::from_min_max(egui::pos2(x0, y0), egui::pos2(x1, y1));
        let s = scissor(r(-5.0, 2.0, 30.0, 90.0), 2.0, [40, 100]).unwrap();
        assert_eq!((s.offset.x, s.offset.y), (0, 4));
        assert_eq!((s.extent.width, s.extent.height), (40, 96));
        assert!(scissor(r(50.0, 0.0, 60.0, 10.0), 1.0, [40, 100]).is_none());
        // NaN clip edges (a degenerate layout) clamp to 0 and draw nothing.
        assert!(scissor(r(f32::NAN, 0.0, f32::NAN, 10.0), 1.0, [40, 100]).is_none());
    }
}
