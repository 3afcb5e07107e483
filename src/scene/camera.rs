//! Pinhole camera in the Vulkan convention the renderer uses.
//!
//! View: right-handed (`look_to_rh`, camera looks down -Z). Projection: `perspective_rh`
//! (clip depth 0..1) with Y flipped, so NDC y = -1 is the top row of the image. Pixel
//! (px, py) of a W×H image, py = 0 the top row, has NDC `((px + 0.5) / W * 2 - 1,
//! (py + 0.5) / H * 2 - 1)` ([`pixel_to_ndc`]).

use super::mesh::Aabb;
use glam::{Mat4, Vec3};

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Camera {
    #[serde(with = "super::serde_vec3")]
    pub position: Vec3,
    #[serde(with = "super::serde_vec3")]
    pub target: Vec3,
    #[serde(with = "super::serde_vec3")]
    pub up: Vec3,
    /// Full vertical field of view in degrees.
    pub vfov_deg: f32,
    pub near: f32,
    pub far: f32,
}

/// Field-of-view limits: a zero fov divides by zero, 180° puts the image plane at infinity.
const MIN_FOV_DEG: f32 = 0.01;
const MAX_FOV_DEG: f32 = 179.0;

/// NDC of the centre of pixel (px, py) in a `width × height` image (py = 0 is the top row).
pub fn pixel_to_ndc(px: f32, py: f32, width: u32, height: u32) -> (f32, f32) {
    (
        (px + 0.5) / width.max(1) as f32 * 2.0 - 1.0,
        (py + 0.5) / height.max(1) as f32 * 2.0 - 1.0,
    )
}

/// An orthonormal camera frame (forward, right, up). Degenerate inputs are repaired rather
/// than producing NaN: a zero or non-finite `forward` looks down -Z, and an `up` that is zero,
/// non-finite or parallel to `forward` (|f × up|² ≤ 1e-12 |up|², i.e. within ~1e-6 rad; a
/// ratio, so scale-free) is replaced by the world axis least aligned with `forward`.
pub fn orthonormal_frame(forward: Vec3, up: Vec3) -> (Vec3, Vec3, Vec3) {
    let f = forward.try_normalize().unwrap_or(Vec3::NEG_Z);
    let c = f.cross(up);
    let right = if c.length_squared() > 1e-12 * up.length_squared() {
        c.normalize()
    } else {
        let alt = if f.y.abs() < 0.9 { Vec3::Y } else { Vec3::Z };
        f.cross(alt).normalize_or(Vec3::X)
    };
    (f, right, right.cross(f))
}

/// Right-handed view matrix from a repaired frame.
pub fn view_matrix(eye: Vec3, forward: Vec3, up: Vec3) -> Mat4 {
    let (f, _, u) = orthonormal_frame(forward, up);
    glam::camera::rh::view::look_to_mat4(eye, f, u)
}

/// Vulkan-style perspective: clip depth 0..1, Y flipped. Inputs are clamped to usable values
/// (fov in [0.01°, 179°], aspect > 0, 0 < near < far) so the matrix is always finite.
pub fn vulkan_perspective(vfov_deg: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let (fov, aspect, near, far) = sanitize_projection(vfov_deg, aspect, near, far);
    // glam's Vulkan projection: right-handed view space, clip depth 0..1, NDC y down.
    glam::camera::rh::proj::vulkan::perspective(fov.to_radians(), aspect, near, far)
}

fn sanitize_projection(vfov_deg: f32, aspect: f32, near: f32, far: f32) -> (f32, f32, f32, f32) {
    let fov = if vfov_deg.is_finite() {
        vfov_deg.clamp(MIN_FOV_DEG, MAX_FOV_DEG)
    } else {
        60.0
    };
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        1.0
    };
    let near = if near.is_finite() && near > 0.0 {
        near
    } else {
        1e-3
    };
    // A far plane at or before near gives a singular matrix; keep the usual 1:1000 ratio.
    let far = if far.is_finite() && far > near {
        far
    } else {
        near * 1000.0
    };
    (fov, aspect, near, far)
}

/// The largest far / near ratio of a camera or a spot light's shadow map: past it the 32-bit
/// depth buffer no longer tells surfaces apart. Measured on the Cornell box at 128x128
/// (lavapipe, near from 1e-3 to 3e-5 with far 10): up to 1e5 the image is the one at a ratio
/// of 200 (at most 2 pixels off by more than 3 of 255, at silhouettes); at 3.3e5 the camera's
/// image has 10 such pixels (up to 21 off, stripes on the blocks) and the light's shadow test
/// fails over 1,786 of them; at 1e8 every depth rounds to the far plane's (a black image).
pub const MAX_DEPTH_RATIO: f32 = 1e5;

