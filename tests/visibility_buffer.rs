//! `--gbuffer visibility`: the raster pass writes each pixel's triangle and a compute pass
//! rebuilds the G-buffer from the triangles' vertices. Its targets against the raster
//! G-buffer's (which tests/gbuffer.rs checks against a CPU ray cast), pixel by pixel: on a
//! flat-coloured scene (albedo from the draw table), a textured one (Sponza: albedo from the
//! raster pass) and a moving object (motion from this frame's and last frame's poses).

mod common;

use glam::Vec3;
use ssgi::config::GBufferMode;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::resources::targets::Target;
use ssgi::scene::{
    asset_dir_from_env, load_scene, sphere, Camera, DynamicObject, MeshBuilder, ObjectKey, Scene,
};
use ssgi::vk::ImageData;

const SIZE: u32 = 64;

/// The G-buffer targets after `frames` frames (`time` of each), in the order of `TARGETS`.
const TARGETS: [Target; 4] = [
    Target::GPosition,
    Target::GNormal,
    Target::GAlbedo,
    Target::GMotion,
];

fn gbuffer(scene: Scene, mode: GBufferMode, times: &[f32]) -> (Vec<ImageData>, Vec<String>) {
    let ctx = common::context();
    let config = RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 128,
        gbuffer: mode,
        ..Default::default()
    };
    let mut r = Renderer::new(&ctx, scene, config).expect("renderer");
    let camera: Camera = r.scene.camera;
    let mut passes = Vec::new();
    for &t in times {
        r.set_time(t);
        r.render_frame(&camera).expect("frame");
    }
    for t in r.finish().expect("finish") {
        passes = t.passes.iter().map(|p| p.0.to_string()).collect();
    }
    let images = TARGETS.iter().map(|&t| common::read(&mut r, t)).collect();
    drop(r);
    common::assert_clean(&ctx);
    (images, passes)
}

/// The largest differences between the raster and the visibility G-buffer.
#[derive(Debug, Default)]
struct Differences {
    /// Pixels where one has geometry and the other background.
    coverage: u32,
    /// Position, in pixel footprints (distance to the eye x the pixel's angle).
    position: f32,
    /// 1 - cos of the angle between the normals.
    normal: f32,
    /// Pixels whose shading normal lies in its triangle's plane (CPU ray cast): no side is
    /// the visible one, so the two may differ.
    side_undecided: u32,
    albedo: f32,
    /// Motion, as a fraction of the largest motion in the image (0 when nothing moves).
    motion: f32,
    moving_pixels: u32,
}

fn differences(raster: &[ImageData], vis: &[ImageData], scene: &Scene) -> Differences {
    let camera = &scene.camera;
    let pixel_angle = 2.0 * (0.5 * camera.vfov_deg).to_radians().tan() / SIZE as f32;
    let v3 = |t: [f32; 4]| Vec3::new(t[0], t[1], t[2]);
    let mut d = Differences::default();
    let mut max_motion = 0.0f32;
    for y in 0..SIZE {
        for x in 0..SIZE {
            max_motion = max_motion.max(v3(raster[3].texel(x, y)).length());
        }
    }
    for y in 0..SIZE {
        for x in 0..SIZE {
            let [rp, vp] = [raster[0].texel(x, y), vis[0].texel(x, y)];
            if rp[3] != vp[3] {
                d.coverage += 1;
                continue;
            }
            if rp[3] == 0.0 {
                continue;
            }
            let footprint = (v3(rp) - camera.position).length() * pixel_angle;
            d.position = d.position.max((v3(rp) - v3(vp)).length() / footprint);
            // fp16 normals are unit length to 1e-3: compare directions.
            let [rn, vn] = [v3(raster[1].texel(x, y)), v3(vis[1].texel(x, y))];
            let cos = rn.normalize_or_zero().dot(vn.normalize_or_zero());
            // The visible side is decided by the sign of the shading normal against the
            // triangle's plane; where a mesh's shading normal lies in that plane (Sponza has
            // such vertices) either side is right, and the raster pass's screen derivatives
            // and the resolve's edge vectors may round to different signs. Such pixels are
            // told apart by the CPU ray cast's geometric normal and counted, not compared.
            if 1.0 - cos > 1e-3 {
                let (nx, ny) = ssgi::scene::pixel_to_ndc(x as f32, y as f32, SIZE, SIZE);
                let (o, dir) = camera.ray(nx, ny, 1.0);
                let in_plane = scene.mesh.raycast(o, dir, f32::MAX).is_some_and(|h| {
                    h.normal.dot(rn.normalize_or_zero()).abs() < 1e-3
                        && h.normal.dot(vn.normalize_or_zero()).abs() < 1e-3
                });
                if in_plane {
                    d.side_undecided += 1;
                    continue;
                }
            }
            d.normal = d.normal.max(1.0 - cos);
            let [ra, va] = [raster[2].texel(x, y), vis[2].texel(x, y)];
            d.albedo = d.albedo.max((v3(ra) - v3(va)).abs().max_element());
            let [rm, vm] = [v3(raster[3].texel(x, y)), v3(vis[3].texel(x, y))];
            if rm != Vec3::ZERO {
                d.moving_pixels += 1;
            }
            if max_motion > 0.0 {
                d.motion = d.motion.max((rm - vm).length() / max_motion);
            } else {
                assert_eq!(vm, Vec3::ZERO, "({x},{y}): motion where nothing moves");
            }
        }
    }
    d
}

