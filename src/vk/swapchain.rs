//! The swapchain: explicit acquire / present synchronisation, out-of-date handling, and the
//! copy of a rendered image into a swapchain image (vkCmdBlitImage, which converts formats,
//! swizzles BGRA and scales when the sizes differ).
//!
//! Synchronisation:
//! - one *acquire* semaphore per frame slot: frame slot `s` acquires with `acquire[s]`, and its
//!   submission waits on it at [`ACQUIRE_WAIT_STAGE`]. The caller must have waited for the
//!   slot's previous submission (the one that waited on the semaphore) before acquiring again.
//! - one *render-finished* semaphore per swapchain image: the submission signals it and the
//!   present waits on it. Per image (not per slot) because a present has no fence: the image
//!   being acquired again is what tells us the present's wait on its semaphore is over.
//! - every swapchain image is tracked like any other image ([`SwapchainImage`] implements
//!   `TrackedImage`); on acquire its state is reset to "contents undefined, last touched at
//!   the acquire wait stage", so the first barrier chains to the acquire semaphore wait.
//!
//! `ERROR_OUT_OF_DATE_KHR` and `SUBOPTIMAL_KHR` from acquire or present are handled in one
//! place ([`Swapchain::note`]): the swapchain is marked stale and the frontend recreates it
//! before the next frame. A zero extent (minimised window) is reported as `None` by
//! [`Swapchain::surface_extent`]: the frontend then does not render.

use super::context::{Context, SubmitSync};
use super::memory::{Buffer, Image};
use super::readback::ImageData;
use super::recorder::Recorder;
use super::surface::Surface;
use super::sync::{Access, ResourceState, Tracked, TrackedImage, Tracker};
use crate::error::{Error, Result, VkContext};
use ash::{khr, vk};
use gpu_allocator::MemoryLocation;
use std::cell::Cell;
use std::sync::Arc;

/// The stage at which a frame's submission waits for the acquired image (the blit into it).
pub const ACQUIRE_WAIT_STAGE: vk::PipelineStageFlags2 = vk::PipelineStageFlags2::BLIT;

/// How long an acquire may block before ssgi reports the presentation engine as stuck.
const ACQUIRE_TIMEOUT_NS: u64 = 10_000_000_000;

/// 8- and 10-bit UNORM formats, best first. The renderer's output is already sRGB-encoded, so
/// a UNORM swapchain image shows it unchanged; an `_SRGB` swapchain would encode it twice.
const PREFERRED_FORMATS: [vk::Format; 4] = [
    vk::Format::B8G8R8A8_UNORM,
    vk::Format::R8G8B8A8_UNORM,
    vk::Format::A2B10G10R10_UNORM_PACK32,
    vk::Format::A2R10G10B10_UNORM_PACK32,
];

/// Which present mode to ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PresentPolicy {
    /// FIFO (vsync): the interactive viewer.
    Vsync,
    /// IMMEDIATE, else MAILBOX, else FIFO: benchmarking, so the display does not cap the rate.
    Benchmark,
}

impl PresentPolicy {
    fn preference(self) -> &'static [vk::PresentModeKHR] {
        match self {
            PresentPolicy::Vsync => &[vk::PresentModeKHR::FIFO],
            PresentPolicy::Benchmark => &[
                vk::PresentModeKHR::IMMEDIATE,
                vk::PresentModeKHR::MAILBOX,
                vk::PresentModeKHR::FIFO,
            ],
        }
    }
}

/// Lower-case name of a present mode, as written in reports.
pub fn present_mode_name(mode: vk::PresentModeKHR) -> &'static str {
    match mode {
        vk::PresentModeKHR::IMMEDIATE => "immediate",
        vk::PresentModeKHR::MAILBOX => "mailbox",
        vk::PresentModeKHR::FIFO => "fifo",
        vk::PresentModeKHR::FIFO_RELAXED => "fifo_relaxed",
        _ => "other",
    }
}

/// First mode of `preference` that `available` offers; FIFO (always supported) otherwise.
pub fn choose_present_mode(
    policy: PresentPolicy,
    available: &[vk::PresentModeKHR],
) -> vk::PresentModeKHR {
    policy
        .preference()
        .iter()
        .copied()
        .find(|m| available.contains(m))
        .unwrap_or(vk::PresentModeKHR::FIFO)
}

