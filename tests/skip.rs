//! Nothing changed, nothing recorded (`RenderConfig::skip_unchanged`): once camera, light and
//! configuration stay put and every temporal effect has converged (its counters read back
//! zero work), a frame records no pass; its output is the previous frame's, bit for bit; a
//! change (camera, light, configuration, a moving object) records the passes the dependency
//! table predicts, draws what a renderer that never skips draws, bit for bit, and once
//! converged again matches a render from scratch of the new state within the golden-image
//! tolerance (`common::golden_compare`).

mod common;

use glam::Vec3;
use ssgi::config::antialias::{AaConfig, AaMode};
use ssgi::config::pcf::Pcf;
use ssgi::config::{Effects, TemporalConfig};
use ssgi::renderer::skip::Change;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::resources::targets::Target;
use ssgi::scene::path::frame_time;
use ssgi::scene::{Camera, Keyframe, LightPath};
use ssgi::vk::{Context, FrameTiming};
use std::collections::BTreeSet;
use std::sync::Arc;

const SIZE: u32 = 32;
/// Enough for the 36-pattern rotation limit, the refresh after the first frame and the
/// counters' two-frame lag.
const MAX_FRAMES: u32 = 240;

fn config(reuse: bool, skip: bool) -> RenderConfig {
    RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 128,
        effects: Effects::ALL,
        // The thesis's pairing: the accumulated 9-sample disc with reuse, the grid without.
        pcf: if reuse { Pcf::NINE } else { Pcf::DEFAULT },
        // Ten frames' evaluations per frame for the refresh after a change (16x16 tiles, a few
        // frames to cover the image): at the 5% default a 32x32 frame refreshes one pixel per
        // frame and takes about 1000 frames to cover.
        temporal: TemporalConfig {
            reuse,
            refresh_budget: 10.0,
            ..Default::default()
        },
        skip_unchanged: skip,
        ..Default::default()
    }
}

/// Render `frames` frames at `camera`, returning every timing (the GPU idle at the end).
fn run(r: &mut Renderer, camera: &Camera, frames: u32) -> Vec<FrameTiming> {
    let mut t = Vec::new();
    for _ in 0..frames {
        t.extend(r.render_frame(camera).expect("frame"));
    }
    t.extend(r.finish().expect("finish"));
    t
}

fn skipped(t: &FrameTiming) -> bool {
    t.passes.is_empty()
}

/// Render until `n` frames in a row were skipped (at most `MAX_FRAMES`); returns the timings.
fn until_skipping(r: &mut Renderer, camera: &Camera, n: usize) -> Vec<FrameTiming> {
    let mut timings: Vec<FrameTiming> = Vec::new();
    while timings.len() < MAX_FRAMES as usize {
        timings.extend(run(r, camera, 8));
        let tail = timings.iter().rev().take_while(|t| skipped(t)).count();
        if tail >= n {
            return timings;
        }
    }
    let work: Vec<String> = timings
        .iter()
        .map(|t| {
            let c: Vec<String> = t
                .counters
                .iter()
                .filter(|(_, v)| *v > 0)
                .map(|(n, v)| format!("{n}={v}"))
                .collect();
            let p: Vec<&str> = t.passes.iter().map(|(n, _)| *n).collect();
            format!("{} passes {}", p.join(","), c.join(" "))
        })
        .collect();
    panic!("no {n} skipped frames in a row within {MAX_FRAMES} frames: {work:?}");
}

fn renderer(ctx: &Arc<Context>, config: RenderConfig) -> Renderer {
    Renderer::new(ctx, ssgi::scene::cornell_box(), config).expect("renderer")
}

