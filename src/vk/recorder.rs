//! Thin typed wrappers over the command-recording calls passes use, so pass code stays free of
//! raw `unsafe`. Every function requires `cmd` to be in the recording state.

use super::debug::DebugNames;
use super::{Buffer, Context, Image, Pipeline};
use ash::vk;

pub struct Recorder<'a> {
    pub device: &'a ash::Device,
    pub cmd: vk::CommandBuffer,
    names: &'a DebugNames,
}

impl<'a> Recorder<'a> {
    /// Record into `cmd` (in the recording state) on `ctx`'s device.
    pub fn new(ctx: &'a Context, cmd: vk::CommandBuffer) -> Self {
        Self {
            device: &ctx.device,
            cmd,
            names: &ctx.names,
        }
    }

    /// Open a debug label region `name` (a pass): validation messages, captures and device-loss
    /// reports name it. Close it with [`Self::end_label`].
    pub fn begin_label(&self, name: &str) {
        self.names.begin_label(self.cmd, name);
    }

    pub fn end_label(&self) {
        self.names.end_label(self.cmd);
    }

    pub fn bind(&self, pipeline: &Pipeline, sets: &[vk::DescriptorSet]) {
        // SAFETY: recording; the pipeline and sets are live and the sets match its layout.
        unsafe {
            self.device
                .cmd_bind_pipeline(self.cmd, pipeline.bind_point, pipeline.raw);
            if !sets.is_empty() {
                self.device.cmd_bind_descriptor_sets(
                    self.cmd,
                    pipeline.bind_point,
                    pipeline.layout,
                    0,
                    sets,
                    &[],
                );
            }
        }
    }

    /// Bind sets starting at `first` (per-draw material sets).
    pub fn bind_sets(&self, pipeline: &Pipeline, first: u32, sets: &[vk::DescriptorSet]) {
        // SAFETY: recording; the sets match the pipeline layout from `first` on.
        unsafe {
            self.device.cmd_bind_descriptor_sets(
                self.cmd,
                pipeline.bind_point,
                pipeline.layout,
                first,
                sets,
                &[],
            )
        };
    }

    pub fn push(&self, pipeline: &Pipeline, bytes: &[u8]) {
        // SAFETY: recording; the range was declared with these stages and at least this size
        // (checked against reflection when the pipeline was built).
        unsafe {
            self.device.cmd_push_constants(
                self.cmd,
                pipeline.layout,
                pipeline.push_stages,
                0,
                bytes,
            )
        };
    }

    /// Dispatch enough workgroups of the pipeline's size to cover `width x height`.
    pub fn dispatch_2d(&self, pipeline: &Pipeline, width: u32, height: u32) {
        let [wx, wy, _] = pipeline.workgroup_size;
        // SAFETY: recording with a compute pipeline bound.
        unsafe {
            self.device.cmd_dispatch(
                self.cmd,
                width.div_ceil(wx.max(1)),
                height.div_ceil(wy.max(1)),
                1,
            )
        };
    }

    /// Dispatch `x` workgroups (y = z = 1).
    pub fn dispatch_groups(&self, x: u32) {
        // SAFETY: recording with a compute pipeline bound.
        unsafe { self.device.cmd_dispatch(self.cmd, x, 1, 1) };
    }

    /// Dispatch with the (x, y, z) workgroup counts stored in `args` at byte `offset`.
    pub fn dispatch_indirect(&self, args: &Buffer, offset: u64) {
        // SAFETY: recording with a compute pipeline bound; `args` has INDIRECT_BUFFER usage
        // and holds three u32 at `offset` (the tracker made the GPU writes visible).
        unsafe {
            self.device
                .cmd_dispatch_indirect(self.cmd, args.raw, offset)
        };
    }

    /// Overwrite the start of `buffer` with `data` (at most 65536 bytes, multiple of 4).
    pub fn update_buffer(&self, buffer: &Buffer, data: &[u8]) {
        // SAFETY: recording outside rendering; the buffer has TRANSFER_DST usage and the
        // tracker put it in the transfer-write state.
        unsafe { self.device.cmd_update_buffer(self.cmd, buffer.raw, 0, data) };
    }

