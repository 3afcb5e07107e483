//! Access-based synchronisation: every use of an image or buffer is declared as an `Access`;
//! the `Tracker` turns "previous access → next access" into explicit synchronization2 barriers.
//! Nothing in ssgi transitions a layout any other way.

use ash::vk;
use std::cell::Cell;

/// The ways a pass can touch a resource. Each maps to (stages, access mask, image layout).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// Contents are garbage (new image, or discarded).
    Undefined,
    ColorAttachmentWrite,
    /// Depth test and write (read + write of the attachment).
    DepthAttachmentWrite,
    /// Sampled (`texture2D` + texelFetch/texture) in a compute shader.
    ComputeSampledRead,
    /// Sampled in a fragment shader.
    FragmentSampledRead,
    ComputeStorageRead,
    ComputeStorageWrite,
    ComputeStorageReadWrite,
    TransferSrc,
    TransferDst,
    /// Read on the host after a copy (buffers).
    HostRead,
    /// Written on the host before use (buffers; ordering comes from the submission).
    HostWrite,
    VertexBufferRead,
    IndexBufferRead,
    UniformRead,
    IndirectCommandRead,
    Present,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccessInfo {
    pub stage: vk::PipelineStageFlags2,
    pub access: vk::AccessFlags2,
    pub layout: vk::ImageLayout,
    pub writes: bool,
}

impl Access {
    pub fn info(self) -> AccessInfo {
        use vk::AccessFlags2 as A;
        use vk::ImageLayout as L;
        use vk::PipelineStageFlags2 as S;
        let (stage, access, layout, writes) = match self {
            Access::Undefined => (S::NONE, A::NONE, L::UNDEFINED, false),
            Access::ColorAttachmentWrite => (
                S::COLOR_ATTACHMENT_OUTPUT,
                A::COLOR_ATTACHMENT_WRITE | A::COLOR_ATTACHMENT_READ,
                L::COLOR_ATTACHMENT_OPTIMAL,
                true,
            ),
            Access::DepthAttachmentWrite => (
                S::EARLY_FRAGMENT_TESTS | S::LATE_FRAGMENT_TESTS,
                A::DEPTH_STENCIL_ATTACHMENT_READ | A::DEPTH_STENCIL_ATTACHMENT_WRITE,
                L::DEPTH_ATTACHMENT_OPTIMAL,
                true,
            ),
            Access::ComputeSampledRead => (
                S::COMPUTE_SHADER,
                A::SHADER_SAMPLED_READ,
                L::SHADER_READ_ONLY_OPTIMAL,
                false,
            ),
            Access::FragmentSampledRead => (
                S::FRAGMENT_SHADER,
                A::SHADER_SAMPLED_READ,
                L::SHADER_READ_ONLY_OPTIMAL,
                false,
            ),
            Access::ComputeStorageRead => {
                (S::COMPUTE_SHADER, A::SHADER_STORAGE_READ, L::GENERAL, false)
            }
            Access::ComputeStorageWrite => {
                (S::COMPUTE_SHADER, A::SHADER_STORAGE_WRITE, L::GENERAL, true)
            }
            Access::ComputeStorageReadWrite => (
                S::COMPUTE_SHADER,
                A::SHADER_STORAGE_READ | A::SHADER_STORAGE_WRITE,
                L::GENERAL,
                true,
            ),
            // Copies and blits (the window frontend blits the output into the swapchain).
            Access::TransferSrc => (
                S::COPY | S::BLIT,
                A::TRANSFER_READ,
                L::TRANSFER_SRC_OPTIMAL,
                false,
            ),
            Access::TransferDst => (
                S::COPY | S::BLIT | S::CLEAR,
                A::TRANSFER_WRITE,
                L::TRANSFER_DST_OPTIMAL,
                true,
            ),
            Access::HostRead => (S::HOST, A::HOST_READ, L::UNDEFINED, false),
            Access::HostWrite => (S::HOST, A::HOST_WRITE, L::UNDEFINED, true),
            Access::VertexBufferRead => (
                S::VERTEX_ATTRIBUTE_INPUT,
                A::VERTEX_ATTRIBUTE_READ,
                L::UNDEFINED,
                false,
            ),
            Access::IndexBufferRead => (S::INDEX_INPUT, A::INDEX_READ, L::UNDEFINED, false),
            Access::UniformRead => (
                S::VERTEX_SHADER | S::FRAGMENT_SHADER | S::COMPUTE_SHADER,
                A::UNIFORM_READ,
                L::UNDEFINED,
                false,
            ),
            Access::IndirectCommandRead => (
                S::DRAW_INDIRECT,
                A::INDIRECT_COMMAND_READ,
                L::UNDEFINED,
                false,
            ),
            Access::Present => (S::NONE, A::NONE, L::PRESENT_SRC_KHR, false),
        };
        AccessInfo {
            stage,
            access,
            layout,
            writes,
        }
    }
}

