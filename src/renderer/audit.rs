//! Numerical audit of every target and history after a frame: NaN, infinite and negative
//! values counted on the GPU (`shaders/probes/image_stats.comp`, one reduction per image),
//! each channel's largest finite magnitude read back. `ssgi stress` and the tests use it to
//! show that no buffer holds a value that could poison later frames.

use super::Renderer;
use crate::effects::FrameInfo;
use crate::error::Result;
use crate::passes::compute::FrameSet;
use crate::resources::targets::Target;
use crate::shaders::{DescriptorKind, ImageStatsPush, ReflectedBinding, IMAGE_STATS_COMP};
use crate::vk::recorder::Recorder;
use crate::vk::{
    one_shot, Access, Buffer, Context, DescriptorPool, Image, Pipeline, SetWriter, Tracker,
};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Bytes of the shader's `Stats` block: four counters and four channel maxima.
const STATS_BYTES: usize = 32;

/// What an audited image holds, for the checks that depend on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AuditKind {
    /// A frame target (G-buffer, RSM, effect outputs).
    Target,
    /// A temporal effect's history: rgb value, a = estimates accumulated.
    History,
    /// A temporal effect's moments (mean squared luminance, gate flag, estimates in the mean).
    Moments,
    /// A temporal effect's history registration (surface point, magnification >= 1; while it
    /// re-accumulates, the value it fades out and a negative marker: shaders/reproject.comp).
    Registration,
}

/// One image's audit.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ImageAudit {
    pub name: String,
    pub kind: AuditKind,
    pub texels: u32,
    /// Channels read per texel.
    pub channels: u32,
    /// Channel values (not texels) that are NaN, infinite, or negative where the image's
    /// meaning forbids it.
    pub nan: u32,
    pub inf: u32,
    pub negative: u32,
    /// Largest finite |value| of each channel (unused channels 0).
    pub max_abs: [f32; 4],
}

impl ImageAudit {
    /// NaN, infinite and forbidden negative values together.
    pub fn bad_values(&self) -> u64 {
        self.nan as u64 + self.inf as u64 + self.negative as u64
    }
}

/// An image to audit: its report name, kind, the channels read (1..=4) and those that may be
/// negative (bit c for channel c).
pub struct AuditRequest<'a> {
    pub name: String,
    pub kind: AuditKind,
    pub image: &'a Image,
    pub channels: u32,
    pub signed_mask: u32,
}

/// Channels the reduction reads for `format`; `None` for formats that cannot hold NaN,
/// infinities or negative values (unorm, unsigned integers).
fn float_channels(format: vk::Format) -> Option<u32> {
    match format {
        vk::Format::R32G32B32A32_SFLOAT | vk::Format::R16G16B16A16_SFLOAT => Some(4),
        vk::Format::R32_SFLOAT | vk::Format::D32_SFLOAT => Some(1),
        _ => None,
    }
}

/// The moments' g is the side of a pending gate crossing, -1, 0 or +1.
const MOMENTS_SIGNED: u32 = 0b0010;
/// A registration's point is a world position (any sign); its w a magnification (>= 1) or a
/// re-accumulation's marker (< 0).
const POSITION_SIGNED: u32 = 0b1111;

impl Renderer {
    /// Audit every float target and every history, moments and registration image of the last
    /// rendered frame (waits for the GPU). Images no frame has written yet are left out.
    pub fn audit(&mut self) -> Result<Vec<ImageAudit>> {
        self.ctx.wait_idle()?;
        let parity = self.last_parity();
        // A history whose lane does not run under this configuration (no reuse, a PCF grid
        // that does not accumulate) holds whatever its memory held: not audited.
        let info = FrameInfo {
            config: &self.config,
            targets: &self.targets,
            frame: FrameSet {
                set: self.frames[parity % self.frames.len()].set,
                parity,
            },
            frame_index: self.frame_index,
            history_valid: true,
            camera_moved: false,
            camera_stopped: false,
            light_changed: false,
            light_view: false,
            objects_moved: false,
        };
        let mut list: Vec<AuditRequest<'_>> = Vec::new();
        for e in &self.effects {
            let Some(t) = e.temporal().filter(|_| e.reprojects(&info)) else {
                continue;
            };
            let name = t.kind.name;
            list.push(AuditRequest {
                name: format!("{name}.history"),
                kind: AuditKind::History,
                image: t.history.current(parity),
                channels: 4,
                signed_mask: 0,
            });
            list.push(AuditRequest {
                name: format!("{name}.moments"),
                kind: AuditKind::Moments,
                image: t.moments.current(parity),
                channels: 4,
                signed_mask: MOMENTS_SIGNED,
            });
            list.push(AuditRequest {
                name: format!("{name}.registration"),
                kind: AuditKind::Registration,
                image: t.registration.current(parity),
                channels: 4,
                signed_mask: POSITION_SIGNED,
            });
        }
        for target in crate::effects::all_targets() {
            let gbuffer_history =
                matches!(target, Target::GPositionHistory | Target::GNormalHistory);
            if gbuffer_history && !self.last_frame_reused {
                continue;
            }
            let image =
                super::resolve_target(&self.targets, &self.effects, &self.config, target, parity);
            let Some(image) = image else { continue };
            let Some(channels) = float_channels(image.desc.format) else {
                continue;
            };
            list.push(AuditRequest {
                name: target.name().to_string(),
                kind: AuditKind::Target,
                image,
                channels,
                signed_mask: target.look().signed_channels(),
            });
        }
        // A target may be a history itself (AO with reuse): audit each image once, under its
        // history name. Never-written images (layout still undefined) hold no values yet.
        let mut seen = std::collections::HashSet::new();
        list.retain(|a| {
            a.image.holds_contents()
                && a.image.desc.usage.contains(vk::ImageUsageFlags::SAMPLED)
                && seen.insert(a.image.raw)
        });
        if self.audit.is_none() {
            self.audit = Some(audit_pipeline(&self.ctx)?);
        }
        let Some(pipeline) = &self.audit else {
            return Ok(Vec::new());
        };
        audit_images(&self.ctx, &mut self.tracker, pipeline, &list)
    }
}

