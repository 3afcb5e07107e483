//! G-buffer world position and normal against a CPU ray cast through the same pixels.

mod common;

use glam::Vec3;
use ssgi::config::pcf::Pcf;
use ssgi::resources::targets::Target;
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

/// The visible side of a two-sided surface is decided per triangle, not per pixel: a quad
/// facing the eye whose (smooth) vertex normals lean so far sideways that they turn away from
/// the eye over part of it keeps them there. Flipping each pixel's normal towards the eye, as
/// before, made a surface point's normal (and its AO and indirect light) depend on the view
/// near every silhouette of a smooth model. The CPU reference agrees (`Surface::facing`).
#[test]
fn smooth_normals_turned_from_the_eye_are_not_flipped() {
    use ssgi::reference::surface::Surface;
    use ssgi::scene::{Camera, Material, MeshBuilder};
    let lean = Vec3::new(-1.0, 0.0, 0.1).normalize();
    let mut b = MeshBuilder::new();
    let m = b.add_material(Material::colour("quad", [0.7, 0.7, 0.7]));
    let h = 2.0;
    let corners = [
        Vec3::new(-h, -h, 0.0),
        Vec3::new(h, -h, 0.0),
        Vec3::new(h, h, 0.0),
        Vec3::new(-h, h, 0.0),
    ];
    b.add_flat_polygon(m, &corners, lean);
    let mut scene = cornell_box();
    scene.name = "leaning-normals".into();
    scene.mesh = b.build();
    scene.camera = Camera::new(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, 60.0, 0.1, 100.0);
    let ctx = common::context();
    let mut r = common::render(&ctx, scene, 32, Pcf::HARD, 1);
    let pos = common::read(&mut r, Target::GPosition);
    let nrm = common::read(&mut r, Target::GNormal);
    let (mut geometry, mut turned_away) = (0, 0);
    for y in 0..32 {
        for x in 0..32 {
            let p = pos.texel(x, y);
            if p[3] == 0.0 {
                continue;
            }
            geometry += 1;
            let position = Vec3::new(p[0], p[1], p[2]);
            let n = nrm.texel(x, y);
            let n = Vec3::new(n[0], n[1], n[2]);
            turned_away += (lean.dot(Vec3::new(0.0, 0.0, 4.0) - position) < 0.0) as u32;
            assert!(
                n.dot(lean) > 0.999,
                "pixel ({x}, {y}) at {position}: normal {n}"
            );
        }
    }
    // The case matters: part of the quad sees its normal turned away from the eye.
    assert!(
        geometry > 500 && turned_away > 100,
        "{geometry} {turned_away}"
    );
    let s = Surface {
        position: Vec3::new(-1.5, 0.0, 0.0),
        geometric: Vec3::NEG_Z, // either winding
        shading: lean,
        albedo: Vec3::ONE,
        triangle: 0,
    };
    assert!(s.facing(Vec3::new(0.0, 0.0, 4.0)).dot(lean) > 0.999);
    assert!(s.facing(Vec3::new(0.0, 0.0, -4.0)).dot(lean) < -0.999);
    drop(r);
    common::assert_clean(&ctx);
}