/// What the tracker remembers about one resource: its layout, the last write, and the reads
/// made since that write (which a later write must wait for).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ResourceState {
    pub layout: vk::ImageLayout,
    pub write_stage: vk::PipelineStageFlags2,
    pub write_access: vk::AccessFlags2,
    pub read_stage: vk::PipelineStageFlags2,
    pub read_access: vk::AccessFlags2,
}

impl Default for ResourceState {
    fn default() -> Self {
        Self {
            layout: vk::ImageLayout::UNDEFINED,
            write_stage: vk::PipelineStageFlags2::NONE,
            write_access: vk::AccessFlags2::NONE,
            read_stage: vk::PipelineStageFlags2::NONE,
            read_access: vk::AccessFlags2::NONE,
        }
    }
}

/// One dependency the tracker decided on (layouts are ignored for buffers).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dependency {
    pub src_stage: vk::PipelineStageFlags2,
    pub src_access: vk::AccessFlags2,
    pub dst_stage: vk::PipelineStageFlags2,
    pub dst_access: vk::AccessFlags2,
    pub old_layout: vk::ImageLayout,
    pub new_layout: vk::ImageLayout,
}

/// Decide the barrier (if any) for `next` after `state`, and update `state`. Pure, so the
/// rules are unit-tested without a GPU.
///
/// - read after read in the same layout, already covered: nothing;
/// - read after write: wait for the write, make it visible;
/// - write (or layout change) after anything: wait for the write and all reads since.
pub fn transition(state: &mut ResourceState, next: Access, is_image: bool) -> Option<Dependency> {
    let n = next.info();
    if next == Access::Undefined {
        // Discard the contents: the next transition starts from UNDEFINED, but still waits
        // for the earlier accesses (a discard is not a licence to race with them).
        if is_image {
            state.layout = vk::ImageLayout::UNDEFINED;
        }
        return None;
    }
    let layout_change = is_image && state.layout != n.layout;
    if !n.writes && !layout_change {
        let covered = state.read_stage.contains(n.stage) && state.read_access.contains(n.access);
        state.read_stage |= n.stage;
        state.read_access |= n.access;
        if covered || state.write_stage == vk::PipelineStageFlags2::NONE {
            return None;
        }
        return Some(Dependency {
            src_stage: state.write_stage,
            src_access: state.write_access,
            dst_stage: n.stage,
            dst_access: n.access,
            old_layout: state.layout,
            new_layout: state.layout,
        });
    }
    let dep = Dependency {
        src_stage: state.write_stage | state.read_stage,
        // Reads need only an execution dependency; writes must be made available.
        src_access: state.write_access,
        dst_stage: n.stage,
        dst_access: n.access,
        old_layout: if is_image {
            state.layout
        } else {
            vk::ImageLayout::UNDEFINED
        },
        new_layout: if is_image {
            n.layout
        } else {
            vk::ImageLayout::UNDEFINED
        },
    };
    let was_untouched = state.write_stage == vk::PipelineStageFlags2::NONE
        && state.read_stage == vk::PipelineStageFlags2::NONE;
    if n.writes {
        state.write_stage = n.stage;
        state.write_access = n.access;
        state.read_stage = vk::PipelineStageFlags2::NONE;
        state.read_access = vk::AccessFlags2::NONE;
    } else {
        // A layout transition is itself a write that the read must follow.
        state.write_stage = n.stage;
        state.write_access = vk::AccessFlags2::NONE;
        state.read_stage = n.stage;
        state.read_access = n.access;
    }
    state.layout = if is_image { n.layout } else { state.layout };
    if was_untouched && !layout_change {
        return None; // first use of a buffer: nothing to wait for
    }
    Some(dep)
}

