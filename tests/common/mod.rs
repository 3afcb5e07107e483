//! Shared test setup: a lavapipe context with validation + synchronization validation, and a
//! check that no validation message was reported.
#![allow(dead_code)]

use ssgi::renderer::pcf::Pcf;
use ssgi::renderer::targets::Target;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::scene::{Camera, Scene};
use ssgi::vk::{Context, ContextOptions, ImageData};
use std::sync::Arc;

pub fn context() -> Arc<Context> {
    Context::new(&ContextOptions {
        validation: true,
        ..Default::default()
    })
    .expect("Vulkan context with validation layers (run tools/setup-vulkan)")
}

/// Fail the test if the validation layers reported anything.
pub fn assert_clean(ctx: &Context) {
    ctx.wait_idle().expect("device idle");
    let log = ctx.validation().expect("validation enabled");
    let messages = log.messages();
    assert!(
        messages.is_empty(),
        "{} validation message(s):\n{}",
        messages.len(),
        messages.join("\n")
    );
}

/// Render `frames` frames of `scene` from its own camera and return the renderer.
pub fn render(ctx: &Arc<Context>, scene: Scene, size: u32, pcf: Pcf, frames: u32) -> Renderer {
    let config = RenderConfig {
        width: size,
        height: size,
        rsm_size: 512,
        pcf,
        ..Default::default()
    };
    let mut r = Renderer::new(ctx, scene, config).expect("renderer");
    let camera: Camera = r.scene.camera;
    for _ in 0..frames {
        r.render_frame(&camera).expect("frame");
    }
    r.finish().expect("finish");
    r
}

pub fn read(r: &mut Renderer, t: Target) -> ImageData {
    r.read(t).expect("readback")
}