    /// Copy the first `size` bytes of `src` to `dst`.
    pub fn copy_buffer(&self, src: &Buffer, dst: &Buffer, size: u64) {
        let region = [vk::BufferCopy {
            src_offset: 0,
            dst_offset: 0,
            size,
        }];
        // SAFETY: recording outside rendering; both buffers are large enough and in the
        // transfer states (tracker).
        unsafe {
            self.device
                .cmd_copy_buffer(self.cmd, src.raw, dst.raw, &region)
        };
    }

    /// Fill the whole of `buffer` with zeros. The tracker must have put it in
    /// `Access::TransferDst`.
    pub fn fill_zero(&self, buffer: &Buffer) {
        // SAFETY: recording outside rendering; the buffer has TRANSFER_DST usage (caller) and
        // is in the transfer-write state (tracker); WHOLE_SIZE rounds down to a multiple of 4.
        unsafe {
            self.device
                .cmd_fill_buffer(self.cmd, buffer.raw, 0, vk::WHOLE_SIZE, 0)
        };
    }

    /// Copy the whole of `image` into the start of `buffer` (tightly packed texels). The tracker
    /// must have put `image` in `Access::TransferSrc` and `buffer` in `Access::TransferDst`.
    pub fn copy_image_to_buffer(&self, image: &Image, buffer: &Buffer) {
        let region = image.copy_region();
        // SAFETY: recording outside rendering; the image has TRANSFER_SRC usage and (caller)
        // TRANSFER_SRC_OPTIMAL layout; the buffer is large enough for the region (caller).
        unsafe {
            self.device.cmd_copy_image_to_buffer(
                self.cmd,
                image.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                buffer.raw,
                &[region],
            )
        };
    }

    /// Begin dynamic rendering into `colors` (cleared to their values) and `depth` (cleared to
    /// 1), with viewport and scissor covering the first attachment.
    pub fn begin_rendering(&self, colors: &[(&Image, [f32; 4])], depth: &Image) {
        let extent = depth.extent();
        let color_infos: Vec<_> = colors
            .iter()
            .map(|(img, clear)| {
                vk::RenderingAttachmentInfo::default()
                    .image_view(img.view)
                    .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
                    .load_op(vk::AttachmentLoadOp::CLEAR)
                    .store_op(vk::AttachmentStoreOp::STORE)
                    .clear_value(vk::ClearValue {
                        color: vk::ClearColorValue { float32: *clear },
                    })
            })
            .collect();
        let depth_info = vk::RenderingAttachmentInfo::default()
            .image_view(depth.view)
            .image_layout(vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::CLEAR)
            .store_op(vk::AttachmentStoreOp::STORE)
            .clear_value(vk::ClearValue {
                depth_stencil: vk::ClearDepthStencilValue {
                    depth: 1.0,
                    stencil: 0,
                },
            });
        let area = vk::Rect2D {
            offset: vk::Offset2D { x: 0, y: 0 },
            extent,
        };
        let info = vk::RenderingInfo::default()
            .render_area(area)
            .layer_count(1)
            .color_attachments(&color_infos)
            .depth_attachment(&depth_info);
        // SAFETY: recording; attachments are in the layouts named above (the tracker
        // transitioned them before this call).
        unsafe {
            self.device.cmd_begin_rendering(self.cmd, &info);
            self.device
                .cmd_set_viewport(self.cmd, 0, &[full_viewport(extent)]);
            self.device.cmd_set_scissor(self.cmd, 0, &[area]);
        }
    }