/// A resource the tracker can follow: it owns its `ResourceState` cell.
pub trait Tracked {
    fn state(&self) -> &Cell<ResourceState>;
}

/// A buffer the tracker can follow.
pub trait TrackedBuffer: Tracked {
    fn handle(&self) -> vk::Buffer;
}

/// An image the tracker can follow (owned images and swapchain images alike).
pub trait TrackedImage: Tracked {
    fn handle(&self) -> vk::Image;
    fn range(&self) -> vk::ImageSubresourceRange;
}

/// Collects barriers for the next `flush` (one `vkCmdPipelineBarrier2` per batch).
#[derive(Default)]
pub struct Tracker {
    images: Vec<vk::ImageMemoryBarrier2<'static>>,
    buffers: Vec<vk::BufferMemoryBarrier2<'static>>,
    /// While `Some`: each pass's declared use of each resource, in recording order
    /// (`ssgi bench --explain`).
    declared: Option<Vec<Declared>>,
}

/// One resource a pass declared, as `--explain` prints it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Declared {
    pub pass: String,
    pub resource: String,
    pub reads: bool,
    pub writes: bool,
}

impl Tracker {
    pub fn new() -> Self {
        Self::default()
    }

    /// Log the declared uses from now on (`take_declared` ends the log).
    pub fn start_declaring(&mut self) {
        self.declared = Some(Vec::new());
    }

    /// The uses declared since `start_declaring`, and stop logging.
    pub fn take_declared(&mut self) -> Vec<Declared> {
        self.declared.take().unwrap_or_default()
    }

    /// A pass's use of a resource (logged only while declaring).
    pub fn declare(&mut self, pass: &str, resource: &str, reads: bool, writes: bool) {
        if let Some(log) = &mut self.declared {
            log.push(Declared {
                pass: pass.to_string(),
                resource: resource.to_string(),
                reads,
                writes,
            });
        }
    }

    pub fn image(&mut self, image: &impl TrackedImage, next: Access) {
        let mut state = image.state().get();
        if let Some(d) = transition(&mut state, next, true) {
            self.images.push(
                vk::ImageMemoryBarrier2::default()
                    .src_stage_mask(d.src_stage)
                    .src_access_mask(d.src_access)
                    .dst_stage_mask(d.dst_stage)
                    .dst_access_mask(d.dst_access)
                    .old_layout(d.old_layout)
                    .new_layout(d.new_layout)
                    .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .image(image.handle())
                    .subresource_range(image.range()),
            );
        }
        image.state().set(state);
    }

    pub fn buffer(&mut self, buffer: &impl TrackedBuffer, next: Access) {
        let mut state = buffer.state().get();
        if let Some(d) = transition(&mut state, next, false) {
            self.buffers.push(
                vk::BufferMemoryBarrier2::default()
                    .src_stage_mask(d.src_stage)
                    .src_access_mask(d.src_access)
                    .dst_stage_mask(d.dst_stage)
                    .dst_access_mask(d.dst_access)
                    .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .buffer(buffer.handle())
                    .offset(0)
                    .size(vk::WHOLE_SIZE),
            );
        }
        buffer.state().set(state);
    }

