//! The CPU ground truth against the renderer: its primary hits are the G-buffer's (same
//! pixels covered, same positions within a pixel footprint, same normals), and
//! `ssgi reference` writes what it promises.

mod common;

use glam::Vec3;
use ssgi::config::pcf::Pcf;
use ssgi::reference::{Accel, AoDefinition, Reference, Settings};
use ssgi::resources::targets::Target;
use ssgi::scene::{cornell_box, load_scene, Scene};

const SIZE: u32 = 64;

fn check_primary_hits(scene: Scene) {
    let ctx = common::context();
    let mut r = common::render(&ctx, scene, SIZE, Pcf::HARD, 1);
    let pos = common::read(&mut r, Target::GPosition);
    let nrm = common::read(&mut r, Target::GNormal);
    let scene = r.scene.clone();
    let accel = Accel::new(&scene.mesh);
    let settings = Settings {
        ao: AoDefinition {
            radius: 1.0,
            attenuation: [0.0, 1.0],
        },
        light_radius: 0.0,
        seed: 1,
    };
    let reference = Reference::new(&accel, &scene, scene.camera, SIZE, SIZE, settings);
    let pixel_angle = 2.0 * (0.5 * scene.camera.vfov_deg).to_radians().tan() / SIZE as f32;
    let (mut coverage_differs, mut far, mut normal_differs, mut both) = (0, 0, 0, 0);
    for (i, p) in reference.primary.iter().enumerate() {
        let (x, y) = ((i as u32) % SIZE, (i as u32) / SIZE);
        let g = pos.texel(x, y);
        match p {
            None if g[3] == 0.0 => {}
            Some(p) if g[3] != 0.0 => {
                both += 1;
                let gp = Vec3::new(g[0], g[1], g[2]);
                let to_eye = scene.camera.position - p.surface.position;
                let cos = p.surface.geometric.dot(to_eye.normalize()).abs().max(0.05);
                let footprint = to_eye.length() * pixel_angle / cos;
                if (gp - p.surface.position).length() > footprint {
                    far += 1;
                }
                let n = nrm.texel(x, y);
                if Vec3::new(n[0], n[1], n[2]).dot(p.normal) < 0.99 {
                    normal_differs += 1;
                }
            }
            _ => coverage_differs += 1,
        }
    }
    let pixels = (SIZE * SIZE) as usize;
    // Silhouettes may round either way; 1 % of the pixels allows for them, not for a shift.
    assert!(
        coverage_differs * 100 <= pixels,
        "{coverage_differs} pixels covered by only one"
    );
    assert!(
        far * 100 <= both,
        "{far} of {both} positions differ by more than a footprint"
    );
    assert!(
        normal_differs * 100 <= both,
        "{normal_differs} of {both} normals differ"
    );
    assert!(both > pixels / 4);
    drop(r);
    common::assert_clean(&ctx);
}

#[test]
fn cornell_primary_hits_are_the_gbuffer() {
    check_primary_hits(cornell_box());
}

#[test]
fn bunny_primary_hits_are_the_gbuffer() {
    let dir = ssgi::scene::asset_dir_from_env().unwrap_or_else(|| {
        panic!("SSGI_ASSETS is not set: this test needs the shared scenes (../shared/scenes); tools/test sets it")
    });
    let scene = load_scene("box:bunny", Some(&dir)).expect("box:bunny");
    check_primary_hits(scene);
}
