//! Spot light: a point source with a smooth cone falloff, also the RSM/shadow-map camera.

use super::camera::{view_matrix, vulkan_perspective};
use super::mesh::Aabb;
use glam::{Mat4, Vec3};

/// The most irradiance a light may give at the scene's own size (its bounding radius away):
/// far beyond what the tonemap shows (irradiance 1 is the automatic light's), so a brighter
/// light only makes every pixel white.
pub const MAX_SCENE_IRRADIANCE: f32 = 1e7;

/// The largest radiant intensity (W/sr) a light may have in a scene of bounding radius
/// `scene_radius`: [`MAX_SCENE_IRRADIANCE`] at that distance. It scales with the scene, as
/// the automatic light's intensity (d² for its distance d) does, so a large model's own light
/// is never refused.
pub fn max_intensity(scene_radius: f32) -> f32 {
    MAX_SCENE_IRRADIANCE * scene_radius * scene_radius
}

/// Why `intensity` is too bright for a scene of bounding radius `scene_radius`, if it is.
pub fn check_intensity(intensity: [f32; 3], scene_radius: f32) -> Result<(), String> {
    let max = max_intensity(scene_radius);
    if intensity.iter().all(|c| *c <= max) {
        return Ok(());
    }
    Err(format!(
        "{intensity:?} W/sr is more than {max:e}, the most for this scene ({MAX_SCENE_IRRADIANCE:e} \
         x its bounding radius {scene_radius}²: irradiance above {MAX_SCENE_IRRADIANCE:e} at \
         the scene's size only makes every pixel white)"
    ))
}

/// The kinds of light a scene file's `[light]` table may describe (its `kind`; `spot` when it
/// has none). This enum is their one list of names: the scene-file parser reads `kind` into it
/// (an unknown name is refused with these, file:line), and a kind's own keys are checked and
/// turned into what the renderer draws where the scene file is read (`scene_file`'s
/// `check_light`, `scene_load`'s `light`).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    serde::Serialize,
    serde::Deserialize,
    clap::ValueEnum,
)]
#[serde(rename_all = "lowercase")]
pub enum LightKind {
    /// A point source with a smooth cone falloff ([`SpotLight`]): `position`, `target` or
    /// `direction`, and optional cone angles, intensity and shadow-map depth range.
    #[default]
    Spot,
}

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SpotLight {
    #[serde(with = "super::serde_vec3")]
    pub position: Vec3,
    /// Unit axis of the cone (normalised again where used, so a sloppy value is harmless).
    #[serde(with = "super::serde_vec3")]
    pub direction: Vec3,
    /// Radiant intensity on the axis, W/sr per RGB channel.
    #[serde(with = "super::serde_vec3")]
    pub intensity: Vec3,
    /// Half-angle (degrees) inside which the light is at full intensity.
    pub inner_deg: f32,
    /// Half-angle (degrees) outside which the light is zero.
    pub outer_deg: f32,
    /// Near/far planes of the light's shadow-map projection.
    pub near: f32,
    pub far: f32,
}

/// Margin added to the full cone angle for the shadow-map frustum, so the cone's edge does
/// not land exactly on the map's border.
pub const FRUSTUM_MARGIN_DEG: f32 = 2.0;

impl SpotLight {
    /// A light at `position` aimed at `target`.
    pub fn aimed(
        position: Vec3,
        target: Vec3,
        intensity: Vec3,
        inner_deg: f32,
        outer_deg: f32,
        near: f32,
        far: f32,
    ) -> Self {
        Self {
            position,
            direction: (target - position).normalize_or(Vec3::NEG_Y),
            intensity,
            inner_deg,
            outer_deg,
            near,
            far,
        }
    }

    /// This light moved to `position` and aimed at `target` (`--light`): same intensity,
    /// colour and cone; the shadow map's far plane pushed out to reach every corner of
    /// `bounds` from there (5% margin), its near plane kept below a tenth of the far one.
    pub fn placed(&self, position: Vec3, target: Vec3, bounds: &Aabb) -> Self {
        let reach = (0..8)
            .map(|i| {
                let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
                let corner = Vec3::new(
                    pick(1, bounds.min.x, bounds.max.x),
                    pick(2, bounds.min.y, bounds.max.y),
                    pick(4, bounds.min.z, bounds.max.z),
                );
                position.distance(corner)
            })
            .fold(0.0f32, f32::max);
        let far = self.far.max(1.05 * reach);
        Self {
            position,
            direction: (target - position).normalize_or(self.axis()),
            near: self.near.min(0.1 * far),
            far,
            ..*self
        }
    }

    fn axis(&self) -> Vec3 {
        self.direction.normalize_or(Vec3::NEG_Y)
    }

    /// Cone falloff for a unit vector from the light towards a point:
    /// `smoothstep(cos outer, cos inner, dot(axis, v))` with `t²(3 - 2t)`; 0 outside the cone,
    /// 1 inside the inner cone. If `inner >= outer` the edge is a hard step at the outer angle.
    pub fn spot_factor(&self, to_point_unit: Vec3) -> f32 {
        let cos_theta = self.axis().dot(to_point_unit);
        let cos_outer = self.outer_deg.to_radians().cos();
        let cos_inner = self.inner_deg.to_radians().cos();
        if cos_theta < cos_outer || cos_theta.is_nan() {
            return 0.0;
        }
        let width = cos_inner - cos_outer;
        if width <= 0.0 {
            return 1.0;
        }
        let t = ((cos_theta - cos_outer) / width).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    }