/// The extent to create the swapchain with: the surface's current extent when it dictates one,
/// else the window size clamped to the surface limits; `None` when either side is zero
/// (minimised window).
pub fn choose_extent(
    caps: &vk::SurfaceCapabilitiesKHR,
    window: (u32, u32),
) -> Option<vk::Extent2D> {
    let e = if caps.current_extent.width != u32::MAX {
        caps.current_extent
    } else {
        vk::Extent2D {
            width: window
                .0
                .clamp(caps.min_image_extent.width, caps.max_image_extent.width),
            height: window
                .1
                .clamp(caps.min_image_extent.height, caps.max_image_extent.height),
        }
    };
    (e.width > 0 && e.height > 0).then_some(e)
}

/// One image of the swapchain, followed by the sync tracker like any other image.
pub struct SwapchainImage {
    pub raw: vk::Image,
    /// A colour view, for passes that draw over the blitted frame (the viewer's overlay).
    pub view: vk::ImageView,
    state: Cell<ResourceState>,
}

/// The state of an image right after acquire: contents undefined, and "last touched" at the
/// stage the submission waits on the acquire semaphore, so the first barrier's source stage
/// chains to that wait.
fn acquired_state() -> ResourceState {
    ResourceState {
        layout: vk::ImageLayout::UNDEFINED,
        write_stage: ACQUIRE_WAIT_STAGE,
        ..ResourceState::default()
    }
}

impl Tracked for SwapchainImage {
    fn state(&self) -> &Cell<ResourceState> {
        &self.state
    }
}

impl TrackedImage for SwapchainImage {
    fn handle(&self) -> vk::Image {
        self.raw
    }

    fn range(&self) -> vk::ImageSubresourceRange {
        color_range()
    }
}

fn color_range() -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        base_mip_level: 0,
        level_count: 1,
        base_array_layer: 0,
        layer_count: 1,
    }
}

fn color_layers() -> vk::ImageSubresourceLayers {
    vk::ImageSubresourceLayers {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        mip_level: 0,
        base_array_layer: 0,
        layer_count: 1,
    }
}

/// An acquired image and the semaphores its frame must use.
#[derive(Clone, Copy, Debug)]
pub struct AcquiredImage {
    pub index: u32,
    /// Waited on by the frame's submission at [`ACQUIRE_WAIT_STAGE`].
    pub acquired: vk::Semaphore,
    /// Signalled by the frame's submission, waited on by the present.
    pub render_finished: vk::Semaphore,
}

impl AcquiredImage {
    /// The semaphores for the frame's submission.
    pub fn submit_sync(&self) -> SubmitSync {
        SubmitSync {
            wait: vec![(self.acquired, ACQUIRE_WAIT_STAGE)],
            signal: vec![self.render_finished],
        }
    }
}

/// Options fixed for the life of the swapchain (kept across recreation).
#[derive(Clone, Copy, Debug)]
pub struct SwapchainOptions {
    pub policy: PresentPolicy,
    /// Frame slots of the renderer: one acquire semaphore each.
    pub frames_in_flight: usize,
    /// Also request TRANSFER_SRC usage, where the surface allows it, so presented images can
    /// be read back (screenshots).
    pub readable: bool,
}

pub struct Swapchain {
    ctx: Arc<Context>,
    loader: khr::swapchain::Device,
    raw: vk::SwapchainKHR,
    images: Vec<SwapchainImage>,
    pub format: vk::Format,
    pub extent: vk::Extent2D,
    pub present_mode: vk::PresentModeKHR,
    options: SwapchainOptions,
    acquire_semaphores: Vec<vk::Semaphore>,
    render_finished: Vec<vk::Semaphore>,
    stale: bool,
    /// The images can be read back (asked for and allowed by the surface).
    readable: bool,
    /// Declared last: destroyed after the swapchain (see `Drop`).
    surface: Surface,
}

fn create_semaphore(ctx: &Context) -> Result<vk::Semaphore> {
    // SAFETY: valid create info; destroyed in `Swapchain::drop` after the device is idle.
    unsafe {
        ctx.device
            .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
    }
    .vk("vkCreateSemaphore")
}

/// Optimal-tiling format features of `format` on the context's device.
pub fn format_features(ctx: &Context, format: vk::Format) -> vk::FormatFeatureFlags {
    // SAFETY: plain query on the context's physical device.
    unsafe {
        ctx.instance
            .raw
            .get_physical_device_format_properties(ctx.physical, format)
    }
    .optimal_tiling_features
}

