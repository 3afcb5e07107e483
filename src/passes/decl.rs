//! A pass's resources, declared once: for each binding, which resource (a [`Slot`]) and how the
//! pass uses it (a [`Use`]). From that one table come the descriptor-set layout (checked
//! against the shader's reflection when the pipeline is built), the descriptor writes, and the
//! tracker accesses that produce the barriers, so the three cannot disagree.

use crate::error::{Error, Result};
use crate::shaders::{DescriptorKind, ReflectedBinding, ShaderModuleInfo};
use crate::vk::{Access, Buffer, Image, SetWriter, Tracker};

/// The per-frame uniform buffer every pass reads (set 0, binding 0).
pub const FRAME_BINDING: ReflectedBinding = ReflectedBinding {
    set: 0,
    binding: 0,
    kind: DescriptorKind::StorageBuffer,
    count: 1,
};

/// A resource as a pass names it; the renderer resolves it to an image or buffer for the
/// frame's parity (the one place that knows which image backs what).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// This frame's G-buffer world position (ping-ponged).
    GPosition,
    /// Last frame's G-buffer world position: the world-position history of eq 2.
    GPositionPrev,
    /// This frame's G-buffer normal (ping-ponged).
    GNormal,
    /// Last frame's G-buffer normal: the disocclusion test's facing check.
    GNormalPrev,
    GAlbedo,
    /// This frame's world-space motion of each pixel's surface point (the G-buffer's).
    GMotion,
    RsmPosition,
    RsmNormal,
    RsmFlux,
    /// The light view's depth: the shadow map.
    RsmDepth,
    GDepth,
    /// `--gbuffer visibility`: each pixel's triangle (0 background, else 1 + its index).
    GVisibility,
    /// The scene's vertex buffer (8 floats a vertex), read as storage.
    SceneVertices,
    /// The scene's index buffer, read as storage.
    SceneIndices,
    /// The draw of each triangle of the index buffer.
    SceneTriangleDraws,
    /// Per draw and frame slot: its colour and this frame's and last frame's pose.
    SceneDraws,
    /// The final RGBA8 image: the composite's, or the antialiasing pass's.
    Output,
    /// With antialiasing: the composite's display-linear colour (fp16), before filtering.
    Shaded,
    /// Subpixel geometry: world position (w = 1 on geometry) at subpixel `n` of the rotated grid.
    SubPosition(u8),
    /// Subpixel geometry: normal at subpixel `n`.
    SubNormal(u8),
    /// Subpixel geometry: the depth buffer the four subpixel renders share.
    SubDepth,
    /// The direct effect's outgoing radiance (written by it, read by effects that bounce it).
    DirectLight,
    /// The temporal effect's history written this frame (rgb value, a = estimates).
    History,
    /// Last frame's history of the same effect.
    HistoryPrev,
    /// The effect's moments history written this frame (mean squared luminance of the
    /// estimates, pending gate crossing): the gated mean's variance and change test.
    Moments,
    /// Last frame's second-moment history.
    MomentsPrev,
    /// The registration of the effect's history (the surface point each value belongs to, and
    /// its magnification since the counts were last scaled), written and read by the
    /// reprojection alone (shaders/reproject.comp).
    Registration,
    /// Last frame's registration.
    RegistrationPrev,
    /// The effect's per-pixel reprojection state.
    State,
    /// The effect's counters and work lists (indirect dispatch arguments first).
    Counters,
    /// An image the effect owns, by name: the effect lists each of its images under the slot
    /// its passes bind it by (`EffectResources::own`), so order cannot pair them wrongly.
    Own(&'static str),
    /// A buffer the effect owns, by name (`EffectResources::own_buffers`).
    OwnBuffer(&'static str),
    /// The `n`-th composite input (the effects' contributions, in registration order).
    Term(u8),
}

/// How a pass uses a resource at one binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Use {
    /// Sampled image, read with texelFetch.
    Sampled,
    StorageRead,
    /// Storage image the pass overwrites wherever it is read later: the old contents are
    /// discarded (transition from UNDEFINED).
    StorageWrite,
    StorageReadWrite,
    BufferRead,
    BufferWrite,
    BufferReadWrite,
    /// Counters whose header holds the pass's indirect dispatch arguments, also updated by it.
    WorkList,
    /// Colour attachment `binding` of a raster pass, cleared and written (not a descriptor).
    ColorAttachment,
    /// The raster pass's depth attachment, cleared and written (not a descriptor).
    DepthAttachment,
}