/// The reduction's compute pipeline (`shaders/probes/image_stats.comp`).
pub fn audit_pipeline(ctx: &Arc<Context>) -> Result<Pipeline> {
    let declared = [
        ReflectedBinding {
            set: 0,
            binding: 0,
            kind: DescriptorKind::SampledImage,
            count: 1,
        },
        ReflectedBinding {
            set: 0,
            binding: 1,
            kind: DescriptorKind::StorageBuffer,
            count: 1,
        },
    ];
    Pipeline::compute(ctx, "image_stats", &IMAGE_STATS_COMP, &declared)
}

/// Audit `list` (images with contents, sampled usage, float formats) with `pipeline`
/// ([`audit_pipeline`]): one reduction per image in one command buffer, the counters back in
/// one wait.
pub fn audit_images(
    ctx: &Arc<Context>,
    tracker: &mut Tracker,
    pipeline: &Pipeline,
    list: &[AuditRequest<'_>],
) -> Result<Vec<ImageAudit>> {
    if list.is_empty() {
        return Ok(Vec::new());
    }
    let pool = DescriptorPool::new(ctx)?;
    let mut buffers = Vec::with_capacity(list.len());
    let mut sets = Vec::with_capacity(list.len());
    for a in list {
        let mut buffer = Buffer::new(
            ctx,
            &format!("audit.{}", a.name),
            STATS_BYTES as u64,
            vk::BufferUsageFlags::STORAGE_BUFFER,
            MemoryLocation::GpuToCpu,
        )?;
        buffer.write(&[0u8; STATS_BYTES])?;
        let set = pool.allocate(pipeline.set_layouts[0], &format!("audit {}", a.name))?;
        SetWriter::new()
            .sampled(0, a.image)
            .storage_buffer(1, &buffer)
            .write(ctx, set);
        buffers.push(buffer);
        sets.push(set);
    }
    one_shot(ctx, |cmd| {
        for (a, buffer) in list.iter().zip(&buffers) {
            tracker.image(a.image, Access::ComputeSampledRead);
            tracker.buffer(buffer, Access::ComputeStorageReadWrite);
        }
        tracker.flush(&ctx.device, cmd);
        let rec = Recorder::new(ctx, cmd);
        for (a, set) in list.iter().zip(&sets) {
            let push = ImageStatsPush {
                size: [a.image.desc.width, a.image.desc.height],
                channels: a.channels,
                signed_mask: a.signed_mask,
            };
            rec.bind(pipeline, &[*set]);
            rec.push(pipeline, &push.to_bytes());
            rec.dispatch_2d(pipeline, a.image.desc.width, a.image.desc.height);
        }
        for buffer in &buffers {
            tracker.buffer(buffer, Access::HostRead);
        }
        tracker.flush(&ctx.device, cmd);
        Ok(())
    })?;
    list.iter()
        .zip(&buffers)
        .map(|(a, buffer)| {
            let bytes = buffer.mapped().ok_or_else(|| {
                crate::error::Error::Config("audit buffer is not host-visible".into())
            })?;
            let word = |i: usize| u32::from_le_bytes(bytes[4 * i..4 * i + 4].try_into().unwrap());
            Ok(ImageAudit {
                name: a.name.clone(),
                kind: a.kind,
                channels: a.channels,
                nan: word(0),
                inf: word(1),
                negative: word(2),
                texels: word(3),
                max_abs: std::array::from_fn(|c| f32::from_bits(word(4 + c))),
            })
        })
        .collect()
}
