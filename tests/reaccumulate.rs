//! Re-accumulation when the camera stops (`TemporalConfig::reaccumulate`,
//! shaders/reproject.comp): after a walk the held view converges to what a render from
//! scratch of it shows, within the golden-image tolerance, without a pop on the way, and in
//! about the rotation limit's frames, after which frames are skipped again. Without it the
//! held view keeps what resampling the histories under motion did to them.

mod common;

use glam::Vec3;
use ssgi::config::pcf::Pcf;
use ssgi::config::{Effects, RenderConfig, TemporalConfig};
use ssgi::renderer::Renderer;
use ssgi::resources::targets::Target;
use ssgi::scene::{cornell_box, Camera};
use ssgi::vk::{Context, ImageData};
use std::sync::Arc;

const SIZE: u32 = 64;
/// Frames the camera walks (each two thirds of a pixel sideways and a little forward).
const STEPS: u32 = 6;
/// Most frames a view may take to converge (the 36-pattern rotation limit, the counters'
/// two-frame lag, a few frames of margin).
const MAX_FRAMES: usize = 80;
/// Chen, Lei, Chang 2012: consecutive frames differing by less are barely notable flicker.
const FLICKER_MSD: f64 = 2.5e-5;

fn config(reaccumulate: bool) -> RenderConfig {
    RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 128,
        pcf: Pcf::NINE,
        effects: Effects::ALL,
        temporal: TemporalConfig {
            reaccumulate,
            ..Default::default()
        },
        skip_unchanged: true,
        ..Default::default()
    }
}

/// The box's camera after `i` steps of the walk.
fn walked(base: Camera, i: u32) -> Camera {
    let distance = (base.target - base.position).length();
    let pixel = 2.0 * distance * (base.vfov_deg.to_radians() / 2.0).tan() / SIZE as f32;
    let step = Vec3::new(0.67 * pixel, 0.0, -0.3 * pixel) * i as f32;
    Camera {
        position: base.position + step,
        target: base.target + step,
        ..base
    }
}

/// What holding `camera` shows: renders until 4 frames in a row are skipped (panics after
/// `MAX_FRAMES`), reading the output after every frame. Returns the last output, the largest
/// mean squared difference between consecutive outputs and the frames that did work.
fn hold(r: &mut Renderer, camera: &Camera) -> (ImageData, f64, usize) {
    let (mut previous, mut worst, mut worked, mut idle) = (None, 0.0f64, 0, 0);
    for _ in 0..MAX_FRAMES {
        let timing = r.render_frame(camera).expect("frame");
        let out = r.read(Target::Output).expect("output");
        if let Some(p) = &previous {
            worst = worst.max(common::msd(p, &out));
        }
        previous = Some(out);
        // Timings come FRAMES_IN_FLIGHT frames late: a frame that recorded nothing.
        match timing {
            Some(t) if t.passes.is_empty() => idle += 1,
            Some(_) => {
                worked += 1;
                idle = 0;
            }
            None => {}
        }
        if idle >= 4 {
            return (previous.unwrap(), worst, worked);
        }
    }
    panic!("no 4 skipped frames in a row within {MAX_FRAMES} frames of holding the view");
}

/// Converged at the box's camera, then the walk, with a pause of a few frames halfway (a
/// re-accumulation the camera interrupts), then `hold` at its end; every history, moments and
/// registration image is finite (and non-negative where it must be) at the end.
fn walk_and_hold(ctx: &Arc<Context>, reaccumulate: bool) -> (ImageData, f64, usize) {
    let mut r = Renderer::new(ctx, cornell_box(), config(reaccumulate)).expect("renderer");
    let base = r.scene.camera;
    hold(&mut r, &base);
    for i in 1..=STEPS {
        let pause = if i == STEPS / 2 { 6 } else { 1 };
        for _ in 0..pause {
            r.render_frame(&walked(base, i)).expect("frame");
        }
    }
    // The first held frame still differs from the last step by the step itself.
    let end = walked(base, STEPS);
    r.render_frame(&end).expect("frame");
    let held = hold(&mut r, &end);
    for a in r.audit().expect("audit") {
        assert_eq!(a.bad_values(), 0, "{a:?}");
    }
    held
}

#[test]
fn a_held_view_converges_to_a_render_from_scratch() {
    let ctx = common::context();
    let end = walked(cornell_box().camera, STEPS);
    let mut fresh = Renderer::new(&ctx, cornell_box(), config(true)).expect("renderer");
    let (want, _, fresh_frames) = hold(&mut fresh, &end);
    let (got, flicker, frames) = walk_and_hold(&ctx, true);
    let (kept, kept_flicker, kept_frames) = walk_and_hold(&ctx, false);
    let off = common::golden_compare(&kept.bytes, &want.bytes, SIZE);
    eprintln!(
        "re-accumulating: largest consecutive-frame MSD {flicker:.2e}, {frames} frames of work \
         (from scratch {fresh_frames}); without: {kept_flicker:.2e}, {kept_frames} frames, \
         against a render from scratch: {off:?}"
    );
    if let Some(msg) = common::golden_compare(&got.bytes, &want.bytes, SIZE) {
        panic!("the held view against a render from scratch of it: {msg}");
    }
    assert!(
        off.is_some(),
        "without re-accumulation the walk's resampling should show in the held view"
    );
    assert!(flicker < FLICKER_MSD, "consecutive-frame MSD {flicker:.2e}");
    // The rotation limit's frames and the counters' lag; not more than a render from scratch.
    assert!(frames <= fresh_frames + 2, "{frames} frames of work");
    common::assert_clean(&ctx);
}
