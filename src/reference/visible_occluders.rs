//! AO with only the occluders the camera sees: the ground truth's AO integral (estimators.rs)
//! where a ray's hit counts (with eq 7's weight at its distance) only if the camera sees that
//! very point, inside the image and unoccluded on the way from the eye. Its error against the
//! traced AO is the occlusion an estimator reading only the G-buffer never observes: occluders
//! hidden behind the visible surfaces or off the image. It is not a bound: estimators that take
//! each visible surface as infinitely thick (all of ours) guess some hidden occluders, rightly
//! where something does stand behind the surface, and can have less error.

use super::estimators::{ao_sample_hit, AoDefinition, Primary};
use super::trace::Reference;
use crate::scene::accel::Accel;
use crate::scene::Camera;
use glam::{Vec2, Vec3, Vec4Swizzles};
use rayon::prelude::*;

/// Directions per pixel: a Hammersley set, the same at every pixel (a bias under 1/256 of
/// visibility, below the traced AO's standard error in the tables).
pub const DIRECTIONS: u32 = 256;

/// Whether the camera sees a world point: inside the image and in front of the near plane,
/// with nothing between it and the eye.
struct Eye<'a> {
    accel: &'a Accel,
    view_proj: glam::Mat4,
    origin: Vec3,
    forward: Vec3,
    near: f32,
    far: f32,
}

impl<'a> Eye<'a> {
    fn new(accel: &'a Accel, camera: &Camera, width: u32, height: u32) -> Self {
        let aspect = width as f32 / height.max(1) as f32;
        Self {
            accel,
            view_proj: camera.view_proj(aspect),
            origin: camera.position,
            forward: camera.frame().0,
            near: camera.near,
            far: camera.far,
        }
    }

    /// `x` (on triangle `triangle`) is in the image, within the depth range, and unoccluded.
    fn sees(&self, x: Vec3, triangle: usize) -> bool {
        let depth = (x - self.origin).dot(self.forward);
        if !(depth > self.near && depth < self.far) {
            return false;
        }
        let clip = self.view_proj * x.extend(1.0);
        let ndc = clip.xy() / clip.w;
        let inside = ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0;
        inside && !self.accel.occluded(self.origin, x, Some(triangle))
    }
}

/// Point k of an n-point Hammersley set in [0, 1)^2.
fn hammersley(k: u32, n: u32) -> Vec2 {
    Vec2::new(
        (k as f32 + 0.5) / n as f32,
        k.reverse_bits() as f32 * (1.0 / 4_294_967_296.0),
    )
}

/// Ambient visibility (1 - occlusion, as the reference's AO buffer) of every pixel of `r`'s
/// primary hits with only the occluders the camera sees; 1 where a pixel has no geometry (the
/// reference's masks leave those out).
pub fn visible_occluder_ao(
    accel: &Accel,
    r: &Reference,
    def: &AoDefinition,
    directions: u32,
) -> Vec<f32> {
    let eye = Eye::new(accel, &r.camera, r.width, r.height);
    let directions = directions.max(1);
    r.primary
        .par_iter()
        .map(|p| match p {
            Some(p) => visibility(&eye, p, def, directions),
            None => 1.0,
        })
        .collect()
}

fn visibility(eye: &Eye<'_>, p: &Primary, def: &AoDefinition, directions: u32) -> f32 {
    let mut occlusion = 0.0f64;
    for k in 0..directions {
        if let Some((hit, weight)) = ao_sample_hit(eye.accel, p, def, hammersley(k, directions)) {
            if eye.sees(hit.0, hit.1) {
                occlusion += weight as f64;
            }
        }
    }
    (1.0 - occlusion / directions as f64) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::trace::Settings;

    /// A reference of `scene` at `camera` with only its primary hits.
    fn primaries(scene: &crate::scene::Scene, camera: Camera, size: u32) -> (Accel, Reference) {
        let accel = Accel::new(&scene.mesh);
        let settings = Settings::for_render(&crate::config::RenderConfig::default(), scene);
        let r = Reference::new(&accel, scene, camera, size, size, settings);
        (accel, r)
    }

    /// A floor (y = 0) meeting a wall (x = 0, facing -x), 40 m each way, the camera 3 m from
    /// the wall looking at the corner: every occluder within the radius of floor points near
    /// the image's middle is in view, so the bound is the closed form of binary visibility
    /// within R on a floor at distance d from the wall, 1 - (acos k - k sqrt(1 - k^2)) / pi
    /// with k = d / R. With the wall off the image, nothing occludes.
    #[test]
    fn floor_beside_a_wall_matches_the_closed_form() {
        use crate::scene::{Material, MeshBuilder};
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::colour("grey", [0.6, 0.6, 0.6]));
        let h = 40.0;
        let floor = [(-h, -h), (-h, h), (0.0, h), (0.0, -h)].map(|(x, z)| Vec3::new(x, 0.0, z));
        b.add_flat_polygon(m, &floor, Vec3::Y);
        let wall = [(-h, 0.0), (h, 0.0), (h, 1.0), (-h, 1.0)].map(|(z, y)| Vec3::new(0.0, y, z));
        b.add_flat_polygon(m, &wall, -Vec3::X);
        let mut scene = crate::scene::cornell_box();
        scene.mesh = b.build();
        let camera = Camera::new(Vec3::new(-3.0, 1.5, 0.0), Vec3::ZERO, 60.0, 0.1, 200.0);
        let (accel, r) = primaries(&scene, camera, 96);
        let radius = 0.5;
        let def = AoDefinition {
            radius,
            attenuation: [0.0, 0.0],
        };
        let ao = visible_occluder_ao(&accel, &r, &def, DIRECTIONS);
        assert!(ao.iter().all(|v| (0.0..=1.0).contains(v)));
        let mut checked = 0;
        for (v, p) in ao.iter().zip(&r.primary) {
            let Some(p) = p else { continue };
            let d = -p.surface.position.x;
            // Floor points near the wall, away from the image's sides.
            let side = p.surface.position.z.abs();
            if p.surface.position.y.abs() > 1e-3 || !(0.05..0.45).contains(&d) || side > 0.6 {
                continue;
            }
            let k = d / radius;
            let expected = 1.0 - (k.acos() - k * (1.0 - k * k).sqrt()) / std::f32::consts::PI;
            assert!((v - expected).abs() < 0.02, "d {d}: {v} vs {expected}");
            checked += 1;
        }
        assert!(checked > 50, "{checked} floor pixels near the wall");
        // Looking down on the floor 0.46-1.54 m from the wall, which is off the image: the
        // floor's occluder within 1 m is not in view, so the bound is 1 (the traced AO is not).
        let down = Camera::new(
            Vec3::new(-1.0, 2.0, 0.3),
            Vec3::new(-1.0, 0.0, 0.0),
            30.0,
            0.1,
            200.0,
        );
        let (accel, r) = primaries(&scene, down, 64);
        let wide = AoDefinition { radius: 1.0, ..def };
        let ao = visible_occluder_ao(&accel, &r, &wide, 64);
        let mut off_image = 0;
        for (v, p) in ao.iter().zip(&r.primary) {
            let Some(p) = p else { continue };
            assert!(p.surface.position.x < -0.4, "the wall is in view: {p:?}");
            if p.surface.position.x > -0.9 {
                assert_eq!(*v, 1.0, "{:?}", p.surface.position);
                off_image += 1;
            }
        }
        assert!(
            off_image > 100,
            "{off_image} floor pixels within 0.9 m of the wall"
        );
    }
}
