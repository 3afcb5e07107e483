//! Debug names and command labels: a validation message about an image carries the image's
//! name and the labels of the passes involved, so a report says what went wrong where.

mod common;

use ssgi::config::Effects;
use ssgi::effects::Recording;
use ssgi::renderer::{FrameHook, RenderConfig, Renderer};
use ssgi::resources::targets::Target;
use ssgi::scene::cornell_box;
use ssgi::vk::{Buffer, Image, SubmitSync};

#[test]
fn a_validation_error_names_the_image_and_the_pass() {
    let ctx = common::context();
    let config = RenderConfig {
        width: 32,
        height: 32,
        rsm_size: 64,
        effects: Effects {
            direct: true,
            ..Effects::NONE
        },
        ..Default::default()
    };
    let mut r = Renderer::new(&ctx, cornell_box(), config).expect("renderer");
    let staging = Buffer::new(
        &ctx,
        "test.staging",
        32 * 32 * 4,
        ash::vk::BufferUsageFlags::TRANSFER_DST,
        gpu_allocator::MemoryLocation::GpuToCpu,
    )
    .unwrap();
    // The mistake under test: copying the output without telling the tracker, so no barrier
    // orders it after the composite's storage write and the image is still in GENERAL.
    let mut record = |r: &mut Recording<'_>, image: &Image| {
        r.rec.copy_image_to_buffer(image, &staging);
    };
    let camera = r.scene.camera;
    r.render_frame_with(
        &camera,
        Some(FrameHook {
            record: &mut record,
            sync: SubmitSync::default(),
            source: Target::Output,
        }),
    )
    .expect("frame");
    r.finish().expect("finish");
    ctx.wait_idle().unwrap();
    let messages = ctx.validation().expect("validation on").messages();
    assert!(
        !messages.is_empty(),
        "the unsynchronised copy was not reported"
    );
    // The layer writes names as `VkImage 0x..[output]`; ssgi appends `[objects: IMAGE
    // "output"]` and `[labels: frame_hook]` from the callback data.
    let named = messages.iter().find(|m| {
        (m.contains("[output]") || m.contains("\"output\"")) && m.contains("[labels: frame_hook]")
    });
    assert!(
        named.is_some(),
        "no message names the image \"output\" and the label frame_hook:\n{}",
        messages.join("\n")
    );
}