#[test]
fn a_converged_static_view_records_nothing_and_keeps_its_image() {
    let ctx = common::context();
    let mut r = renderer(&ctx, config(true, true));
    let camera = r.scene.camera;
    let timings = until_skipping(&mut r, &camera, 16);
    let last16 = &timings[timings.len() - 16..];
    assert!(last16.iter().all(skipped));
    // Every pass of a skipped frame is reported, with its reason.
    let reasons: Vec<(&str, &str)> = last16[0]
        .skipped
        .iter()
        .map(|s| (s.pass, s.reason.name()))
        .collect();
    for (pass, reason) in [
        ("gbuffer", "unchanged"),
        ("light_view", "unchanged"),
        ("reproject", "converged"),
        ("ssao", "converged"),
        ("composite", "unchanged"),
    ] {
        assert!(reasons.contains(&(pass, reason)), "{pass}: {reasons:?}");
    }
    // (No GPU-time bound: a skipped frame records no pass, which `skipped` checks exactly.)
    // The frame before the first skipped one did work and computed nothing: it converged.
    let start = timings.iter().position(skipped).unwrap();
    assert!(
        start > 36,
        "skipped from frame {start}, before the rotation limit"
    );
    let before = &timings[start - 1];
    let work: u64 = before
        .counters
        .iter()
        .filter(|(n, _)| n.ends_with("_computed_pixels"))
        .map(|(_, v)| v)
        .sum();
    assert_eq!(work, 0, "{:?}", before.counters);
    // A skipped frame shows the previous frame's output, bit for bit.
    let a = common::read(&mut r, Target::Output);
    run(&mut r, &camera, 1);
    let b = common::read(&mut r, Target::Output);
    assert_eq!(a.bytes, b.bytes);
    common::assert_clean(&ctx);
}

#[test]
fn with_skipping_off_every_frame_records_its_passes() {
    let ctx = common::context();
    let mut r = renderer(&ctx, config(true, false));
    let camera = r.scene.camera;
    let timings = run(&mut r, &camera, 120);
    assert!(timings.iter().all(|t| !skipped(t)));
    common::assert_clean(&ctx);
}

/// A renderer that skips and one that never does, fed the same frames: every image of the
/// first must equal the second's, bit for bit.
struct Pair {
    skipping: Renderer,
    always: Renderer,
}

impl Pair {
    fn new(ctx: &Arc<Context>) -> Self {
        Self::with(ctx, |c| c)
    }

    /// The pair under `config(true, _)` changed by `f`.
    fn with(ctx: &Arc<Context>, f: impl Fn(RenderConfig) -> RenderConfig) -> Self {
        Self {
            skipping: renderer(ctx, f(config(true, true))),
            always: renderer(ctx, f(config(true, false))),
        }
    }

    /// Render until the skipping one skips 4 frames in a row; the other as many frames.
    /// Returns the skipping one's timings.
    fn converge(&mut self, camera: &Camera) -> Vec<FrameTiming> {
        let timings = until_skipping(&mut self.skipping, camera, 4);
        run(&mut self.always, camera, timings.len() as u32);
        timings
    }

    /// One frame of both; the skipping one's timing.
    fn frame(&mut self, camera: &Camera) -> FrameTiming {
        run(&mut self.always, camera, 1);
        run(&mut self.skipping, camera, 1).pop().unwrap()
    }

    /// The skipping one, converged again after a change, against `fresh` (a renderer that
    /// saw only the new state) converged at `camera`: equal within the golden tolerance.
    fn assert_like_fresh(&mut self, mut fresh: Renderer, camera: &Camera, what: &str) {
        let frames = until_skipping(&mut self.skipping, camera, 4).len();
        run(&mut self.always, camera, frames as u32);
        until_skipping(&mut fresh, camera, 4);
        let x = common::read(&mut self.skipping, Target::Output);
        let y = common::read(&mut fresh, Target::Output);
        if let Some(msg) = common::golden_compare(&x.bytes, &y.bytes, x.width) {
            panic!("{what}: against a render from scratch of the new state: {msg}");
        }
    }

    fn assert_same(&mut self, what: &str) {
        let x = common::read(&mut self.skipping, Target::Output);
        let y = common::read(&mut self.always, Target::Output);
        assert!(
            x.bytes == y.bytes,
            "{what}: the image differs from the unskipped one"
        );
    }
}

/// The passes of `t` but the refresh tiles' (those run on the refresh schedule's frames).
fn scheduled(t: &FrameTiming) -> BTreeSet<&str> {
    t.passes
        .iter()
        .map(|(n, _)| *n)
        .filter(|n| !n.ends_with("_refresh"))
        .collect()
}

/// The passes the dependency table says `change` runs again, among those the configuration
/// records (the passes of `from_scratch`, frames that recorded everything), refresh tiles aside.
fn predicted<'a>(
    r: &Renderer,
    from_scratch: &'a [FrameTiming],
    change: Change,
) -> BTreeSet<&'a str> {
    let table = r.dependency_table();
    from_scratch
        .iter()
        .flat_map(scheduled)
        .filter(|name| {
            table
                .iter()
                .any(|t| t.pass.name() == *name && t.changes.contains(&change))
        })
        .collect()
}