    /// Record every pending barrier into `cmd`.
    pub fn flush(&mut self, device: &ash::Device, cmd: vk::CommandBuffer) {
        if self.images.is_empty() && self.buffers.is_empty() {
            return;
        }
        let info = vk::DependencyInfo::default()
            .image_memory_barriers(&self.images)
            .buffer_memory_barriers(&self.buffers);
        // SAFETY: `cmd` is in the recording state (callers flush only while recording) and
        // every barrier names a live resource owned by the caller.
        unsafe { device.cmd_pipeline_barrier2(cmd, &info) };
        self.images.clear();
        self.buffers.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vk::AccessFlags2 as A;
    use vk::ImageLayout as L;
    use vk::PipelineStageFlags2 as S;

    #[test]
    fn first_write_transitions_from_undefined() {
        let mut s = ResourceState::default();
        let d = transition(&mut s, Access::ColorAttachmentWrite, true).unwrap();
        assert_eq!(d.old_layout, L::UNDEFINED);
        assert_eq!(d.new_layout, L::COLOR_ATTACHMENT_OPTIMAL);
        assert_eq!(d.src_access, A::NONE);
    }

    #[test]
    fn read_after_write_waits_for_the_write() {
        let mut s = ResourceState::default();
        transition(&mut s, Access::ColorAttachmentWrite, true);
        let d = transition(&mut s, Access::ComputeSampledRead, true).unwrap();
        assert_eq!(d.src_stage, S::COLOR_ATTACHMENT_OUTPUT);
        assert!(d.src_access.contains(A::COLOR_ATTACHMENT_WRITE));
        assert_eq!(d.dst_stage, S::COMPUTE_SHADER);
        assert_eq!(d.new_layout, L::SHADER_READ_ONLY_OPTIMAL);
    }

    #[test]
    fn repeated_reads_need_no_barrier() {
        let mut s = ResourceState::default();
        transition(&mut s, Access::ComputeStorageWrite, true);
        assert!(transition(&mut s, Access::ComputeSampledRead, true).is_some());
        assert!(transition(&mut s, Access::ComputeSampledRead, true).is_none());
    }

    #[test]
    fn write_after_reads_waits_for_all_readers() {
        let mut s = ResourceState::default();
        transition(&mut s, Access::ComputeStorageWrite, false);
        transition(&mut s, Access::FragmentSampledRead, false);
        transition(&mut s, Access::ComputeStorageRead, false);
        let d = transition(&mut s, Access::ComputeStorageWrite, false).unwrap();
        assert!(d.src_stage.contains(S::FRAGMENT_SHADER | S::COMPUTE_SHADER));
    }

    #[test]
    fn second_reader_stage_waits_for_the_write() {
        let mut s = ResourceState::default();
        transition(&mut s, Access::ComputeStorageWrite, false);
        transition(&mut s, Access::ComputeStorageRead, false);
        let d = transition(&mut s, Access::IndirectCommandRead, false).unwrap();
        assert_eq!(d.src_stage, S::COMPUTE_SHADER);
        assert_eq!(d.src_access, A::SHADER_STORAGE_WRITE);
    }

    #[test]
    fn first_buffer_use_needs_nothing() {
        let mut s = ResourceState::default();
        assert!(transition(&mut s, Access::TransferDst, false).is_none());
    }

    #[test]
    fn discard_keeps_waiting_for_earlier_readers() {
        let mut s = ResourceState::default();
        transition(&mut s, Access::ComputeStorageWrite, true);
        transition(&mut s, Access::ComputeSampledRead, true);
        transition(&mut s, Access::Undefined, true);
        let d = transition(&mut s, Access::ColorAttachmentWrite, true).unwrap();
        assert_eq!(d.old_layout, L::UNDEFINED);
        assert!(d.src_stage.contains(S::COMPUTE_SHADER));
    }
}
