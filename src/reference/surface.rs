//! What the G-buffer stores at a surface point, computed on the CPU: the interpolated vertex
//! normal and the albedo (material colour × texture, sRGB-decoded and bilinearly filtered with
//! wrapping, as the renderer's R8G8B8A8_SRGB texture and its sampler give).

use crate::scene::accel::Hit;
use crate::scene::{Mesh, TextureImage};
use glam::{Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub struct Surface {
    pub position: Vec3,
    /// Unit geometric normal (winding order; not oriented).
    pub geometric: Vec3,
    /// Unit interpolated vertex normal (not oriented; the geometric normal where the vertex
    /// normals cancel).
    pub shading: Vec3,
    pub albedo: Vec3,
    pub triangle: usize,
}

impl Surface {
    pub fn at(mesh: &Mesh, hit: &Hit) -> Self {
        let idx = &mesh.indices[3 * hit.triangle..3 * hit.triangle + 3];
        let v = [0, 1, 2].map(|k| mesh.vertices[idx[k] as usize]);
        let (u, w) = (hit.uv.x, hit.uv.y);
        let weights = [1.0 - u - w, u, w];
        let [a, b, c] = v.map(|x| x.pos());
        let geometric = (b - a).cross(c - a).normalize_or(Vec3::Y);
        let shading = (0..3)
            .map(|k| Vec3::from_array(v[k].normal) * weights[k])
            .sum::<Vec3>()
            .normalize_or(geometric);
        let tex_uv = (0..3)
            .map(|k| Vec2::from_array(v[k].uv) * weights[k])
            .sum::<Vec2>();
        let albedo = mesh
            .material_of_triangle(hit.triangle)
            .and_then(|m| mesh.materials.get(m))
            .map_or(Vec3::splat(0.8), |m| {
                let base = Vec3::from_array(m.diffuse);
                match &m.diffuse_texture {
                    Some(t) => base * sample_bilinear(t, tex_uv),
                    None => base,
                }
            });
        Self {
            position: hit.position,
            geometric,
            shading,
            albedo,
            triangle: hit.triangle,
        }
    }

    /// The shading normal on the side of the triangle seen from `towards` (the eye for the
    /// G-buffer, the light for the RSM): flipped when it points to the other side of the
    /// geometric normal turned to `towards`, as gbuffer.frag and rsm.frag decide per triangle.
    /// Near a silhouette a smooth normal may face away from `towards` and is kept.
    pub fn facing(&self, towards: Vec3) -> Vec3 {
        let to = towards - self.position;
        let seen = if self.geometric.dot(to) < 0.0 {
            -self.geometric
        } else {
            self.geometric
        };
        if self.shading.dot(seen) < 0.0 {
            -self.shading
        } else {
            self.shading
        }
    }
}

fn srgb_decode(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn texel(t: &TextureImage, x: i64, y: i64) -> Vec3 {
    let (w, h) = (t.width.max(1) as i64, t.height.max(1) as i64);
    let i = 4 * (y.rem_euclid(h) * w + x.rem_euclid(w)) as usize;
    match t.rgba8.get(i..i + 3) {
        Some(p) => Vec3::new(srgb_decode(p[0]), srgb_decode(p[1]), srgb_decode(p[2])),
        None => Vec3::ONE,
    }
}

/// Bilinear filtering with repeat wrapping, texel centres at half-integers.
fn sample_bilinear(t: &TextureImage, uv: Vec2) -> Vec3 {
    if !uv.is_finite() {
        return Vec3::ONE;
    }
    let x = uv.x * t.width as f32 - 0.5;
    let y = uv.y * t.height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let top = texel(t, x0, y0).lerp(texel(t, x0 + 1, y0), fx);
    let bottom = texel(t, x0, y0 + 1).lerp(texel(t, x0 + 1, y0 + 1), fx);
    top.lerp(bottom, fy)
}
