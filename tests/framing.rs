//! Default framing, checked on the G-buffer the GPU rasterizes (64x64): every shared model
//! loaded by name is seen from a sensible place (buildings from inside with at most 5% of the
//! pixels on background or on the back of a surface, single models filling at least 20% of the frame above their ground),
//! and the built-in rooms' orbit never looks out of the room.

mod common;

use ssgi::config::pcf::Pcf;
use ssgi::config::Effects;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::resources::targets::Target;
use ssgi::scene::{asset_dir_from_env, load_scene, Camera, CameraPath, Orbit, Scene};
use ssgi::vk::Context;
use std::sync::Arc;

const SIZE: u32 = 64;
/// Most background pixels a view inside a closed room may have.
const MAX_BACKGROUND: f64 = 0.05;
/// Least share of the frame a single model must cover.
const MIN_MODEL: f64 = 0.20;

fn renderer(ctx: &Arc<Context>, scene: Scene) -> Renderer {
    let config = RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 64,
        pcf: Pcf::HARD,
        effects: Effects {
            direct: true,
            ..Effects::NONE
        },
        ..Default::default()
    };
    Renderer::new(ctx, scene, config).expect("renderer")
}

/// World positions of the covered pixels of `camera`'s view (G-buffer position w = 1) and the
/// number of pixels. With `front_only`, a pixel whose G-buffer normal faces away from the eye
/// (the outside of a room's wall, which the rasterizer draws but nobody should see) counts
/// as not covered.
fn covered(r: &mut Renderer, camera: &Camera, front_only: bool) -> (Vec<glam::Vec3>, usize) {
    r.render_frame(camera).expect("frame");
    r.finish().expect("finish");
    let g = common::read(r, Target::GPosition);
    let n = common::read(r, Target::GNormal);
    let mut out = Vec::new();
    for y in 0..g.height {
        for x in 0..g.width {
            let t = g.texel(x, y);
            let p = glam::Vec3::new(t[0], t[1], t[2]);
            let normal = glam::Vec4::from(n.texel(x, y)).truncate();
            let faces_eye = normal.dot(camera.position - p) > 0.0;
            if t[3] > 0.5 && (faces_eye || !front_only) {
                out.push(p);
            }
        }
    }
    (out, (g.width * g.height) as usize)
}

