//! The screen-space bound of AO: the ground truth's AO integral (estimators.rs) evaluated
//! against what a frame's G-buffer holds instead of the scene. Rays leave each visible point
//! as the reference's do, but they can only meet the visible surfaces, each taken infinitely
//! thick behind its pixel, and they meet nothing past the image's edges. That is what a
//! screen-space estimator such as GTAO (which makes the same thickness assumption) sees when it
//! samples perfectly, so its error against the traced AO is the part of any such estimator's
//! error that better sampling cannot remove: occluders hidden behind the visible surface or off
//! the image, and air behind thin objects counted as occluded.

use super::estimators::{AoDefinition, Primary};
use super::trace::Reference;
use crate::scene::Camera;
use glam::{Vec2, Vec3, Vec4Swizzles};
use rayon::prelude::*;

/// Directions per pixel (a Hammersley set, the same at every pixel) and march steps per
/// direction (evenly spaced over the radius: the hit distance, and so eq 7's weight, is known
/// to R / steps).
pub const DIRECTIONS: u32 = 256;
pub const STEPS: u32 = 64;

/// Relative margin of the depth test: a point counts as behind a surface when it is more than
/// this fraction of its distance from the camera behind it, so a ray grazing its own plane
/// does not occlude itself through rounding (relative, so it holds at any scene scale).
const BEHIND: f32 = 1e-4;
/// Below this cosine between the eye ray and a texel's normal the ray grazes the texel's
/// plane (its intersection is ill-conditioned): the texel's own depth is used instead.
const GRAZING: f32 = 0.05;

/// A world point's place in the image: continuous pixel coordinates and its distance from
/// the camera along the view axis, or None behind the camera's near plane.
struct Projector {
    view_proj: glam::Mat4,
    width: u32,
    height: u32,
    origin: Vec3,
    forward: Vec3,
    near: f32,
}

impl Projector {
    fn new(camera: &Camera, width: u32, height: u32) -> Self {
        let aspect = width as f32 / height.max(1) as f32;
        Self {
            view_proj: camera.view_proj(aspect),
            width,
            height,
            origin: camera.position,
            forward: camera.frame().0,
            near: camera.near,
        }
    }

    /// The pixel `x` falls in, None off the image or in front of the near plane.
    fn pixel(&self, x: Vec3) -> Option<usize> {
        if !((x - self.origin).dot(self.forward) > self.near) {
            return None;
        }
        let clip = self.view_proj * x.extend(1.0);
        let ndc = clip.xy() / clip.w;
        let p = (ndc + Vec2::ONE) * 0.5 * Vec2::new(self.width as f32, self.height as f32);
        let inside =
            p.x >= 0.0 && p.y >= 0.0 && p.x < self.width as f32 && p.y < self.height as f32;
        inside.then(|| p.y as usize * self.width as usize + p.x as usize)
    }