    /// Begin dynamic rendering into one colour `view` of `extent` over its contents (loaded,
    /// not cleared; no depth): the viewer's overlay over the blitted frame. Viewport covers
    /// the extent; set scissors per draw.
    pub fn begin_rendering_over(&self, view: vk::ImageView, extent: vk::Extent2D) {
        let color = [vk::RenderingAttachmentInfo::default()
            .image_view(view)
            .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::LOAD)
            .store_op(vk::AttachmentStoreOp::STORE)];
        let area = vk::Rect2D {
            offset: vk::Offset2D { x: 0, y: 0 },
            extent,
        };
        let info = vk::RenderingInfo::default()
            .render_area(area)
            .layer_count(1)
            .color_attachments(&color);
        // SAFETY: recording; the view's image is in COLOR_ATTACHMENT_OPTIMAL (the tracker
        // transitioned it before this call).
        unsafe {
            self.device.cmd_begin_rendering(self.cmd, &info);
            self.device
                .cmd_set_viewport(self.cmd, 0, &[full_viewport(extent)]);
        }
    }

    /// Restrict the following draws to `rect` (inside the render area).
    pub fn set_scissor(&self, rect: vk::Rect2D) {
        // SAFETY: recording with a pipeline whose scissor is dynamic.
        unsafe { self.device.cmd_set_scissor(self.cmd, 0, &[rect]) };
    }

    /// Bind `vertices` from byte `vertex_offset` and 32-bit `indices` from `index_offset`.
    pub fn bind_mesh_at(
        &self,
        vertices: &Buffer,
        vertex_offset: u64,
        indices: &Buffer,
        index_offset: u64,
    ) {
        // SAFETY: recording; buffers are live, created with vertex/index usage, and the
        // offsets lie inside them (caller).
        unsafe {
            self.device
                .cmd_bind_vertex_buffers(self.cmd, 0, &[vertices.raw], &[vertex_offset]);
            self.device.cmd_bind_index_buffer(
                self.cmd,
                indices.raw,
                index_offset,
                vk::IndexType::UINT32,
            );
        }
    }

    /// `index_count` indices from `first_index`, each added to `vertex_offset`.
    pub fn draw_indexed_offset(&self, first_index: u32, index_count: u32, vertex_offset: i32) {
        // SAFETY: recording inside rendering with a graphics pipeline and mesh bound; the
        // indices (plus the offset) address vertices inside the bound range (caller).
        unsafe {
            self.device
                .cmd_draw_indexed(self.cmd, index_count, 1, first_index, vertex_offset, 0)
        };
    }

    pub fn end_rendering(&self) {
        // SAFETY: recording inside a dynamic rendering scope begun by `begin_rendering`.
        unsafe { self.device.cmd_end_rendering(self.cmd) };
    }

    pub fn bind_mesh(&self, vertices: &Buffer, indices: &Buffer) {
        // SAFETY: recording; buffers are live and were created with vertex/index usage.
        unsafe {
            self.device
                .cmd_bind_vertex_buffers(self.cmd, 0, &[vertices.raw], &[0]);
            self.device
                .cmd_bind_index_buffer(self.cmd, indices.raw, 0, vk::IndexType::UINT32);
        }
    }

    /// As `draw_indexed`, one instance numbered `instance` (the shader's gl_InstanceIndex).
    pub fn draw_indexed_instance(&self, first_index: u32, index_count: u32, instance: u32) {
        // SAFETY: as draw_indexed; a direct draw may start at any instance.
        unsafe {
            self.device
                .cmd_draw_indexed(self.cmd, index_count, 1, first_index, 0, instance)
        };
    }

    pub fn draw_indexed(&self, first_index: u32, index_count: u32) {
        // SAFETY: recording inside rendering with a graphics pipeline and mesh bound; the
        // range lies inside the index buffer (validated when the mesh was built).
        unsafe {
            self.device
                .cmd_draw_indexed(self.cmd, index_count, 1, first_index, 0, 0)
        };
    }
}

/// A viewport covering `extent` with the full depth range.
fn full_viewport(extent: vk::Extent2D) -> vk::Viewport {
    vk::Viewport {
        x: 0.0,
        y: 0.0,
        width: extent.width as f32,
        height: extent.height as f32,
        min_depth: 0.0,
        max_depth: 1.0,
    }
}
