//! G-buffer world position and normal against a CPU ray cast through the same pixels.

mod common;

use glam::Vec3;
use ssgi::renderer::pcf::Pcf;
use ssgi::renderer::targets::Target;
use ssgi::scene::{cornell_box, pixel_to_ndc, pyramids, Scene};

const SIZE: u32 = 96;

fn check_scene(scene: Scene) {
    let ctx = common::context();
    let mut r = common::render(&ctx, scene, SIZE, Pcf::HARD, 1);
    let pos = common::read(&mut r, Target::GPosition);
    let nrm = common::read(&mut r, Target::GNormal);
    let scene = &r.scene;
    let cam = scene.camera;
    // World size of one pixel at distance 1.
    let pixel_angle = 2.0 * (0.5 * cam.vfov_deg).to_radians().tan() / SIZE as f32;
    let mut checked = 0;
    let mut background = 0;
    for y in (1..SIZE - 1).step_by(4) {
        for x in (1..SIZE - 1).step_by(4) {
            let hit = |px: u32, py: u32| {
                let (nx, ny) = pixel_to_ndc(px as f32 + 0.5, py as f32 + 0.5, SIZE, SIZE);
                let (o, d) = cam.ray(nx, ny, 1.0);
                scene.mesh.raycast(o, d, f32::MAX).map(|h| (h, d))
            };
            let gp = pos.texel(x, y);
            let Some((h, dir)) = hit(x, y) else {
                assert_eq!(gp[3], 0.0, "({x},{y}): CPU sees background, GPU geometry");
                background += 1;
                continue;
            };
            // Only pixels whose 4 neighbours hit the same plane: no silhouettes or creases.
            let same_plane =
                [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
                    .iter()
                    .all(|&(a, b)| {
                        hit(a, b).is_some_and(|(n, _)| {
                            n.normal.dot(h.normal) > 0.9999
                                && (n.position - h.position).dot(h.normal).abs() < 1e-4
                        })
                    });
            if !same_plane {
                continue;
            }
            assert_eq!(gp[3], 1.0, "({x},{y}): GPU misses geometry the CPU hits");
            let gpu_p = Vec3::new(gp[0], gp[1], gp[2]);
            // Footprint of a pixel on the surface: distance x pixel angle / cos(incidence).
            let cos_i = h.normal.dot(-dir).abs().max(0.05);
            let footprint = h.t * pixel_angle / cos_i;
            let err = (gpu_p - h.position).length();
            assert!(
                err <= footprint,
                "({x},{y}): GPU position {gpu_p} vs CPU {} differs by {err} > footprint {footprint}",
                h.position
            );
            let gn = nrm.texel(x, y);
            let gpu_n = Vec3::new(gn[0], gn[1], gn[2]);
            // fp16 storage: 1e-3 relative per component.
            assert!(
                gpu_n.dot(h.normal) > 0.998,
                "({x},{y}): GPU normal {gpu_n} vs CPU {}",
                h.normal
            );
            checked += 1;
        }
    }
    assert!(checked >= 100, "only {checked} pixels checked");
    drop(r);
    common::assert_clean(&ctx);
    let _ = background;
}

#[test]
fn cornell_gbuffer_matches_ray_cast() {
    check_scene(cornell_box());
}

#[test]
fn pyramids_gbuffer_matches_ray_cast() {
    check_scene(pyramids());
}