    /// Whether `x` lies behind the visible surface `q` of its pixel: beyond the plane of q's
    /// texel along the eye ray through x (exact for a plane whatever the ray's place in the
    /// pixel), or beyond q's own depth where that ray grazes the plane.
    fn behind(&self, x: Vec3, q: &Primary) -> bool {
        let d = x - self.origin;
        let along = d.dot(q.normal);
        let length = d.length();
        if along.abs() > GRAZING * length {
            // The eye ray meets q's plane at d * s: x is behind it when s < 1.
            let s = (q.surface.position - self.origin).dot(q.normal) / along;
            s > 0.0 && s < 1.0 - BEHIND
        } else {
            let depth_q = (q.surface.position - self.origin).dot(self.forward);
            d.dot(self.forward) > depth_q * (1.0 + BEHIND)
        }
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
/// primary hits seen through the G-buffer as a thick height field; 1 where a pixel has no
/// geometry (the reference's masks leave those out).
pub fn screen_space_ao(r: &Reference, def: &AoDefinition, directions: u32, steps: u32) -> Vec<f32> {
    let projector = Projector::new(&r.camera, r.width, r.height);
    let (directions, steps) = (directions.max(1), steps.max(1));
    r.primary
        .par_iter()
        .map(|p| match p {
            Some(p) => visibility(&projector, &r.primary, p, def, directions, steps),
            None => 1.0,
        })
        .collect()
}

fn visibility(
    projector: &Projector,
    primary: &[Option<Primary>],
    p: &Primary,
    def: &AoDefinition,
    directions: u32,
    steps: u32,
) -> f32 {
    let mut occlusion = 0.0f64;
    for k in 0..directions {
        let (dir, _) = super::sampling::cosine_hemisphere(p.normal, hammersley(k, directions));
        for i in 0..steps {
            let t = def.radius * (i as f32 + 0.5) / steps as f32;
            let x = p.surface.position + dir * t;
            // Off the image: nothing is known there, the march ends unoccluded.
            let Some(pixel) = projector.pixel(x) else {
                break;
            };
            let Some(q) = &primary[pixel] else {
                continue;
            };
            if projector.behind(x, q) {
                let s = t / def.radius;
                let d = 1.0 + def.attenuation[0] * s + def.attenuation[1] * s * s;
                occlusion += 1.0 / d as f64;
                break;
            }
        }
    }
    (1.0 - occlusion / directions as f64) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::trace::Settings;
    use crate::scene::accel::Accel;

    /// A reference of `scene` at `camera` with only its primary hits.
    fn primaries(scene: &crate::scene::Scene, camera: Camera, size: u32) -> Reference {
        let accel = Accel::new(&scene.mesh);
        let settings = Settings::for_render(&crate::config::RenderConfig::default(), scene);
        Reference::new(&accel, scene, camera, size, size, settings)
    }

    /// Every primary hit projects back into its own pixel (the projection and the reference's
    /// pixel_to_ndc agree).
    #[test]
    fn primary_hits_project_to_their_pixels() {
        let scene = crate::scene::cornell_box();
        let r = primaries(&scene, scene.camera, 32);
        let projector = Projector::new(&r.camera, 32, 32);
        let mut hits = 0;
        for (i, p) in r.primary.iter().enumerate() {
            if let Some(p) = p {
                assert_eq!(projector.pixel(p.surface.position), Some(i), "pixel {i}");
                hits += 1;
            }
        }
        assert!(hits > 32 * 32 / 2, "{hits}");
    }

    /// A floor (y = 0) meeting a wall (x = 0, facing -x), 40 m each way, the camera 3 m from
    /// the wall looking at the corner: every occluder within the radius is on screen and
    /// thick, so the bound is the closed form of binary visibility within R on a floor at
    /// distance d from the wall, 1 - (acos k - k sqrt(1 - k^2)) / pi with k = d / R.
    #[test]
    fn floor_beside_a_wall_matches_the_closed_form() {
        use crate::scene::{Material, MeshBuilder};
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::colour("grey", [0.6, 0.6, 0.6]));
        let h = 40.0;
        let floor = [(-h, -h), (-h, h), (0.0, h), (0.0, -h)].map(|(x, z)| Vec3::new(x, 0.0, z));
        b.add_flat_polygon(m, &floor, Vec3::Y);
        let wall = [(-h, 0.0), (h, 0.0), (h, h), (-h, h)].map(|(z, y)| Vec3::new(0.0, y, z));
        b.add_flat_polygon(m, &wall, -Vec3::X);
        let mut scene = crate::scene::cornell_box();
        scene.mesh = b.build();
        let camera = Camera::new(Vec3::new(-3.0, 1.5, 0.0), Vec3::ZERO, 60.0, 0.1, 200.0);
        let r = primaries(&scene, camera, 96);
        let radius = 0.5;
        let def = AoDefinition {
            radius,
            attenuation: [0.0, 0.0],
        };
        let ao = screen_space_ao(&r, &def, DIRECTIONS, STEPS);
        let mut checked = 0;
        for (v, p) in ao.iter().zip(&r.primary) {
            let Some(p) = p else { continue };
            let d = -p.surface.position.x;
            // Floor points near the wall, away from the image's sides (where rays leave it).
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
        // Nothing within a tiny radius: every pixel open (the corner's own pixels aside).
        let tiny = AoDefinition {
            radius: 1e-3,
            ..def
        };
        let open = screen_space_ao(&r, &tiny, 64, 8);
        let closed = open.iter().filter(|v| **v < 0.98).count();
        assert!(closed < 96 * 2, "{closed} pixels occluded within 1 mm");
        assert!(ao.iter().all(|v| (0.0..=1.0).contains(v)));
    }
}