impl Use {
    /// The descriptor type, `None` for attachments.
    pub fn kind(self) -> Option<DescriptorKind> {
        Some(match self {
            Use::Sampled => DescriptorKind::SampledImage,
            Use::StorageRead | Use::StorageWrite | Use::StorageReadWrite => {
                DescriptorKind::StorageImage
            }
            Use::BufferRead | Use::BufferWrite | Use::BufferReadWrite | Use::WorkList => {
                DescriptorKind::StorageBuffer
            }
            Use::ColorAttachment | Use::DepthAttachment => return None,
        })
    }

    /// The same binding with the old contents kept: a pass that leaves a resource alone this
    /// time (a dynamically skipped branch) still names it, and synchronization validation
    /// counts its writes, but it must not discard what is there.
    pub fn keeping_contents(self) -> Use {
        match self {
            Use::StorageWrite => Use::StorageReadWrite,
            other => other,
        }
    }

    /// Whether the pass reads what is there.
    pub fn reads(self) -> bool {
        matches!(
            self,
            Use::Sampled
                | Use::StorageRead
                | Use::StorageReadWrite
                | Use::BufferRead
                | Use::BufferReadWrite
                | Use::WorkList
        )
    }

    /// Whether the pass writes it.
    pub fn writes(self) -> bool {
        !matches!(self, Use::Sampled | Use::StorageRead | Use::BufferRead)
    }

    fn is_buffer(self) -> bool {
        self.kind() == Some(DescriptorKind::StorageBuffer)
    }

    /// The tracker accesses, in order (a discard first for overwritten images).
    fn accesses(self) -> &'static [Access] {
        match self {
            Use::Sampled => &[Access::ComputeSampledRead],
            Use::StorageRead | Use::BufferRead => &[Access::ComputeStorageRead],
            Use::StorageWrite => &[Access::Undefined, Access::ComputeStorageWrite],
            Use::BufferWrite => &[Access::ComputeStorageWrite],
            Use::StorageReadWrite | Use::BufferReadWrite => &[Access::ComputeStorageReadWrite],
            Use::WorkList => &[Access::IndirectCommandRead, Access::ComputeStorageReadWrite],
            Use::ColorAttachment => &[Access::Undefined, Access::ColorAttachmentWrite],
            Use::DepthAttachment => &[Access::Undefined, Access::DepthAttachmentWrite],
        }
    }
}

/// One binding of set 1: `layout(set = 1, binding = N)` in the shader.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bind {
    pub binding: u32,
    pub slot: Slot,
    pub usage: Use,
}

impl Bind {
    pub const fn new(binding: u32, slot: Slot, usage: Use) -> Self {
        Self {
            binding,
            slot,
            usage,
        }
    }
}

/// Resolves slots to this run's resources.
pub trait Resolve {
    /// The image behind `slot` for frame parity `parity`; `None` when the run has none.
    fn image(&self, slot: Slot, parity: usize) -> Option<&Image>;
    fn buffer(&self, slot: Slot) -> Option<&Buffer>;
}

/// The pipeline layout a declaration implies: the frame block at set 0, then set 1.
pub fn layout(binds: &[Bind]) -> Vec<ReflectedBinding> {
    let mut out = vec![FRAME_BINDING];
    out.extend(binds.iter().filter_map(|b| {
        Some(ReflectedBinding {
            set: 1,
            binding: b.binding,
            kind: b.usage.kind()?,
            count: 1,
        })
    }));
    out
}

/// A slot the resolver could not provide: a mistake in an effect's registration, reported with
/// the pass and the slot instead of a bad descriptor.
fn missing(pass: &str, b: &Bind) -> Error {
    Error::Reflection(format!(
        "{pass}: binding {} ({:?}) has no resource in this configuration",
        b.binding, b.slot
    ))
}

/// The descriptor writes of set 1 for `parity`; `module` is the pass's shader, whose storage
/// formats the images must have.
pub fn writes(
    pass: &str,
    module: &ShaderModuleInfo,
    binds: &[Bind],
    res: &dyn Resolve,
    parity: usize,
) -> Result<SetWriter> {
    write_binds(SetWriter::new(), (pass, module), binds, res, parity)
}

/// `w` plus the writes of `binds` (a pass whose set gathers several resolvers' resources).
pub fn write_binds(
    mut w: SetWriter,
    (pass, module): (&str, &ShaderModuleInfo),
    binds: &[Bind],
    res: &dyn Resolve,
    parity: usize,
) -> Result<SetWriter> {
    for b in binds.iter().filter(|b| b.usage.kind().is_some()) {
        w = if b.usage.is_buffer() {
            let buffer = res.buffer(b.slot).ok_or_else(|| missing(pass, b))?;
            w.storage_buffer(b.binding, buffer)
        } else {
            let image = res.image(b.slot, parity).ok_or_else(|| missing(pass, b))?;
            match b.usage {
                Use::Sampled => w.sampled(b.binding, image),
                _ => {
                    check_storage_format(pass, module, b.binding, &image.name, image.desc.format)?;
                    w.storage(b.binding, image)
                }
            }
        };
    }
    Ok(w)
}