/// Both G-buffers of `scene` at `times`; the visibility run also records its resolve.
fn compare(scene: Scene, times: &[f32]) -> Differences {
    let (raster, raster_passes) = gbuffer(scene.clone(), GBufferMode::Raster, times);
    let (vis, vis_passes) = gbuffer(scene.clone(), GBufferMode::Visibility, times);
    assert!(!raster_passes.iter().any(|p| p == "gbuffer_resolve"));
    assert!(
        vis_passes.iter().any(|p| p == "gbuffer_resolve"),
        "{vis_passes:?}"
    );
    let d = differences(&raster, &vis, &scene);
    eprintln!("raster against visibility G-buffer: {d:?}");
    d
}

/// The limits, about 4x lavapipe's measurements (Cornell box and the ball / Sponza): the
/// rasterizer snaps vertices to 1/256 pixel and interpolates in its own order while the
/// resolve solves for the exact pixel centre, so positions agree to 8e-5 / 2.5e-4 of a pixel's
/// footprint; normals (fp16) to 1.8e-7 in 1 - cos; albedo is the same fp16 value (the draw's
/// colour, or in a textured scene the raster pass's own).
fn assert_close(d: &Differences) {
    assert_eq!(d.coverage, 0, "coverage differs: {d:?}");
    assert!(d.position <= 1e-3, "positions differ: {d:?}");
    assert!(d.normal <= 1e-6, "normals differ: {d:?}");
    assert_eq!(d.albedo, 0.0, "albedo differs: {d:?}");
}

#[test]
fn flat_scene_matches_the_raster_gbuffer() {
    let d = compare(ssgi::scene::cornell_box(), &[0.0, 0.0]);
    assert_close(&d);
    assert_eq!(d.side_undecided, 0, "{d:?}");
    assert_eq!(d.moving_pixels, 0);
}

#[test]
fn textured_scene_matches_the_raster_gbuffer() {
    let dir = asset_dir_from_env().unwrap_or_else(|| {
        panic!("SSGI_ASSETS is not set: this test needs the shared scenes (tools/test sets it)")
    });
    let scene = load_scene("sponza", Some(&dir)).unwrap_or_else(|e| panic!("sponza: {e}"));
    let d = compare(scene, &[0.0, 0.0]);
    assert_close(&d);
    // Measured: 3 of 4096 pixels.
    assert!(d.side_undecided <= 8, "{d:?}");
}

/// A ball rolling across the Cornell box: the resolve's motion comes from the draw table's
/// two poses and must match the raster pass's interpolated motion.
#[test]
fn moving_object_motion_matches_the_raster_gbuffer() {
    let mut scene = ssgi::scene::cornell_box();
    let mut b = MeshBuilder::new();
    b.append(&sphere(), 0.2, Vec3::ZERO);
    let key = |time: f32, position: [f32; 3]| ObjectKey {
        time,
        position,
        rotation_deg: [0.0, 40.0 * time, 0.0],
    };
    scene.objects.push(DynamicObject {
        name: "ball".into(),
        mesh: b.build(),
        keys: vec![key(0.0, [-0.6, 0.21, 0.4]), key(1.0, [0.4, 0.21, 0.4])],
    });
    let d = compare(scene, &[0.0, 0.15, 0.3]);
    assert_close(&d);
    assert_eq!(d.side_undecided, 0, "{d:?}");
    assert!(d.moving_pixels > 50, "the ball should move: {d:?}");
    // Measured 4.5e-5 of the largest motion.
    assert!(d.motion <= 2e-4, "motion differs: {d:?}");
}