    /// Floor for d² in the inverse-square law: near². Points closer than the light's own near
    /// plane are outside its shadow map anyway, and the floor keeps 1/d² finite at d → 0.
    /// It scales with the light (near is chosen per scene), so it is not a fixed world-space
    /// epsilon; a near of 0 falls back to f32::MIN_POSITIVE (only guards division by zero).
    pub fn min_distance_sq(&self) -> f32 {
        (self.near * self.near).max(f32::MIN_POSITIVE)
    }

    /// Unshadowed irradiance at `p` on a surface with unit normal `n`:
    /// `intensity × spot_factor × max(0, n·l) / max(d², near²)`, l the unit vector p → light.
    pub fn irradiance(&self, p: Vec3, n: Vec3) -> Vec3 {
        let to_light = self.position - p;
        let d2 = to_light.length_squared();
        let Some(l) = to_light.try_normalize() else {
            return Vec3::ZERO;
        };
        let cos_surface = n.dot(l).max(0.0);
        self.intensity * (self.spot_factor(-l) * cos_surface / d2.max(self.min_distance_sq()))
    }

    pub fn view(&self) -> Mat4 {
        let axis = self.axis();
        // Any up works for a round cone; avoid one parallel to the axis.
        let up = if axis.y.abs() > 0.99 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        view_matrix(self.position, axis, up)
    }

    /// Square frustum covering the cone: fov = 2 × outer + 2° margin (clamped to 179°).
    pub fn proj(&self) -> Mat4 {
        vulkan_perspective(self.frustum_fov_deg(), 1.0, self.near, self.far)
    }

    pub fn frustum_fov_deg(&self) -> f32 {
        2.0 * self.outer_deg + FRUSTUM_MARGIN_DEG
    }

    pub fn view_proj(&self) -> Mat4 {
        self.proj() * self.view()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light() -> SpotLight {
        SpotLight {
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: Vec3::NEG_Y,
            intensity: Vec3::new(6.0, 5.2, 4.2),
            inner_deg: 30.0,
            outer_deg: 45.0,
            near: 0.05,
            far: 10.0,
        }
    }

    #[test]
    fn on_axis_irradiance_is_inverse_square() {
        let l = light();
        for d in [0.5f32, 1.0, 2.0] {
            let e = l.irradiance(l.position - Vec3::Y * d, Vec3::Y);
            assert!(e.abs_diff_eq(l.intensity / (d * d), 1e-5), "{e}");
        }
        // Facing away or behind: nothing.
        assert_eq!(l.irradiance(Vec3::ZERO, Vec3::NEG_Y), Vec3::ZERO);
        assert_eq!(
            l.irradiance(Vec3::new(0.0, 3.0, 0.0), Vec3::NEG_Y),
            Vec3::ZERO
        );
        // At the light itself: finite.
        assert!(l.irradiance(l.position, Vec3::Y).is_finite());
    }

    #[test]
    fn tilted_surface_gets_cosine() {
        let l = light();
        let n = Vec3::new(1.0, 1.0, 0.0).normalize();
        let e = l.irradiance(Vec3::ZERO, n);
        assert!(e.abs_diff_eq(l.intensity / 4.0 * n.y, 1e-5));
    }

    #[test]
    fn smoothstep_cone() {
        let l = light();
        let at = |deg: f32| {
            let r = deg.to_radians();
            l.spot_factor(Vec3::new(r.sin(), -r.cos(), 0.0))
        };
        assert_eq!(at(0.0), 1.0);
        assert_eq!(at(29.9), 1.0);
        assert_eq!(at(45.1), 0.0);
        let (ci, co) = (30f32.to_radians().cos(), 45f32.to_radians().cos());
        let c = 37f32.to_radians().cos();
        let t = (c - co) / (ci - co);
        assert!((at(37.0) - t * t * (3.0 - 2.0 * t)).abs() < 1e-5);
        assert!(at(40.0) < at(35.0));
    }

    #[test]
    fn cone_edge_fits_the_frustum() {
        let l = light();
        let vp = l.view_proj();
        let r = 45f32.to_radians();
        for dir in [
            Vec3::new(r.sin(), -r.cos(), 0.0),
            Vec3::new(0.0, -r.cos(), r.sin()),
        ] {
            let clip = vp * (l.position + dir * 3.0).extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0, "{ndc}");
            assert!(ndc.x.abs().max(ndc.y.abs()) > 0.9, "{ndc}");
            assert!(ndc.z > 0.0 && ndc.z < 1.0);
        }
    }

    #[test]
    fn placed_light_reaches_the_whole_scene() {
        let l = crate::scene::cornell_light();
        let bounds = Aabb {
            min: Vec3::new(-1.0, 0.0, -1.0),
            max: Vec3::new(1.0, 2.0, 1.0),
        };
        let p = l.placed(Vec3::new(0.0, 1.0, 30.0), Vec3::ZERO, &bounds);
        assert_eq!(p.intensity, l.intensity);
        assert_eq!((p.inner_deg, p.outer_deg), (l.inner_deg, l.outer_deg));
        assert!(p
            .direction
            .abs_diff_eq(Vec3::new(0.0, -1.0, -30.0).normalize(), 1e-6));
        let farthest = Vec3::new(0.0, 1.0, 30.0).distance(Vec3::new(1.0, 2.0, -1.0));
        assert!(p.far >= farthest && p.near < 0.1 * p.far, "{p:?}");
    }
}