/// The passes `t` recorded; panics naming any of `passes` it did not.
fn assert_ran<'a>(t: &'a FrameTiming, passes: &[&str]) -> Vec<&'a str> {
    let recorded: Vec<&str> = t.passes.iter().map(|(n, _)| *n).collect();
    for pass in passes {
        assert!(recorded.contains(pass), "{pass}: {recorded:?}");
    }
    recorded
}

/// After skipping: moving the light renders the light view and what the light reaches, but
/// not the G-buffer (the camera stood still) or AO (converged, independent of the light), and
/// once converged the image is a render from scratch of the moved light's; moving the camera
/// by one pixel then renders the G-buffer and every effect again, but not the light view.
/// Each time the passes are those the dependency table predicts and the image is that of a
/// renderer that never skips, bit for bit, until everything converges once more, and then a
/// render from scratch of the new state (after the camera move thanks to the re-accumulation
/// when it stops: docs/techniques.md, "Refresh only where it serves").
#[test]
fn a_change_renders_again() {
    let ctx = common::context();
    let mut p = Pair::new(&ctx);
    let camera = p.skipping.scene.camera;
    let first = p.converge(&camera);
    let from_scratch = &first[..3];
    let mut light = p.skipping.scene.light;
    light.position += Vec3::new(0.05, 0.0, 0.0);
    p.skipping.set_light(light);
    p.always.set_light(light);
    let frame = p.frame(&camera);
    let recorded = assert_ran(
        &frame,
        &[
            "light_view",
            "reproject",
            "shadow",
            "direct",
            "indirect_gather",
            "composite",
        ],
    );
    // What the light does not reach stays: the G-buffer (the camera stood still) and the
    // converged AO.
    let reasons: Vec<(&str, &str)> = frame
        .skipped
        .iter()
        .map(|s| (s.pass, s.reason.name()))
        .collect();
    for (pass, reason) in [("gbuffer", "unchanged"), ("ssao", "converged")] {
        assert!(
            reasons.contains(&(pass, reason)),
            "{pass}: {reasons:?} ran {recorded:?}"
        );
    }
    assert_eq!(
        scheduled(&frame),
        predicted(&p.skipping, from_scratch, Change::Light),
        "light move"
    );
    p.assert_same("after the light move");
    let mut fresh = renderer(&ctx, config(true, true));
    fresh.set_light(light);
    p.assert_like_fresh(fresh, &camera, "after the light moved");
    p.converge(&camera);
    // One pixel sideways at the target's distance.
    let distance = (camera.target - camera.position).length();
    let pixel = 2.0 * distance * (camera.vfov_deg.to_radians() / 2.0).tan() / SIZE as f32;
    let moved = Camera {
        position: camera.position + Vec3::new(pixel, 0.0, 0.0),
        target: camera.target + Vec3::new(pixel, 0.0, 0.0),
        ..camera
    };
    let frame = p.frame(&moved);
    assert_ran(
        &frame,
        &[
            "gbuffer",
            "reproject",
            "ssao",
            "shadow",
            "indirect_gather",
            "composite",
        ],
    );
    assert!(frame.skipped("light_view"));
    assert_eq!(
        scheduled(&frame),
        predicted(&p.skipping, from_scratch, Change::Camera),
        "camera move"
    );
    p.assert_same("after the camera move");
    let mut fresh = renderer(&ctx, config(true, true));
    fresh.set_light(light);
    p.assert_like_fresh(fresh, &moved, "after the camera move");
    p.assert_same("converged after the camera move");
    common::assert_clean(&ctx);
}