impl Swapchain {
    /// Create a swapchain for `surface`. `window` is the window's inner size, used when the
    /// surface does not dictate the extent. Errors when the window has a zero extent (check
    /// [`Self::surface_extent`] first) or when the surface cannot take transfer writes.
    pub fn new(
        ctx: &Arc<Context>,
        surface: Surface,
        window: (u32, u32),
        options: SwapchainOptions,
    ) -> Result<Self> {
        let loader = khr::swapchain::Device::new(&ctx.instance.raw, &ctx.device);
        let mut this = Swapchain {
            ctx: ctx.clone(),
            loader,
            raw: vk::SwapchainKHR::null(),
            images: Vec::new(),
            format: vk::Format::UNDEFINED,
            extent: vk::Extent2D::default(),
            present_mode: vk::PresentModeKHR::FIFO,
            options,
            acquire_semaphores: Vec::new(),
            render_finished: Vec::new(),
            stale: false,
            readable: false,
            surface,
        };
        for _ in 0..options.frames_in_flight.max(1) {
            let s = create_semaphore(ctx)?;
            this.acquire_semaphores.push(s);
        }
        if !this.recreate(window)? {
            return Err(Error::Window(
                "the window has a zero extent (minimised?); cannot create a swapchain".into(),
            ));
        }
        Ok(this)
    }

    /// The extent a swapchain would have now; `None` when the window is minimised.
    pub fn surface_extent(&self, window: (u32, u32)) -> Result<Option<vk::Extent2D>> {
        Ok(choose_extent(&self.surface.capabilities()?, window))
    }

    /// True when acquire or present reported OUT_OF_DATE or SUBOPTIMAL since the last
    /// (re)creation: call [`Self::recreate`] before the next frame.
    pub fn is_stale(&self) -> bool {
        self.stale
    }

    /// Mark the swapchain stale (the window was resized).
    pub fn invalidate(&mut self) {
        self.stale = true;
    }

    pub fn image_count(&self) -> usize {
        self.images.len()
    }

    pub fn image(&self, index: u32) -> &SwapchainImage {
        &self.images[index as usize]
    }