/// Why `near` and `far` cannot be a depth range ([`MAX_DEPTH_RATIO`]), if they cannot.
pub fn depth_range_problem(near: f32, far: f32) -> Option<String> {
    if !(near.is_finite() && near > 0.0) {
        return Some(format!("near {near} must be a positive number"));
    }
    if !(far.is_finite() && far > near) {
        return Some(format!("far {far} must be beyond near {near}"));
    }
    (far / near > MAX_DEPTH_RATIO).then(|| {
        format!(
            "far / near = {:.3e} (near {near}, far {far}) is past {MAX_DEPTH_RATIO:e}, beyond \
             which the 32-bit depth buffer no longer tells surfaces apart (stripes, then a \
             black image): raise near or bring far in",
            far / near
        )
    })
}

impl Camera {
    pub fn new(position: Vec3, target: Vec3, vfov_deg: f32, near: f32, far: f32) -> Self {
        Self {
            position,
            target,
            up: Vec3::Y,
            vfov_deg,
            near,
            far,
        }
    }

    /// Camera on +Z of the bounds' centre, looking at it, far enough that the bounding sphere
    /// fits the vertical field of view (for aspect ≥ 1, the usual case).
    pub fn framing(bounds: &Aabb, vfov_deg: f32) -> Self {
        let center = bounds.center();
        let radius = bounds
            .radius()
            .max(1e-6 * center.abs().max_element())
            .max(1e-6);
        let half = (0.5 * vfov_deg.clamp(MIN_FOV_DEG, MAX_FOV_DEG)).to_radians();
        let distance = radius / half.sin();
        Self::new(
            center + Vec3::Z * distance,
            center,
            vfov_deg,
            // Near/far bracket the bounding sphere with margin (far/near ≈ 6: precise depth).
            (distance - radius) * 0.5,
            (distance + radius) * 1.5,
        )
    }

    /// Unit (forward, right, up) of the view.
    pub fn frame(&self) -> (Vec3, Vec3, Vec3) {
        orthonormal_frame(self.target - self.position, self.up)
    }

    pub fn view(&self) -> Mat4 {
        view_matrix(self.position, self.target - self.position, self.up)
    }

    pub fn proj(&self, aspect: f32) -> Mat4 {
        vulkan_perspective(self.vfov_deg, aspect, self.near, self.far)
    }

    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        self.proj(aspect) * self.view()
    }

    /// World-space ray through NDC (x, y): origin at the eye, unit direction. Consistent
    /// with [`Self::view_proj`]: `view_proj * (origin + t * dir)` lands on (x, y) for t > 0.
    pub fn ray(&self, ndc_x: f32, ndc_y: f32, aspect: f32) -> (Vec3, Vec3) {
        let (fov, aspect, _, _) = sanitize_projection(self.vfov_deg, aspect, self.near, self.far);
        let tan_half = (0.5 * fov).to_radians().tan();
        let (f, r, u) = self.frame();
        // The projection flips y, so NDC y grows downwards while camera-space y grows up.
        let dir = f + r * (ndc_x * tan_half * aspect) - u * (ndc_y * tan_half);
        (self.position, dir.normalize_or(f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    fn cam() -> Camera {
        Camera::new(
            Vec3::new(0.0, 1.0, 3.4),
            Vec3::new(0.0, 1.0, 0.0),
            40.0,
            0.05,
            20.0,
        )
    }

    #[test]
    fn y_flip_puts_up_at_top() {
        let c = cam();
        let above = c.view_proj(1.0) * Vec4::new(0.0, 1.5, 0.0, 1.0);
        assert!(
            above.y / above.w < 0.0,
            "a point above the target is in the top half"
        );
        let right = c.view_proj(1.0) * Vec4::new(0.5, 1.0, 0.0, 1.0);
        assert!(right.x / right.w > 0.0);
    }

    #[test]
    fn depth_range_is_zero_to_one() {
        let c = cam();
        let (o, d) = c.ray(0.3, -0.2, 1.5);
        let near = c.view_proj(1.5) * (o + d * (c.near / d.dot(c.frame().0))).extend(1.0);
        let far = c.view_proj(1.5) * (o + d * (c.far / d.dot(c.frame().0))).extend(1.0);
        assert!((near.z / near.w).abs() < 1e-5);
        assert!((far.z / far.w - 1.0).abs() < 1e-5);
    }

    #[test]
    fn degenerate_inputs_stay_finite() {
        let mut c = cam();
        c.target = c.position;
        c.up = Vec3::ZERO;
        c.vfov_deg = 0.0;
        c.far = 0.0;
        assert!(c.view_proj(0.0).is_finite());
        let (_, d) = c.ray(0.5, 0.5, f32::NAN);
        assert!(d.is_finite() && d.is_normalized());
        // Looking straight down with up = +Y.
        c.target = c.position - Vec3::Y;
        c.up = Vec3::Y;
        assert!(c.view().is_finite());
    }

    #[test]
    fn framing_fits_bounds() {
        let b = Aabb {
            min: Vec3::new(-1.0, 0.0, -2.0),
            max: Vec3::new(3.0, 1.0, 0.0),
        };
        let c = Camera::framing(&b, 40.0);
        let vp = c.view_proj(1.0);
        for i in 0..8 {
            let p = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            let clip = vp * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{p} -> {ndc}");
            assert!(ndc.z > 0.0 && ndc.z < 1.0);
        }
    }
}