/// A configuration change through the viewer (its soft-shadow switch changes the PCF kernel
/// in place): every effect runs again (its inputs include the configuration), the G-buffer
/// does not (the camera stood still), and the image equals that of a renderer that never
/// skips, bit for bit, and, converged, a render from scratch of the new state. Switched back to
/// the accumulated disc after the light moved, the shadows restart rather than come back stale.
#[test]
fn a_configuration_change_reruns_the_effects_but_not_the_gbuffer() {
    let ctx = common::context();
    let mut p = Pair::new(&ctx);
    let camera = p.skipping.scene.camera;
    let first = p.converge(&camera);
    p.skipping.config.pcf = Pcf::HARD;
    p.always.config.pcf = Pcf::HARD;
    let frame = p.frame(&camera);
    let recorded = assert_ran(
        &frame,
        &["shadow", "direct", "ssao", "indirect_gather", "composite"],
    );
    assert!(!recorded.contains(&"gbuffer"), "{recorded:?}");
    assert_eq!(
        scheduled(&frame),
        predicted(&p.skipping, &first[..3], Change::Config),
        "configuration change"
    );
    p.assert_same("after the configuration change");
    let fresh = renderer(
        &ctx,
        RenderConfig {
            pcf: Pcf::HARD,
            ..config(true, true)
        },
    );
    p.assert_like_fresh(fresh, &camera, "after the configuration change");
    // The light moves while the shadows are hard; back on the accumulated disc, the shadow
    // history (of the old light) restarts instead of coming back stale.
    let mut light = p.skipping.scene.light;
    light.position += Vec3::new(0.3, 0.0, 0.0);
    p.skipping.set_light(light);
    until_skipping(&mut p.skipping, &camera, 4);
    p.skipping.config.pcf = Pcf::NINE;
    let mut fresh = renderer(&ctx, config(true, true));
    fresh.set_light(light);
    p.assert_like_fresh(fresh, &camera, "back on the accumulated disc");
    common::assert_clean(&ctx);
}

/// `c` with SRAA.
fn sraa(c: RenderConfig) -> RenderConfig {
    RenderConfig {
        aa: AaConfig {
            mode: AaMode::Sraa,
            ..AaConfig::default()
        },
        ..c
    }
}

/// With SRAA the subpixel geometry is the G-buffer's kin: a moved light records the
/// reconstruction (it filters the new shading) but not the subpixel renders, which see only
/// the camera and the objects, as the table says; the image equals a renderer that never
/// skips, bit for bit.
#[test]
fn with_sraa_a_light_move_keeps_the_subpixel_geometry() {
    let ctx = common::context();
    let mut p = Pair::with(&ctx, sraa);
    let camera = p.skipping.scene.camera;
    let first = p.converge(&camera);
    assert_ran(&first[0], &["sraa_geometry", "sraa"]);
    let mut light = p.skipping.scene.light;
    light.position += Vec3::new(0.05, 0.0, 0.0);
    p.skipping.set_light(light);
    p.always.set_light(light);
    let frame = p.frame(&camera);
    let recorded = assert_ran(&frame, &["light_view", "composite", "sraa"]);
    assert!(
        frame.skipped("sraa_geometry") && frame.skipped("gbuffer"),
        "{recorded:?}"
    );
    assert_eq!(
        scheduled(&frame),
        predicted(&p.skipping, &first[..3], Change::Light),
        "light move"
    );
    p.assert_same("after the light move");
    let mut fresh = renderer(&ctx, sraa(config(true, true)));
    fresh.set_light(light);
    p.assert_like_fresh(fresh, &camera, "after the light move");
    common::assert_clean(&ctx);
}

/// Without reuse every frame is the same fixed-pattern estimate: frames skip from the third,
/// and the image is the one a renderer that never skips draws.
#[test]
fn without_reuse_skipped_frames_match_a_renderer_that_never_skips() {
    let ctx = common::context();
    let mut skipping = renderer(&ctx, config(false, true));
    let mut always = renderer(&ctx, config(false, false));
    let camera = skipping.scene.camera;
    let timings = run(&mut skipping, &camera, 6);
    let pattern: Vec<bool> = timings.iter().map(skipped).collect();
    assert_eq!(pattern, [false, false, true, true, true, true]);
    run(&mut always, &camera, 6);
    let a = common::read(&mut skipping, Target::Output);
    let b = common::read(&mut always, Target::Output);
    assert_eq!(a.bytes, b.bytes);
    common::assert_clean(&ctx);
}