    /// The one place acquire and present results are interpreted: OUT_OF_DATE and SUBOPTIMAL
    /// mark the swapchain stale (recreated before the next frame); other errors are returned.
    /// `Ok(true)` when the operation took effect (an image was acquired / presented).
    fn note(
        &mut self,
        result: std::result::Result<bool, vk::Result>,
        call: &'static str,
    ) -> Result<bool> {
        match result {
            Ok(false) => Ok(true),
            Ok(true) => {
                self.stale = true; // SUBOPTIMAL: usable, but recreate soon
                Ok(true)
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => {
                self.stale = true;
                Ok(false)
            }
            Err(e) => Err(Error::Vulkan { call, result: e }),
        }
    }

    /// (Re)create the swapchain for the surface's current extent. Waits for the device to go
    /// idle first (the caller must not hold frames in flight that use the old images). Returns
    /// false, leaving the old swapchain in place, when the extent is zero (minimised).
    pub fn recreate(&mut self, window: (u32, u32)) -> Result<bool> {
        let caps = self.surface.capabilities()?;
        let Some(extent) = choose_extent(&caps, window) else {
            return Ok(false);
        };
        // COLOR_ATTACHMENT: the viewer's overlay draws over the blitted frame (every surface
        // supports it: VkSurfaceCapabilitiesKHR::supportedUsageFlags must include it).
        let mut usage = vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::COLOR_ATTACHMENT;
        // Reading back is asked for where the surface allows it (`readback_buffer` says so
        // where it does not): a screenshot must not keep the viewer from opening.
        let readable = self.options.readable
            && caps
                .supported_usage_flags
                .contains(vk::ImageUsageFlags::TRANSFER_SRC);
        if readable {
            usage |= vk::ImageUsageFlags::TRANSFER_SRC;
        }
        if !caps.supported_usage_flags.contains(usage) {
            return Err(Error::MissingFeature(format!(
                "swapchain images with usage {usage:?} (the surface supports {:?}); ssgi copies \
                 its output into the swapchain image with a transfer",
                caps.supported_usage_flags
            )));
        }
        let formats = self.surface.formats()?;
        let chosen = PREFERRED_FORMATS.iter().find_map(|want| {
            formats.iter().copied().find(|f| {
                f.format == *want
                    && f.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR
                    && format_features(&self.ctx, f.format)
                        .contains(vk::FormatFeatureFlags::BLIT_DST)
            })
        });
        let Some(format) = chosen else {
            return Err(Error::MissingFeature(format!(
                "a UNORM swapchain format with blit support (wanted one of {PREFERRED_FORMATS:?} \
                 in SRGB_NONLINEAR; the surface offers {:?})",
                formats.iter().map(|f| f.format).collect::<Vec<_>>()
            )));
        };
        let modes = self.surface.present_modes()?;
        let present_mode = choose_present_mode(self.options.policy, &modes);
        let mut count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            count = count.min(caps.max_image_count);
        }
        let alpha = [
            vk::CompositeAlphaFlagsKHR::OPAQUE,
            vk::CompositeAlphaFlagsKHR::INHERIT,
            vk::CompositeAlphaFlagsKHR::PRE_MULTIPLIED,
            vk::CompositeAlphaFlagsKHR::POST_MULTIPLIED,
        ]
        .into_iter()
        .find(|a| caps.supported_composite_alpha.contains(*a))
        .unwrap_or(vk::CompositeAlphaFlagsKHR::OPAQUE);

        self.ctx.wait_idle()?;
        let old = self.raw;
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(self.surface.raw)
            .min_image_count(count)
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(usage)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(alpha)
            .present_mode(present_mode)
            .clipped(true)
            .old_swapchain(old);
        // SAFETY: the surface is live; `old` (possibly null) is this surface's current
        // swapchain; every value was checked against the surface's capabilities above.
        let created = unsafe { self.loader.create_swapchain(&info, None) };
        // The old swapchain is retired by the create call whether or not it succeeded; the
        // device is idle, so nothing uses its images any more.
        if old != vk::SwapchainKHR::null() {
            // SAFETY: device idle (waited above); its images are not used after this.
            unsafe { self.loader.destroy_swapchain(old, None) };
            self.raw = vk::SwapchainKHR::null();
            self.destroy_views();
            self.images.clear();
        }
        self.raw = created.vk("vkCreateSwapchainKHR")?;
        // SAFETY: the swapchain was just created.
        let images =
            unsafe { self.loader.get_swapchain_images(self.raw) }.vk("vkGetSwapchainImagesKHR")?;
        for raw in images {
            let info = vk::ImageViewCreateInfo::default()
                .image(raw)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(format.format)
                .subresource_range(color_range());
            // SAFETY: `raw` is an image of the live swapchain, created with this format;
            // destroyed in `destroy_views` before the swapchain goes.
            let view = unsafe { self.ctx.device.create_image_view(&info, None) }
                .vk("vkCreateImageView")?;
            self.images.push(SwapchainImage {
                raw,
                view,
                state: Cell::new(ResourceState::default()),
            });
        }
        while self.render_finished.len() < self.images.len() {
            let s = create_semaphore(&self.ctx)?;
            self.render_finished.push(s);
        }
        self.format = format.format;
        self.readable = readable;
        self.extent = extent;
        self.present_mode = present_mode;
        self.stale = false;
        Ok(true)
    }

    /// Acquire the next image for frame slot `slot`. The slot's previous submission (which
    /// waited on the slot's acquire semaphore) must have completed. `None` when the swapchain
    /// is out of date: recreate it and try again.
    pub fn acquire(&mut self, slot: usize) -> Result<Option<AcquiredImage>> {
        let acquired = self.acquire_semaphores[slot % self.acquire_semaphores.len()];
        // SAFETY: live swapchain; the semaphore has no pending signal or wait (the caller
        // waited for the slot's previous submission, and a failed acquire leaves it
        // unsignalled).
        let result = unsafe {
            self.loader.acquire_next_image(
                self.raw,
                ACQUIRE_TIMEOUT_NS,
                acquired,
                vk::Fence::null(),
            )
        };
        let (index, suboptimal) = match result {
            Ok(r) => r,
            Err(vk::Result::TIMEOUT) | Err(vk::Result::NOT_READY) => {
                return Err(Error::Window(format!(
                    "vkAcquireNextImageKHR: no image within {} s",
                    ACQUIRE_TIMEOUT_NS / 1_000_000_000
                )))
            }
            Err(e) => {
                self.note(Err(e), "vkAcquireNextImageKHR")?;
                return Ok(None);
            }
        };
        self.note(Ok(suboptimal), "vkAcquireNextImageKHR")?;
        let image = &self.images[index as usize];
        image.state.set(acquired_state());
        Ok(Some(AcquiredImage {
            index,
            acquired,
            render_finished: self.render_finished[index as usize],
        }))
    }