fn assets_scene(name: &str) -> Scene {
    let dir = asset_dir_from_env().unwrap_or_else(|| {
        panic!("SSGI_ASSETS is not set: this test needs the shared scenes (tools/test sets it)")
    });
    load_scene(name, Some(&dir)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn buildings_are_seen_from_inside() {
    let ctx = common::context();
    for name in ["sponza", "sibenik", "conference"] {
        let scene = assets_scene(name);
        assert!(
            matches!(scene.orbit(), Orbit::Inside { .. }),
            "{name} is framed as an interior"
        );
        let camera = scene.camera;
        let mut r = renderer(&ctx, scene);
        let (hits, pixels) = covered(&mut r, &camera, true);
        let background = 1.0 - hits.len() as f64 / pixels as f64;
        assert!(
            background <= MAX_BACKGROUND,
            "{name}: {:.1}% background or back faces",
            100.0 * background
        );
        common::assert_clean(&ctx);
    }
}

#[test]
fn single_models_fill_the_frame_above_their_ground() {
    let ctx = common::context();
    for name in ["bunny", "dragon", "buddha", "venus"] {
        let scene = assets_scene(name);
        assert!(matches!(scene.orbit(), Orbit::Around { .. }), "{name}");
        let b = scene.mesh.bounds;
        let ground = b.min.y + 1e-3 * b.extent().y;
        let camera = scene.camera;
        let mut r = renderer(&ctx, scene);
        let (hits, pixels) = covered(&mut r, &camera, false);
        let model = hits.iter().filter(|p| p.y > ground).count() as f64 / pixels as f64;
        let on_ground = hits.len() as f64 / pixels as f64 - model;
        assert!(
            model >= MIN_MODEL,
            "{name}: the model covers {:.1}%",
            100.0 * model
        );
        assert!(on_ground > 0.0, "{name}: the ground shows");
        common::assert_clean(&ctx);
    }
}

/// A full cycle of the rooms' sweep (8 s at 12 s per turn), every half second.
#[test]
fn room_orbits_never_look_out() {
    let ctx = common::context();
    let orbit = CameraPath::parse("orbit").unwrap();
    for spec in ["cornell-box", "box:bunny"] {
        let scene = if spec == "cornell-box" {
            load_scene(spec, None).unwrap()
        } else {
            assets_scene(spec)
        };
        let (base, rule) = (scene.camera, scene.orbit());
        let mut r = renderer(&ctx, scene);
        for k in 0..=16 {
            let camera = orbit.camera_at(&base, &rule, 0.5 * k as f32);
            let (hits, pixels) = covered(&mut r, &camera, true);
            let background = 1.0 - hits.len() as f64 / pixels as f64;
            assert!(
                background <= MAX_BACKGROUND,
                "{spec} at {} s: {:.1}% background or back faces",
                0.5 * k as f32,
                100.0 * background
            );
        }
        common::assert_clean(&ctx);
    }
}

/// Share of background pixels at each sampled time of `path` in `scene`.
fn path_background(
    ctx: &Arc<Context>,
    scene: Scene,
    path: &CameraPath,
    step: f32,
) -> Vec<(f32, f64)> {
    let (base, rule) = (scene.camera, scene.orbit());
    let duration = path.duration();
    let mut r = renderer(ctx, scene);
    let mut out = Vec::new();
    let mut t = 0.0;
    while t <= duration + 1e-3 {
        let camera = path.camera_at(&base, &rule, t);
        let (hits, pixels) = covered(&mut r, &camera, true);
        out.push((t, 1.0 - hits.len() as f64 / pixels as f64));
        t += step;
    }
    out
}

/// The tables' camera paths never look out of the geometry they show: the box path in the
/// Cornell box and the box room, the walkthroughs in their buildings (as the tables load
/// them, with their lens and light).
#[test]
fn table_paths_stay_inside_their_scenes() {
    let ctx = common::context();
    let dir = asset_dir_from_env().expect("SSGI_ASSETS is not set (tools/test sets it)");
    let boxed = ssgi::bench::tables::paths::BOX.parse().unwrap();
    let mut failures = Vec::new();
    for spec in ["cornell-box", "box:bunny"] {
        let scene = load_scene(spec, Some(&dir)).unwrap();
        for (t, bg) in path_background(&ctx, scene, &boxed, 0.25) {
            if bg > MAX_BACKGROUND {
                failures.push(format!("{spec} at {t} s: {:.1}%", 100.0 * bg));
            }
        }
    }
    for w in &ssgi::bench::tables::walkthroughs::WALKTHROUGHS {
        let path = w.path.parse().unwrap();
        let scene = w.load(Some(&dir), &path).unwrap();
        for (t, bg) in path_background(&ctx, scene, &path, 1.0) {
            if bg > MAX_BACKGROUND {
                failures.push(format!("{} at {t} s: {:.1}%", w.name, 100.0 * bg));
            }
        }
    }
    common::assert_clean(&ctx);
    assert!(
        failures.is_empty(),
        "background above 5%:\n{}",
        failures.join("\n")
    );
}

/// The keyframe example of docs/scenes.md, on the Cornell box it is written for, sees only the
/// inside of the box.
#[test]
fn documented_keyframe_example_stays_inside_the_box() {
    let doc =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scenes.md")).unwrap();
    let section = doc
        .split("## Keyframe files")
        .nth(1)
        .expect("docs/scenes.md has a Keyframe files section");
    let json = section
        .split("```json")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("a json block in the Keyframe files section");
    let file = std::env::temp_dir().join(format!("ssgi-doc-keys-{}.json", std::process::id()));
    std::fs::write(&file, json).unwrap();
    let path = CameraPath::parse(file.to_str().unwrap()).unwrap();
    let ctx = common::context();
    let scene = load_scene("cornell-box", None).unwrap();
    for (t, bg) in path_background(&ctx, scene, &path, 0.125) {
        // An example shows nothing outside the box at all (the old one, [1, 1, 3.0] at 1 s,
        // had 4.7% of the outside of the green wall).
        assert!(
            bg == 0.0,
            "at {t} s: {:.1}% background or back faces",
            100.0 * bg
        );
    }
    common::assert_clean(&ctx);
}

/// Least mean luminance (Rec. 709 weights over the sRGB-encoded 8-bit output, in 0..1) of a
/// shared model rendered by name with nothing else set: no default render is black.
const MIN_MEAN_LUMINANCE: f64 = 0.15;

/// Every shared model (and the built-in Cornell box), rendered with the defaults (every
/// effect, its automatic camera and light), is lit.
#[test]
fn default_renders_are_lit() {
    let ctx = common::context();
    let mut dark = Vec::new();
    for name in [
        "cornell-box",
        "bunny",
        "dragon",
        "buddha",
        "venus",
        "sponza",
        "sibenik",
        "conference",
    ] {
        let scene = if name == "cornell-box" {
            load_scene(name, None).unwrap()
        } else {
            assets_scene(name)
        };
        let camera = scene.camera;
        let config = RenderConfig {
            width: SIZE,
            height: SIZE,
            rsm_size: 128,
            ..Default::default()
        };
        let mut r = Renderer::new(&ctx, scene, config).expect("renderer");
        for _ in 0..2 {
            r.render_frame(&camera).expect("frame");
        }
        r.finish().expect("finish");
        let rgba = common::read(&mut r, Target::Output).rgba8().expect("RGBA8");
        let luminance: f64 = rgba
            .chunks_exact(4)
            .map(|p| (0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64) / 255.0)
            .sum::<f64>()
            / (SIZE * SIZE) as f64;
        if luminance < MIN_MEAN_LUMINANCE {
            dark.push(format!("{name}: mean luminance {luminance:.3}"));
        }
    }
    common::assert_clean(&ctx);
    assert!(
        dark.is_empty(),
        "renders below {MIN_MEAN_LUMINANCE}:\n{}",
        dark.join("\n")
    );
}