/// A light path that moves the spot 2 cm on every other frame of 16 (frames 1, 3, ..., 15;
/// `Renderer::set_time` poses it): the light view is recorded on exactly those 8 frames and
/// the first frame of the run; the shadow and the indirect light run on each of them; AO,
/// which does not read the light, stays converged throughout (skipped as converged).
#[test]
fn a_light_moving_every_other_frame_renders_the_light_view_on_exactly_those_frames() {
    let ctx = common::context();
    let mut scene = ssgi::scene::cornell_box();
    let start = scene.light.position;
    let target = start + scene.light.direction;
    let at = |k: u32| (start + Vec3::new(0.02 * k as f32, 0.0, 0.0)).to_array();
    let key = |time: f32, k: u32| Keyframe {
        time,
        position: at(k),
        target: (target + Vec3::new(0.02 * k as f32, 0.0, 0.0)).to_array(),
    };
    // Cuts (equal times) at the odd frames' times; the light holds in between.
    let mut keys = vec![key(0.0, 0)];
    for k in 1..=8u32 {
        let t = frame_time(2 * k - 1, 60.0);
        keys.extend([key(t, k - 1), key(t, k)]);
    }
    scene.light_path = Some(LightPath::new(keys));
    let mut r = Renderer::new(&ctx, scene, config(true, true)).expect("renderer");
    let camera = r.scene.camera;
    let mut timings = until_skipping(&mut r, &camera, 4);
    let converged = timings.len();
    for i in 0..16 {
        r.set_time(frame_time(i, 60.0));
        timings.extend(run(&mut r, &camera, 1));
    }
    let recorded = |t: &FrameTiming, pass: &str| t.passes.iter().any(|(n, _)| *n == pass);
    let light_views: Vec<u64> = timings
        .iter()
        .filter(|t| recorded(t, "light_view"))
        .map(|t| t.frame)
        .collect();
    let first = converged as u64;
    let moved: Vec<u64> = (0..8).map(|k| first + 2 * k + 1).collect();
    assert_eq!(light_views[0], 0, "the first frame renders the light view");
    assert_eq!(
        light_views[1..],
        moved,
        "light view recorded on {light_views:?}"
    );
    for t in &timings[converged..] {
        if moved.contains(&t.frame) {
            for pass in ["shadow", "indirect_gather"] {
                assert!(recorded(t, pass), "frame {}: {pass} did not run", t.frame);
            }
        }
        let ao = t.skipped.iter().find(|s| s.pass == "ssao");
        assert!(
            ao.is_some_and(|s| s.reason.name() == "converged"),
            "frame {}: AO ran ({:?})",
            t.frame,
            t.counters
        );
    }
    common::assert_clean(&ctx);
}

/// An object that moves once (the dynamic-scenes input of the dependency table): the frame
/// after converging records the light view (the ball is in the light's sight), the G-buffer,
/// the reprojection and every effect, and its image equals that of a renderer that never
/// skips, bit for bit; held still again, frames are skipped once more.
#[test]
fn a_moved_object_renders_what_depends_on_it() {
    let ctx = common::context();
    let ball = || {
        let mut scene = ssgi::scene::cornell_box();
        let mut b = ssgi::scene::MeshBuilder::new();
        b.append(&ssgi::scene::sphere(), 0.2, Vec3::ZERO);
        let key = |time: f32, x: f32| ssgi::scene::ObjectKey {
            time,
            position: [x, 0.2, 0.4],
            rotation_deg: [0.0; 3],
        };
        scene.objects.push(ssgi::scene::DynamicObject {
            name: "ball".into(),
            mesh: b.build(),
            keys: vec![key(0.0, -0.6), key(1.0, 0.4)],
        });
        scene
    };
    let mut p = Pair {
        skipping: Renderer::new(&ctx, ball(), config(true, true)).expect("renderer"),
        always: Renderer::new(&ctx, ball(), config(true, false)).expect("renderer"),
    };
    let camera = p.skipping.scene.camera;
    let first = p.converge(&camera);
    p.skipping.set_time(0.05);
    p.always.set_time(0.05);
    let frame = p.frame(&camera);
    assert_ran(
        &frame,
        &[
            "light_view",
            "gbuffer",
            "reproject",
            "shadow",
            "direct",
            "ssao",
            "indirect_gather",
            "composite",
        ],
    );
    assert_eq!(
        frame.counters.iter().find(|(n, _)| *n == "moved_objects"),
        Some(&("moved_objects", 1))
    );
    assert_eq!(
        scheduled(&frame),
        predicted(&p.skipping, &first[..3], Change::Object),
        "object move"
    );
    p.assert_same("after the object moved");
    let mut fresh = Renderer::new(&ctx, ball(), config(true, true)).expect("renderer");
    fresh.set_time(0.05);
    p.assert_like_fresh(fresh, &camera, "after the object moved");
    common::assert_clean(&ctx);
}
