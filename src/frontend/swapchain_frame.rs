//! The two steps every windowed frame shares, for the interactive viewer (`window/`) and for
//! runs driven from outside the event loop (`window_sink.rs`): bring a stale swapchain up to
//! date, and render one frame into an acquired swapchain image and present it.

use crate::effects::Recording;
use crate::error::Result;
use crate::passes::PassId;
use crate::renderer::{FrameHook, Renderer};
use crate::resources::targets::Target;
use crate::scene::Camera;
use crate::vk::recorder::Recorder;
use crate::vk::swapchain::SwapchainImage;
use crate::vk::{Buffer, FrameTiming, Image, Swapchain, Tracker};
use ash::vk;

/// What [`recreate`] did.
pub enum Recreated {
    /// The swapchain matches the surface again; the timings of the frames the renderer had in
    /// flight (it waited for them: the old images may not be in use when they go).
    Ready(Vec<FrameTiming>),
    /// The window has a zero extent (minimised): nothing was changed; try again later.
    ZeroExtent,
}

/// Recreate `swapchain` for a window of inner size `window`.
pub fn recreate(
    swapchain: &mut Swapchain,
    window: (u32, u32),
    renderer: &mut Renderer,
) -> Result<Recreated> {
    if swapchain.surface_extent(window)?.is_none() {
        return Ok(Recreated::ZeroExtent);
    }
    let pending = renderer.finish()?;
    if !swapchain.recreate(window)? {
        return Ok(Recreated::ZeroExtent);
    }
    Ok(Recreated::Ready(pending))
}

/// What [`render_and_present`] did.
pub enum Presented {
    /// The frame was rendered and queued for presentation; its timing is the one of an older
    /// frame whose slot came round (see `Renderer::render_frame`).
    Frame(Option<FrameTiming>),
    /// The swapchain was out of date: nothing was rendered. Recreate it and try again.
    OutOfDate,
}

/// Records the viewer's overlay over the blitted frame: the swapchain image and its extent
/// (timed as `PassId::OVERLAY`).
pub type OverlayDraw<'a> =
    &'a mut dyn FnMut(&Recorder<'_>, &mut Tracker, &SwapchainImage, vk::Extent2D);

/// Render one frame of `renderer` at `camera` with `source` (or `replace`, an image of the
/// frontend's: the viewer's error map) blitted into the next swapchain image, `overlay` drawn
/// over it, then present it. With `capture`, the presented image is also copied into that
/// buffer (read it after the frame completed).
pub fn render_and_present(
    swapchain: &mut Swapchain,
    renderer: &mut Renderer,
    camera: &Camera,
    (source, replace): (Target, Option<&Image>),
    capture: Option<&Buffer>,
    mut overlay: Option<OverlayDraw<'_>>,
) -> Result<Presented> {
    // The slot's previous submission waited on the slot's acquire semaphore: it must be done
    // before the semaphore is handed to vkAcquireNextImageKHR again.
    renderer.wait_for_next_slot()?;
    let Some(image) = swapchain.acquire(renderer.next_slot())? else {
        return Ok(Presented::OutOfDate);
    };
    let chain = &*swapchain;
    let mut record = |r: &mut Recording<'_>, src: &Image| {
        chain.record_blit(&r.rec, r.tracker, replace.unwrap_or(src), image.index);
        if let Some(draw) = overlay.as_mut() {
            let target = chain.image(image.index);
            r.timed(PassId::OVERLAY, |rec, tracker| {
                draw(rec, tracker, target, chain.extent)
            });
        }
        if let Some(buffer) = capture {
            chain.record_copy(&r.rec, r.tracker, image.index, buffer);
        }
        chain.record_present_barrier(&r.rec, r.tracker, image.index);
    };
    let timing = renderer.render_frame_with(
        camera,
        Some(FrameHook {
            record: &mut record,
            sync: image.submit_sync(),
            source,
        }),
    )?;
    swapchain.present(&image)?;
    Ok(Presented::Frame(timing))
}