    /// Present `image` (its submission signalled `image.render_finished`). Out-of-date and
    /// suboptimal results mark the swapchain stale.
    pub fn present(&mut self, image: &AcquiredImage) -> Result<()> {
        let waits = [image.render_finished];
        let swapchains = [self.raw];
        let indices = [image.index];
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: the image was acquired from this swapchain and transitioned to
        // PRESENT_SRC_KHR by the submission that signals `render_finished`; the queue is only
        // used from this thread.
        let result = unsafe { self.loader.queue_present(self.ctx.queue, &info) };
        self.note(result, "vkQueuePresentKHR")?;
        Ok(())
    }

    /// Whether an image of `format` can be the source of the blit into the swapchain.
    pub fn can_blit_from(&self, format: vk::Format) -> bool {
        format_features(&self.ctx, format).contains(vk::FormatFeatureFlags::BLIT_SRC)
    }

    /// Record the copy of `src` (any colour image with TRANSFER_SRC usage and a BLIT_SRC
    /// format) into swapchain image `index`, scaled to the swapchain extent.
    pub fn record_blit(&self, rec: &Recorder<'_>, tracker: &mut Tracker, src: &Image, index: u32) {
        let dst = &self.images[index as usize];
        tracker.image(src, Access::TransferSrc);
        tracker.image(dst, Access::TransferDst);
        tracker.flush(rec.device, rec.cmd);
        let (sw, sh) = (src.desc.width, src.desc.height);
        let (dw, dh) = (self.extent.width, self.extent.height);
        let same_size = (sw, sh) == (dw, dh);
        let linear = format_features(&self.ctx, src.desc.format)
            .contains(vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR);
        let filter = if same_size || !linear {
            vk::Filter::NEAREST
        } else {
            vk::Filter::LINEAR
        };
        let corner = |w: u32, h: u32| vk::Offset3D {
            x: w as i32,
            y: h as i32,
            z: 1,
        };
        let region = vk::ImageBlit::default()
            .src_subresource(color_layers())
            .src_offsets([vk::Offset3D::default(), corner(sw, sh)])
            .dst_subresource(color_layers())
            .dst_offsets([vk::Offset3D::default(), corner(dw, dh)]);
        // SAFETY: recording; the tracker put `src` in TRANSFER_SRC_OPTIMAL and `dst` in
        // TRANSFER_DST_OPTIMAL; both are colour images whose formats support blit (checked
        // when the swapchain was created and by `can_blit_from`), the regions lie inside both.
        unsafe {
            rec.device.cmd_blit_image(
                rec.cmd,
                src.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                dst.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
                filter,
            )
        };
    }

    /// A host-visible buffer large enough for one swapchain image (see [`Self::record_copy`]).
    pub fn readback_buffer(&self) -> Result<Buffer> {
        if !self.readable {
            return Err(Error::MissingFeature(
                "reading back presented images: the surface does not allow TRANSFER_SRC usage \
                 on swapchain images"
                    .into(),
            ));
        }
        let size = self.extent.width as u64 * self.extent.height as u64 * 4;
        Buffer::new(
            &self.ctx,
            "swapchain.readback",
            size,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuToCpu,
        )
    }

    /// Record a copy of swapchain image `index` (after the blit, before the present barrier)
    /// into `buffer`, made visible to the host. Needs `readable` swapchain options.
    pub fn record_copy(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        index: u32,
        buffer: &Buffer,
    ) {
        let image = &self.images[index as usize];
        tracker.image(image, Access::TransferSrc);
        tracker.buffer(buffer, Access::TransferDst);
        tracker.flush(rec.device, rec.cmd);
        let region = vk::BufferImageCopy::default()
            .image_subresource(color_layers())
            .image_extent(vk::Extent3D {
                width: self.extent.width,
                height: self.extent.height,
                depth: 1,
            });
        // SAFETY: recording; the image is in TRANSFER_SRC_OPTIMAL, was created with
        // TRANSFER_SRC usage (`readable`), and the buffer holds width*height*4 bytes (every
        // format in PREFERRED_FORMATS has 4-byte texels).
        unsafe {
            rec.device.cmd_copy_image_to_buffer(
                rec.cmd,
                image.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                buffer.raw,
                &[region],
            )
        };
        tracker.buffer(buffer, Access::HostRead);
    }