/// A storage image must have the format its shader's layout qualifier declares (Vulkan's
/// rule for a format-qualified storage image; a mismatch reads and writes the wrong texel
/// layout, and no driver or validation layer is obliged to notice). `image` is the bound
/// image's name, for the error.
pub fn check_storage_format(
    pass: &str,
    module: &ShaderModuleInfo,
    binding: u32,
    image: &str,
    format: ash::vk::Format,
) -> Result<()> {
    match module.storage_format(1, binding) {
        Some(declared) if declared == format => Ok(()),
        Some(declared) => Err(Error::Reflection(format!(
            "{pass}: {} declares binding {binding} as a {declared:?} storage image, but {image} \
             is {format:?}: declare the format once (shaders/include/shared_constants.glsl) \
             and use it on both sides",
            module.label()
        ))),
        None => Err(Error::Reflection(format!(
            "{pass}: {} has no storage image at binding {binding}, where {image} is bound",
            module.label()
        ))),
    }
}

/// The colour attachments (in binding order) and the depth attachment a raster pass declares,
/// for parity `parity`.
pub fn attachments<'a>(
    pass: &str,
    binds: &[Bind],
    res: &'a dyn Resolve,
    parity: usize,
) -> Result<(Vec<&'a Image>, Option<&'a Image>)> {
    let mut colors: Vec<(u32, &Image)> = Vec::new();
    let mut depth = None;
    for b in binds {
        let image = || res.image(b.slot, parity).ok_or_else(|| missing(pass, b));
        match b.usage {
            Use::ColorAttachment => colors.push((b.binding, image()?)),
            Use::DepthAttachment => depth = Some(image()?),
            _ => {}
        }
    }
    colors.sort_by_key(|(binding, _)| *binding);
    Ok((colors.into_iter().map(|(_, i)| i).collect(), depth))
}

/// Declare every access of the pass to the tracker (the caller flushes). Every slot resolved
/// when the sets were written ([`writes`]), so a missing one here is a broken invariant.
pub fn access(pass: &str, binds: &[Bind], res: &dyn Resolve, parity: usize, t: &mut Tracker) {
    let unresolved = |b: &Bind| -> ! { panic!("{}", missing(pass, b)) };
    for b in binds {
        let name = if b.usage.is_buffer() {
            let buffer = res.buffer(b.slot).unwrap_or_else(|| unresolved(b));
            for &a in b.usage.accesses() {
                t.buffer(buffer, a);
            }
            &buffer.name
        } else {
            let image = res.image(b.slot, parity).unwrap_or_else(|| unresolved(b));
            for &a in b.usage.accesses() {
                t.image(image, a);
            }
            &image.name
        };
        t.declare(pass, name, b.usage.reads(), b.usage.writes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_follows_the_declaration() {
        let binds = [
            Bind::new(0, Slot::GPosition, Use::Sampled),
            Bind::new(1, Slot::History, Use::StorageReadWrite),
            Bind::new(2, Slot::Counters, Use::WorkList),
        ];
        let l = layout(&binds);
        assert_eq!(l[0], FRAME_BINDING);
        assert_eq!(
            l[1..]
                .iter()
                .map(|b| (b.set, b.binding, b.kind))
                .collect::<Vec<_>>(),
            vec![
                (1, 0, DescriptorKind::SampledImage),
                (1, 1, DescriptorKind::StorageImage),
                (1, 2, DescriptorKind::StorageBuffer),
            ]
        );
        // Attachments are not descriptors.
        let raster = [Bind::new(0, Slot::GNormal, Use::ColorAttachment)];
        assert_eq!(layout(&raster), vec![FRAME_BINDING]);
    }

    #[test]
    fn overwritten_images_are_discarded_and_work_lists_feed_the_dispatch() {
        assert_eq!(
            Use::StorageWrite.accesses(),
            &[Access::Undefined, Access::ComputeStorageWrite]
        );
        assert_eq!(
            Use::WorkList.accesses(),
            &[Access::IndirectCommandRead, Access::ComputeStorageReadWrite]
        );
        assert!(Use::WorkList.is_buffer() && !Use::StorageRead.is_buffer());
    }
}