    /// The host copy of a buffer filled by [`Self::record_copy`] (its frame must have
    /// completed).
    pub fn read_buffer(&self, buffer: &Buffer) -> Result<ImageData> {
        let size = self.extent.width as usize * self.extent.height as usize * 4;
        let bytes =
            buffer.mapped().filter(|m| m.len() >= size).ok_or_else(|| {
                Error::Config("swapchain readback buffer is not host-visible".into())
            })?[..size]
                .to_vec();
        Ok(ImageData {
            width: self.extent.width,
            height: self.extent.height,
            format: self.format,
            bytes,
        })
    }

    /// Record the transition of swapchain image `index` to PRESENT_SRC_KHR (last command of
    /// the frame; the submission's semaphore signal orders it before the present).
    pub fn record_present_barrier(&self, rec: &Recorder<'_>, tracker: &mut Tracker, index: u32) {
        tracker.image(&self.images[index as usize], Access::Present);
        tracker.flush(rec.device, rec.cmd);
    }
}

impl Swapchain {
    /// Destroy the images' views (the device is idle: nothing records or reads them).
    fn destroy_views(&mut self) {
        for image in &mut self.images {
            if image.view != vk::ImageView::null() {
                // SAFETY: callers wait for the device first; the view is not used again.
                unsafe { self.ctx.device.destroy_image_view(image.view, None) };
                image.view = vk::ImageView::null();
            }
        }
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        // SAFETY: wait for the device first (frames in flight may still wait on the
        // semaphores or write the images); then nothing uses the swapchain or semaphores. The
        // surface field drops after this body, so the swapchain goes before its surface.
        unsafe {
            let _ = self.ctx.device.device_wait_idle();
        }
        self.destroy_views();
        // SAFETY: as above: the device is idle.
        unsafe {
            if self.raw != vk::SwapchainKHR::null() {
                self.loader.destroy_swapchain(self.raw, None);
            }
            for s in self
                .acquire_semaphores
                .drain(..)
                .chain(self.render_finished.drain(..))
            {
                self.ctx.device.destroy_semaphore(s, None);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn benchmark_policy_prefers_immediate_then_mailbox_then_fifo() {
        use vk::PresentModeKHR as M;
        let b = PresentPolicy::Benchmark;
        assert_eq!(
            choose_present_mode(b, &[M::FIFO, M::MAILBOX, M::IMMEDIATE]),
            M::IMMEDIATE
        );
        assert_eq!(choose_present_mode(b, &[M::FIFO, M::MAILBOX]), M::MAILBOX);
        assert_eq!(choose_present_mode(b, &[M::FIFO_RELAXED, M::FIFO]), M::FIFO);
        assert_eq!(
            choose_present_mode(PresentPolicy::Vsync, &[M::IMMEDIATE, M::FIFO]),
            M::FIFO
        );
        assert_eq!(choose_present_mode(b, &[]), M::FIFO);
    }

    #[test]
    fn extent_follows_the_surface_or_clamps_the_window() {
        let mut caps = vk::SurfaceCapabilitiesKHR {
            current_extent: vk::Extent2D {
                width: 300,
                height: 200,
            },
            min_image_extent: vk::Extent2D {
                width: 1,
                height: 1,
            },
            max_image_extent: vk::Extent2D {
                width: 4096,
                height: 4096,
            },
            ..Default::default()
        };
        assert_eq!(
            choose_extent(&caps, (10, 10)),
            Some(vk::Extent2D {
                width: 300,
                height: 200
            })
        );
        caps.current_extent = vk::Extent2D {
            width: 0,
            height: 0,
        };
        assert_eq!(choose_extent(&caps, (10, 10)), None, "minimised");
        caps.current_extent = vk::Extent2D {
            width: u32::MAX,
            height: u32::MAX,
        };
        assert_eq!(
            choose_extent(&caps, (8000, 5)),
            Some(vk::Extent2D {
                width: 4096,
                height: 5
            })
        );
        caps.min_image_extent = vk::Extent2D::default();
        assert_eq!(choose_extent(&caps, (0, 5)), None);
    }

    #[test]
    fn acquired_images_chain_to_the_acquire_wait() {
        let mut s = acquired_state();
        let d = super::super::sync::transition(&mut s, Access::TransferDst, true).unwrap();
        assert!(d.src_stage.contains(ACQUIRE_WAIT_STAGE));
        assert_eq!(d.old_layout, vk::ImageLayout::UNDEFINED);
        assert!(d.dst_stage.contains(vk::PipelineStageFlags2::BLIT));
    }
}
